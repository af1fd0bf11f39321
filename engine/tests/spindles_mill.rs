//! The 3-axis mill's tool spindle S1: a spindle without axis function (not among the
//! positions), with the machine data of the preset: MD35100 12000 rev/min, MD35200
//! 50 rev/s² = 3000 rev/min per second, MD35300 1000 rev/min in position control, MD20090
//! master spindle 1. Values worked out by hand from those data (Function Manual S1).

use nctwin_engine::{Channel, SpindleMode, SpindleState, Status};

fn start(program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    ch
}

fn run(program: &str) -> Channel {
    let mut ch = start(program);
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            break;
        }
        ch.step();
    }
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    ch
}

fn s1(ch: &Channel) -> SpindleState {
    let s = ch.snapshot();
    s.spindle_states.iter().find(|(n, _)| n == "S1").unwrap_or_else(|| panic!("S1 in {:?}", s.spindle_states)).1
}

fn names(list: &[(String, f64)]) -> Vec<&str> {
    list.iter().map(|(n, _)| n.as_str()).collect()
}

#[test]
fn the_mill_shows_x_y_z_and_its_spindle_only_under_spindles() {
    let ch = Channel::from_preset("mill-3axis", "").unwrap();
    let s = ch.snapshot();
    assert_eq!(names(&s.machine), ["X", "Y", "Z"]);
    assert_eq!(names(&s.basic), ["X", "Y", "Z"]);
    assert_eq!(names(&s.workpiece), ["X", "Y", "Z"]);
    assert_eq!(names(&s.actual), ["X", "Y", "Z"]);
    assert_eq!(s.spindles, vec![("S1".to_string(), 0.0)]);
    let st = s1(&ch);
    assert_eq!((st.number, st.mode, st.master), (1, SpindleMode::M5, true));
}

#[test]
fn m3_s1000_ramps_at_md35200_and_g4_s_counts_revolutions() {
    // S1000 M3: 0 → 1000 rev/min at 3000 rev/min/s takes 1/3 s. G4 S2 dwells 2 rev at the
    // programmed 1000 rev/min = 0.12 s, so the program ends with the spindle still turning
    // M3 (program end keeps it turning) at 1000 rev/min after the ramp.
    let mut ch = start("S1000 M3\nG4 S2\nM30\n");
    let mut t_full = None;
    for _ in 0..10_000 {
        ch.step();
        if t_full.is_none() && s1(&ch).speed >= 1000.0 {
            t_full = Some(ch.snapshot().time);
        }
        if t_full.is_some() && ch.status() == Status::Idle {
            break;
        }
    }
    let t = t_full.expect("reaches 1000 rev/min");
    let ipo = ch.config().ipo_cycle;
    assert!((t - 1.0 / 3.0).abs() <= 2.0 * ipo, "ramp ends at {t} s");
    let st = s1(&ch);
    assert_eq!(st.mode, SpindleMode::M3);
    assert_eq!(st.speed, 1000.0);
}

#[test]
fn m4_turns_negative_and_m5_brakes_to_a_stop() {
    // M4 S600 for 1 s (ramp 0.2 s), then M5: braking takes 600/3000 = 0.2 s.
    let ch = run("S600 M4\nG4 F1\nM5\nG4 F0.5\nM30\n");
    let st = s1(&ch);
    assert_eq!((st.mode, st.speed), (SpindleMode::M5, 0.0));
    let mut ch = start("S600 M4\nG4 F1\nM30\n");
    for _ in 0..200 {
        ch.step();
    }
    let st = s1(&ch);
    assert_eq!((st.mode, st.speed), (SpindleMode::M4, -600.0));
}

#[test]
fn spos_positions_the_spindle_in_position_control() {
    // SPOS=90 from standstill at 0°: 90° the short way, position control.
    let ch = run("SPOS=90\nM30\n");
    let st = s1(&ch);
    assert_eq!(st.mode, SpindleMode::Positioning);
    assert!((st.position - 90.0).abs() < 1e-9, "{st:?}");
    // M19 goes to SD43240 M19_SPOS = 0°, SPOS=IC(-30) then turns back by 30°: 330°.
    let ch = run("SPOS=90\nM19\nSPOS=IC(-30)\nM30\n");
    assert!((s1(&ch).position - 330.0).abs() < 1e-9, "{:?}", s1(&ch));
}

#[test]
fn spos_moves_at_md35300() {
    // SPOS=ACP(0) after SPOS=0 is no move; SPOS=IC(3600): 10 revolutions at 1000 rev/min
    // (6000 °/s) take 0.6 s plus the ramps (accelerating at 100 rev/s² = 36000 °/s² to
    // 6000 °/s takes 1/6 s over 500°; the same to brake): 3600/6000 + 1/6 = 0.7667 s.
    let mut ch = start("SPOS=0\nSPOS=IC(3600)\nM30\n");
    let mut t0 = None;
    let mut vmax: f64 = 0.0;
    let mut t1 = 0.0;
    for _ in 0..100_000 {
        ch.step();
        let st = s1(&ch);
        if t0.is_none() && st.speed != 0.0 {
            t0 = Some(ch.snapshot().time - ch.config().ipo_cycle);
        }
        if st.speed != 0.0 {
            t1 = ch.snapshot().time;
        }
        vmax = vmax.max(st.speed);
        if ch.status() == Status::Idle {
            break;
        }
    }
    assert!((vmax - 1000.0).abs() < 1e-6, "top speed {vmax} rev/min");
    let dt = t1 - t0.unwrap();
    assert!((dt - (0.6 + 1.0 / 6.0)).abs() < 0.03, "{dt} s");
    assert!(s1(&ch).position.abs() < 1e-6);
}

#[test]
fn g95_on_the_mill_feeds_per_spindle_revolution() {
    // G95 F0.1 at S2000: 200 mm/min once the spindle is at speed (ramp 2/3 s, the dwell waits).
    let mut ch = start("S2000 M3\nG4 F1\nG95 G1 X50 F0.1\nM30\n");
    let x = |ch: &Channel| ch.axis_positions()[0];
    for _ in 0..100_000 {
        ch.step();
        if x(&ch) > 10.0 {
            break;
        }
    }
    let x0 = x(&ch);
    ch.step();
    let v = (x(&ch) - x0) / ch.config().ipo_cycle * 60.0;
    assert!((v - 200.0).abs() < 1e-6, "{v} mm/min");
}

#[test]
fn g331_g332_tap_on_the_mill_with_the_spindle_interpolated() {
    // From Z2: SPOS=0, G331 Z-12 K1.5 S600: 14/1.5 = 9.333 revolutions (3360° ≡ 120°) in,
    // feed 600·1.5 = 900 mm/min; G332 Z2 K1.5: the same 14 mm back, the spindle reversed by
    // −3360°, so it ends at 0° again.
    let mut ch = start("G0 X0 Y0 Z2\nSPOS=0\nG331 Z-12 K1.5 S600\nG332 Z2 K1.5\nM30\n");
    let mut at_bottom = None;
    let mut vmax: f64 = 0.0;
    for _ in 0..100_000 {
        ch.step();
        let z = ch.axis_positions()[2];
        if ch.snapshot().block.is_some_and(|b| b.line == 3) {
            vmax = vmax.max(ch.snapshot().path_velocity);
        }
        if at_bottom.is_none() && (z + 12.0).abs() < 1e-9 {
            at_bottom = Some(s1(&ch).position);
        }
        if ch.status() == Status::Idle {
            break;
        }
    }
    let bottom = at_bottom.expect("reaches Z-12");
    assert!((bottom - 120.0).abs() < 1e-6, "{bottom}");
    assert!((vmax - 900.0).abs() < 1e-6, "{vmax}");
    assert!((ch.axis_positions()[2] - 2.0).abs() < 1e-9);
    let st = s1(&ch);
    assert_eq!(st.mode, SpindleMode::Positioning);
    assert!(st.position.abs() < 1e-6 || (st.position - 360.0).abs() < 1e-6, "{st:?}");
}

#[test]
fn g63_taps_at_f_with_the_spindle_turning() {
    // G63 Z-10 F750 with S500 M3 (pitch 1.5): the axis moves at F and the spindle keeps its
    // speed; G63 is non-modal, so the next block is G1 again.
    let ch = run("S500 M3\nG4 F1\nG0 Z2\nG63 Z-10 F750\nM4\nG63 Z2\nM30\n");
    assert!((ch.axis_positions()[2] - 2.0).abs() < 1e-9);
    assert_eq!(s1(&ch).mode, SpindleMode::M4);
}

#[test]
fn s_above_md35100_is_limited_to_12000() {
    let mut ch = start("S20000 M3\nG4 F6\nM30\n");
    for _ in 0..(5.0 / 0.004) as usize {
        ch.step();
    }
    assert_eq!(s1(&ch).speed, 12000.0);
}
