//! Statements: declarations (DEF) and control flow, executed during block preparation.

use super::eval::scope::{Ctx, SysView, is_main_run_variable, sys_view};
use super::eval::value::Value;
use super::eval::value_lists::List;
use super::eval::vars::Variable;
use super::eval::{eval, eval_f64};
use super::flow::{Ctrl, Pos, SectionEnd};
use super::modal::{Assigned, assign};
use super::{Interpreter, Item, Prep, Programs, StopKind};
use crate::alarm::Alarm;
use crate::lang::{Block, Expr, Stmt, VarDecl, VarType, Word};
use crate::machine_data::MachineConfig;

impl Interpreter {
    /// Reads and prepares the next block of the program. Kept out of `prepare_next`, so that
    /// the fast lane's code there is compiled the same whatever the general path holds.
    #[inline(never)]
    pub(super) fn step_program(
        &mut self,
        cfg: &MachineConfig,
        programs: &Programs,
        main_run_idle: bool,
        out: &mut Vec<Item>,
    ) -> Result<Prep, Alarm> {
        self.refresh_derived_chain_data(cfg);
        let Some(flow) = self.flow.as_mut() else { return Ok(Prep::Done) };
        if !flow.sections.is_empty() && flow.pass_section_ends() == Some(SectionEnd::Return) {
            // The section called from another program (CALL "NAME" BLOCK ..) is done.
            let line = flow.current.line;
            self.return_from_call(cfg, line)?;
            return Ok(Prep::Prepared);
        }
        let (next, current) = (flow.next, flow.current);
        let Some((block, at)) = flow.read() else {
            if let Some(open) = flow.control.last() {
                return Err(Alarm::nesting(open_line(open), "structure not closed before the end of the program"));
            }
            // The end of a subprogram's text returns like M17.
            if self.return_from_call(cfg, current.line)? {
                return Ok(Prep::Prepared);
            }
            out.push(Item::Stop { kind: StopKind::End, line: current.line });
            self.flow = None;
            return Ok(Prep::Done);
        };
        self.read_at = at;
        let block = block.map_err(|d| {
            let mut alarm = Alarm::syntax(d.line, &format!("column {}: {}", d.column, d.message));
            alarm.number = d.alarm;
            alarm
        })?;
        if self.program_control.skips(&block) {
            // SKP: the block is read (its line counts) but nothing of it is executed.
            flow.recycle(block);
            return Ok(Prep::Prepared);
        }
        if self.sync_wait.holds(&self.pos, main_run_idle) || !main_run_idle && block.reads_main_run() {
            // The control's implicit preprocessing stop: wait for the main run, then read again.
            flow.next = next;
            flow.current = current;
            return Ok(Prep::WaitForMainRun);
        }
        // DELOBJ/CORRTRAFO/ISFILE as functions, CORRTRAFO and the file procedures as statements
        // run once, here, after
        // any wait for the main run.
        let mut block = block;
        if block.has_effect_calls() {
            self.check_unbound(block.line)?;
            self.run_effect_calls(block.to_mut(), cfg, programs, out)?;
        }
        match &block.stmt {
            Some(Stmt::Proc { params, attributes, .. }) => {
                let unbound = self.call_unbound();
                self.bind_params(params, *attributes, block.line)?;
                if let Some(flow) = self.flow.as_mut().filter(|_| unbound) {
                    // Only comment lines came before: the next call of this text starts here.
                    flow.proc_at = Some(at);
                }
            }
            Some(stmt) => {
                self.check_unbound(block.line)?;
                self.statement(stmt, &block, at, cfg, out)?;
            }
            None if let Some(arg) = super::calls::exec_string::argument(&block) => {
                self.check_unbound(block.line)?;
                self.exec_string(arg, &block, cfg, programs, out)?;
            }
            None => {
                // Comment lines before a subprogram's PROC line leave its call unbound.
                if !block.words.is_empty() || block.number.is_some() || block.label.is_some() {
                    self.check_unbound(block.line)?;
                    if self.assigns_variables_only(&block) {
                        self.assignment_block(&block, cfg, out)?;
                    } else {
                        self.prepare_block(&block, cfg, programs, out)?;
                        self.level_commands(&block);
                    }
                } else if !self.call_unbound() {
                    self.prepare_block(&block, cfg, programs, out)?;
                }
                // A comment line before the PROC line (a cycle's header, read at every call)
                // does nothing: the calling block prepared the state it finds, and the call
                // changed none of it.
            }
        }
        let line = block.line;
        if let Some(flow) = self.flow.as_mut() {
            flow.recycle(block);
        }
        if out.iter().any(|i| matches!(i, Item::Alarm(_))) {
            // A programmed alarm (SETAL) ends preparation like any other.
            self.flow = None;
            self.calls.clear();
            return Ok(Prep::Done);
        }
        if let Some(i) = out.iter().position(|i| matches!(i, Item::Stop { kind: StopKind::End, .. })) {
            // M17, M2, M30 and RET end a subprogram run; in the main program they end it.
            if !self.calls.is_empty() {
                out.remove(i);
                self.return_from_call(cfg, line)?;
                return Ok(Prep::Prepared);
            }
            self.flow = None;
            return Ok(Prep::Done);
        }
        Ok(Prep::Prepared)
    }

    fn statement(
        &mut self,
        stmt: &Stmt,
        block: &Block,
        at: Pos,
        cfg: &MachineConfig,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = block.line;
        let cond = |this: &Self, e: &Expr| -> Result<bool, Alarm> {
            // A comparison of plain arithmetic (`R1<R10`) needs no system view.
            if let Some(truth) = super::eval::numeric::condition(e, &this.vars.r) {
                return Ok(truth);
            }
            let sys = sys_view!(this, cfg);
            eval(e, &Ctx { vars: &this.vars, sys: &sys }, line)?.as_bool().map_err(|e| Alarm::type_error(line, &e.0))
        };
        match stmt {
            Stmt::Def { global, ty, vars } => {
                for decl in vars {
                    self.declare(*global, *ty, decl, cfg, line)?;
                }
            }
            Stmt::If { cond: c, goto: Some(goto) } => {
                if cond(self, c)? {
                    self.jump(goto, cfg, line, out)?;
                }
            }
            Stmt::If { cond: c, goto: None } => {
                let taken = cond(self, c)?;
                let flow = self.flow_mut();
                flow.open(Ctrl::If { at }, line)?;
                if !taken && flow.skip(line, |s| matches!(s, Stmt::Else | Stmt::EndIf))? == Stmt::EndIf {
                    flow.control.pop();
                }
            }
            Stmt::Else => {
                let flow = self.flow_mut();
                close(flow.control.pop(), line, "ELSE without IF", |c| matches!(c, Ctrl::If { .. }))?;
                flow.skip(line, |s| matches!(s, Stmt::EndIf))?;
            }
            Stmt::EndIf => {
                close(self.flow_mut().control.pop(), line, "ENDIF without IF", |c| matches!(c, Ctrl::If { .. }))?
            }
            Stmt::While(c) => {
                if cond(self, c)? {
                    self.flow_mut().open(Ctrl::While { at }, line)?;
                } else {
                    self.flow_mut().skip(line, |s| matches!(s, Stmt::EndWhile))?;
                }
            }
            Stmt::EndWhile => {
                let flow = self.flow_mut();
                match flow.control.pop() {
                    Some(Ctrl::While { at }) => flow.next = at,
                    other => close(other, line, "ENDWHILE without WHILE", |_| false)?,
                }
            }
            Stmt::For { var, start, end } => {
                self.assign_to(&var.name, &var.indices, start, cfg, line)?;
                let end = eval_f64(end, &Ctx { vars: &self.vars, sys: &self.sys(cfg) }, line)?;
                let value = self.read_var(&var.name, &var.indices, cfg, line)?;
                let flow = self.flow_mut();
                if value <= end {
                    let body = flow.next;
                    flow.open(Ctrl::For { at, body, var: var.clone(), end }, line)?;
                } else {
                    flow.skip(line, |s| matches!(s, Stmt::EndFor))?;
                }
            }
            Stmt::EndFor => {
                let Some(Ctrl::For { at, body, var, end }) = self.flow_mut().control.pop() else {
                    return Err(Alarm::nesting(line, "ENDFOR without FOR"));
                };
                let next = self.read_var(&var.name, &var.indices, cfg, line)? + 1.0;
                self.assign_to(&var.name, &var.indices, &Expr::Number(next), cfg, line)?;
                if next <= end {
                    let flow = self.flow_mut();
                    flow.control.push(Ctrl::For { at, body, var, end });
                    flow.next = body;
                }
            }
            Stmt::Repeat => {
                let flow = self.flow_mut();
                let body = flow.next;
                flow.open(Ctrl::Repeat { at, body }, line)?;
            }
            Stmt::Until(c) => {
                let done = cond(self, c)?;
                let flow = self.flow_mut();
                match flow.control.last() {
                    Some(Ctrl::Repeat { body, .. }) if !done => flow.next = *body,
                    Some(Ctrl::Repeat { .. }) => {
                        flow.control.pop();
                    }
                    _ => return Err(Alarm::nesting(line, "UNTIL without REPEAT")),
                }
            }
            Stmt::Loop => {
                let flow = self.flow_mut();
                let body = flow.next;
                flow.open(Ctrl::Loop { at, body }, line)?;
            }
            Stmt::EndLoop => {
                let flow = self.flow_mut();
                match flow.control.last() {
                    Some(Ctrl::Loop { body, .. }) => flow.next = *body,
                    _ => return Err(Alarm::nesting(line, "ENDLOOP without LOOP")),
                }
            }
            Stmt::Case { expr, arms, default } => {
                let sys = self.sys(cfg);
                let ctx = Ctx { vars: &self.vars, sys: &sys };
                let value = eval(expr, &ctx, line)?;
                let mut target = default.as_ref();
                for (constant, goto) in arms {
                    let c = eval(constant, &ctx, line)?;
                    if equal(&value, &c) {
                        target = Some(goto);
                        break;
                    }
                }
                if let Some(goto) = target.cloned() {
                    self.jump(&goto, cfg, line, out)?;
                }
            }
            Stmt::Goto(goto) => self.jump(goto, cfg, line, out)?,
            // PROC lines are bound in `step_program`.
            Stmt::Proc { .. } => {}
            Stmt::Extern { name, params } => self.call_state.externs.declare(name, params),
            Stmt::RepeatSection { start, end, count } => {
                self.repeat_section(start, end.as_ref(), count.as_ref(), false, cfg, line)?
            }
            Stmt::RepeatBlock { target, count } => {
                self.repeat_section(target, None, count.as_ref(), true, cfg, line)?
            }
            Stmt::Ret => out.push(Item::Stop { kind: StopKind::End, line }),
        }
        Ok(())
    }

    fn flow_mut(&mut self) -> &mut super::flow::Flow {
        self.flow.as_mut().expect("statements run inside a program")
    }

    fn sys<'a>(&'a self, cfg: &'a MachineConfig) -> SysView<'a> {
        sys_view!(self, cfg)
    }

    fn assign_to(
        &mut self,
        name: &str,
        indices: &[Expr],
        value: &Expr,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let sys = sys_view!(self, cfg);
        match assign(name, indices, value, cfg, &mut self.vars, &sys, line)? {
            Assigned::Variable => Ok(()),
            _ => Err(Alarm::type_error(line, &format!("{name} is not a variable"))),
        }
    }

    fn read_var(&self, name: &str, indices: &[Expr], cfg: &MachineConfig, line: u32) -> Result<f64, Alarm> {
        let e = Expr::Var { name: name.to_string(), indices: indices.to_vec() };
        let e = match name.strip_prefix('R').and_then(|n| n.parse::<u32>().ok()) {
            Some(n) if indices.is_empty() => Expr::RParam(Box::new(Expr::Number(n as f64))),
            _ => e,
        };
        eval_f64(&e, &Ctx { vars: &self.vars, sys: &self.sys(cfg) }, line)
    }

    fn declare(
        &mut self,
        global: bool,
        ty: VarType,
        decl: &VarDecl,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        if cfg.program_axis(&decl.name).is_some() || decl.name.starts_with('R') && decl.name[1..].parse::<u32>().is_ok()
        {
            return Err(Alarm::defined_twice(line, &decl.name));
        }
        let sys = self.sys(cfg);
        let ctx = Ctx { vars: &self.vars, sys: &sys };
        let mut dims = Vec::new();
        for d in &decl.dims {
            let n = eval(d, &ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
            if !(1..=65_535).contains(&n) {
                return Err(Alarm::index_error(line, &decl.name, &format!("dimension {n} must be 1..65535")));
            }
            dims.push(n as usize);
        }
        // Sized before anything is allocated: DEF REAL AA[30000,30000] would otherwise ask for
        // 28.8 GB and abort the server.
        let elements = dims.iter().try_fold(1usize, |n, &d| n.checked_mul(d)).unwrap_or(usize::MAX);
        if elements > 1_000_000 {
            return Err(Alarm::index_error(line, &decl.name, "array larger than 1,000,000 elements"));
        }
        if Variable::footprint(ty, elements) > self.vars.free_bytes() {
            return Err(Alarm::user_memory_full(line, &decl.name));
        }
        let mut var = Variable::new(ty, dims);
        if !decl.init.is_empty() {
            List::of_init(&decl.init).write(&mut var, 0, &decl.name, line, |e| eval(e, &ctx, line))?;
        }
        self.vars.declare(&decl.name, var, global).map_err(|_| Alarm::defined_twice(line, &decl.name))
    }
}

fn open_line(c: &Ctrl) -> u32 {
    match c {
        Ctrl::If { at }
        | Ctrl::While { at }
        | Ctrl::For { at, .. }
        | Ctrl::Repeat { at, .. }
        | Ctrl::Loop { at, .. } => at.line,
    }
}

fn close(popped: Option<Ctrl>, line: u32, what: &str, fits: impl Fn(&Ctrl) -> bool) -> Result<(), Alarm> {
    match popped {
        Some(c) if fits(&c) => Ok(()),
        _ => Err(Alarm::nesting(line, what)),
    }
}

fn equal(a: &Value, b: &Value) -> bool {
    match (a.as_f64(), b.as_f64()) {
        (Ok(x), Ok(y)) => (x - y).abs() <= 1e-12 * x.abs().max(y.abs()),
        _ => a.as_text() == b.as_text(),
    }
}

/// True if any expression of the block reads a main-run variable.
pub(super) fn reads_main_run(block: &Block) -> bool {
    // Asked of every block while the main run is busy: no list of the expressions is made.
    let words = block.words.iter().any(|w| match w {
        // SPOS starts from where the spindle stands in the main run.
        Word::Address { name, .. } if name == "SPOS" || name == "SPOSA" => true,
        // M19/M70 and rigid tapping start from the spindle's angle, too.
        Word::M(19 | 70) | Word::G(331 | 332) => true,
        // STOPRE: the programmed preprocessing stop (e.g. before a T="name" that must see
        // what tool monitoring did in the main run).
        Word::Keyword { name, args } if args.is_empty() && name == "STOPRE" => true,
        Word::Address { indices, value, .. } => {
            expr_reads_main_run(&value.expr) || indices.iter().any(expr_reads_main_run)
        }
        // The file procedures act when the main run has reached them, as after a STOPRE: a
        // log line is written when the blocks before it have run, with that time.
        Word::Keyword { name, args } => {
            super::files::PROCEDURES.contains(&name.as_str()) || args.iter().any(expr_reads_main_run)
        }
        _ => false,
    });
    words
        || match &block.stmt {
            Some(Stmt::If { cond, .. } | Stmt::While(cond) | Stmt::Until(cond)) => expr_reads_main_run(cond),
            Some(Stmt::For { start, end, .. }) => expr_reads_main_run(start) || expr_reads_main_run(end),
            Some(Stmt::Case { expr, .. }) => expr_reads_main_run(expr),
            Some(Stmt::Def { vars, .. }) => {
                vars.iter().flat_map(|v| v.init.iter().chain(&v.dims)).any(expr_reads_main_run)
            }
            _ => false,
        }
}

fn expr_reads_main_run(e: &Expr) -> bool {
    match e {
        Expr::Var { name, indices } => is_main_run_variable(name) || indices.iter().any(expr_reads_main_run),
        Expr::RParam(i) | Expr::Unary(_, i) => expr_reads_main_run(i),
        Expr::Binary(_, a, b) => expr_reads_main_run(a) || expr_reads_main_run(b),
        Expr::Call(_, args) => args.iter().any(expr_reads_main_run),
        Expr::Number(_) | Expr::Str(_) | Expr::Bool(_) => false,
    }
}
