//! G645 at tangential transitions with a jump in curvature, and G644 by MD20480 (Function
//! Manual B1 "Continuous-path mode"). Expected values are worked out by hand in each test's
//! comment.

use crate::path_support;

use path_support::DT;

/// Runs `program` on the 3-axis mill with `md` on top: the X, Y setpoints of every IPO cycle.
fn run(md: &str, program: &str) -> Vec<[f64; 2]> {
    // The cycles after the start: the first sample is the position after the first cycle.
    path_support::samples(md, program, 200_000).1.split_off(1)
}

/// The contour: X0 Y0 → X20 (line), counter-clockwise quarter circle about (20, 10) with
/// R10 to (30, 10), then → Y30 (line). Both transitions are tangential (+X, then +Y), and at
/// both the curvature jumps between 0 and 1/10 mm⁻¹.
fn contour(header: &str) -> String {
    format!("G17 G90 G0 X0 Y0\n{header} G1 X20 F1200\nG3 X30 Y10 CR=10\nG1 Y30\nM30")
}

fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Distance of `p` from the contour of [`contour`].
fn to_contour(p: [f64; 2]) -> f64 {
    let angle = (p[1] - 10.0).atan2(p[0] - 20.0);
    let arc = if (-std::f64::consts::FRAC_PI_2..=0.0).contains(&angle) {
        ((p[0] - 20.0).hypot(p[1] - 10.0) - 10.0).abs()
    } else {
        (p[0] - 20.0).hypot(p[1]).min((p[0] - 30.0).hypot(p[1] - 10.0))
    };
    to_segment(p, [0.0, 0.0], [20.0, 0.0]).min(arc).min(to_segment(p, [30.0, 10.0], [30.0, 30.0]))
}

/// The k-th finite difference of the samples divided by `dt^k`, per axis.
fn diff(samples: &[[f64; 2]], k: usize) -> Vec<[f64; 2]> {
    let mut d = samples.to_vec();
    for _ in 0..k {
        d = d.windows(2).map(|w| [(w[1][0] - w[0][0]) / DT, (w[1][1] - w[0][1]) / DT]).collect();
    }
    d
}

fn max_abs(d: &[[f64; 2]]) -> f64 {
    d.iter().map(|v| v[0].abs().max(v[1].abs())).fold(0.0, f64::max)
}

/// The samples of the G1/G3 part (from leaving X0 Y0 on).
fn contour_part(samples: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    samples.into_iter().skip_while(|p| p[0] == 0.0 && p[1] == 0.0).collect()
}

#[test]
fn g645_smooths_a_line_into_a_tangent_arc_within_path_trans_pos_tol() {
    // At F1200 = 20 mm/s the samples are 0.08 mm apart. G645 replaces each transition by
    // a curvature-continuous element whose largest distance from the contour is MD33120 (0.005
    // mm by default; 0.02 here; the smallest of the geometry axes' counts) or 2 % less; the samples on the element come within 10 % of
    // the largest (at 0.08 mm spacing the crest of the element, about d²/(6R) ≈ 1 mm long,
    // is sampled several times). G642 leaves the transitions as programmed: every sample on
    // the contour.
    for tol in [0.005, 0.02] {
        let md = format!(
            "$MA_PATH_TRANS_POS_TOL[X]={tol}\n$MA_PATH_TRANS_POS_TOL[Y]={tol}\n$MA_PATH_TRANS_POS_TOL[Z]={tol}"
        );
        let s = contour_part(run(&md, &contour("G645")));
        let worst = s.iter().map(|&p| to_contour(p)).fold(0.0, f64::max);
        assert!(worst <= tol * 1.0001 && worst >= 0.85 * tol, "tolerance {tol}: deviation {worst}");
        assert_eq!(s.last().unwrap(), &[30.0, 30.0]);
    }
    let g642 = contour_part(run("$MA_PATH_TRANS_POS_TOL[X]=0.02\n$MA_PATH_TRANS_POS_TOL[Y]=0.02", &contour("G642")));
    let worst = g642.iter().map(|&p| to_contour(p)).fold(0.0, f64::max);
    assert!(worst < 1e-9, "G642 left the contour by {worst}");
}

/// Per cycle, the curvature of the sampled path (1/mm): the turn between two consecutive
/// steps over their mean length. Geometric, so the planner's speed profile does not enter.
fn curvature(samples: &[[f64; 2]]) -> Vec<f64> {
    let v = diff(samples, 1);
    v.windows(2)
        .map(|w| {
            let turn = (w[0][0] * w[1][1] - w[0][1] * w[1][0]).atan2(w[0][0] * w[1][0] + w[0][1] * w[1][1]);
            turn.abs() / (0.5 * (w[0][0].hypot(w[0][1]) + w[1][0].hypot(w[1][1])) * DT)
        })
        .collect()
}

#[test]
fn g645_removes_the_curvature_jump_and_so_the_acceleration_jump() {
    // On the arc the curvature is 1/R = 0.1 mm⁻¹ and at 20 mm/s the normal acceleration
    // v²/R = 40 mm/s². Under G642 the curvature jumps from 0 to 0.1 where the line meets the
    // arc: between two cycles it changes by 0.1 (or by two steps of which one is ≥ 0.05 when
    // a cycle straddles the joint), the acceleration by 40 mm/s² at once. Under G645 (0.02 mm)
    // the element, about 8 mm long here (the search takes the largest cut-back within the
    // tolerance: a quintic between a line and a circle deviates far less than a clothoid of
    // its length), builds the curvature up over ≈ 0.4 s = 100 cycles: 0.001 per cycle on
    // average, a quintic's steepest part under twice that; allow 0.003.
    let md = "$MA_PATH_TRANS_POS_TOL[X]=0.02\n$MA_PATH_TRANS_POS_TOL[Y]=0.02\n$MA_PATH_TRANS_POS_TOL[Z]=0.02";
    // Only the constant-speed part (from X5 to Y25): the start and the end are the planner's.
    let middle = |s: Vec<[f64; 2]>| -> Vec<[f64; 2]> { s.into_iter().filter(|p| p[0] > 5.0 && p[1] < 25.0).collect() };
    let step = |s: &[[f64; 2]]| curvature(s).windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
    let g642 = step(&middle(run(md, &contour("G642"))));
    let g645 = step(&middle(run(md, &contour("G645"))));
    assert!(g642 >= 0.05, "G642: curvature step {g642} 1/mm");
    assert!(g645 <= 0.003, "G645: curvature step {g645} 1/mm");
    // Within F everywhere; no axis beyond the preset's 3 m/s² along the contour (the
    // planner's last braking cycle at the program end, the same under G64, is not this
    // test's).
    let s = contour_part(run(md, &contour("G645")));
    let v = diff(&s, 1).iter().map(|d| d[0].hypot(d[1])).fold(0.0, f64::max);
    assert!(v <= 20.02, "path speed {v}");
    let a = max_abs(&diff(&middle(s), 2));
    assert!(a <= 3000.0 * (1.0 + 1e-6), "axis acceleration {a}");
}

#[test]
fn g645_rounds_corners_like_g642_and_collinear_lines_stay() {
    // A square corner X0→20, then Y20 under CTOL 0.05: G645 and G642 give the same samples
    // (corners are rounded alike); a collinear transition X10 → X20 has no curvature jump and
    // is left alone by both.
    let square = |g: &str| run("", &format!("G0 X0 Y0\n{g} CTOL=0.05 G1 X10 F3000\nX20\nY20\nM30"));
    assert!(square("G645") == square("G642"), "G645 rounded the square unlike G642");
}

#[test]
fn g644_rounds_by_mode_thousands_digit_and_ignores_ctol() {
    // MD20480 thousands digit 1: G644 rounds by ADIS as G641 does.
    let corner = |md: &str, g: &str| run(md, &format!("G0 X0 Y0\n{g} G1 X10 F600\nY10\nM30"));
    let by_adis = corner("$MC_SMOOTHING_MODE=1000", "G644 ADIS=0.5");
    assert!(by_adis == corner("", "G641 ADIS=0.5"), "G644 (1xxx) is not G641");
    // Thousands digit 0: MD33100 (0.1 mm by default); CTOL does not act on G644 (B1: G644 is
    // for moves in air), while it does on G642.
    let g644 = corner("", "G644");
    assert!(g644 == corner("", "G644 CTOL=0.5"), "CTOL changed G644");
    assert!(corner("", "G642") != corner("", "G642 CTOL=0.5"), "CTOL did not change G642");
    // The G644 element passes (10, 0) at 0.1 mm (2 % less at most); the samples, 0.04 mm
    // apart at F600, come within 10 % of that.
    let cut = g644.iter().map(|p| (p[0] - 10.0).hypot(p[1])).fold(f64::INFINITY, f64::min);
    assert!((0.09..=0.11).contains(&cut), "G644 cut the corner by {cut}");
}

/// Distance of `p` from the square (0, 0)..(20, 20) (its outline).
fn to_square(p: [f64; 2]) -> f64 {
    let corners = [[0.0, 0.0], [20.0, 0.0], [20.0, 20.0], [0.0, 20.0], [0.0, 0.0]];
    corners.windows(2).map(|w| to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min)
}

#[test]
fn under_trc_g645_smooths_the_transition_circles_and_the_tool_never_gouges() {
    // T1 D1 (radius 5) G42 round the square (0, 0)..(20, 20) counter-clockwise: the tool
    // centre runs outside on the offset lines and, at the three outer corners, on G450's
    // transition circles of radius 5 about them, so on the offset contour every point is
    // exactly 5 mm from the square. Line and transition circle meet tangentially with a
    // curvature jump (0 to 1/5 mm⁻¹): G642 leaves it (every sample 5 mm from the square),
    // G645 smooths it within MD33120 = 0.02 mm: the samples stay within 5 ± 0.02 mm of the
    // square (the tool never comes nearer than radius − tolerance) and leave the offset
    // contour by more than half the tolerance. The approach and retract at (0, 0) are not
    // the contour: samples with x < 1 and y < 1 are left out.
    let md = "$MA_PATH_TRANS_POS_TOL[X]=0.02\n$MA_PATH_TRANS_POS_TOL[Y]=0.02\n$MA_PATH_TRANS_POS_TOL[Z]=0.02";
    let program =
        |g: &str| format!("T1 D1\nG0 X-10 Y-5 Z0\n{g}\nG1 F3000 G42 X0 Y0\nX20\nY20\nX0\nY0\nG40 X-10 Y-5\nM30");
    let band = |g: &str| -> Vec<f64> {
        let s = run(md, &program(g));
        s.into_iter().filter(|p| !(p[0] < 1.0 && p[1] < 1.0)).map(|p| to_square(p) - 5.0).collect()
    };
    let g642 = band("G642");
    assert!(g642.len() > 300 && g642.iter().all(|d| d.abs() < 1e-9), "G642 left the offset contour");
    let g645 = band("G645");
    let (lo, hi) = g645.iter().fold((0.0f64, 0.0f64), |(lo, hi), &d| (lo.min(d), hi.max(d)));
    assert!(lo >= -0.02 * 1.0001 && hi <= 0.02 * 1.0001, "G645: {lo}..{hi} mm off the offset contour");
    assert!(lo.abs().max(hi) > 0.01, "G645 did not smooth: {lo}..{hi}");
}
