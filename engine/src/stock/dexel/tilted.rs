//! Cuts of a tool whose axis is not the dexels' Z: 5-axis orientations, a blank tilted with a
//! trunnion table. The Z-dexels stay as they are; what changes is the primitive: the vertical
//! line through a cell's centre meets the tool in one interval (the tool is convex), and that
//! band is removed from the cell's intervals, splitting one where the tool passes through the
//! material from the side. A cell can so hold any number of intervals (undercuts, holes under
//! an angle, side cuts).
//!
//! The tool is a solid of revolution about its axis: radius R from the tip up to `length`
//! (the shank cuts too; the holder is the collision check's concern), its tip an inscribed
//! staircase of [`LEVELS`] cylinders of radius ρ from the height of the lower surface at ρ
//! ([`Cutter::lower`]); a flat end mill is one exact cylinder. The band of a line is the hull
//! of its intersections with the steps, so it lies inside the true tool (a ball nose tilted
//! leaves at most the step's height, R·(1 − cos(π/2/LEVELS))-ish, which the next sample covers).
//! The segment is sampled every half resolution along the tip's path: the union of the tool at
//! the samples stands for the swept volume (its scallop between samples is below res²/16R).

use super::{DexelGrid, EPS};
use crate::stock::Removal;
use crate::stock::cutter::Cutter;

/// Steps of the staircase standing for a curved tip.
const LEVELS: usize = 6;

/// One cylinder of the tool: radius and the height above the tip where it begins.
pub(super) type Step = (f64, f64);

impl DexelGrid {
    /// Removes what `cutter` sweeps with its tip going from `a` to `b` (BCS of the blank, mm)
    /// with its axis along the unit vector `axis` (tip → holder) and cutting up to `length`
    /// above the tip.
    pub fn cut_tilted(&mut self, cutter: &Cutter, a: [f64; 3], b: [f64; 3], axis: [f64; 3], length: f64) -> Removal {
        let r = cutter.radius;
        if r <= 0.0 || length.is_nan() || length <= 0.0 {
            return Removal::default();
        }
        let o = axis;
        let side = (1.0 - o[2] * o[2]).max(0.0).sqrt();
        // The tool's lowest point anywhere on the segment: nothing to do above the material.
        let low = a[2].min(b[2]) + (length * o[2]).min(0.0) - r * side;
        if low >= self.top_max {
            return Removal::default();
        }
        let steps = steps(cutter);
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let n = ((len / (self.res / 2.0)).ceil() as usize).max(1);
        let (mut removed, mut depth) = (0.0f64, 0.0f32);
        for s in 0..=n {
            let t = s as f64 / n as f64;
            let p = [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]];
            let (v, dep) = self.remove_tool_at(p, o, length, &steps);
            removed += v;
            depth = depth.max(dep);
        }
        let volume = removed * self.res * self.res;
        self.volume -= volume;
        Removal { volume, depth: f64::from(depth) }
    }

    /// Removes the tool standing with its tip at `p`; the sum of the thicknesses removed and
    /// the largest of them.
    ///
    /// Only cells whose line can meet the tool below the stock's highest top are visited: the
    /// axis is clipped to the heights whose slice of the tool reaches below that top (a slice
    /// wholly above it meets no material, and a line that meets only such slices has its band
    /// above it too), and each row to the stretch within the radius of the clipped axis' XY
    /// projection. A tool tilted 30° with its tip 2 mm deep so visits some 2,000 cells
    /// instead of the 10,000 of its whole 100 mm length's box.
    pub(super) fn remove_tool_at(&mut self, p: [f64; 3], o: [f64; 3], length: f64, steps: &[Step]) -> (f64, f32) {
        let r = steps.last().map_or(0.0, |s| s.0);
        let side = (1.0 - o[2] * o[2]).max(0.0).sqrt();
        // Heights h along the axis whose slice (z from p.z + h·o.z − r·side up) reaches below
        // the top.
        let reach = self.top_max - p[2] + r * side;
        let (h0, h1) = if o[2] > 1e-12 {
            (0.0, (reach / o[2]).min(length))
        } else if o[2] < -1e-12 {
            ((reach / o[2]).max(0.0), length)
        } else if reach > 0.0 {
            (0.0, length)
        } else {
            return (0.0, 0.0);
        };
        if h1 < h0 {
            return (0.0, 0.0);
        }
        let a = [p[0] + h0 * o[0], p[1] + h0 * o[1]];
        let d = [(h1 - h0) * o[0], (h1 - h0) * o[1]];
        let res = self.res;
        let range = |lo: f64, hi: f64, origin: f64, n: usize| {
            let first = ((lo - origin) / res - 0.5).ceil().clamp(0.0, n as f64);
            let last = ((hi - origin) / res - 0.5).floor().min(n as f64 - 1.0);
            (first as usize, last as isize)
        };
        let (j0, j1) = range(a[1].min(a[1] + d[1]) - r, a[1].max(a[1] + d[1]) + r, self.y0, self.ny);
        let (mut removed, mut depth) = (0.0f64, 0.0f32);
        for j in j0 as isize..=j1 {
            let y = self.y0 + (j as f64 + 0.5) * res;
            // The part of the projected axis within r of the row in Y: t in [ta, tb].
            let (ta, tb) = if d[1].abs() < 1e-12 {
                (0.0, 1.0)
            } else {
                let (u, v) = ((y - r - a[1]) / d[1], (y + r - a[1]) / d[1]);
                (u.min(v).max(0.0), u.max(v).min(1.0))
            };
            if ta > tb {
                continue;
            }
            let (xa, xb) = (a[0] + ta * d[0], a[0] + tb * d[0]);
            let (i0, i1) = range(xa.min(xb) - r, xa.max(xb) + r, self.x0, self.nx);
            for i in i0 as isize..=i1 {
                let x = self.x0 + (i as f64 + 0.5) * res;
                let k = j as usize * self.nx + i as usize;
                let w = [x - p[0], y - p[1], -p[2]];
                // The whole tool's cylinder first: most cells of the box miss it or its material.
                let Some(outer) = line_in_cylinder(w, o, r, 0.0, length) else { continue };
                if !self.has_material(k, outer) {
                    continue;
                }
                let band = if steps.len() == 1 {
                    Some(outer)
                } else {
                    steps
                        .iter()
                        .filter_map(|&(rho, h0)| line_in_cylinder(w, o, rho, h0, length))
                        .reduce(|u, v| [u[0].min(v[0]), u[1].max(v[1])])
                };
                if let Some([lo, hi]) = band {
                    let t = self.band(k, lo as f32, hi as f32);
                    removed += f64::from(t);
                    depth = depth.max(t);
                }
            }
        }
        (removed, depth)
    }

    /// True if cell `k` holds material inside the Z range `z`.
    pub(super) fn has_material(&self, k: usize, z: [f64; 2]) -> bool {
        let (lo, hi) = (z[0] as f32, z[1] as f32);
        let s = self.spans[k];
        if s[1] > s[0] && s[1] > lo + EPS && s[0] < hi - EPS {
            return true;
        }
        !self.extra.is_empty()
            && self.extra.get(&(k as u32)).is_some_and(|m| m.iter().any(|iv| iv[1] > lo + EPS && iv[0] < hi - EPS))
    }
}

/// The cylinders standing for `cutter` (see the module doc).
pub(super) fn steps(cutter: &Cutter) -> Vec<Step> {
    let r = cutter.radius;
    if cutter.is_flat() {
        return vec![(r, 0.0)];
    }
    (1..=LEVELS)
        .map(|i| {
            let rho = r * i as f64 / LEVELS as f64;
            (rho, cutter.lower(rho))
        })
        .collect()
}

/// The Z range in which the vertical line through `w` (the line's point at Z = 0 minus the
/// tool tip) lies inside the cylinder of radius `rho` about the unit axis `o` between the
/// heights `h0` and `h1` above the tip; `None` if it misses.
pub(super) fn line_in_cylinder(w: [f64; 3], o: [f64; 3], rho: f64, h0: f64, h1: f64) -> Option<[f64; 2]> {
    // A point w + z·ez is at height h(z) = w·o + z·oz and radial distance² |w + z ez|² − h².
    let wo = w[0] * o[0] + w[1] * o[1] + w[2] * o[2];
    let qa = 1.0 - o[2] * o[2];
    let qb = 2.0 * (w[2] - wo * o[2]);
    let qc = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - wo * wo - rho * rho;
    let (mut lo, mut hi) = if qa < 1e-12 {
        // Axis along Z: the radial distance does not depend on z.
        if qc > 0.0 {
            return None;
        }
        (f64::NEG_INFINITY, f64::INFINITY)
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        ((-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa))
    };
    if o[2].abs() > 1e-12 {
        let (za, zb) = ((h0 - wo) / o[2], (h1 - wo) / o[2]);
        lo = lo.max(za.min(zb));
        hi = hi.min(za.max(zb));
    } else if wo < h0 || wo > h1 {
        return None;
    }
    (lo < hi).then_some([lo, hi])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::{Blank, Placement, Shape};
    use std::f64::consts::PI;

    #[test]
    fn a_line_through_a_horizontal_cylinder_meets_it_over_its_diameter() {
        // Axis along +X from the tip at the origin, radius 2, heights 0..10: the vertical line
        // at x = 5, y = 1 meets it where y² + z² <= 4, z in ±sqrt(3).
        let [lo, hi] = line_in_cylinder([5.0, 1.0, 0.0], [1.0, 0.0, 0.0], 2.0, 0.0, 10.0).unwrap();
        assert!((lo + 3f64.sqrt()).abs() < 1e-12 && (hi - 3f64.sqrt()).abs() < 1e-12);
        assert_eq!(line_in_cylinder([11.0, 0.0, 0.0], [1.0, 0.0, 0.0], 2.0, 0.0, 10.0), None);
        // Axis along +Z: the line over the tip's circle from the tip (z = 0) to 10.
        assert_eq!(line_in_cylinder([1.0, 1.0, 0.0], [0.0, 0.0, 1.0], 2.0, 0.0, 10.0), Some([0.0, 10.0]));
    }

    #[test]
    fn a_side_cut_through_a_plate_splits_its_dexels() {
        // 10 x 10 x 10 plate at 0.5 mm; an end mill R1 lying along +X (tip at X−5) travels
        // through it at Z−5 along X: a tunnel of radius 1 through the full 10 mm, π·1²·10 less
        // the sampling of the circle (cells of 0.5 across Y: rows at Y 4.25..5.75, each a band
        // of 2·sqrt(1 − dy²)).
        let blank = Blank { shape: Shape::Box { x: [0.0, 10.0], y: [0.0, 10.0] }, top: 0.0, bottom: -10.0 };
        let mut g = DexelGrid::new(&blank, &Placement::default(), 0.5).unwrap();
        let cutter = Cutter::end_mill(1.0);
        let r = g.cut_tilted(&cutter, [-25.0, 5.0, -5.0], [-5.0, 5.0, -5.0], [1.0, 0.0, 0.0], 30.0);
        let rows: f64 = [0.25f64, 0.75].iter().map(|dy| 2.0 * 2.0 * (1.0 - dy * dy).sqrt()).sum();
        let expected = rows * 0.5 * 10.0;
        assert!((r.volume - expected).abs() < 1e-3, "{r:?} vs {expected}");
        assert!((expected - PI * 10.0).abs() < 1.5);
        let mut iv = Vec::new();
        g.intervals(3, 9, &mut iv);
        let h = (1.0f64 - 0.0625).sqrt() as f32;
        assert_eq!(iv.len(), 2);
        assert!((iv[0][1] - (-5.0 - h)).abs() < 1e-5 && (iv[1][0] - (-5.0 + h)).abs() < 1e-5, "{iv:?}");
    }
}
