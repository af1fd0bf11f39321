//! The program's dynamics words: G group 21 (`BRISK`, `SOFT`, `DRIVE`), G group 24 (`FFWOF`,
//! `FFWON`), G group 59 (`DYNNORM`, `DYNPOS`, `DYNROUGH`, `DYNSEMIFIN`, `DYNFINISH`) and the
//! axial percentages `ACC[axis]=`, `JERKLIM[axis]=`, `VELOLIM[axis]=`.
//!
//! Input: a block's keywords and addresses. Output: [`DynModal`], part of the modal state, and
//! the limits of each prepared move ([`apply`]): the dynamic response mode picks element `n` of
//! MD32300/MD32310/MD32431, ACC and VELOLIM scale acceleration and velocity, and under SOFT the
//! move carries a path jerk (the planner's jerk-limited profile). FFWON/FFWOF reach the main run
//! through the block's G codes (`channel/servo.rs`).
//!
//! Decisions where the manuals leave room:
//! - `DRIVE` is BRISK with the knee-shaped acceleration of B2 (`motion/drive.rs`): a line
//!   carries the speed-dependent curve of its axes (each read at its share of the path speed);
//!   an arc, a rounding element and a move planned through a transformation get B2's
//!   "substitute characteristic", a constant acceleration: the lowest the axes reach on the
//!   move (at the move's top speed; under a transformation `a_red`). With the data's defaults
//!   (MD35220 = 1, MD35230 = 0) DRIVE moves exactly as BRISK. Positioning axes (DRIVEA) are
//!   not modelled.
//! - `ACC[axis]=0`, `JERKLIM[axis]=0` and `VELOLIM[axis]=0` switch the limit back to 100 %, as
//!   the Programming Manual describes for ACC; every percentage is back at 100 % after reset.
//! - Moves already planned through a transformation (machine-axis rates) are scaled by the
//!   smallest ratio over their axes instead of being re-limited axis by axis.

use super::Item;
use super::eval::scope::{Ctx, SysView};
use super::eval::vars::Variables;
use super::eval::{eval, eval_f64};
use crate::alarm::Alarm;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;
use crate::machine_data::dynamics::{DYN_MODE_NAMES, Profile};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::drive::DriveCurve;
use crate::motion::{AxisLimit, AxisLimits, Feed, Move};

/// Which axial percentage a word sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Percent {
    /// `ACC[axis]`: 1..200 % of the axis acceleration.
    Acc,
    /// `JERKLIM[axis]`: 1..200 % of the axis jerk (SOFT).
    JerkLim,
    /// `VELOLIM[axis]`: 1..100 % of the axis velocity.
    VeloLim,
}

impl Percent {
    /// The word's name, if `name` is one of them.
    pub fn of(name: &str) -> Option<Percent> {
        match name {
            "ACC" => Some(Percent::Acc),
            "JERKLIM" => Some(Percent::JerkLim),
            "VELOLIM" => Some(Percent::VeloLim),
            _ => None,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Percent::Acc => "ACC",
            Percent::JerkLim => "JERKLIM",
            Percent::VeloLim => "VELOLIM",
        }
    }

    /// The largest percentage the control accepts.
    fn max(self) -> f64 {
        match self {
            Percent::Acc | Percent::JerkLim => 200.0,
            Percent::VeloLim => 100.0,
        }
    }
}

/// The modal dynamics of block preparation.
#[derive(Debug, Clone, PartialEq)]
pub struct DynModal {
    /// G group 21.
    pub profile: Profile,
    /// G group 24: FFWON.
    pub ffw: bool,
    /// G group 59: index of the dynamic response mode (0 DYNNORM .. 4 DYNFINISH).
    pub mode: usize,
    /// ACC, JERKLIM, VELOLIM per channel axis as factors; `None` while all are 100 %, so the
    /// modal state stays small and plain programs pay nothing.
    factors: Option<Box<[[f64; MAX_CHANNEL_AXES]; 3]>>,
    /// Some channel axis reduces its acceleration under DRIVE (MD35220/MD35230): DRIVE
    /// shapes the moves.
    drive_reduces: bool,
}

impl DynModal {
    /// The reset state of the machine data (MD20150 for groups 21, 24, 59; all at 100 %).
    pub fn reset(cfg: &MachineConfig) -> DynModal {
        let d = &cfg.dynamics;
        let n = cfg.channel_axes.len().min(MAX_CHANNEL_AXES);
        let drive_reduces = (0..n).any(|k| {
            let a = cfg.axis(k);
            a.dynamics.knee(a.max_accel, a.max_velocity).is_some()
        });
        DynModal { profile: d.reset_profile, ffw: d.reset_ffw, mode: d.reset_mode, factors: None, drive_reduces }
    }

    /// True when moves are planned with other limits than the axes' DYNNORM data under BRISK
    /// (the fast lane steps aside then, and [`apply`] re-limits every move).
    pub fn shapes_moves(&self) -> bool {
        self.profile == Profile::Soft
            || self.mode != 0
            || self.factors.is_some()
            || (self.profile == Profile::Drive && self.drive_reduces)
    }

    /// The percentage of `which` for channel axis `k`, as a factor.
    pub fn factor(&self, which: Percent, k: usize) -> f64 {
        self.factors.as_ref().map_or(1.0, |f| f[which as usize][k])
    }

    /// Applies a block's dynamics words.
    pub(super) fn apply(&mut self, w: &DynWords) {
        if let Some(p) = w.profile {
            self.profile = p;
        }
        if let Some(f) = w.ffw {
            self.ffw = f;
        }
        if let Some(m) = w.mode {
            self.mode = m;
        }
        for &(which, k, percent) in &w.percents {
            let f = self.factors.get_or_insert_with(|| Box::new([[1.0; MAX_CHANNEL_AXES]; 3]));
            f[which as usize][k] = if percent == 0.0 { 1.0 } else { percent / 100.0 };
        }
        if self.factors.as_ref().is_some_and(|f| f.iter().flatten().all(|&x| x == 1.0)) {
            self.factors = None;
        }
    }

    /// The limits a move is planned with: element `mode` of the per-mode data, scaled by ACC
    /// and VELOLIM.
    fn limits(&self, cfg: &MachineConfig) -> AxisLimits {
        let mut out = AxisLimit::for_channel(cfg);
        let n = out.len();
        let mut limits = [AxisLimit { max_velocity: 0.0, max_accel: 0.0, accel_overload: 1.0 }; MAX_CHANNEL_AXES];
        for (k, l) in limits[..n].iter_mut().enumerate() {
            let d = &cfg.axis(k).dynamics;
            *l = AxisLimit {
                max_velocity: out[k].max_velocity * self.factor(Percent::VeloLim, k),
                max_accel: d.accel[self.mode] * self.factor(Percent::Acc, k),
                accel_overload: d.overload[self.mode],
            };
        }
        out = AxisLimits::from(&limits[..n]);
        out
    }

    /// The acceleration of channel axis `k`: the mode's, ACC applied.
    fn axis_accel(&self, cfg: &MachineConfig, k: usize) -> f64 {
        cfg.axis(k).dynamics.accel[self.mode] * self.factor(Percent::Acc, k)
    }

    /// The jerk of channel axis `k` under SOFT (mm/s³ or deg/s³), JERKLIM applied.
    fn axis_jerk(&self, cfg: &MachineConfig, k: usize) -> f64 {
        cfg.axis(k).dynamics.jerk[self.mode] * self.factor(Percent::JerkLim, k)
    }
}

/// The dynamics words of one block.
#[derive(Debug, Clone, Default)]
pub struct DynWords {
    pub profile: Option<Profile>,
    pub ffw: Option<bool>,
    pub mode: Option<usize>,
    /// `ACC[X]=50` and its kin: (which, channel axis, percent).
    pub percents: Vec<(Percent, usize, f64)>,
}

impl DynWords {
    /// Takes a keyword of groups 21, 24, 59; false if `name` is none of them. Of two
    /// functions of one group in a block the last one holds, as for every G group here.
    pub(super) fn keyword(&mut self, name: &str) -> bool {
        match name {
            "BRISK" => self.profile = Some(Profile::Brisk),
            "SOFT" => self.profile = Some(Profile::Soft),
            "DRIVE" => self.profile = Some(Profile::Drive),
            "FFWON" => self.ffw = Some(true),
            "FFWOF" => self.ffw = Some(false),
            _ => match DYN_MODE_NAMES.iter().position(|n| *n == name) {
                Some(m) => self.mode = Some(m),
                None => return false,
            },
        }
        true
    }

    /// `ACC[axis]=value` and its kin: checks the axis and the range (alarm 12560 outside
    /// 0..=200 %, VELOLIM 0..=100 %).
    #[allow(clippy::too_many_arguments, reason = "the evaluation context of a block word")]
    pub(super) fn percent(
        &mut self,
        which: Percent,
        indices: &[Expr],
        value: &Expr,
        cfg: &MachineConfig,
        vars: &Variables,
        sys: &SysView,
        line: u32,
    ) -> Result<(), Alarm> {
        let name = which.name();
        let [index] = indices else {
            return Err(Alarm::index_error(line, name, "needs one axis name"));
        };
        let axis_name = eval(index, &Ctx { vars, sys }, line)?.as_text().to_ascii_uppercase();
        let k =
            cfg.program_axis(&axis_name).ok_or_else(|| Alarm::unknown_name(line, &format!("{name}[{axis_name}]")))?;
        let v = eval_f64(value, &Ctx { vars, sys }, line)?;
        if !(0.0..=which.max()).contains(&v) {
            return Err(Alarm::value_out_of_range(line, &format!("{name}[{axis_name}]={v} (0..{})", which.max())));
        }
        self.percents.push((which, k, v));
        Ok(())
    }
}

/// Plans the moves among `items` with the limits of `dynamics` (see the module doc); each
/// move's path jerk under SOFT. Nothing to do for BRISK, DYNNORM and 100 %.
pub(super) fn apply(dynamics: &DynModal, cfg: &MachineConfig, items: &mut [Item]) {
    if !dynamics.shapes_moves() {
        return;
    }
    let base = AxisLimit::for_channel(cfg);
    let limits = dynamics.limits(cfg);
    for item in items {
        let Item::Move { mv, .. } = item else { continue };
        relimit(mv, &base, &limits);
        if dynamics.profile == Profile::Soft {
            mv.jerk = path_jerk(mv, dynamics, cfg);
            mv.seam_jerk = seam_jerk(mv, dynamics, cfg);
            if let Some(arc) = mv.path.arc.as_deref() {
                let n = cfg.channel_axes.len().min(MAX_CHANNEL_AXES);
                let plane = (0..n).filter(|&k| arc.moves_axis(k)).map(|k| dynamics.axis_jerk(cfg, k));
                mv.limit_arc_jerk(plane.fold(f64::INFINITY, f64::min));
            }
        }
        if dynamics.profile == Profile::Drive {
            drive(mv, dynamics, cfg);
        }
    }
}

/// DRIVE: a line gets its axes' speed-dependent acceleration ([`DriveCurve`]) and the lowest
/// value of it as `a_max` (what the look-ahead plans with); every other move a constant
/// substitute (see the module doc).
fn drive(mv: &mut Move, dynamics: &DynModal, cfg: &MachineConfig) {
    let n = cfg.channel_axes.len().min(MAX_CHANNEL_AXES);
    let knee = |k: usize| cfg.axis(k).dynamics.knee(dynamics.axis_accel(cfg, k), cfg.axis(k).max_velocity);
    if mv.axis_tangents.is_some() || mv.machine_space {
        // Planned through a transformation: the machine axes' speeds are not the path's
        // shares; the lowest acceleration any axis reaches (at its MD32000).
        let ratio = (0..n).filter_map(|k| knee(k).map(|kn| kn.a_red / kn.a_max)).fold(1.0, f64::min);
        mv.a_max *= ratio;
        return;
    }
    let rates = mv.path.max_rate_of_first(n);
    let share = |k: usize| rates[k] / mv.length;
    if mv.path.arc.is_none() && mv.path.curve.is_none() {
        let axes = (0..n).filter_map(|k| knee(k).map(|kn| (kn, share(k))));
        if let Some(curve) = DriveCurve::of(mv.a_max, axes) {
            mv.a_max = curve.accel_at(mv.v_axes);
            mv.drive = Some(Box::new(curve));
        }
        return;
    }
    // An arc or a curve: each axis at its highest share of the move's top speed.
    let ratio = (0..n)
        .filter(|&k| share(k) > 1e-12)
        .filter_map(|k| knee(k).map(|kn| kn.accel_at(share(k) * mv.v_axes) / kn.a_max))
        .fold(1.0, f64::min);
    mv.a_max *= ratio;
}

/// Sets the move's velocity and acceleration limits to `limits` in place of `base`.
fn relimit(mv: &mut Move, base: &[AxisLimit], limits: &[AxisLimit]) {
    if mv.axis_tangents.is_none() && !mv.machine_space {
        let feed = if mv.is_rapid() { Feed::Rapid } else { Feed::Path(mv.feed) };
        // VELOLIM only lowers velocities: keep any lower one the preparation set.
        let (v_max, v_axes) = (mv.v_max, mv.v_axes);
        mv.set_limits(mv.length, feed, limits);
        mv.v_max = mv.v_max.min(v_max);
        mv.v_axes = mv.v_axes.min(v_axes);
        return;
    }
    let ratio = |f: fn(&AxisLimit) -> f64| {
        base.iter().zip(limits).map(|(b, l)| if f(b) > 0.0 { f(l) / f(b) } else { 1.0 }).fold(f64::INFINITY, f64::min)
    };
    let (rv, ra) = (ratio(|l| l.max_velocity).min(1.0), ratio(|l| l.max_accel));
    if rv.is_finite() {
        mv.v_max *= rv;
        mv.v_axes *= rv;
    }
    if ra.is_finite() {
        mv.a_max *= ra;
    }
}

/// The jerk the moving axes may see at a transition where the curvature jumps (the smallest
/// over them): MD32432 where it exceeds the axis jerk (see `motion/soft_curvature.rs`).
fn seam_jerk(mv: &Move, dynamics: &DynModal, cfg: &MachineConfig) -> f64 {
    let n = cfg.channel_axes.len().min(MAX_CHANNEL_AXES);
    let rates = mv.path.max_rate_of_first(n);
    (0..n)
        .filter(|&k| rates[k] > 1e-12 * mv.length)
        .map(|k| dynamics.axis_jerk(cfg, k).max(cfg.axis(k).dynamics.trans_jerk))
        .fold(f64::INFINITY, f64::min)
}

/// The highest path jerk with which no axis exceeds its jerk: each axis moves at `rate_k` per
/// unit path length, so its jerk is `rate_k · j_path` on a line (curvature terms of an arc are
/// covered by the planner's arc acceleration margin); capped by MD20600.
fn path_jerk(mv: &Move, dynamics: &DynModal, cfg: &MachineConfig) -> f64 {
    let n = cfg.channel_axes.len().min(MAX_CHANNEL_AXES);
    let rates = mv.path.max_rate_of_first(n);
    let mut j = cfg.dynamics.path_jerk;
    for (k, rate) in rates[..n].iter().enumerate() {
        let d = rate / mv.length;
        if d > 1e-12 {
            j = j.min(dynamics.axis_jerk(cfg, k) / d);
        }
    }
    j
}
