//! `/sessions`: create, list, inspect and delete sessions, and read a session's state.

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use nctwin_engine::Channel;
use nctwin_engine::machine_data::presets;

use super::{PREFIX, find_session};
use crate::dto::{self, CreateSession, ErrorBody, Session, SessionSummary};
use crate::error::ApiError;
use crate::extract::OptionalJson;
use crate::state::AppState;

/// Every live session, oldest first.
#[utoipa::path(
    get,
    path = "/sessions",
    tag = "sessions",
    responses((status = 200, description = "The live sessions", body = Vec<SessionSummary>))
)]
pub async fn list_sessions(State(state): State<AppState>) -> Json<Vec<SessionSummary>> {
    let list = state
        .list_sessions()
        .iter()
        .map(|s| {
            let snapshot = s.snapshot();
            SessionSummary {
                id: s.id().into(),
                machine: s.machine().into(),
                status: snapshot.status.into(),
                mode: snapshot.mode.into(),
            }
        })
        .collect();
    Json(list)
}

/// Creates a session: a simulated channel of a preset machine, plus optional NC data text.
///
/// The body may be empty (all defaults: preset `mill-3axis`).
#[utoipa::path(
    post,
    path = "/sessions",
    tag = "sessions",
    request_body(content = Option<CreateSession>, description = "Optional; empty means defaults"),
    responses(
        (status = 201, description = "The new session", body = Session,
            headers(("location" = String, description = "URL of the new session"))),
        (status = 400, description = "Unknown preset, bad machine data (with its line) or a malformed body", body = ErrorBody),
        (status = 413, description = "Body larger than 1 MiB", body = ErrorBody),
    )
)]
pub async fn create_session(
    State(state): State<AppState>,
    OptionalJson(body): OptionalJson<CreateSession>,
) -> Result<Response, ApiError> {
    let machine = match body.machine {
        Some(m) => m,
        None => presets::PRESETS.first().map(|p| p.id.to_string()).unwrap_or_default(),
    };
    if presets::find(&machine).is_none() {
        let known: Vec<&str> = presets::PRESETS.iter().map(|p| p.id).collect();
        return Err(ApiError::bad_request(format!("unknown machine preset `{machine}` (known: {})", known.join(", "))));
    }
    let channel = Channel::from_preset(&machine, body.machine_data.as_deref().unwrap_or(""))?;
    let handle = state.create_session(&machine, channel);
    let body = Session {
        id: handle.id().into(),
        machine: machine.clone(),
        state: dto::State::from(handle.snapshot().as_ref()),
    };
    let mut response = (StatusCode::CREATED, Json(body)).into_response();
    if let Ok(location) = HeaderValue::from_str(&format!("{PREFIX}/sessions/{}", handle.id())) {
        response.headers_mut().insert(header::LOCATION, location);
    }
    Ok(response)
}

/// One session with its state.
#[utoipa::path(
    get,
    path = "/sessions/{id}",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The session", body = Session),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_session(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<Session>, ApiError> {
    let session = find_session(&state, &id)?;
    Ok(Json(Session {
        id: session.id().into(),
        machine: session.machine().into(),
        state: dto::State::from(session.snapshot().as_ref()),
    }))
}

/// Deletes a session: its channel stops, its streams close and requests waiting on it end.
#[utoipa::path(
    delete,
    path = "/sessions/{id}",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 204, description = "Deleted"),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn delete_session(State(state): State<AppState>, Path(id): Path<String>) -> Result<StatusCode, ApiError> {
    if state.remove_session(&id).await { Ok(StatusCode::NO_CONTENT) } else { Err(ApiError::SessionNotFound(id)) }
}

/// The current state of the session's channel (the latest published snapshot; never waits).
#[utoipa::path(
    get,
    path = "/sessions/{id}/state",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The state", body = dto::State),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_state(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<dto::State>, ApiError> {
    let session = find_session(&state, &id)?;
    Ok(Json(dto::State::from(session.snapshot().as_ref())))
}
