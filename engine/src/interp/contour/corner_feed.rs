//! `FRC=` / `FRCM=`: the feed of a chamfer or rounding (Programming Manual Fundamentals,
//! "Chamfer, rounding"; Function Manual V1 "Feedrate for chamfer/rounding FRC, FRCM").
//!
//! - `FRC=` (non-modal) acts only on the corner of its own block, that is with CHF/CHR/RND in
//!   the block or RNDM active; elsewhere it has no effect. It takes the place of F and FRCM
//!   for that corner. `FRC` ≤ 0: 12560 (the manual: FRC > 0).
//! - `FRCM=` (modal) is the feed of every following corner; `FRCM=0` switches it off, F
//!   applies again. Negative: 12560.
//! - The value is read in the feed type active at the corner's block: mm/min under G94
//!   (G961, G971), mm/rev under G95 (G96, G97), as F is (inch with G700). MD20201
//!   `CHFRND_MODE_MASK` bit 0 (FRC/FRCM of the block before or after the corner) is not
//!   modelled: the corner belongs to the block that programs it, whose FRC/FRCM act.
//! - A chamfer traversed with G0 ignores FRC/FRCM.
//!
//! Without FRC/FRCM the corner keeps the feed of the block before it (`corners.rs`).

use crate::alarm::Alarm;
use crate::interp::Interpreter;
use crate::motion::{AxisLimit, Feed, Move};

/// The feed of a corner element: the path feed bound (mm/s) and, under a feed per
/// revolution, the feed per revolution the main run follows (else 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct CornerFeed {
    pub per_second: f64,
    pub per_rev: f64,
}

impl Interpreter {
    /// Takes the block's `FRC=` and `FRCM=` (program units): updates the modal FRCM and
    /// remembers the feed of this block's corner, if it asks for one.
    pub(in crate::interp) fn corner_feed_words(
        &mut self,
        frc: Option<f64>,
        frcm: Option<f64>,
        line: u32,
    ) -> Result<(), Alarm> {
        if let Some(f) = frcm {
            if f < 0.0 || !f.is_finite() {
                return Err(Alarm::value_out_of_range(line, &format!("FRCM={}", Alarm::shown(f))));
            }
            self.modal.frcm = (f > 0.0).then_some(f);
        }
        if let Some(f) = frc
            && (f <= 0.0 || !f.is_finite())
        {
            return Err(Alarm::value_out_of_range(line, &format!("FRC={}", Alarm::shown(f))));
        }
        self.corner_frc = frc;
        Ok(())
    }

    /// The feed of the corner the block now held asks for: its FRC, else FRCM; `None`: the
    /// corner keeps the held block's feed.
    pub(in crate::interp) fn corner_feed(&self) -> Option<CornerFeed> {
        let f = self.corner_frc.or(self.modal.frcm)? * self.modal.feed_factor();
        let feed = if self.modal.feed_per_rev {
            CornerFeed { per_second: f * self.spindles.reference_speed() / 60.0, per_rev: f }
        } else {
            CornerFeed { per_second: f / 60.0, per_rev: 0.0 }
        };
        Some(feed)
    }
}

/// Gives the corner element `corner` the feed of FRC/FRCM, if the block programmed one.
pub(in crate::interp) fn apply(corner: &mut Move, feed: Option<CornerFeed>, limits: &[AxisLimit]) {
    if let Some(f) = feed {
        let length = corner.length;
        corner.set_limits(length, Feed::Path(f.per_second), limits);
        corner.per_rev = f.per_rev;
    }
}
