//! ORICURVE (F2 §3.11, REFERENCE §6.3.4): the orientation is the direction from the tool tip
//! curve to a second curve through the programmed `XH=`, `YH=`, `ZH=` points, both run through
//! together with the path parameter. Both curves are straight lines within a block (the tool tip
//! of a G1/G0 block; circles are refused by the interpreter), so one sample is two linear
//! interpolations and a normalisation: no allocation, no trigonometry.
//!
//! The compressor's orientation (`compress_ori.rs`) is the same form with the tip at the origin
//! and an upper curve that bends: a quintic through the programmed orientations, whose
//! direction is the orientation ([`TwoCurves::bend`]).

use super::orientation::Vec3;

/// The tool tip line and the upper line of one block, in the BCS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoCurves {
    /// Tool tip at the block start and end.
    pub tip: [Vec3; 2],
    /// Point of the second (upper) curve at the block start and end.
    pub upper: [Vec3; 2],
    /// The upper curve's departure from the line between its ends: coefficient `b[i−2]` of
    /// `uⁱ − u` for `i` = 2..=5 (zero for ORICURVE's lines; a quintic for the compressor).
    pub bend: [Vec3; 4],
}

impl TwoCurves {
    /// ORICURVE's two lines.
    pub fn lines(tip: [Vec3; 2], upper: [Vec3; 2]) -> TwoCurves {
        TwoCurves { tip, upper, bend: [[0.0; 3]; 4] }
    }

    /// The upper curve at `u`.
    fn upper_at(&self, u: f64) -> Vec3 {
        let [h0, h1] = &self.upper;
        let mut p: Vec3 = std::array::from_fn(|i| h0[i] + u * (h1[i] - h0[i]));
        let mut ui = u;
        for b in &self.bend {
            ui *= u;
            for i in 0..3 {
                p[i] += b[i] * (ui - u);
            }
        }
        p
    }

    /// The difference upper − tip at parameter `u` (not normalised).
    fn span(&self, u: f64) -> Vec3 {
        let [t0, t1] = &self.tip;
        let h = self.upper_at(u);
        std::array::from_fn(|i| h[i] - (t0[i] + u * (t1[i] - t0[i])))
    }

    /// Unit orientation at `u` in 0..=1; the start orientation where the curves meet.
    pub fn at(&self, u: f64) -> Vec3 {
        let d = self.span(u.clamp(0.0, 1.0));
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if n > 1e-12 { [d[0] / n, d[1] / n, d[2] / n] } else { self.start() }
    }

    fn start(&self) -> Vec3 {
        let d = self.span(0.0);
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-300);
        [d[0] / n, d[1] / n, d[2] / n]
    }

    /// The part between parameters `u0` and `u1`.
    pub fn slice(&self, u0: f64, u1: f64) -> TwoCurves {
        let lerp = |a: &Vec3, b: &Vec3, u: f64| -> Vec3 { std::array::from_fn(|i| a[i] + u * (b[i] - a[i])) };
        let [t0, t1] = &self.tip;
        // The bend's power coefficients of u = u0 + d·t in t: c'ₖ = Σᵢ cᵢ·C(i,k)·u0^(i−k)·dᵏ
        // (the bend's uⁱ − u terms: their uⁱ parts; the −u parts go into the new line).
        let d = u1 - u0;
        let mut bend = [[0.0; 3]; 4];
        for (k, out) in bend.iter_mut().enumerate().map(|(j, b)| (j + 2, b)) {
            for (j, b) in self.bend.iter().enumerate().skip(k - 2) {
                let i = j + 2;
                let f = binomial(i, k) * u0.powi((i - k) as i32) * d.powi(k as i32);
                for a in 0..3 {
                    out[a] += b[a] * f;
                }
            }
        }
        TwoCurves { tip: [lerp(t0, t1, u0), lerp(t0, t1, u1)], upper: [self.upper_at(u0), self.upper_at(u1)], bend }
    }

    /// Unit direction in which the orientation moves at the block end: the derivative of
    /// `d/|d|`, `d' − (d'·o)·o` normalised; `None` when it does not move.
    pub fn end_direction(&self) -> Option<Vec3> {
        let o = self.at(1.0);
        let [t0, t1] = &self.tip;
        let [h0, h1] = &self.upper;
        // d/du (uⁱ − u) at u = 1 is i − 1.
        let bent = |i: usize| (2..6).zip(&self.bend).map(|(n, b)| b[i] * f64::from(n - 1)).sum::<f64>();
        let dd: Vec3 = std::array::from_fn(|i| (h1[i] - h0[i]) + bent(i) - (t1[i] - t0[i]));
        let along = dd[0] * o[0] + dd[1] * o[1] + dd[2] * o[2];
        let p: Vec3 = std::array::from_fn(|i| dd[i] - along * o[i]);
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        (n > 1e-12).then(|| [p[0] / n, p[1] / n, p[2] / n])
    }
}

/// The binomial coefficient C(n, k) for the small n of a quintic.
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halfway_the_orientation_points_from_the_mid_tip_to_the_mid_upper_point() {
        // Tip (0,0,0) → (10,0,0), upper (0,0,10) → (20,0,10): halfway (5,0,0) → (10,0,10),
        // direction (5,0,10)/√125.
        let c = TwoCurves::lines([[0.0; 3], [10.0, 0.0, 0.0]], [[0.0, 0.0, 10.0], [20.0, 0.0, 10.0]]);
        let o = c.at(0.5);
        let n = 125f64.sqrt();
        assert!((o[0] - 5.0 / n).abs() < 1e-15 && o[1].abs() < 1e-15 && (o[2] - 10.0 / n).abs() < 1e-15);
        assert_eq!(c.slice(0.5, 1.0).at(0.0), o);
        // At the end the orientation tilts further towards +X.
        let e = c.end_direction().unwrap();
        assert!(e[0] > 0.0 && e[2] < 0.0, "{e:?}");
    }

    #[test]
    fn a_bent_upper_curve_slices_into_the_same_curve() {
        // Upper curve (0,0,1) + u·(1,0,0) + 0.5·(u² − u)·(0,1,0) + 0.25·(u⁵ − u)·(0,0,1):
        // at u = 0.5 it is (0.5, −0.125, 1 + 0.25·(1/32 − 1/2)) = (0.5, −0.125, 0.8828125).
        let mut c = TwoCurves::lines([[0.0; 3]; 2], [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0]]);
        c.bend[0] = [0.0, 0.5, 0.0];
        c.bend[3] = [0.0, 0.0, 0.25];
        let h = c.upper_at(0.5);
        assert!((h[0] - 0.5).abs() < 1e-15 && (h[1] + 0.125).abs() < 1e-15 && (h[2] - 0.8828125).abs() < 1e-15);
        let s = c.slice(0.3, 0.9);
        for i in 0..=10 {
            let t = f64::from(i) / 10.0;
            let (a, b) = (s.at(t), c.at(0.3 + 0.6 * t));
            assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-12), "{t}: {a:?} vs {b:?}");
        }
    }
}
