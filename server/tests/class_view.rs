//! A training class on one server with `--auth off`: a watch link (view-only) cannot drive,
//! over REST or the stream, and the stream's action log names who did what.

use crate::common;

use std::time::Duration;

use common::{Server, error_message};
use futures_util::{SinkExt, StreamExt};
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

const READ_GUARD: Duration = Duration::from_secs(20);

#[tokio::test]
async fn a_view_only_client_reads_but_cannot_drive() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let watch = |r: reqwest::RequestBuilder| r.header("nctwin-view-only", "1");
    let state = server.send(watch(server.client.get(server.url(&format!("/sessions/{id}/state"))))).await;
    assert_eq!(state.status, StatusCode::OK, "{}", state.body);
    let run = server
        .send(watch(
            server.client.post(server.url(&format!("/sessions/{id}/run"))).json(&json!({"program": "G0 X5\nM30"})),
        ))
        .await;
    assert!(error_message(&run, StatusCode::FORBIDDEN).contains("observers"));
    // Nothing started.
    assert_eq!(server.get(&format!("/sessions/{id}/state")).await.body["status"], "idle");
    // On the stream too: a jog message of a view-only socket is refused.
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    let (mut socket, _) =
        connect_async(server.ws_url(&format!("/sessions/{id}/stream?view_only=1"))).await.expect("handshake");
    let jog = json!({"type": "jog", "axis": "X", "direction": 1, "coordinates": "WCS"});
    socket.send(Message::Text(jog.to_string().into())).await.expect("sent");
    let reply = next_of(&mut socket, "error").await.expect("an error reply");
    assert!(reply["error"].as_str().unwrap_or("").contains("observers"), "{reply}");
}

#[tokio::test]
async fn the_stream_names_who_did_what() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let (mut socket, _) = connect_async(server.ws_url(&format!("/sessions/{id}/stream"))).await.expect("handshake");
    next_of(&mut socket, "state").await.expect("a first state");
    // "Jürgen M." percent-encoded, as the HMI sends it.
    let reset = server
        .send(
            server
                .client
                .post(server.url(&format!("/sessions/{id}/reset")))
                .header("nctwin-user", "J%C3%BCrgen%20M.")
                .json(&json!({})),
        )
        .await;
    assert_eq!(reset.status, StatusCode::OK, "{}", reset.body);
    let event = loop {
        let e = next_of(&mut socket, "event").await.expect("an event");
        if e["event"] == "operator_action" {
            break e;
        }
    };
    assert_eq!((event["action"].as_str(), event["role"].as_str()), (Some("POST reset"), Some("owner")));
    assert_eq!(event["name"], "Jürgen M.");
}

async fn next_of(
    socket: &mut tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>,
    kind: &str,
) -> Option<Value> {
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
