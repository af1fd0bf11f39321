//! The spindles as block preparation sees them: which one is the master spindle (MD20090,
//! changed by SETMS), and each spindle's programmed speed and direction.
//!
//! S, M3/M4/M5, SPOS, G95 and G4 S act on the master spindle; a lathe that mills with a driven
//! tool makes the tool spindle the master with `SETMS(2)` while the main spindle stands as
//! the TRANSMIT rotary axis.

use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

#[derive(Debug, Clone)]
pub(super) struct Spindles {
    /// Channel axis of the master spindle.
    master: Option<usize>,
    /// Programmed speed (rev/min) by channel axis.
    speed: [f64; MAX_CHANNEL_AXES],
    /// Programmed direction by channel axis: +1 M3, −1 M4, 0 M5 or positioned.
    direction: [i8; MAX_CHANNEL_AXES],
}

impl Spindles {
    pub fn new(cfg: &MachineConfig) -> Spindles {
        Spindles { master: cfg.master_spindle, speed: [0.0; MAX_CHANNEL_AXES], direction: [0; MAX_CHANNEL_AXES] }
    }

    /// Reset: the configured master spindle again; with `stop`, every spindle stopped (a
    /// reset), else the directions stay (program end: spindles turn on until M5 or reset).
    pub fn reset(&mut self, cfg: &MachineConfig, stop: bool) {
        self.master = cfg.master_spindle;
        if stop {
            self.direction = [0; MAX_CHANNEL_AXES];
        }
    }

    pub fn master(&self) -> Option<usize> {
        self.master
    }

    /// SETMS(n) (`Some(n)`) or SETMS (`None`, back to the configured master spindle).
    pub fn set_master(&mut self, spindle: Option<u32>, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        self.master = match spindle {
            None => cfg.master_spindle,
            Some(n) => Some(
                cfg.channel_axes.iter().position(|c| cfg.machine_axes[c.machine_axis].spindle == Some(n)).ok_or_else(
                    || Alarm::value_out_of_range(line, &format!("SETMS({n}): no spindle {n} in the channel")),
                )?,
            ),
        };
        Ok(())
    }

    /// Speed of the master spindle (0 without one).
    pub fn master_speed(&self) -> f64 {
        self.master.map_or(0.0, |k| self.speed[k])
    }

    pub fn master_direction(&self) -> i8 {
        self.master.map_or(0, |k| self.direction[k])
    }

    pub fn set_master_speed(&mut self, rpm: f64) {
        if let Some(k) = self.master {
            self.speed[k] = rpm;
        }
    }

    pub fn set_master_direction(&mut self, direction: i8) {
        if let Some(k) = self.master {
            self.direction[k] = direction;
        }
    }

    /// Whether the spindle on channel axis `axis` was programmed to turn.
    pub fn turns(&self, axis: usize) -> bool {
        self.direction[axis] != 0
    }

    /// Stops the spindle on `axis` in preparation's view (SPOS puts it in position control).
    pub fn stop(&mut self, axis: usize) {
        self.direction[axis] = 0;
    }
}
