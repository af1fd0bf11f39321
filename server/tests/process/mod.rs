//! Helpers for tests that run the real `nctwin` binary as a child process.

#![allow(dead_code)] // Each test binary uses a different part of the harness.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use reqwest::StatusCode;
use serde_json::Value;

/// Sends every line of stdout and stderr to one channel.
pub fn forward_lines(child: &mut Child) -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    let stdout = child.stdout.take().expect("stdout piped");
    let stderr = child.stderr.take().expect("stderr piped");
    for reader in [Box::new(stdout) as Box<dyn Read + Send>, Box::new(stderr)] {
        let tx = tx.clone();
        std::thread::spawn(move || {
            for line in BufReader::new(reader).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
    }
    rx
}

/// The address (`IP:PORT`) from the server's `listening on http://...` line, waiting up to a
/// minute for it; the lines before it are dropped.
pub fn listening_address(lines: &mpsc::Receiver<String>) -> String {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let line = lines.recv_timeout(left).expect("a `listening on http://` line");
        if let Some((_, rest)) = line.split_once("listening on http://") {
            return rest.split_whitespace().next().expect("address").to_string();
        }
    }
}

/// A running `nctwin`; killed if the test fails before it stops it.
pub struct Nctwin {
    pub child: Child,
    /// `http://IP:PORT/api/v1`.
    pub base: String,
    pub client: reqwest::Client,
}

impl Drop for Nctwin {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Nctwin {
    /// Starts the binary on a free port with `data_dir` and waits for its address.
    pub fn start(data_dir: &Path) -> Nctwin {
        Nctwin::start_with(data_dir, None)
    }

    /// [`Nctwin::start`], keeping the sessions in PostgreSQL database `database` if given (as
    /// node `test-node`, so that a restart is the same node).
    pub fn start_with(data_dir: &Path, database: Option<&str>) -> Nctwin {
        match database {
            Some(url) => Nctwin::start_args(data_dir, &["--database", url, "--node-id", "test-node"]),
            None => Nctwin::start_args(data_dir, &[]),
        }
    }

    /// [`Nctwin::start`] with more arguments.
    pub fn start_args(data_dir: &Path, args: &[&str]) -> Nctwin {
        let mut command = Command::new(env!("CARGO_BIN_EXE_nctwin"));
        command.args(args);
        let mut child = command
            .args(["--bind", "127.0.0.1:0", "--data-dir"])
            .arg(data_dir)
            .env("RUST_LOG", "info")
            .env("NO_COLOR", "1")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start nctwin");
        let lines = forward_lines(&mut child);
        let addr = listening_address(&lines);
        // Keep draining the output so the server never blocks on a full pipe.
        std::thread::spawn(move || while lines.recv().is_ok() {});
        Nctwin { child, base: format!("http://{addr}/api/v1"), client: reqwest::Client::new() }
    }

    pub async fn send(&self, method: reqwest::Method, path: &str, body: Option<Value>) -> (StatusCode, Value) {
        let mut request = self.client.request(method, self.url(path));
        if let Some(body) = body {
            request = request.json(&body);
        }
        let response = request.send().await.expect("request");
        let status = response.status();
        let bytes = response.bytes().await.expect("body");
        (status, if bytes.is_empty() { Value::Null } else { serde_json::from_slice(&bytes).expect("JSON") })
    }

    pub fn signal(&self, name: &str) {
        let status = Command::new("kill").args([name, &self.child.id().to_string()]).status().expect("kill");
        assert!(status.success());
    }

    /// Waits for the process to end (at most `limit`), returning whether it exited with 0.
    pub fn wait_exit(&mut self, limit: Duration) -> bool {
        let deadline = Instant::now() + limit;
        loop {
            if let Some(exit) = self.child.try_wait().expect("wait") {
                return exit.success();
            }
            assert!(Instant::now() < deadline, "the server did not exit within {limit:?}");
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// The URL of API path `path` (`/sessions/...`).
    pub fn url(&self, path: &str) -> String {
        format!("{}{path}", self.base)
    }

    /// `GET path`: the status and the body as JSON (`null` when the body is none).
    pub async fn get(&self, path: &str) -> (StatusCode, Value) {
        let response = self.client.get(self.url(path)).send().await.expect("request");
        let status = response.status();
        (status, response.json().await.unwrap_or(Value::Null))
    }
}
