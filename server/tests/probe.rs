//! The probe-target planes of MEAS/MEAW over REST (`GET/PUT .../probe-targets`), over a real
//! socket on port 0.

use crate::common;

use common::Server;
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn a_plane_put_over_rest_stops_a_meas_block_where_the_tool_touches_it() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let empty = server.get(&format!("/sessions/{id}/probe-targets")).await;
    assert_eq!((empty.status, &empty.body), (StatusCode::OK, &json!({"planes": []})));

    // The plane x = 30 with the material on +X; the normal is stored with length 1.
    let put = server
        .put(&format!("/sessions/{id}/probe-targets"), json!({"planes": [{"point": [30, 0, 0], "normal": [-4, 0, 0]}]}))
        .await;
    assert_eq!(put.status, StatusCode::OK, "{}", put.body);
    assert_eq!(put.body["planes"][0]["normal"], json!([-1.0, 0.0, 0.0]));

    // T1 D1 of the preset is an end mill R5 used as the probe's ball: it touches when its
    // centre is at X = 30 − 5 = 25, and MEAS ends the block there (machine X = WCS X).
    let program = "T1 D1\nG0 X0 Y0 Z50\nMEAS=1 G1 X50 F2000\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let x = state.body["positions"]["machine"]["X"].as_f64().expect("X");
    assert!((x - 25.0).abs() < 1e-6, "stopped at X{x}");

    for bad in [
        json!({"planes": [{"point": [0, 0, 0], "normal": [0, 0, 0]}]}),
        json!({"planes": [{"point": [0, 0], "normal": [1, 0, 0]}]}),
    ] {
        let reply = server.put(&format!("/sessions/{id}/probe-targets"), bad.clone()).await;
        assert_eq!(reply.status, StatusCode::BAD_REQUEST, "{bad}: {}", reply.body);
    }
}
