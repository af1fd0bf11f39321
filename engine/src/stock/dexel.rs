//! Z-dexels for milling: the XY plane of the BCS cut into square cells of the resolution, per
//! cell the material along Z as a sorted list of intervals, sampled on the vertical line
//! through the cell's centre.
//!
//! A tool along Z removes everything of a cell above the lowest point its lower surface reaches
//! over that cell while it travels a segment, so a cut clips the cell's intervals from above.
//! The first interval of every cell is kept inline (8 bytes a cell); the further ones, which
//! only an undercut makes ([`DexelGrid::remove_band`]), in a map by cell. Volumes are sums of
//! interval lengths times the cell area; the removed volume is counted as cutting goes.

use std::collections::BTreeMap;

use super::blank::{Blank, Placement};
use super::cutter::Cutter;
use super::{MAX_CELLS, Removal};

mod overlap;
mod swept;
mod tilted;
mod turned;

pub use overlap::Overlap;

/// Material of one cell below this thickness (mm) is not counted as removed: a tool sliding on
/// a face it has just cut removes nothing.
const EPS: f32 = 1e-5;

/// The Z-dexel stock.
#[derive(Debug, Clone, PartialEq)]
pub struct DexelGrid {
    res: f64,
    /// BCS position of the corner of cell (0, 0).
    x0: f64,
    y0: f64,
    nx: usize,
    ny: usize,
    /// The lowest interval of each cell, `[bottom, top]`, row by row; empty when top <= bottom.
    spans: Vec<[f32; 2]>,
    /// The intervals of a cell above its first, sorted, for the few cells that have them.
    extra: BTreeMap<u32, Vec<[f32; 2]>>,
    /// Highest top of any cell: a segment whose tool stays above it removes nothing.
    top_max: f64,
    volume: f64,
    /// Per cell the pen (the session's index of the tool) that last removed material there;
    /// 0: never cut. For the HMI's colours by tool.
    marks: Vec<u8>,
    /// The pen of the cuts from now on.
    pen: u8,
}

impl DexelGrid {
    /// The grid holding `blank` placed by `placement`, cells of `res` mm.
    pub fn new(blank: &Blank, placement: &Placement, res: f64) -> Result<DexelGrid, String> {
        blank.check()?;
        placement.check_upright()?;
        let ([xa, xb], [ya, yb]) = blank.extent();
        let corners = [[xa, ya], [xb, ya], [xa, yb], [xb, yb]].map(|[x, y]| placement.apply([x, y, 0.0]));
        let lo = |k: usize| corners.iter().map(|c| c[k]).fold(f64::INFINITY, f64::min);
        let hi = |k: usize| corners.iter().map(|c| c[k]).fold(f64::NEG_INFINITY, f64::max);
        let (x0, y0) = (lo(0), lo(1));
        let nx = ((hi(0) - x0) / res).ceil().max(1.0);
        let ny = ((hi(1) - y0) / res).ceil().max(1.0);
        if nx * ny > MAX_CELLS as f64 {
            return Err(format!(
                "the blank needs {nx} x {ny} cells at {res} mm, more than {MAX_CELLS}: choose a coarser resolution"
            ));
        }
        let (nx, ny) = (nx as usize, ny as usize);
        let [zb, zt] = placement.z_range(blank);
        let mut spans = vec![[0.0f32; 2]; nx * ny];
        let mut cells = 0usize;
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = (x0 + (i as f64 + 0.5) * res, y0 + (j as f64 + 0.5) * res);
                let (wx, wy) = placement.unapply_xy(x, y);
                if blank.contains(wx, wy) {
                    spans[j * nx + i] = [zb as f32, zt as f32];
                    cells += 1;
                }
            }
        }
        let volume = cells as f64 * res * res * (zt as f32 - zb as f32) as f64;
        let marks = vec![0; nx * ny];
        Ok(DexelGrid { res, x0, y0, nx, ny, spans, extra: BTreeMap::new(), top_max: zt, volume, marks, pen: 0 })
    }

    /// A grid from the material of some cells: `(cell, sorted intervals)` by cell, the others
    /// empty (an STL blank, `target.rs`).
    pub(crate) fn from_intervals(
        res: f64,
        x0: f64,
        y0: f64,
        nx: usize,
        ny: usize,
        top_max: f64,
        cells: Vec<(u32, Vec<[f32; 2]>)>,
    ) -> DexelGrid {
        let mut spans = vec![[0.0f32; 2]; nx * ny];
        let mut extra = BTreeMap::new();
        let mut length = 0.0f64;
        for (k, list) in cells {
            length += list.iter().map(|iv| f64::from(iv[1] - iv[0])).sum::<f64>();
            spans[k as usize] = list[0];
            if list.len() > 1 {
                extra.insert(k, list[1..].to_vec());
            }
        }
        let marks = vec![0; nx * ny];
        DexelGrid { res, x0, y0, nx, ny, spans, extra, top_max, volume: length * res * res, marks, pen: 0 }
    }

    /// The grid from its parts as [`DexelGrid::raw`] gives them (a checkpoint, `saved.rs`);
    /// `Err` if they do not fit together.
    #[allow(clippy::too_many_arguments, reason = "the grid's own fields, one call site")]
    pub(crate) fn from_raw(
        res: f64,
        x0: f64,
        y0: f64,
        nx: usize,
        ny: usize,
        spans: Vec<[f32; 2]>,
        extra: BTreeMap<u32, Vec<[f32; 2]>>,
        top_max: f64,
        volume: f64,
        marks: Vec<u8>,
    ) -> Result<DexelGrid, String> {
        if spans.len() != nx * ny || marks.len() != spans.len() || extra.keys().any(|k| *k as usize >= spans.len()) {
            return Err("the saved stock's cells do not match its grid".into());
        }
        Ok(DexelGrid { res, x0, y0, nx, ny, spans, extra, top_max, volume, marks, pen: 0 })
    }

    /// The grid's parts: first intervals, further intervals, highest top, pens.
    #[allow(clippy::type_complexity, reason = "the grid's own fields, read by the checkpoint codec")]
    pub(crate) fn raw(&self) -> (&[[f32; 2]], &BTreeMap<u32, Vec<[f32; 2]>>, f64, &[u8]) {
        (&self.spans, &self.extra, self.top_max, &self.marks)
    }

    /// The pen (1..=255: the session's index of a tool; 0 leaves no mark) of the cuts from now.
    pub fn set_pen(&mut self, pen: u8) {
        self.pen = pen;
    }

    /// The pen that last cut cell (i, j); 0: never cut.
    pub fn mark(&self, i: usize, j: usize) -> u8 {
        self.marks[j * self.nx + i]
    }

    /// Cell size, mm.
    pub fn resolution(&self) -> f64 {
        self.res
    }

    /// Cells in X and Y.
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// BCS X and Y of the corner of cell (0, 0).
    pub fn origin(&self) -> (f64, f64) {
        (self.x0, self.y0)
    }

    /// Material left, mm³.
    pub fn volume(&self) -> f64 {
        self.volume
    }

    /// The material intervals `[bottom, top]` of cell (i, j), low first, into `out` (cleared).
    pub fn intervals(&self, i: usize, j: usize, out: &mut Vec<[f32; 2]>) {
        out.clear();
        let k = j * self.nx + i;
        let s = self.spans[k];
        if s[1] > s[0] {
            out.push(s);
        }
        if let Some(more) = self.extra.get(&(k as u32)) {
            out.extend_from_slice(more);
        }
    }

    /// Removes what `cutter` sweeps with its tip going from `a` to `b` (tool axis along Z).
    pub fn cut(&mut self, cutter: &Cutter, a: [f64; 3], b: [f64; 3]) -> Removal {
        let r = cutter.radius;
        if r <= 0.0 || a[2].min(b[2]) >= self.top_max {
            return Removal::default();
        }
        let sweep = Sweep::new(cutter, a, b);
        let res = self.res;
        let range = |lo: f64, hi: f64, origin: f64, n: usize| {
            // Clamped to the grid (a segment far away must not wrap an index).
            let first = ((lo - origin) / res - 0.5).ceil().clamp(0.0, n as f64);
            let last = ((hi - origin) / res - 0.5).floor().min(n as f64 - 1.0);
            (first as usize, last as isize)
        };
        let (i0, i1) = range(a[0].min(b[0]) - r, a[0].max(b[0]) + r, self.x0, self.nx);
        let (j0, j1) = range(a[1].min(b[1]) - r, a[1].max(b[1]) + r, self.y0, self.ny);
        let (mut removed, mut depth) = (0.0f64, 0.0f32);
        for j in j0 as isize..=j1 {
            let y = self.y0 + (j as f64 + 0.5) * res;
            let row = j as usize * self.nx;
            for i in i0 as isize..=i1 {
                let x = self.x0 + (i as f64 + 0.5) * res;
                let k = row + i as usize;
                let top = self.spans[k][1];
                // Nothing to do where the cell's material lies below the segment's lowest point
                // (and no undercut keeps more above).
                if f64::from(top) <= sweep.z_low && self.extra.is_empty() {
                    continue;
                }
                if let Some(s) = sweep.surface(x, y) {
                    let d = self.clip(k, s as f32);
                    removed += f64::from(d);
                    depth = depth.max(d);
                }
            }
        }
        let volume = removed * res * res;
        self.volume -= volume;
        Removal { volume, depth: f64::from(depth) }
    }

    /// Removes the material of cell `k` above `s`; the thickness removed (largest interval
    /// part), mm.
    #[inline]
    fn clip(&mut self, k: usize, s: f32) -> f32 {
        let mut total = 0.0f32;
        let span = &mut self.spans[k];
        if span[1] > s + EPS {
            let new_top = span[0].max(s);
            total = span[1] - new_top;
            span[1] = new_top;
            self.marks[k] = self.pen;
        }
        if !self.extra.is_empty()
            && let Some(more) = self.extra.get_mut(&(k as u32))
        {
            for iv in more.iter_mut() {
                if iv[1] > s + EPS {
                    let new_top = iv[0].max(s);
                    total += iv[1] - new_top;
                    iv[1] = new_top;
                }
            }
            more.retain(|iv| iv[1] > iv[0]);
            if more.is_empty() {
                self.extra.remove(&(k as u32));
            }
            if total > 0.0 {
                self.marks[k] = self.pen;
            }
        }
        total
    }

    /// Removes the band `lo..hi` (BCS Z) from cell (i, j): an undercut, which splits an
    /// interval in two (a T-slot cutter, a tool from below). The removed volume, mm³.
    pub fn remove_band(&mut self, i: usize, j: usize, lo: f64, hi: f64) -> f64 {
        let t = self.band(j * self.nx + i, lo as f32, hi as f32);
        let volume = f64::from(t) * self.res * self.res;
        self.volume -= volume;
        volume
    }

    /// Removes the band `lo..hi` from cell `k`; the thickness removed (the volume is the
    /// caller's). A band over the top or under the bottom of a single interval shortens it in
    /// place; only a band inside it splits it.
    fn band(&mut self, k: usize, lo: f32, hi: f32) -> f32 {
        if self.extra.is_empty() || !self.extra.contains_key(&(k as u32)) {
            let s = self.spans[k];
            if s[1] <= s[0] || s[1] <= lo + EPS || s[0] >= hi - EPS {
                return 0.0;
            }
            self.marks[k] = self.pen;
            if hi >= s[1] {
                let new_top = s[0].max(lo);
                self.spans[k][1] = new_top;
                return s[1] - new_top;
            }
            if lo <= s[0] {
                self.spans[k][0] = hi;
                return hi - s[0];
            }
        }
        let mut list: Vec<[f32; 2]> = Vec::with_capacity(4);
        let first = self.spans[k];
        if first[1] > first[0] {
            list.push(first);
        }
        if let Some(more) = self.extra.get(&(k as u32)) {
            list.extend_from_slice(more);
        }
        let mut out: Vec<[f32; 2]> = Vec::with_capacity(list.len() + 1);
        let mut removed = 0.0f32;
        for [b, t] in list {
            removed += (t.min(hi) - b.max(lo)).max(0.0);
            if b < lo {
                out.push([b, t.min(lo)]);
            }
            if t > hi {
                out.push([b.max(hi), t]);
            }
        }
        out.retain(|iv| iv[1] > iv[0]);
        if removed > 0.0 {
            self.marks[k] = self.pen;
        }
        self.spans[k] = out.first().copied().unwrap_or([0.0, 0.0]);
        if out.len() > 1 {
            self.extra.insert(k as u32, out[1..].to_vec());
        } else {
            self.extra.remove(&(k as u32));
        }
        removed
    }
}

/// The lower envelope of a tool travelling a straight segment: per point of the XY plane the
/// lowest Z its lower surface reaches there.
struct Sweep<'a> {
    cutter: &'a Cutter,
    a: [f64; 3],
    d: [f64; 3],
    dxy2: f64,
    r2: f64,
    /// Lowest tip Z of the segment.
    z_low: f64,
}

impl<'a> Sweep<'a> {
    fn new(cutter: &'a Cutter, a: [f64; 3], b: [f64; 3]) -> Sweep<'a> {
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let r2 = cutter.radius * cutter.radius;
        Sweep { cutter, a, d, dxy2: d[0] * d[0] + d[1] * d[1], r2, z_low: a[2].min(b[2]) }
    }

    /// The lowest Z of the tool's lower surface over (x, y), if the tool passes over it.
    #[inline]
    fn surface(&self, x: f64, y: f64) -> Option<f64> {
        let (wx, wy) = (x - self.a[0], y - self.a[1]);
        if self.dxy2 < 1e-18 {
            // A plunge or a standstill: the tool's footprint does not move.
            let q = wx * wx + wy * wy;
            return (q <= self.r2).then(|| self.z_low + self.cutter.lower(q.sqrt()));
        }
        // The part of the segment over which (x, y) lies within the radius: t in [t0, t1].
        let p = wx * self.d[0] + wy * self.d[1];
        let q = wx * wx + wy * wy;
        let disc = p * p - self.dxy2 * (q - self.r2);
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let t0 = ((p - root) / self.dxy2).max(0.0);
        let t1 = ((p + root) / self.dxy2).min(1.0);
        if t0 > t1 {
            return None;
        }
        let z = |t: f64| self.a[2] + t * self.d[2];
        if self.cutter.is_flat() {
            return Some(z(t0).min(z(t1)));
        }
        let dist = |t: f64| {
            let (ex, ey) = (wx - t * self.d[0], wy - t * self.d[1]);
            (ex * ex + ey * ey).sqrt().min(self.cutter.radius)
        };
        let f = |t: f64| z(t) + self.cutter.lower(dist(t));
        let tc = (p / self.dxy2).clamp(t0, t1);
        if self.d[2].abs() < 1e-12 {
            // Level: lowest where the axis passes closest.
            return Some(f(tc));
        }
        // Tip height (linear) plus the lower surface of a convex tool (convex in the distance,
        // which is convex in t): a convex function of t, minimised by golden section.
        let (mut lo, mut hi) = (t0, t1);
        const G: f64 = 0.618_033_988_749_894_8;
        let (mut m1, mut m2) = (hi - G * (hi - lo), lo + G * (hi - lo));
        let (mut f1, mut f2) = (f(m1), f(m2));
        for _ in 0..28 {
            if f1 <= f2 {
                hi = m2;
                m2 = m1;
                f2 = f1;
                m1 = hi - G * (hi - lo);
                f1 = f(m1);
            } else {
                lo = m1;
                m1 = m2;
                f1 = f2;
                m2 = lo + G * (hi - lo);
                f2 = f(m2);
            }
        }
        Some(f(t0).min(f(t1)).min(f1.min(f2)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::Shape;
    use crate::stock::cutter::Kind;

    fn plate() -> DexelGrid {
        // 10 x 10 x 10 at 0.5 mm: 400 cells.
        let blank = Blank { shape: Shape::Box { x: [0.0, 10.0], y: [0.0, 10.0] }, top: 0.0, bottom: -10.0 };
        DexelGrid::new(&blank, &Placement::default(), 0.5).unwrap()
    }

    #[test]
    fn a_box_on_the_grid_holds_its_volume() {
        let g = plate();
        assert_eq!(g.size(), (20, 20));
        assert!((g.volume() - 1000.0).abs() < 1e-9);
    }

    #[test]
    fn a_frame_translation_moves_the_blank() {
        let blank = Blank { shape: Shape::Box { x: [0.0, 10.0], y: [0.0, 10.0] }, top: 0.0, bottom: -10.0 };
        let placement = Placement { trans: [100.0, 50.0, -20.0], ..Placement::default() };
        let g = DexelGrid::new(&blank, &placement, 0.5).unwrap();
        assert_eq!(g.origin(), (100.0, 50.0));
        let mut iv = Vec::new();
        g.intervals(0, 0, &mut iv);
        assert_eq!(iv, vec![[-30.0, -20.0]]);
    }

    #[test]
    fn an_undercut_splits_a_dexel_and_a_cut_from_above_takes_the_upper_part() {
        let mut g = plate();
        let v = g.remove_band(3, 3, -6.0, -4.0);
        assert!((v - 2.0 * 0.25).abs() < 1e-9);
        let mut iv = Vec::new();
        g.intervals(3, 3, &mut iv);
        assert_eq!(iv, vec![[-10.0, -6.0], [-4.0, 0.0]]);
        // A plunge of a flat end mill of radius 0.3 over cell (3, 3) (centre 1.75, 1.75) to Z-5:
        // the upper interval goes, the lower stays.
        let r = g.cut(&Cutter::end_mill(0.3), [1.75, 1.75, 5.0], [1.75, 1.75, -5.0]);
        assert!((r.volume - 4.0 * 0.25).abs() < 1e-6, "{r:?}");
        g.intervals(3, 3, &mut iv);
        assert_eq!(iv, vec![[-10.0, -6.0]]);
    }

    #[test]
    fn a_slot_of_a_flat_end_mill_removes_width_times_length_times_depth() {
        let mut g = plate();
        // Radius 1 through the whole plate along X at Y5, 2 deep: cells with centres within 1 mm
        // of Y5 are the four rows 4.25, 4.75, 5.25, 5.75: 2 mm wide, 10 long, 2 deep.
        let r = g.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -2.0], [15.0, 5.0, -2.0]);
        assert!((r.volume - 40.0).abs() < 1e-9, "{r:?}");
        assert!((r.depth - 2.0).abs() < 1e-6);
        // Far beyond the grid: nothing, and no index wraps.
        assert_eq!(g.cut(&Cutter::end_mill(1.0), [1e30, 5.0, -2.0], [2e30, 5.0, -2.0]).volume, 0.0);
        assert_eq!(g.cut(&Cutter::end_mill(1.0), [-2e30, 5.0, -2.0], [-1e30, 5.0, -2.0]).volume, 0.0);
        // The same cut again removes nothing.
        assert_eq!(g.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -2.0], [15.0, 5.0, -2.0]).volume, 0.0);
    }

    #[test]
    fn a_ramp_of_a_ball_mill_leaves_its_lowest_point_at_the_end() {
        let mut g = plate();
        let ball = Cutter { radius: 2.0, kind: Kind::Mill { corner: 2.0 } };
        g.cut(&ball, [1.0, 5.0, 0.0], [9.0, 5.0, -4.0]);
        let mut iv = Vec::new();
        // Cell (17, 9), centre (8.75, 4.75). The ball's centre runs from (1, 5, 2) to (9, 5, −2);
        // the surface over the point is min over t of z_c(t) − sqrt(4 − h(t)²), h the horizontal
        // distance. Z falls 4 over the 8 mm run, faster than the sphere rises near its bottom,
        // so the minimum is at the end: h² = 0.25² + 0.25², −2 − sqrt(3.875) = −3.968502.
        g.intervals(17, 9, &mut iv);
        assert!((iv[0][1] as f64 + 3.968_502).abs() < 1e-5, "{iv:?}");
    }
}
