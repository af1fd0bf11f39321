//! The read-only views the HMI adds: a session's NC data as text, the registry of every datum,
//! and the number of clients watching a session.

use crate::common;

use common::{Server, error_message};
use reqwest::StatusCode;
use serde_json::json;

#[tokio::test]
async fn a_sessions_nc_data_text_holds_the_preset_and_what_was_applied_since() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.get(&format!("/sessions/{id}/machine-data")).await;
    assert_eq!(reply.status, StatusCode::OK);
    let text = reply.body["text"].as_str().expect("text");
    assert!(text.contains("$MA_MAX_AX_VELO[AX1]=30000.0\n"), "{text}");
    assert!(text.contains("$TC_DP6[1,1]=5.0\n"), "{text}");

    let put = server.put(&format!("/sessions/{id}/machine-data"), json!({"text": "$MA_MAX_AX_VELO[X]=20000"})).await;
    assert_eq!(put.status, StatusCode::OK, "{}", put.body);
    let text = server.get(&format!("/sessions/{id}/machine-data")).await.body["text"].clone();
    assert!(text.as_str().expect("text").contains("$MA_MAX_AX_VELO[AX1]=20000.0\n"), "{text}");
}

#[tokio::test]
async fn the_nc_data_text_applied_again_changes_nothing() {
    let server = Server::start().await;
    let id = server.session("lathe-2axis").await;
    let before = server.get(&format!("/sessions/{id}/machine-data")).await.body["text"].clone();
    let put = server.put(&format!("/sessions/{id}/machine-data"), json!({"text": before})).await;
    assert_eq!(put.status, StatusCode::OK, "{}", put.body);
    assert_eq!(server.get(&format!("/sessions/{id}/machine-data")).await.body["text"], before);
}

#[tokio::test]
async fn nc_data_of_an_unknown_session_is_404() {
    let server = Server::start().await;
    let message = error_message(&server.get("/sessions/nope/machine-data").await, StatusCode::NOT_FOUND);
    assert!(message.contains("nope"), "{message}");
}

#[tokio::test]
async fn the_registry_names_number_scope_type_defaults_and_range_of_each_datum() {
    let server = Server::start().await;
    let reply = server.get("/machine-data/definitions").await;
    assert_eq!(reply.status, StatusCode::OK);
    let list = reply.body.as_array().expect("array");
    let velo = list.iter().find(|d| d["name"] == "$MA_MAX_AX_VELO").expect("$MA_MAX_AX_VELO listed");
    assert_eq!(
        (&velo["number"], &velo["scope"], &velo["kind"], &velo["len"]),
        (&json!(32000), &json!("axis"), &json!("real"), &json!(1))
    );
    assert!(velo["min"].as_f64().expect("bounded") > 0.0, "{velo}");
    let names = list.iter().find(|d| d["name"] == "$MN_AXCONF_MACHAX_NAME_TAB").expect("name table listed");
    assert_eq!(names["defaults"].as_array().map(Vec::len), names["len"].as_u64().map(|n| n as usize));
    assert_eq!((&names["min"], &names["max"]), (&json!(null), &json!(null)), "strings have no range");
}

#[tokio::test]
async fn viewers_count_the_open_streams_of_a_session() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    assert_eq!(server.get(&format!("/sessions/{id}/viewers")).await.body, json!({"streams": 0}));
    let (ws, _) =
        tokio_tungstenite::connect_async(server.ws_url(&format!("/sessions/{id}/stream"))).await.expect("stream");
    let mut seen = json!(null);
    for _ in 0..100 {
        seen = server.get(&format!("/sessions/{id}/viewers")).await.body;
        if seen == json!({"streams": 1}) {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    assert_eq!(seen, json!({"streams": 1}));
    drop(ws);
}
