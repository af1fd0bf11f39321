//! Manual operation fields over real HTTP and WebSocket: the JOG `coordinates` taken from
//! SD42650 when absent, the orientation JOG `rotation` (SD42660), the REPOS target `repos` on
//! NC start, and the reference point approach with its `referencing` state and `wait`.

use crate::common;

use std::time::Duration;

use common::{Server, error_message, pos};
use futures_util::{SinkExt, StreamExt};
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

async fn jog_mode(server: &Server, id: &str) {
    let reply = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
}

/// A `mill5-head-ca` session with TRAORI kept after program end, the head at A30 C0 with the
/// tip at (0, 0, 50), in JOG mode; `md` adds setting data.
async fn head_at_a30(server: &Server, md: &str) -> String {
    let data = format!("$MC_RESET_MODE_MASK='H81'\n{md}");
    let created = server.post("/sessions", json!({"machine": "mill5-head-ca", "machine_data": data})).await;
    assert_eq!(created.status, StatusCode::CREATED, "{}", created.body);
    let id = created.body["id"].as_str().expect("id").to_string();
    let program = "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\nM30";
    let run =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(run.body["transformation"]["name"], "TRAORI", "{}", run.body);
    jog_mode(server, &id).await;
    id
}

#[tokio::test]
async fn rest_jog_takes_the_system_from_sd42650_and_the_rotation_from_the_request() {
    let server = Server::start().await;
    let id = head_at_a30(&server, "$SC_CART_JOG_MODE='H4'").await;
    let before = server.get(&format!("/sessions/{id}/state")).await.body;
    // No `coordinates`: SD42650 bit 2, the TCS. Z moves 10 along o = (0, −sin 30°, cos 30°).
    let body = json!({"axis": "Z", "direction": 1, "increment": 10.0, "pace": "fast", "wait": true});
    let moved = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(moved.status, StatusCode::OK, "{}", moved.body);
    let dy = pos(&moved.body, "machine", "Y") - pos(&before, "machine", "Y");
    let dz = pos(&moved.body, "machine", "Z") - pos(&before, "machine", "Z");
    assert!(close(dy, -5.0, 1e-9) && close(dz, 10.0 * 30f64.to_radians().cos(), 1e-9), "{dy} {dz}");
    // ORIEULER: A2 is the first Euler angle, a turn about Z: C0 → C10 with A30 kept (about X,
    // `AXES`, it would have been A40).
    let body =
        json!({"axis": "A2", "direction": 1, "increment": 10.0, "rotation": "ORIEULER", "pace": "fast", "wait": true});
    let turned = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(turned.status, StatusCode::OK, "{}", turned.body);
    assert!(close(pos(&turned.body, "machine", "C"), 10.0, 1e-6), "{}", turned.body);
    assert!(close(pos(&turned.body, "machine", "A"), 30.0, 1e-6), "{}", turned.body);
    // C2 of ORIEULER does not change the orientation vector: 400 naming it.
    let body = json!({"axis": "C2", "direction": 1, "increment": 1.0, "rotation": "ORIEULER"});
    let refused = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert!(error_message(&refused, StatusCode::BAD_REQUEST).contains("C2"));
    let body = json!({"axis": "A2", "direction": 1, "increment": 1.0, "rotation": "ORIFOO"});
    let bad = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert!(error_message(&bad, StatusCode::BAD_REQUEST).contains("rotation"));
}

#[tokio::test]
async fn a_websocket_jog_carries_rotation_and_falls_back_to_sd42650() {
    let server = Server::start().await;
    let id = head_at_a30(&server, "$SC_CART_JOG_MODE='H4'").await;
    let before = server.get(&format!("/sessions/{id}/state")).await.body;
    let (mut socket, _) =
        connect_async(server.ws_url(&format!("/sessions/{id}/stream?period_ms=20"))).await.expect("ws");
    let mut send = async |v: Value| socket.send(Message::Text(v.to_string().into())).await.expect("sent");
    send(json!({"type": "jog", "axis": "Z", "direction": 1, "increment": 10.0})).await;
    let moved = server
        .state_until(&id, "TCS JOG done", |s| {
            s["status"] == "idle" && pos(s, "machine", "Z") > pos(&before, "machine", "Z") + 1.0
        })
        .await;
    assert!(close(pos(&moved, "machine", "Y") - pos(&before, "machine", "Y"), -5.0, 1e-9), "{moved}");
    // ORIRPY: o = Ry(B2)·Rx(A2)·ez with A2 = 30, B2 = 0; B2 +20 turns about Y:
    // (sin 20°·cos 30°, −sin 30°, cos 20°·cos 30°) = (sin C·sin A, −cos C·sin A, cos A).
    send(json!({"type": "jog", "axis": "B2", "direction": 1, "increment": 20.0, "rotation": "ORIRPY"})).await;
    let turned =
        server.state_until(&id, "B2 done", |s| s["status"] == "idle" && pos(s, "machine", "C").abs() > 1.0).await;
    let (s20, c20) = 20f64.to_radians().sin_cos();
    let o = [s20 * 30f64.to_radians().cos(), -0.5, c20 * 30f64.to_radians().cos()];
    let a = o[2].acos().to_degrees();
    let c = o[0].atan2(-o[1]).to_degrees();
    assert!(close(pos(&turned, "machine", "A"), a, 1e-6) && close(pos(&turned, "machine", "C"), c, 1e-6), "{turned}");
    send(json!({"type": "jog", "axis": "B2", "direction": 1, "increment": 1.0, "rotation": "EULER"})).await;
    loop {
        let message = tokio::time::timeout(Duration::from_secs(20), socket.next()).await.expect("in time");
        let Some(Ok(Message::Text(text))) = message else { panic!("stream ended") };
        let v: Value = serde_json::from_str(&text).expect("JSON");
        if v["type"] == "error" {
            assert_eq!(v["status"], 400, "{v}");
            break;
        }
    }
}

/// Runs `G1 X100 F600` (10 mm/s) in real time, stops it past X5, jogs Y +10 and returns to
/// AUTO; the interruption X and the state's time.
async fn interrupted_line(server: &Server) -> (String, f64, f64) {
    let id = server.session("mill-3axis").await;
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F600\nM30"})).await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    server.state_until(&id, "X past 5", |s| pos(s, "machine", "X") > 5.0).await;
    server.post_empty(&format!("/sessions/{id}/stop")).await;
    let stands = server.state_until(&id, "standstill", |s| s["path_velocity"] == 0.0).await;
    let xi = pos(&stands, "machine", "X");
    jog_mode(server, &id).await;
    let body = json!({"axis": "Y", "direction": 1, "increment": 10.0, "pace": "fast", "wait": true});
    let jogged = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(jogged.body["repos_pending"], true, "{}", jogged.body);
    let auto = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "AUTO"})).await;
    assert_eq!(auto.status, StatusCode::OK);
    (id, xi, jogged.body["time"].as_f64().expect("time"))
}

#[tokio::test]
async fn nc_start_takes_the_repos_target_mode() {
    let server = Server::start().await;
    // RMB: back to the block start (0, 0) and the whole 100 mm again; RME: straight to the block
    // end (100, 0) and done. All at the block's F600 = 10 mm/s (ramps of 3 m/s² add ms).
    for (mode, return_to) in [("RMB", 0.0), ("RME", 100.0), ("RMI", f64::NAN)] {
        let (id, xi, t0) = interrupted_line(&server).await;
        let body = json!({"repos": mode, "pace": "fast", "wait": true});
        let done = server.post(&format!("/sessions/{id}/start"), body).await;
        assert_eq!(done.status, StatusCode::OK, "{}", done.body);
        assert_eq!(done.body["status"], "idle", "{}", done.body);
        assert_eq!((pos(&done.body, "machine", "X"), pos(&done.body, "machine", "Y")), (100.0, 0.0));
        let target = if return_to.is_nan() { xi } else { return_to };
        let expected = ((target - xi).hypot(10.0) + (100.0 - target)) / 10.0;
        let took = done.body["time"].as_f64().expect("time") - t0;
        assert!(took > expected - 0.01 && took < expected + 0.1, "{mode}: {took} s, expected {expected} s plus ramps");
    }
    let (id, _, _) = interrupted_line(&server).await;
    let bad = server.post(&format!("/sessions/{id}/start"), json!({"repos": "RMX"})).await;
    assert!(error_message(&bad, StatusCode::BAD_REQUEST).contains("repos"));
}

#[tokio::test]
async fn referencing_shows_its_phase_stops_on_nc_stop_and_waits_when_asked() {
    let server = Server::start().await;
    let md = "$MA_ENC_REFP_STATE[X]=0\n$MA_REFP_SET_POS[0,X]=100";
    let created = server.post("/sessions", json!({"machine": "mill-3axis", "machine_data": md})).await;
    let id = created.body["id"].as_str().expect("id").to_string();
    jog_mode(&server, &id).await;
    let started = server.post(&format!("/sessions/{id}/reference"), json!({"axis": "X"})).await;
    assert_eq!(started.status, StatusCode::OK, "{}", started.body);
    assert_eq!(started.body["referencing"], json!({"axis": "X", "phase": "cam"}));
    assert_eq!(started.body["status"], "running");
    server.state_until(&id, "X moving", |s| pos(s, "machine", "X") > 1.0).await;
    server.post_empty(&format!("/sessions/{id}/stop")).await;
    let stopped = server.state_until(&id, "aborted", |s| s["status"] == "idle").await;
    assert_eq!(stopped["referenced"]["X"], false);
    assert!(stopped.get("referencing").is_none(), "{stopped}");
    let body = json!({"axis": "X", "pace": "fast", "wait": true});
    let done = server.post(&format!("/sessions/{id}/reference"), body).await;
    assert_eq!(done.status, StatusCode::OK, "{}", done.body);
    assert_eq!(done.body["referenced"]["X"], true, "{}", done.body);
    assert_eq!(pos(&done.body, "machine", "X"), 100.0);
    assert!(done.body.get("referencing").is_none());
}

#[tokio::test]
async fn nc_start_takes_the_reposq_approach_with_disr() {
    let server = Server::start().await;
    let (id, xi, t0) = interrupted_line(&server).await;
    let missing = server.post(&format!("/sessions/{id}/start"), json!({"approach": "REPOSQ"})).await;
    assert!(error_message(&missing, StatusCode::BAD_REQUEST).contains("disr"));
    let negative = server.post(&format!("/sessions/{id}/start"), json!({"approach": "REPOSH", "disr": -1.0})).await;
    assert!(error_message(&negative, StatusCode::BAD_REQUEST).contains("disr"));
    // From (xi, 10) straight to the quarter circle's start (xi − 4, 4), then a quarter of a
    // circle of radius 4 (2π mm) into (xi, 0), then the rest of the block, all at 10 mm/s.
    let body = json!({"approach": "REPOSQ", "disr": 4.0, "pace": "fast", "wait": true});
    let done = server.post(&format!("/sessions/{id}/start"), body).await;
    assert_eq!(done.status, StatusCode::OK, "{}", done.body);
    assert_eq!((pos(&done.body, "machine", "X"), pos(&done.body, "machine", "Y")), (100.0, 0.0));
    let expected = (4f64.hypot(6.0) + 2.0 * std::f64::consts::PI + (100.0 - xi)) / 10.0;
    let took = done.body["time"].as_f64().expect("time") - t0;
    assert!(took > expected - 0.01 && took < expected + 0.1, "{took} s, expected {expected} s plus ramps");
}
