//! The main run of a program: block preparation ahead of the interpolator, handing moves to
//! the planner, executing the non-motion items in order, program stop and end, alarms.

use std::sync::Arc;

use super::pending::NO_SEQ;
use super::{BlockRef, Channel, Event, LOOKAHEAD, MAX_BLOCKS_PER_CYCLE, MoveMeta, Status};
use crate::alarm::{Alarm, Clear};
use crate::interp::program_control::{DryRunFeed, ProgramControl};
use crate::interp::synchronized::MainRunWrite;
use crate::interp::synchronized::flat::Target;
use crate::interp::{CORRTRAFO, DELOBJ, Item, Level, NEWCONF, Prep, StopKind};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{AxisLimit, AxisVec, Move};

impl Channel {
    /// Block preparation: interpret blocks until the look-ahead is full.
    #[inline]
    pub(super) fn prepare(&mut self) {
        // Most cycles find the look-ahead full: nothing to do then.
        if self.program.is_none()
            || self.prep_done
            || self.prep_waits_for_trafo
            || self.pending.len() + self.planner.len() >= LOOKAHEAD
        {
            return;
        }
        self.prepare_blocks();
    }

    /// The program stands at a preprocessing stop: block preparation waits for the main run
    /// (STOPRE, a read of main-run values, a DELDTG's successor) and the path has nothing
    /// left to execute, while something else of the main run still has to finish (a POSA
    /// axis travelling, an online tool offset settling). Not a dwell: that has its own reason.
    /// While the path still runs the blocks before the stop, the channel does not stand; once
    /// all is done the next IPO cycle goes on, so only a wait that lasts shows.
    pub fn stands_at_preprocessing_stop(&self) -> bool {
        self.status == Status::Running
            && self.program.is_some()
            && !self.prep_done
            && self.blending.prep_waits_for_main_run
            && self.pending.is_empty()
            && self.planner.is_empty()
            && self.dwell_ticks == 0
            && self.jog.is_none()
            // Else the main run is done and the next cycle's preparation goes on.
            && (self.positioning.program_moving() || !self.toff.settled(&self.offsets.toff))
    }

    /// Hands SKP and DRY to the interpreter: they act on the blocks it prepares next.
    pub(super) fn hand_program_control(&mut self) {
        let (feed, mode) = self.cfg.dry_run_feed;
        let dry_run = self.dry_run.then(|| DryRunFeed::from_settings(feed, mode));
        self.interp.set_program_control(ProgramControl { dry_run, skip_levels: self.skip_levels });
    }

    /// [`Channel::prepare`]'s work, kept out of the IPO cycle's code: every cycle runs that
    /// code, only about one in fifty prepares a block, and the interpreter between them would
    /// otherwise push the cycle's instructions out of the cache.
    #[inline(never)]
    fn prepare_blocks(&mut self) {
        // A program's own writes to main-run data (`$AC_MARKER[1]=..`, a counter) reach a block
        // that waited for the main run to read them.
        self.hand_process_data();
        self.publish_sync_data();
        for s in self.spindles.iter().filter(|s| !s.axis_mode) {
            self.interp.observe_spindle(s.axis, s.position);
        }
        self.hand_program_control();
        let mut out = Vec::new();
        let mut budget = MAX_BLOCKS_PER_CYCLE;
        while !self.prep_done
            && !self.prep_waits_for_trafo
            && self.pending.len() + self.planner.len() < LOOKAHEAD
            && budget > 0
        {
            budget -= 1;
            let main_run_idle = self.pending.is_empty()
                && self.planner.is_empty()
                && self.dwell_ticks == 0
                && self.toff.settled(&self.offsets.toff)
                && !self.positioning.program_moving()
                // STOPREOF of a synchronized action: the preprocessing stop is over.
                || self.psync.stopreof;
            out.clear();
            let generation = self.interp.transformation_generation();
            // The level the block is read in (a call or return changes it after the read), and
            // the calling block shown instead while a DISPLOF subprogram runs.
            let level = self.interp.level().cloned();
            let hidden = self.interp.hidden_by_call();
            let step = self.interp.single_block_anchor();
            if self.psync.stopreof || self.positioning.has_command_axes() {
                // `$AA_IM` reads where the main run stands (`program_sync.rs`), `$AA_VACTM`
                // how fast it moves there.
                let velocity = self.main_run_velocity();
                self.interp.set_main_run_position(Some((self.machine, velocity)));
                self.psync.main_position_handed = true;
            } else if self.psync.main_position_handed {
                self.interp.set_main_run_position(None);
                self.psync.main_position_handed = false;
            }
            if main_run_idle && self.interp.axes_to_adopt() != 0 {
                // An oscillation has ended: preparation goes on from where the axis stands.
                self.interp.adopt_axes(&self.machine);
            }
            let mut prep = self.interp.prepare_next(&self.cfg, &self.programs, main_run_idle, &mut out);
            if prep != Prep::WaitForMainRun {
                self.psync.stopreof = false;
            }
            self.blending.prep_waits_for_main_run = prep == Prep::WaitForMainRun;
            // A transformation change: continue once the main run has executed it.
            self.prep_waits_for_trafo = self.interp.transformation_generation() != generation;
            if self.prep_waits_for_trafo {
                self.trafo_selection = mark_selection(&mut out, &self.interp);
            }
            for warning in self.interp.take_warnings() {
                // One entry per alarm number until it is cancelled: a contour near a pole
                // would otherwise list every block.
                if !self.alarms.iter().any(|a| a.number == warning.number) {
                    self.notify_alarm(warning);
                }
            }
            let writes = self.interp.take_data_writes();
            if !writes.is_empty() {
                for (line, text) in writes {
                    if let Err(alarm) = self.apply_program_data(line, &text) {
                        out.push(Item::Alarm(alarm));
                        prep = Prep::Done;
                        break;
                    }
                }
                self.publish_stored_data();
            }
            // Remember where each block is, for showing it while its items execute: the block
            // just read is in `level`; a move held back from the block before in that one's.
            let read = ReadBlock { line: self.interp.read_line(), level, hidden };
            let read_offset = self.interp.read_offset();
            let mut last = None;
            let mut seq = NO_SEQ;
            for item in out.drain(..) {
                if let Some(line) = item.line()
                    && last != Some(line)
                {
                    last = Some(line);
                    let block = if line != read.line && line == self.prev_read.line { &self.prev_read } else { &read };
                    seq = if let Some((call_line, caller)) = block.hidden.clone() {
                        // DISPLOF: the calling block stands for all of the subprogram's.
                        self.held_block_seq(call_line, caller)
                    } else if line == read.line {
                        // Where the block just read starts is known: no counting of lines (a
                        // loop's or a cycle's jump back would count from the text's start). A
                        // block read is a new block, whatever its line number.
                        self.queue_block_at(line, read_offset, read.level.clone())
                    } else {
                        // A move held back from the block before is still that block.
                        self.held_block_seq(line, block.level.clone())
                    };
                }
                self.pending.push_back(seq, step, item);
            }
            self.prev_read = read;
            match prep {
                Prep::Prepared => {}
                Prep::WaitForMainRun => break,
                Prep::Done => self.prep_done = true,
            }
        }
    }

    /// The axes' velocities (mm/min, deg/min) while the main run stands elsewhere than
    /// programmed: the path's last step after STOPREOF (at rest otherwise: the wait for the
    /// main run), the speed of each positioning and command axis.
    fn main_run_velocity(&self) -> AxisVec {
        let dt = self.cfg.ipo_cycle;
        let mut v = [0.0; MAX_CHANNEL_AXES];
        if self.psync.stopreof {
            for (k, v) in v.iter_mut().enumerate().take(self.cfg.channel_axes.len()) {
                *v = (self.machine[k] - self.psync.stopreof_from[k]) / dt * 60.0;
            }
        }
        for (k, v) in v.iter_mut().enumerate().take(self.cfg.channel_axes.len()) {
            if let Some(speed) = self.positioning.velocity(k) {
                *v = speed * 60.0;
            }
        }
        v
    }

    /// Applies data a program wrote: tool data and settable frames act at once, machine data
    /// waits for NEWCONF (or a reset).
    pub(super) fn apply_program_data(&mut self, line: u32, text: &str) -> Result<(), Alarm> {
        let bad = |message: String| Alarm::value_out_of_range(line, &message);
        if text == NEWCONF {
            let cfg = self.data.activate().map_err(|e| bad(format!("NEWCONF: {}", e.message)))?;
            if cfg.channel_axes != self.cfg.channel_axes || cfg.geo_axes != self.cfg.geo_axes {
                return Err(bad(
                    "NEWCONF cannot change the axis configuration while a program runs: reset instead".into()
                ));
            }
            self.planner.set_limits(AxisLimit::for_channel(&cfg));
            self.cfg = Arc::new(cfg);
            self.size_signals();
            // New velocities: the synchronized actions' horizons are computed again.
            self.sync.wake_all();
            return Ok(());
        }
        if let Some(kind) = text.strip_prefix(DELOBJ) {
            if let Some(range) = kind.strip_prefix("TOOLCARRIER:") {
                let mut bounds = range.split(':').map(|n| n.parse::<u32>().unwrap_or(0));
                let (start, end) = (bounds.next().unwrap_or(1), bounds.next().unwrap_or(u32::MAX));
                self.data.delete_carriers(start..=end);
                Arc::make_mut(&mut self.cfg).refresh_data(&self.data).map_err(|e| bad(e.message))?;
                return Ok(());
            }
            self.data.delete_kin(kind == "KIN_CHAIN_ELEM", kind == "TRAFO_DATA");
            return Ok(());
        }
        if let Some(t) = text.strip_prefix(crate::interp::DELT) {
            self.data.delete_tool(t.parse().map_err(|_| bad(text.to_string()))?);
            Arc::make_mut(&mut self.cfg).refresh_data(&self.data).map_err(|e| bad(e.message))?;
            return Ok(());
        }
        if let Some(n) = text.strip_prefix(CORRTRAFO) {
            // The corrected $NK_OFF_DIR came just before: the record's data set follows it.
            let n = n.parse().map_err(|_| bad(text.to_string()))?;
            Arc::make_mut(&mut self.cfg)
                .rebuild_chain_trafo(n)
                .map_err(|e| bad(format!("CORRTRAFO: {}", e.message)))?;
            return Ok(());
        }
        self.data.stage_text(text).map_err(|e| bad(format!("{text}: {}", e.message)))?;
        // Everything but machine data acts at once: tool data, frames, setting data (those the
        // typed configuration holds, e.g. SD42980, SD41610; the rest is read where it is used).
        if !text.starts_with("$M") {
            Arc::make_mut(&mut self.cfg).refresh_data(&self.data).map_err(|e| bad(e.message))?;
        }
        Ok(())
    }

    /// Hands consecutive moves from the front of the prepared items to the planner. A move
    /// followed by anything else ends with an exact stop.
    #[inline]
    pub(super) fn feed_planner(&mut self) {
        // A dwell (G4) is a standstill: the next move starts when it has run out. Most cycles
        // have no prepared move waiting.
        if self.dwell_ticks > 0 || !matches!(self.pending.front(), Some(Item::Move { .. })) {
            return;
        }
        self.feed_moves();
    }

    /// [`Channel::feed_planner`]'s work, out of the IPO cycle's code (see `prepare_blocks`).
    #[inline(never)]
    fn feed_moves(&mut self) {
        // RDISABLE of a synchronized action in this cycle: no block starts.
        if self.psync.rdisable {
            return;
        }
        // Single block: one block's moves at a time, and only once the last one is done. So
        // too while an action holds RDISABLE (`program_sync.rs`).
        let one_block = self.single_block || self.psync.rdisable_armed && self.sync.is_active();
        let single = one_block.then(|| self.pending.front_step());
        // A step SBLOF joins goes on as its blocks' moves come in, one block after another.
        let goes_on = single.is_some_and(|s| s.is_some() && s == self.sbl_step);
        if single.is_some() && !goes_on && (!self.planner.is_empty() || self.sbl_done.is_some()) {
            return;
        }
        while let Some(Item::Move { .. }) = self.pending.front() {
            if let Some(Some(step)) = single
                && self.pending.front_step() != Some(step)
            {
                break;
            }
            // Continuous-path rounding: the corner needs the next move.
            if single.is_none() && self.waits_for_corner() {
                break;
            }
            let Some(Item::Move { mut mv, line, offsets }) = self.pending.pop_front() else { unreachable!() };
            let seq = self.pending.popped_seq();
            let step = self.pending.popped_step();
            self.sbl_step = single.map(|_| step);
            if self.search_approach {
                // Block search: approach the start of the first move of the target, like that move.
                self.search_approach = false;
                self.push_approach(&mv, line, &offsets);
            }
            // Anything but a move next (a dwell, a stop, the end) needs standstill first.
            let next_is_other = self.pending.front().is_some_and(|i| {
                !matches!(i, Item::Move { .. }) || single.is_some() && self.pending.front_step() != Some(step)
            });
            let programmed_stop = mv.exact_stop;
            if next_is_other || single.is_some() && self.pending.is_empty() {
                mv.exact_stop = true;
            }
            // A change of the transformation or of the tool it includes needs standstill too.
            if matches!(self.pending.front(), Some(Item::Move { offsets: next, .. }) if next.trafo != offsets.trafo) {
                mv.exact_stop = true;
            }
            if mv.exact_stop && !programmed_stop {
                // The move is pushed next: its tag is `next_tag`.
                self.exact_stop.implicit(self.next_tag);
            }
            let corner = if single.is_some() {
                if mv.orison.is_some() {
                    // A head of ORISON's last zone is planned; no new zone in single block.
                    self.smooth_orientation(&mut mv, false);
                }
                None
            } else {
                self.round_corner(&mut mv)
            };
            let machine_space = mv.machine_space;
            match corner {
                Some(corner) => {
                    self.push_move(mv, MoveMeta { line, seq, offsets: offsets.clone(), machine_space, feed: 0.0 });
                    if self.blending.more.is_empty() {
                        self.push_move(corner, MoveMeta { line, seq, offsets, machine_space, feed: 0.0 });
                    } else {
                        self.push_chain(corner, MoveMeta { line, seq, offsets, machine_space, feed: 0.0 });
                    }
                }
                None => self.push_move(mv, MoveMeta { line, seq, offsets, machine_space, feed: 0.0 }),
            }
        }
    }

    /// Pushes a rounding element and the chain after it (G643, `Blending::more`).
    #[inline(never)]
    fn push_chain(&mut self, corner: Move, meta: MoveMeta) {
        self.push_move(corner, meta.clone());
        for piece in std::mem::take(&mut self.blending.more) {
            self.push_move(piece, meta.clone());
        }
    }

    pub(super) fn push_move(&mut self, mut mv: Move, meta: MoveMeta) {
        let meta = MoveMeta { feed: mv.feed, ..meta };
        mv.tag = self.next_tag;
        self.next_tag = self.next_tag.wrapping_add(1);
        self.in_planner.push_back((mv.tag, meta));
        self.planner.push(mv);
        if !self.sync.active.is_empty() {
            self.note_pushed_move();
        }
        self.sync_current_block();
    }

    #[inline]
    pub(super) fn retire_finished_moves(&mut self) {
        // Most cycles finish nothing: the list stays where it is.
        if self.planner.has_finished() {
            self.retire_moves();
        }
    }

    /// [`Channel::retire_finished_moves`]' work, once per move (out of the cycle's code).
    #[inline(never)]
    fn retire_moves(&mut self) {
        let finished = self.planner.take_finished();
        if finished.is_empty() {
            return;
        }
        for tag in finished {
            while let Some((t, meta)) = self.in_planner.front() {
                let done = *t == tag;
                self.offsets = meta.offsets.clone();
                if done && self.single_block && self.jog.is_none() && meta.line > 0 {
                    self.sbl_done = Some(self.sbl_step.unwrap_or(meta.line));
                }
                self.in_planner.pop_front();
                if done {
                    break;
                }
            }
        }
        self.sync_current_block();
    }

    /// Shows the block whose move is executing.
    pub(super) fn sync_current_block(&mut self) {
        if let Some((_, meta)) = self.in_planner.front() {
            self.offsets = meta.offsets.clone();
            let (line, seq) = (meta.line, meta.seq);
            if line > 0 {
                self.enter_block(line, seq);
            }
        }
    }

    /// Remembers where the text of a prepared block of `line` in `level` is (the main program
    /// when `None`).
    pub(super) fn queue_block(&mut self, line: u32, level: Option<Arc<Level>>) -> u32 {
        let Some(text) = level.as_ref().map(|l| &l.text).or(self.program.as_ref()) else { return NO_SEQ };
        let hint = self.queued_blocks.back().filter(|b| same_level(&b.level, &level)).map(|b| (b.line, b.offset));
        let offset = line_offset(text, line, hint.as_ref());
        self.queue_block_at(line, offset, level)
    }

    /// [`Channel::queue_block`] of a block whose start in its text is known (`offset`). Returns
    /// the block's sequence number ([`NO_SEQ`] without a program).
    fn queue_block_at(&mut self, line: u32, offset: usize, level: Option<Arc<Level>>) -> u32 {
        if level.is_none() && self.program.is_none() {
            return NO_SEQ;
        }
        let seq = self.next_block_seq;
        self.next_block_seq = self.next_block_seq.checked_add(1).unwrap_or(NO_SEQ + 1);
        self.queued_blocks.push_back(QueuedBlock { line, seq, offset, level });
        if self.queued_blocks.len() > 2 * LOOKAHEAD {
            self.queued_blocks.pop_front();
        }
        seq
    }

    /// The sequence number of the last queued block if it is `line` of `level` (the block
    /// still being shown: a move held back from it, the call of a DISPLOF subprogram), else of
    /// that block queued anew.
    fn held_block_seq(&mut self, line: u32, level: Option<Arc<Level>>) -> u32 {
        match self.queued_blocks.back().filter(|b| b.line == line && same_level(&b.level, &level)) {
            Some(b) => b.seq,
            None => self.queue_block(line, level),
        }
    }

    /// The main run enters the block of `line` numbered `seq`: the queued block of that number
    /// (or, without one, the first queued block of that line: the main run executes blocks in
    /// the order they were prepared); the blocks queued before it are done with.
    pub(super) fn enter_block(&mut self, line: u32, seq: u32) {
        // The same line is another block when its sequence number differs (a subprogram's line
        // 1 after the caller's line 1), and another line the same block when the number is the
        // same (the blocks of a DISPLOF subprogram show their call); an item without a number
        // is taken for the shown block.
        let changed = if seq == NO_SEQ { self.current_line != Some(line) } else { seq != self.current_seq };
        if changed {
            self.current_seq = seq;
            let by_seq = (seq != NO_SEQ).then(|| self.queued_blocks.iter().position(|b| b.seq == seq)).flatten();
            self.current_block = match by_seq.or_else(|| self.queued_blocks.iter().position(|b| b.line == line)) {
                Some(i) => {
                    self.queued_blocks.drain(..i);
                    self.queued_blocks.front().cloned()
                }
                None => None,
            };
            let shown = self.current_block.as_ref().filter(|b| b.seq == seq && seq != NO_SEQ).map_or(line, |b| b.line);
            self.current_line = Some(shown);
            if let Some(b) = self.block_ref(shown) {
                self.events.push(Event::BlockChanged(b));
            }
        }
    }

    pub(super) fn block_ref(&self, line: u32) -> Option<BlockRef> {
        let (text, program) = self.block_text(line)?;
        Some(BlockRef { line, text: text.to_string(), program: program.map(str::to_string) })
    }

    /// Executes non-motion items at the head of the queue once all motion before them is done.
    #[inline(never)]
    pub(super) fn execute_actions(&mut self) {
        if self.dwell_ticks > 0 {
            self.dwell_ticks -= 1;
            return;
        }
        if self.psync.rdisable {
            // Read-in disabled by a synchronized action: the next block waits.
            return;
        }
        while self.status == Status::Running {
            // Like motion, a change of the online tool offset finishes before the next action.
            if !self.toff.settled(&self.offsets.toff) {
                return;
            }
            // Single block: the block is done once the items of its step are; then stop. Until
            // the next item is prepared it is not known whether the step goes on.
            if let Some(line) = self.sbl_done
                && self.planner.is_empty()
                && (!self.pending.is_empty() || self.prep_done)
                && self.pending.front_step() != Some(line)
            {
                self.sbl_done = None;
                self.program_stop(line);
                return;
            }
            match self.pending.front() {
                None | Some(Item::Move { .. }) => return,
                Some(_) => {}
            }
            let item = self.pending.pop_front().expect("front exists");
            let seq = self.pending.popped_seq();
            match item {
                Item::Move { .. } => unreachable!(),
                Item::Offsets { line, offsets } => {
                    if offsets.trafo != self.trafo && !self.switch_transformation(offsets.trafo.clone()) {
                        // The rotary spindle is still braking: try again next cycle.
                        self.pending.push_front(Item::Offsets { line, offsets });
                        return;
                    }
                    if self.prep_waits_for_trafo
                        && self.trafo_selection.as_ref().is_some_and(|s| Arc::ptr_eq(s, &offsets))
                    {
                        // The selection is executed: preparation goes on from where the
                        // machine stands now.
                        self.prep_waits_for_trafo = false;
                        self.trafo_selection = None;
                        self.interp.sync_transformation(&self.machine);
                    }
                    self.offsets = offsets;
                    self.enter_block(line, seq);
                }
                Item::Message { text, line } => {
                    self.enter_block(line, seq);
                    self.message = (!text.is_empty()).then_some(text);
                }
                Item::Dwell { seconds, line } => {
                    self.enter_block(line, seq);
                    self.dwell_ticks = (seconds / self.cfg.ipo_cycle).round() as u64;
                    if self.dwell_ticks > 0 {
                        self.dwell_ticks -= 1;
                        return;
                    }
                }
                Item::Spindle { axis, rpm, line } => {
                    self.enter_block(line, seq);
                    let angle = self.planner.position()[axis];
                    if let Some(s) = self.spindles.iter_mut().find(|s| s.axis == axis) {
                        s.leave_axis_mode(angle);
                        s.set_speed(rpm);
                    }
                }
                Item::SpindleControl { ctl, line } => {
                    self.enter_block(line, seq);
                    if !self.spindle_control(&ctl) {
                        // A thread waits for its start angle.
                        self.pending.push_front(Item::SpindleControl { ctl, line });
                        return;
                    }
                }
                Item::SpindleToAxis { axis, angle, line } => {
                    self.enter_block(line, seq);
                    if let Some(s) = self.spindles.iter_mut().find(|s| s.axis == axis) {
                        s.enter_axis_mode(angle);
                    }
                    let mut pos = *self.planner.position();
                    pos[axis] = angle;
                    self.planner.set_position(pos);
                    self.machine[axis] = angle;
                }
                Item::Stop { kind: StopKind::End, line } if self.positioning.program_moving() => {
                    // The program ends when its positioning axes have arrived; one still
                    // oscillating brakes (`oscillation.rs`).
                    self.brake_oscillations();
                    self.pending.push_front(Item::Stop { kind: StopKind::End, line });
                    return;
                }
                Item::Stop { kind, line } => {
                    self.enter_block(line, seq);
                    match kind {
                        StopKind::M0 => self.program_stop(line),
                        StopKind::M1 if self.optional_stop => self.program_stop(line),
                        StopKind::M1 => {}
                        StopKind::End => self.program_end(),
                    }
                }
                Item::Alarm(alarm) => {
                    if let Some(line) = alarm.line {
                        self.enter_block(line, seq);
                    }
                    self.raise(alarm);
                }
                Item::Aux { function, line } => {
                    self.enter_block(line, seq);
                    self.events.push(Event::AuxFunction { function, line });
                    if function.letter == 'M' && function.extension == 0 {
                        self.count_parts_on_m(function.value as u32);
                    }
                }
                Item::DigitalOutput { signal, on, line } => {
                    self.enter_block(line, seq);
                    self.execute_digital_output(signal, on, line);
                }
                Item::MainRunWrite { write, line } => {
                    self.enter_block(line, seq);
                    match write {
                        MainRunWrite::Marker(i, v) => self.write_sync_data(Target::Marker(i), v, line),
                        MainRunWrite::Param(i, v) => self.write_sync_data(Target::Param(i), v, line),
                        MainRunWrite::Timer(i, v) => self.write_sync_data(Target::Timer(i), v, line),
                        MainRunWrite::Parts(counter, n) => self.write_part_count(counter, n),
                        MainRunWrite::StartOver => self.start_over(),
                        MainRunWrite::Preset(axis, position) => self.preset_machine_position(axis, position),
                    }
                }
                Item::SyncAction { def, line } => {
                    self.enter_block(line, seq);
                    self.activate_sync(def);
                }
                Item::SyncControl { op, ids, line } => {
                    self.enter_block(line, seq);
                    self.control_sync(op, &ids);
                }
                Item::Workpiece { request, offsets, line } => {
                    self.enter_block(line, seq);
                    self.execute_workpiece(request, &offsets.frame, line);
                }
                Item::Measure { request, line } => {
                    self.enter_block(line, seq);
                    self.arm_probe(request, line);
                }
                Item::SetPiece { pieces, line } => {
                    self.enter_block(line, seq);
                    self.set_piece(pieces);
                }
                Item::Positioning { axis, target, velocity, motion, line } => {
                    self.enter_block(line, seq);
                    self.start_program_positioning(axis, target, velocity, motion);
                }
                Item::WaitPositioning { axes, strict, line } => {
                    if self.wait_positioning(axes, strict, line) {
                        self.pending.push_front(Item::WaitPositioning { axes, strict, line });
                        return;
                    }
                }
            }
        }
    }

    pub(super) fn program_stop(&mut self, line: u32) {
        self.status = Status::Stopped;
        self.events.push(Event::ProgramStopped { line });
    }

    pub(super) fn program_end(&mut self) {
        self.end_runtimes();
        self.status = Status::Idle;
        self.prep_done = true;
        self.current_line = None;
        self.sync.end_program();
        self.end_command_axes();
        self.psync.end_program();
        self.feed_reference = None;
        self.master_spindle = self.cfg.master_spindle;
        self.flush_tool_monitor();
        self.interp.end_program(&self.cfg);
        // Program end returns the offsets to their reset values (G500); the display follows.
        self.offsets = self.interp.offsets();
        self.adopt_transformation();
        self.events.push(Event::ProgramEnded);
    }

    pub(super) fn raise(&mut self, alarm: Alarm) {
        self.end_runtimes();
        self.planner.abort();
        self.pending.clear();
        self.end_orison_run();
        self.in_planner.clear();
        self.prep_done = true;
        self.prep_waits_for_trafo = false;
        self.jog = None;
        self.repos_returning = false;
        self.drop_interruption();
        if alarm.clear == Clear::Reset {
            self.status = Status::Alarm;
        } else if self.status == Status::Running {
            self.status = Status::Idle;
        }
        self.events.push(Event::AlarmRaised(alarm.clone()));
        self.alarms.push(alarm);
    }
}

/// The block the interpreter read last: its line, its program level and, inside a DISPLOF
/// subprogram, the calling block shown instead (`Interpreter::hidden_by_call`).
#[derive(Debug, Clone, Default)]
pub(super) struct ReadBlock {
    pub line: u32,
    pub level: Option<Arc<Level>>,
    pub hidden: Option<(u32, Option<Arc<Level>>)>,
}

/// A prepared block whose items are queued: its line in its program level, where the line
/// starts in that level's text, and the level (`None`: the main program).
#[derive(Debug, Clone)]
pub(super) struct QueuedBlock {
    pub line: u32,
    /// The block's sequence number (see `pending.rs`): tells apart blocks of the same line.
    pub seq: u32,
    pub offset: usize,
    pub level: Option<Arc<Level>>,
}

/// Whether two blocks were prepared in the same program level (the same call).
pub(super) fn same_level(a: &Option<Arc<Level>>, b: &Option<Arc<Level>>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        _ => false,
    }
}

/// Byte offset of the start of `line`, counting from the last remembered block when it lies
/// before (blocks are mostly prepared in order, so this is a short forward scan).
pub(super) fn line_offset(program: &str, line: u32, last: Option<&(u32, usize)>) -> usize {
    let (mut at_line, mut offset) = match last {
        Some(&(l, o)) if l <= line => (l, o),
        _ => (1, 0),
    };
    while at_line < line {
        match program[offset..].find('\n') {
            Some(i) => offset += i + 1,
            None => break,
        }
        at_line += 1;
    }
    offset
}

/// Gives the offsets item of a block that selected or deselected a transformation a value of
/// its own, so the main run knows when it executes that block: preparation waits for it and
/// then goes on from where the machine stands. An earlier block's switch still in the queue (a
/// tool length taken into the persistent transformation, ahead of the move that follows it)
/// must not end the wait: it would hand back a machine position the prepared moves have not
/// reached yet, and the block after the selection would start from there. A selection that
/// leaves the offsets as they were (the same data set again) gets an item all the same.
/// `None` when the block ended in an alarm.
fn mark_selection(out: &mut Vec<Item>, interp: &crate::interp::Interpreter) -> Option<crate::interp::SharedOffsets> {
    if out.iter().any(|i| matches!(i, Item::Alarm(_))) {
        return None;
    }
    let last = out.iter_mut().rev().find_map(|i| match i {
        Item::Offsets { offsets, .. } => Some(offsets),
        _ => None,
    });
    match last {
        Some(offsets) => {
            *offsets = Arc::new((**offsets).clone());
            Some(offsets.clone())
        }
        None => {
            let offsets = interp.offsets();
            out.push(Item::Offsets { line: interp.read_line(), offsets: offsets.clone() });
            Some(offsets)
        }
    }
}
