//! The motion actions of synchronized actions (Function Manual "Synchronized actions", command
//! axes and spindles): `POS[ax]=`, `MOV[ax]=1/-1/0`, `FA[ax]=` move the axis on the
//! positioning-axis interpolator (`positioning_axes.rs`), `SPOS[n]=` positions a spindle the same
//! way, `M3`/`M4`/`M5` and `S` act on the spindle model (`spindle.rs`) in the cycle they run.
//!
//! Modelled as follows where the manuals leave room:
//! - A command axis must not be a path axis of the block in execution: `POS`/`MOV` on an axis
//!   the running move moves raise alarm 20141; a spindle as an axis likewise (at compile time).
//! - `POS[ax]=v` is in the workpiece system of the axis alone: the active frame's translation
//!   and scale of that axis and the tool length on it (as `$AA_IW` reads it back); a rotation of
//!   the frame is not applied (the manuals give command axes no geometry coupling). `IC(v)` is
//!   relative to where the axis stands; `DC`/`ACP`/`ACN` (and a plain value on a modulo axis)
//!   take the modulo way as in a program. An axis of the active transformation (17610) or a
//!   geometry axis under a rotated frame (16430) cannot be a command axis, as it cannot be a
//!   program's positioning axis (`path_control/positioning.rs`).
//! - A command axis stays with the positioning interpolator until the program ends (the
//!   interpreter has not prepared its position): it then brakes and the path takes it over.
//! - `S` from an action sets the speed of a turning spindle at once (within its ramp); of a
//!   stopped one it is kept for the next `M3`/`M4` of an action. `M3`/`M4`/`M5` also go out to
//!   the PLC like any M function. `SPOS` stops a turning spindle where it is (as the program's
//!   SPOS does here) and positions it at MD35300 `$MA_SPIND_POSCTRL_VELO`, the short way.

use super::Channel;
use crate::alarm::Alarm;
use crate::interp::synchronized::compile::CommandKind;
use crate::interp::synchronized::flat::Fault;
use crate::lang::CoordMode;

impl Channel {
    /// Runs a command-axis action of a synchronized action defined at `line`.
    pub(super) fn sync_command(
        &mut self,
        kind: CommandKind,
        k: usize,
        v: f64,
        mode: Option<CoordMode>,
        line: u32,
    ) -> Result<(), Fault> {
        if !v.is_finite() {
            return Err(Box::new(Alarm::value_out_of_range(line, "command axis value")));
        }
        if matches!(kind, CommandKind::Pos | CommandKind::Mov) && self.path_moves_axis(k) {
            return Err(Box::new(Alarm::sync_axis_type(Some(line), self.cfg.program_axis_name(k))));
        }
        if matches!(kind, CommandKind::Pos | CommandKind::Mov) {
            // As for a program's positioning axis: 17610 under a transformation, 16430 rotated.
            let (trafo, frame) = (self.offsets.trafo.as_ref(), &self.offsets.frame);
            crate::interp::path_control::positioning::refused(k, trafo, frame, &self.cfg, line).map_err(Box::new)?;
        }
        match kind {
            CommandKind::Fa => {
                if v <= 0.0 {
                    return Err(Box::new(Alarm::value_out_of_range(line, &format!("FA={v}"))));
                }
                // mm/min (deg/min) → per second.
                self.set_command_feed(k, v / 60.0);
            }
            CommandKind::Pos => {
                let current = self.positioning.position(k).unwrap_or(self.machine[k]);
                let target = self.command_target(k, v, mode, current);
                let feed = self.command_feed(k);
                self.start_positioning(k, target, feed, true);
            }
            CommandKind::Mov => {
                if v == 0.0 {
                    self.stop_positioning(k);
                } else {
                    let feed = self.command_feed(k);
                    self.start_positioning(k, v.signum() * f64::INFINITY, feed, true);
                }
            }
            CommandKind::Spos => self.sync_spos(k, v, mode),
        }
        Ok(())
    }

    /// Whether the move the path is executing moves channel axis `k`.
    fn path_moves_axis(&self, k: usize) -> bool {
        !self.planner.is_empty() && self.planner.front().is_some_and(|m| m.path.start[k] != m.path.end[k])
    }

    /// The machine position `POS[ax]=v` asks for (see the module doc).
    fn command_target(&self, k: usize, v: f64, mode: Option<CoordMode>, current: f64) -> f64 {
        let frame = &self.offsets.frame;
        if mode == Some(CoordMode::Ic) {
            return current + v * frame.factor[k];
        }
        let target = v * frame.factor[k] + frame.trans[k] + self.offsets.tool[k];
        match self.cfg.axis(k).modulo {
            Some((start, range)) => {
                let wrapped = start + (target - start).rem_euclid(range);
                crate::interp::modulo_target(current, wrapped, range, mode)
            }
            None => target,
        }
    }

    /// `SPOS[n]=angle` from an action: the spindle into position control, then to the angle.
    fn sync_spos(&mut self, k: usize, angle: f64, mode: Option<CoordMode>) {
        let Some(s) = self.spindles.iter_mut().find(|s| s.axis == k) else { return };
        if !s.axis_mode && self.positioning.position(k).is_none() {
            let at = s.position;
            s.enter_axis_mode(at);
            self.machine[k] = at;
            self.planner.place_axis(k, at);
        }
        let current = self.positioning.position(k).unwrap_or(self.machine[k]);
        let target = match mode {
            Some(CoordMode::Ic) => current + angle,
            m => crate::interp::modulo_target(current, angle.rem_euclid(360.0), 360.0, m),
        };
        // MD35300 in rev/min → deg/s.
        let feed = self.cfg.axis(k).spindle_posctrl_velo * 6.0;
        self.start_positioning(k, target, feed, true);
    }

    /// `M3`/`M4`/`M5` (M = direction, `extension` the spindle, 0 the master) or `S` from an
    /// action; other M functions are no spindle words.
    pub(super) fn sync_spindle_word(&mut self, letter: char, extension: u32, value: f64) {
        let axis = match extension {
            0 => self.cfg.master_spindle,
            n => self.cfg.channel_axes.iter().position(|c| self.cfg.machine_axes[c.machine_axis].spindle == Some(n)),
        };
        let Some(k) = axis else { return };
        let Some(i) = self.spindles.iter().position(|s| s.axis == k) else { return };
        match letter {
            'S' => {
                let v = value.abs();
                self.set_action_speed(k, v);
                let s = &mut self.spindles[i];
                if !s.axis_mode && s.programmed() != 0.0 {
                    let sign = s.programmed().signum();
                    s.set_speed(sign * v);
                }
            }
            'M' if matches!(value, 3.0 | 4.0 | 5.0) => {
                // Out of position control first (a SPOS of an action hands the axis back).
                if self.positioning.position(k).is_some() {
                    self.release_positioning_axes(1 << k);
                }
                let angle = self.machine[k];
                if self.spindles[i].programmed() != 0.0 {
                    // The speed stays for a later M3/M4 (the control keeps S beyond M5).
                    let n = self.spindles[i].programmed().abs();
                    self.set_action_speed(k, n);
                }
                let stored = self.action_speed(k);
                let s = &mut self.spindles[i];
                s.leave_axis_mode(angle);
                let n = if stored > 0.0 { stored } else { s.programmed().abs() };
                let rpm = match value as u32 {
                    3 => n,
                    4 => -n,
                    _ => 0.0,
                };
                s.set_speed(rpm);
            }
            _ => {}
        }
    }
}
