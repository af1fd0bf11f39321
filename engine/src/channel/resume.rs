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

use super::{Channel, CommandError, Mode, Status};
use crate::interp::retained::Retained;
use crate::lang::ProgramText;

/// The AUTO program of a checkpoint.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ResumeProgram {
    pub text: String,
    /// The main run's block (1-based line) when the program was active; `None`: only loaded.
    pub line: Option<u32>,
}

/// A channel's resumable state.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ResumeState {
    pub retained: Retained,
    pub program: Option<ResumeProgram>,
}

impl Channel {
    /// The resumable state now (for a checkpoint).
    pub fn resume_state(&self) -> ResumeState {
        let active = matches!(self.status, Status::Running | Status::Stopped);
        let program = self
            .program
            .as_ref()
            .filter(|_| self.program_mode == Mode::Auto)
            .map(|text| ResumeProgram { text: text.to_string(), line: self.current_line.filter(|_| active) });
        ResumeState { retained: self.interp.retained(), program }
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
        self.adopt_transformation();
        let Some(program) = &state.program else { return Ok(()) };
        CommandError::check(&program.text)?;
        match program.line {
            None => {
                self.program = Some(ProgramText::from(program.text.as_str()));
                self.program_mode = Mode::Auto;
                Ok(())
            }
            Some(line) => {
                self.set_mode(Mode::Auto)?;
                self.block_search(Some(&program.text), line)
            }
        }
    }
}
