//! Circle geometry for G2/G3 in the working plane: centre from I/J/K or from the radius CR,
//! start angle and signed sweep.
//!
//! Coordinates are (abscissa, ordinate) of the plane; (abscissa, ordinate, applicate) is right
//! handed for G17 (X,Y,Z), G18 (Z,X,Y) and G19 (Y,Z,X), so "clockwise seen from the positive
//! applicate" (G2) is always a negative sweep.

use std::f64::consts::TAU;

/// Direction of a circle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Turn {
    /// G2.
    Clockwise,
    /// G3.
    CounterClockwise,
}

/// Circle through `start` and `end` in plane coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    pub center: (f64, f64),
    pub radius: f64,
    pub start_angle: f64,
    /// Signed sweep in radians (negative for G2).
    pub sweep: f64,
}

/// Why a circle cannot be built (alarm 14040).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CircleError;

/// Allowed difference between start and end radius: `max(0.01 mm, 0.1 % of the radius)`
/// (MD21000 CIRCLE_ERROR_CONST, MD21010 CIRCLE_ERROR_FACTOR defaults).
fn tolerance(radius: f64) -> f64 {
    (0.001 * radius).max(0.01)
}

/// Circle from its centre. Start equal to end gives a full circle.
pub fn from_center(start: (f64, f64), end: (f64, f64), center: (f64, f64), turn: Turn) -> Result<Circle, CircleError> {
    let r0 = (start.0 - center.0).hypot(start.1 - center.1);
    let r1 = (end.0 - center.0).hypot(end.1 - center.1);
    if r0 < 1e-9 || (r0 - r1).abs() > tolerance(r0) {
        return Err(CircleError);
    }
    let a0 = (start.1 - center.1).atan2(start.0 - center.0);
    let a1 = (end.1 - center.1).atan2(end.0 - center.0);
    let full = (start.0 - end.0).hypot(start.1 - end.1) < 1e-9;
    let ccw = if full { TAU } else { positive_angle(a1 - a0) };
    let sweep = match turn {
        Turn::CounterClockwise => ccw,
        Turn::Clockwise if full => -TAU,
        Turn::Clockwise => ccw - TAU,
    };
    Ok(Circle { center, radius: r0, start_angle: a0, sweep })
}

/// Circle from its radius: `cr > 0` for arcs up to 180°, `cr < 0` for arcs over 180°.
pub fn from_radius(start: (f64, f64), end: (f64, f64), cr: f64, turn: Turn) -> Result<Circle, CircleError> {
    let r = cr.abs();
    let (dx, dy) = (end.0 - start.0, end.1 - start.1);
    let chord = dx.hypot(dy);
    if chord < 1e-9 || r < 1e-9 || chord > 2.0 * r + tolerance(r) {
        return Err(CircleError);
    }
    let h = (r * r - chord * chord / 4.0).max(0.0).sqrt();
    let mid = ((start.0 + end.0) / 2.0, (start.1 + end.1) / 2.0);
    // Left normal of the chord direction: the centre of a short counter-clockwise arc.
    let left = (-dy / chord, dx / chord);
    let side = match (turn, cr > 0.0) {
        (Turn::CounterClockwise, true) | (Turn::Clockwise, false) => 1.0,
        _ => -1.0,
    };
    let center = (mid.0 + side * h * left.0, mid.1 + side * h * left.1);
    from_center(start, end, center, turn)
}

/// Circle from its end point and opening angle `AR=` (degrees, 0 < AR < 360).
pub fn from_end_and_angle(start: (f64, f64), end: (f64, f64), ar: f64, turn: Turn) -> Result<Circle, CircleError> {
    if !(ar > 0.0 && ar < 360.0) {
        return Err(CircleError);
    }
    let chord = (end.0 - start.0).hypot(end.1 - start.1);
    let r = chord / (2.0 * (ar.to_radians() / 2.0).sin());
    // Up to 180° the centre is on the short-arc side (as CR > 0), beyond on the other.
    from_radius(start, end, if ar <= 180.0 { r } else { -r }, turn)
}

/// Circle from its centre and opening angle `AR=` (degrees): the end point follows.
pub fn from_center_and_angle(
    start: (f64, f64),
    center: (f64, f64),
    ar: f64,
    turn: Turn,
) -> Result<(Circle, (f64, f64)), CircleError> {
    if !(ar > 0.0 && ar <= 360.0) {
        return Err(CircleError);
    }
    let sweep = match turn {
        Turn::CounterClockwise => ar.to_radians(),
        Turn::Clockwise => -ar.to_radians(),
    };
    let radius = (start.0 - center.0).hypot(start.1 - center.1);
    if radius < 1e-9 {
        return Err(CircleError);
    }
    let a0 = (start.1 - center.1).atan2(start.0 - center.0);
    let end = (center.0 + radius * (a0 + sweep).cos(), center.1 + radius * (a0 + sweep).sin());
    Ok((Circle { center, radius, start_angle: a0, sweep }, end))
}

/// Adds `turns` full turns (`TURN=`) in the circle's own direction.
pub fn with_turns(mut c: Circle, turns: u32) -> Circle {
    c.sweep += c.sweep.signum() * TAU * f64::from(turns);
    c
}

fn positive_angle(a: f64) -> f64 {
    let a = a.rem_euclid(TAU);
    if a < 1e-12 { TAU } else { a }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn g3_quarter_circle_from_centre_turns_positive() {
        let c = from_center((10.0, 0.0), (0.0, 10.0), (0.0, 0.0), Turn::CounterClockwise).unwrap();
        assert!(close(c.sweep, FRAC_PI_2) && close(c.radius, 10.0));
    }

    #[test]
    fn g2_over_the_same_points_takes_the_long_way() {
        let c = from_center((10.0, 0.0), (0.0, 10.0), (0.0, 0.0), Turn::Clockwise).unwrap();
        assert!(close(c.sweep, -1.5 * PI));
    }

    #[test]
    fn start_equal_to_end_is_a_full_circle() {
        let c = from_center((10.0, 0.0), (10.0, 0.0), (0.0, 0.0), Turn::Clockwise).unwrap();
        assert!(close(c.sweep, -TAU));
    }

    #[test]
    fn positive_cr_gives_the_short_arc_and_negative_the_long_one() {
        // From (0,0) to (20,0) with radius 20: the chord subtends 60° (short) or 300° (long).
        let short = from_radius((0.0, 0.0), (20.0, 0.0), 20.0, Turn::Clockwise).unwrap();
        let long = from_radius((0.0, 0.0), (20.0, 0.0), -20.0, Turn::Clockwise).unwrap();
        assert!(close(short.sweep, -PI / 3.0), "{}", short.sweep);
        assert!(close(long.sweep, -5.0 * PI / 3.0), "{}", long.sweep);
        // A short clockwise arc from left to right bulges upwards: centre below the chord.
        assert!(close(short.center.0, 10.0) && close(short.center.1, -(300.0f64).sqrt()));
    }

    #[test]
    fn a_half_circle_by_radius_has_its_centre_on_the_chord() {
        let c = from_radius((0.0, 0.0), (20.0, 0.0), 10.0, Turn::CounterClockwise).unwrap();
        assert!(close(c.center.0, 10.0) && c.center.1.abs() < 1e-6);
        assert!(close(c.sweep.abs(), PI));
    }

    #[test]
    fn an_opening_angle_with_an_end_point_gives_the_radius() {
        // Chord 20 with AR=90: radius 20/(2 sin 45°) = 14.142, sweep 90°.
        let c = from_end_and_angle((0.0, 0.0), (20.0, 0.0), 90.0, Turn::CounterClockwise).unwrap();
        assert!(close(c.radius, 20.0 / 2f64.sqrt()) && close(c.sweep, FRAC_PI_2));
        let c = from_end_and_angle((0.0, 0.0), (20.0, 0.0), 270.0, Turn::Clockwise).unwrap();
        assert!(close(c.sweep, -1.5 * PI));
    }

    #[test]
    fn an_opening_angle_with_a_centre_gives_the_end_point() {
        let (c, end) = from_center_and_angle((10.0, 0.0), (0.0, 0.0), 90.0, Turn::Clockwise).unwrap();
        assert!(close(end.0, 0.0) && close(end.1, -10.0) && close(c.sweep, -FRAC_PI_2));
    }

    #[test]
    fn turns_add_full_circles_in_the_same_direction() {
        let c = from_center((10.0, 0.0), (0.0, 10.0), (0.0, 0.0), Turn::Clockwise).unwrap();
        assert!(close(with_turns(c, 2).sweep, -1.5 * PI - 2.0 * TAU));
    }

    #[test]
    fn end_points_off_the_circle_are_rejected() {
        assert_eq!(from_center((10.0, 0.0), (0.0, 10.5), (0.0, 0.0), Turn::Clockwise), Err(CircleError));
        assert_eq!(from_radius((0.0, 0.0), (30.0, 0.0), 10.0, Turn::Clockwise), Err(CircleError));
    }
}
