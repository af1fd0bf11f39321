//! Where the tool tip is on the workpiece, cycle by cycle and cheaply: what a display of the
//! executed path or of limit marks draws (`limit_watch.rs`, the server's path history).
//!
//! The BCS is the workpiece's frame only while nothing turns the workpiece, or while the
//! transformation that turns it is active. On a trunnion table moved with `G1 A.. C..` and no
//! TRAORI, the BCS tip stands still while the tool cuts around the part: drawn there, the
//! path would be false. So the tip is taken through the machine's kinematics:
//! - an orientation transformation active, or a TRAORI data set defined (active or not): the
//!   chain's forward map from the machine positions (as the stock is cut, `stock/pose.rs`),
//!   i.e. the tip in the frame that turns with the table (the TRAORI BCS);
//! - another transformation active (TRANSMIT, TRACYL, TRAANG): its BCS, which is Cartesian on
//!   the part; under TRACYL that is the unrolled surface, so the working diameter goes along
//!   for a view to wrap the point onto the cylinder;
//! - no transformation, and a rotary table the blank is clamped on (`stock/table.rs`: a
//!   TRACYL/TRANSMIT rotary axis that is no spindle, tilted by A or B, as on `tracyl-xyzac`):
//!   the tip in the table's frame, the frame the stock is cut in and the HMI draws it in;
//! - no transformation and no data set: the BCS (machine − tool offsets − `$AA_TOFF`).
//!
//! Decision where the manuals are silent (they know no such display): in the last case a
//! rotary axis that is not a spindle standing off 0° may turn the workpiece in a way the
//! machine data does not describe: the point is then marked `exact == false` rather than
//! drawn as if it were true.

use std::sync::Arc;

use super::Channel;
use crate::kinematics::{AnyTrafo, Transformation, Traori};
use crate::machine_data::MachineConfig;

/// The tool tip relative to the workpiece in one cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkpieceTip {
    /// Tool tip, geometry axes 1–3 (mm) in the workpiece frame.
    pub tip: [f64; 3],
    /// The TRACYL working diameter while TRACYL is active (`tip` is then on the unrolled
    /// surface: radial, arc length on this diameter, axial).
    pub tracyl_diameter: Option<f64>,
    /// `false`: a rotary axis the kinematics do not describe stands off 0°, so `tip` is the
    /// BCS, not known to be on the workpiece.
    pub exact: bool,
}

/// Computes [`WorkpieceTip`]s of a channel; keeps the kinematics it built until the channel's
/// machine configuration changes.
#[derive(Debug, Clone, Default)]
pub struct TipProbe {
    built_for: Option<Arc<MachineConfig>>,
    kin: Option<Box<Traori>>,
    /// The rotary axes that are no spindle (the ones that may turn the workpiece unseen).
    turning: Vec<usize>,
    /// The rotary table the blank is clamped on, without TRAORI data (`stock/table.rs`).
    mount: Option<super::stock::table::TableMount>,
}

impl TipProbe {
    /// The tool tip on the workpiece now.
    pub fn tip(&mut self, ch: &Channel) -> WorkpieceTip {
        if !self.built_for.as_ref().is_some_and(|c| Arc::ptr_eq(c, &ch.cfg)) {
            self.kin = ch.stock_kinematics();
            self.built_for = Some(ch.cfg.clone());
            self.mount = ch.stock_table_mount();
            self.turning = (0..ch.axis_positions().len())
                .filter(|&k| {
                    let a = ch.cfg.axis(k);
                    a.rotary && a.spindle.is_none()
                })
                .collect();
        }
        let cfg = &ch.cfg;
        match ch.trafo.as_ref().map(|t| &t.trafo) {
            Some(AnyTrafo::Traori(_)) => {}
            Some(other) => {
                // Its BCS: Cartesian on the part (the display's basic coordinates).
                let bcs = ch.space_of_machine();
                let geo = other.geo_slots();
                let tip = std::array::from_fn(|g| geo[g].map_or(0.0, |k| bcs[k] - ch.offsets.tool[k]));
                let tracyl_diameter = match other {
                    AnyTrafo::Tracyl(c) => Some(c.diameter()),
                    _ => None,
                };
                return WorkpieceTip { tip, tracyl_diameter, exact: true };
            }
            None if self.mount.is_some() => {
                if let Some(m) = &self.mount {
                    let pose = ch.table_tool_pose(m, &ch.machine, ch.machine_tool_vector(&ch.offsets));
                    return WorkpieceTip { tip: pose.tip, tracyl_diameter: None, exact: true };
                }
            }
            None if self.kin.is_none() => {
                let toff = ch.toff.current;
                let tip = std::array::from_fn(|g| {
                    cfg.geo_axes[g].map_or(0.0, |k| ch.machine[k] - ch.offsets.tool[k] - toff[g])
                });
                let exact = self
                    .turning
                    .iter()
                    .all(|&k| (ch.machine[k] / 360.0 - (ch.machine[k] / 360.0).round()).abs() < 1e-9);
                return WorkpieceTip { tip, tracyl_diameter: None, exact };
            }
            None => {}
        }
        let pose = ch.stock_tool_pose(&ch.machine, &ch.offsets, self.kin.as_deref());
        WorkpieceTip { tip: pose.tip, tracyl_diameter: None, exact: true }
    }
}

impl Channel {
    /// The program line of the block in execution (0: none), without building a snapshot:
    /// for recorders that look at every IPO cycle.
    pub fn line_in_execution(&self) -> u32 {
        self.current_line.unwrap_or(0)
    }
}
