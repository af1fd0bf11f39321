//! File names as the file functions take them (Programming Manual Job Planning, "File
//! functions"): `LOG`, `LOG.MPF`, `_N_LOG_MPF` or a path `/_N_MPF_DIR/_N_LOG_MPF`; without a
//! type the file is a main program (`_MPF`).

use crate::programs::{Dir, Kind, canonical_name};

/// A file the program names: its canonical name, the directory of its path (if it gave one)
/// and its type.
#[derive(Debug, Clone, PartialEq)]
pub struct FileName {
    pub name: String,
    pub dir: Option<Dir>,
    pub kind: Kind,
}

/// Why a file name names no file of the part-program store.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NameError {
    /// A directory of the control that holds no part programs (`/_N_DEF_DIR`, the root).
    PathNotPermitted,
    /// A path to no directory of the control.
    PathNotFound,
    /// Not a file name the control allows (letters, digits, `_`, a letter first, at most 32).
    BadName,
    /// A type other than the part programs' `_MPF`, `_SPF` (and `_INI`, read only).
    WrongType,
}

/// Parses a file name or path.
pub fn parse(spec: &str) -> Result<FileName, NameError> {
    let spec = spec.trim();
    let (dir, file) = match spec.rsplit_once('/') {
        Some(("", _)) => return Err(NameError::PathNotPermitted),
        Some((path, file)) => (Some(directory(path)?), file),
        None => (None, spec),
    };
    let upper = file.to_ascii_uppercase();
    let (base, kind) = if let Some(rest) = upper.strip_prefix("_N_") {
        match rest.rsplit_once('_') {
            Some((base, suffix)) if suffix.len() == 3 && suffix.chars().all(|c| c.is_ascii_alphabetic()) => {
                (base.to_string(), Kind::from_suffix(suffix))
            }
            _ => (rest.to_string(), Kind::Main),
        }
    } else if let Some((base, ext)) = upper.rsplit_once('.') {
        (base.to_string(), Kind::from_suffix(ext))
    } else {
        (upper, Kind::Main)
    };
    if !matches!(kind, Kind::Main | Kind::Sub | Kind::Ini) {
        return Err(NameError::WrongType);
    }
    let name = canonical_name(&base).filter(|n| *n == base).ok_or(NameError::BadName)?;
    Ok(FileName { name, dir, kind })
}

/// The directory of a path: one of the part-program directories, or why not.
fn directory(path: &str) -> Result<Dir, NameError> {
    match Dir::parse_path(path) {
        Dir::Other(p) => {
            let upper = p.to_ascii_uppercase();
            let control_dir = upper.strip_prefix("/_N_").is_some_and(|d| d.ends_with("_DIR") && !d.contains('/'));
            Err(if control_dir { NameError::PathNotPermitted } else { NameError::PathNotFound })
        }
        dir => Ok(dir),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok(spec: &str) -> (String, Option<Dir>, Kind) {
        let f = parse(spec).unwrap_or_else(|e| panic!("{spec}: {e:?}"));
        (f.name, f.dir, f.kind)
    }

    #[test]
    fn names_with_and_without_path_and_type() {
        assert_eq!(ok("log"), ("LOG".into(), None, Kind::Main));
        assert_eq!(ok("LOG.SPF"), ("LOG".into(), None, Kind::Sub));
        assert_eq!(ok("_N_MY_LOG_MPF"), ("MY_LOG".into(), None, Kind::Main));
        assert_eq!(ok("/_N_MPF_DIR/_N_LOG_MPF"), ("LOG".into(), Some(Dir::Mpf), Kind::Main));
        assert_eq!(
            ok("/_N_WKS_DIR/_N_SHAFT_WPD/_N_M1_SPF"),
            ("M1".into(), Some(Dir::Workpiece("SHAFT".into())), Kind::Sub)
        );
        assert_eq!(ok("/_N_SPF_DIR/LOG"), ("LOG".into(), Some(Dir::Spf), Kind::Main));
    }

    #[test]
    fn bad_names_and_paths_say_why() {
        assert_eq!(parse("/_N_DEF_DIR/_N_X_DEF"), Err(NameError::PathNotPermitted));
        assert_eq!(parse("/_N_LOG_MPF"), Err(NameError::PathNotPermitted));
        assert_eq!(parse("/TMP/_N_LOG_MPF"), Err(NameError::PathNotFound));
        assert_eq!(parse("_N_X_DEF"), Err(NameError::WrongType));
        assert_eq!(parse("NUL"), Err(NameError::BadName));
        assert_eq!(ok("1LOG"), ("1LOG".into(), None, Kind::Main));
        assert_eq!(parse("MY LOG"), Err(NameError::BadName));
        assert_eq!(parse(""), Err(NameError::BadName));
    }
}
