//! The executed path of a session: the tool tip on the workpiece, looked at in every IPO cycle
//! the session interpolates (real time and fast pace alike), kept so that a viewer who joins
//! later sees where the tool has been (`GET /sessions/{id}/path-history`).
//!
//! Thinned by geometry, not by time, so that a fast-pace run and a real-time run of the same
//! program give the same picture: the last kept point and the newest tip span a chord; the
//! tip of the cycle before becomes a kept point as soon as that chord passes farther than
//! [`TOLERANCE`] from it or from the samples taken since the last kept point (at most
//! [`PROBES`], at least [`TOLERANCE`] apart; halved when full). A sample that goes on along
//! the straight stretch of the samples before it (within [`STRAIGHT`]) replaces its end
//! instead of being added: the distance from the chord is convex along a straight stretch, so
//! its two ends bound it, and a straight run (the bulk of a CAM program) costs two distances
//! per cycle instead of `PROBES`. Every block end is kept (the line in execution changes), and
//! so is a change of TRACYL diameter or of exactness (see
//! `nctwin_engine::channel::workpiece_tip`). Bounded: when [`CAPACITY`] points are held,
//! every second one is dropped (the resolution halves, the path's extent stays). Memory per
//! session is at most `CAPACITY` points; the work per cycle is one tip and at most
//! `PROBES + 1` squared distances.
//!
//! The tip is the one on the workpiece (`workpiece_tip.rs`): through the kinematics on a
//! trunnion table moved without TRAORI, unrolled (with its diameter) under TRACYL.

use nctwin_engine::Channel;
use nctwin_engine::channel::workpiece_tip::TipProbe;

use crate::api::preview::dist;

/// Points held at most.
pub const CAPACITY: usize = 20_000;
/// Display tolerance (mm): no part of the path is farther than this from the drawn polyline
/// (up to the spacing of the samples checked).
pub const TOLERANCE: f64 = 0.01;
/// Samples between two kept points the chord is checked against.
pub const PROBES: usize = 32;
/// How far (mm) a sample may lie from a straight stretch and still extend it: far below
/// [`TOLERANCE`], so the stretch's ends stand for every sample on it.
pub const STRAIGHT: f64 = 1e-5;

/// One point of the executed path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryPoint {
    /// Tool tip on the workpiece, geometry axes (mm); a missing axis reads 0.
    pub basic: [f64; 3],
    /// Program line in execution (0: none).
    pub line: u32,
    /// The TRACYL working diameter while TRACYL is active (`basic` is then unrolled).
    pub tracyl_diameter: Option<f64>,
    /// `false`: the tip is the BCS of a workpiece turned by axes the kinematics do not know.
    pub exact: bool,
}

impl HistoryPoint {
    /// Same block, same kind of coordinates.
    fn same_kind(&self, other: &HistoryPoint) -> bool {
        self.line == other.line && self.tracyl_diameter == other.tracyl_diameter && self.exact == other.exact
    }
}

/// The thinned executed path of one session.
#[derive(Debug, Default)]
pub struct PathHistory {
    /// The kept points, oldest first.
    points: Vec<HistoryPoint>,
    /// Samples since the last kept point, checked against the chord: the corners of a
    /// polyline through every tip since (a straight stretch by its ends).
    since: Vec<[f64; 3]>,
    /// The unit direction of the straight stretch that ends in the last sample (from the
    /// sample or kept point before it); `None`: the last sample starts no stretch.
    stretch: Option<[f64; 3]>,
    /// The newest tip (the end of the path; kept once the path turns away from it).
    head: Option<HistoryPoint>,
    /// Times the path was halved since the session started.
    halvings: u32,
    /// IPO cycles looked at.
    recorded: u64,
    probe: TipProbe,
}

impl PathHistory {
    /// Looks at the cycle the channel has just interpolated.
    pub fn observe(&mut self, ch: &Channel) {
        self.recorded += 1;
        let t = self.probe.tip(ch);
        self.push(HistoryPoint {
            basic: t.tip,
            line: ch.line_in_execution(),
            tracyl_diameter: t.tracyl_diameter,
            exact: t.exact,
        });
    }

    fn push(&mut self, p: HistoryPoint) {
        let Some(head) = self.head.replace(p) else {
            self.keep(p);
            return;
        };
        let anchor = self.points.last().copied().unwrap_or(head);
        if !head.same_kind(&p) {
            // A block end (or another kind of coordinates): the point it ended at stays.
            if head != anchor {
                self.keep(head);
            }
            return;
        }
        if dist(&head.basic, &p.basic) == 0.0 {
            // Standing: the head stays where it was.
            self.head = Some(head);
            return;
        }
        let chord = Chord::new(&anchor.basic, &p.basic);
        if chord.off(&head.basic) || self.since.iter().any(|q| chord.off(q)) {
            self.keep(head);
            return;
        }
        self.sample(&anchor.basic, head.basic);
    }

    /// Adds `q` (a tip within the tolerance of the chord) to the samples: it extends the
    /// straight stretch of the last sample, or becomes a sample of its own at least
    /// [`TOLERANCE`] from the last one.
    fn sample(&mut self, anchor: &[f64; 3], q: [f64; 3]) {
        let n = self.since.len();
        if let Some(dir) = self.stretch
            && n >= 1
        {
            let start = if n >= 2 { self.since[n - 2] } else { *anchor };
            if on_ray(&start, &dir, &self.since[n - 1], &q) {
                self.since[n - 1] = q;
                return;
            }
        }
        let from = self.since.last().copied().unwrap_or(*anchor);
        let d = dist(&from, &q);
        if d < TOLERANCE {
            return;
        }
        if self.since.len() >= PROBES {
            let mut i = 0;
            self.since.retain(|_| {
                i += 1;
                i % 2 == 0
            });
        }
        self.since.push(q);
        // A halving keeps every second sample and the last one, so `from` stays q's corner.
        self.stretch = Some([(q[0] - from[0]) / d, (q[1] - from[1]) / d, (q[2] - from[2]) / d]);
    }

    /// Makes `p` a kept point (the chord starts anew there).
    fn keep(&mut self, p: HistoryPoint) {
        self.since.clear();
        self.stretch = None;
        let n = self.points.len();
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

    /// The path, oldest first: the kept points and the newest tip.
    pub fn points(&self) -> Vec<HistoryPoint> {
        let mut out = self.points.clone();
        if let Some(head) = self.head
            && out.last() != Some(&head)
        {
            out.push(head);
        }
        out
    }

    /// How often the path was halved to stay within [`CAPACITY`].
    pub fn halvings(&self) -> u32 {
        self.halvings
    }

    /// IPO cycles looked at since the session started.
    pub fn recorded(&self) -> u64 {
        self.recorded
    }
}

/// The chord from the last kept point to the newest tip, for squared distances.
struct Chord {
    a: [f64; 3],
    ab: [f64; 3],
    /// 1 / |ab|², 0 for a chord of no length.
    inv_len2: f64,
}

impl Chord {
    fn new(a: &[f64; 3], b: &[f64; 3]) -> Chord {
        let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
        Chord { a: *a, ab, inv_len2: if len2 > 0.0 { 1.0 / len2 } else { 0.0 } }
    }

    /// Whether `p` is farther than [`TOLERANCE`] from the chord (the segment).
    #[inline]
    fn off(&self, p: &[f64; 3]) -> bool {
        let ap = [p[0] - self.a[0], p[1] - self.a[1], p[2] - self.a[2]];
        let t = ((ap[0] * self.ab[0] + ap[1] * self.ab[1] + ap[2] * self.ab[2]) * self.inv_len2).clamp(0.0, 1.0);
        let d = [ap[0] - t * self.ab[0], ap[1] - t * self.ab[1], ap[2] - t * self.ab[2]];
        d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > TOLERANCE * TOLERANCE
    }
}

/// Whether `q` lies on the ray from `start` along the unit `dir` (within [`STRAIGHT`]) and
/// beyond `last`.
#[inline]
fn on_ray(start: &[f64; 3], dir: &[f64; 3], last: &[f64; 3], q: &[f64; 3]) -> bool {
    let v = [q[0] - start[0], q[1] - start[1], q[2] - start[2]];
    // |v × dir|: the distance from the ray's line.
    let c = [v[1] * dir[2] - v[2] * dir[1], v[2] * dir[0] - v[0] * dir[2], v[0] * dir[1] - v[1] * dir[0]];
    let off2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    let ahead = (q[0] - last[0]) * dir[0] + (q[1] - last[1]) * dir[1] + (q[2] - last[2]) * dir[2];
    off2 <= STRAIGHT * STRAIGHT && ahead > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64) -> HistoryPoint {
        HistoryPoint { basic: [x, y, 0.0], line: 1, tracyl_diameter: None, exact: true }
    }

    fn kept(h: &PathHistory) -> Vec<[f64; 3]> {
        h.points().iter().map(|p| p.basic).collect()
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
        let kept = kept(&h);
        assert_eq!(kept.len(), 3, "{kept:?}");
        assert!(dist(&kept[1], &[10.0, 0.0, 0.0]) < 1e-9 && dist(&kept[2], &[10.0, 5.0, 0.0]) < 1e-9, "{kept:?}");
    }

    #[test]
    fn an_arc_is_kept_within_the_tolerance_whatever_the_sampling() {
        // A quarter circle of radius 10 sampled every 0.01 rad (0.1 mm: a fast cycle) and every
        // 0.001 rad. A chord of a circle of radius R deviates from the arc by its sagitta
        // R − √(R² − (c/2)²); within 0.01 mm for R = 10: c ≤ 2√(100 − 9.99²) = 0.894 mm, so the
        // quarter (15.71 mm) needs at least 15.71 / 0.894 = 17.6, i.e. 18 chords; and every
        // chord's middle is within 0.01 mm (+ one sample's sagitta) of the circle.
        for step in [0.01, 0.001] {
            let mut h = PathHistory::default();
            let n = (std::f64::consts::FRAC_PI_2 / step).round() as usize;
            for i in 0..=n {
                let a = i as f64 * step;
                h.push(at(10.0 * a.cos(), 10.0 * a.sin()));
            }
            let kept = kept(&h);
            assert!(kept.len() >= 19, "{step}: {}", kept.len());
            assert!(kept.len() <= 40, "{step}: thinned by geometry, not by time: {}", kept.len());
            for w in kept.windows(2) {
                let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0, 0.0];
                let r = (mid[0] * mid[0] + mid[1] * mid[1]).sqrt();
                assert!(10.0 - r <= TOLERANCE + 1e-3, "{step}: chord {w:?} sags {}", 10.0 - r);
            }
        }
    }

    #[test]
    fn a_straight_run_is_checked_against_its_end_alone() {
        // 10,000 cycles along one line in space: nothing but its ends is kept, and the chord
        // is checked against one sample (the stretch's end), not PROBES of them.
        let mut h = PathHistory::default();
        for i in 0..10_000 {
            let s = f64::from(i) * 0.05;
            h.push(HistoryPoint { basic: [0.3 * s, -0.2 * s, 0.1 * s], ..at(0.0, 0.0) });
        }
        assert!(h.since.len() <= 1, "{} samples", h.since.len());
        assert_eq!(h.points().len(), 2);
    }

    /// The largest distance of `samples` from the polyline `kept`.
    fn deviation(samples: &[[f64; 3]], kept: &[[f64; 3]]) -> f64 {
        samples
            .iter()
            .map(|q| {
                kept.windows(2).map(|w| crate::api::preview::off_line(&w[0], &w[1], q)).fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn every_tip_of_a_gently_turning_polyline_stays_within_the_tolerance() {
        // Segments of 5 mm turning by a small angle, sampled every 0.37 mm (a fast cycle). A
        // turn of 0.1° at a corner puts it 5 · sin(0.05°) = 0.0044 mm from the chord over the
        // two segments, so chords span several corners and only the corners held as samples
        // keep them within 0.01 mm; 0.2° the same way round bends the path into an arc.
        for (turn, alternate) in [(0.1_f64, true), (0.2, false), (1.0, true)] {
            let mut h = PathHistory::default();
            let (mut at_, mut heading, mut samples) = ([0.0, 0.0, 0.0], 0.0_f64, Vec::new());
            for k in 0..200 {
                let dir = [heading.to_radians().cos(), heading.to_radians().sin(), 0.0];
                let n = 14;
                for i in 0..n {
                    let s = 5.0 * f64::from(i) / f64::from(n);
                    samples.push([at_[0] + s * dir[0], at_[1] + s * dir[1], 0.0]);
                }
                at_ = [at_[0] + 5.0 * dir[0], at_[1] + 5.0 * dir[1], 0.0];
                heading += if alternate && k % 2 == 1 { -turn } else { turn };
            }
            samples.push(at_);
            for q in &samples {
                h.push(HistoryPoint { basic: *q, ..at(0.0, 0.0) });
            }
            let kept = kept(&h);
            let worst = deviation(&samples, &kept);
            assert!(worst <= TOLERANCE + 1e-6, "{turn}°: a tip {worst} mm from the kept path");
            assert!(kept.len() < samples.len() / 4, "{turn}°: {} of {}", kept.len(), samples.len());
        }
    }

    #[test]
    fn a_block_end_is_kept_even_on_a_straight_line() {
        let mut h = PathHistory::default();
        for i in 0..=20 {
            h.push(HistoryPoint { line: if i <= 10 { 1 } else { 2 }, ..at(f64::from(i), 0.0) });
        }
        let lines: Vec<u32> = h.points().iter().map(|p| p.line).collect();
        assert_eq!(kept(&h), vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [20.0, 0.0, 0.0]]);
        assert_eq!(lines, vec![1, 1, 2]);
    }

    #[test]
    fn a_long_path_is_halved_and_stays_bounded_with_its_last_point() {
        let mut h = PathHistory::default();
        // A zigzag of 3 × CAPACITY points: every one a corner.
        let n = 3 * CAPACITY;
        for i in 0..n {
            h.push(at(i as f64, (i % 2) as f64));
        }
        assert!(h.points().len() <= CAPACITY + 1, "{}", h.points().len());
        assert!(h.halvings() >= 2);
        assert_eq!(h.points().first().map(|p| p.basic), Some([0.0, 0.0, 0.0]));
        assert_eq!(h.points().last().map(|p| p.basic), Some([(n - 1) as f64, 1.0, 0.0]));
    }

    #[test]
    fn a_reversal_on_a_line_keeps_its_turning_point() {
        // X 0 → 10 → 5: the chord 0 → 5 passes 5 mm from the turning point.
        let mut h = PathHistory::default();
        for i in 0..=10 {
            h.push(at(f64::from(i), 0.0));
        }
        for i in 1..=5 {
            h.push(at(10.0 - f64::from(i), 0.0));
        }
        assert_eq!(kept(&h), vec![[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [5.0, 0.0, 0.0]]);
    }
}
