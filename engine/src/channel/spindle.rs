//! Spindles in speed mode: S and M3/M4/M5 set a target speed; the spindle ramps to it with its
//! axis' acceleration and its position turns with it (shown modulo 360°).

use crate::machine_data::MachineConfig;

#[derive(Debug, Clone, PartialEq)]
pub(super) struct Spindle {
    /// Channel axis of the spindle.
    pub axis: usize,
    /// Current speed in rev/min (+ = M3, - = M4).
    pub speed: f64,
    target: f64,
    /// Acceleration in rev/min per second.
    accel: f64,
    max_speed: f64,
    /// Angle in degrees (not wrapped).
    pub position: f64,
    /// Position control after SPOS: the spindle is a rotary axis moved by the planner.
    pub axis_mode: bool,
    /// Programmed speed before the override.
    programmed: f64,
    override_factor: f64,
}

impl Spindle {
    pub fn is_turning(&self) -> bool {
        self.speed != 0.0 || self.target != 0.0
    }

    pub fn set_speed(&mut self, rpm: f64) {
        self.programmed = rpm;
        self.target = (rpm * self.override_factor).clamp(-self.max_speed, self.max_speed);
    }

    /// SPOS: stops where it is; from now on the planner moves it.
    pub fn enter_axis_mode(&mut self) {
        self.stop_now();
        self.axis_mode = true;
    }

    /// M3/M4/M5 after SPOS: speed control again, from the angle the planner left it at.
    pub fn leave_axis_mode(&mut self, angle: f64) {
        if self.axis_mode {
            self.axis_mode = false;
            self.position = angle;
        }
    }

    /// Spindle override (1.0 = 100 %): the speed follows at once, within the acceleration.
    pub fn set_override(&mut self, factor: f64) {
        self.override_factor = factor;
        self.set_speed(self.programmed);
    }

    pub fn stop_now(&mut self) {
        self.speed = 0.0;
        self.target = 0.0;
        self.programmed = 0.0;
    }

    pub fn step(&mut self, dt: f64) {
        if self.axis_mode {
            return;
        }
        let dv = self.accel * dt;
        let before = self.speed;
        self.speed = if self.target > self.speed {
            (self.speed + dv).min(self.target)
        } else {
            (self.speed - dv).max(self.target)
        };
        // Trapezoidal integration of the angle: rev/min → deg/s is ×6.
        self.position += (before + self.speed) * 0.5 * 6.0 * dt;
        if self.position.abs() > 3.6e9 {
            self.position = self.position.rem_euclid(360.0);
        }
    }
}

/// One spindle per channel axis whose machine axis is a spindle.
pub(super) fn for_config(cfg: &MachineConfig) -> Vec<Spindle> {
    (0..cfg.channel_axes.len())
        .filter(|&k| cfg.axis(k).spindle.is_some())
        .map(|k| {
            let ax = cfg.axis(k);
            Spindle {
                axis: k,
                speed: 0.0,
                target: 0.0,
                // deg/s² → rev/min per s: /360 · 60.
                accel: ax.max_accel / 6.0,
                max_speed: ax.max_velocity / 6.0,
                position: 0.0,
                axis_mode: false,
                programmed: 0.0,
                override_factor: 1.0,
            }
        })
        .collect()
}
