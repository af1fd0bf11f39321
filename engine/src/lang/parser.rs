//! Line-by-line parser for the Sinumerik block syntax. Errors are collected per line and the
//! parser goes on, so one run reports every syntax error of a program.

use super::archive;
use super::ast::*;
use super::cursor::Cursor;
use super::definitions::DefinitionPart;
use super::plain_line::is_plain_line;
use super::statement_scan::may_hold_statement;
use super::structure::Structure;

/// Parses a whole program into memory (tests, small programs).
pub fn parse(source: &str) -> Program {
    let expanded = super::macros::expand(source);
    let source = &*expanded;
    let mut program = Program::default();
    for (line, offset, result) in Lines::new(source, 0, 1) {
        match result {
            Ok(Some(block)) => program.blocks.push(block),
            Ok(None) => {}
            Err((col, message)) => program.diagnostics.push(Diagnostic::syntax(line, offset, col, message)),
        }
    }
    program
}

/// Every error of a program found before it runs, in one streaming pass that keeps no blocks:
/// syntax errors (one per line, the first of the line) and control structures that do not nest
/// (ENDIF without IF, a WHILE never closed, more than 16 levels), in line order.
pub fn check(source: &str) -> Vec<Diagnostic> {
    let expanded = super::macros::expand(source);
    let source = &*expanded;
    let mut structure = Structure::default();
    let mut definitions = DefinitionPart::default();
    let code = |offset: usize| next_line(source, offset).map_or("", |(text, _)| split_comment(text).0);
    let mut out = Vec::new();
    for (line, offset, result) in (Lines { build: false, ..Lines::new(source, 0, 1) }) {
        match result {
            Err((col, message)) => out.push(Diagnostic::syntax(line, offset, col, message)),
            Ok(Some(Block { stmt: Some(stmt), .. })) => {
                out.extend(structure.feed(&stmt, line, offset));
                if definitions.is_open() || matches!(stmt, Stmt::Def { .. } | Stmt::Proc { .. }) {
                    out.extend(definitions.feed(&stmt, code(offset), line, offset));
                }
            }
            Ok(_) if definitions.is_open() && !archive::is_header_line(code(offset)) => {
                definitions.close_if_executable(code(offset), line)
            }
            Ok(_) => {}
        }
    }
    // Apart from the line loop, which stays as lean as it was: only texts in archive form.
    if let Some((line, offset)) = archive::second_header(source) {
        let message = "a second archive header: an archive of several programs is stored program by program";
        out.push(Diagnostic::syntax(line, offset, 0, message.into()));
    }
    out.extend(structure.finish());
    for bad in super::macros::malformed(source) {
        if !out.iter().any(|d| d.line == bad.line) {
            out.push(bad);
        }
    }
    out.sort_by_key(|d| (d.line, d.column));
    out
}

/// Reads the next non-empty block at or after byte `offset` (which starts line `line`).
/// Returns the block (or its syntax error) and the offset and line number after it; `None` at
/// the end of the text. Lets a channel walk a program of any length without holding its blocks.
pub fn read_block(source: &str, offset: usize, line: u32) -> Option<(Result<Block, Diagnostic>, usize, u32)> {
    read_block_reusing(source, offset, line, &mut Vec::new())
}

/// [`read_block`] with the block's words built in `spare`'s allocation (taken from it, left
/// empty when a block is returned): a reader that hands each block's emptied word list back
/// (see `interp::flow`) parses block after block without allocating.
pub fn read_block_reusing(
    source: &str,
    offset: usize,
    line: u32,
    spare: &mut Vec<Word>,
) -> Option<(Result<Block, Diagnostic>, usize, u32)> {
    read_lines(source, offset, line, spare, false)
}

/// [`read_block_reusing`] for a reader that skips a branch and looks only at statements: lines
/// that cannot hold one are passed over unparsed (see `statement_scan.rs`), so the block
/// returned is the next one that may hold a statement (or its syntax error).
pub fn read_statement_block(
    source: &str,
    offset: usize,
    line: u32,
    spare: &mut Vec<Word>,
) -> Option<(Result<Block, Diagnostic>, usize, u32)> {
    read_lines(source, offset, line, spare, true)
}

/// The line loop of `Lines::next`, without the iterator's tuples: the block is built once and
/// moved out once.
fn read_lines(
    source: &str,
    mut offset: usize,
    mut line: u32,
    spare: &mut Vec<Word>,
    statements_only: bool,
) -> Option<(Result<Block, Diagnostic>, usize, u32)> {
    loop {
        let (text, next) = next_line(source, offset)?;
        let (l, off) = (line, offset);
        (offset, line) = (next, line + 1);
        if statements_only && !may_hold_statement(text) {
            continue;
        }
        match parse_line(text, l, off, true, spare) {
            Ok(Some(block)) => return Some((Ok(block), offset, line)),
            Ok(None) => {}
            Err((col, message)) => return Some((Err(Diagnostic::syntax(l, off, col, message)), offset, line)),
        }
    }
}

/// The line starting at byte `offset` (without its line end) and the offset after it; `None`
/// past the end of the text.
#[inline]
fn next_line(source: &str, offset: usize) -> Option<(&str, usize)> {
    if offset > source.len() || (offset == source.len() && offset > 0) {
        return None;
    }
    let rest = &source[offset..];
    let raw = rest.split('\n').next().unwrap_or("");
    Some((raw.strip_suffix('\r').unwrap_or(raw), offset + raw.len() + 1))
}

/// Iterator over the lines of a source: (line, offset of line start, parse result).
struct Lines<'a> {
    source: &'a str,
    offset: usize,
    line: u32,
    /// Build the blocks; without, only the syntax is checked (no words are kept).
    build: bool,
}

impl<'a> Lines<'a> {
    fn new(source: &'a str, offset: usize, line: u32) -> Self {
        Lines { source, offset, line, build: true }
    }
}

impl Iterator for Lines<'_> {
    type Item = (u32, usize, Result<Option<Block>, (usize, String)>);

    fn next(&mut self) -> Option<Self::Item> {
        let (text, next) = next_line(self.source, self.offset)?;
        let (line, offset) = (self.line, self.offset);
        self.offset = next;
        self.line += 1;
        // The check needs no block: a line of plain address words has neither errors nor
        // statements, which a byte scan finds faster than the parser.
        if !self.build && is_plain_line(text) {
            return Some((line, offset, Ok(None)));
        }
        Some((line, offset, parse_line(text, line, offset, self.build, &mut Vec::new())))
    }
}

/// A syntax error: column offset within the line and message.
type PResult<T> = Result<T, (usize, String)>;

/// Parses one line; `Ok(None)` for an empty line.
pub fn parse_block(text: &str, line: u32, offset: usize) -> PResult<Option<Block>> {
    parse_line(text, line, offset, true, &mut Vec::new())
}

/// Parses one line. Without `build` the line is only checked: the block comes back without
/// its words, label and comment, and nothing is copied for them. A block's words take
/// `spare`'s allocation (an empty line leaves it there).
fn parse_line(text: &str, line: u32, offset: usize, build: bool, spare: &mut Vec<Word>) -> PResult<Option<Block>> {
    if archive::is_header_line(text) {
        // `%_N_NAME_MPF`: the archive header names the program; it is no block.
        return archive::header(text).map(|_| None).map_err(|e| (0, e));
    }
    let (code, comment) = split_comment(text);
    let mut cur = Cursor::new(code);
    let mut block = Block {
        line,
        offset,
        skip: None,
        number: None,
        label: None,
        stmt: None,
        // The spare list's room, else room for a typical block's words: one allocation
        // instead of growing 1, 4, 8.
        words: match build && !code.is_empty() {
            true if spare.capacity() > 0 => std::mem::take(spare),
            true => Vec::with_capacity(8),
            false => Vec::new(),
        },
        comment: comment.filter(|_| build).map(|c| c.trim().to_string()),
    };
    cur.skip_ws();
    if cur.eat(b'/') {
        let level = cur.peek().filter(u8::is_ascii_digit).map_or(0, |d| d - b'0');
        block.skip = Some(level);
        cur.eat_digit();
        cur.skip_ws();
    }
    if let Some(c) = cur.peek().filter(|c| matches!(c.to_ascii_uppercase(), b'N' | b':')) {
        let save = cur.pos;
        cur.pos += 1;
        match cur.digits() {
            Some(d) if c == b':' || !cur.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') => {
                block.number = Some(d.parse().map_err(|_| (save, format!("block number {d} is too large")))?);
            }
            _ => cur.pos = save,
        }
        cur.skip_ws();
    }
    // A label is an identifier followed by ':' at the start of the block.
    let save = cur.pos;
    if let Some(span) = cur.ident_span() {
        if cur.eat(b':') {
            block.label = build.then(|| cur.upper(span));
        } else {
            cur.pos = save;
        }
    }
    cur.skip_ws();
    if super::sync_action::opens(cur.slice(cur.pos, code.len())) {
        // A synchronized action fills the rest of the line: checked here, compiled when the
        // block is prepared (see `sync_action.rs`).
        let rest = cur.slice(cur.pos, code.len());
        super::sync_action::parse(rest).map_err(|e| (cur.pos + e.col, e.message))?;
        if build {
            let text = Expr::Str(rest.trim_end().to_string());
            block.words.push(Word::Keyword { name: super::sync_action::SYNC_ACTION_WORD.into(), args: vec![text] });
        }
        return Ok(Some(block));
    }
    let save = cur.pos;
    if let Some(span) = cur.ident_span() {
        if let Some(id) = statement(&cur, span) {
            block.stmt = Some(parse_statement(id, &mut cur)?);
            cur.skip_ws();
            if !cur.at_end() {
                return Err((cur.pos, format!("unexpected text after {id}")));
            }
        } else {
            cur.pos = save;
        }
    }
    loop {
        cur.skip_ws();
        if cur.at_end() {
            break;
        }
        if let Some(name) = synchronized_action(&mut cur) {
            // A synchronized action after other words of a block (a block's own words may not
            // precede it): the block carries the opening word alone, which the interpreter
            // refuses with 12550 naming it.
            if build {
                block.words.push(Word::Keyword { name: name.to_string(), args: Vec::new() });
            }
            break;
        }
        let word = parse_word(&mut cur, build)?;
        if build {
            block.words.push(word);
        }
    }
    let empty = block.words.is_empty()
        && block.stmt.is_none()
        && block.number.is_none()
        && block.label.is_none()
        && block.skip.is_none();
    if empty && block.comment.is_none() {
        // Nothing to hand out: the (empty) word list goes back for the next line.
        if block.words.capacity() > spare.capacity() {
            *spare = block.words;
        }
        return Ok(None);
    }
    Ok(Some(block))
}

/// The word that opens a synchronized action (`WHEN`, `WHENEVER`, `FROM`, `EVERY`, also after
/// `ID=n`/`IDS=n`, which are read as words before it); the cursor is left at the end of the line.
fn synchronized_action(cur: &mut Cursor) -> Option<&'static str> {
    // Most words start with another letter: one byte settles them.
    if !matches!(cur.peek().map(|c| c.to_ascii_uppercase()), Some(b'W' | b'F' | b'E')) {
        return None;
    }
    let save = cur.pos;
    let span = cur.ident_span()?;
    let Some(name) = ["WHENEVER", "WHEN", "FROM", "EVERY"].into_iter().find(|n| cur.span_is(span, n)) else {
        cur.pos = save;
        return None;
    };
    while !cur.at_end() {
        cur.pos += 1;
    }
    Some(name)
}

fn split_comment(text: &str) -> (&str, Option<&str>) {
    let mut in_str = false;
    // Bytes, not chars: `"` and `;` are ASCII, so every index found is a char boundary.
    for (i, c) in text.bytes().enumerate() {
        match c {
            b'"' => in_str = !in_str,
            b';' if !in_str => return (&text[..i], Some(&text[i + 1..])),
            _ => {}
        }
    }
    (text, None)
}

const STATEMENTS: &[&str] = &[
    "DEF", "IF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "FOR", "ENDFOR", "REPEAT", "REPEATB", "UNTIL", "LOOP",
    "ENDLOOP", "CASE", "GOTOF", "GOTOB", "GOTO", "GOTOC", "GOTOS", "PROC", "RET", "EXTERN",
];

fn is_statement(id: &str) -> bool {
    STATEMENTS.contains(&id)
}

/// The statement keyword a name is, if any.
fn statement(cur: &Cursor, span: (usize, usize)) -> Option<&'static str> {
    let len = span.1 - span.0;
    STATEMENTS.iter().find(|s| s.len() == len && cur.span_is(span, s)).copied()
}

fn parse_statement(id: &str, cur: &mut Cursor) -> PResult<Stmt> {
    cur.skip_ws();
    Ok(match id {
        "DEF" => parse_def(cur)?,
        "IF" => {
            let cond = parse_expr(cur)?;
            cur.skip_ws();
            let goto = match goto_kind_at(cur) {
                Some(kind) => Some(parse_goto_target(kind, cur)?),
                None => None,
            };
            Stmt::If { cond, goto }
        }
        "ELSE" => Stmt::Else,
        "ENDIF" => Stmt::EndIf,
        "WHILE" => Stmt::While(parse_expr(cur)?),
        "ENDWHILE" => Stmt::EndWhile,
        "FOR" => {
            let var = parse_lvalue(cur)?;
            cur.skip_ws();
            if !cur.eat(b'=') {
                return Err((cur.pos, "FOR needs `variable = start TO end`".into()));
            }
            cur.skip_ws();
            let start = parse_expr(cur)?;
            cur.skip_ws();
            if !cur.eat_word("TO") {
                return Err((cur.pos, "FOR needs TO".into()));
            }
            cur.skip_ws();
            Stmt::For { var, start, end: parse_expr(cur)? }
        }
        "ENDFOR" => Stmt::EndFor,
        "REPEAT" if cur.at_end() => Stmt::Repeat,
        "REPEAT" | "REPEATB" => parse_section_repeat(id == "REPEATB", cur)?,
        "UNTIL" => Stmt::Until(parse_expr(cur)?),
        "LOOP" => Stmt::Loop,
        "ENDLOOP" => Stmt::EndLoop,
        "CASE" => parse_case(cur)?,
        "GOTOF" => Stmt::Goto(parse_goto_target(GotoKind::Forward, cur)?),
        "GOTOB" => Stmt::Goto(parse_goto_target(GotoKind::Backward, cur)?),
        "GOTO" => Stmt::Goto(parse_goto_target(GotoKind::Both, cur)?),
        "GOTOC" => Stmt::Goto(parse_goto_target(GotoKind::Continue, cur)?),
        "GOTOS" => Stmt::Goto(parse_goto_target(GotoKind::Start, cur)?),
        "PROC" => parse_proc(cur)?,
        "RET" => Stmt::Ret,
        "EXTERN" => parse_extern(cur)?,
        _ => unreachable!("not a statement: {id}"),
    })
}

fn goto_kind_at(cur: &mut Cursor) -> Option<GotoKind> {
    let save = cur.pos;
    let kind = cur.ident_span().and_then(|span| goto_kind(cur, span));
    if kind.is_none() {
        cur.pos = save;
    }
    kind
}

/// The jump a name stands for, if any.
fn goto_kind(cur: &Cursor, span: (usize, usize)) -> Option<GotoKind> {
    if span.1 - span.0 < 4 || !cur.span_is((span.0, span.0 + 4), "GOTO") {
        return None;
    }
    match span.1 - span.0 {
        4 => Some(GotoKind::Both),
        5 => match cur.slice(span.0 + 4, span.1).as_bytes()[0].to_ascii_uppercase() {
            b'F' => Some(GotoKind::Forward),
            b'B' => Some(GotoKind::Backward),
            b'C' => Some(GotoKind::Continue),
            b'S' => Some(GotoKind::Start),
            _ => None,
        },
        _ => None,
    }
}

fn parse_goto_target(kind: GotoKind, cur: &mut Cursor) -> PResult<Goto> {
    if kind == GotoKind::Start {
        return Ok(Goto { kind, target: JumpTarget::ProgramStart });
    }
    cur.skip_ws();
    let start = cur.pos;
    if cur.eat(b':') {
        let n = cur.digits().ok_or((start, "expected a block number after `:`".to_string()))?;
        return Ok(Goto { kind, target: JumpTarget::BlockNumber(block_number(n, start)?) });
    }
    if let Some(n) = cur.digits() {
        return Ok(Goto { kind, target: JumpTarget::BlockNumber(block_number(n, start)?) });
    }
    // A computed target: a string expression (`"N"<<R10`, `(LBL)`).
    if matches!(cur.peek(), Some(b'"' | b'(')) {
        return Ok(Goto { kind, target: JumpTarget::Expr(parse_expr(cur)?) });
    }
    let id = cur.ident().ok_or((start, "jump needs a label, a block number or a STRING expression".to_string()))?;
    if let Some(n) = id.strip_prefix('N').filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit())) {
        return Ok(Goto { kind, target: JumpTarget::BlockNumber(block_number(n, start)?) });
    }
    // `DEST[2]` or `DEST<<"X"`: an expression that starts with a name.
    let after = cur.pos;
    cur.skip_ws();
    if cur.peek() == Some(b'[') || cur.starts_with_ignore_case("<<") {
        cur.pos = start;
        return Ok(Goto { kind, target: JumpTarget::Expr(parse_expr(cur)?) });
    }
    cur.pos = after;
    Ok(Goto { kind, target: JumpTarget::Label(id) })
}

fn block_number(digits: &str, at: usize) -> PResult<u32> {
    digits.parse().map_err(|_| (at, "block number too large".to_string()))
}

fn parse_case(cur: &mut Cursor) -> PResult<Stmt> {
    let expr = parse_expr(cur)?;
    cur.skip_ws();
    if !cur.eat_word("OF") {
        return Err((cur.pos, "CASE needs OF".into()));
    }
    let mut arms = Vec::new();
    let mut default = None;
    loop {
        cur.skip_ws();
        if cur.at_end() {
            break;
        }
        if cur.eat_word("DEFAULT") {
            cur.skip_ws();
            let kind = goto_kind_at(cur).ok_or((cur.pos, "DEFAULT needs GOTOF/GOTOB".to_string()))?;
            default = Some(parse_goto_target(kind, cur)?);
            continue;
        }
        let (value, _) = parse_unary(cur, MAX_EXPR_DEPTH)?;
        cur.skip_ws();
        let kind = goto_kind_at(cur).ok_or((cur.pos, "CASE value needs GOTOF/GOTOB".to_string()))?;
        arms.push((value, parse_goto_target(kind, cur)?));
    }
    Ok(Stmt::Case { expr, arms, default })
}

fn parse_type(cur: &mut Cursor) -> PResult<VarType> {
    let start = cur.pos;
    let id =
        cur.ident().ok_or((start, "expected a type (INT, REAL, BOOL, CHAR, STRING[n], AXIS, FRAME)".to_string()))?;
    Ok(match id.as_str() {
        "INT" => VarType::Int,
        "REAL" => VarType::Real,
        "BOOL" => VarType::Bool,
        "CHAR" => VarType::Char,
        "AXIS" => VarType::Axis,
        "FRAME" => VarType::Frame,
        "STRING" => {
            cur.skip_ws();
            if !cur.eat(b'[') {
                return Err((cur.pos, "STRING needs its length: STRING[n]".into()));
            }
            let n = cur.digits().and_then(|d| d.parse::<u16>().ok()).filter(|n| (1..=400).contains(n));
            let n = n.ok_or((cur.pos, "STRING length must be 1..400".to_string()))?;
            if !cur.eat(b']') {
                return Err((cur.pos, "missing `]`".into()));
            }
            VarType::Str(n)
        }
        other => return Err((start, format!("unknown type {other}"))),
    })
}

fn parse_def(cur: &mut Cursor) -> PResult<Stmt> {
    // Optional storage class of global user data: DEF CHAN / DEF NCK.
    let global = cur.eat_word("CHAN") || cur.eat_word("NCK");
    if global {
        cur.skip_ws();
    }
    let ty = parse_type(cur)?;
    let mut vars = Vec::new();
    loop {
        cur.skip_ws();
        let start = cur.pos;
        let name = cur.ident().ok_or((start, "DEF needs a variable name".to_string()))?;
        if name.starts_with('$') || is_statement(&name) {
            return Err((start, format!("{name} cannot be a variable name")));
        }
        check_user_name(&name, start)?;
        let (dims, _) = parse_indices(cur, MAX_EXPR_DEPTH)?;
        cur.skip_ws();
        let init = if cur.eat(b'=') {
            cur.skip_ws();
            parse_init(cur)?
        } else {
            Vec::new()
        };
        vars.push(VarDecl { name, dims, init });
        cur.skip_ws();
        if !cur.eat(b',') {
            break;
        }
    }
    Ok(Stmt::Def { global, ty, vars })
}

/// The naming rule for user variables and parameters (Programming Manual, Fundamentals,
/// "Identifiers"): the first two characters are letters or underscores. A name such as `E`,
/// `I` or `E1` would read as an address with its value (`E1` = address E, value 1), so the
/// control cannot take it as a name.
fn check_user_name(name: &str, at: usize) -> PResult<()> {
    let lead = |b: Option<&u8>| b.is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_');
    let bytes = name.as_bytes();
    if lead(bytes.first()) && lead(bytes.get(1)) {
        return Ok(());
    }
    Err((at, format!("{name} is not a valid name: a user variable's name begins with two letters or underscores")))
}

/// `value`, `(v1, v2, ...)`, `SET(v1, ...)` or `REP(v)` (the latter as a one-element call).
fn parse_init(cur: &mut Cursor) -> PResult<Vec<Expr>> {
    let save = cur.pos;
    if let Some(id) = cur.ident() {
        cur.skip_ws();
        if id == "SET" && cur.eat(b'(') {
            return Ok(parse_args(cur, MAX_EXPR_DEPTH)?.0);
        }
        if id == "REP" && cur.eat(b'(') {
            return Ok(vec![Expr::Call("REP".into(), parse_args(cur, MAX_EXPR_DEPTH - 1)?.0)]);
        }
    }
    cur.pos = save;
    Ok(vec![parse_expr(cur)?])
}

/// An optional parameter list `(VAR REAL A, INT B[3])` of PROC or EXTERN: `(`, then for each
/// entry an optional `VAR` and a type, the rest of the entry read by `entry`, entries
/// separated by `,` up to `)`. No list at all is an empty one.
fn parse_param_list<T>(
    cur: &mut Cursor,
    what: &str,
    mut entry: impl FnMut(&mut Cursor, bool, VarType) -> PResult<T>,
) -> PResult<Vec<T>> {
    let mut params = Vec::new();
    cur.skip_ws();
    if !cur.eat(b'(') {
        return Ok(params);
    }
    cur.skip_ws();
    if cur.eat(b')') {
        return Ok(params);
    }
    loop {
        cur.skip_ws();
        let by_reference = cur.eat_word("VAR");
        cur.skip_ws();
        let ty = parse_type(cur)?;
        params.push(entry(cur, by_reference, ty)?);
        cur.skip_ws();
        if cur.eat(b')') {
            return Ok(params);
        }
        if !cur.eat(b',') {
            return Err((cur.pos, format!("expected `,` or `)` in {what}")));
        }
    }
}

fn parse_proc(cur: &mut Cursor) -> PResult<Stmt> {
    let name = cur.ident().ok_or((cur.pos, "PROC needs a name".to_string()))?;
    let params = parse_param_list(cur, "PROC parameters", |cur, by_reference, ty| {
        cur.skip_ws();
        let at = cur.pos;
        let pname = cur.ident().ok_or((at, "parameter needs a name".to_string()))?;
        check_user_name(&pname, at)?;
        let (dims, _) = parse_indices(cur, MAX_EXPR_DEPTH)?;
        Ok(Param { by_reference, ty, name: pname, dims })
    })?;
    // Attributes: SAVE, DISPLOF, DISPLON, SBLOF and ACTBLOCNO matter to the interpreter.
    let mut attributes = ProcAttributes::default();
    loop {
        cur.skip_ws();
        if cur.eat(b',') {
            continue;
        }
        match cur.ident_span() {
            Some(span) => {
                attributes.save |= cur.span_is(span, "SAVE");
                attributes.displof |= cur.span_is(span, "DISPLOF");
                attributes.actblocno |= cur.span_is(span, "ACTBLOCNO");
                attributes.sblof |= cur.span_is(span, "SBLOF");
                attributes.displon |= cur.span_is(span, "DISPLON");
            }
            None if cur.at_end() => break,
            None => cur.pos += 1,
        }
    }
    Ok(Stmt::Proc { name, params, attributes })
}

/// `REPEAT START P=n`, `REPEAT START END P=n`, `REPEATB LABEL P=n`: program section
/// repetition (labels or `N..` block numbers; without `P` the section runs once more).
fn parse_section_repeat(single: bool, cur: &mut Cursor) -> PResult<Stmt> {
    let mut targets = Vec::new();
    let mut count = None;
    loop {
        cur.skip_ws();
        if cur.at_end() {
            break;
        }
        let at = cur.pos;
        let id = cur.ident().ok_or((at, "REPEAT needs jump labels and `P=` repetitions".to_string()))?;
        cur.skip_ws();
        if id == "P" && cur.eat(b'=') {
            cur.skip_ws();
            count = Some(parse_expr(cur)?);
            continue;
        }
        if count.is_some() || targets.len() == if single { 1 } else { 2 } {
            return Err((at, format!("unexpected {id} in {}", if single { "REPEATB" } else { "REPEAT" })));
        }
        targets.push(match id.strip_prefix('N').filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit())) {
            Some(n) => JumpTarget::BlockNumber(block_number(n, at)?),
            None => JumpTarget::Label(id),
        });
    }
    let mut targets = targets.into_iter();
    let start = targets.next().ok_or((cur.pos, "REPEAT needs a jump label".to_string()))?;
    Ok(match single {
        true => Stmt::RepeatBlock { target: start, count },
        false => Stmt::RepeatSection { start, end: targets.next(), count },
    })
}

/// `EXTERN NAME(REAL, VAR INT, STRING[8])`: the parameter types of a subprogram, for the checks
/// of its calls.
fn parse_extern(cur: &mut Cursor) -> PResult<Stmt> {
    let name = cur.ident().ok_or((cur.pos, "EXTERN needs a name".to_string()))?;
    let params = parse_param_list(cur, "EXTERN parameter types", |cur, by_reference, ty| {
        // An array parameter's dimensions (`REAL[3]`) need no check here.
        cur.skip_ws();
        if cur.peek() == Some(b'[') {
            parse_indices(cur, MAX_EXPR_DEPTH)?;
        }
        Ok((by_reference, ty))
    })?;
    Ok(Stmt::Extern { name, params })
}

fn parse_lvalue(cur: &mut Cursor) -> PResult<Lvalue> {
    let start = cur.pos;
    let name = cur.ident().ok_or((start, "expected a variable".to_string()))?;
    Ok(Lvalue { name, indices: parse_indices(cur, MAX_EXPR_DEPTH)?.0 })
}

/// `[e1, e2, ...]` after a name, or nothing; each index at most `room` levels deep. Returns
/// the indices and the levels of the deepest (0 without indices).
fn parse_indices(cur: &mut Cursor, room: u32) -> PResult<(Vec<Expr>, u32)> {
    if !cur.eat(b'[') {
        return Ok((Vec::new(), 0));
    }
    let (mut out, mut depth) = (Vec::new(), 0);
    loop {
        cur.skip_ws();
        let (index, d) = expr_within(cur, room)?;
        out.push(index);
        depth = depth.max(d);
        cur.skip_ws();
        if cur.eat(b']') {
            return Ok((out, depth));
        }
        if !cur.eat(b',') {
            return Err((cur.pos, "expected `,` or `]`".into()));
        }
    }
}

/// One word; without `build` (a syntax check) a plain address gets no name.
fn parse_word(cur: &mut Cursor, build: bool) -> PResult<Word> {
    let start = cur.pos;
    let Some(c) = cur.peek() else { return Err((start, "unexpected end of block".into())) };
    if !(c.is_ascii_alphabetic() || c == b'_' || c == b'$') {
        return Err((start, format!("unexpected character `{}`", c as char)));
    }
    // `NAME=value` or `NAME[i]=value` (NAME may carry digits, e.g. axis X1 or R parameter R1).
    let save = cur.pos;
    if let Some(span) = cur.ident_span() {
        if let Some(kind) = goto_kind(cur, span) {
            return Ok(Word::Goto(parse_goto_target(kind, cur)?));
        }
        let (indices, _) = parse_indices(cur, MAX_EXPR_DEPTH)?;
        cur.skip_ws();
        if cur.peek() == Some(b'=') && cur.peek_at(1) != Some(b'=') {
            let name = super::name::of(cur.slice(span.0, span.1));
            cur.pos += 1;
            cur.skip_ws();
            let value = parse_address_value(cur)?;
            return Ok(Word::Address { name, indices, value });
        }
        if !indices.is_empty() {
            let name = cur.upper(span);
            // Axis-specific diameter programming (`DIAMONA[X]`) and the transverse axis of
            // constant cutting speed (`SCC[X]`): keywords with their axis.
            if matches!(name.as_str(), "DIAMONA" | "DIAM90A" | "DIAMOFA" | "DIACYCOFA" | "DIAMCHANA" | "SCC") {
                return Ok(Word::Keyword { name, args: indices });
            }
            return Err((cur.pos, format!("expected `=` after {name}[...]")));
        }
    }
    cur.pos = save;
    if c == b'$' {
        return Err((start, "a system variable needs `=` and a value".into()));
    }
    // One address letter followed directly by a number: `X10`, `G01`, `M30`, `X-5.5`. Longer
    // names with digits (`SUB1`, `L_PART2`) are identifiers: subprogram calls or keywords.
    let (from, to) = cur.letters();
    if to - from == 1 && c.eq_ignore_ascii_case(&b'L') && cur.peek().is_some_and(|c| c.is_ascii_digit()) {
        return parse_l_call(cur, from);
    }
    if to - from == 1 && cur.peek().is_some_and(|c| c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+')) {
        let letter = char::from(c.to_ascii_uppercase());
        let num_start = cur.pos;
        let value = cur.number().ok_or_else(|| (num_start, format!("bad number after {letter}")))?;
        return Ok(match letter {
            'G' | 'M' if value < 0.0 || value.fract() != 0.0 || value > u32::MAX as f64 => {
                return Err((num_start, format!("{letter} needs a whole number, found {value}")));
            }
            'G' => Word::G(value as u32),
            'M' => Word::M(value as u32),
            _ => Word::Address {
                name: super::name::letter(c).filter(|_| build).unwrap_or_default(),
                indices: Vec::new(),
                value: AddressValue { mode: None, expr: Expr::Number(value) },
            },
        });
    }
    // A keyword, possibly with arguments: `SUPA`, `TRANSMIT(1)`, `MSG("x")`.
    cur.pos = to;
    while cur.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_') {
        cur.pos += 1;
    }
    let name = cur.upper((from, cur.pos));
    match name.as_str() {
        "CALL" => return parse_call(cur, name),
        "PCALL" => return parse_pcall(cur, name),
        _ => {}
    }
    let mut args = Vec::new();
    cur.skip_ws();
    if cur.eat(b'(') {
        args = parse_args(cur, MAX_EXPR_DEPTH)?.0;
    } else if cur.peek() == Some(b'"') {
        // `CALL "NAME"`: a keyword with a string operand.
        args.push(parse_literal(cur)?);
    }
    Ok(Word::Keyword { name, args })
}

/// `CALL "NAME"`, `CALL NAME_VAR`, `CALL BLOCK START TO END`, `CALL "NAME" BLOCK START TO END`:
/// a keyword `CALL` whose first argument is the program name (omitted: the current program)
/// and, for a section call, the start and end label (or `N..` block number) as strings.
fn parse_call(cur: &mut Cursor, name: String) -> PResult<Word> {
    cur.skip_ws();
    let mut args = Vec::new();
    if cur.at_end() {
        return Ok(Word::Keyword { name, args });
    }
    let save = cur.pos;
    let section = cur.eat_word("BLOCK");
    if section {
        args.push(Expr::Call("_OMITTED".into(), Vec::new()));
    } else {
        cur.pos = save;
        args.push(parse_expr(cur)?);
        cur.skip_ws();
    }
    if section || cur.eat_word("BLOCK") {
        for keyword in ["", "TO"] {
            cur.skip_ws();
            if !keyword.is_empty() && !cur.eat_word(keyword) {
                return Err((cur.pos, "CALL BLOCK needs `start TO end`".into()));
            }
            cur.skip_ws();
            let at = cur.pos;
            let label = cur.ident().ok_or((at, "CALL BLOCK needs a label or block number".to_string()))?;
            args.push(Expr::Str(label));
        }
    }
    Ok(Word::Keyword { name, args })
}

/// `PCALL /_N_WKS_DIR/_N_SHAFT_WPD/_N_SHAFT_SPF(1, 2)` or `PCALL NAME(1, 2)`: the path as a
/// string, then the arguments.
fn parse_pcall(cur: &mut Cursor, name: String) -> PResult<Word> {
    cur.skip_ws();
    let start = cur.pos;
    while cur.peek().is_some_and(|c| c.is_ascii_alphanumeric() || matches!(c, b'_' | b'/' | b'.')) {
        cur.pos += 1;
    }
    if cur.pos == start {
        return Err((start, "PCALL needs a program path".into()));
    }
    let mut args = vec![Expr::Str(cur.slice(start, cur.pos).to_ascii_uppercase())];
    cur.skip_ws();
    if cur.eat(b'(') {
        args.extend(parse_args(cur, MAX_EXPR_DEPTH)?.0);
    }
    Ok(Word::Keyword { name, args })
}

/// `L123` or `L123(1, 2)`: the call of subprogram `L123`, named by its digits as written
/// (leading zeros count: `L0123` is another program than `L123`).
fn parse_l_call(cur: &mut Cursor, from: usize) -> PResult<Word> {
    while cur.peek().is_some_and(|c| c.is_ascii_digit()) {
        cur.pos += 1;
    }
    if cur.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_' || c == b'.') {
        return Err((cur.pos, "a subprogram number L.. is whole digits".into()));
    }
    let name = cur.upper((from, cur.pos));
    let save = cur.pos;
    cur.skip_ws();
    let args = if cur.eat(b'(') {
        parse_args(cur, MAX_EXPR_DEPTH)?.0
    } else {
        cur.pos = save;
        Vec::new()
    };
    Ok(Word::Keyword { name, args })
}

fn parse_address_value(cur: &mut Cursor) -> PResult<AddressValue> {
    let save = cur.pos;
    // The common case `A3=0.5`: a plain number that ends the word needs no expression parse.
    if let Some(value) = cur.number() {
        let end = cur.pos;
        if ends_word(cur) {
            cur.pos = end;
            return Ok(AddressValue { mode: None, expr: Expr::Number(value) });
        }
        cur.pos = save;
    }
    if let Some(span) = cur.ident_span() {
        const MODES: [(&str, CoordMode); 5] = [
            ("AC", CoordMode::Ac),
            ("IC", CoordMode::Ic),
            ("DC", CoordMode::Dc),
            ("ACP", CoordMode::Acp),
            ("ACN", CoordMode::Acn),
        ];
        let mode = MODES.iter().find(|(name, _)| cur.span_is(span, name)).map(|&(_, mode)| mode);
        cur.skip_ws();
        if let Some(mode) = mode.filter(|_| cur.peek() == Some(b'(')) {
            cur.pos += 1;
            let expr = parse_expr(cur)?;
            cur.skip_ws();
            if !cur.eat(b')') {
                return Err((cur.pos, format!("missing `)` after {}(", cur.upper(span))));
            }
            return Ok(AddressValue { mode: Some(mode), expr });
        }
    }
    cur.pos = save;
    if let Some(list) = parse_coefficients(cur)? {
        return Ok(AddressValue { mode: None, expr: list });
    }
    cur.pos = save;
    Ok(AddressValue { mode: None, expr: parse_expr(cur)? })
}

/// Name of the call that holds a coefficient list `(a, b, ...)`, the value of a polynomial
/// address such as `PO[PHI]=(a2, a3)`.
pub const COEFFICIENTS: &str = "_COEFFICIENTS";

/// `(a, b, ...)` with at least one comma: the coefficient list of a polynomial address, as
/// [`COEFFICIENTS`]`(a, b, ...)`. `None` (cursor moved) if the value is anything else.
fn parse_coefficients(cur: &mut Cursor) -> PResult<Option<Expr>> {
    cur.skip_ws();
    if !cur.eat(b'(') {
        return Ok(None);
    }
    // The list is a call: its items are one level below the value.
    let mut items = vec![expr_within(cur, MAX_EXPR_DEPTH - 1)?.0];
    cur.skip_ws();
    if cur.peek() != Some(b',') {
        return Ok(None);
    }
    while cur.eat(b',') {
        items.push(expr_within(cur, MAX_EXPR_DEPTH - 1)?.0);
        cur.skip_ws();
    }
    if !cur.eat(b')') {
        return Err((cur.pos, "missing `)` after the coefficient list".into()));
    }
    Ok(Some(Expr::Call(COEFFICIENTS.into(), items)))
}

/// True if nothing of an expression follows (end of block, comment, or the next word), so a
/// number read so far is the whole value. Moves the cursor.
fn ends_word(cur: &mut Cursor) -> bool {
    const OPERATORS: [&str; 10] = ["DIV", "MOD", "AND", "OR", "XOR", "NOT", "B_AND", "B_OR", "B_XOR", "B_NOT"];
    cur.skip_ws();
    match cur.peek() {
        None | Some(b';' | b'\n' | b'\r') => true,
        Some(c) if c.is_ascii_alphabetic() || c == b'_' => {
            cur.ident_span().is_some_and(|span| !OPERATORS.iter().any(|op| cur.span_is(span, op)))
        }
        _ => false,
    }
}

/// The arguments after `(` up to `)`, each at most `room` levels deep. Returns them and the
/// levels of the deepest (0 without arguments).
fn parse_args(cur: &mut Cursor, room: u32) -> PResult<(Vec<Expr>, u32)> {
    let (mut args, mut depth) = (Vec::new(), 0);
    cur.skip_ws();
    if cur.eat(b')') {
        return Ok((args, depth));
    }
    loop {
        cur.skip_ws();
        // An omitted argument (`TRAANG(,2)`) is kept as an empty string marker.
        if matches!(cur.peek(), Some(b',' | b')')) {
            if room == 0 {
                return Err(too_deep(cur.pos));
            }
            args.push(Expr::Call("_OMITTED".into(), Vec::new()));
            depth = depth.max(1);
        } else {
            let (arg, d) = expr_within(cur, room)?;
            args.push(arg);
            depth = depth.max(d);
        }
        cur.skip_ws();
        if cur.eat(b')') {
            return Ok((args, depth));
        }
        if !cur.eat(b',') {
            return Err((cur.pos, "expected `,` or `)` in argument list".into()));
        }
    }
}

/// Binary operators by priority level, lowest first (Programming Manual, "Priority of the
/// operations"): comparison < `<<` < OR < XOR < AND < B_OR < B_XOR < B_AND < `+ -` < `* / DIV MOD`.
const LEVELS: &[&[(&str, BinOp)]] = &[
    // `F1:F2` chains frames; it stands below (apart from) every other operator.
    &[(":", BinOp::Chain)],
    &[("==", BinOp::Eq), ("<>", BinOp::Ne), (">=", BinOp::Ge), ("<=", BinOp::Le), (">", BinOp::Gt), ("<", BinOp::Lt)],
    &[("<<", BinOp::Concat)],
    &[("OR", BinOp::Or)],
    &[("XOR", BinOp::Xor)],
    &[("AND", BinOp::And)],
    &[("B_OR", BinOp::BOr)],
    &[("B_XOR", BinOp::BXor)],
    &[("B_AND", BinOp::BAnd)],
    &[("+", BinOp::Add), ("-", BinOp::Sub)],
    &[("*", BinOp::Mul), ("/", BinOp::Div), ("DIV", BinOp::IntDiv), ("MOD", BinOp::Mod)],
];

/// The most levels an expression may have: its syntax tree's depth (a number or name is one
/// level, every operator, call and index one more), with a pair of parentheses and a unary `+`
/// counting as a level too. The parser refuses anything deeper (alarm 12080, "nested too
/// deeply", at the token one level too deep), so every pass that walks an expression
/// recursively (the parser itself, `eval`, the numeric fast path, the effect-call and main-run
/// scans, `Drop`, `Clone`) stays within this many nested calls. The flat `1+1+...+1` is covered
/// too: it is a left-deep tree, one level per operator.
///
/// Why 128: a real program nests a handful of levels and chains a few dozen operators at most
/// (a 50-way `OR` of comparisons is about 50 levels). In a debug build the deepest pass, the parser on
/// nested calls, takes about 5 KiB a level: 128 levels stay within half of a 2 MiB thread stack
/// (a tokio worker's, `std::thread`'s), the other half left to the server's frames above it
/// (`engine/tests/deep_expressions.rs` runs every pass on a 1 MiB thread).
pub const MAX_EXPR_DEPTH: u32 = 128;

/// The syntax error of an expression deeper than [`MAX_EXPR_DEPTH`], at byte `at`.
fn too_deep(at: usize) -> (usize, String) {
    (at, format!("expression nested too deeply (more than {MAX_EXPR_DEPTH} levels)"))
}

/// An expression and the levels of its tree (1 for a number).
type Deep = (Expr, u32);

/// Parses an expression with the control's operator priorities; equal priorities associate
/// to the left. At most [`MAX_EXPR_DEPTH`] levels.
pub(crate) fn parse_expr(cur: &mut Cursor) -> PResult<Expr> {
    Ok(expr_within(cur, MAX_EXPR_DEPTH)?.0)
}

/// An expression of at most `room` levels (a syntax error if deeper) and its levels. Every
/// parse function below takes the room left to it: each level it builds, or parenthesis it
/// opens, passes one less on, so the parser's own recursion is bounded as well.
fn expr_within(cur: &mut Cursor, room: u32) -> PResult<Deep> {
    parse_binary(cur, 0, room)
}

/// Binary operators of priority `min` and above (indices into [`LEVELS`]), by precedence
/// climbing: one loop turn per operator instead of one call per priority level per operand.
/// The operator found at a place is the one the levels give when asked from the highest
/// priority down, as a descent through the levels would find it. A chain of operators is a
/// left-deep tree: each one adds a level.
fn parse_binary(cur: &mut Cursor, min: usize, room: u32) -> PResult<Deep> {
    let (mut lhs, mut depth) = parse_unary(cur, room)?;
    while let Some((op, level, at)) = next_operator(cur, min) {
        if depth >= room {
            return Err(too_deep(at));
        }
        cur.skip_ws();
        let (rhs, d) = parse_binary(cur, level + 1, room - 1)?;
        lhs = Expr::Binary(op, Box::new(lhs), Box::new(rhs));
        depth = 1 + depth.max(d);
    }
    Ok((lhs, depth))
}

/// Consumes the operator that follows (after blanks) if its priority is `min` or above, and
/// says where it starts; the cursor stays put otherwise.
fn next_operator(cur: &mut Cursor, min: usize) -> Option<(BinOp, usize, usize)> {
    let save = cur.pos;
    cur.skip_ws();
    let at = cur.pos;
    // Most operands end at `)`, `,`, the end of the line or the next word: one byte settles it.
    let first = cur.peek().map(|c| c.to_ascii_uppercase());
    if !matches!(
        first,
        Some(b'*' | b'/' | b'+' | b'-' | b'=' | b'<' | b'>' | b'D' | b'M' | b'O' | b'X' | b'A' | b'B' | b':')
    ) {
        cur.pos = save;
        return None;
    }
    cur.pos = save;
    (min..LEVELS.len()).rev().find_map(|level| peek_operator(cur, LEVELS[level]).map(|op| (op, level, at)))
}

/// Consumes an operator of `ops` if one follows (after blanks); word operators must stand
/// alone (`AND`, not `ANDX`).
fn peek_operator(cur: &mut Cursor, ops: &[(&str, BinOp)]) -> Option<BinOp> {
    let save = cur.pos;
    cur.skip_ws();
    // Every primary asks each of the ten levels: most answers are settled by the first byte
    // (the end of the line, `)`, `,` or an operator of another level).
    let first = cur.peek().map(|c| c.to_ascii_uppercase());
    if !ops.iter().any(|(text, _)| Some(text.as_bytes()[0]) == first) {
        cur.pos = save;
        return None;
    }
    for (text, op) in ops {
        if cur.starts_with_ignore_case(text) {
            let after = cur.peek_at(text.len());
            let word = text.as_bytes()[0].is_ascii_alphabetic();
            let glued = word && after.is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_');
            // `<` must not take the first half of `<<`, `<>` or `<=`.
            let partial =
                *text == "<" && matches!(after, Some(b'<' | b'>' | b'=')) || *text == ">" && after == Some(b'=');
            if !glued && !partial {
                cur.pos += text.len();
                return Some(*op);
            }
        }
    }
    cur.pos = save;
    None
}

/// A unary operator and its operand, or a primary (a parenthesised expression, a name or a
/// literal); at most `room` levels. The recursive cases stay in small functions (their frames
/// pile up, one set per level); literals are read in [`parse_literal`], which returns before
/// anything nests.
fn parse_unary(cur: &mut Cursor, room: u32) -> PResult<Deep> {
    cur.skip_ws();
    if room == 0 {
        return Err(too_deep(cur.pos));
    }
    let op = if cur.eat(b'-') {
        UnOp::Neg
    } else if cur.eat(b'+') {
        // No node, but a level of the parser's recursion.
        return parse_unary(cur, room - 1);
    } else if cur.eat_word("NOT") {
        UnOp::Not
    } else if cur.eat_word("B_NOT") {
        UnOp::BNot
    } else {
        return match cur.peek() {
            // `(`, names and literals straight from here: one frame less per level.
            Some(b'(') => parenthesised(cur, room),
            Some(c) if c.is_ascii_alphabetic() || c == b'_' || c == b'$' => parse_name(cur, room),
            _ => Ok((parse_literal(cur)?, 1)),
        };
    };
    let (e, d) = parse_unary(cur, room - 1)?;
    Ok((Expr::Unary(op, Box::new(e)), d + 1))
}

/// `(expr)` at the cursor; the parenthesis takes a level of `room`.
fn parenthesised(cur: &mut Cursor, room: u32) -> PResult<Deep> {
    cur.pos += 1;
    let e = parse_binary(cur, 0, room - 1)?;
    cur.skip_ws();
    if !cur.eat(b')') {
        return Err((cur.pos, "missing `)`".into()));
    }
    Ok(e)
}

/// A name: TRUE/FALSE, an R parameter, a call with its arguments or a variable with its
/// indices; at most `room` levels (at least 1).
fn parse_name(cur: &mut Cursor, room: u32) -> PResult<Deep> {
    // The name is read in `name_head`, whose frame is gone before the arguments nest.
    match name_head(cur, room)? {
        NameHead::Done(e) => Ok(e),
        NameHead::Call(id) => {
            let (args, d) = parse_args(cur, room - 1)?;
            Ok((Expr::Call(id, args), 1 + d))
        }
        NameHead::Indexed(id) => {
            let (indices, d) = parse_indices(cur, room - 1)?;
            if (id == "$R" || id == "R") && indices.len() == 1 {
                return Ok((Expr::RParam(Box::new(indices.into_iter().next().expect("one index"))), 1 + d));
            }
            Ok((Expr::Var { name: id, indices }, 1 + d))
        }
    }
}

/// A name read up to what may follow it.
enum NameHead {
    /// The whole expression: TRUE, FALSE, `R1`.
    Done(Deep),
    /// A call: the cursor is after `(`.
    Call(String),
    /// A variable, with indices (`[`) or without.
    Indexed(String),
}

fn name_head(cur: &mut Cursor, room: u32) -> PResult<NameHead> {
    let start = cur.pos;
    let span = cur.ident_span().ok_or((start, "bad name".to_string()))?;
    if cur.span_is(span, "TRUE") {
        return Ok(NameHead::Done((Expr::Bool(true), 1)));
    }
    if cur.span_is(span, "FALSE") {
        return Ok(NameHead::Done((Expr::Bool(false), 1)));
    }
    // `R1`, the most frequent name of all: no upper-cased copy of it is made.
    let text = cur.slice(span.0, span.1);
    if let Some(n) = text.strip_prefix(['R', 'r']).and_then(|n| n.parse::<u32>().ok()) {
        // Two levels: the parameter and its number.
        if room < 2 {
            return Err(too_deep(start));
        }
        return Ok(NameHead::Done((Expr::RParam(Box::new(Expr::Number(n as f64))), 2)));
    }
    let id = cur.upper(span);
    let save = cur.pos;
    cur.skip_ws();
    if cur.eat(b'(') && !id.starts_with('$') {
        return Ok(NameHead::Call(id));
    }
    cur.pos = save;
    Ok(NameHead::Indexed(id))
}

/// A string, a `'H..'`/`'B..'`/character literal or a number (or the error at the next byte).
fn parse_literal(cur: &mut Cursor) -> PResult<Expr> {
    let start = cur.pos;
    match cur.peek() {
        Some(b'"') => {
            cur.pos += 1;
            let s = cur.pos;
            while cur.peek().is_some_and(|c| c != b'"') {
                cur.pos += 1;
            }
            if !cur.eat(b'"') {
                return Err((start, "unterminated string".into()));
            }
            Ok(Expr::Str(cur.slice(s, cur.pos - 1).to_string()))
        }
        Some(b'\'') => {
            cur.pos += 1;
            let s = cur.pos;
            while cur.peek().is_some_and(|c| c != b'\'') {
                cur.pos += 1;
            }
            if !cur.eat(b'\'') {
                return Err((start, "unterminated literal".into()));
            }
            let inner = cur.slice(s, cur.pos - 1);
            let (radix, digits) = match inner.as_bytes().first().map(u8::to_ascii_uppercase) {
                Some(b'H') => (16, &inner[1..]),
                Some(b'B') => (2, &inner[1..]),
                // A character constant: 'A'.
                _ if inner.chars().count() == 1 => {
                    return Ok(Expr::Number(inner.chars().next().unwrap_or('\0') as u32 as f64));
                }
                _ => return Err((start, format!("bad literal '{inner}' (use 'H..' or 'B..')"))),
            };
            u64::from_str_radix(digits, radix)
                .map(|v| Expr::Number(v as f64))
                .map_err(|_| (start, format!("bad {} literal '{inner}'", if radix == 16 { "hex" } else { "binary" })))
        }
        Some(c) if c.is_ascii_digit() || c == b'.' => {
            cur.number().map(Expr::Number).ok_or_else(|| (start, "bad number".into()))
        }
        Some(c) => Err((start, format!("unexpected character `{}` in expression", c as char))),
        None => Err((start, "missing value".into())),
    }
}

#[cfg(test)]
mod tests;
