//! Synchronized actions whose condition reads only main-run data (signals, markers,
//! parameters): the main run evaluates such a condition again only after one of its inputs
//! changed (`channel/sync/eval.rs`). These runs check that the actions still act in the cycle
//! a real control would: hand-worked on the mill-3axis preset, IPO cycle 4 ms, G1 F600 =
//! 10 mm/s = 0.04 mm per cycle, 3 m/s² (10 mm/s is reached or lost in 3.3 ms, within one
//! cycle), FFWON (no following error at constant speed).

use nctwin_engine::{Channel, Status};

use crate::settle;
use settle::{run_to_end, steps};

fn channel() -> Channel {
    Channel::from_preset("mill-3axis", "").unwrap()
}

fn x(ch: &Channel) -> f64 {
    ch.axis_positions()[0]
}

#[test]
fn an_input_condition_acts_each_time_the_input_changes() {
    // The condition was false for 250 cycles (1 s, X about 10): the input set between two
    // cycles stops the path in the next one (at most one more cycle's 0.04 mm while it
    // brakes), cleared again the path goes on (10 mm/s: 0.4 mm in 10 cycles, less the ramp).
    let mut ch = channel();
    ch.run_program("ID=1 WHENEVER $A_IN[1]==1 DO $AC_OVR=0\nG1 X50 F600\nM30").unwrap();
    steps(&mut ch, 250);
    let at = x(&ch);
    assert!(at > 9.0 && at < 10.5, "X = {at}");
    ch.set_signals(&[(1, true)], &[]).unwrap();
    steps(&mut ch, 2);
    let stop = x(&ch);
    assert!(stop >= at && stop <= at + 0.04 + 1e-9, "stopped at {stop} from {at}");
    steps(&mut ch, 100);
    assert_eq!(x(&ch), stop, "held while the input is set");
    ch.set_signals(&[(1, false)], &[]).unwrap();
    steps(&mut ch, 10);
    let moved = x(&ch) - stop;
    assert!(moved > 0.3 && moved <= 0.4 + 1e-9, "moved {moved} in 10 cycles");
}

#[test]
fn a_marker_written_by_a_lower_id_acts_on_a_higher_id_in_the_same_cycle() {
    // ID=1 sets marker 1 in the first cycle 0.5 s into the block (X about 5); ID=2, checked
    // after it in the same cycle, had been false in every cycle before and now stops the
    // path: X stays within one cycle's travel of 5.
    let mut ch = channel();
    let program = "ID=1 WHEN $AC_TIME>0.5 DO $AC_MARKER[1]=1\n\
                   ID=2 WHENEVER $AC_MARKER[1]==1 DO $AC_OVR=0\nG1 X50 F600\nM30";
    ch.run_program(program).unwrap();
    steps(&mut ch, 500);
    let stop = x(&ch);
    assert!(stop > 4.9 && stop < 5.1, "X stopped at {stop}");
    steps(&mut ch, 50);
    assert_eq!(x(&ch), stop);
    assert_eq!(ch.sync_actions().markers[1], 1.0);
}

#[test]
fn every_on_an_analog_input_counts_its_rising_edges() {
    // EVERY acts once per change of its condition from false to true: 6 V (edge: 1), 7 V
    // (still true: no count), 0 V (false), 9 V (edge: 2).
    let mut ch = channel();
    ch.run_program("ID=1 EVERY $A_INA[1]>5 DO $AC_MARKER[1]=$AC_MARKER[1]+1\nG1 X50 F600\nM30").unwrap();
    for volts in [6.0, 7.0, 0.0, 9.0] {
        ch.set_analog_inputs(&[(1, volts)]).unwrap();
        steps(&mut ch, 10);
    }
    assert_eq!(ch.sync_actions().markers[1], 2.0);
}

#[test]
fn from_acts_in_every_cycle_once_its_condition_held() {
    // The input is high for one cycle only; FROM then adds 1 in every cycle: 20 cycles, 20.
    let mut ch = channel();
    ch.run_program("ID=1 FROM $A_INA[2]>1 DO $AC_PARAM[3]=$AC_PARAM[3]+1\nG1 X50 F600\nM30").unwrap();
    steps(&mut ch, 5);
    ch.set_analog_inputs(&[(2, 2.0)]).unwrap();
    ch.step();
    ch.set_analog_inputs(&[(2, 0.0)]).unwrap();
    steps(&mut ch, 19);
    assert_eq!(ch.sync_actions().params[3], 20.0);
}

#[test]
fn reset_of_an_action_lets_when_act_again_on_an_unchanged_condition() {
    // WHEN acts once; RESET(1) makes it act again the first cycle its condition holds, and
    // the input still stands at 6 V: two counts, though the input never changed.
    let mut ch = channel();
    ch.set_analog_inputs(&[(1, 6.0)]).unwrap();
    let program = "ID=1 WHEN $A_INA[1]>5 DO $AC_MARKER[3]=$AC_MARKER[3]+1\n\
                   G1 X1 F600\nRESET(1)\nG1 X2\nM30";
    ch.run_program(program).unwrap();
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.sync_actions().markers[3], 2.0);
}

#[test]
fn a_digital_output_written_by_one_action_is_read_by_the_next() {
    // ID=1 sets output 4 once X passes 1 (0.1 s at 10 mm/s); ID=2 reads output 4 and stops
    // the path in that same cycle: X within one cycle's travel past 1.
    let mut ch = channel();
    let program = "ID=1 WHEN $AA_IM[X]>1 DO $A_OUT[4]=1\n\
                   ID=2 WHENEVER $A_OUT[4]==1 DO $AC_OVR=0\nG1 X50 F600\nM30";
    ch.run_program(program).unwrap();
    steps(&mut ch, 200);
    let stop = x(&ch);
    assert!(stop > 1.0 && stop <= 1.0 + 2.0 * 0.04 + 1e-9, "X stopped at {stop}");
    assert_eq!(ch.digital_io().output(4), Some(true));
    assert_eq!(ch.status(), Status::Running);
}

#[test]
fn workpiece_position_reads_through_a_rotated_frame() {
    // TRANS X10 and AROT Z90: a workpiece point (wx, wy) is at machine (10 − wy, wx). G1 X50
    // in the workpiece system from machine (0, 0) = workpiece (0, 10) moves machine Y from 0
    // to 50 with machine X at 0. $AA_IW[X] > 5 is machine Y > 5: the path stops within one
    // cycle's travel past it (at most two cycles' 0.04 mm).
    let mut ch = channel();
    let program = "TRANS X10\nAROT Z90\nID=1 WHENEVER $AA_IW[X]>5 DO $AC_OVR=0\nG1 X50 F600\nM30";
    ch.run_program(program).unwrap();
    steps(&mut ch, 1000);
    let p = ch.axis_positions();
    assert!(p[0].abs() < 1e-9, "machine X = {}", p[0]);
    assert!(p[1] > 5.0 && p[1] <= 5.0 + 2.0 * 0.04 + 1e-9, "machine Y = {}", p[1]);
}

#[test]
fn ten_actions_on_a_program_give_the_same_run_as_their_effects_predict() {
    // Ten actions of which only one acts: ID=9 copies $AA_IM[Z] into $AC_PARAM[2] in every
    // cycle. At the end Z stands at -2 and so does the parameter; no override was applied,
    // so the program takes as long as without them (G1 X30 at 10 mm/s: 3 s, 750 cycles, and
    // G1 Z-2 at 10 mm/s: 0.2 s, plus ramps of a few cycles).
    let header = "ID=1 WHENEVER $AA_IM[X]>1000 DO $AC_OVR=50\n\
        ID=2 EVERY $AC_TIME>0.5 DO $AC_MARKER[1]=$AC_MARKER[1]+1\n\
        ID=3 FROM $AA_IW[Y]>500 DO $AC_PARAM[1]=1\n\
        ID=4 WHEN $AC_DTEB<-1 DO M99\n\
        ID=5 WHENEVER SQRT(POT($AA_VACTM[X])+POT($AA_VACTM[Y]))>1000000 DO $AC_OVR=90\n\
        ID=6 WHENEVER $AC_VACTB>500000 DO $AC_OVR=80\n\
        ID=7 WHENEVER $A_IN[1]==1 DO $AC_OVR=0\n\
        ID=8 WHENEVER $A_INA[1]>5 DO $AC_OVR=10\n\
        ID=9 DO $AC_PARAM[2]=$AA_IM[Z]\n\
        ID=10 WHENEVER ($AA_IW[X]>$AC_PARAM[3]+2000) AND ($AA_IW[Z]<-100) DO $AC_MARKER[2]=1\n";
    let mut ch = channel();
    ch.run_program(&format!("{header}G1 X30 F600\nG1 Z-2\nM0\nM30")).unwrap();
    let mut ticks = 0;
    while ch.status() == Status::Running {
        ch.step();
        ticks += 1;
        assert!(ticks < 10_000);
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert!((800..820).contains(&ticks), "{ticks} cycles");
    // Actions run before the cycle's interpolation: in the last cycle of the block ID=9 read
    // the position of the cycle before (Z = -1.96). Stopped at M0 the actions go on.
    assert!((ch.sync_actions().params[2] + 1.96).abs() < 1e-9);
    steps(&mut ch, 1);
    let s = ch.sync_actions();
    assert_eq!(s.params[2], -2.0);
    // ID=2: G1 X30 lasts 3 s (> 0.5 s: one count), G1 Z-2 0.2 s (none).
    assert_eq!((s.markers[1], s.markers[2], s.params[1]), (1.0, 0.0, 0.0));
}
