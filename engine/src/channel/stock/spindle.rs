//! The tool against a blank under TRANSMIT, TRACYL and TRAANG, for `cut.rs`.
//!
//! On a lathe with driven tools the blank is clamped in the work spindle, so it turns with C.
//! The stock then lives in the workpiece's own frame, the frame TRANSMIT programs in: with `q`
//! the tool tip in the non-turning frame on the spindle axis (x radial, y the tool's lateral
//! offset, z axial; `q = M + B − L` as in `kinematics/transmit.rs`, B only while the
//! transformation is active) and `φ = s·(C − c0)`, the tip in the workpiece is `R_z(φ)·q` and
//! the tool's axis (along its length vector L) turns with it. This holds whether TRANSMIT or
//! TRACYL moves C or the program positions C itself: the part is carried either way.
//!
//! The turned profile (axisymmetric) becomes Z-dexels about the spindle axis at the first cut
//! under TRANSMIT/TRACYL (`crate::stock::dexel::turned`); afterwards a turning insert cutting while
//! the work spindle turns in speed control removes a ring of that grid (`ring`).
//!
//! TRAANG does not turn the part: the tip is the transformation's Cartesian BCS position
//! (the inclined axis resolved into X and Z). A TRACON chain is its first member working on the
//! position between the members (`Tracon::intermediate`: TRAANG's Cartesian slide), so a
//! TRANSMIT chained before a slant bed's TRAANG cuts as TRANSMIT does. A TRANSMIT/TRACYL whose
//! rotary axis is a table's, not a spindle's, is `table.rs`'s; one whose rotary axis is
//! neither (or a chain starting with TRAORI) is still skipped (counted).

use super::pose::ToolPose;
use crate::channel::Channel;
use crate::kinematics::{AnyTrafo, Transformation};
use crate::machine_data::TrafoParams;
use crate::motion::AxisVec;
use crate::stock::Stock;

/// The work spindle the blank is clamped in, with the axes of the machine's TRANSMIT or TRACYL
/// data set: `(channel slot, geometry index)` of each role.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::channel) struct SpindleMount {
    rotary: usize,
    radial: (usize, usize),
    /// Geometry index of the rotary role's Cartesian axis: the tool's lateral offset.
    lateral: usize,
    axial: (usize, usize),
    /// A real axis perpendicular to both (TRANSMIT 257, TRACYL 513/514).
    extra: Option<usize>,
    base: [f64; 3],
    rot_offset: f64,
    sign: f64,
}

/// How `cut.rs` finds the tool this cycle.
pub(in crate::channel) enum Mounted {
    /// No transformation of concern: `pose.rs` (3-axis, TRAORI chains, the profile).
    Plain,
    /// The tool in the stock's frame; `ring`: a turning cut of the turning part.
    At(ToolPose, bool),
    /// A motion the stock does not follow.
    Skip,
}

impl SpindleMount {
    /// `R_z(φ)` of the angle `c` of the rotary axis (degrees).
    fn rotation(&self, c: f64) -> impl Fn([f64; 3]) -> [f64; 3] {
        let (s, co) = (self.sign * (c - self.rot_offset)).to_radians().sin_cos();
        move |v: [f64; 3]| [v[0] * co - v[1] * s, v[0] * s + v[1] * co, v[2]]
    }

    /// The tool in the non-turning frame: tip `q`, length vector `(x, y, z)`; `with_base`
    /// while the transformation (and so its base tool) is active.
    fn unturned(&self, machine: &AxisVec, tool: [f64; 3], with_base: bool) -> ([f64; 3], [f64; 3]) {
        let off = |g: usize| if with_base { self.base[g] } else { 0.0 } - tool[g];
        let q = [
            machine[self.radial.0] + off(self.radial.1),
            off(self.lateral) + self.extra.map_or(0.0, |k| machine[k]),
            machine[self.axial.0] + off(self.axial.1),
        ];
        (q, [tool[self.radial.1], tool[self.lateral], tool[self.axial.1]])
    }
}

impl Channel {
    /// The spindle a blank is clamped in: the first TRANSMIT or TRACYL data set whose rotary
    /// axis is a spindle and whose radial and axial axes are the machine's own X and Z (a
    /// lathe); `None` on other machines.
    pub(in crate::channel) fn stock_spindle_mount(&self) -> Option<SpindleMount> {
        let geo = self.cfg.geo_axes;
        self.cfg.trafos.iter().find_map(|set| {
            let (rot_offset, sign_plus, base, with_extra) = match set.params {
                TrafoParams::Transmit { rot_offset, sign_plus, base_tool, .. } => {
                    (rot_offset, sign_plus, base_tool, set.trafo_type == 257)
                }
                TrafoParams::Tracyl { rot_offset, sign_plus, base_tool, .. } => {
                    (rot_offset, sign_plus, base_tool, set.trafo_type != 512)
                }
                _ => return None,
            };
            let role = |n| crate::kinematics::role_geo(set, n);
            let (radial, rotary, axial) = (role(0)?, role(1)?, role(2)?);
            if geo[0] != Some(radial.0) || geo[2] != Some(axial.0) || self.cfg.axis(rotary.0).spindle.is_none() {
                return None;
            }
            Some(SpindleMount {
                rotary: rotary.0,
                radial,
                lateral: rotary.1,
                axial,
                extra: if with_extra { set.axes_in[3] } else { None },
                base,
                rot_offset,
                sign: if sign_plus { 1.0 } else { -1.0 },
            })
        })
    }

    /// The angle of the mount's spindle now: its axis position in position control or under
    /// the transformation, else the speed-controlled spindle's own angle; and whether it turns
    /// in speed control.
    fn mount_angle(&self, m: &SpindleMount) -> (f64, bool) {
        match self.spindles.iter().find(|s| s.axis == m.rotary) {
            Some(s) if !s.axis_mode && self.trafo.is_none() => (s.position, s.is_turning()),
            _ => (self.machine[m.rotary], false),
        }
    }

    /// The tool tip at machine position `machine` in the frame of a milled blank clamped in the
    /// spindle `m` (no transformation active; the probe of MEAS): `R_z(φ)·q` with the spindle's
    /// angle now, its position from `machine` while it is an axis.
    pub(in crate::channel) fn mount_tip_at(
        &self,
        m: &SpindleMount,
        machine: &AxisVec,
        plain_tool: [f64; 3],
    ) -> [f64; 3] {
        let c = match self.spindles.iter().find(|s| s.axis == m.rotary) {
            Some(s) if !s.axis_mode => s.position,
            _ => machine[m.rotary],
        };
        m.rotation(c)(m.unturned(machine, plain_tool, false).0)
    }

    /// The blank's placement in the workpiece frame of a spindle standing at its current angle
    /// (a blank defined on a lathe with a Y axis is milled as dexels that turn with C).
    pub(in crate::channel) fn mount_placement(
        &self,
        p: crate::stock::blank::Placement,
    ) -> crate::stock::blank::Placement {
        let Some(m) = self.stock_spindle_mount() else { return p };
        let rot = m.rotation(self.mount_angle(&m).0);
        let cols: [[f64; 3]; 3] = std::array::from_fn(|c| rot([p.lin[0][c], p.lin[1][c], p.lin[2][c]]));
        crate::stock::blank::Placement {
            lin: std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r])),
            trans: rot(p.trans),
        }
    }

    /// The tool this cycle under the active transformation or on the spindle the blank turns
    /// with; `tool` is the length vector by geometry axis without a transformation.
    pub(in crate::channel) fn stock_mounted_pose(&mut self, plain_tool: [f64; 3]) -> Mounted {
        let toff = self.toff.current;
        let run_mount = self.stock.as_ref().and_then(|r| r.mount);
        let Some(active) = self.trafo.as_ref() else {
            return match (run_mount, self.stock.as_ref().map(|r| &r.stock)) {
                (Some(m), Some(Stock::Milling(_))) => {
                    let (c, ring) = self.mount_angle(&m);
                    let (q, l) = m.unturned(&self.machine, plain_tool, false);
                    Mounted::At(
                        pose(if ring { q } else { m.rotation(c)(q) }, if ring { l } else { m.rotation(c)(l) }),
                        ring,
                    )
                }
                _ => Mounted::Plain,
            };
        };
        let tool = std::array::from_fn(|g| active.tool[g] + toff[g]);
        match &active.trafo {
            AnyTrafo::Traori(_) => Mounted::Plain,
            AnyTrafo::Traang(_) => cartesian_pose(&active.trafo, &self.machine, tool),
            AnyTrafo::Transmit(_) | AnyTrafo::Tracyl(_) => {
                let rotary = active.trafo.rotary_slot();
                let machine = self.machine;
                self.polar_pose(run_mount, rotary, &machine, tool)
            }
            // A chain: its first member works on the position between the members (the
            // Cartesian slide of a slant bed), as it would on the machine's own axes.
            AnyTrafo::Tracon(t) => match &t.first {
                AnyTrafo::Traang(_) => cartesian_pose(&active.trafo, &self.machine, tool),
                AnyTrafo::Transmit(_) | AnyTrafo::Tracyl(_) => {
                    let (rotary, mid) = (t.first.rotary_slot(), t.intermediate(&self.machine));
                    self.polar_pose(run_mount, rotary, &mid, tool)
                }
                _ => Mounted::Skip,
            },
        }
    }

    /// The tool under TRANSMIT or TRACYL whose rotary axis is `rotary`, from the positions
    /// `machine` of the axes it moves: in the turning part's frame if that axis is the spindle
    /// the blank is clamped in (the profile made dexels first), else skipped.
    fn polar_pose(
        &mut self,
        mount: Option<SpindleMount>,
        rotary: Option<usize>,
        machine: &AxisVec,
        tool: [f64; 3],
    ) -> Mounted {
        let Some(m) = mount.filter(|m| rotary == Some(m.rotary)) else {
            return Mounted::Skip;
        };
        if !self.turn_stock_into_dexels() {
            return Mounted::Skip;
        }
        let rot = m.rotation(machine[m.rotary]);
        let (q, l) = m.unturned(machine, tool, true);
        Mounted::At(pose(rot(q), rot(l)), false)
    }

    /// Makes a turned profile the dexels of the part (once, at the first milling cut under
    /// TRANSMIT/TRACYL); false if the grid would be too large (the cut is skipped).
    fn turn_stock_into_dexels(&mut self) -> bool {
        if !matches!(self.stock.as_ref().map(|r| &r.stock), Some(Stock::Turning(_))) {
            return true;
        }
        self.flush_stock_now();
        let res = self.stock_options.resolution;
        let Some(run) = self.stock.as_mut() else { return false };
        let Stock::Turning(p) = &run.stock else { return true };
        let Ok(grid) = crate::stock::dexel::DexelGrid::from_profile(p, res) else { return false };
        // The removed volume goes on from where it was: the grid samples the same part.
        run.shift_initial_volume(grid.volume() - p.volume());
        run.stock = Stock::Milling(grid);
        run.restart_tiles();
        true
    }
}

/// The Cartesian tool tip of a transformation that does not turn the part (TRAANG): its BCS.
fn cartesian_pose(trafo: &AnyTrafo, machine: &AxisVec, tool: [f64; 3]) -> Mounted {
    let mut bcs = *machine;
    trafo.forward(machine, &tool, &mut bcs);
    let geo = trafo.geo_slots();
    let tip = std::array::from_fn(|g| geo[g].map_or(0.0, |k| bcs[k]));
    Mounted::At(ToolPose { tip, axis: [0.0, 0.0, 1.0], length: norm(tool) }, false)
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The pose of a tip with the length vector `l` (its axis; +Z without length).
fn pose(tip: [f64; 3], l: [f64; 3]) -> ToolPose {
    let n = norm(l);
    let axis = if n > 1e-9 { l.map(|c| c / n) } else { [0.0, 0.0, 1.0] };
    ToolPose { tip, axis, length: n }
}
