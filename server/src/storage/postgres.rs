//! [`PostgresStorage`]: the same records in a PostgreSQL database (`--database postgres://...`),
//! for deployments whose server nodes share one database.
//!
//! Schema: tables `nctwin_sessions` and `nctwin_programs` (prefixed, so the database may hold
//! other things) and `nctwin_schema` with the schema version; created on open if missing, under
//! an advisory lock so that nodes starting together do not race. Positions are a
//! `double precision[]`, sent in binary: they round-trip bit for bit.
//!
//! Durability: each trait method is one transaction (or one statement, which PostgreSQL runs as
//! one), and the connection sets `synchronous_commit = on`, so a method returns only after the
//! server has flushed the commit to its write-ahead log. A server running with `fsync = off`
//! cannot keep that promise: opening such a database logs a warning.
//!
//! Connection: one connection behind a std `Mutex`, through the synchronous `postgres` client
//! (it runs its own small Tokio runtime). Callers run on blocking workers (see
//! [`crate::state::AppState`]), never on the server's async threads, where the client's
//! `block_on` would panic. A connection that broke (server restart, network) is replaced by a
//! new one on the next call; the call that saw it break fails (and is not acknowledged). No TLS:
//! use a Unix socket, a trusted network or a TLS-terminating proxy. A password may come in the
//! URL or, to keep it out of the process list, in the `PGPASSWORD` environment variable.

use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use postgres::config::Host;
use postgres::{Client, Config, NoTls};

use super::{Checkpoint, SavedSession, SessionRecord, Storage, StorageError, TokenHashes};

/// Version in `nctwin_schema`; migrations go from each version to the next.
const SCHEMA_VERSION: i32 = 1;

/// Key of the advisory lock held while the schema is created or migrated.
const SCHEMA_LOCK: i64 = 0x6e63_7477_696e; // "nctwin"

const SCHEMA_V1: &str = "
CREATE TABLE nctwin_sessions (
    id            TEXT PRIMARY KEY,
    number        BIGINT NOT NULL,
    machine       TEXT NOT NULL,
    client_ip     TEXT,
    owner_hash    TEXT NOT NULL,
    operator_hash TEXT NOT NULL,
    observer_hash TEXT NOT NULL,
    machine_data  TEXT NOT NULL,
    positions     DOUBLE PRECISION[] NOT NULL,
    mode          TEXT NOT NULL
);
CREATE TABLE nctwin_programs (
    session TEXT NOT NULL REFERENCES nctwin_sessions(id) ON DELETE CASCADE,
    name    TEXT NOT NULL,
    text    TEXT NOT NULL,
    PRIMARY KEY (session, name)
);
";

const UPDATE_CHECKPOINT: &str = "UPDATE nctwin_sessions SET machine_data = $2, positions = $3, mode = $4 WHERE id = $1";

/// A PostgreSQL database.
pub struct PostgresStorage {
    config: Config,
    /// `postgres:user@host:port/dbname`, without the password.
    description: String,
    /// `None` after a connection broke, until the next call reconnects.
    client: Mutex<Option<Client>>,
}

impl std::fmt::Debug for PostgresStorage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PostgresStorage").field("database", &self.description).finish_non_exhaustive()
    }
}

fn pg_error(e: postgres::Error) -> StorageError {
    match e.as_db_error() {
        Some(db) => StorageError(format!("postgres: {} ({})", db.message(), db.code().code())),
        None => StorageError(format!("postgres: {e}")),
    }
}

impl From<postgres::Error> for StorageError {
    fn from(e: postgres::Error) -> StorageError {
        pg_error(e)
    }
}

impl PostgresStorage {
    /// Connects to the database at `url` (`postgres://user[:password]@host[:port]/dbname`, or
    /// a Unix socket directory as the percent-encoded host) and brings its schema up to date.
    ///
    /// Blocks: call it from a blocking worker or a plain thread, not from async code.
    pub fn open(url: &str) -> Result<PostgresStorage, StorageError> {
        let mut config: Config = url.parse().map_err(|e| StorageError(format!("invalid database URL: {e}")))?;
        if config.get_password().is_none()
            && let Ok(password) = std::env::var("PGPASSWORD")
        {
            config.password(password);
        }
        if config.get_connect_timeout().is_none() {
            config.connect_timeout(Duration::from_secs(10));
        }
        let description = describe(&config);
        let mut client = connect(&config, &description)?;
        migrate(&mut client)?;
        let fsync: String = client.query_one("SHOW fsync", &[])?.get(0);
        if fsync != "on" {
            tracing::warn!(database = %description, "the PostgreSQL server runs with fsync={fsync}: saved data may be lost in a crash");
        }
        Ok(PostgresStorage { config, description, client: Mutex::new(Some(client)) })
    }

    /// Runs `f` on the connection, connecting first if there is none. A call that fails for any
    /// reason other than an error the server reported for the statement (one with an SQLSTATE
    /// code) drops the connection, so the next call starts on a new one: the client does not
    /// always know yet that its connection was closed when the failed call returns.
    fn with<R>(&self, f: impl FnOnce(&mut Client) -> Result<R, postgres::Error>) -> Result<R, StorageError> {
        // A panic inside a transaction rolls it back when the transaction is dropped, so the
        // connection behind a poisoned lock is still consistent.
        let mut guard: MutexGuard<'_, Option<Client>> = self.client.lock().unwrap_or_else(|e| e.into_inner());
        if guard.as_ref().is_some_and(Client::is_closed) {
            drop_client(guard.take());
        }
        if guard.is_none() {
            *guard = Some(connect(&self.config, &self.description)?);
        }
        let client = guard.as_mut().ok_or_else(|| StorageError("postgres: no connection".into()))?;
        let result = f(client);
        if result.as_ref().is_err_and(|e| e.code().is_none() || client.is_closed()) {
            drop_client(guard.take());
        }
        result.map_err(pg_error)
    }
}

impl Drop for PostgresStorage {
    fn drop(&mut self) {
        let client = self.client.get_mut().unwrap_or_else(|e| e.into_inner()).take();
        drop_client(client);
    }
}

/// Drops a client on a thread of its own: the client closes its connection with its own
/// runtime's `block_on`, which panics on an async thread (where the last `AppState` may go).
fn drop_client(client: Option<Client>) {
    if let Some(client) = client {
        let _ = std::thread::spawn(move || drop(client)).join();
    }
}

fn describe(config: &Config) -> String {
    let host = match config.get_hosts().first() {
        Some(Host::Tcp(name)) => name.clone(),
        Some(Host::Unix(path)) => path.display().to_string(),
        None => "localhost".into(),
    };
    let port = config.get_ports().first().copied().unwrap_or(5432);
    let user = config.get_user().map(|u| format!("{u}@")).unwrap_or_default();
    let dbname = config.get_dbname().or(config.get_user()).unwrap_or("");
    format!("postgres:{user}{host}:{port}/{dbname}")
}

fn connect(config: &Config, description: &str) -> Result<Client, StorageError> {
    let mut client = config
        .connect(NoTls)
        .map_err(|e| StorageError(format!("cannot connect to {description}: {}", pg_error(e).0)))?;
    // Durable on return even if the server's default says otherwise (see the module doc).
    client.batch_execute("SET synchronous_commit = on")?;
    Ok(client)
}

fn migrate(client: &mut Client) -> Result<(), StorageError> {
    let mut tx = client.transaction()?;
    tx.execute("SELECT pg_advisory_xact_lock($1)", &[&SCHEMA_LOCK])?;
    tx.batch_execute("CREATE TABLE IF NOT EXISTS nctwin_schema (version INTEGER NOT NULL)")?;
    let version: Option<i32> = tx.query_opt("SELECT max(version) FROM nctwin_schema", &[])?.and_then(|r| r.get(0));
    match version {
        None => {
            tx.batch_execute(SCHEMA_V1)?;
            tx.execute("INSERT INTO nctwin_schema (version) VALUES ($1)", &[&SCHEMA_VERSION])?;
        }
        Some(SCHEMA_VERSION) => {}
        Some(other) => {
            return Err(StorageError(format!(
                "database schema version {other} is newer than this server understands ({SCHEMA_VERSION})"
            )));
        }
    }
    tx.commit()?;
    Ok(())
}

fn record_from_row(r: &postgres::Row) -> SessionRecord {
    SessionRecord {
        id: r.get(0),
        number: r.get::<_, i64>(1).max(0) as u64,
        machine: r.get(2),
        client_ip: r.get(3),
        tokens: TokenHashes { owner: r.get(4), operator: r.get(5), observer: r.get(6) },
        checkpoint: Checkpoint { machine_data: r.get(7), positions: r.get(8), mode: r.get(9) },
    }
}

impl Storage for PostgresStorage {
    fn describe(&self) -> String {
        self.description.clone()
    }

    fn backend(&self) -> &'static str {
        "postgres"
    }

    fn check(&self) -> Result<(), StorageError> {
        self.with(|c| c.query_one("SELECT count(*) FROM nctwin_sessions", &[]).map(|_| ()))
    }

    fn load(&self) -> Result<Vec<SavedSession>, StorageError> {
        self.with(|c| {
            // One snapshot for both reads, so sessions and programs agree.
            let mut tx = c.build_transaction().isolation_level(postgres::IsolationLevel::RepeatableRead).start()?;
            let sessions = tx.query(
                "SELECT id, number, machine, client_ip, owner_hash, operator_hash, observer_hash,
                        machine_data, positions, mode
                 FROM nctwin_sessions ORDER BY number, id",
                &[],
            )?;
            let programs =
                tx.query("SELECT session, name, text FROM nctwin_programs ORDER BY session, name COLLATE \"C\"", &[])?;
            tx.commit()?;
            let mut by_session: std::collections::HashMap<String, Vec<(String, String)>> =
                std::collections::HashMap::new();
            for row in &programs {
                by_session.entry(row.get(0)).or_default().push((row.get(1), row.get(2)));
            }
            Ok(sessions
                .iter()
                .map(|row| {
                    let record = record_from_row(row);
                    let programs = by_session.remove(&record.id).unwrap_or_default();
                    SavedSession { record, programs }
                })
                .collect())
        })
    }

    fn create_session(&self, record: &SessionRecord) -> Result<(), StorageError> {
        self.with(|c| {
            let mut tx = c.transaction()?;
            // Replacing a session replaces its programs too (ON DELETE CASCADE).
            tx.execute("DELETE FROM nctwin_sessions WHERE id = $1", &[&record.id])?;
            tx.execute(
                "INSERT INTO nctwin_sessions (id, number, machine, client_ip, owner_hash, operator_hash,
                                              observer_hash, machine_data, positions, mode)
                 VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10)",
                &[
                    &record.id,
                    &(record.number.min(i64::MAX as u64) as i64),
                    &record.machine,
                    &record.client_ip,
                    &record.tokens.owner,
                    &record.tokens.operator,
                    &record.tokens.observer,
                    &record.checkpoint.machine_data,
                    &record.checkpoint.positions,
                    &record.checkpoint.mode,
                ],
            )?;
            tx.commit()
        })
    }

    fn save_checkpoint(&self, id: &str, checkpoint: &Checkpoint) -> Result<(), StorageError> {
        self.with(|c| {
            c.execute(UPDATE_CHECKPOINT, &[&id, &checkpoint.machine_data, &checkpoint.positions, &checkpoint.mode])
                .map(|_| ())
        })
    }

    fn save_checkpoints(&self, checkpoints: &[(String, Checkpoint)]) -> Result<(), StorageError> {
        // One transaction, one WAL flush, however many sessions shut down.
        self.with(|c| {
            let mut tx = c.transaction()?;
            let update = tx.prepare(UPDATE_CHECKPOINT)?;
            for (id, cp) in checkpoints {
                tx.execute(&update, &[id, &cp.machine_data, &cp.positions, &cp.mode])?;
            }
            tx.commit()
        })
    }

    fn delete_session(&self, id: &str) -> Result<(), StorageError> {
        // Programs go with their session (ON DELETE CASCADE), in the same statement.
        self.with(|c| c.execute("DELETE FROM nctwin_sessions WHERE id = $1", &[&id]).map(|_| ()))
    }

    fn put_program(&self, id: &str, name: &str, text: &str) -> Result<(), StorageError> {
        // One statement; the foreign key refuses a session deleted concurrently.
        let stored = self.with(|c| {
            c.execute(
                "INSERT INTO nctwin_programs (session, name, text)
                 SELECT $1, $2, $3 WHERE EXISTS (SELECT 1 FROM nctwin_sessions WHERE id = $1)
                 ON CONFLICT (session, name) DO UPDATE SET text = excluded.text",
                &[&id, &name, &text],
            )
        })?;
        if stored == 0 {
            return Err(StorageError(format!("session `{id}` is not stored")));
        }
        Ok(())
    }

    fn delete_program(&self, id: &str, name: &str) -> Result<(), StorageError> {
        self.with(|c| {
            c.execute("DELETE FROM nctwin_programs WHERE session = $1 AND name = $2", &[&id, &name]).map(|_| ())
        })
    }
}
