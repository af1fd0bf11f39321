//! `GET /sessions/{id}/frames`: the active frame chain over a real socket on port 0.

use crate::common;

use common::Server;
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn the_frame_chain_shows_the_settable_and_programmable_frame_and_their_total() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let put = server.put(&format!("/sessions/{id}/machine-data"), json!({"text": "$P_UIFR[1,X,TR]=100\n"})).await;
    assert_eq!(put.status, StatusCode::OK, "{}", put.body);
    // G54 (X100) then TRANS Z-5: the total is X100 Z-5. Preparation ends with the program.
    let program = "G54\nTRANS Z-5\nG0 X0 Y0 Z10\nM0\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.status, StatusCode::OK, "{}", state.body);
    let chain = server.get(&format!("/sessions/{id}/frames")).await;
    assert_eq!(chain.status, StatusCode::OK, "{}", chain.body);
    assert_eq!((&chain.body["axes"][0], &chain.body["axes"][2]), (&json!("X"), &json!("Z")));
    let links = chain.body["links"].as_array().unwrap();
    let link = |name: &str| links.iter().find(|l| l["name"] == name).unwrap_or_else(|| panic!("{name} in {links:?}"));
    assert_eq!(link("$P_IFRAME")["trans"][0], 100.0);
    assert_eq!(link("$P_PFRAME")["trans"][2], -5.0);
    assert_eq!(link("$P_ACTBFRAME")["neutral"], true);
    let total = link("$P_ACTFRAME");
    assert_eq!((&total["trans"][0], &total["trans"][2]), (&json!(100.0), &json!(-5.0)));
    assert_eq!(links.last().unwrap()["name"], "$P_ACTFRAME");
}
