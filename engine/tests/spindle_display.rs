//! What the T/F/S display shows of a spindle beyond its speed: the gear stage engaged and the
//! spindle load symbol (a flag: the master spindle turns while the path moves at feed and
//! removes stock; NCTwin models no cutting forces, so no load value).

use nctwin_engine::{Channel, SpindleState};

fn master(ch: &Channel) -> SpindleState {
    ch.snapshot().spindle_states.iter().find(|(_, s)| s.master).expect("a master spindle").1
}

fn step_until(ch: &mut Channel, mut done: impl FnMut(&Channel) -> bool) {
    for _ in 0..2_000_000 {
        if done(ch) {
            return;
        }
        ch.step();
    }
    panic!("condition never met");
}

#[test]
fn the_state_shows_the_gear_stage_engaged_and_none_without_stages() {
    let gears = "$MA_GEAR_STEP_CHANGE_ENABLE[SP1]=1\n$MA_NUM_GEAR_STEPS[SP1]=2\n\
                 $MA_GEAR_STEP_MAX_VELO_LIMIT[1,SP1]=1200\n$MA_GEAR_STEP_MAX_VELO_LIMIT[2,SP1]=4000\n\
                 $MA_GEAR_STEP_SPEEDCTRL_ACCEL[1,SP1]=20\n$MA_GEAR_STEP_SPEEDCTRL_ACCEL[2,SP1]=40\n";
    let mut ch = Channel::from_preset("lathe-2axis", gears).unwrap();
    // Stage 1 after power on; M42 engages stage 2.
    assert_eq!(master(&ch).gear, Some(1));
    ch.run_program("M42\nM30").unwrap();
    step_until(&mut ch, |ch| !ch.is_busy());
    assert_eq!(master(&ch).gear, Some(2));
    let ch = Channel::from_preset("lathe-2axis", "").unwrap();
    assert_eq!(master(&ch).gear, None);
}

#[test]
fn the_load_symbol_shows_while_the_spindle_cuts_at_feed_and_not_in_the_air() {
    // mill-3axis, end mill R5 (T1 D1): a 60 x 50 x 20 block X−10..50, Y−10..40, Z−20..0.
    // With the spindle turning, the feed plunge to Z−2 at X−20 is in the air (no symbol); the
    // slot along X (X−20 → X60 at Y15) shows it once the first 8 mm stretch in the material is
    // cut (X > 0); at rest after the program it is off.
    let program = "G17 G90 G94\nT1 D1\nG0 X-20 Y15 Z50\n\
                   WORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS3000 M3\nG1 Z-2 F600\nG1 X60\nG0 Z50\nM30";
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    let x = |ch: &Channel| ch.axis_positions()[0];
    let mut seen_in_air = false;
    step_until(&mut ch, |ch| {
        if ch.is_busy() && x(ch) < -19.0 && ch.axis_positions()[2] < 49.0 {
            seen_in_air |= master(ch).cutting;
        }
        x(ch) > 10.0
    });
    assert!(!seen_in_air, "no symbol moving in the air");
    assert!(master(&ch).cutting, "cutting at X{}", x(&ch));
    step_until(&mut ch, |ch| !ch.is_busy());
    assert!(!master(&ch).cutting);
}
