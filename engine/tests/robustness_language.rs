//! Hardening of the language grown since `robustness.rs`: programs made of the newer constructs
//! (CIP with I1=/J1=/K1=, CT, EXECSTRING, TOFFR, SCC[axis], the two-block ANG= contour,
//! synchronized actions with ID=/IDS=, WHEN/WHENEVER/FROM/EVERY, BOUND and technology cycles,
//! splines and POLY, CYCLE832, DRIVE/SOFT/G643), well-formed and malformed (unterminated strings,
//! EXECSTRING running EXECSTRING, recursion, huge indices, NaN/inf arithmetic in actions, ANG with
//! degenerate geometry, collinear or coincident CIP points, actions naming missing axes), on
//! machine data that resize the synchronized actions' memory and the fast I/O (MD28250..28258,
//! MD10300..10360), with inputs set while the program runs.
//!
//! Each case runs in a thread of its own under a watchdog: no panic, no single IPO cycle that
//! does not return, every alarm with a number and (when it belongs to a block) its line.
//! `NCTWIN_LANG_CASES=n` runs a longer campaign (CI runs 48 cases).

use std::sync::mpsc;
use std::time::Duration;

use nctwin_engine::Channel;
use proptest::prelude::*;

/// IPO cycles a case may run (4 s of machine time): enough for the short moves of the generated
/// programs to end or fail, small enough that an endless loop costs little in a debug build.
const TICK_BUDGET: usize = 1_000;

/// Runs of one case: the first, and one more after each alarm with its line emptied.
const ATTEMPTS: usize = 6;

/// Longest a whole case may take in a debug build before it counts as hung (a single step that
/// never returns, or a program that preparation loops on without a cycle passing).
const WATCHDOG: Duration = Duration::from_secs(60);

/// Numbers put where a number stands: plausible, zero, huge, tiny, and expressions that give
/// NaN or infinity on a computer (the control answers them with an alarm).
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "1",
    "5",
    "-5",
    "10",
    "45",
    "90",
    "180",
    "360",
    "0.001",
    "1EX-9",
    "1EX9",
    "-1EX9",
    "1EX300",
    "1e9",
    "99999999",
    "1/0",
    "SQRT(-1)",
    "1EX300*1EX300",
    "LN(0)",
    "ACOS(2)",
    "TAN(90)",
    "-1.7EX308*10",
    "R1",
    "R1/R2",
];

/// Indices of the synchronized actions' data and signals: in range, at the edges, beyond any
/// size, negative, not whole.
const INDICES: &[&str] = &["0", "1", "2", "7", "8", "16", "49", "50", "255", "99999999999", "-1", "1.5", "1e9", "R1"];

/// Synchronized action IDs: the valid 1..255 and beyond.
const IDS: &[&str] = &["1", "2", "3", "255", "0", "256", "-1", "99999", "1.5"];

/// Axis names: the machine's, a rotary one that may be missing, a spindle, and none at all.
const AXES: &[&str] = &["X", "Y", "Z", "A", "C", "Q", "SP1", "S1", "X1", ""];

/// Conditions of synchronized actions.
const CONDITIONS: &[&str] = &[
    "$AA_IM[{a}]>{n}",
    "$AA_IW[{a}]<{n}",
    "$AC_TIME>{n}",
    "$AC_PATH>{n}",
    "$AC_DTEB<{n}",
    "$A_IN[{i}]==1",
    "$A_INA[{i}]>{n}",
    "$AC_MARKER[{i}]>{n}",
    "$AC_PARAM[{i}]<>{n}",
    "$AC_TIMER[{i}]>{n}",
    "TRUE",
    "1/0>1",
    "SQRT($AA_IM[{a}]-{n})>1",
];

/// Actions after DO.
const ACTIONS: &[&str] = &[
    "$AC_MARKER[{i}]={n}",
    "$AC_MARKER[{i}]=$AC_MARKER[{i}]+1",
    "$AC_PARAM[{i}]={n}/$AC_PARAM[{i}]",
    "$AC_PARAM[{i}]=BOUND({n},{n},{n})",
    "$AC_PARAM[{i}]=SQRT({n})",
    "$AC_TIMER[{i}]=0",
    "$A_OUT[{i}]=1",
    "$A_OUTA[{i}]={n}",
    "$R{i}={n}",
    "$AC_OVR={n}",
    "DELDTG",
    "M{n}",
    "POS[{a}]={n} FA[{a}]={n}",
    "SPOS[{a}]={n}",
    "PRESETON({a},{n})",
    "SETM({i})",
    "CLEARM({i})",
    "CANCEL({id})",
    "LOCK({id})",
    "UNLOCK({id})",
    "SUB1",
    "TECH",
    "NOSUCH",
    "$AA_OFF[{a}]={n}",
];

/// One block of the newer language, with `{n}` numbers, `{i}` indices, `{id}` action IDs and
/// `{a}` axes, `{c}` conditions and `{d}` actions still to fill in.
const TEMPLATES: &[&str] = &[
    // Motion around which the rest happens.
    "G1 X={n} Y={n} F={n}",
    "G0 X={n} Y={n} Z={n}",
    "G1 X5 Y5 F1000",
    "G0 X0 Y0",
    "G17",
    "G18",
    "G19",
    // CIP: through a point, also collinear (X20 through X10 on a line), coincident points and
    // an intermediate point on the end point or on the start.
    "CIP X={n} Y={n} I1={n} J1={n}",
    "CIP X={n} Z={n} I1={n} K1={n}",
    "CIP X20 Y20 I1=10 J1=10",
    "CIP X0 Y0 I1=0 J1=0",
    "CIP X10 Y0 I1=10 J1=0",
    "CIP X10 Y10",
    "CIP I1={n}",
    "X={n} Y={n} I1={n} J1={n}",
    // CT: a tangential circle, also from a standstill and to the start point itself.
    "CT X={n} Y={n}",
    "CT X0 Y0",
    "CT",
    // ANG: single-block and two-block contour definitions, degenerate ones too (parallel
    // lines, 90° with a coordinate that cannot be reached, both coordinates given).
    "ANG={n}",
    "G1 X={n} ANG={n} F1000",
    "G1 Y={n} ANG={n}",
    "X={n} Y={n} ANG={n}",
    "ANG=45\nX40 Y10 ANG=45",
    "ANG=90\nX10 Y0 ANG=90",
    "ANG=0\nX{n} Y={n} ANG=0",
    "ANG={n} RND={n}\nX{n} Y={n} ANG={n}",
    "G91 ANG=30\nX10 Y10 ANG=60",
    "ANG=30 X10 Y10",
    // EXECSTRING: words, assignments, calls, nesting, recursion and broken strings.
    "EXECSTRING(\"G1 X={n} F500\")",
    "EXECSTRING(\"G1 X\")",
    "EXECSTRING(\"G1 X5 F500)",
    "EXECSTRING(\"\")",
    "EXECSTRING()",
    "EXECSTRING(R1)",
    "EXECSTRING(STR_A)",
    "EXECSTRING(STR_B)",
    "EXECSTRING(STR_A << STR_B)",
    "EXECSTRING(\"R1=1/0\")",
    "EXECSTRING(\"GOTOB N1\")",
    "EXECSTRING(\"M30\")",
    "EXECSTRING(\"SUB1\")",
    "EXECSTRING(\"TECH\")",
    "EXECSTRING(\"ID={id} WHEN $AA_IM[X]>1 DO $R1=1\")",
    "EXECSTRING(\"ANG=45\")",
    "EXECSTRING(\"CIP X1 Y1 I1=0.5 J1=0.6\")",
    "EXECSTRING(\"DEF REAL Q\")",
    "STR_A=\"EXECSTRING(STR_A)\"",
    "STR_A=\"EXECSTRING(STR_B)\"",
    "STR_B=\"EXECSTRING(STR_A)\"",
    "STR_A=\"G1 X\" << {n} << \" F800\"",
    "STR_B=\"R2=\" << {n}",
    "STR_A=\"SUB1\"",
    "STR_A=\"",
    // Strings broken only at run time (QT holds the quote character, 34).
    "STR_A=\"EXECSTRING(\" << QT << \"G1 X5\"",
    "STR_B=\"G1 X\" << QT",
    "STR_A=\"G1 X=(1+\"",
    "STR_B=\"IF R1>0\"",
    "STR_A=\"ID={id} WHEN\"",
    "STR_A=STR_A << STR_A << \"X\"",
    // Loops without motion: each IPO cycle must still return.
    "LOOP\nEXECSTRING(\"R1=R1+1\")\nENDLOOP",
    "WHILE R1<{n}\nR1=R1+1\nSTR_B=STR_B << \"Y\"\nENDWHILE",
    // TOFFR, SCC.
    "TOFFR={n}",
    "TOFFR=-{n}",
    "T1 D1",
    "G96 S={n} LIMS={n} SCC[{a}] M3",
    "SCC[{a}]",
    "SCC[{a}] G96 S100",
    "G97 S500",
    "SCC[{a}]={n}",
    // Synchronized actions, well-formed and not.
    "ID={id} WHEN {c} DO {d}",
    "IDS={id} WHENEVER {c} DO {d}",
    "ID={id} FROM {c} DO {d}",
    "ID={id} EVERY {c} DO {d}",
    "WHENEVER {c} DO {d} {d}",
    "DO {d}",
    "ID={id} WHEN {c} DO",
    "ID={id} WHEN DO {d}",
    "WHEN {c}",
    "CANCEL({id})",
    "LOCK({id})",
    "UNLOCK({id})",
    "RESET({id})",
    "$AC_MARKER[{i}]={n}",
    "R3=$AC_PARAM[{i}]",
    "R4=$A_INA[{i}]",
    "$A_OUT[{i}]=1",
    "WAITM({i},1)",
    "STOPRE",
    // Counters, runtimes, the clock, program writes to main-run data, PRESETON.
    "$AC_REQUIRED_PARTS={n}",
    "$AC_ACTUAL_PARTS=$AC_ACTUAL_PARTS+{n}",
    "$AC_SPECIAL_PARTS={n} $AC_TOTAL_PARTS={n}",
    "$AC_CYCLE_TIME={n}",
    "R5=$AC_CYCLE_TIME+$AC_CUTTING_TIME+$AC_OPERATING_TIME",
    "R6=$A_YEAR*$A_MSECOND+$AN_POWERON_TIME",
    "$AC_PARAM[{i}]={n} $AC_TIMER[{i}]={n}",
    "R7=$P_AD[{i}]",
    "PRESETON({a},{n})",
    "PRESETON({a})",
    "PRESETON({a},{n},{a},{n})",
    "IF R1<{n} GOTOS",
    "CORROF({a},\"DRF\")",
    "WAITS",
    // Splines and POLY.
    "ASPLINE X={n} Y={n}",
    "BSPLINE X={n} Y={n} SD={n}",
    "CSPLINE X={n} Y={n}",
    "BAUTO EAUTO",
    "BNAT ENAT",
    "PL={n}",
    "POLY PO[X]=({n},{n}) PO[Y]=({n}) PL={n}",
    "POLY PO[{a}]=({n},{n},{n})",
    "POLY X={n}",
    // Path control and dynamics.
    "CYCLE832({n},_ROUGH,1)",
    "CYCLE832({n},{n},{n})",
    "CYCLE832()",
    "CYCLE832",
    "DRIVE",
    "SOFT",
    "BRISK",
    "G643",
    "G642",
    "G641 ADIS={n}",
    "G64",
    "G60",
    "RND={n}",
    "CHR={n}",
    "FFWON",
    // Calls: a subprogram and a technology cycle that call themselves or each other.
    "SUB1",
    "TECH",
    "M17",
    "M30",
];

/// Machine data that resize the synchronized actions' memory and the fast I/O.
const MACHINE_DATA: &[&str] = &[
    "",
    "$MC_MM_NUM_SYNC_ELEMENTS={n}",
    "$MC_MM_NUM_AC_PARAM={n}",
    "$MC_MM_NUM_AC_MARKER={n}",
    "$MC_MM_NUM_AC_TIMER={n}",
    "$MC_PART_COUNTER={n}",
    "$MC_PART_COUNTER_MCODE[1]={n}",
    "$MC_PROCESSTIMER_MODE={n}",
    "$MN_FASTIO_ANA_NUM_INPUTS={n}",
    "$MN_FASTIO_ANA_NUM_OUTPUTS={n}",
    "$MN_FASTIO_DIG_NUM_INPUTS={n}",
    "$MN_FASTIO_DIG_NUM_OUTPUTS={n}",
];

/// Presets the cases run on: a mill, lathes (SCC, G18, two spindles), 5-axis table and head.
const MACHINES: &[&str] = &["mill-3axis", "lathe-2axis", "mill5-table-ac", "lathe-counter-spindle", "mill5-head-ca"];

/// Choices that fill one template: an index into each table, drawn per placeholder in turn.
type Fill = Vec<(u8, u8, u8)>;

/// Fills the placeholders of `template` from `fill`, cycling through it (nested `{c}`/`{d}`
/// templates take their own placeholders from the same supply).
fn fill(template: &str, supply: &Fill, next: &mut usize) -> String {
    let mut out = String::new();
    let mut rest = template;
    while let Some(start) = rest.find('{') {
        out.push_str(&rest[..start]);
        let end = start + rest[start..].find('}').expect("template placeholder closed");
        let (a, b, _) = supply[*next % supply.len()];
        let (a, b) = (a as usize, b as usize);
        *next += 1;
        let text = match &rest[start + 1..end] {
            "n" => NUMBERS[a % NUMBERS.len()].to_string(),
            "i" => INDICES[a % INDICES.len()].to_string(),
            "id" => IDS[a % IDS.len()].to_string(),
            "a" => AXES[a % AXES.len()].to_string(),
            "c" => fill(CONDITIONS[b % CONDITIONS.len()], supply, next),
            "d" => fill(ACTIONS[b % ACTIONS.len()], supply, next),
            other => panic!("unknown placeholder {other}"),
        };
        out.push_str(&text);
        rest = &rest[end + 1..];
    }
    out.push_str(rest);
    out
}

/// One generated program line (or two, for the ANG pairs), with a block number now and then.
fn line() -> impl Strategy<Value = String> {
    (0..TEMPLATES.len(), prop::collection::vec(any::<(u8, u8, u8)>(), 1..8), prop::option::weighted(0.2, 1u32..99))
        .prop_map(|(t, supply, number)| {
            let mut next = 0;
            let text = fill(TEMPLATES[t], &supply, &mut next);
            match number {
                Some(n) => format!("N{n} {text}"),
                None => text,
            }
        })
}

/// A program: string variables for EXECSTRING, then generated lines, often ending in M30.
fn program() -> impl Strategy<Value = String> {
    (prop::collection::vec(line(), 1..14), any::<bool>()).prop_map(|(lines, end)| {
        let mut text =
            String::from("DEF STRING[60] STR_A\nDEF STRING[60] STR_B\nDEF CHAR QT=34\nN1 G17 G90 G1 F1000\n");
        text.push_str(&lines.join("\n"));
        if end {
            text.push_str("\nM30");
        }
        text
    })
}

/// Inputs a client sets while the program runs: digital and analog, in range or not, finite or
/// not (the refused ones must be refused whole, not crash).
#[derive(Debug, Clone)]
enum Signal {
    Digital(usize, bool),
    Analog(usize, f64),
}

fn signal() -> impl Strategy<Value = (usize, Signal)> {
    let value = prop::sample::select(vec![0.0, 1.0, -5.0, 10.0, 1e300, f64::NAN, f64::INFINITY]);
    (
        0usize..600,
        prop_oneof![
            (0usize..50, any::<bool>()).prop_map(|(n, v)| Signal::Digital(n, v)),
            (0usize..12, value).prop_map(|(n, v)| Signal::Analog(n, v)),
        ],
    )
}

/// What one case is made of.
#[derive(Debug, Clone)]
struct Case {
    machine: &'static str,
    machine_data: String,
    main: String,
    sub1: String,
    tech: String,
    signals: Vec<(usize, Signal)>,
}

fn case() -> impl Strategy<Value = Case> {
    (
        prop::sample::select(MACHINES),
        (0..MACHINE_DATA.len(), any::<(u8, u8, u8)>()),
        program(),
        prop::collection::vec(line(), 0..4),
        prop::collection::vec(line(), 0..3),
        prop::collection::vec(signal(), 0..4),
    )
        .prop_map(|(machine, (md, supply), main, sub1, tech, signals)| {
            let mut next = 0;
            Case {
                machine,
                machine_data: fill(MACHINE_DATA[md], &vec![supply], &mut next),
                main,
                sub1: format!("PROC SUB1\n{}\nM17", sub1.join("\n")),
                tech: format!("PROC TECH\n{}\nM17", tech.join("\n")),
                signals,
            }
        })
}

/// What a case left behind that the checks look at.
struct Outcome {
    alarms: Vec<(u32, String, Option<u32>)>,
    positions_finite: bool,
}

/// Runs a case to its end, an alarm or the budget; after an alarm at a line of the main program
/// that line is emptied and the program run again from a reset (up to [`ATTEMPTS`] runs), so
/// that one bad block does not keep the rest of the program from the engine. Every run's alarms
/// are kept.
fn run(case: &Case) -> Option<Outcome> {
    let mut ch = Channel::from_preset(case.machine, &case.machine_data)
        .or_else(|_| Channel::from_preset(case.machine, ""))
        .ok()?;
    let _ = ch.store_program("SUB1", &without_syntax_errors(&case.sub1));
    let _ = ch.store_program("TECH", &without_syntax_errors(&case.tech));
    let main = without_syntax_errors(&case.main);
    let mut lines: Vec<&str> = main.lines().collect();
    let mut outcome = Outcome { alarms: Vec::new(), positions_finite: true };
    let verbose = std::env::var_os("NCTWIN_LANG_VERBOSE").is_some();
    for _ in 0..ATTEMPTS {
        ch.reset();
        if let Err(e) = ch.run_program(&lines.join("\n")) {
            if verbose {
                eprintln!("refused: {e}");
            }
            break;
        }
        let mut signals = case.signals.clone();
        signals.sort_by_key(|(tick, _)| *tick);
        let mut signals = signals.into_iter().peekable();
        for tick in 0..TICK_BUDGET {
            while let Some((_, s)) = signals.next_if(|(at, _)| *at <= tick) {
                let _ = match s {
                    Signal::Digital(n, v) => ch.set_signals(&[(n, v)], &[(n, !v)]),
                    Signal::Analog(n, v) => ch.set_analog_inputs(&[(n, v)]),
                };
            }
            if !ch.is_busy() {
                break;
            }
            ch.step();
            if tick % 1024 == 0 {
                let _ = ch.snapshot();
            }
        }
        let _ = ch.snapshot();
        let _ = ch.take_events();
        if verbose {
            let alarms: Vec<_> = ch.alarms().iter().map(|a| (a.number, a.line, a.message.clone())).collect();
            eprintln!("{} cycles, busy {}, alarms {alarms:?}", ch.ticks(), ch.is_busy());
        }
        outcome.alarms.extend(ch.alarms().iter().map(|a| (a.number, a.message.clone(), a.line)));
        outcome.positions_finite &= ch.axis_positions().iter().all(|p| p.is_finite());
        let at = ch.alarms().first().and_then(|a| a.line).map(|l| l as usize);
        match at.and_then(|l| lines.get_mut(l.wrapping_sub(1))) {
            Some(line) if !line.is_empty() => *line = "",
            _ => break,
        }
    }
    Some(outcome)
}

/// `text` with the lines the check refuses before a run emptied (so the line numbers stay),
/// so that a malformed line does not keep the rest of the program from the engine. The
/// malformed lines themselves are what `robustness.rs` and the check tests look at.
fn without_syntax_errors(text: &str) -> String {
    let mut lines: Vec<&str> = text.lines().collect();
    for _ in 0..8 {
        let joined = lines.join("\n");
        let errors = nctwin_engine::lang::check(&joined);
        if errors.is_empty() {
            return joined;
        }
        for e in errors {
            if let Some(line) = lines.get_mut(e.line as usize - 1) {
                *line = "";
            }
        }
    }
    lines.join("\n")
}

/// Runs `case` on a thread of its own under [`WATCHDOG`]: `Err` names a panic or a hang.
fn run_watched(case: &Case) -> Result<Option<Outcome>, String> {
    let (tx, rx) = mpsc::channel();
    let owned = case.clone();
    std::thread::Builder::new()
        // The server runs a session's engine on tokio's blocking threads: 2 MiB of stack.
        .stack_size(2 << 20)
        .spawn(move || {
            let _ = tx.send(run(&owned));
        })
        .expect("thread");
    match rx.recv_timeout(WATCHDOG) {
        Ok(outcome) => Ok(outcome),
        Err(mpsc::RecvTimeoutError::Disconnected) => Err("panicked".into()),
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("did not finish within {WATCHDOG:?}")),
    }
}

/// Alarms that are about the machine rather than a block (limits reached by motion in the main
/// run, the drive, the axis): the control shows them without a block number.
fn block_free(number: u32) -> bool {
    matches!(number, 20000..=29999)
}

fn cases() -> u32 {
    std::env::var("NCTWIN_LANG_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(48)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: None, .. ProptestConfig::default() })]

    #[test]
    fn programs_of_the_newer_language_never_panic_or_hang_the_engine(case in case()) {
        let outcome = run_watched(&case);
        let outcome = match outcome {
            Ok(outcome) => outcome,
            Err(why) => return Err(TestCaseError::fail(format!("{why}: {case:#?}\nmain:\n{}", case.main))),
        };
        let Some(outcome) = outcome else { return Ok(()) };
        prop_assert!(outcome.positions_finite, "{case:#?}");
        for (number, message, line) in &outcome.alarms {
            prop_assert!(*number > 0 && !message.is_empty(), "alarm without number or text: {number} {message:?}\n{}", case.main);
            prop_assert!(
                line.is_some() || block_free(*number),
                "alarm {number} ({message}) has no line\nmain:\n{}\nSUB1:\n{}\nTECH:\n{}",
                case.main, case.sub1, case.tech
            );
        }
    }
}

/// Replays one program from the file `NCTWIN_LANG_REPLAY` names (on `NCTWIN_LANG_MACHINE`, or
/// the 3-axis mill) with the alarms printed: for looking at a case the campaign reported.
#[test]
#[ignore = "a tool: NCTWIN_LANG_REPLAY=file cargo test -p nctwin-engine --test integration robustness_language -- --ignored --nocapture"]
fn replay() {
    let Some(path) = std::env::var_os("NCTWIN_LANG_REPLAY") else { return };
    let main = std::fs::read_to_string(path).expect("program file");
    let machine = std::env::var("NCTWIN_LANG_MACHINE").unwrap_or_else(|_| "mill-3axis".into());
    let case = Case {
        machine: MACHINES.iter().find(|m| **m == machine).copied().unwrap_or("mill-3axis"),
        machine_data: String::new(),
        main,
        sub1: "PROC SUB1\nM17".into(),
        tech: "PROC TECH\nM17".into(),
        signals: Vec::new(),
    };
    let outcome = run_watched(&case).expect("no panic, no hang");
    for (number, message, line) in outcome.map(|o| o.alarms).unwrap_or_default() {
        eprintln!("{number} line {line:?}: {message}");
    }
}
