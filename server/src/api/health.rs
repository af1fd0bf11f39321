//! `GET /health`: liveness for load balancers, scripts and CI.

use axum::Json;
use axum::extract::State;

use crate::auth::AuthMode;
use crate::dto::{Health, StorageStatus};
use crate::state::AppState;

/// The server answers; reports its version, the number of live sessions, the auth mode and
/// whether the storage works (a trivial read).
#[utoipa::path(
    get,
    path = "/health",
    tag = "health",
    responses((status = 200, description = "The server is up", body = Health))
)]
pub async fn health(State(state): State<AppState>) -> Json<Health> {
    let storage = state.storage_health().await;
    let status = if storage.error.is_none() { "ok" } else { "degraded" };
    Json(Health {
        status: status.into(),
        version: crate::VERSION.into(),
        sessions: state.session_count(),
        storage: StorageStatus {
            backend: storage.backend.into(),
            status: if storage.error.is_none() { "ok" } else { "error" }.into(),
            error: storage.error,
        },
        auth: match state.auth() {
            AuthMode::Off => "off",
            AuthMode::Required => "required",
        }
        .into(),
    })
}
