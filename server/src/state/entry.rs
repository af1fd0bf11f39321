//! [`SessionEntry`]: what the server keeps per session besides the actor: tokens, who holds
//! control, the command rate limiter, the stream client count, the shared encoded state
//! message of its streams, the save lock, and what idle expiry and the program budget count
//! (last activity, the persistent mark, the bytes of stored programs).

use std::net::IpAddr;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use tokio::time::Instant;

use super::persist::ProgramHashCache;
use crate::api::stream_frame::FrameCache;
use crate::auth::Role;
use crate::error::ApiError;
use crate::limits::{Limits, RateLimiter};
use crate::session::SessionHandle;
use crate::storage::TokenHashes;

/// One live session in the registry.
#[derive(Debug)]
pub struct SessionEntry {
    pub handle: SessionHandle,
    /// Creation number (listing order; ids continue above the highest after a restart).
    pub number: u64,
    /// The client that created the session (per-client session limit).
    pub client_ip: Option<IpAddr>,
    pub tokens: TokenHashes,
    /// The role whose token holds control (`--auth required`); clients sharing a token share
    /// control. The owner holds it when the session is created or restored.
    ///
    /// This and `rate` are std mutexes held for one read or update, never across an await.
    control: Mutex<Option<Role>>,
    rate: Mutex<RateLimiter>,
    stream_clients: Arc<AtomicUsize>,
    /// The last state message, encoded once for all stream clients.
    pub frames: FrameCache,
    /// Serialises "change the channel, then write the change" sequences of this session, so
    /// that storage never ends up older than what a client was told was saved.
    pub save_lock: tokio::sync::Mutex<()>,
    /// The hash of the AUTO program last checkpointed (see [`super::persist`]).
    pub program_hash: Arc<ProgramHashCache>,
    /// The owner marked the session persistent: it never expires for being idle.
    persistent: AtomicBool,
    /// When a client last used the session (Unix time, ms): a request that passed the access
    /// check, an open stream or a running program (see [`super::expiry`]).
    last_active_ms: AtomicU64,
    /// The last activity storage holds (written in batches by the expiry sweep).
    saved_active_ms: AtomicU64,
    /// Bytes of the session's stored programs (the server-wide budget and `/metrics`); set
    /// from the channel's program store whenever it changes.
    pub(super) program_bytes: Arc<AtomicUsize>,
    /// Bytes of program text syntax-checked (`POST .../check`), a std mutex like `rate`.
    check_rate: Mutex<RateLimiter>,
}

impl SessionEntry {
    pub fn new(
        handle: SessionHandle,
        number: u64,
        client_ip: Option<IpAddr>,
        tokens: TokenHashes,
        limits: &Limits,
    ) -> SessionEntry {
        SessionEntry {
            handle,
            number,
            client_ip,
            tokens,
            control: Mutex::new(Some(Role::Owner)),
            rate: Mutex::new(RateLimiter::new(limits.commands_per_second, limits.command_burst, Instant::now())),
            stream_clients: Arc::new(AtomicUsize::new(0)),
            frames: FrameCache::default(),
            save_lock: tokio::sync::Mutex::new(()),
            program_hash: Arc::default(),
            persistent: AtomicBool::new(false),
            last_active_ms: AtomicU64::new(0),
            saved_active_ms: AtomicU64::new(0),
            program_bytes: Arc::new(AtomicUsize::new(0)),
            check_rate: Mutex::new(RateLimiter::new(
                limits.check_bytes_per_second as f64,
                limits.check_burst_bytes as f64,
                Instant::now(),
            )),
        }
    }

    /// Whether the owner marked the session persistent (it never expires when idle).
    pub fn persistent(&self) -> bool {
        self.persistent.load(Ordering::Acquire)
    }

    pub(super) fn set_persistent(&self, persistent: bool) {
        self.persistent.store(persistent, Ordering::Release);
    }

    /// Notes that a client used the session now.
    pub fn touch(&self) {
        self.touch_at(super::expiry::now_ms());
    }

    pub(super) fn touch_at(&self, now_ms: u64) {
        self.last_active_ms.fetch_max(now_ms, Ordering::AcqRel);
    }

    /// When a client last used the session (Unix time, ms).
    pub fn last_active_ms(&self) -> u64 {
        self.last_active_ms.load(Ordering::Acquire)
    }

    /// Sets the activity as storage holds it (at start: a restored or created session).
    pub(super) fn set_saved_activity(&self, ms: u64) {
        self.last_active_ms.fetch_max(ms, Ordering::AcqRel);
        self.saved_active_ms.store(ms, Ordering::Release);
    }

    /// The activity storage holds, as far as this server wrote or read it.
    pub(super) fn saved_active_ms(&self) -> u64 {
        self.saved_active_ms.load(Ordering::Acquire)
    }

    /// Bytes of the session's stored programs.
    pub fn program_bytes(&self) -> usize {
        self.program_bytes.load(Ordering::Acquire)
    }

    pub fn id(&self) -> &str {
        self.handle.id()
    }

    /// Who holds control now.
    pub fn control_holder(&self) -> Option<Role> {
        *self.control.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// `role` takes control: allowed when nobody holds it, when `role` holds it already, and
    /// always for the owner. Observers never hold control.
    pub fn take_control(&self, role: Role) -> Result<(), ApiError> {
        if role == Role::Observer {
            return Err(ApiError::Forbidden("observers cannot take control".into()));
        }
        let mut holder = self.control.lock().unwrap_or_else(|e| e.into_inner());
        match *holder {
            Some(h) if h != role && role != Role::Owner => {
                Err(ApiError::Conflict(format!("control is held by the {h}; it must release it first")))
            }
            _ => {
                *holder = Some(role);
                Ok(())
            }
        }
    }

    /// `role` gives control up; refused when it does not hold it.
    pub fn release_control(&self, role: Role) -> Result<(), ApiError> {
        let mut holder = self.control.lock().unwrap_or_else(|e| e.into_inner());
        if *holder != Some(role) {
            return Err(ApiError::Conflict(format!("the {role} does not hold control")));
        }
        *holder = None;
        Ok(())
    }

    /// Counts one command against the rate limit.
    pub fn take_command(&self, limits: &Limits) -> Result<(), ApiError> {
        let result = self.rate.lock().unwrap_or_else(|e| e.into_inner()).take(Instant::now());
        result.map_err(|wait| ApiError::TooManyRequests {
            message: format!(
                "session `{}` takes at most {} commands per second (bursts of {}); retry later",
                self.id(),
                limits.commands_per_second,
                limits.command_burst
            ),
            retry_after: Some(wait),
        })
    }

    /// Counts a syntax check of `bytes` of program text against the session's check budget.
    pub fn take_check(&self, bytes: usize, limits: &Limits) -> Result<(), ApiError> {
        let result = self.check_rate.lock().unwrap_or_else(|e| e.into_inner()).take_n(bytes as f64, Instant::now());
        result.map_err(|wait| ApiError::TooManyRequests {
            message: format!(
                "session `{}` has at most {} bytes of program text per second syntax-checked (bursts of {}); retry the check later",
                self.id(),
                limits.check_bytes_per_second,
                limits.check_burst_bytes
            ),
            retry_after: Some(wait),
        })
    }

    /// Registers a stream client, also in the server-wide count `all`; the guard unregisters
    /// it when dropped. `429` at the limit.
    pub fn add_stream_client(&self, limits: &Limits, all: &Arc<AtomicUsize>) -> Result<StreamClientGuard, ApiError> {
        let counter = self.stream_clients.clone();
        let before = counter.fetch_add(1, Ordering::AcqRel);
        all.fetch_add(1, Ordering::AcqRel);
        let guard = StreamClientGuard { session: counter, all: all.clone() };
        if before >= limits.stream_clients {
            return Err(ApiError::TooManyRequests {
                message: format!(
                    "session `{}` already has {} stream clients (the limit)",
                    self.id(),
                    limits.stream_clients
                ),
                retry_after: None,
            });
        }
        Ok(guard)
    }

    /// Open WebSocket streams of this session.
    pub fn stream_clients(&self) -> usize {
        self.stream_clients.load(Ordering::Acquire)
    }
}

/// Holds one place among a session's stream clients (and the server's).
#[derive(Debug)]
pub struct StreamClientGuard {
    session: Arc<AtomicUsize>,
    all: Arc<AtomicUsize>,
}

impl Drop for StreamClientGuard {
    fn drop(&mut self) {
        self.session.fetch_sub(1, Ordering::AcqRel);
        self.all.fetch_sub(1, Ordering::AcqRel);
    }
}
