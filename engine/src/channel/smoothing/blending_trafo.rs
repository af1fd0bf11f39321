//! Continuous-path rounding under a kinematic transformation: the corner between two
//! transformed moves is rounded in the BCS (`motion::blend_ori`), and the shortened moves and
//! the element are planned for the machine axes again (`kinematics::plan`), so that every
//! machine axis keeps its limits on the element too.
//!
//! Where the manuals leave room: the BCS is rounded under every transformation (TRAORI,
//! TRANSMIT, TRACYL, TRAANG: B1 rounds the path of the geometry axes, which the
//! transformation maps; only Cartesian PTP blends in the MCS, Transformations FM p.115, and
//! its moves are in machine space: never rounded here). A corner stays sharp where planning
//! a piece for the machine axes turns a pole axis alone first (F2 "Behavior at pole", MD21108
//! units digit 0; TRANSMIT leaving its pole at another angle: the path stands while that axis
//! turns, so there is no motion to blend into) or fails. A piece whose velocity varies along
//! it (beside a pole) stays one move with the smallest limits of its parts.

use super::blending::geo_moves;
use crate::channel::Channel;
use crate::interp::Item;
use crate::kinematics::plan::plan_block;
use crate::kinematics::{ActiveTrafo, Transformation};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::blend_ori::round_transformed_corner;
use crate::motion::{AxisLimit, AxisVec, Move, Path};

impl Channel {
    /// Rounds the corner between the transformed move `mv` and the next prepared move (see the
    /// module doc): as [`Channel::round_corner`], with `full` `mv`'s programmed length.
    pub(super) fn round_transformed(&mut self, mv: &mut Move, full: f64, limits: &[AxisLimit]) -> Option<Move> {
        let Some(Item::Move { mv: next, offsets, .. }) = self.pending.front() else { return None };
        // Both transformed (the next move's machine rates are known).
        next.axis_tangents.as_ref()?;
        let active = offsets.trafo.clone()?;
        // The path length is the BCS geometry axes' (TRANSMIT's Y has no channel axis of its
        // own outside the transformation).
        let mut metric: AxisVec = [0.0; MAX_CHANNEL_AXES];
        for k in active.trafo.geo_slots().into_iter().flatten() {
            metric[k] = 1.0;
        }
        if !(geo_moves(mv, &metric) && geo_moves(next, &metric)) {
            return None;
        }
        let orientation_of = |p: &AxisVec| active.trafo.orientation(p);
        let rounded = round_transformed_corner(mv, next, full, &metric, limits, &orientation_of)?;
        let start = machine_at(&active, &mv.path)?;
        let (first, at) = plan_one(&active, &rounded.first, &start, &self.cfg)?;
        let (corner, at) = plan_one(&active, &rounded.corner, &at, &self.cfg)?;
        let (second, _) = plan_one(&active, &rounded.second, &at, &self.cfg)?;
        let Some(Item::Move { mv: next, .. }) = self.pending.front_mut() else { return None };
        let next_full = next.length;
        *mv = first;
        *next = second;
        self.blending.trimmed = Some((next.length.to_bits(), next_full));
        Some(corner)
    }
}

/// The machine position at the start of `path` (whose orientation slots hold the rotary axes
/// there, the continuity reference of the solution).
pub(super) fn machine_at(active: &ActiveTrafo, path: &Path) -> Option<AxisVec> {
    let bcs = path.start;
    match path.orientation_at(0.0) {
        Some(o) => active.inverse_oriented(&bcs, &o, &bcs).ok(),
        None => active.inverse(&bcs, &bcs).ok(),
    }
}

/// `mv` planned for the machine axes from machine position `start` as one move, and the
/// machine position at its end; `None` if the planning fails or turns a rotary axis alone
/// first (a pole). Where the planning splits the piece into parts (the velocity the axes allow
/// varies along it), the piece stays one move with the smallest limits of its parts: slower
/// than need be on the faster parts, never faster than an axis allows.
pub(super) fn plan_one(
    active: &ActiveTrafo,
    mv: &Move,
    start: &AxisVec,
    cfg: &crate::machine_data::MachineConfig,
) -> Option<(Move, AxisVec)> {
    let planned = plan_block(active, mv, start, cfg).ok()?;
    let mut parts = planned.moves.into_iter();
    let mut one = parts.next()?;
    if one.machine_space {
        return None;
    }
    let end_rates = parts.fold(None, |_, part: Move| {
        one.v_max = one.v_max.min(part.v_max);
        one.v_axes = one.v_axes.min(part.v_axes);
        one.a_max = one.a_max.min(part.a_max);
        one.blend = part.blend;
        one.exact_stop = part.exact_stop;
        part.axis_tangents.map(|t| t.1)
    });
    if let Some(end) = end_rates {
        one.path = mv.path.clone();
        one.length = mv.length;
        // Still the block's move: ORISON smooths its ends (`orison.rs`).
        one.orison = mv.orison.clone();
        if let Some(t) = one.axis_tangents.as_mut() {
            t.1 = end;
        }
    }
    Some((one, planned.end))
}
