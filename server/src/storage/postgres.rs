//! [`PostgresStorage`]: the same records in a PostgreSQL database (`--database postgres://...`),
//! for deployments whose server nodes share one database.
//!
//! Schema: tables `nctwin_sessions` and `nctwin_programs` (prefixed, so the database may hold
//! other things) and `nctwin_schema` with the schema version; created on open if missing, under
//! an advisory lock so that nodes starting together do not race, and migrated in place from
//! older versions (columns added, rows kept). Positions are a `double precision[]`, sent in
//! binary: they round-trip bit for bit.
//!
//! Several nodes: each storage is opened for one node ([`Lease`]). A session row names its
//! holder (`lease_node`); the lease itself is the holder's row in `nctwin_nodes` (its expiry, on
//! the database's clock), so a renewal writes one row per node however many sessions it holds.
//! `load` and `claim_session` take the sessions that are free, already this node's or whose
//! holder's node lease expired; `renew_leases` extends this node's row; `release_leases` frees
//! its sessions and removes the row. Every write to a session first locks its row and checks
//! that this node holds it (`fence`), so a node that lost a session can no longer change it.
//! Session numbers come from the sequence `nctwin_session_numbers`.
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
//! use a Unix socket, a trusted network or a TLS-terminating proxy; `sslmode=require` in the URL
//! is refused at start, `prefer` and `disable` connect without TLS. A password may come in the
//! URL or, to keep it out of the process list, in the `PGPASSWORD` environment variable.

use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use postgres::config::{Host, SslMode};
use std::collections::HashMap;

use postgres::{Client, Config, NoTls, Transaction};

use nctwin_engine::lang::ProgramText;

use super::{
    ActiveProgram, Checkpoint, Claim, HeldBy, Lease, SavedSession, SessionRecord, Storage, StorageError, TokenHashes,
};

/// Version in `nctwin_schema`; migrations go from each version to the next.
const SCHEMA_VERSION: i32 = 5;

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

/// Version 2: the resumable channel state of a checkpoint (NULL in rows of version 1), the
/// session lease (node and expiry; NULL: free, so rows of version 1 go to the first node that
/// asks) and the sequence session numbers come from, so that nodes never make the same id.
const MIGRATE_V2: &str = "
ALTER TABLE nctwin_sessions
    ADD COLUMN channel_state TEXT,
    ADD COLUMN lease_node    TEXT,
    ADD COLUMN lease_expires TIMESTAMPTZ;
CREATE SEQUENCE nctwin_session_numbers;
SELECT setval('nctwin_session_numbers', COALESCE((SELECT max(number) FROM nctwin_sessions), 0) + 1, false);
";

/// Version 3: the AUTO program a checkpoint refers to, one row per session, rewritten only
/// when its hash changes. Rows of version 2 keep the text inline in `channel_state`.
const MIGRATE_V3: &str = "
CREATE TABLE nctwin_active_programs (
    session TEXT PRIMARY KEY REFERENCES nctwin_sessions(id) ON DELETE CASCADE,
    sha256  TEXT NOT NULL,
    text    TEXT NOT NULL
);
";

/// Version 4: the owner's persistent mark and the last activity (NULL in older rows: a restart
/// counts as activity for them). Session numbers already come from a sequence (version 2),
/// which never hands a number out twice.
const MIGRATE_V4: &str = "
ALTER TABLE nctwin_sessions
    ADD COLUMN persistent     BOOLEAN NOT NULL DEFAULT FALSE,
    ADD COLUMN last_active_ms BIGINT;
";

/// Version 5: leases per node, not per session. A node renews one row of `nctwin_nodes`
/// (its name and expiry), whatever number of sessions it holds; a session row names its holder
/// (`lease_node`) and is claimable when that node's row has expired (or is missing).
/// `lease_expires` of a session is no longer read. Existing holders get a row with the latest
/// expiry of their sessions.
const MIGRATE_V5: &str = "
CREATE TABLE nctwin_nodes (
    node    TEXT PRIMARY KEY,
    expires TIMESTAMPTZ NOT NULL
);
INSERT INTO nctwin_nodes (node, expires)
    SELECT lease_node, COALESCE(max(lease_expires), now()) FROM nctwin_sessions
    WHERE lease_node IS NOT NULL GROUP BY lease_node;
CREATE INDEX nctwin_sessions_lease_node ON nctwin_sessions (lease_node);
";

/// SQL condition: the session row `s` may be leased to node `$me` (a parameter named by the
/// caller): it is free, already `$me`'s, or its holder's node lease has expired.
fn claimable(me: &str) -> String {
    format!(
        "(s.lease_node IS NULL OR s.lease_node = {me} OR NOT EXISTS (
            SELECT 1 FROM nctwin_nodes n WHERE n.node = s.lease_node AND n.expires >= now()))"
    )
}

/// SQL: the seconds left of the node lease of session row `s`'s holder (0 if none or expired).
const HOLDER_SECONDS_LEFT: &str = "GREATEST(COALESCE(EXTRACT(EPOCH FROM
    (SELECT n.expires FROM nctwin_nodes n WHERE n.node = s.lease_node) - now()), 0), 0)::float8";

/// SQL: registers or renews node `$1`'s lease for `$2` seconds.
const RENEW_NODE: &str = "INSERT INTO nctwin_nodes (node, expires) VALUES ($1, now() + make_interval(secs => $2))
     ON CONFLICT (node) DO UPDATE SET expires = excluded.expires";

const UPDATE_CHECKPOINT: &str =
    "UPDATE nctwin_sessions SET machine_data = $2, positions = $3, mode = $4, channel_state = $5 WHERE id = $1";

/// A PostgreSQL database, used by one server node.
pub struct PostgresStorage {
    config: Config,
    /// This node's name and lease period (see [`Lease`]).
    lease: Lease,
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
        Some(db) => StorageError::new(format!("postgres: {} ({})", db.message(), db.code().code())),
        None => StorageError::new(format!("postgres: {e}")),
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
        PostgresStorage::open_as(url, Lease::default())
    }

    /// [`PostgresStorage::open`] for the node `lease` names: the sessions it loads, creates and
    /// writes are leased to that node.
    pub fn open_as(url: &str, lease: Lease) -> Result<PostgresStorage, StorageError> {
        if lease.node.is_empty() || lease.period.is_zero() {
            return Err(StorageError::new("a node needs a name and a lease period above zero"));
        }
        let mut config: Config = url.parse().map_err(|e| StorageError::new(format!("invalid database URL: {e}")))?;
        // No TLS in this build: refuse what asks for it rather than connect in the clear.
        // `prefer` (the default) and `disable` connect without TLS.
        if config.get_ssl_mode() == SslMode::Require {
            return Err(StorageError::new(
                "sslmode=require: this server has no TLS for PostgreSQL; use a Unix socket, a trusted network or a TLS-terminating proxy (sslmode=disable)",
            ));
        }
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
        // The node's lease starts with the storage: the sessions it creates are its own from
        // the first one, before any renewal.
        client.execute(RENEW_NODE, &[&lease.node, &lease.period.as_secs_f64()])?;
        let fsync: String = client.query_one("SHOW fsync", &[])?.get(0);
        if fsync != "on" {
            tracing::warn!(database = %description, "the PostgreSQL server runs with fsync={fsync}: saved data may be lost in a crash");
        }
        Ok(PostgresStorage { config, lease, description, client: Mutex::new(Some(client)) })
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
        let client = guard.as_mut().ok_or_else(|| StorageError::new("postgres: no connection"))?;
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
        .map_err(|e| StorageError::new(format!("cannot connect to {description}: {}", pg_error(e).message)))?;
    // Durable on return even if the server's default says otherwise (see the module doc).
    client.batch_execute("SET synchronous_commit = on")?;
    Ok(client)
}

fn migrate(client: &mut Client) -> Result<(), StorageError> {
    let mut tx = client.transaction()?;
    tx.execute("SELECT pg_advisory_xact_lock($1)", &[&SCHEMA_LOCK])?;
    tx.batch_execute("CREATE TABLE IF NOT EXISTS nctwin_schema (version INTEGER NOT NULL)")?;
    let version: Option<i32> = tx.query_opt("SELECT max(version) FROM nctwin_schema", &[])?.and_then(|r| r.get(0));
    // Each step adds to the tables, so every stored row is kept; all steps in one transaction.
    match version {
        None => {
            tx.batch_execute(SCHEMA_V1)?;
            tx.batch_execute(MIGRATE_V2)?;
            tx.batch_execute(MIGRATE_V3)?;
            tx.batch_execute(MIGRATE_V4)?;
            tx.batch_execute(MIGRATE_V5)?;
            tx.execute("INSERT INTO nctwin_schema (version) VALUES ($1)", &[&SCHEMA_VERSION])?;
        }
        Some(version @ (1..=4)) => {
            if version == 1 {
                tx.batch_execute(MIGRATE_V2)?;
            }
            if version <= 2 {
                tx.batch_execute(MIGRATE_V3)?;
            }
            if version <= 3 {
                tx.batch_execute(MIGRATE_V4)?;
            }
            tx.batch_execute(MIGRATE_V5)?;
            tx.execute("UPDATE nctwin_schema SET version = $1", &[&SCHEMA_VERSION])?;
        }
        Some(SCHEMA_VERSION) => {}
        Some(other) => {
            return Err(StorageError::new(format!(
                "database schema version {other} is newer than this server understands ({SCHEMA_VERSION})"
            )));
        }
    }
    tx.commit()?;
    Ok(())
}

const SESSION_COLUMNS: &str = "id, number, machine, client_ip, owner_hash, operator_hash, observer_hash,
     machine_data, positions, mode, channel_state, persistent, last_active_ms";

/// Writes the active program of session `id` where its hash differs from the stored one (or
/// removes it); an unchanged program costs one indexed read: no text is sent or written.
fn write_active_program(
    tx: &mut Transaction<'_>,
    id: &str,
    program: Option<&ActiveProgram>,
) -> Result<(), postgres::Error> {
    let stored: Option<String> =
        tx.query_opt("SELECT sha256 FROM nctwin_active_programs WHERE session = $1", &[&id])?.map(|r| r.get(0));
    match program {
        None if stored.is_some() => {
            tx.execute("DELETE FROM nctwin_active_programs WHERE session = $1", &[&id])?;
        }
        Some(p) if stored.as_deref() != Some(p.sha256.as_str()) => {
            tx.execute(
                "INSERT INTO nctwin_active_programs (session, sha256, text) VALUES ($1, $2, $3)
                 ON CONFLICT (session) DO UPDATE SET sha256 = excluded.sha256, text = excluded.text",
                &[&id, &p.sha256, &&*p.text],
            )?;
        }
        _ => {}
    }
    Ok(())
}

fn record_from_row(r: &postgres::Row) -> SessionRecord {
    SessionRecord {
        id: r.get(0),
        number: r.get::<_, i64>(1).max(0) as u64,
        machine: r.get(2),
        client_ip: r.get(3),
        tokens: TokenHashes { owner: r.get(4), operator: r.get(5), observer: r.get(6) },
        checkpoint: Checkpoint {
            machine_data: r.get(7),
            positions: r.get(8),
            mode: r.get(9),
            channel_state: r.get(10),
            active_program: None,
        },
        persistent: r.get(11),
        last_active_ms: r.get::<_, Option<i64>>(12).map(|ms| ms.max(0) as u64),
    }
}

/// Who holds session `id`, locking its row until the transaction ends (so the lease cannot
/// change between this check and the write that follows): `Ok(Ok(true))` this node,
/// `Ok(Ok(false))` no such session, `Ok(Err(..))` otherwise: [`StorageError::held`] naming the
/// node that holds it, or a plain error when no node does (released; this node must claim it
/// again first).
fn fence(tx: &mut Transaction<'_>, id: &str, node: &str) -> Result<Result<bool, StorageError>, postgres::Error> {
    let row = tx.query_opt(
        &format!("SELECT s.lease_node, {HOLDER_SECONDS_LEFT} FROM nctwin_sessions s WHERE s.id = $1 FOR UPDATE OF s"),
        &[&id],
    )?;
    let Some(row) = row else { return Ok(Ok(false)) };
    Ok(match row.get::<_, Option<String>>(0) {
        Some(holder) if holder == node => Ok(true),
        Some(holder) => Err(StorageError::held(HeldBy {
            session: id.to_string(),
            node: holder,
            seconds_left: row.get::<_, Option<f64>>(1).unwrap_or(0.0),
        })),
        None => Err(StorageError::new(format!("session `{id}` is held by no node, not by this node `{node}`"))),
    })
}

/// Sessions and programs of the rows `sessions` selected, in one snapshot.
fn saved_sessions(
    tx: &mut Transaction<'_>,
    sessions: Vec<postgres::Row>,
) -> Result<Vec<SavedSession>, postgres::Error> {
    let ids: Vec<String> = sessions.iter().map(|r| r.get(0)).collect();
    let programs = tx.query(
        "SELECT session, name, text FROM nctwin_programs WHERE session = ANY($1) ORDER BY session, name COLLATE \"C\"",
        &[&ids],
    )?;
    let mut by_session: HashMap<String, Vec<(String, String)>> = HashMap::new();
    for row in &programs {
        by_session.entry(row.get(0)).or_default().push((row.get(1), row.get(2)));
    }
    let active =
        tx.query("SELECT session, sha256, text FROM nctwin_active_programs WHERE session = ANY($1)", &[&ids])?;
    let mut active: HashMap<String, ActiveProgram> = active
        .iter()
        .map(|row| (row.get(0), ActiveProgram { sha256: row.get(1), text: ProgramText::from(row.get::<_, String>(2)) }))
        .collect();
    Ok(sessions
        .iter()
        .map(|row| {
            let mut record = record_from_row(row);
            record.checkpoint.active_program = active.remove(&record.id);
            let programs = by_session.remove(&record.id).unwrap_or_default();
            SavedSession { record, programs }
        })
        .collect())
}

fn flatten<R>(result: Result<Result<R, StorageError>, StorageError>) -> Result<R, StorageError> {
    result?
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
        let (node, period) = (self.lease.node.as_str(), self.lease.period.as_secs_f64());
        self.with(|c| {
            // Read committed is enough: the rows this statement leases stay locked until the
            // commit, and every other node's write to them checks the lease first (`fence`).
            let mut tx = c.transaction()?;
            tx.execute(RENEW_NODE, &[&node, &period])?;
            // This node's own sessions (a restart under the same name), the free ones and those
            // whose holder stopped renewing.
            let sessions = tx.query(
                &format!(
                    "UPDATE nctwin_sessions s SET lease_node = $1 WHERE {} RETURNING {SESSION_COLUMNS}",
                    claimable("$1")
                ),
                &[&node],
            )?;
            let mut sessions = sessions;
            sessions.sort_by_key(|r| (r.get::<_, i64>(1), r.get::<_, String>(0)));
            let saved = saved_sessions(&mut tx, sessions)?;
            tx.commit()?;
            Ok(saved)
        })
    }

    fn create_session(&self, record: &SessionRecord) -> Result<(), StorageError> {
        let (node, period) = (self.lease.node.as_str(), self.lease.period.as_secs_f64());
        flatten(self.with(|c| {
            let mut tx = c.transaction()?;
            if let Err(held) = fence(&mut tx, &record.id, node)? {
                return Ok(Err(held));
            }
            // The new session is leased for a whole period from now, as before schema 5.
            tx.execute(RENEW_NODE, &[&node, &period])?;
            // Replacing a session replaces its programs too (ON DELETE CASCADE).
            tx.execute("DELETE FROM nctwin_sessions WHERE id = $1", &[&record.id])?;
            tx.execute(
                "INSERT INTO nctwin_sessions (id, number, machine, client_ip, owner_hash, operator_hash,
                                              observer_hash, machine_data, positions, mode, channel_state,
                                              lease_node, lease_expires, persistent, last_active_ms)
                 VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, now() + make_interval(secs => $13),
                         $14, $15)",
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
                    &record.checkpoint.channel_state,
                    &node,
                    &period,
                    &record.persistent,
                    &record.last_active_ms.map(|ms| ms.min(i64::MAX as u64) as i64),
                ],
            )?;
            // A number stored is a number used: the sequence stays above it (a no-op for the
            // numbers the sequence handed out itself).
            tx.execute(
                "SELECT setval('nctwin_session_numbers', $1)
                 WHERE $1 >= (SELECT CASE WHEN is_called THEN last_value + 1 ELSE last_value END
                              FROM nctwin_session_numbers)",
                &[&(record.number.min(i64::MAX as u64) as i64)],
            )?;
            write_active_program(&mut tx, &record.id, record.checkpoint.active_program.as_ref())?;
            tx.commit().map(Ok)
        }))
    }

    fn save_checkpoint(&self, id: &str, checkpoint: &Checkpoint) -> Result<(), StorageError> {
        let node = self.lease.node.as_str();
        flatten(self.with(|c| {
            let mut tx = c.transaction()?;
            if let Err(held) = fence(&mut tx, id, node)? {
                return Ok(Err(held));
            }
            let cp = checkpoint;
            if tx.execute(UPDATE_CHECKPOINT, &[&id, &cp.machine_data, &cp.positions, &cp.mode, &cp.channel_state])? == 1
            {
                write_active_program(&mut tx, id, cp.active_program.as_ref())?;
            }
            tx.commit().map(Ok)
        }))
    }

    fn save_checkpoints(&self, checkpoints: &[(String, Checkpoint)]) -> Result<(), StorageError> {
        // One transaction, one WAL flush, however many sessions shut down. A session another
        // node has taken over is not written (its lease decides).
        let node = self.lease.node.as_str();
        let skipped = self.with(|c| {
            let mut tx = c.transaction()?;
            let update = tx.prepare(&format!("{UPDATE_CHECKPOINT} AND lease_node = $6"))?;
            let mut skipped = 0;
            for (id, cp) in checkpoints {
                let n =
                    tx.execute(&update, &[id, &cp.machine_data, &cp.positions, &cp.mode, &cp.channel_state, &node])?;
                if n == 1 {
                    write_active_program(&mut tx, id, cp.active_program.as_ref())?;
                }
                skipped += usize::from(n == 0);
            }
            tx.commit().map(|()| skipped)
        })?;
        if skipped > 0 {
            tracing::warn!(sessions = skipped, "checkpoints of sessions deleted or held by another node not written");
        }
        Ok(())
    }

    fn delete_session(&self, id: &str) -> Result<(), StorageError> {
        // Programs go with their session (ON DELETE CASCADE), in the same transaction.
        let node = self.lease.node.as_str();
        flatten(self.with(|c| {
            let mut tx = c.transaction()?;
            if let Err(held) = fence(&mut tx, id, node)? {
                return Ok(Err(held));
            }
            tx.execute("DELETE FROM nctwin_sessions WHERE id = $1", &[&id])?;
            tx.commit().map(Ok)
        }))
    }

    fn put_program(&self, id: &str, name: &str, text: &str) -> Result<(), StorageError> {
        let node = self.lease.node.as_str();
        flatten(self.with(|c| {
            let mut tx = c.transaction()?;
            match fence(&mut tx, id, node)? {
                Err(held) => return Ok(Err(held)),
                Ok(false) => return Ok(Err(StorageError::new(format!("session `{id}` is not stored")))),
                Ok(true) => {}
            }
            tx.execute(
                "INSERT INTO nctwin_programs (session, name, text) VALUES ($1, $2, $3)
                 ON CONFLICT (session, name) DO UPDATE SET text = excluded.text",
                &[&id, &name, &text],
            )?;
            tx.commit().map(Ok)
        }))
    }

    fn delete_program(&self, id: &str, name: &str) -> Result<(), StorageError> {
        let node = self.lease.node.as_str();
        flatten(self.with(|c| {
            let mut tx = c.transaction()?;
            if let Err(held) = fence(&mut tx, id, node)? {
                return Ok(Err(held));
            }
            tx.execute("DELETE FROM nctwin_programs WHERE session = $1 AND name = $2", &[&id, &name])?;
            tx.commit().map(Ok)
        }))
    }

    fn set_persistent(&self, id: &str, persistent: bool) -> Result<(), StorageError> {
        let node = self.lease.node.as_str();
        flatten(self.with(|c| {
            let mut tx = c.transaction()?;
            if let Err(held) = fence(&mut tx, id, node)? {
                return Ok(Err(held));
            }
            tx.execute("UPDATE nctwin_sessions SET persistent = $2 WHERE id = $1", &[&id, &persistent])?;
            tx.commit().map(Ok)
        }))
    }

    fn save_activity(&self, activity: &[(String, u64)]) -> Result<(), StorageError> {
        // One transaction; sessions another node holds now are skipped (its node keeps their
        // activity).
        let node = self.lease.node.as_str();
        self.with(|c| {
            let mut tx = c.transaction()?;
            let update =
                tx.prepare("UPDATE nctwin_sessions SET last_active_ms = $2 WHERE id = $1 AND lease_node = $3")?;
            for (id, ms) in activity {
                tx.execute(&update, &[id, &((*ms).min(i64::MAX as u64) as i64), &node])?;
            }
            tx.commit()
        })
    }

    fn next_session_number(&self) -> Result<Option<u64>, StorageError> {
        let n: i64 = self.with(|c| c.query_one("SELECT nextval('nctwin_session_numbers')", &[]).map(|r| r.get(0)))?;
        Ok(Some(n.max(0) as u64))
    }

    fn claim_session(&self, id: &str) -> Result<Claim, StorageError> {
        let (node, period) = (self.lease.node.as_str(), self.lease.period.as_secs_f64());
        self.with(|c| {
            let mut tx = c.transaction()?;
            // This node's own lease first: a node whose row expired (renewals failed) must not
            // take sessions it could not keep.
            tx.execute(RENEW_NODE, &[&node, &period])?;
            let claimed = tx.query(
                &format!(
                    "UPDATE nctwin_sessions s SET lease_node = $2 WHERE s.id = $1 AND {} RETURNING {SESSION_COLUMNS}",
                    claimable("$2")
                ),
                &[&id, &node],
            )?;
            if !claimed.is_empty() {
                let saved = saved_sessions(&mut tx, claimed)?;
                tx.commit()?;
                return Ok(saved.into_iter().next().map_or(Claim::Missing, |s| Claim::Claimed(Box::new(s))));
            }
            let holder = tx.query_opt(
                &format!("SELECT s.lease_node, {HOLDER_SECONDS_LEFT} FROM nctwin_sessions s WHERE s.id = $1"),
                &[&id],
            )?;
            tx.commit()?;
            Ok(match holder {
                None => Claim::Missing,
                Some(row) => Claim::HeldBy {
                    node: row.get::<_, Option<String>>(0).unwrap_or_default(),
                    seconds_left: row.get::<_, Option<f64>>(1).unwrap_or(0.0),
                },
            })
        })
    }

    fn claim_sessions(&self, ids: &[String]) -> Result<Vec<(String, Claim)>, StorageError> {
        // One transaction (one commit to flush) for all: after a node died, the requests for
        // its sessions all wait for the same lease to run out and are claimed together.
        let (node, period) = (self.lease.node.as_str(), self.lease.period.as_secs_f64());
        self.with(|c| {
            let mut tx = c.transaction()?;
            tx.execute(RENEW_NODE, &[&node, &period])?;
            let claimed = tx.query(
                &format!(
                    "UPDATE nctwin_sessions s SET lease_node = $2 WHERE s.id = ANY($1) AND {}
                     RETURNING {SESSION_COLUMNS}",
                    claimable("$2")
                ),
                &[&ids, &node],
            )?;
            let mut outcome: HashMap<String, Claim> = saved_sessions(&mut tx, claimed)?
                .into_iter()
                .map(|saved| (saved.record.id.clone(), Claim::Claimed(Box::new(saved))))
                .collect();
            let rest: Vec<&String> = ids.iter().filter(|id| !outcome.contains_key(*id)).collect();
            if !rest.is_empty() {
                let held = tx.query(
                    &format!(
                        "SELECT s.id, s.lease_node, {HOLDER_SECONDS_LEFT} FROM nctwin_sessions s WHERE s.id = ANY($1)"
                    ),
                    &[&rest],
                )?;
                for row in held {
                    let claim = Claim::HeldBy {
                        node: row.get::<_, Option<String>>(1).unwrap_or_default(),
                        seconds_left: row.get::<_, Option<f64>>(2).unwrap_or(0.0),
                    };
                    outcome.insert(row.get(0), claim);
                }
            }
            tx.commit()?;
            Ok(ids.iter().map(|id| (id.clone(), outcome.remove(id).unwrap_or(Claim::Missing))).collect())
        })
    }

    fn renew_leases(&self) -> Result<Option<Vec<String>>, StorageError> {
        let (node, period) = (self.lease.node.as_str(), self.lease.period.as_secs_f64());
        // One row written per node, however many sessions it holds; the ids are read through
        // the index on `lease_node` (one round trip for both).
        let rows = self.with(|c| {
            c.query(
                &format!("WITH renewed AS ({RENEW_NODE}) SELECT id FROM nctwin_sessions WHERE lease_node = $1"),
                &[&node, &period],
            )
        })?;
        Ok(Some(rows.iter().map(|r| r.get(0)).collect()))
    }

    fn release_leases(&self) -> Result<(), StorageError> {
        let node = self.lease.node.as_str();
        self.with(|c| {
            let mut tx = c.transaction()?;
            tx.execute(
                "UPDATE nctwin_sessions SET lease_node = NULL, lease_expires = NULL WHERE lease_node = $1",
                &[&node],
            )?;
            tx.execute("DELETE FROM nctwin_nodes WHERE node = $1", &[&node])?;
            tx.commit()
        })
    }

    fn lease(&self) -> Option<&Lease> {
        Some(&self.lease)
    }
}
