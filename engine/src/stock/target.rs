//! Meshes from outside: an STL read into triangles, cast onto the dexel grid, for a blank of
//! any shape and for comparing the cut stock with the part it should become.
//!
//! Casting: the vertical line through each cell's centre crosses the closed mesh an even
//! number of times; the crossings sorted by Z pair up into the material intervals. A line
//! through an edge two triangles share is counted once (the half-open edge rule of
//! rasterisers: a point on an edge belongs to the triangle on whose left the edge is "top" or
//! "left"), so a diagonal of a face does not break the pairing. Faces parallel to Z are met
//! only along their edges and add nothing. An open mesh (an odd count on a line) loses the
//! last crossing of that line.
//!
//! Comparison, per cell: what the stock holds beyond the target is an undercut (material left
//! to cut), what the target holds and the stock no longer does an overcut (cut into the part).
//! Thickness is measured along the dexel line (Z): the normal distance on horizontal faces,
//! more than it on slopes and walls (a wall left 0.1 mm thick shows as its height in the
//! cells it covers). Only the stock's grid is compared.

use super::dexel::DexelGrid;
use super::mesh::subtract;

/// Triangles in mm.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub triangles: Vec<[[f64; 3]; 3]>,
}

/// Largest triangle count read from an STL (the memory of one upload).
pub const MAX_TRIANGLES: usize = 4_000_000;

impl Mesh {
    /// Reads a binary or ASCII STL; `Err` says what is wrong.
    pub fn from_stl(bytes: &[u8]) -> Result<Mesh, String> {
        let ascii = bytes.trim_ascii_start().starts_with(b"solid") && {
            // Binary files may begin with "solid" too: their size decides.
            bytes.len() < 84 || 84 + 50 * u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize != bytes.len()
        };
        let triangles = if ascii { read_ascii(bytes)? } else { read_binary(bytes)? };
        if triangles.is_empty() {
            return Err("the STL has no triangles".into());
        }
        if triangles.iter().flatten().flatten().any(|c| !c.is_finite()) {
            return Err("the STL has a vertex that is not a finite number".into());
        }
        Ok(Mesh { triangles })
    }

    /// The smallest box holding the mesh: `[min, max]`.
    pub fn bounds(&self) -> [[f64; 3]; 2] {
        let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
        for v in self.triangles.iter().flatten() {
            for k in 0..3 {
                b[0][k] = b[0][k].min(v[k]);
                b[1][k] = b[1][k].max(v[k]);
            }
        }
        b
    }

    /// Every vertex through `f` (a placement WCS → BCS).
    pub fn map(&self, f: impl Fn([f64; 3]) -> [f64; 3]) -> Mesh {
        Mesh { triangles: self.triangles.iter().map(|t| t.map(&f)).collect() }
    }

    /// The crossings of the vertical lines through the centres of the grid `nx` × `ny` of
    /// cells `res` from (`x0`, `y0`): `(cell, z)` sorted by cell, then Z.
    fn crossings(&self, x0: f64, y0: f64, nx: usize, ny: usize, res: f64) -> Vec<(u32, f64)> {
        let mut hits = Vec::new();
        for t in &self.triangles {
            let [mut a, mut b, c] = *t;
            let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            if area == 0.0 {
                continue;
            }
            if area < 0.0 {
                std::mem::swap(&mut a, &mut b);
            }
            let area = area.abs();
            let lo = |k: usize| a[k].min(b[k]).min(c[k]);
            let hi = |k: usize| a[k].max(b[k]).max(c[k]);
            let first = |v: f64, o: f64, n: usize| ((v - o) / res - 0.5).ceil().clamp(0.0, n as f64) as usize;
            let last = |v: f64, o: f64, n: usize| ((v - o) / res - 0.5).floor().min(n as f64 - 1.0);
            let (i0, i1) = (first(lo(0), x0, nx), last(hi(0), x0, nx));
            let (j0, j1) = (first(lo(1), y0, ny), last(hi(1), y0, ny));
            if i1 < 0.0 || j1 < 0.0 {
                continue;
            }
            for j in j0..=j1 as usize {
                let y = y0 + (j as f64 + 0.5) * res;
                for i in i0..=i1 as usize {
                    let x = x0 + (i as f64 + 0.5) * res;
                    // Edge functions, counter-clockwise: inside where all are positive, on an
                    // edge only for top or left edges.
                    let e = |p: [f64; 3], q: [f64; 3]| {
                        let w = (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
                        let top_left = (q[1] == p[1] && q[0] < p[0]) || q[1] < p[1];
                        w > 0.0 || (w == 0.0 && top_left)
                    };
                    if !(e(a, b) && e(b, c) && e(c, a)) {
                        continue;
                    }
                    let wa = ((b[0] - x) * (c[1] - y) - (b[1] - y) * (c[0] - x)) / area;
                    let wb = ((c[0] - x) * (a[1] - y) - (c[1] - y) * (a[0] - x)) / area;
                    let z = wa * a[2] + wb * b[2] + (1.0 - wa - wb) * c[2];
                    hits.push(((j * nx + i) as u32, z));
                }
            }
        }
        hits.sort_by(|p, q| p.0.cmp(&q.0).then(p.1.total_cmp(&q.1)));
        hits
    }
}

/// The material intervals of every cell with crossings: `(cell, intervals)` by cell.
fn intervals(hits: &[(u32, f64)]) -> Vec<(u32, Vec<[f32; 2]>)> {
    let mut out = Vec::new();
    for run in hits.chunk_by(|p, q| p.0 == q.0) {
        let list: Vec<[f32; 2]> =
            run.chunks_exact(2).map(|p| [p[0].1 as f32, p[1].1 as f32]).filter(|iv| iv[1] > iv[0]).collect();
        if !list.is_empty() {
            out.push((run[0].0, list));
        }
    }
    out
}

impl DexelGrid {
    /// The grid holding `mesh` (BCS, closed) at cells of `res` mm, limited to `max_cells`.
    pub fn from_mesh(mesh: &Mesh, res: f64, max_cells: usize) -> Result<DexelGrid, String> {
        let [lo, hi] = mesh.bounds();
        let nx = ((hi[0] - lo[0]) / res).ceil().max(1.0);
        let ny = ((hi[1] - lo[1]) / res).ceil().max(1.0);
        if nx * ny > max_cells as f64 {
            return Err(format!(
                "the blank needs {nx} x {ny} cells at {res} mm, more than {max_cells}: choose a coarser resolution"
            ));
        }
        let (nx, ny) = (nx as usize, ny as usize);
        let cells = intervals(&mesh.crossings(lo[0], lo[1], nx, ny, res));
        if cells.is_empty() {
            return Err("the STL encloses no material at this resolution (an open or flat mesh?)".into());
        }
        Ok(DexelGrid::from_intervals(res, lo[0], lo[1], nx, ny, hi[2], cells))
    }

    /// The stock against `target` (BCS, closed).
    pub fn compare(&self, target: &Mesh) -> Comparison {
        let (nx, ny) = self.size();
        let (x0, y0) = self.origin();
        let res = self.resolution();
        let target_cells = intervals(&target.crossings(x0, y0, nx, ny, res));
        let mut next = target_cells.iter().peekable();
        let mut c = Comparison::default();
        let (mut here, mut diff) = (Vec::new(), Vec::new());
        let empty: Vec<[f32; 2]> = Vec::new();
        for k in 0..nx * ny {
            let t = match next.peek() {
                Some((cell, list)) if *cell as usize == k => {
                    next.next();
                    list
                }
                _ => &empty,
            };
            let (i, j) = (k % nx, k / nx);
            self.intervals(i, j, &mut here);
            if here.is_empty() && t.is_empty() {
                continue;
            }
            let (x, y) = (x0 + (i as f64 + 0.5) * res, y0 + (j as f64 + 0.5) * res);
            for (over, a, b) in [(false, &here, t), (true, t, &here)] {
                subtract(a, b, &mut diff);
                for iv in &diff {
                    let d = f64::from(iv[1] - iv[0]);
                    let (worst, at, volume) = if over {
                        (&mut c.overcut, &mut c.overcut_at, &mut c.overcut_volume)
                    } else {
                        (&mut c.undercut, &mut c.undercut_at, &mut c.undercut_volume)
                    };
                    *volume += d * res * res;
                    if d > *worst {
                        *worst = d;
                        *at = [x, y, f64::from(iv[0] + iv[1]) / 2.0];
                    }
                }
            }
        }
        c
    }
}

/// The stock against a target part.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Comparison {
    /// Thickest material cut away from the target on one dexel line, mm.
    pub overcut: f64,
    /// Its middle (BCS, mm).
    pub overcut_at: [f64; 3],
    /// Target material the stock lacks, mm³.
    pub overcut_volume: f64,
    /// Thickest material left beyond the target on one dexel line, mm.
    pub undercut: f64,
    pub undercut_at: [f64; 3],
    /// Stock material outside the target, mm³.
    pub undercut_volume: f64,
}

fn read_binary(bytes: &[u8]) -> Result<Vec<[[f64; 3]; 3]>, String> {
    if bytes.len() < 84 {
        return Err(format!("a binary STL has at least 84 bytes, this one {}", bytes.len()));
    }
    let n = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    if n > MAX_TRIANGLES {
        return Err(format!("the STL has {n} triangles, more than {MAX_TRIANGLES}"));
    }
    if bytes.len() < 84 + 50 * n {
        return Err(format!("the binary STL names {n} triangles but holds {} bytes, not {}", bytes.len(), 84 + 50 * n));
    }
    Ok((0..n)
        .map(|t| {
            let f = |k: usize| {
                let o = 84 + 50 * t + 12 + 4 * k;
                f64::from(f32::from_le_bytes(bytes[o..o + 4].try_into().unwrap()))
            };
            [[f(0), f(1), f(2)], [f(3), f(4), f(5)], [f(6), f(7), f(8)]]
        })
        .collect())
}

fn read_ascii(bytes: &[u8]) -> Result<Vec<[[f64; 3]; 3]>, String> {
    let text = std::str::from_utf8(bytes).map_err(|_| "the ASCII STL is not UTF-8 text".to_string())?;
    let mut out = Vec::new();
    let mut corner = Vec::with_capacity(3);
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("vertex") => {
                let v: Vec<f64> = words
                    .map(str::parse)
                    .collect::<Result<_, _>>()
                    .map_err(|_| format!("STL line {}: `vertex` needs three numbers", n + 1))?;
                let [x, y, z] = v[..] else { return Err(format!("STL line {}: `vertex` needs three numbers", n + 1)) };
                corner.push([x, y, z]);
            }
            Some("endloop") => {
                let [a, b, c] = corner[..] else {
                    return Err(format!("STL line {}: a facet needs three vertices", n + 1));
                };
                out.push([a, b, c]);
                corner.clear();
                if out.len() > MAX_TRIANGLES {
                    return Err(format!("the STL has more than {MAX_TRIANGLES} triangles"));
                }
            }
            _ => {}
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::blank::{Blank, Placement, Shape};
    use crate::stock::cutter::Cutter;
    use crate::stock::mesh::dexel_stl;

    fn plate() -> DexelGrid {
        let blank = Blank { shape: Shape::Box { x: [0.0, 10.0], y: [0.0, 10.0] }, top: 0.0, bottom: -10.0 };
        DexelGrid::new(&blank, &Placement::default(), 0.5).unwrap()
    }

    #[test]
    fn the_stl_of_a_stock_read_back_is_the_same_stock() {
        // The STL the stock writes (faces on cell edges, split diagonally) cast on the same
        // grid gives every cell its intervals back: the round trip of an STL blank.
        let mut g = plate();
        g.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -2.0], [15.0, 5.0, -2.0]);
        g.remove_band(3, 3, -6.0, -4.0);
        let mesh = Mesh::from_stl(&dexel_stl(&g)).unwrap();
        let back = DexelGrid::from_mesh(&mesh, 0.5, 1000).unwrap();
        assert_eq!(back.size(), g.size());
        assert!((back.volume() - 959.5).abs() < 1e-6, "{}", back.volume());
        let (mut p, mut q) = (Vec::new(), Vec::new());
        g.intervals(3, 3, &mut p);
        back.intervals(3, 3, &mut q);
        assert_eq!(p, q);
        // Against itself: nothing over, nothing under.
        let c = g.compare(&mesh);
        assert_eq!((c.overcut, c.undercut), (0.0, 0.0));
    }

    #[test]
    fn a_slot_cut_2_deep_against_a_target_1_deep_is_overcut_by_1() {
        // The target: the plate with the 2 mm wide slot only 1 deep (its STL from a stock cut
        // so). The stock cut 2 deep: the four rows of the slot are 1 mm overcut, 4·20 cells of
        // 0.25 mm² by 1 mm = 20 mm³; nothing is left over.
        let mut target = plate();
        target.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -1.0], [15.0, 5.0, -1.0]);
        let target = Mesh::from_stl(&dexel_stl(&target)).unwrap();
        let mut g = plate();
        g.cut(&Cutter::end_mill(1.0), [-5.0, 5.0, -2.0], [15.0, 5.0, -2.0]);
        let c = g.compare(&target);
        assert!((c.overcut - 1.0).abs() < 1e-6 && (c.overcut_volume - 20.0).abs() < 1e-6, "{c:?}");
        assert!((c.overcut_at[2] + 1.5).abs() < 1e-6);
        assert_eq!((c.undercut, c.undercut_volume), (0.0, 0.0));
        // The plate uncut against that target: 1 mm left in the slot, 20 mm³.
        let c = plate().compare(&target);
        assert!((c.undercut - 1.0).abs() < 1e-6 && (c.undercut_volume - 20.0).abs() < 1e-6, "{c:?}");
    }

    #[test]
    fn an_ascii_stl_tetrahedron_casts_its_volume() {
        // Corners (0,0,0), (4,0,0), (0,4,0), (0,0,4): 4³/6 = 10.667 mm³. At 0.1 mm the cells
        // sample the slanted face: the error is under the rim's half cells.
        let text = "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 4 0\nvertex 4 0 0\nendloop\nendfacet\n\
            facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 4 0 0\nvertex 0 0 4\nendloop\nendfacet\n\
            facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 4\nvertex 0 4 0\nendloop\nendfacet\n\
            facet normal 1 1 1\nouter loop\nvertex 4 0 0\nvertex 0 4 0\nvertex 0 0 4\nendloop\nendfacet\nendsolid t\n";
        let mesh = Mesh::from_stl(text.as_bytes()).unwrap();
        let g = DexelGrid::from_mesh(&mesh, 0.1, 100_000).unwrap();
        assert!((g.volume() - 64.0 / 6.0).abs() < 0.3, "{}", g.volume());
        assert!(Mesh::from_stl(b"solid x\nvertex 1 2\nendloop\n").unwrap_err().contains("line 2"));
        assert!(Mesh::from_stl(&[0u8; 10]).unwrap_err().contains("84 bytes"));
    }
}
