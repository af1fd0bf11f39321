//! Chains of moves under G64 pass their seams at the programmed feed (Function Manual B1,
//! continuous-path mode: "the velocity is not reduced at block transitions that are tangent").
//! Run through a whole channel on the 3-axis mill preset (X, Y, Z: 30 m/min, 3 m/s², IPO cycle
//! 4 ms). At F6000 = 100 mm/s the path moves F·T = 0.4 mm per cycle; it accelerates by
//! a·T = 12 mm/s per cycle, so from rest it takes 8 cycles of 12..96 mm/s and reaches the feed
//! in the 9th. Between the first and the last cycle at the feed, every cycle moves 0.4 mm: a
//! seam that slowed the path for one cycle (by about a·T/2 = 6 mm/s) shows as a step 0.024 mm
//! short. Under SOFT (G group 21) the same holds: a seam at the feed needs no braking, so the
//! jerk-limited profile passes it without a change of acceleration.

use crate::path_support;

use path_support::DT;

/// F6000 mm/min for one IPO cycle.
const STEP: f64 = 100.0 * DT;

/// The X, Y, Z samples of every IPO cycle of `program` on the 3-axis mill.
fn run(program: &str) -> Vec<[f64; 3]> {
    run_with("", program)
}

/// [`run`] with machine data `md` on top of the preset.
fn run_with(md: &str, program: &str) -> Vec<[f64; 3]> {
    path_support::samples(md, program, 1_000_000).1
}

/// The distance moved in each cycle.
fn steps(samples: &[[f64; 3]]) -> Vec<f64> {
    samples
        .windows(2)
        .map(|w| ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2) + (w[1][2] - w[0][2]).powi(2)).sqrt())
        .collect()
}

/// The first and last cycle at the feed (within `tol`), after checking that no cycle between
/// them is slower.
fn cruise(steps: &[f64], tol: f64) -> (usize, usize) {
    let full = |x: &f64| (x - STEP).abs() <= tol;
    let first = steps.iter().position(full).expect("the path reaches the feed");
    let last = steps.iter().rposition(full).unwrap();
    // The cycles before the path starts (block preparation) move nothing.
    let start = steps.iter().position(|&x| x > 0.0).unwrap();
    assert_eq!(first - start, 8, "8 cycles of acceleration before the first at the feed");
    let slow: Vec<(usize, f64)> = (first..=last).filter(|&i| !full(&steps[i])).map(|i| (i, steps[i])).collect();
    assert!(slow.is_empty(), "cycles below F·T between the ramps: {slow:?}");
    (first, last)
}

/// The 50 collinear blocks of 2 mm along X at F6000.
fn fifty_blocks(header: &str) -> String {
    let mut text = format!("G0 X0 Y0 Z0\n{header} G1 F6000\n");
    for i in 1..=50 {
        text.push_str(&format!("X{}\n", 2 * i));
    }
    text.push_str("M30\n");
    text
}

/// The largest third difference of X over T³ (the sampled jerk, mm/s³) and second (mm/s²).
fn jerk_and_accel(samples: &[[f64; 3]]) -> (f64, f64) {
    let v: Vec<f64> = samples.windows(2).map(|w| (w[1][0] - w[0][0]) / DT).collect();
    let a: Vec<f64> = v.windows(2).map(|w| (w[1] - w[0]) / DT).collect();
    let j = a.windows(2).map(|w| ((w[1] - w[0]) / DT).abs()).fold(0.0, f64::max);
    (j, a.iter().map(|x| x.abs()).fold(0.0, f64::max))
}

#[test]
fn under_soft_fifty_collinear_blocks_run_at_the_feed_within_the_jerk() {
    // MD32431 = 20 m/s³ on X: along X the path jerk is 20,000 mm/s³ (MD20600 is far above).
    // From rest to 100 mm/s the S curve needs no constant-acceleration phase (its peak,
    // sqrt(j·Δv) = sqrt(20000·100) = 1414 mm/s², is below the 3000 of MD32300): it takes
    // 2·sqrt(Δv/j) = 0.1414 s (35.4 cycles) and 100·0.1414/2 = 7.07 mm, and as much to brake.
    // The other 100 − 14.14 = 85.86 mm are 214.6 cycles at F·T = 0.4 mm. Every seam is planned
    // at the feed, so not one cycle between the ramps may be slower (before: the one-cycle
    // reserve of the braking check dipped the path at every seam, and the S curve then took
    // tens of cycles to recover, never reaching the feed), and the sampled jerk stays within
    // 20,000 mm/s³ in every cycle, the stop included.
    let samples =
        run_with("$MA_MAX_AX_JERK[X]=20\n$MA_MAX_AX_JERK[Y]=20\n$MA_MAX_AX_JERK[Z]=20\n", &fifty_blocks("SOFT G64"));
    let s = steps(&samples);
    let full = |x: &f64| (x - STEP).abs() <= 1e-9;
    let start = s.iter().position(|&x| x > 0.0).unwrap();
    let (first, last) = (s.iter().position(full).unwrap(), s.iter().rposition(full).unwrap());
    // (Sampled, the acceleration rises by j·T = 80 mm/s² from the first cycle on: one cycle
    // less than the continuous 35.4 may do.)
    assert!((34..=36).contains(&(first - start)), "{} cycles of acceleration", first - start);
    let slow: Vec<(usize, f64)> = (first..=last).filter(|&i| !full(&s[i])).map(|i| (i, s[i])).collect();
    assert!(slow.is_empty(), "cycles below F·T between the ramps: {slow:?}");
    assert!((212..=216).contains(&(last - first + 1)), "{} cycles at the feed", last - first + 1);
    let (jerk, accel) = jerk_and_accel(&samples);
    assert!(jerk <= 20_000.0 * (1.0 + 1e-6), "jerk {jerk} mm/s³");
    assert!(accel <= 1414.3, "acceleration {accel} mm/s²");
    assert!((samples.last().unwrap()[0] - 100.0).abs() < 1e-9);
}

#[test]
fn under_soft_with_the_presets_jerk_the_seams_pass_as_under_brisk() {
    // The preset's MD32431 of 1000 m/s³ builds the 3000 mm/s² in 3 ms, within one cycle: the
    // profile is BRISK's (8 cycles of 12 mm/s, then the feed) and, as under G64, no seam slows
    // it. The sampled jerk stays within 1000 m/s³ = 1e6 mm/s³.
    let samples = run(&fifty_blocks("SOFT G64"));
    let (first, last) = cruise(&steps(&samples), 1e-9);
    assert!(last - first + 1 >= 236, "{} cycles at the feed", last - first + 1);
    assert!(jerk_and_accel(&samples).0 <= 1e6 * (1.0 + 1e-9));
}

#[test]
fn fifty_collinear_blocks_pass_every_seam_at_the_feed() {
    // 50 blocks of 2 mm along X: 100 mm. From rest the path takes 8 cycles (12..96 mm/s,
    // 0.004·432 = 1.728 mm) to the feed; braking from 100 mm/s takes about as long, so about
    // 100 − 2·1.73 = 96.5 mm, 241 cycles, run at the feed.
    let samples = run(&fifty_blocks("G64"));
    let s = steps(&samples);
    let (first, last) = cruise(&s, 1e-9);
    assert!(last - first + 1 >= 236, "{} cycles at the feed", last - first + 1);
    assert!((samples.last().unwrap()[0] - 100.0).abs() < 1e-9);
}

#[test]
fn a_g64_chain_of_tangent_lines_and_arcs_runs_at_the_feed() {
    // X50 on a line, a quarter circle G3 of radius 20 to X70 Y20 (tangent +X at its start, +Y
    // at its end), a line to Y60, a quarter circle G2 of radius 20 to X90 Y80 (tangent +Y, then
    // +X), a line to X140: every transition tangent. On the arcs 100 mm/s needs a centripetal
    // 100²/20 = 500 mm/s², well within the axes' 3000 (the planner gives the arc
    // sqrt(0.5·3000·20) = 173 mm/s at most): the whole chain can run at the feed.
    // A cycle's chord on an arc is shorter than its 0.4 mm of path by 0.4·θ²/24 with
    // θ = 0.4/20 rad: 6.7e-6 mm; a slowed seam would be 0.024 mm short.
    let text = "G0 X0 Y0 Z0\nG64 G1 F6000 X50\nG3 X70 Y20 I0 J20\nG1 Y60\nG2 X90 Y80 I20 J0\nG1 X140\nM30\n";
    let samples = run(text);
    let s = steps(&samples);
    let (first, last) = cruise(&s, 1e-5);
    // 50 + 31.42 + 40 + 31.42 + 50 = 202.8 mm of path, less two ramps of ~1.73 mm: about 498
    // cycles at the feed.
    let length = 50.0 + 2.0 * (20.0 * std::f64::consts::FRAC_PI_2) + 40.0 + 50.0;
    assert!(last - first + 1 >= ((length - 2.0 * 1.728) / STEP) as usize - 5, "{} cycles", last - first + 1);
    let end = samples.last().unwrap();
    assert!((end[0] - 140.0).abs() < 1e-9 && (end[1] - 80.0).abs() < 1e-9);
}
