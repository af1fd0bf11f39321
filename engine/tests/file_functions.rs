//! The file functions of the Programming Manual Job Planning on the session's program store:
//! WRITE, READ, DELETE, ISFILE, FILEDATE, FILETIME, FILESIZE, FILESTAT, FILEINFO, and SPRINT
//! to make the lines. Expected texts and error codes are worked out at each test from the
//! manual's rules: WRITE appends the line and a line feed, creating the file; the error codes
//! 0 no error, 1 path not permitted, 2 path not found, 3 file not found, 4 wrong file type,
//! 10 file full (MD11420 $MN_LEN_PROTOCOL_FILE, 1 KB by default), 11 file in use, and for READ
//! 21 no such line, 22 result array too short, 23 line range past the end.

use crate::settle;

use nctwin_engine::Channel;
use nctwin_engine::interp::eval::value::Value;

fn channel() -> Channel {
    Channel::from_preset("mill-3axis", "").unwrap()
}

use settle::{assert_ok as ok, finish as run_on};

fn int(ch: &Channel, name: &str, i: usize) -> i64 {
    match ch.variable(name, i) {
        Some(Value::Int(v)) => v,
        other => panic!("{name}[{i}] = {other:?}"),
    }
}

fn text(ch: &Channel, name: &str, i: usize) -> String {
    match ch.variable(name, i) {
        Some(Value::Str(v)) => v,
        other => panic!("{name}[{i}] = {other:?}"),
    }
}

#[test]
fn write_appends_lines_with_a_line_feed_and_creates_the_file() {
    let mut ch = channel();
    run_on(
        &mut ch,
        "DEF INT ERR1, ERR2, ERR3\nWRITE(ERR1, \"LOG\", \"FIRST\")\nWRITE(ERR2, \"/_N_MPF_DIR/_N_LOG_MPF\", \"SECOND\")\n\
         R1=4.5\nWRITE(ERR3, \"log.mpf\", SPRINT(\"R1=%.2F N=%D\", R1, 7))\nM30",
    );
    ok(&ch);
    assert_eq!([int(&ch, "ERR1", 0), int(&ch, "ERR2", 0), int(&ch, "ERR3", 0)], [0, 0, 0]);
    // The three names are one file: _N_LOG_MPF in the part-program store.
    assert_eq!(ch.stored_program("LOG"), Some("FIRST\nSECOND\nR1=4.50 N=7\n"));
    assert!(ch.stored_programs().iter().any(|(n, size)| n == "LOG" && *size == 25));
}

#[test]
fn write_refuses_paths_types_and_names_with_the_manuals_codes() {
    let mut ch = channel();
    run_on(
        &mut ch,
        "DEF INT ERR[5]\nWRITE(ERR[0], \"/_N_DEF_DIR/_N_X_MPF\", \"A\")\nWRITE(ERR[1], \"/TMP/_N_X_MPF\", \"A\")\n\
         WRITE(ERR[2], \"_N_X_DEF\", \"A\")\nWRITE(ERR[3], \"NUL\", \"A\")\nWRITE(ERR[4], \"_N_X_SPF\", \"A\")\nM30",
    );
    ok(&ch);
    // 1 a control directory without part programs, 2 no such directory, 4 a definition file,
    // 1 a name the control does not allow (a Windows device name); a subprogram is a file WRITE may write.
    let codes: Vec<i64> = (0..5).map(|i| int(&ch, "ERR", i)).collect();
    assert_eq!(codes, [1, 2, 4, 1, 0]);
    assert_eq!(ch.stored_program("X"), Some("A\n"));
}

#[test]
fn a_file_larger_than_md11420_is_full() {
    // MD11420 = 1 KB = 1024 bytes. Each line is 40 characters and a line feed, 41 bytes: 24
    // lines are 984 bytes, a 25th would make 1025 > 1024, so WRITE answers 10 and writes nothing.
    let mut ch = channel();
    run_on(
        &mut ch,
        "DEF INT ERR, NUM, FULL\nFOR NUM=1 TO 30\nWRITE(ERR, \"BIG\", \"0123456789012345678901234567890123456789\")\n\
         IF ERR==10 GOTOF DONE\nENDFOR\nDONE:\nFULL=NUM\nM30",
    );
    ok(&ch);
    assert_eq!(int(&ch, "FULL", 0), 25);
    assert_eq!(ch.stored_program("BIG").map(str::len), Some(984));

    // With MD11420 = 2 the same file takes 49 lines (2009 bytes; a 50th would be 2050 > 2048).
    let mut ch = Channel::from_preset("mill-3axis", "$MN_LEN_PROTOCOL_FILE=2\n").unwrap();
    run_on(
        &mut ch,
        "DEF INT ERR, NUM, FULL\nFOR NUM=1 TO 60\nWRITE(ERR, \"BIG\", \"0123456789012345678901234567890123456789\")\n\
         IF ERR==10 GOTOF DONE\nENDFOR\nDONE:\nFULL=NUM\nM30",
    );
    ok(&ch);
    assert_eq!(int(&ch, "FULL", 0), 50);
}

#[test]
fn read_takes_lines_from_a_first_line_or_the_end() {
    let mut ch = channel();
    ch.store_program("DATA", "; HEADER\nL2\r\nL3\nL4\n").unwrap();
    run_on(
        &mut ch,
        "DEF INT ERR1, ERR2\nDEF STRING[10] LA[3], LB[2]\nREAD(ERR1, \"DATA\", 2, 3, LA)\nREAD(ERR2, \"DATA\", 0, 2, LB)\nM30",
    );
    ok(&ch);
    assert_eq!((int(&ch, "ERR1", 0), int(&ch, "ERR2", 0)), (0, 0));
    // Lines 2..4 (the CR of a CRLF line is no part of it); with 0 the last two.
    assert_eq!([text(&ch, "LA", 0), text(&ch, "LA", 1), text(&ch, "LA", 2)], ["L2", "L3", "L4"]);
    assert_eq!([text(&ch, "LB", 0), text(&ch, "LB", 1)], ["L3", "L4"]);
}

#[test]
fn read_errors_name_the_missing_file_line_and_array() {
    let mut ch = channel();
    ch.store_program("DATA", "L1\nL2\nL3\n").unwrap();
    run_on(
        &mut ch,
        "DEF INT ERR[5]\nDEF STRING[2] TXT[2]\nREAD(ERR[0], \"NONE\", 1, 1, TXT)\nREAD(ERR[1], \"DATA\", 4, 1, TXT)\n\
         READ(ERR[2], \"DATA\", 1, 3, TXT)\nREAD(ERR[3], \"DATA\", 3, 2, TXT)\nREAD(ERR[4], \"/_N_SPF_DIR/DATA\", 1, 1, TXT)\nM30",
    );
    ok(&ch);
    // 3 no such file; 21 line 4 of 3; 22 three lines for two elements; 23 lines 3..4 of 3;
    // the flat session store answers a path's directory with its program of that name.
    let codes: Vec<i64> = (0..5).map(|i| int(&ch, "ERR", i)).collect();
    assert_eq!(codes, [3, 21, 22, 23, 0]);
    assert_eq!(text(&ch, "TXT", 0), "L1");
}

#[test]
fn a_line_longer_than_the_array_strings_is_cut() {
    let mut ch = channel();
    ch.store_program("DATA", "ABCDEFGH\n").unwrap();
    run_on(&mut ch, "DEF INT ERR\nDEF STRING[4] TXT[1]\nREAD(ERR, \"DATA\", 1, 1, TXT)\nM30");
    ok(&ch);
    assert_eq!(text(&ch, "TXT", 0), "ABCD");
}

#[test]
fn delete_and_isfile() {
    let mut ch = channel();
    ch.store_program("OLD", "M17").unwrap();
    run_on(
        &mut ch,
        "DEF INT ERR1, ERR2\nDEF BOOL OK1, OK2\nOK1=ISFILE(\"/_N_MPF_DIR/_N_OLD_MPF\")\nDELETE(ERR1, \"OLD\")\n\
         OK2=ISFILE(\"OLD\")\nDELETE(ERR2, \"OLD\")\nM30",
    );
    ok(&ch);
    assert_eq!(ch.variable("OK1", 0), Some(Value::Bool(true)));
    assert_eq!(ch.variable("OK2", 0), Some(Value::Bool(false)));
    // Deleted, then not there: 0, then 3.
    assert_eq!((int(&ch, "ERR1", 0), int(&ch, "ERR2", 0)), (0, 3));
    assert_eq!(ch.stored_program("OLD"), None);
    assert!(ch.stored_programs().iter().all(|(n, _)| n != "OLD"));
}

#[test]
fn a_running_subprogram_is_in_use() {
    let mut ch = channel();
    ch.store_program(
        "SUB",
        "DEF INT ERR1, ERR2\nDELETE(ERR1, \"SUB\")\nWRITE(ERR2, \"SUB.SPF\", \"X\")\nR1=ERR1\nR2=ERR2\nM17",
    )
    .unwrap();
    run_on(&mut ch, "SUB\nM30");
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (11.0, 11.0));
    assert_eq!(ch.stored_program("SUB").map(|t| t.ends_with("M17")), Some(true));
}

#[test]
fn file_information_in_the_manuals_formats() {
    // The file is written after a dwell of 3725 s (G4 F3725 waits 3725 s; a file procedure
    // waits for the main run like a block after STOPRE): session time 1 h 2 min 5 s after
    // 01.01.2000 00:00:00.
    let mut ch = channel();
    run_on(
        &mut ch,
        "DEF INT ERR[6], SIZE\nDEF STRING[8] DAT, TIM\nDEF STRING[5] ST\nDEF STRING[32] INFO\n\
         G4 F3725\nSTOPRE\nWRITE(ERR[0], \"LOG\", \"ABC\")\nFILESIZE(ERR[1], \"LOG\", SIZE)\nFILEDATE(ERR[2], \"LOG\", DAT)\n\
         FILETIME(ERR[3], \"LOG\", TIM)\nFILESTAT(ERR[4], \"LOG\", ST)\nFILEINFO(ERR[5], \"LOG\", INFO)\nM30",
    );
    ok(&ch);
    assert_eq!((0..6).map(|i| int(&ch, "ERR", i)).collect::<Vec<_>>(), [0; 6]);
    // "ABC" and the line feed: 4 bytes; every right in the session's store.
    assert_eq!(int(&ch, "SIZE", 0), 4);
    assert_eq!(text(&ch, "DAT", 0), "01.01.00");
    assert_eq!(text(&ch, "TIM", 0), "01:02.05");
    assert_eq!(text(&ch, "ST", 0), "rwxsd");
    assert_eq!(text(&ch, "INFO", 0), "rwxsd 4 01.01.00 01:02.05");

    let mut ch = channel();
    run_on(&mut ch, "DEF INT ERR\nDEF STRING[8] DAT\nFILEDATE(ERR, \"NONE\", DAT)\nM30");
    ok(&ch);
    assert_eq!(int(&ch, "ERR", 0), 3);
}

#[test]
fn the_shell_learns_each_changed_file_once() {
    let mut ch = channel();
    ch.store_program("GONE", "M17").unwrap();
    run_on(
        &mut ch,
        "DEF INT ERR, NUM\nFOR NUM=1 TO 5\nWRITE(ERR, \"LOG\", \"LINE \"<<NUM)\nENDFOR\nDELETE(ERR, \"GONE\")\nM30",
    );
    ok(&ch);
    let changes = ch.take_program_changes();
    assert_eq!(
        changes,
        [("GONE".to_string(), None), ("LOG".to_string(), Some("LINE 1\nLINE 2\nLINE 3\nLINE 4\nLINE 5\n".to_string()))]
    );
    assert!(ch.take_program_changes().is_empty());
}

#[test]
fn a_log_of_ten_thousand_lines_is_written_in_one_copy() {
    // 10,000 lines of "LINE n" (n = 1..10000): 9 + 90 + 900 + 9000 + 1 digits = 38,894 digits,
    // plus 10,000 x ("LINE " + LF) = 60,000: 98,894 bytes, under MD11420 = 100 KB.
    let mut ch = Channel::from_preset("mill-3axis", "$MN_LEN_PROTOCOL_FILE=100\n").unwrap();
    let started = std::time::Instant::now();
    run_on(&mut ch, "DEF INT ERR, NUM\nFOR NUM=1 TO 10000\nWRITE(ERR, \"LOG\", \"LINE \"<<NUM)\nENDFOR\nM30");
    let took = started.elapsed();
    ok(&ch);
    let log = ch.stored_program("LOG").expect("written");
    assert_eq!(log.len(), 98_894);
    assert!(log.ends_with("LINE 9999\nLINE 10000\n"));
    eprintln!("10,000 WRITE lines: {took:?} (debug build)");
}

#[test]
fn the_stores_quota_is_no_free_resources() {
    // Quota 20 bytes; "M17" (3) is stored: "0123456789" and its line feed make 14, then a second
    // line would make 25 > 20: error 12, nothing written.
    let mut ch = channel();
    ch.store_program("SUB", "M17").unwrap();
    ch.set_program_budget(Some(20));
    run_on(
        &mut ch,
        "DEF INT ERR1, ERR2\nWRITE(ERR1, \"LOG\", \"0123456789\")\nWRITE(ERR2, \"LOG\", \"0123456789\")\nM30",
    );
    ok(&ch);
    assert_eq!((int(&ch, "ERR1", 0), int(&ch, "ERR2", 0)), (0, 12));
    assert_eq!(ch.stored_program("LOG"), Some("0123456789\n"));
}

#[test]
fn string_conversions_in_programs() {
    let mut ch = channel();
    run_on(
        &mut ch,
        "DEF STRING[16] TXT\nR1=TOINT(2.5)\nR2=TOREAL(\"1.25\")*2\nTXT=SPRINT(\"%S-%03D\", \"T\", 7)\nR3=STRLEN(TXT)\n\
         R4=ISNUMBER(\"12.5\")\nR5=NUMBER(\"3.5\")+1\nR6=INDEX(TXT, \"-\")\nTXT=TOUPPER(SUBSTR(\"abcdef\", 1, 3))\nM30",
    );
    ok(&ch);
    // TOINT rounds half away from zero; "%03D" pads 7 to width 3 with zeros, so TXT = "T-007", 5
    // long with "-" at index 1; SUBSTR from index 1, 3 characters.
    assert_eq!(
        [ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4), ch.r_param(5), ch.r_param(6)],
        [3.0, 2.5, 5.0, 1.0, 4.5, 1.0]
    );
    assert_eq!(text(&ch, "TXT", 0), "BCD");
    run_on(&mut ch, "DEF STRING[16] TXT\nTXT=SPRINT(\"%S-%03D\", \"T\", 7)\nM30");
    assert_eq!(text(&ch, "TXT", 0), "T-007");
}

// --- Data files -------------------------------------------------------------------------------

/// A tool-data file in inch: 1 in = 25.4 mm exactly.
const TOA_INCH: &str = "%_N_TOA_INI\r\n;$PATH=/_N_WKS_DIR/_N_SHAFT_WPD\r\nCHANDATA(1)\r\nINCH\r\n\
                        $TC_TP2[1]=\"DRILL_HALF\"\r\n$TC_DP1[1,1]=200\r\n$TC_DP3[1,1]=4\r\n$TC_DP6[1,1]=0.25\r\n\
                        METRIC\r\n$TC_DP1[2,1]=120\r\n$TC_DP3[2,1]=100\r\nM17\r\n";

#[test]
fn an_inch_tool_data_file_run_as_a_program_loads_its_lengths_in_mm() {
    // Selected and started like a program, the _INI file loads its data: tool 1's length 4 in
    // = 101.6 mm and radius 0.25 in = 6.35 mm; tool 2 after METRIC 100 mm.
    let mut ch = channel();
    run_on(&mut ch, TOA_INCH);
    ok(&ch);
    run_on(&mut ch, "R1=$TC_DP3[1,1]\nR2=$TC_DP6[1,1]\nR3=$TC_DP3[2,1]\nR4=$TC_DP1[1,1]\nM30");
    ok(&ch);
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4)], [4.0 * 25.4, 0.25 * 25.4, 100.0, 200.0]);
    assert_eq!(ch.r_param(1), 101.6);

    // With T1 D1 active the tool length 101.6 mm lifts the tool tip: G0 Z0 puts the flange
    // (machine Z) at 101.6.
    run_on(&mut ch, "T1 M6\nD1\nG0 G90 X0 Y0 Z0\nM30");
    ok(&ch);
    let s = ch.snapshot();
    let z = s.machine.iter().find(|(n, _)| n == "Z").map(|(_, v)| *v);
    assert!(z.is_some_and(|z| (z - 101.6).abs() < 1e-9), "{:?}", s.machine);
}

#[test]
fn a_program_stored_by_the_shell_while_a_file_is_pending_wins() {
    // WRITE while the program runs (a dwell of 1 s follows): the listing shows the line at
    // once; the shell then stores LOG itself: its text stands, the run's change is dropped.
    let mut ch = channel();
    ch.run_program("DEF INT ERR\nWRITE(ERR, \"LOG\", \"A\")\nG4 F1\nM30").unwrap();
    let mut ticks = 0;
    while ch.stored_program("LOG").is_none() {
        ch.step();
        ticks += 1;
        assert!(ticks < 1000, "WRITE not done");
    }
    assert!(ch.is_busy());
    assert_eq!(ch.stored_program("LOG"), Some("A\n"));
    ch.store_program("LOG", "M17").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ok(&ch);
    assert_eq!(ch.stored_program("LOG"), Some("M17"));
    assert!(ch.take_program_changes().is_empty());
}
