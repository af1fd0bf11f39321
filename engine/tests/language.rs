//! Fixture programs under `tests/programs/lang/` and `tests/programs/shop/`, each carrying its expected results in
//! `; expect ...` comments worked out by hand:
//!
//! - `; expect R1=5`            R parameter value
//! - `; expect VAR A=1.5`       user variable (`VAR M[5]=7`: flat element index; TRUE/FALSE for BOOL)
//! - `; expect STR S=abc`       string variable
//! - `; expect X=10`            WCS position of an axis at the end
//! - `; expect TIME=1.1`         simulated seconds at the end (within two IPO cycles)
//! - `; expect alarm 14080 line 4`
//! - `; expect rejected 12640 line 3 column 1`  the program is refused before it runs, with
//!   this error among those reported (column optional); nothing moves
//! - `; expect status alarm`    final channel status (idle unless an alarm is expected)
//! - `; expect MSG text`        the last MSG text
//! - `; machine lathe-2axis`    preset (default mill-3axis)
//! - `; md $P_UIFR[1,X,TR]=100` machine data applied on top of the preset
//! - `; simulation`             the run is a simulation like the HMI's preview (`$P_SIM` TRUE)
//! - `; input 3`                digital input 3 (`$A_IN[3]`) is on when the program starts
//! - `; expect OUT 2=1`         digital output 2 (`$A_OUT[2]`) at the end
//! - `; expect AUX M8 H2=1.5 M30` the M and H functions put out, in order, as written
//! - `; expect FILE LOG=A|B`    the stored program or file LOG holds the lines A and B (`|`
//!   between lines, each ending with a line feed; `FILE LOG=` with nothing: no such file)
//!
//! A line `;;; NAME` starts a subprogram stored under NAME; the main program is what comes first.

use std::path::Path;

use nctwin_engine::interp::eval::value::Value;
use nctwin_engine::{Channel, CommandError, Event, Status};

const TOLERANCE: f64 = 1e-9;
const MAX_TICKS: usize = 5_000_000;

fn run_fixture(path: &Path) -> Result<(), String> {
    // Files stored as on a Windows PC may hold comments in an 8-bit code page: they are read
    // as the engine gets them from a reader that does not know the code page.
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let expectations: Vec<&str> = text.lines().filter_map(|l| l.trim().strip_prefix("; expect ")).collect();
    if expectations.is_empty() {
        return Err("no expectations".into());
    }
    let machine = text.lines().find_map(|l| l.trim().strip_prefix("; machine ")).unwrap_or("mill-3axis");
    let md: Vec<&str> = text.lines().filter_map(|l| l.trim().strip_prefix("; md ")).collect();
    let mut ch = Channel::from_preset(machine, &md.join("\n")).map_err(|e| e.to_string())?;
    let inputs: Vec<(usize, bool)> = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("; input ")?.trim().parse().ok())
        .map(|n| (n, true))
        .collect();
    ch.set_signals(&inputs, &[]).map_err(|e| e.to_string())?;
    ch.set_simulation(text.lines().any(|l| l.trim() == "; simulation"));
    let mut parts = text.split("\n;;; ");
    let main = parts.next().unwrap_or_default();
    for part in parts {
        let (name, body) = part.split_once('\n').unwrap_or((part, ""));
        ch.store_program(name.trim(), body).map_err(|e| format!("subprogram {name}: {e}"))?;
    }
    let rejected: Vec<&str> = expectations.iter().filter_map(|e| e.strip_prefix("rejected ")).collect();
    if !rejected.is_empty() {
        let before = ch.snapshot().machine;
        let Err(CommandError::Syntax { errors, .. }) = ch.run_program(main) else {
            return Err("expected the program to be refused".into());
        };
        for want in rejected {
            let nums: Vec<u32> = want.split_whitespace().filter_map(|w| w.parse().ok()).collect();
            let hit = errors.iter().any(|d| {
                d.alarm == nums[0]
                    && nums.get(1).is_none_or(|l| d.line == *l)
                    && nums.get(2).is_none_or(|c| d.column == *c)
            });
            if !hit {
                return Err(format!("expected rejected {want}, got {errors:?}"));
            }
        }
        for _ in 0..100 {
            ch.step();
        }
        if ch.snapshot().machine != before || ch.is_busy() {
            return Err("a refused program moved the machine".into());
        }
        return Ok(());
    }
    ch.run_program(main).map_err(|e| format!("not started: {e}"))?;
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        if ticks > MAX_TICKS {
            return Err("does not end".into());
        }
    }
    let snap = ch.snapshot();
    let aux: Vec<String> = ch
        .take_events()
        .iter()
        .filter_map(|e| match e {
            Event::AuxFunction { function, .. } => Some(function.text()),
            _ => None,
        })
        .collect();
    let mut expected_status = Status::Idle;
    for e in expectations {
        let fail = |got: String| Err(format!("expected {e}, got {got}"));
        if let Some(rest) = e.strip_prefix("alarm ") {
            expected_status = Status::Alarm;
            let mut parts = rest.split_whitespace();
            let number: u32 = parts.next().and_then(|n| n.parse().ok()).ok_or("bad alarm expectation")?;
            let line: Option<u32> =
                (parts.next() == Some("line")).then(|| parts.next().and_then(|n| n.parse().ok())).flatten();
            let hit = snap.alarms.iter().any(|a| a.number == number && (line.is_none() || a.line == line));
            if !hit {
                return fail(format!("{:?}", snap.alarms));
            }
        } else if let Some(want) = e.strip_prefix("AUX ") {
            if aux.join(" ") != want.trim() {
                return fail(aux.join(" "));
            }
        } else if let Some(out) = e.strip_prefix("OUT ") {
            let (n, want) = out.split_once('=').ok_or("bad OUT expectation")?;
            let n: usize = n.trim().parse().map_err(|_| "bad OUT signal")?;
            let got = ch.digital_io().output(n).ok_or("no such output")?;
            if got != (want.trim() == "1") {
                return fail(format!("{}", u8::from(got)));
            }
        } else if let Some(file) = e.strip_prefix("FILE ") {
            let (name, want) = file.split_once('=').ok_or("bad FILE expectation")?;
            let want: Option<String> = (!want.is_empty()).then(|| want.split('|').map(|l| format!("{l}\n")).collect());
            let got = ch.stored_program(name.trim()).map(str::to_string);
            if got != want {
                return fail(format!("{got:?}"));
            }
        } else if let Some(text) = e.strip_prefix("MSG ") {
            if snap.message.as_deref() != Some(text) {
                return fail(format!("{:?}", snap.message));
            }
        } else if let Some(s) = e.strip_prefix("status ") {
            expected_status = match s {
                "idle" => Status::Idle,
                "stopped" => Status::Stopped,
                "alarm" => Status::Alarm,
                other => return Err(format!("unknown status {other}")),
            };
        } else if let Some(rest) = e.strip_prefix("VAR ").or_else(|| e.strip_prefix("STR ")) {
            let (lhs, want) = rest.split_once('=').ok_or("bad VAR expectation")?;
            let (name, index) = match lhs.split_once('[') {
                Some((n, i)) => (n, i.trim_end_matches(']').parse::<usize>().map_err(|e| e.to_string())?),
                None => (lhs, 0),
            };
            let got = ch.variable(name, index).ok_or(format!("variable {name} not found"))?;
            let ok = match (&got, want) {
                (Value::Bool(b), "TRUE") => *b,
                (Value::Bool(b), "FALSE") => !*b,
                (Value::Str(s), w) => s == w,
                (v, w) => w.parse::<f64>().ok().zip(v.as_f64().ok()).is_some_and(|(w, v)| (w - v).abs() <= TOLERANCE),
            };
            if !ok {
                return fail(format!("{got:?}"));
            }
        } else if let Some(want) = e.strip_prefix("TIME=") {
            let want: f64 = want.parse().map_err(|_| format!("bad number in {e}"))?;
            if (snap.time - want).abs() > 0.0081 {
                return fail(snap.time.to_string());
            }
        } else if let Some((lhs, want)) = e.split_once('=') {
            let want: f64 = want.parse().map_err(|_| format!("bad number in {e}"))?;
            let got = match lhs.strip_prefix('R').and_then(|n| n.parse::<usize>().ok()) {
                Some(n) => ch.r_param(n),
                None => snap.workpiece.iter().find(|(n, _)| n == lhs).ok_or(format!("no axis {lhs}"))?.1,
            };
            if (got - want).abs() > TOLERANCE {
                return fail(got.to_string());
            }
        } else {
            return Err(format!("cannot read expectation `{e}`"));
        }
    }
    if snap.status != expected_status {
        return Err(format!("status {:?}, expected {expected_status:?}; alarms {:?}", snap.status, snap.alarms));
    }
    Ok(())
}

#[test]
fn every_language_fixture_gives_its_expected_results() {
    run_folder("tests/programs/lang", 40);
}

/// The shop corpus: programs in the style of CAM posts and shop floors (archive headers,
/// L subprograms, MCALL, section repetition, EXTERN, PCALL/EXTCALL, H and M functions).
#[test]
fn every_shop_program_gives_its_expected_end_state() {
    run_folder("tests/programs/shop", 40);
}

fn run_folder(folder: &str, at_least: usize) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    assert!(files.len() >= at_least, "only {} fixtures", files.len());
    let failures: Vec<String> = files
        .iter()
        .filter_map(|f| run_fixture(f).err().map(|e| format!("{}: {e}", f.file_name().unwrap().to_string_lossy())))
        .collect();
    assert!(failures.is_empty(), "{} of {} fixtures failed:\n{}", failures.len(), files.len(), failures.join("\n"));
}
