//! KONTC: approach and retract of the tool radius compensation with continuous curvature.
//!
//! What the manual fixes (W1 "Approach and retraction behaviour", Programming Manual NORM/KONT/
//! KONTC/KONTT): the approach is a polynomial in the working plane from the start point (the
//! uncompensated position where the tool stands) to the start of the first equidistant; there it
//! joins with the same tangent and the same curvature, so the path acceleration does not jump
//! when compensation becomes active. The retract is the same in reverse, from the end of the
//! last equidistant to the programmed end point. It says nothing about the direction or
//! curvature at the start point, nor about the polynomial's degree, and notes that the
//! curvature condition can give wide, unwanted curves (the figure "Differences between KONTT and
//! KONTC").
//!
//! What this model chooses where the manual is silent: a quintic Hermite polynomial P(u),
//! u ∈ [0, 1], with
//! - P(0) = start point, P′(0) = L·D, P″(0) = 0: it leaves the start point in the direction D
//!   that KONTT's arc would take there (KONTC is KONTT with the curvature added) and with zero
//!   curvature (as after a straight move or standstill);
//! - P(1) = Q (start of the equidistant), P′(1) = L·T, P″(1) = L²·κ·N: tangent T and signed
//!   curvature κ of the equidistant at Q, N the left normal; with |P′(1)| = L and P″(1) ⟂ T the
//!   curvature there is exactly κ;
//! - L, the parameter speed at both ends, is the length of KONTT's arc (the chord when it is
//!   straight), so the polynomial runs about as KONTT's arc would.
//!
//! When the start point lies on the tangent ahead of Q (KONTT has no arc either) the approach
//! is NORM's straight line, as with KONTT.
//!
//! The motion module has no polynomial path, so the curve is run as a sequence of straight
//! continuous-path moves whose ends lie on the polynomial. Their number follows from a bound on
//! |P″| so that every chord stays within [`CHORD_TOLERANCE`] of the curve: the path geometry is
//! the polynomial within that tolerance (at the joints the direction turns by about √(8·tol·κ)).
//! Axes outside the plane (an infeed in Z) follow the share s(u) = 1 − (1 − u)³ of their travel:
//! they arrive at Q with zero velocity and acceleration, so the path in space also joins the
//! contour with continuous tangent and curvature.

use crate::interp::compensation::approach::Piece;
use crate::interp::compensation::trc::{Elem, P2, left, offset_start, tangent};

/// Largest distance between a chord and the approach polynomial it stands for (1 µm in mm).
pub(in crate::interp) const CHORD_TOLERANCE: f64 = 1e-3;

/// Upper limit of chords per curve: reached only by approach curves metres long, where the
/// chord error then exceeds [`CHORD_TOLERANCE`] rather than the block growing without bound.
const MAX_CHORDS: usize = 4000;

/// A quintic polynomial curve in the plane in Bézier form (control points).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct Quintic {
    b: [P2; 6],
}

impl Quintic {
    /// The quintic with position, first and second derivative given at u = 0 and u = 1.
    pub(in crate::interp) fn hermite(p0: P2, d0: P2, dd0: P2, p1: P2, d1: P2, dd1: P2) -> Quintic {
        let b1 = (p0.0 + d0.0 / 5.0, p0.1 + d0.1 / 5.0);
        let b2 = (2.0 * b1.0 - p0.0 + dd0.0 / 20.0, 2.0 * b1.1 - p0.1 + dd0.1 / 20.0);
        let b4 = (p1.0 - d1.0 / 5.0, p1.1 - d1.1 / 5.0);
        let b3 = (2.0 * b4.0 - p1.0 + dd1.0 / 20.0, 2.0 * b4.1 - p1.1 + dd1.1 / 20.0);
        Quintic { b: [p0, b1, b2, b3, b4, p1] }
    }

    /// The point at parameter `u`.
    pub(in crate::interp) fn at(&self, u: f64) -> P2 {
        bernstein(&self.b, u)
    }

    /// First derivative dP/du.
    #[cfg(test)]
    fn d1(&self, u: f64) -> P2 {
        let d: [P2; 5] = std::array::from_fn(|i| diff(self.b[i + 1], self.b[i], 5.0));
        bernstein(&d, u)
    }

    /// Second derivative d²P/du².
    #[cfg(test)]
    fn d2(&self, u: f64) -> P2 {
        bernstein(&self.second_differences(), u)
    }

    /// Signed curvature at `u` (positive turning left).
    #[cfg(test)]
    fn curvature(&self, u: f64) -> f64 {
        let (d1, d2) = (self.d1(u), self.d2(u));
        (d1.0 * d2.1 - d1.1 * d2.0) / d1.0.hypot(d1.1).powi(3)
    }

    /// The control points of P″ (a cubic); P″ lies in their convex hull, so the longest of
    /// them bounds |P″| on [0, 1].
    fn second_differences(&self) -> [P2; 4] {
        let b = &self.b;
        std::array::from_fn(|i| {
            let x = b[i + 2].0 - 2.0 * b[i + 1].0 + b[i].0;
            let y = b[i + 2].1 - 2.0 * b[i + 1].1 + b[i].1;
            (20.0 * x, 20.0 * y)
        })
    }

    fn d2_bound(&self) -> f64 {
        self.second_differences().iter().map(|p| p.0.hypot(p.1)).fold(0.0, f64::max)
    }
}

#[cfg(test)]
fn diff(a: P2, b: P2, k: f64) -> P2 {
    (k * (a.0 - b.0), k * (a.1 - b.1))
}

/// De Casteljau evaluation of a Bézier curve with up to six control points.
fn bernstein<const N: usize>(b: &[P2; N], u: f64) -> P2 {
    let mut p = *b;
    for level in (1..N).rev() {
        for i in 0..level {
            p[i] = (p[i].0 + u * (p[i + 1].0 - p[i].0), p[i].1 + u * (p[i + 1].1 - p[i].1));
        }
    }
    p[0]
}

/// Signed curvature (positive turning left) of the equidistant at offset `d` where it starts.
pub(in crate::interp) fn start_curvature(first: &Elem, d: f64) -> f64 {
    match *first {
        Elem::Line { .. } => 0.0,
        Elem::Arc { r, sweep, .. } => {
            let turn = sweep.signum();
            turn / (r - d * turn)
        }
    }
}

/// The approach polynomial from `from` onto the equidistant (offset `d`) of `first`; `None`
/// when `from` lies on the tangent ahead of the equidistant's start (no KONTT arc either).
pub(in crate::interp) fn curve(from: P2, first: &Elem, d: f64) -> Option<Quintic> {
    let q = offset_start(first, d);
    let t = tangent(first, false);
    let w = (q.0 - from.0, q.1 - from.1);
    let chord = w.0.hypot(w.1);
    if chord < 1e-9 {
        return None;
    }
    let wh = (w.0 / chord, w.1 / chord);
    // KONTT's arc turns from the chord by the angle θ from the chord to T: it leaves the start
    // point at −θ to the chord and is chord·θ/sin θ long.
    let cos = wh.0 * t.0 + wh.1 * t.1;
    let theta = (wh.0 * t.1 - wh.1 * t.0).atan2(cos);
    if std::f64::consts::PI - theta.abs() < 1e-6 {
        return None;
    }
    let length = if theta.abs() < 1e-12 { chord } else { chord * theta / theta.sin() };
    let dir = (2.0 * cos * wh.0 - t.0, 2.0 * cos * wh.1 - t.1);
    let kappa = start_curvature(first, d);
    let n = left(t);
    let ll = length * length * kappa;
    Some(Quintic::hermite(
        from,
        (length * dir.0, length * dir.1),
        (0.0, 0.0),
        q,
        (length * t.0, length * t.1),
        (ll * n.0, ll * n.1),
    ))
}

/// Share of the travel outside the plane done at parameter `u` (0 at the start point, 1 at the
/// contour, where it stops with zero velocity and acceleration).
pub(in crate::interp) fn infeed_share(u: f64) -> f64 {
    if u >= 1.0 { 1.0 } else { 1.0 - (1.0 - u).powi(3) }
}

/// The chords that stand for `curve` from u = 0 to 1, with the share of the travel `lift`
/// outside the plane done at each chord's end. Uniform in u: with n chords each stays within
/// max|P″|/(8n²) of the curve (the interpolation error of a straight line between two points
/// of a curve), and the axes outside the plane add at most 6·lift to that second derivative.
pub(in crate::interp) fn chords(curve: &Quintic, lift: f64) -> Vec<Piece> {
    let bound = curve.d2_bound() + 6.0 * lift.abs();
    let n = ((bound / (8.0 * CHORD_TOLERANCE)).sqrt().ceil() as usize).clamp(1, MAX_CHORDS);
    let mut s = curve.at(0.0);
    (1..=n)
        .map(|i| {
            let u = i as f64 / n as f64;
            let e = if i == n { curve.b[5] } else { curve.at(u) };
            let piece = (Elem::Line { s, e }, infeed_share(u));
            s = e;
            piece
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: P2, b: P2, tol: f64) -> bool {
        (a.0 - b.0).hypot(a.1 - b.1) < tol
    }

    /// Line contour (0,0) → (50,0) with G41, radius 5: Q = (0, 5), T = +X, curvature 0. From
    /// (−20, −20) KONTT's arc leaves heading (−4.5, 20)/20.5 (perpendicular to the radius to
    /// its centre (0, −15.5), see the KONTT test in tests/compensation.rs).
    #[test]
    fn the_line_approach_meets_position_tangent_and_curvature() {
        let first = Elem::Line { s: (0.0, 0.0), e: (50.0, 0.0) };
        let c = curve((-20.0, -20.0), &first, 5.0).unwrap();
        assert!(close(c.at(0.0), (-20.0, -20.0), 1e-12) && close(c.at(1.0), (0.0, 5.0), 1e-12));
        let d0 = c.d1(0.0);
        let l0 = d0.0.hypot(d0.1);
        assert!(close((d0.0 / l0, d0.1 / l0), (-4.5 / 20.5, 20.0 / 20.5), 1e-12));
        let d1 = c.d1(1.0);
        assert!(d1.1.abs() < 1e-12 && d1.0 > 0.0);
        assert!(c.curvature(1.0).abs() < 1e-12 && c.curvature(0.0).abs() < 1e-12);
    }

    /// Circular pocket of radius 20 about the origin, G3 from (20, 0), G41 radius 5: the
    /// equidistant has radius 15, curvature +1/15, and starts at (15, 0) heading +Y.
    #[test]
    fn the_arc_approach_meets_the_curvature_of_the_equidistant() {
        let first = Elem::Arc { c: (0.0, 0.0), r: 20.0, a0: 0.0, sweep: std::f64::consts::TAU };
        assert!((start_curvature(&first, 5.0) - 1.0 / 15.0).abs() < 1e-15);
        // G42 on the same contour: outside, radius 25, still turning left.
        assert!((start_curvature(&first, -5.0) - 1.0 / 25.0).abs() < 1e-15);
        let c = curve((0.0, 0.0), &first, 5.0).unwrap();
        assert!(close(c.at(1.0), (15.0, 0.0), 1e-12));
        let d1 = c.d1(1.0);
        assert!(d1.0.abs() < 1e-12 && d1.1 > 0.0);
        assert!((c.curvature(1.0) - 1.0 / 15.0).abs() < 1e-12);
        // It stays inside the pocket's equidistant (no cut into the wall).
        for i in 0..1000 {
            let p = c.at(f64::from(i) / 1000.0);
            assert!(p.0.hypot(p.1) <= 15.0 + 1e-9, "{p:?}");
        }
    }

    #[test]
    fn on_the_tangent_ahead_there_is_no_curve() {
        let first = Elem::Line { s: (0.0, 0.0), e: (50.0, 0.0) };
        assert!(curve((30.0, 5.0), &first, 5.0).is_none());
        assert!(curve((0.0, 5.0), &first, 5.0).is_none());
        assert!(curve((-30.0, 5.0), &first, 5.0).is_some());
    }

    /// Every chord stays within the tolerance of the curve: checked by dense sampling against
    /// the distance of curve points from their chord.
    #[test]
    fn chords_stay_within_the_tolerance() {
        let first = Elem::Arc { c: (0.0, 0.0), r: 20.0, a0: 0.0, sweep: std::f64::consts::TAU };
        let c = curve((0.0, 0.0), &first, 5.0).unwrap();
        let pieces = chords(&c, 0.0);
        let n = pieces.len();
        assert!(n > 10);
        for (i, (e, share)) in pieces.iter().enumerate() {
            let Elem::Line { s, e } = *e else { panic!() };
            assert!(*share > 0.0 && *share <= 1.0);
            let (dx, dy) = (e.0 - s.0, e.1 - s.1);
            for k in 0..=20 {
                let u = (i as f64 + f64::from(k) / 20.0) / n as f64;
                let p = c.at(u);
                let t = (((p.0 - s.0) * dx + (p.1 - s.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
                let off = (p.0 - s.0 - t * dx).hypot(p.1 - s.1 - t * dy);
                assert!(off <= CHORD_TOLERANCE, "chord {i}: {off}");
            }
        }
        assert_eq!(pieces.last().map(|p| p.1), Some(1.0));
    }
}
