//! Orientation angle conventions of G group 50 (REFERENCE §6.3.3): the angles A2, B2, C2 ↔ the
//! orientation vector (unit, tip → holder; zero orientation = +Z). Angles in degrees, as
//! programmed. The vector has two degrees of freedom, the angles three: each `*_from_vector`
//! takes the angle that does not influence the vector (or that the caller keeps) as an input.

use super::solve::two_axes;
use super::vec3::{Rot, rotate, unit};
use crate::kinematics::Vec3;

const EZ: Vec3 = [0.0, 0.0, 1.0];

fn rx(a: f64, v: &Vec3) -> Vec3 {
    rotate(&unit(0), a.to_radians(), v)
}
fn ry(a: f64, v: &Vec3) -> Vec3 {
    rotate(&unit(1), a.to_radians(), v)
}
fn rz(a: f64, v: &Vec3) -> Vec3 {
    rotate(&unit(2), a.to_radians(), v)
}

/// ORIEULER (Z, X′, Z″): `o = Rz(A2)·Rx(B2)·Rz(C2)·ez = (sin A2·sin B2, −cos A2·sin B2, cos B2)`;
/// C2 does not influence the vector.
pub fn euler_to_vector(a2: f64, b2: f64, _c2: f64) -> Vec3 {
    rz(a2, &rx(b2, &EZ))
}

/// The ORIEULER angles of `o` (unit): B2 in 0..180, A2 in −180..180; `c2` is passed through.
/// At B2 = 0 (o = +Z) A2 is free and `a2_hint` is kept.
pub fn euler_from_vector(o: &Vec3, a2_hint: f64, c2: f64) -> [f64; 3] {
    let b2 = o[2].clamp(-1.0, 1.0).acos().to_degrees();
    let s = o[0].hypot(o[1]);
    let a2 = if s < 1e-12 { a2_hint } else { o[0].atan2(-o[1]).to_degrees() };
    [a2, b2, c2]
}

/// ORIRPY (A2 about X, B2 about Y, C2 about Z, applied to the Z vector C2 first):
/// `o = Rz(C2)·Ry(B2)·Rx(A2)·ez`. All three angles influence the vector.
pub fn rpy_to_vector(a2: f64, b2: f64, c2: f64) -> Vec3 {
    rz(c2, &ry(b2, &rx(a2, &EZ)))
}

/// The ORIRPY angles of `o` with C2 given: A2 in −90..90, B2 in −180..180.
pub fn rpy_from_vector(o: &Vec3, c2: f64) -> [f64; 3] {
    // Ry(B2)·Rx(A2)·ez = (sin B2·cos A2, −sin A2, cos B2·cos A2) = Rz(−C2)·o.
    let u = rz(-c2, o);
    let a2 = (-u[1]).clamp(-1.0, 1.0).asin().to_degrees();
    let b2 = if u[0].hypot(u[2]) < 1e-12 { 0.0 } else { u[0].atan2(u[2]).to_degrees() };
    [a2, b2, c2]
}

/// ORIRPY2 ("ZYX": A2 about Z, B2 about Y, C2 about X): `o = Rx(C2)·Ry(B2)·Rz(A2)·ez`
/// (order inferred from the name, REFERENCE §6.3.3); A2 does not influence the vector.
pub fn rpy2_to_vector(a2: f64, b2: f64, c2: f64) -> Vec3 {
    rx(c2, &ry(b2, &rz(a2, &EZ)))
}

/// The ORIRPY2 angles of `o`: B2 in −90..90, C2 in −180..180, `a2` passed through.
pub fn rpy2_from_vector(o: &Vec3, a2: f64) -> [f64; 3] {
    // o = (sin B2, −sin C2·cos B2, cos C2·cos B2).
    let b2 = o[0].clamp(-1.0, 1.0).asin().to_degrees();
    let c2 = if o[1].hypot(o[2]) < 1e-12 { 0.0 } else { (-o[1]).atan2(o[2]).to_degrees() };
    [a2, b2, c2]
}

/// The reference axis (0 = X, 1 = Y, 2 = Z) of an `ORIAX_TURN_TAB` entry (1 = X, 2 = Y, 3 = Z).
fn turn_axis(entry: u8) -> Option<usize> {
    matches!(entry, 1..=3).then(|| usize::from(entry) - 1)
}

/// ORIVIRT1/2: the orientation axes rotate in their order about the reference axes of the turn
/// table (MD21120/21130): first A2 about `tab[0]`, then B2 about the turned `tab[1]`, then C2
/// about the twice-turned `tab[2]`: `o = R(tab0, A2)·R(tab1, B2)·R(tab2, C2)·ez`.
/// With tab = (3, 1, 3) this is ORIEULER. `None` for an entry outside 1..3.
pub fn virt_to_vector(tab: [u8; 3], angles: [f64; 3]) -> Option<Vec3> {
    let mut v = EZ;
    for i in (0..3).rev() {
        v = rotate(&unit(turn_axis(tab[i])?), angles[i].to_radians(), &v);
    }
    Some(v)
}

/// The ORIVIRT angles of `o` with the 3rd angle `c2` given; of the two solutions the one with
/// A2 closest to `a2_hint`. `None` for an unreachable vector (e.g. equal first two turn axes)
/// or a bad table entry.
pub fn virt_from_vector(tab: [u8; 3], o: &Vec3, a2_hint: f64, c2: f64) -> Option<[f64; 3]> {
    let (w1, w2, w3) = (unit(turn_axis(tab[0])?), unit(turn_axis(tab[1])?), unit(turn_axis(tab[2])?));
    if w1 == w2 {
        return None;
    }
    let p = Rot::about(&w3, c2.to_radians()).apply(&EZ);
    let s = two_axes(&w1, &w2, &p, o, [a2_hint.to_radians(), 0.0])?;
    let d = |a: f64| ((a.to_degrees() - a2_hint + 180.0).rem_euclid(360.0) - 180.0).abs();
    let best = if d(s[1][0]) < d(s[0][0]) { s[1] } else { s[0] };
    Some([best[0].to_degrees(), best[1].to_degrees(), c2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Vec3, b: &Vec3) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
    }

    #[test]
    fn euler_matches_the_closed_form() {
        let (a, b) = (30f64, 50f64);
        let (sa, ca, sb, cb) = (a.to_radians().sin(), a.to_radians().cos(), b.to_radians().sin(), b.to_radians().cos());
        assert!(close(&euler_to_vector(a, b, 77.0), &[sa * sb, -ca * sb, cb]));
        let back = euler_from_vector(&euler_to_vector(a, b, 0.0), 0.0, 5.0);
        assert!((back[0] - a).abs() < 1e-9 && (back[1] - b).abs() < 1e-9 && back[2] == 5.0);
    }

    #[test]
    fn virt_with_the_euler_table_is_euler() {
        let o = virt_to_vector([3, 1, 3], [25.0, 40.0, 10.0]).unwrap();
        assert!(close(&o, &euler_to_vector(25.0, 40.0, 10.0)));
        let back = virt_from_vector([3, 1, 3], &o, 20.0, 10.0).unwrap();
        assert!(close(&virt_to_vector([3, 1, 3], back).unwrap(), &o), "{back:?}");
        assert!(virt_to_vector([0, 1, 3], [0.0; 3]).is_none());
    }
}
