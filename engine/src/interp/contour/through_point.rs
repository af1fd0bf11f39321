//! `CIP`: a circle through an intermediate point (Programming Manual Fundamentals, "Circular
//! interpolation with intermediate and end point"). G group 1, modal like G2/G3: the block gives
//! the end point and, with `I1=`, `J1=`, `K1=`, a point on the circle between start and end;
//! the three points fix the circle, its direction of rotation and its plane. A circle whose
//! three points lie in a plane parallel to the working plane is an ordinary circle of that plane
//! (tool radius compensation, CT and contour capture work with it as with G2/G3); otherwise it
//! lies obliquely in space.
//!
//! Geometry: with a = M − S and b = E − S, the circumcentre of the
//! triangle S, M, E is S + (|a|²·(b×(a×b)) + |b|²·((a×b)×a)) / (2·|a×b|²). Three points on a
//! line (|a×b| = 0) or coinciding give no circle: 14040, as a circle whose end point does not
//! fit. The sweep runs from S through M to E: below a half turn when M lies on the short arc.

use super::arc::{Circle, CircleError, Turn, from_center};
use crate::kinematics::orient::vec3::{add, cross, dot, scale, sub};
use crate::lang::CoordMode;

type V3 = [f64; 3];

/// A circle in space from `start`: centre, radius, the unit vector `u` from the centre to the
/// start, `v` = normal × `u` (the direction of travel at the start) and the sweep (positive).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpaceCircle {
    pub center: V3,
    pub radius: f64,
    pub u: V3,
    pub v: V3,
    pub sweep: f64,
}

/// The circle through `start`, `mid` and `end`, given as (abscissa, ordinate, applicate) of the
/// working plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ThroughPoint {
    /// In a plane parallel to the working plane: the plane circle and its turn.
    InPlane(Circle, Turn),
    /// Oblique in space.
    Oblique(SpaceCircle),
}

/// The circle from `start` through `mid` to `end` (each (abscissa, ordinate, applicate)).
pub fn circle(start: V3, mid: V3, end: V3) -> Result<ThroughPoint, CircleError> {
    let (a, b) = (sub(&mid, &start), sub(&end, &start));
    let n = cross(&a, &b);
    let n2 = dot(&n, &n);
    let (a2, b2) = (dot(&a, &a), dot(&b, &b));
    let size = a2.max(b2);
    // Collinear or coinciding points: no circle (relative to the points' spread).
    if size < 1e-18 || n2 <= 1e-18 * size * size {
        return Err(CircleError);
    }
    let offset = scale(&add(&scale(&cross(&b, &n), a2), &scale(&cross(&n, &a), b2)), 1.0 / (2.0 * n2));
    let center = add(&start, &offset);
    let flat = (start[2] - mid[2]).abs().max((start[2] - end[2]).abs()) <= 1e-9 * size.sqrt().max(1.0);
    if flat {
        // Seen from the applicate's positive side, S → M → E turning left is G3.
        let turn = if n[2] > 0.0 { Turn::CounterClockwise } else { Turn::Clockwise };
        let c = from_center((start[0], start[1]), (end[0], end[1]), (center[0], center[1]), turn)?;
        return Ok(ThroughPoint::InPlane(c, turn));
    }
    let radius = dot(&offset, &offset).sqrt();
    let normal = scale(&n, 1.0 / n2.sqrt());
    let u = scale(&sub(&start, &center), 1.0 / radius);
    let v = cross(&normal, &u);
    // The end's angle from u towards v; the normal n = a × b makes M lie before E on the way.
    let to_end = sub(&end, &center);
    let mut sweep = dot(&to_end, &v).atan2(dot(&to_end, &u));
    if sweep <= 0.0 {
        sweep += std::f64::consts::TAU;
    }
    Ok(ThroughPoint::Oblique(SpaceCircle { center, radius, u, v, sweep }))
}

/// The intermediate point of a CIP block in (abscissa, ordinate, applicate) of the plane
/// `(pa, po, papp)` (geometry axis indices: `ijk1[g]` is I1/J1/K1 of geometry axis g).
/// G90/G91 or AC/IC apply as to the end point; incremental values count from `start`. An
/// omitted parameter of the plane is 0 (the manual: a parameter of value 0 may be left out);
/// an omitted applicate one is the start's (a CIP block written for the working plane stays in
/// it at any height).
pub fn intermediate(
    ijk1: &[Option<(f64, Option<CoordMode>)>; 3],
    (pa, po, papp): (usize, usize, usize),
    start: V3,
    absolute: bool,
    length_factor: f64,
) -> V3 {
    let value = |g: usize, from: f64, omitted_is_start: bool| match ijk1[g] {
        None if omitted_is_start => from,
        None => {
            if absolute {
                0.0
            } else {
                from
            }
        }
        Some((v, mode)) => {
            let absolute = match mode {
                Some(CoordMode::Ac) => true,
                Some(CoordMode::Ic) => false,
                _ => absolute,
            };
            if absolute { v * length_factor } else { from + v * length_factor }
        }
    };
    [value(pa, start[0], false), value(po, start[1], false), value(papp, start[2], true)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn three_points_of_the_working_plane_give_its_circle_and_turn() {
        // (0,0) over (10,10) to (20,0): the upper half of the circle about (10,0), radius 10,
        // turning clockwise seen from +Z (from the left end over the top to the right).
        let Ok(ThroughPoint::InPlane(c, turn)) = circle([0.0, 0.0, 5.0], [10.0, 10.0, 5.0], [20.0, 0.0, 5.0]) else {
            panic!("a plane circle");
        };
        assert_eq!(turn, Turn::Clockwise);
        assert!(close(c.center.0, 10.0) && close(c.center.1, 0.0) && close(c.radius, 10.0), "{c:?}");
        assert!(close(c.sweep.abs(), PI));
        // The same points under the axis: counter-clockwise, the lower half.
        let Ok(ThroughPoint::InPlane(_, turn)) = circle([0.0, 0.0, 0.0], [10.0, -10.0, 0.0], [20.0, 0.0, 0.0]) else {
            panic!("a plane circle");
        };
        assert_eq!(turn, Turn::CounterClockwise);
    }

    #[test]
    fn an_intermediate_point_on_the_long_arc_makes_the_sweep_long() {
        // About (0,0), radius 10, from angle 0° through 180° to 90°: counter-clockwise the
        // way from 0° would pass 90° before 180°, so the circle turns clockwise, over 270°.
        let Ok(ThroughPoint::InPlane(c, turn)) = circle([10.0, 0.0, 0.0], [-10.0, 0.0, 0.0], [0.0, 10.0, 0.0]) else {
            panic!("a plane circle");
        };
        assert_eq!(turn, Turn::Clockwise);
        assert!(close(c.sweep.abs(), 3.0 * FRAC_PI_2), "{c:?}");
    }

    #[test]
    fn points_off_the_working_plane_give_an_oblique_circle() {
        // A quarter circle in the X/Z plane about the origin, radius 10: (10,0,0) through
        // (10·cos45°, 0, 10·sin45°) to (0,0,10). u = +X, the travel at the start +Z, sweep 90°.
        let h = 10.0 * 0.5f64.sqrt();
        let Ok(ThroughPoint::Oblique(c)) = circle([10.0, 0.0, 0.0], [h, 0.0, h], [0.0, 0.0, 10.0]) else {
            panic!("an oblique circle");
        };
        assert!(c.center.iter().all(|x| x.abs() < 1e-9), "{c:?}");
        assert!(close(c.radius, 10.0));
        assert!(close(c.u[0], 1.0) && close(c.v[2], 1.0), "{c:?}");
        assert!(close(c.sweep, FRAC_PI_2));
    }

    #[test]
    fn collinear_or_coinciding_points_give_no_circle() {
        assert!(circle([0.0; 3], [5.0, 0.0, 0.0], [10.0, 0.0, 0.0]).is_err());
        assert!(circle([0.0; 3], [0.0; 3], [10.0, 0.0, 0.0]).is_err());
        assert!(circle([0.0; 3], [0.0; 3], [0.0; 3]).is_err());
    }
}
