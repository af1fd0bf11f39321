//! `GET /sessions/{id}/viewers`: how many clients watch a session (open WebSocket streams), for
//! the HMI's "who is watching" display.

use axum::Json;
use axum::extract::{Path, State};
use serde::Serialize;
use utoipa::ToSchema;

use super::find_entry;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// Who watches a session.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Viewers {
    /// Open WebSocket streams of the session (each HMI page holds one).
    pub streams: usize,
}

/// How many clients watch the session: its open WebSocket streams.
#[utoipa::path(
    get,
    path = "/sessions/{id}/viewers",
    tag = "control",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The session's viewers", body = Viewers),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_viewers(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<Viewers>, ApiError> {
    let entry = find_entry(&state, &id)?;
    Ok(Json(Viewers { streams: entry.stream_clients() }))
}
