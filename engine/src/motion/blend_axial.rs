//! G643, block-internal rounding with axial tolerances (Function Manual B1): unlike G642's one
//! element within one distance of the contour, every axis rounds its own motion over its own
//! distance, as far as its own MD33100 allows.
//!
//! Between two lines, with `σ` the path length from the corner (negative before it) and `t_a`,
//! `t_b` the axes' rates per unit path length on either side, axis `k` runs
//! `p_k(σ) = C_k + d_k·(t_a,k·x + Δ_k·φ(x))` for `|σ| < d_k` (`x = σ/d_k`, `Δ = t_b − t_a`),
//! and as programmed outside. `φ' = 3y² − 2y³` (`y = (x + 1)/2`) turns the rate from `t_a` to
//! `t_b` with no jump in the acceleration (`φ'' = 0` at both ends), so `φ = 2y³ − y⁴`. The
//! axis' deviation from its programmed position at the same `σ` is largest at the corner,
//! `3/16·d_k·|Δ_k|`: `d_k = 16·tol_k/(3·|Δ_k|)` uses the tolerance fully (at most 36 % of
//! either block, [`super::blend::MAX_SHARE`]). An axis with a larger tolerance (or a smaller
//! change of rate) rounds over a longer distance. Every axis is a quartic in `σ` between
//! the points `±d_k`, so the rounding is a chain of quintic elements joining there with equal
//! tangent and curvature (exact: a quintic holds a quartic).
//!
//! Decision where B1 is silent: the rounding is symmetric about the corner in `σ` for each
//! axis; next to an arc, under a transformation or with an orientation G643 rounds as G642
//! with the smallest of the geometry axes' tolerances (`channel/smoothing/blending.rs`).

use super::blend::{MAX_SHARE, Rounded, feed_of, with_path};
use super::curve::Curve;
use super::path::{AxisVec, Path};
use super::planner::{AxisLimit, Move};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Roundings shorter than this are left out (as in `blend.rs`).
const MIN_DISTANCE: f64 = 1e-4;

/// Rounds the corner between the lines `a` and `b`, axis `k` within `tol[k]`; `None` if either
/// is not a line (or nothing is left to round). `a_full_length` and `metric` as for
/// [`super::round_corner`].
pub fn round_axial(
    a: &Move,
    b: &Move,
    a_full_length: f64,
    tol: &AxisVec,
    metric: &AxisVec,
    limits: &[AxisLimit],
) -> Option<Rounded> {
    let line = |m: &Move| m.path.arc.is_none() && m.path.curve.is_none() && m.path.ori.is_none();
    if !(line(a) && line(b)) || a.exact_stop || !(a.length > 0.0 && b.length > 0.0) {
        return None;
    }
    let ta: AxisVec = std::array::from_fn(|k| (a.path.end[k] - a.path.start[k]) / a.length);
    let tb: AxisVec = std::array::from_fn(|k| (b.path.end[k] - b.path.start[k]) / b.length);
    let d_max = (MAX_SHARE * a_full_length.max(a.length).min(b.length)).min(0.9 * a.length);
    let mut d = [0.0; MAX_CHANNEL_AXES];
    for k in 0..MAX_CHANNEL_AXES {
        let jump = (tb[k] - ta[k]).abs();
        if jump > 1e-12 && tol[k] > 0.0 {
            d[k] = (16.0 * tol[k] / (3.0 * jump)).min(d_max);
        }
    }
    let reach = d.iter().copied().fold(0.0, f64::max);
    if reach.is_nan() || reach < MIN_DISTANCE {
        return None;
    }
    let corner = a.path.end;
    let axes = Axes { corner, ta, tb, d };
    // The pieces' ends: every axis' ±d_k, in order.
    let mut knots: Vec<f64> = d.iter().filter(|&&x| x > 0.0).flat_map(|&x| [-x, x]).collect();
    knots.sort_by(f64::total_cmp);
    knots.dedup_by(|x, y| (*x - *y).abs() < 1e-9);
    let mut pieces = Vec::with_capacity(knots.len() - 1);
    for w in knots.windows(2) {
        let (s0, s1) = (w[0], w[1]);
        let h = s1 - s0;
        let end = |s: f64| {
            let (p, v, acc) = axes.at(s);
            (p, v.map(|x| x * h), acc.map(|x| x * h * h))
        };
        let curve = Curve::hermite([end(s0), end(s1)], *metric);
        let length = curve.length();
        let path = Path {
            start: axes.at(s0).0,
            end: axes.at(s1).0,
            arc: None,
            ori: None,
            curve: Some(std::sync::Arc::new(curve)),
        };
        let mut piece = Move::unlimited(path, false, a.tag);
        piece.set_limits(length, feed_of(a.feed.min(b.feed)), limits);
        pieces.push(piece);
    }
    let (ua, ub) = (1.0 - reach / a.length, reach / b.length);
    let mut first = with_path(a, a.path.slice(0.0, ua));
    first.set_limits(a.length * ua, feed_of(a.feed), limits);
    first.blend = None;
    let mut second = with_path(b, b.path.slice(ub, 1.0));
    second.set_limits(b.length * (1.0 - ub), feed_of(b.feed), limits);
    // The pieces' ends are the lines' cut points (bit for bit: the planner joins them).
    pieces[0].path.start = first.path.end;
    let last = pieces.len() - 1;
    pieces[last].path.end = second.path.start;
    let mut pieces = pieces.into_iter();
    let corner = pieces.next()?;
    Some(Rounded { first, corner, second, cut: (ua, ub), more: pieces.collect() })
}

/// The axes around one corner (see the module doc).
struct Axes {
    corner: AxisVec,
    ta: AxisVec,
    tb: AxisVec,
    d: AxisVec,
}

impl Axes {
    /// Position, rate and its derivative (per unit of `σ`) of every axis at `σ = s`.
    fn at(&self, s: f64) -> (AxisVec, AxisVec, AxisVec) {
        let (mut p, mut v, mut acc) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        for k in 0..MAX_CHANNEL_AXES {
            let (c, ta, tb, d) = (self.corner[k], self.ta[k], self.tb[k], self.d[k]);
            if d > 0.0 && s.abs() < d {
                let x = s / d;
                let y = (x + 1.0) / 2.0;
                let jump = tb - ta;
                p[k] = c + d * (ta * x + jump * (2.0 * y * y * y - y * y * y * y));
                v[k] = ta + jump * (3.0 * y * y - 2.0 * y * y * y);
                acc[k] = jump * 3.0 * y * (1.0 - y) / d;
            } else {
                let t = if s < 0.0 || (d == 0.0 && s == 0.0) { ta } else { tb };
                p[k] = c + s * t;
                v[k] = t;
            }
        }
        (p, v, acc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_axis_deviates_by_its_tolerance_at_the_corner_and_not_before_its_distance() {
        // X along 1 → 0, Y 0 → 1 (a right angle): Δ = 1 on both. tol X 0.2, Y 0.05:
        // d_X = 16·0.2/3 = 1.0667, d_Y = 0.2667. At σ = 0 the axes stand 3/16·d·Δ off the
        // corner: X 0.2 back, Y 0.05 ahead; at σ = −0.5 Y is still on the first line (0).
        let mut corner = [0.0; MAX_CHANNEL_AXES];
        corner[0] = 10.0;
        let (mut ta, mut tb) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        (ta[0], tb[1]) = (1.0, 1.0);
        let mut d = [0.0; MAX_CHANNEL_AXES];
        (d[0], d[1]) = (16.0 * 0.2 / 3.0, 16.0 * 0.05 / 3.0);
        let axes = Axes { corner, ta, tb, d };
        let (p, v, _) = axes.at(0.0);
        assert!((p[0] - 9.8).abs() < 1e-12 && (p[1] - 0.05).abs() < 1e-12, "{p:?}");
        assert!((v[0] - 0.5).abs() < 1e-12 && (v[1] - 0.5).abs() < 1e-12);
        let (p, _, _) = axes.at(-0.5);
        assert_eq!(p[1], 0.0);
        // Continuous in position, rate and its derivative at ±d_k.
        for s in [-d[0], -d[1], d[1], d[0]] {
            let (lo, hi) = (axes.at(s - 1e-9), axes.at(s + 1e-9));
            for k in 0..2 {
                assert!((lo.0[k] - hi.0[k]).abs() < 1e-8 && (lo.1[k] - hi.1[k]).abs() < 1e-7, "{s} {k}");
                assert!((lo.2[k] - hi.2[k]).abs() < 1e-6, "{s} {k}");
            }
        }
    }
}
