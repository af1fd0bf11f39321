//! Set WO in the JOG area: the typed position goes into the active settable frame so the axis
//! reads it without moving. Values worked out by hand: WCS = frame⁻¹(BCS − TR).

use nctwin_engine::{Channel, CommandError, Mode};

use crate::settle;
use settle::{channel, settle};

fn wcs(ch: &Channel, axis: &str) -> f64 {
    ch.snapshot().workpiece.iter().find(|(n, _)| n == axis).map(|(_, v)| *v).expect("axis shown")
}

fn mda(ch: &mut Channel, text: &str) {
    ch.set_mode(Mode::Mda).unwrap();
    ch.mda(text).unwrap();
    settle(ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
}

#[test]
fn set_wo_makes_the_axis_read_the_typed_value_and_later_moves_go_from_there() {
    let mut ch = channel("mill-3axis", "");
    mda(&mut ch, "G0 X30 Y-20");
    assert_eq!((wcs(&ch, "X"), wcs(&ch, "Y")), (30.0, -20.0));
    ch.set_mode(Mode::Jog).unwrap();
    ch.set_work_offset("X", 0.0).unwrap();
    ch.set_work_offset("y", 5.0).unwrap();
    // G500 (the reset value, frame 0) now holds X 30, Y -25: X reads 0, Y reads 5, nothing moved.
    assert_eq!((wcs(&ch, "X"), wcs(&ch, "Y")), (0.0, 5.0));
    assert_eq!(&ch.axis_positions()[..2], &[30.0, -20.0]);
    let frame0 = &ch.config().work_offsets[0].trans;
    assert_eq!((frame0[0], frame0[1]), (30.0, -25.0));
    // G0 X5 Y0 in that offset goes to machine X 35, Y -25.
    mda(&mut ch, "G0 X5 Y0");
    assert_eq!(&ch.axis_positions()[..2], &[35.0, -25.0]);
}

#[test]
fn set_wo_in_a_rotated_offset_shifts_along_the_rotated_axis() {
    let mut ch = channel("mill-3axis", "");
    // G500 rotated 90° about Z: WCS X runs along machine Y.
    ch.apply_machine_data("$P_UIFR[0,Z,RT]=90\n").unwrap();
    mda(&mut ch, "G0 X10 Y0");
    // In the rotated WCS (10, 0) is machine (0, 10).
    assert!((ch.axis_positions()[1] - 10.0).abs() < 1e-9);
    ch.set_mode(Mode::Jog).unwrap();
    ch.set_work_offset("X", 0.0).unwrap();
    // The 10 mm along WCS X are 10 mm along machine Y: TR Y = 10, WCS (0, 0).
    assert!(wcs(&ch, "X").abs() < 1e-9 && wcs(&ch, "Y").abs() < 1e-9);
    let frame0 = &ch.config().work_offsets[0].trans;
    assert!(frame0[0].abs() < 1e-9 && (frame0[1] - 10.0).abs() < 1e-9, "{frame0:?}");
}

#[test]
fn set_wo_is_refused_while_a_program_runs_and_for_an_unknown_axis() {
    let mut ch = channel("mill-3axis", "");
    assert!(matches!(ch.set_work_offset("Q", 1.0), Err(CommandError::UnknownAxis(_))));
    assert!(matches!(ch.set_work_offset("X", f64::NAN), Err(CommandError::Invalid(_))));
    // A typo of 1e308 would overflow the translation (found by probing the server, where it
    // surfaced as "bad value `-inf` for $P_UIFR"): refused, and the offset is unchanged.
    for typo in [1e308, -1e308, 1.000001e6] {
        let Err(CommandError::Invalid(why)) = ch.set_work_offset("X", typo) else { panic!("{typo} taken") };
        assert!(why.contains("no position"), "{why}");
    }
    assert_eq!(ch.config().work_offsets[0].trans[0], 0.0);
    ch.set_work_offset("X", -1e6).unwrap();
    assert_eq!(wcs(&ch, "X"), -1e6);
    ch.set_work_offset("X", 0.0).unwrap();
    ch.run_program("G1 X100 F1000\nM30").unwrap();
    ch.step();
    assert!(matches!(ch.set_work_offset("X", 0.0), Err(CommandError::Busy(_))));
}
