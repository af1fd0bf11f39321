//! Block search with calculation (SERUPRO-like "search with calculation to the contour").
//!
//! The interpreter runs the program from its start to the target line without motion: every
//! block before the target is prepared as in a run, so the modal state (G groups, feed), the
//! tool and its offsets, frames, the transformation, R parameters and variables, and the
//! programmed position are what they would be at the target. Of what the skipped blocks would
//! have done in the main run, the last state counts and is output at NC start before anything
//! else (as the control outputs collected auxiliary functions): the offsets and transformation,
//! the spindle commands (speed and direction, SPOS) per spindle and the last MSG text. Dwells and
//! programmed stops before the target are skipped.
//!
//! After the search the channel is stopped at the target (status `stopped`, the target block
//! shown). NC start executes the collected output, then approaches the start point of the first
//! move of the target block on a straight line (with that move's feed, rapid traverse for G0;
//! with a transformation active in the BCS) and continues with the target block. Axes may be
//! jogged between search and NC start; the approach starts from wherever they are.

use super::main_run::line_offset;
use super::{Channel, CommandError, Mode, MoveMeta, Status};
use crate::alarm::{Alarm, Clear};
use crate::interp::{Item, Prep, SharedOffsets, StopKind};
use crate::lang::ProgramText;
use crate::motion::{Feed, Move};

/// Most blocks a search prepares before it gives up (a program that loops without end).
pub const SEARCH_BLOCK_BUDGET: usize = 200_000;

impl Channel {
    /// Block search with calculation to `line` (1-based) of `text`, or of the active program
    /// when `text` is `None`. AUTO mode in reset state only.
    ///
    /// Refused (nothing changes) for a line beyond the text or a line without a block. A target
    /// that preparation never reaches (skipped by a jump, after the program end, or beyond
    /// [`SEARCH_BLOCK_BUDGET`] blocks) raises alarm 15370; an alarm of a block before the target
    /// is raised as in a run.
    pub fn block_search(&mut self, text: Option<&str>, line: u32) -> Result<(), CommandError> {
        self.search_allowed()?;
        let text = match text {
            Some(t) => {
                CommandError::check(t)?;
                Some(ProgramText::from(t))
            }
            None => None,
        };
        self.block_search_text(text, line)
    }

    /// [`Channel::block_search`] in stored program `name`, sharing its text (no copy of up to
    /// the program size limit; it was checked when it was stored).
    pub fn block_search_stored(&mut self, name: &str, line: u32) -> Result<(), CommandError> {
        let text = self
            .programs
            .get(&super::programs::program_name(name)?)
            .cloned()
            .ok_or_else(|| CommandError::Invalid(format!("no stored program `{name}`")))?;
        self.block_search_text(Some(ProgramText::from(text)), line)
    }

    /// Whether a block search may start now: AUTO mode, reset state, no alarm.
    fn search_allowed(&self) -> Result<(), CommandError> {
        if self.mode != Mode::Auto {
            return Err(CommandError::WrongMode(self.mode.as_str(), "block search needs AUTO mode"));
        }
        if self.status == Status::Alarm {
            return Err(CommandError::AlarmActive);
        }
        if self.is_busy() || self.status == Status::Stopped {
            return Err(CommandError::Busy("a program is active; reset it before a block search"));
        }
        Ok(())
    }

    fn block_search_text(&mut self, text: Option<ProgramText>, line: u32) -> Result<(), CommandError> {
        self.search_allowed()?;
        let text: ProgramText = match text {
            Some(t) => t,
            None => self
                .program
                .clone()
                .ok_or_else(|| CommandError::Invalid("no program loaded: give the program text to search in".into()))?,
        };
        let lines = text.lines().count();
        if line == 0 || line as usize > lines {
            return Err(CommandError::Invalid(format!(
                "line {line} does not exist: the program has {lines} line{}",
                if lines == 1 { "" } else { "s" }
            )));
        }
        let source = text.lines().nth(line as usize - 1).unwrap_or("").trim();
        if source.is_empty() || source.starts_with(';') {
            return Err(CommandError::Invalid(format!("line {line} holds no block (empty or a comment)")));
        }

        self.program = Some(text.clone());
        self.program_mode = Mode::Auto;
        self.queued_blocks.clear();
        self.pending.clear();
        self.prep_done = false;
        self.prep_waits_for_trafo = false;
        self.search_approach = false;
        self.interp.begin_program(text.clone(), &self.machine);
        match self.search_to(line) {
            Ok(()) => {
                self.queued_blocks.push_back((line, line_offset(&text, line, None)));
                self.search_approach = true;
                self.status = Status::Stopped;
                self.enter_block(line);
            }
            Err(alarm) => self.raise(alarm),
        }
        Ok(())
    }

    /// Prepares blocks until the first item of `line`; leaves the collected output and the
    /// target's items in `pending`.
    fn search_to(&mut self, line: u32) -> Result<(), Alarm> {
        let mut trafo = self.trafo.clone();
        let mut machine = self.machine;
        let mut offsets: Option<SharedOffsets> = None;
        let mut spindles: Vec<Item> = Vec::new();
        let mut message: Option<Item> = None;
        let mut out = Vec::new();
        for _ in 0..SEARCH_BLOCK_BUDGET {
            out.clear();
            let generation = self.interp.transformation_generation();
            // The target is a line of the main program: a block of a subprogram with the same
            // line number is not it.
            let in_main_program = self.interp.call_depth() == 0;
            let prep = self.interp.prepare_next(&self.cfg, &self.programs, true, &mut out);
            let trafo_changed = self.interp.transformation_generation() != generation;
            // Blocks passed by the search do not run: what they would report does not show.
            self.interp.take_warnings();
            for (l, data) in self.interp.take_data_writes() {
                self.apply_program_data(l, &data)?;
            }
            let found =
                out.iter().position(|i| in_main_program && i.line() == Some(line) && !matches!(i, Item::Alarm(_)));
            let rest = out.split_off(found.unwrap_or(out.len()));
            let mut trafo_switched = false;
            for item in out.drain(..) {
                match item {
                    Item::Move { mv, offsets: o, .. } => {
                        machine = if mv.machine_space {
                            mv.path.end
                        } else {
                            match &o.trafo {
                                Some(t) => t.inverse(&mv.path.end, &machine).unwrap_or(machine),
                                None => mv.path.end,
                            }
                        };
                        offsets = Some(o);
                    }
                    Item::Offsets { offsets: o, .. } => {
                        if o.trafo != trafo {
                            trafo = o.trafo.clone();
                            trafo_switched = true;
                        }
                        offsets = Some(o);
                    }
                    Item::Spindle { axis, .. } | Item::SpindleToAxis { axis, .. } => {
                        spindles.retain(|s| !matches!(s, Item::Spindle { axis: a, .. } | Item::SpindleToAxis { axis: a, .. } if *a == axis));
                        spindles.push(item);
                    }
                    Item::Message { .. } => message = Some(item),
                    Item::Dwell { .. } | Item::Stop { kind: StopKind::M0 | StopKind::M1, .. } => {}
                    Item::Stop { kind: StopKind::End, .. } => return Err(target_not_found(line)),
                    Item::Alarm(alarm) => return Err(alarm),
                }
            }
            if trafo_changed {
                if trafo_switched {
                    // The selection was skipped: preparation goes on from the machine position
                    // the skipped blocks would have reached.
                    self.interp.sync_transformation(&machine);
                } else {
                    // The target selects it: the main run executes it after NC start.
                    self.prep_waits_for_trafo = true;
                }
            }
            if found.is_some() {
                let line_of = |o: SharedOffsets| Item::Offsets { line, offsets: o };
                self.pending.extend(offsets.map(line_of));
                self.pending.extend(spindles.into_iter().map(|mut s| {
                    set_line(&mut s, line);
                    s
                }));
                self.pending.extend(message.map(|mut m| {
                    set_line(&mut m, line);
                    m
                }));
                self.pending.extend(rest);
                self.prep_done = prep == Prep::Done;
                return Ok(());
            }
            if prep == Prep::Done {
                return Err(target_not_found(line));
            }
        }
        Err(target_not_found(line))
    }

    /// The approach after a block search: from where the axes stand to the start of the target's
    /// first move, moving like that move.
    pub(super) fn push_approach(&mut self, target: &Move, line: u32, offsets: &SharedOffsets) {
        let start = if target.machine_space { self.machine } else { *self.planner.position() };
        let feed = if target.is_rapid() { Feed::Rapid } else { Feed::Path(target.feed) };
        let mut mv = self.straight_move(start, target.path.start, feed);
        mv.machine_space = target.machine_space;
        let meta = MoveMeta { line, offsets: offsets.clone(), machine_space: target.machine_space, feed: 0.0 };
        self.push_bcs_move(mv, meta);
    }
}

fn set_line(item: &mut Item, to: u32) {
    match item {
        Item::Spindle { line, .. } | Item::SpindleToAxis { line, .. } | Item::Message { line, .. } => *line = to,
        _ => {}
    }
}

/// 15370: the search target was not found.
fn target_not_found(line: u32) -> Alarm {
    Alarm {
        number: 15370,
        message: format!("Channel 1 search target not found in block search (line {line})"),
        line: Some(line),
        clear: Clear::Reset,
    }
}
