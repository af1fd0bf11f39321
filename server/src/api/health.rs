//! `GET /health`: liveness for load balancers, scripts and CI.

use axum::Json;
use axum::extract::State;

use crate::dto::Health;
use crate::state::AppState;

/// The server answers; reports its version and the number of live sessions.
#[utoipa::path(
    get,
    path = "/health",
    tag = "health",
    responses((status = 200, description = "The server is up", body = Health))
)]
pub async fn health(State(state): State<AppState>) -> Json<Health> {
    Json(Health { status: "ok".into(), version: crate::VERSION.into(), sessions: state.session_count() })
}
