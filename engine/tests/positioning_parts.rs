//! POSP, positioning in parts (Programming Manual "Positioning axes: POSP"):
//! `POSP[ax]=(end, part length, mode)` reaches the end in parts, standing still after each.
//! Mode 0 (the default) halves the last stretch longer than one part; mode 1 shortens every
//! part so that a whole number of equal parts ends on the end point.
//!
//! Hand-worked with slow axes so that every stop shows: Z with `$MA_MAX_AX_ACCEL[Z]=0.1`
//! (100 mm/s²) and `FA[Z]=600` (10 mm/s): a part of d mm takes d/10 + 10/100 s (ramp 0.1 s,
//! 0.5 mm each way), so 3 mm take 0.4 s (100 cycles of 4 ms), 2 mm 0.3 s, 2.5 mm 0.35 s.
//! The single-axis interpolator takes its steps with the velocity of the cycle's end, so each
//! travel ends up to 6 cycles before the ideal time (a plain POS of 3 mm: 97 cycles): the
//! bounds below allow that per part.

use crate::settle;

use nctwin_engine::Channel;
use settle::{channel, run_to_end};

const SLOW_Z: &str = "$MA_MAX_AX_ACCEL[Z]=0.1\n";

/// Every channel-axis position of axis `k`, cycle by cycle, until the program ends.
fn track(ch: &mut Channel, k: usize) -> Vec<f64> {
    settle::settle(ch).iter().map(|p| p[k]).collect()
}

/// The positions where the axis came to rest on its way: each run of slow samples (below
/// `slow` per cycle on both sides) gives the sample with the least motion around it. The start
/// (at 0) is left out; the last stop is the end point.
fn stops(samples: &[f64], slow: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut run: Option<(f64, f64)> = None; // (least motion, position)
    let mut prev = 0.0;
    for (i, &z) in samples.iter().enumerate() {
        let next = samples.get(i + 1).copied().unwrap_or(z);
        let motion = (z - prev).abs() + (next - z).abs();
        let resting = (z - prev).abs() < slow && (next - z).abs() < slow && z.abs() > 0.2;
        match (resting, run) {
            (true, Some((m, _))) if motion >= m => {}
            (true, _) => run = Some((motion, z)),
            (false, Some((_, at))) => {
                out.push(at);
                run = None;
            }
            (false, None) => {}
        }
        prev = z;
    }
    out.extend(run.map(|(_, at)| at));
    out
}

fn alarm_free(ch: &Channel) {
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
}

#[test]
fn mode_0_travels_3_3_2_2_and_the_block_waits_for_the_end() {
    // 10 mm in parts of 3: 3, 3, then the remaining 4 (longer than one part, at most two)
    // in two halves of 2. Time 0.4 + 0.4 + 0.3 + 0.3 = 1.4 s = 350 cycles; a plain POS takes
    // 10/10 + 0.1 = 1.1 s. X waits for the block's end (POSP ends its block like POS).
    let mut ch = channel("mill-3axis", SLOW_Z);
    ch.run_program("POSP[Z]=(-10, 3, 0) FA[Z]=600\nG1 X1 F600\nM30").unwrap();
    let mut z = Vec::new();
    let mut x_started = None;
    while ch.is_busy() {
        ch.step();
        let p = ch.axis_positions();
        z.push(p[2]);
        if x_started.is_none() && p[0] != 0.0 {
            x_started = Some(z.len());
        }
    }
    alarm_free(&ch);
    let rests = stops(&z, 0.01);
    assert_eq!(rests.len(), 4, "{rests:?}");
    for (got, want) in rests.iter().zip([-3.0, -6.0, -8.0, -10.0]) {
        assert!((got - want).abs() < 0.01, "stops {rests:?}");
    }
    // The part ends are met exactly.
    for end in [-3.0, -6.0, -8.0, -10.0] {
        assert!(z.contains(&end), "never exactly at {end}");
    }
    let arrived = z.iter().position(|&v| v == -10.0).unwrap() + 1;
    assert!((326..=352).contains(&arrived), "Z at its end after {arrived} cycles");
    let started = x_started.expect("X moves");
    assert!(started > arrived, "X starts after Z's end: {started} vs {arrived}");
}

#[test]
fn mode_1_shortens_the_parts_to_four_of_2_5() {
    // ceil(10/3) = 4 parts of 10/4 = 2.5 mm; 4 × 0.35 s = 1.4 s.
    let mut ch = channel("mill-3axis", SLOW_Z);
    ch.run_program("POSP[Z]=(-10, 3, 1) FA[Z]=600\nM30").unwrap();
    let z = track(&mut ch, 2);
    alarm_free(&ch);
    let rests = stops(&z, 0.01);
    assert_eq!(rests.len(), 4, "{rests:?}");
    for end in [-2.5, -5.0, -7.5, -10.0] {
        assert!(z.contains(&end), "never exactly at {end}: stops {rests:?}");
    }
    let arrived = z.iter().position(|&v| v == -10.0).unwrap() + 1;
    assert!((326..=352).contains(&arrived), "{arrived} cycles");
}

#[test]
fn an_exact_multiple_makes_equal_parts_in_both_modes_and_a_short_way_is_one_part() {
    // 9 in parts of 3: 3, 3, 3 (mode 0: the last 6 are halved into 3 and 3).
    for mode in [0, 1] {
        let mut ch = channel("mill-3axis", SLOW_Z);
        ch.run_program(&format!("POSP[Z]=(9, 3, {mode}) FA[Z]=600\nM30")).unwrap();
        let z = track(&mut ch, 2);
        alarm_free(&ch);
        assert_eq!(stops(&z, 0.01).len(), 3, "mode {mode}: {:?}", stops(&z, 0.01));
        assert!(z.contains(&3.0) && z.contains(&6.0), "mode {mode}");
    }
    // 2 mm in parts of 3 (mode 0, the default): one part, 0.3 s.
    let mut ch = channel("mill-3axis", SLOW_Z);
    ch.run_program("G91 POSP[Z]=(2, 3) FA[Z]=600\nM30").unwrap();
    let z = track(&mut ch, 2);
    alarm_free(&ch);
    assert_eq!(stops(&z, 0.01), vec![2.0]);
}

#[test]
fn a_rotary_axis_positions_in_parts_of_degrees() {
    // C of mill5-head-ca with 1 rev/s² (360°/s²) at FA 3600°/min (60°/s): ramp 1/6 s over 5°.
    // 100° in parts of 30, mode 0: 30, 30, then 40 halved: 20, 20 → stops 30, 60, 80, 100.
    // Time 100/60 + 4/6 = 2.333 s = 583 cycles.
    let mut ch = channel("mill5-head-ca", "$MA_MAX_AX_ACCEL[C]=1\n");
    let k = ch.config().channel_axes.iter().position(|a| a.name == "C").expect("C axis");
    ch.run_program("POSP[C]=(100, 30) FA[C]=3600\nM30").unwrap();
    let c = track(&mut ch, k);
    alarm_free(&ch);
    let rests = stops(&c, 0.05);
    assert_eq!(rests.len(), 4, "{rests:?}");
    for end in [30.0, 60.0, 80.0, 100.0] {
        assert!(c.contains(&end), "never exactly at {end}: {rests:?}");
    }
    let arrived = c.iter().position(|&v| v == 100.0).unwrap() + 1;
    assert!((559..=585).contains(&arrived), "{arrived} cycles");
}

#[test]
fn posp_goes_through_the_frame_and_scales_its_parts() {
    // TRANS Z10 ASCALE Z2: machine Z 0 is WCS (0 − 10)/2 = −5, POSP[Z]=(5, 1, 1) ends at
    // 10 + 2·5 = 20; ten parts of 1 mm in the WCS are 2 mm each at the machine: 2, 4, .., 20.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("TRANS Z10\nASCALE Z2\nPOSP[Z]=(5, 1, 1) FA[Z]=3000\nM30").unwrap();
    let z = track(&mut ch, 2);
    alarm_free(&ch);
    for end in [2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0] {
        assert!(z.iter().any(|&v| (v - end).abs() < 1e-9), "never at {end}");
    }
    assert!((z.last().unwrap() - 20.0).abs() < 1e-9);
}

#[test]
fn bad_posp_words_give_alarms() {
    for (program, number) in [
        ("POSP[Z]=5\nM30", 12080),
        ("POSP[Z]=(5)\nM30", 12080),
        ("POSP[Z]=(5, 0)\nM30", 12560),
        ("POSP[Z]=(5, -1, 0)\nM30", 12560),
        ("POSP[Z]=(5, 1, 2)\nM30", 12560),
        ("POSP[Z]=(5, 1) POS[Z]=2\nM30", 12080),
        ("G1 F100 Z1 POSP[Z]=(2, 1)\nM30", 12000),
    ] {
        let mut ch = channel("mill-3axis", "");
        ch.run_program(program).unwrap();
        run_to_end(&mut ch);
        let s = ch.snapshot();
        assert_eq!(s.alarms.first().map(|a| (a.number, a.line)), Some((number, Some(1))), "{program}");
    }
}
