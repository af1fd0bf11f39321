//! A jump searches the program text for its target: a backward jump (the GOTOB loop of many
//! hand-written programs) reads every block from the program start to the jump, on every
//! pass. The text never changes under a [`super::Flow`], so a search from the same place for
//! the same target always finds the same block: a [`JumpMemo`] keeps the last few answers.
//! Bounded: [`ENTRIES`] answers, the oldest replaced first.

use super::Pos;
use crate::lang::JumpTarget;

/// Answers kept: the jumps of a few nested GOTO loops.
pub(super) const ENTRIES: usize = 8;

/// One search: its target, direction, and where it started (forward: the jumping block;
/// backward: the block it must end before), and the block found.
#[derive(Debug, Clone)]
struct Entry {
    target: JumpTarget,
    backward: bool,
    from: usize,
    found: Option<Pos>,
}

/// The last searches' answers (see the module doc).
#[derive(Debug, Clone, Default)]
pub(super) struct JumpMemo {
    entries: Vec<Entry>,
    /// The entry to replace next when all are taken.
    oldest: usize,
}

impl JumpMemo {
    /// The answer of an earlier search, if there was one: `Some(found)`.
    pub fn get(&self, target: &JumpTarget, backward: bool, from: usize) -> Option<Option<Pos>> {
        let entry = self.entries.iter().find(|e| e.from == from && e.backward == backward && e.target == *target)?;
        Some(entry.found)
    }

    /// Keeps the answer of a search.
    pub fn put(&mut self, target: &JumpTarget, backward: bool, from: usize, found: Option<Pos>) {
        let entry = Entry { target: target.clone(), backward, from, found };
        if self.entries.len() < ENTRIES {
            self.entries.push(entry);
        } else {
            self.entries[self.oldest] = entry;
            self.oldest = (self.oldest + 1) % ENTRIES;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_answer_is_found_only_for_the_same_search_and_the_oldest_goes_first() {
        let mut memo = JumpMemo::default();
        let label = |s: &str| JumpTarget::Label(s.to_string());
        let at = |line: u32| Some(Pos { offset: line as usize * 10, line });
        memo.put(&label("START"), true, 500, at(3));
        memo.put(&JumpTarget::BlockNumber(20), false, 100, None);
        assert_eq!(memo.get(&label("START"), true, 500), Some(at(3)));
        assert_eq!(
            memo.get(&JumpTarget::BlockNumber(20), false, 100),
            Some(None),
            "a target not found is an answer too"
        );
        assert_eq!(memo.get(&label("START"), false, 500), None, "another direction");
        assert_eq!(memo.get(&label("START"), true, 510), None, "another place");
        assert_eq!(memo.get(&label("STAR"), true, 500), None, "another target");
        for i in 0..ENTRIES {
            memo.put(&label("L"), true, 1000 + i, at(i as u32));
        }
        assert_eq!(memo.get(&label("START"), true, 500), None, "the oldest answers went first");
        assert!((0..ENTRIES).all(|i| memo.get(&label("L"), true, 1000 + i) == Some(at(i as u32))));
    }
}
