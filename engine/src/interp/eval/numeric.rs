//! The arithmetic most statement blocks are made of (`R2=R1*0.5+SIN(R1)`, `X=R3`, `WHILE
//! R1<R10`) without the general evaluator's `Value`s, dynamic scope calls and alarms: numbers,
//! R parameters, `+ - * /`, unary minus, SIN/COS/TAN/ABS/SQRT and the comparisons.
//!
//! Each function gives exactly what [`super::eval::eval`] gives for such an expression (the
//! same INT and REAL rules), or `None` for anything else or anything that would be an error,
//! so the general evaluator then gives the value or the alarm. The tests check the two
//! against each other on random expressions.

use crate::lang::{BinOp, Expr, UnOp};

/// A numeric value: `Value::Int` or `Value::Real`, without the other types' drop glue.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) enum Num {
    Int(i64),
    Real(f64),
}

impl Num {
    pub fn as_f64(self) -> f64 {
        match self {
            Num::Int(i) => i as f64,
            Num::Real(x) => x,
        }
    }

    /// `Value::as_i64`: REAL rounded; `None` outside the INT range.
    fn as_i64(self) -> Option<i64> {
        let v = self.as_f64();
        (v.abs() <= 2_147_483_647.0).then(|| v.round() as i64)
    }
}

impl From<Num> for crate::interp::eval::value::Value {
    fn from(n: Num) -> Self {
        match n {
            Num::Int(i) => Self::Int(i),
            Num::Real(x) => Self::Real(x),
        }
    }
}

/// The value of `expr` with R parameters `r`, if it is plain arithmetic that evaluates
/// without an error.
pub(in crate::interp) fn numeric(expr: &Expr, r: &[f64]) -> Option<Num> {
    Some(match expr {
        Expr::Number(n) => number(*n),
        Expr::RParam(index) => {
            let n = numeric(index, r)?.as_i64()?;
            Num::Real(*usize::try_from(n).ok().and_then(|i| r.get(i))?)
        }
        Expr::Unary(UnOp::Neg, e) => match numeric(e, r)? {
            Num::Int(i) => Num::Int(-i),
            Num::Real(x) => Num::Real(-x),
        },
        Expr::Binary(op @ (BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div), a, b) => {
            arithmetic(*op, numeric(a, r)?, numeric(b, r)?)?
        }
        Expr::Call(name, args) => match args.as_slice() {
            [arg] => function(name, numeric(arg, r)?)?,
            _ => return None,
        },
        _ => return None,
    })
}

/// The truth of a comparison of two numeric expressions (`R1<R10`), as `eval` and
/// `Value::as_bool` give it.
pub(in crate::interp) fn condition(expr: &Expr, r: &[f64]) -> Option<bool> {
    let Expr::Binary(op @ (BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Lt | BinOp::Ge | BinOp::Le), a, b) = expr else {
        return None;
    };
    let (x, y) = (numeric(a, r)?.as_f64(), numeric(b, r)?.as_f64());
    Some(super::holds(*op, super::numeric_order(x, y)))
}

/// `eval::binary` for `+ - * /` on numbers; `None` for a division by zero (an alarm).
fn arithmetic(op: BinOp, a: Num, b: Num) -> Option<Num> {
    if let (Num::Int(x), Num::Int(y)) = (a, b)
        && op != BinOp::Div
    {
        return Some(int_arithmetic(op, x, y));
    }
    let (x, y) = (a.as_f64(), b.as_f64());
    Some(Num::Real(match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        _ if y == 0.0 => return None,
        _ => x / y,
    }))
}

/// A number written in the program: INT when it is whole and within the INT range, else REAL.
pub(in crate::interp) fn number(n: f64) -> Num {
    if n.fract() == 0.0 && n.abs() <= 2_147_483_647.0 { Num::Int(n as i64) } else { Num::Real(n) }
}

/// `+ - *` of two INT values: INT while the result fits the INT range, else REAL.
pub(in crate::interp) fn int_arithmetic(op: BinOp, x: i64, y: i64) -> Num {
    let r = match op {
        BinOp::Add => x.checked_add(y),
        BinOp::Sub => x.checked_sub(y),
        _ => x.checked_mul(y),
    };
    match r.filter(|r| r.abs() <= 2_147_483_647) {
        Some(r) => Num::Int(r),
        None => Num::Real(match op {
            BinOp::Add => x as f64 + y as f64,
            BinOp::Sub => x as f64 - y as f64,
            _ => x as f64 * y as f64,
        }),
    }
}

/// `eval::call` for the one-argument functions of plain arithmetic; `None` for any other
/// function and for SQRT of a negative number (an alarm).
fn function(name: &str, x: Num) -> Option<Num> {
    Some(match name {
        "SIN" => Num::Real(x.as_f64().to_radians().sin()),
        "COS" => Num::Real(x.as_f64().to_radians().cos()),
        "TAN" => Num::Real(x.as_f64().to_radians().tan()),
        "ABS" => match x {
            Num::Int(i) => Num::Int(i.abs()),
            Num::Real(v) => Num::Real(v.abs()),
        },
        "SQRT" if x.as_f64() >= 0.0 => Num::Real(x.as_f64().sqrt()),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::alarm::Alarm;
    use crate::interp::eval::value::Value;
    use crate::interp::eval::vars::Variables;
    use crate::interp::eval::{Scope, eval, eval_f64};
    use crate::interp::frames::frame::GeoAxes;
    use crate::lang::parse_block;

    /// R parameters and nothing else: what plain arithmetic reads.
    struct RScope(Variables);

    impl Scope for RScope {
        fn vars(&self) -> &Variables {
            &self.0
        }
        fn system(&self, name: &str, _: &[Value], line: u32) -> Result<Value, Alarm> {
            Err(Alarm::unknown_name(line, name))
        }
        fn axis_index(&self, _: &str) -> Option<usize> {
            None
        }
        fn geo_axes(&self) -> GeoAxes {
            [Some(0), Some(1), Some(2)]
        }
    }

    fn scope(values: &[f64]) -> RScope {
        let mut vars = Variables::default();
        vars.r[..values.len()].copy_from_slice(values);
        RScope(vars)
    }

    /// The expression of `R0=<text>`, as the parser builds it.
    fn expr(text: &str) -> Expr {
        let block = parse_block(&format!("R0={text}"), 1, 0).expect("valid").expect("a block");
        match block.words.into_iter().next() {
            Some(crate::lang::Word::Address { value, .. }) => value.expr,
            other => panic!("not an assignment: {other:?}"),
        }
    }

    /// Same value and type, REAL compared by its bits (so -0 differs from 0, NaN equals NaN).
    fn same(a: &Value, b: &Value) -> bool {
        match (a, b) {
            (Value::Real(x), Value::Real(y)) => x.to_bits() == y.to_bits(),
            _ => a == b,
        }
    }

    #[test]
    fn worked_examples() {
        let s = scope(&[0.0, 4.0, -2.5, 1e300]);
        let r = &s.0.r;
        // 1 + 2 * 3: INT throughout.
        assert_eq!(numeric(&expr("1+2*3"), r), Some(Num::Int(7)));
        // R1 * 0.5 + SIN(30) = 4 * 0.5 + 0.5 (sin 30° = 1/2, to the last bit or so).
        assert!(numeric(&expr("R1*0.5+SIN(30)"), r).is_some_and(|n| (n.as_f64() - 2.5).abs() < 1e-15));
        // 7 / 2 divides as REAL: 3.5.
        assert_eq!(numeric(&expr("7/2"), r), Some(Num::Real(3.5)));
        // 2147483647 + 1 leaves the INT range: REAL 2147483648.
        assert_eq!(numeric(&expr("2147483647+1"), r), Some(Num::Real(2_147_483_648.0)));
        // R[1+1] reads R2.
        assert_eq!(numeric(&expr("R[1+1]"), r), Some(Num::Real(-2.5)));
        // Errors are the general evaluator's: division by zero, SQRT(-1), R[-1], R[1e10].
        for text in ["1/R0", "SQRT(R2)", "R[-1]", "R[10000000000]", "R[R3]", "7 MOD 2", "ATAN2(1,1)", "AA"] {
            assert_eq!(numeric(&expr(text), r), None, "{text}");
        }
        assert_eq!(condition(&expr("R1>R2"), r), Some(true));
        // Comparisons are relative: 1 and 1 + 1e-13 are equal.
        assert_eq!(condition(&expr("1==1.0000000000001"), r), Some(true));
        assert_eq!(condition(&expr("R1<>4"), r), Some(false));
        assert_eq!(condition(&expr("R1>1 AND R2<0"), r), None);
    }

    /// A random expression of plain arithmetic, with some nodes outside it (MOD, ATAN2, names),
    /// drawn from `rng`.
    fn random_expr(rng: &mut impl FnMut() -> u64, depth: u32) -> String {
        const NUMBERS: [&str; 12] =
            ["0", "1", "2", "7", "0.5", "1500", "2147483647", "2147483648", "999999999999", "0.1", "3", "1000000"];
        if depth == 0 || rng().is_multiple_of(4) {
            return match rng() % 3 {
                0 => NUMBERS[(rng() % NUMBERS.len() as u64) as usize].to_string(),
                1 => format!("R{}", rng() % 6),
                _ => format!("R[{}]", (rng() % 8) as i64 - 1),
            };
        }
        let a = random_expr(rng, depth - 1);
        let b = random_expr(rng, depth - 1);
        match rng() % 14 {
            0 => format!("({a})+({b})"),
            1 => format!("({a})-({b})"),
            2 => format!("({a})*({b})"),
            3 => format!("({a})/({b})"),
            4 => format!("-({a})"),
            5 => format!("SIN({a})"),
            6 => format!("COS({a})"),
            7 => format!("TAN({a})"),
            8 => format!("ABS({a})"),
            9 => format!("SQRT({a})"),
            10 => format!("({a}) MOD ({b})"),
            11 => format!("ATAN2({a},{b})"),
            12 => format!("R[{a}]"),
            _ => format!("({a})*R{}", rng() % 6),
        }
    }

    #[test]
    fn random_arithmetic_evaluates_as_the_general_evaluator_does() {
        let s = scope(&[0.0, -0.0, 3.25, -1e9, 1e300, 2147483647.0]);
        let r = &s.0.r;
        let mut rng = crate::lang::test_rng::xorshift(0x9e37_79b9_7f4a_7c15);
        let (mut fast, mut total) = (0, 0);
        for _ in 0..20000 {
            let text = random_expr(&mut rng, 4);
            let e = expr(&text);
            total += 1;
            let general = eval(&e, &s, 1);
            if let Some(n) = numeric(&e, r) {
                fast += 1;
                let general = general.unwrap_or_else(|a| panic!("{text}: fast {n:?}, general alarm {a:?}"));
                assert!(same(&Value::from(n), &general), "{text}: fast {n:?}, general {general:?}");
            }
            // eval_f64 (which takes this way) gives what the general evaluator's value is.
            match eval(&e, &s, 1).map(|v| v.as_f64().expect("a number")) {
                Ok(x) if x.is_finite() => {
                    assert_eq!(eval_f64(&e, &s, 1).map(f64::to_bits), Ok(x.to_bits()), "{text}")
                }
                _ => assert!(eval_f64(&e, &s, 1).is_err(), "{text}"),
            }
            // Comparisons of such expressions.
            let cond = expr(&format!("({text})<=R2"));
            if let Some(c) = condition(&cond, r) {
                assert_eq!(eval(&cond, &s, 1).map(|v| v.as_bool().expect("BOOL")), Ok(c), "{text}");
            }
        }
        // The generator reaches both sides.
        assert!(fast > total / 4 && fast < total, "{fast} of {total} evaluated fast");
    }
}
