//! Program control SKP (skip levels `/0`..`/9`, Programming Manual Fundamentals "Skipping
//! blocks") and DRY (dry-run feed SD42100/SD42101, Function Manual K1). Expected positions and
//! move times worked out by hand in each test's comment: the 3-axis mill moves X at 3 m/s²
//! under BRISK, so a line of length L at path speed v takes L/v + v/a (trapezoid).

use crate::path_support;

use nctwin_engine::Channel;
use nctwin_engine::channel::Overrides;
use nctwin_engine::interp::program_control::SkipLevels;
use path_support::{A_MAX, DT};

fn levels(l: &[u8]) -> SkipLevels {
    SkipLevels::from_levels(l).unwrap()
}

/// A mill with `md` on top, SKP levels and DRY set, running `program` until it rests; the X
/// setpoints of every cycle, the start first.
fn run(md: &str, skip: &[u8], dry: bool, program: &str) -> (Channel, Vec<f64>) {
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    ch.skip_levels = levels(skip);
    ch.dry_run = dry;
    ch.run_program(program).unwrap();
    let mut xs = vec![ch.axis_positions()[0]];
    while ch.is_busy() {
        ch.step();
        xs.push(ch.axis_positions()[0]);
        assert!(xs.len() < 100_000, "the program does not end");
    }
    (ch, xs)
}

fn assert_ok(ch: &Channel) {
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
}

/// The time X moves (s): the cycles between the first and the last change of X.
fn move_time(xs: &[f64]) -> f64 {
    let moving: Vec<usize> = xs.windows(2).enumerate().filter(|(_, w)| w[1] != w[0]).map(|(i, _)| i).collect();
    (moving.last().unwrap() - moving.first().unwrap() + 1) as f64 * DT
}

// --- SKP ---------------------------------------------------------------------------------

#[test]
fn an_active_level_skips_its_blocks_and_only_those() {
    // `/` is level /0. With /0 and /2 active: line 2 (/) and line 4 (/2) are skipped, line 3
    // (/1) runs. X goes 10, (20 skipped), 30, (40 skipped), Y stays 0 until line 5.
    let program = "G0 X10\n/G0 X20\n/1 G0 X30\n/2 G0 X40 Y5\nG0 Y7\nM30";
    let (ch, xs) = run("", &[0, 2], false, program);
    assert_ok(&ch);
    assert!(xs.iter().all(|&x| x <= 30.0), "a skipped X target was approached");
    assert_eq!(&ch.axis_positions()[..2], &[30.0, 7.0]);
    // No level active: every block runs.
    let (ch, _) = run("", &[], false, program);
    assert_eq!(&ch.axis_positions()[..2], &[40.0, 7.0]);
}

#[test]
fn a_skipped_block_with_a_number_is_not_executed_but_can_be_a_jump_target() {
    // `/N10 X5`: skipped; GOTOF N10 finds it (the line is still there), execution goes on
    // after it with X9, so X never reaches 5 and line 2 (X3) is jumped over.
    let program = "G0 X1\nGOTOF N10\nG0 X3\n/N10 G0 X5\nG0 X9\nM30";
    let (ch, xs) = run("", &[0], false, program);
    assert_ok(&ch);
    assert!(!xs.contains(&5.0) && !xs.contains(&3.0), "{:?}", xs.iter().fold(0.0f64, |m, &x| m.max(x)));
    assert_eq!(ch.axis_positions()[0], 9.0);
}

#[test]
fn statements_of_a_skipped_block_are_not_executed() {
    // `/R1=5` skipped: R1 stays 0, so `X=R1+2` goes to 2; the unskipped R2=4 acts.
    let (ch, _) = run("", &[0], false, "/R1=5\nR2=4\nG0 X=R1+2 Y=R2\nM30");
    assert_ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (0.0, 4.0));
    assert_eq!(&ch.axis_positions()[..2], &[2.0, 4.0]);
}

#[test]
fn skipped_blocks_inside_a_loop_are_skipped_on_every_pass() {
    // Three passes; `/R2=R2+1` is skipped each time, `R3=R3+1` counts 3. X = R3*10 = 30.
    let program = "R1=0\nWHILE R1<3\nR1=R1+1\n/R2=R2+1\nR3=R3+1\nENDWHILE\nG0 X=R3*10 Y=R2\nM30";
    let (ch, _) = run("", &[0], false, program);
    assert_ok(&ch);
    assert_eq!((ch.r_param(2), ch.r_param(3)), (0.0, 3.0));
    assert_eq!(&ch.axis_positions()[..2], &[30.0, 0.0]);
}

#[test]
fn a_skipped_endif_leaves_the_structure_open() {
    // The IF opens (R1=0 is 0), its ENDIF is skipped. Reaching the end of the text with the
    // structure open raises 12640 (invalid nesting) naming the IF's line 1; no crash.
    let (ch, _) = run("", &[0], false, "IF R1==0\nG0 X4\n/ENDIF\n");
    let alarm = ch.alarms().first().expect("an alarm").clone();
    assert_eq!((alarm.number, alarm.line), (12640, Some(1)));
    // M30 before the end ends the program first (as it does with the structure closed): X4
    // was reached, no alarm.
    let (ch, _) = run("", &[0], false, "IF R1==0\nG0 X4\n/ENDIF\nM30");
    assert_ok(&ch);
    assert_eq!(ch.axis_positions()[0], 4.0);
    // Level /0 inactive: the program without M30 runs clean.
    let (ch, _) = run("", &[], false, "IF R1==0\nG0 X4\n/ENDIF\n");
    assert_ok(&ch);
}

#[test]
fn a_level_change_reaches_only_blocks_not_yet_prepared() {
    // Prepared blocks keep what they were prepared with: without a preprocessing stop line 2
    // is prepared while line 1 moves, so /0 set during the move no longer skips it (X 50).
    // With STOPRE before it, line 3 is prepared after the move: /0 set during the move skips
    // it (X stays 10).
    for (program, end) in [("G1 X10 F600\n/G1 X50\nM30", 50.0), ("G1 X10 F600\nSTOPRE\n/G1 X50\nM30", 10.0)] {
        let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
        ch.run_program(program).unwrap();
        for _ in 0..50 {
            ch.step();
        }
        assert!(ch.axis_positions()[0] > 0.0 && ch.axis_positions()[0] < 10.0, "still moving");
        ch.skip_levels = levels(&[0]);
        while ch.is_busy() {
            ch.step();
        }
        assert_ok(&ch);
        assert_eq!(ch.axis_positions()[0], end, "{program:?}");
    }
}

#[test]
fn with_no_option_selected_skip_marks_change_nothing() {
    // Determinism: a program with skip marks and neither SKP nor DRY runs cycle for cycle as
    // the same program without the marks.
    let marked = "G1 X20 F3000\n/3 G2 X40 I10\n/G1 X60 Y10\nG0 X0 Y0\nM30";
    let plain = "G1 X20 F3000\nG2 X40 I10\nG1 X60 Y10\nG0 X0 Y0\nM30";
    let (_, a) = path_support::samples::<3>("", marked, 100_000);
    let (_, b) = path_support::samples::<3>("", plain, 100_000);
    assert_eq!(a, b);
}

// --- DRY ---------------------------------------------------------------------------------

/// The time of `G1 X100` at `f` with DRY on and SD42101 = `mode` (SD42100 = 5000 mm/min).
fn dry_time(mode: i64, f: f64) -> f64 {
    let md = format!("$SC_DRY_RUN_FEED=5000\n$SC_DRY_RUN_FEED_MODE={mode}\n");
    let (ch, xs) = run(&md, &[], true, &format!("BRISK G1 X100 F{f}\nM30"));
    assert_ok(&ch);
    assert_eq!(*xs.last().unwrap(), 100.0);
    move_time(&xs)
}

/// L/v + v/a for the 100 mm line at `f` mm/min.
fn trapezoid(f: f64) -> f64 {
    let v = f / 60.0;
    100.0 / v + v / A_MAX
}

#[test]
fn dry_run_mode_0_takes_the_larger_feed() {
    // F100 → max(100, 5000) = 5000 mm/min = 83.33 mm/s: 100/83.33 + 83.33/3000 = 1.2278 s.
    let t = dry_time(0, 100.0);
    assert!((t - 1.2278).abs() <= 2.0 * DT, "{t} s");
    // F8000 stays: 133.33 mm/s: 0.75 + 0.0444 = 0.7944 s.
    let t = dry_time(0, 8000.0);
    assert!((t - trapezoid(8000.0)).abs() <= 2.0 * DT && (t - 0.7944).abs() <= 2.0 * DT, "{t} s");
}

#[test]
fn plain_lines_of_the_fast_lane_take_the_dry_run_feed_too() {
    // `G1 X100 F100` is a plain line (the fast lane prepares it); BRISK is the preset's
    // default: 1.2278 s as above, and the next plain line F100 again at 5000.
    let md = "$SC_DRY_RUN_FEED=5000\n$SC_DRY_RUN_FEED_MODE=0\n";
    let (ch, xs) = run(md, &[], true, "G1 X100 F100\nX0\nM30");
    assert_ok(&ch);
    let last_at_100 = xs.iter().rposition(|&x| x == 100.0).unwrap();
    let (t1, t2) = (move_time(&xs[..=last_at_100]), move_time(&xs[last_at_100..]));
    assert!((t1 - 1.2278).abs() <= 2.0 * DT && (t2 - 1.2278).abs() <= 2.0 * DT, "{t1} s, {t2} s");
}

#[test]
fn dry_run_mode_1_takes_the_smaller_feed() {
    // F8000 → min(8000, 5000) = 5000: 1.2278 s. (F100 would stay 100: 60 s.)
    let t = dry_time(1, 8000.0);
    assert!((t - 1.2278).abs() <= 2.0 * DT, "{t} s");
    let t = dry_time(11, 8000.0);
    assert!((t - 1.2278).abs() <= 2.0 * DT, "mode 11 as 1 outside threads: {t} s");
}

#[test]
fn dry_run_mode_2_takes_the_dry_run_feed_whatever_is_programmed() {
    for f in [100.0, 8000.0] {
        let t = dry_time(2, f);
        assert!((t - 1.2278).abs() <= 2.0 * DT, "F{f}: {t} s");
    }
}

#[test]
fn dry_run_leaves_rapid_traverse_and_the_feed_override_acts_on_it() {
    // G0 under DRY mode 2 with SD42100 = 1000: still rapid, 500 mm/s: 0.2 + 500/3000 = 0.3667 s.
    let md = "$SC_DRY_RUN_FEED=1000\n$SC_DRY_RUN_FEED_MODE=2\n";
    let (_, xs) = run(md, &[], true, "BRISK G0 X100\nM30");
    let t = move_time(&xs);
    assert!((t - 0.3667).abs() <= 2.0 * DT, "G0: {t} s");
    // Feed override 50 % on the dry-run feed 5000: 2500 mm/min = 41.67 mm/s:
    // 100/41.67 + 41.67/3000 = 2.4139 s.
    let mut ch = Channel::from_preset("mill-3axis", "$SC_DRY_RUN_FEED_MODE=2\n").unwrap();
    ch.dry_run = true;
    ch.set_overrides(Overrides { feed: 50.0, ..ch.overrides() }).unwrap();
    ch.run_program("BRISK G1 X100 F100\nM30").unwrap();
    let mut xs = vec![0.0];
    while ch.is_busy() {
        ch.step();
        xs.push(ch.axis_positions()[0]);
    }
    let t = move_time(&xs);
    assert!((t - 2.4139).abs() <= 2.0 * DT, "override 50 %: {t} s");
}

#[test]
fn programs_read_the_dry_run_setting_data() {
    // SD42100 defaults to 5000 mm/min, SD42101 to 0; a program reads them as `$SC_..`.
    let (ch, _) = run("$SC_DRY_RUN_FEED_MODE=12\n", &[], false, "R1=$SC_DRY_RUN_FEED\nR2=$SC_DRY_RUN_FEED_MODE\nM30");
    assert_ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (5000.0, 12.0));
}

#[test]
fn dry_run_off_runs_the_programmed_feed() {
    // DRY off, SD42100 = 5000 mode 2 set: F6000 = 100 mm/s: 1 + 100/3000 = 1.0333 s.
    let (ch, xs) = run("$SC_DRY_RUN_FEED_MODE=2\n", &[], false, "BRISK G1 X100 F6000\nM30");
    assert_ok(&ch);
    let t = move_time(&xs);
    assert!((t - 1.0333).abs() <= 2.0 * DT, "{t} s");
}
