//! A block's move under the feed type and thread function: a feed per revolution of the
//! master spindle (G95/G96/G97), inverse-time feed (G93), thread cutting G33 (lead I/J/K,
//! start angle SF) and rigid tapping G331/G332 (the spindle interpolated with the axis).

use super::{Control, FeedType, Thread};
use crate::alarm::Alarm;
use crate::interp::modal::Words;
use crate::interp::{Interpreter, Item};
use crate::machine_data::MachineConfig;
use crate::motion::{AxisLimit, Feed, Move};

impl Interpreter {
    /// Whether the fast lane may prepare plain blocks: feed per minute, no thread and no
    /// diameter programming.
    pub(in crate::interp) fn spindles_plain(&self) -> bool {
        self.spindles.feed_type == FeedType::G94 && self.spindles.thread.is_none() && !self.spindles.diameter.active()
    }

    /// Gives the block's move `mv` (just built, feed from F) what the feed type and thread
    /// function make of it; a thread's start synchronisation goes to `out` before it.
    pub(in crate::interp) fn spindle_motion(
        &mut self,
        mv: &mut Move,
        words: &Words,
        cfg: &MachineConfig,
        limits: &[AxisLimit],
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let thread = self.spindles.thread;
        self.spindles.variable_lead = None;
        if !matches!(thread, Some(Thread::G33 | Thread::G34 | Thread::G35)) {
            self.spindles.thread_chained = false;
        }
        if mv.is_rapid() {
            return Ok(());
        }
        let f = self.modal.feed.unwrap_or(0.0) * self.modal.feed_factor();
        match thread {
            None => match self.spindles.feed_type {
                FeedType::G95 | FeedType::G96 | FeedType::G97 => {
                    self.check_fpr_move(mv, cfg, line)?;
                    mv.per_rev = f;
                }
                FeedType::G93 => {
                    // F is the reciprocal of the block's time in minutes.
                    let length = mv.length;
                    mv.set_limits(length, Feed::Path(f * length / 60.0), limits);
                }
                _ => {}
            },
            Some(th) => {
                let (k, dmaj, lead) = self.thread_lead(mv, words, cfg, line)?;
                let master =
                    self.spindles.master().ok_or_else(|| Alarm::unknown_name(line, "G33 (no master spindle)"))?;
                let length = mv.length;
                if matches!(th, Thread::G33 | Thread::G34 | Thread::G35) {
                    if th != Thread::G33 {
                        // F is the lead change (mm/rev²); the move goes out in segments.
                        if self.modal.trc.is_some() {
                            return Err(Alarm::value_out_of_range(line, "G34/G35 under tool radius compensation"));
                        }
                        let change = self.modal.feed.unwrap_or(0.0) * self.modal.length_factor();
                        let change = if th == Thread::G34 { change } else { -change };
                        let reference = self.spindles.reference_speed();
                        self.spindles.variable_lead =
                            Some(super::lead_change::LeadChange::new(lead.abs(), change, dmaj, reference, line)?);
                    }
                    mv.per_rev = lead.abs() * length / dmaj;
                    let bound = mv.per_rev * self.spindles.reference_speed().max(1.0) / 60.0;
                    mv.set_limits(length, Feed::Path(bound), limits);
                    if let Some(sf) = words.spindle.sf {
                        self.spindles.start_angle = sf;
                    }
                    if !self.spindles.thread_chained || words.spindle.sf.is_some() {
                        let angle = self.spindles.start_angle.rem_euclid(360.0);
                        out.push(Item::SpindleControl { ctl: Control::ThreadStart { axis: master, angle }, line });
                    }
                    self.spindles.thread_chained = true;
                } else {
                    // G331 in, G332 out: the spindle turns |Δ|/lead revolutions, reversed on
                    // the way out (a right-hand thread, K > 0, turns like M3 going in).
                    let speed = self.spindles.master_speed();
                    if speed <= 0.0 {
                        return Err(Alarm::value_out_of_range(line, "G331/G332 need S<speed>"));
                    }
                    let sign = lead.signum() * if th == Thread::G331 { 1.0 } else { -1.0 };
                    if !self.positioned[master] {
                        let angle = self.spindle_angles[master].rem_euclid(360.0);
                        self.positioned[master] = true;
                        self.spindles.stop(master);
                        out.push(Item::SpindleToAxis { axis: master, angle, line });
                        mv.path.start[master] = angle;
                    }
                    let turn = sign * 360.0 * dmaj / lead.abs();
                    mv.path.end[master] = mv.path.start[master] + turn;
                    self.pos[master] = mv.path.end[master];
                    let _ = k;
                    mv.set_limits(length, Feed::Path(speed * lead.abs() * length / dmaj / 60.0), limits);
                }
            }
        }
        Ok(())
    }

    /// The thread's lead from I, J or K (the geometry axis it belongs to is the thread's main
    /// direction) and the travel on that axis.
    fn thread_lead(
        &self,
        mv: &Move,
        words: &Words,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(usize, f64, f64), Alarm> {
        let f = self.modal.length_factor();
        let (g, lead) = (0..3)
            .find_map(|g| words.ijk[g].map(|(v, _)| (g, v * f)))
            .ok_or_else(|| Alarm::syntax(line, "thread needs its lead as I, J or K"))?;
        let k = cfg.geo_axes[g].ok_or_else(|| Alarm::value_out_of_range(line, "thread lead on a missing axis"))?;
        let dmaj = (mv.path.end[k] - mv.path.start[k]).abs();
        if lead == 0.0 || dmaj < 1e-9 {
            return Err(Alarm::value_out_of_range(line, "thread: lead and travel along its axis must not be 0"));
        }
        Ok((k, dmaj, lead))
    }
}
