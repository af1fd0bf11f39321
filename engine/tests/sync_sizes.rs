//! The sizes of the synchronized actions' data and of the NCK signals come from the machine
//! data (MD28254 `$MC_MM_NUM_AC_PARAM`, MD28256 `$MC_MM_NUM_AC_MARKER`, MD28258
//! `$MC_MM_NUM_AC_TIMER`, MD10350/MD10360 `$MN_FASTIO_DIG_NUM_INPUTS/OUTPUTS` in bytes of 8
//! signals, MD10300/MD10310 `$MN_FASTIO_ANA_NUM_INPUTS/OUTPUTS` in signals): the last element
//! works, one beyond is alarm 17020 in the main run (in an action or a program block) and an
//! error from outside (the REST side's 400). MD28250 `$MC_MM_NUM_SYNC_ELEMENTS` bounds the active
//! actions in elements: one beyond is alarm 14751 at the action's line.

use nctwin_engine::{Channel, Status};

fn run(md: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill-3axis", md).expect("machine data");
    ch.run_program(program).expect("program starts");
    for _ in 0..100_000 {
        if !ch.is_busy() {
            return ch;
        }
        ch.step();
    }
    panic!("the program does not end");
}

/// The program ran to its end without an alarm.
fn ok(md: &str, program: &str) -> Channel {
    let ch = run(md, program);
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{program:?} with {md:?}: {:?}", s.alarms);
    ch
}

/// The program ended in alarm 17020 at `line`.
fn index_alarm(md: &str, program: &str, line: u32) {
    let s = run(md, program).snapshot();
    assert_eq!(s.status, Status::Alarm, "{program:?} with {md:?}: expected an alarm");
    assert_eq!((s.alarms[0].number, s.alarms[0].line), (17020, Some(line)), "{:?}", s.alarms[0]);
}

#[test]
fn markers_follow_md28256() {
    let md = "$MC_MM_NUM_AC_MARKER=20";
    let ch = ok(md, "DO $AC_MARKER[19]=4\nG1 X1 F600\nR1=$AC_MARKER[19]\nM30");
    assert_eq!(ch.r_param(1), 4.0);
    index_alarm(md, "DO $AC_MARKER[20]=1\nG1 X1 F600\nM30", 1);
    // A computed index is checked in the main run too.
    index_alarm(md, "DO $AC_MARKER[$AC_PARAM[0]+20]=1\nG1 X1 F600\nM30", 1);
    // In a program block: the list handed to preparation has the configured length.
    index_alarm(md, "G1 X1 F600\nR1=$AC_MARKER[20]\nM30", 2);
    // The default: 8 markers (0..7).
    index_alarm("", "DO $AC_MARKER[8]=1\nG1 X1 F600\nM30", 1);
}

#[test]
fn parameters_follow_md28254() {
    let md = "$MC_MM_NUM_AC_PARAM=60";
    let ch = ok(md, "DO $AC_PARAM[59]=2.5\nG1 X1 F600\nR1=$AC_PARAM[59]\nM30");
    assert_eq!(ch.r_param(1), 2.5);
    index_alarm(md, "DO $AC_PARAM[60]=1\nG1 X1 F600\nM30", 1);
    index_alarm("", "DO $AC_PARAM[50]=1\nG1 X1 F600\nM30", 1);
    // Fewer than the default: 10 parameters, 0..9.
    index_alarm("$MC_MM_NUM_AC_PARAM=10", "WHEN $AC_PARAM[10]>0 DO M99\nG1 X1 F600\nM30", 1);
}

#[test]
fn timers_follow_md28258() {
    let md = "$MC_MM_NUM_AC_TIMER=2";
    ok(md, "DO $AC_TIMER[1]=0\nG1 X1 F600\nM30");
    index_alarm(md, "DO $AC_TIMER[2]=0\nG1 X1 F600\nM30", 1);
}

#[test]
fn digital_signals_follow_md10350_and_md10360_in_bytes() {
    // Two bytes of inputs: $A_IN[1..16]; one byte of outputs: $A_OUT[1..8].
    let md = "$MN_FASTIO_DIG_NUM_INPUTS=2\n$MN_FASTIO_DIG_NUM_OUTPUTS=1";
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    assert_eq!(ch.digital_io().counts(), (16, 8));
    ch.set_signals(&[(16, true)], &[(8, true)]).unwrap();
    let refused = ch.set_signals(&[(17, true)], &[]).unwrap_err().to_string();
    assert!(refused.contains("1..16") && refused.contains("MD10350"), "{refused}");
    let refused = ch.set_signals(&[], &[(9, true)]).unwrap_err().to_string();
    assert!(refused.contains("1..8") && refused.contains("MD10360"), "{refused}");
    assert_eq!((ch.digital_io().input(16), ch.digital_io().output(8)), (Some(true), Some(true)));
    let ch = ok(md, "R1=$A_IN[16]\n$A_OUT[8]=1\nDO $A_OUT[7]=1\nG1 X1 F600\nM30");
    assert_eq!(ch.digital_io().output(7), Some(true));
    index_alarm(md, "R1=$A_IN[17]\nM30", 1);
    index_alarm(md, "$A_OUT[9]=1\nM30", 1);
    index_alarm(md, "WHEN $A_IN[17]==1 DO M99\nG1 X1 F600\nM30", 1);
    index_alarm(md, "DO $A_OUT[9]=1\nG1 X1 F600\nM30", 1);
    // The default: 2 bytes, 16 of each (the "16 digital inputs and outputs").
    assert_eq!(Channel::from_preset("mill-3axis", "").unwrap().digital_io().counts(), (16, 16));
}

#[test]
fn analog_signals_follow_md10300_and_md10310() {
    let md = "$MN_FASTIO_ANA_NUM_INPUTS=6\n$MN_FASTIO_ANA_NUM_OUTPUTS=2";
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    assert_eq!((ch.analog_io().0.len(), ch.analog_io().1.len()), (6, 2));
    ch.set_analog_inputs(&[(6, 1.5)]).unwrap();
    let refused = ch.set_analog_inputs(&[(7, 1.0)]).unwrap_err().to_string();
    assert!(refused.contains("1..6") && refused.contains("MD10300"), "{refused}");
    ch.run_program("DO $A_OUTA[2]=$A_INA[6]*2\nG1 X1 F600\nR1=$A_INA[6]\nR2=$A_OUTA[2]\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (1.5, 3.0));
    index_alarm(md, "DO $A_OUTA[3]=1\nG1 X1 F600\nM30", 1);
    index_alarm(md, "WHEN $A_INA[7]>1 DO M99\nG1 X1 F600\nM30", 1);
    index_alarm(md, "R1=$A_INA[7]\nM30", 1);
    // The default: 4 of each.
    let ch = Channel::from_preset("mill-3axis", "").unwrap();
    assert_eq!((ch.analog_io().0.len(), ch.analog_io().1.len()), (4, 4));
}

#[test]
fn the_sizes_change_with_machine_data_applied_in_reset_state() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.apply_machine_data("$MC_MM_NUM_AC_MARKER=12\n$MN_FASTIO_DIG_NUM_INPUTS=1").unwrap();
    assert_eq!(ch.digital_io().counts(), (8, 16));
    ch.run_program("DO $AC_MARKER[11]=1\nG1 X1 F600\nR1=$AC_MARKER[11]\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    assert_eq!(ch.r_param(1), 1.0);
}

/// The program ended in alarm 14751 (resources for synchronized actions) at `line`.
fn resources_alarm(md: &str, program: &str, line: u32) {
    let s = run(md, program).snapshot();
    assert_eq!(s.status, Status::Alarm, "{program:?} with {md:?}: expected an alarm");
    assert_eq!((s.alarms[0].number, s.alarms[0].line), (14751, Some(line)), "{:?}", s.alarms[0]);
}

/// `n` modal actions `ID=1..n WHEN $AC_TIME>100 DO $AC_MARKER[1]=1`, 4 elements each (2
/// operands in the condition, one assignment of 2), then a move.
fn actions(n: u32) -> String {
    let mut text: String = (1..=n).map(|id| format!("ID={id} WHEN $AC_TIME>100 DO $AC_MARKER[1]=1\n")).collect();
    text.push_str("G1 X1 F600\nM30");
    text
}

#[test]
fn active_actions_are_bounded_by_md28250_in_elements() {
    // Two actions of 4 elements fill 8; the third (line 3) does not fit.
    let md = "$MC_MM_NUM_SYNC_ELEMENTS=8";
    ok(md, &actions(2));
    resources_alarm(md, &actions(3), 3);
    // Elements, not actions: 4 operands ($AA_IM[X], 20, $AA_IM[Y], 5) and one assignment (2)
    // make 6; a compound value adds its further operands: $AC_MARKER[1]+1 is 2 + 1 = 3,
    // raised to the minimum of 4.
    let six = "ID=1 WHENEVER ($AA_IM[X]>20) AND ($AA_IM[Y]<5) DO $AC_OVR=50\nG1 X1 F600\nM30";
    ok("$MC_MM_NUM_SYNC_ELEMENTS=6", six);
    resources_alarm("$MC_MM_NUM_SYNC_ELEMENTS=5", six, 1);
    let count = "ID=1 DO $AC_MARKER[1]=$AC_MARKER[1]+1\nID=2 DO $AC_MARKER[2]=$AC_MARKER[2]+1\nG1 X1 F600\nM30";
    ok(md, count);
    resources_alarm("$MC_MM_NUM_SYNC_ELEMENTS=7", count, 2);
    // An action with the same ID replaces the old one, CANCEL frees its elements.
    let md = "$MC_MM_NUM_SYNC_ELEMENTS=4";
    ok(md, "ID=1 WHEN $AC_TIME>100 DO M99\nID=1 WHEN $AC_TIME>200 DO M98\nG1 X1 F600\nM30");
    ok(md, "ID=1 WHEN $AC_TIME>100 DO M99\nG1 X1 F600\nCANCEL(1)\nID=2 WHEN $AC_TIME>100 DO M98\nG1 X2\nM30");
    resources_alarm(md, "ID=1 WHEN $AC_TIME>100 DO M99\nG1 X1 F600\nID=2 WHEN $AC_TIME>100 DO M98\nG1 X2\nM30", 3);
}

#[test]
fn the_default_159_elements_hold_39_small_actions() {
    // 39 × 4 = 156 ≤ 159; the 40th needs 160.
    ok("", &actions(39));
    resources_alarm("", &actions(40), 40);
    // Beyond the elements NCTwin keeps at most 64 active actions (its schedule's masks).
    let md = "$MC_MM_NUM_SYNC_ELEMENTS=32000";
    ok(md, &actions(64));
    resources_alarm(md, &actions(65), 65);
}

/// Found by `robustness_language.rs`: with MD28254 = 0 `R3=$AC_PARAM[0]` panicked (the alarm's
/// text computed the last valid index as 0 − 1). Every list may be sized to nothing: any index
/// of it is then 17020 at its line (PM Job Planning: the data exist only as far as the machine
/// data make them), in a program block, in an action's compiled index and in one computed
/// in the main run.
#[test]
fn lists_sized_to_nothing_refuse_every_index() {
    index_alarm("$MC_MM_NUM_AC_PARAM=0", "R3=$AC_PARAM[0]", 1);
    index_alarm("$MC_MM_NUM_AC_PARAM=0", "G1 X1 F600\nR3=$AC_PARAM[0]\nM30", 2);
    index_alarm("$MC_MM_NUM_AC_MARKER=0", "R3=$AC_MARKER[0]\nM30", 1);
    index_alarm("$MC_MM_NUM_AC_TIMER=0", "R3=$AC_TIMER[0]\nM30", 1);
    index_alarm("$MN_FASTIO_ANA_NUM_INPUTS=0", "R3=$A_INA[1]\nM30", 1);
    index_alarm("$MN_FASTIO_ANA_NUM_OUTPUTS=0", "R3=$A_OUTA[1]\nM30", 1);
    index_alarm("$MC_MM_NUM_AC_PARAM=0", "DO $AC_PARAM[0]=1\nG1 X1 F600\nM30", 1);
    index_alarm("$MC_MM_NUM_AC_PARAM=0", "WHENEVER $AC_PARAM[$AC_MARKER[0]]>1 DO M99\nG1 X1 F600\nM30", 1);
    index_alarm("$MC_MM_NUM_AC_MARKER=0", "DO $AC_MARKER[$AC_PARAM[0]]=1\nG1 X1 F600\nM30", 1);
    index_alarm("$MN_FASTIO_ANA_NUM_OUTPUTS=0", "DO $A_OUTA[$AC_PARAM[0]+1]=1\nG1 X1 F600\nM30", 1);
    let s = run("$MC_MM_NUM_AC_PARAM=0", "R3=$AC_PARAM[0]").snapshot();
    assert!(s.alarms[0].message.contains("$AC_PARAM: 0 (none: size 0)"), "{}", s.alarms[0].message);
}
