//! `MCALL NAME(args)`: the modal subprogram call. After every following block with path motion
//! on the program level that programmed it, the subprogram runs as if called there; `MCALL`
//! without a name (or the end of that program level, or of the program) ends it. Blocks of the
//! called subprogram itself (and of deeper levels) do not call it again. The arguments are
//! evaluated once, at the MCALL block; only one modal call is active at a time. A hole pattern
//! cycle of the cycle directories called from that level triggers it at each of its positioning
//! blocks (see `in_pattern_cycle`).

use super::{Interpreter, Programs};
use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::eval::value::Value;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;

/// The active modal call.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::interp) struct ModalCall {
    name: String,
    /// The arguments' values at the MCALL block (omitted ones stay omitted).
    args: Vec<Expr>,
    /// The program level (number of calls in progress) that programmed it.
    level: usize,
}

impl Interpreter {
    /// `MCALL` in a block: `call` becomes the modal call, or without one the modal call ends.
    pub(in crate::interp) fn set_modal_call(
        &mut self,
        call: Option<&(String, Vec<Expr>)>,
        programs: &Programs,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let Some((name, args)) = call else {
            self.call_state.mcall = None;
            return Ok(());
        };
        if !programs.contains_key(name) {
            return Err(Alarm::program_not_found(line, name));
        }
        let sys = sys_view!(self, cfg);
        let ctx = Ctx { vars: &self.vars, sys: &sys };
        let mut values = Vec::with_capacity(args.len());
        for a in args {
            values.push(match a {
                a if super::targets::is_omitted(a) => a.clone(),
                a => match eval(a, &ctx, line)? {
                    Value::Str(s) | Value::Axis(s) => Expr::Str(s),
                    Value::Bool(b) => Expr::Bool(b),
                    v => Expr::Number(v.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?),
                },
            });
        }
        self.call_state.externs.check(name, &values, line)?;
        self.call_state.mcall = Some(ModalCall { name: name.clone(), args: values, level: self.calls.len() });
        Ok(())
    }

    /// After a block with path motion: runs the modal subprogram if one is active on this
    /// program level. True if it was called.
    pub(in crate::interp) fn run_modal_call(
        &mut self,
        programs: &Programs,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<bool, Alarm> {
        let here = self.calls.len();
        let Some(mc) = self
            .call_state
            .mcall
            .as_ref()
            .filter(|m| m.level == here || m.level + 1 == here && self.in_pattern_cycle(m))
        else {
            return Ok(false);
        };
        let (name, args) = (mc.name.clone(), mc.args.clone());
        self.call(&name, &args, 1, programs, cfg, line)?;
        Ok(true)
    }

    /// A cycle of the cycle directories (CST, CMA, CUS) called straight from the level that
    /// programmed `mc`, and not `mc`'s own subprogram: the hole pattern cycles (HOLES1, HOLES2,
    /// CYCLE801, CYCLE802) position the tool and the modal call runs at each position, as on
    /// the control.
    fn in_pattern_cycle(&self, mc: &ModalCall) -> bool {
        use crate::programs::Dir;
        self.calls.last().is_some_and(|f| {
            matches!(f.dir, Some(Dir::Cst | Dir::Cma | Dir::Cus)) && f.level.name() != mc.name.as_str()
        })
    }

    /// A program level ends: a modal call it programmed ends with it.
    pub(in crate::interp) fn end_level_modal_call(&mut self) {
        if self.call_state.mcall.as_ref().is_some_and(|m| m.level > self.calls.len()) {
            self.call_state.mcall = None;
        }
    }
}
