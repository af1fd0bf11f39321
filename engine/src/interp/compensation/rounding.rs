//! RND where an arc meets the corner (line-arc, arc-line, arc-arc) under tool radius
//! compensation: the rounding is shaped on the programmed contour first, like the straight
//! corners of `contour::corners`, and then offset with it.
//!
//! The rounding circle of radius ρ touches both elements on the side the path turns to, so
//! its centre lies on both elements' equidistants at distance ρ on that side: their
//! intersection nearest the corner. The tangent points are the feet of the centre on the
//! elements (on an arc: along the ray from the arc's centre).

use crate::alarm::Alarm;
use crate::interp::compensation::trc::{Elem, P2, elem_end, elem_start, forward, intersection, offset_elem, tangent};

/// The first element shortened to the rounding, the rounding arc and the second element
/// shortened to it; None where the elements meet tangentially (no corner to round).
pub(in crate::interp) fn round(a: &Elem, b: &Elem, rho: f64, line: u32) -> Result<Option<(Elem, Elem, Elem)>, Alarm> {
    let (ta, tb) = (tangent(a, true), tangent(b, false));
    let cross = ta.0 * tb.1 - ta.1 * tb.0;
    let dot = ta.0 * tb.0 + ta.1 * tb.1;
    if rho <= 0.0 || (cross.abs() < 1e-9 && dot > 0.0) {
        return Ok(None);
    }
    let too_big = || Alarm::value_out_of_range(line, &format!("RND={rho} does not fit between the adjacent blocks"));
    let s = if cross > 0.0 { rho } else { -rho };
    let p = elem_end(a);
    let (oa, ob) = match (offset_elem(a, s, None, None, line), offset_elem(b, s, None, None, line)) {
        (Ok(oa), Ok(ob)) => (oa, ob),
        _ => return Err(too_big()),
    };
    let c = intersection(&oa, &ob, p).ok_or_else(too_big)?;
    let (t1, t2) = (foot(a, c), foot(b, c));
    if !forward(a, elem_start(a), t1) || !forward(b, t2, elem_end(b)) {
        return Err(too_big());
    }
    let e1 = offset_elem(a, 0.0, None, Some(t1), line)?;
    let e2 = offset_elem(b, 0.0, Some(t2), None, line)?;
    let a0 = (t1.1 - c.1).atan2(t1.0 - c.0);
    let a1 = (t2.1 - c.1).atan2(t2.0 - c.0);
    // The short way round, in the sense of the turn.
    let mut sweep = (a1 - a0).rem_euclid(std::f64::consts::TAU);
    if cross < 0.0 {
        sweep -= std::f64::consts::TAU;
    }
    Ok(Some((e1, Elem::Arc { c, r: rho, a0, sweep }, e2)))
}

/// The foot of `c` on the element's line or circle.
fn foot(e: &Elem, c: P2) -> P2 {
    match *e {
        Elem::Line { s, e } => {
            let d = (e.0 - s.0, e.1 - s.1);
            let t = ((c.0 - s.0) * d.0 + (c.1 - s.1) * d.1) / (d.0 * d.0 + d.1 * d.1);
            (s.0 + t * d.0, s.1 + t * d.1)
        }
        Elem::Arc { c: ac, r, .. } => {
            let l = (c.0 - ac.0).hypot(c.1 - ac.1);
            (ac.0 + r * (c.0 - ac.0) / l, ac.1 + r * (c.1 - ac.1) / l)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Line (0,0)→(30,0), then clockwise about (40,0) radius 10 over the top; RND=3: the
    /// rounding centre is 3 above the line and 13 from (40,0): (40 − √160, 3).
    #[test]
    fn line_into_an_arc() {
        let a = Elem::Line { s: (0.0, 0.0), e: (30.0, 0.0) };
        let b = Elem::Arc { c: (40.0, 0.0), r: 10.0, a0: std::f64::consts::PI, sweep: -std::f64::consts::PI };
        let (e1, r, e2) = round(&a, &b, 3.0, 1).unwrap().unwrap();
        let cx = 40.0 - 160f64.sqrt();
        assert!((elem_end(&e1).0 - cx).abs() < 1e-12 && elem_end(&e1).1.abs() < 1e-12);
        let Elem::Arc { c, r: rr, sweep, .. } = r else { panic!() };
        assert!((c.0 - cx).abs() < 1e-12 && (c.1 - 3.0).abs() < 1e-12 && rr == 3.0 && sweep > 0.0);
        let t2 = elem_start(&e2);
        assert!(((t2.0 - 40.0).hypot(t2.1) - 10.0).abs() < 1e-12);
        assert!(((t2.0 - c.0).hypot(t2.1 - c.1) - 3.0).abs() < 1e-12);
    }
}
