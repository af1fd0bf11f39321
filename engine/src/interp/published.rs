//! The offsets handed out with prepared items, shared while they stay the same.
//!
//! Items carry their block's offsets as a shared pointer: consecutive blocks mostly have the
//! same offsets, and the main run compares pointers before values. The displayed G codes are
//! part of the offsets, so a pocket of G1 lines and G3 arcs changes them every other block.
//! Keeping the offsets published before the current ones as well turns that alternation into a
//! swap of two pointers instead of a new allocation per block.

use super::{Offsets, SharedOffsets};

/// The offsets last handed out, and the ones before them.
#[derive(Debug, Clone, Default)]
pub(super) struct Published {
    current: SharedOffsets,
    previous: SharedOffsets,
    /// How often `current` has changed: a block compares the count before and after itself to
    /// tell whether its offsets changed, instead of holding a copy of the shared pointer (each
    /// copy and drop of it is an atomic operation, a good part of a plain block's time).
    changes: u64,
}

impl Published {
    /// The offsets to hand out now.
    pub(super) fn current(&self) -> &SharedOffsets {
        &self.current
    }

    /// How often the current offsets have changed so far.
    pub(super) fn changes(&self) -> u64 {
        self.changes
    }

    /// Makes `offsets` the current ones: unchanged if they are equal to the current ones, the
    /// previous ones again if equal to those, else a new shared copy.
    pub(super) fn publish(&mut self, offsets: &Offsets) {
        if *self.current == *offsets {
            return;
        }
        if *self.previous == *offsets {
            std::mem::swap(&mut self.current, &mut self.previous);
        } else {
            self.previous = std::mem::replace(&mut self.current, SharedOffsets::new(offsets.clone()));
        }
        self.changes += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_gcodes(motion: &str) -> Offsets {
        let cfg = crate::Channel::from_preset("mill-3axis", "").unwrap().config().clone();
        let mut modal = crate::interp::Modal::reset(&cfg);
        modal.motion = match motion {
            "G1" => crate::interp::MotionMode::Linear,
            _ => crate::interp::MotionMode::Ccw,
        };
        Offsets { gcodes: crate::interp::gcodes::GCodes::of(&modal), ..Offsets::default() }
    }

    #[test]
    fn alternating_offsets_reuse_the_two_shared_copies() {
        let (g1, g3) = (with_gcodes("G1"), with_gcodes("G3"));
        assert_ne!(g1, g3);
        let mut published = Published::default();
        published.publish(&g1);
        assert_eq!(published.changes(), 1);
        let first_g1 = published.current().clone();
        published.publish(&g3);
        let first_g3 = published.current().clone();
        assert!(!SharedOffsets::ptr_eq(&first_g1, &first_g3));
        assert_eq!(*first_g3, g3);
        for _ in 0..3 {
            published.publish(&g1);
            assert!(SharedOffsets::ptr_eq(published.current(), &first_g1));
            let changes = published.changes();
            published.publish(&g1);
            assert!(SharedOffsets::ptr_eq(published.current(), &first_g1));
            assert_eq!(published.changes(), changes, "no change, no count");
            published.publish(&g3);
            assert!(SharedOffsets::ptr_eq(published.current(), &first_g3));
        }
        // A third value is new; the one before it stays at hand.
        let other = Offsets { t: 7, ..g1.clone() };
        published.publish(&other);
        assert_eq!(**published.current(), other);
        published.publish(&g3);
        assert!(SharedOffsets::ptr_eq(published.current(), &first_g3));
        published.publish(&g1);
        assert!(!SharedOffsets::ptr_eq(published.current(), &first_g1));
        assert_eq!(**published.current(), g1);
    }
}
