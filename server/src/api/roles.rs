//! `/sessions/{id}/control`: who holds control of a session, and taking and releasing it.
//!
//! With `--auth required` exactly one role's token holds control at a time; commands need it
//! (see [`crate::auth::access`]). The owner holds it when the session is created and can always
//! take it back; an operator takes it when it is free. With `--auth off` every caller is the
//! owner and these endpoints only report.

use axum::Json;
use axum::extract::{Extension, Path, State};

use super::find_entry;
use crate::auth::access::Caller;
use crate::auth::{AuthMode, Role};
use crate::dto::{ControlState, ErrorBody};
use crate::error::ApiError;
use crate::state::{AppState, SessionEntry};

fn control_state(state: &AppState, entry: &SessionEntry, caller: Role) -> ControlState {
    let holder = entry.control_holder();
    ControlState {
        auth: state.auth() == AuthMode::Required,
        role: caller,
        holder,
        you_hold_control: state.auth() == AuthMode::Off || holder == Some(caller),
    }
}

/// Who holds control, and the caller's role.
#[utoipa::path(
    get,
    path = "/sessions/{id}/control",
    tag = "control",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "Control of the session", body = ControlState),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_control(
    State(state): State<AppState>,
    Path(id): Path<String>,
    Extension(Caller(role)): Extension<Caller>,
) -> Result<Json<ControlState>, ApiError> {
    let entry = find_entry(&state, &id)?;
    Ok(Json(control_state(&state, &entry, role)))
}

/// Takes control: allowed when nobody holds it, and always for the owner (who takes it back
/// from an operator). Observers cannot hold control (`403`).
#[utoipa::path(
    post,
    path = "/sessions/{id}/control/take",
    tag = "control",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The caller holds control", body = ControlState),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Another role holds control", body = ErrorBody),
    )
)]
pub async fn take_control(
    State(state): State<AppState>,
    Path(id): Path<String>,
    Extension(Caller(role)): Extension<Caller>,
) -> Result<Json<ControlState>, ApiError> {
    let entry = find_entry(&state, &id)?;
    if state.auth() == AuthMode::Required {
        entry.take_control(role)?;
    }
    Ok(Json(control_state(&state, &entry, role)))
}

/// Releases control so that another client can take it.
#[utoipa::path(
    post,
    path = "/sessions/{id}/control/release",
    tag = "control",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "Control is free", body = ControlState),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "The caller does not hold control", body = ErrorBody),
    )
)]
pub async fn release_control(
    State(state): State<AppState>,
    Path(id): Path<String>,
    Extension(Caller(role)): Extension<Caller>,
) -> Result<Json<ControlState>, ApiError> {
    let entry = find_entry(&state, &id)?;
    if state.auth() == AuthMode::Required {
        entry.release_control(role)?;
    }
    Ok(Json(control_state(&state, &entry, role)))
}
