//! `$A_INA[n]` and `$AC_DELT` read in program blocks (not only in synchronized actions): both
//! are main-run variables, so the block reading them waits until the main run has caught up
//! (the control's implicit preprocessing stop) and reads the value of that moment.
//! mill-3axis: IPO cycle 4 ms; `G1 X.. F600` is 10 mm/s, 0.04 mm per cycle.

use crate::settle;

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

/// Runs `program` on mill-3axis to its end without an alarm; R1..R4.
fn r1_to_r4(program: &str) -> [f64; 4] {
    let mut ch = channel("mill-3axis", "");
    ch.run_program(program).unwrap();
    run_to_end(&mut ch);
    alarm_free(&ch);
    [ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4)]
}

#[test]
fn axis_values_read_after_a_move_are_those_at_its_end() {
    // Reading a main-run variable stops preprocessing: the block after G1 X10 reads X where
    // the move ended (setpoint 10; FFWON by default: no following error, so the actual value
    // 10 too; no frame: WCS 10) and at rest (speed 0). Under G64 into a following move the
    // same: the preprocessing stop ends the move first, and X then goes on to 20.
    let reads = "R1=$AA_IPO[X]\nR2=$AA_IM[X]\nR3=$AA_IW[X]\nR4=$AA_VACTM[X]";
    assert_eq!(r1_to_r4(&format!("G1 X10 F600\n{reads}\nM30")), [10.0, 10.0, 10.0, 0.0]);
    assert_eq!(r1_to_r4(&format!("G60 G1 X10 F600\n{reads}\nG1 X20\nM30")), [10.0, 10.0, 10.0, 0.0]);
    let mut ch = channel("mill-3axis", "");
    ch.run_program(&format!("G64 G1 X10 F600\n{reads}\nG1 X20\nM30")).unwrap();
    run_to_end(&mut ch);
    alarm_free(&ch);
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4)], [10.0, 10.0, 10.0, 0.0]);
    assert_eq!(ch.axis_positions()[0], 20.0);
}

#[test]
fn a_command_axis_still_travelling_is_read_where_and_how_fast_it_travels() {
    // The action sends Y to 30 (WCS; TRANS Y2: machine 32) at FA 600 mm/min once X has passed
    // 5; the program does not wait for command axes, so the block after G1 X10 reads Y on its
    // way, having travelled as long as X took from 5 to 10 at the same 10 mm/s: about 5 mm
    // (machine). $AA_IW is that point in the WCS (2 less), not the programmed Y0 (WCS; −2
    // before), and $AA_VACTM its speed: the FA of 600 mm/min it reached after its ramp.
    let [ipo, im, iw, vactm] = r1_to_r4(
        "TRANS Y2\nID=1 WHEN $AA_IM[X]>=5 DO POS[Y]=30 FA[Y]=600\nG1 X10 F600\n\
         R1=$AA_IPO[Y] R2=$AA_IM[Y] R3=$AA_IW[Y] R4=$AA_VACTM[Y]\nM30",
    );
    assert!((ipo - 5.0).abs() < 0.1, "$AA_IPO[Y] = {ipo} (about 5 travelled)");
    assert_eq!(im, ipo);
    assert!((iw - (ipo - 2.0)).abs() < 1e-9, "$AA_IW[Y] = {iw} for $AA_IPO[Y] = {ipo}");
    assert!((vactm - 600.0).abs() < 1e-9, "$AA_VACTM[Y] = {vactm}");
}

#[test]
fn after_stopreof_the_path_speed_is_read_while_it_moves() {
    // STOPREOF ends the preprocessing stop while G1 X10 F600 runs at 10 mm/s (0.04 mm per
    // 4 ms cycle): the block after reads X's speed then, 600 mm/min, and its WCS value equal
    // to the setpoint (no frame), somewhere past 2 (the next block waits again).
    let [ipo, _, iw, vactm] =
        r1_to_r4("WHEN $AA_IM[X]>2 DO STOPREOF\nG1 X10 F600\nR1=$AA_IPO[X] R3=$AA_IW[X] R4=$AA_VACTM[X]\nM30");
    assert!((2.0..2.1).contains(&ipo), "$AA_IPO[X] = {ipo}");
    assert_eq!(iw, ipo);
    assert!((vactm - 600.0).abs() < 1e-6, "$AA_VACTM[X] = {vactm}");
}
