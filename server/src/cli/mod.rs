//! Subcommands of `nctwin` besides the server: work with the engine directly, no HTTP.
//!
//! - `nctwin simulate`: runs a program in fast pace and prints the final state and timing
//!   figures as JSON ([`simulate`]).
//! - `nctwin check`: checks folders, archives and program files and prints the findings like
//!   a linter ([`check`]).
//!
//! `folder` opens program folders laid out like the control's (used by both).

mod blocks;
pub mod check;
mod check_beside;
pub mod folder;
mod mapped;
pub mod simulate;

use std::process::ExitCode;

/// The subcommands; without one, `nctwin` serves HTTP.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Runs a part program in fast pace with the engine (no server) and prints the final state
    /// and timing figures as JSON. Exit code 0: normal end; 2: the program ended in an alarm
    /// (or has syntax errors); 3: stopped by --max-sim-time; 1: usage or I/O error.
    Simulate(simulate::SimulateArgs),
    /// Checks every program of folders (laid out like --program-dir), archives and program
    /// files: syntax, nesting, files that cannot be read, called names not defined. Prints one
    /// line per finding (`path:line:col: alarm NNNNN: text`). Exit code 0: nothing found;
    /// 1: findings; 2: usage or I/O error.
    Check(check::CheckArgs),
}

/// Runs a subcommand to its end and returns the process exit code.
pub fn run(command: &Command) -> ExitCode {
    match command {
        Command::Simulate(args) => simulate::main(args),
        Command::Check(args) => check::main(args),
    }
}

/// Handles an error of the argument parser: `--help` and `--version` print and exit 0; a
/// usage error exits with clap's code 2, except under `simulate`, where 2 means "the program
/// ended in an alarm" and usage errors exit with 1.
pub fn parse_error<T>(error: clap::Error) -> T {
    if error.use_stderr() && std::env::args().skip(1).any(|a| a == "simulate") {
        let _ = error.print();
        std::process::exit(1);
    }
    error.exit()
}
