//! The real `nctwin` binary across restarts: sessions come back after a restart, SIGTERM shuts
//! down gracefully (saves, closes streams with a close frame, exits in bounded time), and
//! SIGKILL loses no acknowledged write.

use crate::pg;
use crate::process;

use process::Nctwin;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::StreamExt;
use reqwest::StatusCode;
use serde_json::json;
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

fn data_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nctwin-lifecycle-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sigterm_saves_closes_streams_with_a_close_frame_exits_and_a_restart_restores() {
    let dir = data_dir("sigterm");
    let mut server = Nctwin::start(&dir);
    let (status, created) =
        server.send(reqwest::Method::POST, "/sessions", Some(json!({"machine": "mill-3axis"}))).await;
    assert_eq!(status, StatusCode::CREATED);
    let id = created["id"].as_str().expect("id").to_string();
    let (status, _) = server
        .send(reqwest::Method::PUT, &format!("/sessions/{id}/programs/SUB"), Some(json!({"text": "G0 X1\nM17"})))
        .await;
    assert_eq!(status, StatusCode::OK);
    // A long real-time program keeps the session moving while the server is told to stop.
    let (status, _) = server
        .send(reqwest::Method::POST, &format!("/sessions/{id}/run"), Some(json!({"program": "G1 X200 F300\nM30"})))
        .await;
    assert_eq!(status, StatusCode::OK);
    let ws = format!("{}/sessions/{id}/stream", server.base.replace("http://", "ws://"));
    let (mut socket, _) = connect_async(ws).await.expect("stream");
    tokio::time::sleep(Duration::from_millis(600)).await;
    let (_, state) = server.send(reqwest::Method::GET, &format!("/sessions/{id}/state"), None).await;
    let x_before = state["positions"]["machine"]["X"].as_f64().expect("X");
    assert!(x_before > 0.0, "moving: {state}");

    let started = Instant::now();
    server.signal("-TERM");
    let close = tokio::time::timeout(Duration::from_secs(10), async {
        while let Some(message) = socket.next().await {
            match message {
                Ok(Message::Close(frame)) => return frame,
                Ok(_) => {}
                Err(e) => panic!("stream broke without a close frame: {e}"),
            }
        }
        panic!("stream ended without a close frame");
    })
    .await
    .expect("a close frame in time");
    assert_eq!(u16::from(close.expect("a close code").code), 1001, "going away");
    assert!(server.wait_exit(Duration::from_secs(15)), "exit status 0 after SIGTERM");
    assert!(started.elapsed() < Duration::from_secs(15));

    let server = Nctwin::start(&dir);
    let (status, state) = server.send(reqwest::Method::GET, &format!("/sessions/{id}/state"), None).await;
    assert_eq!(status, StatusCode::OK, "the session is back");
    // The program comes back stopped at its block (NC start would continue it).
    assert_eq!((state["status"].as_str(), &state["block"]["line"]), (Some("stopped"), &json!(1)), "{state}");
    let x_after = state["positions"]["machine"]["X"].as_f64().expect("X");
    assert!(x_after >= x_before && x_after < 200.0, "saved where it stopped: {x_before} .. {x_after}");
    let (status, program) = server.send(reqwest::Method::GET, &format!("/sessions/{id}/programs/SUB"), None).await;
    assert_eq!((status, program["text"].as_str()), (StatusCode::OK, Some("G0 X1\nM17")));
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn sigkill_during_writes_loses_no_acknowledged_write() {
    sigkill_during_writes(None).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn sigkill_during_writes_to_postgresql_loses_no_acknowledged_write() {
    let Some(url) = tokio::task::spawn_blocking(|| pg::postgres_database("sigkill")).await.expect("create") else {
        return;
    };
    sigkill_during_writes(Some(&url)).await;
}

/// Writers store programs while the server is killed with SIGKILL; after a restart on the same
/// storage (the SQLite file under the data directory, or PostgreSQL database `database`) every
/// acknowledged write is there.
async fn sigkill_during_writes(database: Option<&str>) {
    let dir = data_dir(if database.is_some() { "sigkill-pg" } else { "sigkill" });
    let server = Arc::new(Nctwin::start_with(&dir, database));
    let (_, created) = server.send(reqwest::Method::POST, "/sessions", None).await;
    let id = created["id"].as_str().expect("id").to_string();

    // Writers, one session each (the command rate limit is per session), store programs as
    // fast as they may and remember what was acknowledged; the server is killed while they are
    // still writing.
    let mut writers = Vec::new();
    for w in 0..3 {
        let server = server.clone();
        let (_, session) = server.send(reqwest::Method::POST, "/sessions", None).await;
        let sid = session["id"].as_str().expect("id").to_string();
        writers.push(tokio::spawn(async move {
            let mut acknowledged = Vec::new();
            for n in 0.. {
                let name = format!("W{w}_{n}");
                let text = format!("; writer {w} program {n}\nG0 X{n}\nM17");
                let url = format!("{}/sessions/{sid}/programs/{name}", server.base);
                match server.client.put(url).json(&json!({"text": text})).send().await {
                    Ok(response) if response.status() == StatusCode::OK => acknowledged.push((sid.clone(), name, text)),
                    Ok(response) if response.status() == StatusCode::TOO_MANY_REQUESTS => {
                        tokio::time::sleep(Duration::from_millis(20)).await;
                    }
                    Ok(response) => panic!("a write failed before the kill: {}", response.status()),
                    Err(_) => break, // the server is gone: this write was not acknowledged
                }
            }
            acknowledged
        }));
    }
    // A created session and a machine-data change are acknowledged writes too.
    let (status, second) =
        server.send(reqwest::Method::POST, "/sessions", Some(json!({"machine": "lathe-2axis"}))).await;
    assert_eq!(status, StatusCode::CREATED);
    let second = second["id"].as_str().expect("id").to_string();
    let md = json!({"text": "$MA_POS_LIMIT_PLUS[AX1]=77."});
    assert_eq!(
        server.send(reqwest::Method::PUT, &format!("/sessions/{id}/machine-data"), Some(md)).await.0,
        StatusCode::OK
    );

    tokio::time::sleep(Duration::from_millis(700)).await;
    server.signal("-KILL");
    let mut acknowledged = Vec::new();
    for writer in writers {
        acknowledged.extend(writer.await.expect("writer"));
    }
    assert!(acknowledged.len() >= 10, "enough writes to mean something: {}", acknowledged.len());
    drop(server);

    let server = Nctwin::start_with(&dir, database);
    for (sid, name, text) in &acknowledged {
        let (status, program) =
            server.send(reqwest::Method::GET, &format!("/sessions/{sid}/programs/{name}"), None).await;
        assert_eq!(status, StatusCode::OK, "acknowledged {sid}/{name} is missing after SIGKILL");
        assert_eq!(program["text"].as_str(), Some(text.as_str()));
    }
    assert_eq!(server.send(reqwest::Method::GET, &format!("/sessions/{second}"), None).await.0, StatusCode::OK);
    // The machine data change is back: X stops at 77.
    let run = json!({"program": "G0 X80\nM30", "pace": "fast", "wait": true});
    let (_, state) = server.send(reqwest::Method::POST, &format!("/sessions/{id}/run"), Some(run)).await;
    assert_eq!(state["status"], "alarm", "{state}");
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Two nodes on one PostgreSQL database: each serves the sessions it holds a lease on and
/// answers 421 naming the holder for the others; a node killed with SIGKILL loses its leases
/// when they expire and the other node takes its sessions over (with their saved state); a
/// node stopped with SIGTERM hands its sessions over at once.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_nodes_share_one_postgresql_and_take_over_each_others_sessions() {
    let Some(url) = tokio::task::spawn_blocking(|| pg::postgres_database("nodes")).await.expect("create") else {
        return;
    };
    let node = |name: &str, dir: &Path| {
        Nctwin::start_args(dir, &["--database", &url, "--node-id", name, "--lease-seconds", "2"])
    };
    let (dir_a, dir_b) = (data_dir("node-a"), data_dir("node-b"));
    let a = node("a", &dir_a);
    let mut b = node("b", &dir_b);
    let on_a = create_session(&a).await;
    let on_b = create_session(&b).await;
    assert_ne!(on_a, on_b, "the database numbers sessions for every node");

    // The wrong node: 421 naming the holder; nothing happens to the session.
    let (status, body) = b.send(reqwest::Method::GET, &format!("/sessions/{on_a}/state"), None).await;
    assert_eq!(status, StatusCode::MISDIRECTED_REQUEST, "{body}");
    assert!(body["error"].as_str().expect("message").contains("node `a`"), "{body}");
    let mda = json!({"program": "G0 X7 Y-2", "pace": "fast", "wait": true});
    let (status, _) = b.send(reqwest::Method::POST, &format!("/sessions/{on_a}/mda"), Some(mda.clone())).await;
    assert_eq!(status, StatusCode::MISDIRECTED_REQUEST);
    let (status, state) = a.send(reqwest::Method::POST, &format!("/sessions/{on_a}/mda"), Some(mda)).await;
    assert_eq!((status, state["positions"]["machine"]["X"].as_f64()), (StatusCode::OK, Some(7.0)), "{state}");
    // The checkpoint is written in the background once the channel has come to rest.
    let (db, id) = (url.clone(), on_a.clone());
    tokio::task::spawn_blocking(move || {
        let mut client = postgres::Client::connect(&db, postgres::NoTls).expect("connect");
        for _ in 0..500 {
            let row = client.query_one("SELECT positions FROM nctwin_sessions WHERE id = $1", &[&id]).expect("row");
            if row.get::<_, Vec<f64>>(0) == [7.0, -2.0, 0.0] {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        panic!("the checkpoint was never written");
    })
    .await
    .expect("poll");

    // Node a dies: until its 2 s lease runs out b still refers to it, then b takes over.
    a.signal("-KILL");
    drop(a);
    let (status, _) = b.send(reqwest::Method::GET, &format!("/sessions/{on_a}/state"), None).await;
    assert_eq!(status, StatusCode::MISDIRECTED_REQUEST, "a's lease has not expired yet");
    let deadline = Instant::now() + Duration::from_secs(20);
    let state = loop {
        let (status, state) = b.send(reqwest::Method::GET, &format!("/sessions/{on_a}/state"), None).await;
        if status == StatusCode::OK {
            break state;
        }
        assert_eq!(status, StatusCode::MISDIRECTED_REQUEST, "{state}");
        assert!(Instant::now() < deadline, "b never took the session over");
        tokio::time::sleep(Duration::from_millis(200)).await;
    };
    assert_eq!(
        (state["positions"]["machine"]["X"].as_f64(), state["positions"]["machine"]["Y"].as_f64()),
        (Some(7.0), Some(-2.0))
    );

    // Node a comes back under its name: b renews the session it took, so a refers to b.
    let a = node("a", &dir_a);
    let (status, body) = a.send(reqwest::Method::GET, &format!("/sessions/{on_a}/state"), None).await;
    assert_eq!(status, StatusCode::MISDIRECTED_REQUEST, "{body}");
    assert!(body["error"].as_str().expect("message").contains("node `b`"), "{body}");

    // SIGTERM: b saves and releases its leases; a takes both sessions over at once.
    b.signal("-TERM");
    assert!(b.wait_exit(Duration::from_secs(15)));
    for id in [&on_a, &on_b] {
        let (status, body) = a.send(reqwest::Method::GET, &format!("/sessions/{id}/state"), None).await;
        assert_eq!(status, StatusCode::OK, "{id}: {body}");
    }
    drop(a);
    let _ = std::fs::remove_dir_all(&dir_a);
    let _ = std::fs::remove_dir_all(&dir_b);
}

async fn create_session(node: &Nctwin) -> String {
    let (status, body) = node.send(reqwest::Method::POST, "/sessions", Some(json!({"machine": "mill-3axis"}))).await;
    assert_eq!(status, StatusCode::CREATED, "{body}");
    body["id"].as_str().expect("id").to_string()
}
