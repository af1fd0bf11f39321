//! What the HMI's 3D view checks programs with: the preview's limit hits and tool directions,
//! and the executed path a late viewer fetches (`GET .../path-history`), over a real socket.

use crate::common;

use common::Server;
use reqwest::StatusCode;
use serde_json::{Value, json};

fn close(v: &Value, expected: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| v[k].as_f64().is_some_and(|x| (x - expected[k]).abs() <= tol))
}

#[tokio::test]
async fn the_preview_marks_where_an_axis_reached_its_velocity_and_acceleration_limit() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // X: $MA_MAX_AX_VELO 30000 mm/min = 500 mm/s, $MA_MAX_AX_ACCEL 3 m/s² = 3000 mm/s². F40000
    // is more than X can do: it runs at 500 mm/s (reached after 500²/(2·3000) = 41.7 mm) and
    // accelerates and brakes at 3000 mm/s². The G0 of line 1 (at the limits by design) and Y
    // (which does not move in line 2) give no hit; F1000 in line 3 stays below the velocity limit.
    let program = "G0 X0 Y0 Z0\nG1 X300 F40000\nG1 Y5 F1000\nM30";
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({"program": program})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let hits = reply.body["limit_hits"].as_array().expect("limit_hits");
    let find = |axis: &str, kind: &str, line: u64| {
        hits.iter().find(|h| h["axis"] == axis && h["kind"] == kind && h["line"] == line)
    };
    let velo = find("X", "velocity", 2).unwrap_or_else(|| panic!("X velocity in line 2: {hits:?}"));
    assert!((velo["limit"].as_f64().unwrap() - 500.0).abs() < 1e-9, "{velo}");
    // Where: after the 41.7 mm of acceleration, on the line Y0 Z0. The velocity is the
    // setpoints differenced over one IPO cycle (its mean over the cycle), so the hit is seen
    // up to two cycles later: at most 2 × 4 ms × 500 mm/s = 4 mm further.
    let x = velo["basic"][0].as_f64().unwrap();
    assert!((41.6..46.0).contains(&x) && close(&velo["basic"], [x, 0.0, 0.0], 1e-9), "{velo}");
    let accel = find("X", "acceleration", 2).unwrap_or_else(|| panic!("X acceleration in line 2: {hits:?}"));
    assert!((accel["limit"].as_f64().unwrap() - 3000.0).abs() < 1e-9, "{accel}");
    assert!(hits.iter().all(|h| h["line"] != 1), "no hit in G0: {hits:?}");
    assert!(find("Y", "velocity", 3).is_none(), "{hits:?}");
    assert_eq!(reply.body["limit_hits_total"].as_u64(), Some(hits.len() as u64));
    // No orientation transformation: no tool direction.
    assert!(reply.body["tool_direction"].as_array().unwrap().iter().all(Value::is_null), "{}", reply.body);
}

#[tokio::test]
async fn under_traori_the_preview_gives_the_tool_direction_at_each_point() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    // A3/B3/C3 = (0, −1, 1): the tool tilted 45° towards −Y, tip → holder (0, −√½, √½).
    let program = "T1 D1\nTRAORI\nG0 X0 Y0 Z100 A3=0 B3=0 C3=1\nG1 X20 A3=0 B3=-1 C3=1 F2000\nM30";
    let reply = server.post(&format!("/sessions/{id}/preview"), json!({"program": program})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["outcome"], "ended", "{}", reply.body);
    let dirs = reply.body["tool_direction"].as_array().unwrap();
    assert_eq!(dirs.len(), reply.body["points"].as_array().unwrap().len());
    let h = 0.5f64.sqrt();
    // The end of line 4 (the program end deselects TRAORI: the last point has none).
    // (Sampled in the last cycle before the block change, one braking step short of the end
    // orientation: since the planner brakes on the exact discrete stop speed, that step is
    // about 1.5e-4 (0.009°); 2e-4 is still far from the next sample, 0.005 away.)
    assert!(dirs.iter().any(|d| close(d, [0.0, -h, h], 2e-4)), "{dirs:?}");
    assert!(dirs.last().unwrap().is_null(), "{dirs:?}");
    // A slow turn (45° over 60 mm at F600: 0.05° per sample) still keeps a point every 0.5°
    // or so: at least 45 / 0.5 = 90 points along line 4.
    let slow = "T1 D1\nTRAORI\nG0 X0 Y0 Z100 A3=0 B3=0 C3=1\nG1 X60 A3=0 B3=-1 C3=1 F600\nM30";
    let r = server.post(&format!("/sessions/{id}/preview"), json!({"program": slow})).await;
    let in_line_4 = r.body["lines"].as_array().unwrap().iter().filter(|l| **l == 4).count();
    assert!(in_line_4 >= 90, "{in_line_4} points in line 4");
    assert!(dirs.iter().any(|d| close(d, [0.0, 0.0, 1.0], 1e-6)), "{dirs:?}");
}

#[tokio::test]
async fn a_late_viewer_gets_the_executed_path_from_the_session() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let empty = server.get(&format!("/sessions/{id}/path-history")).await;
    assert_eq!(empty.status, StatusCode::OK, "{}", empty.body);
    assert_eq!(empty.body["axes"], json!(["X", "Y", "Z"]));
    // An L in real time (1.2 s): every published state is recorded.
    let program = "G1 X30 F3000\nG1 Y30\nM30";
    let run = server
        .post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "realtime", "wait": true}))
        .await;
    assert_eq!(run.status, StatusCode::OK, "{}", run.body);
    let h = server.get(&format!("/sessions/{id}/path-history")).await.body;
    let points = h["points"].as_array().unwrap();
    assert!(points.len() >= 3, "{h}");
    // Every point on the L (X to 30 at Y0, then Y to 30 at X30), the last at its end.
    for p in points {
        let on_first = close(p, [p[0].as_f64().unwrap(), 0.0, 0.0], 1e-6);
        let on_second = close(p, [30.0, p[1].as_f64().unwrap(), 0.0], 1e-6);
        assert!(on_first || on_second, "{p} off the path: {h}");
    }
    assert!(close(points.last().unwrap(), [30.0, 30.0, 0.0], 1e-9), "{h}");
    assert!(points.iter().any(|p| close(p, [30.0, 0.0, 0.0], 2.0)), "near the corner: {h}");
    assert_eq!(h["lines"].as_array().unwrap().len(), points.len());
    assert!(server.get("/sessions/nope/path-history").await.status == StatusCode::NOT_FOUND);
}

#[tokio::test]
async fn each_preview_point_names_the_program_its_line_is_in() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let sub = "G1 Y20 F2000\nG1 X40\nM17\n";
    let put = server.put(&format!("/sessions/{id}/programs/edge.spf"), json!({"text": sub})).await;
    assert!(put.status.is_success(), "{}", put.body);
    // Main line 2 moves X, the subprogram's lines 1 and 2 move Y and X, main line 4 moves Z.
    let program = "G0 X0 Y0 Z0\nG1 X20 F2000\nEDGE\nG1 Z10\nM30";
    let r = server.post(&format!("/sessions/{id}/preview"), json!({"program": program})).await;
    assert_eq!(r.status, StatusCode::OK, "{}", r.body);
    let names = r.body["programs"].as_array().unwrap();
    assert_eq!(names.len(), 1, "{}", r.body);
    assert!(names[0].as_str().unwrap().eq_ignore_ascii_case("edge"), "{names:?}");
    let points = r.body["points"].as_array().unwrap();
    let lines = r.body["lines"].as_array().unwrap();
    let of = r.body["line_program"].as_array().unwrap();
    assert_eq!((lines.len(), of.len()), (points.len(), points.len()));
    // A point inside each move carries the line of that move (a point at a block change
    // carries the next block's): Y at X20 is the subprogram's line 1, X at Y20 its line 2, Z the
    // main program's line 4.
    let inside = |f: &dyn Fn(f64, f64, f64) -> bool| {
        let k = points
            .iter()
            .position(|q| f(q[0].as_f64().unwrap(), q[1].as_f64().unwrap(), q[2].as_f64().unwrap()))
            .unwrap_or_else(|| panic!("no such point in {points:?}"));
        (lines[k].clone(), of[k].clone())
    };
    assert_eq!(inside(&|x, y, _| x == 20.0 && y > 0.0 && y < 20.0), (json!(1), json!(1)), "{}", r.body);
    assert_eq!(inside(&|x, y, _| y == 20.0 && x > 20.0 && x < 40.0), (json!(2), json!(1)), "{}", r.body);
    assert_eq!(inside(&|_, _, z| z > 0.0 && z < 10.0), (json!(4), json!(0)), "{}", r.body);
    assert_eq!(inside(&|x, y, _| y == 0.0 && x > 0.0 && x < 20.0), (json!(2), json!(0)), "{}", r.body);
}

#[tokio::test]
async fn the_preview_gives_the_blank_the_program_defines_before_it_is_cut() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    // BOX from X-10 Y-10 to X50 Y40, Z0 down to Z-20 (G54 neutral: WCS = BCS); the program
    // then cuts 3 mm deep across it, which the box does not show.
    let program = "T1 D1\nG0 X-30 Y15 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS3000 M3\nG0 Z-3\nG1 X60 F3000\nG0 Z50\nM30";
    let r = server.post(&format!("/sessions/{id}/preview"), json!({"program": program})).await;
    assert_eq!(r.status, StatusCode::OK, "{}", r.body);
    assert_eq!(
        r.body["blank"],
        json!({"turning": false, "min": [-10.0, -10.0, -20.0], "max": [50.0, 40.0, 0.0]}),
        "{}",
        r.body
    );
    // Without WORKPIECE: no blank.
    let r = server.post(&format!("/sessions/{id}/preview"), json!({"program": "G1 X10 F1000\nM30"})).await;
    assert_eq!(r.body["blank"], Value::Null, "{}", r.body);
}
