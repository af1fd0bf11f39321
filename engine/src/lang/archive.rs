//! The archive (punched-tape) format of program files: a program may start with a header line
//! `%_N_<NAME>_MPF` (main program), `_SPF` (subprogram) or `_INI` (initialisation program),
//! usually followed by the comment `;$PATH=/_N_MPF_DIR`; one archive text may hold several
//! programs one after another, each starting with its header.
//!
//! Inside a program text the header is no block: the parser passes over it like an empty line
//! (see `parser.rs`), and [`super::check`] refuses one that follows an NC block (the start of a
//! second program: such a text is an archive file, which `crate::programs::archive` splits).

/// The kind of program a header names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramKind {
    /// `_MPF`: main program.
    Main,
    /// `_SPF`: subprogram.
    Sub,
    /// `_INI`: initialisation program (NC data).
    Ini,
}

/// The header of an archived program: its name (upper case, without `_N_` and the ending)
/// and kind.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ArchiveHeader {
    pub name: String,
    pub kind: ProgramKind,
}

/// True if `line` is a header line (starts with `%`): [`header`] says whether it is a valid one.
#[inline]
pub fn is_header_line(line: &str) -> bool {
    line.as_bytes().first() == Some(&b'%')
}

/// Reads a header line: `%_N_NAME_MPF`, `%_N_NAME_SPF`, `%_N_NAME_INI`, or the short
/// punched-tape forms `%MPF123` / `%SPF123` (named `MPF123` / `SPF123`). Blanks and a comment
/// after the header are allowed. `Err` with a message for a `%` line that is none of these.
pub fn header(line: &str) -> Result<ArchiveHeader, String> {
    let text = line.split(';').next().unwrap_or("").trim_end().to_ascii_uppercase();
    let bad = || format!("bad archive header `{}`: expected %_N_<NAME>_MPF, _SPF or _INI", line.trim_end());
    let body = text.strip_prefix('%').ok_or_else(bad)?;
    let valid_name = |n: &str| crate::programs::canonical_name(n).is_some_and(|c| c == n);
    if let Some(rest) = body.strip_prefix("_N_") {
        let (name, ending) = rest.rsplit_once('_').ok_or_else(bad)?;
        let kind = match ending {
            "MPF" => ProgramKind::Main,
            "SPF" => ProgramKind::Sub,
            "INI" => ProgramKind::Ini,
            _ => return Err(bad()),
        };
        return if valid_name(name) { Ok(ArchiveHeader { name: name.to_string(), kind }) } else { Err(bad()) };
    }
    for (prefix, kind) in [("MPF", ProgramKind::Main), ("SPF", ProgramKind::Sub)] {
        if let Some(n) = body.strip_prefix(prefix).map(str::trim_start)
            && !n.is_empty()
            && n.bytes().all(|b| b.is_ascii_digit())
        {
            return Ok(ArchiveHeader { name: format!("{prefix}{n}"), kind });
        }
    }
    Err(bad())
}

/// The first header line (1-based line, offset) that follows an NC block in a text in archive
/// form (its first line that is not blank or a comment is a header): the start of a second
/// program, which a program text may not hold. A text that does not start with a header is
/// not searched (generated programs of any length pay nothing).
pub fn second_header(text: &str) -> Option<(u32, usize)> {
    let lead = text.lines().map(str::trim).find(|l| !l.is_empty() && !l.starts_with(';'))?;
    if !is_header_line(lead) {
        return None;
    }
    let mut blocks = false;
    let mut offset = 0;
    for (i, line) in text.split_inclusive('\n').enumerate() {
        if blocks && is_header_line(line) {
            return Some((i as u32 + 1, offset));
        }
        let code = line.trim();
        blocks |= !(code.is_empty() || code.starts_with(';') || is_header_line(code));
        offset += line.len();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_name_the_program_and_its_kind() {
        let h = header("%_N_PART1_MPF").unwrap();
        assert_eq!((h.name.as_str(), h.kind), ("PART1", ProgramKind::Main));
        let h = header("%_N_L140_SPF ; cycle").unwrap();
        assert_eq!((h.name.as_str(), h.kind), ("L140", ProgramKind::Sub));
        assert_eq!(header("%_N_TOA_INI\r").unwrap().kind, ProgramKind::Ini);
        assert_eq!(header("%_n_my_cycle_2_spf").unwrap().name, "MY_CYCLE_2");
        assert_eq!(header("%MPF 42").unwrap().name, "MPF42");
        for bad in ["%", "%_N_X_TXT", "%_N__MPF", "%PART1", "%_N_A-B_MPF"] {
            assert!(header(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_second_header_after_blocks_starts_another_program() {
        let text =
            "; archive\n%_N_MAIN_MPF\n;$PATH=/_N_MPF_DIR\nL10\nM30\n%_N_L10_SPF\n;$PATH=/_N_SPF_DIR\nR1=1\nM17\n";
        assert_eq!(second_header(text), Some((6, 50)));
        assert_eq!(second_header("; c\n%_N_A_MPF\n;$PATH=/_N_MPF_DIR\nM30\n"), None);
        assert_eq!(second_header("G0 X1\n%_N_B_MPF\n"), None);
    }
}
