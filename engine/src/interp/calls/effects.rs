//! Predefined functions with side effects inside a block: `DELOBJ(...)`, `CORRTRAFO(...)`,
//! `NEWT(...)` and `ISFILE(...)` in any expression (`IF (DELOBJ("TRAFO_DATA") < 0)`, `R1=CORRTRAFO(...)`),
//! CORRTRAFO, DELT and the file procedures (`WRITE(err, ...)`, [`crate::interp::files`]) as
//! statements. They run once, innermost and left to right, before the block is prepared, and
//! are replaced by their values, so conditions and assignments then read plain numbers.

use crate::alarm::Alarm;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::tools::create_delete;
use crate::interp::{Interpreter, Item, Programs, calls::delobj, files};
use crate::lang::{Block, Expr, Stmt, Word};
use crate::machine_data::MachineConfig;

const FUNCTIONS: &[&str] = &["DELOBJ", "CORRTRAFO", "ISFILE", "NEWT"];

fn calls_any(e: &Expr) -> bool {
    match e {
        Expr::Call(name, args) => FUNCTIONS.contains(&name.as_str()) || args.iter().any(calls_any),
        Expr::Var { indices, .. } => indices.iter().any(calls_any),
        Expr::RParam(i) | Expr::Unary(_, i) => calls_any(i),
        Expr::Binary(_, a, b) => calls_any(a) || calls_any(b),
        Expr::Number(_) | Expr::Str(_) | Expr::Bool(_) => false,
    }
}

/// Every expression of `block` that may hold a call (mutable, in reading order).
fn expressions(block: &mut Block) -> Vec<&mut Expr> {
    let mut out: Vec<&mut Expr> = Vec::new();
    match &mut block.stmt {
        Some(Stmt::If { cond, .. } | Stmt::While(cond) | Stmt::Until(cond)) => out.push(cond),
        Some(Stmt::For { start, end, .. }) => out.extend([start, end]),
        Some(Stmt::Case { expr, .. }) => out.push(expr),
        Some(Stmt::Def { vars, .. }) => out.extend(vars.iter_mut().flat_map(|v| v.dims.iter_mut().chain(&mut v.init))),
        _ => {}
    }
    for w in &mut block.words {
        match w {
            Word::Address { indices, value, .. } => {
                out.extend(indices.iter_mut());
                out.push(&mut value.expr);
            }
            Word::Keyword { args, .. } => out.extend(args.iter_mut()),
            _ => {}
        }
    }
    out
}

/// True if `block` calls DELOBJ or CORRTRAFO as a function, or CORRTRAFO as a statement.
pub(in crate::interp) fn present(block: &Block) -> bool {
    let stmt = match &block.stmt {
        Some(Stmt::If { cond, .. } | Stmt::While(cond) | Stmt::Until(cond)) => calls_any(cond),
        Some(Stmt::For { start, end, .. }) => calls_any(start) || calls_any(end),
        Some(Stmt::Case { expr, .. }) => calls_any(expr),
        Some(Stmt::Def { vars, .. }) => vars.iter().flat_map(|v| v.dims.iter().chain(&v.init)).any(calls_any),
        _ => false,
    };
    stmt || block.words.iter().any(|w| match w {
        Word::Address { indices, value, .. } => indices.iter().any(calls_any) || calls_any(&value.expr),
        Word::Keyword { name, args } => {
            name == "CORRTRAFO"
                || name == "DELT"
                || files::PROCEDURES.contains(&name.as_str())
                || args.iter().any(calls_any)
        }
        _ => false,
    })
}

impl Interpreter {
    /// Runs the block's DELOBJ/CORRTRAFO calls and puts their values in their place; a
    /// CORRTRAFO statement runs and leaves the block. `cfg` is the channel's configuration.
    pub(in crate::interp) fn run_effect_calls(
        &mut self,
        block: &mut Block,
        cfg: &MachineConfig,
        programs: &Programs,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = block.line;
        for e in expressions(block) {
            self.resolve_calls(e, cfg, programs, line, out)?;
        }
        let mut words = std::mem::take(&mut block.words);
        let mut kept = Vec::with_capacity(words.len());
        for w in words.drain(..) {
            match w {
                Word::Keyword { name, args } if name == "CORRTRAFO" => {
                    self.corrtrafo(&args, cfg, line, out)?;
                }
                Word::Keyword { name, args } if name == "DELT" => {
                    let write = self.delt(&args, cfg, line)?;
                    self.data_writes.push((line, write));
                }
                Word::Keyword { name, args } if files::PROCEDURES.contains(&name.as_str()) => {
                    self.file_procedure(&name, &args, cfg, programs, line)?;
                }
                w => kept.push(w),
            }
        }
        block.words = kept;
        Ok(())
    }

    /// `DELT(...)` as a statement: its data-write entry (the tool in the spindle and the one
    /// prepared cannot go).
    fn delt(&self, args: &[Expr], cfg: &MachineConfig, line: u32) -> Result<String, Alarm> {
        let sys = sys_view!(self, cfg);
        let in_use = [self.offsets.t, self.offsets.prepared];
        create_delete::delt(args, &Ctx { vars: &self.vars, sys: &sys }, cfg, in_use, line)
    }

    fn resolve_calls(
        &mut self,
        e: &mut Expr,
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        match e {
            Expr::Call(name, args) => {
                for a in args.iter_mut() {
                    self.resolve_calls(a, cfg, programs, line, out)?;
                }
                let value = match name.as_str() {
                    "DELOBJ" => {
                        let derived = self.trafo.config();
                        let sys = sys_view!(self, derived.as_deref().unwrap_or(cfg));
                        let (value, write) = delobj::function(args, &Ctx { vars: &self.vars, sys: &sys }, line)?;
                        if let Some(write) = write {
                            self.data_writes.push((line, write));
                        }
                        value
                    }
                    "CORRTRAFO" => self.corrtrafo(args, cfg, line, out)?,
                    "NEWT" => {
                        let sys = sys_view!(self, cfg);
                        let ctx = Ctx { vars: &self.vars, sys: &sys };
                        let (t, writes) = create_delete::newt(args, &ctx, cfg, &self.data_writes, line)?;
                        self.data_writes.extend(writes.into_iter().map(|w| (line, w)));
                        i64::from(t)
                    }
                    "ISFILE" => {
                        *e = Expr::Bool(self.isfile(args, cfg, programs, line)?);
                        return Ok(());
                    }
                    _ => return Ok(()),
                };
                *e = Expr::Number(value as f64);
            }
            Expr::Var { indices, .. } => {
                for i in indices.iter_mut() {
                    self.resolve_calls(i, cfg, programs, line, out)?;
                }
            }
            Expr::RParam(i) | Expr::Unary(_, i) => self.resolve_calls(i, cfg, programs, line, out)?,
            Expr::Binary(_, a, b) => {
                self.resolve_calls(a, cfg, programs, line, out)?;
                self.resolve_calls(b, cfg, programs, line, out)?;
            }
            Expr::Number(_) | Expr::Str(_) | Expr::Bool(_) => {}
        }
        Ok(())
    }
}
