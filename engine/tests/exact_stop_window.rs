//! The exact-stop windows of G group 12 under the servo model (Function Manual B1 "Exact
//! stop"): with FFWOF the block after a G60 move starts once every axis' following error is
//! inside MD36010 STOP_LIMIT_FINE (G601), MD36000 STOP_LIMIT_COARSE (G602), or at the
//! interpolator's end (G603). Expected values are worked out by hand in each test's comment.

use crate::path_support;

use path_support::DT;

/// Runs `program` on the 3-axis mill with `md` on top; the X and Y setpoints of every IPO
/// cycle.
fn run(md: &str, program: &str) -> Vec<[f64; 2]> {
    // The cycles after the start: the first sample is the position after the first cycle.
    path_support::samples(md, program, 100_000).1.split_off(1)
}

/// The cycles between the setpoint of `axis` reaching `at` and its first step away: the wait
/// at the exact stop (2 when the next block starts at once: the interpolator's one cycle at
/// rest after every stop, `exact_stop_reversal.rs`, then the first step).
fn wait(samples: &[[f64; 2]], axis: usize, at: f64) -> usize {
    let arrive = samples.iter().position(|p| p[axis] == at).expect("reaches the end point");
    samples[arrive..].iter().position(|p| p[axis] != at).expect("leaves again")
}

/// The samples from the first that leaves the start point (X0 Y0): a block that changes only G
/// functions may cost the preparation a cycle before the first move.
fn moving(samples: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    samples.into_iter().skip_while(|p| *p == [0.0, 0.0]).collect()
}

fn program(window: &str, ffw: &str) -> String {
    format!("{ffw} G60 {window}\nG1 X100 F6000\nX0\nM30")
}

#[test]
fn under_ffwof_g601_waits_longer_than_g602_than_g603() {
    // X moves at 6 m/min = 100 mm/s and brakes at the preset's 3000 mm/s² in T = v/a =
    // 1/30 s. Kv = 1 (m/min)/mm = 1000/60 = 16.667 1/s. During the constant speed the error is
    // v/Kv = 6 mm; while braking linearly, e(t) = v(t)/Kv + a/Kv²·(1 − e^(−Kv·t)), so at the
    // interpolator's end e = 3000/277.78·(1 − e^(−0.5556)) = 10.8·0.4262 = 4.603 mm. Then the
    // setpoint stands and e decays as e^(−Kv·t), Kv·dt = 0.06667 per cycle:
    // - G603: no wait; the interpolator stands for one cycle after the stop and the next
    //   block steps away in the cycle after it: 2.
    // - G602 (0.04 mm): ln(4.603/0.04)/0.06667 = 71.2, so 72 cycles inside, starting at 73.
    // - G601 (0.01 mm): ln(460.3)/0.06667 = 91.97, so 92 cycles, starting at 93.
    // The staircase of the discrete braking moves e at the end by a few percent (< 1 cycle);
    // allow 2 cycles.
    let g603 = wait(&run("", &program("G603", "FFWOF")), 0, 100.0);
    let g602 = wait(&run("", &program("G602", "FFWOF")), 0, 100.0);
    let g601 = wait(&run("", &program("G601", "FFWOF")), 0, 100.0);
    assert_eq!(g603, 2);
    assert!(g602.abs_diff(73) <= 2, "G602 waited {g602} cycles");
    assert!(g601.abs_diff(93) <= 2, "G601 waited {g601} cycles");
    // The difference does not depend on the error at the end: ln(0.04/0.01)/(Kv·dt) = 20.8.
    assert!((g601 - g602).abs_diff(21) <= 1, "G601 − G602 = {} cycles", g601 - g602);
}

#[test]
fn the_slowest_position_loop_decides_the_wait() {
    // X and Y both move 100 mm (a diagonal), Y with Kv = 0.5 (m/min)/mm = 8.333 1/s: its
    // error is twice X's and decays half as fast, so it is the last inside any window. Between
    // the windows 0.04 and 0.01 it needs ln 4/(8.333·0.004) = 41.6 cycles: G601 waits 41 or 42
    // cycles longer than G602 (X alone would make it 21).
    let md = "$MA_POSCTRL_GAIN[Y]=0.5";
    let diag = |w: &str| format!("FFWOF G60 {w}\nG1 X100 Y100 F6000\nX0 Y0\nM30");
    let g602 = wait(&run(md, &diag("G602")), 1, 100.0);
    let g601 = wait(&run(md, &diag("G601")), 1, 100.0);
    assert!((g601 - g602).abs_diff(42) <= 1, "G601 − G602 = {} cycles", g601 - g602);
    // A larger coarse window shortens G602's wait by ln(0.4/0.04)/(8.333·0.004) = 69.1 cycles.
    let wide = wait(&run(&format!("{md}\n$MA_STOP_LIMIT_COARSE[Y]=0.4"), &diag("G602")), 1, 100.0);
    assert!((g602 - wide).abs_diff(69) <= 1, "the wider window saved {} cycles", g602 - wide);
}

#[test]
fn with_ffwon_or_in_continuous_path_mode_the_windows_change_nothing() {
    // FFWON (the presets' reset value): the following error is zero, every window is reached
    // at the interpolator's end, and the three functions give the same samples bit for bit.
    let on: Vec<_> = ["G601", "G602", "G603"].iter().map(|w| moving(run("", &program(w, "FFWON")))).collect();
    assert!(on[0] == on[1] && on[0] == on[2], "the windows changed the samples under FFWON");
    assert_eq!(wait(&on[0], 0, 100.0), 2);
    // G64 under FFWOF: the stop before M30 is implicit, no programmed exact stop, so the
    // program ends at the interpolator's end under every window (the Programming Manual makes
    // G601..G603 effective only with G60 or G9).
    let g64 = |w: &str| moving(run("", &format!("FFWOF G64 {w}\nG1 X100 F6000\nY10\nM30")));
    assert!(g64("G601") == g64("G603"), "the windows changed the samples under G64");
    // G9 asks for the exact stop in its block alone.
    let g9 = run("", "FFWOF G64 G601\nG1 X100 F6000 G9\nX0\nM30");
    assert!(wait(&g9, 0, 100.0).abs_diff(93) <= 2);
    // The time spent waiting is real time: the wait is 92 × 4 ms = 0.37 s.
    assert!((wait(&g9, 0, 100.0) as f64 * DT - 0.372).abs() <= 2.0 * DT);
}

#[test]
fn exact_pos_mode_fixes_the_window_for_g0_and_for_g1() {
    // MD20550 = 03: G0 always at the interpolator end (units digit 3), G1 as programmed (tens
    // digit 0). A G0 move under G601 then starts the next block after the cycle at rest; the
    // G1 move of the first test still waits its 93 cycles (the rest cycle lies within the wait).
    let md = "$MC_EXACT_POS_MODE=3";
    let rapid = run(md, "FFWOF G60 G601\nG0 X100\nG1 X0 F6000\nM30");
    assert_eq!(wait(&rapid, 0, 100.0), 2);
    assert!(wait(&run(md, &program("G601", "FFWOF")), 0, 100.0).abs_diff(93) <= 2);
    // MD20550 = 20: G1 always with the coarse window, whatever is programmed: G601 waits
    // as G602 (73 cycles).
    let coarse = wait(&run("$MC_EXACT_POS_MODE=20", &program("G601", "FFWOF")), 0, 100.0);
    assert!(coarse.abs_diff(73) <= 2, "G601 under MD20550 = 20 waited {coarse} cycles");
}
