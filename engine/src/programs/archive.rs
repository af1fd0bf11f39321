//! Archive (punch-tape) files: several programs one after another, each opened by a header
//! line `%_N_NAME_MPF` (or `_SPF`, `_INI`, ...) and optionally a `;$PATH=/_N_MPF_DIR` line.
//!
//! Input: the file's text (already decoded; LF or CRLF). Output: one [`Entry`] per program,
//! borrowing its text, plus the lines that could not be read ([`Problem`]), so one bad header
//! never hides the other programs. [`write`] produces the same format.

use super::{Dir, Kind};

/// One program of an archive.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry<'a> {
    /// The name the header gives, upper case (not checked against the naming rules).
    pub name: String,
    pub kind: Kind,
    /// The directory of the `;$PATH=` line, if there is one.
    pub dir: Option<Dir>,
    /// 1-based line of the header in the archive.
    pub line: u32,
    /// From the header line to the end of the program (the line before the next header).
    pub text: &'a str,
    /// Byte offset in `text` where the program proper starts (after the header and PATH lines).
    body_start: usize,
}

impl<'a> Entry<'a> {
    /// The program without its header lines, as the control stores it.
    pub fn body(&self) -> &'a str {
        &self.text[self.body_start..]
    }

    /// 1-based line of the archive where [`Entry::body`] starts.
    pub fn body_line(&self) -> u32 {
        self.line + self.text[..self.body_start].matches('\n').count() as u32
    }

    /// The program with its header lines turned into comments (`%` → `;`): line numbers and
    /// byte offsets count from the header line, and a parser that does not know the header
    /// reads it as a comment.
    pub fn numbered_text(&self) -> String {
        let mut text = self.text.to_string();
        if text.starts_with('%') {
            text.replace_range(0..1, ";");
        }
        text
    }
}

/// A line of an archive that could not be read; it and the text up to the next header are
/// skipped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    pub line: u32,
    pub message: String,
}

/// The programs of an archive and its unreadable lines.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Archive<'a> {
    pub entries: Vec<Entry<'a>>,
    pub problems: Vec<Problem>,
}

/// The program being read: its header's line number, the byte offset of the header line, and
/// the header's name and kind (`None` for a header that could not be read).
type Open = (u32, usize, Option<(String, Kind)>);

/// Whether `text` is in archive format: its first line that is not blank starts with `%`
/// (a UTF-8 byte order mark before it is allowed).
pub fn is_archive(text: &str) -> bool {
    text.trim_start_matches('\u{feff}').trim_start().starts_with('%')
}

/// Splits an archive into its programs. Text before the first header may only be blank or
/// comment lines; anything else there is a [`Problem`] (and skipped).
pub fn split(text: &str) -> Archive<'_> {
    let mut archive = Archive::default();
    // (header line number, byte offset of the header line, parsed header) of the open entry.
    let mut open: Option<Open> = None;
    let mut stray_reported = false;
    let mut offset = 0;
    for (i, raw) in text.split_inclusive('\n').enumerate() {
        let line = i as u32 + 1;
        let content = raw.trim_end_matches(['\n', '\r']).trim_start_matches('\u{feff}');
        if content.starts_with('%') {
            close(text, open.take(), offset, &mut archive);
            let header = parse_header(content.trim_end());
            if header.is_none() {
                archive.problems.push(Problem {
                    line,
                    message: format!(
                        "`{}` is not a program header (%_N_NAME_MPF, %_N_NAME_SPF, %_N_NAME_INI)",
                        content.trim_end()
                    ),
                });
            }
            open = Some((line, offset, header));
        } else if open.is_none() && !stray_reported {
            let trimmed = content.trim();
            if !trimmed.is_empty() && !trimmed.starts_with(';') {
                archive.problems.push(Problem { line, message: "text before the first program header".into() });
                stray_reported = true;
            }
        }
        offset += raw.len();
    }
    close(text, open, offset, &mut archive);
    archive
}

/// Ends the open entry at byte `end`.
fn close<'a>(text: &'a str, open: Option<Open>, end: usize, archive: &mut Archive<'a>) {
    let Some((line, start, Some((name, kind)))) = open else { return };
    let text = &text[start..end];
    // The header line, then a `;$PATH=` line right after it.
    let after_header = text.find('\n').map_or(text.len(), |i| i + 1);
    let next = &text[after_header..];
    let next_line = next.split('\n').next().unwrap_or("").trim_end_matches('\r').trim();
    let (dir, body_start) = match next_line.get(..7) {
        Some(p) if p.eq_ignore_ascii_case(";$PATH=") => {
            let end = next.find('\n').map_or(next.len(), |i| i + 1);
            (Some(Dir::parse_path(&next_line[7..])), after_header + end)
        }
        _ => (None, after_header),
    };
    archive.entries.push(Entry { name, kind, dir, line, text, body_start });
}

/// `%_N_NAME_MPF`, `%_N_NAME_SPF`, `%_N_NAME_INI` (read by the language's own header reader,
/// which also knows `%MPF123`), or another file type of the control's archives (`%_N_X_DEF`,
/// kept as [`Kind::Other`] so it can be skipped by name).
fn parse_header(line: &str) -> Option<(String, Kind)> {
    if let Ok(header) = crate::lang::archive::header(line) {
        let kind = match header.kind {
            crate::lang::archive::ProgramKind::Main => Kind::Main,
            crate::lang::archive::ProgramKind::Sub => Kind::Sub,
            crate::lang::archive::ProgramKind::Ini => Kind::Ini,
        };
        return Some((header.name, kind));
    }
    let rest = line.strip_prefix('%')?;
    let rest = match rest.get(..3) {
        Some(p) if p.eq_ignore_ascii_case("_N_") => &rest[3..],
        _ => rest,
    };
    let (name, suffix) = rest.rsplit_once('_')?;
    let suffix_ok = suffix.len() == 3 && suffix.chars().all(|c| c.is_ascii_alphabetic());
    let name_ok = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    (suffix_ok && name_ok).then(|| (name.to_ascii_uppercase(), Kind::from_suffix(suffix)))
}

/// Appends one program in archive format: the header, the `;$PATH=` line when `dir` is given,
/// and `body` (a final line break added if it has none).
pub fn write(out: &mut String, name: &str, kind: &Kind, dir: Option<&Dir>, body: &str) {
    out.push_str(&format!("%_N_{name}_{}\n", kind.suffix()));
    if let Some(dir) = dir {
        out.push_str(&format!(";$PATH={}\n", dir.path()));
    }
    out.push_str(body);
    if !body.is_empty() && !body.ends_with('\n') {
        out.push('\n');
    }
}

/// Whether `text` is an NC data file: its first line that is not blank is the archive header
/// of an `_INI` file (`%_N_TOA_INI`).
pub fn is_data_file(text: &str) -> bool {
    let first = text.lines().map(str::trim).find(|l| !l.is_empty()).unwrap_or("");
    let upper = first.to_ascii_uppercase();
    upper.starts_with("%_N_") && upper.ends_with("_INI")
}

#[cfg(test)]
mod tests {
    use super::*;

    const ARCHIVE: &str = "%_N_PART1_MPF\r\n;$PATH=/_N_WKS_DIR/_N_SHAFT_WPD\r\nN10 G0 X0\r\nSUB1\r\nM30\r\n\
                           %_N_SUB1_SPF\r\n;$PATH=/_N_SPF_DIR\r\nG1 X5 F100\r\nM17\r\n\
                           %_N_TOA_INI\r\nCHANDATA(1)\r\n$TC_DP1[1,1]=120\r\nM17\r\n";

    #[test]
    fn an_archive_splits_into_its_programs_with_their_directories() {
        let archive = split(ARCHIVE);
        assert_eq!(archive.problems, []);
        let got: Vec<_> =
            archive.entries.iter().map(|e| (e.name.as_str(), e.kind.clone(), e.dir.clone(), e.line)).collect();
        assert_eq!(
            got,
            [
                ("PART1", Kind::Main, Some(Dir::Workpiece("SHAFT".into())), 1),
                ("SUB1", Kind::Sub, Some(Dir::Spf), 6),
                ("TOA", Kind::Ini, None, 10),
            ]
        );
        assert_eq!(archive.entries[0].body(), "N10 G0 X0\r\nSUB1\r\nM30\r\n");
        assert_eq!(archive.entries[0].body_line(), 3);
        assert_eq!(archive.entries[1].body(), "G1 X5 F100\r\nM17\r\n");
        assert_eq!(archive.entries[2].body(), "CHANDATA(1)\r\n$TC_DP1[1,1]=120\r\nM17\r\n");
        assert_eq!(archive.entries[2].body_line(), 11);
    }

    #[test]
    fn the_numbered_text_keeps_the_lines_and_comments_the_header_out() {
        let archive = split("%_N_A_MPF\n;$PATH=/_N_MPF_DIR\nG0 X1\n");
        assert_eq!(archive.entries[0].numbered_text(), ";_N_A_MPF\n;$PATH=/_N_MPF_DIR\nG0 X1\n");
    }

    #[test]
    fn a_bad_header_skips_its_program_only() {
        let archive = split("; exported\n%_N_A_MPF\nG0 X1\n%garbage here\nG0 X2\n%B_SPF\nM17");
        assert_eq!(archive.problems.len(), 1);
        assert_eq!(archive.problems[0].line, 4);
        let names: Vec<_> = archive.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["A", "B"]);
        assert_eq!(archive.entries[0].body(), "G0 X1\n");
        assert_eq!(archive.entries[1].body(), "M17");
        assert_eq!(archive.entries[1].dir, None);
    }

    #[test]
    fn text_before_the_first_header_is_a_problem() {
        let archive = split("G0 X1\n%_N_A_MPF\nM30\n");
        assert_eq!(archive.problems, [Problem { line: 1, message: "text before the first program header".into() }]);
        assert_eq!(archive.entries.len(), 1);
        assert!(is_archive("\u{feff}\n  %_N_A_MPF\n"));
        assert!(!is_archive("G0 X1\n%_N_A_MPF\n"));
    }

    #[test]
    fn written_archives_split_back_into_the_same_programs() {
        let mut out = String::new();
        write(&mut out, "PART1", &Kind::Main, Some(&Dir::Mpf), "G0 X1\nM30");
        write(&mut out, "SUB1", &Kind::Sub, Some(&Dir::Cus), "M17\n");
        assert_eq!(out, "%_N_PART1_MPF\n;$PATH=/_N_MPF_DIR\nG0 X1\nM30\n%_N_SUB1_SPF\n;$PATH=/_N_CUS_DIR\nM17\n");
        let archive = split(&out);
        assert_eq!(archive.entries[1].dir, Some(Dir::Cus));
        assert_eq!(archive.entries[1].body(), "M17\n");
    }
}
