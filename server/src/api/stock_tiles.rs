//! The stock's incremental mesh for the HMI: `GET /sessions/{id}/stock/changes?since=N` names
//! the tiles (64 × 64 dexel cells) a cut changed after version N and the tools behind the pens,
//! `GET /sessions/{id}/stock/tiles/{i}/{j}` is one tile as a binary STL whose faces carry the
//! pen of the tool that cut them in their attribute bytes. The state's `stock.version` says
//! when to ask.

use axum::Json;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Path, Query, State};
use axum::http::header::CONTENT_TYPE;
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use utoipa::{IntoParams, ToSchema};

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// Which version the client shows.
#[derive(Debug, Clone, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct Since {
    /// The stock version shown; 0 (or absent): every tile.
    #[serde(default)]
    pub since: u32,
}

/// The tool and cutting edge a pen stands for.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct PenTool {
    /// The pen: the attribute of the faces this tool cut (1, 2, ...; 0 is the blank's own face).
    pub pen: u32,
    pub t: u32,
    pub d: u32,
}

impl PenTool {
    /// The pens of the engine's list (tool and edge of pen n at n − 1).
    pub fn list(pens: &[(u32, u32)]) -> Vec<PenTool> {
        pens.iter().enumerate().map(|(n, (t, d))| PenTool { pen: n as u32 + 1, t: *t, d: *d }).collect()
    }
}

/// One tile's mesh on the stream.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct TileMesh {
    pub i: u32,
    pub j: u32,
    /// The tile as binary STL (as `GET .../stock/tiles/{i}/{j}`), base64.
    pub stl: String,
}

/// The stock's changes pushed on the stream (`{"type": "stock", ...}`): the tiles a cut changed
/// from version `since` to `version`, the meshes of the first few (at most 4 and 512 kB of
/// STL), the others to fetch with `GET .../stock/tiles/{i}/{j}`. `reload`: the client's version
/// cannot be brought up to date from here (it joined later, fell behind, or the blank is new):
/// fetch `GET .../stock/changes?since=0`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StockTilesMessage {
    pub version: u32,
    pub since: u32,
    pub reload: bool,
    /// Cells per tile edge.
    pub tile_cells: usize,
    /// The changed tiles, `[i, j]` (a turned stock: `[0, 0]`, the whole mesh).
    pub tiles: Vec<[u32; 2]>,
    pub pens: Vec<PenTool>,
    pub meshes: Vec<TileMesh>,
}

impl StockTilesMessage {
    /// "Fetch everything of version `version` over REST".
    pub fn reload(version: u32) -> StockTilesMessage {
        StockTilesMessage {
            version,
            since: 0,
            reload: true,
            tile_cells: nctwin_engine::channel::STOCK_TILE,
            tiles: Vec::new(),
            pens: Vec::new(),
            meshes: Vec::new(),
        }
    }
}

/// The tiles changed since a version.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StockChangesReport {
    /// The stock's version now.
    pub version: u32,
    /// Cells per tile edge.
    pub tile_cells: usize,
    /// The changed tiles, `[i, j]`.
    pub tiles: Vec<[u32; 2]>,
    pub pens: Vec<PenTool>,
}

/// The tiles changed since the version the client shows.
#[utoipa::path(
    get,
    path = "/sessions/{id}/stock/changes",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id"), Since),
    responses(
        (status = 200, description = "The changed tiles and the pens' tools", body = StockChangesReport),
        (status = 400, description = "`since` is not a version number", body = ErrorBody),
        (status = 404, description = "No such session, or no blank", body = ErrorBody),
    )
)]
pub async fn get_stock_changes(
    State(state): State<AppState>,
    Path(id): Path<String>,
    query: Result<Query<Since>, QueryRejection>,
) -> Result<Json<StockChangesReport>, ApiError> {
    let Query(q) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    let session = find_session(&state, &id)?;
    let c =
        session.with_channel(move |ch| ch.stock_changes(q.since)).await.map_err(|e| ApiError::from_session(&id, e))?;
    let c = c.ok_or_else(|| ApiError::NotFound(format!("session `{id}` has no blank (WORKPIECE or PUT .../stock)")))?;
    Ok(Json(StockChangesReport {
        version: c.version,
        tile_cells: c.tile,
        tiles: c.tiles,
        pens: PenTool::list(&c.pens),
    }))
}

/// One tile of the stock as a binary STL (the whole stock of a turned one: tile 0, 0).
#[utoipa::path(
    get,
    path = "/sessions/{id}/stock/tiles/{i}/{j}",
    tag = "sessions",
    params(
        ("id" = String, Path, description = "Session id"),
        ("i" = usize, Path, description = "Tile column (X)"),
        ("j" = usize, Path, description = "Tile row (Y)"),
    ),
    responses(
        (status = 200, description = "Binary STL of the tile, faces' attribute = pen", content_type = "model/stl", body = Vec<u8>),
        (status = 400, description = "A tile index that is not a whole number from 0", body = ErrorBody),
        (status = 404, description = "No such session, no blank, or no such tile", body = ErrorBody),
    )
)]
pub async fn get_stock_tile(
    State(state): State<AppState>,
    Path((id, i, j)): Path<(String, String, String)>,
) -> Result<Response, ApiError> {
    let index = |name: &str, text: &str| {
        text.parse::<usize>()
            .map_err(|_| ApiError::bad_request(format!("tile index {name} `{text}` is not a whole number from 0")))
    };
    let (i, j) = (index("i", &i)?, index("j", &j)?);
    let session = find_session(&state, &id)?;
    let stl =
        session.with_channel(move |ch| ch.stock_tile_stl(i, j)).await.map_err(|e| ApiError::from_session(&id, e))?;
    let stl = stl.ok_or_else(|| ApiError::NotFound(format!("session `{id}` has no stock tile {i}, {j}")))?;
    Ok(([(CONTENT_TYPE, "model/stl")], stl).into_response())
}
