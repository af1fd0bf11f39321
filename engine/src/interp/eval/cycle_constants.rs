//! Named constants the standard cycles' global data define for callers (on the control they
//! live in the cycles' global user data): the machining types of the high-speed settings
//! `CYCLE832(0.01, _FINISH, 1)`. A user variable of the same name wins.
//!
//! The values: deselection 0, finishing 1, semi-finishing 2, roughing 3 (the units digit of
//! CYCLE832's machining type); the orientation variants carry a 1 in the tens digit, NCTwin's
//! choice, so that `CYCLE832` also takes the orientation tolerance.

use crate::interp::eval::value::Value;

/// The value of constant `name`, if it is one.
pub(in crate::interp) fn constant(name: &str) -> Option<Value> {
    let v = match name {
        "_OFF" => 0,
        "_FINISH" => 1,
        "_SEMIFIN" => 2,
        "_ROUGH" => 3,
        "_ORI_FINISH" => 11,
        "_ORI_SEMIFIN" => 12,
        "_ORI_ROUGH" => 13,
        _ => return None,
    };
    Some(Value::Int(v))
}
