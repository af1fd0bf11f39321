//! G643: block-internal rounding with axial tolerances (Function Manual B1 "Continuous-path
//! mode"): each axis within its own MD33100, over its own distance. Expected values are worked
//! out by hand in each test's comment.

use crate::path_support;

use path_support::DT;

/// X may leave its path by 0.2 mm, Y by 0.05 mm.
const TOL_MD: &str = "$MA_COMPRESS_POS_TOL[X]=0.2\n$MA_COMPRESS_POS_TOL[Y]=0.05\n";
const TOL_X: f64 = 0.2;
const TOL_Y: f64 = 0.05;

/// A right-angle corner at (10, 0): +X, then +Y, at 10 mm/s (0.04 mm per IPO cycle).
fn corner(mode: &str) -> Vec<[f64; 3]> {
    corner_at(mode, 600.0)
}

fn corner_at(mode: &str, feed: f64) -> Vec<[f64; 3]> {
    path_support::samples::<3>(TOL_MD, &format!("G90 G0 X0 Y0 Z0\n{mode} G1 X10 F{feed}\nY10\nM30"), 100_000).1
}

/// How far into the corner of the tolerance box the path reaches: for a point inside the
/// corner (x < 10, y > 0), X's distance from the second line (x = 10) and Y's from the first
/// (y = 0) as shares of their tolerances; the smaller share is what the point needs of both.
fn box_share(p: &[f64; 3]) -> f64 {
    ((10.0 - p[0]) / TOL_X).min(p[1] / TOL_Y)
}

#[test]
fn g643_keeps_each_axis_within_its_own_tolerance_and_uses_both() {
    // With d_k the axis' rounding distance (σ the path length from the corner), axis k is
    // 3/16·d_k·|Δ_k| off its programmed position at the corner and less elsewhere; Δ is 1 on
    // both axes of a right angle, so d_X = 16·0.2/3 = 1.0667 mm, d_Y = 0.2667 mm, and the
    // path passes (9.8, 0.05): the far corner of the box the two tolerances span. Every point
    // lies within a tolerance box of the contour (y ≤ 0.05 beside the first line, or
    // 10 − x ≤ 0.2 beside the second), and at 1 mm/s the samples (0.004 mm apart, Y moving
    // 0.5 mm per mm of σ at the corner: at most 0.0028 mm of σ from it, 0.03 of Y's share)
    // come within 5 % of (9.8, 0.05). G642 with one tolerance, the smaller (0.05), passes
    // within 0.05 of the corner (by the sampling's 0.004 mm); G643 keeps farther from it.
    let s = corner_at("G643", 60.0);
    for p in &s {
        assert!(p[1] <= TOL_Y + 1e-9 || 10.0 - p[0] <= TOL_X + 1e-9, "{p:?} outside both boxes");
        assert!(p[0] <= 10.0 + 1e-9 && p[1] >= -1e-9, "{p:?}");
    }
    let reach = s.iter().map(box_share).fold(f64::NEG_INFINITY, f64::max);
    assert!((0.95..=1.0 + 1e-9).contains(&reach), "G643 reaches {reach} of the box");
    let closest = |s: &[[f64; 3]]| s.iter().map(|p| (10.0 - p[0]).hypot(p[1])).fold(f64::INFINITY, f64::min);
    let g642 = closest(&corner_at("G642", 60.0));
    assert!(g642 <= TOL_Y + 0.004, "G642 passes {g642} from the corner");
    assert!(closest(&s) > g642 + 0.01, "G643 passes {} from the corner", closest(&s));
    assert_eq!(s.last().unwrap(), &[10.0, 10.0, 0.0]);
}

#[test]
fn the_axis_with_the_larger_tolerance_rounds_over_the_longer_distance() {
    // X's rounding runs to σ = d_X = 1.0667 mm past the corner, where Y has been on its line
    // (y = σ) since σ = d_Y = 0.2667: X is back at exactly 10 only from y = 1.0667 on. Y's
    // rounding starts at σ = −d_Y, where X, inside its own rounding since σ = −d_X, stands at
    // 10 + d_X·(x + φ(x)·(0 − 1)) with x = −0.25, φ = 2y³ − y⁴ at y = 0.375 (0.085693):
    // 10 − 1.0667·0.335693 = 9.6419. Both within one cycle's travel (0.04 mm).
    let s = corner("G643");
    let last_off = s.iter().filter(|p| 10.0 - p[0] > 1e-9 && p[1] > 0.0).map(|p| p[1]).fold(0.0, f64::max);
    assert!((last_off - 16.0 * TOL_X / 3.0).abs() <= 0.04, "X rounds until y = {last_off}");
    let first_y = s.iter().find(|p| p[1] > 1e-12).unwrap();
    assert!((first_y[0] - 9.6419).abs() <= 0.04, "Y leaves its line at x = {}", first_y[0]);
    // Under G642 (one distance for both) the element starts as far before the corner as it
    // ends after it: symmetric, unlike G643's 10 − 9.64 = 0.36 before and 1.07 after.
    let g = corner("G642");
    let before = 10.0 - g.iter().find(|p| p[1] > 1e-12).unwrap()[0];
    let after = g.iter().filter(|p| 10.0 - p[0] > 1e-9 && p[1] > 0.0).map(|p| p[1]).fold(0.0, f64::max);
    assert!((before - after).abs() <= 0.05, "G642: {before} before, {after} after");
}

#[test]
fn g643_passes_its_chain_at_the_feed_within_the_axis_limits() {
    // The chain of elements joins with equal tangent and curvature: between the ramps every
    // cycle moves F·T = 0.04 mm along the path (the chord of a cycle is short of its arc by
    // s³/(24·R²): 1.2e-4 mm where the chain is sharpest, R ≈ 0.15 mm as three samples there
    // give; a seam that slowed the path by 1 % would lose 4e-4 mm), and no axis exceeds
    // its velocity or acceleration in any cycle.
    let s = corner("G643");
    path_support::assert_dynamics(&s);
    let steps: Vec<f64> = s.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).collect();
    let full = |d: &f64| (d - 0.04).abs() < 2e-4;
    let (first, last) = (steps.iter().position(full).unwrap(), steps.iter().rposition(full).unwrap());
    let slow: Vec<(usize, f64)> = (first..=last).filter(|&i| !full(&steps[i])).map(|i| (i, steps[i])).collect();
    assert!(slow.is_empty(), "cycles off the feed: {slow:?}");
    // 20 mm at 10 mm/s: 2 s, less the rounding's shortcut; plus one ramp of 10/3000 s.
    let t = (s.len() - 1) as f64 * DT;
    assert!((1.95..2.05).contains(&t), "{t} s");
}

#[test]
fn g643_rounds_as_g642_next_to_an_arc() {
    // Line into a clockwise arc (a corner: the arc starts at -Y): G643 rounds as G642 with the
    // smaller tolerance there, so both produce the same path.
    let program = |m: &str| format!("G90 G0 X0 Y0\n{m} G1 X10 F600\nG2 X20 Y0 CR=5\nM30");
    let (_, a) = path_support::samples::<3>(TOL_MD, &program("G643"), 100_000);
    let (_, b) = path_support::samples::<3>(TOL_MD, &program("G642"), 100_000);
    assert_eq!(a, b);
}
