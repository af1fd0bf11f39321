//! The syntax check before a run reads every line of a program once more. Most lines of
//! generated toolpaths are only address letters with plain numbers (`G1 X10.5 Y-2 F900`); this
//! recognises such lines in one byte scan, so the check needs the full parser only for the rest.
//!
//! The scan is conservative: it answers true only for lines the parser accepts without a
//! statement (and so without anything for the structure check); anything unusual (a block
//! number that is not all digits, `=`, a string, an exponent, a name longer than one letter) goes to the parser.

/// The most digits of a number the scan accepts (the parser's exact fast path for numbers).
const MAX_DIGITS: usize = 15;

/// The most digits of a G or M number the scan accepts (it must fit a `u32`).
const MAX_FUNCTION_DIGITS: usize = 9;

/// True if `text` (one line without its line end) is blanks, address words made of one letter
/// and a plain number, and an optional comment: a line without syntax errors or statements.
pub(super) fn is_plain_line(text: &str) -> bool {
    scan::<false>(text, |_, _, _| true)
}

/// The one scan behind [`is_plain_line`], handing each address word to `word` as its
/// upper-case letter, the end of its number (a byte offset in `text`) and its value exactly
/// as the parser reads it
/// (block preparation's fast lane reads plain lines with it, so it accepts exactly the syntax
/// the check lets past the parser). True if the line is plain and `word` accepted every word;
/// stops at the first word it refuses.
pub(crate) fn plain_words(text: &str, word: impl FnMut(u8, usize, f64) -> bool) -> bool {
    scan::<true>(text, word)
}

/// [`plain_words`], with the values only if `VALUES` (the check needs none: 0 then).
fn scan<const VALUES: bool>(text: &str, mut word: impl FnMut(u8, usize, f64) -> bool) -> bool {
    let b = text.as_bytes();
    let mut i = 0;
    loop {
        while i < b.len() && matches!(b[i], b' ' | b'\t') {
            i += 1;
        }
        if i == b.len() || b[i] == b';' {
            return true;
        }
        let letter = b[i].to_ascii_uppercase();
        if !letter.is_ascii_uppercase() {
            return false;
        }
        i += 1;
        // G and M need whole numbers; N at the start of a line is a block number. Both only
        // with digits here.
        let whole = matches!(letter, b'G' | b'M' | b'N');
        let Some((end, value)) = plain_number::<VALUES>(b, i, whole) else { return false };
        // After the number: a blank, the end, a comment or the next letter (not E: `EX` is
        // the exponent of a number).
        match b.get(end) {
            None | Some(b' ' | b'\t' | b';') => {}
            Some(c) if c.is_ascii_alphabetic() && !c.eq_ignore_ascii_case(&b'E') => {}
            Some(_) => return false,
        }
        if !word(letter, end, value) {
            return false;
        }
        i = end;
    }
}

/// The end and (if `VALUES`) value of a plain number at `i`: `[+-]digits[.digits]`, `[+-].digits` or
/// `[+-]digits.` with at least one digit; only digits if `whole`.
fn plain_number<const VALUES: bool>(b: &[u8], mut i: usize, whole: bool) -> Option<(usize, f64)> {
    let mut mantissa = 0u64;
    let mut count_digits = |i: &mut usize| {
        let start = *i;
        // A digit is a byte whose distance from `0` is at most 9 (one compare, no second bound).
        while let Some(digit) = b.get(*i).map(|c| c.wrapping_sub(b'0')).filter(|d| *d <= 9) {
            if VALUES {
                // At most 15 digits are accepted: an overflow only happens to a refused number.
                mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(digit));
            }
            *i += 1;
        }
        *i - start
    };
    if whole {
        let n = count_digits(&mut i);
        return (1..=MAX_FUNCTION_DIGITS).contains(&n).then_some((i, mantissa as f64));
    }
    let negative = b.get(i) == Some(&b'-');
    if matches!(b.get(i), Some(b'+' | b'-')) {
        i += 1;
    }
    let mut n = count_digits(&mut i);
    let mut frac = 0;
    if b.get(i) == Some(&b'.') {
        i += 1;
        frac = count_digits(&mut i);
        n += frac;
    }
    let value = || if VALUES { super::cursor::exact_decimal(mantissa, frac, negative) } else { 0.0 };
    (1..=MAX_DIGITS).contains(&n).then(|| (i, value()))
}

#[cfg(test)]
mod tests {
    use super::is_plain_line;
    use crate::lang::parser::parse_block;

    #[test]
    fn toolpath_lines_are_plain() {
        for line in [
            "G3 X75.9329 Y20 Z-0.5 I-1 J0 F600",
            "  G1 X78.9329 Y20\t; comment with = and \"quotes\"",
            "x-.5 y+2. g01 M30",
            "G0X1Y2",
            "N10 G1 X1",
            "",
            "; only a comment",
        ] {
            assert!(is_plain_line(line), "{line}");
        }
    }

    #[test]
    fn anything_else_goes_to_the_parser() {
        for line in [
            "N1.5 G1",
            "G1.5 X1",
            "G-1",
            "X1.5EX3",
            "X=10",
            "R1=5",
            "X1..2",
            "X1-2",
            "X",
            "GOTOF END",
            "IF R1>0",
            "MSG(\"x\")",
            "LABEL: G1",
            "/G1 X1",
            "$P_UIFR[1]=CTRANS()",
            "X1234567890123456",
            "G1234567890",
            "G1 X1 ä",
        ] {
            assert!(!is_plain_line(line), "{line}");
        }
    }

    /// The words of a plain line as the scan reads them: letter and value (a leading N with
    /// digits only is the block number, which the parser keeps apart from the words).
    fn scanned_words(line: &str) -> Vec<(char, u64)> {
        let mut words = Vec::new();
        assert!(super::plain_words(line, |letter, _, value| {
            words.push((char::from(letter), value.to_bits()));
            true
        }));
        words
    }

    fn parsed_words(block: Option<crate::lang::Block>) -> Vec<(char, u64)> {
        use crate::lang::{Expr, Word};
        let Some(block) = block else { return Vec::new() };
        let mut words: Vec<(char, u64)> = block.number.map(|n| ('N', f64::from(n).to_bits())).into_iter().collect();
        for w in block.words {
            words.push(match w {
                Word::G(n) => ('G', f64::from(n).to_bits()),
                Word::M(n) => ('M', f64::from(n).to_bits()),
                Word::Address { name, value, .. } => match value.expr {
                    Expr::Number(v) => (name.chars().next().expect("a letter"), v.to_bits()),
                    other => panic!("plain word {name} with {other:?}"),
                },
                other => panic!("plain line with {other:?}"),
            });
        }
        words
    }

    /// Every line the scan calls plain, the parser accepts without a statement: random lines
    /// from the characters and fragments where the two could disagree, with the same words and
    /// bit-identical values.
    #[test]
    fn plain_lines_are_lines_the_parser_accepts() {
        const PIECES: [&str; 32] = [
            "G",
            "M",
            "N",
            "X",
            "y",
            "E",
            "e",
            "I",
            "1",
            "0",
            "9",
            "12",
            ".",
            "-",
            "+",
            " ",
            "\t",
            ";",
            "=",
            "\"",
            ":",
            "$",
            "_",
            "[",
            "(",
            "IF",
            "GOTOF",
            "EX",
            "/",
            "4294967295",
            "4294967296",
            "123456789012345",
        ];
        let mut next = crate::lang::test_rng::xorshift(0x2545_f491_4f6c_dd1du64);
        let mut plain = 0;
        for _ in 0..200_000 {
            let len = (next() % 8) as usize + 1;
            let line: String = (0..len).map(|_| PIECES[(next() % PIECES.len() as u64) as usize]).collect();
            if is_plain_line(&line) {
                plain += 1;
                match parse_block(&line, 1, 0) {
                    Ok(block) => {
                        assert!(block.as_ref().is_none_or(|b| b.stmt.is_none()), "{line}: statement");
                        assert_eq!(scanned_words(&line), parsed_words(block), "{line:?}");
                    }
                    Err(e) => panic!("{line:?} is plain but the parser says {e:?}"),
                }
            }
        }
        // The test would prove nothing if hardly any random line were plain.
        assert!(plain > 1_000, "only {plain} plain lines");
    }
}
