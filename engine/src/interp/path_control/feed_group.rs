//! `FGROUP(ax, ..)` and `FGREF[rot]=r`: which axes the path feed F refers to, and the
//! reference radius that turns a rotary axis's degrees into millimetres of path (Programming
//! Manual Fundamentals, "Feedrate for path axes with FGROUP").
//!
//! After reset the feed refers to the geometry axes; the other axes of a block follow in the
//! same time. `FGROUP(X, Y, Z, A)` counts A in: a block's path length is then
//! √(ΣΔlinear² + Σ(Δrot · π/180 · FGREF)²) over the group's axes, and the block takes that
//! length over F. Without `FGREF` a rotary axis's degree counts as one millimetre (the
//! control's default reference radius 360/2π mm). `FGROUP()` returns to the geometry axes.
//! Both are modal until reset or program end. A block in which no axis of the group moves
//! refers F to its moving axes as before (the geometry axes, or the others together).
//!
//! Decisions where the manual says nothing NCTwin needs: on an arc the geometry axes count
//! with their arc length when all of them are in the group (with fewer, their chord); `FGREF`
//! of a linear axis is refused (12560): the radius only has a meaning for a rotary axis.

use crate::alarm::Alarm;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;
use crate::motion::Path;

/// The words of one block.
#[derive(Debug, Clone, Default)]
pub struct FeedGroupWords {
    /// `FGROUP(..)`: the axes as a bit mask (0: `FGROUP()`, back to the geometry axes).
    pub axes: Option<u32>,
    /// `FGREF[ax]=r`: channel axis and radius (mm).
    pub fgref: Vec<(usize, f64)>,
}

/// The modal state: `None` in [`crate::interp::Modal`] until a program writes either word.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FeedGroup {
    /// The group's channel axes; `None`: the geometry axes.
    axes: Option<u32>,
    /// Reference radius per channel axis (mm); absent: 360/2π (one degree is one millimetre).
    fgref: Vec<(usize, f64)>,
}

/// `FGROUP(X, Y, Z, A)`: the named channel axes as a bit mask.
pub(in crate::interp) fn axes(args: &[Expr], cfg: &MachineConfig, line: u32) -> Result<u32, Alarm> {
    let mut mask = 0;
    for a in args {
        let k = match a {
            Expr::Var { name, indices } if indices.is_empty() => cfg.program_axis(name),
            _ => None,
        };
        let Some(k) = k else {
            return Err(Alarm::syntax(line, "FGROUP takes channel axis names"));
        };
        mask |= 1 << k;
    }
    Ok(mask)
}

/// `FGREF[ax]` of channel axis `axis` with value `radius`, checked.
pub(in crate::interp) fn fgref(
    cfg: &MachineConfig,
    axis: usize,
    radius: f64,
    line: u32,
) -> Result<(usize, f64), Alarm> {
    if !cfg.axis(axis).rotary || !radius.is_finite() || radius <= 0.0 {
        return Err(Alarm::value_out_of_range(
            line,
            &format!("FGREF[{}]={} (a rotary axis, a radius > 0)", cfg.program_axis_name(axis), Alarm::shown(radius)),
        ));
    }
    Ok((axis, radius))
}

impl FeedGroup {
    /// The state after a block's words (`group` is the modal state before it).
    pub(in crate::interp) fn apply(group: &mut Option<Box<FeedGroup>>, w: &FeedGroupWords) {
        if w.axes.is_none() && w.fgref.is_empty() {
            return;
        }
        let g = group.get_or_insert_with(Default::default);
        if let Some(mask) = w.axes {
            g.axes = (mask != 0).then_some(mask);
        }
        for &(k, r) in &w.fgref {
            g.fgref.retain(|(a, _)| *a != k);
            g.fgref.push((k, r));
        }
    }

    /// The length F refers to on `path`, given `length`, the one the geometry axes give.
    pub(in crate::interp) fn path_length(&self, path: &Path, length: f64, cfg: &MachineConfig) -> f64 {
        let Some(mask) = self.axes else { return length };
        let geo: Vec<usize> = cfg.geo_axes.iter().flatten().copied().collect();
        let in_group = |k: usize| mask >> k & 1 == 1;
        let arc_counts = path.arc.is_some() && geo.iter().all(|&k| in_group(k));
        let mut sum = if arc_counts { length * length } else { 0.0 };
        for k in 0..cfg.channel_axes.len() {
            if !in_group(k) || (arc_counts && geo.contains(&k)) {
                continue;
            }
            let d = path.end[k] - path.start[k];
            let factor = if cfg.axis(k).rotary {
                self.fgref.iter().find(|(a, _)| *a == k).map_or(1.0, |(_, r)| r.to_radians())
            } else {
                1.0
            };
            sum += (d * factor).powi(2);
        }
        if sum > 1e-18 { sum.sqrt() } else { length }
    }
}
