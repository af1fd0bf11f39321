//! The turning stock: the part turns about the spindle axis (Z of the BCS, X = 0), so what is
//! left is axisymmetric. Per slab of `res` along Z an outer and an inner radius (a tube's bore,
//! a drilled hole), sampled at the slab's centre; the slabs tile the blank's length exactly.
//!
//! A turning insert (nose circle of radius r, centre S) travelling a segment removes, in every
//! slab its nose passes, the material outside the lowest radius the nose reaches there: the
//! insert and its holder lie radially outside the nose (external turning, facing). An internal
//! insert (a boring bar, its tip pointing away from the axis) removes the material inside the
//! highest radius its nose reaches. A tool on the spindle axis (a drill, an end mill; within
//! half a slab of X0) bores from the free end: the inner radius grows to what its lower surface
//! reaches. Not modelled: tools off the axis that are not turning tools (driven tools), which
//! break the symmetry.

use super::blank::{Blank, Placement, Shape};
use super::cutter::{Cutter, Kind};
use super::{MAX_CELLS, Removal};

/// Radial changes below this (mm) do not count as removed material.
const EPS: f64 = 1e-6;

/// The radius profile of the turning stock.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    res: f64,
    /// BCS Z of the low end of slab 0.
    z0: f64,
    outer: Vec<f64>,
    inner: Vec<f64>,
    volume: f64,
}

impl Profile {
    /// The profile of `blank` (a cylinder or a tube about Z) placed by `placement`.
    pub fn new(blank: &Blank, placement: &Placement, res: f64) -> Result<Profile, String> {
        blank.check()?;
        let (outer, inner) = match blank.shape {
            Shape::Cylinder { diameter } => (diameter / 2.0, 0.0),
            Shape::Tube { outer, inner } => (outer / 2.0, inner / 2.0),
            _ => return Err("a blank on the spindle of a lathe is a CYLINDER or a PIPE".into()),
        };
        placement.check_upright()?;
        if placement.trans[0].abs() > 1e-9 || placement.trans[1].abs() > 1e-9 {
            return Err("the blank's frame moves X or Y: its axis is not the spindle axis".into());
        }
        let [zb, zt] = placement.z_range(blank);
        let n = ((zt - zb) / res).round().max(1.0);
        if n > MAX_CELLS as f64 {
            return Err(format!("the blank needs {n} slabs at {res} mm, more than {MAX_CELLS}"));
        }
        let n = n as usize;
        let res = (zt - zb) / n as f64;
        let volume = n as f64 * std::f64::consts::PI * (outer * outer - inner * inner) * res;
        Ok(Profile { res, z0: zb, outer: vec![outer; n], inner: vec![inner; n], volume })
    }

    /// Slab length, mm (the resolution, adjusted so the slabs tile the blank).
    pub fn resolution(&self) -> f64 {
        self.res
    }

    /// The profile from its parts (a checkpoint, `saved.rs`).
    pub(crate) fn from_raw(
        res: f64,
        z0: f64,
        outer: Vec<f64>,
        inner: Vec<f64>,
        volume: f64,
    ) -> Result<Profile, String> {
        if outer.len() != inner.len() {
            return Err("the saved profile's radii do not pair up".into());
        }
        Ok(Profile { res, z0, outer, inner, volume })
    }

    /// BCS Z of the low end of the first slab and the number of slabs.
    pub fn extent(&self) -> (f64, usize) {
        (self.z0, self.outer.len())
    }

    /// Outer and inner radius of slab `k` (equal when the slab is gone).
    pub fn radii(&self, k: usize) -> (f64, f64) {
        (self.outer[k], self.inner[k])
    }

    /// Material left, mm³.
    pub fn volume(&self) -> f64 {
        self.volume
    }

    /// Removes what `cutter` sweeps with its tip P going from `a` to `b` (BCS: X radial, Z
    /// along the spindle).
    pub fn cut(&mut self, cutter: &Cutter, a: [f64; 3], b: [f64; 3]) -> Removal {
        match cutter.kind {
            Kind::Turning { centre, internal } => {
                let s0 = [a[2] + centre[0], a[0] + centre[1]];
                let s1 = [b[2] + centre[0], b[0] + centre[1]];
                if internal { self.bore_out(cutter.radius, s0, s1) } else { self.turn(cutter.radius, s0, s1) }
            }
            _ if a[0].abs().max(b[0].abs()) <= self.res / 2.0 => self.bore(cutter, a[2].min(b[2])),
            _ => Removal::default(),
        }
    }

    /// The slabs whose centres lie in `lo..=hi`.
    fn slabs(&self, lo: f64, hi: f64) -> std::ops::Range<usize> {
        let first = ((lo - self.z0) / self.res - 0.5).ceil().max(0.0) as usize;
        let last = ((hi - self.z0) / self.res - 0.5).floor();
        if last < 0.0 {
            return 0..0;
        }
        first..(last as usize + 1).min(self.outer.len())
    }

    /// The nose circle (radius `r`) with its centre going from `s0` to `s1` (Z, X).
    fn turn(&mut self, r: f64, s0: [f64; 2], s1: [f64; 2]) -> Removal {
        let (dz, dx) = (s1[0] - s0[0], s1[1] - s0[1]);
        let mut removal = Removal::default();
        for k in self.slabs(s0[0].min(s1[0]) - r, s0[0].max(s1[0]) + r) {
            let z = self.z0 + (k as f64 + 0.5) * self.res;
            let Some(low) = lowest_radius(r, s0, dz, dx, z) else { continue };
            let (outer, inner) = (self.outer[k], self.inner[k]);
            if low < outer - EPS {
                self.take(k, low.max(inner), inner, &mut removal);
            }
        }
        removal
    }

    /// An internal tool (a boring bar) with its nose centre going from `s0` to `s1` (Z, X): the
    /// bore grows to the highest radius the nose reaches in each slab it passes.
    fn bore_out(&mut self, r: f64, s0: [f64; 2], s1: [f64; 2]) -> Removal {
        let (dz, dx) = (s1[0] - s0[0], s1[1] - s0[1]);
        let mut removal = Removal::default();
        for k in self.slabs(s0[0].min(s1[0]) - r, s0[0].max(s1[0]) + r) {
            let z = self.z0 + (k as f64 + 0.5) * self.res;
            // The highest point is the lowest of the nose mirrored at the axis.
            let Some(high) = lowest_radius(r, [s0[0], -s0[1]], dz, -dx, z).map(|x| -x) else { continue };
            let (outer, inner) = (self.outer[k], self.inner[k]);
            if high > inner + EPS {
                self.take(k, outer, high.min(outer), &mut removal);
            }
        }
        removal
    }

    /// An axial tool whose tip reaches down to `z_tip` on the spindle axis.
    fn bore(&mut self, cutter: &Cutter, z_tip: f64) -> Removal {
        let mut removal = Removal::default();
        let top = self.z0 + self.outer.len() as f64 * self.res;
        for k in self.slabs(z_tip, top) {
            let z = self.z0 + (k as f64 + 0.5) * self.res;
            let reach = cutter.reach(z - z_tip);
            let (outer, inner) = (self.outer[k], self.inner[k]);
            if reach > inner + EPS {
                let new_inner = reach.min(outer);
                self.take(k, outer, new_inner, &mut removal);
            }
        }
        removal
    }

    /// Sets slab `k` to the radii `outer`/`inner` (within the old ones) and counts the change.
    fn take(&mut self, k: usize, outer: f64, inner: f64, removal: &mut Removal) {
        let (o, i) = (self.outer[k], self.inner[k]);
        let area = |o: f64, i: f64| std::f64::consts::PI * (o * o - i * i);
        let volume = (area(o, i) - area(outer, inner)) * self.res;
        if volume <= 0.0 {
            return;
        }
        self.outer[k] = outer;
        self.inner[k] = inner;
        self.volume -= volume;
        removal.volume += volume;
        removal.depth = removal.depth.max((o - outer) + (inner - i));
    }
}

/// The lowest radius (X) the nose circle of radius `r` reaches at `z` while its centre goes
/// from `s0` by (`dz`, `dx`); `None` if it does not pass `z`.
pub(crate) fn lowest_radius(r: f64, s0: [f64; 2], dz: f64, dx: f64, z: f64) -> Option<f64> {
    let at = |t: f64| {
        let u = z - (s0[0] + t * dz);
        s0[1] + t * dx - (r * r - u * u).max(0.0).sqrt()
    };
    // The centre positions whose circle covers z: |z − z_c(t)| <= r.
    let (t0, t1) = if dz.abs() < 1e-12 {
        if (z - s0[0]).abs() > r {
            return None;
        }
        (0.0, 1.0)
    } else {
        let (ta, tb) = ((z - r - s0[0]) / dz, (z + r - s0[0]) / dz);
        (ta.min(tb).max(0.0), ta.max(tb).min(1.0))
    };
    if t0 > t1 {
        return None;
    }
    if r == 0.0 {
        return Some(at(t0).min(at(t1)));
    }
    // x_c linear in t, −sqrt(r² − u²) convex in u and u linear in t: convex, golden section.
    const G: f64 = 0.618_033_988_749_894_8;
    let (mut lo, mut hi) = (t0, t1);
    for _ in 0..40 {
        let (m1, m2) = (hi - G * (hi - lo), lo + G * (hi - lo));
        if at(m1) <= at(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    Some(at(t0).min(at(t1)).min(at((lo + hi) / 2.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn bar() -> Profile {
        // Ø50 x 60, top at Z0.
        let blank = Blank { shape: Shape::Cylinder { diameter: 50.0 }, top: 0.0, bottom: -60.0 };
        Profile::new(&blank, &Placement::default(), 0.25).unwrap()
    }

    #[test]
    fn a_bar_holds_its_volume() {
        assert!((bar().volume() - PI * 625.0 * 60.0).abs() < 1e-6);
    }

    #[test]
    fn a_sharp_tool_along_z_leaves_the_turned_diameter() {
        let mut p = bar();
        let sharp = Cutter { radius: 0.0, kind: Kind::Turning { centre: [0.0, 0.0], internal: false } };
        let r = p.cut(&sharp, [23.0, 0.0, 2.0], [23.0, 0.0, -20.0]);
        // Ring Ø50 → Ø46 over 20 mm: π (25² − 23²) 20.
        assert!((r.volume - PI * 96.0 * 20.0).abs() < 1e-6, "{r:?}");
        assert!((r.depth - 2.0).abs() < 1e-9);
    }

    #[test]
    fn a_boring_bar_opens_the_bore_of_a_tube() {
        let blank = Blank { shape: Shape::Tube { outer: 50.0, inner: 30.0 }, top: 0.0, bottom: -60.0 };
        let mut p = Profile::new(&blank, &Placement::default(), 0.25).unwrap();
        let bar = Cutter { radius: 0.0, kind: Kind::Turning { centre: [0.0, 0.0], internal: true } };
        // Ø30 → Ø32 over 10 mm: π (16² − 15²) · 10 = 973.89 mm³; the outside stays.
        let r = p.cut(&bar, [16.0, 0.0, 2.0], [16.0, 0.0, -10.0]);
        assert!((r.volume - PI * 31.0 * 10.0).abs() < 1e-6, "{r:?}");
        assert_eq!(p.radii(239), (25.0, 16.0));
        assert_eq!(p.radii(0), (25.0, 15.0));
    }

    #[test]
    fn an_axial_drill_bores_with_its_point() {
        let mut p = bar();
        let drill = Cutter { radius: 5.0, kind: Kind::Drill { cot: 1.0 } };
        // 90° point: the cone is 5 high; the tip at Z−20.
        let r = p.cut(&drill, [0.0, 0.0, 5.0], [0.0, 0.0, -20.0]);
        let expected = PI * 25.0 * 15.0 + PI * 25.0 * 5.0 / 3.0;
        // Slabs sample the cone at their centres: within one slab's share of the bore.
        assert!((r.volume - expected).abs() < PI * 25.0 * 0.25, "{} vs {expected}", r.volume);
    }
}
