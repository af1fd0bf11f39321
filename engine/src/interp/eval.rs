//! Evaluation of expressions: operators with the control's semantics, the predefined
//! functions, variables and system variables.

pub(super) mod assignment_block;
pub(super) mod cycle_constants;
pub(super) mod cycle_vars;
pub(super) mod indirect_axis;
pub(super) mod isvar;
pub(crate) mod machine_data;
pub(super) mod name_hash;
pub(crate) mod nc_constants;
pub(super) mod numeric;
pub mod process_vars;
pub mod run_vars;
pub(super) mod scope;
pub(super) mod strings;
pub mod value;
pub(super) mod value_lists;
pub mod vars;

use std::cmp::Ordering;

use super::eval::value::Value;
use super::eval::vars::Variables;
use super::frames::frame::{self, Frame, GeoAxes};
use crate::alarm::Alarm;
use crate::lang::{BinOp, Expr, UnOp};
use crate::machine_data::FrameAngles;

/// What an expression can read besides its literals.
pub trait Scope {
    fn vars(&self) -> &Variables;
    /// A system variable (`$AA_IM[X]`, `$P_TOOLNO`, ...) with evaluated indices.
    fn system(&self, name: &str, indices: &[Value], line: u32) -> Result<Value, Alarm>;
    /// True if `name` is an axis of the channel (a bare axis name evaluates to an AXIS value).
    fn is_axis(&self, name: &str) -> bool {
        self.axis_index(name).is_some()
    }
    /// The channel axis a program name refers to.
    fn axis_index(&self, name: &str) -> Option<usize>;
    /// The geometry axes (for frame functions).
    fn geo_axes(&self) -> GeoAxes;
    /// The geometry axis perpendicular to the working plane (G17: Z).
    fn applicate(&self) -> usize {
        2
    }
    /// How frame rotation angles are written (MD10600).
    fn frame_angles(&self) -> FrameAngles {
        FrameAngles::Rpy
    }
}

/// Relative precision of comparisons: the control compares REAL values for relative, not
/// absolute, equality so that decimal fractions compare as written.
const REL_EQ: f64 = 1e-12;

/// Evaluates `expr`; errors become alarms of `line`.
///
/// Recursive, one call per level of the tree (at most [`crate::lang::MAX_EXPR_DEPTH`]): only
/// the small frames of this function and of [`eval_all`] stay on the stack while operands are
/// evaluated; the work on the values (operators, functions, variables) is done in functions
/// called after, whose larger frames never pile up.
pub fn eval(expr: &Expr, scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    match expr {
        Expr::RParam(index) => r_param(eval(index, scope, line)?, scope, line),
        Expr::Var { name, indices } => variable(name, &eval_indices(name, indices, scope, line)?, scope, line),
        Expr::Unary(op, e) => unary(*op, eval(e, scope, line)?, line),
        Expr::Binary(op, a, b) => operate(*op, eval(a, scope, line)?, eval(b, scope, line)?, scope, line),
        Expr::Call(name, args) => apply(name, &eval_all(args, scope, line)?, scope, line),
        Expr::Number(_) | Expr::Str(_) | Expr::Bool(_) => Ok(literal(expr)),
    }
}

/// The value of a number, string or BOOL literal.
fn literal(expr: &Expr) -> Value {
    match expr {
        Expr::Number(n) => numeric::number(*n).into(),
        Expr::Str(s) => Value::Str(s.clone()),
        Expr::Bool(b) => Value::Bool(*b),
        _ => unreachable!("not a literal: {expr:?}"),
    }
}

/// A binary operator (frame chain included) on evaluated operands.
fn operate(op: BinOp, a: Value, b: Value, scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    match op {
        BinOp::Chain => chain(a, b, scope, line),
        op => binary(op, a, b, line),
    }
}

/// A predefined function on evaluated arguments.
fn apply(name: &str, vals: &[Value], scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    match FRAME_FUNCTIONS.contains(&name) {
        true => frame_function(name, vals, scope, line),
        // GETT and CHKDNO read the tool list, which the scope holds.
        false if name == "GETT" || name == "CHKDNO" => scope.system(name, vals, line),
        false if name == "ISVAR" => isvar::isvar(scope, vals, line),
        false => call(name, vals, line),
    }
}

/// The values of `exprs` in order (a loop, not iterator adapters: fewer frames in the
/// recursion of debug builds).
fn eval_all(exprs: &[Expr], scope: &dyn Scope, line: u32) -> Result<Vec<Value>, Alarm> {
    let mut out = Vec::with_capacity(exprs.len());
    for e in exprs {
        out.push(eval(e, scope, line)?);
    }
    Ok(out)
}

/// The values of a variable's indices; a system variable's bare names among them are keywords
/// (`$P_UIFR[1,X,TR]`).
fn eval_indices(name: &str, indices: &[Expr], scope: &dyn Scope, line: u32) -> Result<Vec<Value>, Alarm> {
    if !name.starts_with('$') {
        return eval_all(indices, scope, line);
    }
    let mut out = Vec::with_capacity(indices.len());
    for e in indices {
        out.push(match keyword(e, scope) {
            Some(name) => Value::Str(name.to_string()),
            None => eval(e, scope, line)?,
        });
    }
    Ok(out)
}

/// The name of a bare name that is neither a variable nor an axis.
fn keyword<'e>(e: &'e Expr, scope: &dyn Scope) -> Option<&'e str> {
    match e {
        Expr::Var { name, indices }
            // A `$` name is a system variable read (`$TC_DP6[$P_TOOLNO,$P_TOOL]`), not a keyword.
            if indices.is_empty() && !name.starts_with('$') && scope.vars().get(name).is_none() && !scope.is_axis(name) =>
        {
            Some(name)
        }
        _ => None,
    }
}

/// `R[n]`.
fn r_param(n: Value, scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    let n = n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    let r = &scope.vars().r;
    let v =
        usize::try_from(n).ok().and_then(|i| r.get(i)).ok_or_else(|| Alarm::unknown_name(line, &format!("R{n}")))?;
    Ok(Value::Real(*v))
}

/// A system variable, user variable or axis name with evaluated indices.
fn variable(name: &str, idx: &[Value], scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    if name.starts_with('$') {
        if let Some(v) = nc_constants::constant(name).filter(|_| idx.is_empty()) {
            return Ok(v);
        }
        return scope.system(name, idx, line);
    }
    if let Some(var) = scope.vars().get(name) {
        let ints =
            idx.iter().map(|v| v.as_i64()).collect::<Result<Vec<_>, _>>().map_err(|e| Alarm::type_error(line, &e.0))?;
        let i = var.index(&ints).map_err(|e| Alarm::index_error(line, name, &e.0))?;
        return Ok(var.data[i].clone());
    }
    if idx.is_empty() && scope.is_axis(name) {
        return Ok(Value::Axis(name.to_string()));
    }
    if let Some(v) = cycle_constants::constant(name).filter(|_| idx.is_empty()) {
        return Ok(v);
    }
    Err(Alarm::unknown_name(line, name))
}

fn unary(op: UnOp, v: Value, line: u32) -> Result<Value, Alarm> {
    let type_err = |e: super::eval::value::TypeError| Alarm::type_error(line, &e.0);
    Ok(match op {
        UnOp::Neg => match v {
            Value::Int(i) => Value::Int(-i),
            other => Value::Real(-other.as_f64().map_err(type_err)?),
        },
        UnOp::Not => Value::Bool(!v.as_bool().map_err(type_err)?),
        UnOp::BNot => Value::Int(!v.as_i64().map_err(type_err)?),
    })
}

/// `F1:F2`.
fn chain(a: Value, b: Value, scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    match (a, b) {
        (Value::Frame(f1), Value::Frame(f2)) => Ok(Value::Frame(Box::new(f1.then(&f2, &scope.geo_axes())))),
        _ => Err(Alarm::type_error(line, "`:` chains frames only")),
    }
}

/// Evaluates to a number (the common case for addresses).
pub fn eval_f64(expr: &Expr, scope: &dyn Scope, line: u32) -> Result<f64, Alarm> {
    // The common case, a literal (`X10.5`): the value `eval` and `as_f64` would give (`+ 0.0`
    // turns -0 into 0 like the INT round trip of a whole number does).
    if let Expr::Number(n) = expr
        && n.is_finite()
    {
        return Ok(*n + 0.0);
    }
    // Plain arithmetic (`R1*0.5+SIN(R2)`) without the general evaluator's values.
    if let Some(x) = numeric::numeric(expr, &scope.vars().r).map(numeric::Num::as_f64)
        && x.is_finite()
    {
        return Ok(x);
    }
    let v = eval(expr, scope, line)?;
    let x = v.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?;
    if x.is_finite() { Ok(x) } else { Err(Alarm::arithmetic(line, "result is not a finite number")) }
}

fn binary(op: BinOp, a: Value, b: Value, line: u32) -> Result<Value, Alarm> {
    let type_err = |e: super::eval::value::TypeError| Alarm::type_error(line, &e.0);
    let num = |v: &Value| v.as_f64().map_err(type_err);
    let int = |v: &Value| v.as_i64().map_err(type_err);
    let both_int = matches!((&a, &b), (Value::Int(_), Value::Int(_)));
    Ok(match op {
        BinOp::Chain => unreachable!("chains are evaluated by `chain`"),
        BinOp::Concat => Value::Str(a.as_text() + &b.as_text()),
        BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Lt | BinOp::Ge | BinOp::Le => {
            Value::Bool(compare(op, &a, &b, line)?)
        }
        BinOp::Or => Value::Bool(a.as_bool().map_err(type_err)? || b.as_bool().map_err(type_err)?),
        BinOp::Xor => Value::Bool(a.as_bool().map_err(type_err)? ^ b.as_bool().map_err(type_err)?),
        BinOp::And => Value::Bool(a.as_bool().map_err(type_err)? && b.as_bool().map_err(type_err)?),
        BinOp::BOr => Value::Int(int(&a)? | int(&b)?),
        BinOp::BXor => Value::Int(int(&a)? ^ int(&b)?),
        BinOp::BAnd => Value::Int(int(&a)? & int(&b)?),
        BinOp::Add | BinOp::Sub | BinOp::Mul if both_int => numeric::int_arithmetic(op, int(&a)?, int(&b)?).into(),
        BinOp::Add => Value::Real(num(&a)? + num(&b)?),
        BinOp::Sub => Value::Real(num(&a)? - num(&b)?),
        BinOp::Mul => Value::Real(num(&a)? * num(&b)?),
        BinOp::Div | BinOp::IntDiv | BinOp::Mod => {
            let (x, y) = (num(&a)?, num(&b)?);
            if y == 0.0 {
                return Err(Alarm::arithmetic(line, "division by zero"));
            }
            match op {
                BinOp::Div => Value::Real(x / y),
                // DIV: division with the result truncated to INT.
                BinOp::IntDiv => Value::Int((x / y).trunc() as i64),
                // MOD: remainder with the sign of the dividend.
                _ if both_int => Value::Int(int(&a)? % int(&b)?),
                _ => Value::Real(x - (x / y).trunc() * y),
            }
        }
    })
}

fn compare(op: BinOp, a: &Value, b: &Value, line: u32) -> Result<bool, Alarm> {
    let ord = match (a, b) {
        (Value::Str(x), Value::Str(y)) => x.cmp(y),
        (Value::Axis(x), Value::Axis(y)) => x.cmp(y),
        // A CHAR compares with a one-character string as that character (`FORM == "E"` with
        // `CHAR FORM`, as the turning cycles' parameters are declared).
        (Value::Char(c), Value::Str(s)) if s.len() == 1 => c.cmp(&s.as_bytes()[0]),
        (Value::Str(s), Value::Char(c)) if s.len() == 1 => s.as_bytes()[0].cmp(c),
        (Value::Str(_) | Value::Axis(_), _) | (_, Value::Str(_) | Value::Axis(_)) => {
            return Err(Alarm::type_error(line, "cannot compare a string with a number"));
        }
        _ => numeric_order(a.as_f64().unwrap_or(0.0), b.as_f64().unwrap_or(0.0)),
    };
    Ok(holds(op, ord))
}

/// The order of two numbers as the control compares them: equal within [`REL_EQ`].
fn numeric_order(x: f64, y: f64) -> Ordering {
    if (x - y).abs() <= REL_EQ * x.abs().max(y.abs()) {
        Ordering::Equal
    } else {
        x.partial_cmp(&y).unwrap_or(Ordering::Equal)
    }
}

/// Whether the comparison `op` (one of `== <> > < >= <=`) holds for operands in order `ord`.
fn holds(op: BinOp, ord: Ordering) -> bool {
    match op {
        BinOp::Eq => ord == Ordering::Equal,
        BinOp::Ne => ord != Ordering::Equal,
        BinOp::Gt => ord == Ordering::Greater,
        BinOp::Lt => ord == Ordering::Less,
        BinOp::Ge => ord != Ordering::Less,
        _ => ord != Ordering::Greater,
    }
}

/// A predefined function of evaluated arguments.
fn call(name: &str, vals: &[Value], line: u32) -> Result<Value, Alarm> {
    let arity = |n: usize| -> Result<(), Alarm> {
        if vals.len() == n { Ok(()) } else { Err(Alarm::syntax(line, &format!("{name} takes {n} argument(s)"))) }
    };
    let type_err = |e: super::eval::value::TypeError| Alarm::type_error(line, &e.0);
    let f = |i: usize| vals[i].as_f64().map_err(type_err);
    let text = |i: usize| match &vals[i] {
        Value::Str(s) => Ok(s.clone()),
        Value::Char(c) => Ok((*c as char).to_string()),
        other => Err(Alarm::type_error(line, &format!("{name} needs a string, not {other:?}"))),
    };
    let undefined = |x: f64| Alarm::arithmetic(line, &format!("{name}({x}) is undefined"));
    let real = |v: f64| Ok(Value::Real(v));
    match name {
        "SIN" | "COS" | "TAN" | "ASIN" | "ACOS" | "SQRT" | "ABS" | "POT" | "TRUNC" | "ROUND" | "LN" | "EXP"
        | "STRLEN" | "TOUPPER" | "TOLOWER" | "NUMBER" | "ISNUMBER" | "AXNAME" | "AXSTRING" => arity(1)?,
        "ATAN2" | "MINVAL" | "MAXVAL" | "INDEX" | "RINDEX" => arity(2)?,
        "BOUND" | "SUBSTR" => arity(3)?,
        "SPRINT" => return strings::sprint(vals, line),
        "TOINT" | "TOREAL" => {
            arity(1)?;
            return if name == "TOINT" { strings::to_int(&vals[0], line) } else { strings::to_real(&vals[0], line) };
        }
        "_OMITTED" => return Err(Alarm::syntax(line, "a value is missing: an empty argument where one is needed")),
        "SET" | "REP" => {
            return Err(Alarm::syntax(line, &format!("{name}(..) only as the value of a DEF or of an array element")));
        }
        _ => return Err(Alarm::unknown_name(line, name)),
    }
    match name {
        "SIN" => real(f(0)?.to_radians().sin()),
        "COS" => real(f(0)?.to_radians().cos()),
        "TAN" => real(f(0)?.to_radians().tan()),
        "ASIN" | "ACOS" => {
            let x = f(0)?;
            if !(-1.0..=1.0).contains(&x) {
                return Err(undefined(x));
            }
            real(if name == "ASIN" { x.asin() } else { x.acos() }.to_degrees())
        }
        "ATAN2" => real(f(0)?.atan2(f(1)?).to_degrees()),
        "SQRT" => {
            let x = f(0)?;
            if x < 0.0 { Err(undefined(x)) } else { real(x.sqrt()) }
        }
        "ABS" => match vals[0] {
            Value::Int(i) => Ok(Value::Int(i.abs())),
            _ => real(f(0)?.abs()),
        },
        "POT" => real(f(0)? * f(0)?),
        "TRUNC" => real(f(0)?.trunc()),
        "ROUND" => real(f(0)?.round()),
        "LN" => {
            let x = f(0)?;
            if x <= 0.0 { Err(undefined(x)) } else { real(x.ln()) }
        }
        "EXP" => real(f(0)?.exp()),
        "MINVAL" => real(f(0)?.min(f(1)?)),
        "MAXVAL" => real(f(0)?.max(f(1)?)),
        // BOUND(min, max, value): the value limited to the range.
        "BOUND" => real(f(2)?.max(f(0)?).min(f(1)?)),
        "STRLEN" => Ok(Value::Int(text(0)?.len() as i64)),
        "TOUPPER" => Ok(Value::Str(text(0)?.to_ascii_uppercase())),
        "TOLOWER" => Ok(Value::Str(text(0)?.to_ascii_lowercase())),
        "INDEX" | "RINDEX" => {
            let (s, c) = (text(0)?, text(1)?);
            let found = if name == "INDEX" { s.find(&c) } else { s.rfind(&c) };
            Ok(Value::Int(found.map_or(-1, |i| i as i64)))
        }
        "SUBSTR" => {
            let s = text(0)?;
            let (start, count) = (vals[1].as_i64().map_err(type_err)?, vals[2].as_i64().map_err(type_err)?);
            let start = usize::try_from(start).unwrap_or(usize::MAX).min(s.len());
            let end = start.saturating_add(usize::try_from(count).unwrap_or(0)).min(s.len());
            Ok(Value::Str(s[start..end].to_string()))
        }
        "NUMBER" => {
            text(0)?.trim().parse::<f64>().map(Value::Real).map_err(|_| Alarm::type_error(line, "NUMBER: not a number"))
        }
        "ISNUMBER" => Ok(Value::Bool(text(0)?.trim().parse::<f64>().is_ok())),
        "AXNAME" => Ok(Value::Axis(text(0)?.to_ascii_uppercase())),
        _ => Ok(Value::Str(vals[0].as_text())),
    }
}

/// Functions that build frames from (axis, value) pairs.
const FRAME_FUNCTIONS: &[&str] = &["CTRANS", "CFINE", "CROT", "CROTS", "CSCALE", "CMIRROR", "CRPL"];

/// `CTRANS(X,10,Y,20)`, `CFINE(...)`, `CROT(Z,45)`, `CROTS(X,10,Y,20)`, `CSCALE(X,2)`, `CMIRROR(X)`, `CRPL(axis, angle)`:
/// a frame with only that component (no arguments: the neutral frame).
fn frame_function(name: &str, vals: &[Value], scope: &dyn Scope, line: u32) -> Result<Value, Alarm> {
    let geo = scope.geo_axes();
    let axis = |v: &Value| -> Result<usize, Alarm> {
        match v {
            Value::Axis(a) | Value::Str(a) => scope.axis_index(a).ok_or_else(|| Alarm::unknown_name(line, a)),
            other => Err(Alarm::type_error(line, &format!("{name} needs axis names, not {other:?}"))),
        }
    };
    let number = |v: &Value| v.as_f64().map_err(|e| Alarm::type_error(line, &e.0));
    let pairs = || -> Result<Vec<(usize, f64)>, Alarm> {
        if !vals.len().is_multiple_of(2) {
            return Err(Alarm::syntax(line, &format!("{name} takes axis, value pairs")));
        }
        vals.chunks(2).map(|p| Ok((axis(&p[0])?, number(&p[1])?))).collect()
    };
    let f = match name {
        "CTRANS" | "CFINE" => {
            let mut t = [0.0; crate::machine_data::registry::MAX_CHANNEL_AXES];
            for (k, v) in pairs()? {
                t[k] += v;
            }
            Frame::translation(t)
        }
        "CROT" => {
            let mut angles = [0.0; 3];
            for (k, v) in pairs()? {
                let g = geo
                    .iter()
                    .position(|a| *a == Some(k))
                    .ok_or_else(|| Alarm::type_error(line, "CROT rotates geometry axes only"))?;
                angles[g] = v;
            }
            Frame::rotation(frame::rotation_of(scope.frame_angles(), angles))
        }
        "CROTS" => {
            let mut angles = Vec::new();
            for (k, v) in pairs()? {
                let g = geo
                    .iter()
                    .position(|a| *a == Some(k))
                    .ok_or_else(|| Alarm::type_error(line, "CROTS rotates geometry axes only"))?;
                angles.push((g, v));
            }
            let r = super::frames::solid_angles::rotation(&angles)
                .map_err(|what| Alarm::value_out_of_range(line, &format!("CROTS: {what}")))?;
            Frame::rotation(r)
        }
        "CSCALE" => Frame::scaling(&geo, &pairs()?),
        "CMIRROR" => {
            let axes = vals.iter().map(axis).collect::<Result<Vec<_>, _>>()?;
            Frame::scaling(&geo, &axes.into_iter().map(|k| (k, -1.0)).collect::<Vec<_>>())
        }
        // CRPL(rotation axis: 0 = applicate of the plane, 1..3 = Z, Y, X; angle)
        _ => {
            let [which, angle] = vals else {
                return Err(Alarm::syntax(line, "CRPL takes (axis code, angle)"));
            };
            let g = match number(which)? as i64 {
                0 => scope.applicate(),
                1 => 2,
                2 => 1,
                3 => 0,
                other => return Err(Alarm::value_out_of_range(line, &format!("CRPL axis code {other}"))),
            };
            Frame::rotation(frame::about_axis(g, number(angle)?))
        }
    };
    Ok(Value::Frame(Box::new(f)))
}
