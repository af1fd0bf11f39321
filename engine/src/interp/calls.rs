//! Subprogram calls: program levels, parameters by value (`REAL A`) and by reference
//! (`VAR REAL A`), repetitions (`P=3`), and the return (RET, M17, M2/M30 or the end of text).
//! `targets.rs`: the program a call word names and the EXTERN checks; `modal_call.rs`: MCALL;
//! `section.rs`: REPEAT/REPEATB and CALL BLOCK.

mod caller_section;
pub(super) mod cycle_alarm;
pub(super) mod delobj;
pub(super) mod effects;
pub(super) mod exec_string;
mod modal_call;
mod section;
pub(super) mod suppression;
pub(super) mod targets;

use std::sync::Arc;

use super::Interpreter;
use super::eval::eval;
use super::eval::scope::{Ctx, sys_view};
use super::eval::value::Value;
use super::eval::vars::Variable;
use super::flow::Flow;
use super::modal::assign;
use super::spindles::FeedType;
use super::spindles::diameter::Diameter;
use crate::alarm::Alarm;
use crate::lang::{Expr, Lvalue, Param, ProcAttributes, ProgramText};
use crate::machine_data::MachineConfig;

/// The stored programs calls are resolved in (by name and directory).
pub use crate::programs::Programs;

/// What calls keep beside the program levels: the modal call (MCALL) and the EXTERN
/// declarations met so far. Both end with the program.
#[derive(Debug, Clone, Default)]
pub(super) struct CallState {
    pub mcall: Option<modal_call::ModalCall>,
    pub externs: targets::Externs,
    /// CALLPATH: the directory searched after `_N_SPF_DIR` for called programs.
    pub callpath: Option<crate::programs::Dir>,
    /// SBLOF/SBLON written as block commands in the main program.
    pub main_commands: suppression::LevelCommands,
}

/// The directory of `CALLPATH("path")`; an empty path ends the extension. Called programs are
/// searched there after `_N_SPF_DIR` until the program ends or the channel is reset.
pub(super) fn callpath(path: &str) -> Option<crate::programs::Dir> {
    let path = path.trim();
    (!path.is_empty()).then(|| crate::programs::Dir::parse_path(path))
}

/// Program levels: the main program plus up to 15 nested subprogram calls.
pub const MAX_LEVELS: usize = 16;

/// Where a subprogram level runs: the calls that lead to it from the main program, and its
/// text. Made once per call and shared by every block prepared in it (the channel shows a
/// block's text and name from it, and a checkpoint records the block's place in the call
/// chain).
#[derive(Debug, PartialEq)]
pub struct Level {
    /// The calls from the main program down to this level, outermost first: the line of the
    /// calling block in its program and the (stored, upper-case) name of the program it calls.
    /// The last entry names this level's program.
    pub calls: Vec<(u32, String)>,
    /// This level's program text.
    pub text: ProgramText,
}

impl Level {
    /// Whether `name` (upper case) runs at this level or calls down to it.
    pub(in crate::interp) fn within(&self, name: &str) -> bool {
        self.calls.iter().any(|(_, n)| n == name)
    }

    /// The name of this level's program.
    pub fn name(&self) -> &str {
        self.calls.last().map_or("", |(_, name)| name.as_str())
    }
}

/// A subprogram call in progress.
#[derive(Debug, Clone)]
pub(super) struct CallFrame {
    /// Which program runs at this level, called from where.
    level: Arc<Level>,
    /// Where the caller goes on.
    caller: Flow,
    text: ProgramText,
    /// The called program's directory, where its own calls are searched first.
    dir: Option<crate::programs::Dir>,
    /// Argument values, bound to the PROC parameters when the subprogram starts (`None`: left
    /// out, the parameter keeps its type's initial value).
    args: Vec<Option<Value>>,
    /// For each argument, the caller's variable it came from (for VAR parameters).
    sources: Vec<Option<Lvalue>>,
    /// (parameter, caller variable) pairs written back on return.
    by_reference: Vec<(String, Lvalue)>,
    /// Runs still to do after the current one.
    repeats_left: u32,
    /// Parameters are bound (the PROC line has been passed).
    bound: bool,
    /// The caller's modal state, programmable and settable frame, diameter programming (group
    /// 29) and feed type (group 15) at the call; restored at each return when the PROC line
    /// says SAVE.
    saved: Box<(super::Modal, super::Frame, Option<super::Frame>, Diameter, FeedType)>,
    /// The PROC line's SAVE, DISPLOF and ACTBLOCNO.
    attributes: ProcAttributes,
    /// The display and single block suppression in force at this level (`suppression.rs`).
    commands: suppression::LevelCommands,
}

/// The arguments of the innermost call (`None`: left out); empty in the main program.
pub(in crate::interp) fn call_args(calls: &[CallFrame]) -> &[Option<Value>] {
    calls.last().map_or(&[], |f| &f.args)
}

impl Interpreter {
    /// Calls program `name` with `args`, `repeat` times, from the block at `line`.
    pub(super) fn call(
        &mut self,
        name: &str,
        args: &[Expr],
        repeat: u32,
        programs: &Programs,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let section = caller_section::labels(name);
        let caller_dir = self.calls.last().map_or(programs.main_dir(), |f| f.dir.as_ref());
        let program = caller_section::in_program(name).map_or(name, |(program, _)| program);
        let (text, dir) = match section {
            Some(_) if program == name => self.caller_text(name, programs, line)?,
            _ => programs.resolve_with_path(program, caller_dir, self.call_state.callpath.as_ref(), line)?,
        };
        if self.calls.len() + 1 >= MAX_LEVELS {
            return Err(Alarm::too_many_levels(line, MAX_LEVELS));
        }
        self.call_state.externs.check(name, args, line)?;
        let sys = sys_view!(self, cfg);
        let ctx = Ctx { vars: &self.vars, sys: &sys };
        let mut values = Vec::new();
        let mut sources = Vec::new();
        for a in args {
            if targets::is_omitted(a) {
                values.push(None);
                sources.push(None);
                continue;
            }
            values.push(Some(eval(a, &ctx, line)?));
            sources.push(match a {
                Expr::Var { name, indices } if !name.starts_with('$') => {
                    Some(Lvalue { name: name.clone(), indices: evaluated(indices, &ctx, line)? })
                }
                Expr::RParam(n) => Some(Lvalue {
                    name: "R".into(),
                    indices: vec![Expr::Number(eval(n, &ctx, line)?.as_f64().unwrap_or(0.0))],
                }),
                _ => None,
            });
        }
        let mut caller = self.flow.take().expect("a call happens inside a program");
        let flow = Flow::for_call(text.clone(), &mut caller);
        let mut chain = self.calls.last().map(|f| f.level.calls.clone()).unwrap_or_default();
        chain.push((line, name.to_string()));
        self.calls.push(CallFrame {
            level: Arc::new(Level { calls: chain, text: text.clone() }),
            caller,
            text: text.clone(),
            dir,
            args: values,
            sources,
            by_reference: Vec::new(),
            repeats_left: repeat.max(1) - 1,
            bound: false,
            saved: Box::new((
                self.modal.clone(),
                (*self.pframe).clone(),
                (*self.iframe).clone(),
                self.spindles.diameter,
                self.spindles.feed_type,
            )),
            attributes: ProcAttributes::default(),
            commands: suppression::LevelCommands::default(),
        });
        self.vars.push_frame();
        self.flow = Some(flow);
        match section {
            Some((start, end)) => self.enter_caller_section(&start, &end, line),
            None => Ok(()),
        }
    }

    /// `alarm` as the operator sees it: raised inside a subprogram whose blocks are not
    /// displayed (`PROC .. DISPLOF` without `ACTBLOCNO`, as the standard cycles are written),
    /// it names the block that called the outermost such subprogram (Programming Manual, Job
    /// planning, "DISPLOF"/"ACTBLOCNO").
    pub(super) fn alarm_as_displayed(&self, alarm: Alarm) -> Alarm {
        let hidden = self.calls.iter().find(|f| f.bound && f.attributes.displof && !f.attributes.actblocno);
        match hidden.and_then(|f| f.level.calls.last()) {
            Some(&(line, _)) if alarm.line.is_some() => alarm.at_block(line),
            _ => alarm,
        }
    }

    /// The block the display shows for the blocks being prepared when they run inside a
    /// subprogram whose `PROC` line says `DISPLOF` (the standard cycles do): the line of the
    /// block that called the outermost such subprogram and the level it is in (`None`: the
    /// main program). `None` while the blocks are shown as themselves.
    pub fn hidden_by_call(&self) -> Option<(u32, Option<Arc<Level>>)> {
        let at = suppression::outermost_hiding(&self.calls)?;
        let &(line, _) = self.calls[at].level.calls.last()?;
        let caller = at.checked_sub(1).map(|i| self.calls[i].level.clone());
        Some((line, caller))
    }

    /// The subprogram level being prepared; `None` in the main program.
    pub fn level(&self) -> Option<&Arc<Level>> {
        self.calls.last().map(|f| &f.level)
    }

    /// Binds the call's arguments to the parameters of the subprogram's PROC line.
    pub(super) fn bind_params(&mut self, params: &[Param], attributes: ProcAttributes, line: u32) -> Result<(), Alarm> {
        let Some(frame) = self.calls.last_mut().filter(|f| !f.bound) else { return Ok(()) };
        frame.bound = true;
        frame.attributes = attributes;
        frame.commands = suppression::LevelCommands::of_proc(attributes);
        if frame.args.len() > params.len() {
            if !newer_cycle_defaults(frame, params.len()) {
                return Err(Alarm::too_many_arguments(
                    line,
                    &format!("{} arguments for {} parameters", frame.args.len(), params.len()),
                ));
            }
            frame.args.truncate(params.len());
            frame.sources.truncate(params.len());
        }
        let args = frame.args.clone();
        let sources = frame.sources.clone();
        let mut by_reference = Vec::new();
        for (i, p) in params.iter().enumerate() {
            let mut var = Variable::new(p.ty, Vec::new());
            if let Some(Some(v)) = args.get(i) {
                var.data[0] = v.clone().convert(p.ty).map_err(|e| Alarm::type_error(line, &e.0))?;
            }
            if p.by_reference {
                match sources.get(i).cloned().flatten() {
                    Some(src) => by_reference.push((p.name.clone(), src)),
                    None if args.get(i).is_some_and(Option::is_some) => {
                        return Err(Alarm::not_a_variable(line, &p.name));
                    }
                    None => {}
                }
            }
            self.vars.declare(&p.name, var, false).map_err(|_| Alarm::defined_twice(line, &p.name))?;
        }
        if let Some(frame) = self.calls.last_mut() {
            frame.by_reference = by_reference;
        }
        Ok(())
    }

    /// Checks, at the first block of a subprogram that is not its PROC line, that no
    /// arguments were passed to a program without parameters.
    /// True while the running subprogram has not reached its first block yet (the block
    /// that binds or refuses the call's arguments).
    pub(super) fn call_unbound(&self) -> bool {
        self.calls.last().is_some_and(|f| !f.bound)
    }

    pub(super) fn check_unbound(&mut self, line: u32) -> Result<(), Alarm> {
        if let Some(frame) = self.calls.last_mut().filter(|f| !f.bound) {
            frame.bound = true;
            if !frame.args.is_empty() {
                return Err(Alarm::too_many_arguments(line, "arguments passed to a program without PROC parameters"));
            }
        }
        Ok(())
    }

    /// Ends the current subprogram run: writes VAR parameters back, repeats or returns to the
    /// caller. Returns false in the main program (the program ends instead).
    pub(super) fn return_from_call(&mut self, cfg: &MachineConfig, line: u32) -> Result<bool, Alarm> {
        let Some(frame) = self.calls.last_mut() else { return Ok(false) };
        let results: Vec<(Lvalue, Value)> = frame
            .by_reference
            .iter()
            .filter_map(|(param, src)| self.vars.get(param).map(|v| (src.clone(), v.data[0].clone())))
            .collect();
        if frame.attributes.save {
            // PROC ... SAVE: the G functions and frames of the caller come back (the feed the
            // subprogram programmed stays, as F is no G function).
            let (modal, pframe, iframe, diameter, feed_type) = (*frame.saved).clone();
            let feed = self.modal.feed;
            let (per_rev, type_index) = (self.modal.feed_per_rev, self.modal.feed_type_index);
            self.modal = super::Modal { feed, ..modal };
            *self.pframe = pframe;
            *self.iframe = iframe;
            self.spindles.diameter = diameter;
            if feed_type.css() == self.spindles.feed_type.css() {
                self.spindles.feed_type = feed_type;
            } else {
                // Constant cutting speed switched on or off in the subprogram stays (not
                // modelled: giving it back would need a spindle command at the return).
                self.modal.feed_per_rev = per_rev;
                self.modal.feed_type_index = type_index;
            }
        }
        let frame = self.calls.last_mut().expect("checked above");
        if frame.repeats_left > 0 {
            frame.repeats_left -= 1;
            frame.bound = false;
            let text = frame.text.clone();
            self.vars.pop_frame();
            self.write_back(&results, cfg, line)?;
            self.vars.push_frame();
            self.flow = Some(match self.flow.take() {
                // The repetition reruns the text of the run that ends.
                Some(run) => run.rerun(),
                None => Flow::new(text),
            });
            return Ok(true);
        }
        let frame = self.calls.pop().expect("checked above");
        self.vars.pop_frame();
        let mut caller = frame.caller;
        if let Some(run) = self.flow.take() {
            run.return_to(&mut caller);
        }
        self.flow = Some(caller);
        self.end_level_modal_call();
        self.write_back(&results, cfg, line)?;
        Ok(true)
    }

    fn write_back(&mut self, results: &[(Lvalue, Value)], cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        for (target, value) in results {
            let expr = match value {
                Value::Str(s) | Value::Axis(s) => Expr::Str(s.clone()),
                Value::Bool(b) => Expr::Bool(*b),
                v => Expr::Number(v.as_f64().unwrap_or(0.0)),
            };
            let sys = sys_view!(self, cfg);
            assign(&target.name, &target.indices, &expr, cfg, &mut self.vars, &sys, line)?;
        }
        Ok(())
    }
}

fn evaluated(indices: &[Expr], ctx: &Ctx, line: u32) -> Result<Vec<Expr>, Alarm> {
    indices.iter().map(|e| Ok(Expr::Number(eval(e, ctx, line)?.as_f64().unwrap_or(0.0)))).collect()
}

impl Interpreter {
    /// The calls at the end of a block: MCALL selects or ends the modal call, CALL BLOCK runs a
    /// section, a call word calls its subprogram; a block with path motion and no call of its
    /// own calls the active modal subprogram.
    pub(super) fn block_calls(
        &mut self,
        words: &super::modal::Words,
        path_motion: bool,
        programs: &Programs,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        if words.mcall {
            return self.set_modal_call(words.call.as_ref(), programs, cfg, line);
        }
        if let Some(section) = &words.section_call {
            let (program, start, end) = &**section;
            return self.call_section(program.as_deref(), start, end, programs, cfg, line);
        }
        if let Some((name, args)) = &words.call {
            return self.call(name, args, words.repeat.unwrap_or(1), programs, cfg, line);
        }
        if let Some(cycle) = self.take_tool_cycle() {
            return self.call(&cycle, &[], 1, programs, cfg, line);
        }
        if path_motion && self.call_state.mcall.is_some() {
            self.run_modal_call(programs, cfg, line)?;
        }
        Ok(())
    }
}

/// Whether the arguments of `frame` beyond its PROC's `known` parameters are a newer Operate's
/// extra parameters of a library cycle left at their defaults (left out, 0 or an empty string):
/// CAM posts for newer controls write the longer parameter lists (`_GMODE`, `_DMODE`, `_AMODE`
/// ..) the library's cycles do not have; at their defaults they ask for what the library's
/// cycle does. Any other value stays 12340, as the cycle cannot do what it asks.
fn newer_cycle_defaults(frame: &CallFrame, known: usize) -> bool {
    let Some((_, name)) = frame.level.calls.last() else { return false };
    let is_library = crate::programs::cycles::find(name)
        .and_then(|cycle| cycle.ready().ok())
        .is_some_and(|text| **text == *frame.text);
    is_library
        && frame.args[known..].iter().all(|arg| match arg {
            None => true,
            Some(Value::Str(s)) => s.is_empty(),
            Some(v) => v.as_f64().is_ok_and(|v| v == 0.0),
        })
}
