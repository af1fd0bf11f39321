//! MD21108 POLE_ORI_MODE on the CA head of `mill5-head-ca` (C about Z carries A about X;
//! `o = (sin C·sin A, −cos C·sin A, cos A)`, the pole is o = Z where C is free).
//!
//! The end orientation (1, 1, 1)/√3 has cos A = 1/√3 ⇒ |A| = 54.7356° and C = atan2(ox, −oy):
//! C = 135° with A = +54.7356°, or C = −45° with A = −54.7356°; from C = 0 the second is nearer.

use nctwin_engine::Channel;

fn samples(md: &str, program: &str) -> Vec<Vec<f64>> {
    let mut ch = Channel::from_preset("mill5-head-ca", md).unwrap();
    ch.run_program(program).unwrap();
    let mut out = Vec::new();
    while ch.is_busy() {
        ch.step();
        out.push(ch.axis_positions().to_vec());
        assert!(out.len() < 1_000_000);
    }
    // 10910 (feed reduced at the pole) is the only alarm the great circle may raise here.
    let alarms = ch.snapshot().alarms;
    assert!(alarms.iter().all(|a| a.number == 10910), "{alarms:?}");
    out
}

fn alarms_of(md: &str, program: &str) -> Vec<u32> {
    let mut ch = Channel::from_preset("mill5-head-ca", md).unwrap();
    ch.run_program(program).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ch.snapshot().alarms.iter().map(|a| a.number).collect()
}

const A_END: f64 = -54.735_610_317_245_35;

fn program(start_a: f64) -> String {
    format!("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A{start_a} C0\nORIWKS\nA3=1 B3=1 C3=1\nM30")
}

/// Samples of the last block (after the M0 the rotary axes leave their start).
fn last_block(s: &[Vec<f64>], start_a: f64) -> Vec<Vec<f64>> {
    s.iter().filter(|m| (m[3] - start_a).abs() > 1e-9 || m[4].abs() > 1e-9).filter(|m| m[4] != 0.0).cloned().collect()
}

#[test]
fn from_the_pole_the_default_great_circle_turns_c_first() {
    // Mode 0: the pole axis is traversed to its end position at the start of the block, the
    // orientation staying in the pole (F2, behaviour at pole): C turns to −45 with A still at
    // 0, within C's own velocity limit (240°/s: at least 45/240 s = 47 cycles of 4 ms), and
    // then the great circle tilts A alone.
    let s = samples("", &program(0.0));
    let end = s.last().unwrap();
    assert!((end[3] - A_END).abs() < 1e-6 && (end[4] + 45.0).abs() < 1e-6, "{end:?}");
    let block = last_block(&s, 0.0);
    let turning = block.iter().take_while(|m| m[3].abs() < 1e-9).count();
    assert!(turning >= 47, "C turned in {turning} cycles");
    assert!((block[turning - 1][4] + 45.0).abs() < 1e-9, "{:?}", block[turning - 1]);
    assert!(block[turning..].iter().all(|m| (m[4] + 45.0).abs() < 1e-6));
    // Neither mode slows the path unevenly: no alarm 10910.
    assert_eq!(alarms_of("", &program(0.0)), Vec::<u32>::new());
    assert_eq!(alarms_of("$MC_POLE_ORI_MODE=1", &program(0.0)), Vec::<u32>::new());
}

#[test]
fn units_digit_1_interpolates_the_rotary_axes_from_the_pole_linearly() {
    let s = samples("$MC_POLE_ORI_MODE=1", &program(0.0));
    let end = s.last().unwrap();
    assert!((end[3] - A_END).abs() < 1e-6 && (end[4] + 45.0).abs() < 1e-6, "{end:?}");
    let block = last_block(&s, 0.0);
    assert!(block.len() > 10);
    for m in block {
        // A/A_END = C/(−45) all along (ORIAXES).
        assert!((m[3] / A_END - m[4] / -45.0).abs() < 1e-6, "{m:?}");
    }
}

#[test]
fn tens_digit_1_acts_inside_the_non_pole_limit_and_units_digit_not() {
    // Start A = 1° (within NON_POLE_LIMIT = 2°, not the pole). The nearer end is still
    // C = −45, A = −54.7356 (travel 45° + 55.7° against 135° + 53.7° for C = 135). With the
    // tens digit 1 both axes go linearly; with only the units digit set the great circle runs.
    let start = 1.0;
    let s = samples("$MC_POLE_ORI_MODE=10", &program(start));
    let block = last_block(&s, start);
    let end = s.last().unwrap();
    let (da, dc) = (end[3] - start, end[4]);
    for m in &block {
        assert!(((m[3] - start) / da - m[4] / dc).abs() < 1e-6, "{m:?}");
    }
    let s = samples("$MC_POLE_ORI_MODE=1", &program(start));
    let block = last_block(&s, start);
    assert!(block.iter().any(|m| ((m[3] - start) / da - m[4] / dc).abs() > 1e-3));
}
