//! [`AppState`]: what every request handler shares (sessions, directories, limits).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use nctwin_engine::Channel;

use crate::session::{ActorConfig, SessionHandle};

/// Server-side limits and pacing; [`Limits::default`] holds the documented values, tests may
/// shrink them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Wake period of real-time pacing (the default stream period): 50 ms, 20 Hz.
    pub period: Duration,
    /// Simulated time one fast-paced command may run before the channel is stopped: 3600 s.
    pub fast_sim_time: f64,
    /// Wall time after which a `wait: true` request is answered with the current state: 600 s.
    pub wait_wall_time: Duration,
    /// IPO cycles per blocking chunk in fast pace: 20,000.
    pub fast_chunk: u64,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            period: Duration::from_millis(50),
            fast_sim_time: 3600.0,
            wait_wall_time: Duration::from_secs(600),
            fast_chunk: 20_000,
        }
    }
}

impl Limits {
    fn actor_config(&self) -> ActorConfig {
        ActorConfig {
            period: self.period,
            fast_sim_time: self.fast_sim_time,
            wait_wall_time: self.wait_wall_time,
            fast_chunk: self.fast_chunk,
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
    /// Live sessions by id, each with its creation number for a stable listing order.
    ///
    /// A std `Mutex`, not Tokio's: it is held only to look up, insert or remove an entry and is
    /// never held across an `.await`, so it cannot block the runtime or deadlock a task.
    sessions: Mutex<HashMap<String, (u64, SessionHandle)>>,
    next_session: AtomicU64,
    data_dir: PathBuf,
    web_dir: PathBuf,
    limits: Limits,
}

impl AppState {
    /// State with the default [`Limits`]. `data_dir` is where persistent data will live (nothing
    /// is persisted yet); `web_dir` holds the HMI's static files.
    pub fn new(data_dir: impl Into<PathBuf>, web_dir: impl Into<PathBuf>) -> AppState {
        AppState::with_limits(data_dir, web_dir, Limits::default())
    }

    /// As [`AppState::new`] with other limits (tests shrink them to reach them quickly).
    pub fn with_limits(data_dir: impl Into<PathBuf>, web_dir: impl Into<PathBuf>, limits: Limits) -> AppState {
        AppState {
            shared: Arc::new(Shared {
                sessions: Mutex::new(HashMap::new()),
                next_session: AtomicU64::new(1),
                data_dir: data_dir.into(),
                web_dir: web_dir.into(),
                limits,
            }),
        }
    }

    /// Where persistent data is to be kept; created by `main`, not written yet.
    pub fn data_dir(&self) -> &Path {
        &self.shared.data_dir
    }

    /// The HMI's static files, served at `/`.
    pub fn web_dir(&self) -> &Path {
        &self.shared.web_dir
    }

    /// The limits every new session gets.
    pub fn limits(&self) -> &Limits {
        &self.shared.limits
    }

    fn sessions(&self) -> MutexGuard<'_, HashMap<String, (u64, SessionHandle)>> {
        // A panic while the lock was held cannot leave the map half-updated (every critical
        // section is one map operation), so a poisoned lock is safe to use.
        self.shared.sessions.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Starts a session for `channel` and registers it under a new short id (`s1`, `s2`, ...,
    /// base 36).
    pub fn create_session(&self, machine: &str, channel: Channel) -> SessionHandle {
        let n = self.shared.next_session.fetch_add(1, Ordering::Relaxed);
        let id = format!("s{}", base36(n));
        let handle = SessionHandle::spawn(&id, machine, channel, self.shared.limits.actor_config());
        self.sessions().insert(id, (n, handle.clone()));
        handle
    }

    /// The live session `id`, if any; the handle stays usable after the lock is released.
    pub fn session(&self, id: &str) -> Option<SessionHandle> {
        self.sessions().get(id).map(|(_, h)| h.clone())
    }

    /// Every live session in creation order.
    pub fn list_sessions(&self) -> Vec<SessionHandle> {
        let mut all: Vec<(u64, SessionHandle)> = self.sessions().values().cloned().collect();
        all.sort_by_key(|(n, _)| *n);
        all.into_iter().map(|(_, h)| h).collect()
    }

    /// Number of live sessions (for `GET /health`).
    pub fn session_count(&self) -> usize {
        self.sessions().len()
    }

    /// Unregisters a session and stops its actor; `false` if there was no such session.
    pub async fn remove_session(&self, id: &str) -> bool {
        let removed = self.sessions().remove(id);
        match removed {
            Some((_, handle)) => {
                handle.shutdown().await;
                true
            }
            None => false,
        }
    }

    /// Stops every session (server shutdown).
    pub async fn close_all_sessions(&self) {
        let all: Vec<SessionHandle> = self.sessions().drain().map(|(_, (_, h))| h).collect();
        for handle in all {
            handle.shutdown().await;
        }
    }
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
}
