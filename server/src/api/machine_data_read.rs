//! Read-only views of NC data for the HMI's machine-data and tool-table screens:
//! `GET /sessions/{id}/machine-data` (a session's NC data as text) and
//! `GET /machine-data/definitions` (the registry of every datum with its number and range).
//! Changes go through `PUT /sessions/{id}/machine-data` (`machine_data.rs`).

use axum::Json;
use axum::extract::{Path, State};
use nctwin_engine::machine_data::Value;
use nctwin_engine::machine_data::registry::{self, Kind, Scope};
use serde::Serialize;
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::state::AppState;

/// A session's NC data as text in the control's syntax.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct MachineDataText {
    /// Machine data, tool data (`$TC_DP`) and settable frames (`$P_UIFR`) that differ from the
    /// defaults, one assignment per line; `PUT .../machine-data` with this text changes nothing.
    #[schema(example = "$MN_AXCONF_MACHAX_NAME_TAB[0]=\"X1\"\n$TC_DP1[1,1]=120\n")]
    pub text: String,
}

/// One datum of the registry.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct MachineDatumDef {
    /// Full name with prefix, as written in NC data text (`$MA_MAX_AX_VELO`).
    pub name: String,
    /// Machine data number as in the Siemens lists (0 for data without one).
    pub number: u32,
    /// `nck` (`$MN_`/`$SN_`), `channel` (`$MC_`/`$SC_`) or `axis` (`$MA_`/`$SA_`, indexed by axis).
    pub scope: String,
    /// `bool`, `int`, `real` or `string`.
    pub kind: String,
    /// Number of array elements; 1 for a scalar.
    pub len: usize,
    /// The default of each element (of a linear axis, for axial data) in NC data syntax.
    pub defaults: Vec<String>,
    /// Smallest valid value of a number datum, when bounded.
    pub min: Option<f64>,
    /// Largest valid value of a number datum, when bounded.
    pub max: Option<f64>,
}

/// A session's NC data (machine data, tool data, settable frames) as text in the control's
/// syntax: what differs from the defaults, one assignment per line.
#[utoipa::path(
    get,
    path = "/sessions/{id}/machine-data",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The session's NC data text", body = MachineDataText),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_machine_data(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<MachineDataText>, ApiError> {
    let session = find_session(&state, &id)?;
    let text =
        session.with_channel(|ch| ch.machine_data().to_text()).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(MachineDataText { text }))
}

/// Every machine and setting datum the server knows, with number, scope, type, array size,
/// default and valid range.
#[utoipa::path(
    get,
    path = "/machine-data/definitions",
    tag = "machines",
    responses((status = 200, description = "The registry, in its order", body = Vec<MachineDatumDef>))
)]
pub async fn list_definitions() -> Json<Vec<MachineDatumDef>> {
    let numeric = |k: Kind| matches!(k, Kind::Int | Kind::Real);
    Json(
        registry::DEFS
            .iter()
            .map(|d| MachineDatumDef {
                name: d.full_name(),
                number: d.number,
                scope: match d.scope {
                    Scope::Nck => "nck",
                    Scope::Channel => "channel",
                    Scope::Axis => "axis",
                }
                .into(),
                kind: match d.kind {
                    Kind::Bool => "bool",
                    Kind::Int => "int",
                    Kind::Real => "real",
                    Kind::Str => "string",
                }
                .into(),
                len: d.len,
                defaults: (0..d.len).map(|i| literal(&d.default_value(i, false))).collect(),
                min: (numeric(d.kind) && d.min.is_finite()).then_some(d.min),
                max: (numeric(d.kind) && d.max.is_finite()).then_some(d.max),
            })
            .collect(),
    )
}

/// A value as NC data text writes it.
fn literal(value: &Value) -> String {
    match value {
        Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.into(),
        Value::Int(i) => i.to_string(),
        Value::Real(r) => format!("{r:?}"),
        Value::Str(s) => format!("\"{s}\""),
    }
}
