//! The real `nctwin` binary: it logs the address it listens on, serves the API there, creates
//! its data directory and shuts down cleanly on SIGINT.

use crate::process;

use process::{forward_lines, listening_address};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Kills the server if the test fails before it stops it.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A plain HTTP/1.1 GET; returns the whole response text.
fn http_get(addr: &str, path: &str) -> String {
    let mut stream = TcpStream::connect(addr).expect("connect");
    stream.set_read_timeout(Some(Duration::from_secs(20))).expect("timeout");
    write!(stream, "GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n").expect("request");
    let mut response = String::new();
    stream.read_to_string(&mut response).expect("response");
    response
}

#[test]
fn the_binary_logs_its_address_serves_health_and_stops_on_sigint() {
    let data_dir = std::env::temp_dir().join(format!("nctwin-binary-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&data_dir);
    let child = Command::new(env!("CARGO_BIN_EXE_nctwin"))
        .args(["--bind", "127.0.0.1:0", "--data-dir"])
        .arg(&data_dir)
        .env("RUST_LOG", "info")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start nctwin");
    let mut server = Running(child);
    let lines = forward_lines(&mut server.0);

    let addr = listening_address(&lines);
    assert!(addr.starts_with("127.0.0.1:") && !addr.ends_with(":0"), "the real bound address: {addr}");

    let response = http_get(&addr, "/api/v1/health");
    assert!(response.starts_with("HTTP/1.1 200"), "{response}");
    assert!(response.contains(r#""status":"ok""#), "{response}");
    assert!(data_dir.is_dir(), "the data directory was created");

    let status = Command::new("kill").args(["-INT", &server.0.id().to_string()]).status().expect("kill -INT");
    assert!(status.success());
    let deadline = Instant::now() + Duration::from_secs(30);
    let exit = loop {
        if let Some(exit) = server.0.try_wait().expect("wait") {
            break exit;
        }
        assert!(Instant::now() < deadline, "the server did not stop on SIGINT");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(exit.success(), "clean exit after SIGINT: {exit}");
    let _ = std::fs::remove_dir_all(&data_dir);
}
