//! The control's predefined constants among the system variables: `$PI`, the circle constant
//! (REAL, readable in part programs and synchronized actions, never writable).
//!
//! Why a table of its own: a constant needs no preparation state, so every scope (the block's,
//! a synchronized action's, the static program check's) answers it the same way, and a write
//! is refused before any writable-datum lookup (alarm 17070, data write-protected, as the
//! control gives for a read-only system variable).

use crate::interp::eval::value::Value;

/// The value of predefined constant `name` (upper case, with its `$`), if it is one.
pub fn constant(name: &str) -> Option<Value> {
    real(name).map(Value::Real)
}

/// The number a predefined constant stands for (every one of them is a REAL).
pub fn real(name: &str) -> Option<f64> {
    match name {
        "$PI" => Some(std::f64::consts::PI),
        _ => None,
    }
}

/// Whether `name` is a predefined constant (a write to it is alarm 17070).
pub fn is_constant(name: &str) -> bool {
    real(name).is_some()
}
