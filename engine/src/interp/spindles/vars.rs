//! The spindle system variables of preparation: `$P_S[n]` (the last programmed speed of
//! spindle n, rev/min) and `$P_SDIR[n]` (its last programmed direction: 3 = M3, 4 = M4,
//! 5 = M5 or in position control), n the spindle number; without an index the master spindle.
//! The tapping cycles read them to put the caller's spindle back as it was.

use super::axis_of;
use crate::alarm::Alarm;
use crate::interp::eval::scope::SysView;
use crate::interp::eval::value::Value;

/// The value of `name`, or `None` if `name` is not one of these variables.
pub(in crate::interp) fn read(sys: &SysView, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
    if !matches!(name, "$P_S" | "$P_SDIR") {
        return None;
    }
    Some(read_spindle(sys, name, indices, line))
}

fn read_spindle(sys: &SysView, name: &str, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let axis = match indices {
        [] => sys.spindles.master().ok_or_else(|| Alarm::unknown_name(line, &format!("{name} (no master spindle)")))?,
        [n] => {
            let n = match n {
                Value::Int(n) => *n as f64,
                Value::Real(r) => *r,
                _ => return Err(Alarm::index_error(line, name, "needs a spindle number")),
            };
            if !(1.0..=32.0).contains(&n) || n.fract() != 0.0 {
                return Err(Alarm::index_error(line, name, "needs a spindle number"));
            }
            axis_of(sys.cfg, n as u32, line, name)?
        }
        _ => return Err(Alarm::index_error(line, name, "takes one index")),
    };
    Ok(match name {
        "$P_S" => Value::Real(sys.spindles.speed_of(axis)),
        _ => Value::Int(match sys.spindles.direction_of(axis) {
            1 => 3,
            -1 => 4,
            _ => 5,
        }),
    })
}
