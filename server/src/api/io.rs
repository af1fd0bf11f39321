//! `GET/PUT /sessions/{id}/io`: the session's digital NCK inputs and outputs (`$A_IN[n]`,
//! `$A_OUT[n]`, n = 1..40). Programs read both and write the outputs; a client stands in for
//! the machine's wiring: it sets inputs (a part-present switch, a clamping signal) and may set
//! outputs too, as a test bench would. The image is the channel's live state; it is not saved
//! (the control's outputs are off after power on).

use axum::Json;
use axum::extract::{Path, State};
use nctwin_engine::interp::io::{DIGITAL_IO, DigitalIo};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::state::AppState;

/// The digital I/O image: element 0 is signal 1 (`$A_IN[1]`, `$A_OUT[1]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct IoImage {
    /// `$A_IN[1..40]`.
    pub inputs: Vec<bool>,
    /// `$A_OUT[1..40]`.
    pub outputs: Vec<bool>,
}

impl From<DigitalIo> for IoImage {
    fn from(io: DigitalIo) -> IoImage {
        IoImage {
            inputs: (1..=DIGITAL_IO).map(|n| io.input(n).unwrap_or(false)).collect(),
            outputs: (1..=DIGITAL_IO).map(|n| io.output(n).unwrap_or(false)).collect(),
        }
    }
}

/// One signal to set: its number (1..40) and level.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Signal {
    #[schema(example = 3)]
    pub signal: u32,
    pub value: bool,
}

/// Signals to change; the others keep their level.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct IoChange {
    #[serde(default)]
    pub inputs: Vec<Signal>,
    #[serde(default)]
    pub outputs: Vec<Signal>,
}

/// The digital inputs and outputs as the main run holds them.
#[utoipa::path(
    get,
    path = "/sessions/{id}/io",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The I/O image", body = IoImage),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_io(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<IoImage>, ApiError> {
    let session = find_session(&state, &id)?;
    let io = session.with_channel(|ch| ch.digital_io()).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(io.into()))
}

/// Sets digital inputs (and outputs) at once, in any mode and while a program runs: a block
/// that reads `$A_IN` after this sees the new level. All or nothing: a signal outside 1..40
/// is a `400` and changes nothing.
#[utoipa::path(
    put,
    path = "/sessions/{id}/io",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = IoChange,
    responses(
        (status = 200, description = "The I/O image after the change", body = IoImage),
        (status = 400, description = "A signal number outside 1..40; nothing changed", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn put_io(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(change): ApiJson<IoChange>,
) -> Result<Json<IoImage>, ApiError> {
    let list = |s: &[Signal]| s.iter().map(|s| (s.signal as usize, s.value)).collect::<Vec<_>>();
    let (inputs, outputs) = (list(&change.inputs), list(&change.outputs));
    let session = find_session(&state, &id)?;
    let result = session
        .with_channel(move |ch| ch.set_signals(&inputs, &outputs).map(|()| ch.digital_io()))
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    let io = result.map_err(|e| ApiError::bad_request(e.to_string()))?;
    Ok(Json(io.into()))
}
