//! DELOBJ(type[, start, end]): deleting data objects from a program, as a statement (errors
//! are alarms) or as a function whose value reports the outcome (`IF DELOBJ(...) < 0`).
//!
//! The types of the Job Planning manual this product holds: `KIN_CHAIN_ELEM` and `TRAFO_DATA`
//! (deleted whole, active with NEWCONF or reset) and `TOOLCARRIER` (toolholders `start..=end`,
//! by their number; acting at once like a `$TC_CARR` write). The function's negative values
//! are this product's choice (the consulted sources only show that a result < 0 is an error).

use crate::alarm::Alarm;
use crate::interp::DELOBJ;
use crate::interp::eval::eval;
use crate::interp::eval::scope::Ctx;
use crate::lang::Expr;

/// The function value: the object type does not exist.
pub const UNKNOWN_TYPE: i64 = -1;
/// The function value: the index range is invalid (or not modelled for the type).
pub const BAD_RANGE: i64 = -2;

/// Why a DELOBJ cannot run, with the text of the alarm the statement form raises.
enum Refusal {
    UnknownType(String),
    BadRange(String),
}

/// The data-write entry `DELOBJ:type[:start:end]` of a DELOBJ, or why it cannot run.
fn entry(args: &[Expr], ctx: &Ctx, line: u32) -> Result<Result<String, Refusal>, Alarm> {
    let Some((kind, range)) = args.split_first() else {
        return Err(Alarm::syntax(line, "DELOBJ needs the object type"));
    };
    let kind = eval(kind, ctx, line)?.as_text().to_ascii_uppercase();
    let mut bounds = Vec::new();
    for e in range {
        if matches!(e, Expr::Call(n, a) if n == "_OMITTED" && a.is_empty()) {
            bounds.push(None);
            continue;
        }
        let v = eval(e, ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
        bounds.push(Some(v));
    }
    Ok(match kind.as_str() {
        "KIN_CHAIN_ELEM" | "TRAFO_DATA" if bounds.iter().all(Option::is_none) => Ok(format!("{DELOBJ}{kind}")),
        "KIN_CHAIN_ELEM" | "TRAFO_DATA" => Err(Refusal::BadRange(format!(
            "DELOBJ(\"{kind}\", ...): index ranges of chain data are not modelled, only the whole type"
        ))),
        "TOOLCARRIER" if bounds.len() <= 2 => {
            let start = bounds.first().copied().flatten().unwrap_or(1);
            let end = bounds.get(1).copied().flatten().unwrap_or(i64::from(u32::MAX));
            if start < 1 || end < start {
                return Ok(Err(Refusal::BadRange(format!("DELOBJ(\"TOOLCARRIER\", {start}, {end})"))));
            }
            Ok(format!("{DELOBJ}TOOLCARRIER:{start}:{}", end.min(i64::from(u32::MAX))))
        }
        "TOOLCARRIER" => {
            return Err(Alarm::syntax(line, "DELOBJ(\"TOOLCARRIER\", start, end): no initialization value"));
        }
        _ => Err(Refusal::UnknownType(format!("DELOBJ(\"{kind}\"): KIN_CHAIN_ELEM, TRAFO_DATA or TOOLCARRIER"))),
    })
}

/// The statement `DELOBJ(...)`: its data-write entry; a refusal is alarm 12560.
pub(in crate::interp) fn statement(args: &[Expr], ctx: &Ctx, line: u32) -> Result<String, Alarm> {
    match entry(args, ctx, line)? {
        Ok(write) => Ok(write),
        Err(Refusal::UnknownType(m) | Refusal::BadRange(m)) => Err(Alarm::value_out_of_range(line, &m)),
    }
}

/// The function `DELOBJ(...)`: its value (0 done, [`UNKNOWN_TYPE`], [`BAD_RANGE`]) and the
/// data-write entry when it deletes.
pub(in crate::interp) fn function(args: &[Expr], ctx: &Ctx, line: u32) -> Result<(i64, Option<String>), Alarm> {
    Ok(match entry(args, ctx, line)? {
        Ok(write) => (0, Some(write)),
        Err(Refusal::UnknownType(_)) => (UNKNOWN_TYPE, None),
        Err(Refusal::BadRange(_)) => (BAD_RANGE, None),
    })
}
