//! SOFT: the jerk-limited velocity profile of the path (G group 21).
//!
//! BRISK changes the path velocity by up to `a·dt` per cycle. Under SOFT the path acceleration
//! itself is a state that changes by at most `j·dt` per cycle (the move's path jerk, from
//! MD32431 per axis and MD20600, see `interp/dynamics.rs`), so the velocity follows S curves:
//! the third difference of the sampled positions over `dt³` stays within the jerk.
//!
//! Each cycle takes the highest acceleration in `[acc − j·dt, acc + j·dt]` (and within `±a`)
//! from which the path can still (1) ramp its acceleration to zero without passing the feed,
//! and (2) brake with the jerk limit to every planned transition speed ahead
//! ([`stop_distance`], exact for the continuous profile, plus one cycle of margin). When no
//! acceleration in that range is safe (a transition planned while the path was already
//! faster), the BRISK brake limit takes over for that cycle, so transition speeds and block
//! ends are always met; only then can the jerk be exceeded.

use super::Planner;

/// Bisection steps between the lowest and the highest acceleration of a cycle.
const REFINE: usize = 12;

/// The distance the path needs to go from velocity `v` and acceleration `acc` to velocity
/// `v_to` with zero acceleration, decelerating with at most `a` and jerk `j`: acceleration
/// ramped down to a peak deceleration, held, and ramped back to zero. When even ramping the
/// acceleration straight to zero ends below `v_to`, that ramp's distance.
pub(super) fn stop_distance(v: f64, acc: f64, v_to: f64, a: f64, j: f64) -> f64 {
    // Velocity to lose plus what the acceleration adds while it is ramped down to zero.
    let excess = v - v_to + acc * acc.abs() / (2.0 * j);
    // (An infinite jerk, a BRISK move ahead, gives the trapezoid's distance.)
    let mut p = if excess > 0.0 { (j * excess).sqrt() } else { 0.0 };
    let mut hold = 0.0;
    if p > a {
        p = a;
        hold = (excess - a * a / j) / a;
    }
    // Already decelerating harder than the peak: the acceleration only ramps back to zero.
    let p = p.max(-acc);
    let mut d = 0.0;
    let (mut v0, mut a0) = (v, acc);
    let mut phase = |t: f64, jerk: f64| {
        if t > 0.0 {
            d += v0 * t + a0 * t * t / 2.0 + jerk * t * t * t / 6.0;
            v0 += a0 * t + jerk * t * t / 2.0;
            a0 += jerk * t;
        }
    };
    phase((acc + p) / j, -j);
    phase(hold, 0.0);
    phase(p / j, j);
    d
}

/// The velocity gained after a cycle with acceleration `acc > 0` while the acceleration is
/// ramped down by `j·dt` per cycle until it is not positive: `dt · Σ (acc − m·j·dt)` over the
/// cycles where that is positive.
fn ramp_gain(acc: f64, j: f64, dt: f64) -> f64 {
    let step = j * dt;
    let q = acc / step;
    // `floor` is a library call on the baseline x86-64 target, and this runs for most SOFT
    // candidates: below 2⁵² a non-negative quotient truncates to the same integer.
    let m = if (0.0..4.5e15).contains(&q) { q as u64 as f64 } else { q.floor() };
    dt * (m * acc - step * m * (m + 1.0) / 2.0)
}

/// A lower bound of an axis' jerk at a transition between moves with path jerk `j` (the
/// smaller of the two) whose rates of the axis per unit path length are `ra` and `rb`: each
/// move's path jerk keeps `rate · j` within the axis jerk.
pub(super) fn corner_jerk(j: f64, ra: f64, rb: f64) -> f64 {
    j * ra.abs().max(rb.abs())
}

impl Planner {
    /// The path velocity of the next cycle under SOFT (the front move has a finite jerk);
    /// updates the path acceleration.
    #[inline(never)]
    pub(super) fn soft_velocity(&mut self, cap: f64) -> f64 {
        let dt = self.dt;
        let front = &self.queue[0];
        let (a, j) = (front.a_max, front.jerk);
        let target = if self.hold { 0.0 } else { cap };
        let (lo, hi) = ((self.acc - j * dt).max(-a), (self.acc + j * dt).min(a));
        // Above the jerk's reach of ±a (a lowered acceleration): back within it at once.
        let (lo, hi) = if lo > hi { (hi.min(a).max(-a), hi.min(a).max(-a)) } else { (lo, hi) };
        // Right after a corner the axes' acceleration pulse of the velocity jump (its jerk
        // planned up to the axis jerk, `corner_jerk`) is still in the third difference: the
        // path acceleration does not rise in this cycle, so the two do not add up.
        let hi = if self.kinked > 0 {
            self.kinked -= 1;
            hi.min(self.acc.max(lo))
        } else {
            hi
        };
        // No transition farther than the longest stop any candidate needs (with the smallest
        // acceleration and jerk queued) can bind: the checks look no farther.
        let (a_min, j_min) = (self.a_min, self.j_min);
        let v_hi = self.v + hi.max(0.0) * dt;
        let horizon = stop_distance(v_hi, hi.max(0.0), 0.0, a_min, j_min) + v_hi * dt;
        // Far from every transition (most cycles of a long move), the candidates need only
        // the target's tests: the same answers without a stop distance each.
        let near = self.transition_near(lo, hi, horizon, target);
        let acc = if self.soft_safe(hi, target, horizon, near) {
            hi
        } else if !self.soft_safe(lo, target, horizon, near) {
            lo
        } else {
            let (mut ok, mut bad) = (lo, hi);
            for _ in 0..REFINE {
                let mid = 0.5 * (ok + bad);
                if self.soft_safe(mid, target, horizon, near) {
                    ok = mid;
                } else {
                    bad = mid;
                }
            }
            ok
        };
        let mut v_new = self.v + acc * dt;
        if v_new > target && v_new <= target * (1.0 + 1e-12) {
            // The rounding of `v + acc·dt` at the target: at the target, so that the tests of
            // transitions planned at the target (seams at the feed) see it as not faster.
            v_new = target;
        }
        // The last bit of a move that ends at standstill, shorter than a cycle's jerk-limited
        // step from rest: travelled in this cycle.
        let remaining = front.length - self.s;
        if self.v_end[0] == 0.0 && !self.hold && self.v <= j * dt * dt && remaining <= j * dt * dt * dt {
            self.acc = 0.0;
            return remaining / dt;
        }
        if v_new <= 0.0 {
            // Standstill (a hold, or a transition reached early): from here the acceleration
            // ramps up again from zero.
            self.acc = 0.0;
            return 0.0;
        }
        // The BRISK limit keeps every transition speed when the S curve cannot (see the doc).
        let hard = self.brake_limited(v_new, target);
        if hard < v_new {
            v_new = hard;
        }
        self.acc = (v_new - self.v) / dt;
        v_new
    }

    /// True when the path, accelerating with `acc` this cycle, can still keep the velocity
    /// target and brake to every planned transition speed ahead with its jerk (those within
    /// `horizon` of the position after this cycle: no stop is longer). `near`: false when
    /// [`Planner::transition_near`] found that no transition can bind.
    fn soft_safe(&self, acc: f64, target: f64, horizon: f64, near: bool) -> bool {
        let dt = self.dt;
        let front = &self.queue[0];
        let j_front = front.jerk;
        let v1 = self.v + acc * dt;
        if v1 < 0.0 {
            return true;
        }
        if acc > 0.0 {
            // Ramping the acceleration down to zero, `j·dt` per cycle, adds what it leaves.
            if v1 + ramp_gain(acc, j_front, dt) > target * (1.0 + 1e-12) {
                return false;
            }
        } else if v1 > target * (1.0 + 1e-12) && acc > (self.acc - j_front * dt).max(-front.a_max) {
            // Above the target: only the hardest braking the jerk allows. (Not for the last
            // bits of `v + acc·dt`'s rounding at the target: the bisection would brake for them
            // by its resolution, a dip of 2·j·dt²/4096 at every seam.)
            return false;
        }
        if acc > 0.0 && self.queue.len() > 1 && !self.acceleration_fits_ahead(v1, acc) {
            return false;
        }
        if !near {
            return true;
        }
        let n = self.queue.len();
        let mut distance = -self.s - v1 * dt;
        let (mut a, mut j) = (f64::INFINITY, f64::INFINITY);
        // Not above the target, the path never passes it (the test above): a transition
        // planned at or above the target binds only a path that is faster now. (With the
        // one-cycle reserve such a seam, collinear or tangent at the feed, would otherwise slow
        // the path before it.)
        let free = target.max(v1);
        for (k, (mv, &v_end)) in self.queue.iter().zip(&self.v_end).enumerate() {
            distance += mv.length;
            a = a.min(mv.a_max);
            j = j.min(mv.jerk);
            let reserve = if k + 1 < n { v_end * dt } else { 0.0 };
            if v_end < free
                && v_end < v1 + acc.max(0.0) * acc.max(0.0) / (2.0 * j)
                && stop_distance(v1, acc, v_end, a, j) - (v1 - v_end) * dt / 2.0 > distance - reserve
            {
                return false;
            }
            if v_end == 0.0 || distance - reserve > horizon {
                break;
            }
        }
        true
    }

    /// True when the path, at `v1` with acceleration `acc > 0` after this cycle, can ramp the
    /// acceleration down (by `j·dt` per cycle) to each later move's own `a_max` before it
    /// reaches that move, one cycle to spare: else the first cycle in a move with less
    /// acceleration would cut it at once, a jerk of `(acc − a)/dt`. Looks only as far as the
    /// longest such ramp reaches (down to zero acceleration).
    fn acceleration_fits_ahead(&self, v1: f64, acc: f64) -> bool {
        let dt = self.dt;
        let front = &self.queue[0];
        let mut j = front.jerk;
        let ramp = |to: f64, j: f64| {
            let t = (acc - to) / j;
            (v1 + acc * dt) * dt + v1 * t + acc * t * t / 2.0 - j * t * t * t / 6.0
        };
        let mut distance = front.length - self.s - v1 * dt;
        for mv in self.queue.iter().skip(1) {
            j = j.min(mv.jerk);
            if distance > ramp(0.0, j) {
                break;
            }
            if mv.a_max < acc && ramp(mv.a_max, j) > distance {
                return false;
            }
            distance += mv.length;
        }
        true
    }

    /// False when no planned transition can fail [`Planner::soft_safe`]'s test for any
    /// acceleration in `lo..=hi` this cycle; true when one might (the candidates then test
    /// each transition). A bound, not the test: per transition the candidates' stop distance
    /// is at most the highest velocity reached (`V = v₁ + acc⁺²/2j` with the highest `v₁` and
    /// `acc`) times an upper bound of [`stop_distance`]'s phase times (`t₁ ≤ (acc⁺ + P)/j`,
    /// hold `≤ E/a`, `t₃ ≤ P/j`, where `E` bounds the velocity to lose and `P` the peak
    /// deceleration: `max(√(j·E), −lo)`), and the distance left is at least the one after the
    /// fastest candidate's cycle. It looks at least as far ahead as any candidate (their
    /// distances are not smaller), and keeps a margin far above rounding. A transition planned
    /// at or above both `target` and the highest velocity is skipped, as every candidate does.
    fn transition_near(&self, lo: f64, hi: f64, horizon: f64, target: f64) -> bool {
        let dt = self.dt;
        let v_hi = self.v + hi * dt;
        if v_hi < 0.0 {
            // Every candidate stands still after this cycle: none reaches the transitions.
            return false;
        }
        let v_lo = (self.v + lo * dt).max(0.0);
        let acc_up = hi.max(0.0);
        let n = self.queue.len();
        let mut distance = -self.s - v_hi * dt;
        let (mut a, mut j) = (f64::INFINITY, f64::INFINITY);
        for (k, (mv, &v_end)) in self.queue.iter().zip(&self.v_end).enumerate() {
            distance += mv.length;
            a = a.min(mv.a_max);
            j = j.min(mv.jerk);
            let reserve = if k + 1 < n { v_end * dt } else { 0.0 };
            let room = distance - reserve;
            let peak_v = v_hi + acc_up * acc_up / (2.0 * j);
            if v_end < target.max(v_hi) && v_end < peak_v * (1.0 + 1e-9) + 1e-9 {
                let lose = (peak_v - v_end).max(0.0);
                let peak_dec = (j * lose).sqrt().max(-lo).max(0.0);
                let time = (acc_up + 2.0 * peak_dec) / j + lose / a;
                let stop = peak_v * time - (v_lo - v_end) * dt / 2.0;
                if !(stop.is_finite() && stop * (1.0 + 1e-9) + 1e-9 < room - 1e-9 * room.abs()) {
                    return true;
                }
            }
            if v_end == 0.0 || room > horizon {
                break;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::super::{AxisLimit, Feed, Move, Path, Planner};
    use super::stop_distance;
    use crate::machine_data::registry::MAX_CHANNEL_AXES;

    #[test]
    fn far_from_every_transition_the_bound_gives_the_answers_of_the_full_test() {
        // SOFT along a zigzag of short and long lines (corners of 90° and less, so planned
        // transition speeds between 0 and the feed): every cycle, candidates across the
        // cycle's acceleration range get the same answer with the bound as with every
        // transition tested; and the bound does spare the tests in many cycles.
        let lim = vec![AxisLimit { max_velocity: 200.0, max_accel: 1000.0, accel_overload: 1.2 }; 3];
        let mut p = Planner::new(0.004, lim.clone(), [0.0; MAX_CHANNEL_AXES]);
        let mut at: [f64; MAX_CHANNEL_AXES] = [0.0; MAX_CHANNEL_AXES];
        for i in 0..24u32 {
            let mut to = at;
            to[0] += [0.4, 3.0, 12.0][i as usize % 3];
            to[1] += if i % 2 == 0 { 0.8 } else { -0.5 };
            let len = ((to[0] - at[0]).powi(2) + (to[1] - at[1]).powi(2)).sqrt();
            let mut mv = Move::new(Path::line(at, to), len, Feed::Path(20.0), &lim, false, i);
            mv.jerk = 20_000.0;
            p.push(mv);
            at = to;
        }
        let (mut checked, mut far) = (0, 0);
        while !p.is_idle() {
            if let Some(front) = p.queue.front() {
                let dt = p.dt;
                let (a, j) = (front.a_max, front.jerk);
                let target = front.capped(1.0, 1.0, 0.0);
                let (lo, hi) = ((p.acc - j * dt).max(-a), (p.acc + j * dt).min(a));
                if lo <= hi {
                    let v_hi = p.v + hi.max(0.0) * dt;
                    let horizon = stop_distance(v_hi, hi.max(0.0), 0.0, p.a_min, p.j_min) + v_hi * dt;
                    let near = p.transition_near(lo, hi, horizon, target);
                    far += usize::from(!near);
                    for i in 0..=40 {
                        let acc = lo + (hi - lo) * f64::from(i) / 40.0;
                        let full = p.soft_safe(acc, target, horizon, true);
                        assert_eq!(p.soft_safe(acc, target, horizon, near), full, "s {} v {} acc {acc}", p.s, p.v);
                        checked += 1;
                    }
                }
            }
            p.step();
            assert!(checked < 10_000_000);
        }
        assert!(far > 100 && checked > 10_000, "{far} cycles far of {checked} answers");
    }

    #[test]
    fn the_stop_distance_of_a_full_s_curve_is_the_mean_velocity_times_its_time() {
        // From 100 mm/s at rest acceleration to 0 with a = 1000 mm/s², j = 10000 mm/s³: the
        // ramps take a/j = 0.1 s each and lose a²/j = 100 mm/s together, so no hold: the
        // peak is sqrt(j·Δv) = 1000 = a exactly; time 0.2 s, the mean velocity 50 mm/s by
        // symmetry: 10 mm.
        assert!((stop_distance(100.0, 0.0, 0.0, 1000.0, 10_000.0) - 10.0).abs() < 1e-9);
        // 300 mm/s: a hold of (300 − 100)/1000 = 0.2 s; time 0.4 s, mean 150: 60 mm.
        assert!((stop_distance(300.0, 0.0, 0.0, 1000.0, 10_000.0) - 60.0).abs() < 1e-9);
        // Braking from 300 to 100 mm/s: the same shape as 200 → 0 (peak sqrt(2e6) > a, hold
        // 0.1 s, time 0.3 s) shifted by 100 mm/s: mean 200 mm/s · 0.3 s = 60 mm.
        assert!((stop_distance(300.0, 0.0, 100.0, 1000.0, 10_000.0) - 60.0).abs() < 1e-9);
    }

    #[test]
    fn an_acceleration_in_progress_lengthens_the_stop() {
        let rest = stop_distance(100.0, 0.0, 0.0, 1000.0, 10_000.0);
        assert!(stop_distance(100.0, 500.0, 0.0, 1000.0, 10_000.0) > rest);
        assert!(stop_distance(100.0, -500.0, 0.0, 1000.0, 10_000.0) < rest);
    }
}
