//! Flat D numbers (Function Manual W1 "Flat D number structure", MD18102
//! `$MN_MM_TYPE_OF_CUTTING_EDGE` = 1): D1..D32000 name offset data sets `$TC_DPx[d]` without
//! reference to a tool; T is still programmed and changes the tool, but leaves the active D.
//!
//! Worked by hand on the 3-axis mill (G17: the length L1 `$TC_DP3` lies along Z, so the
//! machine Z of a tool tip at workpiece Z10 is 10 + L1; no work offset is active).

use crate::settle;

use nctwin_engine::Channel;

const FLAT: &str = "$MN_MM_TYPE_OF_CUTTING_EDGE=1
$MC_TOOL_CHANGE_MODE=0
$MC_TOOL_CHANGE_TIME=0
$TC_DP1[777]=120
$TC_DP3[777]=50.
$TC_DP6[777]=4.
$TC_DP1[12]=120
$TC_DP3[12]=80.
";

fn run(md: &str, program: &str) -> Channel {
    settle::ran("mill-3axis", md, program)
}

fn machine_z(ch: &Channel) -> f64 {
    ch.snapshot().machine.iter().find(|(n, _)| n == "Z").unwrap().1
}

fn alarms(ch: &Channel) -> Vec<(u32, Option<u32>)> {
    ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect()
}

#[test]
fn d777_selects_its_data_set_whatever_the_tool() {
    // L1 = 50: Z10 is machine Z60.
    let ch = run(FLAT, "T1 D777\nG0 X0 Y0 Z10\nM30");
    assert!(alarms(&ch).is_empty(), "{:?}", alarms(&ch));
    assert!((machine_z(&ch) - 60.0).abs() < 1e-9, "{}", machine_z(&ch));
    // D12 (L1 = 80) with T2: Z90.
    let ch = run(FLAT, "T2 D12\nG0 X0 Y0 Z10\nM30");
    assert!((machine_z(&ch) - 90.0).abs() < 1e-9);
}

#[test]
fn a_tool_change_keeps_the_active_d() {
    // T2 after D777: still L1 = 50 (relative D numbers would bring T2's D1, L1 = 120).
    let ch = run(FLAT, "T1 D777\nT2\nG0 X0 Y0 Z10\nM30");
    assert!((machine_z(&ch) - 60.0).abs() < 1e-9, "{}", machine_z(&ch));
}

#[test]
fn programs_read_and_write_flat_data_sets() {
    // $TC_DP3[777] reads 50; writing 70 makes Z10 machine Z80.
    let ch = run(FLAT, "R1=$TC_DP3[777]\nIF R1<>50\nSETAL(61000)\nENDIF\n$TC_DP3[777]=70\nT1 D777\nG0 X0 Y0 Z10\nM30");
    assert!(alarms(&ch).is_empty(), "{:?}", alarms(&ch));
    assert!((machine_z(&ch) - 80.0).abs() < 1e-9, "{}", machine_z(&ch));
}

#[test]
fn an_undefined_flat_d_is_17180_and_relative_numbering_ignores_flat_sets() {
    let ch = run(FLAT, "T1\nD5\nM30");
    assert_eq!(alarms(&ch), vec![(17180, Some(2))]);
    // Without MD18102 the flat set is not reachable: D777 of T1 does not exist.
    let md = FLAT.replace("$MN_MM_TYPE_OF_CUTTING_EDGE=1\n", "");
    let ch = run(&md, "T1\nD777\nM30");
    assert_eq!(alarms(&ch), vec![(17180, Some(2))]);
}
