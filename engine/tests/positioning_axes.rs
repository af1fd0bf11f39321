//! Positioning axes in programs (Function Manual P2, Programming Manual "POS, POSA, FA, WAITP"):
//! an axis on its own interpolator beside the path. Hand-worked on mill-3axis: IPO cycle 4 ms,
//! 3 m/s² on every axis, G60-style exact stop at the block ends that the tests rely on only
//! through the times below.
//!
//! Z with `FA[Z]=300` (5 mm/s) over 5 mm: ramp 5/3000 s = 1.7 ms, so 5/5 + 5/3000 = 1.0017 s
//! ≈ 250.4 cycles. X with `G1 X4 F600` (10 mm/s) over 4 mm: 0.4 + 10/3000 = 0.4033 s ≈ 101
//! cycles.

use nctwin_engine::{Channel, Status};

fn channel(preset: &str) -> Channel {
    Channel::from_preset(preset, "").unwrap()
}

fn steps(ch: &mut Channel, n: usize) {
    for _ in 0..n {
        ch.step();
    }
}

fn run_to_end(ch: &mut Channel) -> usize {
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < 1_000_000, "program does not end");
    }
    ticks
}

fn pos(ch: &Channel, k: usize) -> f64 {
    ch.axis_positions()[k]
}

/// Steps until `done` holds; the number of cycles taken.
fn cycles_until(ch: &mut Channel, limit: usize, done: impl Fn(&Channel) -> bool) -> usize {
    for n in 1..=limit {
        ch.step();
        if done(ch) {
            return n;
        }
    }
    panic!("not reached within {limit} cycles");
}

#[test]
fn pos_block_ends_when_both_the_path_and_the_positioning_axis_have_arrived() {
    let mut ch = channel("mill-3axis");
    ch.run_program("G1 X4 F600 POS[Z]=-5 FA[Z]=300\nG1 Y2\nM30").unwrap();
    // After 150 cycles (0.6 s) X has arrived (≈101 cycles), Z is at about 5·0.6 = 3 mm of 5,
    // and Y has not started: the block waits for Z.
    steps(&mut ch, 150);
    assert!((pos(&ch, 0) - 4.0).abs() < 1e-9, "X = {}", pos(&ch, 0));
    let z = pos(&ch, 2);
    assert!(z < -2.8 && z > -3.2, "Z = {z}");
    assert_eq!(pos(&ch, 1), 0.0);
    // Z arrives after ≈250 cycles in all (100 more, ±3).
    let n = cycles_until(&mut ch, 200, |c| pos(c, 2) == -5.0);
    assert!((97..=104).contains(&n), "Z arrived {n} cycles later");
    assert_eq!(pos(&ch, 1), 0.0, "Y starts only after Z has arrived");
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!((pos(&ch, 0), pos(&ch, 1), pos(&ch, 2)), (4.0, 2.0, -5.0));
}

#[test]
fn posa_travels_across_two_path_blocks_until_waitp() {
    let mut ch = channel("mill-3axis");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nG1 X4 F600\nG1 Y4\nWAITP(Z)\nG1 X0\nM30").unwrap();
    // The two path blocks take about 2 × 101 cycles while Z travels (250 cycles).
    steps(&mut ch, 215);
    assert!((pos(&ch, 0) - 4.0).abs() < 1e-9 && (pos(&ch, 1) - 4.0).abs() < 1e-9, "path done");
    let z = pos(&ch, 2);
    assert!(z > -5.0 && z < -4.0, "Z still travelling during both path blocks: {z}");
    // WAITP holds N5 until Z has arrived.
    let n = cycles_until(&mut ch, 100, |c| pos(c, 2) == -5.0);
    assert!((30..=40).contains(&n), "Z arrived {n} cycles later");
    assert_eq!(pos(&ch, 0), 4.0, "X waits at WAITP");
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!((pos(&ch, 0), pos(&ch, 1), pos(&ch, 2)), (0.0, 4.0, -5.0));
}

#[test]
fn path_block_on_a_travelling_posa_axis_raises_14092() {
    let mut ch = channel("mill-3axis");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nG1 X4 F600\nG1 Z0\nM30").unwrap();
    run_to_end(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm);
    assert_eq!((s.alarms[0].number, s.alarms[0].line), (14092, Some(3)));
}

#[test]
fn path_block_on_an_arrived_posa_axis_runs() {
    // 1 mm at FA 3000 (50 mm/s): 0.02 + 0.017 s, long before X's 0.4 s.
    let mut ch = channel("mill-3axis");
    ch.run_program("POSA[Z]=-1 FA[Z]=3000\nG1 X4 F600\nG1 Z2\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!((pos(&ch, 0), pos(&ch, 2)), (4.0, 2.0));
}

#[test]
fn pos_with_ic_g91_and_a_frame_moves_like_the_axis_word() {
    // TRANS Z10: POS[Z]=-5 is machine -5 + 10 = 5; then IC(2) adds 2 → 7; G91 POS[Z]=-1 → 6.
    let mut ch = channel("mill-3axis");
    ch.run_program("TRANS Z10\nPOS[Z]=-5\nPOS[Z]=IC(2)\nG91 POS[Z]=-1\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert!((pos(&ch, 2) - 6.0).abs() < 1e-9, "Z = {}", pos(&ch, 2));
}

#[test]
fn without_fa_the_axis_uses_md32060() {
    // MD32060 = 600 mm/min (10 mm/s): 10 mm take 1.0033 s ≈ 251 cycles.
    let mut ch = Channel::from_preset("mill-3axis", "$MA_POS_AX_VELO[Z]=600\n").unwrap();
    ch.run_program("POS[Z]=10\nM30").unwrap();
    let n = cycles_until(&mut ch, 400, |c| pos(c, 2) == 10.0);
    assert!((249..=254).contains(&n), "{n} cycles");
}

#[test]
fn bad_positioning_words_give_alarms() {
    for (program, number) in [
        ("POS[Q]=1\nM30", 12550),
        ("FA[Z]=-5\nM30", 12560),
        ("POS[Z]=ACN(5)\nM30", 12560),
        ("POS[Z]=1 POSA[Z]=2\nM30", 12080),
        ("G1 F100 Z1 POS[Z]=2\nM30", 12000),
    ] {
        let mut ch = channel("mill-3axis");
        ch.run_program(program).unwrap();
        run_to_end(&mut ch);
        let s = ch.snapshot();
        assert_eq!(s.alarms.first().map(|a| a.number), Some(number), "{program}");
    }
}

#[test]
fn rotary_modulo_axis_positions_with_acn_and_dc() {
    let mut ch = channel("mill5-head-ca");
    let k = ch.config().channel_axes.iter().position(|a| a.name == "C").expect("C axis");
    let dt = ch.config().ipo_cycle;
    // ACN(90) from 0: the negative way, 270°, at 3600°/min = 60°/s: 4.5 s plus the ramp.
    ch.run_program("POS[C]=ACN(90) FA[C]=3600\nPOS[C]=DC(80)\nM30").unwrap();
    steps(&mut ch, (1.0 / dt) as usize);
    let c = pos(&ch, k).rem_euclid(360.0);
    assert!(c > 290.0 && c < 305.0, "C after 1 s = {c} (went negative)");
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    // DC(80) from 90: the short way, −10°.
    assert!((pos(&ch, k).rem_euclid(360.0) - 80.0).abs() < 1e-9, "C = {}", pos(&ch, k));
}

#[test]
fn nc_stop_brakes_a_positioning_axis_and_nc_start_takes_it_on_to_its_target() {
    let mut ch = channel("mill-3axis");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nG4 F5\nM30").unwrap();
    steps(&mut ch, 100); // Z ≈ −2 at 5 mm/s
    ch.stop();
    // From 5 mm/s at 3000 mm/s² it stands within two cycles.
    steps(&mut ch, 3);
    let z = pos(&ch, 2);
    steps(&mut ch, 50);
    assert_eq!(pos(&ch, 2), z, "Z stands while stopped");
    assert!(z < -1.8 && z > -2.2, "Z = {z}");
    ch.start().unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(pos(&ch, 2), -5.0);
}

#[test]
fn reset_leaves_a_positioning_axis_where_it_is_and_the_next_program_starts_there() {
    let mut ch = channel("mill-3axis");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nG4 F5\nM30").unwrap();
    steps(&mut ch, 100);
    ch.reset();
    let z = pos(&ch, 2);
    assert!(z < -1.8 && z > -2.2, "Z = {z}");
    steps(&mut ch, 10);
    assert_eq!(pos(&ch, 2), z, "nothing moves after the reset");
    // G91 Z1 goes from where Z stands.
    ch.run_program("G91 G1 Z1 F600\nM30").unwrap();
    run_to_end(&mut ch);
    assert!((pos(&ch, 2) - (z + 1.0)).abs() < 1e-9, "Z = {}", pos(&ch, 2));
}

#[test]
fn a_program_ends_only_when_its_posa_axes_have_arrived() {
    // No WAITP: M30 waits for Z (1 s) although the path has nothing to do.
    let mut ch = channel("mill-3axis");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nM30").unwrap();
    let n = run_to_end(&mut ch);
    assert!((249..=256).contains(&n), "{n} cycles");
    assert_eq!(pos(&ch, 2), -5.0);
}
