//! The digital I/O image over REST (`GET/PUT /sessions/{id}/io`) and the M/H functions and
//! output changes a program sends to the event stream, over a real socket on port 0.

use crate::common;

use std::time::Duration;

use common::{Server, error_message};
use futures_util::StreamExt;
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

#[tokio::test]
async fn inputs_set_over_rest_steer_a_program_whose_outputs_read_back() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!(io["inputs"].as_array().map(Vec::len), Some(16), "2 bytes by default (MD10350)");
    assert!(io["outputs"].as_array().unwrap().iter().all(|v| v == false), "all off at power on");

    let reply = server.put(&format!("/sessions/{id}/io"), json!({"inputs": [{"signal": 3, "value": true}]})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["inputs"][2], true, "signal 3 is element 2");

    let program = "IF $A_IN[3] GOTOF CLAMPED\nSETAL(65000)\nCLAMPED: $A_OUT[7]=1\nG0 X5\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!((io["outputs"][6].as_bool(), io["outputs"][5].as_bool()), (Some(true), Some(false)));
}

#[tokio::test]
async fn plc_data_set_over_rest_is_read_by_a_program_and_its_writes_read_back() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // Bytes 10, 11 = 0x12, 0x34: $A_DBW[10] reads 0x1234 = 4660 (big-endian, as the PLC).
    let body = json!({"plc_data": [{"offset": 10, "bytes": [18, 52]}]});
    let reply = server.put(&format!("/sessions/{id}/io"), body).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["plc_data"].as_array().map(Vec::len), Some(12), "up to the last non-zero byte");
    // The program copies the word to bytes 20/21 plus one: 4661 = 0x1235 -> 18, 53.
    let program = "$A_DBW[20]=$A_DBW[10]+1\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!((io["plc_data"][20].as_u64(), io["plc_data"][21].as_u64()), (Some(18), Some(53)));
    // Beyond the 4096 bytes: 400, nothing written.
    let body = json!({"plc_data": [{"offset": 0, "bytes": [1]}, {"offset": 4095, "bytes": [1, 2]}]});
    let reply = server.put(&format!("/sessions/{id}/io"), body).await;
    assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{}", reply.body);
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!(io["plc_data"][0].as_u64(), Some(0));
}

#[tokio::test]
async fn a_signal_outside_the_image_is_refused_and_changes_nothing() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let body = json!({"inputs": [{"signal": 1, "value": true}], "outputs": [{"signal": 41, "value": true}]});
    let reply = server.put(&format!("/sessions/{id}/io"), body).await;
    assert!(error_message(&reply, StatusCode::BAD_REQUEST).contains("signal 41"), "{}", reply.body);
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!(io["inputs"][0], false);
}

#[tokio::test]
async fn m_and_h_functions_and_outputs_are_streamed_as_events() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let (mut socket, _) = connect_async(server.ws_url(&format!("/sessions/{id}/stream"))).await.expect("handshake");
    let program = "G0 X10 M8\nH2=1.5\n$A_OUT[1]=1\nM30";
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast"})).await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    let mut events = Vec::new();
    while !events.iter().any(|e: &Value| e["event"] == "program_ended") {
        let message = tokio::time::timeout(Duration::from_secs(20), socket.next()).await.expect("in time");
        let Some(Ok(Message::Text(text))) = message else { continue };
        let message: Value = serde_json::from_str(&text).expect("JSON");
        if message["type"] == "event" {
            events.push(message);
        }
    }
    let aux: Vec<(String, i64)> = events
        .iter()
        .filter(|e| e["event"] == "aux_function")
        .map(|e| (e["text"].as_str().unwrap().to_string(), e["line"].as_i64().unwrap()))
        .collect();
    assert_eq!(aux, [("M8".to_string(), 1), ("H2=1.5".to_string(), 2), ("M30".to_string(), 4)]);
    let m8 = events.iter().find(|e| e["event"] == "aux_function").unwrap();
    assert_eq!(
        (m8["letter"].as_str(), m8["extension"].as_u64(), m8["value"].as_f64()),
        (Some("M"), Some(0), Some(8.0))
    );
    assert!(
        events
            .iter()
            .any(|e| e["event"] == "digital_output" && e["signal"] == 1 && e["value"] == true && e["line"] == 3),
        "{events:?}"
    );
}
