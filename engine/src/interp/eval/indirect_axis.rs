//! Indirect axis addressing `AX[expr]=value`: the axis a block moves is named by an expression
//! of type AXIS (`AX[$P_AXN3]=-5`, `AX[AXNAME("Z")]=...`), as the standard cycles use it to move
//! the working plane's axes whatever the plane.

use crate::alarm::Alarm;
use crate::interp::eval::scope::{Ctx, SysView};
use crate::interp::eval::value::Value;
use crate::interp::eval::vars::Variables;
use crate::lang::Expr;

/// The channel axis `AX[index]` names.
pub(in crate::interp) fn resolve(index: &Expr, vars: &Variables, sys: &SysView, line: u32) -> Result<usize, Alarm> {
    let name = match index {
        // A bare axis name: `AX[X]`.
        Expr::Var { name, indices } if indices.is_empty() && vars.get(name).is_none() && !name.starts_with('$') => {
            name.to_string()
        }
        e => match super::super::eval::eval(e, &Ctx { vars, sys }, line)? {
            Value::Axis(a) | Value::Str(a) => a,
            _ => return Err(Alarm::type_error(line, "AX[...] needs an axis name")),
        },
    };
    sys.cfg.program_axis(&name).ok_or_else(|| Alarm::unknown_name(line, &format!("AX[{name}]")))
}
