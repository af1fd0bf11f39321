//! Stored programs survive a change of machine data or kinematic chain data: in the live
//! session (listed, callable, deletable, counted against the session's quota) and in storage
//! (an acknowledged delete stays deleted after a restart).

use crate::common;

use common::{Server, error_message};
use nctwin_server::{Config, Limits};
use reqwest::StatusCode;
use serde_json::json;

async fn restart(server: Server) -> Server {
    let dir = server.stop().await;
    Server::start_config(Config::new(dir, common::WEB_DIR)).await
}

/// Stores A and B, changes the data with `change`, then deletes A: B is still listed and
/// callable, A stays deleted, also after a restart.
async fn programs_survive(change: impl AsyncFnOnce(&Server, &str)) {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    for (name, text) in [("A", "G0 X1\nM17"), ("B", "G0 X2\nM17")] {
        let reply = server.put(&format!("/sessions/{id}/programs/{name}"), json!({ "text": text })).await;
        assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    }
    change(&server, &id).await;

    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "A", "size": 9}, {"name": "B", "size": 9}]), "still stored after the change");
    let reply = server.delete(&format!("/sessions/{id}/programs/A")).await;
    assert_eq!(reply.status, StatusCode::NO_CONTENT, "{}", reply.body);
    let run = json!({"program": "B\nM30", "pace": "fast", "wait": true});
    let state = server.post(&format!("/sessions/{id}/run"), run).await.body;
    assert_eq!((state["status"].as_str(), state["positions"]["machine"]["X"].as_f64()), (Some("idle"), Some(2.0)));

    let server = restart(server).await;
    let list = server.get(&format!("/sessions/{id}/programs")).await.body;
    assert_eq!(list, json!([{"name": "B", "size": 9}]), "the acknowledged delete is not undone by a restart");
}

#[tokio::test]
async fn stored_programs_survive_a_machine_data_change() {
    programs_survive(async |server: &Server, id: &str| {
        let reply =
            server.put(&format!("/sessions/{id}/machine-data"), json!({"text": "$MA_POS_LIMIT_PLUS[AX1]=50."})).await;
        assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    })
    .await;
}

#[tokio::test]
async fn stored_programs_survive_a_kinematic_chain_change() {
    programs_survive(async |server: &Server, id: &str| {
        let url = server.url(&format!("/sessions/{id}/kinematic-chains"));
        let chains = server.client.get(&url).send().await.expect("get").text().await.expect("text");
        let request = server.client.put(&url).header("content-type", "text/plain").body(chains);
        let reply = server.send(request).await;
        assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    })
    .await;
}

#[tokio::test]
async fn the_session_program_quota_holds_across_a_machine_data_change() {
    let limits = Limits { session_program_bytes: 1000, ..Limits::default() };
    let server = Server::start_with(limits).await;
    let id = server.session("mill-3axis").await;
    let text = format!(";{}\nM17", "x".repeat(590));
    let reply = server.put(&format!("/sessions/{id}/programs/FIRST"), json!({ "text": text })).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let reply =
        server.put(&format!("/sessions/{id}/machine-data"), json!({"text": "$MA_POS_LIMIT_PLUS[AX1]=50."})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let reply = server.put(&format!("/sessions/{id}/programs/SECOND"), json!({ "text": text })).await;
    let message = error_message(&reply, StatusCode::PAYLOAD_TOO_LARGE);
    assert!(message.contains("1000 bytes"), "{message}");
}
