//! The standard cycle library: NC programs shipped with NCTwin in the control's cycle directory
//! CST (`/_N_CST_DIR`), written by the NCTwin team from the documented parameter lists.
//!
//! The files live in `engine/cycles/` and are embedded at build time. Each is read and checked
//! once per process, at its first call. A session's own programs of the same name (in the
//! caller's directory, SPF, CUS, CMA, CST or the flat store) come first, as a user's or machine
//! builder's cycle overrides Siemens' on the control.

use std::sync::{Arc, LazyLock};

use super::store::StoredProgram;
use super::{Dir, Kind};

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/cycle_files.rs"));
}

static LIBRARY: LazyLock<Vec<StoredProgram>> = LazyLock::new(|| {
    embedded::FILES
        .iter()
        .map(|(name, text)| {
            StoredProgram::unchecked(name.to_string(), Some(Dir::Cst), Some(Kind::Sub), Arc::from(*text))
        })
        .collect()
});

/// The channel data the library declares for itself (`CYC_CONT_DEF.SPF`: the contour CYCLE62
/// names for CYCLE72), as the cycle package's definitions file does on the control: the name
/// check knows them before the first call declares them.
pub const GLOBALS: &[&str] = &["_CYC_CONT"];

/// Every cycle of the library, by name.
pub fn library() -> &'static [StoredProgram] {
    &LIBRARY
}

/// The library's cycle `name` (upper case), if there is one.
pub fn find(name: &str) -> Option<&'static StoredProgram> {
    LIBRARY.binary_search_by(|p| p.name().cmp(name)).ok().map(|i| &LIBRARY[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_cycle_passes_the_check_and_declares_a_proc_of_its_own_name() {
        for cycle in library() {
            let text = cycle.ready().unwrap_or_else(|e| panic!("{}: {e:?}", cycle.name()));
            let proc_line = text
                .lines()
                .find(|l| l.trim_start().to_ascii_uppercase().starts_with("PROC "))
                .unwrap_or_else(|| panic!("{} has no PROC line", cycle.name()));
            let declared = proc_line.trim_start()[5..].trim_start();
            assert!(
                declared.to_ascii_uppercase().starts_with(cycle.name()),
                "{}: PROC names `{declared}`",
                cycle.name()
            );
        }
    }

    #[test]
    fn names_are_sorted_for_lookup() {
        assert!(library().windows(2).all(|w| w[0].name() < w[1].name()));
        for cycle in library() {
            assert!(find(cycle.name()).is_some());
        }
    }
}
