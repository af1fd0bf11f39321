//! Programs as the control files them: names, types, directories, archive files, and the
//! store the interpreter calls subprograms from.
//!
//! Input: archive text (`%_N_NAME_MPF`, `;$PATH=/_N_MPF_DIR`, ...) or single program texts with
//! their directory. Output: [`archive::Entry`]s and a [`Programs`] store that resolves a called
//! name as the control does (the caller's directory, then `_N_SPF_DIR`, then the cycle
//! directories CUS, CMA, CST), reading and checking a program the first time it is called.
//! Reading files is not done here: the shell hands in a [`Loader`] per program.

pub mod archive;
pub mod cycles;
mod qualified;
mod store;

pub use qualified::{qualified_name, split_qualified};

pub use store::{CallError, Loader, Programs, StoredProgram};

use std::fmt;

/// A program's type: the suffix of its control-internal name (`_MPF`, `_SPF`, `_INI`, ...).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    /// `_MPF`: main program.
    Main,
    /// `_SPF`: subprogram.
    Sub,
    /// `_INI`: initialization data (tool data `_N_TOA_INI`, frames `_N_UFR_INI`, ...).
    Ini,
    /// Any other suffix (`_DEF`, `_COM`, ...), upper case without the `_`.
    Other(String),
}

impl Kind {
    /// The kind of a suffix such as `MPF` (any case).
    pub fn from_suffix(suffix: &str) -> Kind {
        match suffix.to_ascii_uppercase().as_str() {
            "MPF" => Kind::Main,
            "SPF" => Kind::Sub,
            "INI" => Kind::Ini,
            other => Kind::Other(other.to_string()),
        }
    }

    /// The suffix without `_`: `MPF`, `SPF`, `INI`, ...
    pub fn suffix(&self) -> &str {
        match self {
            Kind::Main => "MPF",
            Kind::Sub => "SPF",
            Kind::Ini => "INI",
            Kind::Other(s) => s,
        }
    }

    /// Main programs and subprograms: what the interpreter can call.
    pub fn is_program(&self) -> bool {
        matches!(self, Kind::Main | Kind::Sub)
    }
}

/// A directory of the control's passive file system that holds part programs.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Dir {
    /// `/_N_MPF_DIR`: main programs.
    Mpf,
    /// `/_N_SPF_DIR`: global subprograms.
    Spf,
    /// `/_N_WKS_DIR/_N_<NAME>_WPD`: a workpiece folder (name upper case).
    Workpiece(String),
    /// `/_N_CUS_DIR`: user cycles.
    Cus,
    /// `/_N_CMA_DIR`: manufacturer cycles.
    Cma,
    /// `/_N_CST_DIR`: Siemens standard cycles.
    Cst,
    /// Any other path, as written (e.g. `/_N_DEF_DIR`): kept, never searched.
    Other(String),
}

impl Dir {
    /// The directory of a `;$PATH=` value such as `/_N_WKS_DIR/_N_PART_WPD` (any case).
    pub fn parse_path(path: &str) -> Dir {
        let trimmed = path.trim().trim_end_matches('/');
        let upper = trimmed.to_ascii_uppercase();
        let parts: Vec<&str> = upper.split('/').filter(|p| !p.is_empty()).collect();
        match parts.as_slice() {
            ["_N_MPF_DIR"] => Dir::Mpf,
            ["_N_SPF_DIR"] => Dir::Spf,
            ["_N_CUS_DIR"] => Dir::Cus,
            ["_N_CMA_DIR"] => Dir::Cma,
            ["_N_CST_DIR"] => Dir::Cst,
            ["_N_WKS_DIR", wpd] => match wpd.strip_prefix("_N_").and_then(|w| w.strip_suffix("_WPD")) {
                Some(name) if !name.is_empty() => Dir::Workpiece(name.to_string()),
                _ => Dir::Other(trimmed.to_string()),
            },
            _ => Dir::Other(trimmed.to_string()),
        }
    }

    /// The path as a `;$PATH=` line writes it.
    pub fn path(&self) -> String {
        match self {
            Dir::Mpf => "/_N_MPF_DIR".into(),
            Dir::Spf => "/_N_SPF_DIR".into(),
            Dir::Workpiece(name) => format!("/_N_WKS_DIR/_N_{name}_WPD"),
            Dir::Cus => "/_N_CUS_DIR".into(),
            Dir::Cma => "/_N_CMA_DIR".into(),
            Dir::Cst => "/_N_CST_DIR".into(),
            Dir::Other(path) => path.clone(),
        }
    }

    /// The directory a program of `kind` lives in when nothing says otherwise.
    pub fn default_for(kind: &Kind) -> Dir {
        match kind {
            Kind::Sub => Dir::Spf,
            _ => Dir::Mpf,
        }
    }
}

impl fmt::Display for Dir {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.path())
    }
}

/// The canonical name of a program: letters, digits and `_`, at most 32 characters (the
/// control allows 24 in its file names, some tools 32), upper-cased; a `.MPF`/`.SPF` ending is
/// dropped. `None` for anything else. A name may start with a digit (part numbers such as
/// `4711_OP10` are common; the Programming Manual allows them: such a program is called with
/// `CALL "4711_OP10"`, not by its bare name), but not be one of the device names Windows
/// reserves (`CON`, `PRN`, `AUX`, `NUL`, `COM1`..`COM9`, `LPT1`..`LPT9`), which the manual
/// excludes.
pub fn canonical_name(name: &str) -> Option<String> {
    let upper = name.trim().to_ascii_uppercase();
    let base = upper.strip_suffix(".MPF").or_else(|| upper.strip_suffix(".SPF")).unwrap_or(&upper);
    let valid = !base.is_empty()
        && base.len() <= 32
        && base.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !is_reserved_device_name(base);
    valid.then(|| base.to_string())
}

fn is_reserved_device_name(name: &str) -> bool {
    matches!(name, "CON" | "PRN" | "AUX" | "NUL")
        || ["COM", "LPT"]
            .iter()
            .any(|p| name.strip_prefix(p).is_some_and(|d| d.len() == 1 && d.as_bytes()[0].is_ascii_digit() && d != "0"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_of_the_program_directories_read_back_as_written() {
        for dir in [Dir::Mpf, Dir::Spf, Dir::Workpiece("SHAFT".into()), Dir::Cus, Dir::Cma, Dir::Cst] {
            assert_eq!(Dir::parse_path(&dir.path()), dir);
        }
        assert_eq!(Dir::parse_path("/_n_wks_dir/_n_flange_wpd/"), Dir::Workpiece("FLANGE".into()));
        assert_eq!(Dir::parse_path("/_N_DEF_DIR"), Dir::Other("/_N_DEF_DIR".into()));
        assert_eq!(Dir::parse_path("/_N_WKS_DIR/_N__WPD"), Dir::Other("/_N_WKS_DIR/_N__WPD".into()));
    }

    #[test]
    fn names_follow_the_controls_rules() {
        assert_eq!(canonical_name("part1.mpf").as_deref(), Some("PART1"));
        assert_eq!(canonical_name("L123.SPF").as_deref(), Some("L123"));
        assert_eq!(canonical_name("1001.mpf").as_deref(), Some("1001"));
        assert_eq!(canonical_name("4711_op10").as_deref(), Some("4711_OP10"));
        assert_eq!(canonical_name("CON"), None);
        assert_eq!(canonical_name("lpt1.spf"), None);
        assert_eq!(canonical_name("COM10").as_deref(), Some("COM10"));
        assert_eq!(canonical_name(""), None);
        assert_eq!(canonical_name("PART-1"), None);
        assert_eq!(canonical_name(&"A".repeat(33)), None);
        assert_eq!(canonical_name(&"A".repeat(32)).map(|n| n.len()), Some(32));
    }
}
