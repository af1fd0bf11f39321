//! Deeply nested and very long expressions against the real `nctwin` binary (issue 20): every
//! endpoint that takes program text answers them with a 4xx or an alarm (12080, line 2) on the
//! server's own worker threads, and the server keeps serving; expressions at the limit run.
//! `nctwin simulate` on such a file reports the syntax error instead of aborting.

use crate::process;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use nctwin_engine::lang::MAX_EXPR_DEPTH;
use process::{forward_lines, listening_address};
use serde_json::{Value, json};

const M: usize = MAX_EXPR_DEPTH as usize;

/// Kills the server if the test fails before it ends.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The bodies of line 2 of the attack programs, each thousands of levels deep or long.
fn attacks() -> Vec<(&'static str, String)> {
    const N: usize = 5_000;
    let nested = |open: &str, inner: &str, close: &str| format!("{}{inner}{}", open.repeat(N), close.repeat(N));
    vec![
        ("parentheses", format!("R1={}", nested("(", "1", ")"))),
        ("unary minus", format!("R1={}1", "-".repeat(N))),
        ("NOT", format!("R1={}TRUE", "NOT ".repeat(N))),
        ("B_NOT", format!("R1={}1", "B_NOT ".repeat(N))),
        ("SIN(SIN(", format!("R1={}", nested("SIN(", "0", ")"))),
        ("R[R[", format!("R1={}", nested("R[", "1", "]"))),
        ("flat sum", format!("R1={}", vec!["1"; 30_000].join("+"))),
        ("string concatenation", format!("IF {}==\"A\"", vec!["\"A\""; 30_000].join("<<"))),
        ("mixed", format!("R1={}", nested("(-SIN(R[NOT ", "1", "]))"))),
    ]
}

/// Line 2 of programs at the limit: parentheses, a flat sum, nested calls the general evaluator
/// takes (ATAN2), nested R parameters.
fn at_the_limit() -> Vec<String> {
    vec![
        format!("R1={}7{}", "(".repeat(M - 1), ")".repeat(M - 1)),
        format!("R1={}", vec!["1"; M].join("+")),
        format!("R1={}0{}", "ATAN2(1,".repeat(M - 1), ")".repeat(M - 1)),
        format!("R1={}2{}", "R[".repeat(M - 1), "]".repeat(M - 1)),
    ]
}

fn program(line: &str) -> String {
    format!("G0 X0\n{line}\nM30\n")
}

fn data_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nctwin-deep-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Starts the binary on a free port; its address.
fn start(dir: &Path) -> (Running, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_nctwin"))
        .args(["--bind", "127.0.0.1:0", "--data-dir"])
        .arg(dir)
        .env("RUST_LOG", "info")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start nctwin");
    let mut server = Running(child);
    let lines = forward_lines(&mut server.0);
    let addr = listening_address(&lines);
    (server, addr)
}

struct Api {
    client: reqwest::Client,
    base: String,
}

impl Api {
    async fn send(&self, method: reqwest::Method, path: &str, body: Value) -> (u16, Value) {
        let url = format!("{}{path}", self.base);
        let reply = self.client.request(method, url).json(&body).send().await.expect("the server answers");
        let status = reply.status().as_u16();
        (status, reply.json().await.unwrap_or(Value::Null))
    }

    async fn post(&self, path: &str, body: Value) -> (u16, Value) {
        self.send(reqwest::Method::POST, path, body).await
    }

    async fn healthy(&self) -> bool {
        let url = format!("{}/health", self.base);
        self.client.get(url).send().await.is_ok_and(|r| r.status().is_success())
    }
}

/// A 4xx that names line 2, or a 200 whose state holds alarm 12080 of line 2.
fn refused(what: &str, (status, body): &(u16, Value)) {
    let alarm = body["alarms"].as_array().into_iter().flatten().any(|a| a["number"] == 12080 && a["line"] == 2);
    let named = body.to_string().contains("line 2") || body["line"] == 2;
    assert!((400..500).contains(status) && named || *status == 200 && alarm, "{what}: {status} {body}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_endpoint_refuses_deep_expressions_and_the_server_keeps_serving() {
    let dir = data_dir("endpoints");
    let (_server, addr) = start(&dir);
    let api = Api { client: reqwest::Client::new(), base: format!("http://{addr}/api/v1") };
    let (status, session) = api.post("/sessions", json!({"machine": "mill-3axis"})).await;
    assert_eq!(status, 201, "{session}");
    let s = format!("/sessions/{}", session["id"].as_str().expect("id"));
    for (name, line) in attacks() {
        let text = program(&line);
        let (status, check) = api.post(&format!("{s}/check"), json!({"program": text})).await;
        assert_eq!(status, 200, "{name}: {check}");
        let first = &check["diagnostics"][0];
        assert_eq!((&first["alarm"], &first["line"]), (&json!(12080), &json!(2)), "{name}: {first}");
        refused(name, &api.post(&format!("{s}/preview"), json!({"program": text})).await);
        refused(name, &api.post(&format!("{s}/search"), json!({"program": text, "line": 3})).await);
        let put = api.send(reqwest::Method::PUT, &format!("{s}/programs/DEEP"), json!({"text": text})).await;
        refused(name, &put);
        // MDA text is one block: its line 1.
        let (status, mda) = api.post(&format!("{s}/mda"), json!({"program": line, "wait": true})).await;
        assert!((400..500).contains(&status), "{name}: MDA {status} {mda}");
        refused(name, &api.post(&format!("{s}/run"), json!({"program": text, "wait": true})).await);
        assert!(api.healthy().await, "{name}: the server still answers");
    }
    // At the limit, programs run to their end on the server's threads.
    for line in at_the_limit() {
        let text = program(&line);
        let (status, check) = api.post(&format!("{s}/check"), json!({"program": text})).await;
        assert_eq!((status, &check["diagnostics"]), (200, &json!([])), "{line:.40}");
        let (status, state) = api.post(&format!("{s}/run"), json!({"program": text, "wait": true})).await;
        assert_eq!((status, &state["status"], &state["alarms"]), (200, &json!("idle"), &json!([])), "{line:.40}");
        let (status, preview) = api.post(&format!("{s}/preview"), json!({"program": text})).await;
        assert_eq!(status, 200, "{line:.40}: {preview}");
    }
    assert!(api.healthy().await);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `nctwin simulate` on each attack file: the syntax-error report (exit 2), no abort; at the
/// limit the program runs to its end.
#[test]
fn simulate_reports_deep_expressions_as_syntax_errors() {
    let dir = data_dir("simulate");
    std::fs::create_dir_all(&dir).expect("temp folder");
    let simulate = |text: &str, extra: &[&str]| {
        let path = dir.join("deep.mpf");
        std::fs::write(&path, text).expect("write");
        let out = Command::new(env!("CARGO_BIN_EXE_nctwin"))
            .args(["simulate", "--machine", "mill-3axis"])
            .args(extra)
            .arg(&path)
            .output()
            .expect("nctwin runs");
        let json: Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {:?} {}", out.status, String::from_utf8_lossy(&out.stderr)));
        (out.status.code(), json)
    };
    for (name, line) in attacks() {
        for extra in [&[][..], &["--interpret-only"][..]] {
            let (code, r) = simulate(&program(&line), extra);
            assert_eq!((code, &r["outcome"]), (Some(2), &json!("syntax_error")), "{name} {extra:?}");
            let first = &r["syntax_errors"][0];
            assert_eq!((&first["alarm"], &first["line"]), (&json!(12080), &json!(2)), "{name}: {first}");
        }
    }
    for line in at_the_limit() {
        let (code, r) = simulate(&program(&line), &[]);
        assert_eq!((code, &r["outcome"]), (Some(0), &json!("ended")), "{line:.40}: {r}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
