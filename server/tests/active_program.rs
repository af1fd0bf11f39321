//! `GET /sessions/{id}/active-program`: the program the channel runs, whoever started it, by
//! line ranges; the state's `program_serial`; the preview of the loaded program.

use crate::common;

use common::{Server, error_message};
use nctwin_server::Config;
use reqwest::StatusCode;
use serde_json::{Value, json};

fn active(id: &str, query: &str) -> String {
    format!("/sessions/{id}/active-program{query}")
}

async fn run(server: &Server, id: &str, body: Value) -> Value {
    let reply = server.post(&format!("/sessions/{id}/run"), body).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    reply.body
}

#[tokio::test]
async fn a_run_over_rest_is_served_with_its_name_hash_and_lines() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let none = server.get(&active(&id, "")).await;
    assert_eq!(none.status, StatusCode::NOT_FOUND, "no program has run yet: {}", none.body);
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["program_serial"], 0);

    let text = "G0 X0 Y0 Z10\nG1 X20 F1000\nG1 Y10\r\nG1 X0\nM30\n";
    let end = run(&server, &id, json!({"program": text, "pace": "fast", "wait": true, "name": "PART1"})).await;
    assert_eq!(end["program_serial"], 1);
    let reply = server.get(&active(&id, "?from=2&count=2")).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let b = &reply.body;
    assert_eq!((b["serial"].clone(), b["name"].clone(), b["mode"].clone()), (json!(1), json!("PART1"), json!("AUTO")));
    // Five lines: the final line end adds none; line 3's CR is not part of the line.
    assert_eq!((b["line_count"].clone(), b["bytes"].clone()), (json!(5), json!(text.len())));
    assert_eq!((b["from"].clone(), b["lines"].clone()), (json!(2), json!(["G1 X20 F1000", "G1 Y10"])));
    assert_eq!(b["program"], Value::Null);
    // sha256 of the text, as `printf 'G0 X0 Y0 Z10\nG1 X20 F1000\nG1 Y10\r\nG1 X0\nM30\n' | sha256sum`.
    assert_eq!(b["sha256"], "bbd1b6991dcf0f95a7cd846e5fb159342e4a36fdcf3ea1ef4f092f1866cb647a");
    assert_eq!(b["sha256"].as_str().map(str::len), Some(64));
    // The range runs to the end of the text and no further; one past the end is empty.
    let tail = server.get(&active(&id, "?from=4&count=100")).await.body;
    assert_eq!(tail["lines"], json!(["G1 X0", "M30"]));
    let past = server.get(&active(&id, "?from=6")).await.body;
    assert_eq!(past["lines"], json!([]));
}

#[tokio::test]
async fn bad_ranges_are_refused_with_what_is_wrong() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    run(&server, &id, json!({"program": "G0 X1\nM30", "pace": "fast", "wait": true})).await;
    for (query, says) in [
        ("?from=0", "from is 1-based"),
        ("?count=0", "count must be 1..=5000"),
        ("?count=5001", "count must be 1..=5000"),
        ("?from=4", "past the end: the program has 2 lines"),
        ("?from=x", "from"),
    ] {
        let reply = server.get(&active(&id, query)).await;
        let message = error_message(&reply, StatusCode::BAD_REQUEST);
        assert!(message.contains(says), "{query}: {message}");
    }
    let reply = server.get(&active(&id, "?program=NOSUCH")).await;
    error_message(&reply, StatusCode::NOT_FOUND);
    let reply = server.get(&active("nosession", "")).await;
    error_message(&reply, StatusCode::NOT_FOUND);
}

#[tokio::test]
async fn mda_blocks_and_a_stored_programs_text_are_the_active_program() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post(&format!("/sessions/{id}/mda"), json!({"program": "G0 X5", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let mda = server.get(&active(&id, "")).await.body;
    assert_eq!(
        (mda["mode"].clone(), mda["name"].clone(), mda["lines"].clone()),
        (json!("MDA"), Value::Null, json!(["G0 X5"]))
    );
    assert_eq!(mda["serial"], 1);
    server.post_empty(&format!("/sessions/{id}/reset")).await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "AUTO"})).await;
    // A text run without a name that equals a stored program is shown under its name.
    let text = "G0 X1\nG0 X2\nM30\n";
    let put = server.put(&format!("/sessions/{id}/programs/WORK.MPF"), json!({"text": text})).await;
    assert!(put.status.is_success(), "{}", put.body);
    run(&server, &id, json!({"program": text, "pace": "fast", "wait": true})).await;
    let auto = server.get(&active(&id, "")).await.body;
    assert_eq!(
        (auto["mode"].clone(), auto["name"].clone(), auto["serial"].clone()),
        (json!("AUTO"), json!("WORK"), json!(2))
    );
}

#[tokio::test]
async fn a_subprograms_lines_come_with_the_call_stack() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let sub = "PROC HOLE\nG1 Z-1 F100\nM0\nG1 Z5\nM17\n";
    let put = server.put(&format!("/sessions/{id}/programs/HOLE.SPF"), json!({"text": sub})).await;
    assert!(put.status.is_success(), "{}", put.body);
    // Line 3 calls HOLE, whose M0 (its line 3) stops the program there.
    let main = "G0 X0 Y0 Z5\nG0 X10\nHOLE\nG0 X20\nM30\n";
    let stopped = run(&server, &id, json!({"program": main, "pace": "fast", "wait": true})).await;
    assert_eq!(stopped["status"], "stopped");
    assert_eq!((stopped["block"]["program"].clone(), stopped["block"]["line"].clone()), (json!("HOLE"), json!(3)));
    let b = server.get(&active(&id, "?program=hole&from=3&count=1")).await.body;
    assert_eq!(
        (b["program"].clone(), b["program_line_count"].clone(), b["lines"].clone()),
        (json!("HOLE"), json!(5), json!(["M0"]))
    );
    assert_eq!(b["line_count"], 5, "the main program's line count");
    assert_eq!(b["call_stack"], json!([{"program": null, "line": 3}, {"program": "HOLE", "line": 3}]));
}

#[tokio::test]
async fn a_program_resumed_after_a_restart_is_the_active_program_with_the_same_version() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let text = "G0 X0 Y0 Z10\nG1 X5 F1000\nM0\nG1 X10\nM30\n";
    let put = server.put(&format!("/sessions/{id}/programs/RESUME.MPF"), json!({"text": text})).await;
    assert!(put.status.is_success(), "{}", put.body);
    let stopped = run(&server, &id, json!({"program": text, "pace": "fast", "wait": true, "name": "RESUME"})).await;
    assert_eq!(stopped["status"], "stopped");
    let before = server.get(&active(&id, "")).await.body;
    let dir = server.stop().await;
    let server = Server::start_config(Config::new(dir, common::WEB_DIR)).await;
    let after = server.get(&active(&id, "?count=5")).await;
    assert_eq!(after.status, StatusCode::OK, "{}", after.body);
    let after = after.body;
    assert_eq!(after["sha256"], before["sha256"]);
    assert_eq!((after["name"].clone(), after["mode"].clone()), (json!("RESUME"), json!("AUTO")));
    assert_eq!(after["lines"], json!(["G0 X0 Y0 Z10", "G1 X5 F1000", "M0", "G1 X10", "M30"]));
}

#[tokio::test]
async fn the_preview_of_the_active_program_is_its_path() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    run(&server, &id, json!({"program": "G0 X0 Y0 Z10\nG1 X20 F1000\nG1 Y10\nM30\n", "pace": "fast", "wait": true}))
        .await;
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({"active": true, "max_points": 50})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let last = reply.body["points"].as_array().unwrap().last().unwrap().clone();
    // The path ends at the last programmed point (20, 10, 10).
    assert_eq!(last, json!([20.0, 10.0, 10.0]));
    let both = server.post(&format!("/sessions/{id}/preview"), json!({"active": true, "program": "G0 X1"})).await;
    error_message(&both, StatusCode::BAD_REQUEST);
}

#[tokio::test]
async fn a_stored_program_runs_by_name_without_its_text_in_the_request() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // Larger than a run's body limit (1 MiB): stored first, then run by name.
    let mut text = String::from("G0 X0 Y0 Z10\n");
    for i in 0..60_000 {
        text.push_str(&format!("G1 X{}.{:03} Y1 F100000\n", i % 50, i % 1000));
    }
    text.push_str("M30\n");
    assert!(text.len() > 1 << 20);
    let put = server.put(&format!("/sessions/{id}/programs/CAM1"), json!({"text": text})).await;
    assert!(put.status.is_success(), "{}", put.body);
    let reply = server.post(&format!("/sessions/{id}/run"), json!({"name": "CAM1", "pace": "fast"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let b = server.get(&active(&id, "?from=60001&count=5")).await.body;
    assert_eq!((b["name"].clone(), b["line_count"].clone()), (json!("CAM1"), json!(60_002)));
    assert_eq!(b["lines"], json!(["G1 X49.999 Y1 F100000", "M30"]));
    server.post_empty(&format!("/sessions/{id}/reset")).await;
    let missing = server.post(&format!("/sessions/{id}/run"), json!({"name": "NOSUCH"})).await;
    assert!(error_message(&missing, StatusCode::BAD_REQUEST).contains("NOSUCH"));
    let neither = server.post(&format!("/sessions/{id}/run"), json!({"pace": "fast"})).await;
    error_message(&neither, StatusCode::BAD_REQUEST);
}
