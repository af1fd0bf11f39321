//! Commands that stop motion are never refused by the command rate limit: a client flooding a
//! session with commands cannot keep another client from stopping the machine.

use crate::common;

use std::time::Duration;

use common::{Server, pos};
use futures_util::{SinkExt, StreamExt};
use nctwin_server::Limits;
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

/// A limit that a flood spends at once and that refills only after ten seconds.
fn tight() -> Limits {
    Limits { commands_per_second: 0.1, command_burst: 3.0, ..Limits::default() }
}

/// Sends commands that do not stop anything until the session answers 429.
async fn flood(server: &Server, id: &str) {
    for _ in 0..20 {
        let reply = server.put(&format!("/sessions/{id}/overrides"), json!({"feed": 100})).await;
        if reply.status == StatusCode::TOO_MANY_REQUESTS {
            return;
        }
    }
    panic!("the rate limit never refused the flood");
}

#[tokio::test]
async fn nc_stop_and_reset_are_answered_while_the_rate_limit_refuses_commands() {
    let server = Server::start_with(tight()).await;
    let id = server.session("mill-3axis").await;
    let run = json!({"program": "G1 X300 F200\nM30", "pace": "realtime"});
    assert_eq!(server.post(&format!("/sessions/{id}/run"), run).await.status, StatusCode::OK);
    server.state_until(&id, "X moves", |s| pos(s, "machine", "X") > 0.0).await;
    flood(&server, &id).await;

    let reply = server.post_empty(&format!("/sessions/{id}/stop")).await;
    assert_eq!(reply.status, StatusCode::OK, "NC stop refused: {}", reply.body);
    let stopped = server.state_until(&id, "the program stops", |s| s["status"] == "stopped").await;
    let x = pos(&stopped, "machine", "X");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let later = server.get(&format!("/sessions/{id}/state")).await.body;
    assert!((pos(&later, "machine", "X") - x).abs() < 0.5, "X still moves after NC stop: {x} → {later}");

    let reply = server.post_empty(&format!("/sessions/{id}/reset")).await;
    assert_eq!(reply.status, StatusCode::OK, "reset refused: {}", reply.body);
    assert_eq!(reply.body["status"], "idle");
    // Stopping again and again is never refused either.
    for _ in 0..10 {
        assert_eq!(server.post_empty(&format!("/sessions/{id}/stop")).await.status, StatusCode::OK);
        assert_eq!(server.post_empty(&format!("/sessions/{id}/reset")).await.status, StatusCode::OK);
    }
    // The stops took nothing from the bucket, and other commands stay limited.
    let reply = server.put(&format!("/sessions/{id}/overrides"), json!({"feed": 100})).await;
    assert_eq!(reply.status, StatusCode::TOO_MANY_REQUESTS);
}

#[tokio::test]
async fn jog_stop_is_answered_while_the_rate_limit_refuses_commands() {
    let server = Server::start_with(tight()).await;
    let id = server.session("mill-3axis").await;
    assert_eq!(server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await.status, StatusCode::OK);
    let jog = json!({"axis": "X", "direction": 1});
    let reply = server.post(&format!("/sessions/{id}/jog"), jog).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    server.state_until(&id, "X moves", |s| pos(s, "machine", "X") > 0.0).await;
    flood(&server, &id).await;

    let reply = server.post_empty(&format!("/sessions/{id}/jog/stop")).await;
    assert_eq!(reply.status, StatusCode::OK, "JOG stop refused: {}", reply.body);
    x_stands(&server, &id).await;
}

#[tokio::test]
async fn jog_stop_on_the_stream_is_answered_while_the_rate_limit_refuses_commands() {
    let server = Server::start_with(tight()).await;
    let id = server.session("mill-3axis").await;
    assert_eq!(server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await.status, StatusCode::OK);
    let (mut ws, _) = connect_async(server.ws_url(&format!("/sessions/{id}/stream"))).await.expect("stream");
    let jog = json!({"type": "jog", "axis": "X", "direction": 1}).to_string();
    ws.send(Message::text(jog)).await.expect("sent");
    assert_eq!(next_reply(&mut ws).await["type"], "ack");
    flood(&server, &id).await;

    ws.send(Message::text(json!({"type": "jog_stop"}).to_string())).await.expect("sent");
    let reply = next_reply(&mut ws).await;
    assert_eq!((reply["type"].as_str(), reply["request"].as_str()), (Some("ack"), Some("jog_stop")), "{reply}");
    x_stands(&server, &id).await;
}

/// Waits until X has braked to standstill (about 2 s at most), then checks that it stays.
async fn x_stands(server: &Server, id: &str) {
    let x = || async { pos(&server.get(&format!("/sessions/{id}/state")).await.body, "machine", "X") };
    let mut last = x().await;
    for _ in 0..20 {
        tokio::time::sleep(Duration::from_millis(100)).await;
        let now = x().await;
        if now == last {
            tokio::time::sleep(Duration::from_millis(300)).await;
            assert_eq!(x().await, now, "X moves again");
            return;
        }
        last = now;
    }
    panic!("X still moves 2 s after the stop (at {last})");
}

/// The next message of the stream that is not a state.
async fn next_reply<S>(ws: &mut S) -> Value
where
    S: StreamExt<Item = Result<Message, tokio_tungstenite::tungstenite::Error>> + Unpin,
{
    loop {
        let message = tokio::time::timeout(Duration::from_secs(10), ws.next()).await.expect("a message in time");
        let Some(Ok(Message::Text(text))) = message else { panic!("the stream ended: {message:?}") };
        let value: Value = serde_json::from_str(text.as_str()).expect("JSON");
        // States and events (the flood's own commands are logged as operator actions) come
        // between; a reply is an ack or an error.
        if value["type"] != "state" && value["type"] != "event" {
            return value;
        }
    }
}
