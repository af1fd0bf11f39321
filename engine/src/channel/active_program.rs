//! The program the channel runs (or ran last), as a machine screen shows it: whoever started it
//! (a run, MDA, a block search, a restart that resumed it), its text, the mode it runs in, a
//! serial that changes with every load, and the call stack of the block in execution.
//!
//! A display must never show one program's text with another's line numbers: it keys what it
//! holds on [`ActiveProgram::serial`] and reloads when the serial in the state changes.

use super::{Channel, Mode};
use crate::lang::ProgramText;

/// The loaded program, shared (no copy of its text).
#[derive(Debug, Clone)]
pub struct ActiveProgram {
    pub text: ProgramText,
    /// AUTO (a run, a search, a resumed program) or MDA (the MDA buffer).
    pub mode: Mode,
    /// Counts loads on this channel; the same number as the snapshot's `program_serial`.
    pub serial: u64,
}

/// One level of the call stack of the block in execution.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CallLevel {
    /// The program of this level by its stored (upper-case) name; `None`: the main program.
    pub program: Option<String>,
    /// 1-based line in that program's text: the calling block, on the innermost level the
    /// block in execution.
    pub line: u32,
}

impl Channel {
    /// Takes `text` as the loaded program (the caller sets the mode).
    pub(super) fn set_active_program(&mut self, text: ProgramText) {
        self.program = Some(text);
        self.program_serial += 1;
    }

    /// The loaded program; `None` before the first program of the channel. A reset keeps it,
    /// as the control keeps the selected program.
    pub fn active_program(&self) -> Option<ActiveProgram> {
        let text = self.program.clone()?;
        Some(ActiveProgram { text, mode: self.program_mode, serial: self.program_serial })
    }

    /// The number of programs loaded so far (see [`ActiveProgram::serial`]).
    pub fn program_serial(&self) -> u64 {
        self.program_serial
    }

    /// The call stack of the block shown as current, main program first; empty when no block
    /// is current. A block in the main program is one level.
    pub fn call_stack(&self) -> Vec<CallLevel> {
        let Some(block) = &self.current_block else { return Vec::new() };
        let Some(line) = self.current_line else { return Vec::new() };
        let Some(level) = &block.level else { return vec![CallLevel { program: None, line }] };
        // `calls[k]` is (calling line in level k's program, name of level k + 1).
        let mut stack = Vec::with_capacity(level.calls.len() + 1);
        let mut program = None;
        for (calling_line, called) in &level.calls {
            stack.push(CallLevel { program, line: *calling_line });
            program = Some(called.clone());
        }
        stack.push(CallLevel { program, line });
        stack
    }

    /// The text of program `name` as the call stack runs it: the current level's own text when
    /// it is that program, else the stored program or standard cycle of that name.
    pub fn program_text(&self, name: &str) -> Option<ProgramText> {
        let upper = name.trim().to_ascii_uppercase();
        if let Some(level) = self.current_block.as_ref().and_then(|b| b.level.as_ref())
            && level.name() == upper
        {
            return Some(level.text.clone());
        }
        self.programs.resolve(&upper, None, 0).ok().map(|(text, _)| text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mill() -> Channel {
        Channel::from_preset("mill-3axis", "").expect("preset")
    }

    fn run_until_line(ch: &mut Channel, program: Option<&str>, line: u32) {
        let mut seen = Vec::new();
        for _ in 0..200_000 {
            let snap = ch.snapshot();
            let now = snap.block.as_ref().map(|b| (b.program.clone(), b.line));
            if seen.last() != Some(&now) {
                seen.push(now);
            }
            if let Some(b) = &snap.block
                && b.line == line
                && b.program.as_deref() == program
            {
                return;
            }
            ch.step();
        }
        panic!("block {program:?}:{line} never became current: {seen:?} {:?} {:?}", ch.status(), ch.alarms());
    }

    #[test]
    fn every_load_counts_and_a_reset_keeps_the_program() {
        let mut ch = mill();
        assert!(ch.active_program().is_none());
        ch.run_program("G1 X1 F600\nM30").expect("run");
        let first = ch.active_program().expect("loaded");
        assert_eq!((first.serial, first.mode, &*first.text), (1, Mode::Auto, "G1 X1 F600\nM30"));
        assert_eq!(ch.snapshot().program_serial, 1);
        ch.reset();
        assert_eq!(ch.active_program().expect("kept").serial, 1);
        ch.mda("G0 X5").expect("mda");
        let mda = ch.active_program().expect("mda");
        assert_eq!((mda.serial, mda.mode, &*mda.text), (2, Mode::Mda, "G0 X5"));
    }

    #[test]
    fn the_call_stack_names_the_calling_line_and_the_subprogram_line() {
        let mut ch = mill();
        ch.store_program("HOLE", "PROC HOLE\nG1 Z-1 F100\nG1 Z5 F100\nM17").expect("store");
        // Line 3 calls HOLE; its line 3 (G1 Z5) runs as the block in execution.
        ch.run_program("G0 X0 Y0 Z5\nG1 X10 F1000\nHOLE\nG0 X20\nM30").expect("run");
        run_until_line(&mut ch, None, 2);
        assert_eq!(ch.call_stack(), vec![CallLevel { program: None, line: 2 }]);
        run_until_line(&mut ch, Some("HOLE"), 3);
        assert_eq!(
            ch.call_stack(),
            vec![CallLevel { program: None, line: 3 }, CallLevel { program: Some("HOLE".into()), line: 3 }]
        );
        assert_eq!(ch.program_text("hole").as_deref(), Some("PROC HOLE\nG1 Z-1 F100\nG1 Z5 F100\nM17"));
    }

    #[test]
    fn the_snapshot_gives_the_blocks_distance_to_go_and_programmed_feed() {
        let mut ch = mill();
        // From X0: 100 mm at F600 (10 mm/s); after 2 s the axis is somewhere past the ramp.
        ch.run_program("G1 X100 F600\nG0 X0\nM30").expect("run");
        let cycles = (2.0 / ch.config().ipo_cycle).round() as u64;
        for _ in 0..cycles {
            ch.step();
        }
        let s = ch.snapshot();
        let x = s.workpiece[0].1;
        assert!(x > 5.0 && x < 20.0, "x {x}");
        // What is left of the block is what X has still to travel.
        assert!((s.distance_to_go - (100.0 - x)).abs() < 1e-6, "to go {} at x {x}", s.distance_to_go);
        assert_eq!(s.programmed_feed, Some(600.0));
        // The rapid block back has no programmed feed; at the end nothing is left to go.
        while ch.snapshot().block.as_ref().is_some_and(|b| b.line == 1) {
            ch.step();
        }
        assert_eq!(ch.snapshot().programmed_feed, None);
        while ch.is_busy() {
            ch.step();
        }
        assert_eq!((ch.snapshot().distance_to_go, ch.snapshot().programmed_feed), (0.0, None));
    }
}
