//! Hardening: the programs of our own corpus, damaged the way hands and editors damage programs
//! (a word lost, a line doubled, a number made huge or zero, a function of another chapter
//! pasted in, the file cut short), run on any preset. Whatever comes out (an end, an alarm, a
//! program still running when the budget ends), nothing may panic: a panic in the engine ends a
//! server session for every client watching it.
//!
//! Random characters (`robustness.rs`) rarely get past the parser; these mutants do, and reach
//! the cycles, compensation, transformations, synchronized actions and the stock model.
//! `NCTWIN_MUTANTS=n` runs a longer campaign (CI runs 32 cases).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use nctwin_engine::Channel;
use nctwin_engine::machine_data::presets::PRESETS;
use proptest::prelude::*;

/// IPO cycles each mutant may run (40 s of machine time): most corpus programs end or fail
/// within them, and an endless loop a mutation made costs little. Debug builds check every
/// block of the fast lane against the general interpreter (`lane::cross_check`), which makes a
/// cycle of short blocks dear: the budget keeps a case near a second.
const TICK_BUDGET: usize = 10_000;

/// Words pasted into programs: one of each family the engine models, with arguments that are
/// plausible, extreme or wrong.
const PASTED: &[&str] = &[
    "G41 D1",
    "G42",
    "G40",
    "G451",
    "OFFN=3",
    "CDON",
    "TRAORI",
    "TRAFOOF",
    "TRANSMIT",
    "TRACYL(20)",
    "TRAANG",
    "CYCLE800(1,\"\",0,57,0,0,0,30,0,0,0,0,0,1,100,1)",
    "CYCLE81(10,0,2,-5)",
    "MCALL CYCLE81(10,0,2,-5,5)",
    "MCALL",
    "CYCLE83(10,0,2,-30,,-5,,3,0,0,1,0)",
    "POCKET3(10,0,2,-5,40,30,5,20,15,0,2,0,0,500,200,0,21,0,0,0,0,0,0)",
    "CYCLE95(\"KONT\",2,0.2,0.2,0,0.2,0.1,0.1,9,0,0,0)",
    "CYCLE832(0.01,_FINISH,1)",
    "RND=5",
    "CHR=2",
    "G642",
    "G645",
    "COMPCAD",
    "SOFT",
    "FFWOF",
    "G601",
    "G96 S200 LIMS=3000",
    "G95 F0.2",
    "M3 S1000",
    "SPOS=90",
    "G331 Z-20 K1.5 S500",
    "G33 Z-30 K2",
    "T=\"DRILL_8\" M6",
    "T99 M6",
    "D0",
    "DIAMON",
    "STOPRE",
    "ID=1 WHENEVER $AA_IM[X]>5 DO $AC_OVR=0",
    "WHEN $A_IN[1]==1 DO DELDTG",
    "ASPLINE X10 Y5",
    "BSPLINE",
    "POLY PO[X]=(1,2)",
    "TRANS X5",
    "AROT Z30",
    "MIRROR X0",
    "SCALE X2",
    "G2 X10 I5",
    "G3 X0 Y0 CR=0.001",
    "G1 X1e9 F1",
    "G0 X-1e9",
    "F0",
    "ORIWKS",
    "A3=0 B3=0 C3=1",
    "PTP",
    "CP",
    "TCARR=1",
    "TOROT",
    "WORKPIECE(,\"\",,\"BOX\",0,0,-20,-80,-50,-50,100,100)",
    "WORKPIECE(,\"\",,\"CYLINDER\",0,0,-50,-80,40)",
    "REPEAT",
    "GOTOB N10",
    "RET",
    "M17",
    "M30",
    "SETPIECE(1)",
    "M40",
    "G34 Z-10 K2 F0.1",
    // The language grown since (session 16): degenerate and broken on purpose.
    "CIP X20 Y20 I1=10 J1=10",
    "CIP X0 Y0 I1=0 J1=0",
    "CT X5 Y5",
    "ANG=45",
    "X40 Y10 ANG=45",
    "EXECSTRING(\"G1 X\")",
    "EXECSTRING(\"G1 X5 F500)",
    "EXECSTRING(\"EXECSTRING(\")",
    "TOFFR=1EX9",
    "SCC[Q]",
    "G96 S100 SCC[X]",
    "IDS=2 EVERY $AC_TIME>0.1 DO $AC_PARAM[1]=$AC_PARAM[1]/0",
    "ID=3 WHENEVER $AA_IM[Q]>1 DO $AC_MARKER[99999999999]=1",
    "DO $AC_PARAM[1]=BOUND(1,0,SQRT(-1))",
    "POLY PO[X]=(0,0,1EX300)",
    "DRIVE",
    "G643",
];

/// Numbers put in place of a number: zero, huge, tiny, negative, near a full turn.
const NUMBERS: &[&str] = &["0", "-0", "1e9", "-1e9", "1e-9", "99999999", "360.000001", "0.0001", "-5", "1e300"];

#[derive(Debug, Clone)]
enum Mutation {
    /// Remove the n-th whitespace-separated word.
    DropWord(usize),
    /// Replace the n-th number with one of `NUMBERS`.
    Number(usize, usize),
    /// Insert a line from `PASTED` before line n.
    Paste(usize, usize),
    /// Copy line n after itself.
    DoubleLine(usize),
    /// Remove line n.
    DropLine(usize),
    /// Swap lines n and n+1.
    SwapLines(usize),
    /// Cut the text after the n-th character (on a character boundary).
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::DropWord),
        (any::<usize>(), 0..NUMBERS.len()).prop_map(|(n, v)| Mutation::Number(n, v)),
        (any::<usize>(), 0..PASTED.len()).prop_map(|(n, w)| Mutation::Paste(n, w)),
        any::<usize>().prop_map(Mutation::DoubleLine),
        any::<usize>().prop_map(Mutation::DropLine),
        any::<usize>().prop_map(Mutation::SwapLines),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn apply(text: &str, m: &Mutation) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    if lines.is_empty() {
        lines.push(String::new());
    }
    let nl = lines.len();
    match *m {
        Mutation::DropWord(n) => {
            let words: Vec<(usize, usize)> = word_spans(text, |c| !c.is_whitespace());
            if words.is_empty() {
                return text.to_string();
            }
            let (a, b) = words[n % words.len()];
            return format!("{}{}", &text[..a], &text[b..]);
        }
        Mutation::Number(n, v) => {
            let numbers = word_spans(text, |c| c.is_ascii_digit() || c == '.');
            if numbers.is_empty() {
                return text.to_string();
            }
            let (a, b) = numbers[n % numbers.len()];
            return format!("{}{}{}", &text[..a], NUMBERS[v], &text[b..]);
        }
        Mutation::Paste(n, w) => lines.insert(n % (nl + 1), PASTED[w].to_string()),
        Mutation::DoubleLine(n) => {
            let line = lines[n % nl].clone();
            lines.insert(n % nl, line);
        }
        Mutation::DropLine(n) => {
            lines.remove(n % nl);
        }
        Mutation::SwapLines(n) => {
            if nl > 1 {
                let i = n % (nl - 1);
                lines.swap(i, i + 1);
            }
        }
        Mutation::Truncate(n) => {
            let cut = text.char_indices().map(|(i, _)| i).nth(n % text.chars().count().max(1)).unwrap_or(0);
            return text[..cut].to_string();
        }
    }
    lines.join("\n")
}

/// Byte spans of the maximal runs of characters for which `inside` holds.
fn word_spans(text: &str, inside: impl Fn(char) -> bool) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices() {
        match (inside(c), start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                spans.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        spans.push((s, text.len()));
    }
    spans
}

fn corpus() -> &'static [(PathBuf, String)] {
    static CORPUS: OnceLock<Vec<(PathBuf, String)>> = OnceLock::new();
    CORPUS.get_or_init(|| {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/programs");
        let mut files = Vec::new();
        for folder in ["lang", "shop", "k12"] {
            for entry in std::fs::read_dir(root.join(folder)).unwrap() {
                let path = entry.unwrap().path();
                let text = std::fs::read(&path).unwrap();
                files.push((path, String::from_utf8_lossy(&text).into_owned()));
            }
        }
        files.sort();
        assert!(files.len() > 150, "corpus not found: {} files", files.len());
        files
    })
}

/// Runs a (mutated) fixture as `language.rs` would, on `preset` (or the fixture's own machine),
/// until it rests or the budget ends. Errors and alarms are fine; only a panic fails.
fn run_mutant(text: &str, preset: Option<&str>) {
    let machine =
        preset.or_else(|| text.lines().find_map(|l| l.trim().strip_prefix("; machine "))).unwrap_or("mill-3axis");
    let md: Vec<&str> = text.lines().filter_map(|l| l.trim().strip_prefix("; md ")).collect();
    let mut ch = match Channel::from_preset(machine, &md.join("\n")) {
        Ok(ch) => ch,
        Err(_) => match Channel::from_preset(machine, "") {
            Ok(ch) => ch,
            Err(_) => return,
        },
    };
    let mut parts = text.split("\n;;; ");
    let main = parts.next().unwrap_or_default();
    for part in parts {
        let (name, body) = part.split_once('\n').unwrap_or((part, ""));
        let _ = ch.store_program(name.trim(), body);
    }
    let _ = ch.set_signals(&[(1, true)], &[]);
    if ch.run_program(main).is_err() {
        return;
    }
    for tick in 0..TICK_BUDGET {
        if !ch.is_busy() {
            break;
        }
        ch.step();
        if tick % 4096 == 0 {
            let _ = ch.snapshot();
        }
    }
    let _ = ch.snapshot();
    let _ = ch.take_events();
}

fn cases() -> u32 {
    std::env::var("NCTWIN_MUTANTS").ok().and_then(|n| n.parse().ok()).unwrap_or(32)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: None, .. ProptestConfig::default() })]

    #[test]
    fn mutated_corpus_programs_never_panic_the_engine(
        file in any::<prop::sample::Index>(),
        mutations in prop::collection::vec(mutation(), 1..5),
        other_machine in prop::option::weighted(0.25, 0..PRESETS.len()),
    ) {
        let (path, original) = file.get(corpus());
        let text = mutations.iter().fold(original.clone(), |t, m| apply(&t, m));
        let preset = other_machine.map(|i| PRESETS[i].id);
        let outcome = std::panic::catch_unwind(|| run_mutant(&text, preset));
        prop_assert!(
            outcome.is_ok(),
            "{} mutated by {:?} on {:?} panicked; program:\n{}",
            path.display(), mutations, preset, text
        );
    }
}
