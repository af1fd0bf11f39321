//! A byte cursor over the code part of one line, with the token helpers the parser needs.
//!
//! The helpers that find a name return its byte span; the parser copies (and upper-cases) a
//! name only when it goes into the syntax tree, so looking at a word costs no allocation.

pub(crate) struct Cursor<'a> {
    text: &'a str,
    src: &'a [u8],
    pub pos: usize,
}

/// Largest power of ten that is exact in an `f64` (for the fast number path).
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// `mantissa / 10^frac_digits`, negated if `negative`: the fast path of [`Cursor::number`].
/// With at most 15 digits in all, mantissa and power of ten are exact, so the one division
/// rounds correctly and gives exactly what `str::parse` gives.
pub(crate) fn exact_decimal(mantissa: u64, frac_digits: usize, negative: bool) -> f64 {
    debug_assert!(mantissa < 1_000_000_000_000_000 && frac_digits <= 15);
    // Through i64, exact below 10^15 as well: x86-64 converts a signed integer in one
    // instruction, an unsigned one in several. Whole numbers (G3, Y20, F600: most words) skip
    // the division, which is slow, by 1.
    let mantissa = mantissa as i64 as f64;
    let value = if frac_digits == 0 { mantissa } else { mantissa / EXACT_POWERS_OF_TEN[frac_digits] };
    if negative { -value } else { value }
}

impl<'a> Cursor<'a> {
    pub fn new(code: &'a str) -> Self {
        Cursor { text: code, src: code.as_bytes(), pos: 0 }
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
    /// The text between two positions (the parser slices at ASCII characters only).
    pub fn slice(&self, from: usize, to: usize) -> &'a str {
        self.text.get(from..to).unwrap_or("")
    }
    /// The text between two positions, upper-cased: a name for the syntax tree.
    pub fn upper(&self, (from, to): (usize, usize)) -> String {
        self.slice(from, to).to_ascii_uppercase()
    }
    /// True if the span holds `word` (upper case) in any case.
    pub fn span_is(&self, (from, to): (usize, usize), word: &str) -> bool {
        self.src[from..to].eq_ignore_ascii_case(word.as_bytes())
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
    /// A run of digits.
    pub fn digits(&mut self) -> Option<&'a str> {
        let s = self.pos;
        self.skip_digits().then(|| self.slice(s, self.pos))
    }
    /// Skips a run of digits; true if there was one.
    fn skip_digits(&mut self) -> bool {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
        self.pos > s
    }

    /// A run of letters and underscores (possibly empty).
    pub fn letters(&mut self) -> (usize, usize) {
        let s = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') {
            self.pos += 1;
        }
        (s, self.pos)
    }

    fn skip_ident_chars(&mut self) {
        while self.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_') {
            self.pos += 1;
        }
    }
    /// The span of an identifier: `$`? letter (letter | digit | `_`)*.
    pub fn ident_span(&mut self) -> Option<(usize, usize)> {
        let s = self.pos;
        self.eat(b'$');
        if !self.peek().is_some_and(|c| c.is_ascii_alphabetic() || c == b'_') {
            self.pos = s;
            return None;
        }
        self.skip_ident_chars();
        Some((s, self.pos))
    }
    /// An identifier, upper-cased.
    pub fn ident(&mut self) -> Option<String> {
        self.ident_span().map(|span| self.upper(span))
    }
    /// True (and the identifier consumed) if an identifier follows that is `word` in any case.
    pub fn eat_word(&mut self, word: &str) -> bool {
        let save = self.pos;
        match self.ident_span() {
            Some(span) if self.span_is(span, word) => true,
            _ => {
                self.pos = save;
                false
            }
        }
    }
    /// A signed decimal number with optional `EX` exponent (`1.5EX3`).
    pub fn number(&mut self) -> Option<f64> {
        let s = self.pos;
        let negative = self.peek() == Some(b'-');
        if matches!(self.peek(), Some(b'-' | b'+')) {
            self.pos += 1;
        }
        // Digits are gathered into an integer mantissa as they are skipped.
        let mut mantissa = 0u64;
        let mut digits = 0usize;
        while let Some(c) = self.peek().filter(u8::is_ascii_digit) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
            digits += 1;
            self.pos += 1;
        }
        let int = digits > 0;
        let point = self.eat(b'.');
        let mut frac_digits = 0usize;
        while let Some(c) = self.peek().filter(|_| point).filter(u8::is_ascii_digit) {
            mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
            frac_digits += 1;
            self.pos += 1;
        }
        if !int && frac_digits == 0 {
            self.pos = s;
            return None;
        }
        let plain = self.slice(s, self.pos);
        // `1.5EX3` and `5.` take the general path below.
        let general = self.starts_with_ignore_case("EX") || point && frac_digits == 0;
        if !general {
            // The common case: with at most 15 digits, mantissa and power of ten are exact, so
            // one division rounds correctly and gives exactly what `str::parse` gives.
            if digits + frac_digits <= 15 {
                return Some(exact_decimal(mantissa, frac_digits, negative));
            }
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

#[cfg(test)]
mod tests {
    use super::Cursor;

    /// The fast path of `number` agrees bit for bit with the standard library's parser.
    #[test]
    fn numbers_parse_exactly_like_the_standard_library() {
        let mut next = crate::lang::test_rng::xorshift(0x9e37_79b9_7f4a_7c15u64);
        let mut cases: Vec<String> =
            ["0", "-0", "+7", ".5", "-.25", "0.1", "123456789012345", "1.000000000000001", "0.0000000000000000000001"]
                .iter()
                .map(|s| s.to_string())
                .collect();
        for _ in 0..20_000 {
            let int = next() % 10u64.pow((next() % 12) as u32 + 1);
            let frac_len = (next() % 10) as usize;
            let frac: String = (0..frac_len).map(|_| char::from(b'0' + (next() % 10) as u8)).collect();
            let sign = ["", "-", "+"][(next() % 3) as usize];
            cases.push(if frac.is_empty() { format!("{sign}{int}") } else { format!("{sign}{int}.{frac}") });
        }
        for case in cases {
            let ours = Cursor::new(&case).number().expect(&case);
            let std: f64 = case.parse().expect(&case);
            assert_eq!(ours.to_bits(), std.to_bits(), "{case}");
        }
    }
}
