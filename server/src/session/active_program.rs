//! What the server keeps about the channel's loaded program beside the engine: the name it was
//! started under (the engine knows only the text), and its line index and SHA-256, computed
//! once per loaded program so that a viewer can page through a CAM program of millions of
//! blocks by line ranges without the text being scanned per request.
//!
//! Both are keyed by the engine's program serial (`Channel::program_serial`), which changes with
//! every load, so a name or an index can never be paired with another program's text.

use std::sync::{Arc, Mutex};

use nctwin_engine::lang::ProgramText;

/// The loaded program's text with where each line starts, and its hash.
#[derive(Debug)]
pub struct IndexedText {
    /// The program serial this text was loaded as.
    pub serial: u64,
    pub text: ProgramText,
    /// Byte offset of each line's start; a line end at the very end starts no further line.
    starts: Vec<usize>,
    /// SHA-256 of the text, lowercase hex: the program's version.
    pub sha256: String,
}

impl IndexedText {
    /// Indexes `text` (reads it once for the line starts and once for the hash).
    pub fn new(serial: u64, text: ProgramText) -> IndexedText {
        use sha2::{Digest, Sha256};
        let starts = line_starts(&text);
        let digest = Sha256::digest(text.as_bytes());
        let sha256 = digest.iter().map(|b| format!("{b:02x}")).collect();
        IndexedText { serial, text, starts, sha256 }
    }

    /// Indexes `text` for line ranges without its hash (a subprogram's).
    pub fn lines_only(text: ProgramText) -> IndexedText {
        IndexedText { serial: 0, starts: line_starts(&text), text, sha256: String::new() }
    }

    /// Number of lines, as the control numbers them (a final line end adds no line).
    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// Line `n` (1-based) without its line end; `None` past the end.
    pub fn line(&self, n: usize) -> Option<&str> {
        let start = *self.starts.get(n.checked_sub(1)?)?;
        let end = self.starts.get(n).map_or(self.text.len(), |next| next - 1);
        let raw = &self.text[start..end.max(start)];
        let raw = raw.strip_suffix('\n').unwrap_or(raw);
        Some(raw.strip_suffix('\r').unwrap_or(raw))
    }
}

/// Where each line of `text` starts; no line for an empty text or after a final line end.
pub fn line_starts(text: &str) -> Vec<usize> {
    if text.is_empty() {
        return Vec::new();
    }
    let mut starts = vec![0];
    starts.extend(memchr_newlines(text.as_bytes()).map(|i| i + 1).filter(|&i| i < text.len()));
    starts
}

fn memchr_newlines(bytes: &[u8]) -> impl Iterator<Item = usize> + '_ {
    bytes.iter().enumerate().filter(|(_, b)| **b == b'\n').map(|(i, _)| i)
}

/// A session's program name and line index cache (see the module doc). Locks are held only to
/// read or swap an `Arc`, never across an await or a scan of the text.
#[derive(Debug, Default)]
pub struct ActiveCache {
    label: Mutex<Option<(u64, Option<String>)>>,
    index: Mutex<Option<Arc<IndexedText>>>,
    /// The subprogram indexed last (a CAM program called from a short main program).
    sub_index: Mutex<Option<Arc<IndexedText>>>,
}

impl ActiveCache {
    /// Records the name program `serial` was started under (`None`: it has none, e.g. MDA).
    pub fn set_label(&self, serial: u64, name: Option<String>) {
        *self.label.lock().unwrap_or_else(|e| e.into_inner()) = Some((serial, name));
    }

    /// The recorded name of program `serial`: `None` when nothing is recorded for it,
    /// `Some(None)` when it is recorded as having no name.
    pub fn label(&self, serial: u64) -> Option<Option<String>> {
        let label = self.label.lock().unwrap_or_else(|e| e.into_inner());
        label.as_ref().filter(|(s, _)| *s == serial).map(|(_, name)| name.clone())
    }

    /// The index of program `serial` if it is the one indexed last.
    pub fn cached(&self, serial: u64, text: &ProgramText) -> Option<Arc<IndexedText>> {
        let index = self.index.lock().unwrap_or_else(|e| e.into_inner());
        index.as_ref().filter(|i| i.serial == serial && i.text.shares_text_with(text)).cloned()
    }

    /// Keeps `indexed` as the latest index (the previous program's is let go).
    pub fn store(&self, indexed: Arc<IndexedText>) {
        *self.index.lock().unwrap_or_else(|e| e.into_inner()) = Some(indexed);
    }

    /// The index of subprogram text `text`, made once while the same text is asked for.
    pub fn sub_indexed(&self, text: ProgramText) -> Arc<IndexedText> {
        let mut sub = self.sub_index.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(hit) = sub.as_ref().filter(|i| i.text.shares_text_with(&text)) {
            return hit.clone();
        }
        let indexed = Arc::new(IndexedText::lines_only(text));
        *sub = Some(indexed.clone());
        indexed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_numbered_as_the_control_numbers_them() {
        let t = IndexedText::new(1, ProgramText::from("G0 X1\r\nG1 X2 F100\n\nM30\n"));
        // Four lines: the empty third line counts, the final line end adds none.
        assert_eq!(t.line_count(), 4);
        assert_eq!(
            (t.line(1), t.line(2), t.line(3), t.line(4), t.line(5)),
            (Some("G0 X1"), Some("G1 X2 F100"), Some(""), Some("M30"), None)
        );
        assert_eq!(t.line(0), None);
        let last_unterminated = IndexedText::new(1, ProgramText::from("G0 X1\nM30"));
        assert_eq!((last_unterminated.line_count(), last_unterminated.line(2)), (2, Some("M30")));
        assert_eq!(IndexedText::new(1, ProgramText::from("")).line_count(), 0);
    }

    #[test]
    fn the_hash_is_the_sha256_of_the_text() {
        // SHA-256("abc") from FIPS 180-2, appendix B.1.
        let t = IndexedText::new(1, ProgramText::from("abc"));
        assert_eq!(t.sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    }

    #[test]
    fn a_label_belongs_to_its_serial_only() {
        let cache = ActiveCache::default();
        cache.set_label(3, Some("PART".into()));
        assert_eq!(cache.label(3), Some(Some("PART".into())));
        assert_eq!(cache.label(4), None);
    }
}
