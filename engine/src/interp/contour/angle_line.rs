//! `ANG=`: a straight line given by one end coordinate and its angle (Programming Manual
//! Fundamentals, "Contour definitions": drawing dimensions). The single-block form `G1 ANG=α
//! X..` (or with the ordinate) runs from the block's start along the line at α to the positive
//! abscissa of the working plane (counter-clockwise positive, degrees) until it reaches the
//! coordinate given; the other one follows: Δordinate = Δabscissa·tan α.
//!
//! Refused: both plane coordinates with ANG (the line is over-determined) or neither, and an
//! angle parallel to the axis whose coordinate is given (the line never reaches it): 12560,
//! NCTwin's choice of number, the manual naming none. The two-block form (the corner found from
//! the ANG of both blocks) is `angle_corner.rs`; the three-block forms are not modelled.

use crate::alarm::Alarm;

/// The missing plane coordinate of a line from `start` (abscissa, ordinate) at `angle`
/// degrees with the abscissa `end.0` or the ordinate `end.1` given: the full end point.
pub fn end_point(
    start: (f64, f64),
    end: (Option<f64>, Option<f64>),
    angle: f64,
    line: u32,
) -> Result<(f64, f64), Alarm> {
    let (sin, cos) = angle.to_radians().sin_cos();
    let refuse = |why: &str| Err(Alarm::value_out_of_range(line, &format!("ANG={}: {why}", Alarm::shown(angle))));
    match end {
        (Some(a), None) if cos.abs() > 1e-12 => Ok((a, start.1 + (a - start.0) * sin / cos)),
        (None, Some(o)) if sin.abs() > 1e-12 => Ok((start.0 + (o - start.1) * cos / sin, o)),
        (Some(_), None) | (None, Some(_)) => refuse("the line runs parallel to the axis programmed"),
        (Some(_), Some(_)) => refuse("both coordinates of the plane given"),
        (None, None) => refuse("no coordinate of the plane given"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thirty_degrees_to_x20_rises_by_20_tan_30() {
        let (x, y) = end_point((0.0, 0.0), (Some(20.0), None), 30.0, 1).unwrap();
        assert_eq!(x, 20.0);
        assert!((y - 20.0 / 3f64.sqrt()).abs() < 1e-12, "{y}");
    }

    #[test]
    fn an_ordinate_with_135_degrees_goes_back_along_the_abscissa() {
        // From (10,0) at 135° to Y5: Δx = 5·cos/sin = −5.
        let (x, y) = end_point((10.0, 0.0), (None, Some(5.0)), 135.0, 1).unwrap();
        assert!((x - 5.0).abs() < 1e-12 && y == 5.0);
    }

    #[test]
    fn parallel_over_and_under_determined_lines_are_12560() {
        for end in [(None, Some(5.0)), (Some(1.0), Some(1.0)), (None, None)] {
            assert_eq!(end_point((0.0, 0.0), end, 0.0, 3).unwrap_err().number, 12560);
        }
    }
}
