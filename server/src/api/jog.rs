//! JOG: move one axis by hand, continuously or by an increment.

use axum::extract::{Path, State};
use nctwin_engine::JogRequest;

use super::{StateReply, command};
use crate::dto::{self, ErrorBody, JogBody, drive};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::session::Action;
use crate::state::AppState;

/// Starts a JOG motion of one axis (JOG mode only). Continuous JOG (no `increment`) runs until
/// `jog/stop` or the software limit. Same `pace`/`wait` options and limits as `run`.
#[utoipa::path(
    post,
    path = "/sessions/{id}/jog",
    tag = "jog",
    params(("id" = String, Path, description = "Session id")),
    request_body = JogBody,
    responses(
        (status = 200, description = "The state after the start, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "Unknown axis, bad direction or increment, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in JOG mode, an axis moves, or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn jog(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<JogBody>,
) -> Result<StateReply, ApiError> {
    let request =
        JogRequest { axis: body.axis, direction: body.direction, increment: body.increment, rapid: body.rapid };
    command(&state, &id, Action::Jog(request), Some(drive(body.pace, body.wait))).await
}

/// Releases the JOG key: the axis brakes to standstill.
#[utoipa::path(
    post,
    path = "/sessions/{id}/jog/stop",
    tag = "jog",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The state (the axis may still be braking)", body = dto::State),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn jog_stop(State(state): State<AppState>, Path(id): Path<String>) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::JogStop, None).await
}
