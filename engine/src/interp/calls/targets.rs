//! What a block calls: the program name a call word names (`L123`, `NAME`, `CALL "NAME"`,
//! `PCALL /_N_WKS_DIR/_N_PART_WPD/_N_PART_SPF`, `EXTCALL "NAME"`) and the checks of an
//! `EXTERN` declaration against the arguments of a call.

use crate::alarm::Alarm;
use crate::lang::{Expr, VarType};

/// True for `L` followed by digits only: the name of a subprogram called by number.
pub(in crate::interp) fn is_l_call(name: &str) -> bool {
    name.len() > 1 && name.as_bytes()[0] == b'L' && name.bytes().skip(1).all(|b| b.is_ascii_digit())
}

/// The program a path or file name names: the last path component without the `_N_` prefix
/// and the `_SPF`/`_MPF` (or `.SPF`/`.MPF`) ending, upper case
/// (`/_N_WKS_DIR/_N_SHAFT_WPD/_N_SHAFT_SPF` → `SHAFT`).
pub(in crate::interp) fn program_of_path(path: &str) -> String {
    let upper = path.trim().to_ascii_uppercase();
    let last = upper.rsplit(['/', '\\']).next().unwrap_or("");
    let base = last.strip_prefix("_N_").unwrap_or(last);
    let base = ["_SPF", "_MPF", ".SPF", ".MPF"].iter().find_map(|e| base.strip_suffix(e)).unwrap_or(base);
    base.to_string()
}

/// The `EXTERN` declarations met so far: name and parameters (by reference, type).
#[derive(Debug, Clone, Default)]
pub(in crate::interp) struct Externs(Vec<(String, Vec<(bool, VarType)>)>);

impl Externs {
    /// Notes a declaration; a later one of the same name replaces it.
    pub fn declare(&mut self, name: &str, params: &[(bool, VarType)]) {
        self.0.retain(|(n, _)| n != name);
        self.0.push((name.to_string(), params.to_vec()));
    }

    /// Checks a call of `name` with `args` against its declaration, if it has one: no more
    /// arguments than declared parameters (12340), a variable for each VAR parameter given
    /// an argument (12320). A subprogram without a declaration is called unchecked (the
    /// control knows the programs of its directories without EXTERN).
    pub fn check(&self, name: &str, args: &[Expr], line: u32) -> Result<(), Alarm> {
        let Some((_, params)) = self.0.iter().find(|(n, _)| n == name) else { return Ok(()) };
        if args.len() > params.len() {
            return Err(Alarm::too_many_arguments(
                line,
                &format!("{} arguments for {name}, declared with {} by EXTERN", args.len(), params.len()),
            ));
        }
        for (i, (arg, (by_reference, _))) in args.iter().zip(params).enumerate() {
            let variable =
                matches!(arg, Expr::RParam(_)) || matches!(arg, Expr::Var { name, .. } if !name.starts_with('$'));
            if *by_reference && !variable && !is_omitted(arg) {
                return Err(Alarm::not_a_variable(line, &format!("{} of {name}", i + 1)));
            }
        }
        Ok(())
    }
}

/// An argument left out of a call (`L140(1,,3)`).
pub(in crate::interp) fn is_omitted(e: &Expr) -> bool {
    matches!(e, Expr::Call(n, a) if n == "_OMITTED" && a.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_name_their_program() {
        assert_eq!(program_of_path("/_N_WKS_DIR/_N_SHAFT_WPD/_N_SHAFT_SPF"), "SHAFT");
        assert_eq!(program_of_path("/_N_SPF_DIR/pocket_spf"), "POCKET");
        assert_eq!(program_of_path("CONTOUR.SPF"), "CONTOUR");
        assert_eq!(program_of_path("L10"), "L10");
    }

    #[test]
    fn l_calls_are_l_and_digits() {
        assert!(is_l_call("L10") && is_l_call("L0123"));
        assert!(!is_l_call("L") && !is_l_call("LIMS") && !is_l_call("L1A"));
    }
}
