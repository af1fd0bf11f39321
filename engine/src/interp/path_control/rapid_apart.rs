//! `RTLIOF` (G group 55): rapid traverse without linear interpolation, each axis at its own
//! rapid velocity (MD32000) and acceleration, so an axis with a shorter travel arrives first;
//! `RTLION`, the reset value (MD20730 `G0_LINEAR_MODE` = 1 on NCTwin's machines), interpolates
//! G0 linearly. The end points are the same, the path between differs: `G0 X100 Y10` from the
//! origin has Y at 10 by the time X passes 50 (RTLION: Y at 5).
//!
//! A G0 straight line under RTLIOF goes to the main run as one positioning item per moving axis
//! (the single-axis interpolators of POS, `channel/positioning_axes.rs`) at the axis's rapid
//! velocity, and the block ends when all have arrived, as a POS block does. Blocks the control
//! also interpolates linearly under RTLIOF stay linear here: with tool radius compensation or a
//! transformation active, an orientation or an arc (Programming Manual, "RTLIOF").

use crate::interp::{Interpreter, Item, SharedOffsets};
use crate::machine_data::MachineConfig;
use crate::motion::Move;

impl Interpreter {
    /// Puts `mv` out as single-axis rapid motions when RTLIOF applies to it (true), else leaves
    /// it to the caller (false).
    pub(in crate::interp) fn rapid_apart(
        &mut self,
        mv: &Move,
        offsets: &SharedOffsets,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> bool {
        let path = &mv.path;
        if !self.modal.rtliof
            || !mv.is_rapid()
            || path.arc.is_some()
            || path.ori.is_some()
            || path.curve.is_some()
            || self.offsets.trafo.is_some()
        {
            return false;
        }
        out.push(Item::Offsets { line, offsets: offsets.clone() });
        let mut axes = 0;
        for k in 0..cfg.channel_axes.len() {
            if (path.end[k] - path.start[k]).abs() > 1e-12 {
                let velocity = cfg.axis(k).max_velocity;
                let motion = super::positioning::Motion::Pos;
                out.push(Item::Positioning { axis: k, target: path.end[k], velocity, motion, line });
                axes |= 1 << k;
            }
        }
        if axes != 0 {
            out.push(Item::WaitPositioning { axes, strict: false, line });
        }
        true
    }
}
