//! Program section repetition and section calls on the interpreter: `REPEAT START P=n`,
//! `REPEAT START END P=n`, `REPEAT START P=n` with an `ENDLABEL:`, `REPEATB LABEL P=n` and
//! `CALL [NAME] BLOCK START TO END` find their blocks and hand the section to the program
//! level's flow (`flow/sections.rs`), which runs it.
//!
//! The rules (Programming Manual Job Planning, program section repetition):
//! - `REPEATB LABEL P=n`: the block carrying LABEL (searched towards the program start, then
//!   towards its end) runs n times, then the program goes on after the REPEATB.
//! - `REPEAT START P=n`: START is searched towards the program start; the section runs from
//!   START to the block before the REPEAT, or to the first block labelled `ENDLABEL` between
//!   them. A START after the REPEAT needs an `ENDLABEL` after it: the section ends there.
//! - `REPEAT START END P=n`: START is searched towards the start, then the end; END from START
//!   on. The section runs from START to END, both included.
//! - Without `P` a section runs once. After the last run the program goes on after the REPEAT.
//! - `CALL BLOCK START TO END` runs the section START..END of the current program once and goes
//!   on after the CALL; `CALL "NAME" BLOCK START TO END` runs that section of program NAME as
//!   a subprogram (a program level of its own, without its PROC line's parameters).

use super::{Interpreter, Programs};
use crate::alarm::Alarm;
use crate::interp::eval::eval_f64;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::flow::{Pos, Section};
use crate::lang::{Expr, JumpTarget};
use crate::machine_data::MachineConfig;

/// The label that ends a repeated section started by `REPEAT START P=n`.
const ENDLABEL: &str = "ENDLABEL";

impl Interpreter {
    /// `REPEAT START [END] P=n` (`single`: `REPEATB LABEL P=n`) in the block at `line`.
    pub(in crate::interp) fn repeat_section(
        &mut self,
        start: &JumpTarget,
        end: Option<&JumpTarget>,
        count: Option<&Expr>,
        single: bool,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let runs = match count {
            None => 1.0,
            Some(e) => eval_f64(e, &Ctx { vars: &self.vars, sys: &sys_view!(self, cfg) }, line)?,
        };
        if runs.fract() != 0.0 || !(1.0..=9999.0).contains(&runs) {
            return Err(Alarm::value_out_of_range(line, &format!("P={runs}: repetitions are 1..9999")));
        }
        let flow = self.flow.as_mut().expect("statements run inside a program");
        let (here, resume) = (flow.current, flow.next);
        let not_found = |t: &JumpTarget| Alarm::jump_not_found(line, &target_name(t));
        let first = match single || end.is_some() {
            true => flow.locate(start, true).or_else(|| flow.locate(start, false)),
            false => flow.locate(start, true),
        };
        let (first, after) = match (first, end) {
            (None, None) if !single => {
                // START after the REPEAT: the section ends at the next ENDLABEL.
                let first = flow.locate(start, false).ok_or_else(|| not_found(start))?;
                let label = JumpTarget::Label(ENDLABEL.into());
                let last = flow.locate_from(&label, first, usize::MAX).ok_or_else(|| not_found(&label))?;
                (first, flow.after(last))
            }
            (None, _) => return Err(not_found(start)),
            (Some(first), _) if single => (first, flow.after(first)),
            (Some(first), Some(end)) => {
                let last = flow.locate_from(end, first, usize::MAX).ok_or_else(|| not_found(end))?;
                (first, flow.after(last))
            }
            (Some(first), None) => {
                let label = JumpTarget::Label(ENDLABEL.into());
                match flow.locate_from(&label, first, here.offset) {
                    Some(last) => (first, flow.after(last)),
                    None => (first, here),
                }
            }
        };
        if first.offset <= here.offset && here.offset < after.offset && after != here {
            return Err(Alarm::nesting(line, "the repeated section holds its own REPEAT"));
        }
        let section = Section { start: first, after, left: runs as u32 - 1, resume: Some(resume) };
        if !flow.enter_section(section) {
            return Err(Alarm::nesting_too_deep(line, "too many nested program section repetitions"));
        }
        Ok(())
    }

    /// `CALL [NAME] BLOCK START TO END`.
    pub(in crate::interp) fn call_section(
        &mut self,
        program: Option<&str>,
        start: &JumpTarget,
        end: &JumpTarget,
        programs: &Programs,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let not_found = |t: &JumpTarget| Alarm::jump_not_found(line, &target_name(t));
        if let Some(name) = program {
            self.call(name, &[], 1, programs, cfg, line)?;
        }
        let flow = self.flow.as_mut().expect("a section call happens inside a program");
        let first = match program {
            Some(_) => flow.locate_from(start, Pos { offset: 0, line: 1 }, usize::MAX),
            None => flow.locate(start, true).or_else(|| flow.locate(start, false)),
        }
        .ok_or_else(|| not_found(start))?;
        let last = flow.locate_from(end, first, usize::MAX).ok_or_else(|| not_found(end))?;
        let section =
            Section { start: first, after: flow.after(last), left: 0, resume: program.is_none().then_some(flow.next) };
        if !flow.enter_section(section) {
            return Err(Alarm::nesting_too_deep(line, "too many nested program sections"));
        }
        Ok(())
    }
}

fn target_name(t: &JumpTarget) -> String {
    match t {
        JumpTarget::Label(l) => l.clone(),
        JumpTarget::BlockNumber(n) => format!("N{n}"),
        JumpTarget::Expr(_) | JumpTarget::ProgramStart => "(expression)".into(),
    }
}
