//! The gear stages of a spindle (Function Manual S1 "Gear stages for spindles"), read from
//! the machine data once when the configuration is activated:
//!
//! * MD35010 `$MA_GEAR_STEP_CHANGE_ENABLE` bit 0: the spindle has gear stages; without it
//!   only stage 1's data apply and M40..M45 go to the PLC alone.
//! * MD35090 `$MA_NUM_GEAR_STEPS`: stages 1..5 in use.
//! * MD35110 `$MA_GEAR_STEP_MAX_VELO[n]` / MD35120 `$MA_GEAR_STEP_MIN_VELO[n]`: the speed
//!   range in which M40 (automatic selection) picks stage n.
//! * MD35130 `$MA_GEAR_STEP_MAX_VELO_LIMIT[n]` / MD35140 `$MA_GEAR_STEP_MIN_VELO_LIMIT[n]`:
//!   the highest and lowest speed in stage n (setpoints are limited to them; the lowest
//!   only while the spindle turns).
//! * MD35200 `$MA_GEAR_STEP_SPEEDCTRL_ACCEL[n]`: acceleration in speed control (rev/s²).
//!
//! Index 0 of the arrays is the control's axis-mode data set and not used here.

use super::MachineData;

/// Stages 1..=5.
pub const MAX_STAGES: usize = 5;

/// One stage's data (index 1..=5 of the arrays).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GearStage {
    /// MD35120/MD35110: the range M40 selects the stage for (rev/min).
    pub switch_min: f64,
    pub switch_max: f64,
    /// MD35140/MD35130: the lowest and highest speed in the stage (rev/min).
    pub limit_min: f64,
    pub limit_max: f64,
    /// MD35200 (rev/s²).
    pub accel: f64,
}

/// A spindle's gear stages.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Gears {
    /// Stages in use (0: the spindle has none; stage 1's data still apply).
    pub count: u8,
    /// `stages[n - 1]` is stage n.
    pub stages: [GearStage; MAX_STAGES],
}

impl Gears {
    /// The gear data of machine axis `ax`.
    pub fn read(md: &MachineData, ax: usize) -> Gears {
        let num = |name: &str, i: usize| md.num(name, ax, i);
        let enabled = num("$MA_GEAR_STEP_CHANGE_ENABLE", 0) as i64 & 1 != 0;
        let count = if enabled { num("$MA_NUM_GEAR_STEPS", 0).clamp(1.0, MAX_STAGES as f64) as u8 } else { 0 };
        let stages = std::array::from_fn(|i| GearStage {
            switch_min: num("$MA_GEAR_STEP_MIN_VELO", i + 1),
            switch_max: num("$MA_GEAR_STEP_MAX_VELO", i + 1),
            limit_min: num("$MA_GEAR_STEP_MIN_VELO_LIMIT", i + 1),
            limit_max: num("$MA_GEAR_STEP_MAX_VELO_LIMIT", i + 1),
            accel: num("$MA_GEAR_STEP_SPEEDCTRL_ACCEL", i + 1),
        });
        Gears { count, stages }
    }

    /// Stage `n` (1-based; out of range: stage 1).
    pub fn stage(&self, n: u8) -> &GearStage {
        &self.stages[usize::from(n.clamp(1, MAX_STAGES as u8)) - 1]
    }

    /// M40: the stage for speed `s` (rev/min): the current one when `s` lies in its range,
    /// else the first from stage 1 up whose range holds it, else none (no change).
    pub fn select(&self, s: f64, current: u8) -> Option<u8> {
        let fits = |n: u8| {
            let st = self.stage(n);
            (st.switch_min..=st.switch_max).contains(&s)
        };
        if s == 0.0 || self.count == 0 || fits(current) && current <= self.count {
            return None;
        }
        (1..=self.count).find(|&n| fits(n))
    }
}
