//! Program structure as real 840D programs use it: archive headers, subprogram calls of every
//! form, MCALL, program section repetition and the everyday words of shop and CAM programs.
//! Expected values are worked out by hand from the Programming Manual's rules, noted at each test.

use nctwin_engine::{Channel, CommandError, Status};

const MAX_TICKS: usize = 2_000_000;

/// Runs `main` on the 3-axis mill with `subs` stored; returns the channel at rest.
fn run(main: &str, subs: &[(&str, &str)]) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    for (name, text) in subs {
        ch.store_program(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    ch.run_program(main).unwrap_or_else(|e| panic!("not started: {e}"));
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < MAX_TICKS, "program does not end");
    }
    ch
}

/// The channel ended without an alarm.
fn ok(ch: &Channel) {
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert_eq!(s.status, Status::Idle);
}

/// The alarm the channel stopped with: (number, line).
fn alarm(ch: &Channel) -> (u32, Option<u32>) {
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm, "expected an alarm");
    (s.alarms[0].number, s.alarms[0].line)
}

/// WCS position of `axis` at the end.
fn wcs(ch: &Channel, axis: &str) -> f64 {
    ch.snapshot().workpiece.iter().find(|(n, _)| n == axis).unwrap().1
}

// --- 1. Archive headers -------------------------------------------------------------------

#[test]
fn a_main_program_in_archive_form_runs() {
    let ch = run("%_N_PART1_MPF\n;$PATH=/_N_MPF_DIR\nG0 X1\nM30\n", &[]);
    ok(&ch);
    assert_eq!(wcs(&ch, "X"), 1.0);
}

#[test]
fn crlf_line_ends_and_the_punched_tape_header_are_read() {
    let ch = run("%MPF 12\r\n;$PATH=/_N_MPF_DIR\r\nG0 X2\r\nM30\r\n", &[]);
    ok(&ch);
    assert_eq!(wcs(&ch, "X"), 2.0);
}

#[test]
fn a_bad_header_and_a_second_program_are_refused_before_the_run() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    let Err(CommandError::Syntax { errors, .. }) = ch.run_program("%_N_PART1_TXT\nG0 X1\n") else { panic!() };
    assert_eq!((errors[0].alarm, errors[0].line), (12080, 1));
    // A second header after NC blocks starts another program of an archive.
    let Err(CommandError::Syntax { errors, .. }) = ch.run_program("%_N_A_MPF\nG0 X1\nM30\n%_N_B_MPF\nG0 X2\n") else {
        panic!()
    };
    assert_eq!((errors[0].alarm, errors[0].line), (12080, 4));
}

#[test]
fn a_subprogram_may_start_with_comments_blank_lines_and_its_header_before_proc() {
    // Before this, the comment block was taken for the first block of a program without
    // parameters and the call failed with 12340.
    let sub = "; deburring helper\n; (c) shop\n\n%_N_DEBURR_SPF\n;$PATH=/_N_SPF_DIR\nPROC DEBURR(REAL DEPTH) SAVE DISPLOF\nR1=DEPTH*2\nM17\n";
    let ch = run("DEBURR(1.5)\nM30\n", &[("DEBURR", sub)]);
    ok(&ch);
    assert_eq!(ch.r_param(1), 3.0);
}

#[test]
fn an_archive_is_stored_program_by_program_under_its_headers() {
    let archive = "%_N_MAIN_MPF\n;$PATH=/_N_MPF_DIR\nL20\nM30\n%_N_L20_SPF\n;$PATH=/_N_SPF_DIR\nR1=20\nM17\n";
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    assert_eq!(ch.store_archive(archive).unwrap(), vec!["MAIN".to_string(), "L20".to_string()]);
    assert!(ch.stored_program("L20").unwrap().starts_with("%_N_L20_SPF"));
    let main = ch.stored_program("MAIN").unwrap().to_string();
    ch.run_program(&main).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ok(&ch);
    assert_eq!(ch.r_param(1), 20.0);
    // A text without a header, or with a bad one, stores nothing.
    assert!(ch.store_archive("G0 X1\n").is_err());
    assert!(ch.store_archive("%_N_OK_MPF\nM30\n%_N_BAD\n").is_err());
    assert!(ch.stored_program("OK").is_none());
}
