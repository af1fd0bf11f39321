//! A tool whose axis turns while its tip travels a segment (5-axis simultaneous motion, or a
//! tool turning about a tip that stands still): the tool is placed at samples of the segment
//! with its axis turned in proportion (the great circle from the first axis to the second), so
//! closely that no point of it moves more than half the resolution from one sample to the
//! next: the shank, far from the tip, sets the count (angle × (length + radius)).

use super::DexelGrid;
use super::tilted::steps;
use crate::stock::Removal;
use crate::stock::cutter::Cutter;

impl DexelGrid {
    /// Removes what `cutter` sweeps with its tip going from `a` to `b` while its axis (unit,
    /// tip → holder) turns from `axis_a` to `axis_b`, cutting up to `length` above the tip.
    pub fn cut_swept(
        &mut self,
        cutter: &Cutter,
        a: [f64; 3],
        b: [f64; 3],
        axis_a: [f64; 3],
        axis_b: [f64; 3],
        length: f64,
    ) -> Removal {
        let r = cutter.radius;
        if r <= 0.0 || length.is_nan() || length <= 0.0 {
            return Removal::default();
        }
        let steps = steps(cutter);
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let travel = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let angle = dot(axis_a, axis_b).clamp(-1.0, 1.0).acos();
        let reach = travel.max(angle * (length + r));
        let n = ((reach / (self.res / 2.0)).ceil() as usize).clamp(1, 1 << 20);
        let (mut removed, mut depth) = (0.0f64, 0.0f32);
        for s in 0..=n {
            let t = s as f64 / n as f64;
            let p = [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]];
            let (v, dep) = self.remove_tool_at(p, slerp(axis_a, axis_b, angle, t), length, &steps);
            removed += v;
            depth = depth.max(dep);
        }
        let volume = removed * self.res * self.res;
        self.volume -= volume;
        Removal { volume, depth: f64::from(depth) }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The unit vector a fraction `t` of the way from `u` to `v` (`angle` apart) on their great
/// circle; opposite vectors (no great circle) are blended and normalised.
fn slerp(u: [f64; 3], v: [f64; 3], angle: f64, t: f64) -> [f64; 3] {
    let s = angle.sin();
    let (wu, wv) = if s > 1e-6 { (((1.0 - t) * angle).sin() / s, (t * angle).sin() / s) } else { (1.0 - t, t) };
    let w = [wu * u[0] + wv * v[0], wu * u[1] + wv * v[1], wu * u[2] + wv * v[2]];
    let n = dot(w, w).sqrt();
    if n > 1e-12 { w.map(|c| c / n) } else { u }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::{Blank, Placement, Shape};

    fn plate() -> DexelGrid {
        // X−20..20, Y−5..5, Z−20..0 at 0.25 mm.
        let blank = Blank { shape: Shape::Box { x: [-20.0, 20.0], y: [-5.0, 5.0] }, top: 0.0, bottom: -20.0 };
        DexelGrid::new(&blank, &Placement::default(), 0.25).unwrap()
    }

    /// The material intervals of the cell whose centre is (x, y) (on the grid's centres).
    fn cell(g: &DexelGrid, x: f64, y: f64) -> Vec<[f32; 2]> {
        let (x0, y0) = g.origin();
        let mut iv = Vec::new();
        g.intervals(((x - x0) / 0.25) as usize, ((y - y0) / 0.25) as usize, &mut iv);
        iv
    }

    #[test]
    fn a_tool_turning_about_its_tip_clears_the_fan_between_its_end_orientations() {
        // An end mill R1, 30 long, its tip fixed 5 deep at X0.125 Y0.125 (a cell's centre),
        // turns in the XZ plane from 45° one side of vertical to 45° the other. The two end
        // positions alone meet the line over the tip only up to 1/sin 45° = 1.414 above it: a
        // pocket Z−5..−3.586 under material up to Z0. Swept, the vertical position clears that
        // line from the tip up. 3 mm beside the tip the fan's edge, the 45° axis, lies at Z−2
        // and the tool's side R1 below it, 1.414 along the vertical: the line keeps Z−20..−3.414
        // (everything above lies between the end orientations).
        let (s, c) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
        let tip = [0.125, 0.125, -5.0];
        let close = |iv: &[[f32; 2]], want: &[[f64; 2]]| {
            iv.len() == want.len()
                && iv
                    .iter()
                    .zip(want)
                    .all(|(a, b)| (f64::from(a[0]) - b[0]).abs() < 1e-3 && (f64::from(a[1]) - b[1]).abs() < 1e-3)
        };
        let mut g = plate();
        g.cut_tilted(&Cutter::end_mill(1.0), tip, tip, [-s, 0.0, c], 30.0);
        g.cut_tilted(&Cutter::end_mill(1.0), tip, tip, [s, 0.0, c], 30.0);
        let ends = cell(&g, 0.125, 0.125);
        assert!(close(&ends, &[[-20.0, -5.0], [-5.0 + 1.0 / s, 0.0]]), "{ends:?}");
        let mut g = plate();
        let r = g.cut_swept(&Cutter::end_mill(1.0), tip, tip, [-s, 0.0, c], [s, 0.0, c], 30.0);
        assert!(r.volume > 0.0);
        let over = cell(&g, 0.125, 0.125);
        assert!(close(&over, &[[-20.0, -5.0]]), "{over:?}");
        let beside = cell(&g, 3.125, 0.125);
        let edge = -2.0 - std::f64::consts::SQRT_2;
        assert!(beside.len() == 1 && (f64::from(beside[0][1]) - edge).abs() < 0.01, "{beside:?} vs {edge}");
        // Outside the tool's radius the plate is whole.
        assert_eq!(cell(&g, 0.125, 2.125), vec![[-20.0, 0.0]]);
    }
}
