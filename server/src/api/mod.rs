//! The REST API (prefix `/api/v1`) and the WebSocket stream, one file per resource.
//!
//! Handlers are thin: parse the request, send one command to the session, map the reply.

pub mod active_program;
pub mod control;
pub mod cycles;
pub mod frames;
pub mod health;
pub mod io;
pub mod jog;
pub mod kinematic_chains;
pub mod machine_data;
pub mod machine_data_read;
pub mod machines;
pub mod path_history;
pub mod positioning_dto;
pub mod preview;
pub mod preview_blank;
pub mod probe;
pub mod program_archive;
pub mod programs;
pub mod roles;
pub mod sessions;
pub mod set_wo;
pub mod spindle_dto;
pub mod state_json;
pub mod stock;
pub mod stock_mesh;
pub mod stock_tiles;
pub mod stream;
pub mod stream_frame;
pub mod stream_gate;
pub mod swivel;
pub mod swivel_state;
pub mod tools;
pub mod tools_dto;
pub mod viewers;

use std::time::Duration;

use axum::Json;
use axum::extract::DefaultBodyLimit;
use axum::http::{HeaderValue, StatusCode};
use axum::middleware;
use axum::response::{IntoResponse, Response};
use tower_http::timeout::TimeoutLayer;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use crate::dto::State;
use crate::error::ApiError;
use crate::extract::{BodyLimit, limit_body};
use crate::limits::Limits;
use crate::session::{Action, Drive, Limit, Outcome, SessionHandle};
use crate::state::AppState;

/// URL prefix of the REST API.
pub const PREFIX: &str = "/api/v1";

/// Time limit of requests that answer at once (everything that cannot wait for motion).
pub const QUICK_TIMEOUT: Duration = Duration::from_secs(30);

/// Time limit of requests that may wait for motion (`wait: true`, answered after at most 600 s
/// by the session) and of the WebSocket upgrade: longer than any wait, so no wait is cut short.
pub const WAIT_TIMEOUT: Duration = Duration::from_secs(660);

/// Response header set when a server-side limit ended a command or its wait early:
/// `fast-sim-time` (a fast run reached 3600 s of simulated time and was stopped),
/// `fast-wall-time` (a fast run computed for 10 s of wall time and was stopped) or
/// `wait-wall-time` (the request waited 600 s of wall time).
pub const LIMIT_HEADER: &str = "nctwin-limit";

/// Every API route under [`PREFIX`], with its timeout and body limit, and the OpenAPI paths
/// they document. Program uploads take [`Limits::program_body_bytes`], every other body
/// [`Limits::body_bytes`].
pub fn router(limits: &Limits) -> OpenApiRouter<AppState> {
    let quick = OpenApiRouter::new()
        .routes(routes!(health::health))
        .routes(routes!(machines::list_machines))
        .routes(routes!(machines::get_machine))
        .routes(routes!(machine_data_read::list_definitions))
        .routes(routes!(sessions::list_sessions, sessions::create_session))
        .routes(routes!(sessions::get_session, sessions::delete_session, sessions::patch_session))
        .routes(routes!(sessions::get_state))
        .routes(routes!(control::stop))
        .routes(routes!(control::reset))
        .routes(routes!(control::cancel))
        .routes(routes!(control::set_mode))
        .routes(routes!(control::set_overrides))
        .routes(routes!(control::set_parts))
        .routes(routes!(control::set_options))
        .routes(routes!(jog::jog_stop))
        .routes(routes!(jog::handwheel))
        .routes(routes!(jog::reference))
        .routes(routes!(set_wo::set_work_offset))
        .routes(routes!(control::search))
        .routes(routes!(active_program::get_active_program))
        .routes(routes!(machine_data::put_machine_data, machine_data_read::get_machine_data))
        .routes(routes!(kinematic_chains::get_kinematic_chains, kinematic_chains::put_kinematic_chains))
        .routes(routes!(tools::get_tools, tools::put_tools))
        .routes(routes!(tools::load_tool))
        .routes(routes!(tools::unload_tool))
        .routes(routes!(programs::list_programs))
        .routes(routes!(cycles::list_cycles))
        .routes(routes!(cycles::get_cycle))
        .routes(routes!(programs::check))
        .routes(routes!(preview::preview))
        .routes(routes!(roles::get_control))
        .routes(routes!(roles::take_control))
        .routes(routes!(roles::release_control))
        .routes(routes!(viewers::get_viewers))
        .routes(routes!(io::get_io, io::put_io))
        .routes(routes!(stock::get_stock, stock::put_stock, stock::delete_stock))
        .routes(routes!(stock::get_stock_stl))
        .routes(routes!(probe::get_probe_targets, probe::put_probe_targets))
        .routes(routes!(frames::get_frames))
        .routes(routes!(swivel_state::get_active_swivel))
        .routes(routes!(path_history::get_path_history))
        .routes(routes!(stock_tiles::get_stock_changes))
        .routes(routes!(stock_tiles::get_stock_tile));
    let uploads = OpenApiRouter::new()
        .routes(routes!(programs::get_program, programs::put_program, programs::delete_program))
        .routes(routes!(program_archive::import_archive, program_archive::export_archive))
        .routes(routes!(stock_mesh::put_stock_stl))
        .routes(routes!(stock_mesh::compare_stock));
    let quick = with_body_limit(quick, limits.body_bytes)
        .merge(with_body_limit(uploads, limits.program_body_bytes()))
        .layer(TimeoutLayer::with_status_code(StatusCode::SERVICE_UNAVAILABLE, QUICK_TIMEOUT));
    let waiting = OpenApiRouter::new()
        .routes(routes!(control::run))
        .routes(routes!(control::start))
        .routes(routes!(control::mda))
        .routes(routes!(swivel::swivel))
        .routes(routes!(jog::jog))
        .routes(routes!(stream::stream));
    let waiting = with_body_limit(waiting, limits.body_bytes)
        .layer(TimeoutLayer::with_status_code(StatusCode::SERVICE_UNAVAILABLE, WAIT_TIMEOUT));
    OpenApiRouter::new().nest(PREFIX, quick.merge(waiting))
}

fn with_body_limit(routes: OpenApiRouter<AppState>, bytes: usize) -> OpenApiRouter<AppState> {
    routes.layer(DefaultBodyLimit::max(bytes)).layer(middleware::from_fn_with_state(BodyLimit(bytes), limit_body))
}

/// The live session `id`, or `404`.
pub(crate) fn find_session(state: &AppState, id: &str) -> Result<SessionHandle, ApiError> {
    state.session(id).ok_or_else(|| ApiError::SessionNotFound(id.to_string()))
}

/// The registry entry of session `id`, or `404`.
pub(crate) fn find_entry(state: &AppState, id: &str) -> Result<std::sync::Arc<crate::state::SessionEntry>, ApiError> {
    state.entry(id).ok_or_else(|| ApiError::SessionNotFound(id.to_string()))
}

/// Sends one command to session `id` and answers with the resulting state.
pub(crate) async fn command(
    state: &AppState,
    id: &str,
    action: Action,
    drive: Option<Drive>,
) -> Result<StateReply, ApiError> {
    let session = find_session(state, id)?;
    let outcome = session.command(action, drive).await.map_err(|e| ApiError::from_session(id, e))?;
    Ok(StateReply(outcome))
}

/// A command's reply: the state as JSON, plus [`LIMIT_HEADER`] when a limit ended it early.
#[derive(Debug)]
pub struct StateReply(pub Outcome);

impl IntoResponse for StateReply {
    fn into_response(self) -> Response {
        let mut response = Json(State::from(self.0.snapshot.as_ref())).into_response();
        if let Some(limit) = self.0.limit {
            let value = match limit {
                Limit::FastSimTime => "fast-sim-time",
                Limit::FastWallTime => "fast-wall-time",
                Limit::WaitWallTime => "wait-wall-time",
            };
            response.headers_mut().insert(LIMIT_HEADER, HeaderValue::from_static(value));
        }
        response
    }
}
