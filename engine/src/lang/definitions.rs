//! The definition part of a program: the control reads a program (or subprogram) as a
//! definition part (the PROC line, DEF, EXTERN) followed by the statement part. A DEF or PROC
//! after the first executable block is alarm 14500, found before the run, as the control's
//! compiler finds it when the program is selected.

use super::ast::{Diagnostic, Stmt};

/// Alarm 14500: DEF or PROC in the statement part.
pub const DEF_IN_STATEMENT_PART: u32 = 14500;

/// Follows a program's blocks in text order and reports DEF and PROC blocks after the first
/// executable block.
#[derive(Debug, Default)]
pub struct DefinitionPart {
    /// Line of the first executable block, once one was seen.
    closed_at: Option<u32>,
}

impl DefinitionPart {
    /// Whether the definition part is still open: a caller may skip [`Self::close_if_executable`]
    /// (and its look at the line's text) once it is closed.
    pub fn is_open(&self) -> bool {
        self.closed_at.is_none()
    }

    /// A block that is no definition: it closes the definition part when `code` (the line's text
    /// before its comment) holds more than a block number and a label.
    pub fn close_if_executable(&mut self, code: &str, line: u32) {
        if self.closed_at.is_none() && !only_number_and_label(code) {
            self.closed_at = Some(line);
        }
    }

    /// A block with a statement: DEF and PROC are checked, anything else closes the part.
    pub fn feed(&mut self, stmt: &Stmt, code: &str, line: u32, offset: usize) -> Option<Diagnostic> {
        let word = match stmt {
            Stmt::Def { .. } => "DEF",
            Stmt::Proc { .. } => "PROC",
            Stmt::Extern { .. } => return None,
            _ => {
                self.close_if_executable(code, line);
                return None;
            }
        };
        let first = self.closed_at?;
        let message = format!(
            "illegal {word} in the statement part: definitions belong before the first executable block (line {first})"
        );
        Some(Diagnostic::new(DEF_IN_STATEMENT_PART, line, offset, 0, message))
    }
}

/// `N10`, `:10`, `LABEL:`, `/` or nothing at all: no executable content.
fn only_number_and_label(code: &str) -> bool {
    let mut rest = code.trim_start().trim_start_matches('/').trim_start();
    if let Some(after) = rest.strip_prefix(['N', 'n', ':']) {
        let digits = after.len() - after.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        if digits > 0 {
            rest = after[digits..].trim_start();
        }
    }
    if let Some((label, after)) = rest.split_once(':')
        && !label.is_empty()
        && label.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    {
        rest = after;
    }
    rest.trim().is_empty()
}

#[cfg(test)]
mod tests {
    use super::only_number_and_label;

    #[test]
    fn numbers_labels_and_empty_blocks_are_not_executable() {
        for code in ["", "  ", "N10", "N10 ", ":20", "START:", "N5 START:", "/"] {
            assert!(only_number_and_label(code), "{code:?}");
        }
        for code in ["G0 X1", "N10 G1", "R1=2", "START: G0 X1", "MSG(\"A:B\")", "NAME"] {
            assert!(!only_number_and_label(code), "{code:?}");
        }
    }
}
