//! Block search and restart inside subprograms over REST (issue 20, defect 6; the current block
//! of defect 11): a program stopped inside a subprogram, after more than 200,000 blocks, comes
//! back there after a restart; a search goes into subprograms (`path`) and to a calling line.

use crate::common;

use common::{Server, pos};
use nctwin_server::{Config, Limits};
use reqwest::StatusCode;
use serde_json::{Value, json};

/// The 300,000 blocks take seconds in a debug build on a loaded 2-core machine, more than the
/// default 10 s a fast run may take; the test is about where the run stops, not how fast.
fn patient() -> Limits {
    Limits { fast_wall_time: std::time::Duration::from_secs(300), ..Limits::default() }
}

async fn restart(server: Server) -> Server {
    let dir = server.stop().await;
    Server::start_config(Config { limits: patient(), ..Config::new(dir, common::WEB_DIR) }).await
}

/// 100,000 passes of a three-block loop (300,000 blocks), X1, then HOLE (line 6), then M30.
const MAIN: &str = "R1=0\nWHILE R1<100000\nR1=R1+1\nENDWHILE\nG0 X1\nHOLE\nM30";
/// HOLE: Y1, R5 and R6 computed, a programmed stop at line 4, then Z-5.
const HOLE: &str = "G0 Y1\nR5=7\nR6=R5+1\nM0\nG0 Z-5\nM17";

async fn session_with_hole(server: &Server) -> String {
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/programs/hole.spf"), json!({"text": HOLE})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    id
}

fn xyz(state: &Value) -> [f64; 3] {
    ["X", "Y", "Z"].map(|a| pos(state, "machine", a))
}

#[tokio::test]
async fn a_program_stopped_inside_a_subprogram_after_300000_blocks_resumes_there_after_a_restart() {
    let server = Server::start_with(patient()).await;
    let id = session_with_hole(&server).await;
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": MAIN, "pace": "fast", "wait": true})).await;
    let state = reply.body;
    assert_eq!(state["status"], "stopped", "{state}");
    // The current block is HOLE's line 4 with HOLE's text (the main program's line 4 is ENDWHILE).
    assert_eq!(state["block"], json!({"line": 4, "text": "M0", "program": "HOLE"}));

    let server = restart(server).await;
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["alarms"], json!([]), "{state}");
    assert_eq!(state["status"], "stopped", "{state}");
    assert_eq!(state["block"], json!({"line": 4, "text": "M0", "program": "HOLE"}));
    assert_eq!(xyz(&state), [1.0, 1.0, 0.0]);
    // The M0 was executed before the restart: NC start goes on behind it (Z-5), returns to the
    // main program and ends.
    let reply = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    assert_eq!(xyz(&reply.body), [1.0, 1.0, -5.0]);
}

#[tokio::test]
async fn a_search_to_a_calling_line_stops_before_the_call_and_a_path_goes_into_the_subprogram() {
    let server = Server::start().await;
    let id = session_with_hole(&server).await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "AUTO"})).await;
    let main = "G0 X1\nHOLE\nM30";

    // The calling line is the target: no 15370, nothing of HOLE ran yet.
    let reply = server.post(&format!("/sessions/{id}/search"), json!({"line": 2, "program": main})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["alarms"], json!([]), "{}", reply.body);
    assert_eq!(reply.body["status"], "stopped");
    assert_eq!(reply.body["block"], json!({"line": 2, "text": "HOLE", "program": null}));
    let reply = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    // HOLE runs from its start and stops at its M0.
    assert_eq!(reply.body["block"], json!({"line": 4, "text": "M0", "program": "HOLE"}));
    assert_eq!(xyz(&reply.body), [1.0, 1.0, 0.0]);
    server.post_empty(&format!("/sessions/{id}/reset")).await;

    // Into HOLE: its line 5 as called by line 2 (the name as stored or with its ending).
    let body = json!({"line": 2, "program": main, "path": [{"program": "hole.spf", "line": 5}]});
    let reply = server.post(&format!("/sessions/{id}/search"), body).await;
    assert_eq!(reply.body["alarms"], json!([]), "{}", reply.body);
    assert_eq!(reply.body["block"], json!({"line": 5, "text": "G0 Z-5", "program": "HOLE"}));
    let reply = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    // HOLE's M0 was before the target: skipped. Approach to (1, 1, 0), then Z-5, then M30.
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    assert_eq!(xyz(&reply.body), [1.0, 1.0, -5.0]);

    // A step into a program that is not stored, or a line it does not have: 400.
    for path in [json!([{"program": "NOPE", "line": 1}]), json!([{"program": "HOLE", "line": 99}])] {
        let reply =
            server.post(&format!("/sessions/{id}/search"), json!({"line": 2, "program": main, "path": path})).await;
        assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    }
}
