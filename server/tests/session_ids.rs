//! Session ids never repeat: not after the highest-numbered session was deleted and the server
//! restarted (a client still holding the old id would otherwise drive a stranger's session),
//! on SQLite and on PostgreSQL, and not in a data file written before the counter was kept.

use crate::common;
use crate::pg;

use common::{Server, error_message};
use nctwin_server::storage::{self, SqliteStorage, Storage};
use nctwin_server::{Config, Limits};
use reqwest::StatusCode;

/// Creates three sessions, deletes the newest two, restarts, creates one more: its id is none
/// of the three.
async fn ids_never_repeat(config: impl Fn(std::path::PathBuf) -> Config) {
    let dir = common::temp_data_dir();
    let server = Server::start_config(config(dir.clone())).await;
    let ids =
        [server.session("mill-3axis").await, server.session("mill-3axis").await, server.session("mill-3axis").await];
    for gone in &ids[1..] {
        assert_eq!(server.delete(&format!("/sessions/{gone}")).await.status, StatusCode::NO_CONTENT);
    }
    let dir = server.stop().await;
    let server = Server::start_config(config(dir.clone())).await;
    error_message(&server.get(&format!("/sessions/{}", ids[2])).await, StatusCode::NOT_FOUND);
    let new = server.session("mill-3axis").await;
    assert!(!ids.contains(&new), "a new session got an old id: {new} among {ids:?}");
    let newer = server.session("mill-3axis").await;
    assert!(!ids.contains(&newer) && newer != new, "{newer}");
    let _ = std::fs::remove_dir_all(server.stop().await);
}

#[tokio::test]
async fn ids_never_repeat_after_a_restart_on_sqlite() {
    ids_never_repeat(|dir| Config { limits: Limits::default(), ..Config::new(dir, common::WEB_DIR) }).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn ids_never_repeat_after_a_restart_on_postgresql() {
    let Some(url) = tokio::task::spawn_blocking(|| pg::postgres_database("ids")).await.expect("create") else {
        return;
    };
    ids_never_repeat(|dir| Config {
        database: Some(url.clone()),
        node_id: Some("ids-node".into()),
        ..Config::new(dir, common::WEB_DIR)
    })
    .await;
}

/// A data file of schema version 3 (no counter) holding sessions 1 and 5: the migration starts
/// the counter above the highest stored number, and from then on it only grows.
#[test]
fn a_sqlite_file_without_a_counter_continues_above_its_highest_session() {
    let dir = common::temp_data_dir();
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join(storage::SQLITE_FILE);
    {
        let c = rusqlite::Connection::open(&path).expect("create");
        c.execute_batch(
            "CREATE TABLE sessions (
                 id TEXT PRIMARY KEY, number INTEGER NOT NULL, machine TEXT NOT NULL, client_ip TEXT,
                 owner_hash TEXT NOT NULL, operator_hash TEXT NOT NULL, observer_hash TEXT NOT NULL,
                 machine_data TEXT NOT NULL, positions TEXT NOT NULL, mode TEXT NOT NULL, channel_state TEXT);
             CREATE TABLE programs (
                 session TEXT NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
                 name TEXT NOT NULL, text TEXT NOT NULL, PRIMARY KEY (session, name));
             CREATE TABLE active_programs (
                 session TEXT PRIMARY KEY REFERENCES sessions(id) ON DELETE CASCADE,
                 sha256 TEXT NOT NULL, text TEXT NOT NULL);
             INSERT INTO sessions VALUES ('s1', 1, 'mill-3axis', NULL, 'o', 'p', 'v', '', '[0.0]', 'AUTO', NULL);
             INSERT INTO sessions VALUES ('s5', 5, 'mill-3axis', NULL, 'o', 'p', 'v', '', '[0.0]', 'AUTO', NULL);
             PRAGMA user_version = 3;",
        )
        .expect("a version 3 file");
    }
    let storage = SqliteStorage::open(&path).expect("migrated");
    assert_eq!(storage.load().expect("load").len(), 2, "every row kept");
    assert_eq!(storage.next_session_number().expect("number"), Some(6));
    storage.delete_session("s5").expect("delete");
    drop(storage);
    let storage = SqliteStorage::open(&path).expect("reopened");
    assert_eq!(storage.next_session_number().expect("number"), Some(7), "6 was handed out once already");
    drop(storage);
    let _ = std::fs::remove_dir_all(&dir);
}
