//! REPOS target modes: where on the interrupted block the program resumes after JOG.
//!
//! The control's G group 26 names them (Programming Manual, REPOS): RMI, the interruption point
//! (the default); RMB, the start of the interrupted block; RME, its end; RMN, the point of the
//! interrupted block nearest to where the axes stand. NC start travels from where the axes are
//! to that point on a straight line (REPOSL) and the program goes on from there: with RMB the
//! whole block again, with RME the next block, with RMN the rest of the block from that point.
//!
//! "The interrupted block" is the move the program's main run was executing (or about to start)
//! when it was interrupted. A block that a transformation split into several moves (the TRANSMIT
//! pole) restarts from the start of the part being executed. Interrupted between blocks (M0),
//! every mode returns to where the program stopped.

use crate::channel::Channel;
use crate::kinematics::Transformation;
use crate::motion::{AxisVec, Path, Planner};

/// Where the program resumes after JOG in an interrupted program (G group 26).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReposMode {
    /// RMI: the interruption point.
    #[default]
    Interruption,
    /// RMB: the start of the interrupted block, which is then travelled again as a whole.
    BlockStart,
    /// RME: the end of the interrupted block; the program goes on with the next block.
    BlockEnd,
    /// RMN: the nearest point of the interrupted block; the rest of the block from there.
    Nearest,
}

impl ReposMode {
    /// The G function's name (RMI, RMB, RME, RMN).
    pub fn name(self) -> &'static str {
        match self {
            ReposMode::Interruption => "RMI",
            ReposMode::BlockStart => "RMB",
            ReposMode::BlockEnd => "RME",
            ReposMode::Nearest => "RMN",
        }
    }

    /// The mode a G function name selects (case-insensitive).
    pub fn from_name(name: &str) -> Option<ReposMode> {
        [ReposMode::Interruption, ReposMode::BlockStart, ReposMode::BlockEnd, ReposMode::Nearest]
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name))
    }
}

/// How the program's main run takes over at the REPOS target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::channel) enum Resume {
    /// Where it was interrupted (RMI, or nothing to choose).
    AsInterrupted,
    /// At this fraction of the interrupted move (RMB: 0, RMN: the nearest point).
    FrontAt(f64),
    /// After the interrupted move (RME).
    SkipFront,
}

/// The REPOS target in the space of the interrupted planner's front move and how the program
/// resumes there. `here` is the axes' position in that space; `dist_axes` the axes whose
/// distance counts for RMN (the geometry axes).
pub(in crate::channel) fn target(
    planner: &Planner,
    mode: ReposMode,
    here: &AxisVec,
    dist_axes: &[usize],
) -> (AxisVec, Resume) {
    let Some(front) = planner.front() else { return (*planner.position(), Resume::AsInterrupted) };
    match mode {
        ReposMode::Interruption => (*planner.position(), Resume::AsInterrupted),
        ReposMode::BlockStart => (front.path.start, Resume::FrontAt(0.0)),
        ReposMode::BlockEnd => (front.path.end, Resume::SkipFront),
        ReposMode::Nearest => {
            let u = nearest_fraction(&front.path, here, dist_axes);
            let mut p = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
            front.path.at(u, &mut p);
            (p, Resume::FrontAt(u))
        }
    }
}

/// The fraction of `path` nearest to `p` (distance over `axes`): the best of 64 samples, then a
/// golden-section search around it (the distance along a line or one arc has one minimum there).
fn nearest_fraction(path: &Path, p: &AxisVec, axes: &[usize]) -> f64 {
    let dist = |u: f64| {
        let mut q = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
        path.at(u, &mut q);
        axes.iter().map(|&k| (q[k] - p[k]).powi(2)).sum::<f64>()
    };
    const SAMPLES: usize = 64;
    let best = (0..=SAMPLES).min_by(|&a, &b| dist(a as f64 / 64.0).total_cmp(&dist(b as f64 / 64.0))).unwrap_or(0);
    let (mut lo, mut hi) = (best.saturating_sub(1) as f64 / 64.0, (best + 1).min(SAMPLES) as f64 / 64.0);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if dist(a) <= dist(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    (lo + hi) / 2.0
}

impl Channel {
    /// The axes whose distance RMN measures: the geometry axes of the program space (all
    /// channel axes for a move in machine axes).
    pub(in crate::channel) fn repos_distance_axes(&self, machine_space: bool) -> Vec<usize> {
        let geo = match &self.trafo {
            Some(t) if !machine_space => t.trafo.geo_slots(),
            Some(_) => return (0..self.cfg.channel_axes.len()).collect(),
            None => self.cfg.geo_axes,
        };
        geo.iter().flatten().copied().collect()
    }
}
