//! Blocks that only assign to declared variables (`_DEPTH = RFP - DPR`, `_AT = _AT - _STROKE`),
//! a third of what a cycle's body executes, prepared without the general path.
//!
//! The general path (`Interpreter::prepare_block`) sorts the words into `modal::Words` and
//! passes some twenty stages, each of which does nothing for a block whose words are all
//! assignments to user variables: no G or M function, no axis, no keyword, no block number or
//! label. Such a block runs here: its assignments in block order through the same
//! `modal::assign`, then what the general path does to every block whatever its words: the
//! modal rounding as the corner request, the offsets refreshed, and an `Offsets` item when
//! they changed (a subprogram's return restored a frame, for one).

use super::super::contour::corners::Corner;
use super::super::{Interpreter, Item, modal};
use super::scope::sys_view;
use crate::alarm::Alarm;
use crate::lang::{AddressValue, Block, Word};
use crate::machine_data::MachineConfig;

impl Interpreter {
    /// True if every word of `block` assigns to a declared user variable, without a coordinate
    /// mode, and the block has no number, label or skip mark.
    pub(in crate::interp) fn assigns_variables_only(&self, block: &Block) -> bool {
        block.number.is_none()
            && block.label.is_none()
            && block.skip.is_none()
            && !block.words.is_empty()
            && block.words.iter().all(|w| match w {
                Word::Address { name, value: AddressValue { mode: None, .. }, .. } => {
                    is_plain_variable_name(name) && self.vars.get(name).is_some()
                }
                _ => false,
            })
    }

    /// Prepares a block [`Interpreter::assigns_variables_only`] accepted.
    pub(in crate::interp) fn assignment_block(
        &mut self,
        block: &Block,
        cfg: &MachineConfig,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = block.line;
        let derived = self.trafo.config();
        let cfg = derived.as_deref().unwrap_or(cfg);
        for word in &block.words {
            if let Word::Address { name, indices, value } = word {
                let sys = sys_view!(self, cfg);
                modal::assign(name, indices, &value.expr, cfg, &mut self.vars, &sys, line)?;
            }
        }
        self.corner_request = self.modal.rndm.map(Corner::Round);
        let before = self.offsets_mark();
        self.refresh_offsets(cfg);
        if self.offsets_mark() != before {
            out.push(Item::Offsets { line, offsets: self.shared_offsets() });
        }
        Ok(())
    }
}

/// A name `modal::assign` takes as a user variable once it is declared: not a system
/// variable, R parameter, polynomial (`PO`), chain frame or digital signal.
fn is_plain_variable_name(name: &str) -> bool {
    let r_param = name == "R" || name.strip_prefix('R').is_some_and(|n| n.parse::<i64>().is_ok());
    !name.starts_with('$')
        && !r_param
        && name != "PO"
        && super::super::frames::vars::ChainFrame::of(name).is_none()
        && !super::super::io::is_io_name(name)
}
