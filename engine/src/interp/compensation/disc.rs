//! DISC with G450: the transition at an outer corner between two straight equidistants,
//! pulled from the circle about the contour corner (DISC=0) towards the intersection of the
//! equidistants (DISC=100).
//!
//! Convention (the manuals show only the limits): the transition circle of G450 is scaled
//! about the intersection point by `1 − DISC/100`. It stays tangent to both equidistants, its
//! tangent points slide from the perpendicular points to the intersection, and its radius
//! shrinks from the tool radius to zero.

use crate::interp::compensation::trc::{Elem, P2};

/// The end of the first equidistant, the transition arc (None at DISC=100) and the start of
/// the second. `q1`, `q2`: the perpendicular points at the contour corner `p`; `x`: the
/// intersection of the equidistants.
pub(in crate::interp) fn disc_corner(q1: P2, q2: P2, x: P2, p: P2, disc: f64) -> (P2, Option<Elem>, P2) {
    let k = 1.0 - disc.clamp(0.0, 100.0) / 100.0;
    let scale = |q: P2| (x.0 + k * (q.0 - x.0), x.1 + k * (q.1 - x.1));
    let (t1, t2, c) = (scale(q1), scale(q2), scale(p));
    let r = k * (q1.0 - p.0).hypot(q1.1 - p.1);
    if r < 1e-9 {
        return (x, None, x);
    }
    let (v1, v2) = ((t1.0 - c.0, t1.1 - c.1), (t2.0 - c.0, t2.1 - c.1));
    // An outer corner's transition turns by less than half a turn: the short way round.
    let sweep = (v1.0 * v2.1 - v1.1 * v2.0).atan2(v1.0 * v2.0 + v1.1 * v2.1);
    (t1, Some(Elem::Arc { c, r, a0: v1.1.atan2(v1.0), sweep }), t2)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Square corner: contour corner (50, 0), G42 radius 5 going +X then +Y; the equidistants
    /// y = −5 and x = 55 meet at (55, −5).
    #[test]
    fn disc_50_halves_the_circle_towards_the_intersection() {
        let (a, arc, b) = disc_corner((50.0, -5.0), (55.0, 0.0), (55.0, -5.0), (50.0, 0.0), 50.0);
        assert_eq!(a, (52.5, -5.0));
        assert_eq!(b, (55.0, -2.5));
        let Some(Elem::Arc { c, r, sweep, .. }) = arc else { panic!() };
        assert_eq!((c, r), ((52.5, -2.5), 2.5));
        assert!((sweep - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn disc_100_is_the_intersection() {
        let (a, arc, b) = disc_corner((50.0, -5.0), (55.0, 0.0), (55.0, -5.0), (50.0, 0.0), 100.0);
        assert_eq!((a, b), ((55.0, -5.0), (55.0, -5.0)));
        assert!(arc.is_none());
    }
}
