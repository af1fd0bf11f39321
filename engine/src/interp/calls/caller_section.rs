//! `CALL "START:END"` in a subprogram: runs the section from the block labelled START to the
//! block labelled END (both included; `N..` block numbers too) of the program that called the
//! subprogram, as a program level of its own, and returns after END. The standard cycles that
//! take a contour as a labelled section of the calling program (CYCLE95's NPP `"START:END"`)
//! read it so: on the control the contour lies in the part program, usually behind its M30.
//! A program name never holds a colon, so no stored program is shadowed. `CALL
//! "PROGRAM:START:END"` runs the section of the stored program PROGRAM instead.

use super::{Interpreter, Programs};
use crate::alarm::Alarm;
use crate::interp::flow::{Pos, Section};
use crate::lang::{JumpTarget, ProgramText};
use crate::programs::Dir;

/// The labels of a section name `"START:END"` (or `"PROGRAM:START:END"`, see
/// [`in_program`]); `None` for a program name.
pub(super) fn labels(name: &str) -> Option<(JumpTarget, JumpTarget)> {
    let name = in_program(name).map_or(name, |(_, section)| section);
    let (start, end) = name.split_once(':')?;
    let target = |t: &str| {
        let t = t.trim();
        match t.strip_prefix('N').and_then(|n| n.parse().ok()) {
            Some(n) => JumpTarget::BlockNumber(n),
            None => JumpTarget::Label(t.to_string()),
        }
    };
    Some((target(start), target(end)))
}

/// `"PROGRAM:START:END"`: the section START..END of the stored program PROGRAM (CYCLE62's
/// contour as a label pair in a subprogram), split into the program's name and `"START:END"`.
pub(super) fn in_program(name: &str) -> Option<(&str, &str)> {
    let (program, section) = name.split_once(':')?;
    section.contains(':').then_some((program.trim(), section))
}

impl Interpreter {
    /// The text and directory of the program that called the running subprogram (alarm 14011
    /// in the main program: it has no caller).
    pub(super) fn caller_text(
        &self,
        name: &str,
        programs: &Programs,
        line: u32,
    ) -> Result<(ProgramText, Option<Dir>), Alarm> {
        let frame = self.calls.last().ok_or_else(|| Alarm::program_not_found(line, name))?;
        let dir = match self.calls.len() {
            1 => programs.main_dir().cloned(),
            n => self.calls[n - 2].dir.clone(),
        };
        Ok((frame.caller.text.clone(), dir))
    }

    /// Positions the level just entered (on the caller's text) at the section `start`..`end`;
    /// its end returns to the subprogram (alarm 14080 for a label that is not there, at the
    /// line that called the cycle when a cycle of the cycle directories asks, as its own
    /// alarms are).
    pub(super) fn enter_caller_section(
        &mut self,
        start: &JumpTarget,
        end: &JumpTarget,
        line: u32,
    ) -> Result<(), Alarm> {
        let cycle = self.calls.iter().find(|f| matches!(f.dir, Some(Dir::Cst | Dir::Cma | Dir::Cus)));
        let line = cycle.and_then(|f| f.level.calls.last()).map_or(line, |(l, _)| *l);
        let name = |t: &JumpTarget| match t {
            JumpTarget::Label(l) => l.clone(),
            JumpTarget::BlockNumber(n) => format!("N{n}"),
            JumpTarget::Expr(_) | JumpTarget::ProgramStart => "(expression)".into(),
        };
        let flow = self.flow.as_mut().expect("the section's level was just entered");
        let first = flow
            .locate_from(start, Pos { offset: 0, line: 1 }, usize::MAX)
            .ok_or_else(|| Alarm::jump_not_found(line, &name(start)))?;
        let last = flow.locate_from(end, first, usize::MAX).ok_or_else(|| Alarm::jump_not_found(line, &name(end)))?;
        let section = Section { start: first, after: flow.after(last), left: 0, resume: None };
        if !flow.enter_section(section) {
            return Err(Alarm::nesting_too_deep(line, "too many nested program sections"));
        }
        Ok(())
    }
}
