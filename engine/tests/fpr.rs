//! `FPR(axis)`: a feed per revolution (G95) of another spindle or rotary axis instead of the
//! master spindle (Programming Manual "Job planning", revolutional feed rate with reference to
//! a rotary axis or spindle). Worked out by hand: F0.1 mm/rev at 1000 rev/min of the
//! referenced spindle is 100 mm/min, whatever the master spindle does.
//!
//! The transmit-example preset: master spindle 1 is C, spindle 2 the driven tool ASC, Z the
//! geometry axis on channel axis 2.

use nctwin_engine::Channel;

fn channel(preset: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset(preset, "").unwrap();
    ch.run_program(program).unwrap();
    ch
}

/// The path speed (mm/min) along Z once Z has passed -10.
fn z_speed(ch: &mut Channel) -> f64 {
    let z = |ch: &Channel| ch.axis_positions()[2];
    for _ in 0..200_000 {
        ch.step();
        if z(ch) < -10.0 {
            break;
        }
    }
    let z0 = z(ch);
    ch.step();
    (z0 - z(ch)) / ch.config().ipo_cycle * 60.0
}

fn alarms(ch: &mut Channel) -> Vec<(u32, Option<u32>)> {
    for _ in 0..100_000 {
        if !ch.is_busy() {
            break;
        }
        ch.step();
    }
    ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect()
}

#[test]
fn g95_follows_the_spindle_fpr_names() {
    // The master spindle stands; spindle 2 turns at 1000 rev/min: 0.1 · 1000 = 100 mm/min.
    for reference in ["SPI(2)", "ASC"] {
        let program = format!("S2=1000 M2=3\nG4 F2\nFPR({reference})\nG95 G1 Z-50 F0.1\nM30\n");
        let mut ch = channel("transmit-example", &program);
        let v = z_speed(&mut ch);
        assert!((v - 100.0).abs() < 1e-6, "FPR({reference}): path speed {v} mm/min");
    }
}

#[test]
fn the_feed_follows_the_referenced_spindle_at_half_speed() {
    // S2=500: 0.1 · 500 = 50 mm/min.
    let mut ch = channel("transmit-example", "S2=500 M2=3\nG4 F2\nFPR(SPI(2))\nG95 G1 Z-50 F0.1\nM30\n");
    let v = z_speed(&mut ch);
    assert!((v - 50.0).abs() < 1e-6, "path speed {v} mm/min");
}

#[test]
fn program_end_returns_the_reference_to_the_master_spindle() {
    // After FPR(SPI(2)) and M30 the next G95 move follows the master spindle again, which
    // stands: the path does not move although spindle 2 turns.
    let mut ch = channel("transmit-example", "FPR(SPI(2))\nM30\n");
    for _ in 0..1000 {
        ch.step();
    }
    ch.run_program("S2=1000 M2=3\nG4 F1\nG95 G1 Z-50 F0.1\nM30\n").unwrap();
    for _ in 0..(3.0 / ch.config().ipo_cycle) as usize {
        ch.step();
    }
    assert_eq!(ch.axis_positions()[2], 0.0);
}

#[test]
fn fpr_of_a_linear_or_unknown_axis_or_of_the_moving_axis_itself_is_refused() {
    let mut ch = channel("transmit-example", "G0 X10\nFPR(X)\nM30\n");
    assert_eq!(alarms(&mut ch), vec![(12560, Some(2))]);
    let mut ch = channel("transmit-example", "G0 X10\nFPR(Q)\nM30\n");
    assert_eq!(alarms(&mut ch), vec![(12550, Some(2))]);
    let mut ch = channel("transmit-example", "G0 X10\nFPR(SPI(7))\nM30\n");
    assert_eq!(alarms(&mut ch), vec![(12560, Some(2))]);
    // tracyl-xyzac: C is a rotary axis, no spindle. A G95 move of C itself under FPR(C)
    // would feed by its own speed.
    let mut ch = channel("tracyl-xyzac", "FPR(C)\nG95 G1 F0.1 C90\nM30\n");
    assert_eq!(alarms(&mut ch), vec![(12560, Some(2))]);
}

#[test]
fn g95_follows_the_master_spindle_setms_selects() {
    // SETMS(2): spindle 2 is the master spindle; G95 F0.1 at its 1000 rev/min is 100 mm/min
    // while spindle 1 stands (the main run used MD20090's spindle 1 before: no motion at all).
    let mut ch = channel("transmit-example", "S2=1000 M2=3\nG4 F2\nSETMS(2)\nG95 G1 Z-50 F0.1\nM30\n");
    let v = z_speed(&mut ch);
    assert!((v - 100.0).abs() < 1e-6, "path speed {v} mm/min");
    let snap = ch.snapshot();
    let master: Vec<_> = snap.spindle_states.iter().filter(|(_, s)| s.master).map(|(n, _)| n.clone()).collect();
    assert_eq!(master.len(), 1, "{master:?}");
    assert_ne!(master[0], ch.config().spindle_name(ch.config().master_spindle.unwrap()), "the state marks spindle 2");
}

#[test]
fn setms_without_a_spindle_gives_the_master_back_to_the_machine_data() {
    // SETMS: spindle 1 again (it stands at S1=500 M3 → 0.1 · 500 = 50 mm/min).
    let mut ch =
        channel("transmit-example", "S1=500 M3\nS2=1000 M2=3\nG4 F2\nSETMS(2)\nSETMS\nG95 G1 Z-50 F0.1\nM30\n");
    let v = z_speed(&mut ch);
    assert!((v - 50.0).abs() < 1e-6, "path speed {v} mm/min");
}
