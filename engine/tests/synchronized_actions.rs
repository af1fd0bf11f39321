//! Motion-synchronous actions (Function Manual "Synchronized actions"): conditions checked in
//! every IPO cycle of the main run and actions that act in that cycle. Hand-worked on the
//! mill-3axis preset: IPO cycle 4 ms (MD10050 2 ms × MD10070 2), 3 m/s² on every axis,
//! FFWON (no following error at constant speed, so `$AA_IM` equals the setpoint there).

use nctwin_engine::{Channel, CommandError, Status};

const DT: f64 = 0.004;

fn channel() -> Channel {
    Channel::from_preset("mill-3axis", "").unwrap()
}

fn run_to_end(ch: &mut Channel) {
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < 1_000_000, "program does not end");
    }
}

fn steps(ch: &mut Channel, n: usize) {
    for _ in 0..n {
        ch.step();
    }
}

fn x(ch: &Channel) -> f64 {
    ch.axis_positions()[0]
}

fn alarm(ch: &Channel) -> (u32, Option<u32>) {
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm, "expected an alarm");
    (s.alarms[0].number, s.alarms[0].line)
}

#[test]
fn whenever_override_zero_stops_the_axis_within_one_cycle_of_the_limit() {
    // G1 X50 F600: 10 mm/s, 0.04 mm per IPO cycle. The cycle that first samples X > 20 sees
    // at most 20.04 (one cycle's travel past 20); in that cycle $AC_OVR = 0 brakes the path,
    // which from 10 mm/s at 3000 mm/s² takes 3.3 ms < one cycle, so it travels at most one
    // more cycle's 0.04 mm: X stops in (20, 20.08] and stays there while the action holds.
    let mut ch = channel();
    ch.run_program("ID=1 WHENEVER $AA_IM[X]>20 DO $AC_OVR=0\nG1 X50 F600\nM30").unwrap();
    steps(&mut ch, 1500); // 6 s: without the action X would be at 50 after ~5 s
    let stop = x(&ch);
    assert!(stop > 20.0 && stop <= 20.0 + 2.0 * 10.0 * DT + 1e-9, "X stopped at {stop}");
    steps(&mut ch, 100);
    assert_eq!(x(&ch), stop, "the axis stays while the condition holds");
    assert_eq!(ch.status(), Status::Running);
    let list = ch.sync_actions().list();
    assert_eq!(list.len(), 1);
    assert_eq!((list[0].id, list[0].kind, list[0].trigger), (Some(1), "modal", "WHENEVER"));
    assert_eq!(list[0].condition, "$AA_IM[X]>20");
    assert!(list[0].fired);
    // A reset ends the program and its modal action.
    ch.reset();
    assert!(ch.sync_actions().list().is_empty());
}

#[test]
fn when_input_deletes_the_distance_to_go_and_keeps_it_in_ac_delt() {
    // The input arrives between two IPO cycles; the next cycle's action ends the block where the
    // path is at that moment: $AC_DELT = 100 − X. The next block starts from there.
    let mut ch = channel();
    let program = "WHEN $A_IN[1]==1 DO DELDTG\nG1 X100 F600\nG1 Y10\nR1=$AC_DELT\nM30";
    ch.run_program(program).unwrap();
    steps(&mut ch, 750); // 3 s: X about 30, still moving
    let at = x(&ch);
    assert!(at > 20.0 && at < 40.0, "X = {at}");
    ch.set_signals(&[(1, true)], &[]).unwrap();
    ch.step();
    assert_eq!(x(&ch), at, "the path ends in the cycle the input arrived");
    assert!((ch.sync_actions().deleted - (100.0 - at)).abs() < 1e-9);
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    // G1 Y10 went from (at, 0) to (at, 10): X was not moved on to 100.
    assert!((x(&ch) - at).abs() < 1e-9, "X = {}", x(&ch));
    assert!((ch.axis_positions()[1] - 10.0).abs() < 1e-9);
    // The program reads $AC_DELT after the block (a main-run variable: it waits for it).
    assert!((ch.r_param(1) - (100.0 - at)).abs() < 1e-9, "R1 = {}", ch.r_param(1));
}

#[test]
fn deldtg_without_the_input_leaves_the_block_whole() {
    let mut ch = channel();
    ch.run_program("WHEN $A_IN[1]==1 DO DELDTG\nG1 X10 F600\nG1 Y10\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!([x(&ch), ch.axis_positions()[1]], [10.0, 10.0]);
    assert_eq!(ch.sync_actions().deleted, 0.0);
}

#[test]
fn every_counts_the_blocks_that_last_longer_than_a_tenth_of_a_second() {
    // $AC_TIME counts from the start of each block. G1 X10 at 10 mm/s lasts about 1 s: one
    // count. G1 X10.2 lasts 0.2 mm / 10 mm/s = 0.02 s plus at most the ramps (0.2 mm from
    // standstill at 3000 mm/s² takes 2·√(0.1/1500) ≈ 0.016 s): never past 0.1 s, no count.
    // G1 X20 again about 1 s: a count. G4 F0.3 dwells 0.3 s: a count. EVERY counts each
    // change of the condition from false to true once: 3.
    let mut ch = channel();
    let program = "ID=1 EVERY $AC_TIME>0.1 DO $AC_MARKER[1]=$AC_MARKER[1]+1\n\
                   G1 X10 F600\nG1 X10.2\nG1 X20\nG4 F0.3\nM30";
    ch.run_program(program).unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.sync_actions().markers[1], 3.0);
    // The program end ended the modal action.
    assert!(ch.sync_actions().list().is_empty());
}

#[test]
fn cancel_stops_a_modal_action() {
    // DO without a condition runs in every IPO cycle: between its block and CANCEL(1) lies a
    // dwell of 0.1 s = 25 cycles (±1 for the cycles of the two blocks). After CANCEL the
    // second dwell of 0.2 s (50 cycles) adds nothing.
    let mut ch = channel();
    ch.run_program("ID=1 DO $AC_MARKER[2]=$AC_MARKER[2]+1\nG4 F0.1\nCANCEL(1)\nG4 F0.2\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let n = ch.sync_actions().markers[2];
    assert!((24.0..=26.0).contains(&n), "{n} cycles");
}

#[test]
fn static_actions_survive_program_end_and_reset_until_cancelled() {
    let mut ch = channel();
    ch.run_program("IDS=2 WHENEVER $A_IN[2]==1 DO $A_OUT[3]=1\nID=3 DO $AC_PARAM[0]=1\nM30").unwrap();
    run_to_end(&mut ch);
    let list = ch.sync_actions().list();
    assert_eq!(list.len(), 1, "the modal ID=3 ended with the program");
    assert_eq!((list[0].id, list[0].kind, list[0].fired), (Some(2), "static", false));
    // In reset state, without a program: the input sets the output in the next cycle.
    ch.set_signals(&[(2, true)], &[]).unwrap();
    ch.step();
    assert_eq!(ch.digital_io().output(3), Some(true));
    ch.reset();
    assert_eq!(ch.sync_actions().list().len(), 1, "a reset leaves static actions");
    ch.set_signals(&[], &[(3, false)]).unwrap();
    ch.step();
    assert_eq!(ch.digital_io().output(3), Some(true), "still acting after the reset");
    ch.run_program("CANCEL(2)\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.sync_actions().list().is_empty());
}

#[test]
fn lock_and_unlock_suspend_and_resume_an_action() {
    let mut ch = channel();
    ch.run_program("ID=4 DO $AC_MARKER[3]=$AC_MARKER[3]+1\nLOCK(4)\nG4 F0.2\nUNLOCK(4)\nG4 F0.1\nM30").unwrap();
    run_to_end(&mut ch);
    // Locked during the 0.2 s dwell; counting again for the 0.1 s dwell (25 cycles ± 1) and the
    // cycle of its own block.
    let n = ch.sync_actions().markers[3];
    assert!((24.0..=27.0).contains(&n), "{n}");
}

#[test]
fn g70_reads_the_condition_in_inch() {
    // X > 1 inch is X > 25.4 mm: the action copies X (mm) once, in the first cycle past it.
    let mut ch = channel();
    ch.run_program("ID=1 WHEN G70 $AA_IM[X]>1 DO $AC_PARAM[0]=$AA_IM[X] M99\nG1 X30 F600\nM30").unwrap();
    run_to_end(&mut ch);
    let p = ch.sync_actions().params[0];
    assert!(p > 25.4 && p <= 25.4 + 10.0 * DT + 1e-9, "{p}");
}

#[test]
fn actions_write_r_parameters_and_outputs_and_put_out_m_functions() {
    let mut ch = channel();
    ch.take_events();
    ch.run_program("ID=1 WHEN $AA_IM[X]>=5 DO $R10=$AA_IM[X]*2 $A_OUT[5]=1 M99 H2=1.5\nG1 X10 F600\nM30").unwrap();
    let mut events = Vec::new();
    while ch.is_busy() {
        ch.step();
        events.extend(ch.take_events());
    }
    let r = ch.r_param(10);
    assert!((10.0..=10.0 + 2.0 * 10.0 * DT).contains(&r), "R10 = {r}");
    assert_eq!(ch.digital_io().output(5), Some(true));
    let aux: Vec<String> = events
        .iter()
        .filter_map(|e| match e {
            nctwin_engine::Event::AuxFunction { function, line: 1 } => Some(function.text()),
            _ => None,
        })
        .collect();
    assert_eq!(aux, ["M99", "H2=1.5"]);
}

#[test]
fn bad_syntax_is_refused_before_the_run_with_line_and_column() {
    let mut ch = channel();
    let err = ch.run_program("G0 X0\nWHENEVER $AA_IM[X]>20 $AC_OVR=0\nM30").unwrap_err();
    let CommandError::Syntax { line, errors, .. } = err else { panic!("{err:?}") };
    assert_eq!((line, errors[0].alarm, errors[0].column), (2, 12080, 23));
    for bad in ["WHEN DO M1", "ID=300 DO M1", "WHEN $A_IN[1]==1 DO", "WHEN ($A_IN[1]==1 DO M1", "DO R1=1"] {
        assert!(ch.run_program(bad).is_err(), "{bad} accepted");
    }
}

#[test]
fn names_a_synchronized_action_cannot_use_give_the_controls_alarms() {
    for (program, number) in [
        ("G0 X0\nWHEN $AA_IM[Q]>1 DO M1\nM30", 12550),
        ("G0 X0\nWHEN $A_IN[1]==1 DO $AA_IM[X]=1\nM30", 12584),
        ("G0 X0\nID=1 WHEN $A_IN[1]==1 DO DELDTG\nM30", 12571),
        // POSA is a program word; synchronized actions move command axes with POS.
        ("G0 X0\nWHEN $A_IN[1]==1 DO POSA[X]=10\nM30", 12571),
        ("G0 X0\nWHEN $P_EP[X]>1 DO M1\nM30", 12550),
    ] {
        let mut ch = channel();
        ch.run_program(program).unwrap();
        run_to_end(&mut ch);
        assert_eq!(alarm(&ch), (number, Some(2)), "{program}");
    }
}

#[test]
fn a_marker_index_out_of_range_raises_an_alarm_in_the_main_run() {
    let mut ch = channel();
    ch.run_program("DO $AC_MARKER[8]=1\nG1 X1 F600\nM30").unwrap();
    run_to_end(&mut ch);
    assert_eq!(alarm(&ch), (17020, Some(1)));
}

#[test]
fn inputs_replayed_at_their_logged_cycle_counts_give_the_same_run() {
    let program =
        "WHEN $A_IN[1]==1 DO DELDTG\nG1 X100 F600\nG1 Y10\nID=2 WHENEVER $A_INA[1]>1 DO $AC_OVR=50\nG1 X0\nM30";
    let mut first = channel();
    first.run_program(program).unwrap();
    steps(&mut first, 600);
    first.set_signals(&[(1, true)], &[]).unwrap();
    steps(&mut first, 400);
    first.set_analog_inputs(&[(1, 2.0)]).unwrap();
    run_to_end(&mut first);
    let log: Vec<_> = first.input_log().cloned().collect();
    assert_eq!(log.iter().map(|r| r.tick).collect::<Vec<_>>(), [600, 1000]);

    let mut again = channel();
    again.run_program(program).unwrap();
    let mut next = log.iter().peekable();
    while again.is_busy() {
        while let Some(r) = next.next_if(|r| r.tick == again.ticks()) {
            again.apply_inputs(r).unwrap();
        }
        again.step();
    }
    assert_eq!(again.ticks(), first.ticks(), "the same number of cycles");
    assert_eq!(again.axis_positions(), first.axis_positions(), "bit for bit");
    assert_eq!(again.sync_actions().deleted.to_bits(), first.sync_actions().deleted.to_bits());
}

#[test]
fn the_checkpoint_keeps_the_inputs_and_not_the_outputs() {
    let mut ch = channel();
    ch.set_signals(&[(5, true)], &[(2, true)]).unwrap();
    ch.set_analog_inputs(&[(3, -1.25)]).unwrap();
    let state = ch.resume_state();
    let mut restarted = channel();
    restarted.restore_resume_state(&state).unwrap();
    assert_eq!(restarted.digital_io().input(5), Some(true));
    assert_eq!(restarted.digital_io().output(2), Some(false), "outputs are off after power on");
    assert_eq!(restarted.analog_io().0, [0.0, 0.0, -1.25, 0.0]);
}

#[test]
fn analog_inputs_are_bounded() {
    let mut ch = channel();
    assert!(ch.set_analog_inputs(&[(5, 1.0)]).is_err());
    assert!(ch.set_analog_inputs(&[(1, f64::NAN)]).is_err());
    assert_eq!(ch.analog_io().0, [0.0; 4]);
}

#[test]
fn programs_read_markers_timers_and_analog_inputs_of_the_main_run() {
    // The timer starts in the cycle after its action's block and is read in the block after
    // the 0.5 s dwell: 0.5 s within two IPO cycles. The marker counts EVERY's one edge.
    let mut ch = channel();
    ch.set_analog_inputs(&[(1, 2.5)]).unwrap();
    let program = "ID=1 WHEN TRUE DO $AC_TIMER[1]=0 $AC_MARKER[4]=7 $A_OUTA[2]=$A_INA[1]+1\n\
                   G4 F0.5\nR4=$AC_TIMER[1]\nR5=$AC_MARKER[4]\nR6=$A_INA[1]\nR7=$A_OUTA[2]\nM30";
    ch.run_program(program).unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let t = ch.r_param(4);
    assert!((t - 0.5).abs() <= 2.0 * DT + 1e-9, "timer {t}");
    assert_eq!([ch.r_param(5), ch.r_param(6), ch.r_param(7)], [7.0, 2.5, 3.5]);
    // Program blocks may not write the analog inputs.
    let mut ch = channel();
    ch.run_program("G0 X1\n$A_INA[1]=1\nM30").unwrap();
    run_to_end(&mut ch);
    assert_eq!(alarm(&ch), (17070, Some(2)));
}

#[test]
fn bound_limits_a_value_in_an_action_as_in_the_program() {
    // BOUND(min, max, value) clamps: DO $R1=BOUND(2, 5, $AA_IM[X]) while X runs 0 → 10 holds
    // the last X at the block's end, clamped to 5; BOUND(2, 5, 1) = 2 (below the range).
    let mut ch = channel();
    ch.run_program("G0 X0\nID=1 WHENEVER $AA_IM[X]>=0 DO $R1=BOUND(2,5,$AA_IM[X]) $R2=BOUND(2,5,1)\nG1 X10 F3000\nM30")
        .unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!((ch.r_param(1), ch.r_param(2)), (5.0, 2.0));
    // Three arguments, as in the program.
    let mut ch = channel();
    ch.run_program("ID=1 WHENEVER TRUE DO $R1=BOUND(2,5)\nM30").unwrap();
    run_to_end(&mut ch);
    assert_eq!(alarm(&ch).0, 12080);
}
