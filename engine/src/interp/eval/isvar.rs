//! `ISVAR("name")`: whether `name` is a variable the program can read: an R parameter
//! (`"R10"`), a user variable (DEF, global or local), or a system variable or machine datum
//! NCTwin knows. Machine-builder programs test their global data and options with it before
//! they use them (`IF NOT ISVAR("_MY_GUD") ...`).
//!
//! Decisions: an index written in the string (`"$MA_X[AX1]"`, `"ARR[3]"`) is not checked,
//! only the name before it (the control also checks the indices, answering FALSE for one out of
//! range); the name is matched in upper case, as the control reads names.

use crate::alarm::Alarm;
use crate::interp::eval::Scope;
use crate::interp::eval::value::Value;
use crate::interp::eval::vars::R_PARAMS;

/// `ISVAR(text)` over `scope`.
pub(in crate::interp) fn isvar(scope: &dyn Scope, vals: &[Value], line: u32) -> Result<Value, Alarm> {
    let [v] = vals else { return Err(Alarm::syntax(line, "ISVAR takes one name")) };
    let text = v.as_text().trim().to_ascii_uppercase();
    let name = text.split('[').next().unwrap_or_default().trim();
    let known = if let Some(n) = name.strip_prefix('R').and_then(|n| n.parse::<usize>().ok()) {
        n < R_PARAMS
    } else if scope.vars().get(name).is_some() {
        true
    } else if name.starts_with('$') {
        // A read without its indices: a known name answers with its value or an index alarm.
        !matches!(scope.system(name, &[], line), Err(a) if a.number == 12550)
    } else {
        false
    };
    Ok(Value::Bool(known))
}
