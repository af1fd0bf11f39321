//! The bounds the main run guarantees for the variables a synchronized action's condition
//! reads ([`Bounds`] for the channel), from which `interp/synchronized/horizon.rs` computes how
//! long the condition sleeps.
//!
//! The bounds are generous (correctness first): an axis moves at most [`SAFETY`] times its
//! MD32000 MAX_AX_VELO (or its JOG velocity, if higher) per IPO cycle, whatever the override
//! (the planner, JOG, REPOS and the positioning axes all stop at MAX_AX_VELO; the servo's lag
//! only smooths it), plus the TOFF velocity on the geometry axes. What jumps — power on,
//! restore, PRESETON, a probe's deletion of the distance to go, a new transformation, reset —
//! wakes every condition (`SyncActions::wake_all`). Not bounded at all (evaluated in every
//! cycle): spindles and modulo axes (their angles wrap), every axis under a transformation or
//! while referencing, the overrides, `$R`. `$AA_VACTM` and `$AC_VACTB` have no per-cycle bound
//! (a DELDTG or `$AC_OVR=0` stops the path at once) but a range: at most [`SAFETY`] times the
//! axes' maximum velocity. `$AC_DTEB` and `$AC_PATH` only have their sign (the planner's front
//! move may be shortened by a blend when the next one arrives): a threshold on them is
//! evaluated in every cycle unless it lies below zero. `$AC_TIME` grows by one IPO cycle per
//! cycle and starts again with each block (the block change wakes its readers): it never
//! falls below its value of now.
//!
//! While only the path moves the axes (no JOG, REPOS, positioning or command axis travels,
//! the position loops settled), an axis moves no faster than the moves in the planner allow
//! ([`SpeedCaps`]): the highest path speed of any queued move (its feed under 120 % override,
//! the axes' limit for G0) times the axis' highest rate per path length among them, usually
//! far below MD32000. A move pushed later that raises it touches `MOTION_BIT` (the
//! conditions on positions are evaluated again); so does JOG, REPOS or a positioning axis
//! starting. The product of the two maxima covers a cycle that spans two moves.

use crate::channel::Channel;
use crate::interp::synchronized::flat::{MOTION_BIT, Reader, Slot};
use crate::interp::synchronized::horizon::{Bound, Bounds};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{AxisVec, Move};

/// The speed bound of the moves in the planner (see the module doc): at least the path speed
/// any of them can reach and, per axis, its highest rate per unit path length.
#[derive(Debug, Clone)]
pub struct SpeedCaps {
    speed: f64,
    rate: AxisVec,
    /// Moves pushed since the speed was last computed from the queue alone (it only grows
    /// in between: a fast move that left keeps it high until then). The rates are never
    /// lowered: an axis' rate per path length is at most about 1 on the usual paths, so they
    /// settle soon, and lowering them would wake the conditions each time they grow again.
    pushes: u32,
}

impl Default for SpeedCaps {
    fn default() -> Self {
        SpeedCaps { speed: 0.0, rate: [0.0; MAX_CHANNEL_AXES], pushes: 0 }
    }
}

/// Every this many pushes the speed is computed again from the queue (so it comes down
/// after a rapid move has left): once per look-ahead's length.
const RECOMPUTE_EVERY: u32 = crate::channel::LOOKAHEAD as u32;

impl SpeedCaps {
    /// The most axis `k` moves per second under the bound.
    fn axis(&self, k: usize) -> f64 {
        if self.rate[k] == 0.0 { 0.0 } else { self.speed * self.rate[k] }
    }

    /// Takes `mv` in; true if that raised the bound.
    fn include(&mut self, mv: &Move, axes: usize) -> bool {
        let faster = self.include_speed(mv);
        self.include_rates(mv, axes) || faster
    }

    /// Takes `mv`'s speed in; true if that raised it.
    fn include_speed(&mut self, mv: &Move) -> bool {
        // A length of zero moves no axis.
        let speed = if mv.length > 0.0 { mv.speed_cap() } else { 0.0 };
        let speed = if speed.is_nan() { f64::INFINITY } else { speed };
        let raised = speed > self.speed;
        self.speed = self.speed.max(speed);
        raised
    }

    /// Takes `mv`'s axis rates per path length in; true if one grew.
    fn include_rates(&mut self, mv: &Move, axes: usize) -> bool {
        if mv.length.is_nan() || mv.length <= 0.0 {
            return false;
        }
        let mut raised = false;
        let rates = mv.path.max_rate_of_first(axes);
        for (r, q) in self.rate.iter_mut().zip(&rates[..axes]) {
            let q = q / mv.length;
            let q = if q.is_nan() { f64::INFINITY } else { q };
            if q > *r {
                *r = q;
                raised = true;
            }
        }
        raised
    }
}

/// How many times its maximum velocity an axis is assumed to move at most.
pub const SAFETY: f64 = 4.0;
/// How far below zero `$AC_DTEB`/`$AC_PATH` may round (mm).
const LENGTH_SLACK: f64 = 1e-3;

impl Bounds for Channel {
    fn bound(&self, slot: Slot) -> Option<Bound> {
        let dt = self.cfg.ipo_cycle;
        let value = self.read(slot, 0).ok()?;
        let (lo, hi) = (f64::NEG_INFINITY, f64::INFINITY);
        let (rate, lo, hi) = match slot {
            Slot::AaIm(k) | Slot::AaIpo(k) => (self.axis_step(k)?, lo, hi),
            Slot::AaIw(k) => (self.workpiece_step(k)?, lo, hi),
            Slot::AaVactm(k) => {
                let v = self.axis_step(k)? / dt * 60.0;
                (hi, -v, v)
            }
            Slot::AcVactb => {
                let v = self.path_speed_bound()? * 60.0;
                (hi, -v, v)
            }
            // It only grows until the block changes (which wakes its readers): a condition
            // that has flipped stays so, instead of being looked at again and again.
            Slot::AcTime => (dt, value, hi),
            Slot::AcPath | Slot::AcDteb => (hi, -LENGTH_SLACK, hi),
            Slot::Timer(_)
            | Slot::Marker(_)
            | Slot::Param(_)
            | Slot::AIn(_)
            | Slot::AOut(_)
            | Slot::AIna(_)
            | Slot::AOuta(_)
            | Slot::AcDelt => return Some(Bound::fixed(value)),
            Slot::AaOvr(_) | Slot::AcOvr | Slot::R(_) => return None,
        };
        (!rate.is_nan()).then_some(Bound { value, rate, lo, hi })
    }
}

impl Channel {
    /// After a move went into the planner (while actions are active): the bound takes it in,
    /// and wakes the conditions on positions when it grew.
    pub(in crate::channel) fn note_pushed_move(&mut self) {
        let axes = self.cfg.channel_axes.len();
        let caps = &mut self.sync.speed_caps;
        caps.pushes += 1;
        if caps.pushes >= RECOMPUTE_EVERY {
            self.recompute_speed_caps();
            return;
        }
        if let Some(mv) = self.planner.queued().last()
            && caps.include(mv, axes)
        {
            self.sync.touch(1 << MOTION_BIT);
        }
    }

    /// The speed computed from the moves queued now (when actions become active, after
    /// REPOS, every [`RECOMPUTE_EVERY`] pushes), the rates grown by theirs; wakes the
    /// conditions on positions when either grew.
    pub(in crate::channel) fn recompute_speed_caps(&mut self) {
        let axes = self.cfg.channel_axes.len();
        let caps = &mut self.sync.speed_caps;
        let old = caps.speed;
        (caps.speed, caps.pushes) = (0.0, 0);
        let mut grew = false;
        for mv in self.planner.queued() {
            caps.include_speed(mv);
            grew |= caps.include_rates(mv, axes);
        }
        if grew || caps.speed > old {
            self.sync.touch(1 << MOTION_BIT);
        }
    }

    /// JOG, REPOS or a positioning axis starts: the conditions on positions are evaluated
    /// again (their horizons counted on the path alone).
    pub(in crate::channel) fn wake_motion_readers(&mut self) {
        self.sync.touch(1 << MOTION_BIT);
    }

    /// Only the path moves the axes, with no following error: [`SpeedCaps`] bound them.
    fn only_the_path_moves(&self) -> bool {
        self.jog.is_none() && !self.repos_returning && !self.positioning.moving(u32::MAX) && self.servo.is_settled()
    }

    /// The most machine axis `k` moves in one IPO cycle, if bounded now.
    fn axis_step(&self, k: usize) -> Option<f64> {
        if k >= self.cfg.channel_axes.len() || self.trafo.is_some() || self.referencing.is_some() {
            return None;
        }
        let ax = self.cfg.axis(k);
        if ax.spindle.is_some() || ax.modulo.is_some() {
            return None;
        }
        let mut v = fastest(ax);
        if self.only_the_path_moves() {
            v = v.min(self.sync.speed_caps.axis(k));
        }
        if self.cfg.geo_axes.contains(&Some(k)) {
            v += self.cfg.ori.toff_velocity;
        }
        let step = SAFETY * v * self.cfg.ipo_cycle;
        (step.is_finite() && step >= 0.0).then_some(step)
    }

    /// The most `$AA_IW[k]` changes in one IPO cycle: through the frame's inverse from the
    /// axes' steps (the offsets stay: their change wakes the conditions).
    fn workpiece_step(&self, k: usize) -> Option<f64> {
        let inv = self.sync.frame_inverse.as_ref().and_then(|(_, inv)| inv.as_ref())?;
        let geo = &self.cfg.geo_axes;
        match geo.iter().position(|a| *a == Some(k)) {
            Some(g) => {
                let mut step = 0.0;
                for (j, axis) in geo.iter().enumerate() {
                    if let Some(i) = axis {
                        step += inv[g][j].abs() * self.axis_step(*i)?;
                    }
                }
                Some(step)
            }
            None => {
                let factor = self.offsets.frame.factor[k].abs();
                (factor > 0.0).then(|| self.axis_step(k).map(|s| s / factor)).flatten()
            }
        }
    }

    /// The most the path velocity can be (mm/s): [`SAFETY`] times √n times the fastest axis
    /// (a path of n axes moves one of them at least 1/√n of its speed); spindles with axis
    /// function count with their axis velocity (one in axis mode may be a path axis), those
    /// without none.
    fn path_speed_bound(&self) -> Option<f64> {
        if self.trafo.is_some() || self.referencing.is_some() {
            return None;
        }
        let axes = (0..self.cfg.channel_axes.len()).map(|k| self.cfg.axis(k)).filter(|ax| !ax.spindle_only);
        let (n, v) = axes.fold((0, 0.0f64), |(n, v), ax| (n + 1, v.max(fastest(ax))));
        let v = SAFETY * (v + self.cfg.ori.toff_velocity) * f64::from(n).sqrt();
        v.is_finite().then_some(v)
    }
}

/// The fastest an axis moves in any mode: MD32000, the JOG velocities (JOG and REPOS stop at
/// MD32000 too; taken for generosity).
fn fastest(ax: &crate::machine_data::MachineAxis) -> f64 {
    ax.max_velocity.max(ax.jog_velocity).max(ax.jog_rapid_velocity)
}
