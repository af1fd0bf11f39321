//! Stored programs over HTTP: create, read, list, update, delete, call by name, check.

use crate::common;

use common::{Server, pos};
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn a_stored_subprogram_is_called_by_name_with_parameters() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let sub = "PROC MOVE_TO(REAL XP, REAL YP)\nG0 X=XP Y=YP\nRET";
    let reply = server.put(&format!("/sessions/{id}/programs/move_to.spf"), json!({ "text": sub })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["name"], "MOVE_TO");
    let run = json!({"program": "MOVE_TO(12, 2*3)\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!(state["status"], "idle", "{state}");
    assert_eq!((pos(&state, "machine", "X"), pos(&state, "machine", "Y")), (12.0, 6.0));
}

#[tokio::test]
async fn programs_are_listed_read_replaced_and_deleted() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/B"), json!({"text": "G0 X1"})).await.status,
        StatusCode::OK
    );
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/A"), json!({"text": "G0 X2"})).await.status,
        StatusCode::OK
    );
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/A"), json!({"text": "G0 X33"})).await.status,
        StatusCode::OK
    );
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "A", "size": 6}, {"name": "B", "size": 5}]));
    assert_eq!(server.get(&format!("/sessions/{id}/programs/a")).await.body["text"], "G0 X33");
    assert_eq!(server.delete(&format!("/sessions/{id}/programs/A")).await.status, StatusCode::NO_CONTENT);
    assert_eq!(server.get(&format!("/sessions/{id}/programs/A")).await.status, StatusCode::NOT_FOUND);
    assert_eq!(server.delete(&format!("/sessions/{id}/programs/A")).await.status, StatusCode::NOT_FOUND);
}

#[tokio::test]
async fn bad_names_and_programs_with_syntax_errors_are_refused() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/programs/A-BC"), json!({"text": "G0 X1"})).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    let reply = server.put(&format!("/sessions/{id}/programs/CON"), json!({"text": "G0 X1"})).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    let reply = server.put(&format!("/sessions/{id}/programs/OK"), json!({"text": "G0 X1\nG1 X=\n"})).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST);
    assert_eq!(reply.body["line"], 2);
    assert_eq!(server.get(&format!("/sessions/{id}/programs")).await.body, json!([]));
    // A name may start with digits (a part number), as the Programming Manual allows.
    let reply = server.put(&format!("/sessions/{id}/programs/4711_OP10"), json!({"text": "G0 X1"})).await;
    assert!(reply.status.is_success(), "{}", reply.body);
}

#[tokio::test]
async fn check_reports_every_syntax_error_with_line_and_column() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post(&format!("/sessions/{id}/check"), json!({"program": "G0 X1\nG1 X=\nN10 G1 #\n"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let d = reply.body["diagnostics"].as_array().expect("diagnostics").clone();
    assert_eq!(d.len(), 2);
    assert_eq!((d[0]["line"].as_u64(), d[1]["line"].as_u64()), (Some(2), Some(3)));
    // `#` is the 8th character of `N10 G1 #`; both are syntax errors (alarm 12080).
    assert_eq!(d[1]["column"], 8);
    assert_eq!((d[0]["alarm"].as_u64(), d[1]["alarm"].as_u64()), (Some(12080), Some(12080)));
    let clean = server.post(&format!("/sessions/{id}/check"), json!({"program": "G0 X1"})).await.body;
    assert_eq!(clean, json!({"diagnostics": []}));
}

#[tokio::test]
async fn the_standard_cycle_library_is_listed_readable_and_callable() {
    let server = Server::start().await;
    let list = server.get("/cycles").await.body;
    assert!(list.as_array().unwrap().iter().any(|c| c["name"] == "CYCLE81"), "{list}");
    let cycle = server.get("/cycles/cycle81").await;
    assert_eq!(cycle.status, StatusCode::OK);
    assert!(cycle.body["text"].as_str().unwrap().contains("PROC CYCLE81("), "{}", cycle.body);
    assert_eq!(server.get("/cycles/NO_SUCH_CYCLE").await.status, StatusCode::NOT_FOUND);
    // Called from a program of a session: RTP 10, RFP 0, SDIS 2, DP -5 ends at the retraction plane.
    let id = server.session("mill-3axis").await;
    let run = json!({"program": "G17 G90 F500\nG0 X3 Y4 Z20\nCYCLE81(10,0,2,-5)\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!(state["status"], "idle", "{state}");
    assert_eq!((pos(&state, "machine", "X"), pos(&state, "machine", "Z")), (3.0, 10.0));
    // The library is not one of the session's stored programs.
    assert_eq!(server.get(&format!("/sessions/{id}/programs")).await.body, json!([]));
}

#[tokio::test]
async fn a_session_program_may_take_the_name_of_a_library_cycle() {
    // Before, the library's text counted as the replaced program of the same name, and the
    // byte accounting underflowed (a panic in the session's task).
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    assert_eq!(server.get(&format!("/sessions/{id}/programs/CYCLE81")).await.status, StatusCode::NOT_FOUND);
    let own = "PROC CYCLE81(REAL RTP, REAL RFP, REAL SDIS, REAL DP)\nG0 Z=RTP+1\nM17";
    let reply = server.put(&format!("/sessions/{id}/programs/CYCLE81"), json!({ "text": own })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(
        server.get(&format!("/sessions/{id}/programs")).await.body,
        json!([{"name": "CYCLE81", "size": own.len()}])
    );
    let run = json!({"program": "G0 X0 Y0 Z50\nCYCLE81(10,0,2,-5)\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!(pos(&state, "machine", "Z"), 11.0, "the session's CYCLE81 ran: {state}");
}
