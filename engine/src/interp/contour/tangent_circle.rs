//! `CT`: a circle that continues the path tangentially (Programming Manual Fundamentals,
//! "Circular interpolation with tangential transition"). G group 1, modal like G2/G3: the
//! block gives only the end point; the circle starts in the direction the previous block
//! ended in, so its centre lies on the normal of that direction at the start point, and the
//! radius and the direction of rotation follow from the end point.
//!
//! With the unit tangent t at the start S, its left normal n and the chord d = E − S, the
//! centre is S + ρ·n with ρ = |d|² / (2 n·d): ρ > 0 turns counter-clockwise (G3), ρ < 0
//! clockwise (G2), |ρ| is the radius. An end point on the tangent (n·d = 0) leaves no circle,
//! nor does a previous block without a direction in the plane: 14040, as for a circle whose
//! end point does not fit.
//!
//! The previous direction: [`LastMove`] keeps the working-plane start and end (and circle) of
//! the last path block in WCS coordinates, recorded by the general path and the fast lane.

use super::arc::{Circle, CircleError, Turn, from_center};

/// The last path block in the working plane (WCS), for the tangent a CT block starts with.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LastMove {
    start: (f64, f64),
    end: (f64, f64),
    circle: Option<Circle>,
}

impl LastMove {
    /// Records a block from `start` to `end` (plane coordinates), on `circle` if it is one.
    /// Zeros are stored unsigned (`+ 0.0`): the fast lane maps coordinates to −0.0 where the
    /// general path has 0.0, and debug builds compare the two paths' state.
    #[inline]
    pub fn record(&mut self, start: (f64, f64), end: (f64, f64), circle: Option<&Circle>) {
        let unsigned = |(a, o): (f64, f64)| (a + 0.0, o + 0.0);
        let circle = circle.map(|c| Circle { center: unsigned(c.center), start_angle: c.start_angle + 0.0, ..*c });
        *self = LastMove { start: unsigned(start), end: unsigned(end), circle };
    }

    /// The unit direction the block ended in, if it moved in the plane.
    pub fn end_direction(&self) -> Option<(f64, f64)> {
        let (x, y) = match self.circle {
            Some(c) => {
                let a = c.start_angle + c.sweep;
                let turn = c.sweep.signum();
                (-a.sin() * turn, a.cos() * turn)
            }
            None => (self.end.0 - self.start.0, self.end.1 - self.start.1),
        };
        let len = x.hypot(y);
        (len > 1e-12).then(|| (x / len, y / len))
    }
}

/// The circle from `start` to `end` that leaves `start` in the unit direction `tangent`, and
/// its direction of rotation.
pub fn circle(start: (f64, f64), end: (f64, f64), tangent: (f64, f64)) -> Result<(Circle, Turn), CircleError> {
    let d = (end.0 - start.0, end.1 - start.1);
    let normal = (-tangent.1, tangent.0);
    let across = normal.0 * d.0 + normal.1 * d.1;
    let chord2 = d.0 * d.0 + d.1 * d.1;
    if across.abs() <= 1e-9 * chord2.sqrt().max(1.0) || chord2 < 1e-18 {
        return Err(CircleError);
    }
    let rho = chord2 / (2.0 * across);
    let center = (start.0 + rho * normal.0, start.1 + rho * normal.1);
    let turn = if rho > 0.0 { Turn::CounterClockwise } else { Turn::Clockwise };
    Ok((from_center(start, end, center, turn)?, turn))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_along_x_continues_into_a_quarter_circle_to_the_left() {
        // From (10,0) heading +X to (20,10): d = (10,10), n = (0,1), ρ = 200 / 20 = 10:
        // centre (10,10), radius 10, counter-clockwise, a quarter circle.
        let (c, turn) = circle((10.0, 0.0), (20.0, 10.0), (1.0, 0.0)).unwrap();
        assert_eq!(turn, Turn::CounterClockwise);
        assert!((c.center.0 - 10.0).abs() < 1e-12 && (c.center.1 - 10.0).abs() < 1e-12, "{c:?}");
        assert!((c.radius - 10.0).abs() < 1e-12);
        assert!((c.sweep - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn an_end_point_to_the_right_turns_clockwise_and_one_on_the_tangent_is_refused() {
        // (10,0) heading +X to (20,-10): the mirror image, centre (10,-10), G2.
        let (c, turn) = circle((10.0, 0.0), (20.0, -10.0), (1.0, 0.0)).unwrap();
        assert_eq!(turn, Turn::Clockwise);
        assert!((c.center.1 + 10.0).abs() < 1e-12 && (c.radius - 10.0).abs() < 1e-12);
        assert!(circle((10.0, 0.0), (30.0, 0.0), (1.0, 0.0)).is_err());
    }

    #[test]
    fn a_circle_ends_in_the_direction_of_its_turn() {
        let mut last = LastMove::default();
        // Quarter circle counter-clockwise about (10,10) from (10,0) to (20,10): ends heading +Y.
        let (c, _) = circle((10.0, 0.0), (20.0, 10.0), (1.0, 0.0)).unwrap();
        last.record((10.0, 0.0), (20.0, 10.0), Some(&c));
        let (x, y) = last.end_direction().unwrap();
        assert!(x.abs() < 1e-12 && (y - 1.0).abs() < 1e-12);
        last.record((0.0, 0.0), (0.0, 0.0), None);
        assert_eq!(last.end_direction(), None);
    }
}
