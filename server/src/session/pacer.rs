//! Real-time pacing: how many IPO cycles wall time owes a session at each wake-up.
//!
//! Pure arithmetic on instants handed in by the caller, so it is tested without a clock.

use std::time::Duration;

use tokio::time::Instant;

/// Turns elapsed wall time into a whole number of IPO cycles.
///
/// The remainder below one cycle is carried to the next call, so over many wake-ups the
/// simulated time tracks wall time exactly. After a long stall (a busy machine, a suspended
/// laptop) at most [`Pacer::MAX_CATCH_UP`] of cycles are owed: the session then lags wall time
/// instead of bursting through minutes of motion at once.
#[derive(Debug, Clone)]
pub struct Pacer {
    ipo_cycle: f64,
    last: Instant,
    /// Wall time owed but not yet stepped, in seconds; always below one IPO cycle after a call.
    debt: f64,
    /// Cycles given up by the catch-up cap since the last [`Pacer::take_dropped`].
    dropped: u64,
}

impl Pacer {
    /// Most wall time one wake-up catches up on.
    pub const MAX_CATCH_UP: Duration = Duration::from_secs(1);

    /// Starts pacing at `now` with nothing owed. `ipo_cycle` is in seconds and positive.
    pub fn new(ipo_cycle: f64, now: Instant) -> Pacer {
        Pacer { ipo_cycle, last: now, debt: 0.0, dropped: 0 }
    }

    /// IPO cycles owed for the wall time since the previous call (or since [`Pacer::new`]).
    pub fn owed(&mut self, now: Instant) -> u64 {
        let elapsed = now.saturating_duration_since(self.last);
        self.last = now;
        self.debt += elapsed.as_secs_f64();
        let cap = (Self::MAX_CATCH_UP.as_secs_f64() / self.ipo_cycle).ceil() as u64;
        // The small epsilon keeps 0.05 s / 0.004 s from rounding down to 12.499999.
        let cycles = (self.debt / self.ipo_cycle + 1e-9).floor() as u64;
        if cycles > cap {
            self.debt = 0.0;
            self.dropped += cycles - cap;
            return cap;
        }
        self.debt = (self.debt - cycles as f64 * self.ipo_cycle).max(0.0);
        cycles
    }

    /// Cycles the catch-up cap gave up since the last call: simulated time lost against wall
    /// time for good.
    pub fn take_dropped(&mut self) -> u64 {
        std::mem::take(&mut self.dropped)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wake_ups_every_50_ms_average_to_wall_time() {
        let t0 = Instant::now();
        let mut pacer = Pacer::new(0.004, t0);
        let total: u64 = (1..=20).map(|i| pacer.owed(t0 + Duration::from_millis(50 * i))).sum();
        assert_eq!(total, 250, "one second of 4 ms cycles");
    }

    #[test]
    fn the_remainder_below_one_cycle_is_carried_over() {
        let t0 = Instant::now();
        let mut pacer = Pacer::new(0.004, t0);
        assert_eq!(pacer.owed(t0 + Duration::from_millis(6)), 1);
        assert_eq!(pacer.owed(t0 + Duration::from_millis(8)), 1);
    }

    #[test]
    fn a_long_stall_is_capped_at_one_second_of_cycles() {
        let t0 = Instant::now();
        let mut pacer = Pacer::new(0.004, t0);
        assert_eq!(pacer.owed(t0 + Duration::from_secs(30)), 250);
        // 30 s of 4 ms cycles are 7,500; 250 were stepped.
        assert_eq!(pacer.take_dropped(), 7_250);
        assert_eq!(pacer.owed(t0 + Duration::from_millis(30_050)), 12);
        assert_eq!(pacer.take_dropped(), 0);
    }

    #[test]
    fn no_time_owes_no_cycles() {
        let t0 = Instant::now();
        let mut pacer = Pacer::new(0.004, t0);
        assert_eq!(pacer.owed(t0), 0);
    }
}
