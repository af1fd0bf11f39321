//! SOFT where the path curves: on an arc and at a seam where the curvature jumps (Function
//! Manual B2 "Acceleration and jerk", jerk at block transitions without constant curvature,
//! MD32432 `$MA_PATH_TRANS_JERK_LIM`).
//!
//! On an arc of radius `r` run at planar speed `w`, acceleration `a` and jerk `j` along the
//! path, an axis of the plane sees the jerk `(j − w³/r²)` along the tangent and `3·w·a/r` along
//! the radius. The path jerk the moves carry (MD32431 over the axis rates) covers only the
//! first part; [`Move::limit_arc_jerk`] shares the axis jerk `J` out: the cruise speed keeps
//! `w³/r² ≤ J/2`, the path jerk `j + w³/r² ≤ 0.8·J`, the acceleration `3·w·a/r ≤ 0.6·J`, so
//! that `√(0.8² + 0.6²) = 1`: no axis exceeds `J` in any phase of the S curve.
//!
//! A line running tangentially into an arc (or an arc into one of another radius) has no
//! corner, but the centripetal acceleration `v²·κ` of the axes jumps there within one IPO
//! cycle: a jerk of `v²·|Δ(κ·n)_k| / T` on axis `k`. Under SOFT the planner limits the path
//! velocity at such a transition so that this jerk stays within the seam jerk of the moves
//! (`Move::seam_jerk`: MD32431 with JERKLIM, or MD32432 where that is higher). BRISK moves
//! (infinite seam jerk) are not limited, as before.
//!
//! Input: the two moves of the transition. Output: the highest speed at the seam. Free-form
//! elements (rounding curves, splines) and paths not in machine axes (a transformation's
//! pieces) are not looked at: their curvature at the ends is not known here.
//!
//! A rounding element (G641..G645) under SOFT: its curvature changes along it, so an axis sees
//! `w³·|d³p_k/ds³|` at planar speed `w` besides the arc's terms. [`limit_element_jerk`] shares
//! the axis jerk out as for an arc (cruise `w³·|d³p_k/ds³| ≤ J_k/2`, path jerk
//! `j·|dp_k/ds| + w³·|d³p_k/ds³| ≤ 0.8·J_k`, acceleration `3·w·a·|d²p_k/ds²| ≤ 0.6·J_k`). The
//! element does not know the axes' jerk `J_k`; the two moves it joins do: each one's path jerk
//! `j` is at most `J_k / |dp_k/ds|` for the largest rate of every axis along it, so `j` times
//! that rate is a lower bound of `J_k`, and the larger of the two bounds is what the element
//! keeps.

use super::{AxisVec, Move};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

impl Move {
    /// Under SOFT, an arc's speed, acceleration and path jerk lowered so that the axes of its
    /// plane, whose smallest jerk is `jerk`, keep it (see the module doc). Nothing for a line
    /// or an infinite jerk (BRISK).
    pub fn limit_arc_jerk(&mut self, jerk: f64) {
        let Some(arc) = self.path.arc.as_deref() else { return };
        let r = arc.radius;
        // Planar speed per unit path speed (below 1 on a helix whose length counts the lead).
        let k = r * arc.sweep.abs() / self.length;
        if !(jerk.is_finite() && k > 1e-12 && r > 1e-12) {
            return;
        }
        let v_cap = (0.5 * jerk * r * r).cbrt() / k;
        self.v_max = self.v_max.min(v_cap);
        self.v_axes = self.v_axes.min(v_cap);
        let w = self.v_axes * k;
        self.jerk = self.jerk.min((0.8 * jerk - w * w * w / (r * r)) / k);
        self.a_max = self.a_max.min(0.2 * jerk * r / (w * k));
    }
}

impl Move {
    /// Under SOFT (both moves with a finite path jerk), this rounding element between `a` and
    /// `b` gets a cruise speed, acceleration and path jerk that keep every axis within its
    /// jerk (see the module doc). Nothing for BRISK or a move without a curve.
    pub fn limit_element_jerk(&mut self, a: &Move, b: &Move) {
        if !(a.jerk.is_finite() && b.jerk.is_finite()) {
            return;
        }
        let Some(curve) = self.path.curve.as_deref() else { return };
        if curve.length() <= 0.0 {
            return;
        }
        // Lower bounds of the axes' jerk from the two moves: each one's path jerk is at most
        // `J_k` over its largest rate of axis k per unit length (`interp/dynamics.rs`).
        let (ra, rb) = (a.path.max_rate_of_first(MAX_CHANNEL_AXES), b.path.max_rate_of_first(MAX_CHANNEL_AXES));
        let budget: AxisVec = std::array::from_fn(|k| f64::max(a.jerk * ra[k] / a.length, b.jerk * rb[k] / b.length));
        let (p1, p2) = curve.rates();
        let p3 = third_rates(curve);
        let mut v = self.v_axes;
        // An axis neither move moves stays where it is along the element (its rates are rounding).
        let moved = |k: usize| budget[k] > 0.0;
        for k in (0..MAX_CHANNEL_AXES).filter(|&k| moved(k)) {
            if p3[k] > 1e-12 {
                v = v.min((0.5 * budget[k] / p3[k]).cbrt());
            }
        }
        self.v_max = self.v_max.min(v);
        self.v_axes = v;
        let mut jerk = a.jerk.min(b.jerk);
        let mut accel = self.a_max;
        for k in (0..MAX_CHANNEL_AXES).filter(|&k| moved(k)) {
            let turning = if v.is_finite() { v * v * v * p3[k] } else { 0.0 };
            if p1[k] > 1e-12 {
                jerk = jerk.min(((0.8 * budget[k] - turning) / p1[k]).max(0.0));
            }
            if p2[k] > 1e-12 && v.is_finite() && v > 0.0 {
                accel = accel.min(0.2 * budget[k] / (v * p2[k]));
            }
        }
        self.jerk = jerk;
        self.a_max = accel;
        self.seam_jerk = a.seam_jerk.min(b.seam_jerk);
    }
}

/// Per axis the largest `|d³p_k/ds³|` over a curve: the change of `d²p/ds²` between 32 steps
/// of equal length, with a 10 % margin for the peaks between them.
fn third_rates(curve: &crate::motion::Curve) -> AxisVec {
    const N: usize = 32;
    let len = curve.length();
    let step = len / N as f64;
    let scale = 1.0 / (len * len * step);
    let mut out = [0.0; MAX_CHANNEL_AXES];
    let mut last = curve.second(0.0);
    for i in 1..=N {
        let next = curve.second(i as f64 / N as f64);
        for k in 0..MAX_CHANNEL_AXES {
            out[k] = f64::max(out[k], ((next[k] - last[k]) * scale).abs());
        }
        last = next;
    }
    out.map(|x| x * 1.1)
}

/// `d²p/ds²` per axis at the start (`end == false`) or the end of `mv`, with `s` the path
/// length the feed refers to: zero on a line, the centripetal vector of unit speed on an arc
/// (`−r·φ²/L²` along the radius, `φ` the sweep). `None` for a free-form element or a path
/// whose axes are not the machine's.
pub(super) fn curvature(mv: &Move, end: bool) -> Option<AxisVec> {
    let path = &mv.path;
    if path.curve.is_some() || mv.axis_tangents.is_some() || mv.length <= 0.0 {
        return None;
    }
    let mut c = [0.0; MAX_CHANNEL_AXES];
    if let Some(arc) = &path.arc {
        let angle = arc.start_angle + if end { arc.sweep } else { 0.0 };
        let k = -arc.radius * arc.sweep * arc.sweep / (mv.length * mv.length);
        let (sin, cos) = angle.sin_cos();
        for (ck, (u, v)) in c.iter_mut().zip(arc.u.iter().zip(&arc.v)) {
            *ck = k * (cos * u + sin * v);
        }
    }
    Some(c)
}

/// The highest path speed at the transition from `a` to `b` at which no one of the first `n`
/// axes sees its centripetal acceleration jump by more than the seam jerk times `dt`:
/// `v = √(j·dt / |Δc_k|)` for the axis with the largest jump of `d²p/ds²`. Infinite when
/// nothing jumps or a curvature is unknown.
pub(super) fn seam_speed(a: &Move, b: &Move, n: usize, dt: f64) -> f64 {
    let (Some(ca), Some(cb)) = (curvature(a, true), curvature(b, false)) else {
        return f64::INFINITY;
    };
    let jerk = a.seam_jerk.min(b.seam_jerk);
    let jump = (0..n.min(MAX_CHANNEL_AXES)).map(|k| (cb[k] - ca[k]).abs()).fold(0.0, f64::max);
    if jump > 1e-12 { (jerk * dt / jump).sqrt() } else { f64::INFINITY }
}

#[cfg(test)]
mod tests {
    use super::super::{AxisLimit, Feed, Path};
    use super::*;
    use crate::motion::path::Arc;

    fn limits() -> Vec<AxisLimit> {
        vec![AxisLimit { max_velocity: 500.0, max_accel: 3000.0, accel_overload: 1.2 }; 3]
    }

    /// The quarter circle of radius 5 from (10, 0) counterclockwise about (10, 5): it leaves
    /// tangentially along +X, turning towards +Y.
    fn quarter(seam_jerk: f64) -> Move {
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        (start[0], end[0], end[1]) = (10.0, 15.0, 5.0);
        let arc = Arc::in_plane(0, 1, 5.0, -std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2);
        let path = Path { start, end, arc: Some(Box::new(arc)), ori: None, curve: None };
        let len = 5.0 * std::f64::consts::FRAC_PI_2;
        let mut mv = Move::new(path, len, Feed::Path(100.0), &limits(), false, 2);
        mv.seam_jerk = seam_jerk;
        mv
    }

    fn line(seam_jerk: f64) -> Move {
        let mut end = [0.0; MAX_CHANNEL_AXES];
        end[0] = 10.0;
        let mut mv = Move::new(Path::line([0.0; MAX_CHANNEL_AXES], end), 10.0, Feed::Path(100.0), &limits(), false, 1);
        mv.seam_jerk = seam_jerk;
        mv
    }

    #[test]
    fn an_arc_starts_with_its_centripetal_vector_towards_the_centre() {
        // At the start (10, 0) the centre (10, 5) lies in +Y: d²p/ds² = (0, 1/r) = (0, 0.2).
        let c = curvature(&quarter(1.0), false).unwrap();
        assert!(c[0].abs() < 1e-12 && (c[1] - 0.2).abs() < 1e-12, "{:?}", &c[..2]);
        // At the end (15, 5) it points to −X.
        let c = curvature(&quarter(1.0), true).unwrap();
        assert!((c[0] + 0.2).abs() < 1e-12 && c[1].abs() < 1e-12, "{:?}", &c[..2]);
        assert_eq!(curvature(&line(1.0), true), Some([0.0; MAX_CHANNEL_AXES]));
    }

    #[test]
    fn the_seam_speed_keeps_the_jump_of_v_squared_over_r_within_one_cycle_of_jerk() {
        // Line into the R5 arc: Y's acceleration jumps by v²/5. With a seam jerk of 50 m/s³
        // and T = 4 ms: v² = 50000·0.004·5 = 1000, v = 31.623 mm/s. BRISK: no limit.
        let v = seam_speed(&line(50_000.0), &quarter(50_000.0), 3, 0.004);
        assert!((v - 1000f64.sqrt()).abs() < 1e-9, "{v}");
        assert_eq!(seam_speed(&line(f64::INFINITY), &quarter(f64::INFINITY), 3, 0.004), f64::INFINITY);
        // Two lines: nothing jumps.
        assert_eq!(seam_speed(&line(50_000.0), &line(50_000.0), 3, 0.004), f64::INFINITY);
    }

    #[test]
    fn the_planner_crosses_the_seam_at_no_more_than_the_seam_speed() {
        // Line and R5 arc under SOFT with an axis jerk of 100 m/s³: the seam speed
        // √(100 000·0.004·5) = 44.72 mm/s is below the arc's own 86.6 mm/s (half of 3000 mm/s²
        // centripetal) and the arc's 7.85 mm brake the path from far more, so the planned
        // transition speed is the seam speed.
        let mut p = super::super::Planner::new(0.004, limits(), [0.0; MAX_CHANNEL_AXES]);
        let (mut a, mut b) = (line(100_000.0), quarter(100_000.0));
        (a.jerk, b.jerk) = (100_000.0, 100_000.0);
        b.limit_arc_jerk(100_000.0);
        p.push(a);
        p.push(b);
        assert!((p.v_end[0] - 2000f64.sqrt()).abs() < 1e-9, "{}", p.v_end[0]);
    }

    #[test]
    fn an_arc_under_soft_shares_the_axis_jerk_between_turning_and_accelerating() {
        // R5 quarter at J = 20 000 mm/s³: cruise w³/r² ≤ J/2: w = ∛(10 000·25) = 62.996 mm/s;
        // path jerk (0.8·J − w³/r²) = 16 000 − 10 000 = 6000; acceleration 0.2·J·r/w =
        // 20 000/62.996 = 317.48 mm/s² (3·w·a/r = 12 000 = 0.6·J).
        let mut mv = quarter(f64::INFINITY);
        mv.jerk = 20_000.0;
        mv.limit_arc_jerk(20_000.0);
        let w = 250_000f64.cbrt();
        assert!((mv.v_max - w).abs() < 1e-9 && (mv.v_axes - w).abs() < 1e-9, "{}", mv.v_max);
        assert!((mv.jerk - 6000.0).abs() < 1e-6, "{}", mv.jerk);
        assert!((mv.a_max - 20_000.0 / w).abs() < 1e-9, "{}", mv.a_max);
        // A line is left as it is.
        let mut l = line(f64::INFINITY);
        let before = l.clone();
        l.limit_arc_jerk(20_000.0);
        assert_eq!(l, before);
    }
}
