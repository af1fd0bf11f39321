//! The file functions of the Programming Manual Job Planning on the session's program store:
//! `WRITE`, `READ`, `DELETE`, `ISFILE`, `FILEDATE`, `FILETIME`, `FILESIZE`, `FILESTAT`,
//! `FILEINFO`.
//!
//! They run once, when their block is read in preprocessing; a block with a file procedure
//! first waits for the main run to reach it (as if a `STOPRE` stood before it), so a log line
//! is written when the blocks before it have run, and carries that time. `ISFILE` in an
//! expression does not wait. The engine does no I/O: a file is a program of the store
//! ([`crate::programs::Programs`]). Changes are kept here, in [`Files`], until the channel
//! takes them into its store when the program is no longer running (a log written line by line
//! is copied into the store once, not once per line); the interpreter's own reads, and the
//! channel's listing, see them at once.
//!
//! Error codes in the program's error variable are the manual's: 0 no error, 1 path not
//! permitted, 2 path not found, 3 file not found, 4 wrong file type, 10 file full (longer than
//! MD11420 $MN_LEN_PROTOCOL_FILE kilobytes), 11 file in use, 12 no free resources (the
//! session's store would exceed the quota the shell set), 20 other error,
//! and for READ 21 line does not exist, 22 the result array is too short, 23 the line range
//! reaches past the end of the file.

mod clock;
mod functions;
pub mod path;

use std::collections::BTreeMap;

use crate::programs::{Dir, Kind};

pub use clock::{date, time};

/// No error.
pub const OK: i64 = 0;
/// Path not permitted: a directory of the control that holds no part programs.
pub const PATH_NOT_PERMITTED: i64 = 1;
/// Path not found.
pub const PATH_NOT_FOUND: i64 = 2;
/// File not found.
pub const FILE_NOT_FOUND: i64 = 3;
/// Wrong file type.
pub const WRONG_TYPE: i64 = 4;
/// The file would grow past MD11420 $MN_LEN_PROTOCOL_FILE.
pub const FILE_FULL: i64 = 10;
/// The file runs (the program or one of its callers): it may not be written or deleted.
pub const FILE_IN_USE: i64 = 11;
/// No free resources: the session's program store would exceed its quota.
pub const NO_RESOURCES: i64 = 12;
/// Other error (a file whose text cannot be read).
pub const OTHER: i64 = 20;
/// READ: the first line asked for is not in the file.
pub const NO_SUCH_LINE: i64 = 21;
/// READ: the result array has fewer elements than lines asked for.
pub const ARRAY_TOO_SHORT: i64 = 22;
/// READ: the lines asked for reach past the end of the file.
pub const RANGE_TOO_LARGE: i64 = 23;

/// The procedures (`WRITE(err, ...)`): statements of a block.
pub const PROCEDURES: &[&str] =
    &["WRITE", "READ", "DELETE", "FILEDATE", "FILETIME", "FILESIZE", "FILESTAT", "FILEINFO"];

/// A file written or deleted by the program, not yet in the channel's store.
#[derive(Debug, Clone, PartialEq)]
pub struct Pending {
    /// The directory of the stored program it replaces, or of its path.
    pub dir: Option<Dir>,
    pub kind: Kind,
    /// The whole text; `None`: deleted.
    pub text: Option<String>,
}

/// The interpreter's side of the file functions: changes not yet in the store, the time each
/// file was last written, and the session's clock.
#[derive(Debug, Clone, Default)]
pub struct Files {
    pending: BTreeMap<String, Pending>,
    /// Seconds of session time at each file's last WRITE (files not written by a program of
    /// this channel carry none and show the clock's origin).
    stamps: BTreeMap<String, u64>,
    /// The channel's IPO cycles so far: session time (the engine reads no clock).
    tick: u64,
    /// Bytes all programs of the store may hold together (the shell's quota); `None`: no limit.
    budget: Option<usize>,
}

impl Files {
    /// Whether there are changes the channel has not taken yet.
    pub fn has_pending(&self) -> bool {
        !self.pending.is_empty()
    }

    /// The change to `name` not yet in the store, if any.
    pub fn pending(&self, name: &str) -> Option<&Pending> {
        self.pending.get(name)
    }

    /// Every change not yet in the store, by name.
    pub fn pending_all(&self) -> impl Iterator<Item = (&String, &Pending)> {
        self.pending.iter()
    }

    /// Drops the change to `name` not yet in the store: the shell stored or deleted the program
    /// itself, and the last writer wins.
    pub fn discard(&mut self, name: &str) {
        self.pending.remove(name);
    }

    /// Takes the changes for the store.
    pub fn take_pending(&mut self) -> BTreeMap<String, Pending> {
        std::mem::take(&mut self.pending)
    }

    /// Sets the session clock: IPO cycles since the channel's power on (a store per cycle; the
    /// seconds are worked out only when a file is written).
    #[inline]
    pub fn set_tick(&mut self, tick: u64) {
        self.tick = tick;
    }

    /// Whole seconds of session time now, for an IPO cycle of `ipo_cycle` seconds.
    fn now(&self, ipo_cycle: f64) -> u64 {
        (self.tick as f64 * ipo_cycle) as u64
    }

    /// Sets the quota of the whole program store, in bytes, that WRITE keeps to (error 12).
    pub fn set_budget(&mut self, bytes: Option<usize>) {
        self.budget = bytes;
    }

    /// The quota [`Files::set_budget`] set.
    pub fn budget(&self) -> Option<usize> {
        self.budget
    }

    /// Bytes of every program in `programs` with the pending changes applied (a program not
    /// read yet counts 0, as the store's listing shows it).
    fn total_bytes(&self, programs: &crate::programs::Programs) -> usize {
        let stored: usize = programs
            .iter()
            .filter(|p| !self.pending.contains_key(p.name()))
            .map(|p| p.text().map_or(0, |t| t.len()))
            .sum();
        stored + self.pending.values().map(|p| p.text.as_ref().map_or(0, String::len)).sum::<usize>()
    }

    /// Seconds of session time at the last WRITE to `name`; 0 if none.
    pub fn stamp(&self, name: &str) -> u64 {
        self.stamps.get(name).copied().unwrap_or(0)
    }
}
