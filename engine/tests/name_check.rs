//! The static name check (`nctwin_engine::check`) against programs whose runs are known: the
//! fixture programs of `tests/programs/` (each states the alarms its run gives) and the
//! standard cycle library. The check may flag only what the run refuses: a finding is a false
//! alarm unless the fixture expects that alarm number at that line (or, in a subprogram, at
//! all). The property test feeds it random programs: it must never panic.

use std::path::Path;

use nctwin_engine::Channel;
use nctwin_engine::check::{self, NameContext};
use nctwin_engine::lang::Diagnostic;
use proptest::prelude::*;

/// The main program and the `;;; NAME` subprograms of a fixture, and the context of its
/// machine with the subprograms stored.
fn fixture(text: &str) -> (Vec<(String, String)>, NameContext) {
    let machine = text.lines().find_map(|l| l.trim().strip_prefix("; machine ")).unwrap_or("mill-3axis");
    let md: Vec<&str> = text.lines().filter_map(|l| l.trim().strip_prefix("; md ")).collect();
    let mut ch = Channel::from_preset(machine, &md.join("\n")).expect("preset");
    let mut parts = text.split("\n;;; ");
    let mut programs = vec![(String::new(), parts.next().unwrap_or_default().to_string())];
    for part in parts {
        let (name, body) = part.split_once('\n').unwrap_or((part, ""));
        ch.store_program(name.trim(), body).expect("subprogram");
        programs.push((name.trim().to_string(), body.to_string()));
    }
    (programs, ch.name_context())
}

/// The (alarm, line) pairs a fixture's run expects.
fn expected(text: &str) -> Vec<(u32, Option<u32>)> {
    text.lines()
        .filter_map(|l| {
            let rest = l.trim().strip_prefix("; expect ")?;
            let rest = rest.strip_prefix("alarm ").or_else(|| rest.strip_prefix("rejected "))?;
            let nums: Vec<u32> = rest.split_whitespace().filter_map(|w| w.parse().ok()).collect();
            Some((*nums.first()?, nums.get(1).copied()))
        })
        .collect()
}

fn false_alarms(path: &Path) -> Vec<String> {
    // Fixtures stored as on a Windows PC may hold 8-bit comments (see language.rs).
    let text = String::from_utf8_lossy(&std::fs::read(path).expect("fixture")).into_owned();
    let want = expected(&text);
    let (programs, ctx) = fixture(&text);
    let mut wrong = Vec::new();
    for (name, body) in &programs {
        for d in check::names(body, &ctx) {
            let main = name.is_empty();
            let ok = want.iter().any(|(a, l)| *a == d.alarm && (!main || l.is_none_or(|l| l == d.line)));
            if !ok {
                wrong.push(format!("{} {name}: {} line {}: {}", path.display(), d.alarm, d.line, d.message));
            }
        }
    }
    wrong
}

#[test]
fn no_fixture_program_is_flagged_for_a_name_its_run_accepts() {
    let mut wrong = Vec::new();
    let mut count = 0;
    for folder in ["tests/programs/lang", "tests/programs/shop"] {
        let mut paths: Vec<_> = std::fs::read_dir(folder).expect("folder").map(|e| e.expect("entry").path()).collect();
        paths.sort();
        for path in paths {
            count += 1;
            wrong.extend(false_alarms(&path));
        }
    }
    assert!(count > 150, "the fixtures were found");
    assert!(wrong.is_empty(), "{} false findings:\n{}", wrong.len(), wrong.join("\n"));
}

/// On a machine with X, Y and Z: the cycles write axis words of each plane in branches of
/// their own (CYCLE81 drills along Y under G19), which a lathe without Y never reaches, so
/// the library is checked on the mill.
#[test]
fn no_standard_cycle_is_flagged() {
    let ctx = Channel::from_preset("mill-3axis", "").expect("preset").name_context();
    for cycle in nctwin_engine::programs::cycles::library() {
        let text = cycle.ready().expect("cycle text");
        let found = check::names(text, &ctx);
        assert!(found.is_empty(), "{}: {found:?}", cycle.name());
    }
}

fn mill() -> NameContext {
    Channel::from_preset("mill-3axis", "").expect("preset").name_context()
}

fn found(text: &str) -> Vec<(u32, u32, u32)> {
    check::names(text, &mill()).iter().map(|d: &Diagnostic| (d.alarm, d.line, d.column)).collect()
}

#[test]
fn unknown_words_g_functions_and_programs_are_flagged_at_their_line_and_column() {
    // Each line as the run refuses it when it reaches it:
    // line 2: G1234 is no G function (12470) at column 4;
    // line 3: TRANSS is no keyword and no program (12550) at column 1;
    // line 4: CYCLE811 is not in the cycle library nor the session (12550: a plain name);
    // line 5: L9001 is a subprogram call by number whose program is missing (14011);
    // line 6: QQ was never declared (12550) at column 6, after `G1 X=`;
    // line 7: SINN is no predefined function (12550) at column 4;
    // line 8: GOTOF NOWHERE has no label NOWHERE in the program (14080).
    let text =
        "G17 G90\nN10 G1234 X1\nTRANSS X10\nCYCLE811(1,2)\nL9001\nG1 X=QQ F100\nR1=SINN(30)\nGOTOF NOWHERE\nM30\n";
    assert_eq!(
        found(text),
        vec![(12470, 2, 5), (12550, 3, 1), (12550, 4, 1), (14011, 5, 1), (12550, 6, 6), (12550, 7, 4), (14080, 8, 7)]
    );
}

#[test]
fn a_synchronized_action_is_judged_as_its_block_compiles_it() {
    // Line 2: $AA_IMM is no variable of synchronized actions (12550), found at column 15 of
    // `ID=1 WHENEVER $AA_IMM[X]>10 DO $R[1]=1`; line 3 reads known variables of X and writes
    // an R parameter: nothing to flag.
    let text = "G0 X0\nID=1 WHENEVER $AA_IMM[X]>10 DO $R[1]=1\nID=2 WHENEVER $AA_IM[X]>10 DO $R[1]=$PI\nM30\n";
    assert_eq!(found(text), vec![(12550, 2, 15)]);
}

#[test]
fn declared_names_labels_cycles_and_stored_programs_are_not_flagged() {
    // DEF and PROC parameters, a forward label, the cycle library (CYCLE81), the constants
    // $PI and _FINISH, axis names (X, Z) as values, and frame functions with axis arguments.
    let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
    ch.store_program("PART_A", "G1 X1 F100\nM17").expect("stored");
    let ctx = ch.name_context();
    let text = "DEF REAL DEPTH=5, LST[3]\nDEF AXIS AXA=X\nN10 G0 X0 Y0 Z10\nLST[1]=DEPTH*$PI\nCYCLE81(10,0,2,-DEPTH)\n\
                PART_A\nCALL \"PART_A\"\nCYCLE832(0.01,_FINISH,1)\n$P_PFRAME=CTRANS(X,10,Z,2)\nGOTOF LATER\nGOTOB N10\n\
                LATER:\nM30\n";
    assert_eq!(check::names(text, &ctx), Vec::new());
    // Without the stored program, both calls are flagged: a name (12550) and CALL (14011).
    let alarms: Vec<u32> = check::names(text, &mill()).iter().map(|d| d.alarm).collect();
    assert_eq!(alarms, vec![12550, 14011]);
}

#[test]
fn a_global_variable_declared_by_an_earlier_run_is_known() {
    let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
    assert_eq!(check::names("G1 X=GLOB_LEN F100\n", &ch.name_context()).len(), 1);
    ch.run_program("DEF NCK REAL GLOB_LEN=4\nM30").expect("runs");
    while ch.is_busy() {
        ch.step();
    }
    assert_eq!(check::names("G1 X=GLOB_LEN F100\n", &ch.name_context()), Vec::new());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Random program text, from words of the language and noise: the check never panics and
    /// every finding points into the text.
    #[test]
    fn the_check_never_panics(lines in prop::collection::vec(
        prop::collection::vec(prop_oneof![
            Just("G1".to_string()), Just("G9999".to_string()), Just("X=".to_string()), Just("QQ".to_string()),
            Just("GOTOF".to_string()), Just("LBL:".to_string()), Just("DEF REAL".to_string()), Just("CALL".to_string()),
            Just("\"".to_string()), Just("(".to_string()), Just(")".to_string()), Just("[".to_string()), Just(";".to_string()),
            Just("L12".to_string()), Just("IF".to_string()), Just("$PI".to_string()), Just("SIN(".to_string()),
            Just("ü".to_string()), Just("\r".to_string()), Just("=".to_string()), Just(",".to_string()),
            "[A-Z_$]{1,6}[0-9]{0,3}", "[ -~]{0,8}",
        ], 0..8).prop_map(|w| w.join(" ")), 0..12)) {
        let text = lines.join("\n");
        let ctx = mill();
        for d in check::program(&text, &ctx) {
            prop_assert!(d.line >= 1 && d.line as usize <= text.lines().count().max(1) + 1, "{d:?}");
            prop_assert!(d.offset <= text.len(), "{d:?}");
        }
    }
}

#[test]
fn a_geometry_axis_a_transformation_provides_is_not_flagged() {
    // The TRANSMIT lathe has no Y until TRANSMIT maps it onto C; a face-milling program writes
    // Y in the blocks after TRANSMIT, and the check cannot know which blocks those are: Y is
    // known on a machine with transformation data. The plain 2-axis lathe has none, so a Y
    // there is what its run refuses (12550).
    let text = "G17 T1 D1\nTRANSMIT\nG1 X10 Y5 F100\nTRAFOOF\nM30\n";
    let lathe = |preset: &str| Channel::from_preset(preset, "").expect("preset").name_context();
    assert_eq!(check::names(text, &lathe("transmit-example")), Vec::new());
    let plain: Vec<(u32, u32)> =
        check::names("G1 X10 Y5 F100\nM30\n", &lathe("lathe-2axis")).iter().map(|d| (d.alarm, d.line)).collect();
    assert_eq!(plain, vec![(12550, 1)]);
}
