//! Motion-synchronous actions in block preparation: a block holding one is compiled once
//! (`compile.rs`) and handed to the main run as [`Item::SyncAction`], which evaluates it in
//! every IPO cycle (`channel/sync/actions.rs`). `CANCEL(n)`, `LOCK(n)`, `UNLOCK(n)` and
//! `RESET(n)` go to the main run as [`Item::SyncControl`] in program order.
//!
//! A block-modal action with `DELDTG` makes the block after its motion block wait for the
//! main run (the control's preprocessing stop after a distance-to-go deletion): that block
//! must start where the path was stopped, which only the main run knows.

pub(super) mod channel_coordination;
pub mod compile;
pub mod elements;
pub mod flat;
pub mod horizon;
pub mod technology;
pub(super) mod wait_markers;

use std::sync::Arc;

pub use compile::{CExpr, Func, SyncAct, SyncDef, SyncVar};

use super::{Interpreter, Item};
use crate::alarm::Alarm;
use crate::interp::eval::value::Value;
use crate::lang::sync_action::{self, SYNC_ACTION_WORD};
use crate::lang::{Block, Expr, Word};
use crate::machine_data::MachineConfig;
use crate::motion::AxisVec;

/// The main-run data of synchronized actions as block preparation reads them (`R1=$AC_DELT`,
/// `IF $AC_MARKER[1]==1 ...`): like every `$AC_` variable, a block reading them waits for the
/// main run; the channel hands over each new state ([`Interpreter::set_sync_data`]).
#[derive(Debug, Clone, PartialEq)]
pub struct MainRunData {
    pub markers: Vec<f64>,
    pub params: Vec<f64>,
    /// Running timers' seconds (`None`: stopped, read as 0).
    pub timers: Vec<Option<f64>>,
    pub analog_in: Vec<f64>,
    pub analog_out: Vec<f64>,
    /// `$AC_DELT`.
    pub deleted: f64,
    /// The main run's machine positions when they differ from the programmed ones at a
    /// preprocessing stop (STOPREOF ended it while the path moves; command axes or PRESETON
    /// moved axes the program did not): `$AA_IM`/`$AA_IPO` read these.
    pub machine: Option<AxisVec>,
    /// The velocities there (mm/min, deg/min per channel axis) for `$AA_VACTM`; without
    /// [`MainRunData::machine`] the axes are at rest (the read waited for the main run).
    pub velocity: AxisVec,
}

/// Before the channel handed any state over: everything zero in the control's sizes (an empty
/// list read 17020 for `$AC_PARAM[0]` and underflowed forming its message).
impl Default for MainRunData {
    fn default() -> Self {
        let z = flat::SyncSizes::default();
        MainRunData {
            markers: vec![0.0; z.markers],
            params: vec![0.0; z.params],
            timers: vec![None; z.timers],
            analog_in: vec![0.0; z.analog_in],
            analog_out: vec![0.0; z.analog_out],
            deleted: 0.0,
            machine: None,
            velocity: [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES],
        }
    }
}

impl MainRunData {
    /// `$AC_MARKER[n]`, `$AC_PARAM[n]`, `$AC_TIMER[n]` (from 0), `$A_INA[n]`, `$A_OUTA[n]`
    /// (from 1), `$AC_DELT`; `None` for any other name.
    pub(crate) fn read(&self, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
        let (list, first): (&[f64], usize) = match name {
            "$AC_DELT" => return Some(Ok(Value::Real(self.deleted))),
            "$AC_MARKER" => (&self.markers, 0),
            "$AC_PARAM" => (&self.params, 0),
            "$A_INA" => (&self.analog_in, 1),
            "$A_OUTA" => (&self.analog_out, 1),
            "$AC_TIMER" => {
                return Some(
                    index(name, indices, self.timers.len(), 0, line)
                        .map(|i| Value::Real(self.timers[i].unwrap_or(0.0))),
                );
            }
            _ => return None,
        };
        Some(
            index(name, indices, list.len(), first, line)
                .map(|i| if name == "$AC_MARKER" { Value::Int(list[i] as i64) } else { Value::Real(list[i]) }),
        )
    }
}

/// A part program's write to data the main run keeps, done when its block reaches the main
/// run ([`crate::interp::Item::MainRunWrite`]), in order with the motion before it: synchronized
/// actions and the counters read the value from there on, and so does a block after it, which
/// waits for the main run to read any `$AC_` variable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MainRunWrite {
    /// `$AC_MARKER[n] = v` (rounded where it is written: markers are INT).
    Marker(usize, f64),
    /// `$AC_PARAM[n] = v`.
    Param(usize, f64),
    /// `$AC_TIMER[n] = v`: the timer runs from v seconds (a negative v stops it).
    Timer(usize, f64),
    /// `$AC_REQUIRED_PARTS = n` and the other workpiece counters.
    Parts(crate::interp::eval::process_vars::PartCounter, u32),
    /// `PRESETON(ax, v)` in a program block: channel axis `ax`'s machine position becomes `v`
    /// without motion (`frames/preset.rs`).
    Preset(usize, f64),
    /// GOTOS in the main program: it starts over, which counts workpieces and clears the cycle
    /// time where MD27880/MD27860 say so.
    StartOver,
}

/// `name[indices] = expr` as a [`MainRunWrite`], or `None` when `name` is none of that data.
/// The runtimes are read only (write protected); an index outside its list is 17020, a count
/// outside 0..999,999,999 is 12560.
pub(super) fn program_write(
    name: &str,
    indices: &[Expr],
    expr: &Expr,
    cfg: &MachineConfig,
    ctx: &crate::interp::eval::scope::Ctx,
    line: u32,
) -> Result<Option<MainRunWrite>, Alarm> {
    use crate::interp::eval::process_vars::{MAX_PARTS, PartCounter};
    use crate::interp::eval::{eval, eval_f64};
    if matches!(name, "$AC_OPERATING_TIME" | "$AC_CYCLE_TIME" | "$AC_CUTTING_TIME") {
        return Err(Alarm::write_protected(line, name));
    }
    if let Some(counter) = PartCounter::named(name) {
        if !indices.is_empty() {
            return Err(Alarm::index_error(line, name, "takes no index"));
        }
        let v = eval_f64(expr, ctx, line)?.round();
        if !(0.0..=MAX_PARTS as f64).contains(&v) {
            return Err(Alarm::value_out_of_range(line, &format!("{name} = {v}")));
        }
        return Ok(Some(MainRunWrite::Parts(counter, v as u32)));
    }
    let len = match name {
        "$AC_MARKER" => cfg.sync_sizes.markers,
        "$AC_PARAM" => cfg.sync_sizes.params,
        "$AC_TIMER" => cfg.sync_sizes.timers,
        _ => return Ok(None),
    };
    let idx = indices.iter().map(|e| eval(e, ctx, line)).collect::<Result<Vec<_>, _>>()?;
    let i = index(name, &idx, len, 0, line)?;
    let v = eval_f64(expr, ctx, line)?;
    Ok(Some(match name {
        "$AC_MARKER" => MainRunWrite::Marker(i, v),
        "$AC_PARAM" => MainRunWrite::Param(i, v),
        _ => MainRunWrite::Timer(i, v),
    }))
}

/// The element of `name[n]` in a list of `len` numbered from `first` (17020 outside).
fn index(name: &str, indices: &[Value], len: usize, first: usize, line: u32) -> Result<usize, Alarm> {
    let [n] = indices else { return Err(Alarm::index_error(line, name, "needs one index")) };
    let n = n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    usize::try_from(n)
        .ok()
        .filter(|n| (first..first + len).contains(n))
        .map(|n| n - first)
        .ok_or_else(|| Alarm::index_outside(line, name, n, len, first))
}

/// The commands on synchronized actions by ID.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SyncControl {
    /// `CANCEL(n)`: ends the modal or static action n.
    Cancel,
    /// `LOCK(n)`: suspends it (its condition is not checked).
    Lock,
    /// `UNLOCK(n)`: resumes it.
    Unlock,
    /// `RESET(n)`: starts it afresh (a fired WHEN fires again).
    Reset,
}

/// Preparation held back behind a block-modal DELDTG.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum PrepWait {
    #[default]
    None,
    /// The action is prepared; its motion block (the next one that moves) is still to come.
    /// Holds the programmed position at the action.
    AfterMotion(AxisVec),
    /// The motion block is prepared: the next block waits until the main run is idle.
    UntilIdle,
}

impl PrepWait {
    /// Whether the block just read must wait for the main run because of a DELDTG before
    /// it; `pos` is the programmed position.
    #[inline]
    pub(super) fn holds(&mut self, pos: &AxisVec, main_run_idle: bool) -> bool {
        match *self {
            PrepWait::None => false,
            PrepWait::AfterMotion(at) => {
                // The motion block has been prepared once the programmed position moved.
                if at != *pos {
                    *self = PrepWait::UntilIdle;
                    return !main_run_idle;
                }
                false
            }
            PrepWait::UntilIdle => {
                if main_run_idle {
                    *self = PrepWait::None;
                }
                !main_run_idle
            }
        }
    }
}

impl Interpreter {
    /// Prepares a block holding a synchronized action or CANCEL/LOCK/UNLOCK/RESET; `false`
    /// for any other block.
    pub(super) fn synchronized_block(
        &mut self,
        block: &Block,
        cfg: &MachineConfig,
        programs: &crate::programs::Programs,
        out: &mut Vec<Item>,
    ) -> Result<bool, Alarm> {
        let line = block.line;
        let Some(Word::Keyword { name, args }) = block.words.first() else { return Ok(false) };
        if name == SYNC_ACTION_WORD {
            let [Expr::Str(text)] = args.as_slice() else { return Ok(false) };
            let parsed = sync_action::parse(text).map_err(|e| Alarm::syntax(line, &e.message))?;
            let mut def = compile::compile(&parsed, cfg, line)?;
            technology::resolve(&mut def.flat_actions, cfg, programs, line)?;
            if def.id.is_some() && def.deletes_distance() {
                // DELDTG of the path belongs to the block it ends: non-modal actions only.
                return Err(compile::not_admissible(line, "DELDTG in a modal or static action"));
            }
            if def.id.is_some() && def.ends_preprocessing_stop() {
                // STOPREOF ends the stop after the action's own motion block: non-modal only.
                return Err(compile::not_admissible(line, "STOPREOF in a modal or static action"));
            }
            if def.deletes_distance() || def.ends_preprocessing_stop() {
                self.sync_wait = PrepWait::AfterMotion(self.pos);
            }
            out.push(Item::SyncAction { def: Arc::new(def), line });
            return Ok(true);
        }
        let op = match name.as_str() {
            "CANCEL" => SyncControl::Cancel,
            "LOCK" => SyncControl::Lock,
            "UNLOCK" => SyncControl::Unlock,
            "RESET" => SyncControl::Reset,
            _ => return Ok(false),
        };
        if block.words.len() > 1 {
            return Err(Alarm::syntax(line, &format!("{name} stands alone in its block")));
        }
        let ids = args
            .iter()
            .map(|a| match a {
                Expr::Number(n) if n.fract() == 0.0 && (1.0..=255.0).contains(n) => Ok(*n as u32),
                _ => Err(Alarm::value_out_of_range(line, &format!("{name}: an ID 1..255 expected"))),
            })
            .collect::<Result<Vec<_>, _>>()?;
        if ids.is_empty() {
            return Err(Alarm::syntax(line, &format!("{name} needs the ID of a synchronized action")));
        }
        out.push(Item::SyncControl { op, ids, line });
        Ok(true)
    }

    /// Whether the fast lane must step aside (it does not look at DELDTG waits).
    #[inline]
    pub(super) fn sync_wait_pending(&self) -> bool {
        self.sync_wait != PrepWait::None
    }

    /// The main run's data of synchronized actions, after each change.
    pub fn set_sync_data(&mut self, data: MainRunData) {
        let (machine, velocity) = (self.sync_data.machine, self.sync_data.velocity);
        self.sync_data = data;
        self.sync_data.machine = machine;
        self.sync_data.velocity = velocity;
    }

    /// The main run's machine positions for `$AA_IM` reads while they differ from the
    /// programmed ones (see [`MainRunData::machine`]); `None` otherwise.
    /// With it the velocities there (`$AA_VACTM`).
    pub fn set_main_run_position(&mut self, machine: Option<(AxisVec, AxisVec)>) {
        self.sync_data.machine = machine.map(|(m, _)| m);
        self.sync_data.velocity = machine.map_or([0.0; crate::machine_data::registry::MAX_CHANNEL_AXES], |(_, v)| v);
    }

    /// A synchronized action writes R parameter `n` in the main run.
    pub fn write_r_param(&mut self, n: usize, value: f64) -> bool {
        match self.vars.r.get_mut(n) {
            Some(r) => {
                *r = value;
                true
            }
            None => false,
        }
    }
}
