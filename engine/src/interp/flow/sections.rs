//! Program sections run out of their order: program section repetition (`REPEAT`, `REPEATB`)
//! and the section call `CALL BLOCK start TO end`. A section is a range of blocks of the
//! program level's text; the read position goes back to its start for each further run and,
//! after the last, on to where the program resumes. Sections nest (a repeated section may
//! repeat a part of itself), innermost last.

use super::{Flow, Pos};
use crate::lang::{Goto, GotoKind, JumpTarget};

/// Sections open at once on one program level, at most (nested repetitions).
pub const MAX_SECTIONS: usize = 16;

/// A section being run.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::interp) struct Section {
    /// The section's first block.
    pub start: Pos,
    /// The read position right after the section's last block: reaching it ends a run.
    pub after: Pos,
    /// Runs still to do after the current one.
    pub left: u32,
    /// Where the program goes on after the last run; `None` for a section of another program
    /// (`CALL "NAME" BLOCK ..`), whose program level ends with it.
    pub resume: Option<Pos>,
}

/// What reaching the end of a section's last run asks of the interpreter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::interp) enum SectionEnd {
    /// The program level of a section call ends: return to the caller.
    Return,
}

impl Flow {
    /// The block carrying `target`: searched towards the program start from the current block
    /// (`backward`) or towards its end, as a jump searches it.
    pub fn locate(&mut self, target: &JumpTarget, backward: bool) -> Option<Pos> {
        let kind = if backward { GotoKind::Backward } else { GotoKind::Forward };
        self.search(&Goto { kind, target: target.clone() }, backward)
    }

    /// The first block carrying `target` at or after `from` and before byte `until`.
    pub fn locate_from(&self, target: &JumpTarget, from: Pos, until: usize) -> Option<Pos> {
        let mut probe = Flow::at(self.text.clone(), from);
        while let Some((Ok(block), at)) = probe.read() {
            if at.offset >= until {
                return None;
            }
            let hit = match target {
                JumpTarget::Label(l) => block.label.as_deref() == Some(l.as_str()),
                JumpTarget::BlockNumber(n) => block.number == Some(*n),
                JumpTarget::Expr(_) | JumpTarget::ProgramStart => false,
            };
            if hit {
                return Some(at);
            }
            probe.recycle(block);
        }
        None
    }

    /// The read position after the block at `pos`.
    pub fn after(&self, pos: Pos) -> Pos {
        let mut probe = Flow::at(self.text.clone(), pos);
        probe.read();
        probe.next
    }

    /// Starts a section: its first run begins with the next block read.
    pub fn enter_section(&mut self, section: Section) -> bool {
        if self.sections.len() >= MAX_SECTIONS {
            return false;
        }
        self.next = section.start;
        self.sections.push(section);
        true
    }

    /// Called before each read: when the read position has reached the end of the innermost
    /// section, starts its next run or leaves it (for each section ending there).
    #[inline]
    pub fn pass_section_ends(&mut self) -> Option<SectionEnd> {
        while let Some(section) = self.sections.last_mut().filter(|s| s.after == self.next) {
            if section.left > 0 {
                section.left -= 1;
                self.next = section.start;
                return None;
            }
            let resume = section.resume;
            self.sections.pop();
            match resume {
                Some(at) => self.next = at,
                None => return Some(SectionEnd::Return),
            }
        }
        None
    }
}
