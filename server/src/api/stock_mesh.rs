//! `PUT /sessions/{id}/stock.stl` (a blank of any shape from an STL) and
//! `POST /sessions/{id}/stock/compare` (the cut stock against the target part's STL: the
//! largest over- and undercut). Both STLs are binary or ASCII, closed, in mm, in the WCS of
//! the active frame (as a `PUT .../stock` blank); bodies up to the program upload limit.

use axum::Json;
use axum::body::Bytes;
use axum::extract::{Path, State};
use nctwin_engine::stock::target::{Comparison, Mesh};
use serde::Serialize;
use utoipa::ToSchema;

use super::find_session;
use super::stock::{StockReport, report};
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// The stock against the target part.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StockComparison {
    /// Thickest material cut away from the target on one dexel line (along Z), mm.
    pub overcut: f64,
    /// The middle of that material (BCS, mm): where to look.
    pub overcut_at: [f64; 3],
    /// Target material the stock lacks, mm³.
    pub overcut_volume: f64,
    /// Thickest material left beyond the target on one dexel line (along Z), mm.
    pub undercut: f64,
    pub undercut_at: [f64; 3],
    /// Stock material outside the target, mm³.
    pub undercut_volume: f64,
}

impl From<Comparison> for StockComparison {
    fn from(c: Comparison) -> StockComparison {
        StockComparison {
            overcut: c.overcut,
            overcut_at: c.overcut_at,
            overcut_volume: c.overcut_volume,
            undercut: c.undercut,
            undercut_at: c.undercut_at,
            undercut_volume: c.undercut_volume,
        }
    }
}

fn mesh(body: &[u8]) -> Result<Mesh, ApiError> {
    Mesh::from_stl(body).map_err(|e| ApiError::bad_request(format!("STL: {e}")))
}

/// Defines the blank as the closed mesh of an STL (mills; while nothing moves).
#[utoipa::path(
    put,
    path = "/sessions/{id}/stock.stl",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = Vec<u8>, content_type = "model/stl", description = "Binary or ASCII STL of the blank, mm, WCS of the active frame"),
    responses(
        (status = 200, description = "The stock of the new blank", body = StockReport),
        (status = 400, description = "Not an STL, no material in it, too many cells at the resolution, a lathe, a tilted frame", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "Axes move", body = ErrorBody),
    )
)]
pub async fn put_stock_stl(
    State(state): State<AppState>,
    Path(id): Path<String>,
    body: Bytes,
) -> Result<Json<StockReport>, ApiError> {
    let blank = mesh(&body)?;
    let session = find_session(&state, &id)?;
    let r = session
        .with_channel(move |ch| -> Result<StockReport, ApiError> {
            ch.define_stock_mesh(&blank)?;
            Ok(report(ch))
        })
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(r?))
}

/// Compares the stock as it is now with the target part.
#[utoipa::path(
    post,
    path = "/sessions/{id}/stock/compare",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body(content = Vec<u8>, content_type = "model/stl", description = "Binary or ASCII STL of the finished part, mm, WCS of the active frame"),
    responses(
        (status = 200, description = "Largest over- and undercut", body = StockComparison),
        (status = 400, description = "Not an STL, no blank, a turned stock, a tilted frame", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn compare_stock(
    State(state): State<AppState>,
    Path(id): Path<String>,
    body: Bytes,
) -> Result<Json<StockComparison>, ApiError> {
    let target = mesh(&body)?;
    let session = find_session(&state, &id)?;
    let c =
        session.with_channel(move |ch| ch.compare_stock(&target)).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(c?.into()))
}
