//! `PUT /sessions/{id}/machine-data`: change a session's NC data.

use axum::extract::{Path, State};
use axum::http::HeaderValue;
use axum::response::{IntoResponse, Response};

use super::{command, find_entry};
use crate::dto::{self, ErrorBody, MachineDataRequest};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::session::Action;
use crate::state::AppState;

/// Applies NC data text (machine data, tool data, settable frames) all-or-nothing and activates
/// it as a reset would; only in reset state. Axis positions are kept where the axes still exist.
/// The new machine data is saved before the reply. Tool-data and settings files load as they
/// are (`%_N_TOA_INI` header, `CHANDATA(1)`, `METRIC`, `$P_UIFR[n]=CTRANS(...):CROT(...)`,
/// `M17`); tool-management data NCTwin does not model (`$TC_TPC`, `$TC_MPPC`, ...) and setting data it does not
/// know are accepted and ignored, each family named in a `nctwin-nc-data-ignored` header.
#[utoipa::path(
    put,
    path = "/sessions/{id}/machine-data",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = MachineDataRequest,
    responses(
        (status = 200, description = "The state with the new data active", body = dto::State,
            headers(("nctwin-nc-data-ignored" = String, description = "One per family of lines accepted but not modelled (e.g. `$TC_TPC: 12 line(s) from line 3 ...`)"))),
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
) -> Result<Response, ApiError> {
    let warnings = nctwin_engine::machine_data::text::warnings(&body.text);
    let reply = command(&state, &id, Action::MachineData(body.text), None).await?;
    let entry = find_entry(&state, &id)?;
    state.persist_checkpoint(&entry).await?;
    let mut response = reply.into_response();
    for warning in warnings {
        if let Ok(value) = HeaderValue::from_str(&warning) {
            response.headers_mut().append(IGNORED_HEADER, value);
        }
    }
    Ok(response)
}

/// Names a family of NC data lines accepted but not modelled (one header per family).
pub const IGNORED_HEADER: &str = "nctwin-nc-data-ignored";
