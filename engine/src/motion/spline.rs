//! Spline and polynomial geometry (Programming Manual Job planning "Spline interpolation"
//! and "Polynomial interpolation"): the A spline (Akima), the C spline (cubic, C2) and the B
//! spline (NURBS of degree 2 or 3 with point weights) through or near a sequence of points in
//! axis space, cut into pieces that the path's free-form element ([`Curve`], a quintic) runs.
//!
//! Every piece is given by Hermite data at its ends (point, first and second derivative with
//! respect to the piece's own parameter 0..1): for the cubic A/C spline pieces and for
//! polynomial B spline spans the quintic through that data is the piece itself; a rational
//! span (point weights other than 1) is approximated by such quintics, halved until each stays
//! within [`RATIONAL_TOLERANCE`] of the exact curve (checked at nine inner points).
//!
//! Parameters: a piece of the A and C spline runs over its block's parameter interval
//! (`PL`), else the chord length between its points; B spline knots are spaced by `PL` of the
//! block that closes a span, else uniformly by the mean chord of the control polygon.

use super::curve::Curve;
use super::path::AxisVec;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Largest distance of a quintic piece from the rational B spline span it stands for (mm).
pub const RATIONAL_TOLERANCE: f64 = 1e-4;

/// Hermite data of one piece: `(point, first, second derivative)` at both ends.
pub type Piece = [(AxisVec, AxisVec, AxisVec); 2];

/// The transition at the start or end of an A or C spline (G groups 19 and 20).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndCondition {
    /// BAUTO/EAUTO: from the first (last) points alone (C spline: the curvature of the
    /// neighbouring piece continues, parabolic run-out; A spline: Akima's extrapolated slopes).
    Auto,
    /// BNAT/ENAT: zero curvature.
    Natural,
    /// BTAN/ETAN: this direction (unit vector in axis space).
    Tangent(AxisVec),
}

fn zero() -> AxisVec {
    [0.0; MAX_CHANNEL_AXES]
}

fn lin(a: f64, x: &AxisVec, b: f64, y: &AxisVec) -> AxisVec {
    std::array::from_fn(|k| a * x[k] + b * y[k])
}

fn norm(v: &AxisVec) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The cubic Hermite piece with ends `p0`, `p1` and parameter-1 tangents `v0`, `v1`.
fn cubic_piece(p0: &AxisVec, p1: &AxisVec, v0: AxisVec, v1: AxisVec) -> Piece {
    let a0 = std::array::from_fn(|k| 6.0 * (p1[k] - p0[k]) - 4.0 * v0[k] - 2.0 * v1[k]);
    let a1 = std::array::from_fn(|k| -6.0 * (p1[k] - p0[k]) + 2.0 * v0[k] + 4.0 * v1[k]);
    [(*p0, v0, a0), (*p1, v1, a1)]
}

/// The C spline through `points` (at least two) with parameter intervals `h` (one per piece,
/// positive): C2 at every inner point, the given conditions at both ends.
pub fn cubic(points: &[AxisVec], h: &[f64], begin: EndCondition, end: EndCondition) -> Vec<Piece> {
    let n = points.len() - 1;
    let slope = |i: usize| lin(1.0 / h[i], &points[i + 1], -1.0 / h[i], &points[i]);
    // Second derivatives M_0..M_n: a tridiagonal system (sub, diag, sup, rhs) per row.
    let (begin, end) = match (begin, end) {
        // One piece with two free ends has no curvature to carry on: a straight piece.
        (EndCondition::Auto, EndCondition::Auto) if n == 1 => (EndCondition::Natural, EndCondition::Natural),
        c => c,
    };
    let mut rows: Vec<(f64, f64, f64, AxisVec)> = Vec::with_capacity(n + 1);
    rows.push(match begin {
        EndCondition::Natural => (0.0, 1.0, 0.0, zero()),
        EndCondition::Auto => (0.0, 1.0, -1.0, zero()),
        EndCondition::Tangent(d) => (0.0, 2.0 * h[0], h[0], lin(6.0, &slope(0), -6.0, &d)),
    });
    for i in 1..n {
        let rhs = lin(6.0, &slope(i), -6.0, &slope(i - 1));
        rows.push((h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i], rhs));
    }
    rows.push(match end {
        EndCondition::Natural => (0.0, 1.0, 0.0, zero()),
        EndCondition::Auto => (-1.0, 1.0, 0.0, zero()),
        EndCondition::Tangent(d) => (h[n - 1], 2.0 * h[n - 1], 0.0, lin(6.0, &d, -6.0, &slope(n - 1))),
    });
    let m = solve_tridiagonal(rows);
    (0..n)
        .map(|i| {
            let hi = h[i];
            let s = slope(i);
            let d0 = lin(1.0, &s, -hi / 6.0, &lin(2.0, &m[i], 1.0, &m[i + 1]));
            let d1 = lin(1.0, &s, hi / 6.0, &lin(1.0, &m[i], 2.0, &m[i + 1]));
            [
                (points[i], d0.map(|x| x * hi), m[i].map(|x| x * hi * hi)),
                (points[i + 1], d1.map(|x| x * hi), m[i + 1].map(|x| x * hi * hi)),
            ]
        })
        .collect()
}

/// Thomas' algorithm with vector right-hand sides.
fn solve_tridiagonal(mut rows: Vec<(f64, f64, f64, AxisVec)>) -> Vec<AxisVec> {
    let n = rows.len();
    for i in 1..n {
        let w = rows[i].0 / rows[i - 1].1;
        let (sup, rhs) = (rows[i - 1].2, rows[i - 1].3);
        rows[i].1 -= w * sup;
        rows[i].3 = lin(1.0, &rows[i].3, -w, &rhs);
    }
    let mut x = vec![zero(); n];
    x[n - 1] = rows[n - 1].3.map(|v| v / rows[n - 1].1);
    for i in (0..n - 1).rev() {
        let next = x[i + 1];
        x[i] = std::array::from_fn(|k| (rows[i].3[k] - rows[i].2 * next[k]) / rows[i].1);
    }
    x
}

/// The A spline (Akima) through `points` with parameter intervals `h`: tangent-continuous,
/// each tangent from the slopes of the two pieces on either side (weighted by how much the
/// slopes change), so a point moves only the curve near it.
pub fn akima(points: &[AxisVec], h: &[f64], begin: EndCondition, end: EndCondition) -> Vec<Piece> {
    let n = points.len() - 1;
    let m: Vec<AxisVec> = (0..n).map(|i| lin(1.0 / h[i], &points[i + 1], -1.0 / h[i], &points[i])).collect();
    // Slopes m[-2..n+1], extrapolated at both ends as Akima does.
    let slope = |i: isize| -> AxisVec {
        let last = n as isize - 1;
        if (0..=last).contains(&i) {
            return m[i as usize];
        }
        let (a, b) = if i < 0 {
            (m[0], m.get(1).copied().unwrap_or(m[0]))
        } else {
            (m[n - 1], if n >= 2 { m[n - 2] } else { m[n - 1] })
        };
        let e1 = lin(2.0, &a, -1.0, &b);
        if i == -1 || i == last + 1 { e1 } else { lin(2.0, &e1, -1.0, &a) }
    };
    let mut d: Vec<AxisVec> = (0..=n as isize)
        .map(|i| {
            let (mm2, mm1, m0, m1) = (slope(i - 2), slope(i - 1), slope(i), slope(i + 1));
            let w1 = norm(&lin(1.0, &m1, -1.0, &m0));
            let w2 = norm(&lin(1.0, &mm1, -1.0, &mm2));
            if w1 + w2 < 1e-12 { lin(0.5, &mm1, 0.5, &m0) } else { lin(w1 / (w1 + w2), &mm1, w2 / (w1 + w2), &m0) }
        })
        .collect();
    match begin {
        EndCondition::Natural if n >= 1 => d[0] = lin(1.5, &m[0], -0.5, &d[1]),
        EndCondition::Tangent(t) => d[0] = t.map(|x| x * norm(&m[0])),
        _ => {}
    }
    match end {
        EndCondition::Natural if n >= 1 => d[n] = lin(1.5, &m[n - 1], -0.5, &d[n - 1]),
        EndCondition::Tangent(t) => d[n] = t.map(|x| x * norm(&m[n - 1])),
        _ => {}
    }
    (0..n)
        .map(|i| cubic_piece(&points[i], &points[i + 1], d[i].map(|x| x * h[i]), d[i + 1].map(|x| x * h[i])))
        .collect()
}

/// A clamped B spline: control points, their weights, the degree (already at most the
/// number of control points less one) and the knot span lengths (count − degree of them).
pub struct BSpline<'a> {
    pub control: &'a [AxisVec],
    pub weights: &'a [f64],
    pub degree: usize,
    pub spans: &'a [f64],
}

impl BSpline<'_> {
    fn knots(&self) -> Vec<f64> {
        let p = self.degree;
        let mut k = vec![0.0; p + 1];
        let mut t = 0.0;
        for s in self.spans {
            t += s;
            k.push(t);
        }
        // The last span's end is the clamped end: repeat it p more times.
        k.extend(std::iter::repeat_n(t, p));
        k
    }

    /// The homogeneous point (w·P, w) at `t` in span `j` (de Boor).
    fn homogeneous(&self, knots: &[f64], j: usize, t: f64) -> (AxisVec, f64) {
        let p = self.degree;
        let mut d: Vec<(AxisVec, f64)> = (0..=p)
            .map(|i| {
                let (c, w) = (self.control[j + i], self.weights[j + i]);
                (c.map(|x| x * w), w)
            })
            .collect();
        for r in 1..=p {
            for i in (r..=p).rev() {
                let (lo, hi) = (knots[j + i], knots[j + i + p + 1 - r]);
                let a = if hi > lo { (t - lo) / (hi - lo) } else { 0.0 };
                d[i] = (lin(1.0 - a, &d[i - 1].0, a, &d[i].0), (1.0 - a) * d[i - 1].1 + a * d[i].1);
            }
        }
        d[p]
    }

    /// The pieces of the whole curve, one list per knot span.
    pub fn pieces(&self) -> Vec<Vec<Piece>> {
        let knots = self.knots();
        let p = self.degree;
        (0..self.spans.len())
            .map(|s| {
                let (t0, t1) = (knots[s + p], knots[s + p + 1]);
                // The span's homogeneous polynomial, from p+1 samples (Newton's forward
                // differences), as value, first and second derivative in u = 0..1.
                let poly = SpanPolynomial::new(
                    (0..=p).map(|i| self.homogeneous(&knots, s, t0 + (t1 - t0) * i as f64 / p as f64)).collect(),
                );
                let rational = (s..=s + p).any(|i| (self.weights[i] - self.weights[s]).abs() > 1e-12);
                let mut out = Vec::new();
                split_rational(&poly, 0.0, 1.0, rational, 0, &mut out);
                out
            })
            .collect()
    }
}

/// A span's homogeneous polynomial in power form: `coef[j]` of `u^j` (point part, weight).
struct SpanPolynomial {
    coef: Vec<(AxisVec, f64)>,
}

impl SpanPolynomial {
    /// From values at u = i/p, i = 0..=p.
    fn new(samples: Vec<(AxisVec, f64)>) -> SpanPolynomial {
        let p = samples.len() - 1;
        // Newton form on the nodes i/p, then expanded to powers of u.
        let mut diffs = samples.clone();
        let mut newton = vec![diffs[0]];
        for level in 1..=p {
            for i in 0..=p - level {
                let h = level as f64 / p as f64;
                diffs[i] = (lin(1.0 / h, &diffs[i + 1].0, -1.0 / h, &diffs[i].0), (diffs[i + 1].1 - diffs[i].1) / h);
            }
            newton.push(diffs[0]);
        }
        let mut coef: Vec<(AxisVec, f64)> = vec![(zero(), 0.0); p + 1];
        // Horner on the Newton basis (u − x_0)(u − x_1)..., nodes x_i = i/p.
        for level in (0..=p).rev() {
            // coef = coef·(u − x_level) + newton[level]
            let x = level as f64 / p.max(1) as f64;
            let mut next: Vec<(AxisVec, f64)> = vec![(zero(), 0.0); p + 1];
            for j in 0..=p {
                if j < p {
                    next[j + 1].0 = lin(1.0, &next[j + 1].0, 1.0, &coef[j].0);
                    next[j + 1].1 += coef[j].1;
                }
                next[j].0 = lin(1.0, &next[j].0, -x, &coef[j].0);
                next[j].1 -= x * coef[j].1;
            }
            next[0].0 = lin(1.0, &next[0].0, 1.0, &newton[level].0);
            next[0].1 += newton[level].1;
            coef = next;
        }
        SpanPolynomial { coef }
    }

    /// Homogeneous value and its first two derivatives at `u`.
    fn eval(&self, u: f64) -> [(AxisVec, f64); 3] {
        let mut out = [(zero(), 0.0); 3];
        for (j, (c, w)) in self.coef.iter().enumerate() {
            let j = j as i32;
            let (f0, f1, f2) =
                (u.powi(j), f64::from(j) * u.powi((j - 1).max(0)), f64::from(j * (j - 1)) * u.powi((j - 2).max(0)));
            for (o, f) in out.iter_mut().zip([f0, f1, f2]) {
                o.0 = lin(1.0, &o.0, f, c);
                o.1 += f * w;
            }
        }
        out
    }

    /// The curve's point and its first two derivatives at `u` (quotient rule).
    fn point(&self, u: f64) -> (AxisVec, AxisVec, AxisVec) {
        let [(a, w), (a1, w1), (a2, w2)] = self.eval(u);
        let c = a.map(|x| x / w);
        let c1: AxisVec = std::array::from_fn(|k| (a1[k] - w1 * c[k]) / w);
        let c2: AxisVec = std::array::from_fn(|k| (a2[k] - 2.0 * w1 * c1[k] - w2 * c[k]) / w);
        (c, c1, c2)
    }
}

/// Quintic pieces for `u0..u1` of a span: one when the span is polynomial (exact), halves
/// until within [`RATIONAL_TOLERANCE`] when it is rational.
fn split_rational(poly: &SpanPolynomial, u0: f64, u1: f64, rational: bool, depth: u32, out: &mut Vec<Piece>) {
    let l = u1 - u0;
    let end = |u: f64| {
        let (c, c1, c2) = poly.point(u);
        (c, c1.map(|x| x * l), c2.map(|x| x * l * l))
    };
    let piece = [end(u0), end(u1)];
    if rational && depth < 8 {
        let metric = [1.0; MAX_CHANNEL_AXES];
        let q = Curve::hermite_untabled(piece, metric);
        let mut p = zero();
        let off = (1..10).any(|i| {
            let s = f64::from(i) / 10.0;
            q.eval(s, &mut p);
            norm(&lin(1.0, &p, -1.0, &poly.point(u0 + s * l).0)) > RATIONAL_TOLERANCE
        });
        if off {
            let m = 0.5 * (u0 + u1);
            split_rational(poly, u0, m, rational, depth + 1, out);
            split_rational(poly, m, u1, rational, depth + 1, out);
            return;
        }
    }
    out.push(piece);
}

/// The POLY block's polynomial per axis: `start + Σ c_j u^j`, u = 0..1, with `coef[j]` the
/// axis-space coefficient of `u^j` (j = 1..=5); returns its Hermite data (exact for degree 5).
pub fn polynomial(start: &AxisVec, coef: &[AxisVec; 5]) -> Piece {
    let at = |u: f64| {
        let mut p = *start;
        let mut d1 = zero();
        let mut d2 = zero();
        for (j, c) in coef.iter().enumerate() {
            let j = j as i32 + 1;
            for k in 0..MAX_CHANNEL_AXES {
                p[k] += c[k] * u.powi(j);
                d1[k] += f64::from(j) * c[k] * u.powi(j - 1);
                if j >= 2 {
                    d2[k] += f64::from(j * (j - 1)) * c[k] * u.powi(j - 2);
                }
            }
        }
        (p, d1, d2)
    };
    [at(0.0), at(1.0)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: f64, y: f64) -> AxisVec {
        let mut p = zero();
        p[0] = x;
        p[1] = y;
        p
    }

    /// A natural cubic spline through points of a straight line is that line.
    #[test]
    fn collinear_points_give_straight_pieces() {
        let pts = [pt(0.0, 0.0), pt(1.0, 1.0), pt(3.0, 3.0)];
        let h = [2f64.sqrt(), 8f64.sqrt()];
        for piece in cubic(&pts, &h, EndCondition::Natural, EndCondition::Natural) {
            assert!(piece[0].2.iter().chain(piece[1].2.iter()).all(|x| x.abs() < 1e-12));
        }
    }

    /// Degree 2 with control points (0,0), (1,2), (2,0) and one span: the Bézier parabola,
    /// whose middle point is (1, 1).
    #[test]
    fn one_span_of_degree_two_is_the_bezier_parabola() {
        let control = [pt(0.0, 0.0), pt(1.0, 2.0), pt(2.0, 0.0)];
        let b = BSpline { control: &control, weights: &[1.0; 3], degree: 2, spans: &[1.0] };
        let pieces = b.pieces();
        let q = Curve::hermite_untabled(pieces[0][0], [1.0; MAX_CHANNEL_AXES]);
        let mut p = zero();
        q.eval(0.5, &mut p);
        assert!((p[0] - 1.0).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12, "{p:?}");
    }

    /// Weight 3 on the middle control point of the quadratic: C(½) = (w·P1 + P0/4·4...) — the
    /// rational Bézier value (¼P0 + ½·3·P1 + ¼P2)/(¼ + ½·3 + ¼) = (1, 3/2).
    #[test]
    fn a_weight_pulls_the_curve_towards_its_point() {
        let control = [pt(0.0, 0.0), pt(1.0, 2.0), pt(2.0, 0.0)];
        let b = BSpline { control: &control, weights: &[1.0, 3.0, 1.0], degree: 2, spans: &[1.0] };
        let pieces = b.pieces();
        let mut best = f64::INFINITY;
        for piece in &pieces[0] {
            let q = Curve::hermite_untabled(*piece, [1.0; MAX_CHANNEL_AXES]);
            let mut p = zero();
            for i in 0..=100 {
                q.eval(f64::from(i) / 100.0, &mut p);
                best = best.min((p[0] - 1.0).hypot(p[1] - 1.5));
            }
        }
        assert!(best < 2e-4, "{best}");
    }
}
