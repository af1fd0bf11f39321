//! MEAS/MEAW with the simulated touch-trigger probe (Programming Manual "Job planning",
//! "Measurements with touch trigger probe"), values worked out by hand.
//!
//! The probe is tool T3 D1 of the `mill-3axis` preset with the data below: type 710 (3D
//! probe), length 50 to the ball's centre, ball radius 3. Machine Z = workpiece Z + 50 without
//! frames (MCS = BCS + tool length, the preset's tool points down along Z).

use nctwin_engine::channel::ProbeTarget;
use nctwin_engine::{Channel, Event};

const PROBE: &str = "$TC_DP1[3,1]=710\n$TC_DP3[3,1]=50\n$TC_DP6[3,1]=3\n";

/// A 50 x 50 x 20 block, X30..80, Y−10..40, Z−20..0: its face at X30 looks towards −X.
const BLOCK: &str = "WORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,30,-10,80,40)\n";

/// Runs `program` to its end (or to an alarm that stops it); the alarms raised.
fn run(ch: &mut Channel, program: &str) -> Vec<(u32, Option<u32>)> {
    ch.run_program(program).unwrap();
    let mut alarms = Vec::new();
    let mut cycles = 0u64;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < 2_000_000, "program does not end");
        for e in ch.take_events() {
            if let Event::AlarmRaised(a) = e {
                alarms.push((a.number, a.line));
            }
        }
    }
    alarms
}

fn probe_channel() -> Channel {
    Channel::from_preset("mill-3axis", PROBE).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

#[test]
fn meas_against_the_blank_face_measures_the_ball_centre_and_deletes_the_distance_to_go() {
    // The ball (R3) moves along X at Y15 Z−5 towards the face at X30: it touches when its
    // centre is at X = 30 − 3 = 27. MEAS stops the axes there; the block after starts there
    // (G91 X−2: X25). $AA_MM[Z] = −5 + 50 = 45.
    let mut ch = probe_channel();
    let program = format!(
        "G17 G90 G94\nT3 D1\nG0 X-20 Y15 Z50\n{BLOCK}G0 Z-5\nMEAS=1 G1 X50 F500\n\
         R1=$AC_MEA[1] R2=$AA_MW[X] R3=$AA_MM[X] R4=$AA_MW[Y] R5=$AA_MM[Z]\nR6=$AA_IW[X]\nG91 G1 X-2\nG90\nR7=$AA_IW[X]\nM30"
    );
    let alarms = run(&mut ch, &program);
    assert!(alarms.is_empty(), "{alarms:?}");
    let r = |n| ch.r_param(n);
    assert_eq!(r(1), 1.0);
    assert!(close(r(2), 27.0) && close(r(3), 27.0), "MW {} MM {}", r(2), r(3));
    assert!(close(r(4), 15.0) && close(r(5), 45.0), "MW[Y] {} MM[Z] {}", r(4), r(5));
    assert!(close(r(6), 27.0), "stopped at {}", r(6));
    assert!(close(r(7), 25.0), "after G91 X-2: {}", r(7));
}

#[test]
fn the_workpiece_value_goes_through_the_frame() {
    // TRANS X10 after the blank was placed: the face stays at machine (BCS) X30; in the new
    // WCS the centre switches at 27 − 10 = 17, the machine value is still 27.
    let mut ch = probe_channel();
    let program = format!(
        "G17 G90 G94\nT3 D1\nG0 X-20 Y15 Z50\n{BLOCK}TRANS X10\nG0 Z-5\nMEAS=1 G1 X40 F500\n\
         R2=$AA_MW[X] R3=$AA_MM[X]\nM30"
    );
    assert!(run(&mut ch, &program).is_empty());
    assert!(close(ch.r_param(2), 17.0) && close(ch.r_param(3), 27.0), "{} {}", ch.r_param(2), ch.r_param(3));
}

#[test]
fn meaw_records_the_switch_and_runs_the_block_to_its_end() {
    // A target plane x = 30 (normal −X) instead of a blank; diagonal travel from (0, 0) to
    // (50, 50) at Z0: the ball touches when its centre is 3 in front of the plane, X27, and
    // on the diagonal Y27. MEAW keeps going to X50 Y50.
    let mut ch = probe_channel();
    ch.set_probe_targets(vec![ProbeTarget { point: [30.0, 0.0, 0.0], normal: [-2.0, 0.0, 0.0] }]).unwrap();
    let program = "G17 G90 G94\nT3 D1\nG0 X0 Y0 Z0\nMEAW=2 G1 X50 Y50 F1000\nR1=$AC_MEA[2] R2=$AA_MW[X] R3=$AA_MW[Y] R4=$AA_IW[X] R5=$AC_MEA[1]\nM30";
    assert!(run(&mut ch, program).is_empty());
    let r = |n| ch.r_param(n);
    assert_eq!((r(1), r(5)), (1.0, 0.0));
    assert!(close(r(2), 27.0) && close(r(3), 27.0), "{} {}", r(2), r(3));
    assert!(close(r(4), 50.0), "{}", r(4));
}

#[test]
fn a_falling_edge_switches_where_the_ball_leaves_the_surface() {
    // The ball starts at X28, 2 in front of the plane x = 30 (touching); going back to X0 it
    // leaves the plane when its centre is 3 in front: X27.
    let mut ch = probe_channel();
    ch.set_probe_targets(vec![ProbeTarget { point: [30.0, 0.0, 0.0], normal: [-1.0, 0.0, 0.0] }]).unwrap();
    let program = "G17 G90 G94\nT3 D1\nG0 X28 Y0 Z0\nMEAS=-1 G1 X0 F500\nR1=$AC_MEA[1] R2=$AA_MW[X] R3=$AA_IW[X]\nM30";
    assert!(run(&mut ch, program).is_empty());
    assert_eq!(ch.r_param(1), 1.0);
    assert!(close(ch.r_param(2), 27.0) && close(ch.r_param(3), 27.0), "{} {}", ch.r_param(2), ch.r_param(3));
}

#[test]
fn a_probe_deflected_at_the_start_raises_21700_and_one_free_for_a_falling_edge_21703() {
    let mut ch = probe_channel();
    ch.set_probe_targets(vec![ProbeTarget { point: [30.0, 0.0, 0.0], normal: [-1.0, 0.0, 0.0] }]).unwrap();
    let alarms = run(&mut ch, "G17 G90 G94\nT3 D1\nG0 X28 Y0 Z0\nMEAS=1 G1 X50 F500\nM30");
    assert_eq!(alarms, vec![(21700, Some(4))]);
    ch.reset();
    let alarms = run(&mut ch, "G17 G90 G94\nT3 D1\nG0 X0 Y0 Z0\nMEAS=-1 G1 X20 F500\nM30");
    assert_eq!(alarms, vec![(21703, Some(4))]);
}

#[test]
fn no_switch_in_the_block_gives_ac_mea_0_and_the_information_21702() {
    // The ball stops at X20, 7 short of touching: the program goes on and reads 0.
    let mut ch = probe_channel();
    let program = format!(
        "G17 G90 G94\nT3 D1\nG0 X-20 Y15 Z50\n{BLOCK}G0 Z-5\nMEAS=1 G1 X20 F500\nR1=$AC_MEA[1]+10 R2=$AA_IW[X]\nM30"
    );
    let alarms = run(&mut ch, &program);
    assert_eq!(alarms, vec![(21702, Some(6))]);
    assert_eq!(ch.r_param(1), 10.0);
    assert!(close(ch.r_param(2), 20.0));
}

#[test]
fn bad_measuring_words_raise_alarms_with_their_line() {
    for (program, number) in [
        ("G1 X10 F100\nMEAS=3 G1 X20\nM30", 12560),
        ("G1 X10 F100\nMEAS=1\nM30", 12080),
        ("G1 X10 F100\nMEAS=1 MEAW=1 G1 X20\nM30", 0),
        ("G1 X10 F100\nR1=$AC_MEA[3]\nM30", 0),
    ] {
        let mut ch = probe_channel();
        let alarms = run(&mut ch, program);
        assert_eq!(alarms.len(), 1, "{program}: {alarms:?}");
        assert_eq!(alarms[0].1, Some(2), "{program}: {alarms:?}");
        if number != 0 {
            assert_eq!(alarms[0].0, number, "{program}");
        }
    }
}
