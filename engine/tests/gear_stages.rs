//! Gear stages of the lathe's main spindle (Function Manual S1 "Gear stages for spindles"):
//! M41..M45 engage a stage, M40 selects it from the programmed speed; each stage limits the
//! speed to MD35130/MD35140 and accelerates with MD35200. Worked out by hand with two stages:
//!
//! | stage | M40 range (MD35120..MD35110) | limits (MD35140..MD35130) | MD35200 |
//! |---|---|---|---|
//! | 1 | 0..1000 | 0..1200 | 20 rev/s² (1200 rev/min per s) |
//! | 2 | 800..4000 | 400..4000 | 40 rev/s² (2400 rev/min per s) |
//!
//! A change brakes the spindle to a standstill in the old stage, changes the gear (the
//! simulated PLC at once) and accelerates in the new one; the next block waits for the change.

use nctwin_engine::{Channel, Status};

const GEARS: &str = "$MA_GEAR_STEP_CHANGE_ENABLE[SP1]=1
$MA_NUM_GEAR_STEPS[SP1]=2
$MA_GEAR_STEP_MIN_VELO[1,SP1]=0
$MA_GEAR_STEP_MAX_VELO[1,SP1]=1000
$MA_GEAR_STEP_MAX_VELO_LIMIT[1,SP1]=1200
$MA_GEAR_STEP_SPEEDCTRL_ACCEL[1,SP1]=20
$MA_GEAR_STEP_MIN_VELO[2,SP1]=800
$MA_GEAR_STEP_MAX_VELO[2,SP1]=4000
$MA_GEAR_STEP_MIN_VELO_LIMIT[2,SP1]=400
$MA_GEAR_STEP_MAX_VELO_LIMIT[2,SP1]=4000
$MA_GEAR_STEP_SPEEDCTRL_ACCEL[2,SP1]=40
";

fn channel(md: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset("lathe-2axis", md).unwrap();
    ch.run_program(program).unwrap();
    ch
}

fn speed(ch: &Channel) -> f64 {
    ch.snapshot().spindles.iter().find(|(n, _)| n == "SP").unwrap().1
}

fn run_for(ch: &mut Channel, seconds: f64) {
    for _ in 0..(seconds / ch.config().ipo_cycle).round() as usize {
        ch.step();
    }
}

fn finish(ch: &mut Channel) {
    for _ in 0..1_000_000 {
        if !ch.is_busy() {
            break;
        }
        ch.step();
    }
    assert_ne!(ch.status(), Status::Running);
}

#[test]
fn m41_limits_the_speed_to_stage_1() {
    // S2000 in stage 1: limited to MD35130[1] = 1200.
    let mut ch = channel(GEARS, "M41 S2000 M3\nG4 F3\nM30");
    run_for(&mut ch, 2.5);
    assert_eq!(speed(&ch), 1200.0);
}

#[test]
fn m42_raises_a_low_speed_to_the_stage_minimum() {
    // S300 in stage 2: at least MD35140[2] = 400.
    let mut ch = channel(GEARS, "M42 S300 M3\nG4 F3\nM30");
    run_for(&mut ch, 2.5);
    assert_eq!(speed(&ch), 400.0);
}

#[test]
fn m40_changes_to_stage_2_for_a_speed_above_stage_1() {
    // S500 selects stage 1 (ramp 500/1200 s). S2000 lies only in stage 2's range: brake from
    // 500 at 1200/s (0.4167 s), change, accelerate to 2000 at 2400/s (0.8333 s): 1.25 s.
    let mut ch = channel(GEARS, "M40 S500 M3\nG4 F1\nS2000\nG4 F3\nM30");
    run_for(&mut ch, 0.9);
    assert_eq!(speed(&ch), 500.0);
    // Find the cycle where the spindle starts braking, then time the change.
    let mut cycles = 0;
    while speed(&ch) >= 500.0 {
        ch.step();
        cycles += 1;
        assert!(cycles < 1000);
    }
    let mut elapsed = 1;
    while speed(&ch) < 2000.0 {
        ch.step();
        elapsed += 1;
        assert!(elapsed < 10_000, "speed {}", speed(&ch));
    }
    let t = elapsed as f64 * ch.config().ipo_cycle;
    assert!((t - 1.25).abs() <= 2.0 * ch.config().ipo_cycle, "change and ramp took {t} s");
}

#[test]
fn the_next_block_waits_for_the_gear_change() {
    // S2000 under M40 with Z motion after it: Z starts only after the spindle stood (the
    // change), so at Z's first move the spindle has turned up from 0 for at most a few cycles
    // (2400 rev/min per s · 0.012 s < 30 rev/min).
    let mut ch = channel(GEARS, "M40 S500 M3\nG0 X20 Z0\nG4 F1\nS2000\nG1 Z-10 F1000\nM30");
    run_for(&mut ch, 1.3);
    let z0 = ch.axis_positions()[1];
    for _ in 0..10_000 {
        ch.step();
        if ch.axis_positions()[1] != z0 {
            break;
        }
    }
    assert!(speed(&ch) < 30.0, "speed at the first Z motion {}", speed(&ch));
}

#[test]
fn m40_keeps_the_stage_while_the_speed_fits_it() {
    // S900 lies in both ranges; after M42 S2000, M40 S900 stays in stage 2 (no stop): the
    // spindle goes down from 2000 to 900 at stage 2's 2400/s (0.4583 s) without passing 0.
    let mut ch = channel(GEARS, "M42 S2000 M3\nG4 F2\nM40 S900\nG4 F2\nM30");
    run_for(&mut ch, 2.0);
    let mut lowest = f64::MAX;
    for _ in 0..300 {
        ch.step();
        lowest = lowest.min(speed(&ch));
    }
    assert_eq!(lowest, 900.0);
}

#[test]
fn a_stage_beyond_md35090_is_refused_and_without_gear_stages_m41_does_nothing() {
    let mut ch = channel(GEARS, "G0 X10\nM43\nM30");
    finish(&mut ch);
    let alarms: Vec<_> = ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect();
    assert_eq!(alarms, vec![(12560, Some(2))]);
    // The preset has no gear stages: M45 S3000 turns at 3000 (MD35100 4000).
    let mut ch = channel("", "M45 S3000 M3\nG4 F3\nM30");
    run_for(&mut ch, 2.5);
    assert_eq!(speed(&ch), 3000.0);
}

#[test]
fn the_address_extension_selects_the_spindle() {
    // M1=41: spindle 1 in stage 1: S2000 limited to 1200.
    let mut ch = channel(GEARS, "M1=41 S2000 M3\nG4 F3\nM30");
    run_for(&mut ch, 2.5);
    assert_eq!(speed(&ch), 1200.0);
}
