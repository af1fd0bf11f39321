//! Block display and single block suppression: `DISPLOF`/`DISPLON` and `SBLOF`/`SBLON`, on
//! a subprogram's PROC line and as block commands (Programming Manual, Job planning,
//! "Suppress current block display" and "Single block suppression").
//!
//! - `PROC .. DISPLOF`: while the subprogram runs the display shows its calling block;
//!   subprograms it calls are hidden with it unless their PROC line says `DISPLON`.
//! - `DISPLOF`/`DISPLON` in a block of a subprogram: the blocks after it are hidden or shown,
//!   as the PROC attribute would have it, until the other command or the return.
//! - `PROC .. SBLOF`: in single block mode the subprogram is no steps of its own: its blocks
//!   and the calling block (the positioning block of a modal call) are one step, so a standard
//!   cycle stops once, after the cycle.
//! - `SBLOF` in a block: the blocks after it, up to `SBLON` or the end of the level, are one
//!   step, named by the SBLOF block's line.
//!
//! Decisions where the manual is silent: the outermost suppression wins (an SBLON in a
//! subprogram called from a suppressed one does not give stops back; its DISPLON does show its
//! blocks, as the manual describes for the PROC attribute); DISPLOF/DISPLON in the main
//! program change nothing (there is no calling block to show).

use super::CallFrame;
use crate::interp::Interpreter;
use crate::lang::{Block, ProcAttributes, Word};

/// What one program level's PROC line and block commands switched.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(in crate::interp) struct LevelCommands {
    /// `Some(false)` hidden (DISPLOF), `Some(true)` shown (DISPLON), `None` as the caller.
    display: Option<bool>,
    /// The line of the `SBLOF` block in force at this level.
    sblof_at: Option<u32>,
}

impl LevelCommands {
    /// The state a subprogram starts in after its PROC line.
    pub fn of_proc(attributes: ProcAttributes) -> LevelCommands {
        let display = match (attributes.displon, attributes.displof) {
            (true, _) => Some(true),
            (false, true) => Some(false),
            (false, false) => None,
        };
        LevelCommands { display, sblof_at: None }
    }
}

/// The outermost of the innermost run of hidden levels: its calling block is shown while the
/// blocks being prepared run. `None` while they are shown as themselves.
pub(super) fn outermost_hiding(calls: &[CallFrame]) -> Option<usize> {
    let mut hidden_from = None;
    for (i, frame) in calls.iter().enumerate() {
        match frame.commands.display.filter(|_| frame.bound) {
            Some(false) if hidden_from.is_none() => hidden_from = Some(i),
            Some(true) => hidden_from = None,
            _ => {}
        }
    }
    hidden_from
}

impl Interpreter {
    /// Takes the block commands SBLOF, SBLON, DISPLOF and DISPLON of `block` (prepared just
    /// now) for the blocks after it at this level.
    pub(in crate::interp) fn level_commands(&mut self, block: &Block) {
        for word in &block.words {
            let Word::Keyword { name, args } = word else { continue };
            if !args.is_empty() {
                continue;
            }
            let in_main = self.calls.is_empty();
            let commands = match self.calls.last_mut() {
                Some(frame) => &mut frame.commands,
                None => &mut self.call_state.main_commands,
            };
            match name.as_str() {
                "SBLOF" => commands.sblof_at = Some(block.line),
                "SBLON" => commands.sblof_at = None,
                "DISPLOF" if !in_main => commands.display = Some(false),
                "DISPLON" if !in_main => commands.display = Some(true),
                _ => {}
            }
        }
    }

    /// The line single block counts the blocks being prepared to, when SBLOF suppresses its
    /// stops: the block that called the outermost `PROC .. SBLOF` subprogram, or the outermost
    /// `SBLOF` block in force. `None`: each block is a step of its own.
    pub fn single_block_anchor(&self) -> Option<u32> {
        if let Some(line) = self.call_state.main_commands.sblof_at {
            return Some(line);
        }
        self.calls.iter().filter(|f| f.bound).find_map(|f| match f.attributes.sblof {
            true => f.level.calls.last().map(|&(line, _)| line),
            false => f.commands.sblof_at,
        })
    }
}
