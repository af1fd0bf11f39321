//! Orientation interpolation primitives (REFERENCE §6.3.4): the great circle of ORIVECT /
//! ORIPLANE under ORIWKS and the cone rotation of ORICONCW/CCW. The interpolator evaluates
//! them per IPO point; they take and return unit vectors and do not allocate.

use super::vec3::{cross, dot, norm, normalize, rotate};
use crate::kinematics::Vec3;

/// Why an orientation path is not defined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum OriPathError {
    /// Start and end orientation are antiparallel: no plane for the great circle (alarm 14120).
    #[error("start and end orientation are antiparallel (alarm 14120)")]
    Antiparallel,
    /// A zero vector was given as orientation or cone axis.
    #[error("orientation or cone axis is the zero vector")]
    ZeroVector,
}

/// Great-circle interpolation from `os` to `oe` at `u` ∈ 0..=1:
/// `o(u) = [sin((1−u)Ω)·oₛ + sin(uΩ)·oₑ] / sin Ω`, Ω = ∠(oₛ, oₑ). Inputs need not be unit; the
/// result is. Equal directions give `os`.
pub fn slerp(os: &Vec3, oe: &Vec3, u: f64) -> Result<Vec3, OriPathError> {
    let a = normalize(os).ok_or(OriPathError::ZeroVector)?;
    let b = normalize(oe).ok_or(OriPathError::ZeroVector)?;
    let c = dot(&a, &b).clamp(-1.0, 1.0);
    let s = norm(&cross(&a, &b));
    if s < 1e-12 {
        return if c > 0.0 { Ok(a) } else { Err(OriPathError::Antiparallel) };
    }
    let omega = s.atan2(c);
    let (wa, wb) = (((1.0 - u) * omega).sin() / s, (u * omega).sin() / s);
    Ok([wa * a[0] + wb * b[0], wa * a[1] + wb * b[1], wa * a[2] + wb * b[2]])
}

/// The angle Ω (radians) between two orientations, 0..π.
pub fn angle_between(a: &Vec3, b: &Vec3) -> f64 {
    norm(&cross(a, b)).atan2(dot(a, b))
}

/// Cone interpolation: `os` turned by `angle` (radians, right-hand) about the cone axis `k`.
pub fn cone(k: &Vec3, os: &Vec3, angle: f64) -> Result<Vec3, OriPathError> {
    let k = normalize(k).ok_or(OriPathError::ZeroVector)?;
    Ok(rotate(&k, angle, os))
}

/// The sweep (radians) that carries `os` onto `oe` about the cone axis `k`: in 0..2π for a
/// right-hand (counter-clockwise seen from the tip of `k`) turn, in −2π..0 otherwise.
/// `None` if either lies on the axis.
pub fn cone_sweep(k: &Vec3, os: &Vec3, oe: &Vec3, counter_clockwise: bool) -> Option<f64> {
    let k = normalize(k)?;
    let a = super::solve::angle_about(&k, os, oe)?;
    let tau = std::f64::consts::TAU;
    Some(if counter_clockwise { a.rem_euclid(tau) } else { a.rem_euclid(tau) - tau })
}

/// ORICONIO: the cone whose surface carries the unit orientations `os`, `oi` and `oe`, as its
/// axis and the sweep (radians, 0..2π, right-handed about the axis) from `os` to `oe` that
/// passes `oi`. The tips of three unit vectors lie on one circle of the unit sphere; its plane's
/// normal `(oi − os) × (oe − os)` is the cone axis, oriented so that the circle runs
/// os → oi → oe counter-clockwise. `None` when two of them coincide (no cone is defined).
pub fn cone_through(os: &Vec3, oi: &Vec3, oe: &Vec3) -> Option<(Vec3, f64)> {
    use super::vec3::{cross, sub};
    let k = normalize(&cross(&sub(oi, os), &sub(oe, os)))?;
    let a = super::solve::angle_about(&k, os, oe)?;
    Some((k, a.rem_euclid(std::f64::consts::TAU)))
}

/// ORICONTO: the cone that leaves the unit orientation `os` in the direction `t` (the
/// orientation's direction of motion at the end of the previous block, ⟂ `os`) and reaches `oe`,
/// as its axis and sweep (0..2π). The circle on the sphere through `os` and `oe` tangent to `t`
/// lies in the plane through `os` spanned by `t` and `oe − os`; the axis is that plane's normal,
/// oriented so that turning about it moves `os` along `+t`. `None` when `t` ∥ `oe − os` or
/// `oe` = `os`.
pub fn cone_tangent(os: &Vec3, t: &Vec3, oe: &Vec3) -> Option<(Vec3, f64)> {
    use super::vec3::{cross, dot, neg, sub};
    let k = normalize(&cross(t, &sub(oe, os)))?;
    let k = if dot(&cross(&k, os), t) < 0.0 { neg(&k) } else { k };
    let a = super::solve::angle_about(&k, os, oe)?;
    Some((k, a.rem_euclid(std::f64::consts::TAU)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tangential_cone_continues_the_direction_of_motion() {
        // From (0.5, 0, 0.866) moving towards +Y (the cone about Z at 30°) to (−0.5, 0, 0.866):
        // the same cone about +Z, half a turn. Moving towards −Y instead: about −Z.
        let (s, c) = (0.5, 0.75f64.sqrt());
        let (k, sweep) = cone_tangent(&[s, 0.0, c], &[0.0, 1.0, 0.0], &[-s, 0.0, c]).unwrap();
        assert!(k[0].abs() < 1e-12 && k[1].abs() < 1e-12 && (k[2] - 1.0).abs() < 1e-12, "{k:?}");
        assert!((sweep - std::f64::consts::PI).abs() < 1e-12);
        let (k, _) = cone_tangent(&[s, 0.0, c], &[0.0, -1.0, 0.0], &[-s, 0.0, c]).unwrap();
        assert!((k[2] + 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_cone_through_three_points_30_degrees_off_z_is_the_cone_about_z() {
        // os, oi, oe all 30° from Z at azimuths 0°, 90°, 180°: axis Z, sweep 180°.
        let (s, c) = (0.5, 0.75f64.sqrt());
        let (k, sweep) = cone_through(&[s, 0.0, c], &[0.0, s, c], &[-s, 0.0, c]).unwrap();
        assert!(k[0].abs() < 1e-12 && k[1].abs() < 1e-12 && (k[2] - 1.0).abs() < 1e-12, "{k:?}");
        assert!((sweep - std::f64::consts::PI).abs() < 1e-12);
        // Through azimuth 270° instead: the other way round, 180° about −Z.
        let (k, sweep) = cone_through(&[s, 0.0, c], &[0.0, -s, c], &[-s, 0.0, c]).unwrap();
        assert!((k[2] + 1.0).abs() < 1e-12 && (sweep - std::f64::consts::PI).abs() < 1e-12);
        assert!(cone_through(&[s, 0.0, c], &[s, 0.0, c], &[-s, 0.0, c]).is_none());
    }

    #[test]
    fn slerp_halfway_between_z_and_x_is_the_diagonal() {
        let m = slerp(&[0.0, 0.0, 1.0], &[1.0, 0.0, 0.0], 0.5).unwrap();
        let h = 0.5f64.sqrt();
        assert!((m[0] - h).abs() < 1e-15 && m[1].abs() < 1e-15 && (m[2] - h).abs() < 1e-15);
    }

    #[test]
    fn antiparallel_orientations_have_no_great_circle() {
        assert_eq!(slerp(&[0.0, 0.0, 1.0], &[0.0, 0.0, -2.0], 0.3), Err(OriPathError::Antiparallel));
    }

    #[test]
    fn a_cone_about_z_keeps_the_opening_angle() {
        let os = [0.5, 0.0, 0.75f64.sqrt()];
        let o = cone(&[0.0, 0.0, 1.0], &os, 1.0).unwrap();
        assert!((o[2] - os[2]).abs() < 1e-15);
        let sweep = cone_sweep(&[0.0, 0.0, 1.0], &os, &o, false).unwrap();
        assert!((sweep - (1.0 - std::f64::consts::TAU)).abs() < 1e-12);
    }
}
