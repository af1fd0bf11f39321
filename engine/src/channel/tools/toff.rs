//! The main run's side of the online tool length offset (`$AA_TOFF`, see `interp/toff.rs`):
//! the offset reached so far moves towards the value of the executing block with MD21194
//! `TOFF_VELO` and MD21196 `TOFF_ACCEL`, per tool direction, and the transformation maps the
//! path with the tool lengthened by it.

use crate::channel::Channel;
use crate::kinematics::ActiveTrafo;
use crate::motion::AxisVec;

impl Channel {
    /// The active transformation as the main run maps with it: the tool lengthened by the
    /// online offset reached so far (JOG and REPOS plan with it, so they start where the
    /// machine stands).
    pub(in crate::channel) fn trafo_in_force(&self) -> Option<ActiveTrafo> {
        self.trafo.as_ref().map(|t| t.lengthened(&self.toff.current))
    }

    /// The planner's (BCS) position of the machine position, through the active
    /// transformation with the tool lengthened by the online offset reached so far.
    pub(in crate::channel) fn space_of_machine(&self) -> AxisVec {
        let toff = self.toff.current;
        match &self.trafo {
            Some(t) if toff == [0.0; 3] => t.forward(&self.machine),
            Some(t) => t.lengthened(&toff).forward(&self.machine),
            None => {
                let mut m = self.machine;
                for (g, k) in self.cfg.geo_axes.iter().enumerate() {
                    if let Some(k) = k {
                        m[*k] -= toff[g];
                    }
                }
                m
            }
        }
    }
}

/// The online tool offset as the main run has traversed it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(in crate::channel) struct OnlineOffset {
    /// Offset reached in the tool directions X, Y, Z (mm).
    pub current: [f64; 3],
    /// Rate of each direction (mm/s, signed).
    rate: [f64; 3],
}

impl OnlineOffset {
    /// Standing at `current` (a restored channel: the machine position already includes it).
    pub fn at(current: [f64; 3]) -> OnlineOffset {
        OnlineOffset { current, rate: [0.0; 3] }
    }

    /// One IPO cycle `dt` towards `target`: accelerate with `accel` up to `velocity`, and brake
    /// so as to stop on the target (never overshooting it).
    #[inline]
    pub fn step(&mut self, target: &[f64; 3], velocity: f64, accel: f64, dt: f64) {
        // Standing on the target, the usual case: nothing changes (bits compared, so a −0.0
        // target still replaces a +0.0 offset below). Inlined into the caller's cycle.
        let still = |k: usize| self.rate[k] == 0.0 && self.current[k].to_bits() == target[k].to_bits();
        if !(still(0) && still(1) && still(2)) {
            self.ramp(target, velocity, accel, dt);
        }
    }

    /// [`OnlineOffset::step`] while the offset moves.
    #[inline(never)]
    fn ramp(&mut self, target: &[f64; 3], velocity: f64, accel: f64, dt: f64) {
        for ((cur, rate), goal) in self.current.iter_mut().zip(&mut self.rate).zip(target) {
            let d = goal - *cur;
            if d.abs() < 1e-12 {
                *cur = *goal;
                *rate = 0.0;
                continue;
            }
            let s = d.signum();
            // Speed towards the target.
            let towards = *rate * s;
            let brake = (2.0 * accel * d.abs()).sqrt();
            // Positive: at rest (or moving away) it is accel·dt, and brake > 0 while d ≠ 0.
            let v = (towards.max(0.0) + accel * dt).min(velocity).min(brake);
            if v * dt >= d.abs() {
                *cur = *goal;
                *rate = 0.0;
            } else {
                *cur += s * v * dt;
                *rate = s * v;
            }
        }
    }

    /// True once the offset stands on `target`.
    pub fn settled(&self, target: &[f64; 3]) -> bool {
        self.current == *target
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_change_ramps_up_cruises_and_stops_on_the_target() {
        // 10 mm at 1000 mm/min (16.667 mm/s) and 1 m/s²: accelerating takes 16.7 ms and
        // 0.139 mm each way, so the move lasts about 10/16.667 + 0.0167 = 0.617 s.
        let mut t = OnlineOffset::default();
        let (v, a, dt) = (1000.0 / 60.0, 1000.0, 0.004);
        let mut n = 0;
        let mut peak: f64 = 0.0;
        while !t.settled(&[0.0, 0.0, 10.0]) {
            let before = t.current[2];
            t.step(&[0.0, 0.0, 10.0], v, a, dt);
            peak = peak.max((t.current[2] - before) / dt);
            assert!(t.current[2] <= 10.0);
            n += 1;
            assert!(n < 10_000);
        }
        let seconds = n as f64 * dt;
        assert!((seconds - (10.0 / v + v / a)).abs() < 0.02, "{seconds}");
        assert!(peak <= v + 1e-9, "{peak}");
    }
}
