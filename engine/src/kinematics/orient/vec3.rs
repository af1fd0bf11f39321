//! Small 3-vector and rotation helpers on plain `[f64; 3]`, so the innermost loop needs no
//! allocation and no dependency. Angles are radians here; degrees live at the machine-data edge.

use crate::kinematics::Vec3;

pub fn add(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn scale(a: &Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

pub fn neg(a: &Vec3) -> Vec3 {
    [-a[0], -a[1], -a[2]]
}

pub fn dot(a: &Vec3, b: &Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

pub fn norm(a: &Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// `a / |a|`, or `None` for a vector shorter than 1e-12 (a zero direction in machine data or
/// a programmed A3=B3=C3=0).
pub fn normalize(a: &Vec3) -> Option<Vec3> {
    let n = norm(a);
    (n > 1e-12).then(|| scale(a, 1.0 / n))
}

/// A rotation matrix, row-major. Built once per pose and applied to several vectors, which is
/// cheaper than Rodrigues per vector when a chain rotates three offsets by the same angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rot(pub [[f64; 3]; 3]);

impl Rot {
    pub const IDENTITY: Rot = Rot([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);

    /// Right-hand rotation by `angle` (radians) about the unit vector `v` (Rodrigues,
    /// REFERENCE §0.2): `I + sin a·[v]x + (1 − cos a)·[v]x²`.
    pub fn about(v: &Vec3, angle: f64) -> Rot {
        let (s, c) = angle.sin_cos();
        Rot::about_cs(v, c, s)
    }

    /// [`Rot::about`] for an angle given by its cosine `c` and sine `s`.
    pub fn about_cs(v: &Vec3, c: f64, s: f64) -> Rot {
        let t = 1.0 - c;
        let [x, y, z] = *v;
        Rot([
            [c + t * x * x, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, c + t * y * y, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, c + t * z * z],
        ])
    }

    /// `R·a`.
    pub fn apply(&self, a: &Vec3) -> Vec3 {
        let m = &self.0;
        [dot(&m[0], a), dot(&m[1], a), dot(&m[2], a)]
    }

    /// `Rᵀ·a` (the inverse rotation).
    pub fn apply_t(&self, a: &Vec3) -> Vec3 {
        let m = &self.0;
        [
            m[0][0] * a[0] + m[1][0] * a[1] + m[2][0] * a[2],
            m[0][1] * a[0] + m[1][1] * a[1] + m[2][1] * a[2],
            m[0][2] * a[0] + m[1][2] * a[1] + m[2][2] * a[2],
        ]
    }
}

/// Right-hand rotation of `a` by `angle` (radians) about the unit vector `v`.
pub fn rotate(v: &Vec3, angle: f64, a: &Vec3) -> Vec3 {
    Rot::about(v, angle).apply(a)
}

/// The unit vector of Cartesian axis `i` (0 = X, 1 = Y, 2 = Z).
pub fn unit(i: usize) -> Vec3 {
    let mut e = [0.0; 3];
    e[i] = 1.0;
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turn_about_z_takes_x_to_y() {
        let r = Rot::about(&[0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2);
        let y = r.apply(&[1.0, 0.0, 0.0]);
        assert!((y[0]).abs() < 1e-15 && (y[1] - 1.0).abs() < 1e-15 && y[2].abs() < 1e-15);
        let back = r.apply_t(&y);
        assert!((back[0] - 1.0).abs() < 1e-15 && back[1].abs() < 1e-15);
    }

    #[test]
    fn quarter_turn_about_x_takes_y_to_z() {
        let z = rotate(&[1.0, 0.0, 0.0], std::f64::consts::FRAC_PI_2, &[0.0, 1.0, 0.0]);
        assert!(z[0].abs() < 1e-15 && z[1].abs() < 1e-15 && (z[2] - 1.0).abs() < 1e-15);
    }
}
