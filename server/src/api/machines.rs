//! `GET /machines`, `GET /machines/{id}`: the built-in machine presets.

use axum::Json;
use axum::extract::Path;
use nctwin_engine::machine_data::presets;

use crate::dto::{ErrorBody, MachineDetail, MachineSummary};
use crate::error::ApiError;

/// The built-in machine presets a session can be created from.
#[utoipa::path(
    get,
    path = "/machines",
    tag = "machines",
    responses((status = 200, description = "Every preset", body = Vec<MachineSummary>))
)]
pub async fn list_machines() -> Json<Vec<MachineSummary>> {
    Json(presets::PRESETS.iter().map(MachineSummary::from).collect())
}

/// One preset with its NC data text.
#[utoipa::path(
    get,
    path = "/machines/{id}",
    tag = "machines",
    params(("id" = String, Path, description = "Preset id, e.g. `mill-3axis`")),
    responses(
        (status = 200, description = "The preset", body = MachineDetail),
        (status = 404, description = "No such preset", body = ErrorBody),
    )
)]
pub async fn get_machine(Path(id): Path<String>) -> Result<Json<MachineDetail>, ApiError> {
    presets::find(&id).map(|p| Json(MachineDetail::from(p))).ok_or(ApiError::MachineNotFound(id))
}
