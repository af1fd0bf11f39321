//! The simulated touch-trigger probe of MEAS/MEAW (`interp/measuring.rs`).
//!
//! The probe is the active tool: a ball of the cutting edge's radius (`$TC_DP6` + `$TC_DP15`)
//! whose centre is the tool tip (the tool length reaches the ball's centre). It is deflected
//! while the ball touches material: the session's stock (`channel/stock/cut.rs`, read through
//! the stock's public cells and slabs) or one of the probe-target planes set over the API
//! ([`ProbeTarget`]). The ball touches the stock when its point ahead in the direction of travel
//! (rising edge; the point behind for a falling edge) is inside it; it touches a plane when its
//! centre is no more than the radius in front of it. The stock is tested in its own frame: on a
//! table that has turned or tilted it (a TRAORI chain's workpiece side, `stock/table.rs`) the
//! ball's centre and direction of travel are taken back through the table's pose
//! (`Channel::stock_tip_at`), so the face is found where the table has put it.
//!
//! Each IPO cycle of a measuring block the probe looks at the straight piece between the last
//! sample and this one: in steps of at most half the stock's resolution, then by bisection to
//! 1e-9 of the piece, it finds where the signal switches. The switching point is exact on the
//! interpolated path, not the cycle's end sample. MEAS then stops the axes at that point (the
//! distance to go is deleted; NCTwin does not model the braking distance: the ball stops
//! touching the face); MEAW lets the block run on.
//!
//! Alarms (as the control raises them): 21700 the probe is already deflected at the start of a
//! rising-edge job, 21703 it is not deflected at the start of a falling-edge job; 21702 (an
//! information: the program goes on and reads `$AC_MEA[n]` = 0) the block ended without a switch.

use super::Channel;
use crate::alarm::{Alarm, Clear};
use crate::interp::Item;
use crate::interp::measuring::{Request, Results};
use crate::motion::AxisVec;
use crate::stock::Stock;

/// A plane the probe touches: material on the side opposite to `normal` (BCS, mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeTarget {
    /// A point of the surface.
    pub point: [f64; 3],
    /// The outward normal (any length but zero).
    pub normal: [f64; 3],
}

/// The most probe-target planes a session keeps.
pub const MAX_PROBE_TARGETS: usize = 16;

/// A measuring job in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Job {
    request: Request,
    line: u32,
    /// The machine position at the last sample.
    last: AxisVec,
    /// The block's move has reached the planner.
    started: bool,
}

/// The probe's state in the main run.
#[derive(Debug, Clone, Default)]
pub(super) struct Probe {
    job: Option<Job>,
    targets: Vec<ProbeTarget>,
    results: Results,
    /// Material intervals of one dexel cell (reused).
    cell: Vec<[f32; 2]>,
}

impl Probe {
    /// Whether a measuring job runs (checked every IPO cycle: nothing else then).
    #[inline]
    pub(super) fn armed(&self) -> bool {
        self.job.is_some()
    }

    /// A reset ends any job.
    pub(super) fn disarm(&mut self) {
        self.job = None;
    }
}

impl Channel {
    /// The probe-target planes (BCS).
    pub fn probe_targets(&self) -> &[ProbeTarget] {
        &self.probe.targets
    }

    /// Replaces the probe-target planes; `Err` names a plane that is not one.
    pub fn set_probe_targets(&mut self, targets: Vec<ProbeTarget>) -> Result<(), super::CommandError> {
        if targets.len() > MAX_PROBE_TARGETS {
            return Err(super::CommandError::Invalid(format!("at most {MAX_PROBE_TARGETS} probe targets")));
        }
        for (i, t) in targets.iter().enumerate() {
            let finite = t.point.iter().chain(&t.normal).all(|v| v.is_finite());
            if !finite || dot(t.normal, t.normal) < 1e-18 {
                return Err(super::CommandError::Invalid(format!(
                    "probe target {i}: a finite point and a non-zero normal are needed"
                )));
            }
        }
        self.probe.targets = targets
            .into_iter()
            .map(|t| {
                let n = dot(t.normal, t.normal).sqrt();
                ProbeTarget { point: t.point, normal: t.normal.map(|c| c / n) }
            })
            .collect();
        Ok(())
    }

    /// The main run reaches a MEAS/MEAW block: the job starts, `$AC_MEA[n]` is 0 until the
    /// probe switches. `false` with an alarm raised when the probe's state forbids the edge.
    pub(super) fn arm_probe(&mut self, request: Request, line: u32) {
        let n = usize::from(request.probe - 1);
        self.probe.results.triggered[n] = false;
        self.interp.set_measured(self.probe.results);
        let here = self.machine;
        let deflected = self.probe_touches(&here, [0.0; 3], request.rising);
        if deflected == request.rising {
            let (number, what) = if request.rising { (21700, "already") } else { (21703, "not") };
            self.raise(Alarm {
                number,
                message: format!(
                    "Channel 1 block {line} probe {} {what} deflected, edge measurement not possible",
                    request.probe
                ),
                line: Some(line),
                clear: Clear::Reset,
            });
            return;
        }
        self.probe.job = Some(Job { request, line, last: here, started: false });
    }

    /// One IPO cycle of a measuring job (after the machine position was updated).
    #[inline(never)]
    pub(super) fn step_probe(&mut self) {
        let Some(mut job) = self.probe.job else { return };
        let current = self.in_planner.front().map(|(_, m)| m.line);
        if current == Some(job.line) {
            job.started = true;
        } else if job.started || !self.block_move_pending(job.line) {
            // The block is over without a switch.
            self.probe.job = None;
            self.notify_alarm(Alarm {
                number: 21702,
                message: format!(
                    "Channel 1 block {} probe {} measurement aborted: no switch",
                    job.line, job.request.probe
                ),
                line: Some(job.line),
                clear: Clear::Cancel,
            });
            return;
        }
        let (a, b) = (job.last, self.machine);
        job.last = b;
        self.probe.job = Some(job);
        if a == b {
            return;
        }
        let Some(s) = self.switch_point(&a, &b, job.request.rising) else { return };
        let at: AxisVec = std::array::from_fn(|k| a[k] + s * (b[k] - a[k]));
        self.probe_switched(job, at);
    }

    /// Whether the prepared items still hold a move of `line` (the job waits for it).
    fn block_move_pending(&self, line: u32) -> bool {
        self.pending.iter().any(|i| matches!(i, Item::Move { line: l, .. } if *l == line))
    }

    /// Records the switch at machine position `at` and, for MEAS, ends the block there.
    fn probe_switched(&mut self, job: Job, at: AxisVec) {
        self.probe.job = None;
        let n = usize::from(job.request.probe - 1);
        let results = &mut self.probe.results;
        results.triggered[n] = true;
        results.machine = at;
        let mut basic = at;
        for (b, t) in basic.iter_mut().zip(&self.offsets.tool) {
            *b -= t;
        }
        for (g, k) in self.cfg.geo_axes.iter().enumerate() {
            if let Some(k) = k {
                basic[*k] -= self.toff.current[g];
            }
        }
        results.workpiece = self
            .offsets
            .frame
            .unapply(&self.cfg.geo_axes, &basic)
            .unwrap_or([f64::NAN; crate::machine_data::registry::MAX_CHANNEL_AXES]);
        self.interp.set_measured(self.probe.results);
        if !job.request.delete_distance {
            return;
        }
        // Delete the distance to go: the block ends where the probe switched.
        self.planner.abort();
        self.in_planner.clear();
        while matches!(self.pending.front(), Some(Item::Move { line: l, .. }) if *l == job.line) {
            self.pending.pop_front();
        }
        self.planner.set_position(at);
        self.machine = at;
        self.sync.wake_all();
        self.interp.sync_position(&at);
    }

    /// The fraction of the piece `a` → `b` (machine positions) where the probe's signal first
    /// switches to the state of the job's edge; `None` if it does not on this piece.
    fn switch_point(&mut self, a: &AxisVec, b: &AxisVec, rising: bool) -> Option<f64> {
        let geo = self.cfg.geo_axes;
        let dir: [f64; 3] = std::array::from_fn(|g| geo[g].map_or(0.0, |k| b[k] - a[k]));
        let len = dot(dir, dir).sqrt();
        let at = |s: f64| -> AxisVec { std::array::from_fn(|k| a[k] + s * (b[k] - a[k])) };
        // The direction of travel relative to the stock (a table may have turned it).
        let (sa, sb) = (self.stock_tip_at(a), self.stock_tip_at(b));
        let rel = sub(sb, sa);
        let n = dot(rel, rel).sqrt();
        let unit = if n > 0.0 { rel.map(|c| c / n) } else { [0.0; 3] };
        let step = match &self.stock {
            Some(run) => run.stock().resolution() / 2.0,
            None => f64::INFINITY,
        };
        let pieces = (len / step).ceil().clamp(1.0, 256.0) as usize;
        let mut lo = 0.0;
        let mut hi = None;
        for i in 1..=pieces {
            let s = i as f64 / pieces as f64;
            if self.probe_touches(&at(s), unit, rising) == rising {
                hi = Some(s);
                break;
            }
            lo = s;
        }
        let mut hi = hi?;
        while hi - lo > 1e-9 {
            let mid = 0.5 * (lo + hi);
            if self.probe_touches(&at(mid), unit, rising) == rising {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(hi)
    }

    /// Whether the probe ball at machine position `m`, travelling along `unit` (the stock's
    /// frame), touches material; the stock is tested at the ball's point ahead (`rising`) or
    /// behind, in its own frame (on a turned table where the table has put it).
    fn probe_touches(&mut self, m: &AxisVec, unit: [f64; 3], rising: bool) -> bool {
        let geo = self.cfg.geo_axes;
        let toff = self.toff.current;
        let offsets = &self.offsets;
        let centre: [f64; 3] = std::array::from_fn(|g| geo[g].map_or(0.0, |k| m[k] - offsets.tool[k] - toff[g]));
        let radius = self.cfg.edge(offsets.t, offsets.d).map_or(0.0, |p| (p[5] + p[14]).max(0.0));
        if self.probe.targets.iter().any(|t| dot(sub(centre, t.point), t.normal) <= radius) {
            return true;
        }
        if self.stock.is_none() {
            return false;
        }
        let centre = self.stock_tip_at(m);
        let Some(run) = &self.stock else { return false };
        let sign = if rising { radius } else { -radius };
        let p: [f64; 3] = std::array::from_fn(|g| centre[g] + sign * unit[g]);
        inside(run.stock(), p, &mut self.probe.cell)
    }
}

/// Whether BCS point `p` is in the stock's material (a dexel cell's interval or a slab's ring).
fn inside(stock: &Stock, p: [f64; 3], cell: &mut Vec<[f32; 2]>) -> bool {
    match stock {
        Stock::Milling(grid) => {
            let (x0, y0) = grid.origin();
            let (nx, ny) = grid.size();
            let res = grid.resolution();
            let (i, j) = (((p[0] - x0) / res).floor(), ((p[1] - y0) / res).floor());
            if !(0.0..nx as f64).contains(&i) || !(0.0..ny as f64).contains(&j) {
                return false;
            }
            grid.intervals(i as usize, j as usize, cell);
            cell.iter().any(|&[lo, hi]| (f64::from(lo)..=f64::from(hi)).contains(&p[2]))
        }
        Stock::Turning(profile) => {
            let (z0, n) = profile.extent();
            let k = ((p[2] - z0) / profile.resolution()).floor();
            if !(0.0..n as f64).contains(&k) {
                return false;
            }
            let (outer, inner) = profile.radii(k as usize);
            let r = p[0].hypot(p[1]);
            outer > inner && (inner..=outer).contains(&r)
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
