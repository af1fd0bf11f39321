//! The rotation of the tool about its own axis on a generic 6-axis kinematics (THETA,
//! Transformations Function Manual F2 §3.7.5, §3.11.2): besides its orientation `o` the tool
//! has a rotation vector `r` perpendicular to `o`. In the zero position `r` is the tool normal
//! (`TRAFO6_BASE_ORIENT_NORMAL` made perpendicular to the basic orientation); the three rotary
//! axes carry both vectors.
//!
//! THETA is the angle, right-handed about `o`, from a reference direction to `r`; which
//! reference the ORIROTx G functions choose is the interpreter's business, this file only
//! turns vectors and solves the three axis angles for a wanted (`o`, `r`) pair.

use super::chain::{Chain, ChainKind, Pose};
use super::solve::{Turn, angle_about, two_axes_turns};
use super::vec3::{Rot, cross, dot, normalize, scale, sub};
use crate::kinematics::Vec3;

/// `v` without its component along the unit vector `o`, normalised; `None` when `v` ∥ `o`.
pub fn perpendicular(v: &Vec3, o: &Vec3) -> Option<Vec3> {
    let p = sub(v, &scale(o, dot(v, o)));
    (dot(&p, &p) > 1e-18).then(|| normalize(&p)).flatten()
}

/// The rotation vector at unit orientation `o` that lies `theta` radians (right-handed about
/// `o`) from `reference` projected perpendicular to `o`. `None` when `reference` ∥ `o`.
pub fn rotation_vector(o: &Vec3, reference: &Vec3, theta: f64) -> Option<Vec3> {
    let r0 = perpendicular(reference, o)?;
    Some(Rot::about(o, theta).apply(&r0))
}

/// THETA (radians, −π..π) of rotation vector `r` at orientation `o` measured from `reference`.
pub fn theta_of(o: &Vec3, reference: &Vec3, r: &Vec3) -> Option<f64> {
    angle_about(o, reference, r)
}

/// The tool normal at the zero position: `normal` made perpendicular to `base`; when the two
/// are parallel (a basic orientation passed with TRAORI(n, x, y, z) along the normal) the
/// Cartesian axis least aligned with `base`, made perpendicular.
pub fn zero_normal(base: &Vec3, normal: &Vec3) -> Vec3 {
    perpendicular(normal, base).unwrap_or_else(|| {
        let i = (0..3).min_by(|a, b| base[*a].abs().total_cmp(&base[*b].abs())).unwrap_or(0);
        let mut e = [0.0; 3];
        e[i] = 1.0;
        perpendicular(&e, base).unwrap_or([1.0, 0.0, 0.0])
    })
}

impl Chain {
    /// The tool's rotation vector in the BCS at `pose` for the zero-position normal `n0`
    /// (perpendicular to `base`): `R1·R2·R3·n0`. Only tool kinematics carry a third axis;
    /// for the others the vector is carried like the orientation.
    pub fn rotation_vector(&self, pose: &Pose, n0: &Vec3) -> Vec3 {
        let [r1, r2, r3] = &pose.r;
        match self.kind {
            ChainKind::Tool => r1.apply(&r2.apply(&r3.apply(n0))),
            ChainKind::Part => r2.apply_t(&r1.apply_t(n0)),
            ChainKind::Mixed => r2.apply_t(&r1.apply(n0)),
        }
    }

    /// Both angle sets (with cosine and sine) of a 3-axis tool chain that give orientation
    /// `o` and rotation vector `r` (unit, `r` ⟂ `o`), for the zero-position normal `n0`.
    ///
    /// The wanted pose is the rotation `Rt` taking the frame (base, n0, base × n0) onto
    /// (o, r, o × r). Axis 3 leaves its own direction v3 alone, so `R1·R2·v3 = Rt·v3`
    /// (subproblem 2 for axes 1 and 2); then axis 3 turns a vector x (base or n0, whichever
    /// is less parallel to v3) onto `(R1·R2)ᵀ·Rt·x`. `None` when unreachable or not a
    /// 3-axis tool chain.
    pub fn solve_rotated(&self, o: &Vec3, r: &Vec3, n0: &Vec3, hint: &[f64; 3]) -> Option<[[Turn; 3]; 2]> {
        if self.axes != 3 || self.kind != ChainKind::Tool {
            return None;
        }
        let b = &self.base;
        let bn = cross(b, n0);
        let or = cross(o, r);
        let target = |x: &Vec3| -> Vec3 {
            let (cb, cn, cbn) = (dot(b, x), dot(n0, x), dot(&bn, x));
            std::array::from_fn(|i| o[i] * cb + r[i] * cn + or[i] * cbn)
        };
        let [v1, v2, v3] = &self.v;
        let q = target(v3);
        let pairs = two_axes_turns(v1, v2, v3, &q, [hint[0], hint[1]])?;
        let x = if dot(b, v3).abs() < dot(n0, v3).abs() { *b } else { *n0 };
        let y = target(&x);
        let mut out = [[Turn::ZERO; 3]; 2];
        for (slot, [t1, t2]) in out.iter_mut().zip(pairs) {
            let r1 = Rot::about_cs(v1, t1.cos, t1.sin);
            let r2 = Rot::about_cs(v2, t2.cos, t2.sin);
            let local = r2.apply_t(&r1.apply_t(&y));
            let a3 = angle_about(v3, &x, &local).unwrap_or(hint[2]);
            *slot = [t1, t2, Turn::new(a3)];
        }
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn theta_turns_the_projected_reference_about_the_orientation() {
        // o = Z, reference X: THETA = 90° gives Y (right-handed about Z).
        let r = rotation_vector(&[0.0, 0.0, 1.0], &[1.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2).unwrap();
        assert!(close(r, [0.0, 1.0, 0.0]), "{r:?}");
        let back = theta_of(&[0.0, 0.0, 1.0], &[1.0, 0.0, 0.0], &r).unwrap();
        assert!((back - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(rotation_vector(&[0.0, 0.0, 1.0], &[0.0, 0.0, 2.0], 0.3).is_none());
    }

    #[test]
    fn a_normal_along_the_base_falls_back_to_a_perpendicular_axis() {
        assert!(close(zero_normal(&[0.0, 0.0, 1.0], &[0.0, 0.0, 1.0]), [1.0, 0.0, 0.0]));
        assert!(close(zero_normal(&[0.0, 0.0, 1.0], &[1.0, 1.0, 1.0]), [0.5f64.sqrt(), 0.5f64.sqrt(), 0.0]));
    }
}
