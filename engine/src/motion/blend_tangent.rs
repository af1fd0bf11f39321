//! G645's second job (Function Manual B1 "Smoothing with G645"): a block transition whose
//! tangents agree but whose curvature jumps (a line into a tangent arc, two arcs of different
//! radius) is smoothed too, within MD33120 `$MA_PATH_TRANS_POS_TOL`, so the axes'
//! acceleration has no jump there either.
//!
//! The element is the same curvature-continuous quintic as at a corner (`blend.rs`); what
//! differs is how far it may go: at a corner the measure is its distance from the corner
//! point, at a tangential transition the programmed corner point lies on both blocks, so the
//! measure is the element's largest distance from the programmed contour (the end of the
//! first block and the start of the second).

use super::curve::Curve;
use super::path::{AxisVec, Path};
use super::planner::Move;

/// Curvatures that differ by less than this (1/mm) are no jump: radii beyond a kilometre.
const CURVATURE_EPS: f64 = 1e-6;

/// True when the curvature vector `d²p/ds²` of `a` at its end differs from `b`'s at its start
/// (the tangents are known to agree).
pub fn curvature_jumps(a: &Move, b: &Move, metric: &AxisVec) -> bool {
    let ka = curvature(&a.path, 1.0, a.length);
    let kb = curvature(&b.path, 0.0, b.length);
    let jump: f64 = ka.iter().zip(&kb).zip(metric).map(|((x, y), m)| (x - y) * (x - y) * m).sum();
    jump.sqrt() > CURVATURE_EPS
}

/// `d²p/ds²` of a line (zero), an arc or a curve at `u`, per unit path length.
fn curvature(path: &Path, u: f64, length: f64) -> AxisVec {
    super::blend::second_derivative(path, u).map(|x| x / (length * length))
}

/// The element's largest distance from the programmed contour: `a` from `ua` to its end and
/// `b` from its start to `ub`. 33 samples of the element; each sample's distance is the
/// nearer of the two pieces'.
pub fn contour_deviation(curve: &Curve, a: &Move, ua: f64, b: &Move, ub: f64, metric: &AxisVec) -> f64 {
    const N: usize = 32;
    let mut p = a.path.end;
    let mut worst: f64 = 0.0;
    for i in 0..=N {
        curve.eval(i as f64 / N as f64, &mut p);
        let d = distance_to_piece(&a.path, ua, 1.0, &p, metric).min(distance_to_piece(&b.path, 0.0, ub, &p, metric));
        worst = worst.max(d);
    }
    worst
}

/// The smallest distance of `point` from `path` between `u0` and `u1`: 9 samples, then a
/// golden-section search around the nearest (the pieces are short and gently curved).
fn distance_to_piece(path: &Path, u0: f64, u1: f64, point: &AxisVec, metric: &AxisVec) -> f64 {
    let mut q = *point;
    let dist = |u: f64| {
        path.at(u, &mut q);
        q.iter().zip(point).zip(metric).map(|((x, y), m)| (x - y) * (x - y) * m).sum::<f64>()
    };
    super::nearest::least_distance(dist, (u0, u1), 8, 24)
}
