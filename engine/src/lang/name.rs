//! Names of address words without a heap allocation for the common case: the single letters
//! (`X`, `F`, `I` ...) of nearly every block point into a static table; longer names
//! (`CR`, `$TC_DP1`, `X1`) own their text.

use std::borrow::Cow;

/// The upper-case name of an address word.
pub type Name = Cow<'static, str>;

const LETTERS: [&str; 26] = [
    "A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K", "L", "M", "N", "O", "P", "Q", "R", "S", "T", "U", "V", "W",
    "X", "Y", "Z",
];

/// The name of a single address letter (any case); `None` for a byte that is no ASCII letter.
pub fn letter(c: u8) -> Option<Name> {
    c.is_ascii_alphabetic().then(|| Cow::Borrowed(LETTERS[usize::from(c.to_ascii_uppercase() - b'A')]))
}

/// The upper-case name of an identifier's text: a static letter for one letter, else owned.
pub fn of(text: &str) -> Name {
    match text.as_bytes() {
        [c] => letter(*c).unwrap_or_else(|| Cow::Owned(text.to_ascii_uppercase())),
        _ => Cow::Owned(text.to_ascii_uppercase()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn letters_are_static_and_upper_case() {
        assert!(matches!(letter(b'x'), Some(Cow::Borrowed("X"))));
        assert!(matches!(letter(b'A'), Some(Cow::Borrowed("A"))));
        assert!(matches!(letter(b'z'), Some(Cow::Borrowed("Z"))));
        assert!(letter(b'_').is_none() && letter(b'1').is_none());
        assert!(matches!(of("f"), Cow::Borrowed("F")));
        assert_eq!(of("cr"), "CR");
        assert_eq!(of("$tc_dp1"), "$TC_DP1");
        assert_eq!(of("_"), "_");
    }
}
