//! The state's `positioning`: the axes that travel on their own interpolators (POS, POSA and
//! POSP of a program, command axes of synchronized actions), so a display can mark them in its
//! axis table. Additive to the contract's state object (absent when no axis travels so), in
//! channel axis order.

use nctwin_engine::channel::PositioningInfo;
use serde::Serialize;
use utoipa::ToSchema;

/// One positioning axis.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct PositioningState {
    /// Machine axis name, as in `positions.machine`.
    #[schema(example = "Z")]
    pub axis: String,
    /// End point in machine coordinates (mm or degrees; POSP: the last part's end); `null`
    /// for the endless motion of `MOV[ax]=1/-1`.
    pub target: Option<f64>,
    /// Signed velocity in mm/min (deg/min).
    pub velocity: f64,
    /// `POS`, `POSA`, `POSP` (a program's), `OS` (a program's oscillating axis, `target` the
    /// reversal point or end position it travels to), `command` (`POS`/`FA` of a synchronized
    /// action) or `MOV` (an action's endless motion).
    #[schema(example = "POSA")]
    pub kind: &'static str,
    /// The program waits for the axis (WAITP, or the end of its POS/POSP block).
    pub waiting: bool,
}

impl From<&PositioningInfo> for PositioningState {
    fn from(p: &PositioningInfo) -> Self {
        PositioningState {
            axis: p.axis.clone(),
            target: p.target,
            velocity: p.velocity,
            kind: p.kind,
            waiting: p.waiting,
        }
    }
}
