//! Planning one BCS block for the planner while a transformation is active.
//!
//! The planner interpolates the BCS and never learns which transformation maps it; so the
//! per-axis limits must reach it as path limits. For each block this module:
//! 1. rejects a path that enters an unreachable region (TRANSMIT's unmachinable cylinder);
//! 2. cuts the path at pole passages and, where leaving the pole needs another rotary angle
//!    than arriving (a corner in the pole, or `POLE_SIDE_FIX` forbids the radial axis to change
//!    sign), inserts a positioning move of the rotary axis alone in machine space;
//! 3. samples the path densely (every 0.25 mm, at least 8 and at most 400 samples, plus the
//!    transformation's critical points such as the closest approach to the pole), maps each
//!    sample to machine axes with the same continuity rule the channel uses per IPO cycle,
//!    checks the software limits, and takes the machine rates `dm/ds` and their change
//!    `d²m/ds²` by finite differences;
//! 4. limits the path velocity so that every machine axis stays within its velocity
//!    (`v·|dm/ds| ≤ v_max`) and keeps half of its acceleration for the curvature term
//!    (`v²·|d²m/ds²| ≤ a_max/2`), and the path acceleration so that the tangential term fits
//!    into what is left. Where the allowed velocity varies by more than a factor 2 along the
//!    path (near the TRANSMIT pole the rotary axis limits the feed), the block is split into
//!    16 equal parts, each with the limits of its own samples.
//!
//! Conservative by construction between samples only to the sampling density; the property
//! tests check the resulting IPO samples against every machine axis' limits.

use super::{ActiveTrafo, AngleMemo, Transformation, Unreachable};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{AxisVec, Move, Path};

/// Why a block cannot be planned.
#[derive(Debug, Clone, PartialEq)]
pub enum PlanError {
    /// The path enters the working-area limitation (alarm 21619).
    Unreachable,
    /// A machine axis would pass a software limit switch (alarm 10720).
    SoftLimit { axis: String, plus: bool },
    /// The block would have to start on the other side of the pole than the machine stands
    /// (TRANSMIT_POLE_SIDE_FIX forbids the side it is on): alarm 21617.
    PoleSide,
}

impl From<Unreachable> for PlanError {
    fn from(_: Unreachable) -> Self {
        PlanError::Unreachable
    }
}

/// A BCS block planned for the machine axes.
#[derive(Debug, Clone)]
pub struct PlannedBlock {
    /// The moves for the planner, pole positioning moves included.
    pub moves: Vec<Move>,
    /// The machine position at the end of the block.
    pub end: AxisVec,
    /// The machine axes force the path velocity below the programmed one, and unevenly along
    /// the block (near a pole): the control reports this with alarm 10910 and goes on at the
    /// reduced velocity.
    pub irregular_velocity: bool,
}

/// Plans BCS move `mv` starting at machine position `start`.
pub fn plan_block(
    active: &ActiveTrafo,
    mv: &Move,
    start: &AxisVec,
    cfg: &MachineConfig,
) -> Result<PlannedBlock, PlanError> {
    // Leaving the pole of an orientation transformation the pole axis turns first.
    if let Some((turn, from)) = super::pole_turn::pole_turn(active, mv, start, cfg)? {
        let mut rest = plan_block(active, mv, &from, cfg)?;
        rest.moves.insert(0, turn);
        return Ok(rest);
    }
    let t = &active.trafo;
    let tool = &active.tool;
    let path = &mv.path;
    t.check_path(path, tool)?;
    let poles = t.poles(path, tool);
    let mut critical = t.critical_params(path, tool);
    let slots = t.machine_slots();
    // Without a pole inside the block (every block of an orientation transformation) the
    // whole path is one piece: planned straight from the path, no slice and no copy.
    if !poles.iter().any(|&u| u <= 1.0 - 1e-9) && mv.length >= 1e-9 {
        critical.retain(|&c| c > 0.0 && c < 1.0);
        let mut piece = plan_piece(active, mv, path, mv.length, &critical, start, &slots, cfg)?;
        if let Some(last) = piece.moves.last_mut() {
            last.exact_stop |= mv.exact_stop;
        }
        // A block that stays one move may be compressed (`motion/compress_ori.rs`).
        if let [one] = piece.moves.as_mut_slice() {
            one.compress = mv.compress;
            one.orison = mv.orison.clone();
        }
        return Ok(piece);
    }
    let mut cuts = vec![0.0, 1.0];
    cuts.extend(poles.iter().copied().filter(|&u| u > 1e-9 && u < 1.0 - 1e-9));
    cuts.sort_by(f64::total_cmp);

    let mut machine = *start;
    let mut out: Vec<Move> = Vec::new();
    let mut irregular_velocity = false;
    for w in cuts.windows(2) {
        let (u0, u1) = (w[0], w[1]);
        let len = mv.length * (u1 - u0);
        if len < 1e-9 {
            continue;
        }
        let sub = path.slice(u0, u1);
        if let Some(rot) = t.rotary_slot().filter(|_| poles.iter().any(|&p| (p - u0).abs() < 1e-9)) {
            // Leaving the pole: the rotary angle the first step out of the pole needs.
            let mut probe = [0.0; MAX_CHANNEL_AXES];
            sub.at((1e-4 / len).min(0.01), &mut probe);
            let target = active.inverse(&probe, &machine)?[rot];
            if (target - machine[rot]).abs() > 1e-6 {
                if let Some(last) = out.last_mut() {
                    last.exact_stop = true;
                }
                let mut end = machine;
                end[rot] = target;
                out.push(rotation(cfg, rot, &machine, &end, mv.tag));
                machine = end;
            }
        }
        let local: Vec<f64> = critical.iter().filter(|&&c| c > u0 && c < u1).map(|&c| (c - u0) / (u1 - u0)).collect();
        let piece = plan_piece(active, mv, &sub, len, &local, &machine, &slots, cfg)?;
        out.extend(piece.moves);
        machine = piece.end;
        irregular_velocity |= piece.irregular_velocity;
    }
    if let Some(last) = out.last_mut() {
        last.exact_stop |= mv.exact_stop;
    }
    Ok(PlannedBlock { moves: out, end: machine, irregular_velocity })
}

/// Whether transformation `active` can take over the machine where it stands: mapping the
/// position to the BCS and back leaves the linear axes in place. A fixed pole side
/// (`TRANSMIT_POLE_SIDE_FIX`) cannot take over a radial axis standing on the other side.
pub fn takes_over(active: &ActiveTrafo, machine: &AxisVec, cfg: &MachineConfig) -> bool {
    match active.inverse(&active.forward(machine), machine) {
        Ok(m) => !leaves_by_a_jump(machine, &m, &active.trafo.machine_slots(), cfg),
        // Unreachable regions are the blocks' business (21619).
        Err(Unreachable) => true,
    }
}

/// The machine solution at the start of a piece lies away from where the machine stands:
/// the continuity rule could not keep the linear axes where they are, because the
/// transformation allows only the other branch (a fixed pole side).
fn leaves_by_a_jump(start: &AxisVec, first: &AxisVec, slots: &[usize], cfg: &MachineConfig) -> bool {
    slots.iter().any(|&k| !cfg.axis(k).rotary && (first[k] - start[k]).abs() > 1e-3)
}

/// A positioning move of the rotary axis alone, in machine space, at its own limits.
fn rotation(cfg: &MachineConfig, rot: usize, from: &AxisVec, to: &AxisVec, tag: u32) -> Move {
    let ax = cfg.axis(rot);
    Move {
        path: Path::line(*from, *to),
        length: (to[rot] - from[rot]).abs(),
        v_max: ax.max_velocity,
        v_axes: ax.max_velocity,
        // A positioning motion: like rapid traverse, under the rapid override.
        feed: f64::INFINITY,
        a_max: ax.max_accel,
        exact_stop: true,
        tag,
        machine_space: true,
        axis_tangents: None,
        per_rev: 0.0,
        jerk: f64::INFINITY,
        seam_jerk: f64::INFINITY,
        blend: None,
        compress: None,
        orison: None,
        drive: None,
    }
}

/// Extra sample parameters towards the ends of an oriented piece (see `plan_piece`).
const END_SAMPLES: [f64; 3] = [1e-4, 1e-3, 1e-2];

/// Samples one pole-free piece and turns it into one or more moves with machine-derived limits.
/// `slots` are the transformation's machine axes.
#[allow(clippy::too_many_arguments)]
fn plan_piece(
    active: &ActiveTrafo,
    mv: &Move,
    sub: &Path,
    len: f64,
    critical: &[f64],
    start: &AxisVec,
    slots: &[usize],
    cfg: &MachineConfig,
) -> Result<PlannedBlock, PlanError> {
    let t = &active.trafo;
    let n = ((len / 0.25).ceil() as usize).clamp(8, 400);
    let mut us: Vec<f64> = Vec::with_capacity(n + 1 + 3 * critical.len());
    us.extend((0..=n).map(|i| i as f64 / n as f64));
    // An oriented piece may start or end beside an orientation pole, where the rotary axes'
    // rates peak at the very end of the first or last interval: sample towards both ends.
    let refine_ends = sub.ori.is_some();
    if refine_ends {
        us.extend(END_SAMPLES.iter().flat_map(|&e| [e, 1.0 - e]));
    }
    if !critical.is_empty() || refine_ends {
        for &c in critical {
            us.extend([c - 1e-4, c, c + 1e-4].into_iter().filter(|u| *u > 0.0 && *u < 1.0));
        }
        us.sort_by(f64::total_cmp);
        us.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    }

    // Per slot index s (not channel axis): the software limits (none for a modulo axis or a
    // spindle) and the velocity and acceleration the planning may use.
    let ns = slots.len();
    let mut soft = [None::<(f64, f64)>; MAX_CHANNEL_AXES];
    let mut limits = [(0.0, 0.0); MAX_CHANNEL_AXES];
    for (s, &k) in slots.iter().enumerate() {
        let ax = cfg.axis(k);
        if ax.modulo.is_none() && ax.spindle.is_none() {
            soft[s] = Some((ax.limit_minus, ax.limit_plus));
        }
        let share = t.limit_share(k);
        limits[s] = (ax.max_velocity * share, ax.max_accel * share);
    }
    let (soft, limits) = (&soft[..ns], &limits[..ns]);

    // One buffer for the numbers below, by sample or interval j and slot index s (j * ns + s):
    // machine positions `ms` per sample; interval lengths `ds`; rates dm/ds per interval;
    // their change per unit length `bends` at the samples (zero at the ends); the velocity
    // each interval allows.
    let samples = us.len();
    let intervals = samples - 1;
    let mut work = vec![0.0; samples * ns + intervals + intervals * ns + samples * ns + intervals];
    let (ms, rest) = work.split_at_mut(samples * ns);
    let (ds, rest) = rest.split_at_mut(intervals);
    let (rates, rest) = rest.split_at_mut(intervals * ns);
    let (bends, v_allowed) = rest.split_at_mut(samples * ns);

    // Machine positions of the slots along the piece, each sample continuous with the one
    // before: mapped in place in one of two buffers, the other holding the last sample.
    let mut bufs = [*start, [0.0; MAX_CHANNEL_AXES]];
    // The samples follow each other closely: the orientation solve steps from the last one.
    let mut memo = AngleMemo::default();
    for (i, &u) in us.iter().enumerate() {
        let [a, b] = &mut bufs;
        let (prev, m) = if i.is_multiple_of(2) { (&*a, b) } else { (&*b, a) };
        sub.at(u, m);
        match sub.orientation_at(u) {
            Some(o) => t.inverse_oriented_stepped(&o, prev, &active.tool, m, &mut memo)?,
            None => *m = active.inverse(m, prev)?,
        }
        if i == 0 && leaves_by_a_jump(start, m, slots, cfg) {
            return Err(PlanError::PoleSide);
        }
        for (s, &k) in slots.iter().enumerate() {
            if let Some((lo, hi)) = soft[s]
                && (m[k] > hi + 1e-9 || m[k] < lo - 1e-9)
            {
                return Err(PlanError::SoftLimit { axis: cfg.axis(k).name.clone(), plus: m[k] > hi });
            }
            ms[i * ns + s] = m[k];
        }
    }
    let end = bufs[if intervals.is_multiple_of(2) { 1 } else { 0 }];

    for j in 0..intervals {
        ds[j] = (us[j + 1] - us[j]) * len;
        for s in 0..ns {
            rates[j * ns + s] = (ms[(j + 1) * ns + s] - ms[j * ns + s]) / ds[j];
        }
    }
    for j in 1..intervals {
        let h = 0.5 * (ds[j] + ds[j - 1]);
        for s in 0..ns {
            bends[j * ns + s] = (rates[j * ns + s] - rates[(j - 1) * ns + s]).abs() / h;
        }
    }
    // The curvature of interval j: the larger change at its two ends, in place (each entry
    // reads the next one before that is overwritten).
    for i in 0..intervals * ns {
        bends[i] = bends[i].max(bends[i + ns]);
    }
    let (rates, curvatures) = (&*rates, &bends[..intervals * ns]);
    let rate = |j: usize, s: usize| rates[j * ns + s];
    // The curvature likewise: the largest of the interval's and its neighbours'.
    let curvature = |j: usize, s: usize| {
        let c = curvatures[j * ns + s];
        let before = if j > 0 { curvatures[(j - 1) * ns + s] } else { c };
        let after = if j + 1 < intervals { curvatures[(j + 1) * ns + s] } else { c };
        c.max(before).max(after)
    };
    // An interval's rate is its mean; where the rate changes from one interval to the next
    // (beside a pole it grows like the inverse distance) the largest value inside an interval
    // lies beyond that mean, towards the steeper neighbour: the planning takes the largest of
    // the interval's and its neighbours' rates, which is the mean itself on a smooth stretch.
    let peak = |j: usize, s: usize| {
        let r = rate(j, s).abs();
        let before = if j > 0 { rate(j - 1, s).abs() } else { r };
        let after = if j + 1 < intervals { rate(j + 1, s).abs() } else { r };
        r.max(before).max(after)
    };
    for (j, v_j) in v_allowed.iter_mut().enumerate() {
        *v_j = limits.iter().enumerate().fold(f64::INFINITY, |v, (s, &(vmax, amax))| {
            let (r, c) = (peak(j, s), curvature(j, s));
            let v = if r > 1e-12 { v.min(vmax / r) } else { v };
            if c > 1e-12 { v.min((0.5 * amax / c).sqrt()) } else { v }
        });
    }
    let lo = v_allowed.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v_allowed.iter().copied().fold(0.0, f64::max);
    let uneven = hi > 2.0 * lo;
    let parts = if uneven { 16 } else { 1 };

    let mut moves = Vec::with_capacity(parts);
    for part in 0..parts {
        let (a, b) = (part as f64 / parts as f64, (part + 1) as f64 / parts as f64);
        // The intervals overlapping the part: consecutive, as the samples ascend.
        let mut js = (0..intervals).filter(|&j| us[j + 1] > a + 1e-12 && us[j] < b - 1e-12);
        let first = js.next().expect("every part has samples");
        let last = js.next_back().unwrap_or(first);
        let js = first..=last;
        let v_axes = js.clone().fold(mv.v_axes, |v, j| v.min(v_allowed[j]));
        let v_max = v_axes.min(mv.feed);
        let mut a_max = mv.a_max;
        for j in js {
            for (s, &(_, amax)) in limits.iter().enumerate() {
                let r = peak(j, s);
                if r > 1e-12 {
                    let left = (amax - curvature(j, s) * v_max * v_max).max(0.5 * amax);
                    a_max = a_max.min(left / r);
                }
            }
        }
        // The whole piece is the path itself, not a re-interpolated copy of it.
        let piece = if parts == 1 { sub.clone() } else { sub.slice(a, b) };
        let plen = len * (b - a);
        let tangent = |j: usize, u: f64| -> AxisVec {
            let mut tv = piece.tangent(u).map(|x| x / plen);
            for (s, &k) in slots.iter().enumerate() {
                tv[k] = rate(j, s);
            }
            tv
        };
        let axis_tangents = Some(Box::new((tangent(first, 0.0), tangent(last, 1.0))));
        moves.push(Move {
            path: piece,
            length: plen,
            v_max,
            v_axes,
            feed: mv.feed,
            a_max,
            exact_stop: false,
            tag: mv.tag,
            machine_space: false,
            axis_tangents,
            per_rev: mv.per_rev,
            jerk: mv.jerk,
            seam_jerk: mv.seam_jerk,
            // The block's rounding at its end (the channel rounds the corner in the BCS and plans
            // the pieces here again: `channel/smoothing/blending_trafo.rs`).
            blend: if part + 1 == parts { mv.blend } else { None },
            compress: None,
            orison: None,
            drive: None,
        });
    }
    // Alarm 10910 asks for a velocity the axes cannot give only where it varies along the
    // block; a feed that is simply too high for an axis everywhere is an ordinary limitation.
    let irregular_velocity = uneven && lo < mv.feed.min(mv.v_axes);
    Ok(PlannedBlock { moves, end, irregular_velocity })
}
