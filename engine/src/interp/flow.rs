//! Program flow: the read position in the program text, control structures (IF, WHILE, FOR,
//! REPEAT, LOOP, CASE) and jumps (GOTOF, GOTOB, GOTO, GOTOC).
//!
//! The program is never held as a list of blocks: blocks are parsed from the text as they are
//! reached, and jumps and skipped branches scan the text for their target. Memory stays
//! bounded for programs of any length.

mod block_cache;
mod jump_memo;
pub(super) mod jump_target;
mod sections;

use std::sync::Arc;

use crate::alarm::Alarm;
use crate::lang::{self, Block, Goto, GotoKind, JumpTarget, Lvalue, ProgramText, Stmt, Word};
pub(crate) use block_cache::ReadBlock;
use block_cache::{BlockCache, CachedBlock};
use jump_memo::JumpMemo;
pub(super) use sections::{Section, SectionEnd};

/// A position in the program text: byte offset of a line start and its 1-based line number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pos {
    pub offset: usize,
    pub line: u32,
}

/// An open control structure.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Ctrl {
    If { at: Pos },
    While { at: Pos },
    For { at: Pos, body: Pos, var: Lvalue, end: f64 },
    Repeat { at: Pos, body: Pos },
    Loop { at: Pos, body: Pos },
}

impl Ctrl {
    fn at(&self) -> Pos {
        match self {
            Ctrl::If { at }
            | Ctrl::While { at }
            | Ctrl::For { at, .. }
            | Ctrl::Repeat { at, .. }
            | Ctrl::Loop { at, .. } => *at,
        }
    }
}

/// `lang::read_block_reusing` or `lang::read_statement_block`.
type BlockReader = fn(&str, usize, u32, &mut Vec<Word>) -> Option<(Result<Block, lang::Diagnostic>, usize, u32)>;

/// The most control structures open at once (the control allows 16 levels per program level).
pub const MAX_NESTING: usize = 16;

/// The read position of one program level and its open control structures.
#[derive(Clone)]
pub(super) struct Flow {
    pub text: ProgramText,
    /// Next block to read.
    pub next: Pos,
    /// The block read last (the one being prepared).
    pub current: Pos,
    pub control: Vec<Ctrl>,
    /// Program sections being repeated or called (REPEAT, CALL BLOCK), innermost last.
    pub sections: Vec<Section>,
    /// The word list of a block done with (see [`Flow::recycle`]): the next block read is
    /// parsed into its allocation.
    spare: Vec<Word>,
    /// The furthest read position reached: a read before it reads a line again (a loop).
    furthest: usize,
    /// Blocks of lines read again, kept parsed for the next pass; made at the first such read.
    cache: Option<BlockCache>,
    /// The answers of the last jump searches; made at the first jump.
    jumps: Option<Box<JumpMemo>>,
    /// What the last run of a subprogram called from here learned of its text, for the next
    /// call of the same text (a cycle called at every position).
    callee: Option<Box<Learned>>,
    /// Where the PROC line of this subprogram text starts, once a call has bound its
    /// parameters there with only comment lines before it (a cycle's header): later calls of
    /// the same text start reading there, as those lines do nothing.
    pub proc_at: Option<Pos>,
}

/// A finished run's `furthest` and cache, with the text they belong to (kept alive with them,
/// so another text can never pass for it).
#[derive(Clone)]
struct Learned {
    text: ProgramText,
    furthest: usize,
    cache: Option<BlockCache>,
    jumps: Option<Box<JumpMemo>>,
    proc_at: Option<Pos>,
}

/// The state of the read, without what only saves work (`furthest`, the cache, the jump memo,
/// what a callee learned): the debug cross-check of the fast lane compares this, and the lane
/// reads lines past them.
impl std::fmt::Debug for Flow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Flow")
            .field("text", &self.text)
            .field("next", &self.next)
            .field("current", &self.current)
            .field("control", &self.control)
            .field("sections", &self.sections)
            .field("spare", &self.spare)
            .finish_non_exhaustive()
    }
}

impl Flow {
    /// A reader of `text` from its start; a text defining macros (`DEFINE .. AS`) is read
    /// with them replaced (`lang::macros`).
    pub fn new(text: ProgramText) -> Flow {
        let expanded = match lang::macros::expand(&text) {
            std::borrow::Cow::Owned(expanded) => Some(expanded),
            std::borrow::Cow::Borrowed(_) => None,
        };
        Flow::at(expanded.map_or(text, ProgramText::from), Pos { offset: 0, line: 1 })
    }

    /// A reader of `text` positioned at `pos`.
    fn at(text: ProgramText, pos: Pos) -> Flow {
        Flow {
            text,
            next: pos,
            current: pos,
            control: Vec::new(),
            sections: Vec::new(),
            spare: Vec::new(),
            furthest: 0,
            cache: None,
            jumps: None,
            callee: None,
            proc_at: None,
        }
    }

    /// A reader of the subprogram `text` called from `caller`: when the caller's last call ran
    /// the same text, its lines are known (read before, cached) from the start.
    pub fn for_call(text: ProgramText, caller: &mut Flow) -> Flow {
        let mut flow = Flow::new(text);
        if let Some(learned) = caller.callee.take().filter(|l| same_text(&l.text, &flow.text)) {
            (flow.furthest, flow.cache, flow.jumps) = (learned.furthest, learned.cache, learned.jumps);
            flow.start_at_proc(learned.proc_at);
        }
        flow
    }

    /// The next run of the same program (a call with repetitions), with what this run learned.
    pub fn rerun(self) -> Flow {
        let mut flow = Flow::new(self.text);
        (flow.furthest, flow.cache, flow.jumps) = (self.furthest, self.cache, self.jumps);
        flow.start_at_proc(self.proc_at);
        flow
    }

    /// Starts the read at the PROC line a run before learned (see [`Flow::proc_at`]).
    fn start_at_proc(&mut self, proc_at: Option<Pos>) {
        if let Some(at) = proc_at {
            (self.next, self.current, self.proc_at) = (at, at, Some(at));
        }
    }

    /// Hands what this finished subprogram run learned to the `caller` it returns to.
    pub fn return_to(self, caller: &mut Flow) {
        let Flow { text, furthest, cache, jumps, proc_at, .. } = self;
        caller.callee = Some(Box::new(Learned { text, furthest, cache, jumps, proc_at }));
    }

    /// Takes back a block that was read and is done with: a parsed block's word list serves
    /// the next block parsed.
    pub fn recycle(&mut self, block: ReadBlock) {
        match block {
            ReadBlock::Parsed(block) => self.recycle_parsed(*block),
            ReadBlock::Cached(_) => {}
        }
    }

    fn recycle_parsed(&mut self, block: Block) {
        let mut words = block.words;
        if words.capacity() > self.spare.capacity() {
            words.clear();
            self.spare = words;
        }
    }

    /// Reads the block at the read position; returns it with its own position. A line read a
    /// second time (a loop body) is kept parsed and later passes take it from the cache.
    pub fn read(&mut self) -> Option<(Result<ReadBlock, lang::Diagnostic>, Pos)> {
        let from = self.next;
        if let Some((block, next)) = self.cache.as_ref().and_then(|c| c.get(from)) {
            let read = ReadBlock::Cached(block);
            let at = Pos { offset: read.offset, line: read.line };
            (self.next, self.current) = (next, at);
            return Some((Ok(read), at));
        }
        let again = from.offset < self.furthest;
        let (block, at) = self.read_with(lang::read_block_reusing)?;
        Some((
            match block {
                Ok(block) if again => {
                    let block = Arc::new(CachedBlock::new(block));
                    let text = &self.text;
                    let cache = self.cache.get_or_insert_with(|| BlockCache::for_text(text));
                    cache.put(from, Arc::clone(&block), self.next);
                    Ok(ReadBlock::Cached(block))
                }
                other => other.map(|b| ReadBlock::Parsed(Box::new(b))),
            },
            at,
        ))
    }

    /// As [`Flow::read`], passing over lines that cannot hold a statement (skipped branches).
    /// Lines read again (a branch skipped on every pass of a loop) are read whole instead, so
    /// the cache keeps them and later passes skip them without the parser.
    fn read_statement(&mut self) -> Option<(Result<ReadBlock, lang::Diagnostic>, Pos)> {
        if self.next.offset < self.furthest {
            return self.read();
        }
        let (block, at) = self.read_with(lang::read_statement_block)?;
        Some((block.map(|b| ReadBlock::Parsed(Box::new(b))), at))
    }

    fn read_with(&mut self, reader: BlockReader) -> Option<(Result<Block, lang::Diagnostic>, Pos)> {
        let (block, offset, line) = reader(&self.text, self.next.offset, self.next.line, &mut self.spare)?;
        let at = match &block {
            Ok(b) => Pos { offset: b.offset, line: b.line },
            Err(d) => Pos { offset: self.next.offset, line: d.line },
        };
        self.next = Pos { offset, line };
        self.current = at;
        self.furthest = self.furthest.max(offset);
        Some((block, at))
    }

    /// Moves the read position forward past the block that closes the structure opened just
    /// before it. `stop` decides which statements at nesting depth 0 end the search; the
    /// statement found is returned (the read position is after it).
    pub fn skip(&mut self, from_line: u32, stop: impl Fn(&Stmt) -> bool) -> Result<Stmt, Alarm> {
        let mut depth = 0usize;
        // Only statements open, close or end the skipped part.
        loop {
            if let Some(found) = self.skip_cached(&mut depth, &stop) {
                match found {
                    Some(stmt) => return Ok(stmt),
                    None => continue,
                }
            }
            let Some((block, _)) = self.read_statement() else { break };
            let Ok(block) = block else { continue };
            let Some(stmt) = block.stmt.as_ref() else {
                self.recycle(block);
                continue;
            };
            let (found, opened, closed) = (depth == 0 && stop(stmt), opens(stmt), closes(stmt));
            if found {
                let stmt = match block {
                    ReadBlock::Parsed(mut block) => {
                        let stmt = block.stmt.take();
                        self.recycle_parsed(*block);
                        stmt
                    }
                    ReadBlock::Cached(_) => block.stmt.clone(),
                };
                return Ok(stmt.expect("looked at above"));
            }
            self.recycle(block);
            if opened {
                depth += 1;
            } else if closed {
                depth = depth.saturating_sub(1);
            }
        }
        Err(Alarm::nesting(from_line, "the structure is never closed"))
    }

    /// One step of [`Flow::skip`] over a line kept parsed (a branch skipped on every pass of a
    /// loop or call), looked at in the cache without taking a share of it: `None` if the line
    /// at the read position is not kept, else the statement found (`stop` at depth 0) or `None`.
    fn skip_cached(&mut self, depth: &mut usize, stop: &impl Fn(&Stmt) -> bool) -> Option<Option<Stmt>> {
        let (block, next) = self.cache.as_ref()?.peek(self.next)?;
        let at = Pos { offset: block.offset, line: block.line };
        let found = match block.stmt.as_ref() {
            Some(stmt) if *depth == 0 && stop(stmt) => Some(stmt.clone()),
            Some(stmt) if opens(stmt) => {
                *depth += 1;
                None
            }
            Some(stmt) if closes(stmt) => {
                *depth = depth.saturating_sub(1);
                None
            }
            _ => None,
        };
        (self.next, self.current) = (next, at);
        Some(found)
    }

    /// Pushes a control structure, checking the nesting depth.
    pub fn open(&mut self, ctrl: Ctrl, line: u32) -> Result<(), Alarm> {
        if self.control.len() >= MAX_NESTING {
            return Err(Alarm::nesting_too_deep(line, &format!("more than {MAX_NESTING} levels")));
        }
        self.control.push(ctrl);
        Ok(())
    }

    /// Executes a jump from the block at `from`. Returns false for a GOTOC whose target does
    /// not exist (the program goes on with the next block).
    pub fn jump(&mut self, goto: &Goto) -> Result<bool, Alarm> {
        let from = self.current;
        let found = match goto.kind {
            _ if goto.target == JumpTarget::ProgramStart => Some(Pos { offset: 0, line: 1 }),
            GotoKind::Forward => self.search(goto, false),
            GotoKind::Backward => self.search(goto, true),
            GotoKind::Both | GotoKind::Continue | GotoKind::Start => {
                self.search(goto, false).or_else(|| self.search(goto, true))
            }
        };
        let Some(target) = found else {
            if goto.kind == GotoKind::Continue {
                return Ok(false);
            }
            let name = match &goto.target {
                JumpTarget::Label(l) => l.clone(),
                JumpTarget::BlockNumber(n) => format!("N{n}"),
                JumpTarget::Expr(_) | JumpTarget::ProgramStart => "(expression)".into(),
            };
            return Err(Alarm::jump_not_found(from.line, &name));
        };
        // Structures the jump leaves are closed: those opened after the target (backward
        // jumps) and those whose end lies before the target (forward jumps).
        self.control.retain(|c| c.at().offset < target.offset);
        while let Some(c) = self.control.last() {
            let mut probe = Flow::at(self.text.clone(), c.at());
            probe.read();
            let closer = probe.skip(from.line, closes);
            if closer.is_ok() && probe.next.offset <= target.offset {
                self.control.pop();
            } else {
                break;
            }
        }
        self.next = target;
        Ok(true)
    }

    /// [`Flow::find`] from the jumping block (forward) or the program start (backward), answered
    /// from the memo when the same search ran before.
    fn search(&mut self, goto: &Goto, backward: bool) -> Option<Pos> {
        // A backward search ends before the jumping block: that is where it depends on.
        let from = self.current.offset;
        if let Some(found) = self.jumps.as_ref().and_then(|m| m.get(&goto.target, backward, from)) {
            return found;
        }
        let start = if backward { Pos { offset: 0, line: 1 } } else { self.current };
        let found = self.find(goto, start, backward);
        self.jumps.get_or_insert_default().put(&goto.target, backward, from, found);
        found
    }

    /// The block carrying the jump target: searching forward, the first one after `from`;
    /// searching backward (`from` = program start), the last one before the jumping block
    /// `self.jumping`. The target block itself is executed (a label may share its block).
    fn find(&self, goto: &Goto, from: Pos, backward: bool) -> Option<Pos> {
        let end = self.current.offset;
        let mut probe = Flow::at(self.text.clone(), from);
        if !backward {
            // A forward search starts after the jumping block.
            probe.read();
        }
        let last = backward;
        let mut found = None;
        while let Some((Ok(block), at)) = probe.read() {
            if backward && at.offset >= end {
                break;
            }
            let hit = match &goto.target {
                JumpTarget::Label(l) => block.label.as_deref() == Some(l.as_str()),
                JumpTarget::BlockNumber(n) => block.number == Some(*n),
                JumpTarget::Expr(_) | JumpTarget::ProgramStart => false,
            };
            probe.recycle(block);
            if hit {
                found = Some(at);
                if !last {
                    break;
                }
            }
        }
        found
    }
}

/// Whether both read the same bytes in memory. Each call wraps the stored program anew, so the
/// wrappers differ; the bytes do not. `Learned` keeps its text alive, so no other text can
/// have been put at its address.
fn same_text(a: &ProgramText, b: &ProgramText) -> bool {
    std::ptr::eq(a.as_ptr(), b.as_ptr()) && a.len() == b.len()
}

/// Statements that open a structure closed by a later statement.
pub(super) fn opens(s: &Stmt) -> bool {
    matches!(s, Stmt::If { goto: None, .. } | Stmt::While(_) | Stmt::For { .. } | Stmt::Repeat | Stmt::Loop)
}

pub(super) fn closes(s: &Stmt) -> bool {
    matches!(s, Stmt::EndIf | Stmt::EndWhile | Stmt::EndFor | Stmt::Until(_) | Stmt::EndLoop)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads blocks from `from` until (and with) the block at line `last`.
    fn pass(flow: &mut Flow, from: Pos, last: u32) -> Vec<(ReadBlock, Pos, Pos)> {
        flow.next = from;
        let mut out = Vec::new();
        loop {
            let (block, at) = flow.read().expect("a block");
            let block = block.expect("no syntax error");
            let done = block.line == last;
            out.push((block, at, flow.next));
            if done {
                return out;
            }
        }
    }

    /// The start of 1-based line `n` of `text`, worked out by counting line breaks.
    fn line_start(text: &str, n: u32) -> Pos {
        let offset = text.split_inclusive('\n').take(n as usize - 1).map(str::len).sum();
        Pos { offset, line: n }
    }

    #[test]
    fn a_loop_body_read_again_is_the_parse_of_its_text_and_parsed_only_once() {
        let text = "R1=0\nWHILE R1<3\n  R2=R1*2+SIN(30) ; half\n\n  X=R2 Y10\nENDWHILE\nM30\n";
        let expected = lang::parse(text).blocks;
        let mut flow = Flow::new(ProgramText::from_owner(text.to_string()));
        let first = pass(&mut flow, Pos { offset: 0, line: 1 }, 6);
        let while_at = line_start(text, 2);
        let second = pass(&mut flow, while_at, 6);
        let third = pass(&mut flow, while_at, 6);
        // The first pass reads new text; the loop's next passes read it again.
        assert!(first.iter().all(|(b, ..)| matches!(b, ReadBlock::Parsed(_))));
        assert!(second.iter().chain(&third).all(|(b, ..)| matches!(b, ReadBlock::Cached(_))));
        for run in [&first[1..], &second[..], &third[..]] {
            let blocks: Vec<&Block> = run.iter().map(|(b, ..)| &**b).collect();
            assert_eq!(blocks, expected[1..5].iter().collect::<Vec<_>>());
            // Each block stands where its line starts; the empty line 4 is passed over.
            let starts: Vec<Pos> = run.iter().map(|(_, at, _)| *at).collect();
            assert_eq!(starts, [2, 3, 5, 6].map(|n| line_start(text, n)));
            assert_eq!(run.last().map(|(.., next)| *next), Some(line_start(text, 7)));
        }
        // The third pass takes the second pass's blocks: the same allocations, no new parse.
        for ((b2, ..), (b3, ..)) in second.iter().zip(&third) {
            let (ReadBlock::Cached(b2), ReadBlock::Cached(b3)) = (b2, b3) else { unreachable!("checked above") };
            assert!(Arc::ptr_eq(b2, b3));
        }
    }

    #[test]
    fn a_branch_skipped_on_every_pass_stops_at_its_own_else() {
        let text =
            "WHILE R1<2\nIF R1>5\n  IF R2>1\n    R3=1\n  ELSE\n    R3=2\n  ENDIF\nELSE\n  R3=3\nENDIF\nENDWHILE\n";
        let mut flow = Flow::new(ProgramText::from_owner(text.to_string()));
        for _ in 0..4 {
            // WHILE, then the IF whose condition is false: skip to its ELSE (line 8), not to
            // the nested IF's ELSE (line 5).
            pass(&mut flow, Pos { offset: 0, line: 1 }, 2);
            let found = flow.skip(2, |s| matches!(s, Stmt::Else | Stmt::EndIf)).expect("closed");
            assert_eq!(found, Stmt::Else);
            assert_eq!(flow.next, line_start(text, 9));
            assert_eq!(flow.current, line_start(text, 8));
        }
        assert!(flow.cache.is_some(), "the passes after the first read the branch again");
    }

    #[test]
    fn a_body_longer_than_the_cache_still_reads_every_line_right() {
        let lines = 2 * block_cache::MAX_SLOTS + 7;
        let mut text = String::from("LOOP\n");
        for i in 0..lines {
            text.push_str(&format!("R{}=R{}+{i}\n", i % 90, (i + 1) % 90));
        }
        text.push_str("ENDLOOP\n");
        let expected = lang::parse(&text).blocks;
        let last = lines as u32 + 2;
        let mut flow = Flow::new(ProgramText::from_owner(text.clone()));
        for _ in 0..3 {
            let run = pass(&mut flow, line_start(&text, 2), last);
            assert_eq!(run.len(), lines + 1);
            assert!(run.iter().zip(&expected[1..]).all(|((b, ..), e)| **b == *e));
        }
    }

    #[test]
    fn a_subprogram_called_again_reads_its_blocks_from_the_last_runs_cache() {
        // As `Interpreter::call` does: the stored program wrapped anew at every call.
        let stored: Arc<str> = Arc::from("PROC CYC\nR1=R1+1\nG1 X=R1\nM17\n");
        let mut caller = Flow::new(ProgramText::from_owner("CYC\nCYC\nCYC\nM30\n".to_string()));
        let run = |callee: &mut Flow| -> Vec<ReadBlock> {
            std::iter::from_fn(|| callee.read().map(|(b, _)| b.expect("no syntax error"))).collect()
        };
        let mut kinds = Vec::new();
        for _ in 0..3 {
            let mut callee = Flow::for_call(ProgramText::from(Arc::clone(&stored)), &mut caller);
            let blocks = run(&mut callee);
            assert_eq!(blocks.iter().map(|b| b.line).collect::<Vec<_>>(), [1, 2, 3, 4]);
            kinds.push(blocks.iter().all(|b| matches!(b, ReadBlock::Cached(_))));
            callee.return_to(&mut caller);
        }
        // The first call reads new text, the second fills the cache, the third uses it.
        assert_eq!(kinds, [false, true, true]);
        // The same lines in another text (a program loaded anew) are parsed from that text.
        let reloaded = ProgramText::from_owner("PROC CYC\nR1=R1+1\nG1 X=R1\nM17\n".to_string());
        let mut callee = Flow::for_call(reloaded, &mut caller);
        assert!(run(&mut callee).iter().all(|b| matches!(b, ReadBlock::Parsed(_))));
        // A repeated call (`CYC P3`) reruns with what its last run learned.
        let mut again = callee.rerun();
        assert!(run(&mut again).iter().all(|b| matches!(b, ReadBlock::Cached(_))));
    }

    #[test]
    fn a_subprogram_called_again_starts_at_its_proc_line() {
        // A cycle's header: two comment lines (9 and 7 bytes) before the PROC line.
        let stored: Arc<str> = Arc::from("; header\n; more\nPROC CYC\nM17\n");
        let mut caller = Flow::new(ProgramText::from_owner("CYC\nCYC\nM30\n".to_string()));
        let mut first = Flow::for_call(ProgramText::from(Arc::clone(&stored)), &mut caller);
        assert_eq!(first.next, Pos { offset: 0, line: 1 });
        // What `step_program` notes when the PROC line binds the call.
        first.proc_at = Some(Pos { offset: 16, line: 3 });
        first.return_to(&mut caller);
        let mut second = Flow::for_call(ProgramText::from(Arc::clone(&stored)), &mut caller);
        assert_eq!(second.next, Pos { offset: 16, line: 3 });
        let (block, at) = second.read().expect("the PROC line");
        assert!(matches!(block.expect("no syntax error").stmt, Some(Stmt::Proc { .. })));
        assert_eq!(at.line, 3);
        // A repetition (`CYC P2`) starts there too; another text from its start.
        assert_eq!(second.rerun().next.line, 3);
        let other = ProgramText::from_owner("; header\n; more\nPROC CYC\nM17\n".to_string());
        assert_eq!(Flow::for_call(other, &mut caller).next.line, 1);
    }

    #[test]
    fn a_jump_made_again_lands_where_the_first_search_found_its_target() {
        let text = "R1=0\nN10 R2=1\nSTART: R1=R1+1\nG1 X=R1\nIF R1<3 GOTOB START\nGOTOF N10\nGOTOC NOWHERE\nM30\n";
        let mut flow = Flow::new(ProgramText::from_owner(text.to_string()));
        let goto = |kind, target| Goto { kind, target };
        let back = goto(GotoKind::Backward, JumpTarget::Label("START".into()));
        for _ in 0..3 {
            pass(&mut flow, line_start(text, 3), 5);
            assert_eq!(flow.jump(&back), Ok(true));
            assert_eq!(flow.next, line_start(text, 3), "the label's block runs again");
        }
        // N10 lies behind GOTOF: not found, every time (alarm 14080).
        for _ in 0..2 {
            pass(&mut flow, line_start(text, 6), 6);
            assert!(flow.jump(&goto(GotoKind::Forward, JumpTarget::BlockNumber(10))).is_err());
        }
        // GOTOC to a missing label goes on with the next block, every time.
        for _ in 0..2 {
            pass(&mut flow, line_start(text, 7), 7);
            assert_eq!(flow.jump(&goto(GotoKind::Continue, JumpTarget::Label("NOWHERE".into()))), Ok(false));
            assert_eq!(flow.next, line_start(text, 8));
        }
        // GOTO (forward, then backward) from line 6 finds N10 behind it.
        for _ in 0..2 {
            pass(&mut flow, line_start(text, 6), 6);
            assert_eq!(flow.jump(&goto(GotoKind::Both, JumpTarget::BlockNumber(10))), Ok(true));
            assert_eq!(flow.next, line_start(text, 2));
        }
    }
}
