//! The program store: programs by name and directory, read and checked the first time they are
//! called, found in the control's search order.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::{Arc, OnceLock};

use super::{Dir, Kind};
use crate::alarm::{Alarm, Clear};
use crate::lang::{self, Diagnostic, ProgramText};

/// Reads a program's text when it is first called: the shell's file access (the engine does
/// no I/O itself). An `Err` is the reason the text cannot be had (unreadable, undecodable).
pub type Loader = Arc<dyn Fn() -> Result<String, String> + Send + Sync>;

/// Why a stored program cannot be called.
#[derive(Debug, Clone, PartialEq)]
pub enum CallError {
    /// Its text could not be read.
    Unreadable(String),
    /// Its text has errors found before a run ([`lang::check`]).
    Syntax(Vec<Diagnostic>),
}

/// One program of the store. Cloning shares it (and its one-time load and check).
#[derive(Clone)]
pub struct StoredProgram(Arc<Inner>);

struct Inner {
    name: String,
    dir: Option<Dir>,
    kind: Option<Kind>,
    source: Source,
    /// The checked text, or why there is none: set once, at the first call (or at once for a
    /// text checked before it was stored).
    ready: OnceLock<Result<Arc<str>, CallError>>,
}

enum Source {
    Text(Arc<str>),
    Load(Loader),
}

impl StoredProgram {
    /// A program whose text passed [`lang::check`] already.
    pub fn checked(name: String, dir: Option<Dir>, kind: Option<Kind>, text: Arc<str>) -> StoredProgram {
        let ready = OnceLock::from(Ok(text.clone()));
        StoredProgram(Arc::new(Inner { name, dir, kind, source: Source::Text(text), ready }))
    }

    /// A program in memory, checked when it is first called.
    pub fn unchecked(name: String, dir: Option<Dir>, kind: Option<Kind>, text: Arc<str>) -> StoredProgram {
        StoredProgram(Arc::new(Inner { name, dir, kind, source: Source::Text(text), ready: OnceLock::new() }))
    }

    /// A program read by `loader` and checked when it is first called.
    pub fn lazy(name: String, dir: Option<Dir>, kind: Option<Kind>, loader: Loader) -> StoredProgram {
        StoredProgram(Arc::new(Inner { name, dir, kind, source: Source::Load(loader), ready: OnceLock::new() }))
    }

    /// The canonical (upper-case) name.
    pub fn name(&self) -> &str {
        &self.0.name
    }

    /// The directory it lives in; `None` in a flat store (the session's programs).
    pub fn dir(&self) -> Option<&Dir> {
        self.0.dir.as_ref()
    }

    /// Main program or subprogram, when known.
    pub fn kind(&self) -> Option<&Kind> {
        self.0.kind.as_ref()
    }

    /// The text if it is in memory (stored as text, or loaded by a call), checked or not.
    pub fn text(&self) -> Option<&Arc<str>> {
        match (&self.0.source, self.0.ready.get()) {
            (Source::Text(text), _) | (_, Some(Ok(text))) => Some(text),
            _ => None,
        }
    }

    /// The text as stored, checked or not, read by its loader if it is not in memory yet: what
    /// the file functions (`READ`, `FILESIZE`, ...) see, for a log file need not be a program.
    pub fn raw_text(&self) -> Result<Arc<str>, String> {
        match (&self.0.source, self.0.ready.get()) {
            (Source::Text(text), _) | (_, Some(Ok(text))) => Ok(text.clone()),
            (Source::Load(load), _) => load().map(Arc::from),
        }
    }

    /// The checked text: read and checked on the first call, the answer kept.
    pub fn ready(&self) -> Result<&Arc<str>, &CallError> {
        self.0
            .ready
            .get_or_init(|| {
                let text: Arc<str> = match &self.0.source {
                    Source::Text(text) => text.clone(),
                    Source::Load(load) => Arc::from(load().map_err(CallError::Unreadable)?),
                };
                let errors = lang::check(&text);
                if errors.is_empty() { Ok(text) } else { Err(CallError::Syntax(errors)) }
            })
            .as_ref()
    }
}

impl fmt::Debug for StoredProgram {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("StoredProgram")
            .field("name", &self.0.name)
            .field("dir", &self.0.dir)
            .field("kind", &self.0.kind)
            .field("bytes", &self.text().map(|t| t.len()))
            .finish()
    }
}

/// The stored programs by name; a name may live in several directories.
#[derive(Debug, Clone, Default)]
pub struct Programs {
    by_name: BTreeMap<String, Vec<StoredProgram>>,
    /// The directory of the main program, where its calls are searched first.
    main_dir: Option<Dir>,
}

impl Programs {
    pub fn new() -> Programs {
        Programs::default()
    }

    /// Stores `text`, which passed the check, under `name` in the flat store (no directory),
    /// replacing a program of that name there.
    pub fn insert(&mut self, name: String, text: Arc<str>) {
        self.add(StoredProgram::checked(name, None, None, text));
    }

    /// Adds a program, replacing one of the same name in the same directory.
    pub fn add(&mut self, program: StoredProgram) {
        let same = self.by_name.entry(program.name().to_string()).or_default();
        same.retain(|p| p.dir() != program.dir());
        same.push(program);
    }

    /// Whether some directory, or the standard cycle library, holds a program `name` (upper
    /// case).
    pub fn contains_key(&self, name: &str) -> bool {
        self.by_name.contains_key(name) || super::cycles::find(name).is_some()
    }

    /// The text of the session's own program `name` as the main program would find it, if it
    /// is in memory; never one of the standard cycle library, which is no program of the session.
    pub fn get(&self, name: &str) -> Option<&Arc<str>> {
        self.find_stored(name, self.main_dir.as_ref(), None).and_then(StoredProgram::text)
    }

    /// The session's own program `name` (never one of the standard cycle library) as a file
    /// function names it: the one in `dir` if there is one, else the one of the main program's
    /// search (its directory, `_N_SPF_DIR`, the cycle directories, the flat store).
    pub fn file(&self, name: &str, dir: Option<&Dir>) -> Option<&StoredProgram> {
        let candidates = self.by_name.get(name)?;
        dir.and_then(|d| candidates.iter().find(|p| p.dir() == Some(d)))
            .or_else(|| self.find_stored(name, self.main_dir.as_ref(), None))
            .or_else(|| candidates.first())
    }

    /// Removes program `name` from every directory; false if there was none.
    pub fn remove(&mut self, name: &str) -> bool {
        self.by_name.remove(name).is_some()
    }

    /// The program `name` filed in exactly `dir` (`None`: the flat store).
    pub fn in_dir(&self, name: &str, dir: Option<&Dir>) -> Option<&StoredProgram> {
        self.by_name.get(name)?.iter().find(|p| p.dir() == dir)
    }

    /// Removes program `name` from `dir` only; false if it was not there.
    pub fn remove_in(&mut self, name: &str, dir: Option<&Dir>) -> bool {
        let Some(same) = self.by_name.get_mut(name) else { return false };
        let before = same.len();
        same.retain(|p| p.dir() != dir);
        let removed = same.len() != before;
        if same.is_empty() {
            self.by_name.remove(name);
        }
        removed
    }

    /// Every stored program, by name (and by directory within a name in the order stored).
    pub fn iter(&self) -> impl Iterator<Item = &StoredProgram> {
        self.by_name.values().flatten()
    }

    /// Sets the directory the main program runs from (`None`: the flat store).
    pub fn set_main_dir(&mut self, dir: Option<Dir>) {
        self.main_dir = dir;
    }

    pub fn main_dir(&self) -> Option<&Dir> {
        self.main_dir.as_ref()
    }

    /// The program `name` a program in directory `caller` calls: the caller's directory, then
    /// `_N_SPF_DIR`, then the cycle directories CUS, CMA and CST, then the flat store, then the
    /// standard cycle library shipped with NCTwin.
    pub fn find(&self, name: &str, caller: Option<&Dir>) -> Option<&StoredProgram> {
        self.find_with_path(name, caller, None)
    }

    /// [`Programs::find`] with the search path extension of CALLPATH (`callpath`), searched
    /// after `_N_SPF_DIR` and before the cycle directories, as the Programming Manual orders
    /// the search (Job planning, "Search path for subprogram call"); the standard cycle library
    /// comes last.
    pub fn find_with_path(&self, name: &str, caller: Option<&Dir>, callpath: Option<&Dir>) -> Option<&StoredProgram> {
        self.find_stored(name, caller, callpath).or_else(|| super::cycles::find(name))
    }

    /// [`Programs::find_with_path`] among the session's own programs only.
    fn find_stored(&self, name: &str, caller: Option<&Dir>, callpath: Option<&Dir>) -> Option<&StoredProgram> {
        let candidates = self.by_name.get(name)?;
        let in_dir = |dir: Option<&Dir>| candidates.iter().find(|p| p.dir() == dir);
        in_dir(caller)
            .or_else(|| in_dir(Some(&Dir::Spf)))
            .or_else(|| callpath.and_then(|c| in_dir(Some(c))))
            .or_else(|| [Dir::Cus, Dir::Cma, Dir::Cst].iter().find_map(|d| in_dir(Some(d))))
            .or_else(|| in_dir(None))
    }

    /// The checked text and directory of the program `name` called at `line` from a program in
    /// `caller`; the alarm of the call otherwise: 14011 when there is no such program or it
    /// cannot be read, its own first error (naming it, its line and column) when it does not
    /// pass the check.
    pub fn resolve(&self, name: &str, caller: Option<&Dir>, line: u32) -> Result<(ProgramText, Option<Dir>), Alarm> {
        self.resolve_with_path(name, caller, None, line)
    }

    /// [`Programs::resolve`] with the CALLPATH extension (see [`Programs::find_with_path`]).
    pub fn resolve_with_path(
        &self,
        name: &str,
        caller: Option<&Dir>,
        callpath: Option<&Dir>,
        line: u32,
    ) -> Result<(ProgramText, Option<Dir>), Alarm> {
        let program =
            self.find_with_path(name, caller, callpath).ok_or_else(|| Alarm::program_not_found(line, name))?;
        match program.ready() {
            Ok(text) => Ok((ProgramText::from(text.clone()), program.dir().cloned())),
            Err(CallError::Unreadable(reason)) => Err(Alarm {
                number: 14011,
                message: format!("Channel 1 block {line} program {name} not available: {reason}"),
                line: Some(line),
                clear: Clear::Reset,
            }),
            Err(CallError::Syntax(errors)) => {
                let first = &errors[0];
                let more = match errors.len() {
                    1 => String::new(),
                    n => format!(" (and {} more)", n - 1),
                };
                Err(Alarm {
                    number: first.alarm,
                    message: format!(
                        "Channel 1 block {line} program {name} line {} column {}: {}{more}",
                        first.line, first.column, first.message
                    ),
                    line: Some(line),
                    clear: Clear::Reset,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(t: &str) -> Arc<str> {
        Arc::from(t)
    }

    fn store() -> Programs {
        let mut p = Programs::new();
        p.add(StoredProgram::unchecked("SUB".into(), Some(Dir::Cst), None, text("G0 X4\nM17")));
        p.add(StoredProgram::unchecked("SUB".into(), Some(Dir::Cus), None, text("G0 X3\nM17")));
        p.add(StoredProgram::unchecked("SUB".into(), Some(Dir::Spf), None, text("G0 X2\nM17")));
        p.add(StoredProgram::unchecked("SUB".into(), Some(Dir::Workpiece("A".into())), None, text("G0 X1\nM17")));
        p
    }

    fn found(p: &Programs, caller: Option<&Dir>) -> String {
        p.resolve("SUB", caller, 7).map(|(t, _)| t.to_string()).unwrap_or_else(|a| a.message)
    }

    #[test]
    fn a_call_searches_the_callers_directory_then_spf_then_the_cycle_directories() {
        let mut p = store();
        assert_eq!(found(&p, Some(&Dir::Workpiece("A".into()))), "G0 X1\nM17");
        assert_eq!(found(&p, Some(&Dir::Workpiece("B".into()))), "G0 X2\nM17");
        assert_eq!(found(&p, Some(&Dir::Mpf)), "G0 X2\nM17");
        p.by_name.get_mut("SUB").unwrap().retain(|s| s.dir() != Some(&Dir::Spf));
        assert_eq!(found(&p, Some(&Dir::Mpf)), "G0 X3\nM17");
        p.by_name.get_mut("SUB").unwrap().retain(|s| s.dir() != Some(&Dir::Cus));
        assert_eq!(found(&p, None), "G0 X4\nM17");
        p.by_name.get_mut("SUB").unwrap().retain(|s| s.dir() != Some(&Dir::Cst));
        // Only in workpiece A: not reachable from elsewhere.
        assert_eq!(found(&p, None), "Channel 1 block 7 program SUB not available");
    }

    #[test]
    fn the_callpath_directory_comes_after_spf_and_before_the_cycle_directories() {
        let mut p = store();
        let fixture = Dir::Workpiece("A".into());
        let text = |p: &Programs, callpath: Option<&Dir>| {
            p.find_with_path("SUB", Some(&Dir::Mpf), callpath).and_then(StoredProgram::text).map(|t| t.to_string())
        };
        // SPF first, then the CALLPATH directory, then CUS.
        assert_eq!(text(&p, Some(&fixture)).as_deref(), Some("G0 X2\nM17"));
        p.by_name.get_mut("SUB").unwrap().retain(|s| s.dir() != Some(&Dir::Spf));
        assert_eq!(text(&p, Some(&fixture)).as_deref(), Some("G0 X1\nM17"));
        assert_eq!(text(&p, None).as_deref(), Some("G0 X3\nM17"), "without CALLPATH: CUS");
    }

    #[test]
    fn a_broken_program_raises_its_own_error_at_the_call_and_loads_once() {
        let loads = Arc::new(std::sync::atomic::AtomicU32::new(0));
        let counter = loads.clone();
        let loader: Loader = Arc::new(move || {
            counter.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
            Ok("G1 X1 F100\nG1 X=\nM17\n".to_string())
        });
        let mut p = Programs::new();
        p.add(StoredProgram::lazy("BROKEN".into(), Some(Dir::Spf), Some(Kind::Sub), loader));
        p.add(StoredProgram::lazy("GONE".into(), None, None, Arc::new(|| Err("not UTF-8".to_string()))));
        assert_eq!(loads.load(std::sync::atomic::Ordering::SeqCst), 0, "nothing read before a call");
        let alarm = p.resolve("BROKEN", None, 12).unwrap_err();
        assert_eq!((alarm.number, alarm.line), (12080, Some(12)));
        assert!(alarm.message.starts_with("Channel 1 block 12 program BROKEN line 2 column "), "{}", alarm.message);
        p.resolve("BROKEN", None, 13).unwrap_err();
        assert_eq!(loads.load(std::sync::atomic::Ordering::SeqCst), 1, "read and checked once");
        let alarm = p.resolve("GONE", None, 3).unwrap_err();
        assert_eq!(alarm.number, 14011);
        assert!(alarm.message.ends_with("not available: not UTF-8"), "{}", alarm.message);
    }

    #[test]
    fn the_flat_store_keeps_one_program_per_name() {
        let mut p = Programs::new();
        p.insert("A".into(), text("M17"));
        p.insert("A".into(), text("G0 X1\nM17"));
        assert_eq!(p.iter().count(), 1);
        assert_eq!(p.get("A").map(|t| &**t), Some("G0 X1\nM17"));
        assert!(p.remove("A"));
        assert!(!p.contains_key("A"));
    }
}
