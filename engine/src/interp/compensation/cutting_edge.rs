//! Cutting edge position of turning tools ($TC_DP2 = 1..9): where the theoretical tool tip P
//! lies relative to the cutting-edge centre S. Without radius compensation P follows the
//! programmed contour (the tool lengths measure to P); with G41/G42 the centre S runs on the
//! equidistant and the control positions P = S + r·(sx, sy).
//!
//! The table is in the working plane's abscissa/ordinate as seen with the plane normal
//! pointing at the viewer (G18 on a lathe: Z to the right, X up, i.e. a tool behind the
//! turning centre): 1 = (+,+), 2 = (−,+), 3 = (−,−), 4 = (+,−), 5 = (+,0), 6 = (0,+),
//! 7 = (−,0), 8 = (0,−), 9 = S itself. Position 3 is the usual external turning tool cutting
//! towards the chuck (−Z) and the axis (−X). The numbering follows the control's figure
//! from memory; the geometry (tip on the tangents at the nose circle) is exact.

/// The direction of P − S for cutting edge position `position` ($TC_DP2) in the plane's
/// (abscissa, ordinate), the table above; (0, 0) for 9 and positions outside 1..8. The
/// material removal model places its turning inserts with it too.
pub(crate) fn edge_direction(position: f64) -> (f64, f64) {
    match position.round() as i64 {
        1 => (1.0, 1.0),
        2 => (-1.0, 1.0),
        3 => (-1.0, -1.0),
        4 => (1.0, -1.0),
        5 => (1.0, 0.0),
        6 => (0.0, 1.0),
        7 => (-1.0, 0.0),
        8 => (0.0, -1.0),
        _ => (0.0, 0.0),
    }
}

/// P − S in plane coordinates for a tool of type `tool_type` ($TC_DP1) with cutting edge
/// position `position` ($TC_DP2) and radius `r`; zero for milling tools, position 0 or 9.
pub(in crate::interp) fn tip_offset(tool_type: f64, position: f64, r: f64) -> (f64, f64) {
    if !(400.0..600.0).contains(&tool_type) {
        return (0.0, 0.0);
    }
    let (sx, sy) = edge_direction(position);
    (r * sx, r * sy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn milling_tools_and_position_9_have_no_tip_offset() {
        assert_eq!(tip_offset(120.0, 3.0, 5.0), (0.0, 0.0));
        assert_eq!(tip_offset(500.0, 9.0, 0.8), (0.0, 0.0));
    }

    #[test]
    fn the_external_turning_tool_has_its_tip_below_left_of_the_centre() {
        assert_eq!(tip_offset(500.0, 3.0, 0.8), (-0.8, -0.8));
        assert_eq!(tip_offset(510.0, 6.0, 0.4), (0.0, 0.4));
    }
}
