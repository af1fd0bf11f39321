//! Test harness: a real server on `127.0.0.1:0` and small HTTP helpers.

#![allow(dead_code)] // Each test binary uses a different part of the harness.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use nctwin_server::{AppState, Config, Limits};
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio::net::TcpListener;
use tokio::sync::oneshot;

/// A server running in this process until dropped, on SQLite storage in its own temporary
/// data directory (removed on drop unless stopped with [`Server::stop`]).
pub struct Server {
    pub addr: SocketAddr,
    pub client: reqwest::Client,
    pub data_dir: PathBuf,
    shutdown: Option<oneshot::Sender<()>>,
    task: Option<tokio::task::JoinHandle<std::io::Result<()>>>,
}

impl Drop for Server {
    fn drop(&mut self) {
        if let Some(tx) = self.shutdown.take() {
            let _ = tx.send(());
            let _ = std::fs::remove_dir_all(&self.data_dir);
        }
    }
}

/// A fresh, empty data directory for one server of this test process.
pub fn temp_data_dir() -> PathBuf {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("nctwin-test-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The HMI folder the tests serve.
pub const WEB_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../web");

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
        Server::start_config(Config { limits, ..Config::new(temp_data_dir(), WEB_DIR) }).await
    }

    /// A server for `config`, restoring what its data directory holds.
    pub async fn start_config(config: Config) -> Server {
        let state = AppState::open(config).await.expect("storage opens");
        Server::start_state(state).await
    }

    /// A server for a prepared state (e.g. on a test storage).
    pub async fn start_state(state: AppState) -> Server {
        let listener = TcpListener::bind("127.0.0.1:0").await.expect("bind 127.0.0.1:0");
        let addr = listener.local_addr().expect("local address");
        let data_dir = state.data_dir().to_path_buf();
        let (tx, rx) = oneshot::channel::<()>();
        let task = tokio::spawn(nctwin_server::run(listener, state, async {
            let _ = rx.await;
        }));
        Server { addr, client: reqwest::Client::new(), data_dir, shutdown: Some(tx), task: Some(task) }
    }

    /// Shuts the server down gracefully and waits until it has stopped; keeps the data
    /// directory (for a restart on it) and returns it.
    pub async fn stop(mut self) -> PathBuf {
        if let Some(tx) = self.shutdown.take() {
            let _ = tx.send(());
        }
        if let Some(task) = self.task.take() {
            task.await.expect("server task").expect("server ran");
        }
        self.data_dir.clone()
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
