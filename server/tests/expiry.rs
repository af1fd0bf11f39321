//! Sessions expire when idle (deleted, from storage too), unless in use (requests, an open
//! stream, a running program) or marked persistent by their owner; the idle time counts across
//! restarts; a server-wide budget caps the bytes of stored programs; `/metrics` counts each
//! session's program bytes.
//!
//! The timeouts are short, and every wait is "until it happens, within a generous deadline":
//! nothing asserts how fast the sweep is.

use crate::common;
use crate::pg;

use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use common::{Server, error_message};
use nctwin_server::storage::SQLITE_FILE;
use nctwin_server::{AuthMode, Config, Limits};
use reqwest::StatusCode;
use serde_json::json;
use tokio_tungstenite::connect_async;

fn config(dir: PathBuf, idle: Duration) -> Config {
    Config { limits: Limits { session_idle: idle, ..Limits::default() }, ..Config::new(dir, common::WEB_DIR) }
}

/// Waits until session `id` is no longer listed (at most 30 s, then panics). The listing is
/// no use of a session (a request to the session itself would keep it alive).
async fn until_gone(server: &Server, id: &str) {
    for _ in 0..300 {
        let list = server.get("/sessions").await.body;
        if !list.as_array().expect("list").iter().any(|s| s["id"] == id) {
            error_message(&server.get(&format!("/sessions/{id}")).await, StatusCode::NOT_FOUND);
            return;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    panic!("session {id} never expired");
}

fn now_ms() -> i64 {
    SystemTime::now().duration_since(UNIX_EPOCH).expect("after 1970").as_millis() as i64
}

/// The saved last activity of session `id` in the SQLite file of `dir`.
fn saved_activity(dir: &Path, id: &str) -> Option<i64> {
    let c = rusqlite::Connection::open(dir.join(SQLITE_FILE)).expect("open");
    c.query_row("SELECT last_active_ms FROM sessions WHERE id = ?1", [id], |r| r.get(0)).expect("row")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_idle_session_expires_unless_persistent_streamed_or_running() {
    let idle = Duration::from_secs(1);
    let server = Server::start_config(config(common::temp_data_dir(), idle)).await;
    let idle_one = server.session("mill-3axis").await;
    let created = server.post("/sessions", json!({"machine": "mill-3axis", "persistent": true})).await;
    assert_eq!((created.status, created.body["persistent"].as_bool()), (StatusCode::CREATED, Some(true)));
    let persistent = created.body["id"].as_str().expect("id").to_string();
    let streamed = server.session("mill-3axis").await;
    let (_socket, _) = connect_async(server.ws_url(&format!("/sessions/{streamed}/stream"))).await.expect("stream");
    let running = server.session("mill-3axis").await;
    // 50 s of real-time motion: it runs through the whole test.
    let run = json!({"program": "G1 X500 F600\nM30", "pace": "realtime"});
    assert_eq!(server.post(&format!("/sessions/{running}/run"), run).await.status, StatusCode::OK);

    until_gone(&server, &idle_one).await;
    // Twice the timeout more without a request to the others.
    tokio::time::sleep(2 * idle).await;
    for id in [&persistent, &streamed, &running] {
        let reply = server.get(&format!("/sessions/{id}")).await;
        assert_eq!(reply.status, StatusCode::OK, "{id} is in use or persistent: {}", reply.body);
    }
    assert_eq!(server.get(&format!("/sessions/{persistent}")).await.body["persistent"], true);

    // Deleted from storage too: a restart does not bring it back.
    let dir = server.stop().await;
    let server = Server::start_config(config(dir, Duration::from_secs(3600))).await;
    error_message(&server.get(&format!("/sessions/{idle_one}")).await, StatusCode::NOT_FOUND);
    assert_eq!(server.get(&format!("/sessions/{persistent}")).await.status, StatusCode::OK);
    let _ = std::fs::remove_dir_all(server.stop().await);
}

/// The idle time counts across a restart: the last activity is saved, so a session last used
/// two hours ago expires at once under a one-hour timeout, while one used just now stays.
#[tokio::test]
async fn the_idle_time_counts_across_a_restart() {
    let hour = Duration::from_secs(3600);
    let server = Server::start_config(config(common::temp_data_dir(), hour)).await;
    let old = server.session("mill-3axis").await;
    let fresh = server.session("mill-3axis").await;
    let before = now_ms();
    assert_eq!(server.get(&format!("/sessions/{fresh}/state")).await.status, StatusCode::OK);
    let dir = server.stop().await;
    let saved = saved_activity(&dir, &fresh).expect("the activity is saved at shutdown");
    assert!(saved >= before, "the last request counts: {saved} < {before}");
    let c = rusqlite::Connection::open(dir.join(SQLITE_FILE)).expect("open");
    c.execute("UPDATE sessions SET last_active_ms = ?2 WHERE id = ?1", rusqlite::params![old, now_ms() - 7_200_000])
        .expect("two hours ago");
    drop(c);

    let server = Server::start_config(config(dir, hour)).await;
    until_gone(&server, &old).await;
    assert_eq!(server.get(&format!("/sessions/{fresh}")).await.status, StatusCode::OK);
    let _ = std::fs::remove_dir_all(server.stop().await);
}

/// Only the owner marks a session persistent (`--auth required`); the mark is saved.
#[tokio::test]
async fn the_owner_marks_a_session_persistent_and_the_mark_survives_a_restart() {
    let auth = |dir: PathBuf| Config { auth: AuthMode::Required, ..config(dir, Duration::from_secs(3600)) };
    let server = Server::start_config(auth(common::temp_data_dir())).await;
    let created = server.post("/sessions", json!({})).await;
    assert_eq!((created.status, created.body["persistent"].as_bool()), (StatusCode::CREATED, Some(false)));
    let id = created.body["id"].as_str().expect("id").to_string();
    let token = |role: &str| created.body["tokens"][role].as_str().expect("token").to_string();
    let patch = |token: Option<String>| {
        let mut request =
            server.client.patch(server.url(&format!("/sessions/{id}"))).json(&json!({"persistent": true}));
        if let Some(token) = token {
            request = request.bearer_auth(token);
        }
        server.send(request)
    };
    assert_eq!(patch(None).await.status, StatusCode::UNAUTHORIZED);
    assert_eq!(patch(Some(token("observer"))).await.status, StatusCode::FORBIDDEN);
    assert_eq!(patch(Some(token("operator"))).await.status, StatusCode::FORBIDDEN);
    let reply = patch(Some(token("owner"))).await;
    assert_eq!((reply.status, reply.body["persistent"].as_bool()), (StatusCode::OK, Some(true)), "{}", reply.body);

    let dir = server.stop().await;
    let server = Server::start_config(auth(dir)).await;
    let reply =
        server.send(server.client.get(server.url(&format!("/sessions/{id}"))).bearer_auth(token("owner"))).await;
    assert_eq!(reply.body["persistent"], true, "{}", reply.body);
    let _ = std::fs::remove_dir_all(server.stop().await);
}

/// Marked persistent, a session outlives the timeout; unmarked again, it expires.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_session_unmarked_persistent_expires_again() {
    let server = Server::start_config(config(common::temp_data_dir(), Duration::from_secs(1))).await;
    let id = server.session("mill-3axis").await;
    let reply = server
        .send(server.client.patch(server.url(&format!("/sessions/{id}"))).json(&json!({"persistent": true})))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    tokio::time::sleep(Duration::from_secs(3)).await;
    assert_eq!(server.get(&format!("/sessions/{id}")).await.status, StatusCode::OK, "persistent");
    let reply = server
        .send(server.client.patch(server.url(&format!("/sessions/{id}"))).json(&json!({"persistent": false})))
        .await;
    assert_eq!(reply.body["persistent"], false);
    until_gone(&server, &id).await;
}

#[tokio::test]
async fn the_server_wide_program_budget_holds_and_metrics_count_bytes_per_session() {
    let limits = Limits { program_budget_bytes: 1000, ..Limits::default() };
    let server = Server::start_with(limits).await;
    let (a, b) = (server.session("mill-3axis").await, server.session("mill-3axis").await);
    let text = format!(";{}\nM17", "x".repeat(595)); // 600 bytes
    assert_eq!(server.put(&format!("/sessions/{a}/programs/P"), json!({ "text": text })).await.status, StatusCode::OK);
    let message = error_message(
        &server.put(&format!("/sessions/{b}/programs/P"), json!({ "text": text })).await,
        StatusCode::PAYLOAD_TOO_LARGE,
    );
    assert!(message.contains("budget of 1000 bytes"), "{message}");
    // Replacing a program counts only the difference.
    assert_eq!(server.put(&format!("/sessions/{a}/programs/P"), json!({ "text": text })).await.status, StatusCode::OK);

    let text_metrics = server.client.get(format!("http://{}/metrics", server.addr)).send().await.expect("metrics");
    let text_metrics = text_metrics.text().await.expect("text");
    assert!(text_metrics.contains(&format!("nctwin_session_program_bytes{{session=\"{a}\"}} 600\n")), "{text_metrics}");
    assert!(text_metrics.contains(&format!("nctwin_session_program_bytes{{session=\"{b}\"}} 0\n")), "{text_metrics}");
    assert!(text_metrics.contains("nctwin_program_budget_bytes 1000\n"), "{text_metrics}");

    // A deleted session gives its bytes back.
    assert_eq!(server.delete(&format!("/sessions/{a}")).await.status, StatusCode::NO_CONTENT);
    assert_eq!(server.put(&format!("/sessions/{b}/programs/P"), json!({ "text": text })).await.status, StatusCode::OK);
}

/// Every backend keeps the persistent mark and the last activity, and hands out session numbers
/// that never repeat.
#[test]
fn every_storage_keeps_the_mark_and_the_activity() {
    use nctwin_server::storage::{
        Checkpoint, MemoryStorage, PostgresStorage, SessionRecord, SqliteStorage, Storage, TokenHashes,
    };
    let record = |id: &str, number: u64| SessionRecord {
        id: id.into(),
        number,
        machine: "mill-3axis".into(),
        client_ip: None,
        tokens: TokenHashes { owner: "o".into(), operator: "p".into(), observer: "v".into() },
        checkpoint: Checkpoint {
            machine_data: String::new(),
            positions: vec![0.0],
            mode: "AUTO".into(),
            channel_state: None,
            active_program: None,
        },
        persistent: true,
        last_active_ms: Some(5),
    };
    let check = |storage: &dyn Storage| {
        storage.create_session(&record("s1", 1)).expect("create");
        storage.create_session(&SessionRecord { persistent: false, ..record("s2", 2) }).expect("create");
        storage.set_persistent("s1", false).expect("unmark");
        storage.set_persistent("s2", true).expect("mark");
        storage.set_persistent("gone", true).expect("a missing session is no error");
        storage.save_activity(&[("s1".into(), 1_000), ("gone".into(), 7)]).expect("activity");
        let all = storage.load().expect("load");
        let seen: Vec<(bool, Option<u64>)> =
            all.iter().map(|s| (s.record.persistent, s.record.last_active_ms)).collect();
        assert_eq!(seen, [(false, Some(1_000)), (true, Some(5))], "{}", storage.describe());
        if let Some(n) = storage.next_session_number().expect("number") {
            storage.delete_session("s2").expect("delete");
            let next = storage.next_session_number().expect("number").expect("still numbered");
            assert!(n > 2 && next > n, "{}: {n} then {next}", storage.describe());
        }
    };
    check(&MemoryStorage::default());
    let dir = common::temp_data_dir();
    std::fs::create_dir_all(&dir).expect("dir");
    check(&SqliteStorage::open(&dir.join(SQLITE_FILE)).expect("open"));
    let _ = std::fs::remove_dir_all(&dir);
    if let Some(url) = pg::postgres_database("expiry") {
        check(&PostgresStorage::open(&url).expect("open"));
    }
}
