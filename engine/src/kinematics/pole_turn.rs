//! Leaving the pole of an orientation transformation: the pole axis turns first.
//!
//! When the tool orientation stands exactly in the pole (a 5-axis head at A0: C is free) and a
//! block interpolates the orientation as a vector away from it, the pole axis has to stand at
//! the azimuth of the great circle from the first step on; interpolated as it is, it would jump
//! there within one IPO cycle at any speed (the 90° in 52 ms). MD21108 `POLE_ORI_MODE`
//! units digit 0 (F2 "Behavior at pole"): the pole axis is traversed to its end position at the
//! start of the block while the orientation stays in the pole. This module builds that motion
//! as a machine-space move of its own at the axes' limits (the tool tip kept where it is: the
//! linear axes follow the circle the tip describes about the pole axis, for a table or an
//! offset head), which the planner then runs before the block with an exact stop between.
//! The same guard catches a block without vector interpolation whose rotary positions start
//! away from where the machine stands (in the pole the equivalent solution C ± 180° may be
//! chosen): the axes turn there at their limits instead of jumping.

use super::{ActiveTrafo, Transformation, Unreachable};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{Arc, AxisLimit, AxisVec, Feed, Move, Path};

/// A turn of more than this (degrees) over the first millionth of a block is a jump.
const JUMP: f64 = 1.0;

/// For oriented move `mv` starting at machine position `start`: the positioning move of the
/// pole axis that the block needs first, and the machine position it ends at; `None` when the
/// orientation axes follow the block continuously from `start`.
pub fn pole_turn(
    active: &ActiveTrafo,
    mv: &Move,
    start: &AxisVec,
    cfg: &MachineConfig,
) -> Result<Option<(Move, AxisVec)>, Unreachable> {
    let path = &mv.path;
    let slots = active.trafo.orientation_slots();
    if slots.iter().all(Option::is_none) {
        return Ok(None);
    }
    let ori = path.ori.as_deref();
    let mut p = [0.0; MAX_CHANNEL_AXES];
    path.at(1e-6, &mut p);
    let probe = match ori {
        Some(o) => active.inverse_oriented(&p, &o.at(1e-6), start)?,
        None => active.inverse(&p, start)?,
    };
    let mut target = *start;
    let mut turned = false;
    for &k in slots.iter().flatten() {
        let mut d = probe[k] - start[k];
        // Whole turns of a modulo axis are the same position: no motion to plan.
        if cfg.axis(k).modulo.is_some() {
            d = (d + 180.0).rem_euclid(360.0) - 180.0;
        }
        if d.abs() > JUMP {
            target[k] = start[k] + d;
            turned = true;
        }
    }
    if !turned {
        return Ok(None);
    }
    // In the pole the free axis stays where `prev` has it: so the machine position with the
    // pole axis at `f` of the way and the tool tip and orientation of the block start. A block
    // without vector interpolation carries the rotary positions in its BCS slots: they turn
    // from where the machine stands to where the block starts, the tip kept.
    let p0 = path.start;
    let at = |f: f64| -> Result<AxisVec, Unreachable> {
        let mut prev = *start;
        for &k in slots.iter().flatten() {
            prev[k] = start[k] + f * (target[k] - start[k]);
        }
        match ori {
            Some(o) => active.inverse_oriented(&p0, &o.at(0.0), &prev),
            None => {
                let mut bcs = p0;
                for &k in slots.iter().flatten() {
                    bcs[k] = prev[k];
                }
                active.inverse(&bcs, &prev)
            }
        }
    };
    let end = at(1.0)?;
    // Not the pole after all (the start orientation turns the axes by itself): no turn.
    if slots.iter().flatten().any(|&k| (end[k] - target[k]).abs() > 1e-6) {
        return Ok(None);
    }
    let mid = at(0.5)?;
    let turn = slots.iter().flatten().map(|&k| (target[k] - start[k]).abs()).sum::<f64>();
    let linear: Vec<usize> = active.trafo.machine_slots().into_iter().filter(|&k| !slots.contains(&Some(k))).collect();
    let mut path = Path::line(*start, end);
    path.arc = circle_through(start, &mid, &end, &linear).map(Box::new);
    let mut m = Move::new(path, turn, Feed::Rapid, &AxisLimit::for_channel(cfg), true, mv.tag);
    m.machine_space = true;
    Ok(Some((m, end)))
}

/// The arc from `a` over `m` (its middle) to `b` in the axes `linear`, as [`Path::at`] adds it
/// to the straight line; `None` when the three lie on a line (the tip on the pole axis).
fn circle_through(a: &AxisVec, m: &AxisVec, b: &AxisVec, linear: &[usize]) -> Option<Arc> {
    let mut q = [0.0; MAX_CHANNEL_AXES];
    for &k in linear {
        q[k] = 0.5 * (a[k] + b[k]);
    }
    let dist = |x: &AxisVec, y: &AxisVec| linear.iter().map(|&k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt();
    let (h, c) = (dist(m, &q), dist(a, b) * 0.5);
    if h < 1e-9 {
        return None;
    }
    let radius = (c * c + h * h) / (2.0 * h);
    let mut centre = [0.0; MAX_CHANNEL_AXES];
    let (mut u, mut v) = ([0.0; MAX_CHANNEL_AXES], [0.0; MAX_CHANNEL_AXES]);
    for &k in linear {
        centre[k] = m[k] + (q[k] - m[k]) / h * radius;
        u[k] = (a[k] - centre[k]) / radius;
    }
    // v: the unit direction towards the middle point, perpendicular to u.
    let um: f64 = linear.iter().map(|&k| u[k] * (m[k] - centre[k])).sum();
    for &k in linear {
        v[k] = m[k] - centre[k] - um * u[k];
    }
    let vn = linear.iter().map(|&k| v[k] * v[k]).sum::<f64>().sqrt();
    if vn < 1e-12 {
        return None;
    }
    for &k in linear {
        v[k] /= vn;
    }
    let half = (um / radius).clamp(-1.0, 1.0).acos();
    Some(Arc { u, v, radius, start_angle: 0.0, sweep: 2.0 * half })
}
