//! `$A_INA[n]` and `$AC_DELT` read in program blocks (not only in synchronized actions): both
//! are main-run variables, so the block reading them waits until the main run has caught up
//! (the control's implicit preprocessing stop) and reads the value of that moment.
//! mill-3axis: IPO cycle 4 ms; `G1 X.. F600` is 10 mm/s, 0.04 mm per cycle.

#[allow(dead_code)] // the shared helpers this file does not use
mod settle;

use nctwin_engine::Channel;
use settle::{channel, run_to_end, steps};

fn alarm_free(ch: &Channel) {
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
}

#[test]
fn an_analog_input_set_during_a_dwell_is_read_by_the_block_after_it() {
    // Without synchronized actions: the dwell runs 1 s (250 cycles); input 2 is set after
    // 0.4 s. Had the block R1=.. been prepared ahead it would read 0; it waits and reads 7.5.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G4 F1\nR1=$A_INA[2]\nR2=$A_INA[1]\nM30").unwrap();
    steps(&mut ch, 100);
    ch.set_analog_inputs(&[(2, 7.5)]).unwrap();
    run_to_end(&mut ch);
    alarm_free(&ch);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (7.5, 0.0));
}

#[test]
fn an_analog_input_number_outside_the_image_is_17020() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G0 X1\nR1=$A_INA[5]\nM30").unwrap();
    run_to_end(&mut ch);
    let a = &ch.snapshot().alarms[0];
    assert_eq!((a.number, a.line), (17020, Some(2)));
}

#[test]
fn ac_delt_holds_the_distance_a_block_modal_deldtg_left() {
    // The action deletes the rest of G1 X20 once X has passed 5: the path stops in that cycle,
    // at most one cycle's travel (0.04 mm) beyond 5, and $AC_DELT = 20 − X. The program reads
    // it in the block after (R2), and 0 before any deletion (R1); an IF on it (about 15 > 10)
    // jumps over R3=1.
    let mut ch = channel("mill-3axis", "");
    let program = "R1=$AC_DELT\nWHEN $AA_IM[X]>=5 DO DELDTG\nG1 X20 F600\nR2=$AC_DELT\n\
                   IF $AC_DELT>10 GOTOF FAR\nR3=1\nFAR:\nM30";
    ch.run_program(program).unwrap();
    run_to_end(&mut ch);
    alarm_free(&ch);
    let x = ch.axis_positions()[0];
    assert!((5.0..=5.04 + 1e-9).contains(&x), "X stopped at {x}");
    assert_eq!((ch.r_param(1), ch.r_param(3)), (0.0, 0.0));
    assert!((ch.r_param(2) - (20.0 - x)).abs() < 1e-9, "R2 = {} for X = {x}", ch.r_param(2));
}
