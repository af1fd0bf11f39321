//! JOG in an interrupted program and REPOS, the return to the interruption point.
//!
//! After NC stop (or M0, M1, single block) the program is interrupted: it keeps its prepared
//! blocks and its main run (the planner with the rest of the interrupted move) and waits. The
//! operator may change to JOG and move axes away; the first JOG motion puts the program's main
//! run aside ([`Interrupted`]) and JOG runs on a fresh planner. Back in the program's mode, NC
//! start first travels on a straight line from where the axes are to the interruption point
//! (REPOSL, the control's default "repositioning on a straight line"), then restores the
//! program's main run and continues it as if it had never stopped.
//!
//! The REPOS motion runs in the space of the program's moves: with a transformation active
//! (TRANSMIT, TRACYL, TRAANG) it is a straight line of the tool tip in the BCS and the machine
//! axes follow through the transformation, which stays active during JOG and REPOS (the
//! manual: the transformation must be active in the restart block). Its velocity is the
//! programmed feed of the interrupted move (rapid traverse after a G0), or, when no move was
//! interrupted (M0), of the next move; without either, the JOG velocity. Feed and rapid
//! override act on it; NC stop stops it and the next NC start plans it anew from there.

pub(super) mod approach;
pub(super) mod modes;

use std::collections::VecDeque;

use super::{Channel, MoveMeta, Status};
use crate::interp::Item;
use crate::kinematics::{Transformation, plan};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{AxisLimit, AxisVec, Feed, Move, Path, Planner};
use approach::ReposApproach;
use modes::{ReposMode, Resume};

/// The main run of an interrupted program, put aside while the operator jogs.
#[derive(Debug, Clone)]
pub(super) struct Interrupted {
    planner: Planner,
    in_planner: VecDeque<(u32, MoveMeta)>,
    /// Where the main run takes over once the REPOS motion has arrived (RMI/RMB/RME/RMN).
    resume: Resume,
}

impl Channel {
    /// The first JOG motion in an interrupted program puts its main run aside.
    pub(super) fn interrupt_for_jog(&mut self) {
        if self.interrupted.is_some() {
            return;
        }
        let mut fresh = Planner::new(self.cfg.ipo_cycle, AxisLimit::for_channel(&self.cfg), *self.planner.position());
        fresh.set_overrides(self.overrides.feed, self.overrides.rapid);
        let planner = std::mem::replace(&mut self.planner, fresh);
        let in_planner = std::mem::take(&mut self.in_planner);
        self.interrupted = Some(Box::new(Interrupted { planner, in_planner, resume: Resume::AsInterrupted }));
    }

    /// Forgets an interrupted program's main run (reset, alarm).
    pub(super) fn drop_interruption(&mut self) {
        self.interrupted = None;
        self.repos_returning = false;
    }

    /// True when the program was interrupted and axes were moved by JOG since (NC start then
    /// repositions first).
    pub fn repos_pending(&self) -> bool {
        self.interrupted.is_some() || self.repos_returning
    }

    /// NC start in an interrupted program whose axes were moved by JOG; `mode` picks the point
    /// of the interrupted block the program resumes at (see `modes.rs`).
    pub(super) fn start_repos(&mut self, mode: ReposMode, approach: ReposApproach) {
        self.status = Status::Running;
        if !self.planner.is_empty() {
            // A REPOS motion stopped on its way (still braking): it goes on.
            self.planner.set_hold(false);
            self.repos_returning = true;
            self.wake_motion_readers();
            return;
        }
        let Some(int) = &self.interrupted else {
            self.repos_returning = false;
            return;
        };
        if self.search_approach {
            // After a block search the approach starts from wherever the axes stand.
            self.interrupted = None;
            self.planner.set_hold(false);
            return;
        }
        // The space of the target: the interrupted position's move, or the front move's path.
        let at_position = int
            .planner
            .position_tag()
            .and_then(|t| int.in_planner.iter().find(|(tag, _)| *tag == t))
            .is_some_and(|(_, m)| m.machine_space);
        let machine_space = match int.planner.front() {
            Some(front) if mode != ReposMode::Interruption => front.machine_space,
            _ => at_position,
        };
        let here_in_space = if machine_space { self.machine } else { *self.planner.position() };
        let axes = self.repos_distance_axes(machine_space);
        let (mut target, resume) = modes::target(&int.planner, mode, &here_in_space, &axes);
        if let (true, Some(t)) = (machine_space, self.trafo_in_force()) {
            // A machine-axis motion (the TRANSMIT pole): return to its BCS point.
            target = t.forward(&target);
        }
        if let Some(int) = &mut self.interrupted {
            int.resume = resume;
        }
        let Some(int) = &self.interrupted else { return };
        let feed = int
            .planner
            .current_tag()
            .and_then(|tag| int.in_planner.iter().find(|(t, _)| *t == tag))
            .map(|(_, m)| m.feed)
            .or_else(|| {
                self.pending.iter().find_map(|i| match i {
                    Item::Move { mv, .. } => Some(mv.feed),
                    _ => None,
                })
            });
        let here = *self.planner.position();
        if here.iter().zip(&target).all(|(a, b)| (a - b).abs() < 1e-9) {
            self.resume_interrupted();
            return;
        }
        let feed = match feed {
            Some(f) if f.is_infinite() => Feed::Rapid,
            Some(f) if f > 0.0 => Feed::Path(f),
            _ => Feed::Path(self.repos_jog_velocity(&here, &target)),
        };
        let tangent = match (self.interrupted.as_ref().and_then(|i| i.planner.front()), resume) {
            (Some(_), _) if machine_space => [0.0; MAX_CHANNEL_AXES],
            (Some(front), Resume::AsInterrupted) => {
                front.path.tangent(self.interrupted.as_ref().map_or(0.0, |i| i.planner.front_fraction()))
            }
            (Some(front), Resume::FrontAt(u)) => front.path.tangent(u),
            (Some(front), Resume::SkipFront) => front.path.tangent(1.0),
            (None, _) => [0.0; MAX_CHANNEL_AXES],
        };
        let geo = self.repos_distance_axes(false);
        let offsets = self.offsets.clone();
        let meta = MoveMeta { line: 0, seq: super::pending::NO_SEQ, offsets, machine_space: false, feed: 0.0 };
        match approach::approach_arc(approach, &here, &target, &tangent, &geo) {
            Some(arc) => {
                // To the start of the circle on a straight line, then along the circle.
                let start = arc.start;
                if here.iter().zip(&start).any(|(a, b)| (a - b).abs() > 1e-9) {
                    let mv = self.straight_move(here, start, feed);
                    self.push_bcs_move(mv, meta.clone());
                }
                let length = arc.arc.as_ref().map_or(0.0, |a| a.radius * a.sweep.abs());
                let mv = Move::new(arc, length, feed, &AxisLimit::for_channel(&self.cfg), true, self.next_tag);
                self.push_bcs_move(mv, meta);
            }
            None => {
                let mv = self.straight_move(here, target, feed);
                self.push_bcs_move(mv, meta);
            }
        }
        self.repos_returning = true;
        self.wake_motion_readers();
    }

    /// Queues a move of the program space. With a transformation active and the planner empty
    /// (the machine position is where the move starts), it is planned like a program block: the
    /// path velocity keeps every machine axis within its limits, pole passages get their
    /// positioning moves. A move the transformation cannot plan is queued as it is.
    pub(super) fn push_bcs_move(&mut self, mv: Move, meta: MoveMeta) {
        let planned = match self.trafo_in_force() {
            Some(t) if !mv.machine_space && self.planner.is_empty() => {
                plan::plan_block(&t, &mv, &self.machine, &self.cfg).ok().map(|planned| planned.moves)
            }
            _ => None,
        };
        match planned {
            Some(moves) if !moves.is_empty() => {
                for m in moves {
                    let meta = MoveMeta { machine_space: m.machine_space, ..meta.clone() };
                    self.push_move(m, meta);
                }
            }
            _ => self.push_move(mv, meta),
        }
    }

    /// Once the REPOS motion has arrived, the program's main run takes over again.
    pub(super) fn finish_repos_if_done(&mut self) {
        if self.planner.is_idle() {
            self.resume_interrupted();
        }
    }

    fn resume_interrupted(&mut self) {
        self.repos_returning = false;
        if let Some(int) = self.interrupted.take() {
            let Interrupted { mut planner, in_planner, resume } = *int;
            match resume {
                Resume::AsInterrupted => {}
                Resume::FrontAt(u) => planner.restart_front_at(u),
                Resume::SkipFront => planner.skip_front(),
            }
            self.planner = planner;
            self.in_planner = in_planner;
            self.recompute_speed_caps();
            self.planner.set_overrides(self.overrides.feed, self.overrides.rapid);
        }
        self.planner.set_hold(false);
        self.status = Status::Running;
    }

    /// The slowest JOG velocity of the axes that move from `a` to `b`.
    fn repos_jog_velocity(&self, a: &AxisVec, b: &AxisVec) -> f64 {
        (0..self.cfg.channel_axes.len())
            .filter(|&k| (a[k] - b[k]).abs() > 1e-9)
            .map(|k| self.cfg.axis(k).jog_velocity.min(self.cfg.axis(k).max_velocity))
            .fold(f64::INFINITY, f64::min)
    }

    /// A straight move from `start` to `end` that ends at standstill; the feed refers to the
    /// geometry axes' path (all axes when no geometry axis moves).
    pub(super) fn straight_move(&self, start: AxisVec, end: AxisVec, feed: Feed) -> Move {
        let geo = match &self.trafo {
            Some(t) => t.trafo.geo_slots(),
            None => self.cfg.geo_axes,
        };
        let dist =
            |keys: &mut dyn Iterator<Item = usize>| keys.map(|k| (end[k] - start[k]).powi(2)).sum::<f64>().sqrt();
        let mut length = dist(&mut geo.iter().flatten().copied());
        if length < 1e-9 {
            length = dist(&mut (0..self.cfg.channel_axes.len()));
        }
        Move::new(Path::line(start, end), length, feed, &AxisLimit::for_channel(&self.cfg), true, self.next_tag)
    }
}
