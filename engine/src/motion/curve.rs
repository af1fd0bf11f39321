//! A free-form path element: a quintic polynomial in axis space, run at uniform path speed.
//!
//! Corner rounding (G641..G645, [`super::blend`]) inserts such an element between two blocks.
//! It is built from Hermite data at both ends (point, first and second derivative), so it meets
//! the neighbouring blocks with the same tangent and curvature. The planner steps a path by
//! its length, so the curve carries a table from path length to its own parameter.

use super::path::AxisVec;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// Intervals of the length table; the speed along a rounding quintic varies smoothly, so 16
/// intervals with Simpson's rule and cubic Hermite inversion keep the length error far below
/// a micrometre for elements of a few millimetres.
const TABLE: usize = 16;

/// A quintic `p(t) = Σ c_j t^j`, `t` in 0..=1, with its length table; `range` is the part of
/// it a path runs (a slice of the element after an interruption).
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    coef: [AxisVec; 6],
    /// 1.0 for the axes whose distance is the path length (the feed's axes), else 0.0.
    metric: AxisVec,
    /// The axes that move along the element (the others keep `coef[0]`): every loop runs
    /// over these only.
    axes: [usize; MAX_CHANNEL_AXES],
    n_axes: usize,
    /// `(s, t, dt/ds)` at the table's knots, `s` from 0 to the whole length.
    table: Vec<(f64, f64, f64)>,
    /// The part of the whole length this path runs, as fractions (0..=1).
    range: (f64, f64),
    /// [`Curve::rates`] of the run, worked out once (the planner asks for them per move);
    /// `None` (zero rates) until [`Curve::finish`]: the search for an element's size makes
    /// many elements, and none of them needs the allocation.
    rates: Option<Box<(AxisVec, AxisVec)>>,
}

impl Curve {
    /// The quintic with `p(0) = p0`, `p'(0) = v0`, `p''(0) = a0` and likewise at `t = 1`.
    pub fn hermite(ends: [(AxisVec, AxisVec, AxisVec); 2], metric: AxisVec) -> Curve {
        let mut c = Curve::hermite_untabled(ends, metric);
        c.finish();
        c
    }

    /// [`Curve::hermite`] without the length table: enough for [`Curve::eval`] and
    /// [`Curve::distance_to`], which a search for the right size of element calls many times.
    pub fn hermite_untabled(ends: [(AxisVec, AxisVec, AxisVec); 2], metric: AxisVec) -> Curve {
        let [(p0, v0, a0), (p1, v1, a1)] = &ends;
        // Filled in the place it is returned from (no copy of the coefficients).
        let mut c = Curve {
            coef: [[0.0; MAX_CHANNEL_AXES]; 6],
            metric,
            axes: [0; MAX_CHANNEL_AXES],
            n_axes: 0,
            table: Vec::new(),
            range: (0.0, 1.0),
            rates: None,
        };
        for k in 0..MAX_CHANNEL_AXES {
            if p0[k] != p1[k] || v0[k] != 0.0 || v1[k] != 0.0 || a0[k] != 0.0 || a1[k] != 0.0 {
                c.axes[c.n_axes] = k;
                c.n_axes += 1;
            }
        }
        // An axis that does not move keeps `coef[0]`: its other coefficients are never read.
        let coef = &mut c.coef;
        coef[0] = *p0;
        for &k in &c.axes[..c.n_axes] {
            // The quintic Hermite basis in power form.
            coef[1][k] = v0[k];
            coef[2][k] = 0.5 * a0[k];
            coef[3][k] = -10.0 * p0[k] - 6.0 * v0[k] - 1.5 * a0[k] + 0.5 * a1[k] - 4.0 * v1[k] + 10.0 * p1[k];
            coef[4][k] = 15.0 * p0[k] + 8.0 * v0[k] + 1.5 * a0[k] - a1[k] + 7.0 * v1[k] - 15.0 * p1[k];
            coef[5][k] = -6.0 * p0[k] - 3.0 * v0[k] - 0.5 * a0[k] + 0.5 * a1[k] - 3.0 * v1[k] + 6.0 * p1[k];
        }
        c
    }

    /// The smallest distance (in the feed's axes) of the element from `point`: 17 samples,
    /// then a golden-section search around the nearest.
    pub fn distance_to(&self, point: &AxisVec) -> f64 {
        let mut p = *point;
        let dist = |t: f64| {
            self.eval(t, &mut p);
            self.axes().iter().map(|&k| (p[k] - point[k]).powi(2) * self.metric[k]).sum::<f64>()
        };
        // 16 steps shrink the bracket of 1/8 to 3e-5 of the element: far below a micrometre.
        super::nearest::least_distance(dist, (0.0, 1.0), 16, 16)
    }

    /// Builds the length table of an element made with [`Curve::hermite_untabled`].
    pub fn finish(&mut self) {
        self.build_table();
        self.rates = Some(Box::new(self.sample_rates()));
    }

    /// Simpson's rule on each interval, `dt/ds` at every knot for the inversion.
    fn build_table(&mut self) {
        // The speed at the knots and the intervals' midpoints, t = j/32 (exact in binary), each
        // once: a knot ends one interval and starts the next.
        let ts: [f64; 2 * TABLE + 1] = std::array::from_fn(|j| j as f64 / (2 * TABLE) as f64);
        let speed = self.speeds(&ts);
        let h = 1.0 / TABLE as f64;
        let mut s = 0.0;
        let mut table = Vec::with_capacity(TABLE + 1);
        for i in 0..=TABLE {
            let v = speed[2 * i];
            table.push((s, ts[2 * i], if v > 0.0 { 1.0 / v } else { 0.0 }));
            if i < TABLE {
                s += h / 6.0 * (v + 4.0 * speed[2 * i + 1] + speed[2 * i + 2]);
            }
        }
        self.table = table;
    }

    /// `|p'(t)|` in the feed's metric at each of `ts`: one axis at a time over all the
    /// points (a loop the compiler runs on vector registers), the same sums as [`Curve::norm`].
    fn speeds<const N: usize>(&self, ts: &[f64; N]) -> [f64; N] {
        let mut sum = [-0.0; N];
        for &k in self.axes() {
            let d = self.d1_row(k, ts);
            let m = self.metric[k];
            for (s, d) in sum.iter_mut().zip(d) {
                *s += d * d * m;
            }
        }
        sum.map(f64::sqrt)
    }

    /// `p_k(t)` of axis `k` at each of `ts` (the expression of [`Curve::eval`]).
    pub(super) fn eval_row<const N: usize>(&self, k: usize, ts: &[f64; N]) -> [f64; N] {
        let c: [f64; 6] = std::array::from_fn(|j| self.coef[j][k]);
        let mut out = [0.0; N];
        for (o, &t) in out.iter_mut().zip(ts) {
            *o = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
        }
        out
    }

    /// `p_k'(t)` of axis `k` at each of `ts` (the expression of [`Curve::d1_into`]).
    fn d1_row<const N: usize>(&self, k: usize, ts: &[f64; N]) -> [f64; N] {
        let c = &self.coef;
        let (c1, c2, c3, c4, c5) = (c[1][k], 2.0 * c[2][k], 3.0 * c[3][k], 4.0 * c[4][k], c[5][k]);
        let mut out = [0.0; N];
        for (o, &t) in out.iter_mut().zip(ts) {
            *o = c1 + t * (c2 + t * (c3 + t * (c4 + t * 5.0 * c5)));
        }
        out
    }

    /// `p_k''(t)` of axis `k` at each of `ts` (the expression of [`Curve::d2_into`]).
    fn d2_row<const N: usize>(&self, k: usize, ts: &[f64; N]) -> [f64; N] {
        let c = &self.coef;
        let (c2, c3, c4, c5) = (2.0 * c[2][k], 6.0 * c[3][k], 12.0 * c[4][k], c[5][k]);
        let mut out = [0.0; N];
        for (o, &t) in out.iter_mut().zip(ts) {
            *o = c2 + t * (c3 + t * (c4 + t * 20.0 * c5));
        }
        out
    }

    /// The axes that move along the element.
    pub(super) fn axes(&self) -> &[usize] {
        &self.axes[..self.n_axes]
    }

    /// True if axis `k` moves along the element.
    pub fn moves_axis(&self, k: usize) -> bool {
        self.axes().contains(&k)
    }

    /// Length of the whole element in the feed's axes.
    pub fn total_length(&self) -> f64 {
        self.table.last().map_or(0.0, |k| k.0)
    }

    /// Length of the part this path runs.
    pub fn length(&self) -> f64 {
        self.total_length() * (self.range.1 - self.range.0)
    }

    /// The part between fractions `u0` and `u1` of this path's run.
    pub fn slice(&self, u0: f64, u1: f64) -> Curve {
        let (a, b) = self.range;
        let mut c = Curve { range: (a + (b - a) * u0, a + (b - a) * u1), ..self.clone() };
        c.rates = Some(Box::new(c.sample_rates()));
        c
    }

    /// The element's parameter at fraction `u` (0..=1, by length) of this path's run.
    fn param(&self, u: f64) -> f64 {
        let (a, b) = self.range;
        let s = (a + (b - a) * u.clamp(0.0, 1.0)) * self.total_length();
        let i = self.table.partition_point(|k| k.0 <= s).clamp(1, self.table.len() - 1);
        let ((s0, t0, m0), (s1, t1, m1)) = (self.table[i - 1], self.table[i]);
        let h = s1 - s0;
        if h <= 0.0 {
            return t0;
        }
        let x = (s - s0) / h;
        let (x2, x3) = (x * x, x * x * x);
        (2.0 * x3 - 3.0 * x2 + 1.0) * t0
            + (x3 - 2.0 * x2 + x) * h * m0
            + (-2.0 * x3 + 3.0 * x2) * t1
            + (x3 - x2) * h * m1
    }

    /// Position at fraction `u` of the run (the axes the element does not move are left as
    /// they are in `out`).
    pub fn at(&self, u: f64, out: &mut AxisVec) {
        self.eval(self.param(u), out);
    }

    /// `p(t)` of the moving axes.
    pub fn eval(&self, t: f64, out: &mut AxisVec) {
        let c = &self.coef;
        for &k in self.axes() {
            out[k] = c[0][k] + t * (c[1][k] + t * (c[2][k] + t * (c[3][k] + t * (c[4][k] + t * c[5][k]))));
        }
    }

    /// `p'(t)`.
    pub fn d1(&self, t: f64) -> AxisVec {
        let mut d = [0.0; MAX_CHANNEL_AXES];
        self.d1_into(t, &mut d);
        d
    }

    /// `p'(t)` of the moving axes into `d` (the others are left as they are).
    fn d1_into(&self, t: f64, d: &mut AxisVec) {
        let c = &self.coef;
        for &k in self.axes() {
            d[k] = c[1][k] + t * (2.0 * c[2][k] + t * (3.0 * c[3][k] + t * (4.0 * c[4][k] + t * 5.0 * c[5][k])));
        }
    }

    /// `p''(t)`.
    pub fn d2(&self, t: f64) -> AxisVec {
        let mut d = [0.0; MAX_CHANNEL_AXES];
        self.d2_into(t, &mut d);
        d
    }

    /// `p''(t)` of the moving axes into `d` (the others are left as they are).
    fn d2_into(&self, t: f64, d: &mut AxisVec) {
        let c = &self.coef;
        for &k in self.axes() {
            d[k] = 2.0 * c[2][k] + t * (6.0 * c[3][k] + t * (12.0 * c[4][k] + t * 20.0 * c[5][k]));
        }
    }

    /// Length of `v` in the feed's axes.
    pub fn norm(&self, v: &AxisVec) -> f64 {
        self.axes().iter().map(|&k| v[k] * v[k] * self.metric[k]).sum::<f64>().sqrt()
    }

    /// Tangent `dp/du` at fraction `u` of the run (length of the run times the unit tangent).
    pub fn tangent(&self, u: f64) -> AxisVec {
        let d = self.d1(self.param(u));
        let scale = self.length() / self.norm(&d).max(1e-300);
        d.map(|x| x * scale)
    }

    /// `d²p/du²` at fraction `u` of the run: the length of the run squared times `d²p/ds²`
    /// (the curvature vector, the path speed being uniform in `u`).
    pub fn second(&self, u: f64) -> AxisVec {
        let t = self.param(u);
        let (d1, d2) = (self.d1(t), self.d2(t));
        let v2 = self.norm(&d1).powi(2).max(1e-300);
        let along = self.axes().iter().map(|&k| d1[k] * d2[k] * self.metric[k]).sum::<f64>() / v2;
        let l2 = self.length() * self.length();
        let mut out = [0.0; MAX_CHANNEL_AXES];
        for &k in self.axes() {
            out[k] = (d2[k] - along * d1[k]) / v2 * l2;
        }
        out
    }

    /// Per axis: the largest `|dp_k/ds|` and `|d²p_k/ds²|` over the run (sampled at 25
    /// points with 3 % margin, the element being smooth and short).
    pub fn rates(&self) -> (AxisVec, AxisVec) {
        self.rates.as_deref().copied().unwrap_or(([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]))
    }

    fn sample_rates(&self) -> (AxisVec, AxisVec) {
        let mut first = [0.0; MAX_CHANNEL_AXES];
        let mut second = [0.0; MAX_CHANNEL_AXES];
        // Evenly in the element's parameter over the run (no length-table lookups).
        const N: usize = 24;
        let (t0, t1) = (self.param(0.0), self.param(1.0));
        let ts: [f64; N + 1] = std::array::from_fn(|i| t0 + (t1 - t0) * (i as f64 / N as f64));
        // Per sample: |p'|² and p'·p'' in the feed's metric, one axis at a time over all the
        // samples. The derivatives of the first three axes are kept for their rates below
        // (no buffer to clear), those of any further axis worked out again.
        const KEPT: usize = 3;
        let axes = self.axes();
        let rows = |k: usize| [self.d1_row(k, &ts), self.d2_row(k, &ts)];
        let kept: [[[f64; N + 1]; 2]; KEPT] =
            std::array::from_fn(|j| axes.get(j).map_or([[0.0; N + 1]; 2], |&k| rows(k)));
        let (mut v2, mut along) = ([-0.0; N + 1], [-0.0; N + 1]);
        for (j, &k) in axes.iter().enumerate() {
            let other;
            let [d1, d2] = match kept.get(j) {
                Some(row) => row,
                None => {
                    other = rows(k);
                    &other
                }
            };
            let m = self.metric[k];
            for i in 0..=N {
                v2[i] += d1[i] * d1[i] * m;
                along[i] += d1[i] * d2[i] * m;
            }
        }
        // d²p/ds² = (p'' − (p'·p''/|p'|²) p') / |p'|² in the feed's metric.
        let v2 = v2.map(|x| x.sqrt().powi(2).max(1e-300));
        let speed = v2.map(f64::sqrt);
        let along: [f64; N + 1] = std::array::from_fn(|i| along[i] / v2[i]);
        for (j, &k) in axes.iter().enumerate() {
            let other;
            let [d1, d2] = match kept.get(j) {
                Some(row) => row,
                None => {
                    other = rows(k);
                    &other
                }
            };
            let (mut f, mut s) = (first[k], second[k]);
            for i in 0..=N {
                f = f64::max(f, d1[i].abs() / speed[i]);
                s = f64::max(s, (d2[i] - along[i] * d1[i]).abs() / v2[i]);
            }
            (first[k], second[k]) = (f, s);
        }
        // A margin for the peaks between the samples of a smooth short element.
        (first.map(|x| x * 1.03), second.map(|x| x * 1.03))
    }

    /// The rates as the scalar code before [`Curve::sample_rates`] worked them out: one
    /// sample at a time (a test compares the two bit for bit).
    #[cfg(test)]
    fn sample_rates_one_by_one(&self) -> (AxisVec, AxisVec) {
        let mut first = [0.0; MAX_CHANNEL_AXES];
        let mut second = [0.0; MAX_CHANNEL_AXES];
        const N: usize = 24;
        let (t0, t1) = (self.param(0.0), self.param(1.0));
        let (mut d1, mut d2) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        for i in 0..=N {
            let t = t0 + (t1 - t0) * (i as f64 / N as f64);
            self.d1_into(t, &mut d1);
            self.d2_into(t, &mut d2);
            let v2 = self.norm(&d1).powi(2).max(1e-300);
            let along = self.axes().iter().map(|&k| d1[k] * d2[k] * self.metric[k]).sum::<f64>() / v2;
            let speed = v2.sqrt();
            for &k in self.axes() {
                first[k] = f64::max(first[k], d1[k].abs() / speed);
                second[k] = f64::max(second[k], (d2[k] - along * d1[k]).abs() / v2);
            }
        }
        (first.map(|x| x * 1.03), second.map(|x| x * 1.03))
    }

    /// The length table as the scalar code before [`Curve::build_table`] built it: every
    /// interval's three speeds evaluated on their own.
    #[cfg(test)]
    fn table_one_by_one(&self) -> Vec<(f64, f64, f64)> {
        let mut d = [0.0; MAX_CHANNEL_AXES];
        let mut speed = |t: f64| {
            self.d1_into(t, &mut d);
            self.norm(&d)
        };
        let h = 1.0 / TABLE as f64;
        let mut s = 0.0;
        let mut table = Vec::new();
        for i in 0..=TABLE {
            let t = i as f64 * h;
            let v = speed(t);
            table.push((s, t, if v > 0.0 { 1.0 / v } else { 0.0 }));
            if i < TABLE {
                s += h / 6.0 * (v + 4.0 * speed(t + 0.5 * h) + speed(t + h));
            }
        }
        table
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> AxisVec {
        let mut a = [0.0; MAX_CHANNEL_AXES];
        (a[0], a[1]) = (x, y);
        a
    }

    fn metric() -> AxisVec {
        v(1.0, 1.0)
    }

    #[test]
    fn a_straight_hermite_quintic_is_the_line_run_at_uniform_speed() {
        // p0 = 0, p1 = (3, 4), tangents (3, 4) at both ends, no second derivative: the line
        // p(t) = t·(3, 4), length 5; fraction u lies at 5u along it.
        let c = Curve::hermite(
            [(v(0.0, 0.0), v(3.0, 4.0), v(0.0, 0.0)), (v(3.0, 4.0), v(3.0, 4.0), v(0.0, 0.0))],
            metric(),
        );
        assert!((c.length() - 5.0).abs() < 1e-12);
        let mut p = [0.0; MAX_CHANNEL_AXES];
        c.at(0.3, &mut p);
        assert!((p[0] - 0.9).abs() < 1e-12 && (p[1] - 1.2).abs() < 1e-12, "{:?}", &p[..2]);
    }

    /// Hermite data of a bent element in three or four axes (the fourth outside the feed's metric),
    /// from a small deterministic generator: values of either sign and several magnitudes.
    fn bent(seed: u64) -> Curve {
        let mut x = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        let mut ends = [([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]); 2];
        for (p, v, a) in &mut ends {
            // Odd seeds move a fourth axis (past the three whose derivatives are kept).
            for k in 0..3 + (seed % 2) as usize {
                (p[k], v[k], a[k]) = (next() * 10.0, next(), next() * 0.1);
            }
        }
        let mut metric = [0.0; MAX_CHANNEL_AXES];
        metric[..3].fill(1.0);
        Curve::hermite(ends, metric)
    }

    #[test]
    fn the_batched_table_and_rates_are_the_one_by_one_values_bit_for_bit() {
        // The length table and the rates are worked out over all points at once; each point's
        // arithmetic is that of the scalar code (kept in the tests), in the same order, so the
        // planner sees the same limits and the path the same lengths.
        let bits = |v: &AxisVec| v.map(f64::to_bits);
        for seed in 1..200 {
            let c = bent(seed);
            assert_eq!(c.table, c.table_one_by_one(), "seed {seed}");
            for c in [c.clone(), c.slice(0.13, 0.71)] {
                let ((f, s), (f1, s1)) = (c.rates(), c.sample_rates_one_by_one());
                assert_eq!((bits(&f), bits(&s)), (bits(&f1), bits(&s1)), "seed {seed}");
            }
        }
    }

    #[test]
    fn the_length_table_gives_uniform_speed_on_a_bent_element() {
        // A 90° rounding from direction X to Y: equal steps of u give equal chord lengths
        // within 0.05 % (the path speed the planner sets is kept that closely).
        let c = Curve::hermite(
            [(v(0.0, 0.0), v(1.0, 0.0), v(0.0, 0.0)), (v(1.0, 1.0), v(0.0, 1.0), v(0.0, 0.0))],
            metric(),
        );
        let n = 1000;
        let step = c.length() / n as f64;
        let (mut a, mut b) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
        for i in 0..n {
            c.at(i as f64 / n as f64, &mut a);
            c.at((i + 1) as f64 / n as f64, &mut b);
            let d = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            assert!((d - step).abs() < 5e-4 * step, "step {i}: {d} vs {step}");
        }
        c.at(1.0, &mut a);
        assert!((a[0] - 1.0).abs() < 1e-12 && (a[1] - 1.0).abs() < 1e-12);
    }
}
