//! Orientable toolholders (TCARR, REFERENCE §7): which holder is active, the angles it uses,
//! and what it writes — the tool length vector through the holder and `$P_PARTFRAME`.
//!
//! The math is the vector chain of [`crate::kinematics::orient`]; this module only fills a
//! [`Chain`] from the `$TC_CARR` data and applies its pose:
//! * T: `L_eff = −(l1 + R1·(l2 + R2·(l3 + t_c)))` (the chain's tip at M = 0), `o = R1·R2·b`;
//! * P: the tool is unchanged; the table moves the workpiece reference by
//!   `Δ = l2 + R1·(l3 + R2·l4)`, entered as the translation `Δ − Δ(0)` of `$P_PARTFRAME`,
//!   and PAROT adds the table rotation `R1·R2`;
//! * M: the tool part as T with axis 1 (`l1`, `l2`), the table part as P with axis 2
//!   (`Δ = l3 + R2·l4`).
//!
//! Conventions of this product where the sources are silent:
//! * Effective angles are `position − offset` ($TC_CARR24/25), sign +1: a table axis turning
//!   the workpiece is entered with its direction reversed, as the commissioning rules say.
//! * The active holder, its angles, TCOABS/TCOFR, PAROT and G group 53 survive reset and
//!   program end (MD20110 bit 14 taken as set), so a swivel made in MDA stays for the program
//!   that follows, like the system frames it wrote.

use crate::interp::frames::frame::Frame;
use crate::interp::modal::Plane;
use crate::kinematics::Vec3;
use crate::kinematics::orient::vec3::{normalize, sub, unit};
use crate::kinematics::orient::{Chain, ChainKind, Pose};
use crate::machine_data::{Carrier, CarrierKind};

/// G group 42: where the holder's angles come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TcoMode {
    /// TCOABS: the stored angles $TC_CARR13/14, or the axis positions if 21/22 name axes.
    #[default]
    Abs,
    /// TCOFR (Z), TCOFRZ, TCOFRY, TCOFRX: angles that turn the tool along this axis of the
    /// active frame (0 = X, 1 = Y, 2 = Z).
    Frame(usize),
}

/// G group 22: the tool compensation type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CutMode {
    /// CUT2D: the compensation plane follows the holder's tool orientation (default).
    #[default]
    Cut2d,
    /// CUT2DF: the compensation plane comes from the active frame.
    Cut2dF,
    /// CUT3DFS, CUT3DFF: 3D face milling, accepted; compensated like CUT2D / CUT2DF.
    Cut3dFs,
    Cut3dFf,
}

impl CutMode {
    /// True if the holder's tool orientation decides the compensation plane.
    pub fn follows_holder(self) -> bool {
        matches!(self, CutMode::Cut2d | CutMode::Cut3dFs)
    }
}

/// G group 53 (numbering of P7 p.1263): TOROTOF 1, TOROT 2, TOROTZ 3, TOROTY 4, TOROTX 5,
/// TOFRAME 6, TOFRAMEZ 7, TOFRAMEY 8, TOFRAMEX 9.
pub fn g53_code(name: &str) -> Option<i64> {
    Some(match name {
        "TOROTOF" => 1,
        "TOROT" => 2,
        "TOROTZ" => 3,
        "TOROTY" => 4,
        "TOROTX" => 5,
        "TOFRAME" => 6,
        "TOFRAMEZ" => 7,
        "TOFRAMEY" => 8,
        "TOFRAMEX" => 9,
        _ => return None,
    })
}

/// The toolholder state of block preparation.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Holder {
    /// Active toolholder number (0 = none).
    pub number: u32,
    pub tco: TcoMode,
    pub parot: bool,
    /// G group 53 code (1 = TOROTOF).
    pub g53: i64,
    pub cut: CutMode,
    /// Axis positions (degrees) the holder uses now: `$P_TCANG[1]`, `[2]`.
    pub angles: [f64; 2],
    /// The other valid pair of the last TCOFR/CYCLE800 solution: `$P_TCANG[3]`, `[4]`.
    pub second: Option<[f64; 2]>,
    /// `$P_TCSOL`: number of valid solutions (0..2) of the last computation.
    pub solutions: u8,
}

/// The basic tool orientation of the plane in the initial state: G17 ∥ Z, G18 ∥ Y, G19 ∥ X.
pub fn base_orientation(plane: Plane) -> Vec3 {
    match plane {
        Plane::G17 => unit(2),
        Plane::G18 => unit(1),
        Plane::G19 => unit(0),
    }
}

/// Number of rotary axes of `c`: the leading non-zero directions.
fn axis_count(c: &Carrier) -> usize {
    if !c.has_axis(0) {
        0
    } else if !c.has_axis(1) {
        1
    } else {
        2
    }
}

/// The vector chain of holder `c` with basic orientation `base`.
pub fn chain(c: &Carrier, base: Vec3) -> Chain {
    let kind = match c.kind {
        CarrierKind::Tool => ChainKind::Tool,
        CarrierKind::Part => ChainKind::Part,
        CarrierKind::Mixed => ChainKind::Mixed,
    };
    let z = unit(2);
    let v = [normalize(&c.v[0]).unwrap_or(z), normalize(&c.v[1]).unwrap_or(z), z];
    let [l1, l2, l3, l4] = c.l;
    Chain { kind, axes: axis_count(c), v, l1, l2, l3, l4, l23: [0.0; 3], base }
}

/// The pose of `c` at axis positions `pos` (degrees): effective angles `pos − offset`.
pub fn pose(c: &Carrier, ch: &Chain, pos: [f64; 2]) -> Pose {
    let a = |i: usize| if i < ch.axes { (pos[i] - c.offsets[i]).to_radians() } else { 0.0 };
    ch.pose(&[a(0), a(1), 0.0])
}

/// The tool length vector through the holder (tip → machine tool reference) for the plain
/// length `l` (tip → holder at zero angles). Unchanged for P.
pub fn tool_length(c: &Carrier, pos: [f64; 2], l: Vec3) -> Vec3 {
    let ch = chain(c, unit(2));
    let p = pose(c, &ch, pos);
    let t_c = l.map(|x| -x);
    match c.kind {
        CarrierKind::Tool => ch.tip(&[0.0; 3], &p, &t_c).map(|x| -x),
        CarrierKind::Part => l,
        // The tool part: a one-axis head chain with l1, l2 (the table part does not carry it).
        CarrierKind::Mixed => {
            let head = Chain { kind: ChainKind::Tool, axes: ch.axes.min(1), l3: [0.0; 3], ..ch.clone() };
            head.tip(&[0.0; 3], &head.pose(&[p_angle(c, &ch, pos, 0), 0.0, 0.0]), &t_c).map(|x| -x)
        }
    }
}

fn p_angle(c: &Carrier, ch: &Chain, pos: [f64; 2], i: usize) -> f64 {
    if i < ch.axes { (pos[i] - c.offsets[i]).to_radians() } else { 0.0 }
}

/// The table part of holder `c` at `pos`: the translation `Δ − Δ(0)` of the workpiece
/// reference and the table rotation (columns: images of the table's axes in the machine).
/// `None` for T.
pub fn table(c: &Carrier, pos: [f64; 2]) -> Option<(Vec3, [[f64; 3]; 3])> {
    let ch = chain(c, unit(2));
    // A part chain of the table axes alone: P uses both axes, M only axis 2 with l3, l4.
    let (table, angles) = match c.kind {
        CarrierKind::Tool => return None,
        CarrierKind::Part => (ch.clone(), [p_angle(c, &ch, pos, 0), p_angle(c, &ch, pos, 1)]),
        CarrierKind::Mixed => {
            let t = Chain {
                kind: ChainKind::Part,
                axes: usize::from(ch.axes == 2),
                v: [ch.v[1], ch.v[2], ch.v[2]],
                l2: c.l[2],
                l3: [0.0; 3],
                ..ch.clone()
            };
            (t, [p_angle(c, &ch, pos, 1), 0.0])
        }
    };
    let p = table.pose(&[angles[0], angles[1], 0.0]);
    let p0 = table.pose(&[0.0; 3]);
    let zero = [0.0; 3];
    let delta = sub(&table.linear(&zero, &p, &zero), &table.linear(&zero, &p0, &zero));
    // X = Δ + R1·R2·P: the images of the unit vectors.
    let cols: [Vec3; 3] = std::array::from_fn(|j| {
        let e = unit(j);
        sub(&table.linear(&e, &p, &zero), &table.linear(&zero, &p, &zero))
    });
    let rot = std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r]));
    Some((delta, rot))
}

/// The tool orientation in machine coordinates (the table does not turn the tool): T
/// `R1·R2·b`, P `b`, M `R1·b`.
pub fn machine_orientation(c: &Carrier, pos: [f64; 2], base: Vec3) -> Vec3 {
    let ch = chain(c, base);
    match c.kind {
        CarrierKind::Tool => ch.orientation(&pose(c, &ch, pos)),
        CarrierKind::Part => base,
        CarrierKind::Mixed => {
            let head = Chain { kind: ChainKind::Tool, axes: ch.axes.min(1), ..ch.clone() };
            head.orientation(&head.pose(&[p_angle(c, &ch, pos, 0), 0.0, 0.0]))
        }
    }
}

/// The orientation of the machine's axes as seen from the workpiece (table) coordinates:
/// the rotation whose columns are the images of X, Y, Z of the tool system — chain orientation
/// of each unit vector as basic orientation. For direct swivelling.
pub fn relative_rotation(c: &Carrier, pos: [f64; 2]) -> [[f64; 3]; 3] {
    let cols: [Vec3; 3] = std::array::from_fn(|j| {
        let ch = chain(c, unit(j));
        ch.orientation(&pose(c, &ch, pos))
    });
    std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r]))
}

/// Both solutions (axis positions in degrees) that orient the tool along `o`, given in the
/// workpiece-side coordinates ($P_PARTFRAME's parent for T, its child for P and M), each
/// placed by whole turns nearest `near` and checked against the holder's limits (30..33) and
/// Hirth teeth. Invalid ones are dropped; the list has 0..2 entries.
pub fn solve(c: &Carrier, o: Vec3, base: Vec3, near: [f64; 2]) -> Vec<[f64; 2]> {
    let ch = chain(c, base);
    if ch.axes == 0 {
        return Vec::new();
    }
    let Some(o) = normalize(&o) else { return Vec::new() };
    let hint = [p_angle(c, &ch, near, 0), p_angle(c, &ch, near, 1), 0.0];
    let Some(sols) = ch.solve(&o, &hint) else { return Vec::new() };
    let mut out: Vec<[f64; 2]> = Vec::new();
    for s in sols {
        let mut pos = [0.0; 2];
        let mut ok = true;
        for i in 0..2 {
            if i >= ch.axes {
                pos[i] = near[i];
                continue;
            }
            let raw = c.offsets[i] + s[i].to_degrees();
            let mut p = raw + ((near[i] - raw) / 360.0).round() * 360.0;
            if let Some(h) = c.hirth[i] {
                p = h.snap(p);
            }
            if let Some((lo, hi)) = c.limits[i] {
                let fit = [0.0, -360.0, 360.0, -720.0, 720.0]
                    .into_iter()
                    .map(|k| p + k)
                    .filter(|q| *q >= lo - 1e-9 && *q <= hi + 1e-9)
                    .min_by(|a, b| (a - near[i]).abs().total_cmp(&(b - near[i]).abs()));
                match fit {
                    Some(q) => p = q,
                    None => ok = false,
                }
            }
            pos[i] = p;
        }
        // Hirth rounding may leave the orientation; a rounded solution is still used.
        if ok && !out.iter().any(|q| (q[0] - pos[0]).abs() < 1e-9 && (q[1] - pos[1]).abs() < 1e-9) {
            out.push(pos);
        }
    }
    out
}

/// `$P_PARTFRAME` for holder `c` at `pos`: the table offset, rotated with PAROT.
pub fn part_frame(c: &Carrier, pos: [f64; 2], parot: bool, geo: &crate::interp::frames::frame::GeoAxes) -> Frame {
    let Some((delta, rot)) = table(c, pos) else { return Frame::identity() };
    let mut f = Frame::identity();
    for (g, k) in geo.iter().enumerate() {
        if let Some(k) = k {
            f.trans[*k] = delta[g];
        }
    }
    if parot {
        f.lin = rot;
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::MachineData;

    fn carrier(text: &str) -> Carrier {
        let mut md = MachineData::default();
        md.apply_text(&format!("$MN_MM_NUM_TOOL_CARRIER=1\n{text}")).unwrap();
        md.carriers()[&1].clone()
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    #[test]
    fn the_w1_table_example_moves_the_workpiece_zero() {
        // W1 p.4-3: table axis along +Y, l4 = (0, 0, 15), B = 45°: Δ − l4 = (15 sin 45°, 0,
        // −15 (1 − cos 45°)).
        let c = carrier("$TC_CARR23[1]=\"P\"\n$TC_CARR8[1]=1\n$TC_CARR20[1]=15");
        let (d, _) = table(&c, [45.0, 0.0]).unwrap();
        let s = 45f64.to_radians().sin();
        assert!(close(&d, &[15.0 * s, 0.0, -15.0 * (1.0 - s)]), "{d:?}");
        assert!(close(&d, &[10.606601717798213, 0.0, -4.393398282201787]));
    }

    #[test]
    fn a_head_turns_the_tool_length_about_its_pivot() {
        // B head about Y, pivot 150 above the reference (l1 = (0,0,150), l3 = −l1), tool 100:
        // at B = 90° the tip lies 150 + 100 from the pivot along +X... in the tool direction
        // R_y(90°)·(−Z) = −X: L_eff = −(l1 + R·(l3 − L)) = −(0,0,150) − R·(0,0,−250).
        let c = carrier("$TC_CARR8[1]=1\n$TC_CARR3[1]=150\n$TC_CARR17[1]=-150");
        let l = tool_length(&c, [90.0, 0.0], [0.0, 0.0, 100.0]);
        assert!(close(&l, &[250.0, 0.0, -150.0]), "{l:?}");
        assert!(close(&tool_length(&c, [0.0, 0.0], [0.0, 0.0, 100.0]), &[0.0, 0.0, 100.0]));
        assert!(close(&machine_orientation(&c, [90.0, 0.0], unit(2)), &[1.0, 0.0, 0.0]));
    }

    #[test]
    fn both_solutions_respect_the_limits() {
        // CA head: C about Z, A about X, A within −90..90.
        let c = carrier("$TC_CARR9[1]=1\n$TC_CARR10[1]=1\n$TC_CARR31[1]=-90\n$TC_CARR33[1]=90");
        let o = [0.0, -(30f64.to_radians().sin()), 30f64.to_radians().cos()];
        let s = solve(&c, o, unit(2), [0.0, 0.0]);
        assert_eq!(s.len(), 2, "{s:?}");
        for p in &s {
            assert!(close(&machine_orientation(&c, *p, unit(2)), &o), "{p:?}");
        }
        // R_x(30°)·Z = (0, −sin 30°, cos 30°): C = 0, A = 30 or C = 180, A = −30.
        let turn = |p: &[f64; 2]| [(p[0] + 180.0).rem_euclid(360.0) - 180.0, p[1]];
        assert!(s.iter().any(|p| close(&turn(p), &[0.0, 30.0])), "{s:?}");
        assert!(s.iter().any(|p| close(&turn(p), &[-180.0, -30.0])), "{s:?}");
        let narrow = carrier("$TC_CARR9[1]=1\n$TC_CARR10[1]=1\n$TC_CARR31[1]=0\n$TC_CARR33[1]=90");
        let only = solve(&narrow, o, unit(2), [0.0, 0.0]);
        assert!(only.len() == 1 && close(&only[0], &[0.0, 30.0]), "{only:?}");
    }
}
