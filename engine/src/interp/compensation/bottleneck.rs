//! Bottleneck look-ahead (MD20240 CUTCOM_MAXNUM_CHECK_BLOCKS): when the equidistants of an
//! inner corner meet only beyond the end of the second one, that element is too short for the
//! tool. The compensation then looks at the following elements and joins the first
//! equidistant directly to a later one, skipping what lies between (the skipped blocks keep
//! only their motion outside the plane). No join within the examined blocks: alarm 10751.
//!
//! The join with the element `c` after the last skipped element `last`, at the corner point P
//! between them: an outer corner there puts the tool on the circle of the tool radius about
//! P, so the first equidistant is cut with that circle and the tool follows the circle to the
//! start of `c`'s equidistant; an inner corner cuts the first equidistant with `c`'s.

use crate::interp::compensation::trc::{
    Elem, Meet, P2, circle_circle, elem_end, elem_start, intersection, left, line_circle, offset_elem, tangent,
};
use std::f64::consts::TAU;

/// The join of the equidistant `a_eq` (its start is where the tool is) with the element `c`,
/// or None if they do not meet ahead of the tool.
/// `across_outer`: whether the join may go round an outer corner (the circle about it). With
/// CDOF the search goes back over earlier blocks at inside corners (W1); the circle about the
/// corner of a single omitted element counts as the block inserted there. Only collision
/// detection (CDON) joins the equidistants of blocks further apart across an outer corner
/// (which is how it bridges a slot narrower than the tool).
pub(in crate::interp) fn bridge(a_eq: &Elem, last: &Elem, c: &Elem, d: f64, across_outer: bool) -> Option<Meet> {
    let p = elem_end(last);
    let (tl, tc) = (tangent(last, true), tangent(c, false));
    let cross = tl.0 * tc.1 - tl.1 * tc.0;
    let nc = left(tc);
    let q2 = (p.0 + d * nc.0, p.1 + d * nc.1);
    if cross * d < 0.0 {
        if !across_outer {
            return None;
        }
        let r = d.abs();
        let hits = match *a_eq {
            Elem::Line { s, e } => line_circle(s, e, p, r),
            Elem::Arc { c: ac, r: ar, .. } => circle_circle(ac, ar, p, r),
        };
        let x = hits.into_iter().filter_map(|x| ahead(a_eq, x).map(|t| (t, x))).min_by(|a, b| a.0.total_cmp(&b.0))?.1;
        let a0 = (x.1 - p.1).atan2(x.0 - p.0);
        let a1 = (q2.1 - p.1).atan2(q2.0 - p.0);
        let mut sweep = (a1 - a0).rem_euclid(TAU);
        if cross < 0.0 && sweep > 0.0 {
            sweep -= TAU;
        }
        let arc = (sweep.abs() > 1e-12).then_some(Elem::Arc { c: p, r, a0, sweep });
        return Some((x, arc, q2));
    }
    let oc = offset_elem(c, d, None, None, 0).ok()?;
    let x = intersection(a_eq, &oc, p)?;
    ahead(a_eq, x)?;
    // Not beyond the end of c's equidistant.
    if let Elem::Line { s, e } = oc
        && (x.0 - e.0) * (s.0 - e.0) + (x.1 - e.1) * (s.1 - e.1) < -1e-9
    {
        return None;
    }
    Some((x, None, x))
}

/// How far along `e` (from its start, in its direction) the point `x` on it lies; None if
/// behind the start.
fn ahead(e: &Elem, x: P2) -> Option<f64> {
    let t = match *e {
        Elem::Line { s, e } => (x.0 - s.0) * (e.0 - s.0) + (x.1 - s.1) * (e.1 - s.1),
        Elem::Arc { c, a0, sweep, .. } => {
            let a = (x.1 - c.1).atan2(x.0 - c.0);
            let w = (a - a0) * sweep.signum();
            w.rem_euclid(TAU)
        }
    };
    let s = elem_start(e);
    let at_start = (x.0 - s.0).hypot(x.1 - s.1) < 1e-9;
    (t >= -1e-9 || at_start).then_some(t.max(0.0))
}
