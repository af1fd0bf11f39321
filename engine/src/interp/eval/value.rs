//! Values of the NC language and the control's conversions between its types.

use crate::interp::frames::frame::Frame;
use crate::lang::VarType;

/// A value of a variable or an expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f64),
    Bool(bool),
    Char(u8),
    Str(String),
    /// An axis identifier (type AXIS).
    Axis(String),
    /// A coordinate frame (type FRAME).
    Frame(Box<Frame>),
}

/// Why a value cannot be used where it stands.
#[derive(Debug, Clone, PartialEq)]
pub struct TypeError(pub String);

impl Value {
    /// The default value of a type (0, FALSE, empty string).
    pub fn default_of(ty: VarType) -> Value {
        match ty {
            VarType::Int => Value::Int(0),
            VarType::Real => Value::Real(0.0),
            VarType::Frame => Value::Frame(Box::default()),
            VarType::Bool => Value::Bool(false),
            VarType::Char => Value::Char(0),
            VarType::Str(_) => Value::Str(String::new()),
            VarType::Axis => Value::Axis(String::new()),
        }
    }

    /// Numeric view: INT, REAL, BOOL (0/1) and CHAR (its code) are numbers.
    pub fn as_f64(&self) -> Result<f64, TypeError> {
        match self {
            Value::Int(i) => Ok(*i as f64),
            Value::Real(r) => Ok(*r),
            Value::Bool(b) => Ok(f64::from(u8::from(*b))),
            Value::Char(c) => Ok(f64::from(*c)),
            Value::Str(s) => Err(TypeError(format!("string \"{s}\" where a number is needed"))),
            Value::Axis(a) => Err(TypeError(format!("axis {a} where a number is needed"))),
            Value::Frame(_) => Err(TypeError("a frame where a number is needed".into())),
        }
    }

    /// Truth value: numbers are true when not zero.
    pub fn as_bool(&self) -> Result<bool, TypeError> {
        match self {
            Value::Bool(b) => Ok(*b),
            Value::Str(s) => Ok(!s.is_empty()),
            other => Ok(other.as_f64()? != 0.0),
        }
    }

    /// Integer view: REAL is rounded, as the control does when assigning REAL to INT.
    pub fn as_i64(&self) -> Result<i64, TypeError> {
        let v = self.as_f64()?;
        if v.abs() > 2_147_483_647.0 {
            return Err(TypeError(format!("{v} is outside the INT range")));
        }
        Ok(v.round() as i64)
    }

    /// Text view for string operations (`<<`): numbers are written as the control prints them.
    pub fn as_text(&self) -> String {
        match self {
            Value::Int(i) => i.to_string(),
            Value::Real(r) => format_real(*r),
            Value::Bool(b) => if *b { "1" } else { "0" }.to_string(),
            Value::Char(c) => (*c as char).to_string(),
            Value::Str(s) => s.clone(),
            Value::Axis(a) => a.clone(),
            Value::Frame(_) => "FRAME".into(),
        }
    }

    /// Converts a value for storage in a variable of type `ty`.
    pub fn convert(self, ty: VarType) -> Result<Value, TypeError> {
        Ok(match ty {
            VarType::Int => Value::Int(self.as_i64()?),
            VarType::Real => Value::Real(self.as_f64()?),
            VarType::Frame => match self {
                Value::Frame(f) => Value::Frame(f),
                other => return Err(TypeError(format!("{other:?} is not a frame"))),
            },
            VarType::Bool => Value::Bool(self.as_bool()?),
            VarType::Char => match self {
                Value::Str(s) if s.len() == 1 => Value::Char(s.as_bytes()[0]),
                other => Value::Char(
                    u8::try_from(other.as_i64()?).map_err(|_| TypeError("CHAR out of range 0..255".into()))?,
                ),
            },
            VarType::Str(max) => {
                let s = self.as_text();
                if s.len() > max as usize {
                    return Err(TypeError(format!("string of {} characters does not fit STRING[{max}]", s.len())));
                }
                Value::Str(s)
            }
            VarType::Axis => match self {
                Value::Axis(a) | Value::Str(a) => Value::Axis(a),
                other => return Err(TypeError(format!("{other:?} is not an axis"))),
            },
        })
    }
}

/// REAL printed without needless zeros: 1.5 → "1.5", 2.0 → "2".
fn format_real(r: f64) -> String {
    if r.fract() == 0.0 && r.abs() < 1e15 {
        format!("{}", r as i64)
    } else {
        let s = format!("{r:.6}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}
