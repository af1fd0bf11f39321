//! The text of a program as the channel and the interpreter hold it: shared, read-only, and
//! owned by whatever keeps the bytes. A program typed into the HMI is a string in memory; the
//! command line maps a long program file into memory instead, so that the pages the
//! interpreter has passed can be dropped (jumps back simply read them again).

use std::fmt;
use std::ops::Deref;
use std::sync::Arc;

/// Shared program text; derefs to `str`. Cloning shares the text.
#[derive(Clone)]
pub struct ProgramText(Arc<dyn AsRef<str> + Send + Sync>);

impl ProgramText {
    /// Text owned by `owner` (a memory map of a checked UTF-8 file, say).
    pub fn from_owner(owner: impl AsRef<str> + Send + Sync + 'static) -> ProgramText {
        ProgramText(Arc::new(owner))
    }

    /// Whether both share the same text (one allocation), without comparing it: a cheap
    /// "unchanged" test for callers that cache something derived from a text (a hash, say).
    pub fn shares_text_with(&self, other: &ProgramText) -> bool {
        std::ptr::addr_eq(Arc::as_ptr(&self.0), Arc::as_ptr(&other.0))
    }
}

impl Deref for ProgramText {
    type Target = str;
    fn deref(&self) -> &str {
        (*self.0).as_ref()
    }
}

impl AsRef<str> for ProgramText {
    fn as_ref(&self) -> &str {
        self
    }
}

impl fmt::Debug for ProgramText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "ProgramText({} bytes)", self.len())
    }
}

impl PartialEq for ProgramText {
    fn eq(&self, other: &ProgramText) -> bool {
        **self == **other
    }
}

impl From<Arc<str>> for ProgramText {
    fn from(text: Arc<str>) -> ProgramText {
        ProgramText(Arc::new(text))
    }
}

impl From<&str> for ProgramText {
    fn from(text: &str) -> ProgramText {
        ProgramText::from(Arc::<str>::from(text))
    }
}

impl From<String> for ProgramText {
    fn from(text: String) -> ProgramText {
        ProgramText(Arc::new(text))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_owner_reads_as_the_same_text() {
        let a = ProgramText::from("G1 X1\nM30\n");
        let b = ProgramText::from(String::from("G1 X1\nM30\n"));
        let c = ProgramText::from_owner(Box::<str>::from("G1 X1\nM30\n"));
        assert_eq!(&*a, "G1 X1\nM30\n");
        assert_eq!(a, b);
        assert_eq!(b, c);
        assert_eq!(a.clone().lines().count(), 2);
        assert!(a.shares_text_with(&a.clone()), "a clone shares the text");
        assert!(!a.shares_text_with(&b), "an equal text elsewhere is not shared");
    }
}
