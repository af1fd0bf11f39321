//! Reference point state per axis and the NC start lock for unreferenced axes.
//!
//! Machine data (real numbers and names; one default differs from the control, see below):
//! - MD34210 `$MA_ENC_REFP_STATE`: 2 = "absolute encoder adjusted", the axis is referenced from
//!   power on; 0 (or 1) = the axis starts unreferenced, as with an incremental encoder. The
//!   control's default is 0; this simulation's default is 2, so every preset starts referenced.
//! - MD20700 `$MC_REFP_NC_START_LOCK` (default TRUE, as on the control): NC start of a program
//!   (AUTO, MDA) is refused with alarm 16905 while an axis that needs it is unreferenced.
//! - MD34110 `$MA_REFP_CYCLE_NR`: -1 = the axis need not be referenced for NC start; 0 and
//!   1..15 (the order of channel-specific referencing) = it must be.
//!
//! Referencing (`reference_axes`) happens in JOG mode in reset state: axes with an incremental
//! measuring system (MD34200 ENC_REFP_MODE = 1) travel the reference point approach
//! (`approach.rs`), the others are referenced at once. Spindles count as referenced. JOG of
//! unreferenced axes is allowed, as on the control.

pub(super) mod approach;

use super::{Channel, CommandError, Mode, Status};
use crate::alarm::{Alarm, Clear};
use crate::machine_data::{MachineConfig, MachineData};

/// Reference state of each channel axis from the machine data (power on).
pub(super) fn initial_state(data: &MachineData, cfg: &MachineConfig) -> Vec<bool> {
    (0..cfg.channel_axes.len())
        .map(|k| {
            let m = cfg.channel_axes[k].machine_axis;
            cfg.machine_axes[m].spindle.is_some() || data.num("$MA_ENC_REFP_STATE", m, 0) == 2.0
        })
        .collect()
}

impl Channel {
    /// After new machine data: axes that were referenced stay referenced.
    pub(super) fn keep_reference_state(&mut self, old: &Channel) {
        for k in 0..self.cfg.channel_axes.len() {
            let name = &self.cfg.axis(k).name;
            let before = (0..old.cfg.channel_axes.len()).find(|&j| old.cfg.axis(j).name == *name);
            if before.is_some_and(|j| old.referenced.get(j) == Some(&true)) {
                self.referenced[k] = true;
            }
        }
    }

    /// Reference point state of every machine axis of the channel, by machine axis name in
    /// machine axis order.
    pub fn reference_state(&self) -> Vec<(String, bool)> {
        let mut axes: Vec<(usize, (String, bool))> = (0..self.cfg.channel_axes.len())
            .map(|k| (self.cfg.channel_axes[k].machine_axis, (self.cfg.axis(k).name.clone(), self.referenced[k])))
            .collect();
        axes.sort_by_key(|(m, _)| *m);
        axes.into_iter().map(|(_, a)| a).collect()
    }

    /// References the named axis (machine, geometry or channel axis name), or every
    /// unreferenced axis when `axis` is `None`. JOG mode, reset state. Axes with an incremental
    /// measuring system travel the reference point approach (`approach.rs`); the others are
    /// referenced at once.
    pub fn reference_axes(&mut self, axis: Option<&str>) -> Result<(), CommandError> {
        if self.mode != Mode::Jog {
            return Err(CommandError::WrongMode(self.mode.as_str(), "referencing is a JOG function (REF)"));
        }
        if self.is_busy() {
            return Err(CommandError::Busy("an axis is moving"));
        }
        if self.status != Status::Idle {
            return Err(CommandError::Busy(
                "referencing needs the reset state (a program is interrupted or an alarm is active)",
            ));
        }
        let axes: Vec<usize> = match axis {
            None => {
                let mut axes: Vec<usize> = (0..self.cfg.channel_axes.len()).filter(|&k| !self.referenced[k]).collect();
                let order =
                    |k: &usize| self.data.num("$MA_REFP_CYCLE_NR", self.cfg.channel_axes[*k].machine_axis, 0) as i64;
                axes.sort_by_key(|k| (order(k), *k));
                axes
            }
            Some(name) => {
                let cfg = &self.cfg;
                let k = (0..cfg.channel_axes.len())
                    .find(|&k| cfg.axis(k).name.eq_ignore_ascii_case(name))
                    .or_else(|| cfg.program_axis(name))
                    .ok_or_else(|| CommandError::UnknownAxis(name.to_string()))?;
                vec![k]
            }
        };
        let (approach, at_once): (Vec<usize>, Vec<usize>) = axes.into_iter().partition(|&k| self.needs_approach(k));
        for k in at_once {
            self.referenced[k] = true;
        }
        self.start_referencing(approach);
        Ok(())
    }

    /// Marks every axis referenced: for a copy of the channel that only traces a program (the
    /// HMI's preview, like Operate's simulation, runs whatever the machine's reference state).
    pub fn reference_all_for_simulation(&mut self) {
        self.referenced.iter_mut().for_each(|r| *r = true);
    }

    /// The NC start lock (MD20700): alarm 16905 and a refusal while an axis that must be
    /// referenced (MD34110 not -1) is not.
    pub(super) fn check_start_lock(&mut self) -> Result<(), CommandError> {
        if self.data.num("$MC_REFP_NC_START_LOCK", 0, 0) == 0.0 {
            return Ok(());
        }
        let missing = (0..self.cfg.channel_axes.len()).find(|&k| {
            let m = self.cfg.channel_axes[k].machine_axis;
            !self.referenced[k] && self.data.num("$MA_REFP_CYCLE_NR", m, 0) != -1.0
        });
        let Some(k) = missing else { return Ok(()) };
        let name = self.cfg.axis(k).name.clone();
        self.notify_alarm(Alarm {
            number: 16905,
            message: format!("Channel 1 action NC start not allowed: axis {name} is not referenced"),
            line: None,
            clear: Clear::Cancel,
        });
        Err(CommandError::WrongMode(
            self.mode.as_str(),
            "NC start needs every axis referenced (alarm 16905, MD20700 REFP_NC_START_LOCK); reference the axes in JOG mode",
        ))
    }
}
