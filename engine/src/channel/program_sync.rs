//! The actions of synchronized actions that act on the program's run (Function Manual
//! "Synchronized actions"): `STOPREOF` (ends the preprocessing stop after the action's motion
//! block), `RDISABLE` (read-in disable: the next block waits while it holds), `PRESETON(ax, v)`
//! (the axis' actual value set without motion; in a program block too), `SETM(n)`/`CLEARM(n)`
//! (the channel's wait markers) and technology cycles (`DO NAME`: a program of actions run one
//! block per IPO cycle).
//!
//! Modelled as follows where the manuals leave room:
//! - `STOPREOF`: a block that waits for the main run after the action's motion block (a
//!   preprocessing stop, implicit or STOPRE) is prepared in the cycle the action runs, reading
//!   the main-run values of that cycle; the path goes on. It ends one such stop.
//! - `RDISABLE`: while an active action holds RDISABLE the channel hands the prepared blocks to
//!   the main run one at a time (each ends with an exact stop), so that "the next block" is
//!   well defined; in a cycle in which it runs no block is started. A block-modal RDISABLE stays
//!   active past its motion block until the next block has started.
//! - `PRESETON` on an axis the running path block moves is alarm 20141; otherwise the axis stays
//!   with the positioning interpolator (like a command axis) until the program ends, as the
//!   prepared path knows nothing of the new value.
//! - Wait markers: numbers 0..=127; with one channel `WAITM`/`WAITMC` in a program wait for no
//!   other channel (see `Channel::wait_markers`).
//! - A technology cycle runs while its action is active; started again only after it ended (a
//!   WHENEVER restarts it in the cycle after its end). Reset and program end stop it.

use std::sync::Arc;

use super::Channel;
use crate::alarm::Alarm;
use crate::interp::synchronized::compile::CommandKind;
use crate::interp::synchronized::flat::{self, Act, Fault};
use crate::interp::synchronized::technology::TechCycle;
use crate::motion::AxisVec;

/// The program-facing state of the synchronized actions.
#[derive(Debug, Clone, Default)]
pub struct ProgramSync {
    /// STOPREOF ran: the next wait for the main run is over.
    pub(super) stopreof: bool,
    /// The setpoints of the cycle before STOPREOF's: the block it lets through reads the
    /// path's `$AA_VACTM` from them.
    pub(super) stopreof_from: AxisVec,
    /// RDISABLE ran in this IPO cycle.
    pub(super) rdisable: bool,
    /// An active action holds RDISABLE: blocks go to the main run one at a time.
    pub(super) rdisable_armed: bool,
    /// The interpreter was handed the main run's position for `$AA_IM` (until taken back).
    pub(super) main_position_handed: bool,
    /// Wait markers set by SETM (bit n).
    pub(super) wait_markers: u128,
    /// Technology cycles in progress.
    runs: Vec<CycleRun>,
}

/// A technology cycle in progress.
#[derive(Debug, Clone)]
struct CycleRun {
    cycle: Arc<TechCycle>,
    /// The line of the action that called it (alarms are reported there).
    line: u32,
    /// The next block.
    next: usize,
    /// Axes the last block moved: the next block waits until they have arrived.
    waits: u32,
    /// The IPO cycle it ran its last block in.
    ran: u64,
}

impl ProgramSync {
    /// Reset: as program end, and the wait markers are cleared.
    pub(super) fn reset(&mut self) {
        self.end_program();
        self.wait_markers = 0;
    }

    /// Program end: the runs stop, the flags go.
    pub(super) fn end_program(&mut self) {
        self.stopreof = false;
        self.rdisable = false;
        self.rdisable_armed = false;
        self.runs.clear();
    }

    /// Whether technology cycles are in progress.
    pub(super) fn running_cycles(&self) -> bool {
        !self.runs.is_empty()
    }
}

impl Channel {
    /// Runs one program-facing action (see the module doc); any other action does nothing here.
    pub(super) fn program_sync_act(&mut self, act: &Act, line: u32) -> Result<(), Fault> {
        match act {
            Act::StopReOf => {
                // The actions run before this cycle's step: `machine` is the cycle before's.
                self.psync.stopreof = true;
                self.psync.stopreof_from = self.machine;
            }
            Act::RDisable => self.psync.rdisable = true,
            Act::Preset { axis, value } => {
                let v = flat::eval(value, self, line)?;
                self.preset_axis(*axis, v, line)?;
            }
            Act::WaitMarker { set, marker } => {
                let n = flat::eval(marker, self, line)?;
                if !(0.0..=127.0).contains(&n) || n.fract() != 0.0 {
                    return Err(Box::new(Alarm::value_out_of_range(line, &format!("wait marker {n}"))));
                }
                let bit = 1u128 << n as u32;
                if *set {
                    self.psync.wait_markers |= bit;
                } else {
                    self.psync.wait_markers &= !bit;
                }
            }
            Act::Cycle(cycle) => self.start_cycle(cycle, line)?,
            _ => {}
        }
        Ok(())
    }

    /// The channel's wait markers set by SETM (bit n: marker n), cleared by CLEARM and reset.
    pub fn wait_markers(&self) -> u128 {
        self.psync.wait_markers
    }

    /// PRESETON(ax, v): the axis' machine position becomes `v` without motion.
    fn preset_axis(&mut self, k: usize, v: f64, line: u32) -> Result<(), Fault> {
        if !v.is_finite() {
            return Err(Box::new(Alarm::value_out_of_range(line, "PRESETON")));
        }
        let moved = !self.planner.is_empty() && self.planner.front().is_some_and(|m| m.path.start[k] != m.path.end[k]);
        if moved || self.cfg.axis(k).spindle.is_some() {
            return Err(Box::new(Alarm::sync_axis_type(Some(line), self.cfg.program_axis_name(k))));
        }
        if self.positioning.position(k).is_none() {
            let here = self.machine[k];
            let feed = self.command_feed(k);
            self.start_positioning(k, here, feed, true);
        }
        let d = v - self.positioning.position(k).unwrap_or(v);
        self.shift_positioning_axis(k, d);
        self.machine[k] += d;
        self.servo.shift(k, d);
        self.sync.wake_all();
        Ok(())
    }

    /// PRESETON in a program block, reached by the main run after the motion before it:
    /// channel axis `k`'s machine position becomes `position`, without motion. Preparation has
    /// taken the position over already (`interp/frames/preset.rs`).
    pub(super) fn preset_machine_position(&mut self, k: usize, position: f64) {
        let d = position - self.machine[k];
        if self.positioning.position(k).is_some() {
            self.shift_positioning_axis(k, d);
        }
        self.machine[k] = position;
        self.servo.shift(k, d);
        let mut at = *self.planner.position();
        at[k] += d;
        self.planner.set_position(at);
        self.sync.wake_all();
    }

    /// Starts technology cycle `cycle` called from the action at `line`, unless it runs; its
    /// first block runs in this cycle.
    fn start_cycle(&mut self, cycle: &Arc<TechCycle>, line: u32) -> Result<(), Fault> {
        if self.psync.runs.iter().any(|r| Arc::ptr_eq(&r.cycle, cycle) && r.line == line) {
            return Ok(());
        }
        self.psync.runs.push(CycleRun { cycle: cycle.clone(), line, next: 0, waits: 0, ran: 0 });
        let i = self.psync.runs.len() - 1;
        self.step_cycle(i)
    }

    /// One IPO cycle of the technology cycles in progress (after the actions ran).
    pub(super) fn advance_cycles(&mut self) -> Result<(), Fault> {
        let mut i = 0;
        while i < self.psync.runs.len() {
            self.step_cycle(i)?;
            i += 1;
        }
        self.psync.runs.retain(|r| r.next < r.cycle.blocks.len() || r.waits != 0);
        Ok(())
    }

    /// Runs the next block of run `i` unless it ran in this cycle or waits for its axes.
    fn step_cycle(&mut self, i: usize) -> Result<(), Fault> {
        let run = &self.psync.runs[i];
        if run.ran == self.tick || self.positioning.moving(run.waits) {
            return Ok(());
        }
        let (cycle, next, line) = (run.cycle.clone(), run.next, run.line);
        let run = &mut self.psync.runs[i];
        run.waits = 0;
        let Some(block) = cycle.blocks.get(next) else { return Ok(()) };
        run.next += 1;
        run.ran = self.tick;
        let mut waits = 0;
        for act in &block.actions {
            if let Act::Command { kind: CommandKind::Pos | CommandKind::Spos, axis, .. } = act {
                waits |= 1 << axis;
            }
            self.sync_act(act, line)?;
        }
        self.psync.runs[i].waits = waits;
        Ok(())
    }
}
