//! Which program runtimes and workpiece counters the main run keeps, and how (Function Manual
//! K1, "Program runtime / workpiece counter"), as the channel machine data set them:
//!
//! - MD27860 `$MC_PROCESSTIMER_MODE`: bit 0 `$AC_OPERATING_TIME`, bit 1 `$AC_CYCLE_TIME`,
//!   bit 2 `$AC_CUTTING_TIME` run; bit 4 they run under the dry-run feed too; bit 5 during a
//!   program test (NCTwin has none); bit 7 the cutting time runs without an active tool too;
//!   bit 8 GOTOS clears the cycle time; bit 9 they run with the feed override at 0 too.
//! - MD27880 `$MC_PART_COUNTER`: bit 0 `$AC_REQUIRED_PARTS` is watched (bit 1 says against
//!   which counter: 0 `$AC_ACTUAL_PARTS`, 1 `$AC_SPECIAL_PARTS`); bits 4, 8, 12 switch on
//!   `$AC_TOTAL_PARTS`, `$AC_ACTUAL_PARTS`, `$AC_SPECIAL_PARTS`; the bit after each counts
//!   on the M function of MD27882 instead of M2/M30, and the bit three after it counts on
//!   GOTOS as well; bits 16, 20, 24: not in MDA mode.
//! - MD27882 `$MC_PART_COUNTER_MCODE[0..2]`: those M functions, for the total, actual and
//!   special counter in that order.
//!
//! The defaults are the ones the 808D parameter manual lists (the only list of defaults we could
//! find): 'H177' (all three runtimes, also under dry run, GOTOS clears the cycle time) and
//! 'H901' (the actual count runs on M2/M30 and GOTOS, watched against the required count).

use super::MachineData;

/// The runtime and counter switches of one channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ProcessCounting {
    /// MD27860.
    pub timer_mode: u32,
    /// MD27880.
    pub part_counter: u32,
    /// MD27882: the M functions that count the total, actual and special workpieces.
    pub m_codes: [u32; 3],
}

/// The three workpiece counters the main run counts, in MD27882's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CountedParts {
    Total,
    Actual,
    Special,
}

impl CountedParts {
    pub const ALL: [CountedParts; 3] = [CountedParts::Total, CountedParts::Actual, CountedParts::Special];

    /// The counter's four bits in MD27880 (from bit 4, 8, 12) and its MDA bit (16, 20, 24).
    fn bits(self) -> (u32, u32) {
        match self {
            CountedParts::Total => (4, 16),
            CountedParts::Actual => (8, 20),
            CountedParts::Special => (12, 24),
        }
    }
}

/// Which program runtime.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Runtime {
    Operating,
    Cycle,
    Cutting,
}

impl ProcessCounting {
    pub(super) fn read(md: &MachineData) -> ProcessCounting {
        let int = |name: &str, i: usize| md.num(name, 0, i).max(0.0) as u32;
        ProcessCounting {
            timer_mode: int("$MC_PROCESSTIMER_MODE", 0),
            part_counter: int("$MC_PART_COUNTER", 0),
            m_codes: [0, 1, 2].map(|i| int("$MC_PART_COUNTER_MCODE", i)),
        }
    }

    fn part_bit(&self, n: u32) -> bool {
        self.part_counter >> n & 1 == 1
    }

    fn timer_bit(&self, n: u32) -> bool {
        self.timer_mode >> n & 1 == 1
    }

    /// Whether the output of M function `m` (no address extension) counts `counter` up, in
    /// MDA mode (`mda`) or not.
    pub fn counts_on(&self, counter: CountedParts, m: u32, mda: bool) -> bool {
        let (on, mda_off) = counter.bits();
        if !self.part_bit(on) || mda && self.part_bit(mda_off) {
            return false;
        }
        if self.part_bit(on + 1) { m == self.m_codes[counter as usize] } else { m == 2 || m == 30 }
    }

    /// Whether a jump back to the program start (GOTOS) counts `counter` up.
    pub fn counts_on_gotos(&self, counter: CountedParts, mda: bool) -> bool {
        let (on, mda_off) = counter.bits();
        self.part_bit(on) && self.part_bit(on + 3) && !(mda && self.part_bit(mda_off))
    }

    /// The counter `$AC_REQUIRED_PARTS` is watched against, if it is watched at all.
    pub fn watched_against_required(&self) -> Option<CountedParts> {
        self.part_bit(0).then(|| if self.part_bit(1) { CountedParts::Special } else { CountedParts::Actual })
    }

    /// Whether `timer` runs at all.
    pub fn runs(&self, timer: Runtime) -> bool {
        self.timer_bit(timer as u32)
    }

    /// Whether the runtimes run under the dry-run feed.
    pub fn runs_in_dry_run(&self) -> bool {
        self.timer_bit(4)
    }

    /// Whether the cutting time runs without an active tool.
    pub fn cuts_without_tool(&self) -> bool {
        self.timer_bit(7)
    }

    /// Whether GOTOS clears `$AC_CYCLE_TIME`.
    pub fn gotos_clears_cycle_time(&self) -> bool {
        self.timer_bit(8)
    }

    /// Whether the runtimes run while the feed override is 0.
    pub fn runs_at_zero_override(&self) -> bool {
        self.timer_bit(9)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn counting(timer_mode: u32, part_counter: u32, m_codes: [u32; 3]) -> ProcessCounting {
        ProcessCounting { timer_mode, part_counter, m_codes }
    }

    #[test]
    fn the_manuals_examples_switch_the_counters_they_name() {
        // 'H3313' with M80, M17, M77: required watched against the special count; total on
        // M2/M30 (bit 5 clear, so M80 means nothing); actual on M17; special on M77.
        let all = counting(0, 0x3313, [80, 17, 77]);
        assert_eq!(all.watched_against_required(), Some(CountedParts::Special));
        assert!(all.counts_on(CountedParts::Total, 2, false) && all.counts_on(CountedParts::Total, 30, false));
        assert!(!all.counts_on(CountedParts::Total, 80, false));
        assert!(all.counts_on(CountedParts::Actual, 17, false) && !all.counts_on(CountedParts::Actual, 30, false));
        assert!(all.counts_on(CountedParts::Special, 77, false) && !all.counts_on(CountedParts::Special, 2, false));
        // 'H200' with M50: the M function is named, but the counter is not switched on.
        let off = counting(0, 0x200, [0, 50, 0]);
        assert!(!off.counts_on(CountedParts::Actual, 50, false));
        assert_eq!(off.watched_against_required(), None);
    }

    #[test]
    fn the_default_counts_actual_parts_on_m30_and_gotos_in_every_mode() {
        let d = counting(0x177, 0x901, [2, 2, 2]);
        assert!(d.counts_on(CountedParts::Actual, 30, false) && d.counts_on(CountedParts::Actual, 30, true));
        assert!(d.counts_on_gotos(CountedParts::Actual, false));
        assert!(!d.counts_on(CountedParts::Total, 30, false) && !d.counts_on(CountedParts::Special, 30, false));
        assert_eq!(d.watched_against_required(), Some(CountedParts::Actual));
        // Bit 20: not in MDA mode.
        let not_mda = counting(0, 0x100901, [2, 2, 2]);
        assert!(
            !not_mda.counts_on(CountedParts::Actual, 30, true) && !not_mda.counts_on_gotos(CountedParts::Actual, true)
        );
    }

    #[test]
    fn the_timer_mode_bits_read_as_the_manual_numbers_them() {
        // 'H34': the cutting time, also under dry run and in program test.
        let t = counting(0x34, 0, [0; 3]);
        assert!(t.runs(Runtime::Cutting) && !t.runs(Runtime::Operating) && !t.runs(Runtime::Cycle));
        assert!(t.runs_in_dry_run() && !t.cuts_without_tool());
        let d = counting(0x177, 0, [0; 3]);
        assert!(d.runs(Runtime::Operating) && d.runs(Runtime::Cycle) && d.runs(Runtime::Cutting));
        assert!(d.gotos_clears_cycle_time() && !d.runs_at_zero_override());
    }
}
