//! Idle expiry: a session no client has used for [`Limits::session_idle`] is deleted, from
//! storage too, unless its owner marked it persistent.
//!
//! What counts as use: a request to the session that passed the access check (commands and
//! reads alike; see `auth::access`), an open WebSocket stream and a running program (checked at
//! every sweep, so a program running for days keeps its session). Creating a session is its
//! first use.
//!
//! Across restarts: the last activity is saved (Unix time, so it survives the process) in one
//! batch per sweep for the sessions used since the last one, and at shutdown. After a restart
//! a session's idle time continues from what storage holds; the server's downtime counts as
//! idle time. A crash loses at most one sweep period of activity (a quarter of the timeout, at
//! most a minute), so a session can expire that much early after a SIGKILL, never later. Rows
//! saved before schema version 4 have no activity: for them the restart counts as activity.
//!
//! [`Limits::session_idle`]: crate::limits::Limits::session_idle

use std::sync::Arc;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use nctwin_engine::Status;

use super::{AppState, SessionEntry};

/// Now as Unix time in milliseconds (wall time: the activity is compared across restarts).
pub fn now_ms() -> u64 {
    SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_millis().min(u128::from(u64::MAX)) as u64)
}

/// How often the sweep runs for `timeout`: a quarter of it, between 50 ms and one minute.
pub fn sweep_period(timeout: Duration) -> Duration {
    (timeout / 4).clamp(Duration::from_millis(50), Duration::from_secs(60))
}

/// Whether the session is in use right now without a request: a stream is open or a program
/// runs.
fn in_use(entry: &SessionEntry) -> bool {
    entry.stream_clients() > 0 || entry.handle.snapshot().status == Status::Running
}

impl AppState {
    /// Starts the sweep that expires idle sessions and saves the activity (nothing when the
    /// timeout is zero). Ends with the state.
    pub(super) fn start_expiry(&self) {
        let timeout = self.limits().session_idle;
        if timeout.is_zero() {
            return;
        }
        let shared = Arc::downgrade(&self.shared);
        tokio::spawn(async move {
            let mut tick = tokio::time::interval(sweep_period(timeout));
            tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
            loop {
                tick.tick().await;
                let Some(shared) = shared.upgrade() else { return };
                AppState { shared }.sweep(timeout).await;
            }
        });
    }

    /// One sweep: notes the sessions in use, deletes those idle for `timeout` and saves the
    /// activity that changed since the last sweep.
    async fn sweep(&self, timeout: Duration) {
        let now = now_ms();
        let timeout_ms = timeout.as_millis().min(u128::from(u64::MAX)) as u64;
        for entry in self.list_entries() {
            if in_use(&entry) {
                entry.touch_at(now);
            } else if !entry.persistent() && now.saturating_sub(entry.last_active_ms()) >= timeout_ms {
                self.expire(&entry, timeout_ms).await;
            }
        }
        self.save_activity().await;
    }

    /// Deletes `entry` if it is still idle once its save lock is held (a request may have
    /// used it meanwhile).
    async fn expire(&self, entry: &SessionEntry, timeout_ms: u64) {
        let idle =
            || !entry.persistent() && !in_use(entry) && now_ms().saturating_sub(entry.last_active_ms()) >= timeout_ms;
        let guard = entry.save_lock.lock().await;
        if !idle() {
            return;
        }
        let id = entry.id().to_string();
        let key = id.clone();
        if let Err(e) = self.storage_call(move |s| s.delete_session(&key)).await {
            tracing::warn!(session = %id, error = %e, "idle session not deleted from storage (tried again next sweep)");
            return;
        }
        let removed = self.sessions().remove(&id);
        drop(guard);
        let idle_s = now_ms().saturating_sub(entry.last_active_ms()) / 1000;
        tracing::info!(session = %id, idle_s, "idle session expired and deleted");
        if let Some(entry) = removed {
            entry.handle.shutdown().await;
        }
    }

    /// Saves the last activity of every live session used since it was last saved, in one
    /// write.
    pub(super) async fn save_activity(&self) {
        let changed: Vec<(Arc<SessionEntry>, u64)> = self
            .list_entries()
            .into_iter()
            .filter_map(|e| {
                let last = e.last_active_ms();
                (last != e.saved_active_ms()).then_some((e, last))
            })
            .collect();
        if changed.is_empty() {
            return;
        }
        let batch: Vec<(String, u64)> = changed.iter().map(|(e, ms)| (e.id().to_string(), *ms)).collect();
        match self.storage_call(move |s| s.save_activity(&batch)).await {
            Ok(()) => changed.iter().for_each(|(e, ms)| e.set_saved_activity(*ms)),
            Err(e) => tracing::warn!(error = %e, "session activity not saved (tried again next sweep)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sweep_runs_four_times_per_timeout_within_bounds() {
        assert_eq!(sweep_period(Duration::from_secs(2)), Duration::from_millis(500));
        assert_eq!(sweep_period(Duration::from_secs(24 * 3600)), Duration::from_secs(60));
        assert_eq!(sweep_period(Duration::from_millis(1)), Duration::from_millis(50));
    }
}
