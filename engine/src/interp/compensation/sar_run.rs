//! Smooth approach and retract run by the tool radius compensation: the SAR block's sub-moves
//! (P0, P1, P2, P3, P4 of `compensation/sar.rs`) handed to the main run in place of the
//! selection's or deselection's straight line.

use super::{
    Compensator, Held, Prepared, elem_end, finish, left, minus, offset_elem, offset_start, place, plain, tangent,
    to_plane,
};
use crate::alarm::Alarm;
use crate::interp::Item;
use crate::interp::compensation::sar::{self, Sar};
use crate::interp::compensation::trc::{Compensation, Elem, P2};
use crate::motion::{AxisLimit, AxisVec, Feed};

/// One sub-move: the plane element of the tool centre, the axis-space points it runs between
/// (their plane part is the element's) and its feed.
type Leg = (Elem, AxisVec, AxisVec, Feed);

impl Compensator {
    /// The approach of SAR block `a` onto `contour`, the element of the next block `p`.
    #[allow(clippy::too_many_arguments, reason = "the compensator's push, split off")]
    pub(super) fn sar_approach(
        &mut self,
        a: Prepared,
        sar: Sar,
        p: Prepared,
        contour: Elem,
        comp: Compensation,
        limits: &[AxisLimit],
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = a.line;
        let d = comp.offset();
        let (p4, t, p4c) = (super::elem_start(&contour), tangent(&contour, false), offset_start(&contour, d));
        // With P4 from the block after the SAR block, the approach starts where that one did.
        let a3 = self.sar_head.take().map_or(a.mv.path.start, |h| h.mv.path.start);
        let b3 = a.mv.path.end;
        let s0 = minus(to_plane(&a3, &comp), comp.tip);
        let side = sar::side(sar.side, d, Some(s0), p4, t, false, line)?;
        let (p3, elem) = sar::approach_contour(sar.shape, sar.disr, comp.radius, p4c, t, side);
        let h0 = sar::height(&a3, &b3, &sar.normal);
        let hd = sar.clearance;
        sar::check_infeed(h0, hd, line)?;
        let at = |h: f64, q: P2| place(&sar::raised(&b3, &sar.normal, h), q, &comp);
        let f = sar.feed.unwrap_or(a.feed);
        let slow = sar.fad.unwrap_or(f);
        let h1 = sar.retract_plane.unwrap_or(h0);
        sar::check_retraction_plane(h1, hd, line)?;
        let (p1, p2) = (at(h1, p3), at(hd, p3));
        let line_to = |s: P2, e: P2| Elem::Line { s, e };
        let mut legs: Vec<Leg> = vec![(line_to(s0, p3), a3, p1, sar.before), (line_to(p3, p3), p1, p2, sar.before)];
        if sar.in_plane {
            legs.push((line_to(p3, p3), p2, at(0.0, p3), slow));
            legs.push((elem, at(0.0, p3), b3, f));
        } else {
            legs.push((elem, p2, b3, slow));
        }
        self.emit_legs(&a, legs, &comp, limits, out);
        self.tool_at = Some(p4c);
        self.release_pending(limits, out);
        self.held = Some(Held { skipped: Vec::new(), chain: Vec::new(), p, contour, start: p4c, comp });
        self.sar_virtual = sar.zero.is_some();
        Ok(())
    }

    /// The retract of G40 block `p` from the held element's end.
    pub(super) fn sar_retract(
        &mut self,
        p: Prepared,
        sar: Sar,
        limits: &[AxisLimit],
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = p.line;
        let Some(h) = self.held.take().filter(|h| h.skipped.is_empty()) else {
            return Err(Alarm::sar_direction(line));
        };
        let comp = h.comp;
        let d = comp.offset();
        let (p4, t) = (elem_end(&h.contour), tangent(&h.contour, true));
        let n = left(t);
        let p4c = (p4.0 + d * n.0, p4.1 + d * n.1);
        // The last element ends perpendicular to its contour end, where the retract begins.
        let eq = offset_elem(&h.contour, d, Some(h.start), Some(p4c), h.p.line)?;
        let mv = finish(&h.p, eq, &comp, limits, true);
        self.emit(h.p.item_with(mv), out);
        self.tool_at = Some(p4c);
        self.release_pending(limits, out);
        let a3 = self.from(p.mv.path.start);
        let b3 = p.mv.path.end;
        let p0 = minus(to_plane(&b3, &comp), comp.tip);
        let side = sar::side(sar.side, d, sar.end_in_plane.then_some(p0), p4, t, true, line)?;
        let (p3, elem) = sar::retract_contour(sar.shape, sar.disr, comp.radius, p4c, t, side);
        let p0 = if sar.end_in_plane { p0 } else { p3 };
        let h0 = sar::height(&b3, &a3, &sar.normal);
        let hd = sar.clearance;
        sar::check_infeed(h0, hd, line)?;
        let at = |h: f64, q: P2| place(&sar::raised(&a3, &sar.normal, h), q, &comp);
        // The roles of the feeds swap: the contour at the feed before, FAD for the slow part,
        // the block's own feed (G0 or F) from P2 to P0.
        let slow = sar.fad.unwrap_or(sar.before);
        let line_to = |s: P2, e: P2| Elem::Line { s, e };
        let h1 = sar.retract_plane.unwrap_or(h0);
        sar::check_retraction_plane(h1, hd, line)?;
        let (p2, p1) = (at(hd, p3), at(h1, p3));
        let mut legs: Vec<Leg> = Vec::new();
        if sar.in_plane {
            legs.push((elem, a3, at(0.0, p3), sar.before));
            legs.push((line_to(p3, p3), at(0.0, p3), p2, slow));
        } else {
            legs.push((elem, a3, p2, slow));
        }
        legs.push((line_to(p3, p3), p2, p1, p.feed));
        legs.push((line_to(p3, p0), p1, b3, p.feed));
        self.emit_legs(&p, legs, &comp, limits, out);
        self.tool_at = None;
        Ok(())
    }

    /// Hands out the legs that move (as moves of block `b` with their own feeds).
    fn emit_legs(
        &mut self,
        b: &Prepared,
        legs: Vec<Leg>,
        comp: &Compensation,
        limits: &[AxisLimit],
        out: &mut Vec<Item>,
    ) {
        for (elem, from3, to3, feed) in legs {
            let (s, e) = (place(&from3, super::elem_start(&elem), comp), place(&to3, elem_end(&elem), comp));
            let still = matches!(elem, Elem::Line { .. }) && (0..s.len()).all(|k| (s[k] - e[k]).abs() < 1e-9);
            if still {
                continue;
            }
            let q = Prepared { feed, ..b.clone() };
            let mut mv = plain(&q, elem, from3, to3, comp, limits);
            // Only a leg at the block's own feed follows the spindle under G95; rapid and FAD
            // legs keep their feed per minute.
            mv.per_rev = if feed == b.feed { b.mv.per_rev } else { 0.0 };
            self.emit(Item::Move { mv, line: b.line, offsets: b.offsets.clone() }, out);
        }
    }
}
