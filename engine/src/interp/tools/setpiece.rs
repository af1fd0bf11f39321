//! `SETPIECE(n[, spindle])`: the piece count of count-monitored tools (Function Manual Tool
//! Management / W1 "Tool monitoring", "Workpiece count monitoring"; Programming Manual
//! "Job planning").
//!
//! The control counts workpieces, not tool changes: `SETPIECE(n)` lowers the remaining
//! piece count `$TC_MOP4` by n for every count-monitored cutting edge (`$TC_TP9` bit 1) that
//! was active in the spindle since the last `SETPIECE`; n is 0..32000 (`SETPIECE(0)` only
//! clears that memory). The spindle number is optional; without it, and with 0, the master
//! spindle is meant. Preparation checks the arguments and hands the count to the main run
//! ([`crate::interp::Item::SetPiece`]), which knows the edges used (`channel/tools/monitor.rs`).
//!
//! Decisions where the manuals leave it open: NCTwin has one tool holder per channel, and it
//! is the master spindle's; `SETPIECE` for another spindle of the channel counts nothing (no
//! tool was used in it). The edge still in the spindle when `SETPIECE` runs stays in the
//! memory: it goes on cutting the next workpiece.

use super::super::eval::eval;
use super::super::eval::scope::Ctx;
use crate::alarm::Alarm;
use crate::lang::Expr;

/// The control's largest piece count of one `SETPIECE`.
pub const MAX_PIECES: i64 = 32_000;

/// A `SETPIECE` as written: the pieces and the spindle number (`None` or 0: the master).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SetPiece {
    pub pieces: u32,
    pub spindle: Option<u32>,
}

/// Reads the arguments of `SETPIECE(n[, spindle])`.
pub(in crate::interp) fn statement(args: &[Expr], ctx: &Ctx, line: u32) -> Result<SetPiece, Alarm> {
    let int = |e: &Expr| -> Result<i64, Alarm> {
        let v = eval(e, ctx, line)?.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?;
        if v.fract() != 0.0 || !v.is_finite() {
            return Err(Alarm::value_out_of_range(line, &format!("SETPIECE: {v} is no whole number")));
        }
        Ok(v as i64)
    };
    let (pieces, spindle) = match args {
        [n] => (int(n)?, None),
        [n, s] => (int(n)?, Some(int(s)?)),
        _ => return Err(Alarm::syntax(line, "SETPIECE(pieces[, spindle number])")),
    };
    if !(0..=MAX_PIECES).contains(&pieces) {
        return Err(Alarm::value_out_of_range(line, &format!("SETPIECE({pieces}) (0..{MAX_PIECES})")));
    }
    let spindle = match spindle {
        None | Some(0) => None,
        Some(s) if (1..=32).contains(&s) => Some(s as u32),
        Some(s) => return Err(Alarm::value_out_of_range(line, &format!("SETPIECE spindle {s}"))),
    };
    Ok(SetPiece { pieces: pieces as u32, spindle })
}
