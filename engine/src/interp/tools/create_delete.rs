//! `NEWT("name"[, duplo])` creates a tool and returns its T number; `DELT("name"[, duplo])`
//! deletes one (Programming Manual Job Planning, tool management functions).
//!
//! Both act through the data writes of the block, like a program's `$TC_TP` write: the channel
//! applies them when the block has been prepared, so the next block sees the new tool list.
//!
//! Decisions where the manual is silent or NCTwin models less:
//! * The tool store has no separate "tool management on" switch (names and magazines make it
//!   managed, [`crate::machine_data::tools_list::ToolList::is_managed`]), so NEWT and DELT work
//!   in either case: a tool is a name, a duplo number and its T number.
//! * The T number NEWT gives is the lowest number no tool (data or cutting edges) uses yet.
//! * Without a duplo number NEWT gives the next one of that name (highest + 1, 1 for the
//!   first); a name with that duplo already present is alarm 17230.
//! * The new tool has no cutting edges: the program writes `$TC_DP..[t,1]` itself, as with a
//!   tool created from the HMI. Until then it runs with D0.
//! * DELT removes the tool's data, cutting edges, monitoring data and its magazine place; the
//!   tool in the spindle or the one prepared for the next change is alarm 17200, an unknown
//!   name 17191.

use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::Ctx;
use crate::interp::eval::value::Value;
use crate::lang::Expr;
use crate::machine_data::MAX_TOOL_NUMBER;
use crate::machine_data::MachineConfig;

/// Prefix of the data-write entry of DELT, followed by the T number.
pub const DELT: &str = "DELT:";

/// The name and the duplo number (if programmed) of a NEWT or DELT call.
fn name_and_duplo(what: &str, args: &[Expr], ctx: &Ctx, line: u32) -> Result<(String, Option<i64>), Alarm> {
    let usage = || Alarm::syntax(line, &format!("{what} takes a tool name and optionally a duplo number"));
    let (Some(name), rest) = (args.first(), args.get(1..).unwrap_or(&[])) else {
        return Err(usage());
    };
    if rest.len() > 1 {
        return Err(usage());
    }
    let name = match eval(name, ctx, line)? {
        Value::Str(s) if !s.is_empty() => s,
        other => return Err(Alarm::type_error(line, &format!("{what} needs a tool name, not {other:?}"))),
    };
    let duplo = match rest.first() {
        None => None,
        Some(Expr::Call(n, a)) if n == "_OMITTED" && a.is_empty() => None,
        Some(e) => Some(eval(e, ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?),
    };
    if duplo.is_some_and(|d| !(1..=32000).contains(&d)) {
        return Err(Alarm::value_out_of_range(
            line,
            &format!("{what}: duplo number {} (1..32000)", duplo.unwrap_or(0)),
        ));
    }
    Ok((name, duplo))
}

/// The T number in a pending data write `$TC_TPn[t]=...` of the same block.
fn pending_tool(text: &str) -> Option<u32> {
    let rest = text.strip_prefix("$TC_TP")?;
    let open = rest.find('[')?;
    let close = rest.find(']')?;
    rest.get(open + 1..close)?.parse().ok()
}

/// `NEWT(...)`: the new tool's T number and the data writes that create it. `pending` are the
/// data writes of the block not yet applied (two NEWT in one block get two numbers).
pub(in crate::interp) fn newt(
    args: &[Expr],
    ctx: &Ctx,
    cfg: &MachineConfig,
    pending: &[(u32, String)],
    line: u32,
) -> Result<(u32, Vec<String>), Alarm> {
    let (name, duplo) = name_and_duplo("NEWT", args, ctx, line)?;
    let taken = |t: u32| {
        cfg.tool_list.tools.contains_key(&t)
            || cfg.tools.range((t, 0)..=(t, u32::MAX)).next().is_some()
            || pending.iter().any(|(_, w)| pending_tool(w) == Some(t))
    };
    let pending_duplos = pending.iter().filter_map(|(_, w)| {
        let t = pending_tool(w)?;
        (w.starts_with("$TC_TP2[") && w.ends_with(&format!("=\"{name}\"")))
            .then(|| pending.iter().find(|(_, d)| d.starts_with(&format!("$TC_TP1[{t}]="))))
            .flatten()
            .and_then(|(_, d)| d.split('=').nth(1)?.parse::<f64>().ok())
            .map(|d| d as i64)
    });
    let mut duplos: Vec<i64> =
        cfg.tool_list.tools.values().filter(|e| e.name == name).map(|e| e.duplo).chain(pending_duplos).collect();
    duplos.sort_unstable();
    let duplo = match duplo {
        Some(d) if duplos.contains(&d) => return Err(Alarm::duplo_assigned(line, &name, d)),
        Some(d) => d,
        None => duplos.last().map_or(1, |d| d + 1),
    };
    let t = (1..=MAX_TOOL_NUMBER as u32)
        .find(|t| !taken(*t))
        .ok_or_else(|| Alarm::value_out_of_range(line, &format!("NEWT(\"{name}\"): no free T number left")))?;
    Ok((t, vec![format!("$TC_TP1[{t}]={duplo}"), format!("$TC_TP2[{t}]=\"{name}\"")]))
}

/// `DELT(...)`: the data-write entry that deletes the tool. `in_use` are the tool in the
/// spindle and the one prepared for the next change.
pub(in crate::interp) fn delt(
    args: &[Expr],
    ctx: &Ctx,
    cfg: &MachineConfig,
    in_use: [u32; 2],
    line: u32,
) -> Result<String, Alarm> {
    let (name, duplo) = name_and_duplo("DELT", args, ctx, line)?;
    let mut named = cfg.tool_list.tools.values().filter(|e| e.name == name && duplo.is_none_or(|d| e.duplo == d));
    let (Some(tool), None) = (named.next(), named.next()) else {
        // Several duplos of the name and none programmed: which one is meant is unknown.
        let shown = duplo.map_or(name.clone(), |d| format!("{name} duplo {d}"));
        return Err(match cfg.tool_list.tools.values().any(|e| e.name == name) {
            true if duplo.is_none() => Alarm::syntax(line, &format!("DELT(\"{name}\"): several duplos, name one")),
            _ => Alarm::unknown_tool_name(line, &shown),
        });
    };
    if in_use.contains(&tool.number) {
        return Err(Alarm::tool_in_use(line, tool.number));
    }
    Ok(format!("{DELT}{}", tool.number))
}

#[cfg(test)]
mod tests {
    use super::pending_tool;

    #[test]
    fn a_pending_tool_write_names_its_t_number() {
        assert_eq!(pending_tool("$TC_TP2[12]=\"DRILL\""), Some(12));
        assert_eq!(pending_tool("$TC_DP1[12,1]=120"), None);
    }
}
