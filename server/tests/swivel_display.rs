//! What the HMI shows of CYCLE800 (`GET .../active-swivel`) and where a swivel from JOG leaves
//! the channel, over a real socket on port 0.

use crate::common;

use common::{Server, pos};
use reqwest::StatusCode;
use serde_json::{Value, json};

fn near(v: &Value, expected: f64) -> bool {
    v.as_f64().is_some_and(|x| (x - expected).abs() < 1e-9)
}

#[tokio::test]
async fn the_active_swivel_names_the_data_set_its_angles_and_the_turned_wcs() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    let none = server.get(&format!("/sessions/{id}/active-swivel")).await;
    assert_eq!(none.status, StatusCode::OK, "{}", none.body);
    assert_eq!((&none.body["data_set"], &none.body["name"]), (&json!(0), &json!("")), "{}", none.body);
    assert_eq!(none.body["wcs_axes"], json!([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]));

    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    // Axis by axis XYZ, A = 30: the plane turned +30° about X ($TC_CARR34[1] = "HEAD_CA",
    // rotary axis 1 C, axis 2 A: direction + takes C = 0, A = 30).
    let body = json!({"data_set": "HEAD_CA", "mode": "axis_by_axis", "sequence": "XYZ", "a": 30,
        "direction": 1, "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/swivel"), body).await;
    assert_eq!(reply.body["alarms"], json!([]), "{}", reply.body);
    let s = server.get(&format!("/sessions/{id}/active-swivel")).await.body;
    assert_eq!((&s["data_set"], &s["name"]), (&json!(1), &json!("HEAD_CA")), "{s}");
    assert!(near(&s["axis_angles"][0], 0.0) && near(&s["axis_angles"][1], 30.0), "{s}");
    assert!(near(&s["plane"][0], 30.0) && near(&s["plane"][1], 0.0) && near(&s["plane"][2], 0.0), "{s}");
    // Rx(30°): WCS Y points to (0, cos 30°, sin 30°) of the BCS, WCS Z to (0, −sin 30°, cos 30°).
    let (c, h) = (30f64.to_radians().cos(), 0.5);
    for (axis, expected) in [(0, [1.0, 0.0, 0.0]), (1, [0.0, c, h]), (2, [0.0, -h, c])] {
        for k in 0..3 {
            assert!(near(&s["wcs_axes"][axis][k], expected[k]), "axis {axis}: {s}");
        }
    }

    // Deselection (data set "0"): no swivel, the WCS back along the BCS.
    let off = json!({"data_set": "0", "mode": "direct", "pace": "fast", "wait": true});
    server.post(&format!("/sessions/{id}/swivel"), off).await;
    let s = server.get(&format!("/sessions/{id}/active-swivel")).await.body;
    assert_eq!(s["data_set"], 0, "{s}");
    assert!(near(&s["wcs_axes"][2][2], 1.0), "{s}");
}

#[tokio::test]
async fn a_swivel_from_jog_that_fails_returns_to_jog_with_its_alarm() {
    let server = Server::start().await;
    let id = server.session("mill5-head-ca").await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await;
    // A = 120 lies beyond the head's ±110° ($TC_CARR31/33): alarm 61184, nothing moves.
    let body = json!({"data_set": "HEAD_CA", "mode": "direct", "a": 0, "b": 120, "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/swivel"), body).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["alarms"][0]["number"], 61184, "{}", reply.body);
    assert_eq!(reply.body["mode"], "JOG", "{}", reply.body);
    assert_eq!(pos(&reply.body, "machine", "A"), 0.0);
    // From MDA the channel stays in MDA (the swivel was asked for there).
    server.post(&format!("/sessions/{id}/reset"), json!({})).await;
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "MDA"})).await;
    let body = json!({"data_set": "HEAD_CA", "mode": "direct", "a": 0, "b": 120, "pace": "fast", "wait": true});
    let reply = server.post(&format!("/sessions/{id}/swivel"), body).await;
    assert_eq!(reply.body["mode"], "MDA", "{}", reply.body);
}
