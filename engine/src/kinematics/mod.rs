//! Kinematic transformations: the map between the Cartesian basic coordinate system (BCS) in
//! which a program's contour is interpolated and the machine axes that realise it.
//!
//! Input: a transformation data set from the machine data ([`TrafoDataSet`]) plus the selection
//! parameters of the program (TRACYL diameter, TRAANG angle). Output: a value implementing
//! [`Transformation`]: forward (machine → BCS), inverse (BCS → machine, continuous with the
//! previous machine position) and what it knows about poles and unreachable regions.
//!
//! Positions on both sides are [`AxisVec`]s indexed by channel axis. While a transformation is
//! active, the channel axis that a geometry axis is assigned to by `$MC_TRAFO_GEOAX_ASSIGN_TAB_n`
//! holds that Cartesian coordinate on the BCS side (TRANSMIT's Y lives in the rotary axis'
//! slot); every axis the transformation does not touch passes through unchanged. One file per
//! transformation; [`plan`] turns a BCS block into moves that respect every machine axis' limits.

pub mod orient;
pub mod plan;
mod pole_approach;
mod pole_turn;
mod seventh;
mod traang;
mod tracon;
mod tracyl;
mod transmit;
mod traori;

pub use orient::stepped::AngleMemo;
pub use traang::Traang;
pub use tracon::Tracon;
pub use tracyl::Tracyl;
pub use transmit::Transmit;
pub use traori::Traori;

use crate::machine_data::{MachineConfig, TrafoDataSet, TrafoKind, TrafoParams};
use crate::motion::{AxisVec, Path};

/// A 3-vector by geometry axis index (X, Y, Z of the transformation).
pub type Vec3 = [f64; 3];

/// Radius around the TRANSMIT pole within which a point counts as "in the pole" (mm).
pub const POLE_EPS: f64 = 1e-6;

/// A BCS point the machine cannot reach (TRANSMIT's unmachinable cylinder).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("point lies in the working-area limitation of the transformation")]
pub struct Unreachable;

/// One kinematic transformation, built from machine data. The planner never sees it: the
/// interpreter uses it to plan blocks in the BCS, the channel to map each IPO sample.
pub trait Transformation {
    /// The NC word that selects it (`TRANSMIT`, `TRACYL`, `TRAANG`).
    fn name(&self) -> &'static str;
    /// `$MC_TRAFO_TYPE_n`.
    fn trafo_type(&self) -> u32;
    /// Channel axis of the 1st/2nd/3rd geometry axis while active.
    fn geo_slots(&self) -> [Option<usize>; 3];
    /// Channel axes of the machine axes the transformation moves (`TRAFO_AXES_IN_n`).
    fn machine_slots(&self) -> Vec<usize>;
    /// The rotary axis whose own name is blocked while active (TRANSMIT, TRACYL).
    fn rotary_slot(&self) -> Option<usize> {
        None
    }
    /// Machine → BCS for tool length `tool` (by geometry axis). Other slots are copied.
    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec);
    /// BCS → machine; among several solutions (pole side, rotary turns) the one closest to
    /// `prev` in axis travel time. Other slots are copied.
    fn inverse(&self, bcs: &AxisVec, prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable>;
    /// Rejects a block whose path enters an unreachable region.
    fn check_path(&self, _path: &Path, _tool: &Vec3) -> Result<(), Unreachable> {
        Ok(())
    }
    /// Path parameters (0..=1) at which the path passes through a singular point (a pole),
    /// where the machine solution may change branch or need an inserted rotation.
    fn poles(&self, _path: &Path, _tool: &Vec3) -> Vec<f64> {
        Vec::new()
    }
    /// Path parameters where machine axis rates peak (closest approach to a pole), so the
    /// velocity planning samples them.
    fn critical_params(&self, _path: &Path, _tool: &Vec3) -> Vec<f64> {
        Vec::new()
    }
    /// Share of a machine axis' velocity and acceleration the planning may use (TRAANG keeps a
    /// reserve on the parallel axis).
    fn limit_share(&self, _slot: usize) -> f64 {
        1.0
    }
    /// The machine stands on the side of a pole its machine data exclude (TRANSMIT's
    /// `POLE_SIDE_FIX`): a program selection there is allowed, a persistent one is not (21617).
    fn on_excluded_pole_side(&self, _machine: &AxisVec, _tool: &Vec3) -> bool {
        false
    }
    /// Channel axes of the orientation axes (1st, 2nd, 3rd rotary axis of an orientation
    /// transformation). On the BCS side these slots hold the rotary axis positions themselves,
    /// so direct rotary-axis programming and ORIAXES interpolation pass straight through.
    fn orientation_slots(&self) -> [Option<usize>; 3] {
        [None; 3]
    }
    /// Tool orientation in the BCS (unit vector from the tool tip towards the holder) at
    /// machine position `machine`; `None` for transformations that do not orient the tool.
    fn orientation(&self, _machine: &AxisVec) -> Option<Vec3> {
        None
    }
    /// Writes into the orientation slots of `axes` the rotary axis positions that give BCS
    /// orientation `o`: of the candidate solutions the one within the axis limits that is
    /// nearest to `prev` (modulo axes unwrapped to stay continuous). Other slots are untouched.
    fn orientation_axes(&self, _o: &Vec3, _prev: &AxisVec, _axes: &mut AxisVec) -> Result<(), Unreachable> {
        Err(Unreachable)
    }
    /// [`Transformation::orientation_axes`] then [`Transformation::inverse`] in place: `axes`
    /// holds the BCS position on entry and the machine position on return. Once per IPO cycle
    /// of an oriented move, so a transformation may fuse the two (TRAORI reuses the solved angles).
    fn inverse_oriented(&self, o: &Vec3, prev: &AxisVec, tool: &Vec3, axes: &mut AxisVec) -> Result<(), Unreachable> {
        self.orientation_axes(o, prev, axes)?;
        let bcs = *axes;
        self.inverse(&bcs, prev, tool, axes)
    }
    /// [`Transformation::inverse_oriented`] for consecutive IPO cycles: `memo` carries the
    /// last cycle's solve so TRAORI steps its angles instead of computing them afresh (same
    /// result within 1e-12 rad). Others ignore it.
    fn inverse_oriented_stepped(
        &self,
        o: &Vec3,
        prev: &AxisVec,
        tool: &Vec3,
        axes: &mut AxisVec,
        _memo: &mut AngleMemo,
    ) -> Result<(), Unreachable> {
        self.inverse_oriented(o, prev, tool, axes)
    }
}

/// Any of the modelled transformations, as a plain value (cheap to clone and compare).
#[derive(Debug, Clone, PartialEq)]
pub enum AnyTrafo {
    Transmit(Transmit),
    Tracyl(Tracyl),
    Traang(Traang),
    /// Boxed: the orientation chain is several times larger than the other transformations.
    Traori(Box<Traori>),
    Tracon(Box<Tracon>),
}

macro_rules! dispatch {
    ($self:ident, $t:ident => $e:expr) => {
        match $self {
            AnyTrafo::Transmit($t) => $e,
            AnyTrafo::Tracyl($t) => $e,
            AnyTrafo::Traang($t) => $e,
            AnyTrafo::Traori($t) => $e,
            AnyTrafo::Tracon($t) => $e,
        }
    };
}

impl Transformation for AnyTrafo {
    fn name(&self) -> &'static str {
        dispatch!(self, t => t.name())
    }
    fn trafo_type(&self) -> u32 {
        dispatch!(self, t => t.trafo_type())
    }
    fn geo_slots(&self) -> [Option<usize>; 3] {
        dispatch!(self, t => t.geo_slots())
    }
    fn machine_slots(&self) -> Vec<usize> {
        dispatch!(self, t => t.machine_slots())
    }
    fn rotary_slot(&self) -> Option<usize> {
        dispatch!(self, t => t.rotary_slot())
    }
    fn forward(&self, machine: &AxisVec, tool: &Vec3, bcs: &mut AxisVec) {
        dispatch!(self, t => t.forward(machine, tool, bcs))
    }
    fn inverse(&self, bcs: &AxisVec, prev: &AxisVec, tool: &Vec3, machine: &mut AxisVec) -> Result<(), Unreachable> {
        dispatch!(self, t => t.inverse(bcs, prev, tool, machine))
    }
    fn check_path(&self, path: &Path, tool: &Vec3) -> Result<(), Unreachable> {
        dispatch!(self, t => t.check_path(path, tool))
    }
    fn poles(&self, path: &Path, tool: &Vec3) -> Vec<f64> {
        dispatch!(self, t => t.poles(path, tool))
    }
    fn critical_params(&self, path: &Path, tool: &Vec3) -> Vec<f64> {
        dispatch!(self, t => t.critical_params(path, tool))
    }
    fn limit_share(&self, slot: usize) -> f64 {
        dispatch!(self, t => t.limit_share(slot))
    }
    fn on_excluded_pole_side(&self, machine: &AxisVec, tool: &Vec3) -> bool {
        dispatch!(self, t => t.on_excluded_pole_side(machine, tool))
    }
    fn orientation_slots(&self) -> [Option<usize>; 3] {
        dispatch!(self, t => t.orientation_slots())
    }
    fn orientation(&self, machine: &AxisVec) -> Option<Vec3> {
        dispatch!(self, t => t.orientation(machine))
    }
    fn orientation_axes(&self, o: &Vec3, prev: &AxisVec, axes: &mut AxisVec) -> Result<(), Unreachable> {
        dispatch!(self, t => t.orientation_axes(o, prev, axes))
    }
    fn inverse_oriented(&self, o: &Vec3, prev: &AxisVec, tool: &Vec3, axes: &mut AxisVec) -> Result<(), Unreachable> {
        dispatch!(self, t => t.inverse_oriented(o, prev, tool, axes))
    }
    fn inverse_oriented_stepped(
        &self,
        o: &Vec3,
        prev: &AxisVec,
        tool: &Vec3,
        axes: &mut AxisVec,
        memo: &mut AngleMemo,
    ) -> Result<(), Unreachable> {
        dispatch!(self, t => t.inverse_oriented_stepped(o, prev, tool, axes, memo))
    }
}

/// Parameters given with the selection in the program.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SelectArgs {
    /// TRACYL working diameter d.
    pub diameter: Option<f64>,
    /// TRACYL 3rd parameter k (type 514): groove-wall offset on/off.
    pub groove_wall: Option<bool>,
    /// TRAANG angle α; `None` = `$MC_TRAANG_ANGLE_t`.
    pub angle: Option<f64>,
    /// TRAORI(n, x, y, z): basic tool orientation given with the selection (generic types);
    /// `None` = the tool's or `$MC_TRAFO5_BASE_ORIENT_n`.
    pub base_orient: Option<Vec3>,
    /// The active cutting edge's orientation `$TC_DPV3..5` and normal `$TC_DPVN3..5` by
    /// geometry axis, at the selection: the basic orientation of a generic TRAORI when no
    /// vector is passed (F2 §3.9.1).
    pub tool_orient: Option<Vec3>,
    pub tool_normal: Option<Vec3>,
    /// TRACON(n, p1, p2, ...): the parameters for the chain's members, first member first
    /// (TRACYL: the diameter, TRAANG: the angle; TRANSMIT and TRAORI take none).
    pub chain: [Option<f64>; 3],
}

/// Why a selection cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BuildError {
    #[error("{0}")]
    Value(String),
}

/// The transformation of data set `set` with the program's selection parameters.
pub fn build(set: &TrafoDataSet, cfg: &MachineConfig, args: &SelectArgs) -> Result<AnyTrafo, BuildError> {
    Ok(match set.kind {
        TrafoKind::Transmit => AnyTrafo::Transmit(Transmit::new(set, cfg)),
        TrafoKind::Tracyl => AnyTrafo::Tracyl(Tracyl::new(set, args)?),
        TrafoKind::Traang => AnyTrafo::Traang(Traang::new(set, args)?),
        TrafoKind::Traori => AnyTrafo::Traori(Box::new(Traori::new(set, cfg, args)?)),
        TrafoKind::Tracon => {
            let TrafoParams::Tracon { members } = set.params else { unreachable!("TRACON data set") };
            let member = |n: usize| cfg.trafos.iter().find(|s| s.number == n).expect("checked at activation");
            let (first, second) = (member(members[0]), member(members[1]));
            let mut params = args.chain.into_iter();
            let first_args = match first.kind {
                TrafoKind::Tracyl => SelectArgs { diameter: params.next().flatten(), ..SelectArgs::default() },
                TrafoKind::Traang => SelectArgs { angle: params.next().flatten(), ..SelectArgs::default() },
                _ => SelectArgs::default(),
            };
            let second_args = SelectArgs { angle: params.next().flatten(), ..SelectArgs::default() };
            AnyTrafo::Tracon(Box::new(Tracon {
                first: build(first, cfg, &first_args)?,
                second: build(second, cfg, &second_args)?,
            }))
        }
    })
}

/// An active transformation: the kinematics, the tool length it includes and its data set.
#[derive(Debug, Clone, PartialEq)]
pub struct ActiveTrafo {
    pub trafo: AnyTrafo,
    /// Tool length vector (tip → reference) by geometry axis, taken into the transformation.
    pub tool: Vec3,
    /// Data-set number n of `$MC_TRAFO_TYPE_n`.
    pub number: usize,
}

impl ActiveTrafo {
    /// This transformation with the tool lengthened by the online tool offset `toff` (tool
    /// directions X, Y, Z, `$AA_TOFF`): how the main run maps positions while it is in force.
    pub fn lengthened(&self, toff: &Vec3) -> ActiveTrafo {
        let mut t = self.clone();
        for (l, o) in t.tool.iter_mut().zip(toff) {
            *l += o;
        }
        t
    }

    pub fn forward(&self, machine: &AxisVec) -> AxisVec {
        let mut out = *machine;
        self.trafo.forward(machine, &self.tool, &mut out);
        out
    }

    pub fn inverse(&self, bcs: &AxisVec, prev: &AxisVec) -> Result<AxisVec, Unreachable> {
        let mut out = *bcs;
        self.trafo.inverse(bcs, prev, &self.tool, &mut out)?;
        Ok(out)
    }

    /// Like [`ActiveTrafo::inverse`], with the tool orientation `o` (BCS) deciding the rotary
    /// axes instead of the orientation slots of `bcs`.
    pub fn inverse_oriented(&self, bcs: &AxisVec, o: &Vec3, prev: &AxisVec) -> Result<AxisVec, Unreachable> {
        let mut out = *bcs;
        self.trafo.inverse_oriented(o, prev, &self.tool, &mut out)?;
        Ok(out)
    }

    /// [`ActiveTrafo::inverse_oriented`] for consecutive points of one path, the solve stepped
    /// from the last point's in `memo` (see [`Transformation::inverse_oriented_stepped`]).
    pub fn inverse_oriented_stepped(
        &self,
        bcs: &AxisVec,
        o: &Vec3,
        prev: &AxisVec,
        memo: &mut AngleMemo,
    ) -> Result<AxisVec, Unreachable> {
        let mut out = *bcs;
        self.trafo.inverse_oriented_stepped(o, prev, &self.tool, &mut out, memo)?;
        Ok(out)
    }
}

/// The axis roles TRANSMIT and TRACYL share: a radial linear axis, the rotary axis, an
/// optional axial axis and an optional real supplementary axis (257, 513, 514), with the base
/// tool. Each role is (channel axis, geometry index of its Cartesian axis).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RotaryRoles {
    pub radial: (usize, usize),
    pub rotary: (usize, usize),
    pub axial: Option<(usize, usize)>,
    pub extra: Option<usize>,
    pub geo: [Option<usize>; 3],
    pub base_tool: Vec3,
}

impl RotaryRoles {
    /// The roles of `set` (checked at activation); `with_extra` takes role [3] as the real
    /// supplementary axis.
    pub fn new(set: &TrafoDataSet, with_extra: bool, base_tool: Vec3) -> RotaryRoles {
        RotaryRoles {
            radial: role_geo(set, 0).expect("checked at activation"),
            rotary: role_geo(set, 1).expect("checked at activation"),
            axial: role_geo(set, 2),
            extra: if with_extra { set.axes_in[3] } else { None },
            geo: set.geo_axes,
            base_tool,
        }
    }

    /// `B − L` along the Cartesian axis of geometry index `g`.
    pub fn off(&self, tool: &Vec3, g: usize) -> f64 {
        self.base_tool[g] - tool[g]
    }

    /// Offset of the tool tip across the radial line through the rotary axis (TRANSMIT's
    /// lateral offset `e`, TRACYL's tangential offset): base tool minus tool along the rotary
    /// role's Cartesian axis, plus the real supplementary axis.
    pub fn side_offset(&self, pos: &AxisVec, tool: &Vec3) -> f64 {
        self.off(tool, self.rotary.1) + self.extra.map_or(0.0, |k| pos[k])
    }

    /// The channel axes the transformation drives.
    pub fn machine_slots(&self) -> Vec<usize> {
        [Some(self.radial.0), Some(self.rotary.0), self.axial.map(|a| a.0)].into_iter().flatten().collect()
    }
}

/// Where a role of `TRAFO_AXES_IN_n` has its Cartesian coordinate: the channel axis and the
/// geometry axis index that share it.
pub(crate) fn role_geo(set: &TrafoDataSet, role: usize) -> Option<(usize, usize)> {
    let slot = set.axes_in[role]?;
    let g = set.geo_axes.iter().position(|a| *a == Some(slot))?;
    Some((slot, g))
}

/// Local minima of the distance of the path from the axis through the origin of the plane of
/// channel axes `x`, `y`: `(u, r)` pairs, endpoints included. Dense sampling followed by a
/// golden-section refinement, so it works for lines, arcs in any plane and helices alike.
pub(crate) fn radial_minima(path: &Path, x: usize, y: usize) -> Vec<(f64, f64)> {
    const N: usize = 256;
    let mut p = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
    let mut r = |u: f64| -> f64 {
        path.at(u, &mut p);
        p[x].hypot(p[y])
    };
    let samples: Vec<f64> = (0..=N).map(|i| r(i as f64 / N as f64)).collect();
    let mut out = Vec::new();
    for i in 0..=N {
        let left = if i == 0 { f64::INFINITY } else { samples[i - 1] };
        let right = if i == N { f64::INFINITY } else { samples[i + 1] };
        if samples[i] > left || samples[i] > right {
            continue;
        }
        let (mut a, mut b) = ((i.saturating_sub(1)) as f64 / N as f64, ((i + 1).min(N)) as f64 / N as f64);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..80 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if r(c) <= r(d) {
                b = d;
            } else {
                a = c;
            }
        }
        let u = 0.5 * (a + b);
        let (u, ru) = [(u, r(u)), (i as f64 / N as f64, samples[i])]
            .into_iter()
            .min_by(|p, q| p.1.total_cmp(&q.1))
            .expect("two candidates");
        if out.last().is_none_or(|&(v, _): &(f64, f64)| (u - v).abs() > 1e-9) {
            out.push((u, ru));
        }
    }
    out
}

/// `angle` (degrees) shifted by whole turns to lie closest to `near`.
pub(crate) fn unwrap_near(angle: f64, near: f64) -> f64 {
    // Within half a turn the rounding gives ±0 turns: skip it (`round` is a library call).
    if (near - angle).abs() < 180.0 {
        return angle;
    }
    angle + 360.0 * ((near - angle) / 360.0).round()
}
