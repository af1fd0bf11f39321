//! `POST /sessions/{id}/check` flags the names a run would refuse, before Cycle start, at
//! their line and column, judged against the session's machine, stored programs and the cycle
//! library; syntax errors are reported as before, in the same list.

use crate::common;

use common::Server;
use reqwest::StatusCode;
use serde_json::{Value, json};

fn findings(body: &Value) -> Vec<(u64, u64, u64)> {
    body["diagnostics"]
        .as_array()
        .expect("diagnostics")
        .iter()
        .map(|d| (d["alarm"].as_u64().unwrap(), d["line"].as_u64().unwrap(), d["column"].as_u64().unwrap()))
        .collect()
}

#[tokio::test]
async fn unknown_names_are_flagged_with_the_alarm_a_run_would_give() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // Line 2: G1234 (12470, column 5); line 3: a syntax error, the value missing after `X=`
    // (12080, column 6); line 4: PART_B is neither a word nor a program (12550, column 1);
    // line 5: L77 is missing (14011); line 6: SINN is no function (12550, column 8 of
    // `G1 X=1+SINN(30)`).
    let program = "G17 G90 F100\nN10 G1234 X1\nG1 X=\nPART_B\nL77\nG1 X=1+SINN(30)\nM30\n";
    let reply = server.post(&format!("/sessions/{id}/check"), json!({ "program": program })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(
        findings(&reply.body),
        vec![(12470, 2, 5), (12080, 3, 6), (12550, 4, 1), (14011, 5, 1), (12550, 6, 8)],
        "{}",
        reply.body
    );
    let message = reply.body["diagnostics"][2]["message"].as_str().unwrap();
    assert!(message.contains("PART_B"), "{message}");
    // Once the session holds PART_B and L77, only the G function, the syntax error and SINN
    // are left.
    for name in ["PART_B", "L77"] {
        let put = server.put(&format!("/sessions/{id}/programs/{name}"), json!({"text": "G1 X2\nM17"})).await;
        assert_eq!(put.status, StatusCode::OK, "{}", put.body);
    }
    let again = server.post(&format!("/sessions/{id}/check"), json!({ "program": program })).await.body;
    assert_eq!(findings(&again), vec![(12470, 2, 5), (12080, 3, 6), (12550, 6, 8)], "{again}");
}

#[tokio::test]
async fn the_machine_decides_which_axis_names_exist() {
    // A lathe has no Y: `G0 Y10` is 12550 there (column 4), and fine on the mill.
    let server = Server::start().await;
    let lathe = server.session("lathe-2axis").await;
    let mill = server.session("mill-3axis").await;
    let program = json!({"program": "G0 X10\nG0 Y10\nM30"});
    let on_lathe = server.post(&format!("/sessions/{lathe}/check"), program.clone()).await.body;
    assert_eq!(findings(&on_lathe), vec![(12550, 2, 4)], "{on_lathe}");
    let on_mill = server.post(&format!("/sessions/{mill}/check"), program).await.body;
    assert_eq!(on_mill, json!({"diagnostics": []}));
}

#[tokio::test]
async fn declared_names_labels_and_library_cycles_pass() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "DEF REAL DEPTH=5\nG17 G90 F200\nG0 X3 Y4 Z20\nCYCLE81(10,0,2,-DEPTH)\nIF DEPTH>2 GOTOF LATER\n\
                   R1=$PI\nLATER:\nM30\n";
    let reply = server.post(&format!("/sessions/{id}/check"), json!({ "program": program })).await;
    assert_eq!(reply.body, json!({"diagnostics": []}));
}
