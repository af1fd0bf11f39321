//! A program's stored name with its directory: `NAME` for the session's flat store,
//! `<directory path>/NAME` for a program filed in a directory of the control
//! (`/_N_WKS_DIR/_N_SHAFT_WPD/SHAFT`, `/_N_SPF_DIR/POCKET`). The shell stores, lists and
//! exports programs under this name, so a program keeps its directory across restarts.

use super::Dir;

/// The stored name of program `name` in `dir` (`None`: the flat store).
pub fn qualified_name(dir: Option<&Dir>, name: &str) -> String {
    match dir {
        Some(d) => format!("{}/{name}", d.path()),
        None => name.to_string(),
    }
}

/// The directory and the program name of a stored name: a name that starts with `/` has its
/// directory before the last `/`.
pub fn split_qualified(stored: &str) -> (Option<Dir>, &str) {
    let trimmed = stored.trim();
    match trimmed.rsplit_once('/') {
        Some((dir, name)) if trimmed.starts_with('/') && !dir.is_empty() => (Some(Dir::parse_path(dir)), name),
        _ => (None, trimmed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stored_name_keeps_its_directory() {
        let wpd = Dir::Workpiece("SHAFT".into());
        assert_eq!(qualified_name(Some(&wpd), "PART1"), "/_N_WKS_DIR/_N_SHAFT_WPD/PART1");
        assert_eq!(split_qualified("/_N_WKS_DIR/_N_SHAFT_WPD/PART1"), (Some(wpd), "PART1"));
        assert_eq!(split_qualified("/_N_SPF_DIR/POCKET"), (Some(Dir::Spf), "POCKET"));
        assert_eq!(split_qualified("PART1"), (None, "PART1"));
        assert_eq!(qualified_name(None, "PART1"), "PART1");
    }
}
