//! NEWT and DELT on the 3-axis mill preset (Programming Manual Job Planning: `<T no.>=NEWT(
//! "<name>"[, <duplo>])` creates a tool and gives its T number; `DELT("<name>"[, <duplo>])`
//! deletes it).
//!
//! The preset's tool list: T1 "MILL_D10" duplo 1 (length 100) and T2 "DRILL_8" duplo 1 (length
//! 120), both in the chain magazine. MD22550 = 0: `T=` changes the tool at once. In G17 the
//! length acts on Z: Z_machine = Z_programmed + length.

use crate::settle;

use nctwin_engine::Channel;

fn run(program: &str) -> Channel {
    let mut ch = settle::channel("mill-3axis", "");
    settle::finish(&mut ch, program);
    ch
}

fn alarm(ch: &Channel) -> (u32, Option<u32>) {
    let a = &ch.snapshot().alarms;
    assert_eq!(a.len(), 1, "{a:?}");
    (a[0].number, a[0].line)
}

#[test]
fn newt_gives_the_lowest_free_t_number_and_the_tool_is_used_by_name() {
    // T1 and T2 exist: the new tool is T3 with duplo 1 (the first of its name). Its D1 gets a
    // length of 80, so Z0 puts machine Z at 80.
    let ch = run("DEF INT TNR\nTNR=NEWT(\"FACE_D50\")\nR1=TNR R2=GETT(\"FACE_D50\") R3=$TC_TP1[TNR]\n\
         $TC_DP1[TNR,1]=120 $TC_DP3[TNR,1]=80. $TC_DP6[TNR,1]=25.\nT=\"FACE_D50\"\nG0 X0 Y0 Z0\nM30");
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert_eq!((ch.r_param(1), ch.r_param(2), ch.r_param(3)), (3.0, 3.0, 1.0));
    assert_eq!(s.tool, (3, 1));
    assert_eq!(s.tool_name, "FACE_D50");
    assert!((settle::machine_axis(&s, "Z") - 80.0).abs() < 1e-9, "{:?}", s.machine);
}

#[test]
fn newt_of_a_known_name_gives_the_next_duplo_and_a_taken_duplo_is_17230() {
    // DRILL_8 has duplo 1: the new one is T3 with duplo 2; two NEWT in one block get T3, T4.
    let ch = run("R1=NEWT(\"DRILL_8\") R2=NEWT(\"DRILL_8\")\nR3=$TC_TP1[3] R4=$TC_TP1[4]\nM30");
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (3.0, 4.0));
    assert_eq!((ch.r_param(3), ch.r_param(4)), (2.0, 3.0));
    // Duplo 1 of DRILL_8 is T2 already.
    let ch = run("G0 X0 Y0 Z0\nR1=NEWT(\"DRILL_8\", 1)\nM30");
    assert_eq!(alarm(&ch), (17230, Some(2)));
    // A new name with a duplo of its own keeps it.
    let ch = run("R1=NEWT(\"TAP_M6\", 7)\nR2=$TC_TP1[R1]\nM30");
    assert_eq!((ch.r_param(1), ch.r_param(2)), (3.0, 7.0));
}

#[test]
fn delt_deletes_the_tool_and_frees_its_number() {
    // After DELT, GETT finds no DRILL_8 (-1) and the next NEWT takes the free T2.
    let ch = run("DELT(\"DRILL_8\")\nR1=GETT(\"DRILL_8\")\nR2=NEWT(\"SPOT_D6\")\nM30");
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (-1.0, 2.0));
    // Its cutting edge went with it: T2 D1 is no longer there.
    let ch = run("DELT(\"DRILL_8\")\nT2 D1\nM30");
    assert_eq!(alarm(&ch), (17190, Some(2)));
    // Programming the deleted name: 17191.
    let ch = run("DELT(\"DRILL_8\", 1)\nT=\"DRILL_8\"\nM30");
    assert_eq!(alarm(&ch), (17191, Some(2)));
}

#[test]
fn delt_refuses_the_tool_in_use_and_an_unknown_name() {
    // The tool in the spindle cannot be deleted: 17200.
    let ch = run("T=\"MILL_D10\"\nG0 X0 Y0 Z0\nDELT(\"MILL_D10\")\nM30");
    assert_eq!(alarm(&ch), (17200, Some(3)));
    let ch = run("DELT(\"NO_SUCH_TOOL\")\nM30");
    assert_eq!(alarm(&ch), (17191, Some(1)));
    let ch = run("DELT(\"DRILL_8\", 4)\nM30");
    assert_eq!(alarm(&ch), (17191, Some(1)));
}

#[test]
fn newt_without_a_name_is_refused_with_its_line() {
    let ch = run("G0 X0 Y0 Z0\nR1=NEWT(5)\nM30");
    let (number, line) = alarm(&ch);
    assert_eq!(line, Some(2));
    assert_ne!(number, 12550, "NEWT is known");
}

#[test]
fn the_name_check_knows_newt_and_delt() {
    let ctx = settle::channel("mill-3axis", "").name_context();
    let text = "DEF INT TNR\nTNR=NEWT(\"FACE_D50\", 2)\nDELT(\"FACE_D50\", 2)\nM30\n";
    assert!(nctwin_engine::check::names(text, &ctx).is_empty());
}
