//! A long program file mapped into memory for `nctwin simulate`, with its pages given back.
//!
//! The interpreter reads a program from its text front to back and only jumps (GOTOB, loops,
//! subprogram returns) look elsewhere. So the file is mapped read-only instead of read into a
//! string, and a helper thread tells the kernel every few milliseconds that the mapped pages
//! are not needed (`MADV_DONTNEED`): they leave the process' resident set and stay in the page
//! cache; whatever the interpreter reads next, forward or after a jump back, is mapped in again
//! on access. Peak RSS then no longer grows with the program's length.
//!
//! The file must not be truncated while it runs (reading a page beyond the new end would stop
//! the process with SIGBUS); changing its bytes in place changes the program under the run.

use std::fs::File;
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

use memmap2::{Mmap, UncheckedAdvice};
use nctwin_engine::lang::ProgramText;

/// Files from this size on are mapped; smaller ones are read into memory as before.
pub const MAP_FROM_BYTES: u64 = 1 << 20;

/// How often the mapped pages are given back.
const RELEASE_EVERY: Duration = Duration::from_millis(5);

/// A mapped program file whose bytes were checked to be UTF-8.
struct Utf8Map(Arc<Mmap>);

impl AsRef<str> for Utf8Map {
    fn as_ref(&self) -> &str {
        // SAFETY: `map` checked the whole mapping with `str::from_utf8` before building this,
        // and the mapping is read-only.
        unsafe { std::str::from_utf8_unchecked(&self.0) }
    }
}

/// The thread that gives the mapped pages back; stops (and joins) when dropped.
pub struct PageRelease {
    map: Arc<Mmap>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl PageRelease {
    /// Gives the mapped pages back at once: for a caller that reads the text faster than the
    /// thread's period (a scan of the whole file), every few MiB.
    pub fn now(&self) {
        // SAFETY: see the thread in `map`.
        let _ = unsafe { self.map.unchecked_advise(UncheckedAdvice::DontNeed) };
    }
}

/// How much text a whole-file scan reads between two [`PageRelease::now`].
pub const SCAN_CHUNK_BYTES: usize = 4 << 20;

impl Drop for PageRelease {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            t.thread().unpark();
            let _ = t.join();
        }
    }
}

/// Maps `file` (already open, `len` bytes) and starts giving its pages back. Errors: the
/// mapping failed or the text is not UTF-8 (the message says which).
pub fn map(file: &File, path: &Path) -> Result<(ProgramText, PageRelease), String> {
    // SAFETY: the mapping is read-only; the module documentation states what truncating or
    // rewriting the file during the run does, as for any tool that maps its input.
    let map = Arc::new(unsafe { Mmap::map(file) }.map_err(|e| format!("cannot map program {}: {e}", path.display()))?);
    let stop = Arc::new(AtomicBool::new(false));
    let thread = {
        let (map, stop) = (map.clone(), stop.clone());
        std::thread::Builder::new()
            .name("page-release".into())
            .spawn(move || {
                while !stop.load(Ordering::Relaxed) {
                    // SAFETY: the mapping is a read-only file mapping: dropped pages hold no
                    // private changes and are read from the file again on the next access.
                    let _ = unsafe { map.unchecked_advise(UncheckedAdvice::DontNeed) };
                    // Parked rather than asleep: the drop wakes it at once (a sleep would keep
                    // the process waiting for the rest of the period at its end).
                    std::thread::park_timeout(RELEASE_EVERY);
                }
            })
            .map_err(|e| format!("cannot start the page-release thread: {e}"))?
    };
    let release = PageRelease { map: map.clone(), stop, thread: Some(thread) };
    // The UTF-8 check reads the whole file, faster than the thread gives pages back: in
    // chunks that end at a line end (an ASCII byte, so no character is split), each released.
    let mut from = 0;
    while from < map.len() {
        let mut to = (from + SCAN_CHUNK_BYTES).min(map.len());
        if let Some(nl) = map[to..].iter().position(|&b| b == b'\n') {
            to += nl + 1;
        } else {
            to = map.len();
        }
        if let Err(e) = std::str::from_utf8(&map[from..to]) {
            let at = from + e.valid_up_to();
            return Err(format!("cannot read program {}: not UTF-8 (invalid byte at offset {at})", path.display()));
        }
        release.now();
        from = to;
    }
    Ok((ProgramText::from_owner(Utf8Map(map)), release))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mapped_file_reads_as_its_text_and_rejects_bad_utf8() {
        let dir = std::env::temp_dir().join(format!("nctwin-mapped-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let good = dir.join("good.mpf");
        let text = "G1 X1 F100\n".repeat(10_000) + "M30\n";
        std::fs::write(&good, &text).unwrap();
        let (mapped, release) = map(&File::open(&good).unwrap(), &good).unwrap();
        // Read twice with releases in between: the text is the same each time.
        assert_eq!(&*mapped, text);
        std::thread::sleep(RELEASE_EVERY * 3);
        assert_eq!(mapped.lines().count(), 10_001);
        drop(release);
        let bad = dir.join("bad.mpf");
        std::fs::write(&bad, b"G1 X1\n\xff\n").unwrap();
        let err = map(&File::open(&bad).unwrap(), &bad).err().unwrap();
        assert!(err.contains("not UTF-8"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
