//! `GET /sessions/{id}/path-history`: the executed path so far, thinned and bounded
//! (`session/path_history.rs`), so that a viewer who joins a running session sees where the
//! tool has already been.

use axum::Json;
use axum::extract::{Path, State};
use serde::Serialize;
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// The executed path of a session.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct PathHistory {
    /// Geometry axis names of the three coordinates of each point.
    pub axes: [String; 3],
    /// Tool tip on the workpiece (mm), oldest first; at most 20,001 points (the kept ones and
    /// the newest tip). The BCS, or on a table turned without TRAORI the tip through the
    /// machine's kinematics (the frame the table carries, where TRAORI's BCS would be); under
    /// TRACYL on the unrolled surface (see `tracyl_diameter`). Thinned by geometry: the
    /// polyline stays within 0.01 mm of the path, every block end is a point.
    pub points: Vec<[f64; 3]>,
    /// Program line in execution at each point (0: none).
    pub lines: Vec<u32>,
    /// At each point: the TRACYL working diameter while TRACYL was active, else null (the
    /// point is then radial, arc length on this diameter, axial; a view wraps it).
    pub tracyl_diameter: Vec<Option<f64>>,
    /// At each point: `false` when a rotary axis that the machine data's kinematics do not
    /// describe had turned the workpiece, so the point is the BCS and may not lie on the part.
    pub exact: Vec<bool>,
    /// How often the path was halved to stay bounded (the resolution halves each time).
    pub halvings: u32,
    /// IPO cycles looked at since the session started, kept or not.
    pub recorded: u64,
}

/// The executed path since the session started (tool tip on the workpiece, thinned).
#[utoipa::path(
    get,
    path = "/sessions/{id}/path-history",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The executed path, oldest point first", body = PathHistory),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_path_history(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<PathHistory>, ApiError> {
    let session = find_session(&state, &id)?;
    let axes =
        session.with_channel(|ch| ch.config().geo_names.clone()).await.map_err(|e| ApiError::from_session(&id, e))?;
    let history =
        session.path_history().lock().map_err(|_| ApiError::Conflict("the path history is unreadable".into()))?;
    let points = history.points();
    Ok(Json(PathHistory {
        axes,
        points: points.iter().map(|p| p.basic).collect(),
        lines: points.iter().map(|p| p.line).collect(),
        tracyl_diameter: points.iter().map(|p| p.tracyl_diameter).collect(),
        exact: points.iter().map(|p| p.exact).collect(),
        halvings: history.halvings(),
        recorded: history.recorded(),
    }))
}
