//! Deferred synchronized actions (issue 26's performance goal): an action that runs in every
//! IPO cycle by definition (`ID=n DO $AC_PARAM[i]=$AA_IM[Z]`, no condition) and only stores a
//! value nobody else looks at in the main run is not run; the IPO cycle keeps the few
//! positions it reads (its inputs, one store per axis), and the value is computed from them
//! when someone reads it: block preparation (the published main-run data), the channel's
//! [`Channel::sync_actions`], or the moment the list of actions changes (activation, CANCEL,
//! LOCK/UNLOCK/RESET, program end, reset), when it is stored for real.
//!
//! Why the inputs are kept and not read at the read: the action sees the positions of the
//! point in the IPO cycle where the actions run (before the interpolator), and a read between
//! two cycles sees the positions after it; the previous cycle's actual value depends on the
//! following error of then, which the servo does not keep. So the cycle stores exactly the
//! values the action would have read, and the result is bit for bit that of running it.
//!
//! An action is deferred only where that is exact (checked whenever the list changes):
//! - it has no condition (`DO` only), an `ID`/`IDS`, is not locked, and each of its actions
//!   is an assignment to a fixed `$AC_MARKER[i]` or `$AC_PARAM[i]` of `+ - *` over numbers,
//!   `$AA_IM[ax]` and `$AA_IPO[ax]` (no function, no division: nothing can raise an alarm);
//! - no other active action reads or writes that element (no computed index into the same
//!   array, no technology cycle), so no action sees the value and the order of the writes
//!   does not matter;
//! - no active action has PRESETON (which moves an axis between the cycle's actions);
//! - the horizons are on (`Channel::set_sync_horizons(false)` runs every action: the reference).
//!
//! A deferred action shows as fired from its first cycle on, as a `DO` does.

use std::borrow::Cow;

use super::actions::{ActiveSync, SyncActions};
use crate::channel::Channel;
use crate::interp::synchronized::flat::{Act, Array, Code, Fault, Op, Reader, Slot, Target};
use crate::lang::sync_action::{BinOp, SyncId, Trigger};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// The deferred actions and the inputs kept for them.
#[derive(Debug, Clone, Default)]
pub(super) struct Deferred {
    /// Bits of their places in the active list.
    pub(super) actions: u64,
    /// Channel axes whose `$AA_IM` and `$AA_IPO` they read.
    im_axes: u32,
    ipo_axes: u32,
    /// The values of the last IPO cycle's point of the actions.
    im: [f64; MAX_CHANNEL_AXES],
    ipo: [f64; MAX_CHANNEL_AXES],
    /// The inputs were kept since the list last changed: the deferred actions have run.
    seen: bool,
}

impl Deferred {
    /// Whether the IPO cycle has inputs to keep.
    #[inline]
    pub(super) fn any(&self) -> bool {
        self.actions != 0
    }
}

/// The kept inputs as the actions' expressions read them.
struct Kept<'a>(&'a Deferred);

impl Reader for Kept<'_> {
    fn read(&self, slot: Slot, _line: u32) -> Result<f64, Fault> {
        Ok(match slot {
            Slot::AaIm(k) => self.0.im[k],
            Slot::AaIpo(k) => self.0.ipo[k],
            // Not deferred (`plain`): never asked.
            _ => f64::NAN,
        })
    }

    fn read_at(&self, _array: Array, _index: f64, _line: u32) -> Result<f64, Fault> {
        Ok(f64::NAN)
    }
}

/// A deferrable expression: `+ - *` and negation over numbers, `$AA_IM`, `$AA_IPO`.
fn plain(code: &Code) -> bool {
    code.ops.iter().all(|op| match op {
        Op::Num(_) | Op::Neg => true,
        Op::Read(Slot::AaIm(k) | Slot::AaIpo(k)) => *k < MAX_CHANNEL_AXES,
        Op::Bin(op) => matches!(op, BinOp::Add | BinOp::Sub | BinOp::Mul),
        _ => false,
    })
}

/// The element an action of a deferrable action writes.
fn written(act: &Act) -> Option<Target> {
    match act {
        Act::Set { target: t @ (Target::Marker(_) | Target::Param(_)), value, index }
            if index.ops.is_empty() && plain(value) =>
        {
            Some(*t)
        }
        _ => None,
    }
}

/// Whether `code` may read the element `target` (a computed index reads them all).
fn reads(code: &Code, target: Target) -> bool {
    code.ops.iter().any(|op| match (op, target) {
        (Op::Read(Slot::Marker(i)) | Op::Compare(Slot::Marker(i), ..), Target::Marker(j)) => *i == j,
        (Op::Read(Slot::Param(i)) | Op::Compare(Slot::Param(i), ..), Target::Param(j)) => *i == j,
        (Op::ReadAt(Array::Marker), Target::Marker(_)) | (Op::ReadAt(Array::Param), Target::Param(_)) => true,
        _ => false,
    })
}

/// Whether action `act` (of another synchronized action) reads or writes `target`.
fn touches(act: &Act, target: Target) -> bool {
    match act {
        Act::Set { target: t, value, index } => {
            let same = match (t, target) {
                (Target::At(Array::Marker), Target::Marker(_)) | (Target::At(Array::Param), Target::Param(_)) => true,
                (t, target) => *t == target,
            };
            same || reads(value, target) || reads(index, target)
        }
        Act::Aux { value, .. } | Act::Command { value, .. } | Act::Preset { value, .. } => reads(value, target),
        Act::WaitMarker { marker, .. } => reads(marker, target),
        Act::Cycle(_) | Act::CycleName(_) => true,
        Act::DelDtg | Act::StopReOf | Act::RDisable => false,
    }
}

/// The deferred actions of `active` (none with the horizons off).
fn plan(active: &[ActiveSync], horizons: bool) -> Deferred {
    let mut d = Deferred::default();
    if !horizons || active.len() > 64 {
        return d;
    }
    let preset = active.iter().any(|a| a.def.flat_actions.iter().any(|act| matches!(act, Act::Preset { .. })));
    if preset {
        return d;
    }
    for (i, a) in active.iter().enumerate() {
        let def = &a.def;
        let candidate = def.trigger == Trigger::Always
            && def.flat_condition.is_none()
            && matches!(def.id, Some(SyncId::Modal(_) | SyncId::Static(_)))
            && !a.locked
            && !def.flat_actions.is_empty()
            && def.flat_actions.iter().all(|act| written(act).is_some());
        if !candidate {
            continue;
        }
        let alone = def.flat_actions.iter().filter_map(written).all(|target| {
            // Its own assignments may write the same element again (the last one counts, as
            // when it runs); `plain` values read no marker or parameter.
            active.iter().enumerate().filter(|(j, _)| *j != i).all(|(_, other)| {
                let cond = other.def.flat_condition.as_ref().is_some_and(|c| reads(c, target));
                !cond && !other.def.flat_actions.iter().any(|act| touches(act, target))
            })
        });
        if alone {
            d.actions |= 1 << i;
            for act in &def.flat_actions {
                if let Act::Set { value, .. } = act {
                    for op in value.ops.iter() {
                        match op {
                            Op::Read(Slot::AaIm(k)) => d.im_axes |= 1 << k,
                            Op::Read(Slot::AaIpo(k)) => d.ipo_axes |= 1 << k,
                            _ => {}
                        }
                    }
                }
            }
        }
    }
    d
}

impl SyncActions {
    /// The list changed (or the horizons were switched): the deferred actions are chosen
    /// again. [`SyncActions::store_deferred`] must have run before the list changed.
    pub(super) fn replan_deferred(&mut self) {
        self.deferred = plan(&self.active, !self.horizon_off);
        // One deferred until now is due in the next cycle checked (a deferred one sleeps for
        // good, not running in every cycle).
        for a in self.active.iter_mut().filter(|a| a.def.trigger == Trigger::Always) {
            a.wake = 0;
        }
    }

    /// Stores the values of the deferred actions (their last cycle's) into the markers and
    /// parameters: before the list changes (the places of the actions change with it).
    pub(super) fn store_deferred(&mut self) {
        self.store_deferred_of(u64::MAX);
    }

    /// [`SyncActions::store_deferred`] for the actions of `bits` only.
    pub(super) fn store_deferred_of(&mut self, bits: u64) {
        let d = &self.deferred;
        if !d.seen || d.actions & bits == 0 {
            return;
        }
        let mut writes = Vec::new();
        let mut rest = d.actions & bits;
        while rest != 0 {
            let i = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let def = &self.active[i].def;
            for act in &def.flat_actions {
                if let Act::Set { target, value, .. } = act {
                    // `plain` expressions read only the kept inputs and raise no alarm.
                    let v = crate::interp::synchronized::flat::eval(value, &Kept(d), def.line).unwrap_or(f64::NAN);
                    writes.push((*target, v));
                }
            }
        }
        let dirty = !writes.is_empty();
        for (target, v) in writes {
            match target {
                // Markers are INT: a REAL assigned is rounded (as `sync_set`).
                Target::Marker(i) => self.markers[i] = v.round(),
                Target::Param(i) => self.params[i] = v,
                _ => {}
            }
        }
        self.dirty |= dirty;
    }

    /// The inputs of the deferred actions at this IPO cycle's point of the actions.
    #[inline]
    pub(super) fn keep_deferred_inputs(&mut self, machine: &[f64; MAX_CHANNEL_AXES], lag: &[f64; MAX_CHANNEL_AXES]) {
        let d = &mut self.deferred;
        let mut bits = d.im_axes;
        while bits != 0 {
            let k = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            d.im[k] = machine[k] - lag[k];
        }
        let mut bits = d.ipo_axes;
        while bits != 0 {
            let k = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            d.ipo[k] = machine[k];
        }
        d.seen = true;
    }

    /// A copy with the deferred values stored, or these data when nothing is deferred.
    pub(super) fn with_deferred(&self) -> Cow<'_, SyncActions> {
        if self.deferred.any() && self.deferred.seen {
            let mut copy = self.clone();
            copy.store_deferred();
            Cow::Owned(copy)
        } else {
            Cow::Borrowed(self)
        }
    }

    /// The places of the deferred actions in the active list (bits).
    #[inline]
    pub(super) fn deferred_actions(&self) -> u64 {
        self.deferred.actions
    }
}

impl Channel {
    /// Keeps the deferred actions' inputs of this cycle (`$AA_IM` through the following
    /// errors of now: the point of the actions, before the interpolator).
    #[inline]
    pub(super) fn keep_deferred_inputs(&mut self) {
        self.sync.keep_deferred_inputs(&self.machine, self.servo.errors());
    }

    /// After an action of place `failed` raised an alarm in this cycle: the deferred actions
    /// before it ran in this cycle, the others did not (their values stay those of the cycle
    /// before); nothing more is stored until the inputs are kept again.
    pub(super) fn keep_deferred_inputs_until(&mut self, failed: usize) {
        self.sync.store_deferred();
        self.keep_deferred_inputs();
        self.sync.store_deferred_of((1u64 << failed.min(63)) - 1);
        self.sync.deferred.seen = false;
    }

    /// Whether block preparation may read the main-run data now: it waits for the main run,
    /// or would not wait (nothing queued, no program running).
    #[inline]
    pub(super) fn prep_may_read(&self) -> bool {
        self.blending.prep_waits_for_main_run
            || self.status != crate::channel::Status::Running
            || self.pending.is_empty() && self.planner.is_empty()
    }
}
