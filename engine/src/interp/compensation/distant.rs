//! Bottleneck detection between elements that are not neighbours (MD20240
//! CUTCOM_MAXNUM_CHECK_BLOCKS): before the held element's equidistant is released, it is
//! cut with the tool-centre pieces of the elements the look-ahead already joined after its
//! neighbour (their transition circles and equidistants). A crossing means the tool would
//! run into the band within the tool radius of that later element's contour: the contour
//! folds back on itself closer than the tool diameter (a neck, a slot whose walls are several
//! blocks apart).
//!
//! A tool path can also reach into that band without crossing a piece (near the end of the
//! held element, where its piece stops short of its contour's end): the exact least distance
//! between each tool-centre piece and the other element's contour is checked too.
//!
//! The reaction (Function Manual W1, collision detection): with `CDON` the tool path is cut
//! at the crossing and the elements between are skipped (their motion outside the plane runs
//! at the crossing; warning 10763 for each); with `CDOF` (no collision detection, the
//! default), and with CDON where the paths come too near without crossing, alarm 10751 stops
//! the program before any motion of the held element.

use crate::interp::compensation::trc::{Elem, P2, circle_circle, dist, elem_end, elem_start, line_circle, line_line};
use std::f64::consts::TAU;

/// A tool-centre piece of a later element: which chain entry it belongs to, whether it is
/// the transition circle before that element (else its equidistant), and its geometry.
pub(in crate::interp) type Piece = (usize, bool, Elem);

/// The first point along `head` (not at its ends) where it crosses one of the `later`
/// pieces: the owner, whether on its transition, and the point.
pub(in crate::interp) fn first_crossing(head: &Elem, later: &[Piece]) -> Option<(usize, bool, P2)> {
    let (hs, he) = (elem_start(head), elem_end(head));
    later
        .iter()
        .flat_map(|&(owner, transition, piece)| {
            candidates(head, &piece)
                .into_iter()
                .filter(move |&x| on(&piece, x, 1e-9))
                .map(move |x| (owner, transition, x))
        })
        .filter(|&(.., x)| on(head, x, 0.0) && dist(x, hs) > 1e-7 && dist(x, he) > 1e-7)
        .min_by(|a, b| along(head, a.2).total_cmp(&along(head, b.2)).then(b.0.cmp(&a.0)))
}

/// Whether the held element's pieces `head` (its equidistant and the transition after it,
/// released together) and its contour `head_contour` keep the tool radius
/// `r` from the later elements: the owner of the first later element (piece or contour, as
/// listed in `later` and `contours`) that comes nearer, or None.
pub(in crate::interp) fn too_near(
    head: &[Elem],
    head_contour: &Elem,
    later: &[Piece],
    contours: &[(usize, Elem)],
    r: f64,
) -> Option<usize> {
    let limit = r - 1e-7;
    let a = contours.iter().find(|(_, c)| head.iter().any(|h| least_distance(h, c) < limit)).map(|(k, _)| *k);
    let b = later.iter().find(|(.., p)| least_distance(p, head_contour) < limit).map(|(k, ..)| *k);
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Whether one of the tool-centre `pieces` comes nearer than the radius `r` to one of the
/// `contours`.
pub(in crate::interp) fn near_any(pieces: &[Elem], contours: impl Iterator<Item = Elem>, r: f64) -> bool {
    let limit = r - 1e-7;
    contours.into_iter().any(|c| pieces.iter().any(|p| least_distance(p, &c) < limit))
}

/// The least distance between two elements (segments or arcs), exactly: the minimum lies at
/// an end point of one of them, at a crossing, or on the normal through a circle's centre
/// (foot of the centre on a line, or the line through both centres).
fn least_distance(a: &Elem, b: &Elem) -> f64 {
    if candidates(a, b).into_iter().any(|x| on(a, x, 1e-12) && on(b, x, 1e-12)) {
        return 0.0;
    }
    let mut best = [elem_start(a), elem_end(a)].iter().map(|&p| point_distance(p, b)).fold(f64::INFINITY, f64::min);
    best = [elem_start(b), elem_end(b)].iter().map(|&p| point_distance(p, a)).fold(best, f64::min);
    for (x, y) in [(a, b), (b, a)] {
        // Points of x on the normal through y's centre (y an arc), or through its own centre
        // towards y.
        let points: Vec<P2> = match (*x, *y) {
            (Elem::Line { s, e }, Elem::Arc { c, .. }) => vec![foot(s, e, c)],
            (Elem::Arc { c, r, .. }, Elem::Line { s, e }) => {
                let f = foot(s, e, c);
                toward(c, r, f).into_iter().collect()
            }
            (Elem::Arc { c, r, .. }, Elem::Arc { c: c2, .. }) => {
                toward(c, r, c2).into_iter().chain(toward(c, -r, c2)).collect()
            }
            _ => Vec::new(),
        };
        best = points.into_iter().filter(|&p| on(x, p, 1e-12)).map(|p| point_distance(p, y)).fold(best, f64::min);
    }
    best
}

/// The foot of `p` on the line through `s` and `e`.
fn foot(s: P2, e: P2, p: P2) -> P2 {
    let d = (e.0 - s.0, e.1 - s.1);
    let t = ((p.0 - s.0) * d.0 + (p.1 - s.1) * d.1) / (d.0 * d.0 + d.1 * d.1).max(1e-24);
    (s.0 + t * d.0, s.1 + t * d.1)
}

/// The point at signed distance `r` from `c` towards `p`.
fn toward(c: P2, r: f64, p: P2) -> Option<P2> {
    let l = dist(c, p);
    (l > 1e-12).then(|| (c.0 + r * (p.0 - c.0) / l, c.1 + r * (p.1 - c.1) / l))
}

/// Distance of a point from an element.
fn point_distance(p: P2, e: &Elem) -> f64 {
    let ends = dist(p, elem_start(e)).min(dist(p, elem_end(e)));
    match *e {
        Elem::Line { s, e: en } => {
            let f = foot(s, en, p);
            if on(e, f, 0.0) { dist(p, f) } else { ends }
        }
        Elem::Arc { c, r, .. } => match toward(c, r, p) {
            Some(q) if on(e, q, 0.0) => (dist(p, c) - r).abs(),
            _ => ends,
        },
    }
}

/// Where the lines or circles carrying two pieces meet.
fn candidates(a: &Elem, b: &Elem) -> Vec<P2> {
    match (*a, *b) {
        (Elem::Line { s: s1, e: e1 }, Elem::Line { s: s2, e: e2 }) => line_line(s1, e1, s2, e2).into_iter().collect(),
        (Elem::Line { s, e }, Elem::Arc { c, r, .. }) | (Elem::Arc { c, r, .. }, Elem::Line { s, e }) => {
            line_circle(s, e, c, r)
        }
        (Elem::Arc { c: c1, r: r1, .. }, Elem::Arc { c: c2, r: r2, .. }) => circle_circle(c1, r1, c2, r2),
    }
}

/// Whether `x` (on the piece's line or circle) lies on the piece, with `tol` of its length
/// share at either end.
fn on(e: &Elem, x: P2, tol: f64) -> bool {
    let t = along(e, x);
    (-tol..=1.0 + tol).contains(&t)
}

/// How far along the piece `x` lies: 0 at its start, 1 at its end (arcs: by angle in the
/// sense of travel, from the start; outside the sweep above 1).
fn along(e: &Elem, x: P2) -> f64 {
    match *e {
        Elem::Line { s, e } => {
            let d = (e.0 - s.0, e.1 - s.1);
            ((x.0 - s.0) * d.0 + (x.1 - s.1) * d.1) / (d.0 * d.0 + d.1 * d.1).max(1e-24)
        }
        Elem::Arc { c, a0, sweep, .. } => {
            let w = (((x.1 - c.1).atan2(x.0 - c.0) - a0) * sweep.signum()).rem_euclid(TAU);
            // A point a hair behind the start is at the start.
            let w = if w > TAU - 1e-9 { 0.0 } else { w };
            w / sweep.abs().max(1e-12)
        }
    }
}

/// The transition circle from `x` (on it) to its end; None where nothing is left of it.
pub(in crate::interp) fn arc_from(arc: &Elem, x: P2) -> Option<Elem> {
    let Elem::Arc { c, r, sweep, .. } = *arc else { return None };
    let rest = (1.0 - along(arc, x)).max(0.0) * sweep;
    (rest.abs() > 1e-12).then(|| Elem::Arc { c, r, a0: (x.1 - c.1).atan2(x.0 - c.0), sweep: rest })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The head y = 5 from x = 0 to 40 and a later equidistant x = 35 from y = 20 down to
    /// y = −10 cross at (35, 5); a transition circle about (60, 5) radius 5 is not reached.
    #[test]
    fn a_later_equidistant_crossing_the_head_is_found_where_they_cross() {
        let head = Elem::Line { s: (0.0, 5.0), e: (40.0, 5.0) };
        let later = [
            (1, true, Elem::Arc { c: (60.0, 5.0), r: 5.0, a0: 0.0, sweep: std::f64::consts::PI }),
            (2, false, Elem::Line { s: (35.0, 20.0), e: (35.0, -10.0) }),
        ];
        let (owner, transition, x) = first_crossing(&head, &later).unwrap();
        assert_eq!((owner, transition), (2, false));
        assert!(dist(x, (35.0, 5.0)) < 1e-12);
        // A later piece that ends before the head's line is not a crossing.
        let short = [(2, false, Elem::Line { s: (35.0, 20.0), e: (35.0, 6.0) })];
        assert!(first_crossing(&head, &short).is_none());
    }

    /// Least distances worked out by hand: parallel segments 3 apart; a segment and the
    /// quarter arc about (0,0) radius 10 from 0° to 90° seen from (20, 20) along the diagonal
    /// (20√2 − 10); the same arc and one of radius 2 about (15, 0): 15 − 10 − 2 = 3.
    #[test]
    fn least_distances_by_hand() {
        let a = Elem::Line { s: (0.0, 0.0), e: (10.0, 0.0) };
        let b = Elem::Line { s: (5.0, 3.0), e: (20.0, 3.0) };
        assert!((least_distance(&a, &b) - 3.0).abs() < 1e-12);
        let arc = Elem::Arc { c: (0.0, 0.0), r: 10.0, a0: 0.0, sweep: std::f64::consts::FRAC_PI_2 };
        let diag = Elem::Line { s: (30.0, 10.0), e: (10.0, 30.0) };
        assert!((least_distance(&diag, &arc) - (20.0 * 2f64.sqrt() - 10.0)).abs() < 1e-12);
        assert!((least_distance(&arc, &diag) - (20.0 * 2f64.sqrt() - 10.0)).abs() < 1e-12);
        let small = Elem::Arc { c: (15.0, 0.0), r: 2.0, a0: 0.0, sweep: std::f64::consts::TAU - 0.1 };
        assert!((least_distance(&arc, &small) - 3.0).abs() < 1e-12);
        // Crossing segments.
        assert_eq!(least_distance(&a, &Elem::Line { s: (5.0, -1.0), e: (5.0, 1.0) }), 0.0);
    }
}
