//! Positioning axes in the main run (Function Manual P2): each axis that travels outside the
//! path (POS/POSA in a program, a command axis of a synchronized action: `DO POS[ax]=`,
//! `DO MOV[ax]=`) runs on its own single-axis interpolator, stepped once per IPO cycle after
//! the path: a velocity ramp with the axis' acceleration MD32300 up to its feed (`FA[ax]`,
//! else MD32060 `$MA_POS_AX_VELO`, never above MD32000), braking so that it stops on the target.
//!
//! The path planner keeps its own value for such an axis (the interpreter's end point, which
//! the path's moves do not change); while an axis travels here the channel's machine position
//! of that axis is this module's, and when a program axis arrives the planner is told where it
//! stands. A command axis stays with this module until the program ends (the interpreter did
//! not prepare its position), so the path cannot pull it back.
//!
//! Nothing of this runs in an IPO cycle while no axis is here: one test of a bit mask.
//!
//! Modelled as follows where the manuals leave room:
//! - NC stop brakes the positioning axes with their acceleration; NC start continues to the
//!   same target. A reset stops them at once, like the path.
//! - The feed override of the path does not act on them (the manuals give them their own axial
//!   override, `$AA_OVR`, not modelled here).
//! - The profile is acceleration-limited (BRISK), whatever the path's SOFT/BRISK.

use super::Channel;
use crate::alarm::Alarm;
use crate::interp::path_control::positioning::{Motion, Parts};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::stop_speed;

/// One axis travelling on its own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Travel {
    pub(super) position: f64,
    /// Signed velocity, units per second.
    velocity: f64,
    /// End point of the current part (the end point itself but for POSP); ±∞ for endless
    /// motion (`MOV[ax]=±1`).
    pub(super) target: f64,
    pub(super) feed: f64,
    accel: f64,
    /// POSP: the end point and the parts towards it.
    parts: Option<(f64, Parts)>,
    /// What started it, for the state.
    pub(super) motion: Option<Motion>,
    /// OS[ax]=1: the oscillation's course (`oscillation.rs`).
    pub(super) swing: Option<super::oscillation::Swing>,
}

impl Travel {
    /// The end point the axis travels to (the last part's end for POSP).
    fn end(&self) -> f64 {
        self.parts.map_or(self.target, |(end, _)| end)
    }

    /// After a part of POSP or a stroke of an oscillation has ended: the next one starts
    /// (true), or the end is reached.
    fn next_part(&mut self) -> bool {
        if let Some(swing) = self.swing.as_mut() {
            match swing.arrived() {
                Some(next) => self.target = next,
                None => self.swing = None,
            }
            return self.swing.is_some();
        }
        match self.parts {
            Some((end, parts)) if self.position != end => {
                self.target = parts.next_end(self.position, end);
                true
            }
            _ => false,
        }
    }

    /// One cycle of `dt`; true once the axis stands on its target. With `hold` it brakes.
    ///
    /// The exact discrete trapezoid: this cycle's speed is the lowest of the feed, the last
    /// speed plus `a·dt`, and the path planner's [`stop_speed`] of the rest (the fastest speed
    /// from which cycle-wise braking by `a·dt` stops on the target, the stop after the last
    /// cycle included), so no cycle changes speed by more than `a·dt` and the last cycle's
    /// travel ends on the target. (Braking along the continuous `√(2·a·rest)` ended a few
    /// percent early with a last step above the acceleration.)
    fn step(&mut self, dt: f64, hold: bool) -> bool {
        // An oscillation's stop time at a reversal point (it stands).
        if let Some(swing) = self.swing.as_mut().filter(|s| s.dwell > 0.0) {
            if !hold {
                swing.dwell = if swing.dwell > dt * (1.0 + 1e-9) { swing.dwell - dt } else { 0.0 };
            }
            return false;
        }
        let rest = self.target - self.position;
        if rest == 0.0 && self.velocity == 0.0 {
            return true;
        }
        let dir = if hold { 0.0 } else { rest.signum() };
        // Endless motion (`MOV`) has no stop to brake for.
        let stoppable = if rest.is_finite() { stop_speed(rest.abs(), self.accel, dt) } else { f64::INFINITY };
        let wanted = dir * self.feed.min(stoppable);
        let dv = (wanted - self.velocity).clamp(-self.accel * dt, self.accel * dt);
        self.velocity += dv;
        let next = self.position + self.velocity * dt;
        // Reached within this cycle (up to the rounding of the speed's inverse: a last step of
        // less than a nanometre would be a cycle of its own), or passed after a change of
        // target the axis could not brake for: it stands on the target.
        if !hold && ((self.target - next) * rest <= 0.0 || (self.target - next).abs() < LANDING) {
            self.position = self.target;
            self.velocity = 0.0;
            return true;
        }
        self.position = next;
        false
    }
}

/// Below this rest (mm or degrees) a cycle's travel counts as landing on the target: far below
/// any control's position resolution, far above the rounding of [`stop_speed`].
const LANDING: f64 = 1e-9;

/// The travel while braking at once from `v` by `a·dt` per cycle to rest: the speeds
/// `v − a·dt, v − 2·a·dt, ..` while positive, one cycle each.
fn brake_distance(v: f64, a: f64, dt: f64) -> f64 {
    let b = a * dt;
    let m = (v / b).ceil() - 1.0;
    if m <= 0.0 { 0.0 } else { dt * (m * v - b * m * (m + 1.0) / 2.0) }
}

/// A positioning axis as the state shows it (`Snapshot::positioning`): one per axis that
/// travels on its own interpolator, or a command axis held by a synchronized action.
#[derive(Debug, Clone, PartialEq)]
pub struct PositioningInfo {
    /// Machine axis name, as in `Snapshot::machine`.
    pub axis: String,
    /// The end point in machine coordinates (the last part's end for POSP); `None` for the
    /// endless motion of `MOV[ax]=±1`.
    pub target: Option<f64>,
    /// Signed velocity in mm/min (deg/min).
    pub velocity: f64,
    /// `POS`, `POSA`, `POSP` (a program's), `OS` (a program's oscillating axis), `command`
    /// (`POS`/`FA` of a synchronized action) or `MOV` (an action's endless motion).
    pub kind: &'static str,
    /// The program waits for it (WAITP, or the end of its POS/POSP block).
    pub waiting: bool,
}

/// A program's positioning axis still on its way when a checkpoint is taken: a restart sets it
/// travelling again to the same end point (at NC start, like NC stop and start).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SavedPositioning {
    /// Channel axis name.
    pub axis: String,
    /// End point in machine coordinates.
    pub end: f64,
    /// Feed in mm/s (deg/s).
    pub feed: f64,
    /// `POS`, `POSA` or `POSP`.
    pub kind: String,
    /// POSP: the part length (machine units) and whether the last stretch is halved.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub parts: Option<(f64, bool)>,
}

/// The channel's positioning axes.
#[derive(Debug, Clone, Default)]
pub struct PositioningAxes {
    pub(super) axes: [Option<Travel>; MAX_CHANNEL_AXES],
    /// Bit k: channel axis k is here (travelling, or a command axis kept until program end).
    active: u32,
    /// Bit k: channel axis k is a command axis of a synchronized action.
    command: u32,
    /// Bit k: channel axis k has not arrived yet.
    moving: u32,
    /// `FA[ax]` of synchronized actions in mm/s (deg/s); 0: MD32060.
    command_feed: [f64; MAX_CHANNEL_AXES],
    /// `S` of synchronized actions per spindle axis (rev/min), for their next M3/M4.
    speeds: [f64; MAX_CHANNEL_AXES],
    /// Bit k: the program's main run waits for channel axis k (WAITP, a POS block's end).
    waited: u32,
}

impl PositioningAxes {
    /// Whether any axis of `mask` is still on its way.
    pub fn moving(&self, mask: u32) -> bool {
        self.moving & mask != 0
    }

    /// Whether any axis started by the program (POS/POSA) is still on its way.
    pub fn program_moving(&self) -> bool {
        self.moving & !self.command != 0
    }

    /// Whether command axes of synchronized actions (or PRESETON axes) are here: the
    /// programmed positions of the interpreter are not where they stand.
    pub fn has_command_axes(&self) -> bool {
        self.command != 0
    }

    /// The signed velocity of axis `k` (units per second) if it is here.
    pub fn velocity(&self, k: usize) -> Option<f64> {
        self.axes[k].map(|t| t.velocity)
    }

    /// The position of axis `k` if it is here.
    pub fn position(&self, k: usize) -> Option<f64> {
        self.axes[k].map(|t| t.position)
    }
}

impl Channel {
    /// `FA[ax]=` of an action: the axis' feed from now on, also while it travels.
    pub(super) fn set_command_feed(&mut self, k: usize, feed: f64) {
        let feed = feed.min(self.cfg.axis(k).max_velocity);
        self.positioning.command_feed[k] = feed;
        if let Some(t) = self.positioning.axes[k].as_mut() {
            t.feed = feed;
        }
    }

    /// The feed of command axis `k`: its `FA`, else MD32060.
    pub(super) fn command_feed(&self, k: usize) -> f64 {
        match self.positioning.command_feed[k] {
            f if f > 0.0 => f,
            _ => self.cfg.axis(k).pos_velocity,
        }
    }

    /// Remembers `S` of an action for spindle axis `k`.
    pub(super) fn set_action_speed(&mut self, k: usize, rpm: f64) {
        self.positioning.speeds[k] = rpm;
    }

    /// The last `S` of an action for spindle axis `k` (0: none).
    pub(super) fn action_speed(&self, k: usize) -> f64 {
        self.positioning.speeds[k]
    }

    /// Program end: the command axes brake and are handed back to the path once at rest; the
    /// actions' FA and S are forgotten.
    pub(super) fn end_command_axes(&mut self) {
        let command = self.positioning.command;
        for k in 0..MAX_CHANNEL_AXES {
            if command & (1 << k) != 0 {
                self.stop_positioning(k);
            }
        }
        self.positioning.command = 0;
        self.positioning.command_feed = [0.0; MAX_CHANNEL_AXES];
        self.positioning.speeds = [0.0; MAX_CHANNEL_AXES];
    }

    /// A program's POS/POSA/POSP: axis `k` travels from where it stands to `target` at `feed`
    /// (POSP in parts, counted from here).
    pub(super) fn start_program_positioning(&mut self, k: usize, target: f64, feed: f64, motion: Motion) {
        match motion {
            Motion::Oscillate(osc) => return self.start_oscillation(k, target, feed, osc),
            Motion::EndOscillation => return self.end_oscillation(k),
            _ => {}
        }
        self.start_positioning(k, target, feed, false);
        if let Some(t) = self.positioning.axes[k].as_mut() {
            t.motion = Some(motion);
            if let Motion::Posp(parts) = motion {
                let parts = parts.for_way(t.position, target);
                t.parts = Some((target, parts));
                t.target = parts.next_end(t.position, target);
            }
        }
    }

    /// Starts (or retargets) axis `k` from where it stands towards `target` at `feed`.
    pub(super) fn start_positioning(&mut self, k: usize, target: f64, feed: f64, command: bool) {
        let accel = self.cfg.axis(k).max_accel;
        let feed = feed.min(self.cfg.axis(k).max_velocity);
        let p = &mut self.positioning;
        let (position, velocity) = match p.axes[k] {
            Some(t) => (t.position, t.velocity),
            None => (self.machine[k], 0.0),
        };
        p.axes[k] = Some(Travel { position, velocity, target, feed, accel, parts: None, motion: None, swing: None });
        p.active |= 1 << k;
        p.moving |= 1 << k;
        if command {
            p.command |= 1 << k;
        }
        self.wake_motion_readers();
    }

    /// `MOV[ax]=0` on a command axis: it brakes to a stop where its ramp ends.
    pub(super) fn stop_positioning(&mut self, k: usize) {
        if let Some(t) = self.positioning.axes[k].as_mut() {
            t.parts = None;
            let brake = brake_distance(t.velocity.abs(), t.accel, self.cfg.ipo_cycle);
            t.target = t.position + t.velocity.signum() * brake;
            if t.velocity == 0.0 {
                t.target = t.position;
            }
        }
    }

    /// PRESETON: axis `k` (here) and its target move by `d` in the machine system, no motion.
    pub(super) fn shift_positioning_axis(&mut self, k: usize, d: f64) {
        if let Some(t) = self.positioning.axes[k].as_mut() {
            t.position += d;
            t.target += d;
            if let Some((end, _)) = t.parts.as_mut() {
                *end += d;
            }
        }
    }

    /// One IPO cycle of the positioning axes: one test when none is here.
    #[inline]
    pub(super) fn step_positioning_axes(&mut self) {
        if self.positioning.active != 0 {
            self.run_positioning_cycle();
        }
    }

    /// Out of line: the IPO cycle's own code stays small (ARCHITECTURE: the IPO cycle's code).
    #[inline(never)]
    fn run_positioning_cycle(&mut self) {
        if self.positioning.command != 0 && self.status == super::Status::Running {
            self.check_command_axes();
        }
        let dt = self.cfg.ipo_cycle;
        // NC stop and alarms brake them; after the program's end they run on (command axes
        // braking to their stop).
        let hold = matches!(self.status, super::Status::Stopped | super::Status::Alarm);
        let p = &mut self.positioning;
        for k in 0..MAX_CHANNEL_AXES {
            if p.active & (1 << k) == 0 {
                continue;
            }
            let Some(t) = p.axes[k].as_mut() else { continue };
            if p.moving & (1 << k) != 0 && t.step(dt, hold) && !t.next_part() {
                p.moving &= !(1 << k);
            }
            self.machine[k] = t.position;
            if p.moving & (1 << k) == 0 && p.command & (1 << k) == 0 {
                // A program axis has arrived: the planner holds it there from now on.
                p.axes[k] = None;
                p.active &= !(1 << k);
                self.planner.place_axis(k, self.machine[k]);
            }
        }
    }

    /// Reset: every positioning axis stands where it is; the planner takes it over.
    pub(super) fn reset_positioning_axes(&mut self) {
        self.release_positioning_axes(u32::MAX);
        self.positioning.waited = 0;
    }

    /// Writes the positioning axes into `list` (the state), reusing its names; empties it
    /// at once when none is here.
    pub(super) fn refresh_positioning(&self, list: &mut Vec<PositioningInfo>) {
        let p = &self.positioning;
        if p.active == 0 {
            list.clear();
            return;
        }
        let mut len = 0;
        for k in (0..MAX_CHANNEL_AXES).filter(|&k| p.active & (1 << k) != 0) {
            let Some(t) = p.axes[k] else { continue };
            let ax = self.cfg.axis(k);
            let display = |v: f64| match ax.modulo {
                Some((start, range)) => start + (v - start).rem_euclid(range),
                None => v,
            };
            let end = t.end();
            let kind = match t.motion {
                Some(Motion::Pos) => "POS",
                Some(Motion::Posa) => "POSA",
                Some(Motion::Posp(_)) => "POSP",
                Some(Motion::Oscillate(_) | Motion::EndOscillation) => "OS",
                None if end.is_infinite() => "MOV",
                None => "command",
            };
            let info = PositioningInfo {
                axis: String::new(),
                target: end.is_finite().then(|| display(end)),
                velocity: t.velocity * 60.0,
                kind,
                waiting: p.waited & p.moving & (1 << k) != 0,
            };
            if len == list.len() {
                list.push(info);
            } else {
                let name = std::mem::take(&mut list[len].axis);
                list[len] = PositioningInfo { axis: name, ..info };
            }
            if list[len].axis != ax.name {
                list[len].axis.clear();
                list[len].axis.push_str(&ax.name);
            }
            len += 1;
        }
        list.truncate(len);
    }

    /// The program's positioning axes still on their way (for a checkpoint; command axes of
    /// synchronized actions are not kept, as the actions are not).
    pub(super) fn saved_positioning(&self) -> Vec<SavedPositioning> {
        let p = &self.positioning;
        let program = p.moving & !p.command;
        (0..MAX_CHANNEL_AXES)
            .filter(|&k| program & (1 << k) != 0)
            .filter_map(|k| {
                let t = p.axes[k]?;
                let (kind, parts) = match t.motion? {
                    Motion::Pos => ("POS", None),
                    Motion::Posa => ("POSA", None),
                    Motion::Posp(parts) => ("POSP", Some((parts.length, parts.halves))),
                    // An oscillation is not resumed after a restart (a reset ends it).
                    Motion::Oscillate(_) | Motion::EndOscillation => return None,
                };
                let axis = self.cfg.axis(k).name.clone();
                Some(SavedPositioning { axis, end: t.end(), feed: t.feed, kind: kind.into(), parts })
            })
            .collect()
    }

    /// Sets the saved positioning axes travelling again from where they stand (a restart):
    /// an axis the machine data no longer has, or an unknown kind, is an error and nothing
    /// starts.
    pub(super) fn restore_positioning(&mut self, saved: &[SavedPositioning]) -> Result<(), String> {
        let mut starts = Vec::with_capacity(saved.len());
        for s in saved {
            let k = (0..self.cfg.channel_axes.len())
                .find(|&k| self.cfg.axis(k).name == s.axis)
                .ok_or_else(|| format!("positioning axis {} is not in the machine data", s.axis))?;
            let motion = match (s.kind.as_str(), s.parts) {
                ("POS", None) => Motion::Pos,
                ("POSA", None) => Motion::Posa,
                ("POSP", Some((length, halves))) if length > 0.0 => Motion::Posp(Parts { length, halves }),
                _ => return Err(format!("positioning axis {}: kind {} not known", s.axis, s.kind)),
            };
            if !(s.end.is_finite() && s.feed.is_finite() && s.feed > 0.0) {
                return Err(format!("positioning axis {}: end {} at feed {}", s.axis, s.end, s.feed));
            }
            starts.push((k, s.end, s.feed, motion));
        }
        for (k, end, feed, motion) in starts {
            self.start_program_positioning(k, end, feed, motion);
        }
        Ok(())
    }

    /// Hands the axes of `mask` back to the planner, standing where they are.
    pub(super) fn release_positioning_axes(&mut self, mask: u32) {
        let p = &mut self.positioning;
        for k in 0..MAX_CHANNEL_AXES {
            if p.active & mask & (1 << k) != 0
                && let Some(t) = p.axes[k].take()
            {
                self.planner.place_axis(k, t.position);
                self.machine[k] = t.position;
            }
        }
        p.active &= !mask;
        p.moving &= !mask;
        p.command &= !mask;
        if mask == u32::MAX {
            p.command_feed = [0.0; MAX_CHANNEL_AXES];
            p.speeds = [0.0; MAX_CHANNEL_AXES];
        }
    }

    /// The path's move in execution moves a command axis of a synchronized action: alarm
    /// 20141 (the axis belongs to the action until the program ends).
    fn check_command_axes(&mut self) {
        let command = self.positioning.command;
        let Some(mv) = self.planner.front().filter(|_| !self.planner.is_empty()) else { return };
        if let Some(k) = (0..MAX_CHANNEL_AXES).find(|&k| command & (1 << k) != 0 && mv.path.start[k] != mv.path.end[k])
        {
            // The planner may have entered the move in this cycle, before the list follows.
            let line = self.in_planner.iter().find(|(t, _)| *t == mv.tag).map_or(0, |(_, m)| m.line);
            let name = self.cfg.program_axis_name(k).to_string();
            self.raise(Alarm::sync_axis_type(Some(line), &name));
        }
    }

    /// A WAITP (or a POS block's end) at the head of the items: true while it must wait.
    /// `strict`: a path block programs the axes, which must have arrived (alarm 14092).
    pub(super) fn wait_positioning(&mut self, axes: u32, strict: bool, line: u32) -> bool {
        if !self.positioning.moving(axes) {
            self.positioning.waited &= !axes;
            return false;
        }
        if strict {
            let k = (0..MAX_CHANNEL_AXES).find(|&k| self.positioning.moving(1 << k)).unwrap_or(0);
            let name = self.cfg.program_axis_name(k).to_string();
            self.raise(Alarm::wrong_axis_type(line, &name));
            return false;
        }
        self.positioning.waited |= axes;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::Travel;

    #[test]
    fn a_travel_stops_exactly_on_its_target_within_the_ideal_time() {
        // 5 mm at 1000 mm/min (16.67 mm/s) with 3000 mm/s²: ramp 5.6 ms, ideal time
        // 5/16.67 + 16.67/3000 = 0.3056 s = 76.4 cycles of 4 ms.
        let mut t = Travel {
            position: 0.0,
            velocity: 0.0,
            target: -5.0,
            feed: 1000.0 / 60.0,
            accel: 3000.0,
            parts: None,
            motion: None,
            swing: None,
        };
        let mut n = 0;
        while !t.step(0.004, false) {
            n += 1;
            assert!(t.velocity.abs() <= 1000.0 / 60.0 + 1e-9);
            assert!(n < 200);
        }
        assert_eq!(t.position, -5.0);
        assert!((75..=79).contains(&n), "{n} cycles");
    }
}
