//! Tool management on the 3-axis mill preset: tools by name, T and M6 per MD22550, the change
//! time, the length of the new tool, and the system variables of the tool list.
//!
//! The preset's magazine (presets.rs): T1 "MILL_D10" (end mill, length 100, radius 5) in
//! place 1, T2 "DRILL_8" (drill, length 120, radius 4) in place 2 of chain magazine 1. In G17
//! the tool's length 1 acts on Z: Z_machine = Z_programmed + L1 (REFERENCE.md §2.2).

use nctwin_engine::{Channel, Snapshot};

fn run(md: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    ch.run_program(program).unwrap();
    let mut cycles = 0;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < 1_000_000, "program does not end");
    }
    ch
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn no_alarms(s: &Snapshot) {
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
}

/// MD22550 = 1 (T prepares, M6 changes), change time 4 s.
const M6_MODE: &str = "$MC_TOOL_CHANGE_MODE=1\n$MC_TOOL_CHANGE_TIME=4.\n";

#[test]
fn t_by_name_and_m6_change_the_tool_take_the_change_time_and_apply_its_length() {
    // Without the change: G0 to Z10 from Z0 and back; with it, the same plus the change.
    let moves = "G0 X0 Y0 Z0\nG0 Z10\nM30";
    let base = run(M6_MODE, moves).snapshot();
    let prog = "G0 X0 Y0 Z0\nT=\"DRILL_8\"\nR1=$P_TOOLNO R2=$P_TOOLP\nM6\nR3=$P_TOOLNO R4=$P_TOOL\nG0 Z10\nM30";
    let ch = run(M6_MODE, prog);
    let s = ch.snapshot();
    no_alarms(&s);
    // Before M6 the spindle is empty and DRILL_8 (T2) prepared; after it T2 D1 is active.
    assert_eq!((ch.r_param(1), ch.r_param(2)), (0.0, 2.0));
    assert_eq!((ch.r_param(3), ch.r_param(4)), (2.0, 1.0));
    assert_eq!(s.tool, (2, 1));
    assert_eq!(s.tool_name, "DRILL_8");
    // Z10 with the drill's length 120: machine Z 130.
    assert!((machine(&s, "Z") - 130.0).abs() < 1e-9, "{:?}", s.machine);
    // The change took the 4 s of $MC_TOOL_CHANGE_TIME: the same as a change without a time
    // followed by a 4 s dwell.
    let no_time = "$MC_TOOL_CHANGE_MODE=1\n$MC_TOOL_CHANGE_TIME=0\n";
    let with_dwell = prog.replace("M6\n", "M6\nG4 F4\n");
    let dwell = run(no_time, &with_dwell).snapshot().time;
    // Within one IPO cycle (4 ms): the new offsets are taken over in the cycle after the wait.
    assert!((s.time - dwell).abs() <= 0.004 + 1e-9, "{} vs {dwell}", s.time);
    assert!(s.time > base.time + 4.0 - 1e-9);
}

#[test]
fn in_mode_1_t_only_prepares_and_d_acts_on_the_tool_in_the_spindle() {
    // T1 is changed in; T2 D1 prepares T2 while D1 stays on T1: Z0 → machine Z 100.
    let ch = run(M6_MODE, "T1\nM6\nT2 D1\nG0 X0 Y0 Z0\nM6\nG0 Z0\nM30");
    let s = ch.snapshot();
    no_alarms(&s);
    assert!((machine(&s, "Z") - 120.0).abs() < 1e-9, "after M6 the drill: {:?}", s.machine);
    let mut ch = Channel::from_preset("mill-3axis", M6_MODE).unwrap();
    ch.run_program("T1\nM6\nT2 D1\nG0 X0 Y0 Z0\nM0\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let s = ch.snapshot();
    assert!((machine(&s, "Z") - 100.0).abs() < 1e-9, "T2 only prepared: {:?}", s.machine);
    assert_eq!((s.tool, s.prepared_tool), ((1, 1), 2));
    assert_eq!(s.tool_name, "MILL_D10");
}

#[test]
fn in_mode_0_t_changes_at_once_and_m6_is_only_an_m_function() {
    let ch = run("$MC_TOOL_CHANGE_TIME=2.5\n", "T=\"DRILL_8\"\nG0 X0 Y0 Z0\nM6\nM30");
    let s = ch.snapshot();
    no_alarms(&s);
    assert_eq!((s.tool, s.prepared_tool), ((2, 1), 2));
    assert!((machine(&s, "Z") - 120.0).abs() < 1e-9);
    // Selecting the tool already in the spindle again takes no time.
    let once = run("$MC_TOOL_CHANGE_TIME=2.5\n", "T2\nG4 F1\nM30").snapshot().time;
    let twice = run("$MC_TOOL_CHANGE_TIME=2.5\n", "T2\nT2\nG4 F1\nM30").snapshot().time;
    assert!((once - twice).abs() < 1e-9 && once >= 3.5 - 1e-9, "{once} {twice}");
}

#[test]
fn an_unknown_tool_name_is_alarm_17191_with_its_line() {
    let ch = run(M6_MODE, "G0 X0 Y0 Z0\nT=\"NO_SUCH_TOOL\"\nM6\nM30");
    let a = &ch.snapshot().alarms;
    assert_eq!(a.len(), 1, "{a:?}");
    assert_eq!((a[0].number, a[0].line), (17191, Some(2)));
    assert!(a[0].message.contains("NO_SUCH_TOOL"), "{}", a[0].message);
    // A missing cutting edge of an existing tool: 17180.
    let ch = run("", "T2 D3\nM30");
    let a = &ch.snapshot().alarms;
    assert_eq!((a[0].number, a[0].line), (17180, Some(1)), "{a:?}");
}

#[test]
fn a_disabled_duplo_is_passed_over_for_the_next_one_and_tca_takes_it_anyway() {
    // T5 and T6 are both "MILL_D10_B"; duplo 1 (T5) is disabled ($TC_TP8 bit 2).
    let md = "$TC_TP2[5]=\"MILL_D10_B\"\n$TC_TP1[5]=1\n$TC_TP8[5]=4\n$TC_DP1[5,1]=120\n$TC_DP3[5,1]=90.\n\
              $TC_TP2[6]=\"MILL_D10_B\"\n$TC_TP1[6]=2\n$TC_DP1[6,1]=120\n$TC_DP3[6,1]=95.\n";
    let s = run(md, "T=\"MILL_D10_B\"\nG0 X0 Y0 Z0\nM30").snapshot();
    no_alarms(&s);
    assert_eq!(s.tool.0, 6);
    assert!((machine(&s, "Z") - 95.0).abs() < 1e-9);
    let s = run(md, "TCA(\"MILL_D10_B\",1)\nG0 X0 Y0 Z0\nM30").snapshot();
    no_alarms(&s);
    assert_eq!(s.tool.0, 5);
    assert!((machine(&s, "Z") - 90.0).abs() < 1e-9);
}

#[test]
fn a_program_reads_names_places_and_tool_numbers_of_the_tool_list() {
    // T7 is defined without a place: it lands in place 3 (places 1 and 2 hold T1 and T2).
    let md = "$TC_TP2[7]=\"TAP_M6\"\n$TC_DP1[7,1]=240\n$TC_DP3[7,1]=80.\n$TC_DP6[7,1]=3.\n";
    let prog = "DEF STRING[32] NAME\nNAME=$TC_TP2[2]\nIF NAME==\"DRILL_8\"\nR1=1\nENDIF\n\
                R2=GETT(\"TAP_M6\") R3=$TC_MPP6[1,3] R4=GETT(\"NONE\") R5=$TC_MPP1[9998,1]\n\
                T=\"TAP_M6\" D1\nR6=$P_TOOLNO R7=$P_TOOLR\nM30";
    let ch = run(md, prog);
    no_alarms(&ch.snapshot());
    let r: Vec<f64> = (1..=7).map(|i| ch.r_param(i)).collect();
    assert_eq!(r, [1.0, 7.0, 7.0, -1.0, 2.0, 7.0, 3.0]);
}

#[test]
fn t1_d1_programs_without_tool_management_data_keep_working() {
    // A tool known only by its edges (no name, no place) is selected by number as before.
    let md = "$TC_DP1[9,1]=120\n$TC_DP3[9,1]=50.\n";
    let s = run(md, "T9 D1\nG0 X0 Y0 Z0\nM30").snapshot();
    no_alarms(&s);
    assert_eq!((s.tool, s.tool_name.as_str()), ((9, 1), ""));
    assert!((machine(&s, "Z") - 50.0).abs() < 1e-9);
    let a = run("", "T99\nM30").snapshot().alarms;
    assert_eq!((a[0].number, a[0].line), (17190, Some(1)));
}

#[test]
fn tools_are_unloaded_to_the_loading_magazine_and_loaded_into_free_places() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    let place = |ch: &Channel, t: u32| ch.config().tool_list.tools[&t].place;
    assert_eq!(place(&ch, 2), Some((1, 2)));
    ch.unload_tool(2).unwrap();
    assert_eq!(place(&ch, 2), Some((9999, 1)));
    ch.load_tool(2, 1, 5).unwrap();
    assert_eq!(place(&ch, 2), Some((1, 5)));
    let e = ch.load_tool(1, 1, 5).unwrap_err().to_string();
    assert!(e.contains("place 5 holds tool 2"), "{e}");
    let e = ch.load_tool(1, 1, 13).unwrap_err().to_string();
    assert!(e.contains("has no place 13"), "{e}");
    // The data keep the new place over a text round trip (persistence).
    let mut again = nctwin_engine::machine_data::MachineData::default();
    let cfg = again.apply_text(&ch.machine_data().to_text()).unwrap();
    assert_eq!(cfg.tool_list.tools[&2].place, Some((1, 5)));
    // The tool in the spindle stays where it is.
    ch.run_program("T1\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let e = ch.unload_tool(1).unwrap_err().to_string();
    assert!(e.contains("in the spindle"), "{e}");
}

#[test]
fn m6_calls_the_change_cycle_of_md10715_and_its_own_m6_changes() {
    let md = "$MC_TOOL_CHANGE_MODE=1\n$MC_TOOL_CHANGE_TIME=0\n$MN_M_NO_FCT_CYCLE[0]=6\n\
              $MN_M_NO_FCT_CYCLE_NAME[0]=\"TC_CYCLE\"\n";
    let main = "T=\"DRILL_8\"\nM6\nR11=$P_TOOLNO\nG0 X0 Y0 Z0\nM30";
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    ch.store_program("TC_CYCLE.SPF", "PROC TC_CYCLE\nR10=R10+1 R12=$P_TOOLNO\nM6\nRET\n").unwrap();
    ch.run_program(main).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let s = ch.snapshot();
    no_alarms(&s);
    // The cycle ran once, before its M6 the spindle was still empty; after it T2 is in.
    assert_eq!((ch.r_param(10), ch.r_param(12), ch.r_param(11)), (1.0, 0.0, 2.0));
    assert!((machine(&s, "Z") - 120.0).abs() < 1e-9);
    // Without the cycle in the program store M6 changes directly.
    let ch = run(md, main);
    no_alarms(&ch.snapshot());
    assert_eq!((ch.r_param(10), ch.r_param(11)), (0.0, 2.0));
}
