//! JOG: move one axis by hand, continuously, by an increment or by handwheel pulses, in the
//! MCS or the WCS; referencing axes (the JOG function REF).

use axum::extract::{Path, State};
use nctwin_engine::JogRequest;

use super::{StateReply, command};
use crate::dto::{self, ErrorBody, HandwheelBody, JogBody, ReferenceRequest, drive};
use crate::error::ApiError;
use crate::extract::{ApiJson, OptionalJson};
use crate::session::Action;
use crate::state::AppState;

/// Starts a JOG motion of one axis (JOG mode only). Continuous JOG (neither `increment` nor
/// `inc`) runs until `jog/stop` or the software limit; incremental JOG (`inc`: INC1 … INC1000
/// steps of MD31090 JOG_INCR_WEIGHT, or `increment`: a variable distance) stops at its
/// distance. In `WCS` a geometry axis moves along the active frame's axis. With a program
/// interrupted (NC stop, M0) JOG moves away from it and NC start returns (REPOS). Same
/// `pace`/`wait` options and limits as `run`. For the HMI's JOG keys use the dead-man JOG on
/// the WebSocket stream instead.
#[utoipa::path(
    post,
    path = "/sessions/{id}/jog",
    tag = "jog",
    params(("id" = String, Path, description = "Session id")),
    request_body = JogBody,
    responses(
        (status = 200, description = "The state after the start, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time`, `fast-wall-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "Unknown axis, bad direction, increment or inc, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in JOG mode, an axis moves, or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn jog(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<JogBody>,
) -> Result<StateReply, ApiError> {
    body.validate().map_err(ApiError::bad_request)?;
    let request =
        JogRequest { axis: body.axis, direction: body.direction, increment: body.increment, rapid: body.rapid };
    let action = Action::Jog {
        request,
        system: body.coordinates.map(Into::into),
        rotation: body.rotation.map(Into::into),
        inc: body.inc,
    };
    command(&state, &id, action, Some(drive(body.pace, body.wait))).await
}

/// Handwheel pulses: the axis moves `pulses` × `inc` steps of MD31090 JOG_INCR_WEIGHT (signed);
/// pulses that come while it still moves from earlier ones are added to its path (at most 8
/// queued, then `409`). JOG mode only; answers at once.
#[utoipa::path(
    post,
    path = "/sessions/{id}/jog/handwheel",
    tag = "jog",
    params(("id" = String, Path, description = "Session id")),
    request_body = HandwheelBody,
    responses(
        (status = 200, description = "The state after the pulses were taken", body = dto::State),
        (status = 400, description = "Unknown axis, bad pulses or inc, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in JOG mode, another axis moves, or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn handwheel(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<HandwheelBody>,
) -> Result<StateReply, ApiError> {
    let inc = body.validate().map_err(ApiError::bad_request)?;
    let action = Action::Handwheel { axis: body.axis, pulses: body.pulses, inc, system: body.coordinates.into() };
    command(&state, &id, action, Some(drive(dto::PaceOption::Realtime, false))).await
}

/// References one axis (or every unreferenced axis when the body is empty): the JOG function
/// REF, in JOG mode and reset state. An axis with an incremental encoder (MD34200
/// ENC_REFP_MODE = 1) travels the reference point approach: to the cam (MD34010 direction,
/// MD34020 velocity), to the zero mark (MD34040) and to the reference point (MD34080 + MD34090
/// at MD34070), where it takes MD34100 REFP_SET_POS; `referencing` in the state shows the axis
/// and phase, NC stop or reset abort it. With MD34200 = 0 the axis is referenced at once.
/// Unreferenced axes (MD34210 ENC_REFP_STATE below 2; presets start referenced) refuse NC
/// start in AUTO and MDA with alarm 16905 while MD20700 REFP_NC_START_LOCK is set, unless
/// MD34110 REFP_CYCLE_NR is -1. `pace`/`wait` as for `run`.
#[utoipa::path(
    post,
    path = "/sessions/{id}/reference",
    tag = "jog",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = Option<ReferenceRequest>, description = "Optional; empty references every axis"),
    responses(
        (status = 200, description = "The state after the start of the approach, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time`, `fast-wall-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "Unknown axis, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in JOG mode, not in reset state, or an axis moves", body = ErrorBody),
    )
)]
pub async fn reference(
    State(state): State<AppState>,
    Path(id): Path<String>,
    OptionalJson(body): OptionalJson<ReferenceRequest>,
) -> Result<StateReply, ApiError> {
    command(&state, &id, Action::Reference(body.axis), Some(drive(body.pace, body.wait))).await
}

/// Releases the JOG key: the axis brakes to standstill. Never refused by the command rate
/// limit.
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
