//! Inverse orientation: which rotary angles turn one unit vector into another (Paden–Kahan
//! subproblems 1 and 2, REFERENCE §6.4.2). Pure functions of vectors; the chain decides which
//! vectors and axes to pass (tool, part or mixed kinematics).

use super::vec3::{cross, dot, norm, scale, sub};
use crate::kinematics::Vec3;

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
    if norm(&up) < POLE_TOL * norm(u).max(1.0) || norm(&vp) < POLE_TOL * norm(v).max(1.0) {
        return None;
    }
    Some(dot(w, &cross(&up, &vp)).atan2(dot(&up, &vp)))
}

/// Subproblem 2: both pairs `[θ1, θ2]` (radians) with `R(w1, θ1)·R(w2, θ2)·p = q`, for unit
/// axes `w1`, `w2` that are not parallel and unit vectors `p`, `q`.
///
/// `None` when `q` is not reachable (γ² < 0). On the boundary of the reachable cone (γ = 0)
/// the two pairs coincide. In a pole one angle is free and is taken from `hint` (the previous
/// angle, so the pole axis keeps its position): `p ∥ w2` frees θ2, `q ∥ w1` frees θ1; both
/// pairs are then the same.
pub fn two_axes(w1: &Vec3, w2: &Vec3, p: &Vec3, q: &Vec3, hint: [f64; 2]) -> Option<[[f64; 2]; 2]> {
    // Pole of the inner axis: R2 leaves p alone, only θ1 matters.
    if norm(&cross(p, w2)) < POLE_TOL {
        if (dot(w1, p) - dot(w1, q)).abs() > REACH_TOL {
            return None;
        }
        let t1 = angle_about(w1, p, q).unwrap_or(hint[0]);
        return Some([[t1, hint[1]], [t1, hint[1]]]);
    }
    // Pole of the outer axis: q lies on w1, so the intermediate vector is q itself.
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
    // γ² = (|p|² − α² − β² − 2αβ·c12)/|n|² cancels badly next to a pole. The same value is
    // |w1 × q|²/|n|² − β² = |w2 × p|²/|n|² − α² (the distance of c from each axis is kept by
    // the rotations); taking the form with the smaller subtrahend keeps the tilt accurate to
    // the last digits of the orientation's own components.
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

#[cfg(test)]
mod tests {
    use super::super::vec3::Rot;
    use super::*;

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
