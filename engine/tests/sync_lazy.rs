//! Deferred synchronized actions (`channel/sync/lazy.rs`): an action without condition that
//! only stores positions into a marker or parameter nobody else reads is not run in every IPO
//! cycle; its value is computed from the inputs the cycle kept when someone reads it. What a
//! reader sees must be what running it in every cycle gives (the random programs of
//! `sync_horizon_equivalence.rs` compare both bit for bit); here the values by hand.

use crate::settle;

use settle::{channel, run_to_end};

#[test]
fn a_deferred_action_holds_the_actual_value_its_cycle_read() {
    // `$AA_IM[Z]` in an action is the actual value at the actions' point of the IPO cycle,
    // before the interpolator: the position the cycle before ended at. So after each cycle
    // the parameter holds the actual Z from before that cycle.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("ID=1 DO $AC_PARAM[2]=$AA_IM[Z] $AC_MARKER[3]=$AA_IPO[X]*10\nG1 Z-4 X1.26 F900\nM30\n").unwrap();
    ch.step();
    let mut moved = 0;
    for _ in 0..400 {
        let (z, x) = (ch.actual_position(2), ch.axis_positions()[0]);
        ch.step();
        if ch.is_busy() {
            let s = ch.sync_actions();
            assert_eq!(s.params[2], z);
            // Markers are INT: X·10 rounded.
            assert_eq!(s.markers[3], (x * 10.0).round());
            moved += usize::from(z != 0.0);
            assert!(s.list()[0].fired);
        }
    }
    assert!(moved > 50, "Z moved in {moved} cycles");
}

#[test]
fn block_preparation_reads_the_value_of_a_deferred_action() {
    // The block `R1=$AC_PARAM[1] R2=$AC_MARKER[1]` waits for the main run: after the dwell
    // the setpoint X stands at 10, so R1 = 10; the actual value is 10 or just below (the
    // following error decays), so `$AC_MARKER[1]` = round(2 · 10 + 1) = 21.
    let mut ch = channel("mill-3axis", "");
    ch.run_program(
        "ID=4 DO $AC_PARAM[1]=$AA_IPO[X] $AC_MARKER[1]=$AA_IM[X]*2+1\nG1 X10 F3000\nG4 F0.1\nR1=$AC_PARAM[1] R2=$AC_MARKER[1]\nG1 X=R1+R2 F3000\nM30\n",
    )
    .unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.r_param(1), 10.0);
    assert_eq!(ch.r_param(2), 21.0);
    assert_eq!(ch.axis_positions()[0], 31.0);
    // The action ended with the program, which ends in the cycle of the path's last step:
    // the value of that cycle stays, the position before the step (the last step of a stop
    // is shorter than a·dt·dt = 3000 · 0.004² = 0.048 mm).
    let last = ch.sync_actions().params[1];
    assert!(last < 31.0 && last > 31.0 - 0.048, "{last}");
}

#[test]
fn a_program_reads_the_actions_data_before_any_action_ran() {
    // No action yet: markers and parameters are 0 (they were an empty list: 17020).
    let mut ch = channel("mill-3axis", "");
    ch.run_program("R1=$AC_PARAM[3]+$AC_MARKER[7]+1\nM30\n").unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.r_param(1), 1.0);
}

#[test]
fn ten_actions_leave_most_ipo_cycles_alone() {
    // The ten actions of the benchmark (scripts/sync10.mpf) over a square of 40 blocks:
    // their cycle runs at each block change (`$AC_TIME` starts again) and where a condition
    // may change its value, not in every IPO cycle. The program's thresholds are far from
    // where the axes go (X < 1000, Y < 500, speeds below 1e6 and 500000 mm/min), the DO of
    // ID=9 is deferred and `$AA_VACTM` needs no cycle of its own.
    let mut text = String::from(include_str!("../../scripts/sync10.mpf"));
    text.push_str("G0 X0 Y0 Z0\n");
    for i in 0..10 {
        let d = 20.0 + i as f64;
        text.push_str(&format!("G1 X{d} F3000\nG1 Y{d}\nG1 X0\nG1 Y0\n"));
    }
    text.push_str("M30\n");
    let mut ch = channel("mill-3axis", "");
    ch.run_program(&text).unwrap();
    let mut ticks = 0u64;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let run = ch.sync_actions().cycles_run();
    assert!(run * 10 < ticks, "the actions' cycle ran in {run} of {ticks} IPO cycles");
}
