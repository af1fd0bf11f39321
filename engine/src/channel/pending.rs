//! The prepared items waiting for the main run, each with the sequence number of the block that
//! prepared it.
//!
//! A line number alone does not name a block: a subprogram's line 1 follows a main program's
//! line 1, a one-line subprogram called with `P3` repeats its line. The main run shows the block
//! whose item it executes by this number (one integer per item, beside the item rather than in
//! it, so the `Item` enum and the interpreter stay as they are).
//!
//! Beside it, the line single block counts the item to: its own, or the line that names the
//! step of blocks SBLOF joins (`interp/calls/suppression.rs`).

use std::collections::VecDeque;

use crate::interp::Item;

/// Sequence number of an item whose block is not known by number (block search's collected
/// items, JOG and REPOS moves): the display finds such a block by its line.
pub(super) const NO_SEQ: u32 = 0;

/// The queue of prepared items and, in step with it, their blocks' sequence numbers.
#[derive(Debug, Clone, Default)]
pub(super) struct PendingItems {
    items: VecDeque<Item>,
    seqs: VecDeque<u32>,
    /// The single block step of each item (see the module doc).
    steps: VecDeque<u32>,
    /// The sequence number of the item [`PendingItems::pop_front`] took last, for
    /// [`PendingItems::push_front`].
    popped: u32,
    /// Its single block step.
    popped_step: u32,
}

impl PendingItems {
    /// Appends an item prepared for the block numbered `seq`, counted to single block step
    /// `step` when SBLOF joins its block to others (else to its own line).
    #[inline]
    pub fn push_back(&mut self, seq: u32, step: Option<u32>, item: Item) {
        self.steps.push_back(step.or(item.line()).unwrap_or(0));
        self.items.push_back(item);
        self.seqs.push_back(seq);
    }

    /// Puts the item taken last back at the front, with its sequence number.
    pub fn push_front(&mut self, item: Item) {
        self.items.push_front(item);
        self.seqs.push_front(self.popped);
        self.steps.push_front(self.popped_step);
    }

    /// Takes the front item (its block's number: [`PendingItems::popped_seq`]).
    #[inline]
    pub fn pop_front(&mut self) -> Option<Item> {
        let item = self.items.pop_front()?;
        self.popped = self.seqs.pop_front().unwrap_or(NO_SEQ);
        self.popped_step = self.steps.pop_front().unwrap_or(0);
        Some(item)
    }

    /// The single block step of the item [`PendingItems::pop_front`] took last.
    #[inline]
    pub fn popped_step(&self) -> u32 {
        self.popped_step
    }

    /// The single block step of the front item (see the module doc).
    #[inline]
    pub fn front_step(&self) -> Option<u32> {
        self.steps.front().copied()
    }

    /// The block sequence number of the item [`PendingItems::pop_front`] took last.
    #[inline]
    pub fn popped_seq(&self) -> u32 {
        self.popped
    }

    #[inline]
    pub fn front(&self) -> Option<&Item> {
        self.items.front()
    }

    #[inline]
    pub fn front_mut(&mut self) -> Option<&mut Item> {
        self.items.front_mut()
    }

    #[inline]
    pub fn len(&self) -> usize {
        self.items.len()
    }

    #[inline]
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub fn iter(&self) -> impl Iterator<Item = &Item> {
        self.items.iter()
    }

    pub fn remove(&mut self, i: usize) -> Option<Item> {
        self.seqs.remove(i);
        self.steps.remove(i);
        self.items.remove(i)
    }

    pub fn clear(&mut self) {
        self.items.clear();
        self.seqs.clear();
        self.steps.clear();
    }

    /// Keeps the items for which `keep` holds, each with its sequence number.
    pub fn retain(&mut self, mut keep: impl FnMut(&Item) -> bool) {
        let mut tags = std::mem::take(&mut self.seqs).into_iter().zip(std::mem::take(&mut self.steps));
        let (mut seqs, mut steps) = (VecDeque::with_capacity(self.items.len()), VecDeque::new());
        self.items.retain(|item| {
            let (seq, step) = tags.next().unwrap_or((NO_SEQ, 0));
            let keep = keep(item);
            if keep {
                seqs.push_back(seq);
                steps.push_back(step);
            }
            keep
        });
        (self.seqs, self.steps) = (seqs, steps);
    }
}

/// Items appended without a block number ([`NO_SEQ`]): block search's collected state.
impl Extend<Item> for PendingItems {
    fn extend<I: IntoIterator<Item = Item>>(&mut self, iter: I) {
        for item in iter {
            self.push_back(NO_SEQ, None, item);
        }
    }
}
