//! `CHKDNO` (Programming Manual "Job planning", checking D numbers): TRUE when no D number
//! occurs in two of the checked tools.
//!
//! The 3-axis mill preset has T1 (MILL_D10) and T2 (DRILL_8), each with edge D1; the extra
//! data give T5 a single edge D7.

use nctwin_engine::Channel;

fn run(program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", "$TC_DP1[5,7]=120\n$TC_DP3[5,7]=50\n").unwrap();
    ch.run_program(program).unwrap();
    let mut cycles = 0;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < 100_000, "program does not end");
    }
    ch
}

#[test]
fn chkdno_finds_a_d_number_that_two_tools_share() {
    let program = "R1=CHKDNO(1,2)\nR2=CHKDNO(1,5)\nR3=CHKDNO(5)\nR4=CHKDNO(1)\nR5=CHKDNO(1,2,7)\n\
                   R6=CHKDNO(1,2,1)\nR7=CHKDNO()\nR8=CHKDNO(5,5)\nM30";
    let ch = run(program);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    // T1 and T2 both have D1: R1 FALSE; T1 (D1) against T5 (D7): TRUE; D7 of T5 is nowhere
    // else: TRUE; D1 of T1 is also T2's: FALSE; D7 is in neither T1 nor T2: TRUE; D1 in both:
    // FALSE; all tools: D1 twice, FALSE; a tool against itself collides with nothing: TRUE.
    let got: Vec<f64> = (1..=8).map(|n| ch.r_param(n)).collect();
    assert_eq!(got, vec![0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
}

#[test]
fn chkdno_with_too_many_or_negative_arguments_is_an_alarm_with_its_line() {
    let ch = run("R1=1\nR2=CHKDNO(1,2,3,4)\nM30");
    let a = &ch.snapshot().alarms;
    assert_eq!(a.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), vec![(12080, Some(2))]);
    let ch = run("R2=CHKDNO(-1)\nM30");
    let a = &ch.snapshot().alarms;
    assert_eq!(a.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), vec![(12560, Some(1))]);
}
