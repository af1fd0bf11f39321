//! Program structure as real 840D programs use it: archive headers, subprogram calls of every
//! form, MCALL, program section repetition and the everyday words of shop and CAM programs.
//! Expected values are worked out by hand from the Programming Manual's rules, noted at each test.

use crate::settle;

use nctwin_engine::{Channel, CommandError, Status};

/// Runs `main` on the 3-axis mill with `subs` stored; returns the channel at rest.
fn run(main: &str, subs: &[(&str, &str)]) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    for (name, text) in subs {
        ch.store_program(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    settle::finish(&mut ch, main);
    ch
}

/// The channel ended without an alarm.
use settle::assert_ok as ok;

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
    // A second header after NC blocks starts another program of an archive (a text in
    // archive form is searched for one).
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

// --- 2. Subprogram calls ------------------------------------------------------------------

/// A subprogram that moves 10 in X incrementally and counts its runs in R1.
const STEP10: &str = "G91 G1 X10 F2000\nG90\nR1=R1+1\nM17\n";

#[test]
fn l_p_runs_the_subprogram_p_times() {
    // L10 P3: three passes of G91 X10 from X0 end at X30 (R1 counts 3).
    let ch = run("G90 G0 X0\nL10 P3\nM30\n", &[("L10", STEP10)]);
    ok(&ch);
    assert_eq!((wcs(&ch, "X"), ch.r_param(1)), (30.0, 3.0));
}

#[test]
fn l_numbers_keep_their_leading_zeros() {
    // L010 and L10 are two programs (the Programming Manual: leading zeros count).
    let ch = run("L010\nL10\nM30\n", &[("L10", "R1=R1+1\nM17\n"), ("L010", "R2=5\nM17\n")]);
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (1.0, 5.0));
    assert_eq!(alarm(&run("L0999\nM30\n", &[])), (14011, Some(1)));
}

#[test]
fn l_with_arguments_binds_the_proc_parameters() {
    // PROC L140(REAL AA, REAL BB): R1 = AA*10 + BB = 21; an omitted argument keeps 0.
    let sub = "PROC L140(REAL AA, REAL BB)\nR1=AA*10+BB\nR2=R2+1\nM17\n";
    let ch = run("L140(2, 1)\nR3=R1\nL140(, 4)\nM30\n", &[("L140", sub)]);
    ok(&ch);
    assert_eq!((ch.r_param(3), ch.r_param(1), ch.r_param(2)), (21.0, 4.0, 2.0));
}

#[test]
fn named_calls_with_passes_call_pcall_and_extcall_reach_the_stored_program() {
    // Each call adds one run: CONTOUR P2 (2), CALL (1), PCALL with path (1), EXTCALL (1),
    // CALL of a name held in a STRING variable (1): 6 runs, X = 60.
    let main = "DEF STRING[16] PRG=\"CONTOUR\"\nG0 X0\nCONTOUR P2\nCALL \"CONTOUR\"\n\
                PCALL /_N_WKS_DIR/_N_PLATE_WPD/_N_CONTOUR_SPF\nEXTCALL \"/_N_SPF_DIR/_N_CONTOUR_SPF\"\n\
                CALL PRG\nM30\n";
    let ch = run(main, &[("CONTOUR", STEP10)]);
    ok(&ch);
    assert_eq!((ch.r_param(1), wcs(&ch, "X")), (6.0, 60.0));
}

#[test]
fn pcall_passes_its_arguments() {
    let sub = "PROC SHAFT(REAL DIA, INT NUM)\nR1=DIA*NUM\nRET\n";
    let ch = run("PCALL /_N_WKS_DIR/_N_SHAFT_WPD/SHAFT_SPF(2.5, 4)\nM30\n", &[("SHAFT", sub)]);
    ok(&ch);
    assert_eq!(ch.r_param(1), 10.0);
}

#[test]
fn extern_declarations_check_the_arguments_of_a_call() {
    let sub = "PROC POCKET(REAL DEPTH, VAR REAL DONE)\nDONE=DONE+DEPTH\nRET\n";
    // Declared and called right: the VAR parameter writes back (0 + 3, then + 4).
    let ch = run(
        "EXTERN POCKET(REAL, VAR REAL)\nDEF REAL DIA\nPOCKET(3, DIA)\nPOCKET(4, DIA)\nR1=DIA\nM30\n",
        &[("POCKET", sub)],
    );
    ok(&ch);
    assert_eq!(ch.r_param(1), 7.0);
    // More arguments than declared: 12340 at the call, before the subprogram runs.
    let ch = run("EXTERN POCKET(REAL, VAR REAL)\nDEF REAL DIA\nPOCKET(3, DIA, 1)\nM30\n", &[("POCKET", sub)]);
    assert_eq!(alarm(&ch), (12340, Some(3)));
    // A value for a VAR parameter: 12320.
    let ch = run("EXTERN POCKET(REAL, VAR REAL)\nPOCKET(3, 4)\nM30\n", &[("POCKET", sub)]);
    assert_eq!(alarm(&ch), (12320, Some(2)));
}

#[test]
fn ret_m17_m2_and_m30_return_from_a_subprogram() {
    // (Names like A1 would be axis words: the subprograms are called RA, RB, RC, RD.)
    let subs = [("RA", "R1=R1+1\nRET\n"), ("RB", "R1=R1+1\nM17\n"), ("RC", "R1=R1+1\nM2\n"), ("RD", "R1=R1+1\nM30\n")];
    let ch = run("RA\nRB\nRC\nRD\nR2=R1\nM30\nR2=99\n", &subs);
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (4.0, 4.0));
}

#[test]
fn call_block_runs_a_section_of_the_current_or_another_program() {
    // CALL BLOCK A TO B in this program: R1 += 1 + 10; the section of SUB: R2 = 0 + 10 + 100.
    let main = "GOTOF GO\nAA: R1=R1+1\nBB: R1=R1+10\nGO: CALL BLOCK AA TO BB\nCALL \"SUB\" BLOCK S1 TO S2\nM30\n";
    let sub = "PROC SUB\nR2=1000\nS1: R2=R2+10\nS2: R2=R2+100\nR2=R2+5\nM17\n";
    let ch = run(main, &[("SUB", sub)]);
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (11.0, 110.0));
    assert_eq!(alarm(&run("CALL BLOCK NOWHERE TO BB\nBB: M30\n", &[])), (14080, Some(1)));
}

// --- 3. MCALL -----------------------------------------------------------------------------

#[test]
fn mcall_calls_after_every_block_with_path_motion_until_mcall_alone() {
    // Modal DRILL(2): called after X10 and X20 Y5 (R1 = 2 + 2), not after R5=1 (no motion) nor
    // after X30 (MCALL ended it). Inside DRILL, its own Z moves call nothing (R2 counts 2 runs).
    let drill = "PROC DRILL(REAL INC)\nR1=R1+INC\nR2=R2+1\nG0 Z-1\nG0 Z0\nM17\n";
    let main = "G0 X0 Y0\nMCALL DRILL(R10)\nX10\nX20 Y5\nR5=1\nMCALL\nX30\nM30\n";
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.store_program("DRILL", drill).unwrap();
    ch.run_program(&format!("R10=2\n{main}")).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2), wcs(&ch, "X")), (4.0, 2.0, 30.0));
}

#[test]
fn mcall_arguments_are_taken_once_and_an_l_program_can_be_modal() {
    // R10 changes after the MCALL: each call still gets 1. MCALL L30 replaces the modal call.
    let subs = [("HOLE", "PROC HOLE(REAL VAL)\nR1=R1+VAL\nM17\n"), ("L30", "R2=R2+1\nM17\n")];
    let ch = run("R10=1\nMCALL HOLE(R10)\nR10=50\nG0 X1\nX2\nMCALL L30\nX3\nX4\nX5\nM30\n", &subs);
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (2.0, 3.0));
}

#[test]
fn mcall_of_a_missing_program_is_14011_and_the_modal_call_ends_with_the_program() {
    assert_eq!(alarm(&run("MCALL L77\nM30\n", &[])), (14011, Some(1)));
    // After M30 the next program starts without a modal call.
    let mut ch = run("MCALL L1\nM30\n", &[("L1", "R1=R1+1\nM17\n")]);
    ch.run_program("G0 X1\nM30\n").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ok(&ch);
    assert_eq!(ch.r_param(1), 0.0);
}

#[test]
fn mcall_in_a_subprogram_ends_with_its_level() {
    // SUB sets MCALL L1 and moves once (R1 = 1); back in the main program X5 calls nothing.
    let subs = [("SUB", "MCALL L1\nG0 X2\nM17\n"), ("L1", "R1=R1+1\nM17\n")];
    let ch = run("SUB\nG0 X5\nM30\n", &subs);
    ok(&ch);
    assert_eq!(ch.r_param(1), 1.0);
}

// --- 4. Program section repetition --------------------------------------------------------

#[test]
fn repeat_label_runs_the_section_up_to_the_repeat_p_more_times() {
    // BEGIN..the block before REPEAT passes once, then P=3 more: X 4 × 1 incremental = 4.
    let ch = run("G0 X0\nBEGIN: G91 X1\nR1=R1+1\nREPEAT BEGIN P=3\nG90\nM30\n", &[]);
    ok(&ch);
    assert_eq!((wcs(&ch, "X"), ch.r_param(1)), (4.0, 4.0));
}

#[test]
fn repeat_between_two_labels_and_repeatb_repeat_their_blocks() {
    // START..FIN (both included) 1 + 2 runs: 3 × 111 = 333; REPEATB MIDDLE P=4: + 40.
    // With block numbers: N20..N30 once more: + 11.
    let main = "START: R1=R1+1\nMIDDLE: R1=R1+10\nFIN: R1=R1+100\nREPEAT START FIN P=2\nREPEATB MIDDLE P=4\n\
                N20 R2=R2+1\nN30 R2=R2+10\nREPEAT N20 N30\nM30\n";
    let ch = run(main, &[]);
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (373.0, 22.0));
}

#[test]
fn repeat_with_endlabel_ends_the_section_there() {
    // The section SEC..ENDLABEL (2 blocks, + 1 each) runs twice from the REPEAT after DONE;
    // the first pass was jumped over: R1 = 4. REPEATB of a label after it searches forward.
    let main = "GOTOF DONE\nSEC: R1=R1+1\nENDLABEL: R1=R1+1\nR1=R1+100\nDONE: REPEAT SEC P=2\n\
                REPEATB LATER P=2\nM30\nLATER: R2=R2+1\n";
    let ch = run(main, &[]);
    ok(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (4.0, 2.0));
}

#[test]
fn repeat_sections_nest_and_may_hold_calls() {
    // Inner: A..B (R1 += 1) 1 + 1 runs per outer run; outer: OUT..the REPEAT of the outer
    // section, 1 + 2 runs, each with one L10 (X + 10): R1 = 3 × 2 = 6, X = 30.
    let main = "G0 X0\nOUT: L10\nAA: R1=R1+1\nBB: REPEAT AA P=1\nREPEAT OUT P=2\nM30\n";
    let ch = run(main, &[("L10", "G91 G0 X10\nG90\nM17\n")]);
    ok(&ch);
    assert_eq!((ch.r_param(1), wcs(&ch, "X")), (6.0, 30.0));
}

#[test]
fn repeat_errors_name_their_block() {
    assert_eq!(alarm(&run("R1=1\nREPEAT NOWHERE P=2\nM30\n", &[])), (14080, Some(2)));
    assert_eq!(alarm(&run("AA: R1=1\nREPEAT AA P=0\nM30\n", &[])).1, Some(2));
    // A label after the REPEAT without ENDLABEL.
    assert_eq!(alarm(&run("REPEAT LATER P=2\nM30\nLATER: R1=1\n", &[])), (14080, Some(1)));
}

// --- 5. Everyday words --------------------------------------------------------------------

#[test]
fn feed_profiles_drf_single_block_display_and_group_markers_are_accepted() {
    // FLIN/FCUB run as FNORM's constant feed: 100 mm at F3000 take 2 s plus one ramp (50/3000 s)
    // as with FNORM.
    for profile in ["FNORM", "FLIN", "FCUB"] {
        let main = format!(
            "{profile}\nDRFOF\nSBLOF\nDISPLOF\nGROUP_BEGIN(0,\"Contour\",0,0)\nG1 X100 F3000\nGROUP_END(0,0)\nSBLON\nDISPLON\nM30\n"
        );
        let ch = run(&main, &[]);
        ok(&ch);
        assert_eq!(wcs(&ch, "X"), 100.0);
        assert!((ch.time() - (2.0 + 50.0 / 3000.0)).abs() < 0.01, "{profile}: {}", ch.time());
    }
}

#[test]
fn operate_markers_are_comments() {
    let ch = run(";#SM Z:1\n;*RO*\n;*HD*\nG0 X3\n;#End contour definition\nM30\n", &[]);
    ok(&ch);
    assert_eq!(wcs(&ch, "X"), 3.0);
}

#[test]
fn h_functions_and_m_functions_with_address_extension_are_read() {
    let ch = run("H7\nH=5\nH2=1.5\nM1=8\nM2=77\nG0 X1\nM30\n", &[]);
    ok(&ch);
    // On the lathe, spindle 1 is the master spindle: M1=3 turns it like M3, M1=5 stops it.
    let mut lathe = Channel::from_preset("lathe-2axis", "").unwrap();
    lathe.run_program("M1=3 S500\nG4 F0.5\nM1=5\nM30\n").unwrap();
    while lathe.is_busy() {
        lathe.step();
    }
    ok(&lathe);
    // The 2-axis lathe has no spindle 2: M2=3 names a spindle outside the channel (12560, the
    // programmed value out of range); M1=30 is no program end.
    let mut lathe = Channel::from_preset("lathe-2axis", "").unwrap();
    lathe.run_program("M2=3 S500\nM30\n").unwrap();
    while lathe.is_busy() {
        lathe.step();
    }
    assert_eq!(alarm(&lathe), (12560, Some(1)));
    assert_eq!(alarm(&run("G0 X1\nM1=30\n", &[])), (12550, Some(2)));
}

// --- 6. Names the control reserves and NCTwin does not model ------------------------------

#[test]
fn an_unmodelled_reserved_name_is_12550_naming_it_and_its_line() {
    for (word, name) in [
        // WORKPIECE and ACTBLOCNO are accepted now (program_data.rs), the file functions too
        // (file_functions.rs), MEAS/MEAW as well (measuring.rs).
        ("CYCLE952(\"PART\",,\"\",2101311,0.2,0.1,0,0.5,0.1,0.1,0.2,0.1,0.1,4,1,0,0,0)", "CYCLE952"),
        ("R1=$MN_INTERPOLATOR_CYCLE", "$MN_INTERPOLATOR_CYCLE"),
        // Synchronized actions are modelled now (synchronized_actions.rs); a name in one that
        // is not a variable of synchronized actions is still 12550 naming it.
        ("WHEN $AA_IM[X]>5 DO $P_UIFR[1]=1", "$P_UIFR"),
    ] {
        let ch = run(&format!("G0 X2\n{word}\nG0 X3\nM30\n"), &[]);
        let s = ch.snapshot();
        assert_eq!(alarm(&ch), (12550, Some(2)), "{word}");
        assert!(s.alarms[0].message.contains(name), "{word}: {}", s.alarms[0].message);
        assert_eq!(wcs(&ch, "X"), 2.0);
    }
}
