//! Threads with a changing lead: `G34` (increasing) and `G35` (decreasing) (Programming Manual
//! "Fundamentals", "Thread cutting with increasing or decreasing lead"). The block is a G33
//! thread whose lead (I, J or K) is the lead at its start, and whose `F` is the change of the
//! lead per revolution (mm/rev²): after n revolutions the lead is P(n) = P0 ± F·n and the
//! tool has travelled z(n) = P0·n ± F·n²/2 along the thread's main axis, so the end lead is
//! Pe = √(P0² ± 2·F·z) (the manual's F = |Pe² − P0²| / (2·z)).
//!
//! The main run follows a feed per revolution that is constant within a move, so the block
//! runs as consecutive moves of one spindle revolution each ([`SEGMENTS_PER_REV`], at most
//! [`MAX_SEGMENTS`]) without a stop between them: each move takes exactly the revolutions
//! z(n) gives for its part of the thread, so the spindle angle is exact at every seam, and
//! within a move the lead is that revolution's mean, P0 ± F·(k + ½) in revolution k (within
//! F/2 of the exact lead). Whole revolutions keep the seams few: the planner's crossing from
//! one move into the next costs a fraction of an IPO cycle. A G35 whose lead would reach 0
//! before the end is refused (12560), as is G34/G35 under tool radius compensation.
//! `F` is written to the feed register like any F (program a new F after the thread).

use crate::alarm::Alarm;
use crate::interp::{Item, SharedOffsets};
use crate::motion::{AxisLimit, Feed, Move, Path};

/// Moves per spindle revolution of a G34/G35 block.
pub const SEGMENTS_PER_REV: f64 = 1.0;
/// The most moves one block becomes.
pub const MAX_SEGMENTS: usize = 4096;

/// A thread block's changing lead, measured along its main axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeadChange {
    /// Lead at the start (mm/rev, > 0).
    pub start: f64,
    /// Change per revolution (mm/rev², + for G34, − for G35).
    pub change: f64,
    /// Travel along the main axis (mm, > 0).
    pub travel: f64,
    /// The speed (rev/min) the look-ahead bounds each move's feed with.
    pub reference_speed: f64,
}

impl LeadChange {
    /// Checks the lead stays positive to the end (G35), with the block's line for the alarm.
    pub fn new(start: f64, change: f64, travel: f64, reference_speed: f64, line: u32) -> Result<LeadChange, Alarm> {
        let end_squared = start * start + 2.0 * change * travel;
        if end_squared <= 0.0 || !end_squared.is_finite() {
            return Err(Alarm::value_out_of_range(
                line,
                &format!("G35: lead {start} falls to 0 within the thread's {travel} mm"),
            ));
        }
        Ok(LeadChange { start, change, travel, reference_speed })
    }

    /// Revolutions from the start to travel `z` along the main axis.
    pub fn revolutions(&self, z: f64) -> f64 {
        let (p, f) = (self.start, self.change);
        if f.abs() < 1e-12 {
            return z / p;
        }
        // P·n + F·n²/2 = z; the root with n ≥ 0 (written to avoid cancellation).
        2.0 * z / (p + (p * p + 2.0 * f * z).sqrt())
    }

    /// Travel along the main axis after `n` revolutions.
    pub fn travel_after(&self, n: f64) -> f64 {
        self.start * n + self.change * n * n / 2.0
    }

    /// Puts out the thread move `mv` as consecutive moves of equal revolutions.
    pub fn push_segments(
        &self,
        mv: Move,
        line: u32,
        offsets: SharedOffsets,
        limits: &[AxisLimit],
        out: &mut Vec<Item>,
    ) {
        let total = self.revolutions(self.travel);
        let count = ((total * SEGMENTS_PER_REV).ceil() as usize).clamp(1, MAX_SEGMENTS);
        let (start, end) = (mv.path.start, mv.path.end);
        let point = |u: f64| {
            let mut p = start;
            for (a, (s, e)) in p.iter_mut().zip(start.iter().zip(&end)) {
                *a = s + (e - s) * u;
            }
            p
        };
        let mut u0 = 0.0;
        for i in 1..=count {
            let n0 = total * (i - 1) as f64 / count as f64;
            let n1 = total * i as f64 / count as f64;
            let u1 = if i == count { 1.0 } else { self.travel_after(n1) / self.travel };
            let mut seg = mv.clone();
            seg.path = Path::line(if i == 1 { start } else { point(u0) }, if i == count { end } else { point(u1) });
            let length = mv.length * (u1 - u0);
            seg.per_rev = length / (n1 - n0);
            seg.set_limits(length, Feed::Path(seg.per_rev * self.reference_speed.max(1.0) / 60.0), limits);
            if i < count {
                seg.exact_stop = false;
                seg.blend = None;
            }
            out.push(Item::Move { mv: seg, line, offsets: offsets.clone() });
            u0 = u1;
        }
    }
}
