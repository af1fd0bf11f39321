//! `POST .../set-wo`: Set WO of the JOG area over REST. Values by hand: WCS = BCS − TR of G500.

use crate::common;

use common::{Server, error_message, pos};
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn set_wo_makes_the_axis_read_the_typed_value_and_is_refused_while_running() {
    let server = Server::start().await;
    let created = server.post("/sessions", json!({"machine": "mill-3axis"})).await;
    let id = created.body["id"].as_str().expect("id").to_string();
    let run = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X40 Y15\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    let set = server.post(&format!("/sessions/{id}/set-wo"), json!({"axis": "X", "value": 10.0})).await;
    assert_eq!(set.status, StatusCode::OK, "{}", set.body);
    // X reads 10 (G500 TR X = 30), the machine stays at 40; Y untouched.
    assert_eq!(pos(&set.body, "workpiece", "X"), 10.0);
    assert_eq!(pos(&set.body, "machine", "X"), 40.0);
    assert_eq!(pos(&set.body, "workpiece", "Y"), 15.0);
    // The frame data shows the new offset.
    let md = server.get(&format!("/sessions/{id}/machine-data")).await;
    assert!(md.body["text"].as_str().unwrap_or("").contains("$P_UIFR[0,X,TR]=30"), "{}", md.body);
    let unknown = server.post(&format!("/sessions/{id}/set-wo"), json!({"axis": "Q", "value": 1.0})).await;
    error_message(&unknown, StatusCode::BAD_REQUEST);
    let started =
        server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X200 F100\nM30", "pace": "realtime"})).await;
    assert_eq!(started.status, StatusCode::OK, "{}", started.body);
    let busy = server.post(&format!("/sessions/{id}/set-wo"), json!({"axis": "X", "value": 0.0})).await;
    assert!(error_message(&busy, StatusCode::CONFLICT).contains("reset state"));
}
