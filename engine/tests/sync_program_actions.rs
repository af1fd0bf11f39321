//! The program-facing actions of synchronized actions (Function Manual "Synchronized actions"):
//! STOPREOF, RDISABLE, PRESETON, SETM/CLEARM with WAITM, and technology cycles. Hand-worked
//! on mill-3axis: IPO cycle 4 ms, 3 m/s² per axis; `G1 F600` is 10 mm/s, 0.04 mm per cycle.

use nctwin_engine::{Channel, Status};

use crate::settle;
use settle::{run_to_end, steps};

fn channel() -> Channel {
    Channel::from_preset("mill-3axis", "").unwrap()
}

fn pos(ch: &Channel, k: usize) -> f64 {
    ch.axis_positions()[k]
}

fn first_alarm(ch: &Channel) -> Option<(u32, Option<u32>)> {
    ch.snapshot().alarms.first().map(|a| (a.number, a.line))
}

#[test]
fn stopreof_ends_the_preprocessing_stop_when_its_condition_holds() {
    // R1=$AA_IM[X] waits for the main run. Without STOPREOF it reads X at the end of the
    // block (40); with it, in the cycle after the action ran at X = 20 (X one or two cycles'
    // 0.04 mm further).
    let mut ch = channel();
    ch.run_program("WHEN $AA_IM[X]>=20 DO STOPREOF\nG1 X40 F600\nR1=$AA_IM[X]\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let r1 = ch.r_param(1);
    assert!((20.0..20.1).contains(&r1), "R1 = {r1}");
    assert!((pos(&ch, 0) - 40.0).abs() < 1e-9, "the path went on to 40");

    let mut ch = channel();
    ch.run_program("G1 X40 F600\nR1=$AA_IM[X]\nM30").unwrap();
    run_to_end(&mut ch);
    assert!((ch.r_param(1) - 40.0).abs() < 1e-9, "without STOPREOF: R1 = {}", ch.r_param(1));
}

#[test]
fn stopreof_in_a_modal_action_is_refused() {
    let mut ch = channel();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=20 DO STOPREOF\nG1 X40 F600\nM30").unwrap();
    run_to_end(&mut ch);
    assert_eq!(first_alarm(&ch), Some((12571, Some(1))));
}

#[test]
fn rdisable_holds_the_next_block_until_the_input_is_set() {
    // From X ≥ 5 on, the read-in is disabled while input 1 is 0: the block G1 X10 runs to its
    // end (1 s, about 251 cycles), G1 Y10 waits for the input.
    let mut ch = channel();
    ch.run_program("ID=1 WHENEVER ($AA_IM[X]>=5) AND ($A_IN[1]==0) DO RDISABLE\nG1 X10 F600\nG1 Y10\nM30").unwrap();
    steps(&mut ch, 400);
    assert!((pos(&ch, 0) - 10.0).abs() < 1e-9, "X = {}", pos(&ch, 0));
    assert_eq!(pos(&ch, 1), 0.0);
    assert_eq!(ch.status(), Status::Running);
    steps(&mut ch, 100);
    assert_eq!(pos(&ch, 1), 0.0, "still held");
    ch.set_signals(&[(1, true)], &[]).unwrap();
    steps(&mut ch, 3);
    assert!(pos(&ch, 1) > 0.0, "Y starts within the cycles after the input arrived");
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert!((pos(&ch, 1) - 10.0).abs() < 1e-9);
}

#[test]
fn a_modal_rdisable_holds_even_the_first_block() {
    let mut ch = channel();
    ch.run_program("ID=1 WHENEVER $A_IN[1]==0 DO RDISABLE\nG1 X10 F600\nM30").unwrap();
    steps(&mut ch, 100);
    assert_eq!(pos(&ch, 0), 0.0);
    ch.set_signals(&[(1, true)], &[]).unwrap();
    run_to_end(&mut ch);
    assert!((pos(&ch, 0) - 10.0).abs() < 1e-9);
}

#[test]
fn preseton_sets_the_actual_value_without_motion() {
    // At X ≥ 5 the Y axis (standing at 0) becomes 100 in the machine system; the path goes on.
    let mut ch = channel();
    ch.run_program("WHEN $AA_IM[X]>=5 DO PRESETON(Y,100)\nG1 X10 F600\nR2=$AA_IM[Y]\nM30").unwrap();
    let mut max_step: f64 = 0.0;
    let mut last = pos(&ch, 1);
    while ch.is_busy() {
        ch.step();
        max_step = max_step.max((pos(&ch, 1) - last).abs());
        last = pos(&ch, 1);
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(pos(&ch, 1), 100.0);
    assert_eq!(max_step, 100.0, "one jump, no motion");
    assert_eq!(ch.r_param(2), 100.0);
    assert!((pos(&ch, 0) - 10.0).abs() < 1e-9);
}

#[test]
fn preseton_on_the_moving_path_axis_raises_20141() {
    let mut ch = channel();
    ch.run_program("WHEN $AA_IM[X]>=5 DO PRESETON(X,0)\nG1 X10 F600\nM30").unwrap();
    run_to_end(&mut ch);
    assert_eq!(first_alarm(&ch).map(|a| a.0), Some(20141));
}

#[test]
fn setm_and_clearm_set_the_channels_wait_markers() {
    let mut ch = channel();
    let program = "ID=1 WHEN $AA_IM[X]>=5 DO SETM(3)\nID=2 WHEN $AA_IM[X]>=8 DO SETM(70) CLEARM(3)\nG1 X10 F600\nWAITM(3,1)\nWAITMC(70,1)\nM30";
    ch.run_program(program).unwrap();
    steps(&mut ch, 150); // X ≈ 6
    assert_eq!(ch.wait_markers(), 1 << 3);
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.wait_markers(), 1 << 70, "one channel: WAITM/WAITMC wait for nothing");
    ch.reset();
    assert_eq!(ch.wait_markers(), 0);
    for (program, number) in [("DO SETM(128)\nG1 X1 F600\nM30", 12560), ("WAITM(1,2)\nM30", 12560)] {
        let mut ch = channel();
        ch.run_program(program).unwrap();
        run_to_end(&mut ch);
        assert_eq!(first_alarm(&ch).map(|a| a.0), Some(number), "{program}");
    }
}

#[test]
fn a_technology_cycle_runs_block_by_block_and_waits_for_its_axes() {
    // LOADER: Y to 2 at FA 600 (10 mm/s: 0.2 s + 3.3 ms ≈ 51 cycles), then back to 0
    // (≈ 51 cycles), then one count. Called at X ≥ 2 (about cycle 51); X's block takes 4 s.
    let mut ch = channel();
    ch.store_program(
        "LOADER",
        "PROC LOADER\nN10 POS[Y]=2 FA[Y]=600 ; out\nN20 POS[Y]=0\n$AC_MARKER[1]=$AC_MARKER[1]+1\nM17\n",
    )
    .unwrap();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=2 DO LOADER\nG1 X40 F600\nR3=$AC_MARKER[1]\nM30").unwrap();
    steps(&mut ch, 51 + 40);
    let y = pos(&ch, 1);
    assert!(y > 1.0 && y < 2.0, "Y on its way out: {y}");
    steps(&mut ch, 30); // ≈ cycle 121: arrived at 2, coming back
    let y = pos(&ch, 1);
    assert!(y > 0.0 && y < 2.0, "Y on its way back: {y}");
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(pos(&ch, 1), 0.0);
    assert_eq!(ch.r_param(3), 1.0, "the cycle's last block ran once");
}

#[test]
fn a_missing_technology_cycle_is_an_alarm_at_the_calling_line() {
    let mut ch = channel();
    ch.run_program("G1 X1 F600\nID=1 WHEN $AA_IM[X]>=2 DO NOSUCH\nM30").unwrap();
    run_to_end(&mut ch);
    assert_eq!(first_alarm(&ch), Some((12550, Some(2))));
}
