//! ORISON in the main run's feed: a transformed move under ORISON waits in the prepared items
//! for its successor (as a move to be rounded does); where the orientation kinks between the
//! two, `motion::orison` makes the smoothing zone, which becomes the tail of this move's
//! orientation and the head of the next one's. Each move is planned for the machine axes again
//! once, when it is taken with both its ends known (`kinematics::plan`, as the rounding does in
//! `blending_trafo.rs`), so every machine axis keeps its limits along the smoothed
//! orientation. The tool tip's path is not touched.
//!
//! The head is put on the next move at once: a corner rounding that follows at this end then
//! cuts the smoothed orientation, and the next move carries its head whatever happens at its
//! own end. Where planning a move with its zones fails (beside a pole), it keeps the plan of its
//! programmed orientation: no zone is made at its end, and a head it already carries keeps
//! that plan's limits (the orientation stays continuous).

use super::blending_trafo::{machine_at, plan_one};
use crate::channel::Channel;
use crate::interp::Item;
use crate::motion::{Move, orison};

impl Channel {
    /// Smooths the orientation at the end between `mv` (just taken from the prepared items)
    /// and the next prepared move if both are smoothable under ORISON and `with_next` (not in
    /// single block), and plans `mv` again if it carries a zone (see the module doc).
    pub(in crate::channel) fn smooth_orientation(&mut self, mv: &mut Move, with_next: bool) {
        // The transformation a head was made under (the move's own: the same as the last's).
        let head_trafo = self.blending.head_trafo.take();
        let has_head = mv.path.ori.as_ref().is_some_and(|o| o.ends.is_some());
        let next = match self.pending.front() {
            Some(Item::Move { mv: next, offsets, .. }) if with_next => Some((next, offsets.trafo.as_ref())),
            _ => None,
        };
        let zone = next.and_then(|(next, trafo)| Some((orison::zone(mv, next)?, trafo?.clone())));
        let Some((zone, active)) = zone else {
            if has_head && let Some(active) = head_trafo {
                replan(&active, mv, &self.cfg);
            }
            return;
        };
        let mut a = mv.clone();
        let Some(Item::Move { mv: next, .. }) = self.pending.front_mut() else { return };
        let mut b = next.clone();
        orison::apply(&zone, &mut a, &mut b);
        if let Some(from) = machine_at(&active, &a.path)
            && let Some((planned, _)) = plan_one(&active, &a, &from, &self.cfg)
        {
            *mv = planned;
            *next = b;
            self.blending.head_trafo = Some(active);
        } else if has_head {
            replan(&active, mv, &self.cfg);
        }
    }
}

/// `mv` planned for the machine axes again from its own start; as it was where that fails.
fn replan(active: &crate::kinematics::ActiveTrafo, mv: &mut Move, cfg: &crate::machine_data::MachineConfig) {
    if let Some(from) = machine_at(active, &mv.path)
        && let Some((planned, _)) = plan_one(active, mv, &from, cfg)
    {
        *mv = planned;
    }
}
