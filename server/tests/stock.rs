//! Material removal over REST: a blank defined by `PUT .../stock` and by `WORKPIECE`, the volumes
//! and checks of `GET .../stock` and the state, the binary STL of `GET .../stock.stl`, over a
//! real socket on port 0.

mod common;

use common::{Server, error_message};
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn a_rapid_through_a_blank_put_over_rest_is_reported_and_the_stock_downloads_as_stl() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // No blank yet: no stock, no STL.
    let report = server.get(&format!("/sessions/{id}/stock")).await;
    assert_eq!((report.status, report.body["stock"].is_null()), (StatusCode::OK, true), "{}", report.body);
    let stl = reqwest::get(server.url(&format!("/sessions/{id}/stock.stl"))).await.unwrap();
    assert_eq!(stl.status(), StatusCode::NOT_FOUND);

    // The tool above the blank's place first (at power on its tip is at Z−100).
    let state = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "T1 D1\nG0 Z50\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let blank = json!({"shape": "box", "top": 0, "bottom": -20, "x": [-10, 50], "y": [-10, 40]});
    let put = server.put(&format!("/sessions/{id}/stock"), json!({"blank": blank, "depth_limit": 5})).await;
    assert_eq!(put.status, StatusCode::OK, "{}", put.body);
    assert_eq!(put.body["stock"]["initial_volume"], 60000.0);
    assert_eq!(put.body["depth_limit"], 5.0);

    // Line 3: G0 at Z−3 through the block: a slot 10 wide, 60 long, 3 deep.
    let program = "S3000 M3\nG0 X-20 Y15 Z-3\nG0 X60\nG0 Z50\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let report = server.get(&format!("/sessions/{id}/stock")).await.body;
    assert_eq!(report["stock"]["removed"], 1800.0, "{report}");
    // Raised once for the block (at its first segment that cut), with that segment's depth.
    let warnings = report["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{report}");
    assert_eq!(
        (&warnings[0]["check"], &warnings[0]["line"], &warnings[0]["depth"]),
        (&json!("rapid_into_stock"), &json!(3), &json!(3.0))
    );
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["stock"]["last_warning"]["line"], 3, "{state}");

    let stl = reqwest::get(server.url(&format!("/sessions/{id}/stock.stl"))).await.unwrap();
    assert_eq!(stl.status(), StatusCode::OK);
    assert_eq!(stl.headers()["content-type"], "model/stl");
    let bytes = stl.bytes().await.unwrap();
    let triangles = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert!(triangles > 12 && bytes.len() == 84 + 50 * triangles, "{triangles} triangles in {} bytes", bytes.len());

    let gone = server.delete(&format!("/sessions/{id}/stock")).await;
    assert!(gone.body["stock"].is_null(), "{}", gone.body);
}

#[tokio::test]
async fn a_bad_blank_or_resolution_is_refused_naming_it() {
    let server = Server::start().await;
    let id = server.session("lathe-2axis").await;
    let box_on_lathe = json!({"blank": {"shape": "box", "top": 0, "bottom": -20, "x": [0, 10], "y": [0, 10]}});
    let reply = server.put(&format!("/sessions/{id}/stock"), box_on_lathe).await;
    assert!(error_message(&reply, StatusCode::BAD_REQUEST).contains("CYLINDER"), "{}", reply.body);
    let reply = server.put(&format!("/sessions/{id}/stock"), json!({"resolution": 0.001})).await;
    assert!(error_message(&reply, StatusCode::BAD_REQUEST).contains("resolution"), "{}", reply.body);
    let huge =
        json!({"resolution": 0.01, "blank": {"shape": "cylinder", "top": 0, "bottom": -1000000, "diameter": 50}});
    let reply = server.put(&format!("/sessions/{id}/stock"), huge).await;
    assert!(error_message(&reply, StatusCode::BAD_REQUEST).contains("slabs"), "{}", reply.body);
    // Nothing changed: the resolution is still the default.
    assert_eq!(server.get(&format!("/sessions/{id}/stock")).await.body["resolution"], 0.25);
}
