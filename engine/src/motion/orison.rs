//! ORISON, smoothing of the orientation characteristic (Function Manual F2 3.9.4,
//! Programming Manual "Smoothing the orientation characteristic (ORISON, ORISOF)"): a 5-axis
//! CAM program whose tool tip runs smoothly but whose orientation changes in steps from block
//! to block (a kink of the orientation at every block end) gets an orientation that turns
//! smoothly across the block ends, never farther than SD42678 `$SC_ORISON_TOL` (degrees)
//! from the programmed one and over at most SD42680 `$SC_ORISON_DIST` of path. The tool tip
//! keeps its programmed path: only the orientation along it changes.
//!
//! How it is modelled (the manuals name the limits, not the method):
//! - A run is a sequence of smoothable blocks (under ORISON, vector-interpolated as a great
//!   circle, no longer than MD20178 `$MC_ORISON_BLOCK_PATH_LIMIT`, no exact stop between them,
//!   the same transformation). At every block end inside it where the orientation's rate per
//!   mm steps (a kink: rate `a` before, `b` after) the correction `(b − a)·bump(s − s_j, r)`
//!   is added to the programmed tool vector and the sum normalised, `bump` being half of |x|
//!   convolved with a triangle kernel of half width `r` less |x| (`orientation::bump`): it
//!   cancels the kink and is C2, so the tool vector turns without a jump of its angular rate,
//!   and is zero beyond `r`, so the section `s_j ± r` is the path the step may deviate over
//!   (SD42680 `$SC_ORISON_DIST`: `2r` at most that). Where the rate's magnitude changes at a
//!   step (the circles' curvature −κ²·o differs) a jump of the angular acceleration of the
//!   order of that change times the deviation's sine remains: the rate is what is smoothed.
//! - Sections of neighbouring steps may overlap: on blocks shorter than SD42680 a section
//!   reaches over several blocks and several steps' corrections add up. With equal `r` the
//!   sum is the programmed orientation convolved with the triangle kernel (a moving average
//!   over `2r` of path), so an orientation that wobbles from block to block is flattened to
//!   its mean where the tolerance allows (with `r` a whole number of wobble periods exactly).
//! - The deviation is the angle between the smoothed and the programmed tool vector at the
//!   same path point (the tip path is untouched), sampled over the section (32 points and
//!   every block end in it) with all the steps decided before; where it passes SD42678
//!   `$SC_ORISON_TOL` the section is made shorter until it keeps it. Each point is checked by
//!   the last step decided whose section covers it, with all others covering it known, so
//!   the sum keeps the tolerance everywhere (to the sampling).
//! - MD28590 `$MC_MM_ORISON_BLOCKS` is the block memory: a section reaches at most
//!   `(MD28590 − 2) / 2` blocks to either side of its step (MD28590 = 4, the least the
//!   function needs, keeps it within the two blocks at the step), at most 8 (the window the
//!   main run holds, `channel/smoothing/orison.rs`).
//! - A block end without a kink, a rapid, spline, compressed (COMPON ...) or orientation-
//!   only block, an orientation interpolated through the rotary axes (ORIAXES) or on a cone,
//!   and a block longer than MD20178 leave the orientation as programmed there.

use super::orientation::{OriKink, OriPath, Vec3, angle, cross, dot, norm};
use super::planner::Move;

/// The most blocks a section reaches to either side of its step (the main run's window).
pub const MAX_REACH: usize = 8;

/// The limits ORISON smooths within, read at block preparation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OriSmoothing {
    /// SD42678 ORISON_TOL in radians: the largest angle from the programmed orientation.
    pub tol: f64,
    /// SD42680 ORISON_DIST (mm): the longest section one step is smoothed over.
    pub dist: f64,
    /// MD20178 ORISON_BLOCK_PATH_LIMIT (mm): longer blocks are not smoothed.
    pub block_limit: f64,
    /// Blocks a section reaches to either side of its step (from MD28590, 1..=[`MAX_REACH`]).
    pub reach: usize,
}

impl OriSmoothing {
    /// The reach MD28590 `blocks` allows (see the module doc; at least 4 blocks enable it).
    pub fn reach_of(blocks: i64) -> usize {
        usize::try_from((blocks - 2) / 2).unwrap_or(0).clamp(1, MAX_REACH)
    }
}

/// Samples of a section checked against the tolerance, beside the block ends in it.
const SAMPLES: u32 = 32;

/// True if `mv` is a block ORISON smooths at its ends (see the module doc).
pub fn smoothable(mv: &Move) -> bool {
    let Some(spec) = mv.orison.as_deref() else { return false };
    mv.axis_tangents.is_some()
        && mv.compress.is_none()
        && !mv.machine_space
        && !mv.is_rapid()
        && mv.path.curve.is_none()
        && mv.length > 0.0
        && mv.length <= spec.block_limit
        && mv
            .path
            .ori
            .as_deref()
            .is_some_and(|o| o.curve.is_none() && o.turn.is_none() && dot(o.axis, o.start).abs() < 1e-9)
}

/// True if a run under ORISON goes on from `a` into the next move `b` (the same
/// transformation is the caller's to check): the step between them may be smoothed.
pub fn continues(a: &Move, b: &Move) -> bool {
    let Some(spec) = a.orison.as_deref() else { return false };
    spec.tol > 0.0
        && spec.dist > 0.0
        && !a.exact_stop
        && smoothable(a)
        && smoothable(b)
        && matches!((a.path.ori.as_deref(), b.path.ori.as_deref()),
            (Some(oa), Some(ob)) if angle(oa.programmed_at(1.0), ob.programmed_at(0.0)) <= 1e-9)
}

/// The step of the orientation's rate per mm at the end between `a` and `b` (`b`'s rate at
/// its start less `a`'s at its end); zero where either has no orientation.
pub fn jump(a: &Move, b: &Move) -> Vec3 {
    match (a.path.ori.as_deref(), b.path.ori.as_deref()) {
        (Some(oa), Some(ob)) => {
            let (ra, rb) = (rate(oa, 1.0, a.length), rate(ob, 0.0, b.length));
            std::array::from_fn(|i| rb[i] - ra[i])
        }
        _ => [0.0; 3],
    }
}

/// The blocks of a run in view, each with its start on the run's path (mm).
#[derive(Debug, Default)]
pub struct Window<'a> {
    blocks: Vec<(f64, f64, &'a OriPath)>,
}

impl<'a> Window<'a> {
    /// Appends the block of `length` mm starting at `start` with the orientation `ori`.
    pub fn push(&mut self, start: f64, length: f64, ori: &'a OriPath) {
        self.blocks.push((start, length, ori));
    }

    /// The programmed orientation at path position `s` (clamped to the blocks in view).
    fn programmed(&self, s: f64) -> Vec3 {
        let i = self.blocks.partition_point(|b| b.0 + b.1 < s).min(self.blocks.len() - 1);
        let (start, length, ori) = self.blocks[i];
        ori.programmed_at((s - start) / length)
    }
}

/// The step at `at` with the rate jump `jump` (per mm) smoothed over the longest half
/// section up to `most` that keeps `tol` (radians) with the steps decided before (`fixed`,
/// mm of the run's path); `None` where there is no kink or no section keeps it.
pub fn decide(window: &Window, fixed: &[OriKink], at: f64, jump: Vec3, most: f64, tol: f64) -> Option<OriKink> {
    if norm(jump) < 1e-9 || window.blocks.is_empty() {
        return None;
    }
    let limit = tol * (1.0 - 1e-3);
    let mut half = most;
    while half > 1e-6 {
        let step = OriKink { at, half, jump };
        let deviation = deviation(window, fixed, &step);
        if deviation <= limit {
            return Some(step);
        }
        // The deviation grows about linearly with the section's length.
        half *= (0.95 * limit / deviation).clamp(0.05, 0.95);
    }
    None
}

/// The largest angle between the smoothed and the programmed orientation over `step`'s
/// section, with the `fixed` steps' corrections too.
fn deviation(window: &Window, fixed: &[OriKink], step: &OriKink) -> f64 {
    let (from, to) = (step.at - step.half, step.at + step.half);
    let uniform = (1..SAMPLES).map(|i| from + (to - from) * f64::from(i) / f64::from(SAMPLES));
    let ends = window.blocks.iter().map(|b| b.0 + b.1).filter(|&e| e > from && e < to);
    let fixed: Vec<&OriKink> = fixed.iter().filter(|k| k.reaches(from, to)).chain(std::iter::once(step)).collect();
    // The squared chord between the unit vectors: the largest is the largest angle's.
    let chord = uniform
        .chain(ends)
        .map(|s| {
            let programmed = window.programmed(s);
            let mut v = programmed;
            for k in &fixed {
                let (d, _) = k.offset(s);
                v = std::array::from_fn(|i| v[i] + d[i]);
            }
            let n = norm(v);
            (0..3).map(|i| (v[i] / n - programmed[i]).powi(2)).sum::<f64>()
        })
        .fold(0.0, f64::max);
    2.0 * (0.5 * chord.sqrt()).min(1.0).asin()
}

/// The orientation's rate per mm of a great circle `o` at `u` (`l` the block's length).
fn rate(o: &OriPath, u: f64, l: f64) -> Vec3 {
    cross(o.axis, o.programmed_at(u)).map(|x| x * o.angle / l)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::registry::MAX_CHANNEL_AXES;
    use crate::motion::path::Path;
    use crate::motion::planner::{AxisLimit, Feed};

    /// The tool tilted 20° towards +X, turned by `theta` degrees towards −Y on the great
    /// circle through it perpendicular to k = (cos 20°, 0, −sin 20°):
    /// o(θ) = (cos θ·sin 20°, −sin θ, cos θ·cos 20°).
    fn o(theta: f64) -> Vec3 {
        let (s, c) = theta.to_radians().sin_cos();
        let (s20, c20) = 20f64.to_radians().sin_cos();
        [c * s20, -s, c * c20]
    }

    /// A line of `len` mm along X from `x` whose orientation turns from θ0 to θ1 (degrees).
    fn block(x: f64, len: f64, theta0: f64, theta1: f64, tol_deg: f64, dist: f64) -> Move {
        let (mut s, mut e) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (s[0], e[0]) = (x, x + len);
        let mut path = Path::line(s, e);
        path.ori = OriPath::great_circle(o(theta0), o(theta1)).unwrap().map(Box::new);
        let lim = vec![AxisLimit { max_velocity: 200.0, max_accel: 2000.0, accel_overload: 1.2 }; 6];
        let mut mv = Move::new(path, len, Feed::Path(10.0), &lim, false, 1);
        mv.axis_tangents = Some(Box::new(([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES])));
        mv.orison = Some(Box::new(OriSmoothing { tol: tol_deg.to_radians(), dist, block_limit: 50.0, reach: 4 }));
        mv
    }

    /// The signed angle θ of a unit vector on that great circle.
    fn theta(v: Vec3) -> f64 {
        let (s20, c20) = 20f64.to_radians().sin_cos();
        (-v[1]).atan2(v[0] * s20 + v[2] * c20).to_degrees()
    }

    /// `mv` with the steps (mm of a run whose path starts where `mv` starts at `start`).
    fn smoothed(mut mv: Move, start: f64, steps: &[OriKink]) -> Move {
        let len = mv.length;
        let o = mv.path.ori.as_deref_mut().unwrap();
        o.kinks = steps.iter().filter(|k| k.reaches(start, start + len)).map(|k| k.rescaled(start, len)).collect();
        mv
    }

    #[test]
    fn a_zigzag_kink_is_smoothed_to_the_value_by_hand() {
        // −2° → +2° → −2° over 1 mm blocks: +4°/mm, then −4°/mm, a step of −8°/mm at X1.
        // With r = 0.5 mm (half of either block) the correction at the step is 8°/mm·r/6 =
        // 0.667° (bump(0) = r/6) against the programmed +2°: θ = 1.333° there, the largest
        // deviation (bump falls off to both sides). The slope of bump goes from +½ to −½, so
        // the rate at the step is the mean of ±4°/mm: 0 from both sides; at the section's
        // edge (X0.5) bump's slope is 0: the programmed 4°/mm.
        let (a, b) = (block(0.0, 1.0, -2.0, 2.0, 1.0, 5.0), block(1.0, 1.0, 2.0, -2.0, 1.0, 5.0));
        assert!(continues(&a, &b));
        let mut window = Window::default();
        window.push(0.0, 1.0, a.path.ori.as_deref().unwrap());
        window.push(1.0, 1.0, b.path.ori.as_deref().unwrap());
        let step = decide(&window, &[], 1.0, jump(&a, &b), 0.5, 1f64.to_radians()).expect("a kink to smooth");
        assert!((step.half - 0.5).abs() < 1e-12, "{}", step.half);
        assert!((norm(step.jump).to_degrees() - 8.0).abs() < 1e-9);
        let (a, b) = (smoothed(a, 0.0, &[step]), smoothed(b, 1.0, &[step]));
        let (oa, ob) = (a.path.ori.as_ref().unwrap(), b.path.ori.as_ref().unwrap());
        assert!((theta(oa.at(1.0)) - (2.0 - 8.0 * 0.5 / 6.0)).abs() < 1e-3, "{}", theta(oa.at(1.0)));
        assert!(angle(oa.at(1.0), ob.at(0.0)) < 1e-12);
        // Before the section (u < ½) the orientation is the programmed one.
        assert!(angle(oa.at(0.25), o(-1.0)) < 1e-12);
        let h = 1e-6;
        let (left, right) =
            ((theta(oa.at(1.0)) - theta(oa.at(1.0 - h))) / h, (theta(ob.at(h)) - theta(ob.at(0.0))) / h);
        assert!(left.abs() < 1e-3 && right.abs() < 1e-3, "{left} {right}");
        let at_seam = (theta(oa.at(0.5 + h)) - theta(oa.at(0.5))) / h;
        assert!((at_seam - 4.0).abs() < 1e-3, "{at_seam}");
    }

    #[test]
    fn a_tighter_tolerance_shortens_the_section() {
        // The deviation is 8°/mm·r/6 = (4/3)°/mm·r: within 0.5° r ≤ 0.375 mm. From 0.5 (0.667°)
        // one shortening step by 0.95·0.4995/0.667 lands at r = 0.356 mm (0.474°).
        let (a, b) = (block(0.0, 1.0, -2.0, 2.0, 0.5, 5.0), block(1.0, 1.0, 2.0, -2.0, 0.5, 5.0));
        let mut window = Window::default();
        window.push(0.0, 1.0, a.path.ori.as_deref().unwrap());
        window.push(1.0, 1.0, b.path.ori.as_deref().unwrap());
        let step = decide(&window, &[], 1.0, jump(&a, &b), 0.5, 0.5f64.to_radians()).unwrap();
        assert!(step.half <= 0.375 && step.half > 0.3, "{}", step.half);
    }

    #[test]
    fn overlapping_sections_flatten_a_wobble_to_its_mean() {
        // 0.25 mm blocks whose θ zig-zags ±0.1° (kinks of ±1.6°/mm), sections of r = 0.5 mm
        // (2 blocks either side): inside, the sum of the corrections is the zig-zag convolved
        // with the triangle kernel of half width 0.5, i.e. averaged twice over 0.5 mm, its
        // period: the mean 0° (up to the O(θ³) of vectors against angles). Each step is
        // checked with the ones before only; the first alone deviates 1.6·0.5/6 = 0.133°,
        // within the 0.2°, and later ones cancel part of it.
        let n = 16;
        let th = |i: usize| if i.is_multiple_of(2) { -0.1 } else { 0.1 };
        let moves: Vec<Move> = (0..n).map(|i| block(0.25 * i as f64, 0.25, th(i), th(i + 1), 0.2, 1.0)).collect();
        let mut window = Window::default();
        for (i, m) in moves.iter().enumerate() {
            window.push(0.25 * i as f64, 0.25, m.path.ori.as_deref().unwrap());
        }
        let mut steps: Vec<OriKink> = Vec::new();
        for i in 1..n {
            let s = 0.25 * i as f64;
            let most = 0.5f64.min(s).min(0.25 * n as f64 - s);
            let step = decide(&window, &steps, s, jump(&moves[i - 1], &moves[i]), most, 0.2f64.to_radians());
            let step = step.expect("a section");
            assert!((step.half - most).abs() < 1e-12, "step {i}: {}", step.half);
            steps.push(step);
        }
        for (i, m) in moves.into_iter().enumerate() {
            let m = smoothed(m, 0.25 * i as f64, &steps);
            let o = m.path.ori.as_deref().unwrap();
            for j in 0..=10 {
                let (u, s) = (f64::from(j) / 10.0, 0.25 * (i as f64 + f64::from(j) / 10.0));
                let (smooth, programmed) = (theta(o.at(u)), theta(o.programmed_at(u)));
                assert!((smooth - programmed).abs() <= 0.2, "X{s}: {smooth} against {programmed}");
                if (1.0..=3.0).contains(&s) {
                    assert!(smooth.abs() < 1e-3, "X{s}: {smooth}");
                }
            }
        }
    }

    #[test]
    fn the_bump_cancels_a_kink_and_fades_out_c2() {
        use crate::motion::orientation::bump;
        // r = 0.5: bump(0) = r/6; its slope +½ left of 0 and −½ right (|x| less its mean
        // slope); at ±r value, slope and curvature (2/r − 2|x|/r²)/2 reach 0.
        let r = 0.5;
        assert!((bump(0.0, r).0 - r / 6.0).abs() < 1e-15);
        assert!((bump(-1e-12, r).1 - 0.5).abs() < 1e-9 && (bump(1e-12, r).1 + 0.5).abs() < 1e-9);
        let h = 1e-4;
        for x in [-r, r] {
            let inside = x - x.signum() * h;
            assert!(bump(inside, r).0.abs() < 1e-11 && bump(inside, r).1.abs() < 1e-7, "{x}");
            let curvature = (bump(inside, r).1 - bump(inside - x.signum() * h, r).1) / h;
            assert!(curvature.abs() < 1e-3, "{x}: {curvature}");
        }
        // At x = r/2 = 0.25 by hand: r/3 = 1/6, x²/r = 0.125, |x|³/(3r²) = 0.015625/0.75 =
        // 0.125/6, |x| = 0.25: (1/6 + 0.125 − 0.125/6 − 0.25)/2 = 0.0104.
        assert!((bump(0.25, r).0 - (1.0 / 6.0 + 0.125 - 0.125 / 6.0 - 0.25) / 2.0).abs() < 1e-15);
    }

    #[test]
    fn no_kink_or_no_orison_leaves_the_orientation() {
        let (a, b) = (block(0.0, 1.0, -2.0, 2.0, 1.0, 5.0), block(1.0, 1.0, 2.0, 6.0, 1.0, 5.0));
        assert!(continues(&a, &b) && norm(jump(&a, &b)) < 1e-9);
        let (a, b) = (block(0.0, 1.0, -2.0, 2.0, 0.0, 5.0), block(1.0, 1.0, 2.0, -2.0, 0.0, 5.0));
        assert!(!continues(&a, &b));
        let (mut a, b) = (block(0.0, 1.0, -2.0, 2.0, 1.0, 5.0), block(1.0, 1.0, 2.0, -2.0, 1.0, 5.0));
        a.orison.as_mut().unwrap().block_limit = 0.5;
        assert!(!continues(&a, &b));
        assert_eq!(OriSmoothing::reach_of(4), 1);
        assert_eq!(OriSmoothing::reach_of(10), 4);
        assert_eq!(OriSmoothing::reach_of(100), MAX_REACH);
    }
}
