//! The compressor under a kinematic transformation in the main run's feed: a transformed move
//! that asks for compression (COMPON ... under TRAORI, TRANSMIT, TRACYL, TRAANG) becomes a
//! curve in the BCS through its programmed end points (`motion::compress_ori`: the tip within
//! the contour tolerance, the orientation within OTOL), planned for the machine axes again
//! (`kinematics::plan`, as the rounding does in `blending_trafo.rs`), so that every machine
//! axis keeps its velocity and acceleration limits along it.
//!
//! Where the manuals leave room: F2 names TRAORI; B1 compresses the geometry axes' path, which
//! every transformation maps, so TRANSMIT, TRACYL and TRAANG compress the BCS path too. A
//! block that the planning splits (a pole passage, a velocity that varies along it) stays as
//! programmed: its pieces carry no compressor (`plan.rs`).

use super::blending_trafo::{machine_at, plan_one};
use crate::channel::Channel;
use crate::interp::Item;
use crate::kinematics::{ActiveTrafo, Transformation};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::compress::Junction;
use crate::motion::{AxisLimit, AxisVec, Move, compress_ori};

impl Channel {
    /// Compresses the transformed move `mv` (just taken from the prepared items) with the
    /// passage `start` into it (made under `start_trafo`) and the passage into the next
    /// prepared move; true if it passes smoothly into that move (no corner to round).
    pub(super) fn compress_transformed(
        &mut self,
        mv: &mut Move,
        start: Option<Junction>,
        start_trafo: Option<ActiveTrafo>,
    ) -> bool {
        let next = match self.pending.front() {
            Some(Item::Move { mv: next, offsets, .. }) => Some((next, offsets.trafo.as_ref())),
            _ => None,
        };
        // The next move runs under the same transformation (else `mv` is an exact stop).
        let Some(active) = next.and_then(|(_, t)| t.cloned()).or(start_trafo) else { return false };
        let mut metric: AxisVec = [0.0; MAX_CHANNEL_AXES];
        for k in active.trafo.geo_slots().into_iter().flatten() {
            metric[k] = 1.0;
        }
        if !compress_ori::compressible(mv, &metric) {
            return false;
        }
        let start = start.filter(|j| j.point == mv.path.start);
        let end = next.and_then(|(next, _)| compress_ori::junction(mv, next, &metric));
        // The BCS limits of the tip's axes; the others (the orientation's slots) are limited
        // by the machine axes when the curve is planned for them below.
        let unlimited = AxisLimit { max_velocity: f64::INFINITY, max_accel: f64::INFINITY, accel_overload: 1.0 };
        let limits: Vec<AxisLimit> = AxisLimit::for_channel(&self.cfg)
            .iter()
            .enumerate()
            .map(|(k, l)| if metric[k] > 0.0 { *l } else { unlimited })
            .collect();
        let Some(smooth) = compress_ori::smooth(mv, start.as_ref(), end.as_ref(), &metric, &limits) else {
            return false;
        };
        let Some(from) = machine_at(&active, &mv.path) else { return false };
        let Some((planned, _)) = plan_one(&active, &smooth, &from, &self.cfg) else { return false };
        *mv = planned;
        if end.is_some() {
            self.blending.junction = end;
            self.blending.junction_trafo = Some(active);
            return true;
        }
        false
    }
}
