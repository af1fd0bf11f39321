//! `PUT /sessions/{id}/machine-data`: change a session's NC data.

use axum::extract::{Path, State};

use super::{StateReply, command, find_entry};
use crate::dto::{self, ErrorBody, MachineDataRequest};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::session::Action;
use crate::state::AppState;

/// Applies NC data text (machine data, tool data, settable frames) all-or-nothing and activates
/// it as a reset would; only in reset state. Axis positions are kept where the axes still exist.
/// The new machine data is saved before the reply.
#[utoipa::path(
    put,
    path = "/sessions/{id}/machine-data",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = MachineDataRequest,
    responses(
        (status = 200, description = "The state with the new data active", body = dto::State),
        (status = 400, description = "Bad NC data (with its line; nothing applied) or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in reset state", body = ErrorBody),
        (status = 503, description = "Applied, but the storage failed: not saved yet", body = ErrorBody),
    )
)]
pub async fn put_machine_data(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<MachineDataRequest>,
) -> Result<StateReply, ApiError> {
    let reply = command(&state, &id, Action::MachineData(body.text), None).await?;
    let entry = find_entry(&state, &id)?;
    state.persist_checkpoint(&entry).await?;
    Ok(reply)
}
