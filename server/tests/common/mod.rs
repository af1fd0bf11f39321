//! Test harness: a real server on `127.0.0.1:0` and small HTTP helpers.

#![allow(dead_code)] // Each test binary uses a different part of the harness.

use std::net::SocketAddr;
use std::time::Duration;

use nctwin_server::{AppState, Limits};
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio::net::TcpListener;
use tokio::sync::oneshot;

/// A server running in this process until dropped.
pub struct Server {
    pub addr: SocketAddr,
    pub client: reqwest::Client,
    shutdown: Option<oneshot::Sender<()>>,
}

impl Drop for Server {
    fn drop(&mut self) {
        if let Some(tx) = self.shutdown.take() {
            let _ = tx.send(());
        }
    }
}

/// A reply: status, headers and the JSON body (`Value::Null` when the body is empty).
pub struct Reply {
    pub status: StatusCode,
    pub headers: reqwest::header::HeaderMap,
    pub body: Value,
}

impl Server {
    pub async fn start() -> Server {
        Server::start_with(Limits::default()).await
    }

    pub async fn start_with(limits: Limits) -> Server {
        let listener = TcpListener::bind("127.0.0.1:0").await.expect("bind 127.0.0.1:0");
        let addr = listener.local_addr().expect("local address");
        let data_dir = std::env::temp_dir().join(format!("nctwin-test-{}", std::process::id()));
        let web_dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../web");
        let state = AppState::with_limits(data_dir, web_dir, limits);
        let (tx, rx) = oneshot::channel::<()>();
        tokio::spawn(nctwin_server::run(listener, state, async {
            let _ = rx.await;
        }));
        Server { addr, client: reqwest::Client::new(), shutdown: Some(tx) }
    }

    pub fn url(&self, path: &str) -> String {
        format!("http://{}/api/v1{path}", self.addr)
    }

    pub fn ws_url(&self, path: &str) -> String {
        format!("ws://{}/api/v1{path}", self.addr)
    }

    pub async fn send(&self, request: reqwest::RequestBuilder) -> Reply {
        let response = request.send().await.expect("request sent");
        let status = response.status();
        let headers = response.headers().clone();
        let bytes = response.bytes().await.expect("body read");
        let body = if bytes.is_empty() {
            Value::Null
        } else {
            serde_json::from_slice(&bytes)
                .unwrap_or_else(|e| panic!("body is not JSON ({e}): {}", String::from_utf8_lossy(&bytes)))
        };
        Reply { status, headers, body }
    }

    pub async fn get(&self, path: &str) -> Reply {
        self.send(self.client.get(self.url(path))).await
    }

    pub async fn post(&self, path: &str, body: Value) -> Reply {
        self.send(self.client.post(self.url(path)).json(&body)).await
    }

    /// POST without a body.
    pub async fn post_empty(&self, path: &str) -> Reply {
        self.send(self.client.post(self.url(path))).await
    }

    /// POST with a raw body and content type `application/json`.
    pub async fn post_raw(&self, path: &str, body: impl Into<reqwest::Body>) -> Reply {
        let request = self.client.post(self.url(path)).header("content-type", "application/json").body(body);
        self.send(request).await
    }

    pub async fn put(&self, path: &str, body: Value) -> Reply {
        self.send(self.client.put(self.url(path)).json(&body)).await
    }

    pub async fn delete(&self, path: &str) -> Reply {
        self.send(self.client.delete(self.url(path))).await
    }

    /// Creates a session of `machine` and returns its id.
    pub async fn session(&self, machine: &str) -> String {
        let reply = self.post("/sessions", json!({ "machine": machine })).await;
        assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
        reply.body["id"].as_str().expect("id").to_string()
    }

    /// Polls the state until `done` holds (at most about 20 s, then panics).
    pub async fn state_until(&self, id: &str, what: &str, done: impl Fn(&Value) -> bool) -> Value {
        for _ in 0..1000 {
            let reply = self.get(&format!("/sessions/{id}/state")).await;
            assert_eq!(reply.status, StatusCode::OK);
            if done(&reply.body) {
                return reply.body;
            }
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
        panic!("the state never reached: {what}");
    }
}

/// A position from a state: `kind` is machine, basic or workpiece.
pub fn pos(state: &Value, kind: &str, axis: &str) -> f64 {
    state["positions"][kind][axis].as_f64().unwrap_or_else(|| panic!("no {kind} position {axis} in {state}"))
}

/// Asserts a 4xx reply with the JSON error shape and returns the message.
pub fn error_message(reply: &Reply, status: StatusCode) -> String {
    assert_eq!(reply.status, status, "{}", reply.body);
    reply.body["error"].as_str().unwrap_or_else(|| panic!("no error message in {}", reply.body)).to_string()
}
