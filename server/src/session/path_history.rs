//! The executed path of a session: the tool tip (geometry axes in the BCS) of every published
//! state, kept so that a viewer who joins later sees where the tool has been
//! (`GET /sessions/{id}/path-history`).
//!
//! Bounded and thinned: a point is kept only when the tip moved at least [`MIN_STEP`]; a point
//! on the straight line between its neighbours (within [`COLLINEAR_TOL`]) is replaced by the
//! next; when [`CAPACITY`] points are held, every second one is dropped (the resolution halves,
//! the path's extent stays). Memory per session is at most `CAPACITY` × 32 bytes. Points are
//! the states a viewer would have seen: every real-time period, but in fast pace only one per
//! chunk of IPO cycles (recording every cycle would slow the fast lane), so a fast run's history
//! is as coarse as a live viewer's trace of it.

use nctwin_engine::Snapshot;

use crate::api::preview::{dist, off_line};

/// Points held at most.
pub const CAPACITY: usize = 20_000;
/// Smallest motion (mm) that adds a point.
pub const MIN_STEP: f64 = 0.01;
/// A middle point closer than this (mm) to the line of its neighbours is dropped.
pub const COLLINEAR_TOL: f64 = 0.002;

/// One point of the executed path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryPoint {
    /// Tool tip, geometry axes in the BCS (mm); a missing axis reads 0.
    pub basic: [f64; 3],
    /// Program line in execution (0: none).
    pub line: u32,
}

/// The thinned executed path of one session.
#[derive(Debug, Default)]
pub struct PathHistory {
    points: Vec<HistoryPoint>,
    /// Times the path was halved since the session started.
    halvings: u32,
    /// States recorded (kept or not).
    recorded: u64,
}

impl PathHistory {
    /// Records the tip of a published state; `geo` names the geometry axes.
    pub fn record(&mut self, snap: &Snapshot, geo: &[String; 3]) {
        self.recorded += 1;
        let basic = std::array::from_fn(|g| snap.basic.iter().find(|(n, _)| *n == geo[g]).map_or(0.0, |(_, v)| *v));
        let p = HistoryPoint { basic, line: snap.block.as_ref().map_or(0, |b| b.line) };
        self.push(p);
    }

    fn push(&mut self, p: HistoryPoint) {
        let n = self.points.len();
        if n > 0 && dist(&self.points[n - 1].basic, &p.basic) < MIN_STEP {
            return;
        }
        if n >= 2 && off_line(&self.points[n - 2].basic, &p.basic, &self.points[n - 1].basic) < COLLINEAR_TOL {
            self.points[n - 1] = p;
            return;
        }
        if n >= CAPACITY {
            let last = n - 1;
            let mut i = 0;
            self.points.retain(|_| {
                let keep = i % 2 == 0 || i == last;
                i += 1;
                keep
            });
            self.halvings += 1;
        }
        self.points.push(p);
    }

    /// The points held, oldest first.
    pub fn points(&self) -> &[HistoryPoint] {
        &self.points
    }

    /// How often the path was halved to stay within [`CAPACITY`].
    pub fn halvings(&self) -> u32 {
        self.halvings
    }

    /// States recorded since the session started.
    pub fn recorded(&self) -> u64 {
        self.recorded
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64) -> HistoryPoint {
        HistoryPoint { basic: [x, y, 0.0], line: 1 }
    }

    #[test]
    fn a_straight_run_keeps_its_ends_and_the_corner() {
        let mut h = PathHistory::default();
        for i in 0..=100 {
            h.push(at(f64::from(i) * 0.1, 0.0));
        }
        for i in 1..=50 {
            h.push(at(10.0, f64::from(i) * 0.1));
        }
        let kept: Vec<[f64; 3]> = h.points().iter().map(|p| p.basic).collect();
        assert_eq!(kept.len(), 3, "{kept:?}");
        assert!(dist(&kept[1], &[10.0, 0.0, 0.0]) < 1e-9 && dist(&kept[2], &[10.0, 5.0, 0.0]) < 1e-9, "{kept:?}");
    }

    #[test]
    fn a_long_path_is_halved_and_stays_bounded_with_its_last_point() {
        let mut h = PathHistory::default();
        // A zigzag of 3 × CAPACITY points: none collinear, none too close.
        let n = 3 * CAPACITY;
        for i in 0..n {
            h.push(at(i as f64, (i % 2) as f64));
        }
        assert!(h.points().len() <= CAPACITY, "{}", h.points().len());
        assert!(h.halvings() >= 2);
        assert_eq!(h.points().first().map(|p| p.basic), Some([0.0, 0.0, 0.0]));
        assert_eq!(h.points().last().map(|p| p.basic), Some([(n - 1) as f64, 1.0, 0.0]));
    }

    #[test]
    fn motion_below_the_smallest_step_adds_nothing() {
        let mut h = PathHistory::default();
        h.push(at(0.0, 0.0));
        h.push(at(0.005, 0.0));
        assert_eq!(h.points().len(), 1);
    }
}
