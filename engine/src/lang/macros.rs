//! Macros of a program (Programming Manual Job planning, "Macro technique", `DEFINE ... AS`):
//! `DEFINE CLAMP AS M10` makes every later `CLAMP` of the program read `M10`. A macro name is
//! an identifier or an M, H, G or L word (`DEFINE M6 AS L6`, the classic tool change macro);
//! the replacement is the rest of the line up to a comment.
//!
//! The control replaces the text before it interprets the block; so does NCTwin, once per
//! program text, before the text is read: the definition line becomes a comment (it is a
//! definition, not an executable block, so DEFs may follow it), every later whole-word use
//! outside strings and comments gets the replacement, and the lines keep their numbers.
//! Decisions where the manual is silent or was not at hand:
//! - Macros are defined in the definition part, with the DEFs (before the first executable
//!   block; comments, archive headers, PROC and EXTERN may stand between them). A `DEFINE`
//!   after it is no definition: the block runs into alarm 12550 naming DEFINE. So only the
//!   head of a text is looked at, and a long program file is not read through for it (the
//!   command line gives the pages of a mapped file back as the run passes them).
//! - A macro holds for the rest of the program text it is defined in (a subprogram's macros are
//!   its own); the global macro files of the control (`_N_SMAC_DEF` ...) are not read.
//! - A replacement is not searched for macros again (the manual: macros do not nest).
//! - A second definition of a name replaces the first.
//! - A malformed definition (no name, no `AS`, a name that is not an identifier or an M/H/G/L
//!   word) is left as it is, so the parser refuses it at its line as a syntax error.
//! - Names are matched without regard to case, as all names of the language.

use std::borrow::Cow;

use super::ast::Diagnostic;

/// The text with its macros replaced, or the text itself when its definition part defines
/// none.
pub fn expand(text: &str) -> Cow<'_, str> {
    if !definition_part(text).any(starts_with_define) {
        return Cow::Borrowed(text);
    }
    let mut macros: Vec<(String, String)> = Vec::new();
    let mut defined = false;
    let mut in_head = true;
    let mut out = String::with_capacity(text.len() + text.len() / 8);
    for line in text.split_inclusive('\n') {
        let (body, end) = split_line_end(line);
        in_head = in_head && in_definition_part(body);
        match in_head.then(|| definition(body)).flatten() {
            Some((name, replacement)) => {
                macros.retain(|(n, _)| !n.eq_ignore_ascii_case(&name));
                macros.push((name, replacement));
                defined = true;
                out.push(';');
                out.push_str(body);
            }
            None if macros.is_empty() => out.push_str(body),
            None => replace_words(body, &macros, &mut out),
        }
        out.push_str(end);
    }
    if defined { Cow::Owned(out) } else { Cow::Borrowed(text) }
}

/// Syntax errors (12080) for the lines of an expanded text's definition part that still start
/// with `DEFINE`: the definitions [`expand`] could not read.
pub fn malformed(expanded: &str) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let mut offset = 0;
    for (i, line) in definition_part(expanded).enumerate() {
        if starts_with_define(line) {
            let message =
                "macro definition needs `DEFINE <name> AS <text>`, the name an identifier or an M, H, G or L word";
            let col = line.len() - line.trim_start().len();
            out.push(Diagnostic::syntax(u32::try_from(i + 1).unwrap_or(u32::MAX), offset, col, message.into()));
        }
        offset += line.len() + 1;
    }
    out
}

/// The lines of the text's definition part (see the module doc), from its start.
fn definition_part(text: &str) -> impl Iterator<Item = &str> {
    text.split('\n').take_while(|line| in_definition_part(line))
}

/// Whether `line` may stand in the definition part: blank, a comment, an archive header, or a
/// DEF, DEFINE, PROC or EXTERN statement (a block number may stand before it).
fn in_definition_part(line: &str) -> bool {
    let code = line.split(';').next().unwrap_or("").trim();
    if code.is_empty() || code.starts_with('%') {
        return true;
    }
    let code = strip_block_number(code);
    ["DEF", "PROC", "EXTERN"].iter().any(|k| {
        code.get(..k.len()).is_some_and(|w| w.eq_ignore_ascii_case(k))
            && code[k.len()..].chars().next().is_none_or(|c| c == ' ' || c == '\t' || c.eq_ignore_ascii_case(&'I'))
    })
}

/// `DEFINE <name> AS <replacement>` (a block number may stand before it): the name in upper
/// case and the replacement without its comment.
fn definition(line: &str) -> Option<(String, String)> {
    let code = line.split(';').next().unwrap_or("").trim();
    let code = strip_block_number(code);
    let rest = strip_keyword(code, "DEFINE")?;
    let name_len = rest.find(|c: char| !is_word_char(c)).unwrap_or(rest.len());
    let (name, rest) = rest.split_at(name_len);
    if !is_macro_name(name) {
        return None;
    }
    let replacement = strip_keyword(rest.trim_start(), "AS")?.trim();
    (!replacement.is_empty()).then(|| (name.to_ascii_uppercase(), replacement.to_string()))
}

/// An identifier (a letter or `_` first) or an address M, H, G or L with a number.
fn is_macro_name(name: &str) -> bool {
    let mut chars = name.chars();
    match chars.next() {
        Some(c) if c.is_ascii_alphabetic() || c == '_' => {}
        _ => return false,
    }
    let digits = name[1..].bytes().all(|b| b.is_ascii_digit()) && name.len() > 1;
    // A single letter with digits is an address word: only M, H, G and L words are macros.
    !digits || matches!(name.as_bytes()[0].to_ascii_uppercase(), b'M' | b'H' | b'G' | b'L')
}

/// `code` after `keyword` and at least one blank, or `None`.
fn strip_keyword<'a>(code: &'a str, keyword: &str) -> Option<&'a str> {
    let head = code.get(..keyword.len())?;
    let rest = &code[keyword.len()..];
    (head.eq_ignore_ascii_case(keyword) && rest.starts_with([' ', '\t'])).then(|| rest.trim_start())
}

/// `code` without a leading block number `N10` / `:10`.
fn strip_block_number(code: &str) -> &str {
    let b = code.as_bytes();
    if matches!(b.first(), Some(b'N' | b'n' | b':')) && b.get(1).is_some_and(u8::is_ascii_digit) {
        let digits = code[1..].find(|c: char| !c.is_ascii_digit()).map_or(code.len(), |i| i + 1);
        return code[digits..].trim_start();
    }
    code
}

/// Copies `line` to `out` with every whole-word macro name outside strings and the comment
/// replaced.
fn replace_words(line: &str, macros: &[(String, String)], out: &mut String) {
    let mut in_string = false;
    let mut i = 0;
    while i < line.len() {
        let c = line[i..].chars().next().expect("within the line");
        if in_string {
            in_string = c != '"';
        } else if c == '"' {
            in_string = true;
        } else if c == ';' {
            out.push_str(&line[i..]);
            return;
        } else if is_word_char(c) {
            let len = line[i..].find(|c: char| !is_word_char(c)).unwrap_or(line.len() - i);
            let word = &line[i..i + len];
            match macros.iter().rev().find(|(n, _)| n.eq_ignore_ascii_case(word)) {
                Some((_, replacement)) => out.push_str(replacement),
                None => out.push_str(word),
            }
            i += len;
            continue;
        }
        out.push(c);
        i += c.len_utf8();
    }
}

fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The line without its line end, and the line end (`\n`, `\r\n` or nothing).
fn split_line_end(line: &str) -> (&str, &str) {
    let body = line.trim_end_matches(['\n', '\r']);
    (body, &line[body.len()..])
}

/// Whether the line's code (after blanks and a block number) starts with `DEFINE`.
fn starts_with_define(line: &str) -> bool {
    let code = strip_block_number(line.trim_start());
    code.get(..6).is_some_and(|w| w.eq_ignore_ascii_case("DEFINE"))
}

#[cfg(test)]
mod tests {
    use super::expand;

    #[test]
    fn a_program_without_macros_is_not_copied() {
        let text = "G1 X10 F100\nM30\n";
        assert!(matches!(expand(text), std::borrow::Cow::Borrowed(_)));
    }

    #[test]
    fn later_uses_read_the_replacement_and_the_definition_becomes_a_comment() {
        let text = "DEFINE CLAMP AS M10 ; clamp\nN5 define LINE as G1 G94 F300\nCLAMP\nLINE X10 ; LINE here stays\nUNCLAMP R1=2\n";
        assert_eq!(
            expand(text),
            ";DEFINE CLAMP AS M10 ; clamp\n;N5 define LINE as G1 G94 F300\nM10\nG1 G94 F300 X10 ; LINE here stays\nUNCLAMP R1=2\n"
        );
    }

    #[test]
    fn address_words_and_strings_are_kept_and_only_m_h_g_l_words_are_macro_names() {
        let text = "; header\nDEFINE M6 AS L6\nDEFINE X1 AS Y1\nT1 M6\nM66 MSG(\"M6\")\nX1\n";
        assert_eq!(expand(text), "; header\n;DEFINE M6 AS L6\nDEFINE X1 AS Y1\nT1 L6\nM66 MSG(\"M6\")\nX1\n");
    }

    #[test]
    fn a_define_after_the_first_executable_block_is_no_definition() {
        let text = "DEF INT AA\nG0 X1\nDEFINE SPON AS M3\nSPON\n";
        assert!(matches!(expand(text), std::borrow::Cow::Borrowed(_)));
        assert!(crate::lang::check(text).is_empty(), "left to the run: 12550 naming DEFINE at line 3");
    }

    #[test]
    fn malformed_definitions_are_left_to_the_parser() {
        for line in ["DEFINE AS M10", "DEFINE CLAMP M10", "DEFINE CLAMP AS", "DEFINE 12 AS M3", "DEFINEX AS M3"] {
            let text = format!("{line}\nCLAMP\n");
            assert_eq!(expand(&text), text, "{line}");
        }
    }

    #[test]
    fn malformed_definitions_are_syntax_errors_at_their_line() {
        let errors = crate::lang::check("; header\nDEFINE CLAMP M10\nDEFINE OK AS M3\nOK\nM30\n");
        assert_eq!(errors.iter().map(|d| (d.alarm, d.line)).collect::<Vec<_>>(), [(12080, 2)], "{errors:?}");
        assert!(errors[0].message.contains("DEFINE <name> AS <text>"));
    }

    #[test]
    fn a_redefinition_replaces_the_first_and_line_ends_are_kept() {
        let text = "DEFINE SPON AS M3\r\nDEFINE SPON AS M4\r\nSPON\r\nSPON";
        assert_eq!(expand(text), ";DEFINE SPON AS M3\r\n;DEFINE SPON AS M4\r\nM4\r\nM4");
    }
}
