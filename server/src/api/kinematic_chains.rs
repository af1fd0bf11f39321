//! `GET/PUT /sessions/{id}/kinematic-chains`: a session's kinematic chain elements (`$NK_`) and
//! transformations defined by kinematic chains (`$NT_`) as a part program in plain text — the
//! DELOBJ preamble, the assignments, NEWCONF — which a control runs unchanged and which this
//! endpoint accepts back.

use axum::extract::{Path, State};
use axum::http::header::CONTENT_TYPE;
use axum::response::IntoResponse;

use super::{StateReply, command, find_entry, find_session};
use crate::dto::{self, ErrorBody};
use crate::error::ApiError;
use crate::extract::ApiText;
use crate::session::Action;
use crate::state::AppState;

/// The session's kinematic chain data as a part program (`text/plain`).
#[utoipa::path(
    get,
    path = "/sessions/{id}/kinematic-chains",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The chain program: DELOBJ(\"TRAFO_DATA\"), DELOBJ(\"KIN_CHAIN_ELEM\"), every $NK_/$NT_ value that differs from its default, NEWCONF", body = String, content_type = "text/plain"),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_kinematic_chains(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<impl IntoResponse, ApiError> {
    let session = find_session(&state, &id)?;
    let text =
        session.with_channel(|ch| ch.export_kinematic_chains()).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(([(CONTENT_TYPE, "text/plain; charset=utf-8")], text))
}

/// Runs a chain program (as `GET` returns it: `$NK_`/`$NT_` assignments, `DELOBJ("TRAFO_DATA")`,
/// `DELOBJ("KIN_CHAIN_ELEM")`, NEWCONF, comments, block numbers) on the session's data,
/// all-or-nothing, and activates the result as a reset would; only in reset state. Anything
/// else in the program is a `400` naming its line. The new data is saved before the reply.
#[utoipa::path(
    put,
    path = "/sessions/{id}/kinematic-chains",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = String, content_type = "text/plain", description = "The chain program"),
    responses(
        (status = 200, description = "The state with the new chain data active", body = dto::State),
        (status = 400, description = "A line that is no chain datum assignment, bad chain data (with its line) or an inconsistent chain; nothing applied", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in reset state", body = ErrorBody),
        (status = 503, description = "Applied, but the storage failed: not saved yet", body = ErrorBody),
    )
)]
pub async fn put_kinematic_chains(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiText(text): ApiText,
) -> Result<StateReply, ApiError> {
    let reply = command(&state, &id, Action::KinematicChains(text), None).await?;
    let entry = find_entry(&state, &id)?;
    state.persist_checkpoint(&entry).await?;
    Ok(reply)
}
