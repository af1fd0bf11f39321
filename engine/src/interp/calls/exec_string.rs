//! `EXECSTRING(text)`: a block given as a string at run time (Programming Manual Job Planning,
//! "Execute string"). Machine builders assemble a call or an auxiliary function from variables
//! (`EXECSTRING("M" << CODE)`, `EXECSTRING(CMD)` with `CMD="L" << NR`) and run it as if it
//! stood in the program at this line.
//!
//! The string is parsed as one block and prepared in place of the `EXECSTRING` block: NC words,
//! assignments and subprogram calls. A control structure (IF, GOTO, DEF ...) cannot come from
//! a string: 12080 at the `EXECSTRING` line, as a syntax error in the string does.

use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::{Interpreter, Item, Programs};
use crate::lang::{Block, Expr, Word};
use crate::machine_data::MachineConfig;

/// The argument of a block that is an `EXECSTRING(...)` call and nothing else.
pub(in crate::interp) fn argument(block: &Block) -> Option<&Expr> {
    match block.words.as_slice() {
        [Word::Keyword { name, args }] if name == "EXECSTRING" && block.stmt.is_none() => args.first(),
        _ => None,
    }
}

impl Interpreter {
    /// Prepares the block `arg` evaluates to, at the line of `block`.
    pub(in crate::interp) fn exec_string(
        &mut self,
        arg: &Expr,
        block: &Block,
        cfg: &MachineConfig,
        programs: &Programs,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = block.line;
        let text = {
            let sys = sys_view!(self, cfg);
            eval(arg, &Ctx { vars: &self.vars, sys: &sys }, line)?.as_text()
        };
        if text.contains(['\n', '\r']) {
            return Err(Alarm::syntax(line, "EXECSTRING: the string holds more than one block"));
        }
        let parsed = crate::lang::parse_block(&text, line, 0)
            .map_err(|(_, message)| Alarm::syntax(line, &format!("EXECSTRING \"{text}\": {message}")))?;
        let Some(parsed) = parsed else { return Ok(()) };
        if parsed.stmt.is_some() || parsed.label.is_some() {
            return Err(Alarm::syntax(line, &format!("EXECSTRING \"{text}\": no control structure or label")));
        }
        if argument(&parsed).is_some() {
            return Err(Alarm::syntax(line, "EXECSTRING within EXECSTRING"));
        }
        if self.assigns_variables_only(&parsed) {
            self.assignment_block(&parsed, cfg, out)
        } else {
            self.prepare_block(&parsed, cfg, programs, out)
        }
    }
}
