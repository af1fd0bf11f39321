//! The nesting of control structures, checked on the program text before it runs, so that a
//! program whose IF/WHILE/FOR/REPEAT/LOOP do not nest is refused before anything moves
//! (alarm 12640, invalid nesting; 12641, more than 16 levels).

use super::ast::{Diagnostic, Stmt};

/// Alarm 12640: invalid nesting of control structures.
pub const INVALID_NESTING: u32 = 12640;
/// Alarm 12641: nesting depth of control structures too large.
pub const NESTING_TOO_DEEP: u32 = 12641;
/// Levels of control structures per program level.
const MAX_DEPTH: usize = 16;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    If { has_else: bool },
    While,
    For,
    Repeat,
    Loop,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::If { .. } => "IF",
            Kind::While => "WHILE",
            Kind::For => "FOR",
            Kind::Repeat => "REPEAT",
            Kind::Loop => "LOOP",
        }
    }

    fn same(self, other: Kind) -> bool {
        std::mem::discriminant(&self) == std::mem::discriminant(&other)
    }
}

/// Open structures while the text is read line by line.
#[derive(Debug, Default)]
pub struct Structure {
    /// Kind, line and line start offset of each open structure, outermost first.
    open: Vec<(Kind, u32, usize)>,
}

impl Structure {
    /// Takes the statement of the block on `line` (starting at byte `offset`); returns the
    /// errors it shows.
    pub fn feed(&mut self, stmt: &Stmt, line: u32, offset: usize) -> Vec<Diagnostic> {
        let err = |alarm: u32, message: String| vec![Diagnostic::new(alarm, line, offset, 0, message)];
        let opened = match stmt {
            Stmt::If { goto: None, .. } => Some(Kind::If { has_else: false }),
            Stmt::While(_) => Some(Kind::While),
            Stmt::For { .. } => Some(Kind::For),
            Stmt::Repeat => Some(Kind::Repeat),
            Stmt::Loop => Some(Kind::Loop),
            _ => None,
        };
        if let Some(kind) = opened {
            self.open.push((kind, line, offset));
            if self.open.len() == MAX_DEPTH + 1 {
                return err(NESTING_TOO_DEEP, format!("more than {MAX_DEPTH} nested control structures"));
            }
            return Vec::new();
        }
        let (closer, expected) = match stmt {
            Stmt::Else => {
                return match self.open.last_mut() {
                    Some((Kind::If { has_else }, ..)) if !*has_else => {
                        *has_else = true;
                        Vec::new()
                    }
                    Some((Kind::If { .. }, if_line, _)) => {
                        err(INVALID_NESTING, format!("second ELSE for the IF of line {if_line}"))
                    }
                    None => Vec::new(),
                    _ => err(INVALID_NESTING, "ELSE without IF".into()),
                };
            }
            Stmt::EndIf => ("ENDIF", Kind::If { has_else: false }),
            Stmt::EndWhile => ("ENDWHILE", Kind::While),
            Stmt::EndFor => ("ENDFOR", Kind::For),
            Stmt::Until(_) => ("UNTIL", Kind::Repeat),
            Stmt::EndLoop => ("ENDLOOP", Kind::Loop),
            _ => return Vec::new(),
        };
        match self.open.iter().rposition(|(k, ..)| k.same(expected)) {
            Some(i) if i + 1 == self.open.len() => {
                self.open.pop();
                Vec::new()
            }
            // The closer belongs to an outer structure: the inner ones were never closed.
            Some(i) => {
                let inner: Vec<String> =
                    self.open.drain(i..).skip(1).map(|(k, l, _)| format!("{} of line {l}", k.name())).collect();
                err(INVALID_NESTING, format!("{closer} before the end of {}", inner.join(", ")))
            }
            // No structure open at all: real programs carry a stray ENDIF after a jump-form
            // `IF .. GOTOF`, which the control only minds when it is reached (the interpreter
            // raises 12640 there).
            None if self.open.is_empty() => Vec::new(),
            None => err(INVALID_NESTING, format!("{closer} without {}", expected.name())),
        }
    }

    /// The structures still open at the end of the text.
    pub fn finish(self) -> Vec<Diagnostic> {
        self.open
            .into_iter()
            .map(|(k, line, offset)| {
                Diagnostic::new(INVALID_NESTING, line, offset, 0, format!("{} is never closed", k.name()))
            })
            .collect()
    }
}
