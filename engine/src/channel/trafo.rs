//! The main run's side of a kinematic transformation: mapping every IPO sample of the BCS to
//! machine positions, and switching transformations at standstill.

use super::Channel;
use crate::kinematics::{ActiveTrafo, Transformation};
use crate::machine_data::registry::MAX_CHANNEL_AXES;

impl Channel {
    /// Maps the planner's position of this cycle to machine positions: through the
    /// transformation of the move the position lies on, continuous with the last cycle.
    pub(super) fn update_machine_position(&mut self) {
        let tag = self.planner.position_tag();
        // A new move, and every position at rest (a block end with a stop, a hold), is solved
        // directly: stepped angles differ from it in the last digits, which a modulo axis at
        // rest would show (−1e-14° displays as 360°).
        if tag != self.trafo_tag {
            self.enter_move_transformation(tag);
        } else if self.planner.velocity() == 0.0 {
            self.ori_memo.clear();
        }
        let machine_space = self.position_meta(tag).is_some_and(|m| m.machine_space);
        let ori = &self.cfg.ori;
        self.toff.step(&self.offsets.toff, ori.toff_velocity, ori.toff_accel, self.cfg.ipo_cycle);
        let toff = self.toff.current;
        match self.trafo.as_ref().filter(|_| !machine_space) {
            // A machine-axis motion under a transformation (MCS JOG, the pole's positioning
            // moves) already holds machine positions, the offset included.
            None if machine_space => self.machine = *self.planner.position(),
            None => {
                // In two halves: a 160-byte copy is a call to memcpy, 80 bytes are moves inline.
                let (position, half) = (self.planner.position(), MAX_CHANNEL_AXES / 2);
                self.machine[..half].copy_from_slice(&position[..half]);
                self.machine[half..].copy_from_slice(&position[half..]);
                // Without a transformation the tool directions are the geometry axes.
                for (g, k) in self.cfg.geo_axes.iter().enumerate() {
                    if let Some(k) = k {
                        self.machine[*k] += toff[g];
                    }
                }
            }
            Some(_) => self.map_through_transformation(toff),
        }
        self.sync_rotary_spindle();
    }

    /// The queued move `tag` (the one the planner's position lies on) with its block's data.
    #[inline]
    fn position_meta(&self, tag: Option<u32>) -> Option<&super::MoveMeta> {
        // Mostly the oldest move in the planner: found without the queue's iterator.
        match self.in_planner.front() {
            Some((t, meta)) if Some(*t) == tag => Some(meta),
            _ => tag.and_then(|t| self.in_planner.iter().find(|(tag, _)| *tag == t)).map(|(_, meta)| meta),
        }
    }

    /// The planner's position moved onto move `tag`: the stepped angles start afresh, and a
    /// tool change inside a motion block reaches the main run with the move (once per move,
    /// out of the cycle's code).
    #[inline(never)]
    fn enter_move_transformation(&mut self, tag: Option<u32>) {
        self.ori_memo.clear();
        self.trafo_tag = tag;
        let trafo = match self.position_meta(tag) {
            Some(m) if !m.machine_space && m.offsets.trafo != self.trafo => m.offsets.trafo.clone(),
            _ => return,
        };
        self.trafo = trafo;
        self.sync.wake_all();
    }

    /// The planner's position through the active transformation into `machine` (out of line:
    /// the plain IPO cycle does not carry the transformations' code).
    #[inline(never)]
    fn map_through_transformation(&mut self, toff: [f64; 3]) {
        let Some(t) = self.trafo.as_ref() else { return };
        // Mapped in place in a copy of the BCS position (the transformation writes only its
        // own slots); the last machine position stays the continuity reference.
        let mut m = *self.planner.position();
        let tool = [t.tool[0] + toff[0], t.tool[1] + toff[1], t.tool[2] + toff[2]];
        let mapped = match self.planner.orientation() {
            Some(o) => t.trafo.inverse_oriented_stepped(o, &self.machine, &tool, &mut m, &mut self.ori_memo),
            None => t.trafo.inverse(self.planner.position(), &self.machine, &tool, &mut m),
        };
        if mapped.is_ok() {
            self.machine = m;
        }
    }

    /// A spindle used as the transformation's rotary axis is in position control: its angle
    /// is the machine position.
    fn sync_rotary_spindle(&mut self) {
        let Some(k) = self.trafo.as_ref().and_then(|t| t.trafo.rotary_slot()) else { return };
        if let Some(s) = self.spindles.iter_mut().find(|s| s.axis == k) {
            s.position = self.machine[k];
        }
    }

    /// Selects, deselects or updates (new tool) the transformation at standstill. Returns
    /// false while a spindle that is to become the rotary axis still turns.
    pub(super) fn switch_transformation(&mut self, new: Option<ActiveTrafo>) -> bool {
        let rotary = |t: &ActiveTrafo| t.trafo.rotary_slot();
        let spindle = new.as_ref().and_then(rotary).and_then(|k| self.spindles.iter().find(|s| s.axis == k));
        if let Some(s) = spindle {
            if s.is_turning() {
                return false;
            }
            // After SPOS the angle is already the axis position; in speed mode it is the spindle's.
            if self.trafo.as_ref().and_then(rotary) != Some(s.axis) && !s.axis_mode {
                self.machine[s.axis] = s.position;
            }
        }
        self.trafo = new;
        self.sync.wake_all();
        let space = self.space_of_machine();
        self.planner.set_position(space);
        // After a block search the wait for the target's selection ends at its switch; a
        // program's selection ends it when its own block executes (`main_run.rs`).
        if self.prep_waits_for_trafo && self.trafo_selection.is_none() {
            self.prep_waits_for_trafo = false;
            self.interp.sync_transformation(&self.machine);
        }
        true
    }

    /// After reset and program end: takes over the transformation the interpreter's reset
    /// chose (none, the one that stays, or the reset data set); the axes stay where they are.
    pub(super) fn adopt_transformation(&mut self) {
        self.trafo = self.interp.offsets().trafo.clone();
        self.sync.wake_all();
        let space = self.space_of_machine();
        self.planner.set_position(space);
    }
}
