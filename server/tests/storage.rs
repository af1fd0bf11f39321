//! Storage conformance: one test body per behaviour, run against every backend: memory, SQLite
//! and PostgreSQL.
//!
//! PostgreSQL needs a server: `NCTWIN_TEST_POSTGRES_URL` (scripts/test.sh starts a throwaway
//! one and sets it). Each test gets a database of its own on it. Without the variable the
//! PostgreSQL cases print a note and pass without running.

use crate::common;
use crate::pg;

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use common::Server;
use nctwin_engine::lang::ProgramText;
use nctwin_server::storage::{
    self, ActiveProgram, Checkpoint, Claim, Lease, MemoryStorage, PostgresStorage, SessionRecord, SqliteStorage,
    Storage, TokenHashes,
};
use nctwin_server::{AppState, Config};
use pg::postgres_database;
use reqwest::StatusCode;
use serde_json::json;

fn record(id: &str, number: u64) -> SessionRecord {
    SessionRecord {
        id: id.into(),
        number,
        machine: "mill-3axis".into(),
        client_ip: Some("127.0.0.1".into()),
        tokens: TokenHashes { owner: "o".into(), operator: "p".into(), observer: "v".into() },
        checkpoint: Checkpoint {
            machine_data: "$MN_X=1\n".into(),
            positions: vec![1.5, -0.1, 0.0],
            mode: "AUTO".into(),
            channel_state: Some(r#"{"retained":{"tool":3}}"#.into()),
            active_program: None,
        },
        persistent: false,
        last_active_ms: None,
    }
}

/// SHA-256 in hex, by the `sha2` crate directly (what the storage keys the text by).
fn sha256_hex(text: &str) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect()
}

/// A program of `bytes` bytes that no compressor shrinks much (random digits in comments).
fn incompressible_program(bytes: usize, seed: u64) -> String {
    let mut state = seed;
    let mut text = String::with_capacity(bytes + 80);
    while text.len() < bytes {
        text.push_str("; ");
        for _ in 0..60 {
            // A 64-bit LCG (Knuth's MMIX constants); the high bits are the random ones.
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            text.push(char::from(b'0' + (state >> 60) as u8 % 10));
        }
        text.push('\n');
    }
    text.push_str("M30\n");
    text
}

// ---- the shared test bodies ------------------------------------------------------------------

/// The trait's contract, on an empty storage.
fn exercise(storage: &dyn Storage) {
    storage.check().expect("check");
    assert!(storage.load().expect("load").is_empty());
    storage.create_session(&record("s2", 2)).expect("create s2");
    storage.create_session(&record("s1", 1)).expect("create s1");
    storage.put_program("s1", "MAIN", "G0 X1\nM30").expect("put");
    storage.put_program("s1", "MAIN", "G0 X2\nM30").expect("replace");
    storage.put_program("s1", "AUX", "M17").expect("put aux");
    storage.put_program("s1", "ZZ", "M17").expect("put zz");
    storage.put_program("s1", "Ab", "M17").expect("put Ab");
    storage.delete_program("s1", "AUX").expect("delete aux");
    storage.delete_program("s1", "NONE").expect("deleting a missing program is fine");
    storage.delete_program("nobody", "NONE").expect("deleting a program of a missing session is fine");
    assert!(storage.put_program("nobody", "P", "M30").is_err(), "a program of an unknown session is refused");
    let moved = Checkpoint {
        machine_data: "".into(),
        positions: vec![0.1 + 0.2, 1e-300, -7.0, -0.0, f64::MAX, 5e-324],
        mode: "JOG".into(),
        channel_state: None,
        active_program: Some(ActiveProgram::hashed(ProgramText::from("G0 X1\nM0\nM30"))),
    };
    storage.save_checkpoint("s1", &moved).expect("checkpoint");
    let both = [("s2".to_string(), record("s2", 2).checkpoint), ("gone".to_string(), moved.clone())];
    storage.save_checkpoints(&both).expect("a batch, with a missing session in it");

    let all = storage.load().expect("load");
    assert_eq!(all.iter().map(|s| s.record.id.as_str()).collect::<Vec<_>>(), ["s1", "s2"], "creation order");
    let bits = |c: &Checkpoint| c.positions.iter().map(|p| p.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&all[0].record.checkpoint), bits(&moved), "positions round-trip bit for bit");
    assert_eq!(all[0].record.checkpoint, moved);
    let names = all[0].programs.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>();
    assert_eq!(names, ["Ab", "MAIN", "ZZ"], "programs by name, byte order");
    assert_eq!(all[0].programs[1].1, "G0 X2\nM30");
    assert_eq!(all[1].record, record("s2", 2));
    assert!(all[1].programs.is_empty());

    // A checkpoint without an AUTO program drops the stored one; a new one replaces it.
    let mut plain = moved.clone();
    plain.active_program = None;
    storage.save_checkpoint("s1", &plain).expect("checkpoint without a program");
    assert_eq!(storage.load().expect("load")[0].record.checkpoint.active_program, None);
    storage.save_checkpoint("s1", &moved).expect("checkpoint with it again");
    assert_eq!(storage.load().expect("load")[0].record.checkpoint, moved);

    // Creating a session again replaces it, and its programs go.
    let mut again = record("s1", 1);
    again.client_ip = None;
    storage.create_session(&again).expect("replace s1");
    let all = storage.load().expect("load");
    assert_eq!(all[0].record, again);
    assert!(all[0].programs.is_empty(), "a replaced session starts without programs");

    storage.delete_session("s1").expect("delete");
    storage.delete_session("s1").expect("deleting a missing session is fine");
    storage.save_checkpoint("s1", &moved).expect("a late checkpoint of a deleted session is ignored");
    let all = storage.load().expect("load");
    assert_eq!(all.len(), 1);
    assert_eq!(all[0].record.id, "s2");
}

/// What one opening wrote, the next opening reads (a restart).
fn survives_reopening(open: &dyn Fn() -> Box<dyn Storage>) {
    {
        let storage = open();
        storage.create_session(&record("s7", 7)).expect("create");
        storage.put_program("s7", "P", "M30").expect("program");
        let checkpoint = Checkpoint {
            machine_data: "$MN_Y=2\n".into(),
            positions: vec![3.25],
            mode: "MDA".into(),
            channel_state: Some("{}".into()),
            active_program: Some(ActiveProgram::hashed(ProgramText::from("G0 X1\nM30"))),
        };
        storage.save_checkpoint("s7", &checkpoint).expect("checkpoint");
    }
    let storage = open();
    let all = storage.load().expect("load");
    assert_eq!(all.len(), 1);
    assert_eq!(all[0].record.checkpoint.positions, vec![3.25]);
    assert_eq!(all[0].record.checkpoint.mode, "MDA");
    assert_eq!(all[0].record.checkpoint.channel_state.as_deref(), Some("{}"));
    let active = all[0].record.checkpoint.active_program.as_ref().expect("the active program");
    assert_eq!((&*active.text, active.sha256.as_str()), ("G0 X1\nM30", sha256_hex("G0 X1\nM30").as_str()));
    assert_eq!(all[0].programs, vec![("P".to_string(), "M30".to_string())]);
}

/// Several threads writing at once (the server's blocking workers) lose nothing.
fn concurrent_writers(storage: &(dyn Storage + Sync)) {
    std::thread::scope(|scope| {
        for t in 0..4u64 {
            scope.spawn(move || {
                for i in 0..10u64 {
                    let id = format!("t{t}-{i}");
                    storage.create_session(&record(&id, t * 100 + i)).expect("create");
                    storage.put_program(&id, "P", &format!("; {id}")).expect("program");
                }
            });
        }
    });
    let all = storage.load().expect("load");
    assert_eq!(all.len(), 40);
    assert!(all.windows(2).all(|w| w[0].record.number < w[1].record.number), "creation order");
    assert!(all.iter().all(|s| s.programs == [("P".to_string(), format!("; {}", s.record.id))]));
}

// ---- backends --------------------------------------------------------------------------------

/// A scratch directory of one test, removed again when the test ends (also when it fails).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("nctwin-storage-{name}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }

    fn join(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn memory_conforms() {
    exercise(&MemoryStorage::default());
    concurrent_writers(&MemoryStorage::default());
}

#[test]
fn sqlite_conforms() {
    let dir = TempDir::new("sqlite");
    exercise(&SqliteStorage::open(&dir.join("a.sqlite3")).expect("open"));
    survives_reopening(&|| Box::new(SqliteStorage::open(&dir.join("b.sqlite3")).expect("open")));
    concurrent_writers(&SqliteStorage::open(&dir.join("c.sqlite3")).expect("open"));
}

#[test]
fn postgres_conforms() {
    let Some(url) = postgres_database("conforms") else { return };
    let storage = PostgresStorage::open(&url).expect("open");
    assert_eq!(storage.backend(), "postgres");
    assert!(storage.describe().starts_with("postgres:"), "{}", storage.describe());
    exercise(&storage);
    let url = postgres_database("reopen").expect("database");
    // The same node again (a restart under its `--node-id`): its sessions are its own at once.
    survives_reopening(&|| Box::new(PostgresStorage::open_as(&url, node("n1", 60)).expect("open")));
    let url = postgres_database("concurrent").expect("database");
    concurrent_writers(&PostgresStorage::open(&url).expect("open"));
}

fn node(name: &str, seconds: u64) -> Lease {
    Lease { node: name.into(), period: Duration::from_secs(seconds) }
}

#[test]
fn postgres_nodes_share_one_database_and_the_schema_is_versioned() {
    let Some(url) = postgres_database("nodes") else { return };
    // Two nodes opening at once: the schema is created once.
    let (a, b) = std::thread::scope(|scope| {
        let a = scope.spawn(|| PostgresStorage::open_as(&url, node("a", 60)).expect("open a"));
        let b = scope.spawn(|| PostgresStorage::open_as(&url, node("b", 60)).expect("open b"));
        (a.join().expect("a"), b.join().expect("b"))
    });
    // Session numbers come from one sequence: no two nodes make the same id.
    let numbers = [a.next_session_number(), b.next_session_number(), a.next_session_number()]
        .map(|n| n.expect("number").expect("the database numbers"));
    assert_eq!(numbers, [1, 2, 3]);
    a.create_session(&record("s1", 1)).expect("create on a");
    a.put_program("s1", "P", "M30").expect("program on a");
    let refused = b.put_program("s1", "Q", "M30").expect_err("b does not hold s1");
    assert!(refused.message.contains("node `a`"), "{refused}");
    assert!(b.save_checkpoint("s1", &record("s1", 1).checkpoint).is_err(), "nor may b save its checkpoint");
    assert!(b.delete_session("s1").is_err(), "nor delete it");
    assert!(b.load().expect("load on b").is_empty(), "b loads only what it may serve");
    let seen = a.load().expect("load on a");
    assert_eq!(seen[0].programs, vec![("P".to_string(), "M30".to_string())]);

    let mut admin = postgres::Client::connect(&url, postgres::NoTls).expect("connect");
    let version: i32 = admin.query_one("SELECT max(version) FROM nctwin_schema", &[]).expect("version").get(0);
    assert_eq!(version, 5);
    let sync: String = admin.query_one("SHOW synchronous_commit", &[]).expect("show").get(0);
    assert!(!sync.is_empty());
    admin.execute("INSERT INTO nctwin_schema (version) VALUES (99)", &[]).expect("a newer schema");
    let refused = PostgresStorage::open(&url).expect_err("a newer schema is refused");
    assert!(refused.message.contains("newer"), "{refused}");
}

/// The AUTO program's text is written with the first checkpoint that refers to it and not
/// again while it is unchanged: its row keeps the transaction id (`xmin`) of that first write,
/// while the session row is rewritten by every checkpoint. A changed program is written.
#[test]
fn postgres_writes_the_active_program_only_when_it_changed() {
    let Some(url) = postgres_database("active") else { return };
    let storage = PostgresStorage::open_as(&url, node("a", 60)).expect("open");
    let mut admin = postgres::Client::connect(&url, postgres::NoTls).expect("connect");
    let xmin = |admin: &mut postgres::Client, table: &str, column: &str| -> String {
        let sql = format!("SELECT xmin::text FROM {table} WHERE {column} = 's1'");
        admin.query_one(sql.as_str(), &[]).expect("row").get(0)
    };
    storage.create_session(&record("s1", 1)).expect("create");
    let first = incompressible_program(1 << 20, 1);
    let mut checkpoint = record("s1", 1).checkpoint;
    checkpoint.active_program = Some(ActiveProgram::hashed(ProgramText::from(first.as_str())));
    storage.save_checkpoint("s1", &checkpoint).expect("first checkpoint");
    let written = xmin(&mut admin, "nctwin_active_programs", "session");
    let session = xmin(&mut admin, "nctwin_sessions", "id");

    checkpoint.positions[0] = 2.5;
    storage.save_checkpoint("s1", &checkpoint).expect("second checkpoint");
    storage.save_checkpoints(&[("s1".to_string(), checkpoint.clone())]).expect("shutdown checkpoint");
    assert_ne!(xmin(&mut admin, "nctwin_sessions", "id"), session, "the session row was written");
    assert_eq!(xmin(&mut admin, "nctwin_active_programs", "session"), written, "the text was not");

    let second = incompressible_program(1 << 20, 2);
    checkpoint.active_program = Some(ActiveProgram::hashed(ProgramText::from(second.as_str())));
    storage.save_checkpoint("s1", &checkpoint).expect("a new program");
    assert_ne!(xmin(&mut admin, "nctwin_active_programs", "session"), written, "a changed text is written");
    let loaded = storage.load().expect("load");
    let active = loaded[0].record.checkpoint.active_program.as_ref().expect("active program");
    assert!(*active.text == *second && active.sha256 == sha256_hex(&second));
    assert_eq!(loaded[0].record.checkpoint.positions[0], 2.5);
}

#[test]
fn a_lease_that_is_not_renewed_expires_and_another_node_takes_the_session_over() {
    let Some(url) = postgres_database("lease") else { return };
    let a = PostgresStorage::open_as(&url, node("a", 1)).expect("open a");
    let b = PostgresStorage::open_as(&url, node("b", 1)).expect("open b");
    a.create_session(&record("s1", 1)).expect("create on a");
    a.create_session(&record("s2", 2)).expect("create on a");
    match b.claim_session("s1").expect("claim") {
        Claim::HeldBy { node, seconds_left } => {
            assert_eq!(node, "a");
            assert!(seconds_left > 0.0 && seconds_left <= 1.0, "{seconds_left}");
        }
        other => panic!("s1 is a's: {other:?}"),
    }
    assert_eq!(b.claim_session("s9").expect("claim"), Claim::Missing);
    // a renews; then a stops renewing (it "died") and its leases run out after 1 s.
    assert_eq!(a.renew_leases().expect("renew").map(sorted), Some(vec!["s1".to_string(), "s2".to_string()]));
    std::thread::sleep(Duration::from_millis(1_300));
    let Claim::Claimed(saved) = b.claim_session("s1").expect("claim") else { panic!("expired: b takes s1") };
    assert_eq!(saved.record, record("s1", 1));
    // a's late writes are refused; its renewal reports that s1 is gone, s2 (not taken) is kept.
    let late = a.save_checkpoint("s1", &record("s1", 1).checkpoint).expect_err("fenced");
    assert!(late.message.contains("node `b`"), "{late}");
    assert_eq!(a.renew_leases().expect("renew").map(sorted), Some(vec!["s2".to_string()]));
    // b gives its leases up (shutdown): a may take s1 back at once.
    b.release_leases().expect("release");
    assert!(matches!(a.claim_session("s1").expect("claim"), Claim::Claimed(_)));
}

/// A lease renewal writes one row per node, however many sessions the node holds: with 5000
/// sessions leased to node `a` (each with 20 KB of machine data, as real ones have), a renewal
/// rewrites none of their rows (their `xmin`, the writing transaction, stays) and still returns
/// every id the node holds. Prints its time beside that of schema 4's renewal (one `UPDATE` of
/// every session row of the node) on the same rows, for the README.
#[test]
fn a_lease_renewal_writes_one_row_per_node_whatever_the_sessions() {
    let Some(url) = postgres_database("renewal") else { return };
    let a = PostgresStorage::open_as(&url, node("a", 6)).expect("open a");
    a.create_session(&record("s1", 1)).expect("create");
    let mut admin = postgres::Client::connect(&url, postgres::NoTls).expect("connect");
    admin
        .batch_execute(
            "UPDATE nctwin_sessions SET machine_data = repeat('$MA_X=1' || chr(10), 2500) WHERE id = 's1';
             INSERT INTO nctwin_sessions (id, number, machine, client_ip, owner_hash, operator_hash, observer_hash,
                                          machine_data, positions, mode, channel_state, lease_node, lease_expires,
                                          persistent, last_active_ms)
                 SELECT 'x' || g, g + 1, machine, client_ip, owner_hash, operator_hash, observer_hash, machine_data,
                        positions, mode, channel_state, lease_node, lease_expires, persistent, last_active_ms
                 FROM nctwin_sessions, generate_series(1, 4999) g WHERE id = 's1';",
        )
        .expect("5000 sessions of node a");
    admin.batch_execute("VACUUM ANALYZE nctwin_sessions").expect("vacuum");
    let xmins = |admin: &mut postgres::Client| -> Vec<String> {
        let rows = admin.query("SELECT xmin::text FROM nctwin_sessions ORDER BY id", &[]).expect("xmin");
        rows.iter().map(|r| r.get(0)).collect()
    };
    let before = xmins(&mut admin);
    let median = |mut times: Vec<f64>| {
        times.sort_by(f64::total_cmp);
        times[times.len() / 2]
    };
    let mut per_node = Vec::new();
    for _ in 0..21 {
        let t = std::time::Instant::now();
        let held = a.renew_leases().expect("renew").expect("leases");
        per_node.push(t.elapsed().as_secs_f64());
        assert_eq!(held.len(), 5000);
    }
    assert_eq!(xmins(&mut admin), before, "no session row was written by the renewals");
    let mut per_session = Vec::new();
    for _ in 0..21 {
        let t = std::time::Instant::now();
        let n = admin
            .query(
                "UPDATE nctwin_sessions SET lease_expires = now() + interval '6 seconds' WHERE lease_node = 'a' RETURNING id",
                &[],
            )
            .expect("schema 4's renewal")
            .len();
        per_session.push(t.elapsed().as_secs_f64());
        assert_eq!(n, 5000);
    }
    eprintln!(
        "lease renewal with 5000 sessions: {:.2} ms per node (this schema), {:.2} ms rewriting every session row (schema 4); medians of 21",
        median(per_node) * 1e3,
        median(per_session) * 1e3
    );
}

/// Claims of several sessions at once (a node taking over a dead node's sessions): each id
/// gets its own outcome, in the order asked, in one transaction.
#[test]
fn several_sessions_are_claimed_at_once_each_with_its_outcome() {
    let Some(url) = postgres_database("claims") else { return };
    let a = PostgresStorage::open_as(&url, node("a", 1)).expect("open a");
    let b = PostgresStorage::open_as(&url, node("b", 60)).expect("open b");
    let c = PostgresStorage::open_as(&url, node("c", 60)).expect("open c");
    a.create_session(&record("s1", 1)).expect("create on a");
    a.create_session(&record("s2", 2)).expect("create on a");
    c.create_session(&record("s3", 3)).expect("create on c");
    // a stops renewing: after its 1 s lease, b may take s1 and s2 but not c's s3.
    std::thread::sleep(Duration::from_millis(1_300));
    let ids: Vec<String> = ["s2", "s3", "s9", "s1"].iter().map(|s| s.to_string()).collect();
    let claims = b.claim_sessions(&ids).expect("claims");
    let order: Vec<&str> = claims.iter().map(|(id, _)| id.as_str()).collect();
    assert_eq!(order, ["s2", "s3", "s9", "s1"]);
    assert!(matches!(&claims[0].1, Claim::Claimed(saved) if saved.record == record("s2", 2)), "{:?}", claims[0]);
    assert!(matches!(&claims[1].1, Claim::HeldBy { node, seconds_left } if node == "c" && *seconds_left > 50.0));
    assert_eq!(claims[2].1, Claim::Missing);
    assert!(matches!(&claims[3].1, Claim::Claimed(saved) if saved.record == record("s1", 1)));
    assert_eq!(b.renew_leases().expect("renew").map(sorted), Some(vec!["s1".to_string(), "s2".to_string()]));
}

fn sorted(mut v: Vec<String>) -> Vec<String> {
    v.sort();
    v
}

/// A database of schema version 1 (before checkpoints held the channel state and sessions had
/// leases) is migrated in place: every row stays, the new columns are empty, numbering
/// continues above the stored sessions.
#[test]
fn postgres_schema_1_is_migrated_without_losing_data() {
    let Some(url) = postgres_database("migrate") else { return };
    let mut admin = postgres::Client::connect(&url, postgres::NoTls).expect("connect");
    admin
        .batch_execute(
            "CREATE TABLE nctwin_schema (version INTEGER NOT NULL);
             INSERT INTO nctwin_schema VALUES (1);
             CREATE TABLE nctwin_sessions (
                 id TEXT PRIMARY KEY, number BIGINT NOT NULL, machine TEXT NOT NULL, client_ip TEXT,
                 owner_hash TEXT NOT NULL, operator_hash TEXT NOT NULL, observer_hash TEXT NOT NULL,
                 machine_data TEXT NOT NULL, positions DOUBLE PRECISION[] NOT NULL, mode TEXT NOT NULL);
             CREATE TABLE nctwin_programs (
                 session TEXT NOT NULL REFERENCES nctwin_sessions(id) ON DELETE CASCADE,
                 name TEXT NOT NULL, text TEXT NOT NULL, PRIMARY KEY (session, name));
             INSERT INTO nctwin_sessions VALUES
                 ('s7', 7, 'mill-3axis', NULL, 'o', 'p', 'v', '$MN_X=1', '{1.5,-0.1,0}', 'JOG');
             INSERT INTO nctwin_programs VALUES ('s7', 'MAIN', 'G0 X1\nM30');",
        )
        .expect("a version 1 database");
    let storage = PostgresStorage::open_as(&url, node("a", 60)).expect("migrated");
    let all = storage.load().expect("load");
    assert_eq!(all.len(), 1);
    let c = &all[0].record.checkpoint;
    assert_eq!(
        (c.machine_data.as_str(), c.positions.as_slice(), c.mode.as_str()),
        ("$MN_X=1", &[1.5, -0.1, 0.0][..], "JOG")
    );
    assert_eq!(c.channel_state, None);
    assert_eq!(all[0].programs, vec![("MAIN".to_string(), "G0 X1\nM30".to_string())]);
    assert_eq!(storage.next_session_number().expect("number"), Some(8), "above the stored s7");
    let version: i32 = admin.query_one("SELECT max(version) FROM nctwin_schema", &[]).expect("version").get(0);
    assert_eq!(version, 5);
}

#[test]
fn sqlite_schema_1_is_migrated_without_losing_data() {
    let dir = TempDir::new("migrate");
    let path = dir.join("v1.sqlite3");
    {
        let c = rusqlite::Connection::open(&path).expect("create");
        c.execute_batch(
            "CREATE TABLE sessions (
                 id TEXT PRIMARY KEY, number INTEGER NOT NULL, machine TEXT NOT NULL, client_ip TEXT,
                 owner_hash TEXT NOT NULL, operator_hash TEXT NOT NULL, observer_hash TEXT NOT NULL,
                 machine_data TEXT NOT NULL, positions TEXT NOT NULL, mode TEXT NOT NULL);
             CREATE TABLE programs (
                 session TEXT NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
                 name TEXT NOT NULL, text TEXT NOT NULL, PRIMARY KEY (session, name));
             INSERT INTO sessions VALUES ('s7', 7, 'mill-3axis', NULL, 'o', 'p', 'v', '$MN_X=1', '[1.5,-0.1,0.0]', 'JOG');
             INSERT INTO programs VALUES ('s7', 'MAIN', 'M30');
             PRAGMA user_version = 1;",
        )
        .expect("a version 1 file");
    }
    let storage = SqliteStorage::open(&path).expect("migrated");
    let all = storage.load().expect("load");
    assert_eq!(all.len(), 1);
    assert_eq!(all[0].record.checkpoint.positions, vec![1.5, -0.1, 0.0]);
    assert_eq!(all[0].record.checkpoint.channel_state, None);
    assert_eq!(all[0].programs, vec![("MAIN".to_string(), "M30".to_string())]);
    let mut checkpoint = all[0].record.checkpoint.clone();
    checkpoint.channel_state = Some("{}".into());
    storage.save_checkpoint("s7", &checkpoint).expect("the new column is written");
    drop(storage);
    let version: i64 = rusqlite::Connection::open(&path)
        .expect("open")
        .query_row("PRAGMA user_version", [], |r| r.get(0))
        .expect("version");
    assert_eq!(version, 4);
    assert_eq!(SqliteStorage::open(&path).expect("reopen").load().expect("load")[0].record.checkpoint, checkpoint);
}

/// A session saved by schema version 2 (the AUTO program's text inline in the channel state)
/// is migrated and restored: the program stopped at its M0 comes back stopped there, and its
/// next checkpoint moves the text into the active program's row.
#[tokio::test]
async fn a_sqlite_session_of_schema_2_with_its_program_inline_is_restored() {
    let dir = common::temp_data_dir();
    std::fs::create_dir_all(&dir).expect("data dir");
    let mut channel = nctwin_engine::Channel::from_preset("mill-3axis", "").expect("preset");
    channel.run_program("G0 X1\nM0\nG0 X2\nM30").expect("run");
    for _ in 0..100_000 {
        if !channel.is_busy() {
            break;
        }
        channel.step();
    }
    // What schema version 2 wrote: the full state, text included.
    let state = serde_json::to_string(&channel.resume_state()).expect("json");
    assert!(state.contains("G0 X2"), "{state}");
    {
        let c = rusqlite::Connection::open(dir.join(storage::SQLITE_FILE)).expect("create");
        c.execute_batch(
            "CREATE TABLE sessions (
                 id TEXT PRIMARY KEY, number INTEGER NOT NULL, machine TEXT NOT NULL, client_ip TEXT,
                 owner_hash TEXT NOT NULL, operator_hash TEXT NOT NULL, observer_hash TEXT NOT NULL,
                 machine_data TEXT NOT NULL, positions TEXT NOT NULL, mode TEXT NOT NULL, channel_state TEXT);
             CREATE TABLE programs (
                 session TEXT NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
                 name TEXT NOT NULL, text TEXT NOT NULL, PRIMARY KEY (session, name));
             PRAGMA user_version = 2;",
        )
        .expect("a version 2 file");
        let positions = serde_json::to_string(channel.axis_positions()).expect("json");
        c.execute(
            "INSERT INTO sessions VALUES ('s7', 7, 'mill-3axis', NULL, 'o', 'p', 'v', ?1, ?2, 'AUTO', ?3)",
            rusqlite::params![channel.machine_data().to_text(), positions, state],
        )
        .expect("a version 2 row");
    }
    let server = Server::start_config(Config::new(dir.clone(), common::WEB_DIR)).await;
    let state = server.get("/sessions/s7/state").await.body;
    assert_eq!((state["status"].as_str(), state["block"]["line"].as_i64()), (Some("stopped"), Some(2)), "{state}");
    // The shutdown's checkpoint writes the text to its own row and leaves it out of the state.
    let dir = server.stop().await;
    let all = SqliteStorage::open(&dir.join(storage::SQLITE_FILE)).expect("reopen").load().expect("load");
    let checkpoint = &all[0].record.checkpoint;
    assert_eq!(checkpoint.active_program.as_ref().map(|p| &*p.text), Some("G0 X1\nM0\nG0 X2\nM30"));
    assert!(!checkpoint.channel_state.as_deref().unwrap_or("").contains("G0 X2"), "{checkpoint:?}");
    let server = Server::start_config(Config::new(dir.clone(), common::WEB_DIR)).await;
    let reply = server.post("/sessions/s7/start", json!({"pace": "fast", "wait": true})).await;
    assert_eq!((reply.body["status"].as_str(), common::pos(&reply.body, "machine", "X")), (Some("idle"), 2.0));
    let _ = std::fs::remove_dir_all(server.stop().await);
}

#[test]
fn postgres_reconnects_after_the_connection_broke() {
    let Some(url) = postgres_database("reconnect") else { return };
    let storage = PostgresStorage::open(&url).expect("open");
    storage.create_session(&record("s1", 1)).expect("create");
    // Kill every other connection to this database: the storage's connection breaks.
    let mut admin = postgres::Client::connect(&url, postgres::NoTls).expect("connect");
    admin
        .execute(
            "SELECT pg_terminate_backend(pid) FROM pg_stat_activity
             WHERE datname = current_database() AND pid <> pg_backend_pid()",
            &[],
        )
        .expect("terminate");
    // Termination is asynchronous: wait until the storage's backend is gone.
    for _ in 0..500 {
        let others: i64 = admin
            .query_one(
                "SELECT count(*) FROM pg_stat_activity WHERE datname = current_database() AND pid <> pg_backend_pid()",
                &[],
            )
            .expect("count")
            .get(0);
        if others == 0 {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    // The call that meets the broken connection may fail (and is then not acknowledged); the
    // next one runs on a new connection.
    let _ = storage.check();
    storage.check().expect("reconnected");
    assert_eq!(storage.load().expect("load").len(), 1);
}

#[test]
fn an_unknown_database_scheme_is_refused() {
    let error =
        storage::open(Some("mysql://u@h/db"), &TempDir::new("scheme").0, Lease::default()).expect_err("refused");
    assert!(error.message.contains("mysql"), "{error}");
    assert!(storage::open(Some("postgres://u@[bad"), &TempDir::new("bad").0, Lease::default()).is_err(), "invalid URL");
    // No TLS in this build: a URL that requires it is refused before any connection is tried.
    let tls = PostgresStorage::open("postgres://u@127.0.0.1:1/db?sslmode=require").expect_err("refused");
    assert!(tls.message.contains("sslmode=require") && tls.message.contains("no TLS"), "{tls}");
}

/// The whole server on PostgreSQL: sessions and programs survive a restart, and health says
/// which backend answers.
#[tokio::test]
async fn the_server_restarts_on_postgres() {
    let Some(url) = tokio::task::spawn_blocking(|| postgres_database("server")).await.expect("task") else {
        return;
    };
    let config = || Config { database: Some(url.clone()), ..Config::new(common::temp_data_dir(), common::WEB_DIR) };
    let server = Server::start_config(config()).await;
    let health = server.get("/health").await.body;
    assert_eq!(health["storage"], json!({"backend": "postgres", "status": "ok"}));
    let id = server.session("mill-3axis").await;
    let reply = server.put(&format!("/sessions/{id}/programs/main"), json!({"text": "G0 X1\nM30"})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let reply = server
        .post(&format!("/sessions/{id}/mda"), json!({"program": "G0 X12.5 Y-3.25", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let before = server.get(&format!("/sessions/{id}/state")).await.body;
    let dir = server.stop().await;
    let _ = std::fs::remove_dir_all(dir);

    let server = Server::start_config(config()).await;
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["positions"], before["positions"]);
    let program = server.get(&format!("/sessions/{id}/programs/MAIN")).await.body;
    assert_eq!(program["text"], "G0 X1\nM30");
    // An AUTO program stopped at its M0 comes back stopped there (its text from the active
    // program's row), and NC start goes on behind the M0.
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X1\nM0\nG0 X2\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(
        (reply.body["status"].as_str(), reply.body["block"]["line"].as_i64()),
        (Some("stopped"), Some(2)),
        "{}",
        reply.body
    );
    let dir = server.stop().await;
    let _ = std::fs::remove_dir_all(dir);
    let server = Server::start_config(config()).await;
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!((state["status"].as_str(), state["block"]["line"].as_i64()), (Some("stopped"), Some(2)), "{state}");
    let reply = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!((reply.body["status"].as_str(), common::pos(&reply.body, "machine", "X")), (Some("idle"), 2.0));
    // The last `AppState` (and with it the PostgreSQL client) is dropped on an async thread.
    drop(server);
}

#[tokio::test]
async fn health_reports_the_backend() {
    let state = AppState::with_storage(
        Config::new(common::temp_data_dir(), common::WEB_DIR),
        Arc::new(MemoryStorage::default()),
    );
    let server = Server::start_state(state).await;
    assert_eq!(server.get("/health").await.body["storage"]["backend"], "memory");
}

/// Node `a` (lease period `lease_s`) on a fresh test database with one session, whose row's
/// lease is then rewritten to node `b` for `b_interval` (a PostgreSQL interval), as another
/// node taking it over would. `None` without a test PostgreSQL server.
async fn session_of_node_a_taken_by_b(
    database: &'static str,
    lease_s: u64,
    b_interval: &'static str,
) -> Option<(Server, String)> {
    let url = tokio::task::spawn_blocking(move || postgres_database(database)).await.expect("task")?;
    let config = Config {
        database: Some(url.clone()),
        node_id: Some("a".into()),
        lease_period: Duration::from_secs(lease_s),
        ..Config::new(common::temp_data_dir(), common::WEB_DIR)
    };
    let server = Server::start_config(config).await;
    let id = server.session("mill-3axis").await;
    let key = id.clone();
    tokio::task::spawn_blocking(move || {
        let mut admin = postgres::Client::connect(&url, postgres::NoTls).expect("connect");
        // The lease is node b's row (renewed per node); the session row names b as its holder.
        let statement = format!(
            "INSERT INTO nctwin_nodes (node, expires) VALUES ('b', now() + interval '{b_interval}')
             ON CONFLICT (node) DO UPDATE SET expires = excluded.expires"
        );
        admin.execute(statement.as_str(), &[]).expect("node b");
        let n = admin.execute("UPDATE nctwin_sessions SET lease_node = 'b' WHERE id = $1", &[&key]).expect("take over");
        assert_eq!(n, 1);
    })
    .await
    .expect("task");
    Some((server, id))
}

/// A node whose session was taken by another node (here: the row's lease rewritten, as after
/// a network partition longer than the lease) stops serving it at its next heartbeat, answers
/// 421 naming the new holder, and cannot write it any more.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_node_that_lost_a_lease_stops_serving_the_session() {
    let Some((server, id)) = session_of_node_a_taken_by_b("lost", 1, "1 hour").await else { return };
    // The heartbeat runs three times per second here.
    let mut reply = server.get(&format!("/sessions/{id}/state")).await;
    for _ in 0..100 {
        if reply.status != StatusCode::OK {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
        reply = server.get(&format!("/sessions/{id}/state")).await;
    }
    assert_eq!(reply.status, StatusCode::MISDIRECTED_REQUEST, "{}", reply.body);
    assert!(reply.body["error"].as_str().expect("message").contains("node `b`"), "{}", reply.body);
    assert_eq!(server.get("/sessions").await.body, json!([]), "no longer listed here");
    let write = server.put(&format!("/sessions/{id}/programs/P"), json!({"text": "M30"})).await;
    assert_eq!(write.status, StatusCode::MISDIRECTED_REQUEST, "{}", write.body);
    drop(server);
}

/// A write that finds the session's lease taken after this node routed the request to itself
/// (here: before any heartbeat noticed, the lease period being a minute) is refused with 421
/// naming the holder, not 503, and this node stops serving the session at once.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_write_that_finds_the_lease_taken_answers_421_naming_the_holder() {
    // b's lease is fresh (the whole period left): b is alive, so a answers 421 at once rather
    // than waiting for the lease of a holder that looks dead.
    let Some((server, id)) = session_of_node_a_taken_by_b("taken", 60, "60 seconds").await else { return };
    // Still served here (no heartbeat yet): the write reaches the database and is fenced.
    assert_eq!(server.get(&format!("/sessions/{id}/state")).await.status, StatusCode::OK);
    let write = server.put(&format!("/sessions/{id}/programs/P"), json!({"text": "M30"})).await;
    assert_eq!(write.status, StatusCode::MISDIRECTED_REQUEST, "{}", write.body);
    let message = write.body["error"].as_str().expect("message");
    assert!(message.contains("node `b`") && message.contains(&format!("`{id}`")), "{message}");
    // The lease runs 60 s: the message says so, rounded (59 or 60 by the time it is read).
    assert!(message.contains("another 60 s") || message.contains("another 59 s"), "{message}");
    // Not served here any more: 421 from the routing check too, and not listed.
    let reply = server.get(&format!("/sessions/{id}/state")).await;
    assert_eq!(reply.status, StatusCode::MISDIRECTED_REQUEST, "{}", reply.body);
    assert_eq!(server.get("/sessions").await.body, json!([]));
    drop(server);
}

/// Behind a proxy (deploy/haproxy.cfg): a node names the holder of a session in
/// `nctwin-holder` (itself on a success, the holder on a 421). A request the proxy meant for a
/// holder it could not reach (`nctwin-routed-holder`) is not answered 421: the node waits
/// until that holder's lease has run out, takes the session over and answers.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_request_meant_for_an_unreachable_holder_waits_for_its_lease_and_is_served() {
    // a's period 6 s (renewing every 2 s); b's lease has 4 s left, so b looks alive (a live
    // holder never has less than 4 s; below 3 s, a second of slack, it missed a renewal): no
    // wait without the header.
    let Some((server, id)) = session_of_node_a_taken_by_b("routed", 6, "4 seconds").await else { return };
    assert_eq!(server.get(&format!("/sessions/{id}/state")).await.headers["nctwin-holder"], "a", "a serves it still");
    // The write is fenced (b holds the row): 421 naming b, and a stops serving it.
    let write = server.put(&format!("/sessions/{id}/programs/P"), json!({"text": "M30"})).await;
    assert_eq!(write.status, StatusCode::MISDIRECTED_REQUEST, "{}", write.body);
    assert_eq!(write.headers["nctwin-holder"], "b");
    let reply = server.get(&format!("/sessions/{id}/state")).await;
    assert_eq!(reply.status, StatusCode::MISDIRECTED_REQUEST, "b looks alive: {}", reply.body);
    assert_eq!(reply.headers["nctwin-holder"], "b");
    // The proxy meant the request for b and could not reach it: a waits out b's lease (under
    // 4 s now) and takes the session over.
    let started = std::time::Instant::now();
    let request = server.client.get(server.url(&format!("/sessions/{id}/state"))).header("nctwin-routed-holder", "b");
    let reply = server.send(request).await;
    let waited = started.elapsed().as_secs_f64();
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.headers["nctwin-holder"], "a");
    assert!(waited > 2.0 && waited < 5.0, "waited {waited} s for the rest of b's lease");
    drop(server);
}
