//! Roles and tokens with `--auth required`, and that `--auth off` needs none.

use crate::common;

use common::{Reply, Server, error_message};
use futures_util::StreamExt;
use nctwin_server::{AuthMode, Config};
use reqwest::StatusCode;
use serde_json::{Value, json};
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Error as WsError;

async fn server_with_auth() -> Server {
    Server::start_config(Config { auth: AuthMode::Required, ..Config::new(common::temp_data_dir(), common::WEB_DIR) })
        .await
}

struct Session {
    id: String,
    owner: String,
    operator: String,
    observer: String,
}

async fn create(server: &Server) -> Session {
    let reply = server.post_empty("/sessions").await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    let token = |role: &str| reply.body["tokens"][role].as_str().expect("token").to_string();
    Session {
        id: reply.body["id"].as_str().expect("id").into(),
        owner: token("owner"),
        operator: token("operator"),
        observer: token("observer"),
    }
}

async fn as_token(server: &Server, token: &str, method: reqwest::Method, path: &str, body: Option<Value>) -> Reply {
    let mut request = server.client.request(method, server.url(path)).bearer_auth(token);
    if let Some(body) = body {
        request = request.json(&body);
    }
    server.send(request).await
}

async fn run(server: &Server, token: &str, id: &str) -> Reply {
    let body = json!({"program": "G0 X1\nM30", "pace": "fast", "wait": true});
    as_token(server, token, reqwest::Method::POST, &format!("/sessions/{id}/run"), Some(body)).await
}

async fn post(server: &Server, token: &str, path: &str) -> Reply {
    as_token(server, token, reqwest::Method::POST, path, None).await
}

#[tokio::test]
async fn a_new_session_comes_with_three_distinct_128_bit_tokens() {
    let server = server_with_auth().await;
    let s = create(&server).await;
    for token in [&s.owner, &s.operator, &s.observer] {
        let hex = token.strip_prefix("nct_").expect("prefix");
        assert!(hex.len() == 32 && hex.bytes().all(|b| b.is_ascii_hexdigit()), "{token}");
    }
    assert!(s.owner != s.operator && s.operator != s.observer);
    let other = create(&server).await;
    assert_ne!(other.owner, s.owner);
}

#[tokio::test]
async fn requests_without_a_valid_token_are_401() {
    let server = server_with_auth().await;
    let s = create(&server).await;
    let other = create(&server).await;
    let state = format!("/sessions/{}/state", s.id);
    let reply = server.get(&state).await;
    error_message(&reply, StatusCode::UNAUTHORIZED);
    assert_eq!(reply.headers["www-authenticate"], "Bearer");
    error_message(&as_token(&server, "nct_0123", reqwest::Method::GET, &state, None).await, StatusCode::UNAUTHORIZED);
    let message = error_message(
        &as_token(&server, &other.owner, reqwest::Method::GET, &state, None).await,
        StatusCode::UNAUTHORIZED,
    );
    assert!(message.contains(&s.id), "another session's token: {message}");
    error_message(&run(&server, "", &s.id).await, StatusCode::UNAUTHORIZED);
    // What is not about one session needs no token.
    assert_eq!(server.get("/health").await.body["auth"], "required");
    assert_eq!(server.get("/machines").await.status, StatusCode::OK);
    // The listing shows only the token's sessions, and needs a token.
    error_message(&server.get("/sessions").await, StatusCode::UNAUTHORIZED);
    let list = as_token(&server, &s.observer, reqwest::Method::GET, "/sessions", None).await.body;
    assert_eq!(list.as_array().map(|l| l.len()), Some(1));
    assert_eq!(list[0]["id"], s.id.as_str());
}

#[tokio::test]
async fn observers_read_everything_and_every_command_is_403() {
    let server = server_with_auth().await;
    let s = create(&server).await;
    let t = &s.observer;
    let id = &s.id;
    for path in [
        format!("/sessions/{id}"),
        format!("/sessions/{id}/state"),
        format!("/sessions/{id}/programs"),
        format!("/sessions/{id}/control"),
    ] {
        assert_eq!(as_token(&server, t, reqwest::Method::GET, &path, None).await.status, StatusCode::OK, "{path}");
    }
    let check = json!({"program": "G0 X1"});
    assert_eq!(
        as_token(&server, t, reqwest::Method::POST, &format!("/sessions/{id}/check"), Some(check)).await.status,
        StatusCode::OK
    );
    error_message(&run(&server, t, id).await, StatusCode::FORBIDDEN);
    for path in ["stop", "reset", "cancel", "start", "jog/stop", "control/take", "control/release"] {
        error_message(&post(&server, t, &format!("/sessions/{id}/{path}")).await, StatusCode::FORBIDDEN);
    }
    let mode = json!({"mode": "JOG"});
    error_message(
        &as_token(&server, t, reqwest::Method::PUT, &format!("/sessions/{id}/mode"), Some(mode)).await,
        StatusCode::FORBIDDEN,
    );
    let program = json!({"text": "M17"});
    error_message(
        &as_token(&server, t, reqwest::Method::PUT, &format!("/sessions/{id}/programs/P"), Some(program)).await,
        StatusCode::FORBIDDEN,
    );
    error_message(
        &as_token(&server, t, reqwest::Method::DELETE, &format!("/sessions/{id}"), None).await,
        StatusCode::FORBIDDEN,
    );
    let control = as_token(&server, t, reqwest::Method::GET, &format!("/sessions/{id}/control"), None).await.body;
    assert_eq!(control, json!({"auth": true, "role": "observer", "holder": "owner", "you_hold_control": false}));
}

#[tokio::test]
async fn one_role_holds_control_and_the_owner_can_always_take_it_back() {
    let server = server_with_auth().await;
    let s = create(&server).await;
    let id = &s.id;
    let take = format!("/sessions/{id}/control/take");
    let release = format!("/sessions/{id}/control/release");

    assert_eq!(run(&server, &s.owner, id).await.status, StatusCode::OK, "the owner holds control first");
    error_message(&run(&server, &s.operator, id).await, StatusCode::CONFLICT);
    error_message(&post(&server, &s.operator, &take).await, StatusCode::CONFLICT);
    error_message(&post(&server, &s.operator, &release).await, StatusCode::CONFLICT);

    assert_eq!(post(&server, &s.owner, &release).await.body["holder"], Value::Null);
    error_message(&run(&server, &s.owner, id).await, StatusCode::CONFLICT);
    let taken = post(&server, &s.operator, &take).await;
    assert_eq!(taken.body, json!({"auth": true, "role": "operator", "holder": "operator", "you_hold_control": true}));
    assert_eq!(run(&server, &s.operator, id).await.status, StatusCode::OK);
    error_message(&run(&server, &s.owner, id).await, StatusCode::CONFLICT);
    // An operator may drive but not delete.
    error_message(
        &as_token(&server, &s.operator, reqwest::Method::DELETE, &format!("/sessions/{id}"), None).await,
        StatusCode::FORBIDDEN,
    );

    assert_eq!(post(&server, &s.owner, &take).await.body["holder"], "owner", "taken back");
    error_message(&run(&server, &s.operator, id).await, StatusCode::CONFLICT);
    assert_eq!(run(&server, &s.owner, id).await.status, StatusCode::OK);
    let deleted = as_token(&server, &s.owner, reqwest::Method::DELETE, &format!("/sessions/{id}"), None).await;
    assert_eq!(deleted.status, StatusCode::NO_CONTENT);
}

#[tokio::test]
async fn the_stream_takes_its_token_in_the_query() {
    let server = server_with_auth().await;
    let s = create(&server).await;
    let url = server.ws_url(&format!("/sessions/{}/stream", s.id));
    match connect_async(url.as_str()).await {
        Err(WsError::Http(response)) => assert_eq!(response.status(), StatusCode::UNAUTHORIZED),
        other => panic!("expected 401, got {:?}", other.map(|(_, r)| r.status())),
    }
    let (mut socket, _) = connect_async(format!("{url}?token={}", s.observer)).await.expect("observer may watch");
    let first = tokio::time::timeout(std::time::Duration::from_secs(20), socket.next()).await.expect("in time");
    let text = first.expect("a message").expect("ok").into_text().expect("text");
    assert!(text.contains("\"type\":\"state\""), "{text}");
}

#[tokio::test]
async fn tokens_survive_a_restart() {
    let server = server_with_auth().await;
    let s = create(&server).await;
    let dir = server.stop().await;
    let server = Server::start_config(Config { auth: AuthMode::Required, ..Config::new(dir, common::WEB_DIR) }).await;
    assert_eq!(run(&server, &s.owner, &s.id).await.status, StatusCode::OK);
    let state = as_token(&server, &s.observer, reqwest::Method::GET, &format!("/sessions/{}/state", s.id), None).await;
    assert_eq!(state.status, StatusCode::OK);
    error_message(&server.get(&format!("/sessions/{}/state", s.id)).await, StatusCode::UNAUTHORIZED);
}

#[tokio::test]
async fn with_auth_off_nothing_needs_a_token_and_control_only_reports() {
    let server = Server::start().await;
    let s = create(&server).await;
    assert!(s.owner.starts_with("nct_"), "tokens are made anyway, for a later --auth required");
    let control = server.post_empty(&format!("/sessions/{}/control/release", s.id)).await;
    assert_eq!(control.body, json!({"auth": false, "role": "owner", "holder": "owner", "you_hold_control": true}));
    let reply = server.post(&format!("/sessions/{}/run", s.id), json!({"program": "M30", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK);
}
