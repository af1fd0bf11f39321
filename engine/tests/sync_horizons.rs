//! Horizons of synchronized actions' conditions (`interp/synchronized/horizon.rs`): a
//! condition sleeps while it provably keeps its value, and the actions still act in exactly
//! the IPO cycles of an evaluation in every cycle. Hand-worked on the mill-3axis preset: IPO
//! cycle 4 ms, 30 m/min (500 mm/s) and 3 m/s² on X, Y, Z, FFWON (no following error).

use nctwin_engine::{Channel, Status};

use crate::settle;
use settle::{channel, steps};

fn mill() -> Channel {
    channel("mill-3axis", "")
}

/// Steps until the program ends (at most `limit` cycles); returns the X setpoint of every cycle.
fn run_x(ch: &mut Channel, limit: usize) -> Vec<f64> {
    let mut xs = Vec::new();
    while ch.status() == Status::Running && xs.len() < limit {
        ch.step();
        xs.push(ch.axis_positions()[0]);
    }
    xs
}

#[test]
fn a_position_threshold_fires_in_the_cycle_that_first_reads_the_position_past_it() {
    // G1 X50 F6000 from X0 (BRISK): 100 mm/s; at 3000 mm/s² the speed grows by 12 mm/s per
    // 4 ms cycle, the cycle travelling at the speed it ends with: 12, 24, .. 96 mm/s in
    // cycles 1..8 (X = 0.004·12·(1+..+8) = 1.728), 100 mm/s from cycle 9 (X = 2.128), then
    // 0.4 mm per cycle: X = 2.128 + 0.4·(k − 9) passes 20 in cycle k = 54 (44.68 cycles
    // after the 9th) at 20.128. The condition reads the position before the cycle
    // interpolates: it fires in the 55th cycle of motion and reads 20.128 (within one
    // cycle's 0.4 mm past 20). With the horizon the condition sleeps: from X0 it cannot flip
    // for 20/(4·500 mm/s·0.004 s) = 2.5 cycles, and it is evaluated less often than every
    // cycle all the way to 20.
    for horizons in [true, false] {
        let mut ch = mill();
        ch.set_sync_horizons(horizons);
        ch.run_program("ID=1 WHEN $AA_IM[X]>20 DO $AC_PARAM[1]=$AA_IM[X]\nG1 X50 F6000\nM30").unwrap();
        let mut xs = Vec::new();
        let mut fired_at = None;
        while ch.status() == Status::Running && xs.len() < 2000 {
            ch.step();
            xs.push(ch.axis_positions()[0]);
            if fired_at.is_none() && ch.sync_actions().params[1] != 0.0 {
                fired_at = Some(xs.len() - 1);
            }
        }
        let first_motion = xs.iter().position(|x| *x > 0.0).unwrap();
        let passed = xs.iter().position(|x| *x > 20.0).unwrap();
        let fired = fired_at.expect("the action fired");
        assert_eq!(passed - first_motion + 1, 54, "X passes 20 in the 54th cycle of motion");
        assert!((xs[passed] - 20.128).abs() < 1e-9, "X = {} there", xs[passed]);
        assert_eq!(fired, passed + 1, "fires in the next cycle (horizons {horizons})");
        assert_eq!(ch.sync_actions().params[1], xs[passed]);
        assert!((xs.last().unwrap() - 50.0).abs() < 1e-9);
        let evaluated = ch.sync_actions().evaluations();
        if horizons {
            // 55 cycles of motion and a few before: at most two thirds of them evaluated.
            assert!(evaluated * 3 < fired as u64 * 2, "{evaluated} evaluations in {fired} cycles");
        } else {
            assert!(evaluated > passed as u64, "{evaluated} evaluations");
        }
    }
}

#[test]
fn a_time_condition_sleeps_until_the_cycle_it_flips_in() {
    // EVERY $AC_TIME>0.5 counts the blocks that last longer than 0.5 s: G1 X30 at F600
    // (3 s) and G1 Y1 at F600 (0.1 s): one count. $AC_TIME grows by exactly 4 ms per cycle,
    // so after each block change the condition is evaluated about once, then again when
    // 0.5 s are near, not in each of the ~775 cycles.
    let mut ch = mill();
    ch.run_program("ID=1 EVERY $AC_TIME>0.5 DO $AC_MARKER[1]=$AC_MARKER[1]+1\nG1 X30 F600\nG1 Y1\nM30").unwrap();
    let xs = run_x(&mut ch, 5000);
    assert!((750..800).contains(&xs.len()), "{} cycles", xs.len());
    assert_eq!(ch.sync_actions().markers[1], 1.0);
    let evaluated = ch.sync_actions().evaluations();
    assert!(evaluated < 60, "{evaluated} evaluations");
}

#[test]
fn ten_actions_that_cannot_fire_sleep() {
    // The ten actions of the README's benchmark row on a short program (3.2 s, ~810
    // cycles): ID=9 has no condition, ID=7/8 read signals nobody sets (never evaluated again),
    // ID=1/3/10 positions far from their thresholds, ID=5/6 speeds beyond any the axes reach
    // (4 × 500 mm/s), ID=4 a distance to go below zero: the conditions together are
    // evaluated a few times per block, not ten times per cycle.
    let header = include_str!("../../scripts/sync10.mpf");
    let mut ch = mill();
    ch.run_program(&format!("{header}G1 X30 F600\nG1 Z-2\nM30")).unwrap();
    let xs = run_x(&mut ch, 5000);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert!((800..820).contains(&xs.len()), "{} cycles", xs.len());
    let evaluated = ch.sync_actions().evaluations();
    assert!(evaluated < 200, "{evaluated} evaluations in {} cycles", xs.len());
    // ID=9 ran in every cycle: in the last one before the end it read the Z of the cycle
    // before (−1.96: 10 mm/s, 0.04 mm per cycle short of −2).
    assert!((ch.sync_actions().params[2] + 1.96).abs() < 1e-9);
}

#[test]
fn a_preset_wakes_a_sleeping_position_condition() {
    // X stands at 0; ID=2 sleeps (X cannot reach 100 for 100/8 = 12 cycles and then again).
    // PRESETON X 150 from ID=1 after 0.1 s makes $AA_IM[X] = 150 without motion: ID=2 fires
    // in that same cycle (it is checked after ID=1), as with evaluation in every cycle.
    for horizons in [true, false] {
        let mut ch = mill();
        ch.set_sync_horizons(horizons);
        let program = "ID=1 WHEN $AC_TIME>0.1 DO PRESETON(X,150)\n\
                       ID=2 WHEN $AA_IM[X]>100 DO $AC_MARKER[2]=$AC_TIME*1000\nG4 F1\nM30";
        ch.run_program(program).unwrap();
        steps(&mut ch, 100);
        assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
        assert_eq!(ch.axis_positions()[0], 150.0);
        // $AC_TIME counts from the dwell's start: the first cycle past 0.1 s reads 0.104.
        assert_eq!(ch.sync_actions().markers[2], 104.0, "horizons {horizons}");
    }
}

#[test]
fn a_far_threshold_sleeps_through_a_slow_move() {
    // G1 X100 F600: 10 mm/s, 2,500 cycles. While only the path moves X, X moves at most
    // F600 under the highest override (120 %: 12 mm/s), counted four times: 0.192 mm per
    // cycle, so from X ≤ 100 the threshold 1000 is at least 900 / 0.192 ≈ 4,688 cycles away:
    // the condition is evaluated at the activation and the block change only (under
    // 4 × MD32000, 8 mm per cycle, it was evaluated about every 112 cycles: over 20 times).
    let mut ch = mill();
    ch.run_program("ID=1 WHENEVER $AA_IM[X]>1000 DO $AC_OVR=50\nG1 X100 F600\nM30").unwrap();
    let xs = run_x(&mut ch, 5000);
    assert!((2500..2600).contains(&xs.len()), "{} cycles", xs.len());
    let evaluated = ch.sync_actions().evaluations();
    assert!(evaluated <= 4, "{evaluated} evaluations");
}

#[test]
fn a_command_axis_starting_wakes_a_condition_counted_on_the_slow_path() {
    // The path moves X slowly (F600) and Y not at all; after 0.1 s ID=1 sends Y to 50 at
    // 30 m/min (500 mm/s, far above what the path's moves allow). ID=2 waits for Y > 30: it
    // slept on the path's bound (Y does not move along G1 X10: for good), the positioning
    // axis' start wakes it, and it fires in the same cycle as with evaluation in every cycle
    // (without the wake it never fires).
    let mut fired = Vec::new();
    for horizons in [true, false] {
        let mut ch = mill();
        ch.set_sync_horizons(horizons);
        let program = "ID=1 WHEN $AC_TIME>0.1 DO POS[Y]=50 FA[Y]=30000\n\
                       ID=2 WHEN $AA_IM[Y]>30 DO $AC_MARKER[2]=$AC_TIME*1000\nG1 X10 F600\nM30";
        ch.run_program(program).unwrap();
        steps(&mut ch, 400);
        assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
        fired.push(ch.sync_actions().markers[2]);
    }
    assert!(fired[0] > 100.0, "fired at {} ms", fired[0]);
    assert_eq!(fired[0], fired[1]);
}
