//! Computed jump targets: `GOTOF DEST` with `DEF STRING[..] DEST`, `GOTOF "N"<<R10`. The
//! Programming Manual allows a STRING variable (or expression) as the jump destination; its
//! text names a label or a block number.

use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::{Ctx, sys_view};
use crate::interp::eval::value::Value;
use crate::interp::synchronized::MainRunWrite;
use crate::interp::{Interpreter, Item};
use crate::lang::{Goto, GotoKind, JumpTarget, VarType};
use crate::machine_data::MachineConfig;

impl Interpreter {
    /// Executes the jump `goto` of the block at `line`, reading a computed target first.
    pub(in crate::interp) fn jump(
        &mut self,
        goto: &Goto,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        if goto.target == JumpTarget::ProgramStart && self.calls.is_empty() {
            // The main program starts over: workpiece counters and the cycle time see it.
            self.trc.emit_or_defer(Item::MainRunWrite { write: MainRunWrite::StartOver, line }, out);
        }
        let resolved = self.resolve_target(goto, cfg, line)?;
        if let Some(flow) = self.flow.as_mut() {
            flow.jump(resolved.as_ref().unwrap_or(goto))?;
        }
        Ok(())
    }

    /// The literal target of a computed jump; `None` when the target is literal already.
    fn resolve_target(&self, goto: &Goto, cfg: &MachineConfig, line: u32) -> Result<Option<Goto>, Alarm> {
        let sys = sys_view!(self, cfg);
        let ctx = Ctx { vars: &self.vars, sys: &sys };
        let value = match &goto.target {
            // A name that is a STRING variable stands for the text it holds.
            JumpTarget::Label(name) => match self.vars.get(name) {
                Some(var) if matches!(var.ty, VarType::Str(_)) && var.dims.is_empty() => var.data[0].clone(),
                _ => return Ok(None),
            },
            JumpTarget::Expr(e) => eval(e, &ctx, line)?,
            _ => return Ok(None),
        };
        let target = match value {
            // GOTOC goes on with the next block when the text names no target.
            Value::Str(text) if goto.kind == GotoKind::Continue => match target_of_text(&text) {
                Some(t) => t,
                None => {
                    return Ok(Some(Goto { kind: goto.kind, target: JumpTarget::Expr(crate::lang::Expr::Str(text)) }));
                }
            },
            Value::Str(text) => {
                target_of_text(&text).ok_or_else(|| Alarm::jump_not_found(line, &format!("\"{text}\"")))?
            }
            other => {
                return Err(Alarm::type_error(line, &format!("a jump destination is a STRING, not {other:?}")));
            }
        };
        Ok(Some(Goto { kind: goto.kind, target }))
    }
}

/// A jump destination written as text: `N100`, `:100` or `100` is a block number, anything
/// else that is a name is a label. `None` for text that is neither (empty, blanks inside).
pub fn target_of_text(text: &str) -> Option<JumpTarget> {
    let t = text.trim().to_ascii_uppercase();
    let digits = t.strip_prefix('N').or_else(|| t.strip_prefix(':')).unwrap_or(&t);
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        return digits.parse().ok().map(JumpTarget::BlockNumber);
    }
    let name = t.strip_suffix(':').unwrap_or(&t);
    let mut chars = name.chars();
    let first_ok = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    (first_ok && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')).then(|| JumpTarget::Label(name.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_names_a_block_number_or_a_label() {
        assert_eq!(target_of_text("N100"), Some(JumpTarget::BlockNumber(100)));
        assert_eq!(target_of_text(" 20 "), Some(JumpTarget::BlockNumber(20)));
        assert_eq!(target_of_text(":7"), Some(JumpTarget::BlockNumber(7)));
        assert_eq!(target_of_text("marke_2"), Some(JumpTarget::Label("MARKE_2".into())));
        assert_eq!(target_of_text(""), None);
        assert_eq!(target_of_text("TWO WORDS"), None);
    }
}
