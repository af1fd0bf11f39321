//! Persistence: everything about a session that must survive a restart goes through the
//! [`Storage`] trait, and nothing else in the server touches files.
//!
//! What is stored per session ([`SessionRecord`]): its id and creation number, the preset it
//! came from, the client address that created it (for the per-client session limit), the
//! SHA-256 hashes of its three tokens (never the tokens themselves), and a [`Checkpoint`] of
//! the channel: the whole machine data as NC data text (machine data, tool data, settable
//! frames; applying it to default data rebuilds the same data), the axis positions, the
//! operating mode and the resumable channel state (JSON, see [`crate::state::persist`]). Stored programs are kept one row per program, so a large program is written
//! once, not with every checkpoint; so is the AUTO program a checkpoint refers to
//! ([`ActiveProgram`]: one row per session, rewritten only when its SHA-256 changes).
//!
//! Durability: every method returns only after the change is on disk (see [`sqlite`]). Callers
//! acknowledge a client's write only after the storage call returned `Ok`.
//!
//! The trait is synchronous (SQLite is, and the PostgreSQL client used is); async callers run it
//! on a blocking worker ([`crate::state::AppState`] does that in one place).
//!
//! Backends: [`SqliteStorage`] (the embedded default under `--data-dir`), [`PostgresStorage`]
//! (`--database postgres://...`, for several server nodes on one database) and
//! [`MemoryStorage`] (tests). The conformance test every backend passes is
//! `server/tests/storage.rs`.

mod memory;
mod postgres;
mod sqlite;

use std::fmt::Debug;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use nctwin_engine::lang::ProgramText;

pub use memory::MemoryStorage;
pub use postgres::PostgresStorage;
pub use sqlite::SqliteStorage;

/// File name of the embedded database inside `--data-dir`.
pub const SQLITE_FILE: &str = "nctwin.sqlite3";

/// A storage failure (disk full, database locked by another process, corrupt file, ...), or a
/// write refused because another node holds the session's lease.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("storage: {message}")]
pub struct StorageError {
    pub message: String,
    /// Set when the write was refused because another node holds the session (several nodes
    /// on one database): the client is sent there (`421`), not told the storage failed.
    pub held_by: Option<HeldBy>,
}

/// The node holding a session's lease, when a write of this node was refused for it.
#[derive(Debug, Clone, PartialEq)]
pub struct HeldBy {
    pub session: String,
    pub node: String,
    /// How long the lease runs without renewal.
    pub seconds_left: f64,
}

impl StorageError {
    /// A failure of the storage itself.
    pub fn new(message: impl Into<String>) -> StorageError {
        StorageError { message: message.into(), held_by: None }
    }

    /// A write refused because node `held.node` holds session `held.session`.
    pub fn held(held: HeldBy) -> StorageError {
        let message = format!("session `{}` is held by node `{}`, not by this node", held.session, held.node);
        StorageError { message, held_by: Some(held) }
    }
}

impl From<rusqlite::Error> for StorageError {
    fn from(e: rusqlite::Error) -> StorageError {
        StorageError::new(e.to_string())
    }
}

/// The text of the AUTO program a checkpoint's channel state refers to (its `program.text` is
/// left empty). A backend keeps it once per session, beside the checkpoint, and writes it only
/// when `sha256` differs from the stored one: a program of up to 16 MiB is not rewritten with
/// every checkpoint.
#[derive(Debug, Clone, PartialEq)]
pub struct ActiveProgram {
    /// SHA-256 of the text, lowercase hex: what "changed" is decided by.
    pub sha256: String,
    pub text: ProgramText,
}

impl ActiveProgram {
    /// `text` with its hash computed (reads the whole text: callers cache it per session).
    pub fn hashed(text: ProgramText) -> ActiveProgram {
        use sha2::{Digest, Sha256};
        let digest = Sha256::digest(text.as_bytes());
        ActiveProgram { sha256: digest.iter().map(|b| format!("{b:02x}")).collect(), text }
    }
}

/// The part of a channel's state that is saved whenever a command ends and at shutdown.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    /// The channel's complete machine data as NC data text (`MachineData::to_text`).
    pub machine_data: String,
    /// Channel axis positions in machine coordinates, channel axis order.
    pub positions: Vec<f64>,
    /// Operating mode: `JOG`, `MDA` or `AUTO`.
    pub mode: String,
    /// The rest of the channel state a restart takes back (tool and cutting edge, toolholder,
    /// system frames, R parameters, a transformation kept over reset, the AUTO program and its
    /// block) as JSON; `None` in rows written before schema version 2. Since schema version 3
    /// the AUTO program's text is not in it but in `active_program`; older rows carry it inline.
    pub channel_state: Option<String>,
    /// The AUTO program the channel state refers to, if any.
    pub active_program: Option<ActiveProgram>,
}

/// SHA-256 hashes (lowercase hex) of a session's tokens.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TokenHashes {
    pub owner: String,
    pub operator: String,
    pub observer: String,
}

/// A session as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct SessionRecord {
    pub id: String,
    /// Creation number: the listing order, and the next id after a restart continues above it.
    pub number: u64,
    /// Preset id the session was created from.
    pub machine: String,
    /// Address of the client that created it, if known.
    pub client_ip: Option<String>,
    pub tokens: TokenHashes,
    pub checkpoint: Checkpoint,
    /// The owner marked the session persistent: it never expires for being idle.
    pub persistent: bool,
    /// When a client last used the session (Unix time, milliseconds), as last saved; `None`
    /// in rows written before schema version 4 (a restart then counts as activity).
    pub last_active_ms: Option<u64>,
}

/// A stored session with its stored programs (name, text), by name.
#[derive(Debug, Clone, PartialEq)]
pub struct SavedSession {
    pub record: SessionRecord,
    pub programs: Vec<(String, String)>,
}

/// The lease a node holds on the sessions it serves, when several nodes share one database.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Lease {
    /// The node's name, unique among the nodes on the database (`--node-id`).
    pub node: String,
    /// How long a lease lasts without renewal; a node renews its leases three times per period.
    pub period: Duration,
}

/// Default lease period: a node that died frees its sessions after at most this long (after
/// 4 to 6 s, as it renewed every 2 s), so that behind a proxy its sessions serve again within
/// 10 s; a renewal is one row per node, so renewing every 2 s costs nothing measurable.
pub const DEFAULT_LEASE_PERIOD: Duration = Duration::from_secs(6);

/// This host's name (`node` if unknown).
pub fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .unwrap_or_else(|| "node".into())
}

impl Default for Lease {
    /// This host's name and a random suffix: unique, but not kept over a restart (`nctwin`
    /// names a node after its host and port unless `--node-id` names it).
    fn default() -> Lease {
        let host = host_name();
        let mut suffix = [0u8; 4];
        let _ = getrandom::fill(&mut suffix);
        let suffix: String = suffix.iter().map(|b| format!("{b:02x}")).collect();
        Lease { node: format!("{host}-{suffix}"), period: DEFAULT_LEASE_PERIOD }
    }
}

/// What [`Storage::claim_session`] found.
#[derive(Debug, Clone, PartialEq)]
pub enum Claim {
    /// The session is now leased to this node; here it is, to start.
    Claimed(Box<SavedSession>),
    /// Another node holds a lease that has not expired.
    HeldBy { node: String, seconds_left: f64 },
    /// No such session.
    Missing,
}

/// Where sessions are kept. Every method is durable when it returns `Ok`.
pub trait Storage: Send + Sync + Debug {
    /// A short description for logs and `GET /health`, e.g. `sqlite:/var/lib/nctwin/nctwin.sqlite3`.
    fn describe(&self) -> String;
    /// Kind of backend: `sqlite`, `postgres` or `memory`.
    fn backend(&self) -> &'static str;
    /// Checks that the storage answers (a trivial read).
    fn check(&self) -> Result<(), StorageError>;
    /// Every stored session with its programs, in creation order (with leases: every session
    /// this node may serve, now leased to it).
    fn load(&self) -> Result<Vec<SavedSession>, StorageError>;
    /// Stores a new session (replacing one with the same id, with its programs).
    fn create_session(&self, record: &SessionRecord) -> Result<(), StorageError>;
    /// Replaces the checkpoint of session `id` (its active program only if the hash differs
    /// from the stored one); a deleted session stays deleted (no error).
    fn save_checkpoint(&self, id: &str, checkpoint: &Checkpoint) -> Result<(), StorageError>;
    /// Replaces the checkpoints of many sessions at once (shutdown); the default saves them one
    /// by one, a backend may do it in one transaction.
    fn save_checkpoints(&self, checkpoints: &[(String, Checkpoint)]) -> Result<(), StorageError> {
        checkpoints.iter().try_for_each(|(id, checkpoint)| self.save_checkpoint(id, checkpoint))
    }
    /// Deletes a session and its programs; deleting a missing session is no error.
    fn delete_session(&self, id: &str) -> Result<(), StorageError>;
    /// Stores (creates or replaces) program `name` of session `id`.
    fn put_program(&self, id: &str, name: &str, text: &str) -> Result<(), StorageError>;
    /// Deletes program `name` of session `id`; a missing program is no error.
    fn delete_program(&self, id: &str, name: &str) -> Result<(), StorageError>;
    /// Marks session `id` persistent (never expires when idle) or not; a missing session is no
    /// error.
    fn set_persistent(&self, id: &str, persistent: bool) -> Result<(), StorageError>;
    /// Records when sessions were last used (id, Unix time in milliseconds), all in one write;
    /// missing sessions (and, with leases, those another node holds) are skipped.
    fn save_activity(&self, activity: &[(String, u64)]) -> Result<(), StorageError>;

    // ---- several nodes on one database (PostgreSQL); a storage of one node keeps the defaults
    // (except `next_session_number`, which every storage that outlives the process implements).
    // With leases, `load` returns (and leases) only the sessions this node may serve, and every
    // write to a session another node holds fails.

    /// The number of a new session: never handed out before by this storage, also not after
    /// the session that had it was deleted and the server restarted (ids never repeat). `None`:
    /// the caller counts (a storage that keeps nothing over a restart).
    fn next_session_number(&self) -> Result<Option<u64>, StorageError> {
        Ok(None)
    }
    /// Leases session `id` to this node if it is free, expired or already this node's.
    fn claim_session(&self, _id: &str) -> Result<Claim, StorageError> {
        Ok(Claim::Missing)
    }
    /// [`Storage::claim_session`] for several sessions at once (a node taking over the sessions
    /// of a dead one), each with its outcome; a backend may do it in one transaction.
    fn claim_sessions(&self, ids: &[String]) -> Result<Vec<(String, Claim)>, StorageError> {
        ids.iter().map(|id| Ok((id.clone(), self.claim_session(id)?))).collect()
    }
    /// Renews this node's leases; the ids still held (`None`: no leases).
    fn renew_leases(&self) -> Result<Option<Vec<String>>, StorageError> {
        Ok(None)
    }
    /// Gives every lease of this node up (shutdown), so other nodes may take over at once.
    fn release_leases(&self) -> Result<(), StorageError> {
        Ok(())
    }
    /// This node's lease, if the storage has leases.
    fn lease(&self) -> Option<&Lease> {
        None
    }
}

/// Opens (creating if needed) the embedded default storage in `data_dir`.
pub fn open_default(data_dir: &Path) -> Result<SqliteStorage, StorageError> {
    std::fs::create_dir_all(data_dir)
        .map_err(|e| StorageError::new(format!("cannot create data directory {}: {e}", data_dir.display())))?;
    SqliteStorage::open(&data_dir.join(SQLITE_FILE))
}

/// Opens the storage `nctwin` runs on: the database at `database` when given (a
/// `postgres://` or `postgresql://` URL, used as node `lease`), else the embedded default in
/// `data_dir`. Blocks.
pub fn open(database: Option<&str>, data_dir: &Path, lease: Lease) -> Result<Arc<dyn Storage>, StorageError> {
    match database {
        None => Ok(Arc::new(open_default(data_dir)?)),
        Some(url) if url.starts_with("postgres://") || url.starts_with("postgresql://") => {
            Ok(Arc::new(PostgresStorage::open_as(url, lease)?))
        }
        Some(other) => {
            let scheme = other.split_once(':').map_or(other, |(scheme, _)| scheme);
            Err(StorageError::new(format!("unsupported database `{scheme}:`: expected a postgres:// URL")))
        }
    }
}
