//! How many elements of MD28250 `$MC_MM_NUM_SYNC_ELEMENTS` a synchronized action occupies
//! while it is active. The control sizes the memory of synchronized actions in elements, not
//! in actions; the Function Manual (Synchronized actions, "Configuration") gives guide values
//! for the count, which NCTwin takes as the count itself:
//!
//! - an action takes at least 4 elements;
//! - each operand of the condition 1;
//! - each action at least 1, an assignment 2;
//! - each further operand of a compound expression 1.
//!
//! So `ID=1 WHENEVER $AA_IM[X]>20 DO $AC_OVR=0` takes 4 (2 operands, 1 assignment), and
//! `DO $AC_MARKER[1]=$AC_MARKER[1]+1` takes 4 too (1 assignment of 2 operands: 2 + 1 = 3,
//! raised to the minimum). A variable's computed index counts its operands as further
//! operands; a constant index is part of the variable. The actions of a technology cycle
//! (`DO NAME`) are counted as one action: the cycle's blocks run one at a time.

use super::compile::{CExpr, SyncAct, SyncDef, SyncVar};

/// The least number of elements an action takes.
pub const MIN_ELEMENTS: usize = 4;

impl SyncDef {
    /// The elements of MD28250 this action occupies while active (see the module's doc).
    pub fn elements(&self) -> usize {
        let condition = self.condition.as_ref().map_or(0, operands);
        let actions: usize = self.actions.iter().map(action_elements).sum();
        (condition + actions).max(MIN_ELEMENTS)
    }
}

/// An action's elements: 2 for an assignment, 1 for any other, plus 1 for each operand of its
/// value beyond the first.
fn action_elements(act: &SyncAct) -> usize {
    let further = |e: &CExpr| operands(e).saturating_sub(1);
    match act {
        SyncAct::Set(_, value) => 2 + further(value),
        SyncAct::Aux { value, .. } | SyncAct::Command { value, .. } | SyncAct::Preset { value, .. } => {
            1 + further(value)
        }
        SyncAct::WaitMarker { marker, .. } => 1 + further(marker),
        SyncAct::DelDtg | SyncAct::StopReOf | SyncAct::RDisable | SyncAct::Cycle(_) => 1,
    }
}

/// The operands of an expression: its constants and variables (a variable with a computed
/// index also the index's operands).
fn operands(e: &CExpr) -> usize {
    match e {
        CExpr::Num(_) => 1,
        CExpr::Var(v) => 1 + index(v).map_or(0, operands),
        CExpr::Neg(a) | CExpr::Not(a) => operands(a),
        CExpr::Bin(_, a, b) => operands(a) + operands(b),
        CExpr::Func(_, args) => args.iter().map(operands).sum(),
    }
}

/// A variable's computed index (none when the index is a constant or an axis).
fn index(v: &SyncVar) -> Option<&CExpr> {
    match v {
        SyncVar::AcTimer(i)
        | SyncVar::AcMarker(i)
        | SyncVar::AcParam(i)
        | SyncVar::R(i)
        | SyncVar::AIn(i)
        | SyncVar::AOut(i)
        | SyncVar::AIna(i)
        | SyncVar::AOuta(i)
        | SyncVar::AaS(i) => (!matches!(**i, CExpr::Num(_))).then_some(&**i),
        _ => None,
    }
}
