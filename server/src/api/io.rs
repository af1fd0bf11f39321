//! `GET/PUT /sessions/{id}/io`: the session's NCK inputs and outputs, digital (`$A_IN[n]`,
//! `$A_OUT[n]`, n = 1..40) and analog (`$A_INA[n]`, `$A_OUTA[n]`, n = 1..4); the counts are
//! the machine data's (MD10350/MD10360 bytes of 8 digital signals, MD10300/MD10310 analog
//! signals), the numbers here NCTwin's defaults. Programs and
//! synchronized actions read them and write the outputs; a client stands in for the machine's
//! wiring: it sets inputs (a part-present switch, a clamping signal, a gauge's voltage) and may
//! set digital outputs too, as a test bench would. Inputs act from the next IPO cycle on and
//! are logged with its count (the `inputs_changed` event), so a run replays exactly. The
//! checkpoint keeps the inputs; the outputs are off after a restart, as after power on.
//! The PLC data area programs read and write as `$A_DBB[n]`, `$A_DBW[n]`, `$A_DBD[n]`,
//! `$A_DBR[n]` (4096 bytes, big-endian words) is shown and set here too (`plc_data`), standing
//! in for the PLC; the checkpoint keeps it.

use axum::Json;
use axum::extract::{Path, State};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::find_session;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::state::AppState;

/// The digital I/O image: element 0 is signal 1 (`$A_IN[1]`, `$A_OUT[1]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct IoImage {
    /// `$A_IN[1..16]` by default (as many as MD10350 FASTIO_DIG_NUM_INPUTS configures: 8 per byte, up to 40).
    pub inputs: Vec<bool>,
    /// `$A_OUT[1..16]` by default (MD10360 FASTIO_DIG_NUM_OUTPUTS, 8 per byte, up to 40).
    pub outputs: Vec<bool>,
    /// `$A_INA[1..4]` (MD10300 FASTIO_ANA_NUM_INPUTS; `$A_OUTA`: MD10310).
    #[serde(default)]
    pub analog_inputs: Vec<f64>,
    /// `$A_OUTA[1..4]` (written by synchronized actions).
    #[serde(default)]
    pub analog_outputs: Vec<f64>,
    /// The PLC data area from byte 0 (`$A_DBB[0]`) up to its last non-zero byte (the rest of
    /// the 4096 bytes are 0).
    #[serde(default)]
    pub plc_data: Vec<u8>,
}

impl IoImage {
    fn of(ch: &nctwin_engine::Channel) -> IoImage {
        let (io, (analog_in, analog_out)) = (ch.digital_io(), ch.analog_io());
        let (ins, outs) = io.counts();
        IoImage {
            inputs: (1..=ins).map(|n| io.input(n).unwrap_or(false)).collect(),
            outputs: (1..=outs).map(|n| io.output(n).unwrap_or(false)).collect(),
            analog_inputs: analog_in.to_vec(),
            analog_outputs: analog_out.to_vec(),
            plc_data: ch.plc_data().to_vec(),
        }
    }
}

/// One analog input to set: its number (1..4) and value.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct AnalogSignal {
    #[schema(example = 1)]
    pub signal: u32,
    #[schema(example = 2.5)]
    pub value: f64,
}

/// One signal to set: its number (1..40) and level.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Signal {
    #[schema(example = 3)]
    pub signal: u32,
    pub value: bool,
}

/// Bytes to write into the PLC data area from byte `offset` on.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PlcBytes {
    #[schema(example = 10)]
    pub offset: u32,
    #[schema(example = json!([18, 52]))]
    pub bytes: Vec<u8>,
}

/// Signals to change; the others keep their level.
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct IoChange {
    #[serde(default)]
    pub inputs: Vec<Signal>,
    #[serde(default)]
    pub outputs: Vec<Signal>,
    #[serde(default)]
    pub analog_inputs: Vec<AnalogSignal>,
    /// PLC data to write (`$A_DBB[offset]`..).
    #[serde(default)]
    pub plc_data: Vec<PlcBytes>,
}

/// The digital inputs and outputs as the main run holds them.
#[utoipa::path(
    get,
    path = "/sessions/{id}/io",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    responses(
        (status = 200, description = "The I/O image", body = IoImage),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn get_io(State(state): State<AppState>, Path(id): Path<String>) -> Result<Json<IoImage>, ApiError> {
    let session = find_session(&state, &id)?;
    let io = session.with_channel(|ch| IoImage::of(ch)).await.map_err(|e| ApiError::from_session(&id, e))?;
    Ok(Json(io))
}

/// Sets digital inputs (and outputs) and analog inputs at once, in any mode and while a program
/// runs: a block that reads `$A_IN` after this sees the new level, a synchronized action the
/// next IPO cycle. All or nothing: a signal outside 1..16 (analog: 1..4, or a value that is not
/// finite; the counts the machine data configure) is a `400` naming the limit and changes
/// nothing.
#[utoipa::path(
    put,
    path = "/sessions/{id}/io",
    tag = "sessions",
    params(("id" = String, Path, description = "Session id")),
    request_body = IoChange,
    responses(
        (status = 200, description = "The I/O image after the change", body = IoImage),
        (status = 400, description = "A signal number outside 1..16 (analog 1..4, by default; the counts of MD10350/MD10360/MD10300), an analog value not finite or PLC data beyond the 4096 bytes; nothing changed", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
    )
)]
pub async fn put_io(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(change): ApiJson<IoChange>,
) -> Result<Json<IoImage>, ApiError> {
    let list = |s: &[Signal]| s.iter().map(|s| (s.signal as usize, s.value)).collect::<Vec<_>>();
    let (inputs, outputs) = (list(&change.inputs), list(&change.outputs));
    let analog: Vec<(usize, f64)> = change.analog_inputs.iter().map(|s| (s.signal as usize, s.value)).collect();
    // Checked before anything is set (the analog inputs in the channel, below).
    let area = nctwin_engine::interp::io::plc_data::PLC_DATA_BYTES;
    if let Some(w) = change.plc_data.iter().find(|w| w.offset as usize + w.bytes.len() > area) {
        return Err(ApiError::bad_request(format!(
            "PLC data: {} bytes from byte {} reach beyond the area of {area} bytes",
            w.bytes.len(),
            w.offset
        )));
    }
    let plc = change.plc_data;
    let session = find_session(&state, &id)?;
    let result = session
        .with_channel(move |ch| {
            // Checked before anything is set, so a bad analog input leaves the digital ones too.
            let count = ch.analog_io().0.len();
            if let Some((n, v)) = analog.iter().find(|(n, v)| !(1..=count).contains(n) || !v.is_finite()) {
                return Err(nctwin_engine::CommandError::Invalid(format!(
                    "analog input {n} = {v}: analog inputs are 1..{count} (MD10300 FASTIO_ANA_NUM_INPUTS) with finite values"
                )));
            }
            if !inputs.is_empty() || !outputs.is_empty() {
                ch.set_signals(&inputs, &outputs)?;
            }
            if !analog.is_empty() {
                ch.set_analog_inputs(&analog)?;
            }
            for w in &plc {
                ch.set_plc_data(w.offset as usize, &w.bytes)?;
            }
            Ok::<_, nctwin_engine::CommandError>(IoImage::of(ch))
        })
        .await
        .map_err(|e| ApiError::from_session(&id, e))?;
    let io = result.map_err(|e| ApiError::bad_request(e.to_string()))?;
    Ok(Json(io))
}
