//! [`AppState`]: what every request handler shares: the session registry, the storage, the
//! configured directories, limits and auth mode, and the metrics.
//!
//! Every save of a session goes through here (`persist_*`, `put_program`, ...), on a blocking
//! worker, so the storage's disk waits never block the async runtime.

mod entry;
pub mod expiry;
pub mod persist;

use std::collections::HashMap;
use std::net::IpAddr;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

use nctwin_engine::Channel;

pub use self::entry::{SessionEntry, StreamClientGuard};
use crate::auth::{AuthMode, TokenSet};
use crate::error::ApiError;
pub use crate::limits::Limits;
use crate::metrics::Metrics;
use crate::session::SessionHandle;
use crate::storage::{self, Claim, Lease, MemoryStorage, SessionRecord, Storage, StorageError};

/// How the server is set up (from `nctwin`'s flags, or by tests).
#[derive(Debug, Clone)]
pub struct Config {
    /// Where persistent data lives (`--data-dir`).
    pub data_dir: PathBuf,
    /// A database URL (`--database postgres://...`) to keep sessions in instead of the
    /// embedded SQLite file under `data_dir`.
    pub database: Option<String>,
    /// The HMI's static files, served at `/`.
    pub web_dir: PathBuf,
    pub limits: Limits,
    pub auth: AuthMode,
    /// This node's name on a shared database (`--node-id`); `None`: the host name with a random
    /// suffix. Only a PostgreSQL storage uses it.
    pub node_id: Option<String>,
    /// How long this node's session leases last without renewal (`--lease-seconds`).
    pub lease_period: std::time::Duration,
    /// Web page origins (`http://host:port`) besides the server's own that may call the API
    /// from a browser (`--allow-origin`); see [`crate::site`].
    pub allow_origins: Vec<String>,
    /// Host names besides the bound address and localhost that the server answers to
    /// (`--allow-host`, `NAME` or `NAME:PORT`); see [`crate::site`].
    pub allow_hosts: Vec<String>,
}

impl Config {
    /// Default limits, auth off.
    pub fn new(data_dir: impl Into<PathBuf>, web_dir: impl Into<PathBuf>) -> Config {
        Config {
            data_dir: data_dir.into(),
            database: None,
            web_dir: web_dir.into(),
            limits: Limits::default(),
            auth: AuthMode::Off,
            node_id: None,
            lease_period: storage::DEFAULT_LEASE_PERIOD,
            allow_origins: Vec::new(),
            allow_hosts: Vec::new(),
        }
    }
}

/// Cheap-to-clone shared state of the server.
#[derive(Debug, Clone)]
pub struct AppState {
    shared: Arc<Shared>,
}

#[derive(Debug)]
struct Shared {
    /// Live sessions by id.
    ///
    /// A std `Mutex`, not Tokio's: it is held only to look up, insert or remove an entry (and to
    /// count for the session limits) and is never held across an `.await`, so it cannot block
    /// the runtime or deadlock a task.
    sessions: Mutex<HashMap<String, Arc<SessionEntry>>>,
    next_session: AtomicU64,
    /// Serialises session creation from the limit check to the registration, so concurrent
    /// creations cannot together pass the session limits.
    create_lock: tokio::sync::Mutex<()>,
    /// Serialises taking over sessions from the shared database, so two requests for the same
    /// session cannot start it twice.
    claim_lock: tokio::sync::Mutex<()>,
    /// Sessions requests wait to take over, claimed together by whoever holds `claim_lock`.
    claim_queue: Mutex<std::collections::BTreeSet<String>>,
    /// Serialises the server-wide program budget's check and the session's new count (a std
    /// `Mutex` held for a sum over the registry, never across an await), so concurrent uploads
    /// to different sessions cannot together pass the budget.
    budget_lock: Mutex<()>,
    config: Config,
    storage: Arc<dyn Storage>,
    metrics: Metrics,
    /// Open WebSocket streams of every session, including those of sessions already closed
    /// whose close frame is still being sent (graceful shutdown waits for them).
    open_streams: Arc<AtomicUsize>,
}

/// Health of the storage, for `GET /health`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StorageHealth {
    pub backend: &'static str,
    pub error: Option<String>,
}

impl AppState {
    /// State with default [`Limits`], auth off and storage in memory: nothing survives the
    /// process. `nctwin` uses [`AppState::open`].
    pub fn new(data_dir: impl Into<PathBuf>, web_dir: impl Into<PathBuf>) -> AppState {
        AppState::with_limits(data_dir, web_dir, Limits::default())
    }

    /// As [`AppState::new`] with other limits.
    pub fn with_limits(data_dir: impl Into<PathBuf>, web_dir: impl Into<PathBuf>, limits: Limits) -> AppState {
        let config = Config { limits, ..Config::new(data_dir, web_dir) };
        AppState::with_storage(config, Arc::new(MemoryStorage::default()))
    }

    /// State on the given storage, with no session started (see [`AppState::restore`]).
    pub fn with_storage(config: Config, storage: Arc<dyn Storage>) -> AppState {
        AppState {
            shared: Arc::new(Shared {
                sessions: Mutex::new(HashMap::new()),
                next_session: AtomicU64::new(1),
                create_lock: tokio::sync::Mutex::new(()),
                claim_lock: tokio::sync::Mutex::new(()),
                claim_queue: Mutex::new(std::collections::BTreeSet::new()),
                budget_lock: Mutex::new(()),
                config,
                storage,
                metrics: Metrics::default(),
                open_streams: Arc::new(AtomicUsize::new(0)),
            }),
        }
    }

    /// Opens the storage (the database of `config.database` if set, else the embedded SQLite
    /// file under `config.data_dir`, creating it) and restores every saved session. Needs a
    /// Tokio runtime (the sessions' actors start on it).
    pub async fn open(config: Config) -> Result<AppState, StorageError> {
        let dir = config.data_dir.clone();
        let database = config.database.clone();
        let mut lease = Lease::default();
        if let Some(node) = &config.node_id {
            lease.node = node.clone();
        }
        lease.period = config.lease_period;
        let storage = tokio::task::spawn_blocking(move || storage::open(database.as_deref(), &dir, lease))
            .await
            .map_err(|e| StorageError::new(format!("opening the storage failed: {e}")))??;
        let state = AppState::with_storage(config, storage);
        let restored = state.restore().await?;
        let node = state.shared.storage.lease().map(|l| l.node.clone());
        tracing::info!(storage = %state.shared.storage.describe(), node = ?node, sessions = restored, "storage opened");
        state.start_heartbeat();
        state.start_expiry();
        Ok(state)
    }

    /// Starts every session the storage holds for this node (see [`persist`] for what a
    /// restored session looks like) and continues numbering above them. Returns how many were
    /// restored.
    pub async fn restore(&self) -> Result<usize, StorageError> {
        let saved = self.storage_call(|s| s.load()).await?;
        let mut restored = 0;
        for session in saved {
            restored += usize::from(self.start_saved(&session).is_some());
        }
        Ok(restored)
    }

    /// Rebuilds and starts a saved session; `None` (logged, the record stays in storage) if it
    /// no longer applies.
    fn start_saved(&self, session: &storage::SavedSession) -> Option<Arc<SessionEntry>> {
        let record = &session.record;
        self.shared.next_session.fetch_max(record.number.saturating_add(1), Ordering::Relaxed);
        let channel = match persist::rebuild(session) {
            Ok(channel) => channel,
            Err(e) => {
                tracing::error!(session = %record.id, error = %e, "saved session not restored (kept in storage)");
                return None;
            }
        };
        let client_ip = record.client_ip.as_deref().and_then(|ip| ip.parse().ok());
        let entry =
            self.start_session(&record.id, record.number, &record.machine, channel, client_ip, record.tokens.clone());
        entry.set_persistent(record.persistent);
        // A row without activity (saved before schema version 4): the restart counts as use.
        entry.set_saved_activity(record.last_active_ms.unwrap_or_else(expiry::now_ms));
        Some(entry)
    }

    /// The session `id` this node serves: a live one, or, on a shared database, one this node
    /// takes over because its lease is free or expired. `421` names the node that holds it;
    /// `404` if there is none. A holder that looks dead (the proxy meant the request for it but
    /// it arrived here, see [`crate::cluster`], or it missed a renewal) is waited for: once its
    /// lease ran out the session is taken over here, and the request is answered after that
    /// pause.
    pub async fn find_entry(&self, id: &str) -> Result<Arc<SessionEntry>, ApiError> {
        if let Some(entry) = self.entry(id) {
            return Ok(entry);
        }
        let Some(period) = self.shared.storage.lease().map(|l| l.period) else {
            return Err(ApiError::SessionNotFound(id.to_string()));
        };
        let mut waited = false;
        loop {
            let claim = {
                // Requests for sessions to take over queue their ids; whoever gets the lock
                // claims every queued one in one storage call (after a node died, the requests
                // for its sessions all wait for the same lease and come here together).
                self.claim_queue().insert(id.to_string());
                let _claiming = self.shared.claim_lock.lock().await;
                if let Some(entry) = self.entry(id) {
                    self.claim_queue().remove(id);
                    return Ok(entry);
                }
                let mut ids: Vec<String> = std::mem::take(&mut *self.claim_queue()).into_iter().collect();
                ids.retain(|queued| queued == id || self.entry(queued).is_none());
                if !ids.iter().any(|queued| queued == id) {
                    ids.push(id.to_string());
                }
                let started = std::time::Instant::now();
                let key = ids.clone();
                let claims = self.storage_call(move |s| s.claim_sessions(&key)).await?;
                let claimed_in = started.elapsed();
                let mut mine = Claim::Missing;
                let mut taken = 0;
                for (sid, claim) in claims {
                    match claim {
                        Claim::Claimed(saved) => {
                            taken += 1;
                            if self.start_saved(&saved).is_none() && sid == id {
                                return Err(ApiError::StorageUnavailable(format!(
                                    "session `{id}` is stored but cannot be restored here"
                                )));
                            }
                            if sid == id {
                                mine = Claim::Claimed(saved);
                            }
                        }
                        other if sid == id => mine = other,
                        _ => {}
                    }
                }
                if taken > 0 {
                    let total = started.elapsed();
                    for _ in 0..taken {
                        self.shared.metrics.lease_takeover(total / taken);
                    }
                    tracing::info!(
                        sessions = taken,
                        asked = ids.len(),
                        claim_ms = claimed_in.as_secs_f64() * 1e3,
                        restore_ms = (total - claimed_in).as_secs_f64() * 1e3,
                        "sessions taken over from the shared database"
                    );
                }
                if let Claim::Claimed(_) = mine {
                    return self.entry(id).ok_or_else(|| ApiError::SessionEnded(id.to_string()));
                }
                mine
            };
            match claim {
                Claim::HeldBy { node, seconds_left } => {
                    let wait = (!waited).then(|| takeover_wait(&node, seconds_left, period)).flatten();
                    let Some(wait) = wait else {
                        crate::cluster::note_holder(&node);
                        return Err(ApiError::WrongNode { session: id.to_string(), node, seconds_left });
                    };
                    tracing::info!(session = %id, holder = %node, wait_s = wait.as_secs_f64(), "waiting for a dead holder's lease to run out");
                    waited = true;
                    tokio::time::sleep(wait).await;
                }
                Claim::Missing | Claim::Claimed(_) => return Err(ApiError::SessionNotFound(id.to_string())),
            }
        }
    }

    /// Ids of sessions that requests wait to take over (see [`AppState::find_entry`]).
    fn claim_queue(&self) -> MutexGuard<'_, std::collections::BTreeSet<String>> {
        self.shared.claim_queue.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// This node's name on a shared database (`None`: a single node, no leases).
    pub fn node_name(&self) -> Option<String> {
        self.shared.storage.lease().map(|l| l.node.clone())
    }

    /// With leases (a shared database): renews this node's leases three times per lease
    /// period, and stops serving (without saving) every session whose lease another node has
    /// taken over meanwhile. Ends with the state.
    fn start_heartbeat(&self) {
        let Some(period) = self.shared.storage.lease().map(|l| l.period) else { return };
        let shared = Arc::downgrade(&self.shared);
        tokio::spawn(async move {
            let mut tick = tokio::time::interval(period / 3);
            tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
            tick.tick().await;
            loop {
                tick.tick().await;
                let Some(shared) = shared.upgrade() else { return };
                let state = AppState { shared };
                // No creation or takeover between the renewal and the comparison: a session
                // leased after the renewal's snapshot would look lost.
                let _creating = state.shared.create_lock.lock().await;
                let _claiming = state.shared.claim_lock.lock().await;
                let started = std::time::Instant::now();
                let renewed = state.storage_call(|s| s.renew_leases()).await;
                state
                    .shared
                    .metrics
                    .lease_renewal(renewed.as_ref().ok().and_then(Option::as_ref).map(Vec::len), started.elapsed());
                match renewed {
                    Ok(Some(held)) => state.drop_lost_sessions(&held).await,
                    Ok(None) => return,
                    Err(e) => tracing::warn!(error = %e, "session leases not renewed"),
                }
            }
        });
    }

    /// Stops the live sessions not in `held` (their lease went to another node).
    async fn drop_lost_sessions(&self, held: &[String]) {
        let lost: Vec<Arc<SessionEntry>> = {
            let mut sessions = self.sessions();
            let ids: Vec<String> = sessions.keys().filter(|id| !held.contains(id)).cloned().collect();
            ids.iter().filter_map(|id| sessions.remove(id)).collect()
        };
        for entry in lost {
            tracing::warn!(session = %entry.id(), "lease lost to another node: session no longer served here");
            entry.handle.shutdown().await;
        }
    }

    pub fn data_dir(&self) -> &Path {
        &self.shared.config.data_dir
    }

    pub fn web_dir(&self) -> &Path {
        &self.shared.config.web_dir
    }

    pub fn limits(&self) -> &Limits {
        &self.shared.config.limits
    }

    /// How the server was set up.
    pub fn config(&self) -> &Config {
        &self.shared.config
    }

    pub fn auth(&self) -> AuthMode {
        self.shared.config.auth
    }

    pub fn metrics(&self) -> &Metrics {
        &self.shared.metrics
    }

    fn sessions(&self) -> MutexGuard<'_, HashMap<String, Arc<SessionEntry>>> {
        // A panic while the lock was held cannot leave the map half-updated (every critical
        // section is one map operation), so a poisoned lock is safe to use.
        self.shared.sessions.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Runs a storage call on a blocking worker and counts it.
    async fn storage_call<R: Send + 'static>(
        &self,
        call: impl FnOnce(&dyn Storage) -> Result<R, StorageError> + Send + 'static,
    ) -> Result<R, StorageError> {
        let storage = self.shared.storage.clone();
        let result = tokio::task::spawn_blocking(move || call(storage.as_ref()))
            .await
            .unwrap_or_else(|e| Err(StorageError::new(format!("storage call failed: {e}"))));
        self.shared.metrics.storage_call(result.is_ok());
        if let Err(StorageError { held_by: Some(held), .. }) = &result {
            crate::cluster::note_holder(&held.node);
            self.stop_serving(&held.session);
        }
        result
    }

    /// Stops serving session `id` at once, without saving: a write found that another node took
    /// its lease (the heartbeat would find out at its next tick). The request that saw it is
    /// answered `421` naming that node (see [`ApiError`]'s `From<StorageError>`).
    fn stop_serving(&self, id: &str) {
        let Some(entry) = self.sessions().remove(id) else { return };
        tracing::warn!(session = %id, "lease lost to another node: session no longer served here");
        tokio::spawn(async move { entry.handle.shutdown().await });
    }

    /// Whether the storage answers, for `GET /health`.
    pub async fn storage_health(&self) -> StorageHealth {
        let backend = self.shared.storage.backend();
        StorageHealth { backend, error: self.storage_call(|s| s.check()).await.err().map(|e| e.message) }
    }

    /// Creates a session for `channel`: checks the session limits, makes its tokens, saves it
    /// (durably) and starts its actor. Ids are `s1`, `s2`, ... (base 36), numbered by the
    /// storage, which never hands a number out twice (not after a delete and a restart either,
    /// nor on another node of a shared database). `persistent`: never expires when idle.
    pub async fn create_session(
        &self,
        machine: &str,
        channel: Channel,
        client_ip: Option<IpAddr>,
        persistent: bool,
    ) -> Result<(Arc<SessionEntry>, TokenSet), ApiError> {
        let limits = *self.limits();
        let _creating = self.shared.create_lock.lock().await;
        {
            let sessions = self.sessions();
            if sessions.len() >= limits.sessions {
                return Err(ApiError::TooManyRequests {
                    message: format!("the server holds {} sessions, its limit; delete one first", limits.sessions),
                    retry_after: None,
                });
            }
            if let Some(ip) = client_ip
                && sessions.values().filter(|e| e.client_ip == Some(ip)).count() >= limits.sessions_per_ip
            {
                return Err(ApiError::TooManyRequests {
                    message: format!(
                        "{ip} has {} sessions, the limit per client; delete one first",
                        limits.sessions_per_ip
                    ),
                    retry_after: None,
                });
            }
        }
        let tokens = TokenSet::generate()
            .map_err(|e| ApiError::StorageUnavailable(format!("no random numbers for tokens: {e}")))?;
        // The storage hands out numbers (durably, so ids never repeat; on a shared database
        // nodes never make the same id); only a storage that keeps nothing leaves it to us.
        let number = match self.storage_call(|s| s.next_session_number()).await? {
            Some(n) => n,
            None => self.shared.next_session.fetch_add(1, Ordering::Relaxed),
        };
        let id = format!("s{}", base36(number));
        let record = SessionRecord {
            id: id.clone(),
            number,
            machine: machine.to_string(),
            client_ip: client_ip.map(|ip| ip.to_string()),
            tokens: tokens.hashes(),
            checkpoint: persist::checkpoint(&channel),
            persistent,
            last_active_ms: Some(expiry::now_ms()),
        };
        let created_ms = record.last_active_ms.unwrap_or_default();
        // Saved before it is started: a session the client hears of is on disk.
        self.storage_call(move |s| s.create_session(&record)).await?;
        let entry = self.start_session(&id, number, machine, channel, client_ip, tokens.hashes());
        entry.set_persistent(persistent);
        entry.set_saved_activity(created_ms);
        Ok((entry, tokens))
    }

    /// Registers a session and starts its actor and its saver (which writes a checkpoint each
    /// time the channel comes to rest after commands).
    fn start_session(
        &self,
        id: &str,
        number: u64,
        machine: &str,
        mut channel: Channel,
        client_ip: Option<IpAddr>,
        tokens: storage::TokenHashes,
    ) -> Arc<SessionEntry> {
        // Files programs write (WRITE) keep to the session's quota, as programs PUT over REST do.
        channel.set_program_budget(Some(self.limits().session_program_bytes));
        let program_bytes = stored_bytes(&channel);
        let handle = SessionHandle::spawn(id, machine, channel, self.limits().actor_config());
        let entry = Arc::new(SessionEntry::new(handle.clone(), number, client_ip, tokens, self.limits()));
        entry.program_bytes.store(program_bytes, Ordering::Release);
        self.sessions().insert(id.to_string(), entry.clone());
        let state = self.clone();
        let mut settled = handle.watch_settled();
        let saver_entry = entry.clone();
        tokio::spawn(async move {
            // Ends when the actor ends (the counter's sender is dropped).
            while settled.changed().await.is_ok() {
                if let Err(e) = state.persist_checkpoint(&saver_entry).await {
                    tracing::warn!(session = %saver_entry.id(), error = %e, "checkpoint not saved");
                }
            }
        });
        entry
    }

    /// Reads the channel's checkpoint and saves it. The read happens under the save lock, so
    /// the last write is always of the newest state.
    pub async fn persist_checkpoint(&self, entry: &SessionEntry) -> Result<(), ApiError> {
        let _guard = entry.save_lock.lock().await;
        // The files the program wrote since the last checkpoint are saved with it.
        let ((mut checkpoint, text), changes, bytes) = entry
            .handle
            .with_channel(|ch| {
                let changes = ch.take_program_changes();
                let bytes = (!changes.is_empty()).then(|| stored_bytes(ch));
                (persist::checkpoint_unhashed(ch), changes, bytes)
            })
            .await
            .map_err(|e| ApiError::from_session(entry.id(), e))?;
        if let Some(bytes) = bytes {
            entry.program_bytes.store(bytes, Ordering::Release);
        }
        let id = entry.id().to_string();
        let hashes = entry.program_hash.clone();
        self.storage_call(move |s| {
            persist::save_program_changes(s, &id, &changes)?;
            checkpoint.active_program = hashes.checkpointed(text);
            s.save_checkpoint(&id, &checkpoint)
        })
        .await?;
        Ok(())
    }

    /// Stores a program in the channel and in storage; the stored name on success.
    pub async fn put_program(&self, entry: &SessionEntry, name: String, text: String) -> Result<String, ApiError> {
        let limits = *self.limits();
        if text.len() > limits.program_bytes {
            return Err(ApiError::TooLarge(format!(
                "program of {} bytes is larger than the limit of {} bytes",
                text.len(),
                limits.program_bytes
            )));
        }
        let _guard = entry.save_lock.lock().await;
        let id = entry.id().to_string();
        let text = Arc::<str>::from(text);
        let for_channel = text.clone();
        let state = self.clone();
        let counter = entry.program_bytes.clone();
        let (stored, previous) = entry
            .handle
            .with_channel(move |ch| {
                let previous = ch.stored_program(&name).map(str::to_string);
                let total = stored_bytes(ch);
                let replaced = previous.as_ref().map_or(0, String::len);
                let after = total - replaced + for_channel.len();
                if after > limits.session_program_bytes {
                    return Err(ApiError::TooLarge(format!(
                        "the session's programs would exceed the limit of {} bytes in total; delete some first",
                        limits.session_program_bytes
                    )));
                }
                state.reserve_program_bytes(&counter, after)?;
                let stored = ch.store_program(&name, &for_channel).map_err(ApiError::from);
                if stored.is_err() {
                    counter.store(total, Ordering::Release);
                }
                Ok((stored?, previous))
            })
            .await
            .map_err(|e| ApiError::from_session(&id, e))??;
        let name = stored.clone();
        let written = self.storage_call(move |s| s.put_program(&id, &name, &text)).await;
        if let Err(e) = written {
            // Not saved, so not applied either: the channel gets its previous program back.
            let name = stored.clone();
            let counter = entry.program_bytes.clone();
            let _ = entry
                .handle
                .with_channel(move |ch| {
                    match previous {
                        Some(text) => drop(ch.store_program(&name, &text)),
                        None => drop(ch.delete_program(&name)),
                    }
                    counter.store(stored_bytes(ch), Ordering::Release);
                })
                .await;
            return Err(e.into());
        }
        Ok(stored)
    }

    /// Deletes a stored program from the channel and from storage; `false` if there was none.
    pub async fn delete_program(&self, entry: &SessionEntry, name: String) -> Result<bool, ApiError> {
        let _guard = entry.save_lock.lock().await;
        let id = entry.id().to_string();
        // The engine normalises names (upper case, no .MPF/.SPF); the one that disappeared is
        // the stored name.
        let counter = entry.program_bytes.clone();
        let removed = entry
            .handle
            .with_channel(move |ch| {
                let before = ch.stored_programs();
                let text = ch.stored_program(&name).map(str::to_string)?;
                if !ch.delete_program(&name) {
                    return None;
                }
                let after = ch.stored_programs();
                counter.store(after.iter().map(|(_, size)| size).sum(), Ordering::Release);
                let canonical = before.into_iter().map(|(n, _)| n).find(|n| !after.iter().any(|(a, _)| a == n))?;
                Some((canonical, text))
            })
            .await
            .map_err(|e| ApiError::from_session(&id, e))?;
        let Some((canonical, text)) = removed else { return Ok(false) };
        let name = canonical.clone();
        if let Err(e) = self.storage_call(move |s| s.delete_program(&id, &name)).await {
            // Not saved, so not applied either: the program is put back.
            let counter = entry.program_bytes.clone();
            let _ = entry
                .handle
                .with_channel(move |ch| {
                    drop(ch.store_program(&canonical, &text));
                    counter.store(stored_bytes(ch), Ordering::Release);
                })
                .await;
            return Err(e.into());
        }
        Ok(true)
    }

    /// Sets a session's count of stored program bytes to `after` if the server's budget allows
    /// it (a count that shrinks always may); `413` naming the budget otherwise.
    fn reserve_program_bytes(&self, counter: &AtomicUsize, after: usize) -> Result<(), ApiError> {
        let budget = self.limits().program_budget_bytes;
        let _budget = self.shared.budget_lock.lock().unwrap_or_else(|e| e.into_inner());
        let before = counter.load(Ordering::Acquire);
        if after > before {
            let used = self.program_bytes_total();
            if used - before.min(used) + after > budget {
                return Err(ApiError::TooLarge(format!(
                    "the server's budget of {budget} bytes for stored programs (all sessions together) would be exceeded ({used} bytes held); delete programs or sessions first"
                )));
            }
        }
        counter.store(after, Ordering::Release);
        Ok(())
    }

    /// Bytes of stored programs in every live session.
    pub fn program_bytes_total(&self) -> usize {
        self.sessions().values().map(|e| e.program_bytes()).sum()
    }

    /// Marks a session persistent (it never expires when idle) or not; saved before the reply.
    pub async fn set_persistent(&self, entry: &SessionEntry, persistent: bool) -> Result<(), ApiError> {
        let _guard = entry.save_lock.lock().await;
        let id = entry.id().to_string();
        self.storage_call(move |s| s.set_persistent(&id, persistent)).await?;
        entry.set_persistent(persistent);
        Ok(())
    }

    /// The live session `id`, if any; the handle stays usable after the lock is released.
    pub fn session(&self, id: &str) -> Option<SessionHandle> {
        self.sessions().get(id).map(|e| e.handle.clone())
    }

    /// The registry entry of session `id`.
    pub fn entry(&self, id: &str) -> Option<Arc<SessionEntry>> {
        self.sessions().get(id).cloned()
    }

    /// Every live session in creation order.
    pub fn list_sessions(&self) -> Vec<SessionHandle> {
        self.list_entries().into_iter().map(|e| e.handle.clone()).collect()
    }

    /// Every registry entry in creation order.
    pub fn list_entries(&self) -> Vec<Arc<SessionEntry>> {
        let mut all: Vec<Arc<SessionEntry>> = self.sessions().values().cloned().collect();
        all.sort_by_key(|e| e.number);
        all
    }

    /// Registers a WebSocket client of `entry` (`429` at the per-session limit).
    pub fn add_stream_client(&self, entry: &SessionEntry) -> Result<StreamClientGuard, ApiError> {
        entry.add_stream_client(self.limits(), &self.shared.open_streams)
    }

    /// Open WebSocket streams on the whole server.
    pub fn open_streams(&self) -> usize {
        self.shared.open_streams.load(Ordering::Acquire)
    }

    /// Number of live sessions.
    pub fn session_count(&self) -> usize {
        self.sessions().len()
    }

    /// Deletes a session from storage, then unregisters it and stops its actor; `Ok(false)` if
    /// there was no such session.
    pub async fn remove_session(&self, id: &str) -> Result<bool, ApiError> {
        let Some(entry) = self.entry(id) else { return Ok(false) };
        let _guard = entry.save_lock.lock().await;
        let key = id.to_string();
        self.storage_call(move |s| s.delete_session(&key)).await?;
        let removed = self.sessions().remove(id);
        if let Some(entry) = removed {
            entry.handle.shutdown().await;
        }
        Ok(true)
    }

    /// Server shutdown: saves every session's checkpoint in one write, then stops every actor
    /// (which closes every stream and answers every waiting request).
    pub async fn shutdown_sessions(&self) {
        // The idle clocks go on from here after the restart.
        self.save_activity().await;
        let all = self.list_entries();
        // Every save lock is held from the read to the write, so no later write is overtaken.
        let mut guards = Vec::with_capacity(all.len());
        let mut checkpoints = Vec::with_capacity(all.len());
        for entry in &all {
            guards.push(entry.save_lock.lock().await);
            let changes = entry.handle.with_channel(|ch| ch.take_program_changes()).await.unwrap_or_default();
            if !changes.is_empty() {
                let id = entry.id().to_string();
                if let Err(e) = self.storage_call(move |s| persist::save_program_changes(s, &id, &changes)).await {
                    tracing::warn!(session = %entry.id(), error = %e, "files written by programs not saved at shutdown");
                }
            }
            match entry.handle.with_channel(|ch| persist::checkpoint_unhashed(ch)).await {
                Ok((mut checkpoint, text)) => {
                    // Cached: hashed when the program was checkpointed last, unless it changed.
                    checkpoint.active_program = entry.program_hash.checkpointed(text);
                    checkpoints.push((entry.id().to_string(), checkpoint));
                }
                Err(e) => tracing::warn!(session = %entry.id(), error = %e, "no checkpoint at shutdown"),
            }
        }
        let saved = checkpoints.len();
        match self.storage_call(move |s| s.save_checkpoints(&checkpoints)).await {
            Ok(()) => {
                tracing::info!(sessions = saved, "every session saved");
                // Saved: other nodes may take the sessions over at once.
                if let Err(e) = self.storage_call(|s| s.release_leases()).await {
                    tracing::warn!(error = %e, "session leases not released (they expire)");
                }
            }
            Err(e) => tracing::error!(error = %e, "sessions not saved at shutdown"),
        }
        drop(guards);
        let all: Vec<Arc<SessionEntry>> = self.sessions().drain().map(|(_, e)| e).collect();
        for entry in all {
            entry.handle.shutdown_for_server_stop().await;
        }
    }
}

/// Bytes of a channel's stored programs.
fn stored_bytes(channel: &Channel) -> usize {
    channel.stored_programs().iter().map(|(_, size)| size).sum()
}

/// `n` in base 36 with digits `0-9a-z`.
fn base36(mut n: u64) -> String {
    const DIGITS: &[u8; 36] = b"0123456789abcdefghijklmnopqrstuvwxyz";
    let mut out = Vec::new();
    loop {
        out.push(DIGITS[(n % 36) as usize]);
        n /= 36;
        if n == 0 {
            break;
        }
    }
    out.reverse();
    String::from_utf8(out).unwrap_or_default()
}

/// How long to wait before claiming a session that node `holder` holds with `seconds_left` of
/// its lease (period `period`, as this node's: every node of a database runs the same
/// `--lease-seconds`), or `None` to answer `421` at once because the holder looks alive. A
/// live holder renews three times per period, so its lease never runs below two thirds of the
/// period (less a second of slack for a slow renewal); below that it missed a renewal. A holder
/// the proxy meant the request for (it did not reach it) is waited for whatever its lease says.
fn takeover_wait(holder: &str, seconds_left: f64, period: std::time::Duration) -> Option<std::time::Duration> {
    let reported_down = crate::cluster::routed_to().is_some_and(|n| n == holder);
    let missed_renewal = seconds_left < period.as_secs_f64() * 2.0 / 3.0 - 1.0;
    // 50 ms past the expiry: the database's clock decides, and this node's sleep is not exact.
    (reported_down || missed_renewal)
        .then(|| std::time::Duration::from_secs_f64(seconds_left.clamp(0.0, period.as_secs_f64()) + 0.05))
}

#[cfg(test)]
mod tests {
    use super::base36;

    #[test]
    fn session_numbers_are_written_in_base_36() {
        assert_eq!(base36(0), "0");
        assert_eq!(base36(35), "z");
        assert_eq!(base36(36), "10");
        assert_eq!(base36(1_295), "zz");
    }

    /// Period 6 s, renewed every 2 s: a live holder has 4..6 s left; below 3 s (a second of
    /// slack) it missed a renewal and its lease is waited out (plus 50 ms).
    #[test]
    fn a_holder_is_waited_for_only_when_it_missed_a_renewal() {
        use std::time::Duration;
        let period = Duration::from_secs(6);
        assert_eq!(super::takeover_wait("b", 5.9, period), None);
        assert_eq!(super::takeover_wait("b", 3.5, period), None);
        assert_eq!(super::takeover_wait("b", 2.5, period), Some(Duration::from_secs_f64(2.55)));
        assert_eq!(super::takeover_wait("b", 0.0, period), Some(Duration::from_millis(50)));
        // A lease period of 1 s never leaves room for a missed renewal to be seen.
        assert_eq!(super::takeover_wait("b", 0.1, Duration::from_secs(1)), None);
    }
}
