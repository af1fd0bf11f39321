//! Synchronized actions driven over REST: an input set with `PUT .../io` while a block runs
//! acts in the main run (DELDTG ends the block), the state lists the active actions, the
//! event stream carries the input with its IPO cycle count, and analog inputs are checked.

use crate::common;

use std::time::Duration;

use common::{Server, error_message, pos};
use futures_util::StreamExt;
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

#[tokio::test]
async fn an_input_set_over_rest_deletes_the_distance_to_go_of_the_running_block() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let (mut socket, _) = connect_async(server.ws_url(&format!("/sessions/{id}/stream"))).await.expect("handshake");
    // G1 X100 at 600 mm/min takes 10 s of wall-clock time at real-time pace.
    let program = "ID=1 WHENEVER $AA_IM[X]>200 DO M99\nWHEN $A_IN[1]==1 DO DELDTG\nG1 X100 F600\nG1 Y10\nM30";
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": program})).await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    let state = server.state_until(&id, "X moving", |s| pos(s, "machine", "X") > 1.0).await;
    let actions = state["synchronized_actions"].as_array().expect("listed while active").clone();
    assert_eq!(actions.len(), 2, "{actions:?}");
    assert_eq!(
        (actions[0]["id"].as_u64(), actions[0]["kind"].as_str(), actions[0]["condition"].as_str()),
        (Some(1), Some("modal"), Some("$AA_IM[X]>200"))
    );
    assert_eq!((actions[1]["id"].is_null(), actions[1]["trigger"].as_str()), (true, Some("WHEN")));

    let reply = server.put(&format!("/sessions/{id}/io"), json!({"inputs": [{"signal": 1, "value": true}]})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let state = server.state_until(&id, "program end", |s| s["status"] == "idle").await;
    // The block ended where the input found it: X well short of 100, then Y10 from there.
    let x = pos(&state, "machine", "X");
    assert!(x > 1.0 && x < 90.0, "X = {x}");
    assert!((pos(&state, "machine", "Y") - 10.0).abs() < 1e-9);
    assert!(state.get("synchronized_actions").is_none(), "none active after the end: {state}");

    // The stream told about the input with the cycle count it arrived at.
    let mut change = None;
    while change.is_none() {
        let message = tokio::time::timeout(Duration::from_secs(20), socket.next()).await.expect("in time");
        let Some(Ok(Message::Text(text))) = message else { continue };
        let message: Value = serde_json::from_str(&text).expect("JSON");
        if message["type"] == "event" && message["event"] == "inputs_changed" {
            change = Some(message);
        }
    }
    let change = change.unwrap();
    assert_eq!(change["inputs"], json!([{"signal": 1, "value": true}]));
    assert!(change["tick"].as_u64().is_some_and(|t| t > 0), "{change}");
}

#[tokio::test]
async fn analog_inputs_are_set_and_checked_all_or_nothing() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!(io["analog_inputs"], json!([0.0, 0.0, 0.0, 0.0]));
    let reply =
        server.put(&format!("/sessions/{id}/io"), json!({"analog_inputs": [{"signal": 2, "value": 2.5}]})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["analog_inputs"][1], 2.5);
    // A synchronized action copies it to an analog output.
    let program = "ID=1 DO $A_OUTA[1]=$A_INA[2]*2\nG4 F0.05\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!(io["analog_outputs"][0], 5.0);
    let body = json!({"inputs": [{"signal": 4, "value": true}], "analog_inputs": [{"signal": 5, "value": 1.0}]});
    let reply = server.put(&format!("/sessions/{id}/io"), body).await;
    assert!(error_message(&reply, StatusCode::BAD_REQUEST).contains("analog input 5"), "{}", reply.body);
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    assert_eq!(io["inputs"][3], false, "nothing changed");
}

#[tokio::test]
async fn bad_synchronized_action_syntax_is_a_400_naming_the_line() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "G0 X1\nWHENEVER $AA_IM[X]>20 $AC_OVR=0\nM30";
    let reply = server.post(&format!("/sessions/{id}/run"), json!({"program": program})).await;
    let message = error_message(&reply, StatusCode::BAD_REQUEST);
    assert!(message.contains("line 2") && message.contains("DO expected"), "{message}");
}

#[tokio::test]
async fn the_io_lists_follow_the_machine_data_and_one_beyond_is_a_400_naming_the_limit() {
    // MD10350 = 2 bytes of inputs (16), MD10360 = 1 byte of outputs (8), MD10300 = 6 analog
    // inputs, MD10310 = 2 analog outputs.
    let server = Server::start().await;
    let md = "$MN_FASTIO_DIG_NUM_INPUTS=2\n$MN_FASTIO_DIG_NUM_OUTPUTS=1\n\
              $MN_FASTIO_ANA_NUM_INPUTS=6\n$MN_FASTIO_ANA_NUM_OUTPUTS=2";
    let reply = server.post("/sessions", json!({"machine": "mill-3axis", "machine_data": md})).await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    let id = reply.body["id"].as_str().expect("id").to_string();
    let io = server.get(&format!("/sessions/{id}/io")).await.body;
    let len = |key: &str| io[key].as_array().map(Vec::len);
    assert_eq!(
        (len("inputs"), len("outputs"), len("analog_inputs"), len("analog_outputs")),
        (Some(16), Some(8), Some(6), Some(2))
    );
    let last = json!({"inputs": [{"signal": 16, "value": true}], "outputs": [{"signal": 8, "value": true}],
                      "analog_inputs": [{"signal": 6, "value": 1.5}]});
    let reply = server.put(&format!("/sessions/{id}/io"), last).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!((&reply.body["inputs"][15], &reply.body["analog_inputs"][5]), (&json!(true), &json!(1.5)));
    for (body, limit) in [
        (json!({"inputs": [{"signal": 17, "value": true}]}), "1..16"),
        (json!({"outputs": [{"signal": 9, "value": true}]}), "1..8"),
        (json!({"analog_inputs": [{"signal": 7, "value": 1.0}]}), "1..6"),
    ] {
        let reply = server.put(&format!("/sessions/{id}/io"), body).await;
        let message = error_message(&reply, StatusCode::BAD_REQUEST);
        assert!(message.contains(limit), "{message}");
    }
}
