//! String functions of the Programming Manual Job Planning that need more than one line in
//! [`super::call`](crate::interp::eval): `SPRINT` (formatted text) and the conversions `TOINT`
//! and `TOREAL`.

use super::value::Value;
use crate::alarm::Alarm;

/// `SPRINT("format", values...)`: the format with each `%` field replaced by the next value.
/// Fields: `%D` integer (a REAL rounded), `%F` REAL with 6 decimals, `%E` exponential, `%G`
/// the shorter of both, `%S` string, `%B` TRUE/FALSE, `%C` a character, `%X` hexadecimal,
/// `%%` a percent sign; `%<width>` pads on the left with blanks (`%0<width>` a number with
/// zeros), `%.<n>F` / `%.<n>E` give the decimals.
/// A field without its value, or a value left over, is an alarm naming it.
pub fn sprint(vals: &[Value], line: u32) -> Result<Value, Alarm> {
    let Some((format, args)) = vals.split_first() else {
        return Err(Alarm::syntax(line, "SPRINT needs a format text"));
    };
    let format = format.as_text();
    let mut args = args.iter();
    let mut out = String::with_capacity(format.len() + 16);
    let mut chars = format.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        if chars.peek() == Some(&'%') {
            chars.next();
            out.push('%');
            continue;
        }
        let mut width = String::new();
        while let Some(d) = chars.next_if(char::is_ascii_digit) {
            width.push(d);
        }
        let mut precision = None;
        if chars.next_if_eq(&'.').is_some() {
            let mut p = String::new();
            while let Some(d) = chars.next_if(char::is_ascii_digit) {
                p.push(d);
            }
            precision = Some(p.parse::<usize>().unwrap_or(0));
        }
        let Some(kind) = chars.next().map(|k| k.to_ascii_uppercase()) else {
            return Err(Alarm::type_error(line, "SPRINT: the format ends inside a % field"));
        };
        let value =
            args.next().ok_or_else(|| Alarm::type_error(line, &format!("SPRINT: no value for the field %{kind}")))?;
        let number = || value.as_f64().map_err(|e| Alarm::type_error(line, &format!("SPRINT %{kind}: {}", e.0)));
        let field = match kind {
            'D' | 'I' => format!("{}", number()?.round() as i64),
            'F' => format!("{:.*}", precision.unwrap_or(6), number()?),
            'E' => exponential(number()?, precision.unwrap_or(6)),
            'G' => {
                let x = number()?;
                let fixed = format!("{x}");
                let exp = exponential(x, precision.unwrap_or(6));
                if fixed.len() <= exp.len() { fixed } else { exp }
            }
            'X' => format!("{:X}", number()?.round() as i64),
            'B' => if value.as_bool().unwrap_or(false) { "TRUE" } else { "FALSE" }.to_string(),
            'C' => match value {
                Value::Char(c) => (*c as char).to_string(),
                other => other.as_text().chars().next().map(String::from).unwrap_or_default(),
            },
            'S' => {
                let s = value.as_text();
                match precision {
                    Some(n) => s.chars().take(n).collect(),
                    None => s,
                }
            }
            other => return Err(Alarm::type_error(line, &format!("SPRINT: unknown field %{other}"))),
        };
        let zeros = width.starts_with('0') && matches!(kind, 'D' | 'I' | 'F' | 'E' | 'G' | 'X');
        let width = width.parse::<usize>().unwrap_or(0);
        let pad = width.saturating_sub(field.chars().count());
        if zeros {
            // `%05D`: zeros after the sign, as C pads.
            let (sign, digits) = field.strip_prefix('-').map_or(("", field.as_str()), |d| ("-", d));
            out.push_str(sign);
            out.extend(std::iter::repeat_n('0', pad));
            out.push_str(digits);
        } else {
            out.extend(std::iter::repeat_n(' ', pad));
            out.push_str(&field);
        }
    }
    if args.next().is_some() {
        return Err(Alarm::type_error(line, "SPRINT: more values than % fields"));
    }
    Ok(Value::Str(out))
}

/// `x` as `d.dddddde+XX` (C's `%e`: a sign and at least two exponent digits).
fn exponential(x: f64, precision: usize) -> String {
    let s = format!("{x:.precision$e}");
    match s.split_once('e') {
        Some((mantissa, exp)) => {
            let (sign, digits) = exp.strip_prefix('-').map_or(("+", exp), |d| ("-", d));
            format!("{mantissa}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

/// `TOINT(value)`: a REAL rounded to the nearest integer (half away from zero), a BOOL 0/1, a
/// STRING read as a number; a STRING that is none is an alarm.
pub fn to_int(v: &Value, line: u32) -> Result<Value, Alarm> {
    Ok(Value::Int(match v {
        Value::Int(i) => *i,
        Value::Str(s) => parse(s, line)?.round() as i64,
        other => other.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?.round() as i64,
    }))
}

/// `TOREAL(value)`: the value as REAL (a STRING read as a number).
pub fn to_real(v: &Value, line: u32) -> Result<Value, Alarm> {
    Ok(Value::Real(match v {
        Value::Str(s) => parse(s, line)?,
        other => other.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?,
    }))
}

fn parse(s: &str, line: u32) -> Result<f64, Alarm> {
    s.trim().parse::<f64>().map_err(|_| Alarm::type_error(line, &format!("\"{s}\" is no number")))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sp(vals: &[Value]) -> String {
        match sprint(vals, 1) {
            Ok(Value::Str(s)) => s,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn sprint_fields_follow_the_c_like_formats() {
        let f = |s: &str| Value::Str(s.into());
        assert_eq!(sp(&[f("PART %D OK"), Value::Real(6.5)]), "PART 7 OK");
        assert_eq!(sp(&[f("X=%F"), Value::Real(12.5)]), "X=12.500000");
        assert_eq!(sp(&[f("X=%.3F Y=%8.2F"), Value::Real(1.0), Value::Real(-2.126)]), "X=1.000 Y=   -2.13");
        assert_eq!(sp(&[f("%E"), Value::Real(1234.5)]), "1.234500e+03");
        assert_eq!(sp(&[f("%S=%B %%"), f("ON"), Value::Bool(true)]), "ON=TRUE %");
        assert_eq!(sp(&[f("%5D|%X"), Value::Int(42), Value::Int(255)]), "   42|FF");
        assert_eq!(sp(&[f("%05D"), Value::Int(-42)]), "-0042");
        assert!(sprint(&[f("%D %D"), Value::Int(1)], 3).is_err());
        assert!(sprint(&[f("%D"), Value::Int(1), Value::Int(2)], 3).is_err());
    }

    #[test]
    fn conversions_round_and_read_strings() {
        assert_eq!(to_int(&Value::Real(2.5), 1), Ok(Value::Int(3)));
        assert_eq!(to_int(&Value::Real(-2.5), 1), Ok(Value::Int(-3)));
        assert_eq!(to_int(&Value::Str(" 17 ".into()), 1), Ok(Value::Int(17)));
        assert_eq!(to_real(&Value::Str("1.25".into()), 1), Ok(Value::Real(1.25)));
        assert!(to_real(&Value::Str("A1".into()), 1).is_err());
    }
}
