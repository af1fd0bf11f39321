//! Persistence through a restart: two in-process servers, one after the other, on the same data
//! directory (SQLite). The real binary's restart, SIGTERM and SIGKILL are in `lifecycle.rs`.

use crate::common;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use common::{Server, error_message, pos};
use nctwin_server::storage::{Checkpoint, MemoryStorage, SavedSession, SessionRecord, Storage, StorageError};
use nctwin_server::{AppState, Config};
use reqwest::StatusCode;
use serde_json::json;

async fn restart(server: Server) -> Server {
    let dir = server.stop().await;
    Server::start_config(Config::new(dir, common::WEB_DIR)).await
}

#[tokio::test]
async fn sessions_programs_machine_data_positions_and_mode_survive_a_restart() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let other = server.session("lathe-2axis").await;

    let sub = "PROC HOLE\nG1 Z-1 F100\nG0 Z5\nRET";
    assert_eq!(
        server.put(&format!("/sessions/{id}/programs/hole.spf"), json!({"text": sub})).await.status,
        StatusCode::OK
    );
    let reply =
        server.put(&format!("/sessions/{id}/machine-data"), json!({"text": "$MA_POS_LIMIT_PLUS[AX1]=50."})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let reply = server
        .post(&format!("/sessions/{id}/mda"), json!({"program": "G0 X12.5 Y-3.25 Z7", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    let before = server.put(&format!("/sessions/{id}/mode"), json!({"mode": "JOG"})).await.body;
    assert_eq!(before["mode"], "JOG");

    let server = restart(server).await;
    let list = server.get("/sessions").await.body;
    assert_eq!(
        list,
        json!([
            {"id": id, "machine": "mill-3axis", "status": "idle", "mode": "JOG"},
            {"id": other, "machine": "lathe-2axis", "status": "idle", "mode": "AUTO"},
        ])
    );
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["positions"], before["positions"], "positions bit for bit");
    let program = server.get(&format!("/sessions/{id}/programs/HOLE")).await;
    assert_eq!(program.body, json!({"name": "HOLE", "text": sub}));

    // The machine data came back too: X stops at the software limit of 50.
    server.put(&format!("/sessions/{id}/mode"), json!({"mode": "AUTO"})).await;
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X60\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.body["status"], "alarm", "{}", reply.body);

    let new = server.session("mill-3axis").await;
    assert!(new != id && new != other, "new ids continue after the restored ones: {new}");
}

#[tokio::test]
async fn deleted_sessions_and_programs_stay_deleted() {
    let server = Server::start().await;
    let gone = server.session("mill-3axis").await;
    let kept = server.session("mill-3axis").await;
    for name in ["A", "B"] {
        server.put(&format!("/sessions/{kept}/programs/{name}"), json!({"text": "M17"})).await;
    }
    assert_eq!(server.delete(&format!("/sessions/{kept}/programs/a")).await.status, StatusCode::NO_CONTENT);
    assert_eq!(server.delete(&format!("/sessions/{gone}")).await.status, StatusCode::NO_CONTENT);

    let server = restart(server).await;
    error_message(&server.get(&format!("/sessions/{gone}")).await, StatusCode::NOT_FOUND);
    let programs = server.get(&format!("/sessions/{kept}/programs")).await.body;
    assert_eq!(programs, json!([{"name": "B", "size": 3}]));
}

#[tokio::test]
async fn a_running_program_comes_back_stopped_at_its_block_where_the_axes_were_at_shutdown() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server.post(&format!("/sessions/{id}/run"), json!({"program": "G1 X100 F600\nM30"})).await;
    assert_eq!(reply.body["status"], "running");
    server.state_until(&id, "X moved", |s| pos(s, "machine", "X") > 0.5).await;

    let server = restart(server).await;
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["status"], "stopped", "{state}");
    assert!(state["block"]["line"] == 1 && state["alarms"] == json!([]), "{state}");
    let x = pos(&state, "machine", "X");
    assert!(x > 0.5 && x < 100.0, "stopped between start and target: {x}");
    // It is a usable session: after a reset it runs a program from there.
    assert_eq!(server.post_empty(&format!("/sessions/{id}/reset")).await.body["status"], "idle");
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G1 X0 F5000\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!((reply.body["status"].as_str(), pos(&reply.body, "machine", "X")), (Some("idle"), 0.0));
}

#[tokio::test]
async fn positions_are_saved_when_a_command_ends_without_a_graceful_shutdown() {
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": "G0 X3 Y4\nM30", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(pos(&reply.body, "machine", "Y"), 4.0);
    // Read the database while the server still runs: the checkpoint is written in the
    // background shortly after the command has come to rest.
    let db = server.data_dir.join(nctwin_server::storage::SQLITE_FILE);
    let mut saved = Vec::new();
    for _ in 0..200 {
        let storage = nctwin_server::storage::SqliteStorage::open(&db).expect("open");
        use nctwin_server::storage::Storage;
        saved = storage.load().expect("load");
        if saved[0].record.checkpoint.positions == [3.0, 4.0, 0.0] {
            return;
        }
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    panic!("positions never saved: {:?}", saved.first().map(|s| &s.record.checkpoint));
}

/// A storage that works until it is told to fail (a full disk, a lost database file).
#[derive(Debug, Default)]
struct BreakableStorage {
    inner: MemoryStorage,
    broken: AtomicBool,
}

impl BreakableStorage {
    fn ok(&self) -> Result<(), StorageError> {
        if self.broken.load(Ordering::Relaxed) { Err(StorageError::new("disk full")) } else { Ok(()) }
    }
}

impl Storage for BreakableStorage {
    fn describe(&self) -> String {
        "breakable".into()
    }
    fn backend(&self) -> &'static str {
        "memory"
    }
    fn check(&self) -> Result<(), StorageError> {
        self.ok()
    }
    fn load(&self) -> Result<Vec<SavedSession>, StorageError> {
        self.ok()?;
        self.inner.load()
    }
    fn create_session(&self, record: &SessionRecord) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.create_session(record)
    }
    fn save_checkpoint(&self, id: &str, checkpoint: &Checkpoint) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.save_checkpoint(id, checkpoint)
    }
    fn delete_session(&self, id: &str) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.delete_session(id)
    }
    fn put_program(&self, id: &str, name: &str, text: &str) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.put_program(id, name, text)
    }
    fn delete_program(&self, id: &str, name: &str) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.delete_program(id, name)
    }
    fn set_persistent(&self, id: &str, persistent: bool) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.set_persistent(id, persistent)
    }
    fn save_activity(&self, activity: &[(String, u64)]) -> Result<(), StorageError> {
        self.ok()?;
        self.inner.save_activity(activity)
    }
}

#[tokio::test]
async fn a_failing_storage_is_503_nothing_is_acknowledged_and_health_says_so() {
    let storage = Arc::new(BreakableStorage::default());
    let state = AppState::with_storage(Config::new(common::temp_data_dir(), common::WEB_DIR), storage.clone());
    let server = Server::start_state(state).await;
    let id = server.session("mill-3axis").await;
    storage.broken.store(true, Ordering::Relaxed);

    let message = error_message(&server.post_empty("/sessions").await, StatusCode::SERVICE_UNAVAILABLE);
    assert!(message.contains("disk full"), "{message}");
    assert_eq!(server.get("/sessions").await.body.as_array().map(Vec::len), Some(1), "no session without its record");
    error_message(
        &server.put(&format!("/sessions/{id}/programs/P"), json!({"text": "M17"})).await,
        StatusCode::SERVICE_UNAVAILABLE,
    );
    error_message(&server.delete(&format!("/sessions/{id}")).await, StatusCode::SERVICE_UNAVAILABLE);
    assert_eq!(server.get(&format!("/sessions/{id}")).await.status, StatusCode::OK, "not deleted when not saved");
    let health = server.get("/health").await.body;
    assert_eq!((health["status"].as_str(), health["storage"]["status"].as_str()), (Some("degraded"), Some("error")));
    assert!(health["storage"]["error"].as_str().is_some_and(|e| e.contains("disk full")), "{health}");

    storage.broken.store(false, Ordering::Relaxed);
    assert_eq!(server.get("/health").await.body["status"], "ok");
    assert_eq!(server.delete(&format!("/sessions/{id}")).await.status, StatusCode::NO_CONTENT);
}

/// W1 p.4-3 (REFERENCE §7.3): a table toolholder (kind P) about +Y at 45° with l4 = (0, 0, 15)
/// and a 13 mm tool: WCS (0, 10, 0) is machine (15·sin 45°, 10, −15·(1 − cos 45°) + 13) =
/// (10.607, 10, 8.607). Holder 1 with this data comes with the session's machine data.
const W1_TABLE: &str = "$MN_MM_NUM_TOOL_CARRIER=1\n$TC_CARR8[1]=1\n$TC_CARR20[1]=15\n$TC_CARR13[1]=45\n\
                        $TC_CARR23[1]=\"P\"\n$TC_DP3[1,1]=13";

fn near(got: f64, want: f64, what: &str) {
    assert!((got - want).abs() < 1e-9, "{what}: {got}, expected {want}");
}

#[tokio::test]
async fn tool_toolholder_system_frame_and_r_parameters_survive_a_restart() {
    let server = Server::start().await;
    let reply = server.post("/sessions", json!({"machine": "mill-3axis", "machine_data": W1_TABLE})).await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    let id = reply.body["id"].as_str().expect("id").to_string();
    // T1 D1, holder 1 ($P_PARTFRAME: the table offset), $P_SETFRAME shifting Y by 2, R7; the
    // MDA ends with a reset, which keeps all four (the modal G groups go to their reset values).
    let mda = "T1 D1\nTCARR=1\n$P_SETFRAME=CTRANS(Y,2)\nR7=2.5\nG0 X0 Y10 Z0";
    let reply =
        server.post(&format!("/sessions/{id}/mda"), json!({"program": mda, "pace": "fast", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    let s = 45f64.to_radians().sin();
    let (x0, z0) = (15.0 * s, -15.0 * (1.0 - s) + 13.0);
    near(pos(&reply.body, "machine", "X"), x0, "X before");
    near(pos(&reply.body, "machine", "Y"), 12.0, "Y before: 10 + the set frame's 2");
    near(pos(&reply.body, "machine", "Z"), z0, "Z before");

    let server = restart(server).await;
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["tool"], json!({"t": 1, "d": 1, "name": "MILL_D10", "prepared": 1}), "{state}");
    // The machine stands where it stood; seen through the restored tool, holder and set frame
    // it is WCS (0, 10, 0) again (without them it would read (10.607, 12, 8.607)).
    near(pos(&state, "machine", "X"), x0, "X after");
    near(pos(&state, "workpiece", "X"), 0.0, "WCS X after");
    near(pos(&state, "workpiece", "Y"), 10.0, "WCS Y after");
    near(pos(&state, "workpiece", "Z"), 0.0, "WCS Z after");
    // A move after the restart uses all four: X = R7 + 15·sin 45°, Y = 5 + 2, Z = 1 + table + tool.
    let reply = server
        .post(&format!("/sessions/{id}/mda"), json!({"program": "G0 X=R7 Y5 Z1", "pace": "fast", "wait": true}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    near(pos(&reply.body, "machine", "X"), 2.5 + x0, "X moved");
    near(pos(&reply.body, "machine", "Y"), 7.0, "Y moved");
    near(pos(&reply.body, "machine", "Z"), 1.0 + z0, "Z moved");
}

#[tokio::test]
async fn a_program_interrupted_by_the_shutdown_comes_back_stopped_at_its_block() {
    let server = Server::start().await;
    let data = "$P_UIFR[1,X,TR]=100\n$TC_DP3[1,1]=13";
    let reply = server.post("/sessions", json!({"machine": "mill-3axis", "machine_data": data})).await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.body);
    let id = reply.body["id"].as_str().expect("id").to_string();
    // Line 4 takes 30 s at F100: the shutdown comes while it runs.
    let program = "G54 G90 T1 D1\nG0 X0 Y0 Z10\nG91\nG1 X50 F100\nY5\nM30";
    let reply = server
        .post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "realtime", "wait": false}))
        .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    server.state_until(&id, "line 4 running", |s| s["block"]["line"] == 4 && pos(s, "machine", "X") > 100.5).await;

    let server = restart(server).await;
    let state = server.get(&format!("/sessions/{id}/state")).await.body;
    assert_eq!(state["status"], "stopped", "{state}");
    assert_eq!(state["mode"], "AUTO");
    assert_eq!(state["block"]["line"], 4, "{state}");
    // NC start: the approach to the start of line 4, line 4 and 5 with G54 (X + 100), G91 and
    // the 13 mm tool re-established by the search: WCS (50, 5, 10) = machine (150, 5, 23).
    let reply = server.post(&format!("/sessions/{id}/start"), json!({"pace": "fast", "wait": true})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.body);
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    near(pos(&reply.body, "machine", "X"), 150.0, "X");
    near(pos(&reply.body, "machine", "Y"), 5.0, "Y");
    near(pos(&reply.body, "machine", "Z"), 23.0, "Z");
}

#[tokio::test]
async fn the_cut_stock_survives_a_restart() {
    // A 60 x 50 x 20 blank slotted 3 deep over 60 mm with the R5 end mill (1800 mm³ removed)
    // comes back after the restart with its volumes and its holder setting; the STL is the
    // same bytes.
    let server = Server::start().await;
    let id = server.session("mill-3axis").await;
    let program = "T1 D1\nG0 X-30 Y15 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS3000 M3\nG0 Z-3\nG1 X60 F3000\nG0 Z50\nM30";
    let reply =
        server.post(&format!("/sessions/{id}/run"), json!({"program": program, "pace": "fast", "wait": true})).await;
    assert_eq!(reply.body["status"], "idle", "{}", reply.body);
    let put = server.put(&format!("/sessions/{id}/stock"), json!({"holder": [[40, 60]]})).await;
    assert_eq!(put.body["stock"]["removed"], 1800.0, "{}", put.body);
    let stl = reqwest::get(server.url(&format!("/sessions/{id}/stock.stl"))).await.unwrap().bytes().await.unwrap();

    let server = restart(server).await;
    let report = server.get(&format!("/sessions/{id}/stock")).await.body;
    assert_eq!(
        (&report["stock"]["initial_volume"], &report["stock"]["removed"], &report["holder"]),
        (&json!(60000.0), &json!(1800.0), &json!([[40.0, 60.0]])),
        "{report}"
    );
    let again = reqwest::get(server.url(&format!("/sessions/{id}/stock.stl"))).await.unwrap().bytes().await.unwrap();
    assert_eq!(again, stl);
}
