//! Stored programs of a session (main programs and subprograms called by name) and the check
//! of a program text (syntax and names) before Cycle start.

use axum::Json;
use axum::extract::{Path, State};
use axum::http::StatusCode;

use super::{find_entry, find_session};
use crate::dto::{CheckRequest, CheckResponse, ErrorBody, ProgramBody, ProgramInfo, ProgramText, first_diagnostics};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::state::AppState;

/// Lists the session's stored programs by name.
#[utoipa::path(
    get,
    path = "/sessions/{id}/programs",
    tag = "programs",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "Stored programs by name", body = [ProgramInfo]),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn list_programs(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<Vec<ProgramInfo>>, ApiError> {
    let session = find_session(&state, &id)?;
    let list = session.with_channel(|ch| ch.stored_programs()).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(list.into_iter().map(|(name, size)| ProgramInfo { name, size }).collect()))
}

/// A stored program's text.
#[utoipa::path(
    get,
    path = "/sessions/{id}/programs/{name}",
    tag = "programs",
    params(("id" = String, Path, description = "Session id"), ("name" = String, Path, description = "Program name")),
    responses(
        (status = 200, description = "The program", body = ProgramText),
        (status = 404, description = "No such session or program", body = ErrorBody),
    )
)]
pub async fn get_program(
    State(state): State<AppState>,
    Path((id, name)): Path<(String, String)>,
) -> Result<Json<ProgramText>, ApiError> {
    let session = find_session(&state, &id)?;
    let wanted = name.clone();
    let text = session
        .with_channel(move |ch| ch.stored_program(&wanted).map(str::to_string))
        .await
        .map_err(|e| ApiError::from_session(&id, e))?
        .ok_or_else(|| ApiError::NotFound(format!("program `{name}`")))?;
    Ok(Json(ProgramText { name: name.to_ascii_uppercase(), text }))
}

/// Stores (creates or replaces) a program under `name`, for calls by name from other
/// programs. A text with syntax errors is refused with the first error's line. The program is
/// saved before the reply. Limits: 16 MiB per program, 64 MiB per session and 2 GiB on the
/// whole server, all sessions together (`413` naming the limit); this is the
/// one endpoint whose body may exceed 1 MiB, so large programs are stored here and called by
/// name from a short `run`.
#[utoipa::path(
    put,
    path = "/sessions/{id}/programs/{name}",
    tag = "programs",
    params(("id" = String, Path, description = "Session id"), ("name" = String, Path, description = "Program name: letters, digits, _; at most 32; .MPF/.SPF dropped")),
    request_body = ProgramBody,
    responses(
        (status = 200, description = "Stored", body = ProgramInfo),
        (status = 400, description = "Bad name, syntax error (with its line) or malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 413, description = "The program, the session's programs or the server's programs together exceed their size limit", body = ErrorBody),
        (status = 503, description = "The storage failed; the program was not saved", body = ErrorBody),
    )
)]
pub async fn put_program(
    State(state): State<AppState>,
    Path((id, name)): Path<(String, String)>,
    ApiJson(body): ApiJson<ProgramBody>,
) -> Result<Json<ProgramInfo>, ApiError> {
    let entry = find_entry(&state, &id)?;
    let size = body.text.len();
    let stored = state.put_program(&entry, name, body.text).await?;
    Ok(Json(ProgramInfo { name: stored, size }))
}

/// Deletes a stored program.
#[utoipa::path(
    delete,
    path = "/sessions/{id}/programs/{name}",
    tag = "programs",
    params(("id" = String, Path, description = "Session id"), ("name" = String, Path, description = "Program name")),
    responses(
        (status = 204, description = "Deleted"),
        (status = 404, description = "No such session or program", body = ErrorBody),
        (status = 503, description = "The storage failed; the deletion was not saved", body = ErrorBody),
    )
)]
pub async fn delete_program(
    State(state): State<AppState>,
    Path((id, name)): Path<(String, String)>,
) -> Result<StatusCode, ApiError> {
    let entry = find_entry(&state, &id)?;
    let deleted = state.delete_program(&entry, name.clone()).await?;
    if deleted { Ok(StatusCode::NO_CONTENT) } else { Err(ApiError::NotFound(format!("program `{name}`"))) }
}

/// Checks a program without running it: every syntax error, and every name a run would refuse
/// (unknown G function 12470, name not defined 12550, called program missing 14011, jump
/// destination missing 14080; judged against the session's machine, its stored programs, the
/// cycle library and its global user data), with its line and column (the first 1000 listed,
/// `omitted` counts the others). A check costs in proportion to its text, so
/// each session may have 4 MiB of text per second checked, in bursts of 8 MiB (`429` with
/// `Retry-After` beyond).
#[utoipa::path(
    post,
    path = "/sessions/{id}/check",
    tag = "programs",
    params(("id" = String, Path, description = "Session id")),
    request_body = CheckRequest,
    responses(
        (status = 200, description = "The errors found (empty when the program parses and every name is defined)", body = CheckResponse),
        (status = 400, description = "Malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 429, description = "More program text checked per second than the session allows", body = ErrorBody,
            headers(("retry-after" = u64, description = "Seconds until the check would be accepted"))),
    )
)]
pub async fn check(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<CheckRequest>,
) -> Result<Json<CheckResponse>, ApiError> {
    let entry = find_entry(&state, &id)?;
    entry.take_check(body.program.len(), state.limits())?;
    // The names the program may use besides its own: taken from the session's channel (names
    // only, cheap), so that the walk itself does not hold up the session's IPO cycles.
    let session = find_session(&state, &id)?;
    let names = session.with_channel(|ch| ch.name_context()).await.map_err(|e| ApiError::from_session(&id, e))?;
    // On a blocking worker: a check of a large program takes milliseconds of CPU.
    let checked =
        tokio::task::spawn_blocking(move || first_diagnostics(&nctwin_engine::check::program(&body.program, &names)))
            .await
            .map_err(|e| {
                tracing::error!(error = %e, "the syntax check failed");
                ApiError::bad_request("the syntax check of this program failed")
            })?;
    let (diagnostics, omitted) = checked;
    Ok(Json(CheckResponse { diagnostics, omitted }))
}
