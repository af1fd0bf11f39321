//! Server-side limits answer 4xx/429 with a message, and `GET /metrics`.

use crate::common;

use std::time::Duration;

use common::{Server, error_message};
use nctwin_server::Limits;
use reqwest::StatusCode;
use serde_json::json;
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Error as WsError;

#[tokio::test]
async fn the_session_count_is_limited_in_total_and_per_client() {
    let server = Server::start_with(Limits { sessions: 2, ..Limits::default() }).await;
    server.session("mill-3axis").await;
    server.session("mill-3axis").await;
    let message = error_message(&server.post_empty("/sessions").await, StatusCode::TOO_MANY_REQUESTS);
    assert!(message.contains("2 sessions"), "{message}");

    let server = Server::start_with(Limits { sessions_per_ip: 1, ..Limits::default() }).await;
    let first = server.session("mill-3axis").await;
    let message = error_message(&server.post_empty("/sessions").await, StatusCode::TOO_MANY_REQUESTS);
    assert!(message.contains("127.0.0.1"), "{message}");
    server.delete(&format!("/sessions/{first}")).await;
    server.session("mill-3axis").await;
}

#[tokio::test]
async fn commands_beyond_the_rate_are_429_with_retry_after_and_reads_are_not_counted() {
    let server = Server::start_with(Limits { commands_per_second: 0.5, command_burst: 2.0, ..Limits::default() }).await;
    let id = server.session("mill-3axis").await;
    for _ in 0..2 {
        assert_eq!(server.post_empty(&format!("/sessions/{id}/cancel")).await.status, StatusCode::OK);
    }
    let reply = server.post_empty(&format!("/sessions/{id}/cancel")).await;
    let message = error_message(&reply, StatusCode::TOO_MANY_REQUESTS);
    assert!(message.contains("commands per second"), "{message}");
    assert_eq!(reply.headers["retry-after"], "2");
    for _ in 0..5 {
        assert_eq!(server.get(&format!("/sessions/{id}/state")).await.status, StatusCode::OK);
    }
    let other = server.session("mill-3axis").await;
    assert_eq!(server.post_empty(&format!("/sessions/{other}/cancel")).await.status, StatusCode::OK, "per session");
}

#[tokio::test]
async fn stream_clients_per_session_are_limited() {
    let server = Server::start_with(Limits { stream_clients: 1, ..Limits::default() }).await;
    let id = server.session("mill-3axis").await;
    let url = server.ws_url(&format!("/sessions/{id}/stream"));
    let (first, _) = connect_async(url.as_str()).await.expect("the first client");
    match connect_async(url.as_str()).await {
        Err(WsError::Http(response)) => assert_eq!(response.status(), StatusCode::TOO_MANY_REQUESTS),
        other => panic!("expected 429, got {:?}", other.map(|(_, r)| r.status())),
    }
    drop(first);
    // The place is freed once the server notices the client is gone.
    for _ in 0..200 {
        if connect_async(url.as_str()).await.is_ok() {
            return;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    panic!("the stream client place was never freed");
}

#[tokio::test]
async fn programs_may_exceed_the_body_limit_up_to_the_program_limit() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let big = "; a comment line of a large program\n".repeat(60_000); // about 2.2 MB
    let reply = server.put(&format!("/sessions/{id}/programs/BIG"), json!({"text": big})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(server.get(&format!("/sessions/{id}/programs/BIG")).await.body["text"], big.as_str());
    // Other bodies keep the 1 MiB limit.
    error_message(
        &server.post(&format!("/sessions/{id}/check"), json!({"program": big})).await,
        StatusCode::PAYLOAD_TOO_LARGE,
    );

    let server =
        Server::start_with(Limits { program_bytes: 1000, session_program_bytes: 1500, ..Limits::default() }).await;
    let id = server.session("mill-3axis").await;
    let text = |n: usize| format!("{}M17\n", ";\n".repeat(n));
    let message = error_message(
        &server.put(&format!("/sessions/{id}/programs/A"), json!({"text": text(600)})).await,
        StatusCode::PAYLOAD_TOO_LARGE,
    );
    assert!(message.contains("1000"), "{message}");
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/A"), json!({"text": text(400)})).await.status,
        StatusCode::OK
    );
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/A"), json!({"text": text(450)})).await.status,
        StatusCode::OK,
        "replacing counts once"
    );
    let message = error_message(
        &server.put(&format!("/sessions/{id}/programs/B"), json!({"text": text(400)})).await,
        StatusCode::PAYLOAD_TOO_LARGE,
    );
    assert!(message.contains("1500"), "{message}");
}

#[tokio::test]
async fn metrics_are_served_in_the_prometheus_text_format() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    server.get(&format!("/sessions/{id}/state")).await;
    let response = server.client.get(format!("http://{}/metrics", server.addr)).send().await.expect("metrics");
    assert_eq!(response.status(), StatusCode::OK);
    assert!(response.headers()["content-type"].to_str().expect("type").starts_with("text/plain; version=0.0.4"));
    let text = response.text().await.expect("text");
    for needle in [
        "nctwin_sessions 1\n",
        "nctwin_stream_clients 0\n",
        "nctwin_ipo_lag_seconds_max 0\n",
        "nctwin_http_requests_total{method=\"POST\",route=\"/api/v1/sessions\",status=\"201\"} 1\n",
        "nctwin_http_request_duration_seconds_count{method=\"GET\",route=\"/api/v1/sessions/{id}/state\"} 1\n",
        "nctwin_storage_operations_total{result=\"error\"} 0\n",
    ] {
        assert!(text.contains(needle), "{needle} in\n{text}");
    }
}
