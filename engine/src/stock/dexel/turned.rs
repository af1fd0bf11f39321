//! A turned part that stops being axisymmetric: milling with driven tools on a lathe (TRANSMIT
//! on the face, TRACYL on the periphery). The profile (`profile.rs`) cannot hold a slot, so the
//! part becomes Z-dexels in the frame of the workpiece, which turns with the spindle (C): the
//! grid's Z is the spindle axis, its origin on the axis. From then on a turning insert cutting
//! while the spindle turns in speed control removes a ring ([`DexelGrid::cut_ring`]): per cell at
//! radius ρ from the axis the stretch of Z over which the swept nose reaches below ρ (external)
//! or above it (internal), found on Z steps of at most half the resolution.

use super::DexelGrid;
use crate::stock::cutter::{Cutter, Kind};
use crate::stock::profile::{Profile, lowest_radius};
use crate::stock::{MAX_CELLS, Removal};

impl DexelGrid {
    /// The dexels of `profile` on a square grid of `res` mm centred on the spindle axis: a
    /// cell's intervals are the runs of slabs whose ring (inner ≤ ρ < outer) holds the radius ρ
    /// of the cell's centre.
    pub fn from_profile(profile: &Profile, res: f64) -> Result<DexelGrid, String> {
        let (z0, n) = profile.extent();
        let slab = profile.resolution();
        let rmax = (0..n).map(|k| profile.radii(k).0).fold(0.0, f64::max);
        let side = ((2.0 * rmax) / res).ceil().max(1.0);
        if side * side > MAX_CELLS as f64 {
            return Err(format!(
                "the turned part needs {side} x {side} cells at {res} mm, more than {MAX_CELLS}: choose a coarser resolution"
            ));
        }
        let side = side as usize;
        let origin = -(side as f64) * res / 2.0;
        let mut cells = Vec::new();
        let mut list: Vec<[f32; 2]> = Vec::new();
        for j in 0..side {
            let y = origin + (j as f64 + 0.5) * res;
            for i in 0..side {
                let x = origin + (i as f64 + 0.5) * res;
                let rho = x.hypot(y);
                list.clear();
                for k in 0..n {
                    let (outer, inner) = profile.radii(k);
                    if !(inner <= rho && rho < outer) {
                        continue;
                    }
                    let (lo, hi) = ((z0 + k as f64 * slab) as f32, (z0 + (k + 1) as f64 * slab) as f32);
                    match list.last_mut() {
                        Some(last) if (last[1] - lo).abs() < 1e-6 => last[1] = hi,
                        _ => list.push([lo, hi]),
                    }
                }
                if !list.is_empty() {
                    cells.push(((j * side + i) as u32, list.clone()));
                }
            }
        }
        let top = z0 + n as f64 * slab;
        Ok(DexelGrid::from_intervals(res, origin, origin, side, side, top, cells))
    }

    /// Removes the ring a turning insert sweeps with its theoretical tip going from `a` to `b`
    /// (in the non-turning frame: X radial, Z along the spindle axis) while the part turns
    /// under it. `None` for a cutter that is no turning insert (the caller decides).
    pub fn cut_ring(&mut self, cutter: &Cutter, a: [f64; 3], b: [f64; 3]) -> Option<Removal> {
        let Kind::Turning { centre, internal } = cutter.kind else { return None };
        let r = cutter.radius;
        let s0 = [a[2] + centre[0], a[0].hypot(a[1]) + centre[1]];
        let s1 = [b[2] + centre[0], b[0].hypot(b[1]) + centre[1]];
        let (dz, dx) = (s1[0] - s0[0], s1[1] - s0[1]);
        let (zlo, zhi) = (s0[0].min(s1[0]) - r, s0[0].max(s1[0]) + r);
        // Steps of at most half the resolution that tile zlo..zhi exactly, so the bands of
        // consecutive segments meet.
        let steps = (((zhi - zlo) / (self.res / 2.0)).ceil() as usize).max(1);
        let h = (zhi - zlo) / steps as f64;
        // Per Z step the radius the nose reaches: material beyond it (external) or within it
        // (internal) goes; NaN where the nose does not pass.
        let reach: Vec<f64> = (0..steps)
            .map(|m| {
                let z = zlo + (m as f64 + 0.5) * h;
                if internal {
                    lowest_radius(r, [s0[0], -s0[1]], dz, -dx, z).map_or(f64::NAN, |x| -x)
                } else {
                    lowest_radius(r, s0, dz, dx, z).unwrap_or(f64::NAN)
                }
            })
            .collect();
        let (mut removed, mut depth) = (0.0f64, 0.0f32);
        for j in 0..self.ny {
            let y = self.y0 + (j as f64 + 0.5) * self.res;
            for i in 0..self.nx {
                let x = self.x0 + (i as f64 + 0.5) * self.res;
                let k = j * self.nx + i;
                if !self.has_material(k, [zlo, zhi]) {
                    continue;
                }
                let rho = x.hypot(y);
                let takes = |q: &f64| if internal { rho < *q } else { rho > *q };
                let (Some(first), Some(last)) = (reach.iter().position(takes), reach.iter().rposition(takes)) else {
                    continue;
                };
                let (lo, hi) = (zlo + first as f64 * h, zlo + (last + 1) as f64 * h);
                let t = self.band(k, lo as f32, hi as f32);
                removed += f64::from(t);
                depth = depth.max(t);
            }
        }
        let volume = removed * self.res * self.res;
        self.volume -= volume;
        Some(Removal { volume, depth: f64::from(depth) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::{Blank, Placement, Shape};
    use std::f64::consts::PI;

    fn bar() -> Profile {
        // Ø20 x 10, top at Z0, slabs of 0.25.
        let blank = Blank { shape: Shape::Cylinder { diameter: 20.0 }, top: 0.0, bottom: -10.0 };
        Profile::new(&blank, &Placement::default(), 0.25).unwrap()
    }

    #[test]
    fn a_bar_becomes_dexels_of_its_length_inside_its_radius() {
        let g = DexelGrid::from_profile(&bar(), 0.25).unwrap();
        // 80 x 80 cells over X/Y −10..10; a cell whose centre lies within R10 holds Z−10..0.
        assert_eq!(g.size(), (80, 80));
        let mut iv = Vec::new();
        g.intervals(40, 40, &mut iv);
        assert_eq!(iv, vec![[-10.0, 0.0]]);
        g.intervals(0, 0, &mut iv);
        assert!(iv.is_empty());
        // π·100·10 = 3141.6 within the cells a circle's rim crosses (2πR/res·res²/2 · 10 = 78).
        assert!((g.volume() - PI * 1000.0).abs() < 78.0, "{}", g.volume());
    }

    #[test]
    fn a_turning_insert_on_the_grid_removes_the_ring() {
        let mut g = DexelGrid::from_profile(&bar(), 0.25).unwrap();
        let before = g.volume();
        // A sharp external tool at R8 from Z2 to Z−5: the ring R8..10 over 5 mm, π(100 − 64)·5
        // = 565.5, sampled at the cells (rims at R8 and R10: ±(2π·18/0.25)·0.25²/2·5 = 35).
        let sharp = Cutter { radius: 0.0, kind: Kind::Turning { centre: [0.0, 0.0], internal: false } };
        let r = g.cut_ring(&sharp, [8.0, 0.0, 2.0], [8.0, 0.0, -5.0]).unwrap();
        assert!((r.volume - PI * 36.0 * 5.0).abs() < 35.0, "{r:?}");
        assert!((before - g.volume() - r.volume).abs() < 1e-6);
        let mut iv = Vec::new();
        // Cell (73, 40): centre X8.375, Y0.125: outside R8, so cut down to Z−5.
        g.intervals(73, 40, &mut iv);
        assert_eq!(iv, vec![[-10.0, -5.0]]);
        assert!(g.cut_ring(&Cutter::end_mill(2.0), [0.0; 3], [1.0; 3]).is_none());
    }
}
