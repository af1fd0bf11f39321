//! Coordinate frames between the workpiece (WCS) and basic (BCS) coordinate systems.
//!
//! A frame maps child coordinates to parent coordinates, `p_parent = t + A·p_child` for the
//! geometry axes (A: rotation × scale × mirror, kept as one matrix so that any chain of frame
//! instructions composes exactly) and `p = t + f·p` for every other channel axis. The active
//! frame is the settable frame (G54 ...) followed by the programmable frame (TRANS, ROT, SCALE,
//! MIRROR and their additive forms).

use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::machine_data::{FrameAngles, FrameData};
use crate::motion::AxisVec;

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n > 1e-12).then(|| v.map(|x| x / n))
}

/// Geometry axes by channel-axis index (`None`: not present).
pub type GeoAxes = [Option<usize>; 3];

#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Frame {
    /// Translation per channel axis (coarse plus fine).
    pub trans: AxisVec,
    /// Linear part for the geometry axes (rows: parent axis, columns: child axis).
    pub lin: [[f64; 3]; 3],
    /// Factor per channel axis for the axes that are not geometry axes (scale, mirror).
    pub factor: AxisVec,
}

impl Default for Frame {
    fn default() -> Self {
        Frame::identity()
    }
}

impl Frame {
    pub fn identity() -> Frame {
        Frame {
            trans: [0.0; MAX_CHANNEL_AXES],
            lin: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            factor: [1.0; MAX_CHANNEL_AXES],
        }
    }

    /// A stored frame of the data management (settable or basic frame) on this channel's axes.
    pub fn from_data(data: &FrameData, geo: &GeoAxes, angles: FrameAngles) -> Frame {
        let mut f = Frame::identity();
        if data.is_neutral() {
            return f;
        }
        for (k, t) in data.trans.iter().enumerate() {
            f.trans[k] = *t;
        }
        let factor = |k: usize| data.scale[k] * if data.mirror[k] { -1.0 } else { 1.0 };
        for k in 0..data.scale.len() {
            f.factor[k] = factor(k);
        }
        // Rotation of the scaled and mirrored child axes: R · diag(factors).
        let r = rotation_of(angles, data.rot);
        for (c, axis) in geo.iter().enumerate() {
            let s = axis.map_or(1.0, factor);
            for (row, r_row) in f.lin.iter_mut().zip(&r) {
                row[c] = r_row[c] * s;
            }
        }
        f
    }

    /// The frame as stored frame data for `n` channel axes: the rotation of the geometry axes
    /// as RPY or Euler angles (MD10600), scale and mirror per axis. `None` when the linear part is
    /// no rotation with per-axis scale and mirror (a shear), which stored frames cannot hold.
    pub fn to_data(&self, geo: &GeoAxes, n: usize, angles: FrameAngles) -> Option<FrameData> {
        let mut data = FrameData::neutral(n);
        data.trans.copy_from_slice(&self.trans[..n]);
        for k in 0..n {
            data.scale[k] = self.factor[k].abs();
            data.mirror[k] = self.factor[k] < 0.0;
        }
        // Columns of the linear part: rotation columns times signed factors.
        let mut q = self.lin;
        let mut d = [1.0; 3];
        for c in 0..3 {
            let norm = (0..3).map(|r| q[r][c] * q[r][c]).sum::<f64>().sqrt();
            if norm < 1e-12 {
                return None;
            }
            d[c] = norm;
            for row in q.iter_mut() {
                row[c] /= norm;
            }
        }
        let det = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0])
            + q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
        if det < 0.0 {
            // One mirrored axis: the one whose column points most against its own direction.
            let c = (0..3).min_by(|a, b| q[*a][*a].total_cmp(&q[*b][*b])).expect("three columns");
            d[c] = -d[c];
            for row in q.iter_mut() {
                row[c] = -row[c];
            }
        }
        data.rot = angles_of(angles, &q);
        for (g, axis) in geo.iter().enumerate() {
            if let Some(k) = *axis {
                data.scale[k] = d[g].abs();
                data.mirror[k] = d[g] < 0.0;
            }
        }
        let back = Frame::from_data(&data, geo, angles);
        let same = (0..3).all(|r| (0..3).all(|c| (back.lin[r][c] - self.lin[r][c]).abs() < 1e-9));
        same.then_some(data)
    }

    /// A pure translation.
    pub fn translation(trans: AxisVec) -> Frame {
        Frame { trans, ..Frame::identity() }
    }

    /// A rotation of the geometry axes by the matrix `r` (columns: images of the child axes).
    pub fn rotation(r: [[f64; 3]; 3]) -> Frame {
        Frame { lin: r, ..Frame::identity() }
    }

    /// Scale factors (negative ones mirror) for the listed channel axes; geometry axes go
    /// into the matrix.
    pub fn scaling(geo: &GeoAxes, factors: &[(usize, f64)]) -> Frame {
        let mut f = Frame::identity();
        for &(k, s) in factors {
            match geo.iter().position(|g| *g == Some(k)) {
                Some(g) => f.lin[g][g] = s,
                None => f.factor[k] = s,
            }
        }
        f
    }

    /// True if geometry axes are mixed (a rotation): programming one moves others.
    pub fn couples_axes(&self) -> bool {
        (0..3).any(|i| (0..3).any(|j| i != j && self.lin[i][j].abs() > 1e-15))
    }

    /// True if the frame is the identity.
    pub fn is_identity(&self) -> bool {
        // Field by field, stopping at the first difference (no identity frame is built).
        self.trans.iter().all(|&t| t == 0.0) && self.linear_is_identity() && self.factor.iter().all(|&f| f == 1.0)
    }

    /// True if the geometry axes are neither rotated, scaled nor mirrored.
    pub fn linear_is_identity(&self) -> bool {
        self.lin == [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    }

    /// `self ∘ child`: first `child`, then `self`.
    pub fn then(&self, child: &Frame, geo: &GeoAxes) -> Frame {
        let mut out = Frame::identity();
        for i in 0..3 {
            for j in 0..3 {
                out.lin[i][j] = (0..3).map(|k| self.lin[i][k] * child.lin[k][j]).sum();
            }
        }
        out.trans = self.apply_vector(geo, &child.trans);
        for k in 0..MAX_CHANNEL_AXES {
            out.trans[k] += self.trans[k];
            out.factor[k] = self.factor[k] * child.factor[k];
        }
        out
    }

    /// Whether `other` holds the same numbers bit for bit: what a copy of a frame is compared
    /// with to see whether it needs refreshing (cheaper than `==` on 49 floats, which cannot
    /// be vectorised; a `0.0` against a `-0.0` only counts as a difference).
    pub fn same_bits(&self, other: &Frame) -> bool {
        let bits = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0u64, |acc, (x, y)| acc | (x.to_bits() ^ y.to_bits()));
        bits(&self.trans, &other.trans)
            | bits(self.lin.as_flattened(), other.lin.as_flattened())
            | bits(&self.factor, &other.factor)
            == 0
    }

    /// Maps a point from child to parent coordinates.
    pub fn apply(&self, geo: &GeoAxes, p: &AxisVec) -> AxisVec {
        let mut out = self.apply_vector(geo, p);
        for (o, t) in out.iter_mut().zip(&self.trans) {
            *o += t;
        }
        out
    }

    /// Maps a direction (no translation) from child to parent coordinates.
    pub fn apply_vector(&self, geo: &GeoAxes, p: &AxisVec) -> AxisVec {
        let mut out = *p;
        for (o, f) in out.iter_mut().zip(&self.factor) {
            *o *= f;
        }
        let child = geo.map(|a| a.map_or(0.0, |k| p[k]));
        for (g, axis) in geo.iter().enumerate() {
            if let Some(k) = axis {
                out[*k] = (0..3).map(|j| self.lin[g][j] * child[j]).sum();
            }
        }
        out
    }

    /// A direction of the geometry axes (an orientation vector) from child to parent,
    /// normalised.
    pub fn rotate_direction(&self, v: [f64; 3]) -> [f64; 3] {
        let l = &self.lin;
        unit(std::array::from_fn(|g| l[g][0] * v[0] + l[g][1] * v[1] + l[g][2] * v[2])).unwrap_or(v)
    }

    /// A direction of the geometry axes from parent back to child, normalised. The linear part
    /// of a frame is a rotation with mirroring and uniform scale, so its transpose inverts the
    /// direction.
    pub fn unrotate_direction(&self, v: [f64; 3]) -> [f64; 3] {
        let l = &self.lin;
        unit(std::array::from_fn(|j| l[0][j] * v[0] + l[1][j] * v[1] + l[2][j] * v[2])).unwrap_or(v)
    }

    /// Maps a point from parent back to child coordinates; `None` if the frame is singular
    /// (a scale factor of zero).
    pub fn unapply(&self, geo: &GeoAxes, p: &AxisVec) -> Option<AxisVec> {
        self.unapply_inverted(&self.linear_inverse()?, geo, p)
    }

    /// The inverse of the rotation and scale part, `None` if singular: kept by callers that
    /// map many points back through one frame ([`Frame::unapply_inverted`]).
    pub fn linear_inverse(&self) -> Option<[[f64; 3]; 3]> {
        invert3(&self.lin)
    }

    /// [`Frame::unapply`] with the inverse of [`Frame::linear_inverse`] computed once.
    pub fn unapply_inverted(&self, inv: &[[f64; 3]; 3], geo: &GeoAxes, p: &AxisVec) -> Option<AxisVec> {
        let mut out = *p;
        for k in 0..MAX_CHANNEL_AXES {
            if self.factor[k] == 0.0 {
                return None;
            }
            out[k] = (p[k] - self.trans[k]) / self.factor[k];
        }
        let d = geo.map(|a| a.map_or(0.0, |k| p[k] - self.trans[k]));
        for (g, axis) in geo.iter().enumerate() {
            if let Some(k) = axis {
                out[*k] = (0..3).map(|j| inv[g][j] * d[j]).sum();
            }
        }
        Some(out)
    }

    /// The image of the unit vector of geometry axis `g` in parent coordinates.
    pub fn geo_direction(&self, geo: &GeoAxes, g: usize) -> AxisVec {
        let mut out = [0.0; MAX_CHANNEL_AXES];
        for (row, axis) in geo.iter().enumerate() {
            if let Some(k) = axis {
                out[*k] = self.lin[row][g];
            }
        }
        out
    }
}

/// The system frames the control writes itself (toolholder, tool alignment, cycles), each a
/// link of the frame chain. Like the control's system frames they survive a reset; the
/// function that wrote one deletes it (TOROTOF, PAROTOF, CYCLE800 deselection).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SystemFrames {
    /// `$P_PARTFRAME`: TCARR table offset and PAROT rotation (nearest to the BCS).
    pub part: Frame,
    /// `$P_SETFRAME`: actual value setting (written by programs here).
    pub set: Frame,
    /// `$P_EXTFRAME`: external work offset (written by programs here).
    pub ext: Frame,
    /// `$P_WPFRAME`: workpiece reference points (written by programs here).
    pub wp: Frame,
    /// `$P_TRAFRAME`: transformation frame (written by programs here).
    pub tra: Frame,
    /// `$P_TOOLFRAME`: TOROT / TOFRAME.
    pub tool: Frame,
    /// `$P_CYCFRAME`: the swivel cycle (nearest to the WCS).
    pub cycle: Frame,
}

/// Frames from the BCS towards the WCS chained into one, skipping neutral links.
pub fn chain(links: &[&Frame], geo: &GeoAxes) -> Frame {
    let mut out: Option<Frame> = None;
    for link in links.iter().filter(|f| !f.is_identity()) {
        out = Some(match out {
            None => (*link).clone(),
            Some(parent) => parent.then(link, geo),
        });
    }
    out.unwrap_or_default()
}

/// `Rz(z)·Ry(y)·Rx(x)`: the RPY rotation of ROT X.. Y.. Z.. (MD10600 FRAME_ANGLE_INPUT_MODE = 1),
/// angles in degrees, right-hand rule.
pub fn rpy(x: f64, y: f64, z: f64) -> [[f64; 3]; 3] {
    let (sx, cx) = x.to_radians().sin_cos();
    let (sy, cy) = y.to_radians().sin_cos();
    let (sz, cz) = z.to_radians().sin_cos();
    [
        [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
        [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
        [-sy, cy * sx, cy * cx],
    ]
}

/// `Rz(z)·Rx(x)·Rz(y)`: the Euler rotation of ROT X.. Y.. Z.. with MD10600 = 2 (K2: "in the
/// order Z, X', Z''"; the X angle is the middle one, 0 ≤ x < 180, so the Z angle turns first and
/// the Y angle last, about the new Z).
pub fn euler(x: f64, y: f64, z: f64) -> [[f64; 3]; 3] {
    let m = |a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    };
    m(&m(&about_axis(2, z), &about_axis(0, x)), &about_axis(2, y))
}

/// The rotation for the angles about X, Y, Z as written in a frame, per MD10600.
pub fn rotation_of(angles: FrameAngles, [x, y, z]: [f64; 3]) -> [[f64; 3]; 3] {
    match angles {
        FrameAngles::Rpy => rpy(x, y, z),
        FrameAngles::Euler => euler(x, y, z),
    }
}

/// The angles [x, y, z] of a rotation matrix in the ranges the control reads them back in:
/// RPY −180 ≤ x ≤ 180, −90 ≤ y ≤ 90, −180 ≤ z ≤ 180; Euler 0 ≤ x ≤ 180, y and z ±180 (at x = 0
/// or 180 only z + y or z − y is defined; y reads 0 then).
pub fn angles_of(angles: FrameAngles, q: &[[f64; 3]; 3]) -> [f64; 3] {
    match angles {
        FrameAngles::Rpy => {
            [q[2][1].atan2(q[2][2]), (-q[2][0]).clamp(-1.0, 1.0).asin(), q[1][0].atan2(q[0][0])].map(f64::to_degrees)
        }
        FrameAngles::Euler => {
            let x = q[2][2].clamp(-1.0, 1.0).acos();
            let (y, z) = if x.sin().abs() > 1e-12 {
                (q[2][0].atan2(q[2][1]), q[0][2].atan2(-q[1][2]))
            } else {
                (0.0, q[1][0].atan2(q[0][0]))
            };
            [x, y, z].map(f64::to_degrees)
        }
    }
}

/// Rotation about geometry axis `g` (0 = X, 1 = Y, 2 = Z) by `angle` degrees.
pub fn about_axis(g: usize, angle: f64) -> [[f64; 3]; 3] {
    match g {
        0 => rpy(angle, 0.0, 0.0),
        1 => rpy(0.0, angle, 0.0),
        _ => rpy(0.0, 0.0, angle),
    }
}

fn invert3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    // The identity (no rotation or scale, most frames): the formula's result below, with the
    // signs of its zeros, without the arithmetic.
    const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    const IDENTITY_INVERSE: [[f64; 3]; 3] = [[1.0, -0.0, 0.0], [-0.0, 1.0, -0.0], [0.0, -0.0, 1.0]];
    if m.as_flattened().iter().zip(IDENTITY.as_flattened()).all(|(a, b)| a.to_bits() == b.to_bits()) {
        return Some(IDENTITY_INVERSE);
    }
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if det.abs() < 1e-15 {
        return None;
    }
    let c = |r0: usize, c0: usize, r1: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    Some([
        [c(1, 1, 2, 2) / det, -c(0, 1, 2, 2) / det, c(0, 1, 1, 2) / det],
        [-c(1, 0, 2, 2) / det, c(0, 0, 2, 2) / det, -c(0, 0, 1, 2) / det],
        [c(1, 0, 2, 1) / det, -c(0, 0, 2, 1) / det, c(0, 0, 1, 1) / det],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    const GEO: GeoAxes = [Some(0), Some(1), Some(2)];

    #[test]
    fn the_identity_shortcut_of_the_inverse_is_the_formula_bit_for_bit() {
        // The cofactor formula for the identity, written out: -(0·1 − 0·0) is −0.
        let m = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0f64]];
        let det = 1.0f64;
        let c = |r0: usize, c0: usize, r1: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
        let formula = [
            [c(1, 1, 2, 2) / det, -c(0, 1, 2, 2) / det, c(0, 1, 1, 2) / det],
            [-c(1, 0, 2, 2) / det, c(0, 0, 2, 2) / det, -c(0, 0, 1, 2) / det],
            [c(1, 0, 2, 1) / det, -c(0, 0, 2, 1) / det, c(0, 0, 1, 1) / det],
        ];
        let shortcut = invert3(&m).expect("regular");
        let bits = |a: &[[f64; 3]; 3]| a.as_flattened().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&shortcut), bits(&formula));
        // A negative zero in the matrix is no identity for the shortcut: the formula runs.
        let signed = [[1.0, -0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(invert3(&signed).expect("regular")[0][1].to_bits(), (0.0f64).to_bits());
    }

    fn p(x: f64, y: f64, z: f64) -> AxisVec {
        let mut v = [0.0; MAX_CHANNEL_AXES];
        v[..3].copy_from_slice(&[x, y, z]);
        v
    }

    fn close(a: &AxisVec, b: &AxisVec) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    #[test]
    fn a_positive_rotation_about_z_turns_x_towards_y() {
        let f = Frame::rotation(rpy(0.0, 0.0, 90.0));
        assert!(close(&f.apply(&GEO, &p(1.0, 0.0, 0.0)), &p(0.0, 1.0, 0.0)));
    }

    #[test]
    fn rpy_applies_x_first_then_y_then_z() {
        // Rx(90) takes Y to Z, Rz(90) leaves Z alone: Y → Z.
        let f = Frame::rotation(rpy(90.0, 0.0, 90.0));
        assert!(close(&f.apply(&GEO, &p(0.0, 1.0, 0.0)), &p(0.0, 0.0, 1.0)));
        // X: Rx leaves it, Rz(90) turns it to Y.
        assert!(close(&f.apply(&GEO, &p(1.0, 0.0, 0.0)), &p(0.0, 1.0, 0.0)));
    }

    #[test]
    fn an_additive_translation_after_a_rotation_moves_along_the_rotated_axes() {
        let rot = Frame::rotation(rpy(0.0, 0.0, 90.0));
        let f = rot.then(&Frame::translation(p(10.0, 0.0, 0.0)), &GEO);
        assert!(close(&f.apply(&GEO, &p(0.0, 0.0, 0.0)), &p(0.0, 10.0, 0.0)));
    }

    #[test]
    fn euler_turns_about_z_then_the_new_x_then_the_new_z() {
        // z = 90 takes X to Y; x = 90 then turns about that new X (= old Y): the new Z (old Z)
        // goes to the old -X... worked by hand: Rz(90)·Rx(90)·ez = Rz(90)·(0,-1,0) = (1,0,0).
        let r = euler(90.0, 0.0, 90.0);
        let f = Frame::rotation(r);
        assert!(close(&f.apply(&GEO, &p(0.0, 0.0, 1.0)), &p(1.0, 0.0, 0.0)));
        // y alone turns about Z like z alone.
        assert!(close(&Frame::rotation(euler(0.0, 30.0, 0.0)).apply(&GEO, &p(1.0, 0.0, 0.0)), &{
            let a = 30f64.to_radians();
            p(a.cos(), a.sin(), 0.0)
        }));
    }

    #[test]
    fn angles_read_back_in_both_conventions() {
        for (mode, a) in [(FrameAngles::Rpy, [10.0, -20.0, 30.0]), (FrameAngles::Euler, [40.0, -120.0, 75.0])] {
            let back = angles_of(mode, &rotation_of(mode, a));
            assert!(back.iter().zip(&a).all(|(x, y)| (x - y).abs() < 1e-9), "{mode:?}: {back:?}");
        }
        // Euler with x = 0: only z + y is defined, read back as z.
        let back = angles_of(FrameAngles::Euler, &euler(0.0, 20.0, 15.0));
        assert!((back[2] - 35.0).abs() < 1e-9 && back[0].abs() < 1e-9, "{back:?}");
    }

    #[test]
    fn unapply_inverts_apply() {
        let f = Frame::translation(p(5.0, -3.0, 2.0))
            .then(&Frame::rotation(rpy(10.0, 20.0, 30.0)), &GEO)
            .then(&Frame::scaling(&GEO, &[(0, 2.0), (1, -1.0), (2, 0.5)]), &GEO);
        let q = p(1.5, -7.0, 3.25);
        assert!(close(&f.unapply(&GEO, &f.apply(&GEO, &q)).unwrap(), &q));
    }
}
