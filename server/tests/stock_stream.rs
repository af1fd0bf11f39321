//! The stock's changes pushed on the stream (issue 28): after a state showing a new stock
//! version come `{"type": "stock"}` messages with the tiles cut since the version before and
//! their meshes, so the HMI need not poll REST.

use crate::common;

use std::time::Duration;

use common::Server;
use futures_util::StreamExt;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

#[tokio::test]
async fn the_stream_pushes_the_tiles_a_cut_changed_with_their_meshes() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let (mut socket, _) = connect_async(server.ws_url(&format!("/sessions/{id}/stream?period_ms=20"))).await.unwrap();
    // The 60 x 50 block from X−10 Y−10 (tiles of 64 cells of 0.25 mm, 16 mm: 4 x 4); T1 (R5)
    // plunges at X5 Y5 and reaches X0..10, Y0..10: tiles [0, 0], [1, 0], [0, 1], [1, 1].
    let program = "T1 D1\nG0 X5 Y5 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS3000 M3\nG0 Z2\nG1 Z-2 F3000\nG0 Z50\nM30";
    let run = server.post(&format!("/sessions/{id}/run"), json!({"program": program})).await;
    assert_eq!(run.body["status"], "running", "{}", run.body);
    let mut pushes: Vec<Value> = Vec::new();
    let mut ran = false;
    let last_state = loop {
        let message = tokio::time::timeout(Duration::from_secs(20), socket.next()).await.expect("in time");
        let Some(Ok(Message::Text(text))) = message else { continue };
        let m: Value = serde_json::from_str(&text).unwrap();
        match m["type"].as_str() {
            Some("stock") => pushes.push(m),
            Some("state") => {
                ran |= m["status"] == "running";
                if ran && m["status"] == "idle" {
                    break m;
                }
            }
            _ => {}
        }
    };
    // A chain of versions from the blank (since 0: every tile named, the first four with
    // their meshes) to the version of the last state, each message starting where the last
    // one ended; no reload was needed.
    assert!(!pushes.is_empty());
    assert!(pushes.iter().all(|p| p["reload"] == false), "{pushes:?}");
    assert_eq!((&pushes[0]["since"], pushes[0]["tiles"].as_array().unwrap().len()), (&json!(0), 16));
    assert_eq!(pushes[0]["meshes"].as_array().unwrap().len(), 4);
    for w in pushes.windows(2) {
        assert_eq!(w[1]["since"], w[0]["version"]);
    }
    let last = pushes.last().unwrap();
    assert_eq!(last["version"], last_state["stock"]["version"]);
    // The cut changed exactly the four tiles round the plunge, each pushed with its mesh, the
    // same bytes the REST tile has, coloured by pen 1 = T1 D1.
    let mut cut: Vec<Value> = pushes[1..].iter().flat_map(|p| p["tiles"].as_array().unwrap().clone()).collect();
    cut.sort_by_key(|t| (t[1].as_u64(), t[0].as_u64()));
    cut.dedup();
    assert_eq!(Value::Array(cut), json!([[0, 0], [1, 0], [0, 1], [1, 1]]));
    assert_eq!(last["pens"], json!([{"pen": 1, "t": 1, "d": 1}]));
    let mesh = |i: u64, j: u64| {
        pushes.iter().rev().flat_map(|p| p["meshes"].as_array().unwrap()).find(|m| m["i"] == i && m["j"] == j).cloned()
    };
    let tile = reqwest::get(server.url(&format!("/sessions/{id}/stock/tiles/1/1"))).await.unwrap();
    let bytes = tile.bytes().await.unwrap();
    assert_eq!(mesh(1, 1).expect("tile 1, 1 pushed")["stl"], nctwin_engine::stock::saved::base64(&bytes));
}

#[tokio::test]
async fn a_client_joining_after_the_cut_fetches_over_rest_and_is_not_pushed_old_steps() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "T1 D1\nG0 X5 Y5 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS3000 M3\nG0 Z2\nG1 Z-2 F3000\nG0 Z50\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    let version = state.body["stock"]["version"].clone();
    let (mut socket, _) = connect_async(server.ws_url(&format!("/sessions/{id}/stream"))).await.unwrap();
    let Some(Ok(Message::Text(text))) = socket.next().await else { panic!("the first state") };
    let first: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(first["stock"]["version"], version);
    // Then a facing cut over the whole block: the client, at the version it was shown, gets
    // the steps from there on only.
    let program = "G0 X-20 Y-5 Z-1\nG1 X60 F6000\nG0 Z50\nM30";
    server.post(&format!("/sessions/{id}/run"), json!({"program": program})).await;
    loop {
        let message = tokio::time::timeout(Duration::from_secs(20), socket.next()).await.expect("in time");
        let Some(Ok(Message::Text(text))) = message else { continue };
        let m: Value = serde_json::from_str(&text).unwrap();
        if m["type"] == "stock" {
            assert_eq!(m["since"], version, "{m}");
            assert_eq!(m["reload"], false);
            break;
        }
    }
}
