//! How much material lies inside a body that must not touch it (the holder), with the body
//! moved along a segment: the collision check's question, answered without removing anything.

use super::DexelGrid;
use super::tilted::line_in_cylinder;

/// The worst overlap found along a segment.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Overlap {
    /// Material inside the body at the worst sample, mm³.
    pub volume: f64,
    /// The thickest material inside it on one dexel line, mm.
    pub depth: f64,
    /// The tool tip at that sample.
    pub at: [f64; 3],
}

impl DexelGrid {
    /// The material inside the stack of `cylinders` (radius, from, to: heights above the tip
    /// along the unit `axis`) while the tip goes from `a` to `b`, sampled every half resolution.
    pub fn overlap(&self, cylinders: &[(f64, f64, f64)], a: [f64; 3], b: [f64; 3], axis: [f64; 3]) -> Overlap {
        let o = axis;
        let side = (1.0 - o[2] * o[2]).max(0.0).sqrt();
        let rmax = cylinders.iter().map(|c| c.0).fold(0.0, f64::max);
        // Lowest point of any cylinder over the segment: nothing to find above the material.
        let low = cylinders.iter().map(|c| (c.1 * o[2]).min(c.2 * o[2])).fold(f64::INFINITY, f64::min);
        if a[2].min(b[2]) + low - rmax * side >= self.top_max {
            return Overlap::default();
        }
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let n = ((len / (self.res / 2.0)).ceil() as usize).max(1);
        let mut worst = Overlap::default();
        let mut list = Vec::new();
        for s in 0..=n {
            let t = s as f64 / n as f64;
            let p = [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]];
            let (mut volume, mut depth) = (0.0f64, 0.0f64);
            for &(rho, h0, h1) in cylinders {
                let (lo_end, hi_end) = ([p[0] + h0 * o[0], p[1] + h0 * o[1]], [p[0] + h1 * o[0], p[1] + h1 * o[1]]);
                if p[2] + (h0 * o[2]).min(h1 * o[2]) - rho * side >= self.top_max {
                    continue;
                }
                let res = self.res;
                let range = |lo: f64, hi: f64, origin: f64, n: usize| {
                    let first = ((lo - origin) / res - 0.5).ceil().clamp(0.0, n as f64);
                    let last = ((hi - origin) / res - 0.5).floor().min(n as f64 - 1.0);
                    (first as usize, last as isize)
                };
                let (i0, i1) = range(lo_end[0].min(hi_end[0]) - rho, lo_end[0].max(hi_end[0]) + rho, self.x0, self.nx);
                let (j0, j1) = range(lo_end[1].min(hi_end[1]) - rho, lo_end[1].max(hi_end[1]) + rho, self.y0, self.ny);
                for j in j0 as isize..=j1 {
                    let y = self.y0 + (j as f64 + 0.5) * res;
                    for i in i0 as isize..=i1 {
                        let x = self.x0 + (i as f64 + 0.5) * res;
                        let Some([zl, zh]) = line_in_cylinder([x - p[0], y - p[1], -p[2]], o, rho, h0, h1) else {
                            continue;
                        };
                        self.intervals(i as usize, j as usize, &mut list);
                        let inside: f64 =
                            list.iter().map(|iv| (f64::from(iv[1]).min(zh) - f64::from(iv[0]).max(zl)).max(0.0)).sum();
                        volume += inside;
                        depth = depth.max(inside);
                    }
                }
            }
            let volume = volume * self.res * self.res;
            if volume > worst.volume {
                worst = Overlap { volume, depth, at: p };
            }
        }
        worst
    }
}
