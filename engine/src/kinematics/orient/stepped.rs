//! The angles of [`super::solve::two_axes_turns`] from one IPO cycle to the next without an
//! `atan2`: between cycles each in-plane direction turns by a tiny angle, so the new angle is
//! the last one plus `atan` of the small turn, read off the new direction rotated back by the
//! last cosine and sine (two products) and summed as a short odd series.
//!
//! The memo is only an accelerator: whatever direction it last held, the turn from it to the
//! new one is measured exactly, so a stale or foreign memo costs at most an `atan2` (a turn
//! of more than [`MAX_STEP`]) and never a wrong angle. The rounding of the sum grows by about
//! one unit in the last place per cycle; every [`EXACT_EVERY`]th cycle takes `atan2` afresh.

use super::solve::{Turn, atan2, wrap};
use std::f64::consts::FRAC_PI_2;

/// Cycles after which an angle is computed afresh with `atan2` (drift stays below 1e-13 rad).
pub const EXACT_EVERY: u32 = 64;

/// The largest turn (tangent, ≈ radians) taken by the series; larger ones use `atan2`. A
/// 5-axis head turns well below 0.01 rad per IPO cycle at its maximum velocity.
pub const MAX_STEP: f64 = 0.02;

/// One angle of the last cycle with its cosine and sine, and the cycles since `atan2`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Slot {
    turn: Turn,
    stepped: u32,
}

/// The last angles of each `atan2` site of one solve (see [`AngleMemo::of`]); the channel
/// keeps one across IPO cycles. Empty (the default) means every angle is computed directly.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AngleMemo {
    slots: [Option<Slot>; 4],
}

impl AngleMemo {
    /// Forgets every angle: the next solve is computed directly (block starts).
    pub fn clear(&mut self) {
        self.slots = [None; 4];
    }

    /// The direction of the plane vector (x, y), not both zero, at site `k`
    /// (0..4), with the angle stepped from the one the site held in the last cycle when the
    /// turn is small. The cosine and sine are always those of (x, y) itself.
    #[inline]
    pub fn of(&mut self, k: usize, y: f64, x: f64) -> Turn {
        // The exact directions of coordinate-aligned axes (the constant sites of every preset):
        // what `atan2` and the division by r = |x| or |y| give, without either.
        if y == 0.0 && x > 0.0 {
            return Turn { angle: y, cos: 1.0, sin: y };
        }
        if x == 0.0 && y != 0.0 {
            return Turn { angle: FRAC_PI_2.copysign(y), cos: x, sin: 1.0f64.copysign(y) };
        }
        let r = (x * x + y * y).sqrt();
        let (cos, sin) = (x / r, y / r);
        let slot = &mut self.slots[k];
        let next = match *slot {
            Some(last) if last.stepped < EXACT_EVERY => {
                // (x, y) turned back by the last angle: r·(cos δ, sin δ) of the turn since. Read
                // off (x, y) itself, not the quotients, so it runs beside the square root.
                let xr = x * last.turn.cos + y * last.turn.sin;
                let yr = y * last.turn.cos - x * last.turn.sin;
                if xr > 0.0 && yr.abs() <= MAX_STEP * xr {
                    let angle = wrap(last.turn.angle + atan_small(yr / xr));
                    Slot { turn: Turn { angle, cos, sin }, stepped: last.stepped + 1 }
                } else {
                    Slot { turn: Turn { angle: atan2(y, x), cos, sin }, stepped: 0 }
                }
            }
            _ => Slot { turn: Turn { angle: atan2(y, x), cos, sin }, stepped: 0 },
        };
        *slot = Some(next);
        next.turn
    }
}

/// `atan(t)` for |t| ≤ [`MAX_STEP`]: the series to t⁹, whose remainder t¹¹/11 is below 2e-20.
#[inline]
fn atan_small(t: f64) -> f64 {
    let t2 = t * t;
    t * (1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0 - t2 / 9.0))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::{PI, TAU};

    /// Angle difference modulo a whole turn (±π are the same direction).
    fn diff(a: f64, b: f64) -> f64 {
        let d = (a - b).rem_euclid(TAU);
        d.min(TAU - d)
    }

    #[test]
    fn the_series_is_atan_to_the_last_digits() {
        for i in -2000..=2000 {
            let t = MAX_STEP * f64::from(i) / 2000.0;
            // Two units in the last place of the result.
            assert!((atan_small(t) - t.atan()).abs() <= 4.5e-16 * t.abs(), "t = {t}");
        }
    }

    #[test]
    fn an_empty_memo_gives_atan2_and_the_quotients_bit_for_bit() {
        let cases = [(0.3, -0.7), (-1e-3, 2.0), (0.0, 1.0), (-0.0, 3.5), (5.0, 0.0), (-2.5, -0.0), (-0.0, -1.0)];
        for (y, x) in cases {
            let t = AngleMemo::default().of(0, y, x);
            let r = (x * x + y * y).sqrt();
            let bits = |t: Turn| [t.angle.to_bits(), t.cos.to_bits(), t.sin.to_bits()];
            assert_eq!(bits(t), bits(Turn { angle: atan2(y, x), cos: x / r, sin: y / r }), "({y}, {x})");
        }
    }

    #[test]
    fn a_direction_turning_through_minus_pi_keeps_the_range_of_atan2() {
        // From 179° to −179° in 0.05° steps, radius 3.
        let mut memo = AngleMemo::default();
        for i in 0..=40 {
            let a = (179.0 + 0.05 * f64::from(i)).to_radians();
            let (y, x) = (3.0 * a.sin(), 3.0 * a.cos());
            let t = memo.of(1, y, x);
            assert!((-PI..=PI).contains(&t.angle), "{}", t.angle);
            assert!(diff(t.angle, y.atan2(x)) < 1e-13, "step {i}: {} vs {}", t.angle, y.atan2(x));
        }
    }

    proptest! {
        /// Random walks of a plane vector (small and occasional large turns, changing radius):
        /// every stepped angle agrees with the direct `atan2` within 1e-12 rad, and the cosine
        /// and sine are those of the vector.
        #[test]
        fn stepped_angles_follow_atan2(
            start in -PI..PI,
            steps in prop::collection::vec((-0.03f64..0.03, 0.2f64..5.0, 0u8..20), 1..400),
        ) {
            let mut memo = AngleMemo::default();
            let mut a = start;
            for (d, r, jump) in steps {
                a += if jump == 0 { 10.0 * d } else { d };
                let (y, x) = (r * a.sin(), r * a.cos());
                let t = memo.of(2, y, x);
                prop_assert!(diff(t.angle, y.atan2(x)) < 1e-12, "{} vs {}", t.angle, y.atan2(x));
                prop_assert!((-PI..=PI).contains(&t.angle));
                prop_assert!((t.cos - x / r).abs() < 1e-15 && (t.sin - y / r).abs() < 1e-15);
            }
        }
    }
}
