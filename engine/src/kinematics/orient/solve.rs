//! Inverse orientation: which rotary angles turn one unit vector into another (Paden–Kahan
//! subproblems 1 and 2, REFERENCE §6.4.2). Pure functions of vectors; the chain decides which
//! vectors and axes to pass (tool, part or mixed kinematics).
//!
//! [`two_axes`] runs once per IPO cycle of a 5-axis program, so it is written for speed: it
//! never builds the intermediate vector `c` of subproblem 2 but reads both roots' angles off
//! the in-plane coordinates of `p`, `c` and `q` (four `atan2`, two of them exact constants for
//! the usual perpendicular axes), see [`two_axes`].

use super::stepped::AngleMemo;
use super::vec3::{cross, dot, scale, sub};
use crate::kinematics::Vec3;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A vector counts as parallel to a rotary axis (a pole) when the sine of the angle between
/// them is below this. Small enough that a pose 1e-7 rad off the pole is still solved exactly.
pub const POLE_TOL: f64 = 1e-10;

/// Slack for "the orientation lies on the reachable cone" checks (dimensionless, on unit
/// vectors), absorbing rounding of orientations that came out of a forward computation.
pub const REACH_TOL: f64 = 1e-9;

/// Subproblem 1: the angle (radians, −π..π) of the right-hand rotation about the unit axis `w`
/// that takes the component of `u` perpendicular to `w` onto that of `v`. `None` when either
/// is parallel to `w` (the angle is free). Components along `w` are ignored, which is also how
/// a one-axis (3-/4-axis) transformation projects an orientation it cannot reach exactly.
pub fn angle_about(w: &Vec3, u: &Vec3, v: &Vec3) -> Option<f64> {
    let up = sub(u, &scale(w, dot(w, u)));
    let vp = sub(v, &scale(w, dot(w, v)));
    // |x| < tol·max(|y|, 1) compared squared: no square roots.
    let tiny = |x: &Vec3, y: &Vec3| dot(x, x) < POLE_TOL * POLE_TOL * dot(y, y).max(1.0);
    if tiny(&up, u) || tiny(&vp, v) {
        return None;
    }
    Some(atan2(dot(w, &cross(&up, &vp)), dot(&up, &vp)))
}

/// `y.atan2(x)`, bit for bit, with the two exact cases answered without the library call:
/// on the positive x axis (±0) and on the y axis (±π/2). They are what the coordinate-aligned
/// axes and basic orientations of real kinematics produce for the constant terms of
/// [`two_axes`].
pub fn atan2(y: f64, x: f64) -> f64 {
    if y == 0.0 && x > 0.0 {
        y
    } else if x == 0.0 && y != 0.0 {
        FRAC_PI_2.copysign(y)
    } else {
        y.atan2(x)
    }
}

/// `a` shifted by a whole turn into −π..π, as `atan2` answers (for a sum or difference of two
/// `atan2`, or a stepped angle).
pub(super) fn wrap(a: f64) -> f64 {
    if a > PI {
        a - TAU
    } else if a < -PI {
        a + TAU
    } else {
        a
    }
}

/// An angle (radians) with its cosine and sine. [`two_axes_turns`] gets the cosine and sine
/// from the same in-plane coordinates as the angle, so the caller builds the rotation matrices
/// of the pose without a `sin_cos` per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turn {
    pub angle: f64,
    pub cos: f64,
    pub sin: f64,
}

impl Turn {
    /// No rotation.
    pub const ZERO: Turn = Turn { angle: 0.0, cos: 1.0, sin: 0.0 };

    pub fn new(angle: f64) -> Turn {
        let (sin, cos) = angle.sin_cos();
        Turn { angle, cos, sin }
    }

    /// The opposite rotation.
    pub fn reversed(self) -> Turn {
        Turn { angle: -self.angle, cos: self.cos, sin: -self.sin }
    }

    /// `self − other`, the angle wrapped into −π..π.
    fn minus(self, other: Turn) -> Turn {
        Turn {
            angle: wrap(self.angle - other.angle),
            cos: self.cos * other.cos + self.sin * other.sin,
            sin: self.sin * other.cos - self.cos * other.sin,
        }
    }
}

/// Subproblem 2: both pairs `[θ1, θ2]` (radians, −π..π) with `R(w1, θ1)·R(w2, θ2)·p = q`, for
/// unit axes `w1`, `w2` that are not parallel and unit vectors `p`, `q`. The first pair is the
/// "+γ" root.
///
/// `None` when `q` is not reachable (γ² < 0). On the boundary of the reachable cone (γ = 0)
/// the two pairs coincide. In a pole one angle is free and is taken from `hint` (the previous
/// angle, so the pole axis keeps its position): `p ∥ w2` frees θ2, `q ∥ w1` frees θ1; both
/// pairs are then the same.
///
/// Method: the intermediate vector is `c = α·w1 + β·w2 ± γ·n` (n = w1 × w2). θ1 turns c into
/// q about w1: in the plane normal to w1 with the right-handed basis (w2 − c12·w1, n), both of
/// length |n|, c has the coordinates (β, ±γ)·|n|² and q (q·w2 − c12·q·w1, q·n), so
/// `θ1 = φq ∓ atan2(γ, β)`. Likewise θ2 turns p into c about w2, in the basis
/// (w1 − c12·w2, −n): `θ2 = ∓atan2(γ, α) − φp`, φp = atan2(−p·n, p·w1 − c12·p·w2). Four
/// `atan2` give both roots; with perpendicular axes and p or q on an axis (every preset)
/// two of them are the exact constants that [`atan2`] answers at once.
pub fn two_axes(w1: &Vec3, w2: &Vec3, p: &Vec3, q: &Vec3, hint: [f64; 2]) -> Option<[[f64; 2]; 2]> {
    Some(two_axes_turns(w1, w2, p, q, hint)?.map(|r| r.map(|t| t.angle)))
}

/// [`two_axes`] with the cosine and sine of every angle.
#[inline]
pub fn two_axes_turns(w1: &Vec3, w2: &Vec3, p: &Vec3, q: &Vec3, hint: [f64; 2]) -> Option<[[Turn; 2]; 2]> {
    two_axes_turns_stepped(w1, w2, p, q, hint, &mut AngleMemo::default())
}

/// [`two_axes_turns`] once per IPO cycle: the four angles are stepped from the last cycle's
/// in `memo` (see [`super::stepped`]) instead of four `atan2`. An empty memo gives the direct
/// result bit for bit.
#[inline]
pub fn two_axes_turns_stepped(
    w1: &Vec3,
    w2: &Vec3,
    p: &Vec3,
    q: &Vec3,
    hint: [f64; 2],
    memo: &mut AngleMemo,
) -> Option<[[Turn; 2]; 2]> {
    AxisPair::new(w1, w2).turns_stepped(p, q, hint, memo)
}

/// The two axes of subproblem 2 with the terms that depend on them alone, worked out once per
/// kinematic chain instead of once per IPO cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisPair {
    w1: Vec3,
    w2: Vec3,
    /// w1 · w2.
    c12: f64,
    /// c12² − 1.
    d: f64,
    /// w1 × w2 and its squared length.
    n: Vec3,
    n2: f64,
}

impl AxisPair {
    /// The unit axes `w1` (outer) and `w2` (inner), not parallel.
    pub fn new(w1: &Vec3, w2: &Vec3) -> AxisPair {
        let c12 = dot(w1, w2);
        let n = cross(w1, w2);
        AxisPair { w1: *w1, w2: *w2, c12, d: c12 * c12 - 1.0, n, n2: dot(&n, &n) }
    }

    /// [`two_axes_turns_stepped`] about these axes.
    #[inline]
    pub fn turns_stepped(&self, p: &Vec3, q: &Vec3, hint: [f64; 2], memo: &mut AngleMemo) -> Option<[[Turn; 2]; 2]> {
        let (w1, w2) = (&self.w1, &self.w2);
        let tol2 = POLE_TOL * POLE_TOL;
        // |p × w2|² and |q × w1|²: the pole tests, and below the terms of γ².
        let (pw2, qw1) = (cross(p, w2), cross(q, w1));
        let (sp2, sq2) = (dot(&pw2, &pw2), dot(&qw1, &qw1));
        // Pole of the inner axis: R2 leaves p alone, only θ1 matters.
        if sp2 < tol2 {
            if (dot(w1, p) - dot(w1, q)).abs() > REACH_TOL {
                return None;
            }
            let t1 = Turn::new(angle_about(w1, p, q).unwrap_or(hint[0]));
            let t2 = Turn::new(hint[1]);
            return Some([[t1, t2], [t1, t2]]);
        }
        // Pole of the outer axis: q lies on w1, so the intermediate vector is q itself.
        if sq2 < tol2 {
            if (dot(w2, p) - dot(w2, q)).abs() > REACH_TOL {
                return None;
            }
            let t1 = Turn::new(hint[0]);
            let t2 = Turn::new(angle_about(w2, p, q).unwrap_or(hint[1]));
            return Some([[t1, t2], [t1, t2]]);
        }
        let (c12, d, n, n2) = (self.c12, self.d, &self.n, self.n2);
        let (w1p, w2p, w1q, w2q) = (dot(w1, p), dot(w2, p), dot(w1, q), dot(w2, q));
        let alpha = (c12 * w2p - w1q) / d;
        let beta = (c12 * w1q - w2p) / d;
        // γ² = (|p|² − α² − β² − 2αβ·c12)/|n|² cancels badly next to a pole. The same value is
        // |w1 × q|²/|n|² − β² = |w2 × p|²/|n|² − α² (the distance of c from each axis is kept by
        // the rotations); taking the form with the smaller subtrahend keeps the tilt accurate to
        // the last digits of the orientation's own components.
        let g2 = if beta.abs() <= alpha.abs() { sq2 / n2 - beta * beta } else { sp2 / n2 - alpha * alpha };
        if g2 < -REACH_TOL {
            return None;
        }
        let g = g2.max(0.0).sqrt();
        // q and p are off the axes here (the pole tests above): their in-plane parts are not zero.
        let phi_q = memo.of(0, dot(q, n), w2q - c12 * w1q);
        let phi_p = memo.of(1, -dot(p, n), w1p - c12 * w2p);
        // c lies on w1 (w2) when both its in-plane coordinates vanish: θ1 (θ2) is free.
        let chi = (n2 * (beta * beta + g * g) >= tol2).then(|| memo.of(2, g, beta));
        let psi = (n2 * (alpha * alpha + g * g) >= tol2).then(|| memo.of(3, g, alpha));
        let t1 = |chi: Turn| phi_q.minus(chi);
        let t2 = |psi: Turn| psi.minus(phi_p);
        let (free1, free2) = (|| Turn::new(hint[0]), || Turn::new(hint[1]));
        Some([
            [chi.map_or_else(free1, t1), psi.map_or_else(free2, |psi| t2(psi.reversed()))],
            [chi.map_or_else(free1, |chi| t1(chi.reversed())), psi.map_or_else(free2, t2)],
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::super::vec3::{Rot, norm, normalize};
    use super::*;
    use proptest::prelude::*;

    /// The textbook subproblem 2 that [`two_axes`] replaced: build `c`, then subproblem 1 on
    /// each side. The reference the closed form must reproduce.
    fn reference(w1: &Vec3, w2: &Vec3, p: &Vec3, q: &Vec3, hint: [f64; 2]) -> Option<[[f64; 2]; 2]> {
        if norm(&cross(p, w2)) < POLE_TOL {
            if (dot(w1, p) - dot(w1, q)).abs() > REACH_TOL {
                return None;
            }
            let t1 = angle_about(w1, p, q).unwrap_or(hint[0]);
            return Some([[t1, hint[1]], [t1, hint[1]]]);
        }
        if norm(&cross(q, w1)) < POLE_TOL {
            if (dot(w2, p) - dot(w2, q)).abs() > REACH_TOL {
                return None;
            }
            let t2 = angle_about(w2, p, q).unwrap_or(hint[1]);
            return Some([[hint[0], t2], [hint[0], t2]]);
        }
        let c12 = dot(w1, w2);
        let d = c12 * c12 - 1.0;
        let (w2p, w1q) = (dot(w2, p), dot(w1, q));
        let alpha = (c12 * w2p - w1q) / d;
        let beta = (c12 * w1q - w2p) / d;
        let n = cross(w1, w2);
        let n2 = dot(&n, &n);
        let g2 = if beta.abs() <= alpha.abs() {
            dot(&cross(w1, q), &cross(w1, q)) / n2 - beta * beta
        } else {
            dot(&cross(w2, p), &cross(w2, p)) / n2 - alpha * alpha
        };
        if g2 < -REACH_TOL {
            return None;
        }
        let g = g2.max(0.0).sqrt();
        let mut out = [[0.0; 2]; 2];
        for (k, sign) in [1.0, -1.0].into_iter().enumerate() {
            let c = [
                alpha * w1[0] + beta * w2[0] + sign * g * n[0],
                alpha * w1[1] + beta * w2[1] + sign * g * n[1],
                alpha * w1[2] + beta * w2[2] + sign * g * n[2],
            ];
            out[k] = [angle_about(w1, &c, q).unwrap_or(hint[0]), angle_about(w2, p, &c).unwrap_or(hint[1])];
        }
        Some(out)
    }

    /// Largest angle difference (radians, modulo 2π) between two solution sets.
    fn max_diff(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> f64 {
        let d = |x: f64, y: f64| (x - y + PI).rem_euclid(TAU) - PI;
        (0..2).flat_map(|k| (0..2).map(move |i| d(a[k][i], b[k][i]).abs())).fold(0.0, f64::max)
    }

    /// Unit vector from three components, or along Z for a near-zero draw.
    fn dir(v: [f64; 3]) -> Vec3 {
        normalize(&v).filter(|_| norm(&v) > 0.1).unwrap_or([0.0, 0.0, 1.0])
    }

    /// The coordinate axes in both senses, as the presets use them.
    fn axis(i: usize) -> Vec3 {
        let mut v = [0.0; 3];
        v[i % 3] = if i < 3 { 1.0 } else { -1.0 };
        v
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, .. ProptestConfig::default() })]

        /// Random oblique axes and vectors, the target reached by a random pose: the closed
        /// form gives the reference's two roots to 1e-12 rad, both in −π..π, and both carry p
        /// onto q.
        #[test]
        fn the_closed_form_matches_the_reference_on_random_geometry(
            a in prop::array::uniform3(-1.0f64..1.0), b in prop::array::uniform3(-1.0f64..1.0),
            p in prop::array::uniform3(-1.0f64..1.0), t in prop::array::uniform2(-3.1f64..3.1),
            hint in prop::array::uniform2(-3.0f64..3.0)) {
            let (w1, w2, p) = (dir(a), dir(b), dir(p));
            prop_assume!(norm(&cross(&w1, &w2)) > 0.05);
            let q = Rot::about(&w1, t[0]).apply(&Rot::about(&w2, t[1]).apply(&p));
            let (fast, slow) = (two_axes(&w1, &w2, &p, &q, hint), reference(&w1, &w2, &p, &q, hint));
            let (fast, slow) = (fast.expect("reachable"), slow.expect("reachable"));
            prop_assert!(max_diff(&fast, &slow) < 1e-12, "{fast:?} vs {slow:?}");
            // The cosines and sines carried along are those of the angles.
            for t in two_axes_turns(&w1, &w2, &p, &q, hint).expect("reachable").as_flattened() {
                prop_assert!((t.cos - t.angle.cos()).abs() < 1e-12 && (t.sin - t.angle.sin()).abs() < 1e-12, "{t:?}");
            }
            for [t1, t2] in fast {
                prop_assert!((-PI..=PI).contains(&t1) && (-PI..=PI).contains(&t2));
                let back = Rot::about(&w1, t1).apply(&Rot::about(&w2, t2).apply(&p));
                prop_assert!((0..3).all(|i| (back[i] - q[i]).abs() < 1e-9), "{back:?} vs {q:?}");
            }
        }

        /// Perpendicular coordinate axes with p or q on an axis (every preset: head, table,
        /// mixed), including poses up to 1e-6 rad from the pole: the roots match the reference
        /// to 1e-12 rad; unreachable targets are refused by both.
        #[test]
        fn coordinate_axes_match_the_reference_next_to_the_poles(
            i1 in 0usize..6, d2 in 1usize..3, s2 in any::<bool>(), ip in 0usize..6, fixed_is_p in any::<bool>(),
            o in prop::array::uniform3(-1.0f64..1.0), near_pole in any::<bool>(),
            eps in prop::sample::select(vec![0.0, 1e-11, 1e-9, 1e-7, 1e-6, 1e-3]),
            hint in prop::array::uniform2(-3.0f64..3.0)) {
            let (w1, w2, fixed) = (axis(i1), axis((i1 + d2) % 3 + if s2 { 3 } else { 0 }), axis(ip));
            // An arbitrary direction, or one `eps` off the outer axis (the pole).
            let o = if near_pole { dir(std::array::from_fn(|i| w1[i] + eps * o[i])) } else { dir(o) };
            let (p, q) = if fixed_is_p { (fixed, o) } else { (o, fixed) };
            match (two_axes(&w1, &w2, &p, &q, hint), reference(&w1, &w2, &p, &q, hint)) {
                (Some(fast), Some(slow)) => prop_assert!(max_diff(&fast, &slow) < 1e-12, "{fast:?} vs {slow:?}"),
                (fast, slow) => prop_assert!(fast.is_none() && slow.is_none(), "{fast:?} vs {slow:?}"),
            }
        }
    }

    #[test]
    fn the_exact_atan2_cases_are_libms() {
        for (y, x) in
            [(0.0, 1.0), (-0.0, 2.5), (1.0, 0.0), (-3.0, 0.0), (2.0, -0.0), (0.3, -0.7), (0.0, -1.0), (0.0, 0.0)]
        {
            assert_eq!(atan2(y, x).to_bits(), y.atan2(x).to_bits(), "atan2({y}, {x})");
        }
    }

    fn close(a: &Vec3, b: &Vec3) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
    }

    #[test]
    fn both_roots_reproduce_the_target_for_a_ca_head() {
        let (z, x) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        let q = Rot::about(&z, 0.7).apply(&Rot::about(&x, 0.5).apply(&z));
        let s = two_axes(&z, &x, &z, &q, [0.0, 0.0]).unwrap();
        for [t1, t2] in s {
            assert!(close(&Rot::about(&z, t1).apply(&Rot::about(&x, t2).apply(&z)), &q));
        }
        assert!((s[0][1] + s[1][1]).abs() < 1e-12, "the tilt changes sign: {s:?}");
    }

    #[test]
    fn an_unreachable_target_has_no_solution() {
        // A cardan head with the 2nd axis at 45° between X and Z reaches at most 90° of tilt.
        let w2 = [0.5f64.sqrt(), 0.0, 0.5f64.sqrt()];
        assert!(two_axes(&[0.0, 0.0, 1.0], &w2, &[0.0, 0.0, 1.0], &[0.0, 0.6, -0.8], [0.0; 2]).is_none());
    }

    #[test]
    fn in_the_pole_the_free_angle_is_the_hint() {
        let (z, x) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
        let s = two_axes(&z, &x, &z, &z, [1.25, 0.3]).unwrap();
        assert_eq!(s[0], [1.25, 0.0]);
    }
}
