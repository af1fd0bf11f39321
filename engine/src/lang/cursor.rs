//! A byte cursor over the code part of one line, with the token helpers the parser needs.

pub(crate) struct Cursor<'a> {
    src: &'a [u8],
    pub pos: usize,
}

impl<'a> Cursor<'a> {
    pub fn new(code: &'a str) -> Self {
        Cursor { src: code.as_bytes(), pos: 0 }
    }
    pub fn len(&self) -> usize {
        self.src.len()
    }
    pub fn peek(&self) -> Option<u8> {
        self.src.get(self.pos).copied()
    }
    pub fn peek_at(&self, ahead: usize) -> Option<u8> {
        self.src.get(self.pos + ahead).copied()
    }
    pub fn at_end(&self) -> bool {
        self.pos >= self.src.len()
    }
    /// The text between two positions (the source is ASCII where the parser slices it).
    pub fn slice(&self, from: usize, to: usize) -> &'a str {
        std::str::from_utf8(&self.src[from..to]).unwrap_or("")
    }
    pub fn starts_with_ignore_case(&self, text: &str) -> bool {
        self.src.len() >= self.pos + text.len()
            && self.src[self.pos..self.pos + text.len()].eq_ignore_ascii_case(text.as_bytes())
    }
    pub fn eat(&mut self, c: u8) -> bool {
        if self.peek() == Some(c) {
            self.pos += 1;
            true
        } else {
            false
        }
    }
    pub fn eat_digit(&mut self) {
        if self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
    }
    pub fn skip_ws(&mut self) {
        while self.peek().is_some_and(|c| c == b' ' || c == b'\t') {
            self.pos += 1;
        }
    }
    pub fn digits(&mut self) -> Option<String> {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
        (self.pos > s).then(|| self.slice(s, self.pos).to_string())
    }
    /// Skips a run of digits; true if there was one.
    fn skip_digits(&mut self) -> bool {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
        self.pos > s
    }

    /// A run of letters and underscores, upper-cased.
    pub fn letters(&mut self) -> String {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') {
            self.pos += 1;
        }
        self.slice(s, self.pos).to_ascii_uppercase()
    }
    pub fn ident_continue(&mut self) -> String {
        let s = self.pos;
        self.skip_ident_chars();
        self.slice(s, self.pos).to_ascii_uppercase()
    }

    fn skip_ident_chars(&mut self) {
        while self.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_') {
            self.pos += 1;
        }
    }
    /// An identifier: `$`? letter (letter | digit | `_`)*, upper-cased.
    pub fn ident(&mut self) -> Option<String> {
        let s = self.pos;
        self.eat(b'$');
        if !self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') {
            self.pos = s;
            return None;
        }
        self.skip_ident_chars();
        Some(self.slice(s, self.pos).to_ascii_uppercase())
    }
    /// A signed decimal number with optional `EX` exponent (`1.5EX3`).
    pub fn number(&mut self) -> Option<f64> {
        let s = self.pos;
        if matches!(self.peek(), Some(b'-' | b'+')) {
            self.pos += 1;
        }
        let int = self.skip_digits();
        let frac = if self.eat(b'.') { self.skip_digits() } else { false };
        if !int && !frac {
            self.pos = s;
            return None;
        }
        let plain = self.slice(s, self.pos);
        if !self.starts_with_ignore_case("EX") && !plain.ends_with('.') {
            // The common case parses straight from the source, without a copy.
            return plain.parse::<f64>().ok().filter(|v| v.is_finite());
        }
        let mut text = plain.to_string();
        if self.starts_with_ignore_case("EX") {
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
