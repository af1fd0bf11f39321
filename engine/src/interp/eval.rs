//! Evaluation of arithmetic expressions in block words (R parameters and the basic functions).

use crate::alarm::Alarm;
use crate::lang::{BinOp, Expr};

/// Evaluates `expr` with R parameters `r`; errors become alarms of `line`.
pub fn eval(expr: &Expr, r: &[f64], line: u32) -> Result<f64, Alarm> {
    let v = match expr {
        Expr::Number(n) => *n,
        Expr::Str(s) => return Err(Alarm::syntax(line, &format!("string \"{s}\" where a number is needed"))),
        Expr::RParam(n) => *r.get(*n as usize).ok_or_else(|| Alarm::unknown_name(line, &format!("R{n}")))?,
        Expr::Neg(e) => -eval(e, r, line)?,
        Expr::Binary(op, a, b) => {
            let (a, b) = (eval(a, r, line)?, eval(b, r, line)?);
            match op {
                BinOp::Add => a + b,
                BinOp::Sub => a - b,
                BinOp::Mul => a * b,
                BinOp::Div if b == 0.0 => return Err(Alarm::arithmetic(line, "division by zero")),
                BinOp::Div => a / b,
            }
        }
        Expr::Call(name, args) => call(name, args, r, line)?,
    };
    if v.is_finite() { Ok(v) } else { Err(Alarm::arithmetic(line, "result is not a finite number")) }
}

fn call(name: &str, args: &[Expr], r: &[f64], line: u32) -> Result<f64, Alarm> {
    let vals = args.iter().map(|a| eval(a, r, line)).collect::<Result<Vec<_>, _>>()?;
    let arity = |n: usize| -> Result<(), Alarm> {
        if vals.len() == n { Ok(()) } else { Err(Alarm::syntax(line, &format!("{name} takes {n} argument(s)"))) }
    };
    let x = vals.first().copied().unwrap_or(0.0);
    let checked =
        |ok: bool, v: f64| if ok { Ok(v) } else { Err(Alarm::arithmetic(line, &format!("{name}({x}) is undefined"))) };
    match name {
        "SIN" | "COS" | "TAN" | "ASIN" | "ACOS" | "SQRT" | "ABS" | "POT" | "TRUNC" | "ROUND" | "LN" | "EXP" => {
            arity(1)?
        }
        "ATAN2" => arity(2)?,
        _ => return Err(Alarm::unknown_name(line, name)),
    }
    match name {
        "SIN" => Ok(x.to_radians().sin()),
        "COS" => Ok(x.to_radians().cos()),
        "TAN" => Ok(x.to_radians().tan()),
        "ASIN" => checked((-1.0..=1.0).contains(&x), x.asin().to_degrees()),
        "ACOS" => checked((-1.0..=1.0).contains(&x), x.acos().to_degrees()),
        "ATAN2" => Ok(vals[0].atan2(vals[1]).to_degrees()),
        "SQRT" => checked(x >= 0.0, x.sqrt()),
        "ABS" => Ok(x.abs()),
        "POT" => Ok(x * x),
        "TRUNC" => Ok(x.trunc()),
        "ROUND" => Ok(x.round()),
        "LN" => checked(x > 0.0, x.ln()),
        _ => Ok(x.exp()),
    }
}
