//! `WORKPIECE(ref, spindle, _, "type", flags, Z0, Z1, ZB, v1, v2, v3, v4)`: the blank of the
//! simulation's material removal, read into a [`Request`] (the parameter list and the
//! decisions are in `stock/blank.rs`). The main run places it in the WCS of the block's frame.

use super::calls::targets::is_omitted;
use super::eval::eval;
use super::eval::scope::Ctx;
use crate::alarm::Alarm;
use crate::lang::Expr;
use crate::stock::blank::Request;

/// Most parameters `WORKPIECE` takes.
const MAX_ARGS: usize = 12;

/// The blank `args` describe; a wrong one raises 12560 (value out of range) naming the problem.
pub(super) fn read(args: &[Expr], ctx: &Ctx, line: u32) -> Result<Request, Alarm> {
    if args.len() > MAX_ARGS {
        return Err(Alarm::too_many_arguments(line, "WORKPIECE"));
    }
    let arg = |i: usize| args.get(i).filter(|e| !is_omitted(e));
    let kind = match arg(3) {
        Some(e) => eval(e, ctx, line)?.as_text().to_ascii_uppercase(),
        None => String::new(),
    };
    let number =
        |e: &Expr| -> Result<f64, Alarm> { eval(e, ctx, line)?.as_f64().map_err(|e| Alarm::type_error(line, &e.0)) };
    let flags = match arg(4) {
        Some(e) => number(e)?,
        None => 0.0,
    };
    if flags.fract() != 0.0 || !(0.0..=65535.0).contains(&flags) {
        return Err(Alarm::value_out_of_range(line, &format!("WORKPIECE: flags {flags}")));
    }
    let mut numbers = Vec::with_capacity(MAX_ARGS);
    for i in 5..args.len() {
        numbers.push(match arg(i) {
            Some(e) => Some(number(e)?),
            None => None,
        });
    }
    Request::from_workpiece(kind.trim(), flags as i64, &numbers).map_err(|m| Alarm::value_out_of_range(line, &m))
}
