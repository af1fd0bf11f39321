//! Continuous-path smoothing in the main run's feed: a move whose block asks for corner
//! rounding (`Move::blend`, G641..G645) or compression (`Move::compress`, COMPON ...) waits
//! in the prepared items until the next item is known. If that is a move too (nothing that
//! needs a stop in between, the same transformation), the compressor first makes a smooth
//! passage through the point between them (`motion::compress`); where it does not, the
//! corner is rounded (`motion::blend`): the shortened move and the rounding element go on,
//! the shortened next move waits for its own successor. Transformed moves are compressed in
//! `compress_trafo.rs`; under ORISON their orientation is smoothed first (`orison.rs`).

use crate::channel::Channel;
use crate::interp::Item;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::blend::{self, Blend, Rounded};
use crate::motion::blend_axial;
use crate::motion::compress::{self, Junction};
use crate::motion::{AxisLimit, AxisVec, Move};

/// What the rounding remembers between two corners.
#[derive(Debug, Clone, Default)]
pub(in crate::channel) struct Blending {
    /// The first prepared move was shortened at its start by the corner before it: its
    /// length now (bits) and its programmed length (the 36 % rule refers to that).
    pub(super) trimmed: Option<(u64, f64)>,
    /// The compressor's passage through the start point of the first prepared move.
    pub(super) junction: Option<Junction>,
    /// The transformation the passage was made under (`compress_trafo.rs`).
    pub(super) junction_trafo: Option<crate::kinematics::ActiveTrafo>,
    /// ORISON's run of smoothed moves (`orison.rs`).
    pub(super) ori_run: super::orison::OriRun,
    /// Preparation waits for the main run to empty (STOPRE, reading main-run values): a
    /// waiting move is handed on without its successor.
    pub(in crate::channel) prep_waits_for_main_run: bool,
    /// The elements after the one [`Channel::round_corner`] returned (G643's chain), to be
    /// planned right after it.
    pub(in crate::channel) more: Vec<Move>,
}

impl Channel {
    /// True if the move at the front of the prepared items waits for its successor to round
    /// the corner between them (under ORISON: for the window of moves its orientation's
    /// smoothing needs, `orison.rs`).
    pub(in crate::channel) fn waits_for_corner(&self) -> bool {
        let Some(Item::Move { mv, .. }) = self.pending.front() else { return false };
        let can_wait = !self.prep_done && !self.prep_waits_for_trafo && !self.blending.prep_waits_for_main_run;
        if !can_wait || mv.exact_stop {
            return false;
        }
        if mv.orison.is_some() && mv.axis_tangents.is_some() {
            return self.orison_waits();
        }
        self.pending.len() == 1 && (mv.blend.is_some() || mv.compress.is_some())
    }

    /// Rounds the corner between `mv` (just taken from the prepared items) and the next
    /// prepared move, if `mv` asks for it: `mv` becomes the shortened move, the next prepared
    /// move is shortened at its start, and the rounding element is returned to be planned
    /// right after `mv`.
    pub(in crate::channel) fn round_corner(&mut self, mv: &mut Move) -> Option<Move> {
        let full = match self.blending.trimmed.take() {
            Some((bits, full)) if bits == mv.length.to_bits() => full,
            _ => mv.length,
        };
        if mv.orison.is_some() {
            // ORISON: the orientation smoothed across the end (`orison.rs`), before rounding.
            self.smooth_orientation(mv, true);
        }
        if mv.blend.is_none() && mv.compress.is_none() {
            self.blending.junction = None;
            return None;
        }
        let start = self.blending.junction.take();
        let start_trafo = self.blending.junction_trafo.take();
        let mut metric: AxisVec = [0.0; MAX_CHANNEL_AXES];
        for &k in self.cfg.geo_axes.iter().flatten() {
            metric[k] = 1.0;
        }
        let limits = AxisLimit::for_channel(&self.cfg);
        let next = match self.pending.front() {
            Some(Item::Move { mv: next, .. }) => Some(next),
            _ => None,
        };
        if mv.axis_tangents.is_some() {
            // A transformed move: compressed in the BCS, planned for the machine axes again.
            if self.compress_transformed(mv, start, start_trafo) {
                return None;
            }
        } else if compress::compressible(mv) {
            let start = start.filter(|j| j.point == mv.path.start);
            let end = next.and_then(|next| compress::junction(mv, next, &metric));
            // Where the curve would leave the chord, the line stays, and so does its corner.
            if let Some(smooth) = compress::smooth(mv, start.as_ref(), end.as_ref(), &metric, &limits) {
                *mv = smooth;
                if end.is_some() {
                    // A smooth passage: no corner to round.
                    self.blending.junction = end;
                    return None;
                }
            }
        }
        let axial = match mv.blend? {
            Blend::Axial { geo, other, ori } => {
                let tol = self.axial_tolerances(geo, other, &metric);
                // Where G643 rounds as G642: the geometry axes' smallest tolerance.
                let common =
                    (0..MAX_CHANNEL_AXES).filter(|&k| metric[k] > 0.0).map(|k| tol[k]).fold(f64::INFINITY, f64::min);
                mv.blend = Some(Blend::Tolerance { contour: common, ori });
                Some(tol)
            }
            _ => None,
        };
        let Some(Item::Move { mv: next, .. }) = self.pending.front_mut() else { return None };
        // B1: a change between BRISK and SOFT (a jerk limit or none) inserts no rounding.
        if mv.jerk.is_finite() != next.jerk.is_finite() {
            return None;
        }
        if mv.axis_tangents.is_some() {
            // A transformed move: rounded in the BCS, planned for the machine axes again.
            return self.round_transformed(mv, full, &limits);
        }
        if !(geo_moves(mv, &metric) && geo_moves(next, &metric)) {
            return None;
        }
        let next_full = next.length;
        let rounded = match &axial {
            Some(tol) if mv.path.ori.is_none() => blend_axial::round_axial(mv, next, full, tol, &metric, &limits),
            _ => None,
        };
        let Rounded { first, corner, second, more, .. } =
            rounded.or_else(|| blend::round_corner(mv, next, full, &metric, &limits))?;
        *mv = first;
        *next = second;
        self.blending.more = more;
        self.blending.trimmed = Some((next.length.to_bits(), next_full));
        Some(corner)
    }
}

impl Channel {
    /// G643's tolerance of every channel axis: `geo` for the geometry axes (`metric`) and
    /// `other` for the rest where not negative, else the axis' MD33100.
    fn axial_tolerances(&self, geo: f64, other: f64, metric: &AxisVec) -> AxisVec {
        let data = &self.cfg.path_control.axis_tol;
        std::array::from_fn(|k| {
            let set = if metric[k] > 0.0 { geo } else { other };
            if set >= 0.0 { set } else { data.get(k).copied().unwrap_or(0.0) }
        })
    }
}

/// True if `mv` moves channel axis `k`.
fn moves_axis(mv: &Move, k: usize) -> bool {
    mv.path.start[k] != mv.path.end[k] || mv.path.arc.as_ref().is_some_and(|a| a.moves_axis(k))
}

/// True if `mv` moves a geometry axis (the feed's length is theirs).
pub(super) fn geo_moves(mv: &Move, metric: &AxisVec) -> bool {
    (0..MAX_CHANNEL_AXES).any(|k| metric[k] > 0.0 && moves_axis(mv, k))
}
