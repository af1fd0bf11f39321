//! Tool monitoring on the 3-axis mill preset (Function Manual Tool Management, "Tool
//! monitoring"): time monitoring counts `$TC_MOP2` (remaining minutes) down while the tool
//! cuts in feed motion (count monitoring and `SETPIECE`: `setpiece.rs`); the prewarning limit sets `$TC_TP8` bit 4 (alarm 6411), the limit bit 2 (disabled,
//! alarm 6413), and `T="name"` then selects an enabled duplo or raises 22069.
//!
//! The preset (presets.rs): T1 "MILL_D10" duplo 1 (length 100, radius 5) and T2 "DRILL_8"
//! duplo 1, both enabled (`$TC_TP8`=2), in places 1 and 2 of magazine 1. MD22550 = 1 here
//! (T prepares, M6 changes) with no change time, so only the moves take time.

use nctwin_engine::{Channel, Snapshot};

const MODE: &str = "$MC_TOOL_CHANGE_MODE=1\n$MC_TOOL_CHANGE_TIME=0\n";

fn channel(md: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", &format!("{MODE}{md}")).unwrap();
    ch.run_program(program).unwrap();
    ch
}

fn finish(ch: &mut Channel) {
    let mut cycles = 0;
    while ch.is_busy() {
        ch.step();
        cycles += 1;
        assert!(cycles < 2_000_000, "program does not end");
    }
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap().1
}

fn state(ch: &Channel, t: u32) -> i64 {
    ch.config().tool_list.tools[&t].state
}

fn mop(ch: &Channel, n: u32, t: u32, d: u32) -> f64 {
    ch.config().tool_list.read(&format!("$TC_MOP{n}"), t, d).unwrap().as_f64().unwrap()
}

fn alarm_numbers(s: &Snapshot) -> Vec<u32> {
    s.alarms.iter().map(|a| a.number).collect()
}

/// MILL_D10 time-monitored: 1.0 min remaining, prewarning at 0.5 min.
const TIME_MONITORED: &str = "$TC_TP9[1]=1\n$TC_MOP2[1,1]=1.0\n$TC_MOP1[1,1]=0.5\n";

#[test]
fn a_tool_with_one_minute_left_is_disabled_after_one_minute_of_cutting() {
    // G1 X150 at F100 takes 90 s. Cutting starts at X0 (the G0 there does not count): the
    // prewarning (0.5 min left) comes after 30 s at X = 100/60 * 30 = 50 mm, the limit after
    // 60 s at X = 100 mm. The acceleration to 100 mm/min costs far less than a cycle's path
    // (1.67 mm/s * 4 ms = 0.007 mm), so 0.05 mm covers it.
    let program = "T=\"MILL_D10\" M6\nG0 X0 Y0 Z50\nG1 F100 X150\nM30";
    let mut ch = channel(TIME_MONITORED, program);
    let (mut warned_at, mut disabled_at) = (None, None);
    while ch.is_busy() {
        ch.step();
        if warned_at.is_none() && state(&ch, 1) & 16 != 0 {
            warned_at = Some(machine(&ch.snapshot(), "X"));
        }
        if disabled_at.is_none() && state(&ch, 1) & 4 != 0 {
            disabled_at = Some(machine(&ch.snapshot(), "X"));
            // Written into the tool data at once: no time left.
            assert!(mop(&ch, 2, 1, 1).abs() < 1e-4, "{}", mop(&ch, 2, 1, 1));
        }
    }
    let warned_at = warned_at.expect("prewarning reached");
    let disabled_at = disabled_at.expect("limit reached");
    assert!((warned_at - 50.0).abs() < 0.05, "prewarning at X{warned_at}");
    assert!((disabled_at - 100.0).abs() < 0.05, "disabled at X{disabled_at}");
    let s = ch.snapshot();
    // Both alarms are information only: the program ran to its end, the tool cut on.
    assert_eq!(alarm_numbers(&s), vec![6411, 6413]);
    assert!(s.alarms[1].message.contains("MILL_D10") && s.alarms[1].message.contains("D = 1"));
    assert!((machine(&s, "X") - 150.0).abs() < 1e-6);
    // State: enabled (2) + disabled (4) + prewarning (16); the 90 s of cutting leave
    // 1.0 - 1.5 = -0.5 min (the count goes on while the disabled tool keeps cutting).
    assert_eq!(state(&ch, 1), 2 | 4 | 16);
    assert!((mop(&ch, 2, 1, 1) + 0.5).abs() < 1e-4, "{}", mop(&ch, 2, 1, 1));
}

#[test]
fn rapid_traverse_and_dwells_do_not_count() {
    // 0.1 min = 6 s of life; G0 moves over 400 mm and a 10 s dwell use none of it; 3 s of G1
    // (F100 over 5 mm) use 0.05 min.
    let md = "$TC_TP9[1]=1\n$TC_MOP2[1,1]=0.1\n";
    let mut ch = channel(md, "T=\"MILL_D10\" M6\nG0 X200 Y0 Z50\nG0 X0\nG4 F10\nG1 F100 X5\nM30");
    finish(&mut ch);
    assert_eq!(state(&ch, 1) & 4, 0);
    assert!((mop(&ch, 2, 1, 1) - 0.05).abs() < 1e-4, "{}", mop(&ch, 2, 1, 1));
    assert!(ch.snapshot().alarms.is_empty());
}

#[test]
fn the_next_duplo_is_selected_once_the_first_is_disabled() {
    // A second MILL_D10, duplo 2, as T3 (length 90). After 36 s at F100 (X0 to X60) the
    // 0.5 min of T1 are used up at X50; after STOPRE the next T="MILL_D10" finds duplo 1
    // disabled and takes duplo 2: $P_TOOLNO = 3, and Z50 is machine Z 50 + 90.
    let md = "$TC_TP9[1]=1\n$TC_MOP2[1,1]=0.5\n$TC_TP2[3]=\"MILL_D10\"\n$TC_TP1[3]=2\n$TC_TP8[3]=2\n\
              $TC_DP1[3,1]=120\n$TC_DP3[3,1]=90\n$TC_DP6[3,1]=5\n";
    let program = "T=\"MILL_D10\" M6\nG0 X0 Y0 Z50\nG1 F100 X60\nSTOPRE\nT=\"MILL_D10\" M6\nR1=$P_TOOLNO\nG0 Z50\nM30";
    let mut ch = channel(md, program);
    finish(&mut ch);
    let s = ch.snapshot();
    assert_eq!(alarm_numbers(&s), vec![6413]);
    assert_eq!(ch.r_param(1), 3.0);
    assert_eq!(s.tool, (3, 1));
    assert!((machine(&s, "Z") - 140.0).abs() < 1e-9, "{:?}", s.machine);
    assert_eq!(alarm_numbers(&s), vec![6413]);
}

#[test]
fn a_name_without_an_enabled_duplo_is_alarm_22069_with_its_line() {
    // Only one MILL_D10: once it is disabled in line 3, line 5 finds no tool ready.
    let md = "$TC_TP9[1]=1\n$TC_MOP2[1,1]=0.5\n";
    let program = "T=\"MILL_D10\" M6\nG0 X0 Y0 Z50\nG1 F100 X60\nSTOPRE\nT=\"MILL_D10\" M6\nM30";
    let mut ch = channel(md, program);
    finish(&mut ch);
    let s = ch.snapshot();
    let a = s.alarms.iter().find(|a| a.number == 22069).expect("22069");
    assert_eq!(a.line, Some(5));
    assert!(a.message.contains("MILL_D10"));
    // Disabled in the data from the start: the first block already fails.
    let mut ch = channel("$TC_TP8[1]=6\n", "T=\"MILL_D10\" M6\nM30");
    finish(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), vec![(22069, Some(1))]);
}

#[test]
fn without_monitored_tools_the_data_stay_untouched() {
    let mut ch = channel("", "T=\"MILL_D10\" M6\nG1 F1000 X10 Y0 Z50\nM30");
    let before = ch.machine_data().to_text();
    finish(&mut ch);
    assert_eq!(ch.machine_data().to_text(), before);
    assert!(!ch.config().tool_list.monitored);
}
