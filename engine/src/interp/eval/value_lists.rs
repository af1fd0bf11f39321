//! Value lists for arrays (Programming Manual, job planning: "Definition and initialization of
//! array variables"): `SET(v1, v2, ...)` writes its values one after another from an element on
//! (the last index running fastest), an empty position keeping the element's value;
//! `REP(v)` writes `v` into every element from there to the end, `REP(v, n)` into `n` elements.
//! Both serve in `DEF` (from the first element) and in assignments `A[2]=SET(..)`.

use crate::alarm::Alarm;
use crate::interp::eval::value::Value;
use crate::interp::eval::vars::Variable;
use crate::lang::ast::Expr;

/// A value list: the parser's `SET(...)` (in DEF: the bare list) or `REP(...)`.
pub(in crate::interp) enum List<'a> {
    /// Values in order; `None` where a position was left empty.
    Set(Vec<Option<&'a Expr>>),
    /// One value, repeated to the end or `count` times.
    Rep { value: &'a Expr, count: Option<&'a Expr> },
}

impl<'a> List<'a> {
    /// The value list an assignment's right-hand side is, if it is one.
    pub(in crate::interp) fn of_expr(expr: &'a Expr) -> Option<List<'a>> {
        match expr {
            Expr::Call(f, args) if f == "SET" => Some(List::Set(args.iter().map(present).collect())),
            Expr::Call(f, args) if f == "REP" && matches!(args.len(), 1 | 2) => {
                Some(List::Rep { value: &args[0], count: args.get(1) })
            }
            _ => None,
        }
    }

    /// A DEF's initial values: `REP(..)`, else the list of `SET(..)` or `(..)` or one value.
    pub(in crate::interp) fn of_init(init: &'a [Expr]) -> List<'a> {
        match init {
            [single] => List::of_expr(single).unwrap_or(List::Set(vec![present(single)])),
            values => List::Set(values.iter().map(present).collect()),
        }
    }

    /// Writes the list into `var` from flat element `start` on; `eval` gives each value.
    /// More values than elements left is alarm 12260, as in a DEF.
    pub(in crate::interp) fn write(
        &self,
        var: &mut Variable,
        start: usize,
        name: &str,
        line: u32,
        mut eval: impl FnMut(&Expr) -> Result<Value, Alarm>,
    ) -> Result<(), Alarm> {
        let room = var.data.len() - start;
        let ty = var.ty;
        let convert = |v: Value| v.convert(ty).map_err(|e| Alarm::type_error(line, &e.0));
        match self {
            List::Set(values) => {
                if values.len() > room {
                    return Err(Alarm::too_many_initial_values(line, name));
                }
                for (slot, e) in var.data[start..].iter_mut().zip(values) {
                    if let Some(e) = e {
                        *slot = convert(eval(e)?)?;
                    }
                }
            }
            List::Rep { value, count } => {
                let n = match count {
                    None => room,
                    Some(c) => {
                        let n = eval(c)?.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
                        usize::try_from(n).ok().filter(|&n| n <= room).ok_or_else(|| {
                            Alarm::too_many_initial_values(
                                line,
                                &format!("{name} (REP count {n}, {room} elements left)"),
                            )
                        })?
                    }
                };
                let v = convert(eval(value)?)?;
                var.data[start..start + n].iter_mut().for_each(|slot| *slot = v.clone());
            }
        }
        Ok(())
    }
}

/// The parser marks a position left empty in an argument list with an internal call.
fn present(e: &Expr) -> Option<&Expr> {
    (!matches!(e, Expr::Call(n, a) if n == "_OMITTED" && a.is_empty())).then_some(e)
}
