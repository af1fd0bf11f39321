//! The main run's workpiece counters and program runtimes (Function Manual K1, "Program
//! runtime / workpiece counter"), switched by MD27860/MD27880/MD27882
//! (`machine_data/process_counting.rs`), and the channel's clock.
//!
//! - A counter switched on counts up when the main run outputs its M function (M2/M30, or the
//!   one MD27882 names) and, if MD27880 says so, when GOTOS starts the main program over.
//!   When `$AC_REQUIRED_PARTS` is watched and above 0 and the watched counter reaches it,
//!   alarm 21800 shows "workpiece setpoint reached" (the program goes on); the actual count then
//!   starts again from 0 (the special count is the user's to reset).
//! - `$AC_OPERATING_TIME` sums the time of AUTO programs from start to end, `$AC_CYCLE_TIME`
//!   the time of the AUTO program started last (cleared at its start, and at GOTOS under
//!   MD27860 bit 8), `$AC_CUTTING_TIME` the time the path moves at feed (not rapid traverse,
//!   not a dwell) with a tool active, in AUTO and MDA. None runs while the program is stopped
//!   or in an alarm, nor with the feed override at 0 (MD27860 bit 9 lets the first two run),
//!   nor under the dry-run feed without MD27860 bit 4.
//! - The IPO cycle only counts: one increment while a program runs, one in the planner while
//!   the path moves at feed. The times are worked out from the counts when read and settled at
//!   each block prepared and before the feed override changes, so a change of DRY or the tool
//!   is attributed to within one block; a cycle costs two increments instead of the tests.
//! - The counters and runtimes are not touched by a mode change or reset, are kept in a
//!   checkpoint, and can be written by programs (the counters) and over REST.
//! - Decisions where the manuals leave it open: a counter switched on counts whatever
//!   `$AC_REQUIRED_PARTS` holds (the watch needs it above 0); the alarm number 21800 could not
//!   be confirmed in a public text.

use super::{Channel, Mode};
use crate::alarm::Alarm;
use crate::interp::eval::process_vars::{MAX_PARTS, PartCounter, PartCounts, ProcessData, Runtimes};
use crate::machine_data::process_counting::{CountedParts, Runtime};

/// The counters, runtimes and clock of one channel.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Counters {
    pub parts: PartCounts,
    pub times: Runtimes,
    /// The wall time (ms since 1970 UTC) at tick 0, as the shell set it.
    pub clock_base_ms: i64,
    /// IPO cycles in which a program ran (not stopped, not JOG), ever.
    pub run_cycles: u64,
    /// `run_cycles` and the planner's feed cycles when `times` was last settled.
    settled_run: u64,
    settled_feed: u64,
    /// A program is running or interrupted: its cycles count.
    active: bool,
}

/// The counters and runtimes a checkpoint keeps.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SavedCounters {
    pub parts: PartCounts,
    pub times: Runtimes,
}

impl CountedParts {
    fn counter(self) -> PartCounter {
        match self {
            CountedParts::Total => PartCounter::Total,
            CountedParts::Actual => PartCounter::Actual,
            CountedParts::Special => PartCounter::Special,
        }
    }
}

impl Channel {
    /// Sets the channel's clock: `unix_ms` (milliseconds since 1970-01-01 00:00 UTC) is the
    /// wall time now; `$A_YEAR`.. read it plus the simulated time from here on.
    pub fn set_clock(&mut self, unix_ms: i64) {
        let elapsed_ms = (self.tick as f64 * self.cfg.ipo_cycle * 1000.0).round() as i64;
        self.counters.clock_base_ms = unix_ms.saturating_sub(elapsed_ms);
        self.hand_process_data();
    }

    /// The workpiece counters.
    pub fn part_counts(&self) -> PartCounts {
        self.counters.parts
    }

    /// Sets the workpiece counters, as the operator does on the control's times/counters page
    /// (each 0..999,999,999).
    pub fn set_part_counts(&mut self, parts: PartCounts) -> Result<(), super::CommandError> {
        let all = [parts.required, parts.total, parts.actual, parts.special];
        if let Some(n) = all.iter().find(|&&n| i64::from(n) > MAX_PARTS) {
            return Err(super::CommandError::Invalid(format!("a workpiece count is at most {MAX_PARTS}, not {n}")));
        }
        self.counters.parts = parts;
        self.hand_process_data();
        Ok(())
    }

    /// The counters and runtimes for a checkpoint.
    pub(super) fn saved_counters(&self) -> Option<SavedCounters> {
        let (parts, times) = (self.counters.parts, self.runtimes());
        (parts != PartCounts::default() || times != Runtimes::default()).then_some(SavedCounters { parts, times })
    }

    /// Takes back the counters and runtimes of a checkpoint.
    pub(super) fn restore_counters(&mut self, saved: &SavedCounters) {
        let finite = |v: f64| if v.is_finite() && v >= 0.0 { v } else { 0.0 };
        let clamp = |n: u32| n.min(MAX_PARTS as u32);
        let p = saved.parts;
        self.counters.parts = PartCounts {
            required: clamp(p.required),
            total: clamp(p.total),
            actual: clamp(p.actual),
            special: clamp(p.special),
        };
        let t = saved.times;
        self.counters.times =
            Runtimes { operating: finite(t.operating), cycle: finite(t.cycle), cutting: finite(t.cutting) };
        self.hand_process_data();
    }

    /// Block preparation reads the counters, runtimes and clock as they are now.
    pub(super) fn hand_process_data(&mut self) {
        self.settle_runtimes();
        let powered_on_s = self.tick as f64 * self.cfg.ipo_cycle;
        let clock_ms = self.counters.clock_base_ms.saturating_add((powered_on_s * 1000.0).round() as i64);
        self.interp.set_process_data(ProcessData {
            parts: self.counters.parts,
            times: self.counters.times,
            clock_ms,
            powered_on_s,
        });
    }

    /// A new program starts: its cycle time starts from 0, and the runtimes count from here.
    pub(super) fn start_runtimes(&mut self) {
        if self.mode == Mode::Auto {
            self.counters.times.cycle = 0.0;
        }
        self.resume_runtimes();
    }

    /// A program goes on after a block search (the operator's, or a restart's): the runtimes
    /// count from here, the cycle time from where it stood.
    pub(super) fn resume_runtimes(&mut self) {
        let c = &mut self.counters;
        c.settled_run = c.run_cycles;
        c.settled_feed = self.planner.feed_cycles();
        c.active = true;
    }

    /// The program ended (M30, reset, an alarm): its runtimes are taken over, and nothing
    /// counts until the next one starts (JOG after it is no program time).
    pub(super) fn end_runtimes(&mut self) {
        self.settle_runtimes();
        self.counters.active = false;
    }

    /// Takes the cycles since the last settling into the runtimes, under the conditions now
    /// (feed override, DRY, the tool): called at every block prepared and whenever one of
    /// those conditions is about to change, so a change is attributed to at most one block.
    pub(super) fn settle_runtimes(&mut self) {
        self.counters.times = self.runtimes();
        self.counters.settled_run = self.counters.run_cycles;
        self.counters.settled_feed = self.planner.feed_cycles();
    }

    /// The program runtimes in seconds: the settled ones plus what the cycles since add. The
    /// IPO cycle only counts its cycles (one increment while a program runs, one in the
    /// planner while the path moves at feed); this is where they become times.
    pub fn runtimes(&self) -> Runtimes {
        let c = &self.counters;
        let mut times = c.times;
        let mode = self.cfg.process_counting;
        if !c.active || self.dry_run && !mode.runs_in_dry_run() {
            return times;
        }
        let dt = self.cfg.ipo_cycle;
        let ran = (c.run_cycles - c.settled_run) as f64 * dt;
        if self.program_mode == Mode::Auto && (self.overrides.feed > 0.0 || mode.runs_at_zero_override()) {
            if mode.runs(Runtime::Operating) {
                times.operating += ran;
            }
            if mode.runs(Runtime::Cycle) {
                times.cycle += ran;
            }
        }
        if mode.runs(Runtime::Cutting) && (self.offsets.t != 0 || mode.cuts_without_tool()) {
            times.cutting += (self.planner.feed_cycles() - c.settled_feed) as f64 * dt;
        }
        times
    }

    /// The main run outputs M function `m` (no address extension): the counters switched on
    /// for it count.
    pub(super) fn count_parts_on_m(&mut self, m: u32) {
        let mda = self.program_mode == Mode::Mda;
        let counting = self.cfg.process_counting;
        for counted in CountedParts::ALL {
            if counting.counts_on(counted, m, mda) {
                self.count_part(counted);
            }
        }
    }

    /// A program writes workpiece counter `counter`, as its block reaches the main run.
    pub(super) fn write_part_count(&mut self, counter: PartCounter, n: u32) {
        *self.counters.parts.get_mut(counter) = n;
        self.hand_process_data();
    }

    /// GOTOS starts the main program over: the counters switched on for it count, and the
    /// cycle time starts again if MD27860 bit 8 says so.
    pub(super) fn start_over(&mut self) {
        let mda = self.program_mode == Mode::Mda;
        let counting = self.cfg.process_counting;
        for counted in CountedParts::ALL {
            if counting.counts_on_gotos(counted, mda) {
                self.count_part(counted);
            }
        }
        if counting.gotos_clears_cycle_time() {
            self.settle_runtimes();
            self.counters.times.cycle = 0.0;
        }
    }

    fn count_part(&mut self, counted: CountedParts) {
        let required = self.counters.parts.required;
        let count = self.counters.parts.get_mut(counted.counter());
        *count = (*count + 1).min(MAX_PARTS as u32);
        if required > 0 && *count == required && self.cfg.process_counting.watched_against_required() == Some(counted) {
            if counted == CountedParts::Actual {
                *count = 0;
            }
            self.notify_alarm(Alarm::workpiece_setpoint_reached(required));
        }
        self.hand_process_data();
    }
}
