//! Loop bodies are read again on every pass (WHILE, FOR, REPEAT, LOOP, a backward GOTO), and
//! parsing a line costs more than most of what preparing it does. A [`BlockCache`] keeps the
//! parsed blocks of lines read a second time, so later passes take them without the parser.
//!
//! Memory stays flat in the program's length: a bounded number of slots, one per line number
//! modulo their count (the consecutive lines of a body up to that many lines long never evict
//! each other; a longer one only loses the cache's benefit). A text of up to [`MAX_SLOTS`]
//! lines gets a slot for each of its lines ([`BlockCache::for_text`]): a cycle called at every
//! position keeps its whole body parsed, its last lines never evicting its first. A cache
//! belongs to one [`super::Flow`], whose program text never changes, so an entry never goes
//! stale.

use std::ops::Deref;
use std::sync::{Arc, OnceLock};

use super::Pos;
use crate::lang::Block;

/// The fewest slots of a cache: lines of a loop body kept parsed.
pub(super) const SLOTS: usize = 128;
/// The most slots of a cache (a text longer than this shares slots between its lines).
pub(super) const MAX_SLOTS: usize = 1024;

/// A block read from the program: parsed just now (its own to change and recycle), or shared
/// with the cache. A parsed block is boxed: the read is handed on by value three or four times
/// before the block runs, and a whole `Block` copied each time cost more than the box's
/// allocation (a cycle's body, read from the cache at every call, paid the copies of the big
/// variant for a pointer).
#[derive(Debug)]
pub(crate) enum ReadBlock {
    Parsed(Box<Block>),
    Cached(Arc<CachedBlock>),
}

/// A kept block and what preparation asks of every block before it runs, worked out at the
/// first pass that asks (both depend on the block's text only).
#[derive(Debug)]
pub(crate) struct CachedBlock {
    block: Block,
    effect_calls: OnceLock<bool>,
    reads_main_run: OnceLock<bool>,
}

impl CachedBlock {
    pub fn new(block: Block) -> CachedBlock {
        CachedBlock { block, effect_calls: OnceLock::new(), reads_main_run: OnceLock::new() }
    }
}

impl Deref for ReadBlock {
    type Target = Block;
    fn deref(&self) -> &Block {
        match self {
            ReadBlock::Parsed(b) => b,
            ReadBlock::Cached(b) => &b.block,
        }
    }
}

impl ReadBlock {
    /// The block to change (DELOBJ/CORRTRAFO put their results in): a cached block is copied
    /// first, so the cache keeps the text's block.
    pub fn to_mut(&mut self) -> &mut Block {
        if let ReadBlock::Cached(shared) = self {
            *self = ReadBlock::Parsed(Box::new(shared.block.clone()));
        }
        match self {
            ReadBlock::Parsed(b) => b,
            ReadBlock::Cached(_) => unreachable!("copied above"),
        }
    }

    /// `effects::present`: the block calls DELOBJ or CORRTRAFO.
    pub fn has_effect_calls(&self) -> bool {
        let find = crate::interp::calls::effects::present;
        match self {
            ReadBlock::Parsed(b) => find(b),
            ReadBlock::Cached(c) => *c.effect_calls.get_or_init(|| find(&c.block)),
        }
    }

    /// `statements::reads_main_run`: the block waits for the main run before it is prepared.
    pub fn reads_main_run(&self) -> bool {
        let find = crate::interp::statements::reads_main_run;
        match self {
            ReadBlock::Parsed(b) => find(b),
            ReadBlock::Cached(c) => *c.reads_main_run.get_or_init(|| find(&c.block)),
        }
    }
}

/// One kept read: the block found reading from `from`, and the read position after it.
#[derive(Debug, Clone)]
struct Entry {
    from: usize,
    block: Arc<CachedBlock>,
    next: Pos,
}

/// Parsed blocks by the position their read started at (see the module doc).
#[derive(Debug, Clone)]
pub(super) struct BlockCache {
    slots: Box<[Option<Entry>]>,
}

impl Default for BlockCache {
    fn default() -> Self {
        BlockCache { slots: vec![None; SLOTS].into_boxed_slice() }
    }
}

impl BlockCache {
    /// A cache with a slot for every line of `text` (at least [`SLOTS`], at most
    /// [`MAX_SLOTS`]). Counting stops at the cap, so a long program costs no more than a
    /// short one.
    pub fn for_text(text: &str) -> BlockCache {
        let lines = text.bytes().filter(|&b| b == b'\n').take(MAX_SLOTS).count() + 1;
        BlockCache { slots: vec![None; lines.clamp(SLOTS, MAX_SLOTS)].into_boxed_slice() }
    }

    fn slot(&self, from: Pos) -> usize {
        from.line as usize % self.slots.len()
    }

    /// The block a read from `from` found before, and the read position after it.
    pub fn get(&self, from: Pos) -> Option<(Arc<CachedBlock>, Pos)> {
        let entry = self.slots[self.slot(from)].as_ref().filter(|e| e.from == from.offset)?;
        Some((Arc::clone(&entry.block), entry.next))
    }

    /// As [`BlockCache::get`], lending the block instead of sharing it: a skipped line is only
    /// looked at.
    pub fn peek(&self, from: Pos) -> Option<(&Block, Pos)> {
        let entry = self.slots[self.slot(from)].as_ref().filter(|e| e.from == from.offset)?;
        Some((&entry.block.block, entry.next))
    }

    /// Keeps the block a read from `from` found (replacing the slot's older line).
    pub fn put(&mut self, from: Pos, block: Arc<CachedBlock>, next: Pos) {
        let slot = self.slot(from);
        self.slots[slot] = Some(Entry { from: from.offset, block, next });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lang::parse_block;

    fn block(text: &str, line: u32, offset: usize) -> Arc<CachedBlock> {
        Arc::new(CachedBlock::new(parse_block(text, line, offset).expect("valid").expect("not empty")))
    }

    #[test]
    fn a_read_is_found_only_from_the_same_position() {
        let mut cache = BlockCache::default();
        let from = Pos { offset: 40, line: 3 };
        let next = Pos { offset: 52, line: 4 };
        cache.put(from, block("R1=R1+1", 3, 40), next);
        let (found, after) = cache.get(from).expect("kept");
        assert_eq!((found.block.line, found.block.offset, after), (3, 40, next));
        // Same slot (line + SLOTS), other text position: a different line, not this block.
        let other = Pos { offset: 4000, line: 3 + SLOTS as u32 };
        assert!(cache.get(other).is_none());
        // It replaces the slot's entry.
        cache.put(other, block("R2=1", other.line, other.offset), Pos { offset: 4005, line: other.line + 1 });
        assert!(cache.get(from).is_none());
        assert_eq!(cache.get(other).map(|(b, _)| b.block.line), Some(3 + SLOTS as u32));
    }

    #[test]
    fn a_body_of_slots_lines_keeps_every_line() {
        let mut cache = BlockCache::default();
        let pos = |i: u32| Pos { offset: 10 * i as usize, line: 100 + i };
        for i in 0..SLOTS as u32 {
            cache.put(pos(i), block("G1 X1", pos(i).line, pos(i).offset), pos(i + 1));
        }
        assert!(
            (0..SLOTS as u32)
                .all(|i| cache.get(pos(i)).is_some_and(|(b, n)| b.block.line == 100 + i && n == pos(i + 1)))
        );
    }

    #[test]
    fn a_text_gets_a_slot_for_each_of_its_lines_within_the_bounds() {
        // 200 lines (199 line breaks and a last line): 200 slots; 10 lines: the least, 128;
        // 5000 lines: the most, 1024.
        let text = |lines: usize| "R1=1\n".repeat(lines - 1) + "M17";
        for (lines, slots) in [(200, 200), (10, SLOTS), (5000, MAX_SLOTS)] {
            assert_eq!(BlockCache::for_text(&text(lines)).slots.len(), slots, "{lines} lines");
        }
        // Lines 1 and 129 of a 200-line text keep their own slots.
        let mut cache = BlockCache::for_text(&text(200));
        let (first, far) = (Pos { offset: 0, line: 1 }, Pos { offset: 640, line: 129 });
        cache.put(first, block("R1=1", 1, 0), Pos { offset: 5, line: 2 });
        cache.put(far, block("R1=1", 129, 640), Pos { offset: 645, line: 130 });
        assert!(cache.get(first).is_some() && cache.get(far).is_some());
    }

    #[test]
    fn changing_a_cached_block_leaves_the_cache_alone() {
        let shared = block("X10 Y20", 1, 0);
        let mut read = ReadBlock::Cached(Arc::clone(&shared));
        read.to_mut().words.clear();
        assert!(read.words.is_empty());
        assert_eq!(shared.block.words.len(), 2, "the cached block still holds the line's words");
    }

    #[test]
    fn what_is_asked_of_a_cached_block_is_what_its_text_says() {
        // SPOS reads where the spindle stands in the main run; DELOBJ as a function has effects.
        for (text, effects, main_run) in
            [("X10", false, false), ("SPOS=90", false, true), ("R1=DELOBJ(\"K\") X=$AA_IM[X]", true, true)]
        {
            let parsed = ReadBlock::Parsed(Box::new(parse_block(text, 1, 0).expect("valid").expect("not empty")));
            let cached = ReadBlock::Cached(block(text, 1, 0));
            for read in [&parsed, &cached, &cached] {
                assert_eq!((read.has_effect_calls(), read.reads_main_run()), (effects, main_run), "{text}");
            }
        }
    }
}
