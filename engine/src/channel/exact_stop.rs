//! The block change after an exact stop (G60/G9) waits for the exact-stop window of G group 12
//! (Function Manual B1 "Exact stop"): `G601` until every axis' following error is inside
//! MD36010 `$MA_STOP_LIMIT_FINE`, `G602` inside MD36000 `$MA_STOP_LIMIT_COARSE`, `G603` at the
//! interpolator's end (no wait). MD20550 `$MC_EXACT_POS_MODE` may fix the window for G0
//! (units digit) and for the other G group 1 functions (tens digit): 1 G601, 2 G602, 3 G603,
//! 0 the programmed one.
//!
//! Input: the planner's front move before each IPO cycle, the servo model's following errors
//! (`servo.rs`) and the finished block's G group 12. Output: whether the planner may step.
//!
//! With FFWON the position loops are settled (following error 0) and every window is reached
//! in the cycle the interpolator ends, so the three functions run alike and nothing here
//! costs more than one flag test per cycle. With FFWOF the error decays as `e·e^(−Kv·t)` once
//! the setpoint stands still, and the next block starts in the first cycle after the error
//! of every axis is inside its window. Moves that stop without G60/G9 (continuous path before
//! a block without motion or the program end, a change of transformation, single block) end
//! at the interpolator's end: the Programming Manual ("Exact stop") makes G601..G603
//! effective only with G60 or G9, so NCTwin checks the window only for the exact stop the
//! program asks for.

use std::collections::VecDeque;

use super::servo::Servo;
use crate::interp::path_control::StopWindow;
use crate::machine_data::MachineConfig;
use crate::motion::Planner;

/// The wait for an exact-stop window between two blocks.
#[derive(Debug, Clone, Default)]
pub(super) struct ExactStop {
    /// The window the axes must reach before the next block starts: set when a G60/G9 move
    /// has ended with its axes still lagging.
    waiting: Option<StopWindow>,
    /// The tags of the last moves that stop only implicitly (before a block without motion,
    /// at a change of transformation, in single block): they end at the interpolator's end.
    implicit: VecDeque<u32>,
}

/// How many implicit stops are remembered: they are the last moves before a non-move item,
/// so few are ever in the planner at once.
const IMPLICIT_KEPT: usize = 8;

impl ExactStop {
    /// True while the next block must wait: the last G60/G9 move ended and some axis'
    /// following error is still outside the window. Clears the wait once it is reached.
    #[inline]
    pub(super) fn holds(&mut self, servo: &Servo, cfg: &MachineConfig) -> bool {
        match self.waiting {
            None => false,
            Some(window) => self.check(window, servo, cfg),
        }
    }

    /// [`ExactStop::holds`] with a wait to check (out of the plain cycle's code).
    #[inline(never)]
    fn check(&mut self, window: StopWindow, servo: &Servo, cfg: &MachineConfig) -> bool {
        let limits = match window {
            StopWindow::Fine => &cfg.path_control.stop_fine,
            StopWindow::Coarse => &cfg.path_control.stop_coarse,
            StopWindow::IpoEnd => &Vec::new(),
        };
        let inside = limits.iter().zip(servo.errors()).all(|(&limit, e)| e.abs() <= limit);
        if inside {
            self.waiting = None;
        }
        !inside
    }

    /// The move that will carry `tag` stops because of what follows it, not because the
    /// program asks for G60/G9.
    pub(super) fn implicit(&mut self, tag: u32) {
        if self.implicit.len() == IMPLICIT_KEPT {
            self.implicit.pop_front();
        }
        self.implicit.push_back(tag);
    }

    /// Before the planner's step: the tag of the front move and whether it is rapid traverse,
    /// when it ends in an exact stop while the position loops lag (only then can a window be
    /// outside after it).
    #[inline]
    pub(super) fn watch(planner: &Planner, servo: &Servo) -> Option<(u32, bool)> {
        if servo.is_settled() {
            return None;
        }
        planner.front().filter(|m| m.exact_stop).map(|m| (m.tag, m.is_rapid()))
    }

    /// After the planner's step, for a watched move `(tag, rapid)`: if it ended in this cycle
    /// (`finished`) in a programmed exact stop, the next block waits for `programmed`, the
    /// finished block's G group 12, or the window MD20550 fixes for G0 or the other G group 1
    /// functions.
    #[inline(never)]
    pub(super) fn after_step(
        &mut self,
        (tag, rapid): (u32, bool),
        finished: bool,
        programmed: StopWindow,
        cfg: &MachineConfig,
    ) {
        if !finished {
            return;
        }
        if let Some(i) = self.implicit.iter().position(|&t| t == tag) {
            self.implicit.remove(i);
            return;
        }
        let mode = cfg.path_control.exact_pos_mode;
        let window = match if rapid { mode % 10 } else { mode / 10 % 10 } {
            1 => StopWindow::Fine,
            2 => StopWindow::Coarse,
            3 => StopWindow::IpoEnd,
            _ => programmed,
        };
        if window != StopWindow::IpoEnd {
            self.waiting = Some(window);
        }
    }

    /// The next block is waiting for the window.
    #[inline]
    pub(super) fn is_waiting(&self) -> bool {
        self.waiting.is_some()
    }
}
