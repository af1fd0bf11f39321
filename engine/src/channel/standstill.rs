//! Whether a running channel still makes progress on its own.
//!
//! A real control that cannot go on simply stands: `G33 Z-20 K1.5` with the spindle stopped
//! (or G95 feed without spindle speed) leaves the axes waiting for the spindle, with no alarm,
//! until the operator acts; a program waiting for an input that never comes stands the same way.
//! A shell that runs programs unattended (`nctwin simulate`) must notice that instead of
//! running forever: it compares [`Channel::progress_mark`] taken some simulated seconds apart.
//! The mark holds everything that changes while anything happens: every axis's actual position,
//! every spindle's speed and angle, the dwell still to run (G4, a tool change's time), the block
//! shown and the read position of block preparation, the status and the alarms. Active
//! synchronized actions may change something on a timer or a condition at any time, so while
//! one is active the mark carries the IPO cycle count and never repeats.

use super::{Channel, Status};

/// What a channel's progress is measured by (see the module doc): equal marks taken apart in
/// time mean nothing moved, counted down or was read in between.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgressMark {
    /// Bits of the axes' actual positions and of the spindles' speeds and angles.
    values: Vec<u64>,
    dwell_ticks: u64,
    block: (Option<u32>, u32),
    read_offset: usize,
    status: Status,
    alarms: usize,
    /// The IPO cycle count while synchronized actions are active, else 0.
    sync_tick: u64,
}

impl Channel {
    /// The channel's progress mark now (a few dozen numbers; meant to be taken every few
    /// thousand IPO cycles, not every cycle).
    pub fn progress_mark(&self) -> ProgressMark {
        let n = self.cfg.channel_axes.len();
        let mut values: Vec<u64> = (0..n).map(|k| self.actual_position(k).to_bits()).collect();
        for s in &self.spindles {
            values.push(s.speed.to_bits());
            values.push(s.position.to_bits());
        }
        ProgressMark {
            values,
            dwell_ticks: self.dwell_ticks,
            block: (self.current_line, self.current_seq),
            read_offset: self.interp.read_offset(),
            status: self.status,
            alarms: self.alarms.len(),
            sync_tick: if self.sync.is_active() { self.tick } else { 0 },
        }
    }
}
