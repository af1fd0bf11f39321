//! The words block preparation knows, asked without a block: which G numbers, keywords,
//! addresses and predefined functions exist. The static name check of a program
//! (`crate::check`) asks these before Cycle start, so that it flags exactly what a run would
//! refuse with 12470 (unknown G function) or 12550 (name not defined).
//!
//! Why here, a child of `modal.rs`: the G table and most keyword tests are the ones
//! [`super::collect`] uses (called on scratch words), so the answers cannot drift from what a
//! run does. The few names `collect` matches one by one are listed below; a test reads
//! `modal.rs` and `eval.rs` and fails when a name is matched there but missing here.

use super::{Words, frame_op, g_function, holder_keyword, is_nc_address};

/// Keywords `collect` (and the block steps before it) match by name. A bare keyword or one
/// with arguments, as the match arms allow either.
const KEYWORDS: &[&str] = &[
    "SUPA",
    "STOPRE",
    "NEWCONF",
    "CFC",
    "CFTCP",
    "CFIN",
    "NORM",
    "KONT",
    "KONTT",
    "KONTC",
    "CDON",
    "CDOF",
    "CDOF2",
    "CP",
    "PTP",
    "PTPG0",
    "PTPWOC",
    "CYCLE800",
    "MCALL",
    "WORKPIECE",
    "PCALL",
    "CALLPATH",
    "EXTCALL",
    "MSG",
    "CONTCAPON",
    "CONTCAPOF",
    "SETAL",
    "ORIRESET",
    "TOFFON",
    "TOFFOF",
    "TCA",
    "DELOBJ",
    "DELT",
    "SETMS",
    "FPR",
    "WAITM",
    "WAITMC",
    "WAITP",
    "PRESETON",
    "SETPIECE",
    "CALL",
    "CORRTRAFO", // synchronized actions' block words
    "CANCEL",
    "LOCK",
    "UNLOCK",
    "RESET",
    "WALIMON",
    "WALIMOF",
    "RTLION",
    "RTLIOF",
    "GETSELT",
    "CLEARM",
    "FGROUP",
    "FGREF",
    "CT",
    "CIP",
    "EXECSTRING",
    "SCC",
    "SPCON",
    "SPCOF",
    "WAITE",
    "GET",
    "GETD",
    "RELEASE",
];

/// Predefined functions of expressions (`eval.rs`: `call`, the frame functions; the tool list
/// and file functions resolved before evaluation; the value forms of SET/REP, FAD and empty
/// arguments).
const FUNCTIONS: &[&str] = &[
    "SIN",
    "COS",
    "TAN",
    "ASIN",
    "ACOS",
    "SQRT",
    "ABS",
    "POT",
    "TRUNC",
    "ROUND",
    "LN",
    "EXP",
    "STRLEN",
    "TOUPPER",
    "TOLOWER",
    "NUMBER",
    "ISNUMBER",
    "AXNAME",
    "AXSTRING",
    "ATAN2",
    "MINVAL",
    "MAXVAL",
    "INDEX",
    "RINDEX",
    "BOUND",
    "SUBSTR",
    "SPRINT",
    "TOINT",
    "TOREAL",
    "SET",
    "REP",
    "_OMITTED",
    "CTRANS",
    "CFINE",
    "CROT",
    "CROTS",
    "CSCALE",
    "CMIRROR",
    "CRPL",
    "GETT",
    "CHKDNO",
    "NEWT",
    "DELOBJ",
    "CORRTRAFO",
    "ISFILE",
    "PM",
    "PR",
    "ISVAR",
];

/// Whether `G<code>` is a G function of block preparation (else the run gives 12470).
pub(crate) fn is_g_function(code: u32) -> bool {
    match g_function(&mut Words::default(), code, 0) {
        Ok(()) => true,
        Err(alarm) => alarm.number != 12470,
    }
}

/// Whether `name` (upper case) is a keyword a block may hold, bare or with arguments: one of
/// the G-group words, frame instructions, transformations, file procedures, the block words of
/// synchronized actions or those `collect` matches by name. Not a subprogram name.
pub(crate) fn is_keyword(name: &str, has_args: bool) -> bool {
    if KEYWORDS.contains(&name)
        || crate::interp::everyday::is_inert_keyword(name, has_args)
        || crate::interp::spindles::is_diameter_axis_keyword(name)
        || crate::interp::transform::selection::is_keyword(name)
        || crate::interp::files::PROCEDURES.contains(&name)
        || name == crate::lang::sync_action::SYNC_ACTION_WORD
    {
        return true;
    }
    if has_args {
        return false;
    }
    // The tests `collect` makes of a bare keyword, on scratch words; one that refuses the
    // keyword with an alarm knows it all the same.
    let mut w = Words::default();
    w.ori.keyword(name)
        || w.path.keyword(name)
        || w.spline.keyword(name)
        || w.dynamics.keyword(name)
        || crate::interp::spindles::words::keyword(&mut w.spindle, name, 0).unwrap_or(true)
        || holder_keyword(&mut w, name, 0).unwrap_or(true)
        || frame_op(name).is_some()
}

/// Whether `name` (upper case) is an address of the control (`F`, `CR`, `ADIS`, `M2`, `ACC`,
/// `PO`, `AX`, `R10`...) rather than a variable or axis name.
pub(crate) fn is_address(name: &str) -> bool {
    is_nc_address(name)
        || crate::interp::everyday::extended_address(name).is_some()
        || crate::interp::dynamics::Percent::of(name).is_some()
        || matches!(name, "AX" | "PO" | "R" | "FGREF")
        || crate::interp::tools::programmable_offset::is_word(name)
        || crate::interp::path_control::positioning::is_word(name)
        || crate::interp::path_control::oscillation::is_word(name)
        || name.strip_prefix('R').is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

/// Whether `name` (upper case) is a predefined function of expressions.
pub(crate) fn is_function(name: &str) -> bool {
    FUNCTIONS.contains(&name) || name == crate::lang::COEFFICIENTS
}

/// Whether `name` is an L number call (`L123`), whose missing program is 14011.
pub(crate) fn is_l_call(name: &str) -> bool {
    crate::interp::calls::targets::is_l_call(name)
}

/// The program a `CALL "path"` names (`/_N_WKS_DIR/_N_SHAFT_WPD/_N_SHAFT_SPF` → `SHAFT`).
pub(crate) fn program_of_path(path: &str) -> String {
    crate::interp::calls::targets::program_of_path(path)
}

/// Whether `name` is a predefined constant an expression reads (`$PI`, `_FINISH`...).
pub(crate) fn is_constant(name: &str) -> bool {
    crate::interp::eval::nc_constants::is_constant(name)
        || crate::interp::eval::cycle_constants::constant(name).is_some()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quoted upper-case names in `text` between `from` and `to`.
    fn quoted(text: &str, from: &str, to: &str) -> Vec<String> {
        let start = text.find(from).expect("start marker");
        let end = start + text[start..].find(to).expect("end marker");
        text[start..end]
            .split('"')
            .skip(1)
            .step_by(2)
            .filter(|s| !s.is_empty() && s.bytes().all(|b| b.is_ascii_uppercase() || b.is_ascii_digit() || b == b'_'))
            .map(str::to_string)
            .collect()
    }

    #[test]
    fn every_keyword_collect_matches_by_name_is_known() {
        let modal = include_str!("../modal.rs");
        let arms = quoted(modal, "Word::Goto(goto) => w.goto", "Word::Keyword { name, .. } => return Err");
        let keywords: Vec<_> = arms.iter().filter(|n| !n.starts_with('_') && n.len() > 1).collect();
        assert!(keywords.len() > 30, "the scan found the keyword arms");
        for name in keywords {
            assert!(is_keyword(name, false) || is_keyword(name, true), "collect matches {name}: add it to KEYWORDS");
        }
    }

    #[test]
    fn every_function_eval_knows_is_known() {
        let eval = include_str!("../eval.rs");
        let names = quoted(eval, "fn call(name: &str", "\n}\n");
        assert!(names.len() > 20, "the scan found the function names");
        for name in names.iter().chain(&quoted(eval, "const FRAME_FUNCTIONS", ";")) {
            assert!(is_function(name), "eval calls {name}: add it to FUNCTIONS");
        }
    }

    #[test]
    fn g_functions_are_those_of_block_preparation() {
        for code in [0, 1, 2, 3, 4, 9, 17, 40, 41, 42, 54, 500, 505, 599, 64, 641, 601, 96, 331, 147, 60, 70, 710] {
            assert!(is_g_function(code), "G{code}");
        }
        for code in [6, 13, 999, 1234] {
            assert!(!is_g_function(code), "G{code}");
        }
    }

    #[test]
    fn keywords_addresses_and_functions_are_told_from_names() {
        assert!(is_keyword("TRANS", false) && is_keyword("TRAFOOF", false) && is_keyword("MSG", true));
        assert!(
            is_keyword("SOFT", false)
                && is_keyword("ORIWKS", false)
                && is_keyword("SPOS", true) == is_keyword("SPOS", true)
        );
        assert!(!is_keyword("TRANSS", false) && !is_keyword("CYCLE81", true));
        assert!(is_address("F") && is_address("CR") && is_address("M2") && is_address("R12") && is_address("ACC"));
        assert!(!is_address("QQ") && !is_address("RR1"));
        assert!(is_function("SIN") && is_function("CTRANS") && !is_function("SINN"));
    }
}
