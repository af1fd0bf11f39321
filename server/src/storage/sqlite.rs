//! [`SqliteStorage`]: the embedded default, one SQLite file under `--data-dir`.
//!
//! Durability: the database runs in WAL mode with `synchronous=FULL`, so every committed
//! transaction is fsynced to the write-ahead log before `commit` returns; each trait method is
//! one transaction. A process killed at any moment (SIGKILL, power loss after the fsync) keeps
//! every change whose method returned `Ok`, and loses at most the one in flight, whole.
//!
//! One connection behind a std `Mutex`: the server writes little (a few rows per command), and a
//! single writer is what SQLite supports anyway. Callers run on blocking workers, so waiting for
//! the lock or the disk never blocks the async runtime.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use rusqlite::{Connection, OptionalExtension, params};

use nctwin_engine::lang::ProgramText;

use super::{ActiveProgram, Checkpoint, SavedSession, SessionRecord, Storage, StorageError, TokenHashes};

/// Schema version written to `PRAGMA user_version`; migrations go from each version to the next.
const SCHEMA_VERSION: i64 = 4;

const SCHEMA_V1: &str = "
CREATE TABLE sessions (
    id            TEXT PRIMARY KEY,
    number        INTEGER NOT NULL,
    machine       TEXT NOT NULL,
    client_ip     TEXT,
    owner_hash    TEXT NOT NULL,
    operator_hash TEXT NOT NULL,
    observer_hash TEXT NOT NULL,
    machine_data  TEXT NOT NULL,
    positions     TEXT NOT NULL,   -- JSON array of f64, exact round trip
    mode          TEXT NOT NULL
);
CREATE TABLE programs (
    session TEXT NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
    name    TEXT NOT NULL,
    text    TEXT NOT NULL,
    PRIMARY KEY (session, name)
);
";

/// Version 2: the resumable channel state of a checkpoint (NULL in rows of version 1).
const MIGRATE_V2: &str = "ALTER TABLE sessions ADD COLUMN channel_state TEXT;";

/// Version 3: the AUTO program a checkpoint refers to, one row per session, rewritten only
/// when its hash changes. Rows of version 2 keep the text inline in `channel_state`.
const MIGRATE_V3: &str = "
CREATE TABLE active_programs (
    session TEXT PRIMARY KEY REFERENCES sessions(id) ON DELETE CASCADE,
    sha256  TEXT NOT NULL,
    text    TEXT NOT NULL
);
";

/// Version 4: the session number counter (it only grows, so an id is never handed out twice,
/// also not after the highest-numbered session was deleted; a file of version 3 starts it above
/// its highest stored session), the owner's persistent mark and the last activity (NULL in
/// older rows: a restart counts as activity for them).
const MIGRATE_V4: &str = "
CREATE TABLE counters (
    name  TEXT PRIMARY KEY,
    value INTEGER NOT NULL
);
INSERT INTO counters (name, value) VALUES ('next_session', COALESCE((SELECT max(number) FROM sessions), 0) + 1);
ALTER TABLE sessions ADD COLUMN persistent INTEGER NOT NULL DEFAULT 0;
ALTER TABLE sessions ADD COLUMN last_active_ms INTEGER;
";

/// A SQLite database file.
#[derive(Debug)]
pub struct SqliteStorage {
    path: PathBuf,
    connection: Mutex<Connection>,
}

impl SqliteStorage {
    /// Opens or creates the database at `path` and brings its schema up to date.
    pub fn open(path: &Path) -> Result<SqliteStorage, StorageError> {
        let connection = Connection::open(path)
            .map_err(|e| StorageError::new(format!("cannot open database {}: {e}", path.display())))?;
        // WAL + FULL: a commit is durable when it returns (see the module doc). The busy timeout
        // covers a second process (a backup tool) holding the lock briefly.
        let mode: String = connection.query_row("PRAGMA journal_mode=WAL", [], |r| r.get(0))?;
        if !mode.eq_ignore_ascii_case("wal") {
            return Err(StorageError::new(format!("{} cannot use WAL journaling (got {mode})", path.display())));
        }
        connection.execute_batch("PRAGMA synchronous=FULL; PRAGMA foreign_keys=ON; PRAGMA busy_timeout=5000;")?;
        migrate(&connection)?;
        Ok(SqliteStorage { path: path.to_path_buf(), connection: Mutex::new(connection) })
    }

    fn connection(&self) -> MutexGuard<'_, Connection> {
        // A panic inside a transaction rolls it back when the transaction is dropped, so the
        // connection behind a poisoned lock is still consistent.
        self.connection.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Brings the schema from the file's version to [`SCHEMA_VERSION`] in one transaction: each
/// step adds to the tables, so every stored row is kept.
fn migrate(connection: &Connection) -> Result<(), StorageError> {
    let version: i64 = connection.query_row("PRAGMA user_version", [], |r| r.get(0))?;
    let steps = match version {
        0 => format!("{SCHEMA_V1} {MIGRATE_V2} {MIGRATE_V3} {MIGRATE_V4}"),
        1 => format!("{MIGRATE_V2} {MIGRATE_V3} {MIGRATE_V4}"),
        2 => format!("{MIGRATE_V3} {MIGRATE_V4}"),
        3 => MIGRATE_V4.to_string(),
        SCHEMA_VERSION => return Ok(()),
        other => {
            return Err(StorageError::new(format!(
                "database schema version {other} is newer than this server understands ({SCHEMA_VERSION})"
            )));
        }
    };
    connection.execute_batch(&format!("BEGIN; {steps} PRAGMA user_version = {SCHEMA_VERSION}; COMMIT;"))?;
    Ok(())
}

const UPDATE_CHECKPOINT: &str =
    "UPDATE sessions SET machine_data = ?2, positions = ?3, mode = ?4, channel_state = ?5 WHERE id = ?1";

/// Writes the active program of session `id` where its hash differs from the stored one (or
/// removes it); an unchanged program costs one indexed read and no write.
fn write_active_program(
    connection: &Connection,
    id: &str,
    program: Option<&ActiveProgram>,
) -> Result<(), StorageError> {
    let stored: Option<String> =
        connection.query_row("SELECT sha256 FROM active_programs WHERE session = ?1", [id], |r| r.get(0)).optional()?;
    match program {
        None if stored.is_some() => {
            connection.execute("DELETE FROM active_programs WHERE session = ?1", [id])?;
        }
        Some(p) if stored.as_deref() != Some(p.sha256.as_str()) => {
            connection.execute(
                "INSERT INTO active_programs (session, sha256, text) VALUES (?1, ?2, ?3)
                 ON CONFLICT (session) DO UPDATE SET sha256 = excluded.sha256, text = excluded.text",
                params![id, p.sha256, &*p.text],
            )?;
        }
        _ => {}
    }
    Ok(())
}

/// Replaces the checkpoint of session `id`, if it is stored.
fn write_checkpoint(connection: &Connection, id: &str, c: &Checkpoint) -> Result<(), StorageError> {
    let updated = connection.execute(
        UPDATE_CHECKPOINT,
        params![id, c.machine_data, positions_text(&c.positions), c.mode, c.channel_state],
    )?;
    if updated == 1 {
        write_active_program(connection, id, c.active_program.as_ref())?;
    }
    Ok(())
}

fn positions_text(positions: &[f64]) -> String {
    // serde_json writes the shortest text that reads back as the same f64.
    serde_json::to_string(positions).unwrap_or_else(|_| "[]".into())
}

impl Storage for SqliteStorage {
    fn describe(&self) -> String {
        format!("sqlite:{}", self.path.display())
    }

    fn backend(&self) -> &'static str {
        "sqlite"
    }

    fn check(&self) -> Result<(), StorageError> {
        let n: i64 = self.connection().query_row("SELECT count(*) FROM sessions", [], |r| r.get(0))?;
        debug_assert!(n >= 0);
        Ok(())
    }

    fn load(&self) -> Result<Vec<SavedSession>, StorageError> {
        let connection = self.connection();
        let mut sessions = connection.prepare(
            "SELECT id, number, machine, client_ip, owner_hash, operator_hash, observer_hash,
                    machine_data, positions, mode, channel_state, a.sha256, a.text, persistent, last_active_ms
             FROM sessions LEFT JOIN active_programs a ON a.session = sessions.id ORDER BY number",
        )?;
        let rows = sessions.query_map([], |r| {
            let positions: String = r.get(8)?;
            Ok(SessionRecord {
                id: r.get(0)?,
                number: r.get::<_, i64>(1)?.max(0) as u64,
                machine: r.get(2)?,
                client_ip: r.get(3)?,
                tokens: TokenHashes { owner: r.get(4)?, operator: r.get(5)?, observer: r.get(6)? },
                checkpoint: Checkpoint {
                    machine_data: r.get(7)?,
                    positions: serde_json::from_str(&positions).unwrap_or_default(),
                    mode: r.get(9)?,
                    channel_state: r.get(10)?,
                    active_program: match (r.get::<_, Option<String>>(11)?, r.get::<_, Option<String>>(12)?) {
                        (Some(sha256), Some(text)) => Some(ActiveProgram { sha256, text: ProgramText::from(text) }),
                        _ => None,
                    },
                },
                persistent: r.get::<_, i64>(13)? != 0,
                last_active_ms: r.get::<_, Option<i64>>(14)?.map(|ms| ms.max(0) as u64),
            })
        })?;
        let records = rows.collect::<Result<Vec<_>, _>>()?;
        let mut programs = connection.prepare("SELECT name, text FROM programs WHERE session = ?1 ORDER BY name")?;
        let mut out = Vec::with_capacity(records.len());
        for record in records {
            let list = programs
                .query_map([&record.id], |r| Ok((r.get(0)?, r.get(1)?)))?
                .collect::<Result<Vec<(String, String)>, _>>()?;
            out.push(SavedSession { record, programs: list });
        }
        Ok(out)
    }

    fn create_session(&self, record: &SessionRecord) -> Result<(), StorageError> {
        let mut connection = self.connection();
        let tx = connection.transaction()?;
        tx.execute("DELETE FROM sessions WHERE id = ?1", [&record.id])?;
        tx.execute(
            "INSERT INTO sessions (id, number, machine, client_ip, owner_hash, operator_hash, observer_hash,
                                   machine_data, positions, mode, channel_state, persistent, last_active_ms)
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13)",
            params![
                record.id,
                record.number as i64,
                record.machine,
                record.client_ip,
                record.tokens.owner,
                record.tokens.operator,
                record.tokens.observer,
                record.checkpoint.machine_data,
                positions_text(&record.checkpoint.positions),
                record.checkpoint.mode,
                record.checkpoint.channel_state,
                record.persistent,
                record.last_active_ms.map(|ms| ms.min(i64::MAX as u64) as i64),
            ],
        )?;
        // A number stored is a number used: the counter stays above it.
        tx.execute(
            "UPDATE counters SET value = max(value, ?1 + 1) WHERE name = 'next_session'",
            [record.number.min(i64::MAX as u64 - 1) as i64],
        )?;
        write_active_program(&tx, &record.id, record.checkpoint.active_program.as_ref())?;
        tx.commit()?;
        Ok(())
    }

    fn save_checkpoint(&self, id: &str, checkpoint: &Checkpoint) -> Result<(), StorageError> {
        let mut connection = self.connection();
        let tx = connection.transaction()?;
        write_checkpoint(&tx, id, checkpoint)?;
        tx.commit()?;
        Ok(())
    }

    fn save_checkpoints(&self, checkpoints: &[(String, Checkpoint)]) -> Result<(), StorageError> {
        // One transaction, one fsync, however many sessions shut down.
        let mut connection = self.connection();
        let tx = connection.transaction()?;
        for (id, c) in checkpoints {
            write_checkpoint(&tx, id, c)?;
        }
        tx.commit()?;
        Ok(())
    }

    fn delete_session(&self, id: &str) -> Result<(), StorageError> {
        // Programs go with their session (ON DELETE CASCADE), in the same transaction.
        self.connection().execute("DELETE FROM sessions WHERE id = ?1", [id])?;
        Ok(())
    }

    fn put_program(&self, id: &str, name: &str, text: &str) -> Result<(), StorageError> {
        let connection = self.connection();
        let exists =
            connection.query_row("SELECT 1 FROM sessions WHERE id = ?1", [id], |_| Ok(())).optional()?.is_some();
        if !exists {
            return Err(StorageError::new(format!("session `{id}` is not stored")));
        }
        connection.execute(
            "INSERT INTO programs (session, name, text) VALUES (?1, ?2, ?3)
             ON CONFLICT (session, name) DO UPDATE SET text = excluded.text",
            params![id, name, text],
        )?;
        Ok(())
    }

    fn delete_program(&self, id: &str, name: &str) -> Result<(), StorageError> {
        self.connection().execute("DELETE FROM programs WHERE session = ?1 AND name = ?2", [id, name])?;
        Ok(())
    }

    fn set_persistent(&self, id: &str, persistent: bool) -> Result<(), StorageError> {
        self.connection().execute("UPDATE sessions SET persistent = ?2 WHERE id = ?1", params![id, persistent])?;
        Ok(())
    }

    fn save_activity(&self, activity: &[(String, u64)]) -> Result<(), StorageError> {
        let mut connection = self.connection();
        let tx = connection.transaction()?;
        {
            let mut update = tx.prepare_cached("UPDATE sessions SET last_active_ms = ?2 WHERE id = ?1")?;
            for (id, ms) in activity {
                update.execute(params![id, (*ms).min(i64::MAX as u64) as i64])?;
            }
        }
        tx.commit()?;
        Ok(())
    }

    fn next_session_number(&self) -> Result<Option<u64>, StorageError> {
        // One statement, one transaction: durable before the number is used.
        let n: i64 = self.connection().query_row(
            "UPDATE counters SET value = value + 1 WHERE name = 'next_session' RETURNING value - 1",
            [],
            |r| r.get(0),
        )?;
        Ok(Some(n.max(0) as u64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_db(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("nctwin-sqlite-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temp dir");
        dir.join("test.sqlite3")
    }

    /// Session `s1` on mill-3axis, its one axis at `position`, in `mode`.
    fn session_s1(position: f64, mode: &str) -> SessionRecord {
        SessionRecord {
            id: "s1".into(),
            number: 1,
            machine: "mill-3axis".into(),
            client_ip: None,
            tokens: TokenHashes { owner: "a".into(), operator: "b".into(), observer: "c".into() },
            checkpoint: Checkpoint {
                machine_data: String::new(),
                positions: vec![position],
                mode: mode.into(),
                channel_state: Some("{}".into()),
                active_program: None,
            },
            persistent: false,
            last_active_ms: None,
        }
    }

    #[test]
    fn data_survives_reopening_and_the_database_is_in_wal_mode_with_full_sync() {
        let path = temp_db("reopen");
        {
            let storage = SqliteStorage::open(&path).expect("open");
            let record = session_s1(3.25, "MDA");
            storage.create_session(&record).expect("create");
            storage.put_program("s1", "P", "M30").expect("program");
            let connection = storage.connection();
            let sync: i64 = connection.query_row("PRAGMA synchronous", [], |r| r.get(0)).expect("pragma");
            assert_eq!(sync, 2, "synchronous=FULL");
        }
        let storage = SqliteStorage::open(&path).expect("reopen");
        let all = storage.load().expect("load");
        assert_eq!(all.len(), 1);
        assert_eq!(all[0].record.checkpoint.positions, vec![3.25]);
        assert_eq!(all[0].programs, vec![("P".to_string(), "M30".to_string())]);
        let _ = std::fs::remove_dir_all(path.parent().expect("dir"));
    }

    /// What `write` writes: the pages it appends to the write-ahead log (the log is emptied
    /// first by a TRUNCATE checkpoint; a passive checkpoint after the write reports how many
    /// frames it holds) and the rows it inserts, updates or deletes (SQLite's change counter).
    /// SQLite skips pages whose bytes an update leaves as they were, so the rows tell what the
    /// storage chose to write even where the pages do not.
    fn written(storage: &SqliteStorage, write: impl FnOnce()) -> (i64, u64) {
        let truncate = |c: &Connection| c.query_row("PRAGMA wal_checkpoint(TRUNCATE)", [], |r| r.get::<_, i64>(1));
        assert_eq!(truncate(&storage.connection()).expect("truncate"), 0, "an empty log");
        let rows = storage.connection().total_changes();
        write();
        let connection = storage.connection();
        let frames = connection
            .query_row("PRAGMA wal_checkpoint(PASSIVE)", [], |r| r.get::<_, i64>(1))
            .expect("passive checkpoint");
        (frames, connection.total_changes() - rows)
    }

    #[test]
    fn a_checkpoint_writes_the_active_program_only_when_it_changed() {
        let path = temp_db("active");
        let storage = SqliteStorage::open(&path).expect("open");
        let page: i64 = storage.connection().query_row("PRAGMA page_size", [], |r| r.get(0)).expect("page size");
        let record = session_s1(0.0, "AUTO");
        storage.create_session(&record).expect("create");
        // 1 MiB of distinct lines: at least 1 MiB / page size pages wherever it is written.
        let text = |seed: u32| (0..60_000).map(|i| format!("N{i} G1 X{seed}.{i:06} F{seed}\n")).collect::<String>();
        let (first, second) = (text(1), text(2));
        assert!(first.len() >= 1 << 20 && second.len() >= 1 << 20);
        let text_pages = (1 << 20) / page;
        let mut checkpoint = record.checkpoint.clone();
        checkpoint.active_program = Some(ActiveProgram::hashed(ProgramText::from(first.as_str())));

        let (pages, rows) = written(&storage, || storage.save_checkpoint("s1", &checkpoint).expect("first"));
        assert!(pages >= text_pages && rows == 2, "the first checkpoint writes the text: {pages} pages, {rows} rows");
        checkpoint.positions = vec![1.5];
        let (pages, rows) = written(&storage, || storage.save_checkpoint("s1", &checkpoint).expect("second"));
        // The session row only: its page (and the b-tree above it at most), no text.
        assert!((1..=4).contains(&pages) && rows == 1, "the second checkpoint writes {pages} pages, {rows} rows");
        checkpoint.positions = vec![2.5];
        let batch = [("s1".to_string(), checkpoint.clone())];
        let (pages, rows) = written(&storage, || storage.save_checkpoints(&batch).expect("shutdown"));
        assert!((1..=4).contains(&pages) && rows == 1, "the shutdown's checkpoint writes {pages} pages, {rows} rows");
        checkpoint.active_program = Some(ActiveProgram::hashed(ProgramText::from(second.as_str())));
        let (pages, rows) = written(&storage, || storage.save_checkpoint("s1", &checkpoint).expect("changed"));
        assert!(pages >= text_pages && rows == 2, "a changed program is written: {pages} pages, {rows} rows");

        drop(storage);
        let loaded = SqliteStorage::open(&path).expect("reopen").load().expect("load");
        assert_eq!(loaded[0].record.checkpoint, checkpoint, "the changed program and the positions");
        let _ = std::fs::remove_dir_all(path.parent().expect("dir"));
    }

    #[test]
    fn a_program_of_an_unknown_session_is_refused() {
        let path = temp_db("unknown");
        let storage = SqliteStorage::open(&path).expect("open");
        assert!(storage.put_program("nope", "P", "M30").is_err());
        let _ = std::fs::remove_dir_all(path.parent().expect("dir"));
    }
}
