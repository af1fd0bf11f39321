//! `POST /sessions/{id}/preview`: the programmed toolpath from a throwaway copy of the channel.

use crate::common;

use common::{Server, error_message, pos};
use reqwest::StatusCode;
use serde_json::{Value, json};

fn points(body: &Value) -> Vec<[f64; 3]> {
    list(body, "points")
}

fn list(body: &Value, key: &str) -> Vec<[f64; 3]> {
    body[key]
        .as_array()
        .expect("points")
        .iter()
        .map(|p| {
            let a = p.as_array().expect("point");
            [a[0].as_f64().unwrap(), a[1].as_f64().unwrap(), a[2].as_f64().unwrap()]
        })
        .collect()
}

/// Within one sampling step: 8 ms at F1000 is 1000 / 60 * 0.008 = 0.133 mm.
fn near(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 0.14)
}

#[tokio::test]
async fn a_rectangle_comes_back_as_its_corners_and_the_session_does_not_move() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let before = server.get(&format!("/sessions/{id}/state")).await.body;
    // Corners by hand: (0,0,10) after the rapid, (20,0,10), (20,10,10), back to (0,10,10).
    let program = "G0 X0 Y0 Z10\nG1 X20 F1000\nG1 Y10\nG1 X0\nM30\n";
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({ "program": program })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["outcome"], "ended");
    assert_eq!(reply.body["axes"], json!(["X", "Y", "Z"]));
    let pts = points(&reply.body);
    for corner in [[0.0, 0.0, 10.0], [20.0, 0.0, 10.0], [20.0, 10.0, 10.0]] {
        assert!(pts.iter().any(|p| near(*p, corner)), "corner {corner:?} missing from {pts:?}");
    }
    let end = *pts.last().unwrap();
    assert!((0..3).all(|i| (end[i] - [0.0, 10.0, 10.0][i]).abs() < 1e-6), "the end point is exact: {pts:?}");
    // 50 mm at F1000 take 3 s: hundreds of samples, thinned to the straight segments' ends.
    let samples = reply.body["samples"].as_u64().unwrap();
    assert!(samples > 300, "{samples}");
    assert!(pts.len() < 20, "straight lines keep only their ends: {pts:?}");
    // Line 2 moves from X0 to X20: the time is 20 mm / 1000 mm/min = 1.2 s plus the others.
    assert!(reply.body["time"].as_f64().unwrap() > 50.0 / 1000.0 * 60.0);
    let after = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!((after["status"].clone(), after["tick"].clone()), (before["status"].clone(), before["tick"].clone()));
    assert_eq!(pos(&after, "workpiece", "X"), pos(&before, "workpiece", "X"));
}

#[tokio::test]
async fn an_arc_is_sampled_on_its_circle_within_the_point_bound() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // A full circle of radius 10 about the origin in G17, starting at (10, 0).
    let program = "G0 X10 Y0 Z5\nG2 X10 Y0 I-10 J0 F2000\nM30\n";
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({ "program": program, "max_points": 50 })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let pts = points(&reply.body);
    assert!(pts.len() <= 50 && pts.len() > 10, "{}", pts.len());
    let lines = reply.body["lines"].as_array().unwrap();
    let on_arc: Vec<_> = pts.iter().zip(lines).filter(|(_, l)| l.as_u64() == Some(2)).map(|(p, _)| *p).collect();
    assert!(on_arc.len() > 5, "{on_arc:?}");
    for p in on_arc {
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
        assert!((r - 10.0).abs() < 0.01 && (p[2] - 5.0).abs() < 1e-6, "{p:?} is off the circle (r = {r})");
    }
}

#[tokio::test]
async fn a_stored_program_is_previewed_by_name_and_time_is_bounded() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let put = server.put(&format!("/sessions/{id}/programs/SLOW"), json!({ "text": "G1 X400 F10\nM30\n" })).await;
    assert!(put.status.is_success(), "{}", put.body);
    // 400 mm at 10 mm/min would take 2400 s; stopped after 6 s, at X <= 10/60*6 = 1 mm.
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({ "name": "SLOW", "max_time": 6 })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["outcome"], "limit");
    let end = *points(&reply.body).last().unwrap();
    assert!(end[0] > 0.5 && end[0] <= 1.0 + 1e-6, "{end:?}");
}

#[tokio::test]
async fn bad_preview_requests_are_4xx_naming_the_problem() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let path = format!("/sessions/{id}/preview");
    let both = server.post(&path, json!({ "program": "M30", "name": "A" })).await;
    assert!(error_message(&both, StatusCode::BAD_REQUEST).contains("either"));
    let none = server.post(&path, json!({})).await;
    assert!(error_message(&none, StatusCode::BAD_REQUEST).contains("either"));
    let syntax = server.post(&path, json!({ "program": "G1 X10\nIF R1 >\nM30" })).await;
    assert_eq!(syntax.status, StatusCode::BAD_REQUEST, "{}", syntax.body);
    assert_eq!(syntax.body["line"], 2);
    let points = server.post(&path, json!({ "program": "M30", "max_points": 1 })).await;
    assert!(error_message(&points, StatusCode::BAD_REQUEST).contains("max_points"));
    let time = server.post(&path, json!({ "program": "M30", "max_time": 0 })).await;
    assert!(error_message(&time, StatusCode::BAD_REQUEST).contains("max_time"));
    let missing = server.post(&path, json!({ "name": "NOPE" })).await;
    assert!(error_message(&missing, StatusCode::NOT_FOUND).contains("NOPE"));
    let unknown = server.post("/sessions/nope/preview", json!({ "program": "M30" })).await;
    assert_eq!(unknown.status, StatusCode::NOT_FOUND);
}

#[tokio::test]
async fn points_come_in_the_wcs_and_the_bcs_apart_by_the_work_offset() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // G54 shifted by (100, 50, -20): the BCS point is the WCS point plus that offset.
    let md = server
        .put(
            &format!("/sessions/{id}/machine-data"),
            json!({"text": "$P_UIFR[1,X,TR]=100\n$P_UIFR[1,Y,TR]=50\n$P_UIFR[1,Z,TR]=-20"}),
        )
        .await;
    assert_eq!(md.status, StatusCode::OK, "{}", md.body);
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({ "program": "G54 G0 X10 Y20 Z30\nM30" })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let (wcs, bcs) = (points(&reply.body), list(&reply.body, "basic"));
    assert_eq!(wcs.len(), bcs.len());
    let (w, b) = (*wcs.last().unwrap(), *bcs.last().unwrap());
    assert!(near(w, [10.0, 20.0, 30.0]) && near(b, [110.0, 70.0, 10.0]), "WCS {w:?} BCS {b:?}");
}

#[tokio::test]
async fn points_under_tracyl_carry_the_working_diameter_and_the_others_none() {
    let server = Server::start().await;
    let id = server.session("tracyl-xyzc").await;
    // Line 3 selects TRACYL with d = 40; lines 4 and 5 run on the unrolled surface (Y up to 60
    // of arc length), line 6 deselects it and line 7 moves Cartesian again.
    let program = "T1 D1 G19\nG0 X60 Z-20\nTRACYL(40)\nG1 X20 Y0 Z-20 F3000\nG1 Y60\nTRAFOOF\nG0 X60\nM30\n";
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({ "program": program })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["outcome"], "ended", "{}", reply.body);
    let lines: Vec<u64> = reply.body["lines"].as_array().unwrap().iter().map(|l| l.as_u64().unwrap()).collect();
    let diameters = reply.body["tracyl_diameter"].as_array().expect("tracyl_diameter").clone();
    assert_eq!(diameters.len(), lines.len());
    let basic = list(&reply.body, "basic");
    for ((line, d), p) in lines.iter().zip(&diameters).zip(&basic) {
        match line {
            1 | 2 | 7 => assert!(d.is_null(), "line {line} ran without TRACYL: {d}"),
            4 | 5 => assert_eq!(d.as_f64(), Some(40.0), "line {line} at {p:?}"),
            _ => {}
        }
    }
    // Line 5 runs on the unrolled surface up to Y = 60 mm of arc, under d = 40: its last sample
    // lies within one sampling step of the end (8 ms at F3000 = 3000 / 60 * 0.008 = 0.4 mm).
    let end = lines.iter().zip(&diameters).zip(&basic).rfind(|((l, _), _)| **l == 5).expect("line 5 sampled");
    assert!(
        (end.1[1] - 60.0).abs() < 0.4 && (end.1[0] - 20.0).abs() < 1e-9 && end.0.1.as_f64() == Some(40.0),
        "{end:?}"
    );
}

#[tokio::test]
async fn a_preview_runs_before_the_axes_are_referenced() {
    // Z starts unreferenced (incremental encoder): NC start of the session is locked (16905),
    // but the preview draws the path, as Operate's simulation does, and the session stays
    // unreferenced.
    let server = Server::start().await;
    let created =
        server.post("/sessions", json!({"machine": "mill-3axis", "machine_data": "$MA_ENC_REFP_STATE[Z]=0"})).await;
    let id = created.body["id"].as_str().expect("id").to_string();
    let program = "G0 X0 Y0 Z10\nG1 X20 F1000\nM30\n";
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({ "program": program })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["outcome"], "ended");
    let end = *points(&reply.body).last().unwrap();
    assert!((0..3).all(|i| (end[i] - [20.0, 0.0, 10.0][i]).abs() < 1e-6), "{end:?}");
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["referenced"]["Z"], false);
}
