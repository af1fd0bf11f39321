//! Material removal over REST: a blank defined by `PUT .../stock` and by `WORKPIECE`, the volumes
//! and checks of `GET .../stock` and the state, the binary STL of `GET .../stock.stl`, over a
//! real socket on port 0.

use crate::common;
use crate::stl_support;

use common::{Server, error_message};
use reqwest::StatusCode;
use serde_json::json;
use stl_support::box_stl;

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

#[tokio::test]
async fn an_stl_blank_a_holder_and_a_target_comparison_over_rest() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let client = reqwest::Client::new();
    let state = server
        .post(
            &format!("/sessions/{id}/run"),
            json!({"program": "T1 D1\nG0 X20 Y15 Z50\nM30", "pace": "fast", "wait": true}),
        )
        .await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    // The blank as an STL: 60 x 50 x 20.
    let put = client
        .put(server.url(&format!("/sessions/{id}/stock.stl")))
        .body(box_stl([-10.0, -10.0, -20.0], [50.0, 40.0, 0.0]))
        .send()
        .await
        .unwrap();
    assert_eq!(put.status(), StatusCode::OK);
    let body: serde_json::Value = put.json().await.unwrap();
    assert_eq!(body["stock"]["initial_volume"], 60000.0, "{body}");
    // Not an STL: 400 naming it.
    let bad = client
        .put(server.url(&format!("/sessions/{id}/stock.stl")))
        .body("solid x\nvertex 1\nendloop\n")
        .send()
        .await
        .unwrap();
    assert_eq!(bad.status(), StatusCode::BAD_REQUEST);
    assert!(bad.text().await.unwrap().contains("STL line 2"));

    // A holder Ø60 × 40 above the gauge line of T1 (L100): a plunge to Z−101 puts its face at
    // Z−1, 1 mm into the block beyond the tool's R5 hole.
    let put = server.put(&format!("/sessions/{id}/stock"), json!({"holder": [[60, 40]]})).await;
    assert_eq!((put.status, &put.body["holder"]), (StatusCode::OK, &json!([[60.0, 40.0]])), "{}", put.body);
    let bad = server.put(&format!("/sessions/{id}/stock"), json!({"holder": [[0, 40]]})).await;
    assert!(error_message(&bad, StatusCode::BAD_REQUEST).contains("section 1"), "{}", bad.body);
    let program = "S3000 M3\nG0 Z2\nG1 Z-101 F5000\nG1 Z2\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let report = server.get(&format!("/sessions/{id}/stock")).await.body;
    let first = &report["warnings"][0];
    assert_eq!((&first["check"], &first["line"]), (&json!("holder_collision"), &json!(3)), "{report}");
    // Raised at the plunge's first segment that touched; the retract of line 4 starts with
    // the holder's face 1 mm deep and T1's shank (it cuts over 3·D = 30 mm, above that a Ø20
    // body up to the gauge line, `stock/body.rs`) through Z−20..−1 of the block: 19 mm on one
    // dexel line, the thickest.
    let second = &report["warnings"][1];
    assert_eq!((&second["line"], &second["depth"]), (&json!(4), &json!(19.0)), "{report}");

    // The target: the block with a Ø10 hole 20 deep would be exact; against the plain block
    // the hole (π·25·20 ≈ 1571 mm³ at the grid's sampling) is all overcut, 20 mm thick.
    let compare = client
        .post(server.url(&format!("/sessions/{id}/stock/compare")))
        .body(box_stl([-10.0, -10.0, -20.0], [50.0, 40.0, 0.0]))
        .send()
        .await
        .unwrap();
    assert_eq!(compare.status(), StatusCode::OK);
    let c: serde_json::Value = compare.json().await.unwrap();
    assert!((c["overcut"].as_f64().unwrap() - 20.0).abs() < 1e-4, "{c}");
    assert!((c["overcut_volume"].as_f64().unwrap() - std::f64::consts::PI * 25.0 * 20.0).abs() < 40.0, "{c}");
    assert_eq!(c["undercut"], 0.0, "{c}");
}

#[tokio::test]
async fn the_hmi_fetches_the_changed_tiles_of_the_stock_coloured_by_pen() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // The 60 x 50 block from X−10 Y−10 (tiles of 64 cells, 16 mm: 4 x 4); T1 plunges at X5 Y5
    // and reaches X0..10, Y0..10: tiles 0..1 in X and Y.
    let program = "T1 D1\nG0 X5 Y5 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS3000 M3\nG0 Z2\nG1 Z-2 F3000\nG0 Z50\nM30";
    let state =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(state.body["status"], "idle", "{}", state.body);
    let version = state.body["stock"]["version"].as_u64().unwrap();
    assert!(version > 1, "{}", state.body);
    let all = server.get(&format!("/sessions/{id}/stock/changes")).await.body;
    assert_eq!((all["tiles"].as_array().unwrap().len(), &all["tile_cells"]), (16, &json!(64)), "{all}");
    let changed = server.get(&format!("/sessions/{id}/stock/changes?since=1")).await.body;
    assert_eq!(changed["tiles"], json!([[0, 0], [1, 0], [0, 1], [1, 1]]), "{changed}");
    assert_eq!(changed["pens"], json!([{"pen": 1, "t": 1, "d": 1}]));
    assert_eq!(changed["version"], version);
    let bad = server.get(&format!("/sessions/{id}/stock/changes?since=x")).await;
    assert_eq!(bad.status, StatusCode::BAD_REQUEST);
    let tile = reqwest::get(server.url(&format!("/sessions/{id}/stock/tiles/0/0"))).await.unwrap();
    assert_eq!((tile.status(), tile.headers()["content-type"].to_str().unwrap()), (StatusCode::OK, "model/stl"));
    let bytes = tile.bytes().await.unwrap();
    let n = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert!((0..n).any(|t| bytes[84 + 50 * t + 48] == 1), "a face cut by pen 1");
    let none = reqwest::get(server.url(&format!("/sessions/{id}/stock/tiles/9/0"))).await.unwrap();
    assert_eq!(none.status(), StatusCode::NOT_FOUND);
    let negative = server.get(&format!("/sessions/{id}/stock/tiles/0/-1")).await;
    assert_eq!(negative.status, StatusCode::BAD_REQUEST);
    assert!(negative.body["error"].as_str().unwrap().contains("tile index j `-1`"), "{}", negative.body);
}
