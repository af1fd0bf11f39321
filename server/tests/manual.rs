//! Manual operation over REST and the WebSocket: INC and handwheel JOG, JOG in the WCS, REPOS,
//! block search, reference point state, and the dead-man JOG on the stream.

use crate::common;

use std::time::Duration;

use common::{Server, error_message, pos};
use futures_util::{SinkExt, StreamExt};
use nctwin_server::{AuthMode, Config};
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream, connect_async};

type Socket = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// Guards every read so a broken stream fails the test instead of hanging it.
const READ_GUARD: Duration = Duration::from_secs(20);

async fn jog_mode(server: &Server, id: &str) {
    let reply = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

// ---- REST ----

#[tokio::test]
async fn inc_jog_moves_by_md31090_steps_and_wcs_jog_follows_the_frame() {
    let server = Server::start().await;
    let reply = server
        .post("/sessions", json!({"machine": "mill-3axis", "machine_data": "$MA_JOG_INCR_WEIGHT[0,Z]=0.01"}))
        .await;
    let id = reply.body["id"].as_str().expect("id").to_string();
    jog_mode(&server, &id).await;
    // INC1000 on X: 1000 × 0.001 mm; INC100 on Z with a weight of 0.01 mm: 1 mm.
    let body = json!({"axis": "X", "direction": 1, "inc": 1000, "pace": "fast", "wait": true});
    let x = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(x.status, StatusCode::OK, "{}", x.body);
    assert_eq!(pos(&x.body, "machine", "X"), 1.0);
    let body = json!({"axis": "Z", "direction": -1, "inc": 100, "coordinates": "WCS", "pace": "fast", "wait": true});
    let z = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(z.status, StatusCode::OK, "{}", z.body);
    assert!(close(pos(&z.body, "machine", "Z"), -1.0, 1e-12));
    assert!(close(pos(&z.body, "workpiece", "Z"), -1.0, 1e-12));

    for (body, needle) in [
        (json!({"axis": "X", "direction": 1, "inc": 7}), "inc must be 1, 10, 100 or 1000"),
        (json!({"axis": "X", "direction": 1, "inc": 10, "increment": 2.0}), "not both"),
        (json!({"axis": "X", "direction": 1, "coordinates": "SZS"}), "coordinates"),
    ] {
        let reply = server.post(&format!("/sessions/{id}/jog"), body).await;
        let message = error_message(&reply, StatusCode::BAD_REQUEST);
        assert!(message.contains(needle), "{message}");
    }
}

#[tokio::test]
async fn handwheel_pulses_move_by_pulses_times_increment() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    jog_mode(&server, &id).await;
    let reply =
        server.post(&format!("/sessions/{id}/jog/handwheel"), json!({"axis": "Y", "pulses": -5, "inc": 100})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    // 5 detents × 100 steps × 0.001 mm backwards.
    let stands = server.state_until(&id, "Y at -0.5", |s| s["status"] == "idle").await;
    assert!(close(pos(&stands, "machine", "Y"), -0.5, 1e-12), "{stands}");
    for body in [json!({"axis": "Y", "pulses": 0}), json!({"axis": "Y", "pulses": 1, "inc": 3})] {
        let reply = server.post(&format!("/sessions/{id}/jog/handwheel"), body).await;
        error_message(&reply, StatusCode::BAD_REQUEST);
    }
    let unknown = server.post(&format!("/sessions/{id}/jog/handwheel"), json!({"axis": "Q", "pulses": 1})).await;
    assert!(error_message(&unknown, StatusCode::BAD_REQUEST).contains('Q'));
}

#[tokio::test]
async fn repos_after_jog_returns_to_the_interruption_point_and_finishes_the_program() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // 100 mm at 3000 mm/min: two seconds of real time.
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F3000\nM30"})).await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    server.state_until(&id, "X past 5", |s| pos(s, "machine", "X") > 5.0).await;
    let stop = server.post_empty(&format!("/sessions/{id}/stop")).await;
    assert_eq!(stop.body["status"], "stopped");
    let stands = server.state_until(&id, "standstill", |s| s["path_velocity"] == 0.0).await;
    let xi = pos(&stands, "machine", "X");
    assert!(xi > 5.0 && xi < 100.0, "{xi}");
    jog_mode(&server, &id).await;
    let body = json!({"axis": "Y", "direction": 1, "increment": 10.0, "pace": "fast", "wait": true});
    let jogged = server.post(&format!("/sessions/{id}/jog"), body).await;
    assert_eq!(jogged.status, StatusCode::OK, "{}", jogged.body);
    assert_eq!(jogged.body["status"], "stopped", "the program stays interrupted");
    assert_eq!(jogged.body["repos_pending"], true);
    assert_eq!((pos(&jogged.body, "machine", "X"), pos(&jogged.body, "machine", "Y")), (xi, 10.0));
    let mda = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "MDA"})).await;
    error_message(&mda, StatusCode::CONFLICT);
    let auto = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "AUTO"})).await;
    assert_eq!(auto.status, StatusCode::OK, "{}", auto.body);
    let done = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(done.status, StatusCode::OK, "{}", done.body);
    assert_eq!(done.body["status"], "idle");
    assert_eq!((pos(&done.body, "machine", "X"), pos(&done.body, "machine", "Y")), (100.0, 0.0));
}

#[tokio::test]
async fn block_search_stops_at_the_target_and_start_approaches_and_continues() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "G0 X0 Y0\nG1 X10 F1000\nG1 Y20\nX30 Y25\nM30";
    let search = server.post(&format!("/sessions/{id}/search"), json!({"line": 4, "program": program})).await;
    assert_eq!(search.status, StatusCode::OK, "{}", search.body);
    assert_eq!(search.body["status"], "stopped");
    assert_eq!(search.body["block"], json!({"line": 4, "text": "X30 Y25", "program": null}));
    assert_eq!(pos(&search.body, "machine", "X"), 0.0);
    let done = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(done.body["status"], "idle", "{}", done.body);
    assert_eq!((pos(&done.body, "machine", "X"), pos(&done.body, "machine", "Y")), (30.0, 25.0));
    // The approach (0,0)→(10,20) is √500 mm and the block √425 mm, both at F1000.
    let expected = (500f64.sqrt() + 425f64.sqrt()) / (1000.0 / 60.0);
    let time = done.body["time"].as_f64().expect("time") - search.body["time"].as_f64().expect("time");
    assert!(time > expected && time < expected + 0.5, "{time} s, expected {expected} s plus ramps");

    // Again in the active program, and in a stored one.
    let again = server.post(&format!("/sessions/{id}/search"), json!({"line": 3})).await;
    assert_eq!(again.body["block"]["line"], 3, "{}", again.body);
    server.post_empty(&format!("/sessions/{id}/reset")).await;
    let stored = server.put(&format!("/sessions/{id}/programs/PART1"), json!({"text": program})).await;
    assert_eq!(stored.status, StatusCode::OK, "{}", stored.body);
    let named = server.post(&format!("/sessions/{id}/search"), json!({"line": 2, "name": "PART1"})).await;
    assert_eq!(named.body["block"], json!({"line": 2, "text": "G1 X10 F1000", "program": null}), "{}", named.body);
    server.post_empty(&format!("/sessions/{id}/reset")).await;

    let missing = server.post(&format!("/sessions/{id}/search"), json!({"line": 99})).await;
    let message = error_message(&missing, StatusCode::BAD_REQUEST);
    assert!(message.contains("line 99 does not exist"), "{message}");
    let both =
        server.post(&format!("/sessions/{id}/search"), json!({"line": 1, "name": "PART1", "program": "M30"})).await;
    error_message(&both, StatusCode::BAD_REQUEST);
    let unknown = server.post(&format!("/sessions/{id}/search"), json!({"line": 1, "name": "NOPE"})).await;
    assert!(error_message(&unknown, StatusCode::BAD_REQUEST).contains("NOPE"));
    let after_end = server.post(&format!("/sessions/{id}/search"), json!({"line": 2, "program": "M30\nG0 X1"})).await;
    assert_eq!(after_end.body["status"], "alarm", "{}", after_end.body);
    assert_eq!(after_end.body["alarms"][0]["number"], 15370);
    server.post_empty(&format!("/sessions/{id}/reset")).await;
    jog_mode(&server, &id).await;
    let in_jog = server.post(&format!("/sessions/{id}/search"), json!({"line": 1})).await;
    error_message(&in_jog, StatusCode::CONFLICT);
}

#[tokio::test]
async fn unreferenced_axes_refuse_nc_start_until_referenced() {
    let server = Server::start().await;
    let created =
        server.post("/sessions", json!({"machine": "mill-3axis", "machine_data": "$MA_ENC_REFP_STATE[Z]=0"})).await;
    assert_eq!(created.body["state"]["referenced"], json!({"X": true, "Y": true, "Z": false}));
    let id = created.body["id"].as_str().expect("id").to_string();
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": "G0 X1\nM30", "wait": true})).await;
    assert!(error_message(&run, StatusCode::CONFLICT).contains("16905"));
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["alarms"][0]["number"], 16905);
    assert_eq!(pos(&state, "machine", "X"), 0.0);
    let in_auto = server.post(&format!("/sessions/{id}/reference"), json!({"axis": "Z"})).await;
    error_message(&in_auto, StatusCode::CONFLICT);
    jog_mode(&server, &id).await;
    let unknown = server.post(&format!("/sessions/{id}/reference"), json!({"axis": "Q"})).await;
    error_message(&unknown, StatusCode::BAD_REQUEST);
    // Z has an incremental encoder (MD34200 = 1): the approach runs to its end with `wait`.
    let referenced = server.post(&format!("/sessions/{id}/reference"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(referenced.status, StatusCode::OK, "{}", referenced.body);
    assert_eq!(referenced.body["referenced"], json!({"X": true, "Y": true, "Z": true}));
    server.post_empty(&format!("/sessions/{id}/cancel")).await;
    let run = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X1\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    assert_eq!(pos(&run.body, "machine", "X"), 1.0);
}

// ---- WebSocket dead-man JOG ----

async fn connect(server: &Server, path: &str) -> Socket {
    let (socket, _) = connect_async(server.ws_url(path)).await.expect("WebSocket handshake");
    socket
}

async fn send(socket: &mut Socket, message: Value) {
    socket.send(Message::Text(message.to_string().into())).await.expect("sent");
}

/// The next message of `type` (skipping others); `None` when the stream closed.
async fn next_of(socket: &mut Socket, kind: &str) -> Option<Value> {
    loop {
        let message = tokio::time::timeout(READ_GUARD, socket.next()).await.expect("a message in time");
        match message {
            None | Some(Err(_)) | Some(Ok(Message::Close(_))) => return None,
            Some(Ok(Message::Text(text))) => {
                let v: Value = serde_json::from_str(&text).expect("JSON");
                if v["type"] == kind {
                    return Some(v);
                }
            }
            Some(Ok(_)) => {}
        }
    }
}

async fn jog_socket(server: &Server) -> (String, Socket) {
    let id = server.session("mill-3axis").await;
    jog_mode(server, &id).await;
    let mut socket = connect(server, &format!("/sessions/{id}/stream?period_ms=20")).await;
    next_of(&mut socket, "state").await.expect("first state");
    (id, socket)
}

#[tokio::test]
async fn a_websocket_jog_stops_when_its_client_disconnects() {
    let server = Server::start().await;
    let (id, mut socket) = jog_socket(&server).await;
    send(&mut socket, json!({"type": "jog", "axis": "X", "direction": 1})).await;
    assert_eq!(next_of(&mut socket, "ack").await.expect("ack")["request"], "jog");
    server.state_until(&id, "X moving", |s| pos(s, "machine", "X") > 0.0).await;
    drop(socket);
    let stands = server.state_until(&id, "stopped after the disconnect", |s| s["status"] == "idle").await;
    let x = pos(&stands, "machine", "X");
    // Far from the software limit at 500 mm: the disconnect stopped it, not the limit.
    assert!(x > 0.0 && x < 400.0, "X = {x}");
    assert_eq!(stands["alarms"], json!([]));
}

#[tokio::test]
async fn a_websocket_jog_without_keepalives_stops_after_the_dead_man_time() {
    let server = Server::start().await;
    let (id, mut socket) = jog_socket(&server).await;
    send(&mut socket, json!({"type": "jog", "axis": "Y", "direction": -1})).await;
    next_of(&mut socket, "ack").await.expect("ack");
    let error = next_of(&mut socket, "error").await.expect("the dead-man stop is reported");
    assert_eq!((error["request"].as_str(), error["status"].as_u64()), (Some("jog"), Some(408)), "{error}");
    let stands = server.state_until(&id, "stopped by the dead man", |s| s["status"] == "idle").await;
    let y = pos(&stands, "machine", "Y");
    assert!(y < 0.0 && y > -250.0, "Y = {y}");
    // The socket stays usable: a new press starts a new motion.
    send(&mut socket, json!({"type": "jog", "axis": "Y", "direction": 1, "inc": 1000})).await;
    assert_eq!(next_of(&mut socket, "ack").await.expect("ack")["request"], "jog");
    let after = server.state_until(&id, "INC1000 done", |s| s["status"] == "idle" && pos(s, "machine", "Y") > y).await;
    assert!(close(pos(&after, "machine", "Y"), y + 1.0, 1e-9));
}

#[tokio::test]
async fn keepalives_hold_a_websocket_jog_until_jog_stop() {
    let server = Server::start().await;
    let (id, mut socket) = jog_socket(&server).await;
    send(&mut socket, json!({"type": "jog", "axis": "X", "direction": 1})).await;
    next_of(&mut socket, "ack").await.expect("ack");
    // Keep-alives every 50 ms for 1.5 s (the dead man allows 400 ms between two).
    for i in 0..30 {
        tokio::time::sleep(Duration::from_millis(50)).await;
        let keepalive = if i % 2 == 0 {
            json!({"type": "jog_keepalive"})
        } else {
            json!({"type": "jog", "axis": "X", "direction": 1})
        };
        send(&mut socket, keepalive).await;
    }
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["status"], "running", "still moving: {state}");
    // JOG_VELO 2000 mm/min: well beyond the 13.3 mm one dead-man time would allow.
    assert!(pos(&state, "machine", "X") > 20.0, "{state}");
    let other = json!({"type": "jog", "axis": "Y", "direction": 1});
    send(&mut socket, other).await;
    assert_eq!(next_of(&mut socket, "error").await.expect("refused")["status"], 409);
    send(&mut socket, json!({"type": "jog_stop"})).await;
    assert_eq!(next_of(&mut socket, "ack").await.expect("ack")["request"], "jog_stop");
    let stands = server.state_until(&id, "released", |s| s["status"] == "idle").await;
    assert_eq!(stands["alarms"], json!([]));
}

#[tokio::test]
async fn bad_client_messages_are_answered_with_an_error() {
    let server = Server::start().await;
    let (_, mut socket) = jog_socket(&server).await;
    send(&mut socket, json!({"type": "fly"})).await;
    assert_eq!(next_of(&mut socket, "error").await.expect("error")["status"], 400);
    send(&mut socket, json!({"type": "jog", "axis": "X", "direction": 1, "inc": 3})).await;
    let error = next_of(&mut socket, "error").await.expect("error");
    assert!(error["error"].as_str().unwrap_or("").contains("inc must be"), "{error}");
    send(&mut socket, json!({"type": "handwheel", "axis": "X", "pulses": 4, "inc": 10})).await;
    assert_eq!(next_of(&mut socket, "ack").await.expect("ack")["request"], "handwheel");
}

#[tokio::test]
async fn observers_and_operators_without_control_cannot_jog_over_the_websocket() {
    let server = Server::start_config(Config {
        auth: AuthMode::Required,
        ..Config::new(common::temp_data_dir(), common::WEB_DIR)
    })
    .await;
    let created = server.post_empty("/sessions").await;
    let id = created.body["id"].as_str().expect("id").to_string();
    let token = |role: &str| created.body["tokens"][role].as_str().expect("token").to_string();
    let mode = server.client.put(server.url(&format!("/sessions/{id}/mode"))).bearer_auth(token("owner"));
    assert_eq!(server.send(mode.json(&json!({"mode": "JOG"}))).await.status, StatusCode::OK);
    for (role, status) in [("observer", 403), ("operator", 409)] {
        let mut socket = connect(&server, &format!("/sessions/{id}/stream?token={}", token(role))).await;
        send(&mut socket, json!({"type": "jog", "axis": "X", "direction": 1})).await;
        let error = next_of(&mut socket, "error").await.expect("refused");
        assert_eq!(error["status"], status, "{role}: {error}");
    }
    let mut owner = connect(&server, &format!("/sessions/{id}/stream?token={}", token("owner"))).await;
    send(&mut owner, json!({"type": "jog", "axis": "X", "direction": 1, "inc": 10})).await;
    assert_eq!(next_of(&mut owner, "ack").await.expect("the owner holds control")["request"], "jog");
}
