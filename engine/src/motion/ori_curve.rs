//! ORICURVE (F2 §3.11, REFERENCE §6.3.4): the orientation is the direction from the tool tip
//! curve to a second curve through the programmed `XH=`, `YH=`, `ZH=` points, both run through
//! together with the path parameter. Both curves are straight lines within a block (the tool tip
//! of a G1/G0 block; circles are refused by the interpreter), so one sample is two linear
//! interpolations and a normalisation: no allocation, no trigonometry.

use super::orientation::Vec3;

/// The tool tip line and the upper line of one block, in the BCS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoCurves {
    /// Tool tip at the block start and end.
    pub tip: [Vec3; 2],
    /// Point of the second (upper) curve at the block start and end.
    pub upper: [Vec3; 2],
}

impl TwoCurves {
    /// The difference upper − tip at parameter `u` (not normalised).
    fn span(&self, u: f64) -> Vec3 {
        let [t0, t1] = &self.tip;
        let [h0, h1] = &self.upper;
        std::array::from_fn(|i| (h0[i] + u * (h1[i] - h0[i])) - (t0[i] + u * (t1[i] - t0[i])))
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
        let [h0, h1] = &self.upper;
        TwoCurves { tip: [lerp(t0, t1, u0), lerp(t0, t1, u1)], upper: [lerp(h0, h1, u0), lerp(h0, h1, u1)] }
    }

    /// Unit direction in which the orientation moves at the block end: the derivative of
    /// `d/|d|`, `d' − (d'·o)·o` normalised; `None` when it does not move.
    pub fn end_direction(&self) -> Option<Vec3> {
        let o = self.at(1.0);
        let [t0, t1] = &self.tip;
        let [h0, h1] = &self.upper;
        let dd: Vec3 = std::array::from_fn(|i| (h1[i] - h0[i]) - (t1[i] - t0[i]));
        let along = dd[0] * o[0] + dd[1] * o[1] + dd[2] * o[2];
        let p: Vec3 = std::array::from_fn(|i| dd[i] - along * o[i]);
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        (n > 1e-12).then(|| [p[0] / n, p[1] / n, p[2] / n])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halfway_the_orientation_points_from_the_mid_tip_to_the_mid_upper_point() {
        // Tip (0,0,0) → (10,0,0), upper (0,0,10) → (20,0,10): halfway (5,0,0) → (10,0,10),
        // direction (5,0,10)/√125.
        let c = TwoCurves { tip: [[0.0; 3], [10.0, 0.0, 0.0]], upper: [[0.0, 0.0, 10.0], [20.0, 0.0, 10.0]] };
        let o = c.at(0.5);
        let n = 125f64.sqrt();
        assert!((o[0] - 5.0 / n).abs() < 1e-15 && o[1].abs() < 1e-15 && (o[2] - 10.0 / n).abs() < 1e-15);
        assert_eq!(c.slice(0.5, 1.0).at(0.0), o);
        // At the end the orientation tilts further towards +X.
        let e = c.end_direction().unwrap();
        assert!(e[0] > 0.0 && e[2] < 0.0, "{e:?}");
    }
}
