//! Tool selection and tool change as the control's tool management does them (W1, Function
//! Manual Tool Management).
//!
//! `T=n`, `T="name"` and `TCA("name", duplo)` program a tool; MD22550 TOOL_CHANGE_MODE decides
//! whether it is changed at once (0) or only prepared until the M function of MD22560 (M6)
//! changes it (1). A change puts the tool into the spindle with its first cutting edge (MD20270
//! CUTTING_EDGE_DEFAULT = 1) and, where `$MC_TOOL_CHANGE_TIME` is set, the program waits that
//! long (the PLC's change). `$P_TOOLNO` is the tool in the spindle, `$P_TOOLP` the programmed
//! (prepared) one.
//!
//! A name selects the enabled tool of that name with the lowest duplo number
//! ([`crate::machine_data::tools_list::ToolList::by_name`]); an unknown name is alarm 17191,
//! a name whose duplos are all disabled 22069 (the tool group has no tool ready). A tool that
//! tool monitoring disabled while the program ran is seen by the next `T="name"` prepared
//! after it: block preparation runs ahead, so a program that must see it waits with `STOPRE`. `TCA` takes the named duplo whatever its state.

use super::super::eval::eval;
use super::super::eval::scope::Ctx;
use super::super::eval::value::Value;
use super::super::{Interpreter, Item};
use crate::alarm::Alarm;
use crate::interp::calls::Programs;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;
use crate::machine_data::tools_list::NameError;

/// A tool programmed by name: `T="name"` (duplo `None`: the list's choice) or `TCA("name",
/// duplo)`.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedTool {
    pub name: String,
    pub duplo: Option<i64>,
}

/// `T=<expr>` when the expression is a string: the tool's name. `None` for a number.
pub(in crate::interp) fn named_t(expr: &Expr, ctx: &Ctx, line: u32) -> Result<Option<NamedTool>, Alarm> {
    if matches!(expr, Expr::Number(_)) {
        return Ok(None);
    }
    Ok(match eval(expr, ctx, line)? {
        Value::Str(name) => Some(NamedTool { name, duplo: None }),
        _ => None,
    })
}

/// `TCA("name", duplo[, spindle])`: change to that duplo whatever its state.
pub(in crate::interp) fn tca(args: &[Expr], ctx: &Ctx, line: u32) -> Result<NamedTool, Alarm> {
    let (Some(name), Some(duplo)) = (args.first(), args.get(1)) else {
        return Err(Alarm::syntax(line, "TCA takes a tool name, a duplo number and optionally a spindle"));
    };
    let name = match eval(name, ctx, line)? {
        Value::Str(s) => s,
        other => return Err(Alarm::type_error(line, &format!("TCA needs a tool name, not {other:?}"))),
    };
    let duplo = eval(duplo, ctx, line)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    Ok(NamedTool { name, duplo: Some(duplo) })
}

/// The tool number a name stands for.
fn resolve(named: &NamedTool, cfg: &MachineConfig, line: u32) -> Result<u32, Alarm> {
    let list = &cfg.tool_list;
    match named.duplo {
        Some(duplo) => list
            .tools
            .values()
            .find(|e| e.name == named.name && e.duplo == duplo)
            .map(|e| e.number)
            .ok_or_else(|| Alarm::unknown_tool_name(line, &format!("{} duplo {duplo}", named.name))),
        None => list.by_name(&named.name).map_err(|e| match e {
            NameError::Unknown => Alarm::unknown_tool_name(line, &named.name),
            NameError::Disabled => Alarm::no_usable_tool(line, &named.name),
        }),
    }
}

/// `GETT("name"[, duplo])`: the tool number of that tool, -1 if there is none (with the
/// duplo omitted: the tool `T="name"` would select).
pub(in crate::interp) fn gett(cfg: &MachineConfig, args: &[Value], line: u32) -> Result<Value, Alarm> {
    let (name, duplo) = match args {
        [Value::Str(n)] => (n, None),
        [Value::Str(n), d] => (n, Some(d.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?)),
        _ => return Err(Alarm::syntax(line, "GETT takes a tool name and optionally a duplo number")),
    };
    let named = NamedTool { name: name.clone(), duplo };
    Ok(Value::Int(resolve(&named, cfg, line).map_or(-1, i64::from)))
}

/// `$P_TOOLEXIST[t]`: whether tool `t` exists (has tool data or cutting edges), as programs
/// check before they select a tool that a presetter may not have loaded.
pub(in crate::interp) fn tool_exists(cfg: &MachineConfig, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let t = match indices {
        [t] => t.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?,
        _ => return Err(Alarm::index_error(line, "$P_TOOLEXIST", "needs one index (the T number)")),
    };
    Ok(Value::Bool(u32::try_from(t).is_ok_and(|t| t != 0 && exists(cfg, t))))
}

/// A program's read of tool-management data (`$TC_TP2[t]`, `$TC_MPP6[m,p]`, ...).
pub(in crate::interp) fn read(cfg: &MachineConfig, name: &str, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let mut idx = [0u32; 2];
    let two = !name.starts_with("$TC_TP") && !name.starts_with("$TC_MAP");
    if indices.len() != 1 + usize::from(two) {
        let what = if two { "needs two indices" } else { "needs one index" };
        return Err(Alarm::index_error(line, name, what));
    }
    for (slot, v) in idx.iter_mut().zip(indices) {
        let i = v.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
        *slot = u32::try_from(i).map_err(|_| Alarm::index_error(line, name, &format!("index {i} out of range")))?;
    }
    let v = cfg.tool_list.read(name, idx[0], idx[1]).ok_or_else(|| Alarm::unknown_name(line, name))?;
    Ok(match v {
        crate::machine_data::Value::Str(s) => Value::Str(s),
        crate::machine_data::Value::Real(r) => Value::Real(r),
        crate::machine_data::Value::Int(i) => Value::Int(i),
        crate::machine_data::Value::Bool(b) => Value::Bool(b),
    })
}

/// Whether tool `t` exists: cutting edges or tool data.
fn exists(cfg: &MachineConfig, t: u32) -> bool {
    cfg.tool_list.tools.contains_key(&t)
}

impl Interpreter {
    /// T, T="name", TCA, the tool-change M function and D of a block, in that order: a D in
    /// the block of the change applies to the new tool.
    pub(in crate::interp) fn select_tool(
        &mut self,
        words: &super::super::modal::Words,
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let programmed = match (&words.tool, &words.tool_name) {
            (&Some(t), _) => {
                if t != 0 && !exists(cfg, t) {
                    return Err(Alarm::illegal_t(line, t));
                }
                Some(t)
            }
            (None, Some(named)) => Some(resolve(named, cfg, line)?),
            (None, None) => None,
        };
        // TCA changes at once in either mode.
        let at_once = !cfg.tool_change.with_m || words.tool_name.as_ref().is_some_and(|n| n.duplo.is_some());
        if let Some(t) = programmed {
            self.offsets.prepared = t;
            if at_once {
                self.change_tool(t, cfg, line, out)?;
            }
        }
        if words.tool_change
            && let Some(cycle) = self.replacing_cycle(cfg, programs)
        {
            // MD10715/10716: the M function calls the change cycle after the block; its own M6
            // (at any level below it) changes.
            self.tool_cycle = Some(cycle);
        } else if words.tool_change && cfg.tool_change.with_m {
            self.change_tool(self.offsets.prepared, cfg, line, out)?;
        }
        if let Some(d) = words.edge {
            if d != 0 && cfg.edge(self.offsets.t, d).is_none() {
                return Err(Alarm::illegal_d(line, d));
            }
            self.offsets.d = d;
        }
        Ok(())
    }

    /// The change cycle the M function calls: configured, in the program store, and not
    /// already running (its own M6 changes).
    fn replacing_cycle(&self, cfg: &MachineConfig, programs: &Programs) -> Option<String> {
        let cycle = cfg.tool_change.m_cycle.as_ref()?;
        let inside = self.level().is_some_and(|l| l.within(cycle));
        (!inside && programs.contains_key(cycle)).then(|| cycle.clone())
    }

    /// The change cycle a block's M6 asked for (taken once, by the block's calls).
    pub(in crate::interp) fn take_tool_cycle(&mut self) -> Option<String> {
        self.tool_cycle.take()
    }

    /// Puts tool `t` into the spindle with its first cutting edge; a different tool takes the
    /// change time.
    fn change_tool(&mut self, t: u32, cfg: &MachineConfig, line: u32, out: &mut Vec<Item>) -> Result<(), Alarm> {
        let changes = t != self.offsets.t;
        self.offsets.t = t;
        if cfg.flat_d {
            // Flat D numbers: the active D is independent of the tool (`flat_d.rs`).
            return self.tool_change_time(changes, cfg, line, out);
        }
        // MD20270 CUTTING_EDGE_DEFAULT = 1: a new tool brings its first cutting edge; a tool
        // that has edges but no D1 cannot (17180), one without any edges runs with D0.
        let has_edges = cfg.tools.range((t, 0)..=(t, u32::MAX)).next().is_some();
        self.offsets.d = if t == 0 || !has_edges { 0 } else { 1 };
        if has_edges && !cfg.tools.contains_key(&(t, 1)) {
            return Err(Alarm::illegal_d(line, 1));
        }
        self.tool_change_time(changes, cfg, line, out)
    }

    /// A change of the tool in the spindle takes `$MC_TOOL_CHANGE_TIME`.
    fn tool_change_time(
        &mut self,
        changes: bool,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let seconds = cfg.tool_change.seconds;
        if changes && seconds > 0.0 {
            self.trc.emit_or_defer(Item::Dwell { seconds, line }, out);
        }
        Ok(())
    }
}
