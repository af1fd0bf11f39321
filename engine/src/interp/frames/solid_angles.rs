//! ROTS/AROTS/CROTS: frame rotations given by two solid (projection) angles.
//!
//! Programming Manual: `ROTS X.. Y..` turns the frame so that the new X axis lies in the old
//! Z-X plane, `ROTS Z.. X..` the new Z axis in the old Y-Z plane, `ROTS Y.. Z..` the new Y axis
//! in the old X-Y plane. The value of an axis is the angle its plane is turned by about the
//! other axis (REFERENCE.md 8.2: the construction of CYCLE800's projection angles with no third
//! rotation, which `swivel::rotation` builds).

use crate::interp::tools::swivel::{SwivelMode, rotation as swivel_rotation};

/// The rotation for `(geometry axis, angle)` pairs: one or two different axes. With one angle
/// the other is 0 (the result is the plain rotation about that axis).
pub fn rotation(angles: &[(usize, f64)]) -> Result<[[f64; 3]; 3], &'static str> {
    let (first, second) = match angles {
        [a] => (*a, ((a.0 + 1) % 3, 0.0)),
        [a, b] if a.0 != b.0 => (*a, *b),
        [_, _] => return Err("the two angles need two different axes"),
        _ => return Err("one or two solid angles (X/Y, Z/X or Y/Z)"),
    };
    let third = 3 - first.0 - second.0;
    swivel_rotation(SwivelMode::Projection([first.0, second.0, third]), [first.1, second.1, 0.0])
        .ok_or("the angles leave no plane (90 degrees about both axes)")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(r: &[[f64; 3]; 3], c: usize) -> [f64; 3] {
        [r[0][c], r[1][c], r[2][c]]
    }

    #[test]
    fn x_and_y_keep_the_new_x_in_the_old_zx_plane() {
        // ROTS X30 Y45: new X = Ry(45)·ex = (cos45, 0, -sin45); new Y ⟂ new X inside the plane
        // spanned with Rx(30)·ey = (0, cos30, sin30).
        let r = rotation(&[(0, 30.0), (1, 45.0)]).unwrap();
        let x = column(&r, 0);
        let s = 0.5f64.sqrt();
        assert!((x[0] - s).abs() < 1e-12 && x[1].abs() < 1e-12 && (x[2] + s).abs() < 1e-12, "{x:?}");
        // The new Z is the normal of the plane through new X and Rx(30)·ey.
        let y30 = [0.0, 30f64.to_radians().cos(), 30f64.to_radians().sin()];
        let z = column(&r, 2);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        assert!(dot(z, y30).abs() < 1e-12 && dot(z, x).abs() < 1e-12 && z[2] > 0.0, "{z:?}");
    }

    #[test]
    fn one_angle_is_the_plain_rotation() {
        let r = rotation(&[(2, 90.0)]).unwrap();
        // About Z by 90: X → Y.
        let x = column(&r, 0);
        assert!(x[0].abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12, "{x:?}");
    }

    #[test]
    fn ninety_degrees_about_both_axes_is_refused() {
        assert!(rotation(&[(0, 90.0), (1, 90.0)]).is_err());
        assert!(rotation(&[(0, 1.0), (1, 2.0), (2, 3.0)]).is_err());
    }
}
