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
//!
//! The target is a position in the call chain, as on the control: a main program line, then for
//! each subprogram level the program its caller's line calls and the line in it
//! ([`PathStep`]). A block is the target when it is read at that line in a level reached through
//! exactly those calls (the interpreter's [`Level`]); the subprograms' blocks before it are
//! prepared like the main program's. The target block is found when it is read, even if it puts
//! out nothing: a target line that calls a subprogram stops before the subprogram runs.
//!
//! A search is not limited by the blocks a real program needs before its target: it asks its
//! caller every [`SEARCH_ASK_EVERY`] blocks whether to go on ([`Channel::block_search_with`];
//! the server bounds it by wall time) and otherwise stops at [`SEARCH_BLOCK_BUDGET`] blocks, a
//! program that loops without end, with alarm 15370.

use std::sync::Arc;

use super::{Channel, CommandError, Mode, MoveMeta, Status};
use crate::alarm::{Alarm, Clear};
use crate::interp::{Item, Level, Prep, SharedOffsets, StopKind};
use crate::lang::ProgramText;
use crate::motion::{Feed, Move};

/// Most blocks a search prepares before it gives up with alarm 15370 (a program that loops
/// without end must not hold the channel), unless the caller decides with
/// [`Channel::block_search_with`]. A real control searches any length; this is far beyond any
/// program whose target is reached at all (a release build prepares two to three million
/// blocks a second: a search that runs into the limit takes seconds).
pub const SEARCH_BLOCK_BUDGET: usize = 20_000_000;

/// How often (in blocks) a search asks its caller whether to go on.
pub const SEARCH_ASK_EVERY: usize = 65_536;

/// One step of a block search target into a subprogram: the program the line of the level
/// above calls, and the line (1-based) in it.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PathStep {
    /// The called program's stored name (`HOLE`, `hole.spf`: upper-cased, the ending dropped).
    pub program: String,
    pub line: u32,
}

/// The position of a block in the call chain, as [`Channel::block_search_at`] takes it: its
/// main program line, then one step per subprogram level.
pub(super) fn chain_of(line: u32, path: &[PathStep]) -> Vec<(u32, String)> {
    let callers = std::iter::once(line).chain(path.iter().map(|s| s.line));
    callers.zip(path).map(|(l, s)| (l, s.program.clone())).collect()
}

/// A block's position as a main program line and the steps into subprograms (the inverse of
/// [`chain_of`]): `line` in `level`.
pub(super) fn path_of(line: u32, level: Option<&Level>) -> (u32, Vec<PathStep>) {
    let Some(level) = level.filter(|l| !l.calls.is_empty()) else { return (line, Vec::new()) };
    let lines = level.calls.iter().skip(1).map(|(l, _)| *l).chain(std::iter::once(line));
    let path =
        level.calls.iter().zip(lines).map(|((_, name), line)| PathStep { program: name.clone(), line }).collect();
    (level.calls[0].0, path)
}

impl Channel {
    /// Block search with calculation to `line` (1-based) of `text`, or of the active program
    /// when `text` is `None`. AUTO mode in reset state only.
    ///
    /// Refused (nothing changes) for a line beyond the text or a line without a block. A target
    /// that preparation never reaches (skipped by a jump, after the program end, or beyond
    /// [`SEARCH_BLOCK_BUDGET`] blocks) raises alarm 15370; an alarm of a block before the target
    /// is raised as in a run.
    pub fn block_search(&mut self, text: Option<&str>, line: u32) -> Result<(), CommandError> {
        self.block_search_at(text, line, &[])
    }

    /// [`Channel::block_search`] to a block inside subprograms: `line` of the main program
    /// calls `path[0].program`, whose line `path[0].line` is the target or calls
    /// `path[1].program`, and so on; the last step's line is the target. The search stops at
    /// the first time preparation reaches that block through that chain of calls (the blocks
    /// of the subprograms before the target are computed like the main program's). An empty
    /// path is the main program's `line`. Each step must name a stored program and a line of
    /// it holding a block.
    pub fn block_search_at(&mut self, text: Option<&str>, line: u32, path: &[PathStep]) -> Result<(), CommandError> {
        self.block_search_with(text, None, line, path, &mut |blocks| blocks < SEARCH_BLOCK_BUDGET)
    }

    /// [`Channel::block_search_at`] in `text`, or in stored program `name`, or in the active
    /// program, asking `go_on` every [`SEARCH_ASK_EVERY`] blocks (with the number of blocks
    /// prepared so far) whether to go on instead of stopping at [`SEARCH_BLOCK_BUDGET`]: the
    /// server bounds a search by wall time this way (the engine knows no clock). A search
    /// `go_on` ends raises alarm 15370 naming how many blocks it prepared.
    pub fn block_search_with(
        &mut self,
        text: Option<&str>,
        name: Option<&str>,
        line: u32,
        path: &[PathStep],
        go_on: &mut dyn FnMut(usize) -> bool,
    ) -> Result<(), CommandError> {
        self.search_allowed()?;
        if let Some(name) = name {
            let text = self
                .programs
                .get(&super::programs::program_name(name)?)
                .cloned()
                .ok_or_else(|| CommandError::Invalid(format!("no stored program `{name}`")))?;
            return self.block_search_text(Some(ProgramText::from(text)), line, path, go_on);
        }
        let text = match text {
            Some(t) => {
                CommandError::check(t)?;
                Some(ProgramText::from(t))
            }
            None => None,
        };
        self.block_search_text(text, line, path, go_on)
    }

    /// [`Channel::block_search`] in stored program `name`, sharing its text (no copy of up to
    /// the program size limit; it was checked when it was stored).
    pub fn block_search_stored(&mut self, name: &str, line: u32) -> Result<(), CommandError> {
        self.block_search_stored_at(name, line, &[])
    }

    /// [`Channel::block_search_at`] in stored program `name` (see
    /// [`Channel::block_search_stored`]).
    pub fn block_search_stored_at(&mut self, name: &str, line: u32, path: &[PathStep]) -> Result<(), CommandError> {
        self.block_search_with(None, Some(name), line, path, &mut |blocks| blocks < SEARCH_BLOCK_BUDGET)
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

    fn block_search_text(
        &mut self,
        text: Option<ProgramText>,
        line: u32,
        path: &[PathStep],
        go_on: &mut dyn FnMut(usize) -> bool,
    ) -> Result<(), CommandError> {
        self.search_allowed()?;
        let text: ProgramText = match text {
            Some(t) => t,
            None => self
                .program
                .clone()
                .ok_or_else(|| CommandError::Invalid("no program loaded: give the program text to search in".into()))?,
        };
        check_target_line(&text, line, None)?;
        let mut steps = Vec::with_capacity(path.len());
        for step in path {
            let name = super::programs::program_name(&step.program)?;
            let sub = self
                .programs
                .get(&name)
                .ok_or_else(|| CommandError::Invalid(format!("no stored program `{}` to search in", step.program)))?;
            check_target_line(sub, step.line, Some(&name))?;
            steps.push(PathStep { program: name, line: step.line });
        }
        let chain = chain_of(line, &steps);
        let target = steps.last().map_or(line, |s| s.line);

        self.set_active_program(text.clone());
        self.program_mode = Mode::Auto;
        self.queued_blocks.clear();
        self.current_block = None;
        self.pending.clear();
        self.end_orison_run();
        self.prep_done = false;
        self.prep_waits_for_trafo = false;
        self.search_approach = false;
        self.interp.begin_program(text.clone(), &self.machine);
        self.interp.set_searching(true);
        let searched = self.search_to(target, &chain, go_on);
        self.interp.set_searching(false);
        match searched {
            Ok(level) => {
                self.queued_blocks.clear();
                self.queue_block(target, level);
                self.prev_read = super::main_run::ReadBlock::default();
                self.search_approach = true;
                self.status = Status::Stopped;
                // The program goes on from here at NC start: its runtimes count on (a restart
                // resumed this way keeps the cycle time its checkpoint had).
                self.resume_runtimes();
                self.enter_block(target, super::pending::NO_SEQ);
            }
            Err(alarm) => self.raise(alarm),
        }
        Ok(())
    }

    /// Prepares blocks until the block at `line` of the program level reached through the
    /// calls `chain` (empty: the main program); leaves the collected output and the target's
    /// items in `pending` and returns the target's level.
    fn search_to(
        &mut self,
        line: u32,
        chain: &[(u32, String)],
        go_on: &mut dyn FnMut(usize) -> bool,
    ) -> Result<Option<Arc<Level>>, Alarm> {
        let mut trafo = self.trafo.clone();
        let mut machine = self.machine;
        let mut offsets: Option<SharedOffsets> = None;
        let mut spindles: Vec<Item> = Vec::new();
        let mut message: Option<Item> = None;
        let mut blank: Option<Item> = None;
        let mut out = Vec::new();
        let mut blocks = 0usize;
        loop {
            if blocks > 0 && blocks.is_multiple_of(SEARCH_ASK_EVERY) && !go_on(blocks) {
                return Err(search_given_up(line, blocks));
            }
            blocks += 1;
            out.clear();
            let generation = self.interp.transformation_generation();
            // The target is a line of one program level: a block of another level (a
            // subprogram, or the same one called from elsewhere) with that line is not it.
            let at_level = match self.interp.level() {
                None => chain.is_empty(),
                Some(level) => level.calls == chain,
            };
            let level = if at_level { self.interp.level().cloned() } else { None };
            self.hand_program_control();
            let prep = self.interp.prepare_next(&self.cfg, &self.programs, true, &mut out);
            // The block read is the target even when it puts out nothing (a call: the search
            // stops before the subprogram runs; an R parameter assignment).
            let read_target = at_level && self.interp.read_line() == line;
            let trafo_changed = self.interp.transformation_generation() != generation;
            // Blocks passed by the search do not run: what they would report does not show.
            self.interp.take_warnings();
            let writes = self.interp.take_data_writes();
            if !writes.is_empty() {
                for (l, data) in writes {
                    self.apply_program_data(l, &data)?;
                }
                self.publish_stored_data();
            }
            let found = out
                .iter()
                .position(|i| at_level && i.line() == Some(line) && !matches!(i, Item::Alarm(_)))
                .or_else(|| read_target.then_some(out.len()));
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
                    Item::SpindleControl { ctl: crate::interp::spindles::Control::ThreadStart { .. }, .. } => {}
                    Item::SpindleControl { .. } => spindles.push(item),
                    Item::Spindle { axis, .. } | Item::SpindleToAxis { axis, .. } => {
                        spindles.retain(|s| !matches!(s, Item::Spindle { axis: a, .. } | Item::SpindleToAxis { axis: a, .. } if *a == axis));
                        spindles.push(item);
                    }
                    Item::Message { .. } => message = Some(item),
                    // The last blank of the skipped blocks is defined (uncut: their motion does not run).
                    Item::Workpiece { .. } => blank = Some(item),
                    // Auxiliary functions and outputs of skipped blocks are not put out.
                    Item::Dwell { .. }
                    | Item::Stop { kind: StopKind::M0 | StopKind::M1, .. }
                    | Item::Aux { .. }
                    | Item::DigitalOutput { .. }
                    | Item::MainRunWrite { .. }
                    | Item::SyncAction { .. }
                    | Item::SyncControl { .. }
                    | Item::SetPiece { .. }
                    | Item::Measure { .. }
                    // Positioning axes: the approach move takes them to where the
                    // interpreter left them (the skipped blocks' targets).
                    | Item::Positioning { .. }
                    | Item::WaitPositioning { .. } => {}
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
                    self.trafo_selection = None;
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
                self.pending.extend(blank);
                self.pending.extend(rest);
                self.prep_done = prep == Prep::Done;
                return Ok(level);
            }
            if prep == Prep::Done {
                return Err(target_not_found(line));
            }
        }
    }

    /// The approach after a block search: from where the axes stand to the start of the target's
    /// first move, moving like that move.
    pub(super) fn push_approach(&mut self, target: &Move, line: u32, offsets: &SharedOffsets) {
        let start = if target.machine_space { self.machine } else { *self.planner.position() };
        let feed = if target.is_rapid() { Feed::Rapid } else { Feed::Path(target.feed) };
        let mut mv = self.straight_move(start, target.path.start, feed);
        mv.machine_space = target.machine_space;
        let meta = MoveMeta {
            line,
            seq: super::pending::NO_SEQ,
            offsets: offsets.clone(),
            machine_space: target.machine_space,
            feed: 0.0,
        };
        self.push_bcs_move(mv, meta);
    }
}

fn set_line(item: &mut Item, to: u32) {
    match item {
        Item::Spindle { line, .. }
        | Item::SpindleControl { line, .. }
        | Item::SpindleToAxis { line, .. }
        | Item::Message { line, .. } => *line = to,
        _ => {}
    }
}

/// Refuses a search target line that is not in `text` or holds no block; `program` names a
/// subprogram's text in the message.
fn check_target_line(text: &str, line: u32, program: Option<&str>) -> Result<(), CommandError> {
    let of = program.map(|p| format!(" of {p}")).unwrap_or_default();
    let lines = text.lines().count();
    if line == 0 || line as usize > lines {
        return Err(CommandError::Invalid(format!(
            "line {line}{of} does not exist: the program has {lines} line{}",
            if lines == 1 { "" } else { "s" }
        )));
    }
    let source = text.lines().nth(line as usize - 1).unwrap_or("").trim();
    if source.is_empty() || source.starts_with(';') {
        return Err(CommandError::Invalid(format!("line {line}{of} holds no block (empty or a comment)")));
    }
    Ok(())
}

/// 15370 when the search gave up after `blocks` blocks (see [`Channel::block_search_with`]).
fn search_given_up(line: u32, blocks: usize) -> Alarm {
    Alarm {
        number: 15370,
        message: format!(
            "Channel 1 search target not found in block search (line {line}): search limit reached after {blocks} blocks"
        ),
        line: Some(line),
        clear: Clear::Reset,
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
