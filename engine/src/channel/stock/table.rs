//! The blank on a rotary table that no orientation transformation describes, for
//! `cut.rs`, `probe.rs` and the state's stock frame.
//!
//! A milling machine whose TRACYL (or TRANSMIT) data set names a rotary axis that is not a
//! spindle carries the cylinder on a rotary table (`tracyl-xyzac`: a trunnion A about X holding
//! the table C). The blank is clamped on that table, so it turns with C and tilts with A (or B)
//! whether TRACYL moves them or the program positions them: the stock lives in the table's
//! frame, which is the machine frame while every table axis stands at zero (the blank of
//! `WORKPIECE` or `PUT .../stock` is given in that frame, as on a TRAORI table).
//!
//! The machine data say nothing of the table's geometry besides the TRACYL data, so (decision):
//! - C turns the part about the table's Z through the machine zero by `φ = s·(C − c0)` with the
//!   sign and offset of the TRACYL/TRANSMIT data set, the way `spindle.rs` turns a blank
//!   in a work spindle: a point of the table frame lies at `R_z(−φ)·p` in the unturned frame.
//!   TRACYL's own mapping then holds: the unrolled coordinate `Y = r·φ` is under the tool.
//! - The tilting axis is the channel's other rotary axis that is no spindle, named A (about
//!   machine X) or B (about Y), through the machine zero, turning the table right-handedly by
//!   its position: on `tracyl-xyzac`, A = −90° lays the C axis onto +Y, as the preset's TRACYL
//!   data assume (the rotary axis on the line X = Z = 0 of the tool tip).
//!
//! So `machine = R_tilt(A)·R_z(−φ)·p` for a point `p` of the table frame; the tool tip and
//! axis of the vertical spindle are taken back through it every cycle.

use super::pose::ToolPose;
use crate::channel::Channel;
use crate::machine_data::TrafoParams;
use crate::motion::AxisVec;

/// A rotation matrix (rows).
pub type Mat3 = [[f64; 3]; 3];

/// The rotary table a blank is clamped on (channel slots of its axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::channel) struct TableMount {
    rotary: usize,
    /// The tilting axis' slot and the machine axis it turns about (0 X for A, 1 Y for B).
    tilt: Option<(usize, usize)>,
    rot_offset: f64,
    sign: f64,
}

impl TableMount {
    /// The table's turn at machine position `machine`: `machine = R·p` for `p` in the table's
    /// frame.
    pub(in crate::channel) fn pose(&self, machine: &AxisVec) -> Mat3 {
        let turn = rotation(2, -self.sign * (machine[self.rotary] - self.rot_offset));
        match self.tilt {
            Some((k, about)) => mul(&rotation(about, machine[k]), &turn),
            None => turn,
        }
    }
}

/// The right-handed rotation by `deg` degrees about machine axis `about` (0 X, 1 Y, 2 Z).
pub(in crate::channel) fn rotation(about: usize, deg: f64) -> Mat3 {
    let (s, c) = deg.to_radians().sin_cos();
    match about {
        0 => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
        1 => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        _ => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
    }
}

fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| a[r][k] * b[k][c]).sum()))
}

/// `mᵀ·v`: a machine vector in the table's frame.
pub(in crate::channel) fn apply_t(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|c| (0..3).map(|r| m[r][c] * v[r]).sum())
}

impl Channel {
    /// The rotary table the blank sits on: the first TRACYL or TRANSMIT data set of a milling
    /// machine without TRAORI data whose rotary axis is no spindle; `None` elsewhere.
    pub(in crate::channel) fn stock_table_mount(&self) -> Option<TableMount> {
        if self.stock_turns() || self.cfg.trafos.iter().any(|s| s.kind == crate::machine_data::TrafoKind::Traori) {
            return None;
        }
        self.cfg.trafos.iter().find_map(|set| {
            let (rot_offset, sign_plus) = match set.params {
                TrafoParams::Transmit { rot_offset, sign_plus, .. }
                | TrafoParams::Tracyl { rot_offset, sign_plus, .. } => (rot_offset, sign_plus),
                _ => return None,
            };
            let rotary = set.axes_in[1]?;
            let axis = self.cfg.axis(rotary);
            if !axis.rotary || axis.spindle.is_some() {
                return None;
            }
            let tilt = (0..self.cfg.channel_axes.len()).find_map(|k| {
                let a = self.cfg.axis(k);
                if k == rotary || !a.rotary || a.spindle.is_some() {
                    return None;
                }
                match self.cfg.channel_axes[k].name.as_str() {
                    "A" => Some((k, 0)),
                    "B" => Some((k, 1)),
                    _ => None,
                }
            });
            Some(TableMount { rotary, tilt, rot_offset, sign: if sign_plus { 1.0 } else { -1.0 } })
        })
    }

    /// The vertical spindle's tool in the frame of the table `m` at `machine`; `tool` is the
    /// length vector by geometry axis of the machine (no transformation).
    pub(in crate::channel) fn table_tool_pose(&self, m: &TableMount, machine: &AxisVec, tool: [f64; 3]) -> ToolPose {
        let geo = self.cfg.geo_axes;
        let r = m.pose(machine);
        let tip: [f64; 3] = std::array::from_fn(|g| geo[g].map_or(0.0, |k| machine[k]) - tool[g]);
        let n = (tool[0] * tool[0] + tool[1] * tool[1] + tool[2] * tool[2]).sqrt();
        let dir = if n > 1e-9 { tool.map(|c| c / n) } else { [0.0, 0.0, 1.0] };
        ToolPose { tip: apply_t(&r, tip), axis: apply_t(&r, dir), length: n }
    }

    /// The tool's length vector by geometry axis of the machine: the active transformation's
    /// (by its own geometry axes) carried over through the channel slots, else the offsets'.
    pub(in crate::channel) fn machine_tool_vector(&self, offsets: &crate::interp::Offsets) -> [f64; 3] {
        let geo = self.cfg.geo_axes;
        let toff = self.toff.current;
        match &self.trafo {
            Some(active) => {
                use crate::kinematics::Transformation;
                let slots = active.trafo.geo_slots();
                std::array::from_fn(|g| {
                    let from = geo[g].and_then(|k| slots.iter().position(|s| *s == Some(k)));
                    from.map_or(0.0, |t| active.tool[t] + toff[t])
                })
            }
            None => std::array::from_fn(|g| geo[g].map_or(0.0, |k| offsets.tool[k]) + toff[g]),
        }
    }
}
