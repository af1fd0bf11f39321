//! Replies that tell the client the truth: a refusal that leaves the body unread says the
//! connection closes, the limit header names the limit that ended a run, a request waiting at
//! shutdown is told to come back, and a syntax check answers a bounded list.

use crate::common;

use std::time::Duration;

use common::{Server, error_message};
use nctwin_server::Limits;
use reqwest::StatusCode;
use serde_json::json;
use tokio::io::{AsyncBufReadExt, AsyncReadExt, AsyncWriteExt, BufReader};
use tokio::net::TcpStream;

/// One HTTP/1.1 response read off a raw connection: status, lower-case header lines, body.
struct Raw {
    status: u16,
    headers: Vec<(String, String)>,
    body: Vec<u8>,
}

impl Raw {
    fn header(&self, name: &str) -> Option<&str> {
        self.headers.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_str())
    }

    fn closes(&self) -> bool {
        self.header("connection").is_some_and(|v| v.eq_ignore_ascii_case("close"))
    }
}

/// Writes `request` and reads one response; `None` when the server closed the connection.
async fn exchange(stream: &mut BufReader<TcpStream>, request: &str) -> Option<Raw> {
    stream.get_mut().write_all(request.as_bytes()).await.ok()?;
    let mut line = String::new();
    if stream.read_line(&mut line).await.ok()? == 0 {
        return None;
    }
    let status = line.split_whitespace().nth(1)?.parse().ok()?;
    let mut headers = Vec::new();
    loop {
        line.clear();
        stream.read_line(&mut line).await.ok()?;
        let trimmed = line.trim_end();
        if trimmed.is_empty() {
            break;
        }
        let (name, value) = trimmed.split_once(':')?;
        headers.push((name.trim().to_ascii_lowercase(), value.trim().to_string()));
    }
    let length: usize =
        headers.iter().find(|(n, _)| n == "content-length").and_then(|(_, v)| v.parse().ok()).unwrap_or(0);
    let mut body = vec![0; length];
    stream.read_exact(&mut body).await.ok()?;
    Some(Raw { status, headers, body })
}

fn request(method: &str, addr: &str, path: &str, body: &str) -> String {
    format!(
        "{method} {path} HTTP/1.1\r\nhost: {addr}\r\ncontent-type: application/json\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    )
}

/// A keep-alive client as HTTP/1.1 clients are written: it reuses the connection unless the
/// response said `Connection: close`. Its requests after a refused one must not fail.
#[tokio::test]
async fn a_refusal_that_leaves_the_body_unread_says_the_connection_closes() {
    let server =
        Server::start_with(Limits { commands_per_second: 0.01, command_burst: 1.0, ..Limits::default() }).await;
    let id = server.session("mill-3axis").await;
    let addr = server.addr.to_string();
    let connect = || async { BufReader::new(TcpStream::connect(server.addr).await.expect("connect")) };
    let mut stream = connect().await;
    let path = format!("/api/v1/sessions/{id}/overrides");
    let mut refused = 0;
    for i in 0..6 {
        // Larger than what the server reads with the headers: the unread rest stays in the
        // connection (a small body read along with the headers is drained by the server).
        let body = format!("{}{}", json!({"feed": 90, "spindle": 100, "rapid": 100}), " ".repeat(300_000));
        let reply = exchange(&mut stream, &request("PUT", &addr, &path, &body))
            .await
            .unwrap_or_else(|| panic!("request {i} on a connection the server kept open got no reply"));
        if reply.status == 429 {
            refused += 1;
        } else {
            assert_eq!(reply.status, 200, "{}", String::from_utf8_lossy(&reply.body));
        }
        let health = request("GET", &addr, "/api/v1/health", "");
        if reply.closes() {
            stream = connect().await;
        }
        let reply = exchange(&mut stream, &health).await.unwrap_or_else(|| panic!("no reply after request {i}"));
        assert_eq!(reply.status, 200);
        if reply.closes() {
            stream = connect().await;
        }
    }
    assert!(refused >= 4, "the rate limit refused {refused} requests");

    // The same for other refusals before the body is read: a wrong content type, a bad host.
    let padded = format!("{{}}{}", " ".repeat(300_000));
    let wrong_type = format!(
        "POST /api/v1/sessions HTTP/1.1\r\nhost: {addr}\r\ncontent-type: text/plain\r\ncontent-length: {}\r\n\r\n{padded}",
        padded.len()
    );
    let reply = exchange(&mut stream, &wrong_type).await.expect("a reply");
    assert_eq!(reply.status, 415);
    if reply.closes() {
        stream = connect().await;
    }
    let health = request("GET", &addr, "/api/v1/health", "");
    assert_eq!(exchange(&mut stream, &health).await.expect("the connection is usable").status, 200);
}

#[tokio::test]
async fn a_body_that_was_read_keeps_the_connection_open() {
    let server = Server::start().await;
    let addr = server.addr.to_string();
    let mut stream = BufReader::new(TcpStream::connect(server.addr).await.expect("connect"));
    for _ in 0..3 {
        let reply = exchange(&mut stream, &request("POST", &addr, "/api/v1/sessions", "{\"machine\": \"nope\"}"))
            .await
            .expect("a reply");
        assert_eq!(reply.status, 400);
        assert!(!reply.closes(), "{:?}", reply.headers);
    }
}

#[tokio::test]
async fn the_limit_header_names_the_wall_time_limit_when_it_ended_a_fast_run() {
    let limits = Limits { fast_sim_time: 1e9, fast_wall_time: Duration::from_millis(300), ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let program = "LOOP\nG1 X100 F20000\nG1 X0\nENDLOOP\nM30";
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.headers["nctwin-limit"], "fast-wall-time");
    assert!(reply.body["time"].as_f64().is_some_and(|t| t < 1e9));

    // The simulated-time limit still says so.
    let limits = Limits { fast_sim_time: 1.0, ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(reply.headers["nctwin-limit"], "fast-sim-time");
}

#[tokio::test]
async fn a_request_waiting_at_shutdown_is_told_to_retry() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let request = server
        .client
        .post(server.url(&format!("/sessions/{id}/run")))
        .json(&json!({"program": "G1 X300 F100\nM30", "wait": true}));
    let waiting = tokio::spawn(request.send());
    server.state_until(&id, "the program runs", |s| s["status"] == "running").await;
    let stopped = tokio::spawn(server.stop());
    let response = tokio::time::timeout(Duration::from_secs(10), waiting)
        .await
        .expect("answered at shutdown")
        .expect("task")
        .expect("a response");
    assert_eq!(response.status(), StatusCode::SERVICE_UNAVAILABLE);
    assert!(response.headers().get("retry-after").is_some(), "{:?}", response.headers());
    let body: serde_json::Value = response.json().await.expect("JSON");
    assert!(body["error"].as_str().is_some_and(|e| e.contains("shutting down")), "{body}");
    let data_dir = stopped.await.expect("stopped");
    let _ = std::fs::remove_dir_all(data_dir);
}

#[tokio::test]
async fn a_check_of_many_errors_answers_the_first_thousand_and_counts_the_rest() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "X=(\n".repeat(175_000); // 700 KB, an error on every line
    let response = server
        .client
        .post(server.url(&format!("/sessions/{id}/check")))
        .json(&json!({"program": program}))
        .send()
        .await
        .expect("a response");
    assert_eq!(response.status(), StatusCode::OK);
    let bytes = response.bytes().await.expect("body");
    assert!(bytes.len() < 500_000, "{} bytes", bytes.len());
    let body: serde_json::Value = serde_json::from_slice(&bytes).expect("JSON");
    let listed = body["diagnostics"].as_array().expect("diagnostics");
    assert_eq!(listed.len(), 1000);
    assert_eq!(listed[0]["line"], 1);
    assert_eq!(listed[999]["line"], 1000, "the first ones, in order");
    assert!(body["omitted"].as_u64().is_some_and(|n| n >= 174_000), "{}", body["omitted"]);

    let clean = server.post(&format!("/sessions/{id}/check"), json!({"program": "G1 X1 F100\nM30"})).await;
    assert_eq!(clean.body, json!({"diagnostics": []}), "unchanged when every error is listed");
}

#[tokio::test]
async fn checks_are_rate_limited_by_the_text_they_cost() {
    let limits = Limits { check_bytes_per_second: 10_000, check_burst_bytes: 300_000, ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let program = "G1 X1 Y2 Z3 F100\n".repeat(6_000); // 102 KB
    let mut statuses = Vec::new();
    for _ in 0..4 {
        statuses.push(server.post(&format!("/sessions/{id}/check"), json!({"program": program})).await);
    }
    assert!(statuses[..2].iter().all(|r| r.status == StatusCode::OK));
    for refused in &statuses[2..] {
        let message = error_message(refused, StatusCode::TOO_MANY_REQUESTS);
        assert!(message.contains("check"), "{message}");
        assert!(refused.headers.get("retry-after").is_some());
    }
    // A refused check takes nothing from the budget: small checks (the HMI's, as the operator
    // types) still pass.
    let small = server.post(&format!("/sessions/{id}/check"), json!({"program": "G1 X1\nM30"})).await;
    assert_eq!(small.status, StatusCode::OK, "{}", small.body);
    // Per session: another session's checks are not affected.
    let other = server.session("mill-3axis").await;
    let reply = server.post(&format!("/sessions/{other}/check"), json!({"program": program})).await;
    assert_eq!(reply.status, StatusCode::OK);
}
