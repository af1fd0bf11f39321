//! Loop bodies are read again on every pass (WHILE, FOR, REPEAT, LOOP, a backward GOTO), and
//! parsing a line costs more than most of what preparing it does. A [`BlockCache`] keeps the
//! parsed blocks of lines read a second time, so later passes take them without the parser.
//!
//! Memory stays flat in the program's length: a fixed number of slots, one per line number
//! modulo [`SLOTS`] (the consecutive lines of a body up to [`SLOTS`] lines long never evict
//! each other; a longer one only loses the cache's benefit). A cache belongs to one
//! [`super::Flow`], whose program text never changes, so an entry never goes stale.

use std::ops::Deref;
use std::sync::{Arc, OnceLock};

use super::Pos;
use crate::lang::Block;

/// Slots of a cache: lines of a loop body kept parsed.
pub(super) const SLOTS: usize = 128;

/// A block read from the program: parsed just now (its own to change and recycle), or shared
/// with the cache. A parsed block stays unboxed: a box would cost an allocation per block read
/// on the way of every line that is read once.
#[derive(Debug)]
#[allow(clippy::large_enum_variant)]
pub(crate) enum ReadBlock {
    Parsed(Block),
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
            *self = ReadBlock::Parsed(shared.block.clone());
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
    fn slot(from: Pos) -> usize {
        from.line as usize % SLOTS
    }

    /// The block a read from `from` found before, and the read position after it.
    pub fn get(&self, from: Pos) -> Option<(Arc<CachedBlock>, Pos)> {
        let entry = self.slots[Self::slot(from)].as_ref().filter(|e| e.from == from.offset)?;
        Some((Arc::clone(&entry.block), entry.next))
    }

    /// Keeps the block a read from `from` found (replacing the slot's older line).
    pub fn put(&mut self, from: Pos, block: Arc<CachedBlock>, next: Pos) {
        self.slots[Self::slot(from)] = Some(Entry { from: from.offset, block, next });
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
            let parsed = ReadBlock::Parsed(parse_block(text, 1, 0).expect("valid").expect("not empty"));
            let cached = ReadBlock::Cached(block(text, 1, 0));
            for read in [&parsed, &cached, &cached] {
                assert_eq!((read.has_effect_calls(), read.reads_main_run()), (effects, main_run), "{text}");
            }
        }
    }
}
