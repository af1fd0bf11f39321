//! Durability under SIGKILL with machine-data and chain-data writes mixed in: writers store and
//! delete programs and change machine data (and re-import kinematic chain data) on their
//! sessions while the real `nctwin` is killed, several rounds in a row. After every restart the
//! server's state is exactly what was acknowledged: no acknowledged write lost, no acknowledged
//! delete undone; only the one write in flight at the kill may have gone either way.
//!
//! (`lifecycle.rs` has the plain program-writes SIGKILL test; this one adds the writes that
//! rebuild the channel.)

use crate::pg;
use crate::process;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use process::Nctwin;
use reqwest::StatusCode;
use serde_json::{Value, json};

/// What a session holds, as far as the writers were told.
#[derive(Debug, Clone, Default, PartialEq)]
struct Model {
    programs: BTreeMap<String, String>,
    /// `$MA_POS_LIMIT_PLUS[AX1]`.
    limit: f64,
}

/// One write.
#[derive(Debug, Clone)]
enum Op {
    Put(String, String),
    Delete(String),
    Limit(f64),
    /// Re-import of the session's kinematic chain data: changes no datum, rebuilds the channel.
    Chains,
}

impl Model {
    fn apply(&mut self, op: &Op) {
        match op {
            Op::Put(name, text) => drop(self.programs.insert(name.clone(), text.clone())),
            Op::Delete(name) => drop(self.programs.remove(name)),
            Op::Limit(value) => self.limit = *value,
            Op::Chains => {}
        }
    }
}

/// The `n`th write of writer `w` on `model`: puts, deletes of stored programs, machine-data
/// changes and chain re-imports interleaved.
fn op(w: usize, n: usize, model: &Model) -> Op {
    match n % 7 {
        2 | 5 if !model.programs.is_empty() => {
            let names: Vec<&String> = model.programs.keys().collect();
            Op::Delete(names[(n / 7) % names.len()].clone())
        }
        3 => Op::Limit(100.0 + (w * 10_000 + n) as f64),
        6 => Op::Chains,
        _ => Op::Put(format!("W{w}_{}", n % 11), format!("; writer {w} write {n}\nG0 X{}\nM17", n % 50)),
    }
}

/// Sends `op`; `Some(true)` acknowledged, `None` no answer (the server is gone: in doubt).
async fn send(server: &Nctwin, sid: &str, op: &Op, chains: &str) -> Option<bool> {
    let c = &server.client;
    let request = match op {
        Op::Put(name, text) => {
            c.put(server.url(&format!("/sessions/{sid}/programs/{name}"))).json(&json!({"text": text}))
        }
        Op::Delete(name) => c.delete(server.url(&format!("/sessions/{sid}/programs/{name}"))),
        Op::Limit(value) => c
            .put(server.url(&format!("/sessions/{sid}/machine-data")))
            .json(&json!({"text": format!("$MA_POS_LIMIT_PLUS[AX1]={value:.1}")})),
        Op::Chains => c
            .put(server.url(&format!("/sessions/{sid}/kinematic-chains")))
            .header("content-type", "text/plain")
            .body(chains.to_string()),
    };
    let response = request.send().await.ok()?;
    let status = response.status();
    if status == StatusCode::TOO_MANY_REQUESTS {
        return Some(false);
    }
    let body = response.text().await.ok()?;
    let expected = if matches!(op, Op::Delete(_)) { StatusCode::NO_CONTENT } else { StatusCode::OK };
    assert_eq!(status, expected, "{op:?} on {sid} before the kill: {body}");
    Some(true)
}

/// What the server holds for session `sid`.
async fn observed(server: &Nctwin, sid: &str) -> Model {
    let (status, list) = server.get(&format!("/sessions/{sid}/programs")).await;
    assert_eq!(status, StatusCode::OK, "{sid}: {list}");
    let mut programs = BTreeMap::new();
    for entry in list.as_array().expect("list") {
        let name = entry["name"].as_str().expect("name");
        let (status, program) = server.get(&format!("/sessions/{sid}/programs/{name}")).await;
        assert_eq!(status, StatusCode::OK, "{sid}/{name} is listed but not readable");
        programs.insert(name.to_string(), program["text"].as_str().expect("text").to_string());
    }
    let (_, data) = server.get(&format!("/sessions/{sid}/machine-data")).await;
    let text = data["text"].as_str().expect("machine data text");
    let limit = text
        .lines()
        .find_map(|l| l.strip_prefix("$MA_POS_LIMIT_PLUS[AX1]="))
        .and_then(|v| v.parse().ok())
        .expect("the X limit");
    Model { programs, limit }
}

fn data_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("nctwin-durability-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn sigkill_during_program_and_machine_data_writes_loses_and_undoes_nothing() {
    sigkill_rounds(None).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn sigkill_during_program_and_machine_data_writes_to_postgresql_loses_and_undoes_nothing() {
    let Some(url) = tokio::task::spawn_blocking(|| pg::postgres_database("durability")).await.expect("create") else {
        return;
    };
    sigkill_rounds(Some(&url)).await;
}

/// Three rounds of: writers write, the server is killed, the restarted server must hold exactly
/// the acknowledged state (the one write in flight per writer may have gone either way; what
/// the server holds then becomes the model of the next round).
async fn sigkill_rounds(database: Option<&str>) {
    const WRITERS: usize = 3;
    let dir = data_dir(if database.is_some() { "pg" } else { "sqlite" });
    let mut server = Arc::new(Nctwin::start_with(&dir, database));
    let mut sessions = Vec::new();
    for _ in 0..WRITERS {
        let response = server.client.post(server.url("/sessions")).send().await.expect("create");
        assert_eq!(response.status(), StatusCode::CREATED);
        let body: Value = response.json().await.expect("json");
        let sid = body["id"].as_str().expect("id").to_string();
        let model = observed(&server, &sid).await;
        sessions.push((sid, model));
    }
    let chains = server.client.get(server.url(&format!("/sessions/{}/kinematic-chains", sessions[0].0))).send().await;
    let chains = Arc::new(chains.expect("chains").text().await.expect("text"));

    let mut next_n = [0usize; WRITERS];
    for round in 0..3 {
        let mut writers = Vec::new();
        for (w, (sid, model)) in sessions.iter().cloned().enumerate() {
            let (server, chains, start) = (server.clone(), chains.clone(), next_n[w]);
            writers.push(tokio::spawn(async move {
                let mut model = model;
                let mut n = start;
                loop {
                    let op = op(w, n, &model);
                    match send(&server, &sid, &op, &chains).await {
                        Some(true) => {
                            model.apply(&op);
                            n += 1;
                        }
                        Some(false) => tokio::time::sleep(Duration::from_millis(20)).await,
                        None => return (model, Some(op), n + 1), // killed: this one is in doubt
                    }
                }
            }));
        }
        // Kill at a different moment each round.
        tokio::time::sleep(Duration::from_millis(500 + 250 * round)).await;
        server.signal("-KILL");
        let mut outcomes = Vec::new();
        for writer in writers {
            outcomes.push(writer.await.expect("writer"));
        }
        drop(server);

        server = Arc::new(Nctwin::start_with(&dir, database));
        let mut acknowledged = 0;
        for (w, (model, in_doubt, n)) in outcomes.into_iter().enumerate() {
            let sid = sessions[w].0.clone();
            acknowledged += n - next_n[w];
            let seen = observed(&server, &sid).await;
            let mut applied = model.clone();
            if let Some(op) = &in_doubt {
                applied.apply(op);
            }
            assert!(
                seen == model || seen == applied,
                "round {round}, {sid}: the server holds\n{seen:?}\nbut acknowledged was\n{model:?}\n(or with the write in flight, {in_doubt:?}:\n{applied:?})"
            );
            sessions[w].1 = seen;
            next_n[w] = n;
        }
        assert!(acknowledged >= 10, "round {round}: enough writes to mean something: {acknowledged}");
    }
    drop(server);
    let _ = std::fs::remove_dir_all(&dir);
}
