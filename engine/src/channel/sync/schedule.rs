//! Which synchronized actions the main run looks at in an IPO cycle: a condition sleeps
//! while it provably keeps its value (its horizon, `interp/synchronized/horizon.rs`, ends at
//! the cycle `ActiveSync::wake`) and no data or event it depends on changed (`Touched`).
//!
//! In a quiet cycle — no horizon ends, nothing any condition reads changed in this cycle or
//! the one before —
//! only the actions that run in every cycle (WHENEVER while true, FROM after it held, DO)
//! are visited, through a bit mask; the others cost nothing. Once one of them changes data
//! the actions after it are checked one by one (the change may wake them in this cycle, in
//! ID order, as with evaluation in every cycle). After a full check the earliest wake cycle
//! and the mask are computed again.

use super::actions::ActiveSync;
use crate::alarm::Alarm;
use crate::channel::Channel;
use crate::interp::synchronized::flat::{self, Fault};
use crate::interp::synchronized::{SyncDef, horizon};
use crate::lang::sync_action::Trigger;

impl Channel {
    /// Runs the actions of this cycle in order; returns the place and the alarm of the first
    /// that failed. Deferred actions (`lazy.rs`) are not run: they show as fired.
    pub(super) fn check_actions(&mut self, active: &mut [ActiveSync]) -> Option<(usize, Alarm)> {
        let tick = self.tick;
        let deps = self.sync.deps;
        let quiet = tick < self.sync.cond_wake && !self.sync.touched.any(deps) && !self.sync.block_modal;
        self.sync.touched.begin_checks();
        // Where the check one by one begins.
        let mut from = 0;
        if quiet {
            from = active.len();
            let mut bits = self.sync.each;
            while bits != 0 {
                let i = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                if let Err(alarm) = self.run_actions(&active[i].def) {
                    return Some((i, *alarm));
                }
                if self.sync.touched.any(deps) {
                    from = i + 1;
                    break;
                }
            }
        }
        let mut failed = None;
        if from < active.len() {
            let deferred = self.sync.deferred_actions();
            for (i, a) in active.iter_mut().enumerate().skip(from) {
                if !a.checked() {
                    continue;
                }
                if deferred & (1 << i) != 0 {
                    (a.fired, a.run_each, a.wake) = (true, false, u64::MAX);
                    continue;
                }
                let done = if tick < a.wake && !self.sync.touched.any(a.deps) {
                    // Asleep: the condition has the value it had.
                    if a.run_each { self.run_actions(&a.def) } else { Ok(()) }
                } else {
                    self.run_sync(a)
                };
                if let Err(alarm) = done {
                    failed = Some((i, *alarm));
                    break;
                }
            }
            let (mut wake, mut each, mut deps) = (u64::MAX, 0, 0);
            for (i, a) in active.iter().enumerate().filter(|(_, a)| a.checked()) {
                wake = wake.min(a.wake);
                each |= u64::from(a.run_each) << i;
                deps |= a.deps;
            }
            (self.sync.cond_wake, self.sync.each, self.sync.deps) = (wake, each, deps);
        }
        failed
    }

    /// Checks one action's condition and runs its actions as its trigger says; notes how
    /// long the condition keeps its value (its horizon).
    fn run_sync(&mut self, a: &mut ActiveSync) -> Result<(), Fault> {
        // The list is out of `self` while it runs: its definitions are borrowed, not cloned.
        let def = &*a.def;
        let tick = self.tick;
        // Conditions no longer checked (WHEN after it acted, FROM after it held, DO) sleep
        // for good: only RESET/UNLOCK or a new activation wakes them. One whose evaluation
        // fails is due again.
        a.wake = if def.flat_condition.is_some() { 0 } else { u64::MAX };
        let cond = match (def.trigger, &def.flat_condition) {
            (Trigger::When, _) if a.fired => {
                a.run_each = false;
                a.wake = u64::MAX;
                return Ok(());
            }
            // FROM: once it held the actions run in every cycle, the condition no longer checked.
            (Trigger::From, _) if a.fired => true,
            (_, None) => true,
            (_, Some(c)) => {
                self.sync.evaluations += 1;
                a.cond = flat::eval(c, self, def.line)? != 0.0;
                // Conditions on data only (markers, signals...) wait for a change of it (`deps`).
                a.wake = if self.sync.horizon_off {
                    tick + 1
                } else if c.volatile {
                    tick + 1 + horizon::horizon(c, self, a.cond)
                } else {
                    u64::MAX
                };
                a.cond
            }
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
        a.run_each = match def.trigger {
            Trigger::Always | Trigger::Whenever => cond,
            Trigger::From => a.fired,
            Trigger::When | Trigger::Every => false,
        };
        if a.fired && matches!(def.trigger, Trigger::When | Trigger::From) {
            a.wake = u64::MAX;
        }
        if run { self.run_actions(def) } else { Ok(()) }
    }

    /// Runs an action's actions.
    fn run_actions(&mut self, def: &SyncDef) -> Result<(), Fault> {
        for act in &def.flat_actions {
            self.sync_act(act, def.line)?;
        }
        Ok(())
    }
}
