//! Line-by-line parser for the Sinumerik block syntax. Errors are collected per line and the
//! parser goes on, so one run reports every syntax error of a program.

use super::ast::*;

/// Parses a whole program into memory (tests, small programs).
pub fn parse(source: &str) -> Program {
    let mut program = Program::default();
    for (line, offset, result) in Lines::new(source, 0, 1) {
        match result {
            Ok(Some(block)) => program.blocks.push(block),
            Ok(None) => {}
            Err((col, message)) => program.diagnostics.push(Diagnostic { line, offset: offset + col, message }),
        }
    }
    program
}

/// Every syntax error of a program, found in one streaming pass that keeps no blocks.
pub fn check(source: &str) -> Vec<Diagnostic> {
    Lines::new(source, 0, 1)
        .filter_map(|(line, offset, r)| {
            r.err().map(|(col, message)| Diagnostic { line, offset: offset + col, message })
        })
        .collect()
}

/// Reads the next non-empty block at or after byte `offset` (which starts line `line`).
/// Returns the block (or its syntax error) and the offset and line number after it; `None` at
/// the end of the text. Lets a channel walk a program of any length without holding its blocks.
pub fn read_block(source: &str, offset: usize, line: u32) -> Option<(Result<Block, Diagnostic>, usize, u32)> {
    let mut lines = Lines::new(source, offset, line);
    loop {
        let (l, off, result) = lines.next()?;
        let after = (lines.offset, lines.line);
        match result {
            Ok(Some(block)) => return Some((Ok(block), after.0, after.1)),
            Ok(None) => {}
            Err((col, message)) => {
                return Some((Err(Diagnostic { line: l, offset: off + col, message }), after.0, after.1));
            }
        }
    }
}

/// Iterator over the lines of a source: (line, offset of line start, parse result).
struct Lines<'a> {
    source: &'a str,
    offset: usize,
    line: u32,
}

impl<'a> Lines<'a> {
    fn new(source: &'a str, offset: usize, line: u32) -> Self {
        Lines { source, offset, line }
    }
}

impl Iterator for Lines<'_> {
    type Item = (u32, usize, Result<Option<Block>, (usize, String)>);

    fn next(&mut self) -> Option<Self::Item> {
        if self.offset > self.source.len() || (self.offset == self.source.len() && self.offset > 0) {
            return None;
        }
        let rest = &self.source[self.offset..];
        let raw = rest.split('\n').next().unwrap_or("");
        let text = raw.strip_suffix('\r').unwrap_or(raw);
        let (line, offset) = (self.line, self.offset);
        self.offset += raw.len() + 1;
        self.line += 1;
        Some((line, offset, parse_block(text, line, offset)))
    }
}

/// Parses one line; `Ok(None)` for an empty line.
pub fn parse_block(text: &str, line: u32, offset: usize) -> Result<Option<Block>, (usize, String)> {
    let (code, comment) = split_comment(text);
    let mut cur = Cursor { src: code.as_bytes(), pos: 0 };
    let mut block = Block {
        line,
        offset,
        text: text.to_string(),
        skip: false,
        number: None,
        label: None,
        words: Vec::new(),
        comment: comment.map(|c| c.trim().to_string()),
    };
    cur.skip_ws();
    if cur.eat(b'/') {
        block.skip = true;
        cur.eat_digit();
        cur.skip_ws();
    }
    if let Some(c) = cur.peek().filter(|c| matches!(c.to_ascii_uppercase(), b'N' | b':')) {
        let save = cur.pos;
        cur.pos += 1;
        match cur.digits() {
            Some(d) if c != b'N' || !cur.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') => {
                block.number = Some(d.parse().map_err(|_| (save, format!("block number {d} is too large")))?);
            }
            _ => cur.pos = save,
        }
        cur.skip_ws();
    }
    // A label is an identifier followed by ':' at the start of the block.
    let save = cur.pos;
    if let Some(id) = cur.ident() {
        if cur.eat(b':') {
            block.label = Some(id);
        } else {
            cur.pos = save;
        }
    }
    loop {
        cur.skip_ws();
        if cur.at_end() {
            break;
        }
        let word = parse_word(&mut cur)?;
        block.words.push(word);
    }
    let empty = block.words.is_empty() && block.number.is_none() && block.label.is_none() && !block.skip;
    Ok(if empty && block.comment.is_none() { None } else { Some(block) })
}

fn split_comment(text: &str) -> (&str, Option<&str>) {
    let mut in_str = false;
    for (i, c) in text.char_indices() {
        match c {
            '"' => in_str = !in_str,
            ';' if !in_str => return (&text[..i], Some(&text[i + 1..])),
            _ => {}
        }
    }
    (text, None)
}

fn parse_word(cur: &mut Cursor) -> Result<Word, (usize, String)> {
    let start = cur.pos;
    let Some(c) = cur.peek() else { return Err((start, "unexpected end of block".into())) };
    if !(c.is_ascii_alphabetic() || c == b'_' || c == b'$') {
        return Err((start, format!("unexpected character `{}`", c as char)));
    }
    // `NAME=value` (NAME may carry digits, e.g. axis X1 or R parameter R1).
    let save = cur.pos;
    if let Some(id) = cur.ident() {
        cur.skip_ws();
        if cur.eat(b'=') {
            cur.skip_ws();
            let value = parse_address_value(cur)?;
            return Ok(Word::Address { name: id, value });
        }
    }
    cur.pos = save;
    // Letters followed directly by a number: `X10`, `G01`, `M30`, `X-5.5`.
    let letters = cur.letters();
    if letters.is_empty() {
        return Err((start, "expected an address letter".into()));
    }
    if cur.peek().is_some_and(|c| c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+')) {
        let num_start = cur.pos;
        let value = cur.number().ok_or_else(|| (num_start, format!("bad number after {letters}")))?;
        return Ok(match letters.as_str() {
            "G" | "M" if value < 0.0 || value.fract() != 0.0 || value > u32::MAX as f64 => {
                return Err((num_start, format!("{letters} needs a whole number, found {value}")));
            }
            "G" => Word::G(value as u32),
            "M" => Word::M(value as u32),
            _ => Word::Address { name: letters, value: AddressValue { mode: None, expr: Expr::Number(value) } },
        });
    }
    // A keyword, possibly with arguments: `SUPA`, `TRANSMIT(1)`, `MSG("x")`.
    let rest = cur.ident_continue();
    let name = format!("{letters}{rest}");
    let mut args = Vec::new();
    cur.skip_ws();
    if cur.eat(b'(') {
        args = parse_args(cur)?;
    }
    Ok(Word::Keyword { name, args })
}

fn parse_address_value(cur: &mut Cursor) -> Result<AddressValue, (usize, String)> {
    let save = cur.pos;
    if let Some(id) = cur.ident() {
        let mode = match id.as_str() {
            "AC" => Some(CoordMode::Ac),
            "IC" => Some(CoordMode::Ic),
            "DC" => Some(CoordMode::Dc),
            "ACP" => Some(CoordMode::Acp),
            "ACN" => Some(CoordMode::Acn),
            _ => None,
        };
        cur.skip_ws();
        if let Some(mode) = mode.filter(|_| cur.peek() == Some(b'(')) {
            cur.pos += 1;
            let expr = parse_expr(cur)?;
            cur.skip_ws();
            if !cur.eat(b')') {
                return Err((cur.pos, format!("missing `)` after {id}(")));
            }
            return Ok(AddressValue { mode: Some(mode), expr });
        }
    }
    cur.pos = save;
    Ok(AddressValue { mode: None, expr: parse_expr(cur)? })
}

fn parse_args(cur: &mut Cursor) -> Result<Vec<Expr>, (usize, String)> {
    let mut args = Vec::new();
    cur.skip_ws();
    if cur.eat(b')') {
        return Ok(args);
    }
    loop {
        args.push(parse_expr(cur)?);
        cur.skip_ws();
        if cur.eat(b')') {
            return Ok(args);
        }
        if !cur.eat(b',') {
            return Err((cur.pos, "expected `,` or `)` in argument list".into()));
        }
    }
}

/// `expr := term (('+'|'-') term)*` — spaces are allowed around operators.
pub(crate) fn parse_expr(cur: &mut Cursor) -> Result<Expr, (usize, String)> {
    let mut lhs = parse_term(cur)?;
    loop {
        let save = cur.pos;
        cur.skip_ws();
        let op = match cur.peek() {
            Some(b'+') => BinOp::Add,
            Some(b'-') => BinOp::Sub,
            _ => {
                cur.pos = save;
                return Ok(lhs);
            }
        };
        cur.pos += 1;
        cur.skip_ws();
        lhs = Expr::Binary(op, Box::new(lhs), Box::new(parse_term(cur)?));
    }
}

fn parse_term(cur: &mut Cursor) -> Result<Expr, (usize, String)> {
    let mut lhs = parse_unary(cur)?;
    loop {
        let save = cur.pos;
        cur.skip_ws();
        let op = match cur.peek() {
            Some(b'*') => BinOp::Mul,
            Some(b'/') => BinOp::Div,
            _ => {
                cur.pos = save;
                return Ok(lhs);
            }
        };
        cur.pos += 1;
        cur.skip_ws();
        lhs = Expr::Binary(op, Box::new(lhs), Box::new(parse_unary(cur)?));
    }
}

fn parse_unary(cur: &mut Cursor) -> Result<Expr, (usize, String)> {
    if cur.eat(b'-') {
        cur.skip_ws();
        return Ok(Expr::Neg(Box::new(parse_unary(cur)?)));
    }
    if cur.eat(b'+') {
        cur.skip_ws();
    }
    parse_primary(cur)
}

fn parse_primary(cur: &mut Cursor) -> Result<Expr, (usize, String)> {
    let start = cur.pos;
    match cur.peek() {
        Some(b'(') => {
            cur.pos += 1;
            cur.skip_ws();
            let e = parse_expr(cur)?;
            cur.skip_ws();
            if !cur.eat(b')') {
                return Err((cur.pos, "missing `)`".into()));
            }
            Ok(e)
        }
        Some(b'"') => {
            cur.pos += 1;
            let s = cur.pos;
            while cur.peek().is_some_and(|c| c != b'"') {
                cur.pos += 1;
            }
            if !cur.eat(b'"') {
                return Err((start, "unterminated string".into()));
            }
            Ok(Expr::Str(String::from_utf8_lossy(&cur.src[s..cur.pos - 1]).into_owned()))
        }
        Some(c) if c.is_ascii_digit() || c == b'.' => {
            cur.number().map(Expr::Number).ok_or_else(|| (start, "bad number".into()))
        }
        Some(b'$') => {
            let id = cur.ident().unwrap_or_default();
            if id == "$R" && cur.eat(b'[') {
                let n = cur.digits().and_then(|d| d.parse().ok());
                if let (Some(n), true) = (n, cur.eat(b']')) {
                    return Ok(Expr::RParam(n));
                }
                return Err((start, "expected $R[<number>]".into()));
            }
            Err((start, format!("system variable {id} is not supported in expressions yet")))
        }
        Some(c) if c.is_ascii_alphabetic() || c == b'_' => {
            let id = cur.ident().unwrap_or_default();
            if let Some(n) = id.strip_prefix('R').and_then(|n| n.parse::<u32>().ok()) {
                return Ok(Expr::RParam(n));
            }
            cur.skip_ws();
            if cur.eat(b'(') {
                return Ok(Expr::Call(id, parse_args(cur)?));
            }
            Err((start, format!("unknown name {id} in expression")))
        }
        Some(c) => Err((start, format!("unexpected character `{}` in expression", c as char))),
        None => Err((start, "missing value".into())),
    }
}

/// A byte cursor over one line's code part.
pub(crate) struct Cursor<'a> {
    src: &'a [u8],
    pos: usize,
}

impl Cursor<'_> {
    fn peek(&self) -> Option<u8> {
        self.src.get(self.pos).copied()
    }
    fn at_end(&self) -> bool {
        self.pos >= self.src.len()
    }
    fn eat(&mut self, c: u8) -> bool {
        if self.peek() == Some(c) {
            self.pos += 1;
            true
        } else {
            false
        }
    }
    fn eat_digit(&mut self) {
        if self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
    }
    fn skip_ws(&mut self) {
        while self.peek().is_some_and(|c| c == b' ' || c == b'\t') {
            self.pos += 1;
        }
    }
    fn digits(&mut self) -> Option<String> {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
        (self.pos > s).then(|| String::from_utf8_lossy(&self.src[s..self.pos]).into_owned())
    }
    fn letters(&mut self) -> String {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_' || (c == b'$' && self.pos == s)) {
            self.pos += 1;
        }
        String::from_utf8_lossy(&self.src[s..self.pos]).to_ascii_uppercase()
    }
    fn ident_continue(&mut self) -> String {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_') {
            self.pos += 1;
        }
        String::from_utf8_lossy(&self.src[s..self.pos]).to_ascii_uppercase()
    }
    /// An identifier: `$`? letter (letter | digit | `_`)*, upper-cased.
    fn ident(&mut self) -> Option<String> {
        let s = self.pos;
        self.eat(b'$');
        if !self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') {
            self.pos = s;
            return None;
        }
        self.ident_continue();
        Some(String::from_utf8_lossy(&self.src[s..self.pos]).to_ascii_uppercase())
    }
    /// A signed decimal number with optional `EX` exponent (`1.5EX3`).
    fn number(&mut self) -> Option<f64> {
        let s = self.pos;
        if matches!(self.peek(), Some(b'-' | b'+')) {
            self.pos += 1;
        }
        let int = self.digits();
        let frac = if self.eat(b'.') { self.digits() } else { None };
        if int.is_none() && frac.is_none() {
            self.pos = s;
            return None;
        }
        let mut text = String::from_utf8_lossy(&self.src[s..self.pos]).into_owned();
        if self.src[self.pos..].len() >= 2 && self.src[self.pos..self.pos + 2].eq_ignore_ascii_case(b"EX") {
            let save = self.pos;
            self.pos += 2;
            let sign = if self.eat(b'-') {
                "-"
            } else {
                self.eat(b'+');
                ""
            };
            match self.digits() {
                Some(e) => text = format!("{text}e{sign}{e}"),
                None => self.pos = save,
            }
        }
        if text.ends_with('.') {
            text.push('0');
        }
        text.parse::<f64>().ok().filter(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(src: &str) -> Vec<Word> {
        let p = parse(src);
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        p.blocks.into_iter().flat_map(|b| b.words).collect()
    }

    fn num(name: &str, v: f64) -> Word {
        Word::Address { name: name.into(), value: AddressValue { mode: None, expr: Expr::Number(v) } }
    }

    #[test]
    fn empty_input_yields_no_blocks() {
        assert!(parse("").blocks.is_empty());
        assert!(parse("\n  \n").blocks.is_empty());
    }

    #[test]
    fn words_may_be_written_without_spaces() {
        assert_eq!(words("G1X10Y-20.5F1000"), vec![Word::G(1), num("X", 10.0), num("Y", -20.5), num("F", 1000.0)]);
    }

    #[test]
    fn leading_zeros_and_trailing_points_are_numbers() {
        assert_eq!(words("G01 X10. Z.5"), vec![Word::G(1), num("X", 10.0), num("Z", 0.5)]);
    }

    #[test]
    fn block_numbers_skip_marks_labels_and_comments_are_recognised() {
        let p = parse("/N20 G0 X1 ; rapid\nSTART: G1 X2\n:30 M30");
        let b = &p.blocks;
        assert!(b[0].skip);
        assert_eq!(b[0].number, Some(20));
        assert_eq!(b[0].comment.as_deref(), Some("rapid"));
        assert_eq!(b[1].label.as_deref(), Some("START"));
        assert_eq!(b[2].number, Some(30));
        assert_eq!(b[2].words, vec![Word::M(30)]);
    }

    #[test]
    fn addresses_with_equals_take_expressions_and_coordinate_modes() {
        let w = words("X=AC(10) CR=-5 F=2*(R1+3)");
        assert_eq!(
            w[0],
            Word::Address {
                name: "X".into(),
                value: AddressValue { mode: Some(CoordMode::Ac), expr: Expr::Number(10.0) }
            }
        );
        assert!(
            matches!(&w[1], Word::Address { name, value } if name == "CR" && value.expr == Expr::Neg(Box::new(Expr::Number(5.0))))
        );
        assert!(
            matches!(&w[2], Word::Address { name, value: AddressValue { expr: Expr::Binary(BinOp::Mul, _, _), .. } } if name == "F")
        );
    }

    #[test]
    fn axis_names_with_digits_need_equals() {
        assert_eq!(words("X1=5"), vec![num("X1", 5.0)]);
        assert_eq!(words("X1"), vec![num("X", 1.0)]);
    }

    #[test]
    fn keywords_with_and_without_arguments_are_words() {
        let w = words("SUPA TRANSMIT(2)");
        assert_eq!(w[0], Word::Keyword { name: "SUPA".into(), args: vec![] });
        assert_eq!(w[1], Word::Keyword { name: "TRANSMIT".into(), args: vec![Expr::Number(2.0)] });
    }

    #[test]
    fn every_syntax_error_is_reported_with_its_line() {
        let p = parse("G1 X10\nG1 X=\nG1 #\nG1.5\n");
        let lines: Vec<u32> = p.diagnostics.iter().map(|d| d.line).collect();
        assert_eq!(lines, vec![2, 3, 4]);
        assert_eq!(p.blocks.len(), 1);
    }

    #[test]
    fn offsets_point_into_the_source() {
        let src = "G0 X0\nG1 X=(\n";
        let p = parse(src);
        assert_eq!(p.blocks[0].offset, 0);
        assert!(p.diagnostics[0].offset >= 6);
    }
}

#[cfg(test)]
mod streaming_tests {
    use super::*;

    #[test]
    fn reading_block_by_block_gives_the_same_blocks_as_parsing_at_once() {
        let src = "N10 G0 X1\n\n; only a comment\r\nG1 X2 F3\nM30";
        let mut streamed = Vec::new();
        let (mut offset, mut line) = (0, 1);
        while let Some((block, next_offset, next_line)) = read_block(src, offset, line) {
            streamed.push(block.unwrap());
            (offset, line) = (next_offset, next_line);
        }
        assert_eq!(streamed, parse(src).blocks);
    }

    #[test]
    fn check_reports_what_parse_reports() {
        let src = "G1 X=\nG0 X1\nG1 #";
        assert_eq!(check(src), parse(src).diagnostics);
    }
}
