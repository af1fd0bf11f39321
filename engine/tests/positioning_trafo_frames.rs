//! Positioning axes under a transformation or a rotated frame, as the control refuses them:
//!
//! - An axis of the active transformation (its geometry axes, its `TRAFO_AXES_IN_n` axes, the
//!   orientation axes of TRAORI) cannot be a POS/POSA/POSP positioning axis: alarm 17610
//!   "axis involved in the transformation, action cannot be carried out" (Transformations FM
//!   F2: "the kinematic transformation does not act on positioning axes"; FM M1 TRACYL: the
//!   peripheral and groove-wall axes "cannot be used as a positioning axis"). An axis outside
//!   the transformation stays a positioning axis.
//! - In a frame with a rotation a geometry axis cannot be a positioning axis: alarm 16430
//!   "geometry axis cannot traverse as positioning axis in rotated coordinate system" (its
//!   direction in the rotated system would move several machine axes, and a positioning axis
//!   has one interpolator of its own). Axes outside the geometry are not rotated and position
//!   through their own frame component.

use crate::settle;

use nctwin_engine::{Channel, Status};
use settle::{channel, run_to_end};

/// Runs `program` to its end; the first alarm's number and line.
fn first_alarm(ch: &mut Channel, program: &str) -> Option<(u32, Option<u32>)> {
    ch.run_program(program).unwrap();
    run_to_end(ch);
    ch.snapshot().alarms.first().map(|a| (a.number, a.line))
}

fn axis(ch: &Channel, name: &str) -> usize {
    ch.config().channel_axes.iter().position(|a| a.name == name).unwrap_or_else(|| panic!("no axis {name}"))
}

#[test]
fn a_geometry_axis_in_a_rotated_frame_is_alarm_16430() {
    for program in ["ROT Z30\nPOS[X]=10\nM30", "ROT Z30\nPOSA[Z]=5\nM30", "G0 X1\nAROT X10\nPOSP[Y]=(4, 1)\nM30"] {
        let mut ch = channel("mill-3axis", "");
        let line = program.lines().position(|l| l.contains("POS")).unwrap() as u32 + 1;
        assert_eq!(first_alarm(&mut ch, program), Some((16430, Some(line))), "{program}");
        assert_eq!(ch.snapshot().status, Status::Alarm);
    }
}

#[test]
fn without_the_rotation_the_geometry_axis_positions_again() {
    // ROT alone clears the rotation; TRANS X5 then puts POS[X]=10 at machine 15.
    let mut ch = channel("mill-3axis", "");
    assert_eq!(first_alarm(&mut ch, "ROT Z30\nROT\nTRANS X5\nPOS[X]=10\nM30"), None);
    assert!((ch.axis_positions()[0] - 15.0).abs() < 1e-9, "{:?}", ch.axis_positions());
}

#[test]
fn a_rotary_axis_positions_in_a_rotated_frame() {
    // C of the 5-axis head is no geometry axis: ROT Z30 does not act on it, POS[C]=90 is 90.
    let mut ch = channel("mill5-head-ca", "");
    let c = axis(&ch, "C");
    assert_eq!(first_alarm(&mut ch, "ROT Z30\nPOS[C]=90 FA[C]=7200\nM30"), None);
    assert!((ch.axis_positions()[c] - 90.0).abs() < 1e-9, "C = {}", ch.axis_positions()[c]);
}

#[test]
fn axes_of_an_active_transformation_are_alarm_17610() {
    for (preset, program, line) in [
        // TRANSMIT: X and Z are geometry axes of the transformation (Z also AXES_IN[2]).
        ("transmit-example", "T1 D1 G17\nG0 X20 Z10\nTRANSMIT\nPOS[X]=10\nM30", 4),
        ("transmit-example", "T1 D1 G17\nG0 X20 Z10\nTRANSMIT\nPOSA[Z]=5\nM30", 4),
        // TRACYL: Y (the unrolled surface on C's slot) and the groove-wall axis XC (AXES_IN[3]).
        ("tracyl-xyzac", "T1 D1\nG0 X20 Y0 Z0\nTRACYL(40)\nPOS[Y]=10\nM30", 4),
        ("tracyl-xyzac", "T1 D1\nG0 X20 Y0 Z0\nTRACYL(40)\nPOSP[XC]=(3, 1)\nM30", 4),
        // TRAORI: the orientation axes are the transformation's.
        ("mill5-head-ca", "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nPOS[C]=90\nM30", 4),
    ] {
        let mut ch = channel(preset, "");
        assert_eq!(first_alarm(&mut ch, program), Some((17610, Some(line))), "{preset}: {program}");
    }
}

#[test]
fn an_axis_outside_the_transformation_stays_a_positioning_axis() {
    // TRACYL on tracyl-xyzac leaves the trunnion A out of the transformation: POS[A]=-90
    // turns it while TRACYL is active; after TRAFOOF the geometry axes position again: Z=-5
    // with the slot mill's length 80 along ZM is machine ZC = 75.
    let mut ch = channel("tracyl-xyzac", "");
    let a = axis(&ch, "A");
    let program = "T1 D1\nG0 X20 Y0 Z0\nTRACYL(40)\nPOS[A]=-90 FA[A]=7200\nTRAFOOF\nPOS[Z]=-5\nM30";
    assert_eq!(first_alarm(&mut ch, program), None, "{:?}", ch.alarms());
    let p = ch.axis_positions();
    assert!((p[a] + 90.0).abs() < 1e-9, "A = {}", p[a]);
    assert!((p[2] - 75.0).abs() < 1e-9, "ZC = {}", p[2]);
}

#[test]
fn command_axes_of_synchronized_actions_follow_the_same_rules() {
    for (preset, program, number) in [
        ("mill-3axis", "ROT Z30\nID=1 WHEN TRUE DO POS[Z]=5\nG4 F0.2\nM30", 16430),
        ("transmit-example", "T1 D1 G17\nG0 X20 Z10\nTRANSMIT\nID=1 WHEN TRUE DO POS[X]=5\nG4 F0.2\nM30", 17610),
        ("transmit-example", "T1 D1 G17\nG0 X20 Z10\nTRANSMIT\nID=1 WHEN TRUE DO MOV[Z]=1\nG4 F0.2\nM30", 17610),
    ] {
        let mut ch = channel(preset, "");
        let line = program.lines().position(|l| l.contains("DO")).unwrap() as u32 + 1;
        assert_eq!(first_alarm(&mut ch, program), Some((number, Some(line))), "{preset}: {program}");
    }
    // The trunnion A outside TRACYL is a command axis as before: -90° at FA 7200°/min.
    let mut ch = channel("tracyl-xyzac", "");
    let a = axis(&ch, "A");
    let program = "T1 D1\nG0 X20 Y0 Z0\nTRACYL(40)\nID=1 WHEN TRUE DO FA[A]=7200 POS[A]=-90\nG4 F1\nM30";
    assert_eq!(first_alarm(&mut ch, program), None, "{:?}", ch.alarms());
    assert!((ch.axis_positions()[a] + 90.0).abs() < 1e-9, "A = {}", ch.axis_positions()[a]);
}
