//! The walk over a program's blocks that finds the names a run would refuse.
//!
//! One streaming pass (no block list in memory): G functions, keywords and calls are judged
//! at once; variable names and jump destinations are noted when no word of the control knows
//! them and judged at the end, when every `DEF`, `PROC` parameter, label and block number of
//! the program is known (a jump may go forward).

use std::collections::{BTreeMap, BTreeSet};

use super::NameContext;
use crate::alarm::Alarm;
use crate::interp::vocabulary;
use crate::lang::{Block, Diagnostic, Expr, Goto, GotoKind, JumpTarget, Stmt, Word};

/// Functions whose arguments are words of their own (`DELOBJ(T_CARRIER)`), not expressions
/// over the program's names.
const WORD_ARGUMENTS: &[&str] = &["DELOBJ", "CORRTRAFO", "GETT", "CHKDNO"];

/// A name to judge at the end: what it is, the name, and where.
struct Pending {
    jump: bool,
    name: String,
    line: u32,
    line_start: usize,
}

pub(super) struct Walker<'a> {
    source: &'a str,
    ctx: &'a NameContext,
    /// Variables and parameters the program declares.
    declared: BTreeSet<String>,
    /// The program's own PROC name (a recursive call).
    procs: BTreeSet<String>,
    labels: BTreeSet<String>,
    numbers: BTreeSet<u32>,
    pending: Vec<Pending>,
    out: Vec<Diagnostic>,
    /// What the plain-line scan learnt: G numbers and single letters known or not.
    g_codes: BTreeMap<u32, bool>,
    letters: [Option<bool>; 26],
}

impl<'a> Walker<'a> {
    pub(super) fn new(source: &'a str, ctx: &'a NameContext) -> Walker<'a> {
        Walker {
            source,
            ctx,
            declared: BTreeSet::new(),
            procs: BTreeSet::new(),
            labels: BTreeSet::new(),
            numbers: BTreeSet::new(),
            pending: Vec::new(),
            out: Vec::new(),
            g_codes: BTreeMap::new(),
            letters: [None; 26],
        }
    }

    pub(super) fn run(mut self) -> Vec<Diagnostic> {
        let source = self.source;
        let (mut offset, mut line) = (0, 1);
        while offset < source.len() {
            let end = source[offset..].find('\n').map_or(source.len(), |n| offset + n);
            let text = source[offset..end].strip_suffix('\r').unwrap_or(&source[offset..end]);
            // Most lines of a toolpath are letters and plain numbers: judged from one byte scan,
            // the parser only for the others (and for a plain line with a word to report).
            if !crate::lang::plain_words(text, |letter, _, value| self.plain_word(letter, value))
                && let Some((Ok(block), _, _)) = crate::lang::read_block(source, offset, line)
                && block.line == line
            {
                self.block(&block);
            }
            (offset, line) = (end + 1, line + 1);
        }
        for p in std::mem::take(&mut self.pending) {
            let known = match p.jump {
                true => self.labels.contains(&p.name) || self.numbers_hold(&p.name) || self.declared.contains(&p.name),
                false => self.declared.contains(&p.name) || self.ctx.globals.contains(&p.name),
            };
            if !known {
                let alarm = match p.jump {
                    true => Alarm::jump_not_found(p.line, &p.name),
                    false => Alarm::unknown_name(p.line, &p.name),
                };
                self.flag(alarm, p.line, p.line_start, &p.name);
            }
        }
        self.out.sort_by_key(|d| (d.line, d.column));
        self.out.dedup_by(|a, b| a.line == b.line && a.message == b.message);
        self.out
    }

    /// Whether a word of a plain line (`G1`, `X10.5`, `N20`) is known; false sends the line to
    /// the parser (`L12` is a call there, `R1` a parameter, an unknown letter a name).
    fn plain_word(&mut self, letter: u8, value: f64) -> bool {
        match letter {
            b'G' => {
                let code = value as u32;
                *self.g_codes.entry(code).or_insert_with(|| vocabulary::is_g_function(code))
            }
            b'M' => true,
            b'N' => {
                self.numbers.insert(value as u32);
                true
            }
            b'L' | b'R' => false,
            b'A'..=b'Z' => *self.letters[usize::from(letter - b'A')].get_or_insert_with(|| {
                let name = char::from(letter).to_string();
                vocabulary::is_address(&name) || self.ctx.is_axis(&name)
            }),
            _ => false,
        }
    }

    fn block(&mut self, b: &Block) {
        if let Some(label) = &b.label {
            self.labels.insert(label.clone());
        }
        if let Some(n) = b.number {
            self.numbers.insert(n);
        }
        if let Some(stmt) = &b.stmt {
            self.statement(stmt, b);
        }
        for word in &b.words {
            self.word(word, b);
        }
    }

    fn statement(&mut self, stmt: &Stmt, b: &Block) {
        match stmt {
            Stmt::Def { vars, .. } => {
                for v in vars {
                    self.declared.insert(v.name.clone());
                    v.dims.iter().chain(&v.init).for_each(|e| self.expr(e, b));
                }
            }
            Stmt::Proc { name, params, .. } => {
                self.procs.insert(name.clone());
                for p in params {
                    self.declared.insert(p.name.clone());
                }
            }
            Stmt::If { cond, goto } => {
                self.expr(cond, b);
                if let Some(g) = goto {
                    self.goto(g, b);
                }
            }
            Stmt::While(e) | Stmt::Until(e) => self.expr(e, b),
            Stmt::For { var, start, end } => {
                if var.indices.is_empty() && !vocabulary::is_address(&var.name) {
                    self.note(false, &var.name, b);
                }
                var.indices.iter().chain([start, end]).for_each(|e| self.expr(e, b));
            }
            Stmt::Case { expr, arms, default } => {
                self.expr(expr, b);
                for (value, g) in arms {
                    self.expr(value, b);
                    self.goto(g, b);
                }
                if let Some(g) = default {
                    self.goto(g, b);
                }
            }
            Stmt::Goto(g) => self.goto(g, b),
            Stmt::RepeatSection { count, .. } | Stmt::RepeatBlock { count, .. } => {
                if let Some(e) = count {
                    self.expr(e, b);
                }
            }
            Stmt::Else
            | Stmt::EndIf
            | Stmt::EndWhile
            | Stmt::EndFor
            | Stmt::Repeat
            | Stmt::Loop
            | Stmt::EndLoop
            | Stmt::Ret
            | Stmt::Extern { .. } => {}
        }
    }

    fn word(&mut self, word: &Word, b: &Block) {
        match word {
            Word::G(code) if !vocabulary::is_g_function(*code) => {
                let token = format!("G{code}");
                self.flag(Alarm::unknown_g(b.line, *code), b.line, b.offset, &token);
            }
            Word::G(_) | Word::M(_) => {}
            Word::Goto(g) => self.goto(g, b),
            Word::Address { name, indices, value } => {
                if !name.starts_with('$') {
                    if !vocabulary::is_address(name) && !self.ctx.is_axis(name) {
                        self.note(false, name, b);
                    }
                    indices.iter().for_each(|e| self.expr(e, b));
                }
                self.expr(&value.expr, b);
            }
            Word::Keyword { name, args } => self.keyword(name, args, b),
        }
    }

    /// A bare word or call: a keyword of the control (its arguments are its own), a call of a
    /// program (its arguments are expressions), or a name the run refuses.
    fn keyword(&mut self, name: &str, args: &[Expr], b: &Block) {
        if name == "CALL"
            && let Some(Expr::Str(path)) = args.first()
        {
            let program = vocabulary::program_of_path(path);
            if !self.ctx.program_exists(&program) && !self.procs.contains(&program) {
                self.flag(Alarm::program_not_found(b.line, &program), b.line, b.offset, "CALL");
            }
            return;
        }
        if name == crate::lang::sync_action::SYNC_ACTION_WORD {
            return self.sync_action(args, b);
        }
        if vocabulary::is_keyword(name, !args.is_empty()) {
            return;
        }
        if self.ctx.program_exists(name) || self.procs.contains(name) {
            args.iter().for_each(|e| self.expr(e, b));
            return;
        }
        let alarm = match vocabulary::is_l_call(name) {
            true => Alarm::program_not_found(b.line, name),
            false => Alarm::unknown_name(b.line, name),
        };
        self.flag(alarm, b.line, b.offset, name);
    }

    /// A synchronized action: compiled as its block would be (without the session's
    /// technology cycles), its variables, functions and axes judged there. Only a name the
    /// compiler does not know is reported; its other alarms are the run's to give.
    fn sync_action(&mut self, args: &[Expr], b: &Block) {
        let [Expr::Str(text)] = args else { return };
        let Ok(parsed) = crate::lang::sync_action::parse(text) else { return };
        if let Err(alarm) = crate::interp::synchronized::compile::compile(&parsed, &self.ctx.cfg, b.line)
            && alarm.number == 12550
        {
            // The column is that of the name the alarm's text names (`... name $AA_IMM[X] not
            // defined ...`), without its index.
            let named = alarm.message.split(" name ").nth(1).and_then(|m| m.split([' ', '[']).next());
            let name = named.unwrap_or_default().to_string();
            self.flag(alarm, b.line, b.offset, &name);
        }
    }

    fn goto(&mut self, g: &Goto, b: &Block) {
        match &g.target {
            // GOTOC goes on when the destination is missing.
            _ if g.kind == GotoKind::Continue => {}
            JumpTarget::Label(label) => self.note(true, label, b),
            JumpTarget::BlockNumber(n) if !self.numbers.contains(n) => self.note(true, &format!("N{n}"), b),
            JumpTarget::Expr(e) => self.expr(e, b),
            JumpTarget::BlockNumber(_) | JumpTarget::ProgramStart => {}
        }
    }

    /// The names an expression reads: variables, axes, predefined functions and constants.
    fn expr(&mut self, e: &Expr, b: &Block) {
        match e {
            Expr::Number(_) | Expr::Str(_) | Expr::Bool(_) => {}
            Expr::RParam(i) | Expr::Unary(_, i) => self.expr(i, b),
            Expr::Binary(_, l, r) => {
                self.expr(l, b);
                self.expr(r, b);
            }
            // A system variable's indices may be words of their own (`$P_UIFR[1,X,TR]`).
            Expr::Var { name, .. } if name.starts_with('$') => {}
            Expr::Var { name, indices } => {
                let known = self.ctx.is_axis(name) || vocabulary::is_constant(name);
                if !known {
                    self.note(false, name, b);
                }
                indices.iter().for_each(|i| self.expr(i, b));
            }
            Expr::Call(name, args) => {
                if !vocabulary::is_function(name) {
                    self.flag(Alarm::unknown_name(b.line, name), b.line, b.offset, name);
                }
                if !WORD_ARGUMENTS.contains(&name.as_str()) {
                    args.iter().for_each(|a| self.expr(a, b));
                }
            }
        }
    }

    /// Notes a name to judge at the end (a later label or block number counts; a variable is
    /// declared before it is used or not at all).
    fn note(&mut self, jump: bool, name: &str, b: &Block) {
        if jump && self.numbers_hold(name) {
            return;
        }
        self.pending.push(Pending { jump, name: name.to_string(), line: b.line, line_start: b.offset });
    }

    /// `N<n>` of a block number already seen.
    fn numbers_hold(&self, name: &str) -> bool {
        name.strip_prefix('N').and_then(|n| n.parse().ok()).is_some_and(|n| self.numbers.contains(&n))
    }

    fn flag(&mut self, alarm: Alarm, line: u32, line_start: usize, name: &str) {
        let col = column(self.source, line_start, name);
        self.out.push(Diagnostic::new(alarm.number, line, line_start, col, alarm.message));
    }
}

/// The byte column (0-based) of `name` in the line starting at `line_start`: the first word
/// that is `name` (case-insensitive), else the first that begins with it and goes on with a
/// digit, `=`, `[` or `(`; the line's start when neither is found.
fn column(source: &str, line_start: usize, name: &str) -> usize {
    let text = source.get(line_start..).unwrap_or("");
    let text = &text[..text.find('\n').unwrap_or(text.len())];
    let bytes = text.as_bytes();
    let is_word = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'$';
    let mut first_prefixed = None;
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b';' {
            break;
        }
        if bytes[i] == b'"' {
            i += 1 + bytes[i + 1..].iter().position(|&c| c == b'"').unwrap_or(bytes.len() - i - 1) + 1;
            continue;
        }
        if !is_word(bytes[i]) {
            i += 1;
            continue;
        }
        let start = i;
        while i < bytes.len() && is_word(bytes[i]) {
            i += 1;
        }
        let word = &text[start..i];
        if word.eq_ignore_ascii_case(name) {
            return start;
        }
        let prefixed = word.len() > name.len()
            && word.is_char_boundary(name.len())
            && word[..name.len()].eq_ignore_ascii_case(name)
            && word.as_bytes()[name.len()].is_ascii_digit();
        if prefixed && first_prefixed.is_none() {
            first_prefixed = Some(start);
        }
    }
    first_prefixed.unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::column;

    #[test]
    fn the_column_is_that_of_the_name_in_its_line() {
        assert_eq!(column("G1 X10\nN20 G01 QQ=5 ; QQ", 7, "QQ"), 8);
        assert_eq!(column("MSG(\"QQ\") QQ=1", 0, "QQ"), 10);
        assert_eq!(column("g1 x10 cycle81(1)", 0, "CYCLE81"), 7);
        assert_eq!(column("N10 G1234 X1", 0, "G1234"), 4);
        assert_eq!(column("X10", 0, "X"), 0);
        assert_eq!(column("Y1 X10", 0, "X"), 3);
        assert_eq!(column("", 0, "X"), 0);
    }
}
