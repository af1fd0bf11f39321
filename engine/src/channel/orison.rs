//! ORISON in the main run's feed: a transformed move under ORISON waits in the prepared items
//! for its successor (as a move to be rounded does); where the orientation kinks between the
//! two, `motion::orison` makes the smoothing zone, which becomes the tail of this move's
//! orientation and the head of the next one's. Both are planned for the machine axes again
//! (`kinematics::plan`, as the rounding does in `blending_trafo.rs`), so every machine axis
//! keeps its limits along the smoothed orientation. The tool tip's path is not touched.
//!
//! The zone is put on the next move at once: a corner rounding that follows at this end then
//! cuts the smoothed orientation, and the next move carries its head whatever happens at its
//! own end. Where planning either move fails, both stay as programmed.

use super::Channel;
use super::blending_trafo::{machine_at, plan_one};
use crate::interp::Item;
use crate::motion::{Move, orison};

impl Channel {
    /// Smooths the orientation at the end between `mv` (just taken from the prepared items)
    /// and the next prepared move, if both are smoothable under ORISON (see the module doc).
    pub(super) fn smooth_orientation(&mut self, mv: &mut Move) {
        let Some(Item::Move { mv: next, offsets, .. }) = self.pending.front() else { return };
        let Some(zone) = orison::zone(mv, next) else { return };
        let Some(active) = offsets.trafo.clone() else { return };
        let (mut a, mut b) = (mv.clone(), next.clone());
        orison::apply(&zone, &mut a, &mut b);
        let Some(from) = machine_at(&active, &a.path) else { return };
        let Some((a, at)) = plan_one(&active, &a, &from, &self.cfg) else { return };
        let Some((b, _)) = plan_one(&active, &b, &at, &self.cfg) else { return };
        *mv = a;
        if let Some(Item::Move { mv: next, .. }) = self.pending.front_mut() {
            *next = b;
        }
    }
}
