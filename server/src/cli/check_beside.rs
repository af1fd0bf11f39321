//! The syntax check of a program on a second thread, beside the run on the calling thread.
//!
//! `lang::check` is a whole pass over the text, as long as block preparation itself for
//! plain programs; the report's block count ([`count_blocks`]) is another, which follows the
//! check on its thread. `nctwin simulate` starts the run at once with the check beside it; a run
//! whose check finds errors is discarded (the report is the syntax-error report, as if nothing
//! had run), and the run is told to give up early through [`Verdict::failed`].

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Instant;

use nctwin_engine::lang::{self, Diagnostic};

use super::blocks::count_blocks;
use super::mapped::PageRelease;

/// What the checking thread found out, readable by the run while both go on.
#[derive(Debug)]
pub struct Verdict {
    failed: AtomicBool,
    /// The program's blocks once counted; `u64::MAX` until then.
    blocks: AtomicU64,
}

impl Verdict {
    fn new() -> Verdict {
        Verdict { failed: AtomicBool::new(false), blocks: AtomicU64::new(u64::MAX) }
    }

    /// True once the check has finished and found an error: the run's results will be
    /// discarded, so it may stop.
    pub fn failed(&self) -> bool {
        self.failed.load(Ordering::Relaxed)
    }

    /// The program's blocks ([`count_blocks`]), once the thread has counted them.
    pub fn blocks(&self) -> Option<u64> {
        Some(self.blocks.load(Ordering::Relaxed)).filter(|&b| b != u64::MAX)
    }
}

/// The check's result with its own figures.
#[derive(Debug)]
pub struct Checked {
    /// Every error in the order `lang::check` reports them (empty: the program passed).
    pub errors: Vec<Diagnostic>,
    /// The program's blocks ([`count_blocks`]).
    pub blocks: u64,
    /// Wall time from the start of [`check_beside`] until the check finished, seconds.
    pub wall_s: f64,
    /// CPU time of the check's thread, seconds (`None` where /proc is missing).
    pub cpu_s: Option<f64>,
}

/// Runs `lang::check(text)` and then [`count_blocks`] on a scoped second thread while `work`
/// runs on this one, and returns both results. `work` gets the [`Verdict`] to look at now and
/// then. Where no thread can be started, both run first on this thread (then `work` sees the
/// final verdict). `release`: the pages of a mapped program, given back during the count.
pub fn check_beside<T>(text: &str, release: Option<&PageRelease>, work: impl FnOnce(&Verdict) -> T) -> (T, Checked) {
    let started = Instant::now();
    let verdict = Verdict::new();
    let check = || {
        let cpu_start = thread_cpu_time_s();
        let errors = lang::check(text);
        if !errors.is_empty() {
            verdict.failed.store(true, Ordering::Relaxed);
        }
        let wall_s = started.elapsed().as_secs_f64();
        let blocks = count_blocks(text, release);
        verdict.blocks.store(blocks, Ordering::Relaxed);
        let cpu_s = thread_cpu_time_s().zip(cpu_start).map(|(end, start)| end - start);
        Checked { errors, blocks, wall_s, cpu_s }
    };
    std::thread::scope(|scope| {
        match std::thread::Builder::new().name("syntax-check".into()).spawn_scoped(scope, check) {
            Ok(handle) => {
                let result = work(&verdict);
                // The check never panics on any text; if it did, the process reports it as
                // the panic it is rather than a silently unchecked run.
                let checked = handle.join().unwrap_or_else(|p| std::panic::resume_unwind(p));
                (result, checked)
            }
            Err(_) => {
                let checked = check();
                (work(&verdict), checked)
            }
        }
    })
}

/// CPU time of the calling thread in seconds (first field of /proc/thread-self/schedstat, ns).
pub fn thread_cpu_time_s() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = stat.split_whitespace().next()?.parse().ok()?;
    Some(ns as f64 * 1e-9)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_check_beside_reports_every_error_in_order_and_flags_the_run() {
        // Line 2 has an address without value (12080 family), line 4 an ENDIF inside the WHILE
        // of line 3 without an IF (nesting): both in line order, whatever the work does meanwhile.
        let text = "G0 X10\nG1 X=\nWHILE 1\nENDIF\nENDWHILE\nM30\n";
        let (seen_failed, checked) = check_beside(text, None, |verdict| {
            // Wait (bounded) for the verdict, as the run looks at it between chunks.
            let until = Instant::now() + std::time::Duration::from_secs(10);
            while !verdict.failed() && Instant::now() < until {
                std::thread::yield_now();
            }
            verdict.failed()
        });
        assert!(seen_failed);
        let lines: Vec<u32> = checked.errors.iter().map(|d| d.line).collect();
        assert_eq!(lines, lang::check(text).iter().map(|d| d.line).collect::<Vec<_>>());
        assert_eq!(lines, [2, 4]);
        assert!(checked.wall_s >= 0.0);
        assert_eq!(checked.blocks, 6);
    }

    #[test]
    fn a_clean_program_passes_and_the_work_result_comes_back() {
        let (n, checked) = check_beside("G0 X1\n\nM30\n", None, |verdict| {
            // A clean program never flags the run, however far the check has got.
            assert!(!verdict.failed());
            42
        });
        assert_eq!(n, 42);
        assert!(checked.errors.is_empty());
        // The blank line is no block.
        assert_eq!(checked.blocks, 2);
    }
}
