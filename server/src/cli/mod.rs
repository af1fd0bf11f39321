//! Subcommands of `nctwin` besides the server: work with the engine directly, no HTTP.
//!
//! - `nctwin simulate`: runs a program in fast pace and prints the final state and timing
//!   figures as JSON ([`simulate`]).

mod blocks;
mod check_beside;
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
}

/// Runs a subcommand to its end and returns the process exit code.
pub fn run(command: &Command) -> ExitCode {
    match command {
        Command::Simulate(args) => simulate::main(args),
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
