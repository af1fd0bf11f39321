//! Publishing a session's state without building a new snapshot per frame.
//!
//! The actor publishes the channel's state on a `watch` as an `Arc<Snapshot>` 20 times a second
//! while it runs. Building a new `Snapshot` each time (its names, G codes and block text as new
//! strings) and dropping the previous one was a quarter of a frame's cost. So the actor keeps the
//! snapshots it retired and, once nobody else holds one any more (the viewers have encoded it,
//! the REST replies are gone), refreshes it in place (`Channel::refresh_snapshot`) as the next
//! candidate. A candidate equal to the published state is not published and is kept for the
//! next time.

use std::sync::Arc;

use nctwin_engine::{Channel, Snapshot};
use tokio::sync::watch;

/// Retired snapshots kept for reuse. Two are enough when viewers keep up (one being encoded,
/// one free); a slow viewer may hold one a little longer.
const SPARES: usize = 3;

/// The actor's retired snapshots.
#[derive(Debug, Default)]
pub(super) struct SnapshotPool {
    spares: Vec<Arc<Snapshot>>,
}

impl SnapshotPool {
    /// Publishes the channel's state on `state` if it differs from the published one; true if
    /// it did.
    pub(super) fn publish(&mut self, channel: &Channel, state: &watch::Sender<Arc<Snapshot>>) -> bool {
        let next = self.refreshed(channel);
        let mut kept = Some(next);
        let changed = state.send_if_modified(|current| match kept.take() {
            Some(next) if *next != **current => {
                kept = Some(std::mem::replace(current, next));
                true
            }
            unused => {
                kept = unused;
                false
            }
        });
        if let Some(spare) = kept {
            self.keep(spare);
        }
        changed
    }

    /// The channel's state in a spare nobody else holds, else in a new snapshot.
    fn refreshed(&mut self, channel: &Channel) -> Arc<Snapshot> {
        if let Some(i) = self.spares.iter_mut().position(|s| Arc::get_mut(s).is_some()) {
            let mut spare = self.spares.swap_remove(i);
            if let Some(s) = Arc::get_mut(&mut spare) {
                channel.refresh_snapshot(s);
                return spare;
            }
        }
        Arc::new(channel.snapshot())
    }

    /// Keeps `spare` for reuse; the oldest spare goes when there are too many.
    fn keep(&mut self, spare: Arc<Snapshot>) {
        if self.spares.len() >= SPARES {
            self.spares.remove(0);
        }
        self.spares.push(spare);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stepped(channel: &mut Channel, cycles: usize) {
        for _ in 0..cycles {
            channel.step();
        }
    }

    #[test]
    fn published_states_equal_new_snapshots_and_spares_are_reused() {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let (state, mut viewer) = watch::channel(Arc::new(channel.snapshot()));
        let mut pool = SnapshotPool::default();
        channel.run_program("G1 X10 F600\nG2 X20 I5 J0\nG0 Z10\nM30").expect("program");
        let mut addresses = std::collections::HashSet::new();
        let mut frames = 0;
        while channel.is_busy() {
            stepped(&mut channel, 12);
            assert!(pool.publish(&channel, &state), "a running channel changes every frame");
            // The viewer takes the new state (and drops the one before, as the stream does).
            let seen = viewer.borrow_and_update().clone();
            assert_eq!(*seen, channel.snapshot(), "frame {frames}");
            addresses.insert(Arc::as_ptr(&seen) as usize);
            frames += 1;
        }
        assert!(frames > 50, "{frames} frames");
        // Three snapshots in turn at most: the initial one, and two refreshed alternately.
        assert!(addresses.len() <= 3, "{} distinct snapshots for {frames} frames", addresses.len());
    }

    #[test]
    fn an_unchanged_state_is_not_published_and_a_held_snapshot_is_not_overwritten() {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let (state, viewer) = watch::channel(Arc::new(channel.snapshot()));
        let mut pool = SnapshotPool::default();
        assert!(!pool.publish(&channel, &state), "idle: nothing changed");

        channel.run_program("G1 X10 F600\nM30").expect("program");
        let mut held = Vec::new();
        for _ in 0..6 {
            stepped(&mut channel, 5);
            assert!(pool.publish(&channel, &state));
            // A slow reader holds on to every state it saw: they must stay as they were.
            let s = viewer.borrow().clone();
            held.push((s.tick, s));
        }
        for (tick, s) in &held {
            assert_eq!(s.tick, *tick, "a held snapshot was written over");
        }
        assert_eq!(**viewer.borrow(), channel.snapshot());
    }
}
