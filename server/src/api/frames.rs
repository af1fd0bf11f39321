//! `GET /sessions/{id}/frames`: the active frame chain link by link (basic frames, settable
//! frame, programmable frame and the system frames) and its total, for the work-offset screen's
//! overview (`nctwin_engine::Channel::frame_chain`).

use axum::Json;
use axum::extract::{Path, State};
use serde::Serialize;
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// One link of the chain as frame data.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FrameLink {
    /// Its system variable: `$P_PARTFRAME`, `$P_SETFRAME`, `$P_EXTFRAME`, `$P_ACTBFRAME`
    /// (basic frames), `$P_IFRAME` (settable frame), `$P_TOOLFRAME`, `$P_WPFRAME`,
    /// `$P_TRAFRAME`, `$P_PFRAME` (programmable frame), `$P_CYCFRAME`; `$P_ACTFRAME` the total.
    #[schema(example = "$P_IFRAME")]
    pub name: String,
    /// Whether the link changes nothing.
    pub neutral: bool,
    /// Translation per channel axis (in `axes` order), mm or degrees.
    pub trans: Vec<f64>,
    /// Rotation about X, Y, Z in degrees (RPY or Euler angles as MD10600 says); `null` when
    /// the link is no rotation with scale and mirror.
    pub rot: Option<[f64; 3]>,
    /// Scale factor per channel axis.
    pub scale: Vec<f64>,
    /// Mirrored per channel axis.
    pub mirror: Vec<bool>,
}

/// The active frame chain from the BCS towards the WCS, then the total.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FrameChain {
    /// The channel axes the per-axis lists refer to.
    pub axes: Vec<String>,
    /// The links in chain order, the last one `$P_ACTFRAME` (the total).
    pub links: Vec<FrameLink>,
}

fn chain(ch: &nctwin_engine::Channel) -> FrameChain {
    let cfg = ch.config();
    let n = cfg.channel_axes.len();
    let axes = (0..n).map(|k| cfg.program_axis_name(k).to_string()).collect();
    let links = ch
        .frame_chain()
        .into_iter()
        .map(|l| match l.data {
            Some(d) => FrameLink {
                name: l.name.into(),
                neutral: d.is_neutral(),
                trans: d.trans,
                rot: Some(d.rot),
                scale: d.scale,
                mirror: d.mirror,
            },
            None => FrameLink {
                name: l.name.into(),
                neutral: false,
                trans: Vec::new(),
                rot: None,
                scale: Vec::new(),
                mirror: Vec::new(),
            },
        })
        .collect();
    FrameChain { axes, links }
}

/// The active frame chain: each link and the total.
#[utoipa::path(
    get,
    path = "/sessions/{id}/frames",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The links of the active frame chain and their total", body = FrameChain),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_frames(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<FrameChain>, ApiError> {
    let session = find_session(&state, &id)?;
    let r = session.with_channel(|ch| chain(ch)).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(r))
}
