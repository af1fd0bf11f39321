//! ORISON in the main run's feed: a transformed move under ORISON waits in the prepared items
//! until the window of moves its steps need is there (`Channel::orison_waits`): the next
//! move, then up to `2·reach` moves (MD28590) or SD42680 of path beyond it, or the end of
//! the run (a block not smoothed, an exact stop, another transformation, anything but a
//! move). When a move is taken, `motion::orison` decides every step of the orientation's rate
//! whose section could still reach the next move, and the next move gets all the steps that
//! reach it: from then on it is final (later steps are decided with their sections beyond
//! it), so a corner rounding at this end cuts the smoothed orientation of both, and in single
//! block no step reaches into a block not yet released. Each move is planned for the machine
//! axes again once, when it is taken with its steps (`kinematics::plan`, as the rounding does
//! in `blending_trafo.rs`), so every machine axis keeps its limits along the smoothed
//! orientation; where that fails (beside a pole) it keeps the plan of the programmed
//! orientation. The tool tip's path is not touched. Memory: the steps whose sections reach
//! past the final move, at most `2·reach + 1`, whatever the program's length.

use super::blending_trafo::{machine_at, plan_one};
use crate::channel::Channel;
use crate::interp::Item;
use crate::kinematics::ActiveTrafo;
use crate::motion::orison::{self, Window};
use crate::motion::{Move, OriKink};

/// What ORISON remembers between the moves of a run (see the module doc).
#[derive(Debug, Clone, Default)]
pub(in crate::channel) struct OriRun {
    /// The front prepared move has its steps (it is final), put on under this transformation.
    front_final: Option<ActiveTrafo>,
    /// Where the front prepared move ends on the run's path (mm), and its index in the run.
    front_end: f64,
    front_index: usize,
    /// The index of the next step not decided (step `i` is at the end of the run's block `i`).
    next_step: usize,
    /// The steps decided whose sections reach past the front prepared move (mm of the run).
    steps: Vec<OriKink>,
    /// The prepared items' count, the last block taken and the front move's length (bits)
    /// when the window was last found short: while they stay, it still is (asked every IPO
    /// cycle while it waits). Forgotten when a move is taken.
    short: std::cell::Cell<(usize, u32, u64)>,
}

impl Channel {
    /// Forgets the run (the prepared items were dropped: reset, alarm, block search).
    pub(in crate::channel) fn end_orison_run(&mut self) {
        self.blending.ori_run = OriRun::default();
    }

    /// True if the front prepared move (under ORISON) waits for more prepared moves before
    /// it is taken: its window is neither complete nor ended (see the module doc).
    pub(in crate::channel) fn orison_waits(&self) -> bool {
        let mut items = self.pending.iter();
        let Some(Item::Move { mv: front, .. }) = items.next() else { return false };
        let Some(spec) = front.orison.as_deref() else { return false };
        let key = (self.pending.len(), self.pending.popped_seq(), front.length.to_bits());
        if self.blending.ori_run.short.get() == key {
            return true;
        }
        // A change of the transformation is not looked for here (comparing it per move and
        // cycle costs): the window then only waits for a few moves more, and
        // `smooth_orientation` ends the run at the change.
        let (mut prev, mut beyond) = (front, 0.0);
        for (i, item) in items.enumerate().map(|(i, item)| (i + 1, item)) {
            let Item::Move { mv: next, .. } = item else { return false };
            if !orison::continues(prev, next) {
                return false;
            }
            if i > 1 {
                beyond += next.length;
            }
            if i >= 2 * spec.reach || beyond >= spec.dist {
                return false;
            }
            prev = next;
        }
        self.blending.ori_run.short.set(key);
        true
    }

    /// Smooths the orientation of `mv` (just taken from the prepared items) and of the next
    /// prepared move if the run goes on into it; decides new steps only if `with_next` (not
    /// in single block); plans `mv` again if it carries steps (see the module doc).
    pub(in crate::channel) fn smooth_orientation(&mut self, mv: &mut Move, with_next: bool) {
        let final_trafo = self.blending.ori_run.front_final.take();
        self.blending.ori_run.short.take();
        let first = final_trafo.is_none();
        if first {
            self.blending.ori_run = OriRun { front_end: mv.length, ..OriRun::default() };
        }
        let run = &mut self.blending.ori_run;
        let reach = mv.orison.as_deref().map_or(1, |s| s.reach);
        // The moves the run goes on into, with their transformation.
        let mut chain: Vec<&Move> = Vec::new();
        let mut active: Option<&ActiveTrafo> = None;
        for item in self.pending.iter().take(if with_next { 2 * reach } else { 1 }) {
            let Item::Move { mv: next, offsets, .. } = item else { break };
            let Some(trafo) = offsets.trafo.as_ref() else { break };
            let prev = chain.last().copied().unwrap_or(mv);
            if active.is_some_and(|a| a != trafo) || !orison::continues(prev, next) {
                break;
            }
            active = Some(trafo);
            chain.push(next);
        }
        // Block starts on the run's path: `mv` (the run's block `run.front_index`), the chain.
        let mut starts = vec![run.front_end - mv.length, run.front_end];
        for next in &chain {
            starts.push(starts[starts.len() - 1] + next.length);
        }
        if with_next && !chain.is_empty() {
            decide_steps(run, mv, &chain, &starts, first);
        }
        if first {
            put_steps(mv, &run.steps, starts[0]);
        }
        let (chained, active) = (!chain.is_empty(), active.cloned());
        if chained {
            run.front_index += 1;
            run.front_end = starts[2];
            run.next_step = run.next_step.max(run.front_index);
            if let Some(Item::Move { mv: next, .. }) = self.pending.front_mut() {
                put_steps(next, &run.steps, starts[1]);
            }
            // Only the steps reaching past the now final move are needed later.
            let end = run.front_end;
            run.steps.retain(|k| k.at + k.half > end);
            run.front_final = active.clone();
        } else {
            run.steps.clear();
        }
        if let Some(active) = final_trafo.or(active)
            && mv.path.ori.as_ref().is_some_and(|o| !o.kinks.is_empty())
        {
            replan(&active, mv, &self.cfg);
        }
    }
}

/// Decides the steps whose sections could still reach the next move `chain[0]`, each within
/// MD28590's reach, the run's blocks in view and what is final (see the module doc).
fn decide_steps(run: &mut OriRun, mv: &Move, chain: &[&Move], starts: &[f64], first: bool) {
    let k = run.front_index;
    let mut window = Window::default();
    if first {
        window.push(starts[0], mv.length, mv.path.ori.as_deref().expect("a smoothable move"));
    }
    for (i, next) in chain.iter().enumerate() {
        window.push(starts[i + 1], next.length, next.path.ori.as_deref().expect("a smoothable move"));
    }
    // New sections start after what is final: the end of `mv`, or its start if it is new.
    let back_limit = if first { starts[0] } else { starts[1] };
    let last = k + chain.len();
    while run.next_step < last {
        // Step j between the run's blocks j and j+1, at the end of block j.
        let j = run.next_step;
        let a = if j == k { mv } else { chain[j - k - 1] };
        let Some(spec) = a.orison.as_deref() else { break };
        let s = starts[j + 1 - k];
        if j > k + spec.reach || s - 0.5 * spec.dist >= starts[2] {
            break;
        }
        let back = starts[(j + 1).saturating_sub(spec.reach).max(k) - k].max(back_limit);
        let forward = starts[(j + 1 + spec.reach).min(last + 1) - k];
        let most = (0.5 * spec.dist).min(s - back).min(forward - s);
        let jump = orison::jump(a, chain[j - k]);
        if let Some(step) = orison::decide(&window, &run.steps, s, jump, most, spec.tol) {
            run.steps.push(step);
        }
        run.next_step = j + 1;
    }
}

/// Puts on `mv` (starting at `start` on the run's path) the steps whose sections reach it.
fn put_steps(mv: &mut Move, steps: &[OriKink], start: f64) {
    let len = mv.length;
    if let Some(o) = mv.path.ori.as_deref_mut() {
        o.kinks = steps.iter().filter(|k| k.reaches(start, start + len)).map(|k| k.rescaled(start, len)).collect();
    }
}

/// `mv` planned for the machine axes again from its own start; as it was where that fails.
fn replan(active: &ActiveTrafo, mv: &mut Move, cfg: &crate::machine_data::MachineConfig) {
    if let Some(from) = machine_at(active, &mv.path)
        && let Some((planned, _)) = plan_one(active, mv, &from, cfg)
    {
        *mv = planned;
    }
}
