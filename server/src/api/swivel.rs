//! The swivel of the HMI: CYCLE800 with named parameters, run as an MDA block.

use axum::extract::{Path, State};
use nctwin_engine::Mode;

use super::{StateReply, command, find_session};
use crate::dto::{self, ErrorBody, SwivelMode, SwivelRequest, drive};
use crate::error::ApiError;
use crate::extract::ApiJson;
use crate::session::Action;
use crate::state::AppState;

/// The CYCLE800 block for `r`, or the reason the parameters do not fit together.
pub fn cycle800(r: &SwivelRequest) -> Result<String, String> {
    let data_set = r.data_set.clone().unwrap_or_default();
    if data_set.len() > 32 || !data_set.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err("data_set: at most 32 letters, digits or `_`".into());
    }
    if data_set == "0" {
        return Ok("CYCLE800(0,\"0\")".into());
    }
    if ![0, 1, 2, 4, 5].contains(&r.retract) {
        return Err(format!("retract {} (0, 1, 2, 4 or 5)", r.retract));
    }
    if r.retract_distance < 0.0 {
        return Err(format!("retract_distance {} must not be negative", r.retract_distance));
    }
    if r.retract != 5 && r.retract_distance != 0.0 {
        return Err("retract_distance needs retract 5".into());
    }
    if !(-1..=1).contains(&r.direction) {
        return Err(format!("direction {} (-1, 0 or 1)", r.direction));
    }
    let numbers = [r.x0, r.y0, r.z0, r.a, r.b, r.c, r.x1, r.y1, r.z1, r.retract_distance];
    if numbers.iter().any(|v| !v.is_finite() || v.abs() > 1e6) {
        return Err("coordinates and angles must be finite and within ±1e6".into());
    }
    let sequence = r.sequence.to_ascii_uppercase();
    let axes: Vec<u32> = sequence
        .chars()
        .map(|c| match c {
            'X' => Ok(1),
            'Y' => Ok(2),
            'Z' => Ok(3),
            other => Err(format!("sequence: {other} is not X, Y or Z")),
        })
        .collect::<Result<_, _>>()?;
    let permutation = axes.len() == 3 && axes[0] != axes[1] && axes[1] != axes[2] && axes[0] != axes[2];
    let sequence_bits = || -> Result<u32, String> {
        if !permutation {
            return Err(format!("sequence {sequence}: a permutation of XYZ"));
        }
        Ok(axes[0] | axes[1] << 2 | axes[2] << 4)
    };
    let mode = match r.mode {
        SwivelMode::AxisByAxis => sequence_bits()?,
        SwivelMode::SolidAngle => 64,
        SwivelMode::ProjectionAngle => 128 + sequence_bits()?,
        SwivelMode::Direct => 192,
    };
    let st = u32::from(r.additive) + 10 * u32::from(r.tracking);
    let n = |v: f64| format!("{v:?}");
    Ok(format!(
        "CYCLE800({},\"{data_set}\",{st},{mode},{},{},{},{},{},{},{},{},{},{},{},1)",
        r.retract,
        n(r.x0),
        n(r.y0),
        n(r.z0),
        n(r.a),
        n(r.b),
        n(r.c),
        n(r.x1),
        n(r.y1),
        n(r.z1),
        r.direction,
        n(r.retract_distance),
    ))
}

/// Swivels the working plane (CYCLE800) in JOG or MDA, as the HMI's swivel function does: the
/// parameters become one MDA block `CYCLE800(...)`. A swivel from JOG with `wait: true` returns
/// to JOG when it ended, also with an alarm (which stays, naming the reason). Parameters that do not fit together are `400`;
/// those the kinematics cannot reach give the cycle's alarm (61184 ...) without motion.
#[utoipa::path(
    post,
    path = "/sessions/{id}/swivel",
    tag = "program",
    params(("id" = String, Path, description = "Session id")),
    request_body = SwivelRequest,
    responses(
        (status = 200, description = "The state after the start, or at the end of the wait", body = dto::State,
            headers(("nctwin-limit" = String, description = "`fast-sim-time`, `fast-wall-time` or `wait-wall-time` when a server-side limit ended the command or its wait"))),
        (status = 400, description = "Parameters that do not fit together, or a malformed body", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 409, description = "A program is active or an alarm needs a reset", body = ErrorBody),
    )
)]
pub async fn swivel(
    State(state): State<AppState>,
    Path(id): Path<String>,
    ApiJson(body): ApiJson<SwivelRequest>,
) -> Result<StateReply, ApiError> {
    let program = cycle800(&body).map_err(ApiError::bad_request)?;
    let from_jog = find_session(&state, &id)?.snapshot().mode == Mode::Jog;
    let reply = command(&state, &id, Action::Mda { program }, Some(drive(body.pace, body.wait))).await?;
    let snapshot = &reply.0.snapshot;
    // Ended, with or without an alarm (a stopped or still running cycle stays in MDA): back to
    // JOG, where the swivel was asked for. An alarm stays displayed: it says why it failed.
    let ended = matches!(snapshot.status, nctwin_engine::Status::Idle | nctwin_engine::Status::Alarm);
    if from_jog && body.wait && ended && snapshot.mode != Mode::Jog {
        return command(&state, &id, Action::SetMode(Mode::Jog), None).await;
    }
    Ok(reply)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(json: serde_json::Value) -> SwivelRequest {
        serde_json::from_value(json).unwrap()
    }

    #[test]
    fn the_named_parameters_become_the_cycle_call() {
        let r = request(
            serde_json::json!({"data_set": "HEAD_CA", "mode": "axis_by_axis", "sequence": "ZYX", "a": 30, "direction": -1}),
        );
        assert_eq!(cycle800(&r).unwrap(), "CYCLE800(0,\"HEAD_CA\",0,27,0.0,0.0,0.0,30.0,0.0,0.0,0.0,0.0,0.0,-1,0.0,1)");
        let r = request(serde_json::json!({"mode": "projection_angle", "additive": true, "tracking": true}));
        assert!(cycle800(&r).unwrap().starts_with("CYCLE800(0,\"\",11,185,"));
    }

    #[test]
    fn parameters_that_do_not_fit_are_refused() {
        for (json, needle) in [
            (serde_json::json!({"mode": "axis_by_axis", "sequence": "XXZ"}), "permutation"),
            (serde_json::json!({"mode": "direct", "retract": 3}), "retract 3"),
            (serde_json::json!({"mode": "direct", "retract": 5, "retract_distance": -1}), "negative"),
            (serde_json::json!({"mode": "direct", "retract_distance": 4}), "needs retract 5"),
            (serde_json::json!({"mode": "direct", "direction": 2}), "direction"),
            (serde_json::json!({"mode": "direct", "data_set": "A\")M30"}), "data_set"),
        ] {
            let e = cycle800(&request(json.clone())).unwrap_err();
            assert!(e.contains(needle), "{json}: {e}");
        }
    }
}
