//! `GET /sessions/{id}/active-swivel`: the active swivel as the HMI shows it beside T, F, S
//! (data set, rotary axis angles, the swivelled plane) and the WCS directions its 3D view turns
//! the coordinate triad with (`nctwin_engine::Channel::active_swivel`).

use axum::Json;
use axum::extract::{Path, State};
use serde::Serialize;
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// The active swivel of the channel.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ActiveSwivel {
    /// The active toolholder (swivel) data set, `$P_TCNUM`; 0 when none is active.
    pub data_set: u32,
    /// Its `$TC_CARR34` name; empty without one.
    #[schema(example = "HEAD_BC")]
    pub name: String,
    /// Positions of the data set's rotary axes 1 and 2 in degrees (`$P_TCANG[1]`, `[2]`).
    pub axis_angles: [f64; 2],
    /// The swivelled plane (`$P_TOOLFRAME`): rotation about X, Y, Z in degrees (RPY or Euler
    /// angles as MD10600 says); zeros when the plane is not turned.
    pub plane: [f64; 3],
    /// Unit directions of the WCS X, Y and Z axes in the BCS through the whole frame chain.
    pub wcs_axes: [[f64; 3]; 3],
}

impl From<nctwin_engine::interp::ActiveSwivel> for ActiveSwivel {
    fn from(s: nctwin_engine::interp::ActiveSwivel) -> Self {
        ActiveSwivel {
            data_set: s.data_set,
            name: s.name,
            axis_angles: s.axis_angles,
            plane: s.plane,
            wcs_axes: s.wcs_axes,
        }
    }
}

/// The active swivel: data set, axis angles, plane, WCS directions.
#[utoipa::path(
    get,
    path = "/sessions/{id}/active-swivel",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The active swivel (data set 0: none)", body = ActiveSwivel),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_active_swivel(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<ActiveSwivel>, ApiError> {
    let session = find_session(&state, &id)?;
    let s = session.with_channel(|ch| ch.active_swivel()).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(s.into()))
}
