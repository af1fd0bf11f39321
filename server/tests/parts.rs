//! The workpiece counters and program runtimes over REST: the state's `parts` and `runtimes`,
//! `PUT .../parts`, and a restart that keeps them. Values by hand: one M30 is one part, a
//! dwell of G4 F0.5 is half a second of cycle time.

use crate::common;

use common::{Server, error_message};
use nctwin_server::Config;
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn a_program_counts_a_part_the_operator_sets_the_counts_and_a_restart_keeps_them() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "$AC_REQUIRED_PARTS=5\nG4 F0.5\nM30";
    let run =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    assert_eq!(run.body["parts"], json!({"required": 5, "total": 0, "actual": 1, "special": 0}));
    let cycle = run.body["runtimes"]["cycle"].as_f64().expect("cycle time");
    assert!((0.5 - 1e-9..0.52).contains(&cycle), "{cycle}");
    assert_eq!(run.body["runtimes"]["operating"].as_f64(), Some(cycle));
    assert_eq!(run.body["runtimes"]["cutting"].as_f64(), Some(0.0));

    // Absent fields keep their value.
    let set = server.put(&format!("/sessions/{id}/parts"), json!({"actual": 4, "special": 9})).await;
    assert_eq!(set.status, StatusCode::OK, "{}", set.body);
    assert_eq!(set.body["parts"], json!({"required": 5, "total": 0, "actual": 4, "special": 9}));

    // The fifth part reaches the setpoint: alarm 21800, the actual count starts from 0.
    let run =
        server.post(&format!("/sessions/{id}/run"), json!({"program": "M30", "pace": "fast", "wait": true})).await;
    assert_eq!(run.body["parts"]["actual"], 0, "{}", run.body);
    assert_eq!(run.body["alarms"][0]["number"], 21800, "{}", run.body);

    for bad in [json!({"actual": 1_000_000_000}), json!({"total": -1}), json!({"actual": 1.5}), json!({"parts": 1})] {
        let reply = server.put(&format!("/sessions/{id}/parts"), bad.clone()).await;
        error_message(&reply, StatusCode::BAD_REQUEST);
    }
    let unknown = server.put("/sessions/nope/parts", json!({"actual": 1})).await;
    error_message(&unknown, StatusCode::NOT_FOUND);

    let before = server.get(&format!("/sessions/{id}/state")).await.body;
    let dir = server.stop().await;
    let server = Server::start_config(Config::new(dir, common::WEB_DIR)).await;
    let after = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(after["parts"], before["parts"]);
    assert_eq!(after["runtimes"], before["runtimes"]);
}
