//! `nctwin check DIR-or-FILE...`: checks every program of folders, archives and program files
//! the way a run would meet them, and prints one line per finding, like a linter:
//!
//! ```text
//! path:line:col: alarm NNNNN: text
//! path: error: text          (a file that cannot be read, or an odd program name)
//! path: warning: text        (a file skipped that is no program: printed, not a finding)
//! ```
//!
//! Found: syntax errors and bad nesting ([`lang::check`]), files that cannot be read or decoded,
//! names that are no program names, and called names that are not defined: `L123`,
//! `CALL "NAME"` and bare names that are neither a program the call would find (in the
//! control's search order from the caller's directory) nor a word of the language. Line
//! numbers are the file's. Exit code: 0 nothing found, 1 findings, 2 usage or I/O error.

use std::collections::HashMap;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use nctwin_engine::interp::{Interpreter, Item, Prep, Programs};
use nctwin_engine::lang::{self, Expr, Word};
use nctwin_engine::machine_data::registry::MAX_CHANNEL_AXES;
use nctwin_engine::programs::{CallError, Dir, StoredProgram};
use nctwin_engine::{Channel, MachineConfig};

use super::folder::{self, Folder, Origin};

/// Arguments of `nctwin check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Machine preset whose language words are known (axis names are words too).
    #[arg(long, value_name = "PRESET", default_value = "mill-3axis")]
    pub machine: String,
    /// Program folders (laid out like --program-dir), program files and archives.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
}

/// Entry point of the subcommand.
pub fn main(args: &CheckArgs) -> ExitCode {
    let channel = match Channel::from_preset(&args.machine, "") {
        Ok(channel) => channel,
        Err(e) => {
            eprintln!("nctwin check: {e}");
            return ExitCode::from(2);
        }
    };
    let mut out = Vec::new();
    for path in &args.paths {
        let opened = if path.is_dir() { folder::open(path) } else { folder::open_file(path) };
        match opened {
            Ok(folder) => check_folder(&folder, channel.config(), &mut out),
            Err(e) => {
                eprintln!("nctwin check: {e}");
                return ExitCode::from(2);
            }
        }
    }
    let findings = out.iter().filter(|f| f.error).count();
    let mut stdout = std::io::stdout().lock();
    for finding in &out {
        if writeln!(stdout, "{}", finding.text).is_err() {
            return ExitCode::from(2);
        }
    }
    if findings > 0 { ExitCode::from(1) } else { ExitCode::SUCCESS }
}

/// One printed line; `error` lines make the exit code 1.
struct Finding {
    text: String,
    error: bool,
}

fn check_folder(folder: &Folder, cfg: &MachineConfig, out: &mut Vec<Finding>) {
    for note in &folder.notes {
        let at = note.line.map(|l| format!(":{l}")).unwrap_or_default();
        let level = if note.finding { "error" } else { "warning" };
        out.push(Finding { text: format!("{}{at}: {level}: {}", note.path, note.message), error: note.finding });
    }
    let mut store = Programs::new();
    for (program, _) in &folder.programs {
        store.add(program.clone());
    }
    let mut words = WordProbe::new(cfg);
    for (program, origin) in &folder.programs {
        let path = origin.path.display();
        match program.ready() {
            Err(CallError::Unreadable(reason)) => {
                let prefix = format!("{path}: ");
                let reason = reason.strip_prefix(&prefix).unwrap_or(reason);
                out.push(Finding { text: format!("{path}: error: {reason}"), error: true });
            }
            Err(CallError::Syntax(errors)) => {
                for d in errors {
                    let line = d.line + origin.first_line - 1;
                    let text = format!("{path}:{line}:{}: alarm {}: {}", d.column, d.alarm, d.message);
                    out.push(Finding { text, error: true });
                }
            }
            Ok(text) => check_calls(program, origin, text, &store, &mut words, out),
        }
    }
}

/// Called names of a program that passed the syntax check and that nothing defines.
fn check_calls(
    program: &StoredProgram,
    origin: &Origin,
    text: &str,
    store: &Programs,
    words: &mut WordProbe,
    out: &mut Vec<Finding>,
) {
    for block in lang::parse(text).blocks {
        for word in &block.words {
            // (name, called explicitly: L or CALL)
            let called = match word {
                // `L123`: the parser names the call by its digits as written.
                Word::Keyword { name, .. }
                    if name.len() > 1 && name.starts_with('L') && name[1..].bytes().all(|b| b.is_ascii_digit()) =>
                {
                    Some((name.clone(), true))
                }
                Word::Keyword { name, args } if name == "CALL" => match args.as_slice() {
                    [Expr::Str(s)] => Some((s.to_ascii_uppercase(), true)),
                    _ => None,
                },
                Word::Keyword { name, .. } if store.contains_key(name) || !words.known(name) => {
                    Some((name.clone(), false))
                }
                _ => None,
            };
            let Some((name, explicit)) = called else { continue };
            if store.find(&name, program.dir()).is_some() {
                continue;
            }
            let line_text = text[block.offset..].lines().next().unwrap_or("");
            let column = line_text.to_ascii_uppercase().find(&name).map_or(1, |c| c + 1);
            let line = block.line + origin.first_line - 1;
            let message = match (store.contains_key(&name), program.dir()) {
                (true, Some(dir)) => {
                    format!("alarm 14011: program {name} not available from {}", Dir::path(dir))
                }
                (true, None) => format!("alarm 14011: program {name} not available"),
                (false, _) if explicit => format!("alarm 14011: program {name} not available"),
                (false, _) => format!("alarm 12550: name {name} not defined"),
            };
            out.push(Finding { text: format!("{}:{line}:{column}: {message}", origin.path.display()), error: true });
        }
    }
}

/// Whether a bare name is a word of the language: the interpreter is asked with the name alone
/// in a block of an empty store (12550 means it does not know it). Answers are kept.
struct WordProbe<'a> {
    cfg: &'a MachineConfig,
    known: HashMap<String, bool>,
}

impl<'a> WordProbe<'a> {
    fn new(cfg: &'a MachineConfig) -> WordProbe<'a> {
        WordProbe { cfg, known: HashMap::new() }
    }

    fn known(&mut self, name: &str) -> bool {
        if let Some(&known) = self.known.get(name) {
            return known;
        }
        let mut interp = Interpreter::new(self.cfg);
        interp.begin_program(format!("{name}\n"), &[0.0; MAX_CHANNEL_AXES]);
        let mut out = Vec::new();
        let empty = Programs::new();
        let mut known = true;
        for _ in 0..4 {
            out.clear();
            let prep = interp.prepare_next(self.cfg, &empty, true, &mut out);
            if out.iter().any(|i| matches!(i, Item::Alarm(a) if a.number == 12550)) {
                known = false;
            }
            if prep == Prep::Done {
                break;
            }
        }
        self.known.insert(name.to_string(), known);
        known
    }
}
