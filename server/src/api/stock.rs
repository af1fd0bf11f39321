//! `GET/PUT/DELETE /sessions/{id}/stock` and `GET /sessions/{id}/stock.stl`: the session's
//! workpiece being cut (material removal, `nctwin_engine::stock`).
//!
//! A program defines the blank with `WORKPIECE(..)`; `PUT` defines it from outside (in the
//! WCS of the active frame, while nothing moves) and sets the resolution (for the next blank)
//! and the depth-of-cut limit. `GET` answers the volumes and the checks raised (rapid into
//! stock, no spindle, depth of cut, each with its program line; the state carries the summary
//! and the stream the `stock` event). The STL is the stock as it is now, in the BCS, in mm.

use axum::Json;
use axum::extract::{Path, State};
use axum::http::header::CONTENT_TYPE;
use axum::response::{IntoResponse, Response};
use nctwin_engine::channel::{StockInfo, StockOptions, StockWarning};
use nctwin_engine::stock::blank::{Blank, Shape};
use nctwin_engine::stock::holder::Holder;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::state::AppState;

/// One check's finding.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StockWarningInfo {
    /// `rapid_into_stock`, `no_spindle`, `depth_of_cut` or `holder_collision`.
    #[schema(example = "rapid_into_stock")]
    pub check: String,
    /// Program line of the block that cut.
    pub line: u32,
    /// Volume that block's segment removed, mm³.
    pub volume: f64,
    /// Its depth of cut, mm.
    pub depth: f64,
    /// Where the segment that cut began: the tool tip in the BCS, mm (X, Y, Z).
    pub position: [f64; 3],
}

impl From<&StockWarning> for StockWarningInfo {
    fn from(w: &StockWarning) -> StockWarningInfo {
        StockWarningInfo {
            check: w.check.as_str().into(),
            line: w.line,
            volume: w.volume,
            depth: w.depth,
            position: w.position,
        }
    }
}

/// The stock summary of the state (`stock`), absent without a blank.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StockSummary {
    /// `turning` (radius profile on a lathe) or `milling` (Z-dexels).
    #[schema(example = "milling")]
    pub model: String,
    /// Cell size or slab length, mm.
    pub resolution: f64,
    /// Blank volume at the resolution, mm³.
    pub initial_volume: f64,
    /// Material left, mm³.
    pub volume: f64,
    /// Material removed, mm³.
    pub removed: f64,
    /// Checks raised since the blank was defined.
    pub warnings: u64,
    /// The latest of them.
    pub last_warning: Option<StockWarningInfo>,
    /// Grows with every cut that removed material: fetch `GET .../stock/changes?since=` when
    /// it differs from the version shown.
    pub version: u32,
    /// Where the stock's frame lies in the machine's Cartesian frame now, as the rows of
    /// `[R | t]` (`machine = R·p + t`, mm): the pose of the rotary table carrying the blank,
    /// so the mesh (given in the stock's frame) turns with C and tilts with A/B on screen.
    /// `null` where the blank does not move (a 3-axis mill, a lathe).
    pub frame: Option<[[f64; 4]; 3]>,
}

impl From<&StockInfo> for StockSummary {
    fn from(s: &StockInfo) -> StockSummary {
        StockSummary {
            model: if s.turning { "turning" } else { "milling" }.into(),
            resolution: s.resolution,
            initial_volume: s.initial_volume,
            volume: s.volume,
            removed: s.removed,
            warnings: s.warnings,
            last_warning: s.last_warning.as_ref().map(StockWarningInfo::from),
            version: s.version,
            frame: s.frame,
        }
    }
}

/// The stock and its settings.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct StockReport {
    /// The stock; `null` without a blank.
    pub stock: Option<StockSummary>,
    /// The latest checks raised (at most 64), oldest first.
    pub warnings: Vec<StockWarningInfo>,
    /// IPO cycles not cut because a transformation was active (not modelled yet).
    pub skipped_cycles: u64,
    /// Resolution of the next blank, mm.
    pub resolution: f64,
    /// Depth-of-cut limit, mm; `null`: none.
    pub depth_limit: Option<f64>,
    /// The holder checked for collisions: `[diameter, length]` sections from the tool's gauge
    /// line up, mm; empty: no holder check.
    pub holder: Vec<[f64; 2]>,
}

/// A blank in the WCS, as `WORKPIECE(..)` describes it.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BlankSpec {
    /// `box` (needs `x` and `y`), `cylinder` (`diameter`), `tube` (`diameter`,
    /// `inner_diameter`) or `polygon` (`edges`, `across_flats`).
    #[schema(example = "box")]
    pub shape: String,
    /// Top and bottom Z in the WCS.
    #[schema(example = 0.0)]
    pub top: f64,
    #[schema(example = -20.0)]
    pub bottom: f64,
    /// Box: X and Y from / to.
    #[serde(default)]
    pub x: Option<[f64; 2]>,
    #[serde(default)]
    pub y: Option<[f64; 2]>,
    #[serde(default)]
    pub diameter: Option<f64>,
    #[serde(default)]
    pub inner_diameter: Option<f64>,
    #[serde(default)]
    pub edges: Option<u32>,
    #[serde(default)]
    pub across_flats: Option<f64>,
}

impl BlankSpec {
    fn blank(&self) -> Result<Blank, String> {
        let need = |v: Option<f64>, name: &str| v.ok_or_else(|| format!("blank `{}` needs `{name}`", self.shape));
        let shape = match self.shape.as_str() {
            "box" => {
                let x = self.x.ok_or("blank `box` needs `x`")?;
                let y = self.y.ok_or("blank `box` needs `y`")?;
                Shape::Box { x: [x[0].min(x[1]), x[0].max(x[1])], y: [y[0].min(y[1]), y[0].max(y[1])] }
            }
            "cylinder" => Shape::Cylinder { diameter: need(self.diameter, "diameter")? },
            "tube" => Shape::Tube {
                outer: need(self.diameter, "diameter")?,
                inner: need(self.inner_diameter, "inner_diameter")?,
            },
            "polygon" => {
                let edges = self.edges.filter(|n| (3..=64).contains(n)).ok_or("blank `polygon` needs `edges` 3..64")?;
                Shape::Polygon { edges, across_flats: need(self.across_flats, "across_flats")? }
            }
            other => return Err(format!("blank shape `{other}`: box, cylinder, tube or polygon")),
        };
        let values = [self.top, self.bottom]
            .into_iter()
            .chain(self.x.into_iter().flatten())
            .chain(self.y.into_iter().flatten())
            .chain(self.diameter)
            .chain(self.inner_diameter)
            .chain(self.across_flats);
        if values.into_iter().any(|v| !v.is_finite()) {
            return Err("blank dimensions must be finite numbers".into());
        }
        let blank = Blank { shape, top: self.top, bottom: self.bottom };
        blank.check()?;
        Ok(blank)
    }
}

/// What to change; absent fields keep their value.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StockChange {
    /// Resolution of the next blank, mm (at least 0.01; memory grows with its inverse square).
    #[serde(default)]
    pub resolution: Option<f64>,
    /// Depth-of-cut limit, mm; `0` removes the limit.
    #[serde(default)]
    pub depth_limit: Option<f64>,
    /// A new blank, placed in the WCS of the active frame (only while nothing moves).
    #[serde(default)]
    pub blank: Option<BlankSpec>,
    /// The holder for the collision check: 1 to 4 `[diameter, length]` sections from the
    /// tool's gauge line (the end its length is measured to) up, mm; `[]` removes it.
    #[serde(default)]
    pub holder: Option<Vec<[f64; 2]>>,
}

pub(super) fn report(ch: &mut nctwin_engine::Channel) -> StockReport {
    let info = ch.stock_info();
    let options = ch.stock_options();
    StockReport {
        stock: info.as_ref().map(StockSummary::from),
        warnings: ch.stock_warnings().iter().map(StockWarningInfo::from).collect(),
        skipped_cycles: info.map_or(0, |i| i.skipped),
        resolution: options.resolution,
        depth_limit: options.depth_limit,
        holder: options.holder.map(|h| h.sections().to_vec()).unwrap_or_default(),
    }
}

/// The stock's volumes, the checks raised and the settings.
#[utoipa::path(
    get,
    path = "/sessions/{id}/stock",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The stock (`stock: null` without a blank)", body = StockReport),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_stock(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<StockReport>, ApiError> {
    let session = find_session(&state, &id)?;
    let r = session.with_channel(report).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(r))
}

/// Sets the resolution and the depth-of-cut limit and defines a blank, all or nothing.
#[utoipa::path(
    put,
    path = "/sessions/{id}/stock",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = StockChange,
    responses(
        (status = 200, description = "The stock after the change", body = StockReport),
        (status = 400, description = "A resolution below 0.01 mm, a negative limit, a holder section without size, a blank without volume or too fine for the cell limit; nothing changed", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "A blank while axes move", body = ErrorBody),
    )
)]
pub async fn put_stock(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(change): ApiJson<StockChange>,
) -> Result<Json<StockReport>, ApiError> {
    let blank = change.blank.as_ref().map(BlankSpec::blank).transpose().map_err(ApiError::bad_request)?;
    let holder = match change.holder.as_deref() {
        None => None,
        Some([]) => Some(None),
        Some(sections) => Some(Some(Holder::new(sections).map_err(ApiError::bad_request)?)),
    };
    let session = find_session(&state, &id)?;
    let result = session
        .with_channel(move |ch| {
            let before = ch.stock_options();
            let options = StockOptions {
                resolution: change.resolution.unwrap_or(before.resolution),
                depth_limit: match change.depth_limit {
                    None => before.depth_limit,
                    Some(0.0) => None,
                    Some(d) => Some(d),
                },
                holder: holder.unwrap_or(before.holder),
            };
            ch.set_stock_options(options)?;
            if let Some(blank) = blank
                && let Err(e) = ch.define_stock(blank)
            {
                ch.set_stock_options(before)?;
                return Err(e);
            }
            Ok(report(ch))
        })
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(result?))
}

/// Removes the blank: no material removal until the next one.
#[utoipa::path(
    delete,
    path = "/sessions/{id}/stock",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "No blank any more", body = StockReport),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn delete_stock(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<StockReport>, ApiError> {
    let session = find_session(&state, &id)?;
    let r = session
        .with_channel(|ch| {
            ch.clear_stock();
            report(ch)
        })
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(r))
}

/// The stock as it is now, a binary STL in the BCS (mm).
#[utoipa::path(
    get,
    path = "/sessions/{id}/stock.stl",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "Binary STL of the stock", content_type = "model/stl", body = Vec<u8>),
        (status = 404, description = "No such session, or no blank defined", body = ErrorBody),
    )
)]
pub async fn get_stock_stl(State(state): State<AppState>, Path(id): Path<String>) -> Result<Response, ApiError> {
    let session = find_session(&state, &id)?;
    let stl = session.with_channel(|ch| ch.stock_stl()).await.map_err(|e| ApiError::from_session(&id, e))?;
    let stl =
        stl.ok_or_else(|| ApiError::NotFound(format!("session `{id}` has no blank (WORKPIECE or PUT .../stock)")))?;
    Ok(([(CONTENT_TYPE, "model/stl")], stl).into_response())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(json: serde_json::Value) -> Result<Blank, String> {
        serde_json::from_value::<BlankSpec>(json).unwrap().blank()
    }

    #[test]
    fn blanks_are_read_with_their_dimensions_or_refused_naming_the_missing_one() {
        let b = spec(serde_json::json!({"shape": "box", "top": 0, "bottom": -20, "x": [50, -10], "y": [-10, 40]}));
        assert_eq!(b.unwrap().shape, Shape::Box { x: [-10.0, 50.0], y: [-10.0, 40.0] });
        let e = spec(serde_json::json!({"shape": "tube", "top": 0, "bottom": -20, "diameter": 50})).unwrap_err();
        assert!(e.contains("inner_diameter"), "{e}");
        let e = spec(serde_json::json!({"shape": "cylinder", "top": 0, "bottom": 5, "diameter": 50})).unwrap_err();
        assert!(e.contains("below"), "{e}");
    }
}
