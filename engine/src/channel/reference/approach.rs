//! The reference point approach of an axis with an incremental measuring system (JOG REF).
//!
//! Machine data (real numbers and names; MD34200 = 1, the control's default, selects the
//! approach with reference cam and zero mark; 0 = no approach, the axis counts as referenced at
//! once; MD34210 ENC_REFP_STATE = 2, an adjusted absolute encoder, is referenced from power on):
//! - phase 1, cam search: the axis travels in the direction of MD34010 REFP_CAM_DIR_IS_MINUS at
//!   MD34020 REFP_VELO_SEARCH_CAM until it reaches the reference cam, then brakes;
//! - phase 2, zero mark search: it travels at MD34040 REFP_VELO_SEARCH_MARKER to the first zero
//!   mark after the cam;
//! - phase 3, reference point: it travels MD34080 REFP_MOVE_DIST + MD34090 REFP_MOVE_DIST_CORR
//!   (signed, in axis coordinates) at MD34070 REFP_VELO_POS and takes MD34100 REFP_SET_POS[0] as
//!   its position there: the axis is referenced.
//!
//! Simulation rule (the simulated encoder already counts in machine coordinates, so the
//! reference point lies where the data put it): the reference point is at REFP_SET_POS[0], the
//! zero mark at REFP_SET_POS[0] − (REFP_MOVE_DIST + REFP_MOVE_DIST_CORR), and the cam edge
//! MD34093 REFP_CAM_MARKER_DIST before the zero mark in the approach direction (on the control a
//! measured display value; here the cam's position). An axis already past the cam edge starts
//! with the zero mark search. The velocities act with the feed override. NC stop brakes and
//! aborts the approach (the axis stays unreferenced); reset aborts it at once. With
//! `reference_axes(None)` the axes that need an approach follow one another in the order of
//! MD34110 REFP_CYCLE_NR (then channel order), as the channel-specific referencing does.

use crate::channel::{Channel, MoveMeta, Status};
use crate::motion::{AxisLimit, Feed, Move, Path};

/// The phase of a reference point approach.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferencePhase {
    /// Travelling to the reference cam (and braking on it).
    Cam,
    /// Travelling to the zero mark.
    Marker,
    /// Travelling from the zero mark to the reference point.
    Position,
}

impl ReferencePhase {
    pub fn as_str(self) -> &'static str {
        match self {
            ReferencePhase::Cam => "cam",
            ReferencePhase::Marker => "marker",
            ReferencePhase::Position => "position",
        }
    }
}

/// Where the cam, zero mark and reference point of an axis are, and the approach velocities
/// (units per second).
#[derive(Debug, Clone, Copy)]
struct Plan {
    dir: f64,
    cam: f64,
    marker: f64,
    reference: f64,
    v_cam: f64,
    v_marker: f64,
    v_pos: f64,
}

/// A reference point approach in progress.
#[derive(Debug, Clone)]
pub(in crate::channel) struct Referencing {
    axis: usize,
    phase: ReferencePhase,
    plan: Plan,
    /// Braking on the cam (phase 1) or after NC stop.
    braking: bool,
    aborted: bool,
    /// The moves are in machine axes while a transformation is active.
    machine_space: bool,
    /// Axes to reference after this one.
    queue: Vec<usize>,
}

impl Channel {
    /// True when channel axis `k` is referenced by an approach motion (MD34200 = 1, no
    /// adjusted absolute encoder, not a spindle).
    pub(in crate::channel) fn needs_approach(&self, k: usize) -> bool {
        let m = self.cfg.channel_axes[k].machine_axis;
        self.cfg.axis(k).spindle.is_none()
            && self.data.num("$MA_ENC_REFP_MODE", m, 0) == 1.0
            && self.data.num("$MA_ENC_REFP_STATE", m, 0) != 2.0
    }

    /// Starts the approach of the first of `axes`; the others follow.
    pub(in crate::channel) fn start_referencing(&mut self, mut axes: Vec<usize>) {
        if axes.is_empty() {
            return;
        }
        let axis = axes.remove(0);
        let plan = self.reference_plan(axis);
        let machine_space = self.trafo.is_some();
        if machine_space {
            self.planner.set_position(self.machine);
        }
        self.sync.wake_all();
        self.referencing = Some(Referencing {
            axis,
            phase: ReferencePhase::Cam,
            plan,
            braking: false,
            aborted: false,
            machine_space,
            queue: axes,
        });
        self.status = Status::Running;
        let pos = self.machine[axis];
        if plan.dir * (pos - plan.cam) >= 0.0 {
            // Already on the cam: the zero mark search starts at once.
            self.enter_reference_phase(ReferencePhase::Marker);
        } else {
            // Far enough past the cam to brake on it before the move ends.
            let beyond = plan.cam + plan.dir * (2.0 * plan.v_cam * plan.v_cam / self.cfg.axis(axis).max_accel + 1.0);
            self.push_reference_move(beyond, plan.v_cam);
        }
    }

    /// The cam, zero mark and reference point of channel axis `k` (see the module doc).
    fn reference_plan(&self, k: usize) -> Plan {
        let m = self.cfg.channel_axes[k].machine_axis;
        let num = |name: &str| self.data.num(name, m, 0);
        let velo = if self.cfg.axis(k).rotary { 360.0 / 60.0 } else { 1.0 / 60.0 };
        let dir = if num("$MA_REFP_CAM_DIR_IS_MINUS") != 0.0 { -1.0 } else { 1.0 };
        let reference = num("$MA_REFP_SET_POS");
        let marker = reference - (num("$MA_REFP_MOVE_DIST") + num("$MA_REFP_MOVE_DIST_CORR"));
        Plan {
            dir,
            cam: marker - dir * num("$MA_REFP_CAM_MARKER_DIST"),
            marker,
            reference,
            v_cam: num("$MA_REFP_VELO_SEARCH_CAM") * velo,
            v_marker: num("$MA_REFP_VELO_SEARCH_MARKER") * velo,
            v_pos: num("$MA_REFP_VELO_POS") * velo,
        }
    }

    /// Queues a move of the referencing axis alone to `to` at `velocity`.
    fn push_reference_move(&mut self, to: f64, velocity: f64) {
        let Some(r) = &self.referencing else { return };
        let (axis, machine_space) = (r.axis, r.machine_space);
        let start = *self.planner.position();
        let mut end = start;
        end[axis] = to;
        let length = (to - start[axis]).abs();
        let mut mv = Move::new(
            Path::line(start, end),
            length,
            Feed::Path(velocity.max(1e-6)),
            &AxisLimit::for_channel(&self.cfg),
            true,
            self.next_tag,
        );
        mv.machine_space = machine_space;
        self.push_move(
            mv,
            MoveMeta {
                line: 0,
                seq: crate::channel::pending::NO_SEQ,
                offsets: self.offsets.clone(),
                machine_space,
                feed: 0.0,
            },
        );
    }

    fn enter_reference_phase(&mut self, phase: ReferencePhase) {
        let Some(r) = &mut self.referencing else { return };
        r.phase = phase;
        r.braking = false;
        let plan = r.plan;
        match phase {
            ReferencePhase::Cam => {}
            ReferencePhase::Marker => self.push_reference_move(plan.marker, plan.v_marker),
            ReferencePhase::Position => self.push_reference_move(plan.reference, plan.v_pos),
        }
    }

    /// One IPO cycle of the approach: the cam signal, phase changes, the end.
    pub(in crate::channel) fn step_referencing(&mut self) {
        let Some(r) = &mut self.referencing else { return };
        let pos = self.machine[r.axis];
        if r.phase == ReferencePhase::Cam && !r.braking && !r.aborted && r.plan.dir * (pos - r.plan.cam) >= 0.0 {
            // The cam signal: brake to standstill.
            r.braking = true;
            self.planner.stop_and_flush();
            return;
        }
        if !self.planner.is_idle() {
            return;
        }
        let (phase, aborted, axis) = (r.phase, r.aborted, r.axis);
        match phase {
            _ if aborted => self.finish_referencing(),
            ReferencePhase::Cam => {
                self.planner.set_hold(false);
                self.enter_reference_phase(ReferencePhase::Marker);
            }
            ReferencePhase::Marker => self.enter_reference_phase(ReferencePhase::Position),
            ReferencePhase::Position => {
                self.referenced[axis] = true;
                let queue = self.referencing.as_mut().map(|r| std::mem::take(&mut r.queue)).unwrap_or_default();
                if queue.is_empty() {
                    self.finish_referencing();
                } else {
                    self.referencing = None;
                    self.start_referencing(queue);
                }
            }
        }
    }

    /// NC stop: the axis brakes and the approach ends unreferenced.
    pub(in crate::channel) fn abort_referencing(&mut self) {
        if let Some(r) = &mut self.referencing {
            r.aborted = true;
            self.planner.stop_and_flush();
        }
    }

    fn finish_referencing(&mut self) {
        let machine_space = self.referencing.take().is_some_and(|r| r.machine_space);
        self.planner.set_hold(false);
        if machine_space && let Some(t) = &self.trafo {
            let bcs = t.forward(&self.machine);
            self.planner.set_position(bcs);
        }
        match &self.trafo {
            Some(_) => self.interp.sync_transformation(&self.machine),
            None => self.interp.sync_position(self.planner.position()),
        }
        self.status = Status::Idle;
    }

    /// The axis being referenced and the phase of its approach.
    pub fn referencing(&self) -> Option<(String, ReferencePhase)> {
        self.referencing.as_ref().map(|r| (self.cfg.axis(r.axis).name.clone(), r.phase))
    }
}
