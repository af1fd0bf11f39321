//! [`SessionEntry`]: what the server keeps per session besides the actor: tokens, who holds
//! control, the command rate limiter, the stream client count, the shared encoded state
//! message of its streams and the save lock.

use std::net::IpAddr;
use std::sync::atomic::{AtomicUsize, Ordering};
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
            check_rate: Mutex::new(RateLimiter::new(
                limits.check_bytes_per_second as f64,
                limits.check_burst_bytes as f64,
                Instant::now(),
            )),
        }
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
