//! `GET/PUT /sessions/{id}/tools` and `POST /sessions/{id}/tools/{name}/load|unload`: the
//! session's tool list (tools with names, duplo numbers, cutting edges and places, the
//! magazines) as the control's tool management keeps it. Changes act at once, only in reset
//! state, and are saved with the machine data before the reply.

use axum::Json;
use axum::extract::{Path, Query, State};

use super::tools_dto::{LoadRequest, ToolList, UnloadQuery};
use super::{command, find_entry, find_session};
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::session::Action;
use crate::state::AppState;

/// The session's tool list.
#[utoipa::path(
    get,
    path = "/sessions/{id}/tools",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "Tools (with edges, places, whether a place was given at activation, the tool in the spindle) and magazines", body = ToolList),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_tools(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<ToolList>, ApiError> {
    Ok(Json(tool_list(&state, &id).await?))
}

/// Replaces the whole tool list (every cutting edge and tool-management datum) all-or-nothing;
/// only in reset state. Named tools without a place go into the first free magazine place.
#[utoipa::path(
    put,
    path = "/sessions/{id}/tools",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = ToolList,
    responses(
        (status = 200, description = "The new tool list", body = ToolList),
        (status = 400, description = "A bad value, naming its field (e.g. `tools[1].edges[0].d: 13 is out of range 1..12`), or inconsistent data (a tool in two places, two tools with one name and duplo number); nothing applied", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in reset state", body = ErrorBody),
        (status = 503, description = "Applied, but the storage failed: not saved yet", body = ErrorBody),
    )
)]
pub async fn put_tools(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<ToolList>,
) -> Result<Json<ToolList>, ApiError> {
    let (text, fields) = body.to_text().map_err(ApiError::bad_request)?;
    let result = command(&state, &id, Action::ToolData(text), None).await;
    if let Err(ApiError::BadRequest { message, line: Some(line) }) = &result
        && let Some(field) = fields.get((*line as usize).wrapping_sub(1))
    {
        // A line of the tool data text was refused: name the field it came from.
        let why = message.split_once(&format!("line {line}: ")).map_or(message.as_str(), |(_, why)| why);
        return Err(ApiError::bad_request(format!("{field}: {why}")));
    }
    result?;
    save(&state, &id).await?;
    Ok(Json(tool_list(&state, &id).await?))
}

/// Loads a tool into a magazine place (a free, enabled ordinary place of a real magazine).
#[utoipa::path(
    post,
    path = "/sessions/{id}/tools/{name}/load",
    tag = "sessions",
    params(
        ("id" = String, Path, description = "Session id"),
        ("name" = String, Path, description = "Tool name ($TC_TP2), or the T number of a tool without one"),
    ),
    request_body = LoadRequest,
    responses(
        (status = 200, description = "The new tool list", body = ToolList),
        (status = 400, description = "No such tool, no such place, or the place is occupied or disabled", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in reset state", body = ErrorBody),
        (status = 503, description = "Applied, but the storage failed: not saved yet", body = ErrorBody),
    )
)]
pub async fn load_tool(
    State(state): State<AppState>,
    Path((id, name)): Path<(String, String)>,
    ApiJson(body): ApiJson<LoadRequest>,
) -> Result<Json<ToolList>, ApiError> {
    let action = Action::LoadTool { name, duplo: body.duplo, magazine: body.magazine, place: body.place };
    command(&state, &id, action, None).await?;
    save(&state, &id).await?;
    Ok(Json(tool_list(&state, &id).await?))
}

/// Unloads a tool from its place to the loading magazine 9999 (not the tool in the spindle).
#[utoipa::path(
    post,
    path = "/sessions/{id}/tools/{name}/unload",
    tag = "sessions",
    params(
        ("id" = String, Path, description = "Session id"),
        ("name" = String, Path, description = "Tool name ($TC_TP2), or the T number of a tool without one"),
        UnloadQuery,
    ),
    responses(
        (status = 200, description = "The new tool list", body = ToolList),
        (status = 400, description = "No such tool, the tool is not loaded or is in the spindle", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Not in reset state", body = ErrorBody),
        (status = 503, description = "Applied, but the storage failed: not saved yet", body = ErrorBody),
    )
)]
pub async fn unload_tool(
    State(state): State<AppState>,
    Path((id, name)): Path<(String, String)>,
    query: Result<Query<UnloadQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Json<ToolList>, ApiError> {
    let Query(query) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    command(&state, &id, Action::UnloadTool { name, duplo: query.duplo }, None).await?;
    save(&state, &id).await?;
    Ok(Json(tool_list(&state, &id).await?))
}

async fn tool_list(state: &AppState, id: &str) -> Result<ToolList, ApiError> {
    let session = find_session(state, id)?;
    session
        .with_channel(|ch| {
            let s = ch.snapshot();
            let list = ToolList::from_config(ch.config(), s.tool.0, s.prepared_tool);
            match ch.monitored_edge() {
                Some((t, d, minutes)) => list.with_remaining_time(t, d, minutes),
                None => list,
            }
        })
        .await
        .map_err(|e| ApiError::from_session(id, e))
}

async fn save(state: &AppState, id: &str) -> Result<(), ApiError> {
    let entry = find_entry(state, id)?;
    state.persist_checkpoint(&entry).await
}
