//! `GET/PUT /sessions/{id}/probe-targets`: planes the simulated touch-trigger probe of
//! MEAS/MEAW touches besides the session's stock (`nctwin_engine::channel::ProbeTarget`), so a
//! measuring program can be tried without a blank.

use axum::Json;
use axum::extract::{Path, State};
use nctwin_engine::channel::{MAX_PROBE_TARGETS, ProbeTarget};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::state::AppState;

/// A plane in the BCS (mm): the material lies behind it, against its normal.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ProbePlane {
    /// A point of the surface, X, Y, Z.
    #[schema(example = json!([30.0, 0.0, 0.0]))]
    pub point: [f64; 3],
    /// The outward normal (normalised when stored).
    #[schema(example = json!([-1.0, 0.0, 0.0]))]
    pub normal: [f64; 3],
}

/// The probe-target planes of a session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ProbeTargets {
    /// At most 16 planes; `[]` removes them.
    pub planes: Vec<ProbePlane>,
}

fn targets(ch: &nctwin_engine::Channel) -> ProbeTargets {
    ProbeTargets {
        planes: ch.probe_targets().iter().map(|t| ProbePlane { point: t.point, normal: t.normal }).collect(),
    }
}

/// The planes the probe touches besides the stock.
#[utoipa::path(
    get,
    path = "/sessions/{id}/probe-targets",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The probe-target planes", body = ProbeTargets),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_probe_targets(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<ProbeTargets>, ApiError> {
    let session = find_session(&state, &id)?;
    let r = session.with_channel(|ch| targets(ch)).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(r))
}

/// Replaces the probe-target planes, all or nothing.
#[utoipa::path(
    put,
    path = "/sessions/{id}/probe-targets",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = ProbeTargets,
    responses(
        (status = 200, description = "The planes as stored (normals of length 1)", body = ProbeTargets),
        (status = 400, description = "More than 16 planes, a zero normal or a value that is not a finite number", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn put_probe_targets(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<ProbeTargets>,
) -> Result<Json<ProbeTargets>, ApiError> {
    if body.planes.len() > MAX_PROBE_TARGETS {
        return Err(ApiError::bad_request(format!("at most {MAX_PROBE_TARGETS} probe-target planes")));
    }
    let planes: Vec<ProbeTarget> =
        body.planes.iter().map(|p| ProbeTarget { point: p.point, normal: p.normal }).collect();
    let session = find_session(&state, &id)?;
    let result = session
        .with_channel(move |ch| {
            ch.set_probe_targets(planes)?;
            Ok::<_, nctwin_engine::channel::CommandError>(targets(ch))
        })
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(result?))
}
