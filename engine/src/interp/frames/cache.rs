//! The active frame `$P_ACTFRAME` is needed by every block, but changes only when a program or
//! a function writes a link of the frame chain, selects another settable frame, or the machine
//! data change. Building it chains ten links (most of them neutral) and builds the basic and the
//! settable frame from the stored data: the largest share of a plain block's preparation. This
//! keeps the last chain and rebuilds it only when one of its inputs changed.
//!
//! The interpreter's own links are [`Tracked`]: every mutable access marks them changed, so a
//! write cannot bypass the cache. The inputs from the machine data are compared by value.

use std::ops::{Deref, DerefMut};

use crate::interp::frames::frame::{Frame, GeoAxes};
use crate::machine_data::{FrameAngles, FrameData, MachineConfig};

/// A value that remembers whether it was borrowed mutably since the last [`Tracked::take_changed`].
#[derive(Debug, Default)]
pub(in crate::interp) struct Tracked<T> {
    value: T,
    changed: bool,
}

/// A copy counts as changed: it may be put back later (`x = saved`), after caches moved on.
impl<T: Clone> Clone for Tracked<T> {
    fn clone(&self) -> Self {
        Tracked { value: self.value.clone(), changed: true }
    }
}

impl<T> Tracked<T> {
    pub fn new(value: T) -> Tracked<T> {
        Tracked { value, changed: true }
    }

    /// Whether the value may have changed since the last call; clears the mark.
    pub fn take_changed(&mut self) -> bool {
        std::mem::take(&mut self.changed)
    }
}

impl<T> Deref for Tracked<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}

impl<T> DerefMut for Tracked<T> {
    fn deref_mut(&mut self) -> &mut T {
        self.changed = true;
        &mut self.value
    }
}

/// What the active frame was built from besides the tracked links.
#[derive(Debug, Clone, PartialEq)]
struct Key {
    work_offset: usize,
    rotary_slot: Option<usize>,
    geo_axes: GeoAxes,
    angles: FrameAngles,
    work_data: Option<FrameData>,
    base_frames: Vec<FrameData>,
    ncu_base_frames: Vec<FrameData>,
}

impl Key {
    fn matches(&self, cfg: &MachineConfig, work_offset: usize, rotary_slot: Option<usize>) -> bool {
        self.work_offset == work_offset
            && self.rotary_slot == rotary_slot
            && self.geo_axes == cfg.geo_axes
            && self.angles == cfg.frame_angles
            && self.work_data.as_ref() == cfg.work_offsets.get(work_offset)
            && self.base_frames == cfg.base_frames
            && self.ncu_base_frames == cfg.ncu_base_frames
    }

    fn of(cfg: &MachineConfig, work_offset: usize, rotary_slot: Option<usize>) -> Key {
        Key {
            work_offset,
            rotary_slot,
            geo_axes: cfg.geo_axes,
            angles: cfg.frame_angles,
            work_data: cfg.work_offsets.get(work_offset).cloned(),
            base_frames: cfg.base_frames.clone(),
            ncu_base_frames: cfg.ncu_base_frames.clone(),
        }
    }
}

/// The last active frame and what it was built from.
#[derive(Debug, Clone, Default)]
pub(in crate::interp) struct FrameCache {
    key: Option<Key>,
    frame: Frame,
}

impl FrameCache {
    /// The cached frame if `links_changed` is false and the machine data inputs are the same;
    /// otherwise `build`'s frame, kept for the next call.
    pub fn get(
        &mut self,
        cfg: &MachineConfig,
        work_offset: usize,
        rotary_slot: Option<usize>,
        links_changed: bool,
        build: impl FnOnce() -> Frame,
    ) -> &Frame {
        let same_key = self.key.as_ref().is_some_and(|k| k.matches(cfg, work_offset, rotary_slot));
        if links_changed || !same_key {
            self.frame = build();
            // A program that writes its frames (TRANS, AROT in a loop) leaves the machine data
            // alone: the key (copies of the frame data) is made again only when they changed.
            if !same_key {
                self.key = Some(Key::of(cfg, work_offset, rotary_slot));
            }
        } else if cfg!(debug_assertions) {
            // Every debug test run checks that no input of the chain escaped the key.
            let fresh = build();
            debug_assert!(fresh == self.frame, "stale active frame: cached {:?}, built {fresh:?}", self.frame);
        }
        &self.frame
    }
}

#[cfg(test)]
mod tests {
    use crate::interp::Tracked;

    #[test]
    fn every_write_and_every_copy_counts_as_a_change() {
        let mut t = Tracked::new(1.0);
        assert!(t.take_changed(), "a new value is unknown to every cache");
        assert!(!t.take_changed(), "taking the mark clears it");
        assert_eq!(*t + 1.0, 2.0);
        assert!(!t.take_changed(), "reading is no change");
        *t = 3.0;
        assert!(t.take_changed());
        let saved = t.clone();
        assert!(!t.take_changed());
        t = saved;
        assert!(t.take_changed(), "a copy put back must be looked at again");
        assert_eq!(*t, 3.0);
    }
}
