//! `POST /sessions/{id}/set-wo`: the JOG area's "Set WO".

use axum::extract::{Path, State};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use utoipa::ToSchema;

use super::{command, find_entry};
use crate::dto::{self, ErrorBody};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::session::Action;
use crate::state::AppState;

/// Body of `POST /sessions/{id}/set-wo`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SetWorkOffsetRequest {
    /// The axis as the WCS display names it (geometry name X/Y/Z, else the channel axis name).
    #[schema(example = "X")]
    pub axis: String,
    /// The position the axis shall read in the WCS (a diameter on the transverse axis under
    /// DIAMON), mm or degrees.
    #[schema(example = 0.0)]
    pub value: f64,
}

/// Sets the active settable work offset (`$P_UIFR[n]` of the active G500/G54..) so that the
/// axis reads `value` in the WCS without moving, as Operate's "Set WO" in JOG: the difference
/// to the position it reads now goes into the offset's translation (through the frame's
/// rotation, so the other axes keep reading what they read). Reset state only, no active
/// kinematic transformation. The changed frame data is saved before the reply.
#[utoipa::path(
    post,
    path = "/sessions/{id}/set-wo",
    tag = "jog",
    params(("id" = String, Path, description = "Session id")),
    request_body = SetWorkOffsetRequest,
    responses(
        (status = 200, description = "The state with the changed work offset active", body = dto::State),
        (status = 400, description = "Unknown axis, a value that is no number, an active transformation, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in reset state", body = ErrorBody),
        (status = 503, description = "Applied, but the storage failed: not saved yet", body = ErrorBody),
    )
)]
pub async fn set_work_offset(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<SetWorkOffsetRequest>,
) -> Result<Response, ApiError> {
    let reply = command(&state, &id, Action::SetWorkOffset { axis: body.axis, value: body.value }, None).await?;
    let entry = find_entry(&state, &id)?;
    state.persist_checkpoint(&entry).await?;
    Ok(reply.into_response())
}
