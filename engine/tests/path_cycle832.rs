//! CYCLE832's call forms of the cycles manual ("Programming cycles externally": `_TOLM`
//! decimal-coded, units the machining type 0..4, tens the orientation tolerance, hundreds ..
//! hundred thousands kept for compatibility, millions the mold-making function) and the G
//! codes each leaves, read back through `$P_GG` as a program does. G group positions
//! (Programming Manual's lists): group 10 G60 1, G64 2, G641 3, G642 4; group 21 BRISK 1,
//! SOFT 2; group 24 FFWOF 1, FFWON 2; group 30 COMPOF 1, COMPON 2, COMPCURV 3, COMPCAD 4,
//! COMPSURF 5; group 59 DYNNORM 1, DYNPOS 2, DYNROUGH 3, DYNSEMIFIN 4, DYNFINISH 5.

use nctwin_engine::Channel;

/// Runs `program` on the 3-axis mill to its end; the channel and the X, Y of every cycle.
fn run_sampled(program: &str) -> (Channel, Vec<[f64; 2]>) {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap_or_else(|e| panic!("not started: {e}"));
    let mut samples = Vec::new();
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            return (ch, samples);
        }
        ch.step();
        samples.push([ch.axis_positions()[0], ch.axis_positions()[1]]);
    }
    panic!("the program does not end");
}

fn run(program: &str) -> Channel {
    run_sampled(program).0
}

/// `$P_GG` of groups 10, 21, 24, 30 and 59 after `call`.
fn groups_after(call: &str) -> [f64; 5] {
    let ch = run(&format!(
        "G17 G90 F2000\nG0 X0 Y0 Z0\n{call}\nR1=$P_GG[10] R2=$P_GG[21] R3=$P_GG[24] R4=$P_GG[30] R5=$P_GG[59]\nM30"
    ));
    assert!(ch.alarms().is_empty(), "{call}: {:?}", ch.alarms());
    std::array::from_fn(|i| ch.r_param(i + 1))
}

#[test]
fn each_machining_type_leaves_its_g_codes() {
    // Finishing, semi-finishing, roughing: G642 SOFT FFWON COMPCAD and DYNFINISH /
    // DYNSEMIFIN / DYNROUGH. Smooth finishing (4): the same as finishing (no DYNPREC in
    // NCTwin's group 59, see CYCLE832.SPF). Deselection: G64, COMPOF, DYNNORM, SOFT and FFWON
    // kept.
    assert_eq!(groups_after("CYCLE832(0.01,_FINISH,1)"), [4.0, 2.0, 2.0, 4.0, 5.0]);
    assert_eq!(groups_after("CYCLE832(0.05,_SEMIFIN,1)"), [4.0, 2.0, 2.0, 4.0, 4.0]);
    assert_eq!(groups_after("CYCLE832(0.1,_ROUGH,1)"), [4.0, 2.0, 2.0, 4.0, 3.0]);
    assert_eq!(groups_after("CYCLE832(0.005,4,1)"), [4.0, 2.0, 2.0, 4.0, 5.0]);
    assert_eq!(groups_after("CYCLE832(0.01,_ORI_ROUGH,0.5)"), [4.0, 2.0, 2.0, 4.0, 3.0]);
    assert_eq!(groups_after("CYCLE832(0.01,1)\nCYCLE832(0.01,_OFF)"), [2.0, 2.0, 2.0, 1.0, 1.0]);
}

#[test]
fn the_mold_making_digit_selects_top_surface_and_the_compatibility_digits_are_read_over() {
    // Millions 1 or 2: Top Surface, COMPSURF (group 30 position 5); millions 0: COMPCAD.
    // Hundreds .. hundred thousands (here 1001 in thousands and units: finishing) change
    // nothing.
    assert_eq!(groups_after("CYCLE832(0.01,1000001,1)"), [4.0, 2.0, 2.0, 5.0, 5.0]);
    assert_eq!(groups_after("CYCLE832(0.01,2000013,1)"), [4.0, 2.0, 2.0, 5.0, 3.0]);
    assert_eq!(groups_after("CYCLE832(0.01,101002,1)"), [4.0, 2.0, 2.0, 4.0, 4.0]);
}

#[test]
fn an_undefined_digit_is_alarm_61000() {
    for call in ["CYCLE832(0.01,5,1)", "CYCLE832(0.01,21,1)", "CYCLE832(0.01,3000001,1)"] {
        let ch = run(&format!("G17 G90 F2000\nG0 X0 Y0 Z0\n{call}\nM30"));
        assert!(ch.alarms().iter().any(|a| a.number == 61000), "{call}: {:?}", ch.alarms());
    }
}

#[test]
fn smooth_finishing_rounds_a_corner_within_its_tolerance() {
    // A square corner at (10, 0) after CYCLE832(0.005, 4, 1): G642 with CTOL 0.005. The path
    // passes the corner at no more than 0.005 mm (plus the 0.0002 mm the 0.004 mm sample
    // spacing at F60 may add: s²/(2·tol) for s = 0.002) and really cuts it (> 0.0005).
    let (ch, samples) = run_sampled("G17 G90 G0 X0 Y0 Z0\nCYCLE832(0.005,4,1)\nG1 X10 F60\nY10\nM30");
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let gap = samples.iter().map(|p| ((p[0] - 10.0).powi(2) + p[1].powi(2)).sqrt()).fold(f64::INFINITY, f64::min);
    assert!(gap <= 0.005 + 5e-4 && gap > 5e-4, "the corner is passed at {gap} mm");
}
