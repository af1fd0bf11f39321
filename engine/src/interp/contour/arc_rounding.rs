//! RND (and RNDM) where a circle meets the corner, without tool radius compensation:
//! line-arc, arc-line and arc-arc. The rounding circle of the programmed radius touches both
//! elements on the side the path turns to (the same geometry TRC shapes into its contour,
//! `compensation::rounding`); here the two moves are cut back to the tangent points and the
//! rounding arc is put between them.
//!
//! The plane of the rounding is the plane of the (first) circle, read from its own axes, so
//! a corner under a rotated frame rounds in the rotated plane. Motion outside that plane
//! (a helix) is shortened in proportion with the block; the rounding arc carries none of its
//! own except to join the two cut ends; a line with motion outside the plane rounds with its
//! projection. Where the second arc lies in another plane the corner stays sharp.

use crate::alarm::Alarm;
use crate::interp::compensation::rounding;
use crate::interp::compensation::trc::{Elem, P2, elem_end, elem_start};
use crate::motion::{Arc, AxisLimit, AxisVec, Feed, Move, Path};
use std::f64::consts::TAU;

/// `first` cut back to the rounding (returned), the rounding arc (returned) and `next` cut in
/// place; None where there is no corner to round (tangent elements) or no common plane.
/// Alarm 12560 on `line` where the radius does not fit on the elements.
pub(in crate::interp) fn round_at_arc(
    first: &Move,
    next: &mut Move,
    rho: f64,
    line: u32,
    limits: &[AxisLimit],
) -> Result<Option<(Move, Move)>, Alarm> {
    let Some(plane) = first.path.arc.as_ref().or(next.path.arc.as_ref()).map(|a| (a.u, a.v)) else {
        return Ok(None);
    };
    if !orthonormal(&plane) {
        return Ok(None);
    }
    let (Some(a), Some(b)) = (element(first, &plane), element(next, &plane)) else { return Ok(None) };
    let Some((e1, round, e2)) = rounding::round(&a, &b, rho, line)? else { return Ok(None) };
    let Elem::Arc { r, a0, sweep, .. } = round else { return Ok(None) };
    let s1 = share(&a, elem_end(&e1));
    let s2 = share(&b, elem_start(&e2));
    let mut shortened = cut(first, 0.0, s1);
    shortened.exact_stop = false;
    let rest = cut(next, s2, 1.0);
    let path = Path {
        start: shortened.path.end,
        end: rest.path.start,
        arc: Some(Box::new(Arc { u: plane.0, v: plane.1, radius: r, start_angle: a0, sweep })),
        ori: None,
        curve: None,
    };
    let out_of_plane = {
        let d: AxisVec = std::array::from_fn(|k| path.end[k] - path.start[k]);
        let (du, dv) = (dot(&d, &plane.0), dot(&d, &plane.1));
        (dot(&d, &d) - du * du - dv * dv).max(0.0)
    };
    let length = ((r * sweep).powi(2) + out_of_plane).sqrt();
    // The rounding runs at the first block's feed, within the axes' limits on its arc.
    let corner = Move::new(path, length, Feed::Path(first.v_max), limits, first.exact_stop, first.tag);
    *next = rest;
    Ok(Some((shortened, corner)))
}

/// The move's part between path parameters `u0` and `u1` (uniform in length), its length and
/// everything else kept.
fn cut(mv: &Move, u0: f64, u1: f64) -> Move {
    let mut out = mv.clone();
    out.path = mv.path.slice(u0, u1);
    out.length = mv.length * (u1 - u0);
    out
}

/// Where `p` (on the element) lies along it, 0 at its start and 1 at its end.
fn share(e: &Elem, p: P2) -> f64 {
    let s = match *e {
        Elem::Line { s, e } => {
            let d = (e.0 - s.0, e.1 - s.1);
            ((p.0 - s.0) * d.0 + (p.1 - s.1) * d.1) / (d.0 * d.0 + d.1 * d.1)
        }
        Elem::Arc { c, a0, sweep, .. } => {
            let a = (p.1 - c.1).atan2(p.0 - c.0);
            let w = ((a - a0) * sweep.signum()).rem_euclid(TAU);
            // A point just behind the start (rounding error) is at the start, not a turn on.
            let w = if w > TAU - 1e-9 { 0.0 } else { w };
            w / sweep.abs()
        }
    };
    s.clamp(0.0, 1.0)
}

/// The move's element in the plane (u, v); None where it leaves the plane in a way the
/// rounding cannot follow (an arc in another plane) or has no motion in it.
fn element(mv: &Move, plane: &(AxisVec, AxisVec)) -> Option<Elem> {
    let to = |p: &AxisVec| (dot(p, &plane.0), dot(p, &plane.1));
    let (s, e) = (to(&mv.path.start), to(&mv.path.end));
    match &mv.path.arc {
        Some(arc) => {
            let ru = (dot(&arc.u, &plane.0), dot(&arc.u, &plane.1));
            let rv = (dot(&arc.v, &plane.0), dot(&arc.v, &plane.1));
            let orient = ru.0 * rv.1 - ru.1 * rv.0;
            if (orient.abs() - 1.0).abs() > 1e-9 {
                return None;
            }
            let (cs, sn) = (arc.start_angle.cos(), arc.start_angle.sin());
            let a0 = (cs * ru.1 + sn * rv.1).atan2(cs * ru.0 + sn * rv.0);
            let c = (s.0 - arc.radius * a0.cos(), s.1 - arc.radius * a0.sin());
            Some(Elem::Arc { c, r: arc.radius, a0, sweep: arc.sweep * orient.signum() })
        }
        None if (e.0 - s.0).hypot(e.1 - s.1) > 1e-9 => Some(Elem::Line { s, e }),
        None => None,
    }
}

fn orthonormal((u, v): &(AxisVec, AxisVec)) -> bool {
    (dot(u, u) - 1.0).abs() < 1e-9 && (dot(v, v) - 1.0).abs() < 1e-9 && dot(u, v).abs() < 1e-9
}

fn dot(a: &AxisVec, b: &AxisVec) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
