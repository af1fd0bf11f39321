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

use super::{Channel, Event};
use crate::alarm::Alarm;
use crate::interp::Item;
use crate::interp::auxiliary::AuxFunction;
use crate::interp::synchronized::{CExpr, Func, MainRunData, SyncAct, SyncControl, SyncDef, SyncVar};
use crate::lang::sync_action::{BinOp, SyncId, Trigger};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// `$AC_MARKER[0..7]`: MD28256 MM_NUM_AC_MARKER's default.
pub const MARKERS: usize = 8;
/// `$AC_PARAM[0..49]`: MD28254 MM_NUM_AC_PARAM's default.
pub const PARAMS: usize = 50;
/// `$AC_TIMER[0..7]` (MD28258 MM_NUM_AC_TIMER; NCTwin keeps 8).
pub const TIMERS: usize = 8;
/// `$A_INA[1..4]`, `$A_OUTA[1..4]`: the default of 4 analog signals each (MD10300/10310).
pub const ANALOG_IO: usize = 4;
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
    active: Vec<ActiveSync>,
    pub markers: [f64; MARKERS],
    pub params: [f64; PARAMS],
    /// Running timers' seconds (`None`: stopped).
    pub timers: [Option<f64>; TIMERS],
    /// Whether any timer runs: kept with `timers`, so an idle cycle tests one flag.
    timing: bool,
    pub analog_in: [f64; ANALOG_IO],
    pub analog_out: [f64; ANALOG_IO],
    /// `$AC_DELT`: what the last DELDTG deleted (mm of path).
    pub deleted: f64,
    /// `$AC_OVR` and `$AA_OVR` of this cycle (percent; 100 unless an action wrote them).
    ovr: f64,
    axis_ovr: [f64; MAX_CHANNEL_AXES],
    /// An override of the actions is in the planner (restored when no longer written).
    ovr_applied: bool,
    /// The block `$AC_TIME` counts from, and the cycle it began.
    block: Option<u32>,
    block_start: u64,
    /// The setpoints of the cycle before, for `$AA_VACTM`.
    prev_setpoint: [f64; MAX_CHANNEL_AXES],
    /// Inputs set from outside, with their cycle counts.
    log: std::collections::VecDeque<InputRecord>,
    /// The data changed since it was last handed to block preparation.
    dirty: bool,
    /// The workpiece coordinates of this cycle, once an action read `$AA_IW`.
    wcs: std::cell::Cell<Option<[f64; MAX_CHANNEL_AXES]>>,
}

impl Default for SyncActions {
    fn default() -> Self {
        SyncActions {
            active: Vec::new(),
            markers: [0.0; MARKERS],
            params: [0.0; PARAMS],
            timers: [None; TIMERS],
            timing: false,
            analog_in: [0.0; ANALOG_IO],
            analog_out: [0.0; ANALOG_IO],
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
        }
    }
}

/// One active synchronized action.
#[derive(Debug, Clone)]
struct ActiveSync {
    def: Arc<SyncDef>,
    /// The action ran (WHEN, FROM, EVERY: since activation; WHENEVER, DO: in the last cycle).
    fired: bool,
    /// The condition's value in the last cycle (EVERY's edge).
    was_true: bool,
    locked: bool,
    /// Block-modal: the line of the motion block it belongs to, once that block runs.
    bound: Option<u32>,
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
    #[inline]
    fn idle(&self) -> bool {
        self.active.is_empty() && !self.ovr_applied && !self.dirty && !self.timing
    }

    /// The data as block preparation reads it.
    fn main_run_data(&self) -> MainRunData {
        MainRunData {
            markers: self.markers.to_vec(),
            params: self.params.to_vec(),
            timers: self.timers.to_vec(),
            analog_in: self.analog_in.to_vec(),
            analog_out: self.analog_out.to_vec(),
            deleted: self.deleted,
        }
    }

    /// Program end or reset: modal and block-modal actions end, static ones stay.
    pub fn end_program(&mut self) {
        self.active.retain(|a| matches!(a.def.id, Some(SyncId::Static(_))));
    }

    /// Makes `out` the list of the active actions (nothing allocated while there are none).
    pub(super) fn refresh_list(&self, out: &mut Vec<SyncActionInfo>) {
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
    /// The synchronized actions and their data.
    pub fn sync_actions(&self) -> &SyncActions {
        &self.sync
    }

    /// Sets analog inputs `$A_INA[n]` from outside, each `(n, value)` with n = 1..[`ANALOG_IO`];
    /// all or nothing. They act from the next IPO cycle on.
    pub fn set_analog_inputs(&mut self, inputs: &[(usize, f64)]) -> Result<(), super::CommandError> {
        if let Some((n, v)) = inputs.iter().find(|(n, v)| !(1..=ANALOG_IO).contains(n) || !v.is_finite()) {
            return Err(super::CommandError::Invalid(format!(
                "analog input {n} = {v}: inputs are 1..{ANALOG_IO} with finite values"
            )));
        }
        for &(n, v) in inputs {
            self.sync.analog_in[n - 1] = v;
        }
        self.sync.dirty = true;
        self.publish_sync_data();
        self.log_inputs(InputRecord { tick: self.tick, inputs: vec![], outputs: vec![], analog: inputs.to_vec() });
        Ok(())
    }

    /// The analog inputs and outputs `$A_INA[1..]`, `$A_OUTA[1..]`.
    pub fn analog_io(&self) -> ([f64; ANALOG_IO], [f64; ANALOG_IO]) {
        (self.sync.analog_in, self.sync.analog_out)
    }

    /// The inputs set from outside, oldest first (at most [`INPUT_LOG`]), each with the cycle
    /// count it arrived at: fed to a fresh channel at the same counts
    /// ([`Channel::apply_inputs`]), they reproduce the run.
    pub fn input_log(&self) -> impl Iterator<Item = &InputRecord> {
        self.sync.log.iter()
    }

    /// Sets the signals of a logged record (a replay).
    pub fn apply_inputs(&mut self, record: &InputRecord) -> Result<(), super::CommandError> {
        if !record.inputs.is_empty() || !record.outputs.is_empty() {
            self.set_signals(&record.inputs, &record.outputs)?;
        }
        if !record.analog.is_empty() {
            self.set_analog_inputs(&record.analog)?;
        }
        Ok(())
    }

    /// Logs signals set from outside and publishes them as an event.
    pub(super) fn log_inputs(&mut self, record: InputRecord) {
        if self.sync.log.len() == INPUT_LOG {
            self.sync.log.pop_front();
        }
        self.sync.log.push_back(record.clone());
        self.events.push(Event::InputsChanged(record));
    }

    /// Takes back the inputs of a checkpoint (digital input bits, analog input values).
    pub(super) fn restore_inputs(&mut self, digital: u64, analog: &[f64]) {
        let mut io = self.io;
        io.inputs = digital & ((1u64 << crate::interp::io::DIGITAL_IO) - 1);
        self.set_digital_io(io);
        for (to, v) in self.sync.analog_in.iter_mut().zip(analog) {
            *to = if v.is_finite() { *v } else { 0.0 };
        }
        self.sync.dirty = true;
        self.publish_sync_data();
    }

    /// Hands the data to block preparation when it changed and preparation may read it: it
    /// waits for the main run, or would not wait (nothing queued, no program running). While a
    /// program's moves are queued no block that reads main-run data is prepared, so the copy
    /// is not made in every cycle.
    fn publish_sync_data(&mut self) {
        let may_read = self.blending.prep_waits_for_main_run
            || self.status != super::Status::Running
            || self.pending.is_empty() && self.planner.is_empty();
        if self.sync.dirty && may_read {
            self.sync.dirty = false;
            self.interp.set_sync_data(self.sync.main_run_data());
        }
    }

    /// Main run: a synchronized action's block is reached.
    pub(super) fn activate_sync(&mut self, def: Arc<SyncDef>) {
        let line = def.line;
        let new = ActiveSync { def, fired: false, was_true: false, locked: false, bound: None };
        let list = &mut self.sync.active;
        match new.def.id {
            Some(id) => {
                let n = id.number();
                list.retain(|a| a.def.id.map(SyncId::number) != Some(n));
                let at = list.iter().position(|a| a.def.id.is_none_or(|i| i.number() > n)).unwrap_or(list.len());
                list.insert(at, new);
            }
            None => list.push(new),
        }
        if self.sync.active.len() > MAX_ACTIVE {
            self.sync.active.pop();
            self.raise(Alarm {
                number: 14751,
                message: format!("Channel 1 block {line} resources for motion synchronous actions not sufficient"),
                line: Some(line),
                clear: crate::alarm::Clear::Reset,
            });
        }
    }

    /// Main run: CANCEL/LOCK/UNLOCK/RESET(ids). An ID no action has is passed over.
    pub(super) fn control_sync(&mut self, op: SyncControl, ids: &[u32]) {
        let hit = |a: &ActiveSync| a.def.id.is_some_and(|i| ids.contains(&i.number()));
        match op {
            SyncControl::Cancel => self.sync.active.retain(|a| !hit(a)),
            _ => {
                for a in self.sync.active.iter_mut().filter(|a| hit(a)) {
                    match op {
                        SyncControl::Lock => a.locked = true,
                        SyncControl::Unlock => a.locked = false,
                        _ => (a.fired, a.was_true) = (false, false),
                    }
                }
            }
        }
    }

    /// One IPO cycle of the synchronized actions: one test when none is active.
    #[inline]
    pub(super) fn step_sync_actions(&mut self) {
        if !self.sync.idle() {
            self.run_sync_cycle();
        }
    }

    /// Out of line: the IPO cycle's own code stays small (ARCHITECTURE: the IPO cycle's code).
    #[inline(never)]
    fn run_sync_cycle(&mut self) {
        let dt = self.cfg.ipo_cycle;
        for t in self.sync.timers.iter_mut().flatten() {
            *t += dt;
            self.sync.dirty = true;
        }
        if self.sync.block != self.current_line {
            self.sync.block = self.current_line;
            self.sync.block_start = self.tick;
        }
        self.sync.ovr = 100.0;
        self.sync.axis_ovr = [100.0; MAX_CHANNEL_AXES];
        self.sync.wcs.set(None);
        let running = self.in_planner.front().map(|(_, m)| m.line);
        let mut active = std::mem::take(&mut self.sync.active);
        // Block-modal actions: bound to the first motion block after them, gone after it.
        active.retain_mut(|a| {
            if a.def.id.is_some() {
                return true;
            }
            match a.bound {
                None => {
                    a.bound = running.filter(|l| *l != a.def.line);
                    true
                }
                Some(l) => running == Some(l),
            }
        });
        let mut failed = None;
        for a in active.iter_mut() {
            if a.locked || a.def.id.is_none() && a.bound.is_none() {
                continue;
            }
            match self.run_sync(a) {
                Ok(()) => {}
                Err(alarm) => {
                    failed = Some(*alarm);
                    break;
                }
            }
        }
        // Actions only change the data, never the list: put it back.
        self.sync.active = active;
        self.sync.prev_setpoint = self.machine;
        self.publish_sync_data();
        if let Some(alarm) = failed {
            self.raise(alarm);
            return;
        }
        let factor = self.sync.ovr / 100.0 * self.sync.axis_ovr.iter().copied().fold(100.0, f64::min) / 100.0;
        if factor != 1.0 || self.sync.ovr_applied {
            let o = self.overrides;
            self.planner.set_overrides(o.feed * factor, o.rapid * factor);
            self.sync.ovr_applied = factor != 1.0;
        }
    }

    /// Checks one action's condition and runs its actions as its trigger says.
    fn run_sync(&mut self, a: &mut ActiveSync) -> Result<(), Fault> {
        // The list is out of `self` while it runs: its definitions are borrowed, not cloned.
        let def = &*a.def;
        if def.trigger == Trigger::When && a.fired {
            return Ok(());
        }
        let cond = match &def.condition {
            Some(c) => self.sync_eval(c, def.line)? != 0.0,
            None => true,
        };
        let run = match def.trigger {
            Trigger::Always => true,
            Trigger::Whenever => cond,
            Trigger::When => cond,
            Trigger::From => cond || a.fired,
            Trigger::Every => cond && !a.was_true,
        };
        a.was_true = cond;
        a.fired = match def.trigger {
            Trigger::Always | Trigger::Whenever => run,
            _ => a.fired || run,
        };
        if run {
            for act in &def.actions {
                self.sync_act(act, def.line)?;
            }
        }
        Ok(())
    }

    fn sync_act(&mut self, act: &SyncAct, line: u32) -> Result<(), Fault> {
        match act {
            SyncAct::Set(var, e) => {
                let v = self.sync_eval(e, line)?;
                self.sync_write(var, v, line)
            }
            SyncAct::Aux { letter, extension, value } => {
                let value = self.sync_eval(value, line)?;
                let function = AuxFunction { letter: *letter, extension: *extension, value };
                self.events.push(Event::AuxFunction { function, line });
                Ok(())
            }
            SyncAct::DelDtg => {
                self.delete_distance_to_go();
                Ok(())
            }
        }
    }

    /// DELDTG: the block running ends here; `$AC_DELT` keeps the path distance it had left.
    /// The path stops in this cycle (NCTwin does not brake it); preparation waited for the
    /// main run after this block (see `interp/synchronized.rs`) and continues from here.
    fn delete_distance_to_go(&mut self) {
        let Some((_, meta)) = self.in_planner.front() else { return };
        let line = meta.line;
        let left = self.planner.front().map_or(0.0, |m| m.length * (1.0 - self.planner.front_fraction()));
        self.sync.deleted = left;
        self.sync.dirty = true;
        self.planner.abort();
        self.in_planner.clear();
        while matches!(self.pending.front(), Some(Item::Move { line: l, .. }) if *l == line) {
            self.pending.pop_front();
        }
        let pos = *self.planner.position();
        self.interp.sync_position(&pos);
    }

    fn sync_index(&self, e: &CExpr, name: &str, size: usize, first: usize, line: u32) -> Result<usize, Fault> {
        // Most indices are written as whole numbers: no rounding call for them.
        let v = match e {
            CExpr::Num(v) => *v,
            e => self.sync_eval(e, line)?,
        };
        let n = if v.fract() == 0.0 { v } else { v.round() };
        if v.is_finite() && n >= first as f64 && n < (size + first) as f64 {
            Ok(n as usize - first)
        } else {
            Err(Box::new(Alarm::index_error(line, name, &format!("{v} ({first}..{})", size + first - 1))))
        }
    }

    fn sync_write(&mut self, var: &SyncVar, v: f64, line: u32) -> Result<(), Fault> {
        self.sync.dirty |=
            matches!(var, SyncVar::AcTimer(_) | SyncVar::AcMarker(_) | SyncVar::AcParam(_) | SyncVar::AOuta(_));
        match var {
            SyncVar::AcOvr => self.sync.ovr = v.clamp(0.0, 200.0),
            SyncVar::AaOvr(k) => self.sync.axis_ovr[*k] = v.clamp(0.0, 200.0),
            SyncVar::AcTimer(i) => {
                let i = self.sync_index(i, "$AC_TIMER", TIMERS, 0, line)?;
                // A value of 0 or more starts the timer from there, a negative one stops it.
                self.sync.timers[i] = (v >= 0.0).then_some(v);
                self.sync.timing = self.sync.timers.iter().any(Option::is_some);
            }
            SyncVar::AcMarker(i) => {
                let i = self.sync_index(i, "$AC_MARKER", MARKERS, 0, line)?;
                // Markers are INT: a REAL assigned is rounded.
                self.sync.markers[i] = v.round();
            }
            SyncVar::AcParam(i) => {
                let i = self.sync_index(i, "$AC_PARAM", PARAMS, 0, line)?;
                self.sync.params[i] = v;
            }
            SyncVar::R(i) => {
                let n = self.sync_eval(i, line)?;
                if !(n >= 0.0 && self.interp.write_r_param(n.round() as usize, v)) {
                    return Err(Box::new(Alarm::index_error(line, "$R", &format!("{n}"))));
                }
            }
            SyncVar::AOut(i) => {
                let n = self.sync_index(i, "$A_OUT", crate::interp::io::DIGITAL_IO, 1, line)? + 1;
                let on = v != 0.0;
                if self.io.output(n) != Some(on) {
                    self.execute_digital_output(n, on, line);
                }
            }
            SyncVar::AOuta(i) => {
                let i = self.sync_index(i, "$A_OUTA", ANALOG_IO, 1, line)?;
                self.sync.analog_out[i] = v;
            }
            _ => return Err(Box::new(Alarm::write_protected(line, "synchronized action variable"))),
        }
        Ok(())
    }

    /// The value of a compiled expression in this cycle (booleans 1/0).
    fn sync_eval(&self, e: &CExpr, line: u32) -> Result<f64, Fault> {
        Ok(match e {
            CExpr::Num(v) => *v,
            CExpr::Var(v) => self.sync_read(v, line)?,
            CExpr::Neg(x) => -self.sync_eval(x, line)?,
            CExpr::Not(x) => f64::from(self.sync_eval(x, line)? == 0.0),
            CExpr::Bin(op, a, b) => {
                let (a, b) = (self.sync_eval(a, line)?, self.sync_eval(b, line)?);
                match op {
                    BinOp::Add => a + b,
                    BinOp::Sub => a - b,
                    BinOp::Mul => a * b,
                    BinOp::Div | BinOp::IntDiv | BinOp::Mod if b == 0.0 => {
                        return Err(Box::new(Alarm::arithmetic(line, "division by zero in a synchronized action")));
                    }
                    BinOp::Div => a / b,
                    BinOp::IntDiv => (a / b).trunc(),
                    BinOp::Mod => a % b,
                    BinOp::And => f64::from(a != 0.0 && b != 0.0),
                    BinOp::Or => f64::from(a != 0.0 || b != 0.0),
                    BinOp::Xor => f64::from((a != 0.0) != (b != 0.0)),
                    // REAL comparisons on the control are within 1e-12 relative (MD10280).
                    BinOp::Eq => f64::from(same(a, b)),
                    BinOp::Ne => f64::from(!same(a, b)),
                    BinOp::Lt => f64::from(a < b && !same(a, b)),
                    BinOp::Gt => f64::from(a > b && !same(a, b)),
                    BinOp::Le => f64::from(a <= b || same(a, b)),
                    BinOp::Ge => f64::from(a >= b || same(a, b)),
                }
            }
            CExpr::Func(f, args) => {
                let x = self.sync_eval(&args[0], line)?;
                let y = || args.get(1).map_or(Ok(0.0), |a| self.sync_eval(a, line));
                let v = match f {
                    Func::Sin => x.to_radians().sin(),
                    Func::Cos => x.to_radians().cos(),
                    Func::Tan => x.to_radians().tan(),
                    Func::Asin => x.asin().to_degrees(),
                    Func::Acos => x.acos().to_degrees(),
                    Func::Atan2 => x.atan2(y()?).to_degrees(),
                    Func::Sqrt => x.sqrt(),
                    Func::Abs => x.abs(),
                    Func::Pot => x * x,
                    Func::Trunc => x.trunc(),
                    Func::Round => x.round(),
                    Func::Ln => x.ln(),
                    Func::Exp => x.exp(),
                    Func::MinVal => x.min(y()?),
                    Func::MaxVal => x.max(y()?),
                };
                if !v.is_finite() {
                    return Err(Box::new(Alarm::arithmetic(line, "a function's argument outside its domain")));
                }
                v
            }
        })
    }

    fn sync_read(&self, var: &SyncVar, line: u32) -> Result<f64, Fault> {
        let dt = self.cfg.ipo_cycle;
        Ok(match var {
            SyncVar::AaIm(k) => self.actual_position(*k),
            SyncVar::AaIpo(k) => self.machine[*k],
            SyncVar::AaIw(k) => {
                if let Some(w) = self.sync.wcs.get() {
                    return Ok(w[*k]);
                }
                let mut basic = [0.0; MAX_CHANNEL_AXES];
                for (i, b) in basic.iter_mut().enumerate().take(self.cfg.channel_axes.len()) {
                    *b = self.actual_position(i) - self.offsets.tool[i];
                }
                let w = self.offsets.frame.unapply(&self.cfg.geo_axes, &basic).unwrap_or([f64::NAN; MAX_CHANNEL_AXES]);
                self.sync.wcs.set(Some(w));
                w[*k]
            }
            SyncVar::AaVactm(k) => (self.machine[*k] - self.sync.prev_setpoint[*k]) / dt * 60.0,
            SyncVar::AaOvr(k) => self.sync.axis_ovr[*k],
            SyncVar::AcTime => (self.tick - self.sync.block_start) as f64 * dt,
            SyncVar::AcPath => self.planner.front().map_or(0.0, |m| m.length * self.planner.front_fraction()),
            SyncVar::AcDteb => self.planner.front().map_or(0.0, |m| m.length * (1.0 - self.planner.front_fraction())),
            SyncVar::AcVactb => self.planner.velocity() * 60.0,
            SyncVar::AcOvr => self.sync.ovr,
            SyncVar::AcDelt => self.sync.deleted,
            SyncVar::AcTimer(i) => self.sync.timers[self.sync_index(i, "$AC_TIMER", TIMERS, 0, line)?].unwrap_or(0.0),
            SyncVar::AcMarker(i) => self.sync.markers[self.sync_index(i, "$AC_MARKER", MARKERS, 0, line)?],
            SyncVar::AcParam(i) => self.sync.params[self.sync_index(i, "$AC_PARAM", PARAMS, 0, line)?],
            SyncVar::R(i) => {
                let n = self.sync_eval(i, line)?;
                let r = &self.interp.variables().r;
                *r.get(n.round().max(0.0) as usize)
                    .filter(|_| n >= 0.0)
                    .ok_or_else(|| Alarm::index_error(line, "$R", &format!("{n}")))?
            }
            SyncVar::AIn(i) => {
                let n = self.sync_index(i, "$A_IN", crate::interp::io::DIGITAL_IO, 1, line)? + 1;
                f64::from(u8::from(self.io.input(n).unwrap_or(false)))
            }
            SyncVar::AOut(i) => {
                let n = self.sync_index(i, "$A_OUT", crate::interp::io::DIGITAL_IO, 1, line)? + 1;
                f64::from(u8::from(self.io.output(n).unwrap_or(false)))
            }
            SyncVar::AIna(i) => self.sync.analog_in[self.sync_index(i, "$A_INA", ANALOG_IO, 1, line)?],
            SyncVar::AOuta(i) => self.sync.analog_out[self.sync_index(i, "$A_OUTA", ANALOG_IO, 1, line)?],
            SyncVar::AaS(i) => {
                let n = self.sync_index(i, "$AA_S", self.spindles.len().max(1), 1, line)?;
                self.spindles.get(n).map_or(0.0, |s| s.speed)
            }
        })
    }
}

/// An alarm of the main run's evaluation, boxed: the evaluator's results stay two words wide,
/// which keeps the IPO cycle's recursion cheap.
type Fault = Box<Alarm>;

/// Equal within the control's relative tolerance for REAL comparisons.
fn same(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
}
