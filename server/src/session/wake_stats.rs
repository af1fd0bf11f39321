//! How late real-time wake-ups come, over all sessions of the process: the IPO lag as the
//! server sees it, without the delivery delay of a stream or the scheduling of its client.
//!
//! A real-time session is behind wall time only between a wake-up's schedule and the wake-up
//! itself: the wake-up then steps every cycle owed ([`super::Pacer`]). Simulated time is lost
//! for good only when one wake-up owes more than [`super::Pacer::MAX_CATCH_UP`]; those cycles are
//! counted as dropped. Plain atomics (a few per wake-up of 50 ms), read by `GET /metrics`.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// Upper bounds (seconds) of the lateness histogram: from timer resolution to the catch-up cap.
pub const LATENESS_BUCKETS: [f64; 10] = [0.001, 0.002, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0];

/// Counters of the process's real-time wake-ups.
#[derive(Debug)]
pub struct WakeStats {
    /// Per bucket of [`LATENESS_BUCKETS`] (not cumulative), plus one for +Inf.
    buckets: [AtomicU64; LATENESS_BUCKETS.len() + 1],
    sum_micros: AtomicU64,
    dropped_cycles: AtomicU64,
}

/// A copy of the counters at one moment.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WakeCounts {
    /// Per bucket of [`LATENESS_BUCKETS`] (not cumulative), plus one for +Inf.
    pub buckets: Vec<u64>,
    pub sum: Duration,
    /// IPO cycles not stepped because a wake-up owed more than the catch-up cap.
    pub dropped_cycles: u64,
}

impl WakeCounts {
    /// Number of wake-ups counted.
    pub fn count(&self) -> u64 {
        self.buckets.iter().sum()
    }
}

static STATS: WakeStats = WakeStats::new();

/// The process's counters (one set for every server in the process).
pub fn wake_stats() -> &'static WakeStats {
    &STATS
}

impl WakeStats {
    const fn new() -> WakeStats {
        WakeStats {
            buckets: [const { AtomicU64::new(0) }; LATENESS_BUCKETS.len() + 1],
            sum_micros: AtomicU64::new(0),
            dropped_cycles: AtomicU64::new(0),
        }
    }

    /// Counts one wake-up that came `lateness` after its schedule and dropped `dropped` cycles.
    pub fn record(&self, lateness: Duration, dropped: u64) {
        let seconds = lateness.as_secs_f64();
        let bucket = LATENESS_BUCKETS.iter().position(|b| seconds <= *b).unwrap_or(LATENESS_BUCKETS.len());
        self.buckets[bucket].fetch_add(1, Ordering::Relaxed);
        self.sum_micros.fetch_add(u64::try_from(lateness.as_micros()).unwrap_or(u64::MAX), Ordering::Relaxed);
        if dropped > 0 {
            self.dropped_cycles.fetch_add(dropped, Ordering::Relaxed);
        }
    }

    /// The counters now.
    pub fn counts(&self) -> WakeCounts {
        WakeCounts {
            buckets: self.buckets.iter().map(|b| b.load(Ordering::Relaxed)).collect(),
            sum: Duration::from_micros(self.sum_micros.load(Ordering::Relaxed)),
            dropped_cycles: self.dropped_cycles.load(Ordering::Relaxed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wake_ups_land_in_the_bucket_of_their_lateness() {
        let stats = WakeStats::new();
        stats.record(Duration::from_micros(300), 0); // ≤ 1 ms
        stats.record(Duration::from_millis(30), 0); // ≤ 50 ms
        stats.record(Duration::from_millis(50), 0); // ≤ 50 ms (bounds are inclusive)
        stats.record(Duration::from_secs(3), 500); // +Inf, 500 cycles dropped
        let counts = stats.counts();
        assert_eq!(counts.buckets, vec![1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]);
        assert_eq!(counts.count(), 4);
        assert_eq!(counts.sum, Duration::from_micros(300 + 30_000 + 50_000 + 3_000_000));
        assert_eq!(counts.dropped_cycles, 500);
    }
}
