//! `nctwin simulate`: one program in fast pace on one channel, straight on the engine.
//!
//! For CI users (no server needed: the exit code tells whether the program ran to its end) and
//! for benchmarks (no HTTP in the figures). Prints one JSON object on stdout: the final state in
//! the same shape as `GET /api/v1/sessions/{id}/state`, and the timing figures.
//!
//! Exit codes: 0 the program ended normally; 2 it ended in an alarm or has syntax errors;
//! 3 it was stopped by `--max-sim-time`; 4 the channel stood still with nothing left that could
//! change (a thread or G95 block with the spindle stopped, a wait for an input): a real control
//! stands there without an alarm until the operator acts, so the run ends with a message instead
//! of running for ever; 1 usage or I/O error (message on stderr).

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use nctwin_engine::alarm::Clear;
use nctwin_engine::interp::{Interpreter, Item, Prep, Programs};
use nctwin_engine::lang::ProgramText;
use nctwin_engine::machine_data::registry::MAX_CHANNEL_AXES;
use nctwin_engine::programs::{Kind, StoredProgram, archive, canonical_name};
use nctwin_engine::{Channel, Event, Status};
use nctwin_server::dto;
use nctwin_server::text_decode::decode;

use super::blocks::count_blocks;
use super::check_beside::{Checked, Verdict, check_beside, thread_cpu_time_s};
use super::folder::{self, Note};
use super::mapped;
use serde::Serialize;

/// Exit code: the program ended in an alarm or did not pass the syntax check.
pub const EXIT_ALARM: u8 = 2;
/// Exit code: `--max-sim-time` stopped the program.
pub const EXIT_LIMIT: u8 = 3;

/// Exit code: the channel could make no more progress (see [`STANDSTILL_S`]).
pub const EXIT_STANDSTILL: u8 = 4;

/// Simulated seconds over which a busy channel's progress mark must stay the same before the
/// run ends as standing still. Every countdown (G4, a tool change's time) is in the mark, so
/// this only needs to be longer than a check interval; a minute leaves room.
const STANDSTILL_S: f64 = 60.0;

/// How many IPO cycles run between two looks at the events, the time limit and the syntax check.
const CHUNK: u64 = 4096;

/// How many preparation steps of `--interpret-only` run between two looks at the syntax check.
const PREP_CHUNK: u64 = 1024;

/// Arguments of `nctwin simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    /// Built-in machine preset, e.g. mill-3axis (see GET /api/v1/machines).
    #[arg(long, value_name = "PRESET")]
    pub machine: String,
    /// NC data text applied on top of the preset ($MN_/$MC_/$MA_, $TC_DP, $P_UIFR).
    #[arg(long, value_name = "FILE")]
    pub machine_data: Option<PathBuf>,
    /// Folder of programs for calls by name: *.SPF/*.MPF files (any case) and archives, loose or
    /// in the control's directories (MPF, SPF, WKS/<NAME>.WPD, CUS, CMA, CST). Each program is
    /// read and checked when it is first called.
    #[arg(long, value_name = "DIR")]
    pub program_dir: Option<PathBuf>,
    /// Stop (NC stop, then braking) after this many simulated seconds; exit code 3.
    #[arg(long, value_name = "SECONDS")]
    pub max_sim_time: Option<f64>,
    /// Stay at M0 (and M1 with --optional-stop) instead of continuing as an operator's NC
    /// start would.
    #[arg(long)]
    pub stop_at_m0: bool,
    /// Optional stop selected: M1 stops like M0.
    #[arg(long)]
    pub optional_stop: bool,
    /// Block preparation only: every block parsed and interpreted into moves, nothing
    /// planned or interpolated (no IPO cycles). The figure to compare with interpreters that
    /// only translate a program into motion segments. The report has no `state`.
    #[arg(long)]
    pub interpret_only: bool,
    /// Print the JSON on one line.
    #[arg(long)]
    pub compact: bool,
    /// Write the stock (the blank of `WORKPIECE(..)` as the program cut it) as a binary STL
    /// at the end (BCS, mm). A program without a blank is a usage error (exit code 1).
    #[arg(long, value_name = "FILE")]
    pub stock_out: Option<PathBuf>,
    /// Resolution of material removal, mm: the dexel cell (milling) or slab (turning).
    #[arg(long, value_name = "MM", default_value_t = nctwin_engine::stock::DEFAULT_RESOLUTION)]
    pub stock_resolution: f64,
    /// Depth of cut beyond which the `depth_of_cut` check is raised, mm.
    #[arg(long, value_name = "MM")]
    pub depth_limit: Option<f64>,
    /// The part program (main program) to run; an NC data file (`.INI`, or an archive whose
    /// header is `%_N_<NAME>_INI`) runs as the control runs it: its data are loaded.
    pub program: PathBuf,
}

/// How the run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// M2/M30 or the end of the text.
    Ended,
    /// Stopped at M0/M1 (`--stop-at-m0`).
    Stopped,
    /// An alarm stopped the program.
    Alarm,
    /// `--max-sim-time` stopped the program.
    Limit,
    /// The channel stood still with nothing that could change any more (`standstill` says where).
    Standstill,
    /// The program (or a stored subprogram) did not pass the syntax check; nothing ran.
    SyntaxError,
}

/// An error found before the run (syntax, nesting of control structures).
#[derive(Debug, Clone, Serialize)]
pub struct SyntaxError {
    /// Program file the error is in.
    pub program: String,
    /// The NC alarm number (12080 syntax error, 12640 invalid nesting, ...).
    pub alarm: u32,
    pub line: u32,
    pub column: u32,
    pub message: String,
}

impl SyntaxError {
    /// One entry per error of `program`.
    fn all(program: &str, errors: Vec<nctwin_engine::lang::Diagnostic>) -> impl Iterator<Item = SyntaxError> + '_ {
        errors.into_iter().map(move |d| SyntaxError {
            program: program.to_string(),
            alarm: d.alarm,
            line: d.line,
            column: d.column,
            message: d.message,
        })
    }
}

/// What `nctwin simulate` prints.
#[derive(Debug, Serialize)]
pub struct Report {
    pub outcome: Outcome,
    pub program: String,
    pub machine: String,
    /// The channel's state at the end, as `GET /api/v1/sessions/{id}/state` shows it (not
    /// with `--interpret-only`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub state: Option<dto::State>,
    /// With `--interpret-only`: the moves prepared and the alarm that ended preparation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub moves: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alarm: Option<dto::AlarmInfo>,
    /// With outcome `standstill`: the block the channel stood at and why the run ended there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub standstill: Option<Standstill>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub syntax_errors: Vec<SyntaxError>,
    /// Files of `--program-dir` (and lines of archives) that were skipped, and NC data lines
    /// of `--machine-data` stored but not modelled: why, one entry each.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<Note>,
    /// Program size in bytes.
    pub program_bytes: usize,
    /// Non-empty lines of the program (one block each, comment lines included), the count the
    /// benchmark generator and the peers' figures use.
    pub blocks: u64,
    /// Blocks that became the current block (blocks with motion or a main-run action).
    pub block_changes: u64,
    /// M0/M1 stops continued.
    pub program_stops: u64,
    pub ipo_cycle_s: f64,
    pub ipo_cycles: u64,
    pub simulated_time_s: f64,
    /// Wall time of loading (syntax check) and running the program.
    pub wall_time_s: f64,
    /// Wall time of the syntax check (part of `wall_time_s`): it runs on a second thread
    /// beside the run, which starts at once and is discarded if the check finds errors.
    pub load_time_s: f64,
    /// CPU time of the simulating thread plus the syntax check's thread over `wall_time_s`
    /// (from /proc/thread-self/schedstat; `null` where missing): on a busy machine
    /// `blocks / cpu_time_s` is the steadier figure.
    pub cpu_time_s: Option<f64>,
    pub blocks_per_s: f64,
    pub cycles_per_s: f64,
    /// Simulated time per wall time.
    pub real_time_factor: f64,
    /// Peak resident set size of the process (VmHWM), KiB; `null` where /proc is missing.
    pub peak_rss_kib: Option<u64>,
    /// The checks of material removal raised (the latest 64): rapid into stock, cutting
    /// without the spindle, depth of cut; the volumes are in `state.stock`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stock_warnings: Vec<nctwin_server::api::stock::StockWarningInfo>,
}

/// Where a run that could make no more progress stood.
#[derive(Debug, Clone, Serialize)]
pub struct Standstill {
    /// The line of the block shown when the channel stood (`null` before the first block).
    pub line: Option<u32>,
    /// Simulated seconds the channel stood before the run ended.
    pub stood_s: f64,
    pub message: String,
}

/// Usage and I/O errors: printed on stderr, exit code 1.
#[derive(Debug)]
struct UsageError(String);

/// Entry point of the subcommand.
pub fn main(args: &SimulateArgs) -> ExitCode {
    match simulate(args) {
        Ok(report) => {
            let json =
                if args.compact { serde_json::to_string(&report) } else { serde_json::to_string_pretty(&report) };
            let written = json.map_err(std::io::Error::from).and_then(|json| {
                let mut stdout = std::io::stdout().lock();
                writeln!(stdout, "{json}").and_then(|()| stdout.flush())
            });
            match written {
                Ok(()) => {}
                // The reader went away (`| head`): nothing to tell it, and no panic either.
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => return ExitCode::FAILURE,
                Err(e) => {
                    eprintln!("nctwin simulate: cannot write the report: {e}");
                    return ExitCode::FAILURE;
                }
            }
            match report.outcome {
                Outcome::Ended | Outcome::Stopped => ExitCode::SUCCESS,
                Outcome::Alarm | Outcome::SyntaxError => ExitCode::from(EXIT_ALARM),
                Outcome::Limit => ExitCode::from(EXIT_LIMIT),
                Outcome::Standstill => {
                    if let Some(s) = &report.standstill {
                        eprintln!("nctwin simulate: {}", s.message);
                    }
                    ExitCode::from(EXIT_STANDSTILL)
                }
            }
        }
        Err(UsageError(message)) => {
            eprintln!("nctwin simulate: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Reads a text file in any encoding [`decode`] knows.
fn read_text(path: &Path, what: &str) -> Result<String, UsageError> {
    let bytes = std::fs::read(path).map_err(|e| UsageError(format!("cannot read {what} {}: {e}", path.display())))?;
    decode(&bytes).map(|d| d.text).map_err(|e| UsageError(format!("cannot read {what} {}: {e}", path.display())))
}

/// Reads a program into the shared text the channel keeps. A long one (from
/// [`mapped::MAP_FROM_BYTES`]) is mapped instead, with a [`mapped::PageRelease`] that keeps its
/// pages out of the resident set while it lives; a short one is read straight into memory, once
/// (reading into a `String` and converting would hold it twice at the peak). A file that is not
/// UTF-8 is decoded into memory ([`decode`]: legacy code pages).
fn read_shared_text(path: &Path) -> Result<(ProgramText, Option<mapped::PageRelease>), UsageError> {
    let error = |e: std::io::Error| UsageError(format!("cannot read program {}: {e}", path.display()));
    let mut file = std::fs::File::open(path).map_err(error)?;
    let len = file.metadata().map_err(error)?.len();
    if len >= mapped::MAP_FROM_BYTES {
        return match mapped::map(&file, path) {
            Ok((text, release)) => Ok((text, Some(release))),
            Err(e) if e.contains("not UTF-8") => Ok((ProgramText::from(read_text(path, "program")?), None)),
            Err(e) => Err(UsageError(e)),
        };
    }
    let len = usize::try_from(len).map_err(|_| UsageError(format!("program {} is too large", path.display())))?;
    let mut bytes: Arc<[u8]> = std::iter::repeat_n(0u8, len).collect();
    file.read_exact(Arc::get_mut(&mut bytes).expect("not shared yet")).map_err(error)?;
    if file.read(&mut [0u8]).map_err(error)? != 0 {
        return Err(UsageError(format!("program {} changed while it was read", path.display())));
    }
    if std::str::from_utf8(&bytes).is_err() || bytes.starts_with(b"\xEF\xBB\xBF") {
        let decoded = decode(&bytes).map_err(|e| UsageError(format!("cannot read program {}: {e}", path.display())))?;
        return Ok((ProgramText::from(decoded.text), None));
    }
    // SAFETY: the bytes were checked to be UTF-8 just above, and `str` has the layout of `[u8]`,
    // so the allocation is a valid `Arc<str>` (this is how std converts `Arc<[u8]>` itself).
    let text: Arc<str> = unsafe { Arc::from_raw(Arc::into_raw(bytes) as *const str) };
    Ok((ProgramText::from(text), None))
}

/// A main program file in archive format: its first main program (or first program) runs, with
/// its header lines as comments; the file's other programs join the store, in the directory of
/// their `;$PATH=` line or the main program's.
fn main_from_archive(
    channel: &mut Channel,
    path: &Path,
    text: &str,
    notes: &mut Vec<Note>,
) -> Result<ProgramText, UsageError> {
    let split = archive::split(text);
    for problem in &split.problems {
        let message = problem.message.clone();
        notes.push(Note { path: path.display().to_string(), line: Some(problem.line), message, finding: true });
    }
    let programs: Vec<_> = split.entries.iter().filter(|e| e.kind.is_program()).collect();
    let main = programs
        .iter()
        .position(|e| e.kind == Kind::Main)
        .or((!programs.is_empty()).then_some(0))
        .ok_or_else(|| UsageError(format!("{}: no program in the archive", path.display())))?;
    let main_dir = channel.program_store().main_dir().cloned();
    for entry in programs.iter().enumerate().filter(|(i, _)| *i != main).map(|(_, e)| e) {
        let Some(name) = canonical_name(&entry.name) else {
            let message = "not a program name: skipped".to_string();
            notes.push(Note { path: path.display().to_string(), line: Some(entry.line), message, finding: true });
            continue;
        };
        let dir = entry.dir.clone().or(main_dir.clone());
        let text = Arc::from(entry.numbered_text());
        channel.program_store_mut().add(StoredProgram::unchecked(name, dir, Some(entry.kind.clone()), text));
    }
    if let Some(dir) = &programs[main].dir {
        channel.program_store_mut().set_main_dir(Some(dir.clone()));
    }
    Ok(ProgramText::from(programs[main].numbered_text()))
}

fn simulate(args: &SimulateArgs) -> Result<Report, UsageError> {
    if let Some(t) = args.max_sim_time
        && !(t.is_finite() && t > 0.0)
    {
        return Err(UsageError(format!("--max-sim-time must be a positive number of seconds, not {t}")));
    }
    let extra = match &args.machine_data {
        Some(path) => read_text(path, "machine data")?,
        None => String::new(),
    };
    let md_path = args.machine_data.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
    let warnings = nctwin_engine::machine_data::text::warnings(&extra);
    let mut channel = Channel::from_preset(&args.machine, &extra).map_err(|e| match e.line {
        Some(line) => UsageError(format!("machine data line {line}: {}", e.message)),
        None => UsageError(e.message),
    })?;
    channel.optional_stop = args.optional_stop;
    nctwin_server::session::start_clock(&mut channel);
    let options = nctwin_engine::channel::StockOptions {
        resolution: args.stock_resolution,
        depth_limit: args.depth_limit,
        holder: None,
    };
    channel.set_stock_options(options).map_err(|e| UsageError(format!("--stock-resolution/--depth-limit: {e}")))?;
    let mut syntax_errors = Vec::new();
    let mut notes = warnings
        .into_iter()
        .map(|message| Note { path: md_path.clone(), line: None, message, finding: false })
        .collect();
    if let Some(dir) = &args.program_dir {
        store_programs(&mut channel, dir, &args.program, &mut notes)?;
    }
    // Pages of a mapped program are given back until the run is over.
    let (mut text, release) = read_shared_text(&args.program)?;
    // A data file (`_N_TOA_INI` archive, `.INI` file) runs as the control runs it: its data
    // are loaded (the channel does so for a text with the `_INI` header; a `.INI` file without
    // one is loaded here, with its own line numbers, and leaves nothing to run).
    let ini = args.program.extension().is_some_and(|e| e.eq_ignore_ascii_case("ini"));
    if ini && !archive::is_data_file(&text) {
        channel.run_data_file(&text).map_err(|e| UsageError(format!("{}: {e}", args.program.display())))?;
        text = ProgramText::from(String::new());
    }
    if archive::is_archive(&text) && !archive::is_data_file(&text) {
        text = main_from_archive(&mut channel, &args.program, &text, &mut notes)?;
    }
    let program_bytes = text.len();
    let program = args.program.display().to_string();

    if args.interpret_only {
        return Ok(interpret_only(&channel, args, (text, release.as_ref()), (syntax_errors, notes), program));
    }
    // The state a program with syntax errors leaves: nothing ran.
    let (idle_state, idle_ticks, idle_time) = (dto::State::from(&channel.snapshot()), channel.ticks(), channel.time());
    let started = Instant::now();
    let cpu_started = thread_cpu_time_s();
    // The main program's check runs beside the run; stored programs were checked above.
    let (started_run, Beside { blocks, load_time_s, check_cpu_s }) =
        run_beside_check((&text, release.as_ref()), &program, &mut syntax_errors, |verdict| {
            channel.run_program_prechecked(text.clone()).map(|()| run_to_end(&mut channel, args, verdict))
        });
    let run = started_run.transpose().map_err(|e| UsageError(e.to_string()))?.unwrap_or_default();
    drop(text);
    let loaded = syntax_errors.is_empty();
    let wall_time_s = started.elapsed().as_secs_f64();
    let cpu_time_s = cpu_since(cpu_started, check_cpu_s);

    let outcome = if !loaded {
        Outcome::SyntaxError
    // Alarms cleared by the cancel key only inform (10910): the run still ended or stopped.
    } else if channel.status() == Status::Alarm || channel.alarms().iter().any(|a| a.clear == Clear::Reset) {
        Outcome::Alarm
    } else if run.limit_hit {
        Outcome::Limit
    } else if run.standstill.is_some() {
        Outcome::Standstill
    } else if channel.status() == Status::Stopped {
        Outcome::Stopped
    } else {
        Outcome::Ended
    };
    // The stock's last segment is cut before the state shows its volumes.
    let _ = channel.stock_info();
    if let Some(path) = &args.stock_out {
        let stl = channel.stock_stl().ok_or_else(|| {
            UsageError(format!("--stock-out {}: the program defines no blank (WORKPIECE)", path.display()))
        })?;
        std::fs::write(path, stl).map_err(|e| UsageError(format!("cannot write {}: {e}", path.display())))?;
    }
    let stock_warnings =
        channel.stock_warnings().iter().map(nctwin_server::api::stock::StockWarningInfo::from).collect();
    let (ipo_cycles, simulated_time_s, state) = if loaded {
        (channel.ticks(), channel.time(), dto::State::from(&channel.snapshot()))
    } else {
        (idle_ticks, idle_time, idle_state)
    };
    let per_s = |n: f64| if wall_time_s > 0.0 { n / wall_time_s } else { 0.0 };
    Ok(Report {
        outcome,
        program,
        machine: args.machine.clone(),
        state: Some(state),
        moves: None,
        alarm: None,
        standstill: run.standstill,
        syntax_errors,
        notes,
        program_bytes,
        blocks,
        block_changes: run.block_changes,
        program_stops: run.program_stops,
        ipo_cycle_s: channel.config().ipo_cycle,
        ipo_cycles,
        simulated_time_s,
        wall_time_s,
        load_time_s,
        cpu_time_s,
        blocks_per_s: per_s(blocks as f64),
        cycles_per_s: per_s(ipo_cycles as f64),
        real_time_factor: per_s(simulated_time_s),
        peak_rss_kib: peak_rss_kib(),
        stock_warnings,
    })
}

/// What the thread beside the run found besides the errors.
struct Beside {
    /// The program's blocks ([`count_blocks`]).
    blocks: u64,
    /// The check's wall time.
    load_time_s: f64,
    /// The thread's CPU time (`None` where /proc is missing).
    check_cpu_s: Option<f64>,
}

/// Runs `work` with the main program's syntax check (and block count) beside it, unless
/// `syntax_errors` already holds some (then nothing runs and the blocks are counted here). The
/// check's errors join `syntax_errors`; `work`'s result is kept only when there are none (an
/// error found by the check wins over whatever the discarded run ran into).
fn run_beside_check<T>(
    (text, release): (&str, Option<&mapped::PageRelease>),
    program: &str,
    syntax_errors: &mut Vec<SyntaxError>,
    work: impl FnOnce(&Verdict) -> T,
) -> (Option<T>, Beside) {
    if !syntax_errors.is_empty() {
        let blocks = count_blocks(text, release);
        return (None, Beside { blocks, load_time_s: 0.0, check_cpu_s: Some(0.0) });
    }
    let (result, Checked { errors, blocks, wall_s, cpu_s }) = check_beside(text, release, work);
    syntax_errors.extend(SyntaxError::all(program, errors));
    (syntax_errors.is_empty().then_some(result), Beside { blocks, load_time_s: wall_s, check_cpu_s: cpu_s })
}

/// CPU time of this thread since `started` plus the check thread's (`None` where /proc is missing).
fn cpu_since(started: Option<f64>, check_cpu_s: Option<f64>) -> Option<f64> {
    thread_cpu_time_s().zip(started).zip(check_cpu_s).map(|((end, start), check)| end - start + check)
}

/// `--interpret-only`: block preparation of the whole program (as if the main run had executed
/// everything prepared so far), counting the moves, with the syntax check beside it (a program
/// with errors reports them and nothing else).
fn interpret_only(
    channel: &Channel,
    args: &SimulateArgs,
    (text, release): (ProgramText, Option<&mapped::PageRelease>),
    (mut syntax_errors, notes): (Vec<SyntaxError>, Vec<Note>),
    program: String,
) -> Report {
    let program_bytes = text.len();
    let started = Instant::now();
    let cpu_started = thread_cpu_time_s();
    let (prepared, Beside { blocks, load_time_s, check_cpu_s }) =
        run_beside_check((&text, release), &program, &mut syntax_errors, |verdict| {
            prepare_all(channel, text.clone(), verdict)
        });
    let Prepared { moves, alarm, limit_hit } = prepared.unwrap_or_default();
    let wall_time_s = started.elapsed().as_secs_f64();
    let cpu_time_s = cpu_since(cpu_started, check_cpu_s);
    let outcome = if !syntax_errors.is_empty() {
        Outcome::SyntaxError
    } else if alarm.is_some() {
        Outcome::Alarm
    } else if limit_hit {
        Outcome::Limit
    } else {
        Outcome::Ended
    };
    Report {
        outcome,
        program,
        machine: args.machine.clone(),
        state: None,
        moves: Some(moves),
        alarm,
        standstill: None,
        syntax_errors,
        notes,
        program_bytes,
        blocks,
        block_changes: 0,
        program_stops: 0,
        ipo_cycle_s: channel.config().ipo_cycle,
        ipo_cycles: 0,
        simulated_time_s: 0.0,
        wall_time_s,
        load_time_s,
        cpu_time_s,
        blocks_per_s: if wall_time_s > 0.0 { blocks as f64 / wall_time_s } else { 0.0 },
        cycles_per_s: 0.0,
        real_time_factor: 0.0,
        peak_rss_kib: peak_rss_kib(),
        stock_warnings: Vec::new(),
    }
}

/// What `--interpret-only`'s preparation found.
#[derive(Debug, Default)]
struct Prepared {
    moves: u64,
    alarm: Option<dto::AlarmInfo>,
    limit_hit: bool,
}

/// Prepares every block of `text` on a fresh interpreter, counting the moves, until the end,
/// an alarm, the step budget, or the syntax check beside it failing (the result is then
/// discarded).
fn prepare_all(channel: &Channel, text: ProgramText, verdict: &Verdict) -> Prepared {
    let cfg = channel.config();
    let programs: &Programs = channel.program_store();
    let mut position = [0.0; MAX_CHANNEL_AXES];
    position[..channel.axis_positions().len()].copy_from_slice(channel.axis_positions());
    // Loops without end would never finish: stop after 100 preparation steps per block plus a
    // million. Until the thread beside has counted the blocks, the program's bytes (at least
    // one per block) stand in for them.
    let bytes = text.len() as u64;
    let budget = || verdict.blocks().unwrap_or(bytes).saturating_mul(100).saturating_add(1_000_000);
    let mut interp = Interpreter::new(cfg);
    // Programs read the session's machine data and I/O image, as on the channel.
    interp.set_stored_data(std::sync::Arc::new(channel.machine_data().clone()));
    interp.set_io(channel.digital_io());
    interp.begin_program(text, &position);
    let mut out = Vec::new();
    let mut found = Prepared::default();
    let mut steps = 0u64;
    loop {
        out.clear();
        let prep = interp.prepare_next(cfg, programs, true, &mut out);
        drop(interp.take_data_writes());
        // Read in place: moving each item out would copy every move once more.
        for item in &out {
            match item {
                Item::Move { .. } => found.moves += 1,
                Item::Alarm(a) => found.alarm = Some(dto::AlarmInfo::from(a)),
                _ => {}
            }
        }
        steps += 1;
        if prep == Prep::Done || found.alarm.is_some() || steps.is_multiple_of(PREP_CHUNK) && verdict.failed() {
            break;
        }
        if steps >= budget() {
            found.limit_hit = true;
            break;
        }
    }
    found
}

/// Opens the program folder `dir` ([`folder::open`]): every program is read and checked when
/// it is first called, so a broken or undecodable file stops only a run that calls it; skipped
/// files become notes. The main program runs from the directory of the folder holding it.
fn store_programs(channel: &mut Channel, dir: &Path, main: &Path, notes: &mut Vec<Note>) -> Result<(), UsageError> {
    let opened = folder::open(dir).map_err(UsageError)?;
    let main_dir = opened.dir_of(main).flatten();
    let store = channel.program_store_mut();
    for (program, _) in opened.programs {
        store.add(program);
    }
    store.set_main_dir(main_dir);
    notes.extend(opened.notes);
    Ok(())
}

#[derive(Debug, Default)]
struct Run {
    block_changes: u64,
    program_stops: u64,
    limit_hit: bool,
    standstill: Option<Standstill>,
}

/// Steps the channel until the program is over (or stopped at M0 with `--stop-at-m0`, or by
/// the time limit, or the syntax check beside it failed). Events are drained every [`CHUNK`]
/// cycles so memory stays flat.
fn run_to_end(channel: &mut Channel, args: &SimulateArgs, verdict: &Verdict) -> Run {
    let mut run = Run::default();
    let limit_tick = args.max_sim_time.map(|t| channel.ticks() + (t / channel.config().ipo_cycle).ceil() as u64);
    // The last progress mark and the IPO cycle it was first seen at.
    let mut mark = (channel.progress_mark(), channel.ticks());
    let standstill_ticks = (STANDSTILL_S / channel.config().ipo_cycle).ceil() as u64;
    loop {
        while channel.is_busy() {
            if verdict.failed() {
                // The run is discarded: no need to finish it.
                return run;
            }
            let mut steps = CHUNK;
            if let Some(limit) = limit_tick.filter(|_| !run.limit_hit) {
                if channel.ticks() >= limit {
                    // NC stop: the axes brake on the path, as the server's fast-pace limit does.
                    channel.stop();
                    run.limit_hit = true;
                } else {
                    steps = steps.min(limit - channel.ticks());
                }
            }
            for _ in 0..steps {
                channel.step();
                if !channel.is_busy() {
                    break;
                }
            }
            count_events(channel, &mut run);
            if !channel.is_busy() || run.limit_hit {
                continue;
            }
            let now = channel.progress_mark();
            if now != mark.0 {
                mark = (now, channel.ticks());
            } else if channel.ticks() - mark.1 >= standstill_ticks {
                run.standstill = Some(standstill(channel, channel.ticks() - mark.1));
                // NC stop, as the operator would press it; nothing moves, so it stops at once.
                channel.stop();
                return run;
            }
        }
        count_events(channel, &mut run);
        if channel.status() == Status::Stopped && !run.limit_hit && !args.stop_at_m0 {
            // M0/M1: the operator presses NC start.
            run.program_stops += 1;
            if channel.start().is_ok() {
                continue;
            }
        }
        return run;
    }
}

/// What the run reports when the channel stood still for `ticks` IPO cycles.
fn standstill(channel: &Channel, ticks: u64) -> Standstill {
    let line = channel.snapshot().block.map(|b| b.line);
    let stood_s = ticks as f64 * channel.config().ipo_cycle;
    let at = line.map_or_else(|| "before the first block".to_string(), |l| format!("at line {l}"));
    let message = format!(
        "the channel stood still {at} for {stood_s:.0} s of simulated time with nothing left that could change \
         (no axis, spindle, dwell or synchronized action): a thread or feed per revolution with the spindle \
         stopped, or a wait for an input? A real control stands there until the operator acts; the run was \
         ended with NC stop"
    );
    Standstill { line, stood_s, message }
}

fn count_events(channel: &mut Channel, run: &mut Run) {
    for event in channel.take_events() {
        if let Event::BlockChanged(_) = event {
            run.block_changes += 1;
        }
    }
}

/// Peak resident set size of this process in KiB (`VmHWM` of /proc/self/status).
pub fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
}
