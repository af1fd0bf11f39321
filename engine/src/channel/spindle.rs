//! The spindles in the main run, one IPO cycle at a time (Function Manual S1).
//!
//! In speed control S and M3/M4/M5 set a target speed; the actual speed ramps to it with the
//! acceleration of MD35200 `$MA_GEAR_STEP_SPEEDCTRL_ACCEL` (rev/s², gear stage 1) and the
//! angle turns with it (trapezoidal integration). The target is limited by the spindle's
//! highest speed (MD35100 `$MA_SPIND_VELO_LIMIT`, MD35130 `$MA_GEAR_STEP_MAX_VELO_LIMIT[1]`),
//! the programmed limits G25/G26 and, under constant cutting speed (G96/G961), by `LIMS`.
//! Under G96/G961 the target follows the transverse axis each cycle: n = v_c·1000/(π·D), D the
//! workpiece diameter at the tool tip. In position control (SPOS, M19, G331) the spindle is a
//! rotary axis moved by the planner and this model only keeps its angle.

use crate::interp::spindles::Control;
use crate::machine_data::gears::Gears;
use crate::machine_data::{MachineConfig, MachineData};

/// What a spindle is doing, as the T/F/S display shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpindleMode {
    /// M3: clockwise (seen from the spindle's rear towards the tool or workpiece).
    M3,
    /// M4: counter-clockwise.
    M4,
    /// M5 (or reset): stopped in speed control.
    #[default]
    M5,
    /// Position control (SPOS, M19, M70, G331/G332): the spindle is moved as an axis.
    Positioning,
}

impl SpindleMode {
    /// The name the state gives the mode.
    pub fn name(self) -> &'static str {
        match self {
            SpindleMode::M3 => "M3",
            SpindleMode::M4 => "M4",
            SpindleMode::M5 => "M5",
            SpindleMode::Positioning => "SPOS",
        }
    }
}

/// One spindle in the state: the published view of [`Spindle`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpindleState {
    /// Spindle number (`$MA_SPIND_ASSIGN_TO_MACHAX`).
    pub number: u32,
    /// Actual speed in rev/min (signed: + = M3); 0 in position control when at rest.
    pub speed: f64,
    pub mode: SpindleMode,
    /// Angle in degrees, 0 ≤ angle < 360.
    pub position: f64,
    /// The channel's master spindle (MD20090, SETMS).
    pub master: bool,
    /// The gear stage engaged (M40..M45, MD35010); `None` for a spindle without gear stages.
    pub gear: Option<u8>,
    /// The spindle load symbol of the T/F/S display: the master spindle turns while the path
    /// moves at feed and the last stretch of it (a stock segment, at most 8 mm) removed
    /// material from the session's stock. Not a load value: NCTwin models no cutting forces.
    pub cutting: bool,
    /// The spindle is in position control: SPCON until SPCOF, or moved as an axis (SPOS,
    /// M19, M70, G331/G332). Machine-builder programs switch with SPCON before they orient.
    pub position_control: bool,
}

/// Constant cutting speed as the main run evaluates it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Css {
    /// Cutting speed in m/min.
    pub cutting_speed: f64,
    /// +1 M3, −1 M4, 0 stopped.
    pub direction: f64,
    /// Channel axis of the transverse axis.
    pub transverse: usize,
    /// Machine position of the turning centre on the transverse axis (workpiece X0).
    pub centre: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub(super) struct Spindle {
    /// Channel axis of the spindle.
    pub axis: usize,
    /// Current speed in rev/min (+ = M3, - = M4).
    pub speed: f64,
    target: f64,
    /// Acceleration in rev/min per second.
    accel: f64,
    /// Highest speed of the spindle (machine data), rev/min.
    max_speed: f64,
    /// Angle in degrees (not wrapped).
    pub position: f64,
    /// Angle in the cycle before (for the thread start angle).
    previous: f64,
    /// Position control after SPOS: the spindle is a rotary axis moved by the planner.
    pub axis_mode: bool,
    /// SPCON: speed control in a closed position loop, until SPCOF.
    position_control: bool,
    /// In position control: the speed the planner moved it at in the last cycle (rev/min,
    /// signed), for the display only.
    axis_speed: f64,
    /// Programmed speed before the override (signed).
    programmed: f64,
    override_factor: f64,
    /// G25 lower and G26 upper speed limit (rev/min).
    lower: f64,
    upper: f64,
    /// LIMS: upper limit under constant cutting speed.
    lims: f64,
    pub css: Option<Css>,
    /// The gear stage engaged (1..=5) and the spindle's stages (`machine_data/gears.rs`).
    gear: u8,
    gears: Gears,
    /// MD35100 `$MA_SPIND_VELO_LIMIT`: the highest speed in any stage.
    velo_limit: f64,
    /// MD35140 of the stage engaged: the lowest speed while turning.
    min_speed: f64,
}

impl Spindle {
    /// The published view: `planner_angle` is the spindle's axis position, which is its
    /// angle while in position control.
    pub fn state(&self, number: u32, master: bool, planner_angle: f64) -> SpindleState {
        let (mode, speed, angle) = if self.axis_mode {
            (SpindleMode::Positioning, self.axis_speed, planner_angle)
        } else {
            // A spindle braking after M5 (target 0) shows M5 at once.
            let mode = if self.target > 0.0 {
                SpindleMode::M3
            } else if self.target < 0.0 {
                SpindleMode::M4
            } else {
                SpindleMode::M5
            };
            (mode, self.speed, self.position)
        };
        let gear = (self.gears.count > 0).then_some(self.gear);
        let position_control = self.position_control || self.axis_mode;
        SpindleState {
            number,
            speed,
            mode,
            position: angle.rem_euclid(360.0),
            master,
            gear,
            cutting: false,
            position_control,
        }
    }

    /// The programmed speed before the override (signed: + = M3), 0 after M5.
    pub fn programmed(&self) -> f64 {
        self.programmed
    }

    pub fn is_turning(&self) -> bool {
        self.speed != 0.0 || self.target != 0.0
    }

    pub fn set_speed(&mut self, rpm: f64) {
        self.programmed = rpm;
        self.css = None;
        self.retarget(rpm.abs());
    }

    /// The target from an unsigned speed `n`: override, then the limits.
    fn retarget(&mut self, n: f64) {
        let sign = if self.css.is_some() { self.css.map_or(0.0, |c| c.direction) } else { self.programmed.signum() };
        if n == 0.0 || sign == 0.0 {
            self.target = 0.0;
            return;
        }
        let mut upper = self.max_speed.min(self.upper);
        if self.css.is_some() {
            upper = upper.min(self.lims);
        }
        let lower = self.lower.max(self.min_speed);
        let n = (n * self.override_factor).min(upper).max(lower.min(upper));
        self.target = sign * n;
    }

    /// SPOS: stops where it is; from now on the planner moves it.
    pub fn enter_axis_mode(&mut self, angle: f64) {
        self.stop_now();
        self.axis_mode = true;
        self.previous = angle;
        self.axis_speed = 0.0;
    }

    /// M3/M4/M5 after SPOS: speed control again, from the angle the planner left it at.
    pub fn leave_axis_mode(&mut self, angle: f64) {
        if self.axis_mode {
            self.axis_mode = false;
            self.position = angle;
            self.previous = angle;
        }
    }

    /// Spindle override (1.0 = 100 %): the speed follows at once, within the acceleration.
    pub fn set_override(&mut self, factor: f64) {
        self.override_factor = factor;
        if self.css.is_none() {
            self.retarget(self.programmed.abs());
        }
    }

    pub fn stop_now(&mut self) {
        self.speed = 0.0;
        self.target = 0.0;
        self.programmed = 0.0;
        self.css = None;
    }

    /// A spindle command of the program other than a plain speed (see [`Control`]).
    pub fn control(&mut self, c: &Control) {
        match *c {
            Control::Limits { lower, upper, lims, .. } => {
                self.lower = lower;
                self.upper = upper;
                self.lims = lims;
                if self.css.is_none() {
                    self.retarget(self.programmed.abs());
                }
            }
            Control::Css { cutting_speed, direction, transverse, centre, .. } => {
                self.css = Some(Css { cutting_speed, direction: f64::from(direction), transverse, centre });
                self.programmed = f64::from(direction);
            }
            Control::ThreadStart { .. }
            | Control::FeedReference { .. }
            | Control::Gear { .. }
            | Control::Master { .. }
            | Control::PositionControl { .. } => {}
        }
    }

    /// M40..M45 reached the main run: engages gear stage `stage`. The spindle brakes to a
    /// standstill first (the simulated PLC then changes the gear at once) and afterwards
    /// returns to its programmed speed within the new stage's limits. False while braking:
    /// the block change waits, as the control's does for the PLC.
    pub fn change_gear(&mut self, stage: u8) -> bool {
        if stage == self.gear {
            return true;
        }
        if self.speed != 0.0 {
            self.target = 0.0;
            return false;
        }
        self.engage(stage);
        if self.css.is_none() {
            self.retarget(self.programmed.abs());
        }
        true
    }

    /// Takes over the limits and acceleration of gear stage `stage`.
    fn engage(&mut self, stage: u8) {
        let st = *self.gears.stage(stage);
        self.gear = stage;
        self.max_speed = self.velo_limit.min(st.limit_max);
        self.min_speed = st.limit_min;
        // rev/s² → rev/min per s.
        self.accel = st.accel * 60.0;
    }

    /// Whether the spindle's angle passed `angle` (degrees, modulo 360) in the last cycle.
    pub fn passed(&self, angle: f64) -> bool {
        let turns = |p: f64| ((p - angle) / 360.0).floor();
        let (now, before) = (turns(self.position), turns(self.previous));
        (self.speed > 0.0 && now > before) || (self.speed < 0.0 && now < before)
    }

    /// Constant cutting speed: the target from the transverse axis' position (out of the
    /// plain cycle's code).
    #[inline(never)]
    fn follow_diameter(&mut self, c: Css, machine: &[f64]) {
        let diameter = 2.0 * (machine[c.transverse] - c.centre).abs();
        let n = if diameter > 1e-9 { c.cutting_speed * 1000.0 / (std::f64::consts::PI * diameter) } else { f64::MAX };
        self.retarget(n);
    }

    /// One IPO cycle: under constant cutting speed the target from the transverse axis'
    /// machine position `machine`, then the ramp and the angle.
    #[inline]
    pub fn step(&mut self, dt: f64, machine: &[f64]) {
        // At rest or at constant speed in speed control (the common cases): only the angle
        // advances, inline. The ramp's trapezoid at constant speed s is (s + s)·0.5·6·dt,
        // exactly s·6·dt, so the angle is the same to the bit as the ramp would make it.
        if !self.axis_mode && self.css.is_none() && self.speed == self.target {
            self.previous = self.position;
            if self.speed != 0.0 {
                self.position += self.speed * 6.0 * dt;
                if self.position.abs() > 3.6e9 {
                    self.wrap();
                }
            }
            return;
        }
        self.step_moving(dt, machine);
    }

    /// Keeps a long-turning spindle's angle small (whole turns taken off both angles).
    #[cold]
    #[inline(never)]
    fn wrap(&mut self) {
        let wrap = self.position - self.position.rem_euclid(360.0);
        self.position -= wrap;
        self.previous -= wrap;
    }

    /// [`Spindle::step`] of a turning, ramping or positioning spindle (out of line: the IPO
    /// cycle's own code stays small).
    #[inline(never)]
    fn step_moving(&mut self, dt: f64, machine: &[f64]) {
        if self.axis_mode {
            // rev/min from the axis' travel in °: ×60/360.
            let angle = machine[self.axis];
            self.axis_speed = (angle - self.previous) / dt / 6.0;
            self.previous = angle;
            return;
        }
        if let Some(c) = self.css {
            self.follow_diameter(c, machine);
        }
        let dv = self.accel * dt;
        let before = self.speed;
        self.speed = if self.target > self.speed {
            (self.speed + dv).min(self.target)
        } else {
            (self.speed - dv).max(self.target)
        };
        self.previous = self.position;
        // Trapezoidal integration of the angle: rev/min → deg/s is ×6.
        self.position += (before + self.speed) * 0.5 * 6.0 * dt;
        if self.position.abs() > 3.6e9 {
            self.wrap();
        }
    }
}

/// One spindle per channel axis whose machine axis is a spindle, with its machine data.
pub(super) fn for_config(cfg: &MachineConfig, data: &MachineData) -> Vec<Spindle> {
    (0..cfg.channel_axes.len())
        .filter(|&k| cfg.axis(k).spindle.is_some())
        .map(|k| {
            let m = cfg.channel_axes[k].machine_axis;
            let mut s = Spindle {
                axis: k,
                speed: 0.0,
                target: 0.0,
                accel: 0.0,
                max_speed: 0.0,
                position: 0.0,
                previous: 0.0,
                axis_mode: false,
                position_control: false,
                axis_speed: 0.0,
                programmed: 0.0,
                override_factor: 1.0,
                lower: 0.0,
                upper: f64::INFINITY,
                lims: f64::INFINITY,
                css: None,
                gear: 1,
                gears: cfg.gears.get(&k).cloned().unwrap_or_default(),
                velo_limit: data.num("$MA_SPIND_VELO_LIMIT", m, 0),
                min_speed: 0.0,
            };
            // Gear stage 1 after power on.
            s.engage(1);
            s
        })
        .collect()
}

impl super::Channel {
    /// One IPO cycle of every spindle; the master spindle's actual speed is what moves with a
    /// feed per revolution follow.
    pub(super) fn step_spindles(&mut self) {
        let dt = self.cfg.ipo_cycle;
        let mut rate = 0.0;
        let reference = self.feed_reference.map_or(self.master_spindle, |(k, _)| Some(k));
        for s in &mut self.spindles {
            s.step(dt, &self.machine);
            if Some(s.axis) == reference {
                rate = if s.axis_mode { s.axis_speed.abs() } else { s.speed.abs() } / 60.0;
            }
        }
        if let Some((k, previous)) = self.feed_reference.filter(|&(k, _)| self.cfg.axis(k).spindle.is_none()) {
            rate = self.fpr_axis_rate(k, previous, dt);
        }
        self.planner.set_spindle_rate(rate);
    }

    /// FPR on a rotary axis that is no spindle: its actual speed in rev/s (out of line).
    #[inline(never)]
    fn fpr_axis_rate(&mut self, k: usize, previous: f64, dt: f64) -> f64 {
        let now = self.machine[k];
        self.feed_reference = Some((k, now));
        (now - previous).abs() / 360.0 / dt
    }

    /// A spindle command of the program; false while it has to wait (a thread's start angle).
    pub(super) fn spindle_control(&mut self, c: &Control) -> bool {
        match *c {
            Control::FeedReference { axis } => {
                self.feed_reference = Some((axis, self.machine[axis]));
                return true;
            }
            Control::Master { axis } => {
                self.master_spindle = Some(axis);
                return true;
            }
            _ => {}
        }
        let Some(s) = self.spindles.iter_mut().find(|s| s.axis == c.axis()) else { return true };
        match *c {
            Control::ThreadStart { angle, .. } => s.passed(angle),
            Control::Gear { stage, .. } => s.change_gear(stage),
            Control::PositionControl { on, .. } => {
                if !on {
                    // SPCOF ends an axis mode as well: speed control, stopped.
                    let angle = self.planner.position()[s.axis];
                    s.leave_axis_mode(angle);
                }
                s.position_control = on;
                true
            }
            _ => {
                let angle = self.planner.position()[s.axis];
                s.leave_axis_mode(angle);
                s.control(c);
                true
            }
        }
    }
}
