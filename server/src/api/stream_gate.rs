//! When a stream may send its next state message: one per period, on a fixed grid.
//!
//! The session actor publishes a new state once per its own period (50 ms by default, the same as
//! the default stream period). A gate that allowed the next message only a full period after the
//! last one was sent lost a frame whenever a publish came a little early, and then waited on a
//! timer for every frame: 19.3 instead of 20 messages per second, and two wake-ups per frame.
//! This gate keeps a grid of slots `first + k·period`: a state may go out from a quarter period
//! before its slot on, at most one per slot, so a publish that is a little early goes out at once
//! and the long-run rate is exactly one message per period. A stream that fell behind (a slow
//! client, a busy machine) does not burst: the next slot is always after the send time.
//!
//! Pure arithmetic on instants handed in by the caller, so it is tested without a clock.

use std::time::Duration;

use tokio::time::Instant;

/// The slot grid of one stream.
#[derive(Debug, Clone)]
pub struct FrameGate {
    period: Duration,
    /// The slot the next state message belongs to.
    slot: Instant,
}

impl FrameGate {
    /// A gate whose first message was sent at `sent`; the next slot is one period later.
    pub fn new(sent: Instant, period: Duration) -> FrameGate {
        FrameGate { period, slot: sent + period }
    }

    /// How early before its slot a message may go out.
    fn early(&self) -> Duration {
        self.period / 4
    }

    /// From when on the next state message may be sent.
    pub fn opens_at(&self) -> Instant {
        self.slot.checked_sub(self.early()).unwrap_or(self.slot)
    }

    /// Whether a state message may be sent at `now`.
    pub fn is_open(&self, now: Instant) -> bool {
        now >= self.opens_at()
    }

    /// Records a state message sent at `now` (with the gate open): the next slot is the first
    /// one on the grid that opens after `now`.
    pub fn sent(&mut self, now: Instant) {
        self.slot += self.period;
        if self.opens_at() <= now {
            // Late by more than the early margin: skip the slots already past, keep the grid.
            let behind = now.duration_since(self.opens_at());
            let skip = behind.as_nanos() / self.period.as_nanos().max(1) + 1;
            self.slot += self.period * u32::try_from(skip).unwrap_or(u32::MAX);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: Duration = Duration::from_millis(50);

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn publishes_every_period_with_jitter_all_go_out_at_once() {
        // The actor publishes at 50, 100, 150 ... ms, each up to 3 ms early or late; every one
        // of them finds the gate open (the margin is 12.5 ms), so 20 of 20 go out in one second.
        let t0 = Instant::now();
        let mut gate = FrameGate::new(t0, P);
        let jitter = [3i64, -3, 2, -1, 0, -3, 3, 1, -2, 0, 2, -3, 3, 0, -1, 1, 2, -2, 3, -3];
        let mut sent = 0;
        for (k, j) in jitter.iter().enumerate() {
            let at = (50 * (k as i64 + 1) + j) as u64;
            let now = t0 + ms(at);
            assert!(gate.is_open(now), "publish {k} at {at} ms");
            gate.sent(now);
            sent += 1;
        }
        assert_eq!(sent, 20);
    }

    #[test]
    fn at_most_one_message_per_slot() {
        let t0 = Instant::now();
        let mut gate = FrameGate::new(t0, P);
        // Slot 1 is at 50 ms, open from 37.5 ms.
        assert!(!gate.is_open(t0 + ms(37)));
        assert!(gate.is_open(t0 + ms(38)));
        gate.sent(t0 + ms(38));
        // The next slot is at 100 ms, open from 87.5 ms: a change at 60 ms waits.
        assert!(!gate.is_open(t0 + ms(60)));
        assert_eq!(gate.opens_at(), t0 + Duration::from_micros(87_500));
    }

    #[test]
    fn a_late_send_skips_past_slots_instead_of_bursting() {
        let t0 = Instant::now();
        let mut gate = FrameGate::new(t0, P);
        // Sent 230 ms late (slot 50 ms): the slots at 100..250 ms opened before 280 ms and are
        // skipped; the next is the one at 300 ms, open from 287.5 ms.
        gate.sent(t0 + ms(280));
        assert_eq!(gate.opens_at(), t0 + Duration::from_micros(287_500));
        assert!(!gate.is_open(t0 + ms(281)));
    }

    #[test]
    fn over_a_long_run_the_rate_is_one_per_period() {
        // A change every 10 ms for 10 s, each sent as soon as the gate opens: 200 messages
        // (10 s / 50 ms), never more.
        let t0 = Instant::now();
        let mut gate = FrameGate::new(t0, P);
        let mut sent = 0;
        for i in 1..=1000u64 {
            let now = t0 + ms(10 * i);
            if gate.is_open(now) {
                gate.sent(now);
                sent += 1;
            }
        }
        assert_eq!(sent, 200);
    }
}
