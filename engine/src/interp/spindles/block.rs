//! A block's spindle words turned into main-run items: feed type and limits, speeds and
//! directions (with address extension), constant cutting speed, SPOS/SPOSA/M19/M70.

use super::words::Spos;
use super::{Control, FeedType, axis_of};
use crate::alarm::Alarm;
use crate::interp::modal::{MotionMode, Words};
use crate::interp::{Interpreter, Item, compensation};
use crate::lang::CoordMode;
use crate::machine_data::MachineConfig;
use crate::motion::{AxisLimit, Feed, Move, Path};

impl Interpreter {
    /// The spindle part of a block, before its motion. Returns whether the block positioned a
    /// spindle (SPOS, M19, M70).
    pub(in crate::interp) fn spindle_block(
        &mut self,
        words: &Words,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<bool, Alarm> {
        let sw = &words.spindle;
        if let Some(mode) = sw.diameter {
            self.spindles.diameter.select(mode, cfg, line)?;
        }
        for &(axis, mode) in &sw.axis_diameter {
            match axis {
                Some(k) => self.spindles.diameter.select_axis(k, mode, cfg, line)?,
                None => self.spindles.diameter.link_all(cfg),
            }
        }
        self.modal.diameter_slot = self.spindles.diameter.gcode_slot();
        self.modal.diameter_display_axes = self.spindles.diameter.display_mask();
        let was_css = self.spindles.feed_type.css();
        if let Some(t) = sw.feed_type {
            self.spindles.feed_type = t;
        } else if let Some(per_rev) = words.feed_per_rev {
            self.spindles.feed_type = if per_rev { FeedType::G95 } else { FeedType::G94 };
        }
        if let Some(k) = sw.fpr {
            self.select_fpr(k, cfg, line, out);
        }
        let css_axis_changed = sw.css_axis.is_some_and(|k| self.spindles.css_axis != Some(k));
        if sw.css_axis.is_some() {
            self.spindles.css_axis = sw.css_axis;
        }
        if words.set_master.is_some()
            && let Some(axis) = self.spindles.master()
        {
            // SETMS (already applied to preparation): the main run's master follows.
            self.trc.emit_or_defer(Item::SpindleControl { ctl: Control::Master { axis }, line }, out);
        }
        let t = self.spindles.feed_type;
        self.modal.feed_per_rev = t.per_rev();
        self.modal.feed_type_index = match t {
            FeedType::G94 | FeedType::G95 => 0,
            FeedType::G93 => 2,
            FeedType::G96 => 3,
            FeedType::G961 => 4,
            FeedType::G97 => 5,
            FeedType::G971 => 6,
        };
        if let Some(th) = sw.thread {
            self.spindles.thread = Some(th);
            self.modal.motion = MotionMode::Linear;
        } else if words.motion.is_some() {
            self.spindles.thread = None;
        }

        // G25/G26 take the block's S as the limit; LIMS the limit of constant cutting speed.
        let master = self.spindles.master();
        let mut limits = sw.lims.is_some();
        if let Some(l) = sw.lims {
            self.spindles.lims = l;
        }
        if let Some(which) = sw.limit.filter(|_| sw.work_area_limit(words).is_none()) {
            let s = words.speed.ok_or_else(|| Alarm::syntax(line, "G25/G26 need S<speed limit>"))?;
            match which {
                super::words::SpeedLimit::G25 => self.spindles.lower = s,
                super::words::SpeedLimit::G26 => self.spindles.upper = s,
            }
            limits = true;
        }
        if let Some(axis) = master.filter(|_| limits) {
            let s = &self.spindles;
            let (lower, upper, lims) = (s.lower, s.upper, s.lims);
            self.trc
                .emit_or_defer(Item::SpindleControl { ctl: Control::Limits { axis, lower, upper, lims }, line }, out);
        }

        // Speeds: S for the master spindle (the cutting speed under G96/G961), S<n>= for spindle n.
        let mut touched: [bool; crate::machine_data::registry::MAX_CHANNEL_AXES] = Default::default();
        if let Some(s) = words.speed.filter(|_| !words.dwell && sw.limit.is_none()) {
            if s < 0.0 {
                return Err(Alarm::value_out_of_range(line, &format!("S{s}")));
            }
            if let Some(k) = master {
                touched[k] = true;
                if t.css() { self.spindles.cutting_speed = s } else { self.spindles.speed[k] = s }
            }
        }
        for &(n, v) in &sw.speeds {
            let k = axis_of(cfg, n, line, &format!("S{n}="))?;
            touched[k] = true;
            if Some(k) == master && t.css() { self.spindles.cutting_speed = v } else { self.spindles.speed[k] = v }
        }
        // Gear stages (M40..M45, M40's choice for a new master speed) before the speed.
        let new_speed = master.filter(|k| touched[*k] && !t.css()).map(|k| (k, self.spindles.speed[k]));
        self.gear_block(sw.gear, new_speed, cfg, line, out)?;
        self.position_control_block(sw.position_control.as_ref(), cfg, line, out)?;
        let mut old_direction = self.spindles.direction;
        if let Some(dir) = words.spindle_dir {
            // M3/M4/M5 act on the master spindle, M<n>=3/4/5 on spindle n.
            let k = match words.spindle_ext {
                Some(n) => Some(axis_of(cfg, n, line, &format!("M{n}="))?),
                None => master,
            };
            if let Some(k) = k {
                self.spindles.direction[k] = dir;
                // M3/M4/M5 return a positioned spindle to speed control.
                self.positioned[k] = false;
                touched[k] = true;
                // A direction given anew is sent even if unchanged (a new speed may come with it).
                old_direction[k] = i8::MAX;
            }
        }
        // G96 selected or left, or its transverse axis changed (SCC): the spindle changes its
        // speed rule.
        if let Some(k) = master.filter(|_| t.css() != was_css || (t.css() && css_axis_changed)) {
            touched[k] = true;
            if !t.css() && was_css {
                // G97/G971/G94/G95 after G96: the speed reached at the block's start point stays.
                self.spindles.speed[k] = self.css_speed(cfg, &self.pos).unwrap_or(0.0);
            }
        }
        for k in (0..cfg.channel_axes.len()).filter(|&k| touched[k]) {
            let direction = self.spindles.direction[k];
            if direction == old_direction[k] && direction == 0 {
                continue;
            }
            let item = match self.turning_centre(cfg).filter(|_| Some(k) == master && t.css()) {
                Some((transverse, centre)) => {
                    let cutting_speed = self.spindles.cutting_speed;
                    Item::SpindleControl {
                        ctl: Control::Css { axis: k, cutting_speed, direction, transverse, centre },
                        line,
                    }
                }
                None => Item::Spindle { axis: k, rpm: direction as f64 * self.spindles.speed[k], line },
            };
            // Before the block's motion, after the held compensated move.
            self.trc.emit_or_defer(item, out);
        }

        // SPOS first; axis words of the same block then move the path (one after the other
        // here, where the control runs the two side by side).
        if sw.axis_mode {
            let axis = master.ok_or_else(|| Alarm::unknown_name(line, "M70 (no master spindle)"))?;
            let angle = self.spindle_angles[axis].rem_euclid(360.0);
            self.positioned[axis] = true;
            self.spindles.stop(axis);
            self.pos[axis] = angle;
            self.trc.emit_or_defer(Item::SpindleToAxis { axis, angle, line }, out);
        }
        if let Some(spos) = sw.spos {
            let (mv, feed, axis) = self.spindle_position(spos, cfg, line)?;
            // With compensation active SPOS is a block without motion in the plane.
            self.trc.emit_or_defer(Item::SpindleToAxis { axis, angle: mv.path.start[axis], line }, out);
            let offsets = self.shared_offsets();
            let approach = self.modal.approach;
            let prepared = compensation::trc::Prepared { mv, feed, line, offsets, approach, corner: None };
            let comp = self.compensation(cfg, words, line)?;
            self.trc.push(prepared, comp, &AxisLimit::for_channel(cfg), out)?;
        }
        Ok(sw.spos.is_some() || sw.axis_mode)
    }

    /// SPOS/SPOSA/M19: stops the spindle where it is, switches it to position control and
    /// moves it to the target: DC (and a plain value) the short way, ACP in the positive, ACN
    /// in the negative direction, IC by the value.
    fn spindle_position(&mut self, spos: Spos, cfg: &MachineConfig, line: u32) -> Result<(Move, Feed, usize), Alarm> {
        let axis = match spos.spindle {
            Some(n) => axis_of(cfg, n, line, "SPOS")?,
            None => self.spindles.master().ok_or_else(|| Alarm::unknown_name(line, "SPOS (no master spindle)"))?,
        };
        let start_angle =
            if self.positioned[axis] { self.pos[axis] } else { self.spindle_angles[axis].rem_euclid(360.0) };
        self.positioned[axis] = true;
        self.spindles.stop(axis);
        let mut start = self.pos;
        start[axis] = start_angle;
        let mut end = start;
        let target = spos.angle.rem_euclid(360.0);
        let forward = (target - start_angle).rem_euclid(360.0);
        end[axis] = start_angle
            + match spos.mode {
                Some(CoordMode::Ic) => spos.angle,
                Some(CoordMode::Acp) => forward,
                Some(CoordMode::Acn) => forward - if forward > 0.0 { 360.0 } else { 0.0 },
                _ if forward > 180.0 => forward - 360.0,
                _ => forward,
            };
        self.pos = end;
        let length = (end[axis] - start[axis]).abs();
        let path = Path::line(start, end);
        // Position control moves at MD35300 `$MA_SPIND_POSCTRL_VELO` (rev/min → °/s).
        let feed = Feed::Path(cfg.axis(axis).spindle_posctrl_velo * 6.0);
        Ok((Move::new(path, length, feed, &AxisLimit::for_channel(cfg), true, line), feed, axis))
    }

    /// The master spindle speed `G4 S` counts revolutions at (rev/min): the programmed speed,
    /// under constant cutting speed (G96/G961) the speed at the diameter where the tool
    /// stands, within LIMS and G26.
    pub(in crate::interp) fn dwell_speed(&self, cfg: &MachineConfig) -> f64 {
        if self.spindles.feed_type.css() {
            self.css_speed(cfg, &self.pos).unwrap_or(0.0)
        } else {
            self.spindles.master_speed()
        }
    }

    /// The transverse axis (SCC's, else MD20100 `$MC_DIAMETER_AX_DEF`, else the first geometry axis) and
    /// the machine position of the turning centre on it: where the workpiece coordinate is 0
    /// through the active frame and tool length (a frame that only translates on that axis).
    pub(in crate::interp) fn turning_centre(&self, cfg: &MachineConfig) -> Option<(usize, f64)> {
        let tx = self.spindles.css_axis.or(cfg.transverse_axis).or(cfg.geo_axes[0])?;
        let basic = self.basic_position();
        let current = self.offsets.frame.unapply(&cfg.geo_axes, &basic).unwrap_or(basic);
        Some((tx, self.pos[tx] - current[tx]))
    }

    /// The speed constant cutting speed gives at machine position `pos` (rev/min), within LIMS
    /// and G26.
    fn css_speed(&self, cfg: &MachineConfig, pos: &crate::motion::AxisVec) -> Option<f64> {
        let (tx, centre) = self.turning_centre(cfg)?;
        let d = 2.0 * (pos[tx] - centre).abs();
        let n = if d > 1e-9 { self.spindles.cutting_speed * 1000.0 / (std::f64::consts::PI * d) } else { f64::MAX };
        Some(n.min(self.spindles.lims).min(self.spindles.upper))
    }
}
