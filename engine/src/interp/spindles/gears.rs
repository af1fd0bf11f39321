//! Gear stages in block preparation (Function Manual S1 "Gear stages for spindles";
//! `machine_data/gears.rs` for the data): `M41`..`M45` engage stage 1..5, `M40` selects the
//! stage from each programmed speed (the current one when the speed lies in its MD35110/35120
//! range, else the first from stage 1 up, else no change), also with the spindle number as
//! address extension (`M2=42`). A change goes to the main run before the block's speed
//! ([`super::Control::Gear`]): the spindle brakes, the stage changes, and the block waits.
//!
//! Decisions where the manuals leave it open: the simulated PLC changes the gear at once when
//! the spindle stands (no oscillation, no change time); under constant cutting speed
//! (G96/G961) M40 keeps the stage; a stage above MD35090 `$MA_NUM_GEAR_STEPS` is alarm 12560;
//! a spindle without gear stages (MD35010 bit 0 = 0) passes M40..M45 to the PLC only.
//! Reset and program end switch M40 on again; the stage engaged stays.

use super::axis_of;
use crate::alarm::Alarm;
use crate::interp::{Interpreter, Item};
use crate::machine_data::MachineConfig;

/// `M40` (`0`) or `M41`..`M45` (stage) in a block, with the spindle number of `M<n>=`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GearWord {
    pub spindle: Option<u32>,
    pub stage: u8,
}

/// The gear word of M function `code` (40..45), if it is one.
pub(in crate::interp) fn of_m(code: u32, spindle: Option<u32>) -> Option<GearWord> {
    (40..=45).contains(&code).then(|| GearWord { spindle, stage: (code - 40) as u8 })
}

impl Interpreter {
    /// The block's gear word and, under M40, the stage for the master spindle's new speed
    /// `speed` (rev/min; `None`: S not programmed); a change goes to `out`.
    pub(in crate::interp) fn gear_block(
        &mut self,
        word: Option<GearWord>,
        speed: Option<(usize, f64)>,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let mut change = None;
        if let Some(w) = word {
            let k = match w.spindle {
                Some(n) => Some(axis_of(cfg, n, line, &format!("M{n}={}", 40 + w.stage))?),
                None => self.spindles.master(),
            };
            let Some(k) = k else { return Ok(()) };
            let Some(gears) = cfg.gears.get(&k).filter(|g| g.count > 0) else { return Ok(()) };
            if w.stage == 0 {
                self.spindles.gear_auto[k] = true;
                let s = speed.filter(|(a, _)| *a == k).map_or(self.spindles.speed_of(k), |(_, s)| s);
                change = gears.select(s, self.spindles.gear[k]).map(|n| (k, n));
            } else {
                if w.stage > gears.count {
                    return Err(Alarm::value_out_of_range(
                        line,
                        &format!("M{}: gear stage {} (MD35090 = {})", 40 + w.stage, w.stage, gears.count),
                    ));
                }
                self.spindles.gear_auto[k] = false;
                change = Some((k, w.stage));
            }
        } else if let Some((k, s)) =
            speed.filter(|(k, _)| self.spindles.gear_auto[*k] && !self.spindles.feed_type.css())
            && let Some(gears) = cfg.gears.get(&k)
        {
            change = gears.select(s, self.spindles.gear[k]).map(|n| (k, n));
        }
        if let Some((axis, stage)) = change.filter(|&(k, n)| self.spindles.gear[k] != n) {
            self.spindles.gear[axis] = stage;
            let ctl = super::Control::Gear { axis, stage };
            self.trc.emit_or_defer(Item::SpindleControl { ctl, line }, out);
        }
        Ok(())
    }
}
