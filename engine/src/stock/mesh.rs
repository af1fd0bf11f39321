//! The stock as a binary STL (BCS, mm): for CI (`nctwin simulate --stock-out`), the REST
//! download and the HMI's 3D view.
//!
//! Dexels: the top and bottom of every interval as a face over its cell (runs of equal cells
//! in a row merged into one quad), and walls where a cell's material is not matched by its
//! neighbour's. Turning: the profile revolved in [`TURNING_SEGMENTS`] steps: a band per slab
//! for the outer and inner radius and the annuli where neighbouring slabs differ. Closed and
//! outward-facing by construction (a watertight solid up to the facets' resolution).

use super::dexel::DexelGrid;
use super::profile::Profile;

/// Facets round the spindle axis of a turned stock.
pub const TURNING_SEGMENTS: usize = 72;

/// Triangles collected into the bytes of a binary STL.
struct Stl {
    bytes: Vec<u8>,
    count: u32,
}

impl Stl {
    fn new() -> Stl {
        let mut bytes = Vec::with_capacity(84 + 50 * 1024);
        let mut header = [b' '; 80];
        header[..20].copy_from_slice(b"NCTwin stock, BCS mm");
        bytes.extend_from_slice(&header);
        bytes.extend_from_slice(&0u32.to_le_bytes());
        Stl { bytes, count: 0 }
    }

    fn triangle(&mut self, n: [f32; 3], v: [[f32; 3]; 3]) {
        self.triangle_pen(n, v, 0);
    }

    /// A triangle with `pen` in its attribute bytes (the tool that cut the face).
    fn triangle_pen(&mut self, n: [f32; 3], v: [[f32; 3]; 3], pen: u8) {
        for c in n.iter().chain(v.iter().flatten()) {
            self.bytes.extend_from_slice(&c.to_le_bytes());
        }
        self.bytes.extend_from_slice(&u16::from(pen).to_le_bytes());
        self.count += 1;
    }

    /// A quad of corners in counter-clockwise order seen from outside (along `n`).
    fn quad(&mut self, n: [f32; 3], q: [[f32; 3]; 4]) {
        self.quad_pen(n, q, 0);
    }

    fn quad_pen(&mut self, n: [f32; 3], q: [[f32; 3]; 4], pen: u8) {
        self.triangle_pen(n, [q[0], q[1], q[2]], pen);
        self.triangle_pen(n, [q[0], q[2], q[3]], pen);
    }

    fn finish(mut self) -> Vec<u8> {
        self.bytes[80..84].copy_from_slice(&self.count.to_le_bytes());
        self.bytes
    }
}

/// `a` minus `b`, both sorted lists of disjoint intervals, into `out` (cleared).
pub(crate) fn subtract(a: &[[f32; 2]], b: &[[f32; 2]], out: &mut Vec<[f32; 2]>) {
    out.clear();
    for &[mut lo, hi] in a {
        for &[blo, bhi] in b {
            if bhi <= lo || blo >= hi {
                continue;
            }
            if blo > lo {
                out.push([lo, blo]);
            }
            lo = lo.max(bhi);
            if lo >= hi {
                break;
            }
        }
        if lo < hi {
            out.push([lo, hi]);
        }
    }
}

/// The dexel stock as a binary STL; each face's attribute bytes hold the pen of its cell (the
/// session's index of the tool that last cut there, 0 for the blank's own faces).
pub fn dexel_stl(g: &DexelGrid) -> Vec<u8> {
    let (nx, ny) = g.size();
    dexel_stl_region(g, [0, nx], [0, ny])
}

/// The faces of the cells `i` × `j` (half-open ranges) as a binary STL: a tile of the stock
/// for the HMI's incremental updates. Walls look at the neighbours beyond the region, so the
/// tiles of a grid fit together into [`dexel_stl`]'s solid.
pub fn dexel_stl_region(g: &DexelGrid, i_range: [usize; 2], j_range: [usize; 2]) -> Vec<u8> {
    let mut stl = Stl::new();
    let (nx, ny) = g.size();
    let (x0, y0) = g.origin();
    let res = g.resolution();
    let xc = |i: usize| (x0 + i as f64 * res) as f32;
    let yc = |j: usize| (y0 + j as f64 * res) as f32;
    let (mut here, mut there, mut wall) = (Vec::new(), Vec::new(), Vec::new());
    let ([ia, ib], [ja, jb]) = ([i_range[0].min(nx), i_range[1].min(nx)], [j_range[0].min(ny), j_range[1].min(ny)]);
    for j in ja..jb {
        // Tops and bottoms: runs of cells with the same single interval and pen make one quad.
        let mut i = ia;
        while i < ib {
            g.intervals(i, j, &mut here);
            let pen = g.mark(i, j);
            if here.len() == 1 {
                let run = here[0];
                let mut end = i + 1;
                while end < ib {
                    g.intervals(end, j, &mut there);
                    if there.as_slice() != [run] || g.mark(end, j) != pen {
                        break;
                    }
                    end += 1;
                }
                horizontal_faces(&mut stl, [xc(i), xc(end)], [yc(j), yc(j + 1)], &[run], pen);
                i = end;
            } else {
                horizontal_faces(&mut stl, [xc(i), xc(i + 1)], [yc(j), yc(j + 1)], &here, pen);
                i += 1;
            }
        }
        for i in ia..ib {
            let pen = g.mark(i, j);
            g.intervals(i, j, &mut here);
            // Walls towards −X/+X and −Y/+Y where the neighbour (or the grid's edge) has no
            // material at that height.
            for (di, dj) in [(-1isize, 0isize), (1, 0), (0, -1), (0, 1)] {
                let (ni, nj) = (i as isize + di, j as isize + dj);
                if ni >= 0 && nj >= 0 && (ni as usize) < nx && (nj as usize) < ny {
                    g.intervals(ni as usize, nj as usize, &mut there);
                } else {
                    there.clear();
                }
                subtract(&here, &there, &mut wall);
                for &[lo, hi] in &wall {
                    let (x_lo, x_hi, y_lo, y_hi) = (xc(i), xc(i + 1), yc(j), yc(j + 1));
                    let q = match (di, dj) {
                        (-1, _) => [[x_lo, y_hi, lo], [x_lo, y_lo, lo], [x_lo, y_lo, hi], [x_lo, y_hi, hi]],
                        (1, _) => [[x_hi, y_lo, lo], [x_hi, y_hi, lo], [x_hi, y_hi, hi], [x_hi, y_lo, hi]],
                        (_, -1) => [[x_lo, y_lo, lo], [x_hi, y_lo, lo], [x_hi, y_lo, hi], [x_lo, y_lo, hi]],
                        _ => [[x_hi, y_hi, lo], [x_lo, y_hi, lo], [x_lo, y_hi, hi], [x_hi, y_hi, hi]],
                    };
                    stl.quad_pen([di as f32, dj as f32, 0.0], q, pen);
                }
            }
        }
    }
    stl.finish()
}

/// Top (+Z) and bottom (−Z) faces of `intervals` over the rectangle `x` × `y`.
fn horizontal_faces(stl: &mut Stl, x: [f32; 2], y: [f32; 2], intervals: &[[f32; 2]], pen: u8) {
    for &[lo, hi] in intervals {
        stl.quad_pen([0.0, 0.0, 1.0], [[x[0], y[0], hi], [x[1], y[0], hi], [x[1], y[1], hi], [x[0], y[1], hi]], pen);
        stl.quad_pen([0.0, 0.0, -1.0], [[x[0], y[0], lo], [x[0], y[1], lo], [x[1], y[1], lo], [x[1], y[0], lo]], pen);
    }
}

/// The turned stock as a binary STL, revolved in `segments` steps about Z.
pub fn profile_stl(p: &Profile, segments: usize) -> Vec<u8> {
    let mut stl = Stl::new();
    let (z0, n) = p.extent();
    let res = p.resolution();
    let ring: Vec<(f32, f32)> = (0..=segments)
        .map(|s| {
            let a = s as f64 * std::f64::consts::TAU / segments as f64;
            (a.cos() as f32, a.sin() as f32)
        })
        .collect();
    let annulus = |k: usize| -> Vec<[f32; 2]> {
        let (o, i) = if k < n { p.radii(k) } else { (0.0, 0.0) };
        if o > i { vec![[i as f32, o as f32]] } else { Vec::new() }
    };
    let mut exposed = Vec::new();
    for k in 0..=n {
        let z = (z0 + k as f64 * res) as f32;
        let below = if k > 0 { annulus(k - 1) } else { Vec::new() };
        let above = annulus(k);
        // The top of the slab below where the slab above does not cover it, and the other way.
        subtract(&below, &above, &mut exposed);
        for &[r0, r1] in &exposed {
            disc(&mut stl, &ring, z, r0, r1, 1.0);
        }
        subtract(&above, &below, &mut exposed);
        for &[r0, r1] in &exposed {
            disc(&mut stl, &ring, z, r0, r1, -1.0);
        }
        if k < n && !above.is_empty() {
            let z1 = (z0 + (k + 1) as f64 * res) as f32;
            let [ri, ro] = above[0];
            for w in ring.windows(2) {
                let ((c0, s0), (c1, s1)) = (w[0], w[1]);
                let nrm = [(c0 + c1) / 2.0, (s0 + s1) / 2.0, 0.0];
                stl.quad(
                    nrm,
                    [[ro * c0, ro * s0, z], [ro * c1, ro * s1, z], [ro * c1, ro * s1, z1], [ro * c0, ro * s0, z1]],
                );
                if ri > 0.0 {
                    let inward = [-nrm[0], -nrm[1], 0.0];
                    stl.quad(
                        inward,
                        [[ri * c1, ri * s1, z], [ri * c0, ri * s0, z], [ri * c0, ri * s0, z1], [ri * c1, ri * s1, z1]],
                    );
                }
            }
        }
    }
    stl.finish()
}

/// The annulus `r0..r1` at height `z`, facing +Z (`up` = 1) or −Z (−1).
fn disc(stl: &mut Stl, ring: &[(f32, f32)], z: f32, r0: f32, r1: f32, up: f32) {
    for w in ring.windows(2) {
        let (a, b) = if up > 0.0 { (w[0], w[1]) } else { (w[1], w[0]) };
        let outer = ([r1 * a.0, r1 * a.1, z], [r1 * b.0, r1 * b.1, z]);
        if r0 <= 0.0 {
            stl.triangle([0.0, 0.0, up], [[0.0, 0.0, z], outer.0, outer.1]);
        } else {
            stl.quad([0.0, 0.0, up], [[r0 * a.0, r0 * a.1, z], outer.0, outer.1, [r0 * b.0, r0 * b.1, z]]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::{Blank, Placement, Shape};
    use crate::stock::cutter::Cutter;

    /// The volume a closed STL encloses (divergence theorem over its triangles).
    fn enclosed(stl: &[u8]) -> f64 {
        let n = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
        assert_eq!(stl.len(), 84 + 50 * n);
        (0..n)
            .map(|t| {
                let f = |k: usize| {
                    let o = 84 + 50 * t + 12 + 4 * k;
                    f64::from(f32::from_le_bytes(stl[o..o + 4].try_into().unwrap()))
                };
                let v = |i: usize| [f(3 * i), f(3 * i + 1), f(3 * i + 2)];
                let (a, b, c) = (v(0), v(1), v(2));
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }

    #[test]
    fn subtracting_intervals_leaves_the_uncovered_parts() {
        let mut out = Vec::new();
        subtract(&[[0.0, 10.0]], &[[2.0, 3.0], [5.0, 12.0]], &mut out);
        assert_eq!(out, vec![[0.0, 2.0], [3.0, 5.0]]);
    }

    #[test]
    fn the_mesh_of_a_slotted_plate_encloses_its_volume() {
        let blank = Blank { shape: Shape::Box { x: [0.0, 10.0], y: [0.0, 10.0] }, top: 0.0, bottom: -10.0 };
        let mut g = DexelGrid::new(&blank, &Placement::default(), 0.5).unwrap();
        g.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -2.0], [15.0, 5.0, -2.0]);
        g.remove_band(3, 3, -6.0, -4.0);
        // 1000 − 40 (slot) − 0.5 (band): a closed, outward mesh encloses exactly that.
        assert!((enclosed(&dexel_stl(&g)) - 959.5).abs() < 1e-3);
        // Four tiles of 10 x 10 cells together are the same solid.
        let tiles: f64 = [[0, 10], [10, 20]]
            .iter()
            .flat_map(|i| [[0, 10], [10, 20]].map(|j| enclosed(&dexel_stl_region(&g, *i, j))))
            .sum();
        assert!((tiles - 959.5).abs() < 1e-3, "{tiles}");
    }

    #[test]
    fn the_mesh_of_a_turned_tube_encloses_the_revolved_volume_of_its_facets() {
        let blank = Blank { shape: Shape::Tube { outer: 50.0, inner: 30.0 }, top: 0.0, bottom: -10.0 };
        let p = Profile::new(&blank, &Placement::default(), 0.25).unwrap();
        // 72 facets: the polygon's area is n/2 r² sin(2π/n) of the circle's π r².
        let n = TURNING_SEGMENTS as f64;
        let polygon = n / 2.0 * (2.0 * std::f64::consts::PI / n).sin();
        assert!((enclosed(&profile_stl(&p, TURNING_SEGMENTS)) - polygon * (625.0 - 225.0) * 10.0).abs() < 0.05);
    }
}
