//! The executed path a late viewer fetches (`GET .../path-history`): thinned by geometry, the
//! same in fast pace and in real time, and true on a turned table; the preview's limit marks
//! under TRACYL carry their diameter. Values worked out by hand in the comments.

use crate::common;

use common::Server;
use reqwest::StatusCode;
use serde_json::{Value, json};

fn point(v: &Value) -> [f64; 3] {
    std::array::from_fn(|k| v[k].as_f64().unwrap())
}

async fn history_after(server: &Server, preset: &str, program: &str, pace: &str) -> Value {
    let id = server.session(preset).await;
    let run =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": pace, "wait": true})).await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    server.get(&format!("/sessions/{id}/path-history")).await.body
}

#[tokio::test]
async fn a_circle_run_fast_and_in_real_time_gives_the_same_fine_path() {
    let server = Server::start().await;
    // A full circle of radius 10 about X10 Y0 (0.63 s at F6000). Within the display tolerance
    // of 0.01 mm a chord is at most 2·√(10² − 9.99²) = 0.894 mm: the 62.8 mm circle needs at
    // least 71 chords, however coarse the published states of a fast run are.
    let program = "G0 X0 Y0 Z0\nG2 X0 Y0 I10 J0 F6000\nM30";
    let fast = history_after(&server, "mill-3axis", program, "fast").await;
    let live = history_after(&server, "mill-3axis", program, "realtime").await;
    let (f, l) = (fast["points"].as_array().unwrap(), live["points"].as_array().unwrap());
    assert!(f.len() >= 72, "{}", f.len());
    assert_eq!(f.len(), l.len(), "fast {fast}\nlive {live}");
    for (a, b) in f.iter().zip(l) {
        let (a, b) = (point(a), point(b));
        assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-9), "{a:?} {b:?}");
    }
    // Every kept point on the circle (the arc's own interpolation error is far below 1 µm).
    for p in f.iter().map(point).filter(|p| p != &[0.0, 0.0, 0.0]) {
        let r = ((p[0] - 10.0).powi(2) + p[1].powi(2)).sqrt();
        assert!((r - 10.0).abs() < 1e-3, "{p:?} r {r}");
    }
    assert_eq!(fast["exact"].as_array().unwrap().iter().filter(|e| **e != json!(true)).count(), 0);
}

#[tokio::test]
async fn on_a_table_turned_without_traori_the_path_is_drawn_on_the_table() {
    let server = Server::start().await;
    // mill5-table-ac, no TRAORI: the tool tip stands at X10 Y0 Z50 (machine Z 150 with T1
    // L100) while C turns the table by 90° (DIN-reversed type 33: the tool moves +90° about
    // +Z relative to the part, about the table centre X0 Y0). On the table the tip runs a
    // quarter circle of radius 10 from X10 Y0 to X0 Y10, where the BCS stays at X10 Y0.
    let h = history_after(&server, "mill5-table-ac", "T1 D1\nG0 X10 Y0 Z50\nG1 C90 F3000\nM30", "fast").await;
    let points: Vec<[f64; 3]> = h["points"].as_array().unwrap().iter().map(point).collect();
    let last = points.last().unwrap();
    assert!((last[0]).abs() < 1e-6 && (last[1] - 10.0).abs() < 1e-6 && (last[2] - 50.0).abs() < 1e-6, "{h}");
    let on_arc = points.iter().filter(|p| (p[2] - 50.0).abs() < 1e-6).collect::<Vec<_>>();
    assert!(on_arc.len() >= 10, "a quarter of 15.7 mm needs at least 18 chords of 0.894 mm: {h}");
    for p in on_arc {
        assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 10.0).abs() < 1e-6, "{p:?}");
    }
}

#[tokio::test]
async fn a_limit_mark_under_tracyl_carries_its_diameter() {
    let server = Server::start().await;
    let id = server.session("tracyl-xyzac").await;
    // TRACYL(40) with A at −90° (C along +Y): the tip at X20 (radial, on the surface) Y0 (arc
    // length 0); Z (along the cylinder, on YM) asked for F100000 runs YM into its limits. The
    // marks are on the unrolled surface at X20 Y0, Z between 0 and 60, with the diameter 40.
    let program = "T1 D1\nG0 X20 Y0 Z0\nG1 A-90 F5000\nTRACYL(40)\nG1 X20 Y0 Z0\nG1 Z60 F100000\nTRAFOOF\nM30";
    let r = server.post(&format!("/sessions/{id}/preview"), json!({"program": program})).await;
    assert_eq!(r.status, StatusCode::OK, "{}", r.body);
    let hits = r.body["limit_hits"].as_array().unwrap();
    let in_line_6: Vec<&Value> = hits.iter().filter(|h| h["line"] == 6).collect();
    assert!(!in_line_6.is_empty(), "{}", r.body);
    for h in in_line_6 {
        assert_eq!(h["tracyl_diameter"].as_f64(), Some(40.0), "{h}");
        assert_eq!(h["exact"], json!(true), "{h}");
        let p = point(&h["basic"]);
        assert!((p[0] - 20.0).abs() < 1e-6 && p[1].abs() < 1e-6 && (0.0..=60.0).contains(&p[2]), "{h}");
    }
}
