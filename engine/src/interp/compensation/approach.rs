//! Approach and retract of the tool radius compensation (G group 17): how the selection block
//! (G41/G42) reaches the first equidistant and how the deselection block (G40) leaves the last
//! one. All geometry is in plane coordinates of the tool centre.
//!
//! - NORM: a straight line to (from) the point perpendicular to the contour start (end).
//! - KONT: as NORM unless the start point lies behind the contour start and the tool would have
//!   to turn round an outer corner there; then it goes round the contour start point like at an
//!   outer corner: a tangent line onto the circle of the tool radius about it and that circle
//!   (G450), or the intersection of the tangent line with the first equidistant (G451).
//!   Start point within the tool radius of the contour start: alarm 10755 (retract 10756).
//! - KONTT: the approach is one circular arc from the start point that joins the first
//!   equidistant tangentially (continuous tangent at the contour; the direction at the start
//!   point is free, as with the control's approach polynomial).
//! - KONTC: a polynomial that joins the first equidistant with continuous tangent and
//!   curvature, run as short chords (`trc_kontc`).
//!
//! The retract is the approach of the reversed contour, reversed.

use crate::interp::compensation::trc::{
    Compensation, CornerMode, Elem, P2, dist, elem_start, left, line_line, offset_start, tangent,
};

// A child of this module so that the module list in `interp/mod.rs` stays untouched.
use crate::alarm::Alarm;
use crate::interp::compensation::kontc;
use std::f64::consts::TAU;

/// G group 17.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ApproachMode {
    /// NORM: perpendicular to the contour (default).
    Norm,
    /// KONT: round the contour start/end point when it lies behind the start/end point.
    Kont,
    /// KONTT: with continuous tangent.
    Tangent,
    /// KONTC: with continuous tangent and curvature (a polynomial, run as chords).
    Curvature,
}

/// A piece of an approach or retract path in plane coordinates, and the share (0..=1) of the
/// block's travel outside the plane that is done at its end.
pub(in crate::interp) type Piece = (Elem, f64);

/// The pieces from the tool centre `from` onto the equidistant (at signed offset `d`) of the
/// first element, and the point where that equidistant then starts. `lift` is the length of
/// the block's travel outside the plane (it refines KONTC's chords).
pub(in crate::interp) fn approach(
    mode: ApproachMode,
    from: P2,
    first: &Elem,
    d: f64,
    lift: f64,
    comp: &Compensation,
    line: u32,
) -> Result<(Vec<Piece>, P2), Alarm> {
    onto(mode, from, first, d, lift, comp.corners, line, false)
}

/// The point where the equidistant of `last` ends and the pieces from there to `to`.
pub(in crate::interp) fn retract(
    mode: ApproachMode,
    last: &Elem,
    d: f64,
    to: P2,
    lift: f64,
    comp: &Compensation,
    line: u32,
) -> Result<(P2, Vec<Piece>), Alarm> {
    // Travelled backwards the contour has the tool on the other side.
    let (pieces, end) = onto(mode, to, &reversed(last), -d, lift, comp.corners, line, true)?;
    // Reversed, a piece ends where it started: the share done there, counted from the contour.
    let starts: Vec<f64> = std::iter::once(0.0).chain(pieces.iter().map(|p| p.1)).collect();
    Ok((end, pieces.iter().enumerate().rev().map(|(i, (e, _))| (reversed(e), 1.0 - starts[i])).collect()))
}

/// Except for KONTC the first piece carries the whole travel outside the plane.
#[allow(clippy::too_many_arguments, reason = "the approach's geometry and where an alarm points")]
fn onto(
    mode: ApproachMode,
    from: P2,
    first: &Elem,
    d: f64,
    lift: f64,
    corners: CornerMode,
    line: u32,
    retract: bool,
) -> Result<(Vec<Piece>, P2), Alarm> {
    let q = offset_start(first, d);
    let norm = || if dist(from, q) < 1e-9 { (Vec::new(), q) } else { (vec![(Elem::Line { s: from, e: q }, 1.0)], q) };
    let whole = |elems: Vec<Elem>| elems.into_iter().map(|e| (e, 1.0)).collect::<Vec<Piece>>();
    match mode {
        ApproachMode::Norm => Ok(norm()),
        ApproachMode::Curvature => Ok(match kontc::curve(from, first, d) {
            Some(curve) => (kontc::chords(&curve, lift), q),
            None => norm(),
        }),
        ApproachMode::Tangent => {
            Ok(tangential(from, q, tangent(first, false)).map(|(e, q)| (whole(e), q)).unwrap_or_else(norm))
        }
        ApproachMode::Kont => {
            let p1 = elem_start(first);
            let tb = tangent(first, false);
            let to_p1 = (p1.0 - from.0, p1.1 - from.1);
            let len = to_p1.0.hypot(to_p1.1);
            if len < 1e-9 {
                return Ok(norm());
            }
            let ta = (to_p1.0 / len, to_p1.1 / len);
            let cross = ta.0 * tb.1 - ta.1 * tb.0;
            let behind = (from.0 - p1.0) * tb.0 + (from.1 - p1.1) * tb.1 > 1e-9;
            if !(behind && cross * d < 0.0) {
                return Ok(norm());
            }
            let rho = d.abs();
            if len <= rho + 1e-9 {
                return Err(Alarm::trc_kont(line, retract));
            }
            let turn = cross.signum();
            let u0 = ((from.0 - p1.0) / len, (from.1 - p1.1) / len);
            let beta = (rho / len).acos();
            let touch = [beta, -beta]
                .into_iter()
                .map(|b| {
                    let (sn, cs) = b.sin_cos();
                    (p1.0 + rho * (u0.0 * cs - u0.1 * sn), p1.1 + rho * (u0.0 * sn + u0.1 * cs))
                })
                .find(|t| {
                    // Travelling the circle in the corner's turning sense continues the line.
                    let n = left(((t.0 - p1.0) / rho, (t.1 - p1.1) / rho));
                    ((t.0 - from.0) * n.0 + (t.1 - from.1) * n.1) * turn > 0.0
                })
                .ok_or_else(|| Alarm::trc_kont(line, retract))?;
            if corners == CornerMode::Intersection
                && let Elem::Line { .. } = first
                && let Some(x) = line_line(from, touch, q, (q.0 + tb.0, q.1 + tb.1))
                && (x.0 - q.0) * tb.0 + (x.1 - q.1) * tb.1 <= 1e-9
            {
                return Ok((whole(vec![Elem::Line { s: from, e: x }]), x));
            }
            let a0 = (touch.1 - p1.1).atan2(touch.0 - p1.0);
            let a1 = (q.1 - p1.1).atan2(q.0 - p1.0);
            let sweep = turning(a1 - a0, turn);
            Ok((whole(vec![Elem::Line { s: from, e: touch }, Elem::Arc { c: p1, r: rho, a0, sweep }]), q))
        }
    }
}

/// The arc from `from` that reaches `q` with direction `t`; None if `from` lies on the tangent
/// (a straight line then joins tangentially, or nothing does).
fn tangential(from: P2, q: P2, t: P2) -> Option<(Vec<Elem>, P2)> {
    let n = left(t);
    let w = (q.0 - from.0, q.1 - from.1);
    let ww = w.0 * w.0 + w.1 * w.1;
    let nw = n.0 * w.0 + n.1 * w.1;
    if ww < 1e-18 {
        return Some((Vec::new(), q));
    }
    if nw.abs() < 1e-9 * ww.sqrt() {
        return None;
    }
    let lambda = -ww / (2.0 * nw);
    let c = (q.0 + lambda * n.0, q.1 + lambda * n.1);
    let a0 = (from.1 - c.1).atan2(from.0 - c.0);
    let a1 = (q.1 - c.1).atan2(q.0 - c.0);
    // Counter-clockwise exactly when the centre lies left of the direction at q.
    let sweep = turning(a1 - a0, lambda.signum());
    Some((vec![Elem::Arc { c, r: lambda.abs(), a0, sweep }], q))
}

/// `delta` brought into (0, 2π) for `turn` > 0, into (−2π, 0) otherwise.
fn turning(delta: f64, turn: f64) -> f64 {
    let mut s = delta.rem_euclid(TAU);
    if turn < 0.0 {
        s -= TAU;
    }
    if s.abs() < 1e-12 { 0.0 } else { s }
}

fn reversed(e: &Elem) -> Elem {
    match *e {
        Elem::Line { s, e } => Elem::Line { s: e, e: s },
        Elem::Arc { c, r, a0, sweep } => Elem::Arc { c, r, a0: a0 + sweep, sweep: -sweep },
    }
}
