//! Command axes and spindles from synchronized actions (Function Manual "Synchronized
//! actions": POS/MOV/FA/SPOS, M3/M4/M5, S), hand-worked on mill-3axis: IPO cycle 4 ms, 3 m/s²
//! per axis, FFWON (at constant speed `$AA_IM` is the setpoint). X with `G1 F600` runs at
//! 10 mm/s, 0.04 mm per cycle. The tool spindle S1: 50 rev/s² in speed control, SPOS at
//! MD35300 = 1000 rev/min with 100 rev/s².

use nctwin_engine::{Channel, SpindleMode, Status};

use crate::settle;
use settle::{run_to_end, steps};

fn channel() -> Channel {
    Channel::from_preset("mill-3axis", "").unwrap()
}

fn pos(ch: &Channel, k: usize) -> f64 {
    ch.axis_positions()[k]
}

#[test]
fn when_x_passes_20_z_starts_and_reaches_its_target_after_its_own_profile() {
    // Z: 5 mm at FA 1000 mm/min (16.67 mm/s), 3000 mm/s²: 5/16.67 + 16.67/3000 = 0.3056 s,
    // 76.4 cycles. The action reads $AA_IM of the cycle before, so Z moves first in the cycle
    // after the one in which X reached 20.
    let mut ch = channel();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=20 DO POS[Z]=-5 FA[Z]=1000\nG1 X40 F600\nM30").unwrap();
    let (mut x_at, mut z_start, mut z_end) = (None, None, None);
    for tick in 1..=1500 {
        ch.step();
        // The control compares REAL values within a relative tolerance: 19.99999999999975
        // (the sum of 0.04 steps) counts as 20.
        if x_at.is_none() && ch.actual_position(0) >= 20.0 - 1e-9 {
            x_at = Some(tick);
        }
        if z_start.is_none() && pos(&ch, 2) != 0.0 {
            z_start = Some(tick);
            assert!(pos(&ch, 0) >= 20.0 && pos(&ch, 0) < 20.0 + 0.04 + 1e-9, "X = {}", pos(&ch, 0));
        }
        if z_end.is_none() && pos(&ch, 2) == -5.0 {
            z_end = Some(tick);
        }
    }
    let (x_at, z_start, z_end) = (x_at.unwrap(), z_start.unwrap(), z_end.unwrap());
    assert_eq!(z_start, x_at + 1, "Z starts in the cycle after $AA_IM[X] reached 20");
    assert!((75..=79).contains(&(z_end - z_start + 1)), "Z took {} cycles", z_end - z_start + 1);
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert!((pos(&ch, 0) - 40.0).abs() < 1e-9);
    assert_eq!(pos(&ch, 2), -5.0);
}

#[test]
fn mov_runs_endlessly_until_mov_zero() {
    // Z at FA 600 (10 mm/s) from X = 10 (t ≈ 1 s) to X = 30 (t ≈ 3 s): 2 s at 10 mm/s; the ramp
    // up loses 10²/6000 mm and the braking ramp adds as much, so Z ≈ −20 (± a cycle's 0.04 mm).
    let mut ch = channel();
    let program =
        "ID=1 WHEN $AA_IM[X]>=10 DO MOV[Z]=-1 FA[Z]=600\nID=2 WHEN $AA_IM[X]>=30 DO MOV[Z]=0\nG1 X40 F600\nM30";
    ch.run_program(program).unwrap();
    run_to_end(&mut ch);
    steps(&mut ch, 10);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let z = pos(&ch, 2);
    assert!((z + 20.0).abs() < 0.1, "Z = {z}");
}

#[test]
fn a_command_axis_that_the_running_block_moves_raises_20141() {
    let mut ch = channel();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=5 DO POS[X]=0\nG1 X40 F600\nM30").unwrap();
    run_to_end(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm);
    assert_eq!(s.alarms[0].number, 20141);
}

#[test]
fn a_path_block_on_a_command_axis_raises_20141() {
    let mut ch = channel();
    ch.run_program("WHEN $AA_IM[X]>=1 DO POS[Z]=-1\nG1 X4 F600\nG1 Z5\nM30").unwrap();
    run_to_end(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.alarms.first().map(|a| (a.number, a.line)), Some((20141, Some(3))));
}

#[test]
fn spos_from_an_action_positions_the_spindle_the_short_way() {
    // 90° at 36000°/s² (100 rev/s²) never reaches 6000°/s: a triangle of 2·√(90/36000) = 0.1 s.
    let mut ch = channel();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=2 DO SPOS=90\nG1 X10 F600\nM30").unwrap();
    run_to_end(&mut ch);
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    let (_, sp) = &s.spindle_states[0];
    assert_eq!(sp.mode, SpindleMode::Positioning);
    assert!((sp.position - 90.0).abs() < 1e-9, "angle {}", sp.position);
}

#[test]
fn s_and_m3_m5_from_actions_drive_the_spindle() {
    // S2000 M3 at X ≥ 2 (t ≈ 0.2 s): 2000 rev/min after 2000/3000 s = 0.67 s, long before the
    // block ends at 1 s. M5 at X ≥ 9 (t ≈ 0.9 s): the spindle brakes from 2000.
    let mut ch = channel();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=2 DO S2000 M3\nID=2 WHEN $AA_IM[X]>=9 DO M5\nG1 X10 F600\nM30").unwrap();
    steps(&mut ch, 220); // 0.88 s: X = 8.8
    let (_, sp) = ch.snapshot().spindle_states[0].clone();
    assert_eq!((sp.mode, sp.speed), (SpindleMode::M3, 2000.0));
    steps(&mut ch, 50);
    let (_, sp) = ch.snapshot().spindle_states[0].clone();
    assert_eq!(sp.mode, SpindleMode::M5);
    assert!(sp.speed < 2000.0);
    // M3, M5 went to the PLC as well.
    let aux = ch
        .take_events()
        .into_iter()
        .filter_map(|e| match e {
            nctwin_engine::Event::AuxFunction { function, .. } => Some((function.letter, function.value)),
            _ => None,
        })
        .collect::<Vec<_>>();
    assert_eq!(aux[..2], [('M', 3.0), ('M', 5.0)]);
}

#[test]
fn bad_command_actions_are_refused_before_the_run() {
    for (program, number) in [
        ("DO POS[Q]=1\nM30", 12550),
        ("DO POSA[Z]=1\nM30", 12571),
        ("DO MOV[Z]=IC(1)\nM30", 12560),
        ("DO POS[Z]=DC(1)\nM30", 12560),
        ("DO SPOS[7]=1\nM30", 12550),
    ] {
        let mut ch = channel();
        ch.run_program(program).unwrap();
        run_to_end(&mut ch);
        let s = ch.snapshot();
        assert_eq!(s.alarms.first().map(|a| a.number), Some(number), "{program}");
    }
}
