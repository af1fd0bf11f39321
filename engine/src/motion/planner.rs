//! The main run: a queue of prepared moves, a look-ahead over it, and one IPO step at a time.
//!
//! The path velocity is advanced once per IPO cycle: it rises by at most `a·dt`, never exceeds
//! the block's limit, and never exceeds the speed from which the remaining queue can still be
//! braked to its planned transition speeds. The result is a trapezoidal (BRISK) profile that
//! is exact to one cycle and never violates a limit, however the queue changes.

use std::collections::VecDeque;

use super::front::FrontMove;
use super::orientation::Vec3;
use super::path::{AxisVec, Path};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

#[path = "soft.rs"]
mod soft;
#[path = "soft_curvature.rs"]
mod soft_curvature;

/// Velocity requested for a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// G0: every axis at its own maximum, interpolated together.
    Rapid,
    /// Path feed in units per second.
    Path(f64),
}

/// Per-axis dynamics the planner respects (engine units per second).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisLimit {
    pub max_velocity: f64,
    pub max_accel: f64,
    /// Factor by which the acceleration may be exceeded for one cycle at a block transition.
    pub accel_overload: f64,
}

impl AxisLimit {
    /// The limits of every channel axis, from the machine axis behind it. A fixed array on the
    /// stack: block preparation asks for them several times per block and must not allocate.
    pub fn for_channel(cfg: &MachineConfig) -> AxisLimits {
        let mut out = AxisLimits { limits: [AxisLimit::NONE; MAX_CHANNEL_AXES], len: 0 };
        for k in 0..cfg.channel_axes.len().min(MAX_CHANNEL_AXES) {
            let a = cfg.axis(k);
            out.limits[k] =
                AxisLimit { max_velocity: a.max_velocity, max_accel: a.max_accel, accel_overload: a.accel_overload };
            out.len = k + 1;
        }
        out
    }

    /// Placeholder for unused slots of [`AxisLimits`].
    const NONE: AxisLimit = AxisLimit { max_velocity: 0.0, max_accel: 0.0, accel_overload: 1.0 };
}

/// The limits of a channel's axes without a heap allocation; derefs to `[AxisLimit]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisLimits {
    limits: [AxisLimit; MAX_CHANNEL_AXES],
    len: usize,
}

impl std::ops::Deref for AxisLimits {
    type Target = [AxisLimit];
    fn deref(&self) -> &[AxisLimit] {
        &self.limits[..self.len]
    }
}

impl From<&[AxisLimit]> for AxisLimits {
    /// The first [`MAX_CHANNEL_AXES`] limits of the slice.
    fn from(limits: &[AxisLimit]) -> AxisLimits {
        let mut out =
            AxisLimits { limits: [AxisLimit::NONE; MAX_CHANNEL_AXES], len: limits.len().min(MAX_CHANNEL_AXES) };
        out.limits[..out.len].copy_from_slice(&limits[..out.len]);
        out
    }
}

impl From<Vec<AxisLimit>> for AxisLimits {
    fn from(limits: Vec<AxisLimit>) -> AxisLimits {
        AxisLimits::from(limits.as_slice())
    }
}

/// One prepared block ready for the main run.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    pub path: Path,
    /// Path length in the units the feed refers to.
    pub length: f64,
    /// Highest path velocity allowed by feed and axes.
    pub v_max: f64,
    /// Highest path velocity the axes allow (what an override above 100 % may reach).
    pub v_axes: f64,
    /// The programmed path feed; infinite for rapid traverse.
    pub feed: f64,
    /// Highest path acceleration allowed by the axes.
    pub a_max: f64,
    /// Stop exactly at the end (G60/G9, or the next item is not a move).
    pub exact_stop: bool,
    /// Caller's identifier (the block the move belongs to).
    pub tag: u32,
    /// The path is in machine axes although a kinematic transformation is active (a positioning
    /// motion such as the rotation in the TRANSMIT pole). The planner ignores it; the caller
    /// uses it to map samples to machine positions.
    pub machine_space: bool,
    /// Rates of the machine axes per unit path length `dm/ds` at the start and at the end of
    /// the move, when the path is not in machine axes. Used for the velocity jump at block
    /// transitions instead of the path's own tangent.
    pub axis_tangents: Option<Box<(AxisVec, AxisVec)>>,
    /// Feed per revolution of the master spindle (G95, G96, G33) in path length per
    /// revolution; 0 for a feed per time. The path speed then follows the spindle's actual
    /// speed each cycle ([`Planner::set_spindle_rate`]); `feed` is only the look-ahead's bound.
    pub per_rev: f64,
    /// Highest path jerk under SOFT (units per s³); infinite under BRISK, the
    /// acceleration-limited profile (see `motion/soft.rs`).
    pub jerk: f64,
    /// Under SOFT, the jerk the axes may see where the curvature jumps at this move's ends
    /// (MD32431, or MD32432 above it); infinite under BRISK (see `motion/soft_curvature.rs`).
    pub seam_jerk: f64,
    /// Continuous-path rounding at the end of this move (G641..G645), from the block's modal
    /// state; the channel inserts the rounding element when the next move is known.
    pub blend: Option<super::blend::Blend>,
    /// The compressor (COMPON, COMPCAD ...) is on for this move's block: its limits.
    pub compress: Option<super::compress::Compress>,
    /// ORISON is on for this move's block (under an orientation transformation the channel
    /// smooths the orientation across its ends, `motion/orison.rs`): its limits (boxed: a
    /// move is copied often, and most moves have none).
    pub orison: Option<Box<super::orison::OriSmoothing>>,
    /// Under DRIVE with a reducing axis: the speed-dependent acceleration (`motion/drive.rs`);
    /// `a_max` is then its lowest value, the one the look-ahead plans with.
    pub drive: Option<Box<super::drive::DriveCurve>>,
}

impl Move {
    /// Builds a move, deriving its velocity and acceleration limits from the axes.
    /// `length` is the path length the feed refers to (geometry axes, or all axes if none moves).
    pub fn new(path: Path, length: f64, feed: Feed, limits: &[AxisLimit], exact_stop: bool, tag: u32) -> Move {
        let mut mv = Move::unlimited(path, exact_stop, tag);
        mv.set_limits(length, feed, limits);
        mv
    }

    /// A move along `path` without limits yet, for a caller that builds it in its place (a move
    /// is ≈ 400 bytes, and each pass by value copies it) and then calls [`Move::set_limits`].
    pub fn unlimited(path: Path, exact_stop: bool, tag: u32) -> Move {
        Move {
            path,
            length: 0.0,
            v_max: f64::INFINITY,
            v_axes: f64::INFINITY,
            feed: f64::INFINITY,
            a_max: f64::INFINITY,
            exact_stop,
            tag,
            machine_space: false,
            axis_tangents: None,
            per_rev: 0.0,
            jerk: f64::INFINITY,
            seam_jerk: f64::INFINITY,
            blend: None,
            compress: None,
            orison: None,
            drive: None,
        }
    }

    /// Sets the path length the feed refers to, the feed and the velocity and acceleration
    /// limits the axes allow along the path (see [`Move::new`]).
    pub fn set_limits(&mut self, length: f64, feed: Feed, limits: &[AxisLimit]) {
        let path = &self.path;
        // A line's rate per axis is its span, read in the loop (no array built and copied).
        let rate = (path.arc.is_some() || path.curve.is_some()).then(|| path.max_rate_of_first(limits.len()));
        let feed = match feed {
            Feed::Rapid => f64::INFINITY,
            Feed::Path(f) => f,
        };
        let mut v_max = f64::INFINITY;
        let mut a_max = f64::INFINITY;
        for (i, lim) in limits.iter().enumerate() {
            let rate_i = rate.as_ref().map_or_else(|| (path.end[i] - path.start[i]).abs(), |r| r[i]);
            let d = rate_i / length;
            if d > 1e-12 {
                v_max = v_max.min(lim.max_velocity / d);
                a_max = a_max.min(lim.max_accel / d);
            }
        }
        if let Some(arc) = &path.arc {
            // Half of the plane axes' acceleration goes to the centripetal part, half to the
            // tangential part, so their sum never exceeds either axis' limit.
            let k = arc.radius * arc.sweep.abs() / length;
            let a_plane = limits
                .iter()
                .enumerate()
                .filter(|(i, _)| arc.moves_axis(*i))
                .map(|(_, l)| l.max_accel)
                .fold(f64::INFINITY, f64::min);
            if k > 1e-12 {
                v_max = v_max.min((0.5 * a_plane * arc.radius).sqrt() / k);
                a_max = a_max.min(0.5 * a_plane / k);
            }
        }
        if let Some(curve) = &path.curve {
            (v_max, a_max) = super::blend::curve_limits(curve, limits, v_max, a_max);
        }
        self.length = length;
        self.v_max = v_max.min(feed);
        self.v_axes = v_max;
        self.feed = feed;
        self.a_max = a_max;
    }

    /// True for rapid traverse (G0).
    pub fn is_rapid(&self) -> bool {
        self.feed.is_infinite()
    }

    /// The fastest path speed the planner can give this move (units/s): its feed under the
    /// highest feed override the planner takes (120 %), at most the axes' limit along it;
    /// that limit for rapid traverse (its override stops at 100 %) and a feed per revolution.
    pub fn speed_cap(&self) -> f64 {
        if self.is_rapid() || self.per_rev > 0.0 {
            self.v_axes
        } else {
            (self.feed * MAX_FEED_OVERRIDE).min(self.v_axes)
        }
    }

    /// The velocity cap under the overrides: the feed override scales the programmed feed (up to
    /// the axes' limit), the rapid override scales rapid traverse.
    fn capped(&self, feed_override: f64, rapid_override: f64, spindle_rate: f64) -> f64 {
        if self.is_rapid() {
            self.v_axes * rapid_override.min(1.0)
        } else if self.per_rev > 0.0 {
            (self.per_rev * spindle_rate * feed_override).min(self.v_axes)
        } else {
            (self.feed * feed_override).min(self.v_axes)
        }
    }
}

/// The highest feed override the planner applies (a factor).
pub const MAX_FEED_OVERRIDE: f64 = 1.2;

/// Where the planner is in the cycle at rest after a stop (see [`Planner::step`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rest {
    /// Moving, or at rest for long enough.
    None,
    /// The last cycle ended in a stop: the next cycle stands.
    Due,
    /// This cycle stood.
    Now,
}

/// The move queue and its interpolator state.
#[derive(Debug, Clone)]
pub struct Planner {
    dt: f64,
    /// The cycles in which the path moved at feed (not rapid traverse), since the planner was
    /// made: the channel's cutting time (`$AC_CUTTING_TIME`) is read off it.
    feed_cycles: u64,
    limits: AxisLimits,
    queue: VecDeque<Move>,
    /// The smallest acceleration of the queued moves (kept up to date on push and pop, so the
    /// per-cycle braking check does not scan the queue).
    a_min: f64,
    /// The smallest path jerk of the queued moves, kept like `a_min` (SOFT's look-ahead horizon).
    j_min: f64,
    /// Planned velocity at the end of each queued move.
    v_end: VecDeque<f64>,
    /// The corner speed at the end of each queued move but the last ([`Planner::corner_speed`]):
    /// it depends on that move, the next and the limits only, so a push computes one.
    corner: VecDeque<f64>,
    /// The limits changed: the next replan recomputes every corner and end velocity.
    replan_all: bool,
    /// Distance travelled within the front move.
    s: f64,
    /// Current path velocity.
    v: f64,
    /// Path acceleration of the last cycle: the state of SOFT's jerk-limited profile.
    acc: f64,
    /// SOFT crossed a corner (the axis rates jump) in the last cycle, or entered or left a
    /// rounding curve: this many next cycles keep the path acceleration from rising
    /// ([`Planner::soft_velocity`]).
    kinked: u8,
    /// Feed hold: brake to standstill on the path.
    hold: bool,
    /// The cycle at rest after a stop: the cycle that lands on a move's end point still moved
    /// the axes (by up to `a·dt²`, see [`stop_speed`]); an exact stop means the axes are at rest
    /// before the next move starts, and a move that reversed an axis in the very next cycle
    /// stepped it by up to `2·a·dt`.
    rest: Rest,
    /// Feed override and rapid traverse override as factors (1.0 = 100 %).
    feed_override: f64,
    rapid_override: f64,
    /// Actual speed of the master spindle in rev/s (for moves with a feed per revolution).
    spindle_rate: f64,
    /// Drop the queue once standstill is reached under hold (JOG key released).
    flush_at_standstill: bool,
    position: AxisVec,
    /// Tag of the move whose path produced `position` (`None` after [`Planner::set_position`]).
    position_tag: Option<u32>,
    /// Tool orientation at `position` when that move interpolates it as a vector.
    orientation: Option<Vec3>,
    finished: Vec<u32>,
    /// What every cycle of the front move needs (its moving axes, the arc's constants, the
    /// stepped angles): built on its first cycle, dropped whenever the front changes.
    front_move: Option<FrontMove>,
}

impl Planner {
    pub fn new(dt: f64, limits: impl Into<AxisLimits>, position: AxisVec) -> Planner {
        Planner {
            dt,
            feed_cycles: 0,
            limits: limits.into(),
            queue: VecDeque::new(),
            a_min: f64::INFINITY,
            j_min: f64::INFINITY,
            v_end: VecDeque::new(),
            corner: VecDeque::new(),
            replan_all: false,
            s: 0.0,
            v: 0.0,
            acc: 0.0,
            kinked: 0,
            hold: false,
            rest: Rest::None,
            feed_override: 1.0,
            rapid_override: 1.0,
            spindle_rate: 0.0,
            flush_at_standstill: false,
            position,
            position_tag: None,
            orientation: None,
            finished: Vec::new(),
            front_move: None,
        }
    }

    /// Appends a move and replans the look-ahead. Zero-length moves are finished at once.
    pub fn push(&mut self, mv: Move) {
        if mv.length <= 1e-9 {
            self.finished.push(mv.tag);
            return;
        }
        self.a_min = self.a_min.min(mv.a_max);
        self.j_min = self.j_min.min(mv.jerk);
        if self.queue.is_empty() {
            self.front_move = None;
        }
        self.queue.push_back(mv);
        self.v_end.push_back(0.0);
        self.corner.push_back(0.0);
        let n = self.queue.len();
        if self.replan_all {
            for k in 0..n - 1 {
                self.corner[k] = self.corner_speed(k);
            }
        } else if n > 1 {
            self.corner[n - 2] = self.corner_speed(n - 2);
        }
        self.replan();
    }

    /// Replaces the axis limits (new machine data); queued moves keep the limits they were
    /// planned with.
    pub fn set_limits(&mut self, limits: impl Into<AxisLimits>) {
        self.limits = limits.into();
        self.replan_all = true;
    }

    /// Number of queued moves.
    pub fn len(&self) -> usize {
        self.queue.len()
    }

    /// The cycles in which the path moved at feed since the planner was made.
    pub fn feed_cycles(&self) -> u64 {
        self.feed_cycles
    }

    pub fn is_empty(&self) -> bool {
        self.queue.is_empty()
    }

    /// True when nothing moves and nothing is queued.
    pub fn is_idle(&self) -> bool {
        self.queue.is_empty() && self.v == 0.0
    }

    /// Current interpolated position of every axis.
    pub fn position(&self) -> &AxisVec {
        &self.position
    }

    /// Tool orientation at the current position, when its move interpolates the orientation
    /// as a vector (the rotary axes are then derived from it).
    pub fn orientation(&self) -> Option<&Vec3> {
        self.orientation.as_ref()
    }

    /// Tag of the move the current position lies on (the last one finished when idle).
    pub fn position_tag(&self) -> Option<u32> {
        self.position_tag
    }

    /// Current path velocity.
    pub fn velocity(&self) -> f64 {
        self.v
    }

    /// The moves queued now, the front one first.
    pub fn queued(&self) -> impl Iterator<Item = &Move> {
        self.queue.iter()
    }

    /// For the display: the path length still to go of the block being executed (the moves of
    /// its tag) and its programmed feed (infinite for rapid traverse); `None` when nothing is
    /// queued.
    pub fn block_to_go(&self) -> Option<(f64, f64)> {
        let front = self.queue.front()?;
        let rest: f64 = self.queue.iter().skip(1).take_while(|m| m.tag == front.tag).map(|m| m.length).sum();
        Some(((front.length - self.s).max(0.0) + rest, front.feed))
    }

    /// Tag of the move being executed.
    pub fn current_tag(&self) -> Option<u32> {
        self.queue.front().map(|m| m.tag)
    }

    /// True when a move finished since the last [`Planner::take_finished`].
    #[inline]
    pub fn has_finished(&self) -> bool {
        !self.finished.is_empty()
    }

    /// Tags of moves finished since the last call.
    pub fn take_finished(&mut self) -> Vec<u32> {
        std::mem::take(&mut self.finished)
    }

    /// Feed override and rapid traverse override in percent (0..=120; rapid above 100 acts as 100).
    pub fn set_overrides(&mut self, feed_percent: f64, rapid_percent: f64) {
        self.feed_override = feed_percent.clamp(0.0, 100.0 * MAX_FEED_OVERRIDE) / 100.0;
        self.rapid_override = rapid_percent.clamp(0.0, 120.0) / 100.0;
    }

    /// The master spindle's actual speed in rev/s (unsigned), which moves with a feed per
    /// revolution follow (see [`Move::per_rev`]); set by the channel every IPO cycle.
    pub fn set_spindle_rate(&mut self, rev_per_s: f64) {
        self.spindle_rate = rev_per_s;
    }

    /// Feed hold on/off (NC stop / NC start). The path is kept.
    pub fn set_hold(&mut self, hold: bool) {
        self.hold = hold;
        if !hold {
            self.flush_at_standstill = false;
        }
    }

    pub fn is_held(&self) -> bool {
        self.hold
    }

    /// Brakes to standstill on the path, then drops every queued move.
    pub fn stop_and_flush(&mut self) {
        self.hold = true;
        self.flush_at_standstill = true;
    }

    /// Drops everything at once (reset): the axes stay where they are.
    pub fn abort(&mut self) {
        self.queue.clear();
        self.front_move = None;
        self.a_min = f64::INFINITY;
        self.j_min = f64::INFINITY;
        self.v_end.clear();
        self.corner.clear();
        self.s = 0.0;
        self.v = 0.0;
        self.acc = 0.0;
        self.kinked = 0;
        self.hold = false;
        self.rest = Rest::None;
        self.flush_at_standstill = false;
    }

    /// The caller let a cycle pass without [`Planner::step`] (the wait for an exact-stop
    /// window): the axes stood in it, which is the stop's cycle at rest.
    #[inline]
    pub fn stood(&mut self) {
        self.rest = Rest::None;
    }

    /// True in the cycle at rest after a stop (the axes stand although the next move is the
    /// front one: a tool's cutting time does not count it).
    pub fn is_resting(&self) -> bool {
        self.rest == Rest::Now
    }

    /// Sets the position of a stationary machine (after reset or a configuration change).
    pub fn set_position(&mut self, position: AxisVec) {
        debug_assert!(self.queue.is_empty());
        self.position = position;
        self.position_tag = None;
        self.orientation = None;
    }

    /// Puts axis `k` at `v` without a move: a positioning axis that travelled outside the
    /// path has arrived there (`channel/positioning_axes.rs`); the queued moves do not move it.
    pub fn place_axis(&mut self, k: usize, v: f64) {
        self.position[k] = v;
    }

    /// The move being executed (or next to execute), if any.
    pub fn front(&self) -> Option<&Move> {
        self.queue.front()
    }

    /// How far along the front move the interpolation is, as a fraction of its length.
    pub fn front_fraction(&self) -> f64 {
        self.queue.front().map_or(0.0, |m| self.s / m.length)
    }

    /// Puts the interpolation point of a stationary planner at fraction `u` (0..=1) of the front
    /// move, so the rest of the move is travelled from there (REPOS RMB, RMN).
    pub fn restart_front_at(&mut self, u: f64) {
        debug_assert!(self.v == 0.0);
        let Some(front) = self.queue.front() else { return };
        let u = u.clamp(0.0, 1.0);
        self.s = u * front.length;
        front.path.at(u, &mut self.position);
        self.orientation = front.path.orientation_at(u);
        self.position_tag = Some(front.tag);
    }

    /// Drops the front move of a stationary planner as if it had been travelled: the position is
    /// its end and its tag is reported finished (REPOS RME).
    pub fn skip_front(&mut self) {
        debug_assert!(self.v == 0.0);
        let Some(done) = self.queue.pop_front() else { return };
        self.v_end.pop_front();
        self.corner.pop_front();
        self.front_move = None;
        self.rescan_minima();
        self.position = done.path.end;
        self.orientation = done.path.orientation_at(1.0);
        self.position_tag = Some(done.tag);
        self.s = 0.0;
        self.finished.push(done.tag);
    }

    /// Advances one IPO cycle.
    ///
    /// The front move's scalars (length, deceleration, planned end speed) are read from the
    /// queues once per cycle and handed to the brake limit, and the usual cycle, which stays
    /// within the front move, leaves without the loop over move ends.
    pub fn step(&mut self) {
        let dt = self.dt;
        if self.rest != Rest::None && self.rest_after_stop() {
            return;
        }
        let Some(front) = self.queue.front() else {
            self.v = 0.0;
            return;
        };
        let many = self.queue.len() > 1;
        let (a, length) = (front.a_max, front.length);
        let at_feed = !front.is_rapid();
        let soft = front.jerk.is_finite();
        let cap = front.capped(self.feed_override, self.rapid_override, self.spindle_rate);
        let v_end = self.v_end[0];
        let remaining = length - self.s;
        // Above the cap (override lowered) the path brakes at the axes' deceleration.
        let mut v_new = if soft {
            self.soft_velocity(cap)
        } else {
            if let Some(curve) = front.drive.as_deref() {
                self.drive_velocity(curve, cap, remaining, v_end, many)
            } else {
                let v_new = if self.hold {
                    (self.v - a * dt).max(0.0)
                } else if self.v > cap {
                    (self.v - a * dt).max(cap)
                } else {
                    (self.v + a * dt).min(cap)
                };
                if self.acc != 0.0 {
                    // SOFT's state: a later SOFT move starts from constant velocity.
                    self.acc = 0.0;
                }
                self.brake_limited_at(v_new, remaining, a, v_end, many, 0.0)
            }
        };
        // A cycle that crosses into the next move crosses at no more than the planned
        // transition speed, so the corner's velocity jump stays as planned.
        if many && v_new * dt >= remaining && v_new > v_end {
            v_new = v_end.max(self.v - a * dt).max(remaining / dt).min(v_new);
        }
        self.v = v_new;
        self.feed_cycles += u64::from(at_feed && v_new > 0.0);
        if v_new == 0.0 && self.hold {
            if self.flush_at_standstill {
                self.abort();
            }
            return;
        }
        let d = v_new * dt;
        if d < remaining - 1e-12 {
            self.s += d;
            let u = self.s / length;
            self.interpolate_front(u);
            return;
        }
        self.cross_ends(d);
    }

    /// The position at fraction `u` of the front move (which ends after this cycle). A move
    /// without an orientation path, once its [`FrontMove`] is built, needs nothing of the
    /// queue: its cycles do not look the move up again.
    #[inline(always)]
    fn interpolate_front(&mut self, u: f64) {
        if let Some(cycles) = &mut self.front_move
            && !cycles.oriented
        {
            cycles.position(u, &mut self.position);
            self.position_tag = Some(cycles.tag);
            return;
        }
        self.interpolate_front_slow(u);
    }

    /// [`Planner::interpolate_front`] on the front move's first cycle, or with an orientation.
    #[inline(never)]
    fn interpolate_front_slow(&mut self, u: f64) {
        let Some(front) = self.queue.front() else { return };
        let cycles = self.front_move.get_or_insert_with(|| FrontMove::new(&front.path, &mut self.position, front.tag));
        cycles.position(u, &mut self.position);
        if let Some(o) = &front.path.ori {
            self.orientation = Some(cycles.orientation(o, u));
        } else if self.orientation.is_some() {
            self.orientation = None;
        }
        self.position_tag = Some(front.tag);
    }

    /// The cycle's travel `d` reaches the end of the front move: finishes it, and every later
    /// move `d` also reaches, and interpolates within the move it ends in. Once per move: kept
    /// out of the cycle's code.
    #[inline(never)]
    fn cross_ends(&mut self, mut d: f64) {
        loop {
            let Some(front) = self.queue.front() else { return };
            let remaining = front.length - self.s;
            if d < remaining - 1e-12 {
                self.s += d;
                let u = self.s / front.length;
                self.interpolate_front(u);
                return;
            }
            // The move ends within this cycle.
            d -= remaining;
            if self.finish_front() {
                return;
            }
        }
    }

    /// The cycle at rest after a stop (see [`Rest`]): true when this cycle is it. The position
    /// is the start of the next move, where the stop left it, and lies on that move (its
    /// transformation, or its machine axes, map it), as in the move's first cycle. Once per
    /// stop: kept out of the cycle's code.
    #[inline(never)]
    fn rest_after_stop(&mut self) -> bool {
        // An idle cycle stands as well.
        if self.rest == Rest::Now || self.queue.is_empty() {
            self.rest = Rest::None;
            return false;
        }
        self.rest = Rest::Now;
        self.interpolate_front_slow(0.0);
        true
    }

    /// The front move ends within this cycle: the position is its end, the next move comes to
    /// the front. True if the path stops there (or nothing follows). Once per move: kept out
    /// of the cycle's code.
    #[inline(never)]
    fn finish_front(&mut self) -> bool {
        let Some(done) = self.queue.pop_front() else { return true };
        self.position = done.path.end;
        self.orientation = done.path.orientation_at(1.0);
        self.position_tag = Some(done.tag);
        let stop_here = self.v_end[0] == 0.0;
        self.front_move = None;
        if done.drive.is_some() {
            // SOFT's state: the DRIVE cycle leaves it alone, a later SOFT move starts from
            // constant velocity.
            self.acc = 0.0;
        }
        // A BRISK move's infinite jerk leaves `j_min` as it is: no rescan of the queue then.
        if done.a_max <= self.a_min || (done.jerk <= self.j_min && done.jerk.is_finite()) {
            self.rescan_minima();
        }
        self.v_end.pop_front();
        self.corner.pop_front();
        self.finished.push(done.tag);
        self.s = 0.0;
        if done.jerk.is_finite() && !stop_here {
            // Entering or leaving a free-form element (a rounding curve) from or for a line or an
            // arc, the axes' turning acceleration it starts or ends lies in the crossing cycle
            // and the next one: two cycles without a rise.
            self.kinked = match self.queue.front() {
                Some(next) if next.jerk.is_finite() && is_kink(&done, next) => 1,
                Some(next) if next.jerk.is_finite() && done.path.curve.is_some() != next.path.curve.is_some() => 2,
                _ => 0,
            };
        }
        if stop_here || self.queue.is_empty() {
            self.v = 0.0;
            self.acc = 0.0;
            self.rest = Rest::Due;
            return true;
        }
        false
    }

    /// The smallest acceleration and jerk of the queued moves, from scratch (the move that
    /// held one of them left the queue).
    fn rescan_minima(&mut self) {
        (self.a_min, self.j_min) =
            self.queue.iter().fold((f64::INFINITY, f64::INFINITY), |(a, j), m| (a.min(m.a_max), j.min(m.jerk)));
    }

    /// `v`, lowered to the highest speed from which every planned transition ahead can still be
    /// met. Looks past the front move so that a cycle which crosses into the next move cannot
    /// arrive too fast. A transition that `v` can meet is recognised without the square root of
    /// [`brake_speed`] (`brake_speed(d, v_end, a) ≥ v ⇔ v·(v + a·dt) ≤ 2·a·d + v_end²`), so a
    /// cycle far from any braking point takes none; one planned at or above `v` and `free` needs
    /// no braking at all (see [`Planner::brake_limited_at`]).
    #[inline(always)]
    fn brake_limited(&self, v: f64, free: f64) -> f64 {
        let (Some(front), Some(&v_end)) = (self.queue.front(), self.v_end.front()) else { return v };
        self.brake_limited_at(v, front.length - self.s, front.a_max, v_end, self.queue.len() > 1, free)
    }

    /// [`Planner::brake_limited`] from the front move's scalars: the distance to its end, its
    /// deceleration, its planned end speed and whether another move follows.
    ///
    /// A transition planned at or above both the speed so far and `free` does not limit it:
    /// that speed may cross it as it is. (The braking condition with its one-cycle reserve is
    /// conservative, by `v_end·dt` and more: applied there it lowered the path speed for a
    /// cycle at every seam of a chain of collinear or tangent moves, where the transition
    /// speed is the feed.) BRISK passes 0. SOFT's fallback passes its velocity target: a
    /// transition planned below the target is kept with the conservative limit its S curves
    /// brake against (were it dropped, the fallback would let the path arrive faster than the
    /// S curve planned, and the crossing clamp would jump), one at or above it is never
    /// reached faster, as the S curve does not pass its target; and SOFT's limit is never cut
    /// below a transition's speed by that transition ([`soft_floor`]).
    #[inline(always)]
    fn brake_limited_at(&self, v: f64, distance: f64, a: f64, v_end: f64, many: bool, free: f64) -> f64 {
        let dt = self.dt;
        // The smallest deceleration anywhere ahead bounds how far ahead a transition can matter
        // (moves split by a kinematic transformation may decelerate very differently).
        let a_min = self.a_min;
        // The front move's own transition first, without the queue's iterators: most cycles
        // look no farther. The same arithmetic as the loop's first pass.
        let mut limit = v;
        if limit.max(free) > v_end {
            let reserve = if many { v_end * dt } else { 0.0 };
            limit = brake_bound(limit, distance - reserve, v_end, a, dt).max(soft_floor(limit, v_end, free));
        }
        if v_end == 0.0 || distance > limit * limit / a_min {
            return limit;
        }
        self.brake_limited_ahead(distance, a, limit, free)
    }

    /// [`Planner::brake_limited`] past the front move, from the distance to its end, the
    /// smallest deceleration so far and the limit so far (out of line: rarely reached).
    #[inline(never)]
    fn brake_limited_ahead(&self, mut distance: f64, mut a: f64, mut limit: f64, free: f64) -> f64 {
        let dt = self.dt;
        let a_min = self.a_min;
        let n = self.queue.len();
        for (k, (mv, &v_end)) in self.queue.iter().zip(&self.v_end).enumerate().skip(1) {
            distance += mv.length;
            a = a.min(mv.a_max);
            // One cycle at the transition speed is kept in reserve for the crossing cycle.
            if limit.max(free) > v_end {
                let reserve = if k + 1 < n { v_end * dt } else { 0.0 };
                limit = brake_bound(limit, distance - reserve, v_end, a, dt).max(soft_floor(limit, v_end, free));
            }
            if v_end == 0.0 || distance > limit * limit / a_min {
                break;
            }
        }
        limit
    }

    /// The BRISK cycle of a move under DRIVE (`motion/drive.rs`): it speeds up along the
    /// curve, loses at most `a(v)·dt` from speed `v` (hold, a lowered override) and stops at
    /// its end as fast as the curve allows; a transition at speed and the moves ahead are
    /// braked for with the move's lowest acceleration (`a_max`), which holds at every speed.
    /// Out of line: the BRISK cycle stays as it was.
    #[inline(never)]
    fn drive_velocity(
        &self,
        curve: &super::drive::DriveCurve,
        cap: f64,
        remaining: f64,
        v_end: f64,
        many: bool,
    ) -> f64 {
        let (dt, v) = (self.dt, self.v);
        let down = v - curve.accel_at(v) * dt;
        let v_new = if self.hold {
            down.max(0.0)
        } else if v > cap {
            down.max(cap)
        } else {
            curve.accelerate(v, dt).min(cap)
        };
        if v_end == 0.0 {
            return curve.stop_speed(v_new, remaining, dt);
        }
        let a = self.queue.front().map_or(f64::INFINITY, |m| m.a_max);
        self.brake_limited_at(v_new, remaining, a, v_end, many, 0.0)
    }

    /// Backward pass: the highest transition speed at each boundary from which every later
    /// move can still be braked in time; the last queued move ends at standstill.
    fn replan(&mut self) {
        let n = self.queue.len();
        let mut next_v_end = 0.0;
        self.v_end[n - 1] = 0.0;
        for k in (0..n - 1).rev() {
            let next = &self.queue[k + 1];
            let reach = brake_speed(next.length, next_v_end, next.a_max, self.dt);
            let v = self.corner[k].min(reach);
            // v_end[k] depends only on the moves from k on: where it comes out as before the
            // push, every earlier one does too.
            if v.to_bits() == self.v_end[k].to_bits() && !self.replan_all {
                return;
            }
            self.v_end[k] = v;
            next_v_end = v;
        }
        self.replan_all = false;
    }

    /// The highest speed at the transition from move `k` to `k+1`. Within the transition
    /// cycle an axis may also be accelerating at its full `a`, so the velocity jump a corner adds
    /// is limited to `(overload − 1) · a · dt`: together they stay within `overload · a`
    /// (MD32310 MAX_ACCEL_OVL_FACTOR). Tangent transitions need no slowdown.
    fn corner_speed(&self, k: usize) -> f64 {
        let (a, b) = (&self.queue[k], &self.queue[k + 1]);
        if a.exact_stop {
            return 0.0;
        }
        if a.machine_space != b.machine_space {
            return 0.0;
        }
        let (ta, tb) = (end_rates(a, true), end_rates(b, false));
        let mut v = a.v_max.min(b.v_max);
        // SOFT: the jump lasts one cycle, so it is an acceleration pulse; its jerk
        // `jump·v/dt²` stays within the axis jerk, of which the moves' path jerks give a lower
        // bound (`soft::corner_jerk`).
        let jerk = a.jerk.min(b.jerk);
        for i in 0..MAX_CHANNEL_AXES.min(self.limits.len()) {
            let jump = (tb[i] - ta[i]).abs();
            if jump > 1e-12 {
                let lim = &self.limits[i];
                v = v.min((lim.accel_overload - 1.0) * lim.max_accel * self.dt / jump);
                if jerk.is_finite() {
                    v = v.min(soft::corner_jerk(jerk, ta[i], tb[i]) * self.dt * self.dt / jump);
                }
            }
        }
        if a.seam_jerk.is_finite() || b.seam_jerk.is_finite() {
            v = v.min(soft_curvature::seam_speed(a, b, self.limits.len(), self.dt));
        }
        v
    }
}

/// The axis rates per unit path length of move `m` at its end (`end`) or its start.
fn end_rates(m: &Move, end: bool) -> AxisVec {
    match &m.axis_tangents {
        Some(t) => {
            if end {
                t.1
            } else {
                t.0
            }
        }
        None => m.path.tangent(if end { 1.0 } else { 0.0 }).map(|x| x / m.length),
    }
}

/// True when the axis rates jump between the end of move `a` and the start of move `b`: a
/// corner, whose velocity jump is an acceleration pulse on the axes.
fn is_kink(a: &Move, b: &Move) -> bool {
    let (ta, tb) = (end_rates(a, true), end_rates(b, false));
    ta.iter().zip(&tb).any(|(x, y)| (y - x).abs() > 1e-12)
}

/// The speed SOFT's fallback brake limit keeps at a transition planned at `v_end` (`free`, its
/// velocity target, is positive; BRISK passes 0 and keeps none): the conservative bound with its
/// one-cycle reserve lies below `v_end` in the last cycle or two before the transition, so a path
/// that the S curve had brought to `v_end` was cut there, cycle after cycle, to
/// `brake_speed(0, v_end)` and crept into the corner far below its planned speed. Not above
/// `v_end` the path meets the transition as it is.
#[inline(always)]
fn soft_floor(limit: f64, v_end: f64, free: f64) -> f64 {
    if free > 0.0 { limit.min(v_end) } else { 0.0 }
}

/// `v`, lowered where needed so that braking with deceleration `a` from `d` before a transition
/// still meets its speed `v_end`: [`brake_speed`], or [`stop_speed`] for a stop. The test
/// without a square root first (`brake_speed(d, v_end, a) ≥ v ⇔ v·(v + a·dt) ≤ 2·a·d + v_end²`;
/// for a stop with the `(a·dt)²/4` by which the exact stop may need more).
#[inline(always)]
fn brake_bound(v: f64, d: f64, v_end: f64, a: f64, dt: f64) -> f64 {
    let b = a * dt;
    if v_end == 0.0 {
        if v * (v + b) + 0.25 * b * b > 2.0 * a * d.max(0.0) {
            return v.min(stop_speed(d, a, dt));
        }
    } else if v * (v + b) > 2.0 * a * d.max(0.0) + v_end * v_end {
        return v.min(brake_speed(d, v_end, a, dt));
    }
    v
}

/// The highest speed at a point `distance` before a standstill from which the path can stop on
/// it, one IPO cycle at a time, never losing more than `a·dt` of speed in a cycle, the last
/// cycle's speed included (it is followed by rest). From `v = (n + f)·a·dt` (`0 ≤ f < 1`) the
/// shortest such stop runs `v, v − a·dt, …, f·a·dt, 0` and covers
/// `S(v) = dt·(n + 1)·(v − n·a·dt/2)`: piecewise linear in `v`, so its inverse is exact.
/// [`brake_speed`]'s `v²/(2a) + v·dt/2` is short by `a·dt²·f·(1 − f)/2`, up to an eighth of
/// `a·dt²`: braking on that curve ended with a last cycle that lost more than `a·dt`.
pub fn stop_speed(distance: f64, a: f64, dt: f64) -> f64 {
    let b = a * dt;
    let d = distance.max(0.0);
    // The number n of whole steps: S(n·b) = b·dt·n(n+1)/2 ≤ d.
    let q = (((1.0 + 8.0 * d / (b * dt)).sqrt() - 1.0) / 2.0).max(0.0);
    // (`floor` is a library call on the baseline target; below 2⁵² truncation is the same.)
    let n = if q < 4.5e15 { q as u64 as f64 } else { q.floor() };
    let base = if n > 0.0 { n * b / 2.0 } else { 0.0 };
    d / (dt * (n + 1.0)) + base
}

/// The highest speed at a point `distance` before a boundary from which cycle-wise braking
/// with deceleration `a` reaches `v_end` at the boundary. Accounts for the cycle discretisation:
/// braking from `v` in steps of `a·dt` covers `v²/(2a) + v·dt/2` (a stop is [`stop_speed`]).
pub fn brake_speed(distance: f64, v_end: f64, a: f64, dt: f64) -> f64 {
    let b = a * dt;
    (-b + (b * b + 4.0 * (2.0 * a * distance.max(0.0) + v_end * v_end)).sqrt()) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 0.004;

    fn limits(v: f64, a: f64) -> Vec<AxisLimit> {
        vec![AxisLimit { max_velocity: v, max_accel: a, accel_overload: 1.2 }; 3]
    }

    fn line(from: [f64; 3], to: [f64; 3]) -> Path {
        let mut start = [0.0; MAX_CHANNEL_AXES];
        let mut end = [0.0; MAX_CHANNEL_AXES];
        start[..3].copy_from_slice(&from);
        end[..3].copy_from_slice(&to);
        Path::line(start, end)
    }

    fn run(p: &mut Planner) -> Vec<AxisVec> {
        let mut out = vec![*p.position()];
        while !p.is_idle() {
            p.step();
            out.push(*p.position());
            assert!(out.len() < 1_000_000);
        }
        out
    }

    #[test]
    fn the_brake_limit_without_square_roots_is_the_smallest_brake_speed_ahead() {
        // A queue of short and long moves with corners (planned transition speeds > 0): at
        // many points of the front move and candidate speeds, `brake_limited(v)` is
        // min(v, every transition's brake speed), the latter written out here for all moves
        // (no early stop), with the one-cycle reserve before each transition but the last;
        // a transition planned at or above the speed so far does not lower it.
        let lim = limits(1000.0, 500.0);
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        let pts: [[f64; 3]; 6] =
            [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.5, 1.0, 0.0], [40.0, 1.5, 0.0], [41.0, 9.0, 0.0], [90.0, 9.0, 0.0]];
        for (i, w) in pts.windows(2).enumerate() {
            let len = (0..3).map(|k| (w[1][k] - w[0][k]).powi(2)).sum::<f64>().sqrt();
            p.push(Move::new(line(w[0], w[1]), len, Feed::Path(400.0), &lim, false, i as u32));
        }
        let reference = |p: &Planner, v: f64| {
            let (mut distance, mut a, mut out) = (-p.s, f64::INFINITY, v);
            for (k, mv) in p.queue.iter().enumerate() {
                distance += mv.length;
                a = a.min(mv.a_max);
                // A transition planned at or above the speed so far is crossed as it is.
                if out > p.v_end[k] {
                    let reserve = if k + 1 < p.queue.len() { p.v_end[k] * DT } else { 0.0 };
                    let d = distance - reserve;
                    let stop = if p.v_end[k] == 0.0 { stop_speed(d, a, DT) } else { brake_speed(d, p.v_end[k], a, DT) };
                    out = out.min(stop);
                }
            }
            out
        };
        let mut checked = 0;
        for i in 0..=20 {
            p.s = p.queue[0].length * f64::from(i) / 20.0;
            for v in [0.0, 1.0, 10.0, 37.5, 80.0, 150.0, 400.0, f64::INFINITY] {
                let brisk = p.brake_limited_at(v, p.queue[0].length - p.s, p.queue[0].a_max, p.v_end[0], true, 0.0);
                let (got, want) = (brisk, reference(&p, v));
                assert!((got - want).abs() <= 1e-12 * want.max(1.0), "s {} v {v}: {got} vs {want}", p.s);
                checked += usize::from(want < v);
            }
        }
        assert!(checked > 20, "the brake limit binds in {checked} of the cases");
    }

    #[test]
    fn the_stop_speed_is_the_fastest_discrete_stop_that_fits() {
        // a = 3000 mm/s², T = 4 ms: a cycle loses at most 12 mm/s. From 100 mm/s the fastest
        // stop runs 100, 88, ..., 4 and rests: 0.004·468 = 1.872 mm. From 24: 24, 12, then rest:
        // 0.144 mm. Below 12 mm/s the stop is the one cycle itself: 0.016 mm at 4 mm/s.
        for (d, v) in [(1.872, 100.0), (0.144, 24.0), (0.016, 4.0), (0.0, 0.0)] {
            assert!((stop_speed(d, 3000.0, DT) - v).abs() < 1e-9, "{d} mm: {}", stop_speed(d, 3000.0, DT));
        }
        // Everywhere: stepping down by a·T from the stop speed covers the distance exactly, and
        // the old formula's speed is at least as high (up to a·T²/8 of distance short).
        for i in 0..2000 {
            let d = f64::from(i) * 0.00137;
            let v = stop_speed(d, 3000.0, DT);
            let (mut w, mut covered) = (v, 0.0);
            while w > 0.0 {
                covered += w * DT;
                w -= 12.0;
            }
            assert!((covered - d).abs() < 1e-9, "{d}: {covered}");
            assert!(brake_speed(d, 0.0, 3000.0, DT) >= v - 1e-9);
        }
    }

    /// The backward pass from scratch over the whole queue, as it was before the corner speeds
    /// were kept: every transition's corner speed recomputed, no early stop.
    fn full_backward_pass(p: &Planner) -> Vec<f64> {
        let n = p.queue.len();
        let mut v_end = vec![0.0; n];
        for k in (0..n.saturating_sub(1)).rev() {
            let next = &p.queue[k + 1];
            let reach = brake_speed(next.length, v_end[k + 1], next.a_max, DT);
            v_end[k] = p.corner_speed(k).min(reach);
        }
        v_end
    }

    #[test]
    fn the_kept_corner_speeds_give_the_end_velocities_of_a_full_backward_pass() {
        // A zigzag of short and long moves, some exact stop, pushed while the front runs and
        // is popped; halfway the limits change (lower acceleration: every corner gets slower).
        // After every push the end velocities equal, bit for bit, those of the full pass.
        let lim = limits(1000.0, 500.0);
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        let mut at = [0.0; 3];
        let mut compared = 0;
        let mut corner_binds = 0;
        for i in 0..120u32 {
            let len = if i % 7 == 3 { 25.0 } else { 0.5 + f64::from(i % 5) * 0.3 };
            let (dx, dy) = if i % 2 == 0 { (len * 0.8, len * 0.6) } else { (len, 0.0) };
            let next = [at[0] + dx, at[1] + dy, 0.0];
            p.push(Move::new(line(at, next), len, Feed::Path(300.0), &lim, i % 11 == 10, i));
            at = next;
            let want = full_backward_pass(&p);
            let got: Vec<f64> = p.v_end.iter().copied().collect();
            assert_eq!(
                got.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                want.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                "push {i}: {got:?} vs {want:?}"
            );
            compared += 1;
            corner_binds +=
                (0..p.queue.len().saturating_sub(1)).filter(|&k| p.v_end[k] > 0.0 && p.v_end[k] == p.corner[k]).count();
            if i == 60 {
                p.set_limits(limits(1000.0, 120.0));
            }
            for _ in 0..(i % 4) * 10 {
                p.step();
            }
        }
        assert_eq!(compared, 120);
        assert!(corner_binds > 50, "the corner speed decides {corner_binds} transitions");
    }

    #[test]
    fn a_long_move_takes_the_trapezoid_time() {
        // 100 mm at 50 mm/s with 500 mm/s²: ramp 0.1 s and 2.5 mm each way,
        // cruise 95 mm in 1.9 s: 2.1 s in all.
        let mut p = Planner::new(DT, limits(1000.0, 500.0), [0.0; MAX_CHANNEL_AXES]);
        let path = line([0.0; 3], [100.0, 0.0, 0.0]);
        p.push(Move::new(path, 100.0, Feed::Path(50.0), &limits(1000.0, 500.0), true, 1));
        let samples = run(&mut p);
        let t = (samples.len() - 1) as f64 * DT;
        assert!((t - 2.1).abs() <= 2.0 * DT, "took {t}");
        assert_eq!(samples.last().unwrap()[0], 100.0);
    }

    #[test]
    fn a_short_move_takes_the_triangle_time() {
        // 1 mm with 500 mm/s², never reaching feed: t = 2·sqrt(1/500) = 0.0894 s.
        let lim = limits(1000.0, 500.0);
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        p.push(Move::new(line([0.0; 3], [1.0, 0.0, 0.0]), 1.0, Feed::Path(1000.0), &lim, true, 1));
        let t = (run(&mut p).len() - 1) as f64 * DT;
        assert!((t - 0.0894).abs() <= 2.0 * DT, "took {t}");
    }

    #[test]
    fn rapid_moves_run_the_slowest_axis_at_its_limit() {
        // X 100 mm at 200 mm/s and Y 50 mm at 50 mm/s: Y limits, 1 s cruise plus ramps.
        let lim = vec![
            AxisLimit { max_velocity: 200.0, max_accel: 1e6, accel_overload: 1.0 },
            AxisLimit { max_velocity: 50.0, max_accel: 1e6, accel_overload: 1.0 },
        ];
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        let len = (100.0f64 * 100.0 + 50.0 * 50.0).sqrt();
        p.push(Move::new(line([0.0; 3], [100.0, 50.0, 0.0]), len, Feed::Rapid, &lim, true, 1));
        let t = (run(&mut p).len() - 1) as f64 * DT;
        assert!((t - 1.0).abs() <= 2.0 * DT, "took {t}");
    }

    #[test]
    fn no_axis_ever_exceeds_its_velocity_or_acceleration() {
        let lim = vec![
            AxisLimit { max_velocity: 100.0, max_accel: 800.0, accel_overload: 1.2 },
            AxisLimit { max_velocity: 60.0, max_accel: 400.0, accel_overload: 1.2 },
            AxisLimit { max_velocity: 30.0, max_accel: 300.0, accel_overload: 1.2 },
        ];
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        let pts = [
            [0.0, 0.0, 0.0],
            [30.0, 0.0, 0.0],
            [30.0, 20.0, 5.0],
            [0.0, 40.0, 0.0],
            [5.0, 41.0, -3.0],
            [80.0, 0.0, 0.0],
        ];
        for (i, w) in pts.windows(2).enumerate() {
            let path = line(w[0], w[1]);
            let len = (0..3).map(|k| (w[1][k] - w[0][k]).powi(2)).sum::<f64>().sqrt();
            p.push(Move::new(path, len, Feed::Path(1000.0), &lim, false, i as u32));
        }
        let s = run(&mut p);
        let vel: Vec<[f64; 3]> = s.windows(2).map(|w| std::array::from_fn(|k| (w[1][k] - w[0][k]) / DT)).collect();
        for v in &vel {
            for k in 0..3 {
                assert!(v[k].abs() <= lim[k].max_velocity * (1.0 + 1e-9), "axis {k} at {}", v[k]);
            }
        }
        for (i, w) in vel.windows(2).enumerate() {
            for k in 0..3 {
                let acc = (w[1][k] - w[0][k]).abs() / DT;
                assert!(
                    acc <= lim[k].max_accel * lim[k].accel_overload * (1.0 + 1e-6),
                    "axis {k} accel {acc} at {i}: {:?} {:?} {:?}",
                    vel[i.saturating_sub(1)],
                    w[0],
                    w[1]
                );
            }
        }
        assert_eq!(&s.last().unwrap()[..3], &[80.0, 0.0, 0.0]);
    }

    #[test]
    fn continuous_path_is_faster_than_exact_stop_on_collinear_blocks() {
        let lim = limits(1000.0, 500.0);
        let time = |exact| {
            let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
            for i in 0..10 {
                let path = line([i as f64 * 10.0, 0.0, 0.0], [(i + 1) as f64 * 10.0, 0.0, 0.0]);
                p.push(Move::new(path, 10.0, Feed::Path(100.0), &lim, exact, i));
            }
            run(&mut p).len()
        };
        assert!(time(false) < time(true));
        // Continuous: 100 mm at 100 mm/s plus one ramp of 0.2 s total (~1.2 s).
        assert!(((time(false) - 1) as f64 * DT - 1.2).abs() < 3.0 * DT);
    }

    #[test]
    fn collinear_seams_are_crossed_at_the_feed() {
        // 30 collinear moves of 2 mm at 100 mm/s, 500 mm/s², dt 4 ms: the path accelerates by
        // a·dt = 2 mm/s per cycle to 100 mm/s (50 cycles, 0.004·(2+4+..+98) = 9.8 mm), and
        // brakes the same way over the last 9.8 mm and more. Every transition is planned at
        // the feed (no corner, the moves ahead are long enough to brake in), so every cycle in
        // between moves exactly F·dt = 0.4 mm, across the seams too.
        let lim = limits(1000.0, 500.0);
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        for i in 0..30 {
            let path = line([f64::from(i) * 2.0, 0.0, 0.0], [f64::from(i + 1) * 2.0, 0.0, 0.0]);
            p.push(Move::new(path, 2.0, Feed::Path(100.0), &lim, false, i as u32));
        }
        let steps: Vec<f64> = run(&mut p).windows(2).map(|w| w[1][0] - w[0][0]).collect();
        let full = |x: &f64| (x - 0.4).abs() < 1e-9;
        let first = steps.iter().position(full).unwrap();
        let last = steps.iter().rposition(full).unwrap();
        assert_eq!(first, 49, "50 cycles of acceleration");
        let slow: Vec<usize> = (first..=last).filter(|&i| !full(&steps[i])).collect();
        assert!(slow.is_empty(), "cycles below the feed between the ramps: {slow:?}");
        // 60 mm minus two ramps of 9.8 mm at 0.4 mm per cycle: 101 cycles at the feed with an
        // exact braking point. The backward pass's brake speeds keep a margin of up to a cycle's
        // travel for each of the last moves (5 moves of 2 mm in the 10 mm ramp), so the ramp
        // down may begin up to 3 cycles early (safe side); but not one cycle dips at a seam.
        assert!((98..=101).contains(&(last - first + 1)), "{} cycles at the feed", last - first + 1);
    }

    #[test]
    fn feed_hold_brakes_on_the_path_and_resumes() {
        let lim = limits(1000.0, 500.0);
        let mut p = Planner::new(DT, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        p.push(Move::new(line([0.0; 3], [100.0, 0.0, 0.0]), 100.0, Feed::Path(50.0), &lim, true, 1));
        for _ in 0..100 {
            p.step();
        }
        p.set_hold(true);
        for _ in 0..100 {
            p.step();
        }
        assert_eq!(p.velocity(), 0.0);
        assert!(p.position()[0] > 10.0 && p.position()[0] < 100.0);
        p.set_hold(false);
        run(&mut p);
        assert_eq!(p.position()[0], 100.0);
    }
}
