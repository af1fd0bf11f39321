//! `SETPIECE` and workpiece count monitoring on the 3-axis mill preset (Function Manual Tool
//! Management / W1 "Workpiece count monitoring"): `SETPIECE(n)` lowers the remaining piece
//! count `$TC_MOP4` by n for every count-monitored cutting edge (`$TC_TP9` bit 1) that was
//! active in the spindle since the last `SETPIECE`; tool changes alone count nothing. The
//! prewarning limit `$TC_MOP3` sets `$TC_TP8` bit 4 (alarm 6411), 0 left sets bit 2 (disabled,
//! alarm 6413).
//!
//! The preset: T1 "MILL_D10" and T2 "DRILL_8", each with D1, both enabled (`$TC_TP8`=2).
//! MD22550 = 1 (T prepares, M6 changes), no change time.

use nctwin_engine::{Channel, Snapshot};

const MODE: &str = "$MC_TOOL_CHANGE_MODE=1\n$MC_TOOL_CHANGE_TIME=0\n";
/// DRILL_8 count-monitored: 3 pieces left, prewarning at 2.
const DRILL_COUNTED: &str = "$TC_TP9[2]=2\n$TC_MOP4[2,1]=3\n$TC_MOP3[2,1]=2\n";
/// MILL_D10 count-monitored: 10 pieces left, no prewarning.
const MILL_COUNTED: &str = "$TC_TP9[1]=2\n$TC_MOP4[1,1]=10\n";

fn run(md: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", &format!("{MODE}{md}")).unwrap();
    ch.run_program(program).unwrap();
    let mut cycles = 0;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < 2_000_000, "program does not end");
    }
    ch
}

fn mop4(ch: &Channel, t: u32) -> f64 {
    ch.config().tool_list.read("$TC_MOP4", t, 1).unwrap().as_f64().unwrap()
}

fn state(ch: &Channel, t: u32) -> i64 {
    ch.config().tool_list.tools[&t].state
}

fn alarms(s: &Snapshot) -> Vec<(u32, Option<u32>)> {
    s.alarms.iter().map(|a| (a.number, a.line)).collect()
}

/// One workpiece: drill, then mill, each with a short cut.
const PIECE: &str = "T=\"DRILL_8\" M6\nG1 F1000 X10\nT=\"MILL_D10\" M6\nG1 X0\n";

#[test]
fn tool_changes_alone_count_no_pieces() {
    let ch = run(DRILL_COUNTED, &format!("G0 X0 Y0 Z50\n{PIECE}{PIECE}M30"));
    assert_eq!(mop4(&ch, 2), 3.0);
    assert_eq!(state(&ch, 2), 2);
    assert!(alarms(&ch.snapshot()).is_empty());
}

#[test]
fn setpiece_counts_each_monitored_edge_used_since_the_last_one() {
    // One SETPIECE(1) after a piece: the drill 3 -> 2, which is the prewarning limit (6411,
    // state 2 | 16). The mill was used too but has no monitoring: left alone.
    let ch = run(DRILL_COUNTED, &format!("G0 X0 Y0 Z50\n{PIECE}SETPIECE(1)\nM30"));
    assert_eq!(mop4(&ch, 2), 2.0);
    assert_eq!(state(&ch, 2), 2 | 16);
    assert_eq!(state(&ch, 1), 2);
    assert_eq!(alarms(&ch.snapshot()), vec![(6411, None)]);

    // Three pieces: 3 -> 2 (6411) -> 1 -> 0 (6413, disabled: 2 | 4 | 16).
    let program = format!("G0 X0 Y0 Z50\n{0}SETPIECE(1)\n{0}SETPIECE(1)\n{0}SETPIECE(1)\nM30", PIECE);
    let ch = run(DRILL_COUNTED, &program);
    assert_eq!(mop4(&ch, 2), 0.0);
    assert_eq!(state(&ch, 2), 2 | 4 | 16);
    assert_eq!(alarms(&ch.snapshot()).iter().map(|a| a.0).collect::<Vec<_>>(), vec![6411, 6413]);
}

#[test]
fn a_tool_used_twice_in_one_piece_counts_once_and_both_monitored_tools_count() {
    // Drill and mill both count-monitored; two drill/mill rounds before one SETPIECE(1):
    // drill 3 -> 2, mill 10 -> 9.
    let md = format!("{DRILL_COUNTED}{MILL_COUNTED}");
    let ch = run(&md, &format!("G0 X0 Y0 Z50\n{PIECE}{PIECE}SETPIECE(1)\nM30"));
    assert_eq!(mop4(&ch, 2), 2.0);
    assert_eq!(mop4(&ch, 1), 9.0);
}

#[test]
fn setpiece_n_counts_n_pieces_and_the_edge_in_the_spindle_stays_remembered() {
    // SETPIECE(2): the mill 10 -> 8. It stays in the spindle, so the next SETPIECE(3) counts
    // it again without a new change: 8 -> 5.
    let ch = run(MILL_COUNTED, "T=\"MILL_D10\" M6\nG0 X0 Y0 Z50\nG1 F1000 X10\nSETPIECE(2)\nG1 X0\nSETPIECE(3)\nM30");
    assert_eq!(mop4(&ch, 1), 5.0);
}

#[test]
fn setpiece_0_forgets_the_tools_used_without_counting() {
    // The drill is forgotten by SETPIECE(0) while the mill is in the spindle; the mill has
    // no count monitoring, so the later SETPIECE(1) counts nothing at all.
    let program = format!("G0 X0 Y0 Z50\n{PIECE}SETPIECE(0)\nG1 X5\nSETPIECE(1)\nM30");
    let ch = run(DRILL_COUNTED, &program);
    assert_eq!(mop4(&ch, 2), 3.0);
}

#[test]
fn setpiece_for_the_master_spindle_by_number_and_by_0() {
    // The mill preset's master spindle is S1: SETPIECE(1, 1) and SETPIECE(1, 0) both count.
    let ch = run(MILL_COUNTED, "T=\"MILL_D10\" M6\nG0 X0 Y0 Z50\nSETPIECE(1,1)\nSETPIECE(1,0)\nM30");
    assert_eq!(mop4(&ch, 1), 8.0);
}

#[test]
fn bad_setpiece_arguments_raise_alarms_with_their_line() {
    // Pieces 0..32000; a spindle the channel has; a whole number; one or two arguments.
    for (program, number) in [
        ("G0 X0\nSETPIECE(32001)\nM30", 12560),
        ("G0 X0\nSETPIECE(-1)\nM30", 12560),
        ("G0 X0\nSETPIECE(1.5)\nM30", 12560),
        ("G0 X0\nSETPIECE(1,5)\nM30", 12560),
    ] {
        let ch = run(MILL_COUNTED, program);
        assert_eq!(alarms(&ch.snapshot()), vec![(number, Some(2))], "{program}");
    }
    let ch = run(MILL_COUNTED, "G0 X0\nSETPIECE\nM30");
    let a = alarms(&ch.snapshot());
    assert_eq!(a.len(), 1);
    assert_eq!(a[0].1, Some(2));
}
