//! The WebSocket stream over a real socket on port 0.

use crate::common;

use std::time::Duration;

use common::{Server, pos};
use futures_util::StreamExt;
use serde_json::{Value, json};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream, connect_async};

type Socket = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// Guards every read so a broken stream fails the test instead of hanging it.
const READ_GUARD: Duration = Duration::from_secs(20);

async fn connect(server: &Server, path: &str) -> Socket {
    let (socket, _) = connect_async(server.ws_url(path)).await.expect("WebSocket handshake");
    socket
}

/// The next text message as JSON; `None` when the server closed the stream.
async fn next_json(socket: &mut Socket) -> Option<Value> {
    loop {
        let message = tokio::time::timeout(READ_GUARD, socket.next()).await.expect("a message in time");
        match message {
            None | Some(Err(_)) | Some(Ok(Message::Close(_))) => return None,
            Some(Ok(Message::Text(text))) => return Some(serde_json::from_str(&text).expect("JSON message")),
            Some(Ok(_)) => {}
        }
    }
}

#[tokio::test]
async fn the_stream_sends_the_state_at_once_and_positions_change_during_a_realtime_run() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut socket = connect(&server, &format!("/sessions/{id}/stream")).await;

    let first = next_json(&mut socket).await.expect("first message");
    assert_eq!(first["type"], "state");
    assert_eq!(first["status"], "idle");
    assert_eq!(pos(&first, "machine", "X"), 0.0);

    // 50 mm at 3000 mm/min: about one second in real time.
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X50 F3000\nM30"})).await;
    assert_eq!(run.body["status"], "running");

    let mut xs = Vec::new();
    let mut events = Vec::new();
    while let Some(message) = next_json(&mut socket).await {
        match message["type"].as_str() {
            Some("state") => {
                xs.push(pos(&message, "machine", "X"));
                if message["status"] == "idle" {
                    break;
                }
            }
            Some("event") => events.push(message),
            other => panic!("unknown message type {other:?}: {message}"),
        }
    }
    assert!(xs.iter().any(|&x| x > 0.0 && x < 50.0), "an intermediate position was streamed: {xs:?}");
    assert_eq!(xs.last().copied(), Some(50.0));
    assert!(xs.windows(2).all(|w| w[0] <= w[1]), "X only grows: {xs:?}");
    assert!(
        events.iter().any(|e| e["event"] == "block_changed" && e["line"] == 1 && e["text"] == "G1 X50 F3000"),
        "{events:?}"
    );
}

#[tokio::test]
async fn events_are_streamed_as_they_happen() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut socket = connect(&server, &format!("/sessions/{id}/stream?period_ms=10")).await;
    assert_eq!(next_json(&mut socket).await.expect("state")["type"], "state");

    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X700\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.body["status"], "alarm");
    server.post_empty(&format!("/sessions/{id}/reset")).await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;

    let mut seen = Vec::new();
    while let Some(message) = next_json(&mut socket).await {
        if message["type"] == "event" {
            let done = message["event"] == "mode_changed";
            seen.push(message);
            if done {
                break;
            }
        }
    }
    let raised = seen.iter().find(|e| e["event"] == "alarm_raised").expect("alarm_raised");
    assert_eq!(raised["alarm"]["number"], 10720);
    assert!(seen.iter().any(|e| e["event"] == "alarm_cleared" && e["number"] == 10720), "{seen:?}");
    assert_eq!(seen.last().expect("mode event")["mode"], "JOG");
}

#[tokio::test]
async fn the_stream_reports_program_stop_and_end() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut socket = connect(&server, &format!("/sessions/{id}/stream")).await;
    next_json(&mut socket).await.expect("state");
    let body = json!({"program": "G1 X1 F1000\nM0\nM30", "pace": "fast", "wait": true});
    server.post(&format!("/sessions/{id}/run"), body).await;
    server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    let mut seen = Vec::new();
    while let Some(message) = next_json(&mut socket).await {
        if message["type"] == "event" {
            let done = message["event"] == "program_ended";
            seen.push(message);
            if done {
                break;
            }
        }
    }
    assert!(seen.iter().any(|e| *e == json!({"type": "event", "event": "program_stopped", "line": 2})), "{seen:?}");
    assert_eq!(seen.last(), Some(&json!({"type": "event", "event": "program_ended"})));
}

#[tokio::test]
async fn deleting_the_session_closes_the_stream() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut socket = connect(&server, &format!("/sessions/{id}/stream")).await;
    next_json(&mut socket).await.expect("state");
    server.delete(&format!("/sessions/{id}")).await;
    while next_json(&mut socket).await.is_some() {}
}

#[tokio::test]
async fn a_bad_period_is_refused_before_the_upgrade() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    for period in ["5", "5001", "abc"] {
        let reply = server.get(&format!("/sessions/{id}/stream?period_ms={period}")).await;
        assert_eq!(reply.status, reqwest::StatusCode::BAD_REQUEST, "{period}: {}", reply.body);
        assert!(reply.body["error"].is_string());
    }
    assert!(connect_async(server.ws_url(&format!("/sessions/{id}/stream?period_ms=1"))).await.is_err());
}

#[tokio::test]
async fn the_stream_works_for_clients_that_accept_gzip_like_browsers() {
    use tokio_tungstenite::tungstenite::client::IntoClientRequest;
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let mut request = server.ws_url(&format!("/sessions/{id}/stream")).into_client_request().expect("request");
    request.headers_mut().insert("accept-encoding", "gzip, deflate".parse().expect("header"));
    let (mut socket, response) = connect_async(request).await.expect("WebSocket handshake");
    assert!(response.headers().get("content-encoding").is_none(), "an upgrade is never compressed");
    assert_eq!(next_json(&mut socket).await.expect("state")["type"], "state");
}
