//! `/sessions`: create, list, inspect and delete sessions, and read a session's state.

use std::net::SocketAddr;

use axum::Json;
use axum::extract::{ConnectInfo, Extension, Path, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use nctwin_engine::Channel;
use nctwin_engine::machine_data::presets;

use super::{PREFIX, find_entry, find_session};
use crate::auth::access;
use crate::dto::{self, CreateSession, CreatedSession, ErrorBody, Session, SessionPatch, SessionSummary, Tokens};
use crate::error::ApiError;
use crate::extract::{ApiJson, OptionalJson};
use crate::state::{AppState, SessionEntry};

/// Every live session, oldest first. With `--auth required`, the sessions the bearer token
/// belongs to.
#[utoipa::path(
    get,
    path = "/sessions",
    tag = "sessions",
    responses(
        (status = 200, description = "The live sessions", body = Vec<SessionSummary>),
        (status = 401, description = "No bearer token (auth required only)", body = ErrorBody),
    ),
    security((), ("bearer" = []))
)]
pub async fn list_sessions(State(state): State<AppState>, headers: HeaderMap) -> Json<Vec<SessionSummary>> {
    let token = access::bearer(&headers);
    let list = access::visible_to(&state, token.as_deref())
        .iter()
        .map(|e| {
            let s = &e.handle;
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
/// The body may be empty (all defaults: preset `mill-3axis`). The session is saved before the
/// reply. Unless created `persistent`, a session no client uses for the server's idle timeout
/// (`--session-idle-timeout`, default 24 h) is deleted. The reply holds the session's three tokens (owner, operator, observer), shown only
/// here; with `--auth required` every request to the session needs one of them. Creating a
/// session needs no token.
#[utoipa::path(
    post,
    path = "/sessions",
    tag = "sessions",
    request_body(content = Option<CreateSession>, description = "Optional; empty means defaults"),
    responses(
        (status = 201, description = "The new session with its tokens", body = CreatedSession,
            headers(("location" = String, description = "URL of the new session"))),
        (status = 400, description = "Unknown preset, bad machine data (with its line) or a malformed body", body = ErrorBody),
        (status = 413, description = "Body larger than 1 MiB", body = ErrorBody),
        (status = 429, description = "Too many sessions on the server or from this client address", body = ErrorBody),
        (status = 503, description = "The storage failed; no session was created", body = ErrorBody),
    )
)]
pub async fn create_session(
    State(state): State<AppState>,
    peer: Option<Extension<ConnectInfo<SocketAddr>>>,
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
    let mut channel = Channel::from_preset(&machine, body.machine_data.as_deref().unwrap_or(""))?;
    crate::session::start_clock(&mut channel);
    let client_ip = peer.map(|Extension(ConnectInfo(addr))| addr.ip());
    let persistent = body.persistent.unwrap_or(false);
    let (entry, tokens) = state.create_session(&machine, channel, client_ip, persistent).await?;
    let handle = &entry.handle;
    let body = CreatedSession {
        id: handle.id().into(),
        machine: machine.clone(),
        state: dto::State::from(handle.snapshot().as_ref()),
        tokens: Tokens { owner: tokens.owner, operator: tokens.operator, observer: tokens.observer },
        persistent,
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
    Ok(Json(session_body(&*find_entry(&state, &id)?)))
}

fn session_body(entry: &SessionEntry) -> Session {
    let session = &entry.handle;
    Session {
        id: session.id().into(),
        machine: session.machine().into(),
        state: dto::State::from(session.snapshot().as_ref()),
        persistent: entry.persistent(),
    }
}

/// Changes a session's settings: `persistent` (`true`: it never expires when idle). Saved
/// before the reply. Owner only.
#[utoipa::path(
    patch,
    path = "/sessions/{id}",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = SessionPatch,
    responses(
        (status = 200, description = "The session with the change", body = Session),
        (status = 400, description = "A malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 503, description = "The storage failed; nothing changed", body = ErrorBody),
    )
)]
pub async fn patch_session(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<SessionPatch>,
) -> Result<Json<Session>, ApiError> {
    let entry = find_entry(&state, &id)?;
    if let Some(persistent) = body.persistent {
        state.set_persistent(&entry, persistent).await?;
    }
    Ok(Json(session_body(&entry)))
}

/// Deletes a session: its channel stops, its streams close, requests waiting on it end and it
/// is removed from storage (with its programs) before the reply. Owner only.
#[utoipa::path(
    delete,
    path = "/sessions/{id}",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 204, description = "Deleted"),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 503, description = "The storage failed; the session was not deleted", body = ErrorBody),
    )
)]
pub async fn delete_session(State(state): State<AppState>, Path(id): Path<String>) -> Result<StatusCode, ApiError> {
    if state.remove_session(&id).await? { Ok(StatusCode::NO_CONTENT) } else { Err(ApiError::SessionNotFound(id)) }
}

/// The current state of the session's channel (the latest published snapshot; never waits).
#[utoipa::path(
    get,
    path = "/sessions/{id}/state",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The state", body = dto::State),
        (status = 404, description = "No such session, or its engine has ended (the last state would be stale)", body = ErrorBody),
    )
)]
pub async fn get_state(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<dto::State>, ApiError> {
    let session = find_session(&state, &id)?;
    if session.has_ended() {
        return Err(ApiError::SessionEnded(id));
    }
    Ok(Json(dto::State::from(session.snapshot().as_ref())))
}
