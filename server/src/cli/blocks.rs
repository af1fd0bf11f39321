//! The block count of `nctwin simulate`'s report: non-empty lines, the count the benchmark
//! generator and the peers' figures use.

use super::mapped::{PageRelease, SCAN_CHUNK_BYTES};

/// Non-empty lines of the program (lines with a character that is not white space, as
/// `str::trim` sees it). A mapped program gives its pages back every few MiB of the scan (the
/// scan is faster than the release thread).
///
/// A byte loop rather than `str::lines`: the lines are short (≈ a tenth of `--interpret-only`'s
/// instructions with `lines`). It runs on the check's thread, after the check.
pub fn count_blocks(text: &str, release: Option<&PageRelease>) -> u64 {
    let bytes = text.as_bytes();
    let (mut blocks, mut start, mut released_at) = (0u64, 0usize, 0usize);
    while start < bytes.len() {
        let end = bytes[start..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |i| start + i);
        let first_visible = bytes[start..end].iter().find(|b| !matches!(b, b' ' | b'\t' | b'\r' | 0x0b | 0x0c));
        blocks += u64::from(match first_visible {
            None => false,
            Some(b) if b.is_ascii() => true,
            // Unicode white space (NBSP, ...) counts as blank, as `trim` has it.
            Some(_) => !text[start..end].trim().is_empty(),
        });
        start = end + 1;
        if let Some(r) = release.filter(|_| start - released_at >= SCAN_CHUNK_BYTES) {
            r.now();
            released_at = start;
        }
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::count_blocks;
    use proptest::prelude::*;

    /// The definition: lines that `trim` leaves non-empty.
    fn by_definition(text: &str) -> u64 {
        text.lines().filter(|l| !l.trim().is_empty()).count() as u64
    }

    #[test]
    fn blank_lines_do_not_count() {
        // Three blocks: X1, the comment and Y2; blank, tab-only, CR-only and NBSP-only lines are
        // not blocks, nor is the empty piece after the last line end.
        let text = "X1\n\n \t\r\n; note\n\u{a0}\r\n\x0b\x0c\nY2\r\n";
        assert_eq!(count_blocks(text, None), 3);
        assert_eq!(count_blocks("", None), 0);
        assert_eq!(count_blocks("M30", None), 1);
    }

    proptest! {
        #[test]
        fn counts_as_trim_does(text in "([ \\t\\r\\n\\x0b\\x0c]|\u{a0}|\u{2003}|é|X|;){0,40}") {
            prop_assert_eq!(count_blocks(&text, None), by_definition(&text));
        }
    }
}
