//! Motion-synchronous actions in the main run: the active actions, checked in every IPO cycle
//! in the order of their IDs (modal `ID` and static `IDS`), then the block-modal ones in the
//! order programmed (Function Manual Synchronized actions, "Sequence of execution"), and the
//! main-run data they read and write: `$AC_MARKER`, `$AC_PARAM`, `$AC_TIMER`, the analog
//! signals `$A_INA`/`$A_OUTA`, the override of the cycle `$AC_OVR`, `$AC_DELT`.
//!
//! Lifetimes: a block-modal action (no ID) acts while the next motion block runs; `ID=n`
//! until CANCEL(n), the program's end or a reset; `IDS=n` until CANCEL(n): static actions
//! are untouched by program end, reset and mode changes, as on the control.
//!
//! [`Channel::step_sync_actions`] is called once per cycle, before the interpolator; with
//! no action active and no timer running it returns after one test.

use std::sync::Arc;

use super::eval::Touched;
use crate::alarm::Alarm;
use crate::channel::Channel;
use crate::channel::Event;
use crate::interp::io::DigitalIo;
use crate::interp::synchronized::flat::{BLOCK_BIT, DELT_BIT, FRAME_BIT, MOTION_BIT, Slot, TIMER_BIT};
use crate::interp::synchronized::{MainRunData, SyncControl, SyncDef};
use crate::interp::{Item, SharedOffsets};
use crate::lang::sync_action::SyncId;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

use crate::machine_data::sync_sizes::SyncSizes;
/// Active synchronized actions at most (MD28250 MM_NUM_SYNC_ELEMENTS bounds them on the control).
pub const MAX_ACTIVE: usize = 64;
/// Input changes kept in [`Channel::input_log`] (the oldest go first).
pub const INPUT_LOG: usize = 4096;

/// Signals set from outside at one IPO cycle count: they act from the next cycle on.
#[derive(Debug, Clone, PartialEq)]
pub struct InputRecord {
    /// [`Channel::ticks`] when they arrived.
    pub tick: u64,
    /// Digital inputs and outputs `(signal, level)`, analog inputs `(signal, value)`.
    pub inputs: Vec<(usize, bool)>,
    pub outputs: Vec<(usize, bool)>,
    pub analog: Vec<(usize, f64)>,
}

/// The synchronized actions and their data in the main run.
#[derive(Debug, Clone)]
pub struct SyncActions {
    /// Modal and static ones by ID, then block-modal ones in program order.
    pub(in crate::channel) active: Vec<ActiveSync>,
    /// Sized by the machine data ([`SyncSizes`]).
    pub markers: Vec<f64>,
    pub params: Vec<f64>,
    /// Running timers' seconds (`None`: stopped).
    pub timers: Vec<Option<f64>>,
    /// Whether any timer runs: kept with `timers`, so an idle cycle tests one flag.
    pub(super) timing: bool,
    pub analog_in: Vec<f64>,
    pub analog_out: Vec<f64>,
    /// `$AC_DELT`: what the last DELDTG deleted (mm of path).
    pub deleted: f64,
    /// `$AC_OVR` and `$AA_OVR` of this cycle (percent; 100 unless an action wrote them).
    pub(super) ovr: f64,
    pub(super) axis_ovr: [f64; MAX_CHANNEL_AXES],
    /// An override of the actions is in the planner (restored when no longer written).
    ovr_applied: bool,
    /// The block `$AC_TIME` counts from, and the cycle it began.
    block: Option<u32>,
    pub(super) block_start: u64,
    /// The setpoints of the cycle before, for `$AA_VACTM`.
    pub(super) prev_setpoint: [f64; MAX_CHANNEL_AXES],
    /// Inputs set from outside, with their cycle counts.
    log: std::collections::VecDeque<InputRecord>,
    /// The data changed since it was last handed to block preparation.
    pub(in crate::channel) dirty: bool,
    /// The workpiece coordinates of this cycle, once an action read `$AA_IW`.
    /// One cell per axis and a bit per axis computed (nothing copied whole for each read).
    pub(super) wcs: [std::cell::Cell<f64>; MAX_CHANNEL_AXES],
    pub(super) wcs_valid: std::cell::Cell<u32>,
    /// The offsets whose frame's inverse `$AA_IW` uses, and that inverse (`None`: singular).
    pub(super) frame_inverse: Option<(SharedOffsets, Option<[[f64; 3]; 3]>)>,
    /// A block-modal action is in `active` (they are bound to their block each cycle).
    pub(super) block_modal: bool,
    /// An action wrote `$AA_OVR` in this cycle.
    pub(super) axis_ovr_written: bool,
    /// The data the conditions read that changed lately, and the digital signals last seen.
    pub(super) touched: Touched,
    pub(super) io_seen: DigitalIo,
    /// The first cycle in which any action has something to do (a condition whose horizon
    /// ends, an action that runs in every cycle): until then the IPO cycle skips them all,
    /// unless the block or the offsets change (see [`Channel::step_sync_actions`]).
    pub(super) next_wake: u64,
    /// The first cycle in which a condition must be evaluated (0: all are looked at), and the
    /// actions (bits of their places in `active`) that run their actions in every cycle
    /// meanwhile (`schedule.rs`).
    pub(super) cond_wake: u64,
    pub(super) each: u64,
    /// What the conditions of the checked actions read (their data and events together).
    pub(super) deps: u64,
    /// The channel axes whose `$AA_VACTM` an active action reads (their setpoints of the
    /// cycle before are kept; all of them for a technology cycle).
    velocity_axes: u32,
    /// Test switch: every condition evaluated in every cycle (the reference the horizons
    /// are checked against).
    pub(super) horizon_off: bool,
    /// Actions not run but computed when read, and their inputs (`lazy.rs`).
    pub(super) deferred: super::lazy::Deferred,
    /// The speed bound of the moves in the planner (`horizon.rs`).
    pub(super) speed_caps: super::horizon::SpeedCaps,
    /// Conditions evaluated so far.
    pub(super) evaluations: u64,
    /// IPO cycles in which the actions' cycle ran (not skipped while all sleep).
    pub(super) cycles_run: u64,
}

impl Default for SyncActions {
    fn default() -> Self {
        let z = SyncSizes::default();
        SyncActions {
            active: Vec::new(),
            markers: vec![0.0; z.markers],
            params: vec![0.0; z.params],
            timers: vec![None; z.timers],
            timing: false,
            analog_in: vec![0.0; z.analog_in],
            analog_out: vec![0.0; z.analog_out],
            deleted: 0.0,
            ovr: 100.0,
            axis_ovr: [100.0; MAX_CHANNEL_AXES],
            ovr_applied: false,
            block: None,
            block_start: 0,
            prev_setpoint: [0.0; MAX_CHANNEL_AXES],
            log: Default::default(),
            dirty: false,
            wcs: Default::default(),
            wcs_valid: Default::default(),
            frame_inverse: None,
            block_modal: false,
            axis_ovr_written: false,
            touched: Touched::default(),
            io_seen: DigitalIo::default(),
            next_wake: 0,
            cond_wake: 0,
            each: 0,
            deps: 0,
            velocity_axes: 0,
            horizon_off: false,
            deferred: Default::default(),
            speed_caps: Default::default(),
            evaluations: 0,
            cycles_run: 0,
        }
    }
}

/// One active synchronized action.
#[derive(Debug, Clone)]
pub(in crate::channel) struct ActiveSync {
    pub(super) def: Arc<SyncDef>,
    /// The action ran (WHEN, FROM, EVERY: since activation; WHENEVER, DO: in the last cycle).
    pub(super) fired: bool,
    /// The condition's value in the last cycle (EVERY's edge).
    pub(super) was_true: bool,
    pub(super) locked: bool,
    /// Block-modal (no ID): the line of the motion block it belongs to, once that block runs.
    pub(super) block_modal: bool,
    pub(super) bound: Option<u32>,
    /// The condition's value when last evaluated: it keeps it until the cycle `wake` (its
    /// horizon, `interp/synchronized/horizon.rs`) or until data or events of `deps` change.
    pub(super) cond: bool,
    pub(in crate::channel) wake: u64,
    pub(super) deps: u64,
    /// Its actions run in every cycle while it sleeps (WHENEVER true, FROM after it held, DO).
    pub(super) run_each: bool,
}

impl ActiveSync {
    /// Checked in this cycle at all (not locked; a block-modal one once bound to its block).
    #[inline]
    pub(super) fn checked(&self) -> bool {
        !self.locked && (!self.block_modal || self.bound.is_some())
    }
}

/// A synchronized action as the state shows it.
#[derive(Debug, Clone, PartialEq)]
pub struct SyncActionInfo {
    /// `Some(n)` for `ID=n`/`IDS=n`.
    pub id: Option<u32>,
    /// "block", "modal" or "static".
    pub kind: &'static str,
    /// WHEN, WHENEVER, FROM, EVERY or DO.
    pub trigger: &'static str,
    pub condition: String,
    pub fired: bool,
    pub locked: bool,
    pub line: u32,
}

impl SyncActions {
    /// How many conditions the main run evaluated so far (asleep ones are not): for tests
    /// and measurements of the horizons.
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// In how many IPO cycles the actions' cycle ran (the others cost a few compares): the
    /// deterministic measure of their cost for tests.
    pub fn cycles_run(&self) -> u64 {
        self.cycles_run
    }

    /// Whether any synchronized action is active.
    pub(in crate::channel) fn is_active(&self) -> bool {
        !self.active.is_empty()
    }

    /// Data block preparation has not seen: changed (`dirty`), or changing unseen in every
    /// cycle (deferred actions).
    #[inline]
    fn unpublished(&self) -> bool {
        self.dirty || self.deferred.any()
    }

    #[inline]
    fn idle(&self) -> bool {
        self.active.is_empty() && !self.ovr_applied && !self.dirty && !self.timing
    }

    /// Data or an event of `bits` changed: the conditions reading it are looked at in the
    /// next cycle checked, which is the next one.
    #[inline]
    pub(super) fn touch(&mut self, bits: u64) {
        self.touched.touch(bits);
        self.next_wake = 0;
    }

    /// The actions are checked in the next cycle (a signal or the offsets may have changed,
    /// the list changed).
    pub(in crate::channel) fn wake(&mut self) {
        self.next_wake = 0;
        self.cond_wake = 0;
    }

    /// Every condition is evaluated again in the next cycle: the axes jumped (power on,
    /// restore, preset, a probe's deletion, a new transformation) or the program ended.
    pub(in crate::channel) fn wake_all(&mut self) {
        for a in &mut self.active {
            a.wake = 0;
        }
        self.touch(1 << MOTION_BIT | 1 << FRAME_BIT | 1 << BLOCK_BIT);
        self.wake();
    }

    /// Whether `offsets` are those `$AA_IW`'s inverse was made for.
    #[inline]
    pub(super) fn frame_of(&self, offsets: &SharedOffsets) -> bool {
        self.frame_inverse.as_ref().is_some_and(|(o, _)| Arc::ptr_eq(o, offsets))
    }

    /// Test switch: `false` evaluates every condition in every cycle (no horizons).
    fn set_horizons(&mut self, on: bool) {
        self.store_deferred();
        self.horizon_off = !on;
        self.replan_deferred();
        self.wake_all();
    }

    /// Notes the axes whose `$AA_VACTM` active actions read; returns those read from now on.
    fn note_velocity_readers(&mut self) -> u32 {
        let before = self.velocity_axes;
        self.velocity_axes = self.active.iter().fold(0, |axes, a| axes | velocity_axes(&a.def));
        self.velocity_axes & !before
    }

    /// The arrays take the sizes of the machine data `z` (the elements kept keep their values,
    /// new ones are zero, a stopped timer).
    pub(in crate::channel) fn resize(&mut self, z: &SyncSizes) {
        self.markers.resize(z.markers, 0.0);
        self.params.resize(z.params, 0.0);
        self.timers.resize(z.timers, None);
        self.timing = self.timers.iter().any(Option::is_some);
        self.analog_in.resize(z.analog_in, 0.0);
        self.analog_out.resize(z.analog_out, 0.0);
        self.dirty = true;
    }

    /// The data as block preparation reads it (the deferred actions' values computed).
    pub(in crate::channel) fn main_run_data(&self) -> MainRunData {
        let data = self.with_deferred();
        let data = &*data;
        MainRunData {
            markers: data.markers.clone(),
            params: data.params.clone(),
            timers: data.timers.clone(),
            analog_in: data.analog_in.clone(),
            analog_out: data.analog_out.clone(),
            deleted: data.deleted,
            machine: None,
            velocity: [0.0; MAX_CHANNEL_AXES],
        }
    }

    /// Program end or reset: modal and block-modal actions end, static ones stay.
    pub fn end_program(&mut self) {
        self.store_deferred();
        self.active.retain(|a| matches!(a.def.id, Some(SyncId::Static(_))));
        self.replan_deferred();
        self.block_modal = false;
        self.note_velocity_readers();
        self.wake_all();
    }

    /// Makes `out` the list of the active actions (nothing allocated while there are none).
    pub(in crate::channel) fn refresh_list(&self, out: &mut Vec<SyncActionInfo>) {
        if self.active.is_empty() {
            out.clear();
        } else {
            *out = self.list();
        }
    }

    /// The active actions, for the state.
    pub fn list(&self) -> Vec<SyncActionInfo> {
        self.active
            .iter()
            .map(|a| SyncActionInfo {
                id: a.def.id.map(SyncId::number),
                kind: match a.def.id {
                    None => "block",
                    Some(SyncId::Modal(_)) => "modal",
                    Some(SyncId::Static(_)) => "static",
                },
                trigger: a.def.trigger.as_str(),
                condition: a.def.condition_text.clone(),
                fired: a.fired,
                locked: a.locked,
                line: a.def.line,
            })
            .collect()
    }
}

impl Channel {
    /// The synchronized actions and their data (with the values of deferred actions,
    /// `lazy.rs`, computed: then a copy).
    pub fn sync_actions(&self) -> std::borrow::Cow<'_, SyncActions> {
        self.sync.with_deferred()
    }

    /// Test switch: `false` evaluates every synchronized action's condition in every IPO
    /// cycle, as without horizons (the reference the horizons are checked against).
    #[doc(hidden)]
    pub fn set_sync_horizons(&mut self, on: bool) {
        self.sync.set_horizons(on);
    }

    /// Sets analog inputs `$A_INA[n]` from outside, each `(n, value)` with n = 1.. the count
    /// of MD10300 FASTIO_ANA_NUM_INPUTS; all or nothing. They act from the next IPO cycle on.
    pub fn set_analog_inputs(&mut self, inputs: &[(usize, f64)]) -> Result<(), crate::channel::CommandError> {
        let count = self.sync.analog_in.len();
        if let Some((n, v)) = inputs.iter().find(|(n, v)| !(1..=count).contains(n) || !v.is_finite()) {
            return Err(crate::channel::CommandError::Invalid(format!(
                "analog input {n} = {v}: inputs are 1..{count} (MD10300 FASTIO_ANA_NUM_INPUTS) with finite values"
            )));
        }
        for &(n, v) in inputs {
            self.sync.analog_in[n - 1] = v;
        }
        self.sync.dirty = true;
        self.note_analog_inputs();
        self.publish_sync_data();
        self.log_inputs(InputRecord { tick: self.tick, inputs: vec![], outputs: vec![], analog: inputs.to_vec() });
        Ok(())
    }

    /// The analog inputs and outputs `$A_INA[1..]`, `$A_OUTA[1..]`.
    pub fn analog_io(&self) -> (&[f64], &[f64]) {
        (&self.sync.analog_in, &self.sync.analog_out)
    }

    /// The inputs set from outside, oldest first (at most [`INPUT_LOG`]), each with the cycle
    /// count it arrived at: fed to a fresh channel at the same counts
    /// ([`Channel::apply_inputs`]), they reproduce the run.
    pub fn input_log(&self) -> impl Iterator<Item = &InputRecord> {
        self.sync.log.iter()
    }

    /// Sets the signals of a logged record (a replay).
    pub fn apply_inputs(&mut self, record: &InputRecord) -> Result<(), crate::channel::CommandError> {
        if !record.inputs.is_empty() || !record.outputs.is_empty() {
            self.set_signals(&record.inputs, &record.outputs)?;
        }
        if !record.analog.is_empty() {
            self.set_analog_inputs(&record.analog)?;
        }
        Ok(())
    }

    /// Logs signals set from outside and publishes them as an event.
    pub(in crate::channel) fn log_inputs(&mut self, record: InputRecord) {
        if self.sync.log.len() == INPUT_LOG {
            self.sync.log.pop_front();
        }
        self.sync.log.push_back(record.clone());
        self.events.push(Event::InputsChanged(record));
    }

    /// Takes back the inputs of a checkpoint (digital input bits, analog input values).
    pub(in crate::channel) fn restore_inputs(&mut self, digital: u64, analog: &[f64]) {
        let mut io = self.io;
        io.inputs = digital;
        let io = io.sized(self.cfg.sync_sizes.digital_in, self.cfg.sync_sizes.digital_out);
        self.set_digital_io(io);
        for (to, v) in self.sync.analog_in.iter_mut().zip(analog) {
            *to = if v.is_finite() { *v } else { 0.0 };
        }
        self.sync.dirty = true;
        self.note_analog_inputs();
        self.publish_sync_data();
    }

    /// Hands the data to block preparation when it changed and preparation may read it: it
    /// waits for the main run, or would not wait (nothing queued, no program running). While a
    /// program's moves are queued no block that reads main-run data is prepared, so the copy
    /// is not made in every cycle.
    pub(in crate::channel) fn publish_sync_data(&mut self) {
        if !self.sync.unpublished() {
            return;
        }
        if self.prep_may_read() {
            self.sync.dirty = false;
            self.interp.set_sync_data(self.sync.main_run_data());
        }
    }

    /// Main run: a synchronized action's block is reached.
    pub(in crate::channel) fn activate_sync(&mut self, def: Arc<SyncDef>) {
        if let Some(alarm) = self.sync_resources_short(&def) {
            self.raise(alarm);
            return;
        }
        if def.disables_read_in() {
            // Blocks go one at a time from now on; a modal RDISABLE is evaluated before the
            // next block may start (`program_sync.rs`).
            self.psync.rdisable_armed = true;
            self.psync.rdisable |= def.id.is_some();
        }
        let deps = def.flat_condition.as_ref().map_or(0, |c| c.deps);
        let block_modal = def.id.is_none();
        let new = ActiveSync {
            def,
            fired: false,
            was_true: false,
            locked: false,
            block_modal,
            bound: None,
            cond: false,
            wake: 0,
            deps,
            run_each: false,
        };
        self.sync.store_deferred();
        let list = &mut self.sync.active;
        match new.def.id {
            Some(id) => {
                let n = id.number();
                list.retain(|a| a.def.id.map(SyncId::number) != Some(n));
                let at = list.iter().position(|a| a.def.id.is_none_or(|i| i.number() > n)).unwrap_or(list.len());
                list.insert(at, new);
            }
            None => {
                list.push(new);
                self.sync.block_modal = true;
            }
        }
        self.sync.wake();
        // The moves queued before it bound the axes' speeds for its horizons.
        self.recompute_speed_caps();
        self.sync.replan_deferred();
        let new = self.sync.note_velocity_readers();
        for k in (0..MAX_CHANNEL_AXES).filter(|k| new & (1 << k) != 0) {
            // `$AA_VACTM` counts from the setpoints of now (main-run blocks are activated
            // with the path at rest).
            self.sync.prev_setpoint[k] = self.machine[k];
        }
    }

    /// Alarm 14751 if `def` does not fit beside the active actions: their elements together
    /// beyond MD28250 `$MC_MM_NUM_SYNC_ELEMENTS`, or more than [`MAX_ACTIVE`] actions (NCTwin's
    /// own bound: the schedule's masks have 64 bits). An action with the same ID is replaced,
    /// so its elements are free.
    fn sync_resources_short(&self, def: &SyncDef) -> Option<Alarm> {
        let replaced = |a: &&ActiveSync| def.id.is_some_and(|n| a.def.id.map(SyncId::number) == Some(n.number()));
        let kept = || self.sync.active.iter().filter(|a| !replaced(a));
        let used: usize = kept().map(|a| a.def.elements()).sum();
        let (need, limit) = (def.elements(), self.cfg.sync_sizes.elements);
        let why = if used + need > limit {
            format!(
                "MD28250 MM_NUM_SYNC_ELEMENTS: {need} elements needed, {} of {limit} free",
                limit.saturating_sub(used)
            )
        } else if kept().count() >= MAX_ACTIVE {
            format!("at most {MAX_ACTIVE} active actions")
        } else {
            return None;
        };
        let line = def.line;
        Some(Alarm {
            number: 14751,
            message: format!("Channel 1 block {line} resources for motion synchronous actions not sufficient ({why})"),
            line: Some(line),
            clear: crate::alarm::Clear::Reset,
        })
    }

    /// Main run: CANCEL/LOCK/UNLOCK/RESET(ids). An ID no action has is passed over.
    pub(in crate::channel) fn control_sync(&mut self, op: SyncControl, ids: &[u32]) {
        let hit = |a: &ActiveSync| a.def.id.is_some_and(|i| ids.contains(&i.number()));
        self.sync.store_deferred();
        match op {
            SyncControl::Cancel => self.sync.active.retain(|a| !hit(a)),
            _ => {
                for a in self.sync.active.iter_mut().filter(|a| hit(a)) {
                    // An unlocked RDISABLE counts again (see `run_sync_cycle`).
                    self.psync.rdisable_armed |= op == SyncControl::Unlock && a.def.disables_read_in();
                    match op {
                        SyncControl::Lock => a.locked = true,
                        SyncControl::Unlock => a.locked = false,
                        _ => (a.fired, a.was_true) = (false, false),
                    }
                    a.wake = 0;
                }
            }
        }
        self.sync.replan_deferred();
        self.sync.note_velocity_readers();
        self.sync.wake();
    }

    /// One IPO cycle of the synchronized actions: one test when none is active; while all
    /// sleep (no horizon ends, none runs its actions in every cycle) three compares: the
    /// wake cycle, the block (`$AC_TIME` counts from its start), the offsets (`$AA_IW`); then
    /// the setpoints for `$AA_VACTM` and the inputs of deferred actions are kept
    /// (`lazy.rs`), and the cycle runs when block preparation may read their values.
    #[inline]
    pub(in crate::channel) fn step_sync_actions(&mut self) {
        if !self.sync.idle() {
            self.step_active_sync();
        }
    }

    /// [`Channel::step_sync_actions`] with actions (or their data) active. Out of line: the
    /// IPO cycle without actions keeps its one test.
    #[inline(never)]
    fn step_active_sync(&mut self) {
        if self.tick >= self.sync.next_wake
            || self.current_line != self.sync.block
            || !self.sync.frame_of(&self.offsets)
            || self.sync.unpublished() && self.prep_may_read()
        {
            self.run_sync_cycle();
        } else {
            self.keep_sync_history();
        }
    }

    /// What a cycle in which the actions sleep keeps for later ones: the setpoints of now
    /// for `$AA_VACTM`, the deferred actions' inputs.
    #[inline]
    fn keep_sync_history(&mut self) {
        let mut axes = self.sync.velocity_axes;
        if axes != 0 && axes < 1 << 4 {
            // Readers among axes 0..3 (the usual): one copy of fixed size. The other axes'
            // setpoints copied with them are read by no action (`velocity_axes` covers
            // every reader; a new one takes its own at activation).
            self.sync.prev_setpoint[..4].copy_from_slice(&self.machine[..4]);
            axes = 0;
        }
        while axes != 0 {
            let k = axes.trailing_zeros() as usize;
            axes &= axes - 1;
            self.sync.prev_setpoint[k] = self.machine[k];
        }
        if self.sync.deferred.any() {
            self.keep_deferred_inputs();
        }
    }

    /// Out of line: the IPO cycle's own code stays small (ARCHITECTURE: the IPO cycle's code).
    #[inline(never)]
    fn run_sync_cycle(&mut self) {
        self.sync.cycles_run += 1;
        let dt = self.cfg.ipo_cycle;
        let tick = self.tick;
        if self.sync.timing {
            for t in self.sync.timers.iter_mut().flatten() {
                *t += dt;
            }
            self.sync.dirty = true;
            self.sync.touch(1 << TIMER_BIT);
        }
        if self.sync.block != self.current_line {
            self.sync.block = self.current_line;
            self.sync.block_start = tick;
            self.sync.touch(1 << BLOCK_BIT);
        }
        self.sync.ovr = 100.0;
        self.psync.rdisable = false;
        if self.sync.axis_ovr_written {
            self.sync.axis_ovr = [100.0; MAX_CHANNEL_AXES];
            self.sync.axis_ovr_written = false;
        }
        self.sync.wcs_valid.set(0);
        if self.refresh_frame_inverse() {
            self.sync.touch(1 << FRAME_BIT);
        }
        self.note_io();
        let mut active = std::mem::take(&mut self.sync.active);
        // Block-modal actions: bound to the first motion block after them, gone after it.
        if self.sync.block_modal {
            let running = self.in_planner.front().map(|(_, m)| m.line);
            let before = active.len();
            active.retain_mut(|a| {
                if a.def.id.is_some() {
                    return true;
                }
                match a.bound {
                    None => {
                        a.bound = running.filter(|l| *l != a.def.line);
                        true
                    }
                    // RDISABLE holds the next block: it stays until that block has started.
                    Some(l) => running == Some(l) || running.is_none() && a.def.disables_read_in(),
                }
            });
            self.sync.block_modal = active.iter().any(|a| a.def.id.is_none());
            if active.len() != before {
                // The places changed: the mask of the actions run in every cycle is made
                // again by a full check (a stale bit pointed past the list's end).
                self.sync.cond_wake = 0;
            }
        }
        let failed = self.check_actions(&mut active);
        if self.sync.deferred.any()
            && let Some((at, _)) = failed
        {
            // The deferred actions after the failed one did not run in this cycle.
            self.sync.active = std::mem::take(&mut active);
            self.keep_deferred_inputs_until(at);
            active = std::mem::take(&mut self.sync.active);
        }
        let mut failed = failed.map(|(_, alarm)| alarm);
        if self.psync.rdisable_armed {
            // Set when an action with RDISABLE was activated: nothing to look at without one.
            self.psync.rdisable_armed = active.iter().any(|a| !a.locked && a.def.disables_read_in());
        }
        // Actions only change the data, never the list: put it back.
        self.sync.active = active;
        if failed.is_none()
            && self.psync.running_cycles()
            && let Err(alarm) = self.advance_cycles()
        {
            failed = Some(*alarm);
        }
        if failed.is_some() {
            // Only the setpoints: the deferred inputs were kept as far as the actions ran.
            let deferred = std::mem::take(&mut self.sync.deferred);
            self.keep_sync_history();
            self.sync.deferred = deferred;
        } else {
            self.keep_sync_history();
        }
        self.publish_sync_data();
        // Data not yet handed to block preparation (`dirty`) waits for `prep_may_read`, which
        // `step_active_sync` tests in every cycle.
        let each_cycle = self.sync.timing
            || self.sync.block_modal
            || self.sync.axis_ovr_written
            || self.psync.rdisable
            || self.psync.running_cycles()
            || self.sync.touched.in_this_cycle();
        self.sync.touched.next_cycle();
        if let Some(alarm) = failed {
            self.sync.next_wake = tick + 1;
            self.raise(alarm);
            return;
        }
        let axis =
            if self.sync.axis_ovr_written { self.sync.axis_ovr.iter().copied().fold(100.0, f64::min) } else { 100.0 };
        let factor = self.sync.ovr / 100.0 * axis / 100.0;
        if factor != 1.0 || self.sync.ovr_applied {
            let o = self.overrides;
            self.planner.set_overrides(o.feed * factor, o.rapid * factor);
            self.sync.ovr_applied = factor != 1.0;
        }
        self.sync.next_wake =
            if each_cycle || self.sync.ovr_applied || self.sync.each != 0 { tick + 1 } else { self.sync.cond_wake };
    }

    /// DELDTG: the block running ends here; `$AC_DELT` keeps the path distance it had left.
    /// The path stops in this cycle (NCTwin does not brake it); preparation waited for the
    /// main run after this block (see `interp/synchronized.rs`) and continues from here.
    pub(super) fn delete_distance_to_go(&mut self) {
        let Some((_, meta)) = self.in_planner.front() else { return };
        let line = meta.line;
        let left = self.planner.front().map_or(0.0, |m| m.length * (1.0 - self.planner.front_fraction()));
        self.sync.deleted = left;
        self.sync.dirty = true;
        self.sync.touch(1 << DELT_BIT);
        self.planner.abort();
        self.in_planner.clear();
        while matches!(self.pending.front(), Some(Item::Move { line: l, .. }) if *l == line) {
            self.pending.pop_front();
        }
        let pos = *self.planner.position();
        self.interp.sync_position(&pos);
    }
}

/// The channel axes whose `$AA_VACTM` an action reads (in its condition or its actions; a
/// technology cycle counts as reading all).
fn velocity_axes(def: &SyncDef) -> u32 {
    use crate::interp::synchronized::flat::{Act, Code, Op};
    let axes = |c: &Code| {
        c.ops.iter().fold(0u32, |axes, op| match op {
            Op::Read(Slot::AaVactm(k)) | Op::Compare(Slot::AaVactm(k), _, _) => {
                axes | 1u32.checked_shl(*k as u32).unwrap_or(0)
            }
            _ => axes,
        })
    };
    let mut all = def.flat_condition.as_ref().map_or(0, axes);
    for act in &def.flat_actions {
        all |= match act {
            Act::Set { value, index, .. } => axes(value) | axes(index),
            Act::Aux { value, .. } | Act::Command { value, .. } | Act::Preset { value, .. } => axes(value),
            Act::WaitMarker { marker, .. } => axes(marker),
            Act::Cycle(_) | Act::CycleName(_) => u32::MAX >> (32 - MAX_CHANNEL_AXES),
            Act::DelDtg | Act::StopReOf | Act::RDisable => 0,
        };
    }
    all
}
