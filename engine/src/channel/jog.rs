//! JOG: one axis at a time, continuous (until released) or by an increment, stopping at the
//! software limits.

use super::{Channel, CommandError, JogRequest, Mode, MoveMeta, Status};
use crate::alarm::Alarm;
use crate::motion::{AxisLimit, Feed, Move, Path};

impl Channel {
    /// Starts a JOG motion of one axis (JOG mode only).
    pub fn jog(&mut self, req: &JogRequest) -> Result<(), CommandError> {
        if self.mode != Mode::Jog {
            return Err(CommandError::WrongMode(self.mode.as_str(), "JOG needs JOG mode"));
        }
        if self.status == Status::Alarm {
            return Err(CommandError::AlarmActive);
        }
        if self.is_busy() {
            return Err(CommandError::Busy("an axis is moving"));
        }
        if req.direction != 1 && req.direction != -1 {
            return Err(CommandError::Invalid(format!("direction must be 1 or -1, not {}", req.direction)));
        }
        let k = self.cfg.program_axis(&req.axis).ok_or_else(|| CommandError::UnknownAxis(req.axis.clone()))?;
        let ax = self.cfg.axis(k).clone();
        if ax.spindle.is_some() {
            return Err(CommandError::Invalid(format!("{} is a spindle", req.axis)));
        }
        let start = *self.planner.position();
        let dir = req.direction as f64;
        let target = match req.increment {
            Some(inc) if inc.is_finite() && inc > 0.0 => start[k] + dir * inc,
            Some(inc) => return Err(CommandError::Invalid(format!("increment must be positive, not {inc}"))),
            None if ax.modulo.is_some() => start[k] + dir * 1e9,
            None => {
                if dir > 0.0 {
                    ax.limit_plus
                } else {
                    ax.limit_minus
                }
            }
        };
        // Without modulo, JOG stops at the software limit.
        let target = if ax.modulo.is_some() { target } else { target.clamp(ax.limit_minus, ax.limit_plus) };
        if (target - start[k]).abs() < 1e-9 {
            self.raise(Alarm::rests_on_software_limit(&ax.name, dir > 0.0));
            return Ok(());
        }
        let mut end = start;
        end[k] = target;
        let velocity = if req.rapid { ax.jog_rapid_velocity } else { ax.jog_velocity }.min(ax.max_velocity);
        let length = (target - start[k]).abs();
        let mv = Move::new(
            Path::line(start, end),
            length,
            Feed::Path(velocity),
            &AxisLimit::for_channel(&self.cfg),
            true,
            self.next_tag,
        );
        self.push_move(mv, MoveMeta { line: 0, offsets: self.offsets.clone(), machine_space: false });
        self.jog_axis = Some(k);
        self.status = Status::Running;
        Ok(())
    }

    /// Releases the JOG key: the axis brakes to standstill.
    pub fn jog_stop(&mut self) {
        if self.jog_axis.is_some() {
            self.planner.stop_and_flush();
        }
    }

    pub(super) fn finish_jog_if_done(&mut self) {
        let Some(k) = self.jog_axis else { return };
        if !self.planner.is_idle() {
            return;
        }
        self.jog_axis = None;
        if self.status == Status::Running {
            self.status = Status::Idle;
        }
        let ax = self.cfg.axis(k);
        let p = self.planner.position()[k];
        if ax.modulo.is_none() && (p >= ax.limit_plus || p <= ax.limit_minus) {
            let name = ax.name.clone();
            self.raise(Alarm::rests_on_software_limit(&name, p >= ax.limit_plus));
        }
        self.interp.sync_position(self.planner.position());
    }
}
