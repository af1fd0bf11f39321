//! What a checkpoint of a channel holds beyond its machine data, axis positions and mode, and
//! how a restarted channel takes it back: the state a reset keeps (see
//! [`crate::interp::retained`]) and the program in AUTO mode with the block the main run was
//! at.
//!
//! A program that was running or stopped comes back stopped at its block, the way an operator
//! resumes after a power failure: block search with calculation to that block (the modal
//! state, frames, tool and transformation of the target are re-established by preparing the
//! program up to it), then NC start approaches the block and continues. A program that was
//! only loaded comes back loaded. MDA blocks are not resumed.

use super::search::{PathStep, path_of};
use super::{Channel, CommandError, Mode, Status};
use crate::interp::retained::Retained;
use crate::interp::{Item, StopKind};
use crate::lang::ProgramText;

/// The AUTO program of a checkpoint.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ResumeProgram {
    /// The program text; empty in the state of [`Channel::resume_state_shared`], whose caller
    /// stores the text elsewhere and puts it back before [`Channel::restore_resume_state`].
    pub text: String,
    /// The main run's block (1-based line) when the program was active; `None`: only loaded.
    /// Inside a subprogram: the line of the main program whose call leads there, and `path`
    /// goes on from it.
    pub line: Option<u32>,
    /// Inside a subprogram: the steps from `line` to the block, one per program level (see
    /// [`Channel::block_search_at`]); empty in the main program (and in checkpoints written
    /// before subprogram levels were recorded).
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Vec::is_empty"))]
    pub path: Vec<PathStep>,
    /// The program stood at a programmed stop (M0, M1) of that block, already executed: NC
    /// start after the restart goes on behind it instead of stopping there again.
    #[cfg_attr(feature = "serde", serde(default))]
    pub after_stop: bool,
}

/// A channel's resumable state.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ResumeState {
    pub retained: Retained,
    pub program: Option<ResumeProgram>,
    /// The inputs set from outside (the machine's wiring keeps them over a restart); the
    /// outputs start off, as after power on. `None` in checkpoints written before.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub inputs: Option<SavedInputs>,
    /// The stock being cut (`stock/saved.rs`). `None` without a blank and in checkpoints
    /// written before.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub stock: Option<super::SavedStock>,
    /// The program's positioning axes still on their way (POS/POSA/POSP): after the restart
    /// they travel on to their end points at NC start. Empty when none, and in checkpoints
    /// written before.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Vec::is_empty"))]
    pub positioning: Vec<super::SavedPositioning>,
    /// The workpiece counters and program runtimes (`counters.rs`): a restart keeps them, as
    /// the control's power on does. `None` while all are 0, and in checkpoints written before.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub counters: Option<super::SavedCounters>,
}

/// The inputs of a checkpoint.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SavedInputs {
    /// `$A_IN[n]` is bit n−1.
    pub digital: u64,
    /// `$A_INA[1..]`.
    pub analog: Vec<f64>,
}

impl Channel {
    /// The resumable state now (for a checkpoint).
    pub fn resume_state(&self) -> ResumeState {
        let (mut state, text) = self.resume_state_shared();
        if let (Some(program), Some(text)) = (state.program.as_mut(), text) {
            program.text = text.to_string();
        }
        state
    }

    /// The resumable state without a copy of the AUTO program's text (up to the program size
    /// limit, unchanged from one checkpoint to the next): its `program.text` is empty, and the
    /// shared text comes beside it.
    pub fn resume_state_shared(&self) -> (ResumeState, Option<ProgramText>) {
        let active = matches!(self.status, Status::Running | Status::Stopped);
        // Stopped without feed hold, interruption or a pending search: at a programmed stop
        // (or a single-block stop, whose block has no stop to skip).
        // After a block search (a restart resumed here, say) the block's M0/M1 is still to come
        // unless the restore took it away: then it stays done for the next restart too.
        let stop_done = !self.search_approach || !self.pending.iter().any(|item| matches!(item, Item::Stop { kind: StopKind::M0 | StopKind::M1, line } if Some(*line) == self.current_line));
        let after_stop = self.status == Status::Stopped
            && !self.planner.is_held()
            && self.interrupted.is_none()
            && !self.repos_returning
            && stop_done;
        let text = self.program.as_ref().filter(|_| self.program_mode == Mode::Auto);
        let level = self.current_block.as_ref().and_then(|b| b.level.as_deref());
        let (line, path) = match self.current_line.filter(|_| active) {
            Some(line) => {
                let (line, path) = path_of(line, level);
                (Some(line), path)
            }
            None => (None, Vec::new()),
        };
        let program = text.map(|_| ResumeProgram { text: String::new(), line, path, after_stop });
        let (digital, analog) = (self.io.inputs, &self.sync.analog_in);
        let inputs = (digital != 0 || analog.iter().any(|v| *v != 0.0))
            .then(|| SavedInputs { digital, analog: analog.to_vec() });
        let stock = self.saved_stock();
        let positioning = if line.is_some() { self.saved_positioning() } else { Vec::new() };
        let retained = self.interp.retained();
        let counters = self.saved_counters();
        (ResumeState { retained, program, inputs, stock, positioning, counters }, text.cloned())
    }

    /// Takes back a saved resumable state; only in reset state with nothing moving. The
    /// retained state is all or nothing (an error names what no longer fits and changes
    /// nothing). A program comes back loaded; one that was active is then searched to its block
    /// in AUTO mode, and an alarm of that search is raised as in any block search.
    pub fn restore_resume_state(&mut self, state: &ResumeState) -> Result<(), CommandError> {
        if self.is_busy() || self.status != Status::Idle {
            return Err(CommandError::Busy("a saved state can only be restored in reset state"));
        }
        let machine = self.machine;
        self.interp.restore_retained(&state.retained, &self.cfg, &machine).map_err(CommandError::Invalid)?;
        self.offsets = self.interp.offsets();
        // The online offset is in force at once, without a ramp: no axis moves.
        self.toff = super::tools::toff::OnlineOffset::at(self.offsets.toff);
        self.adopt_transformation();
        if let Some(inputs) = &state.inputs {
            self.restore_inputs(inputs.digital, &inputs.analog);
        }
        if let Some(counters) = &state.counters {
            self.restore_counters(counters);
        }
        let Some(program) = &state.program else {
            self.restore_saved_stock(state);
            return Ok(());
        };
        CommandError::check(&program.text)?;
        match program.line {
            None => {
                self.set_active_program(ProgramText::from(program.text.as_str()));
                self.program_mode = Mode::Auto;
                self.restore_saved_stock(state);
                Ok(())
            }
            Some(main_line) => {
                self.set_mode(Mode::Auto)?;
                self.block_search_at(Some(&program.text), main_line, &program.path)?;
                let line = program.path.last().map_or(main_line, |s| s.line);
                if program.after_stop && self.status == Status::Stopped {
                    let stop = self.pending.iter().position(
                        |item| matches!(item, Item::Stop { kind: StopKind::M0 | StopKind::M1, line: l } if *l == line),
                    );
                    if let Some(i) = stop {
                        self.pending.remove(i);
                    }
                }
                self.restore_saved_stock(state);
                self.restore_positioning(&state.positioning).map_err(CommandError::Invalid)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settle(ch: &mut Channel) {
        for _ in 0..1_000_000 {
            if !ch.is_busy() {
                return;
            }
            ch.step();
        }
        panic!("still busy");
    }

    /// The saved channel's machine position and state on a new channel of the same data.
    fn restart(ch: &Channel, extra: &str) -> Channel {
        let mut new = Channel::from_preset("mill5-head-ca", extra).expect("preset");
        new.restore_positions(ch.axis_positions()).expect("positions");
        new.restore_resume_state(&ch.resume_state()).expect("restore");
        new
    }

    fn wcs(ch: &Channel, axis: &str) -> f64 {
        ch.snapshot().workpiece.iter().find(|(n, _)| n == axis).map(|(_, v)| *v).expect("axis")
    }

    #[test]
    fn a_transformation_kept_over_reset_comes_back_with_the_tool_tip_where_it_was() {
        // RESET_MODE_MASK bit 7: TRAORI stays after M30; the CA head at A30 with the tool tip at
        // WCS (0, 0, 50), as programmed.
        let md = "$MC_RESET_MODE_MASK='H81'";
        let mut ch = Channel::from_preset("mill5-head-ca", md).expect("preset");
        ch.run_program("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\nM30").expect("run");
        settle(&mut ch);
        let new = restart(&ch, md);
        assert_eq!(new.snapshot().transformation.map(|t| t.name), Some("TRAORI".to_string()));
        assert_eq!(new.snapshot().tool, (1, 1));
        for (axis, want) in [("X", 0.0), ("Y", 0.0), ("Z", 50.0)] {
            assert!((wcs(&new, axis) - want).abs() < 1e-9, "{axis}: {}", wcs(&new, axis));
        }
        // Without bit 7 the transformation is not taken back (a reset would not keep it).
        let mut plain = ch.resume_state();
        plain.retained.transformation = None;
        let mut other = Channel::from_preset("mill5-head-ca", md).expect("preset");
        other.restore_resume_state(&plain).expect("restore");
        assert_eq!(other.snapshot().transformation, None);
    }

    #[test]
    fn a_program_stopped_at_m0_goes_on_behind_it_after_the_restart() {
        let mut ch = Channel::from_preset("mill5-head-ca", "").expect("preset");
        ch.run_program("G0 X1\nM0\nG0 X2\nM30").expect("run");
        settle(&mut ch);
        assert_eq!((ch.status(), ch.snapshot().block.map(|b| b.line)), (Status::Stopped, Some(2)));
        let saved = ch.resume_state();
        assert!(saved.program.as_ref().is_some_and(|p| p.after_stop && p.line == Some(2)), "{saved:?}");
        let new = restart(&ch, "");
        assert_eq!((new.status(), new.snapshot().block.map(|b| b.line)), (Status::Stopped, Some(2)));
        // A second restart before NC start still knows the M0 is done.
        let mut new = restart(&new, "");
        assert_eq!((new.status(), new.snapshot().block.map(|b| b.line)), (Status::Stopped, Some(2)));
        new.start().expect("NC start");
        settle(&mut new);
        // One NC start: no second stop at M0, the program ends at X2.
        assert_eq!(new.status(), Status::Idle);
        assert_eq!(new.snapshot().machine[0], ("X".to_string(), 2.0));
    }

    #[test]
    fn the_shared_state_hands_out_the_loaded_text_itself_not_a_copy() {
        let mut ch = Channel::from_preset("mill5-head-ca", "").expect("preset");
        ch.run_program("G0 X1\nM0\nG0 X2\nM30").expect("run");
        settle(&mut ch);
        let (state, text) = ch.resume_state_shared();
        let (_, again) = ch.resume_state_shared();
        let (text, again) = (text.expect("a program"), again.expect("a program"));
        assert!(text.shares_text_with(&again), "two checkpoints share one text");
        assert_eq!(&*text, "G0 X1\nM0\nG0 X2\nM30");
        assert_eq!(state.program.as_ref().map(|p| (p.text.as_str(), p.line)), Some(("", Some(2))));
        // The full state carries the text, and is the shared state with it put back.
        let mut full = state.clone();
        if let Some(p) = full.program.as_mut() {
            p.text = text.to_string();
        }
        assert_eq!(ch.resume_state(), full);
    }

    #[test]
    fn a_block_search_to_an_m0_keeps_the_stop_to_come_over_a_restart() {
        // The operator searched to line 2 (M0) and has not started: NC start stops at the M0,
        // before and after a restart.
        let mut ch = Channel::from_preset("mill5-head-ca", "").expect("preset");
        ch.set_mode(Mode::Auto).expect("auto");
        ch.block_search(Some("G0 X1\nM0\nG0 X2\nM30"), 2).expect("search");
        assert!(ch.resume_state().program.is_some_and(|p| !p.after_stop && p.line == Some(2)));
        let mut new = restart(&ch, "");
        new.start().expect("NC start");
        settle(&mut new);
        assert_eq!((new.status(), new.snapshot().block.map(|b| b.line)), (Status::Stopped, Some(2)));
    }

    #[test]
    fn the_online_tool_offset_comes_back_in_force_without_moving_an_axis() {
        // No tool, no transformation: TOFFON(Z, 5) adds 5 mm to the Z axis, so WCS Z10 is
        // machine Z15; after the restart WCS Z still reads 10 and G0 Z20 goes to machine Z25.
        let mut ch = Channel::from_preset("mill5-head-ca", "").expect("preset");
        ch.run_program("G0 X0 Y0 Z10\nTOFFON(Z, 5)\nG0 Z10\nM30").expect("run");
        settle(&mut ch);
        let z = |c: &Channel| c.snapshot().machine.iter().find(|(n, _)| n == "Z").map(|(_, v)| *v).expect("Z");
        assert!((z(&ch) - 15.0).abs() < 1e-9, "machine Z {}", z(&ch));
        assert_eq!(ch.resume_state().retained.toff, [0.0, 0.0, 5.0]);
        let mut new = restart(&ch, "");
        assert!((wcs(&new, "Z") - 10.0).abs() < 1e-9, "WCS Z {}", wcs(&new, "Z"));
        assert!(!new.is_busy(), "nothing moves");
        new.run_program("G0 Z20\nM30").expect("run");
        settle(&mut new);
        assert!((z(&new) - 25.0).abs() < 1e-9, "machine Z {}", z(&new));
    }

    #[test]
    fn a_search_in_a_stored_program_shares_its_text() {
        let mut ch = Channel::from_preset("mill5-head-ca", "").expect("preset");
        ch.store_program("PART", "G0 X1\nG0 X2\nM30").expect("store");
        ch.set_mode(Mode::Auto).expect("auto");
        assert!(ch.block_search_stored("nope", 2).is_err(), "an unknown name is refused");
        ch.block_search_stored("part.mpf", 2).expect("search");
        let (_, text) = ch.resume_state_shared();
        let stored = ch.programs.get("PART").cloned().map(ProgramText::from).expect("stored");
        assert_eq!(text.as_deref(), Some("G0 X1\nG0 X2\nM30"));
        // One allocation: the stored Arc<str> is what both point into.
        assert_eq!(text.map(|t| t.as_ptr()), Some(stored.as_ptr()));
        ch.start().expect("NC start");
        settle(&mut ch);
        assert_eq!(ch.snapshot().machine[0], ("X".to_string(), 2.0));
    }

    #[test]
    fn a_state_that_no_longer_fits_the_machine_data_changes_nothing() {
        let mut ch = Channel::from_preset("mill5-head-ca", "").expect("preset");
        let mut state = ch.resume_state();
        state.retained.tool = 1;
        state.retained.edge = 1;
        state.retained.holder.number = 7;
        let error = ch.restore_resume_state(&state).expect_err("no holder 7");
        assert!(error.to_string().contains("toolholder 7"), "{error}");
        assert_eq!(ch.snapshot().tool, (0, 0), "the tool was not taken either");
        state.retained.holder.number = 0;
        state.retained.r = vec![f64::NAN];
        assert!(ch.restore_resume_state(&state).is_err(), "R parameters must be finite");
    }
}
