//! TRACON selected straight after a move on the slant-bed lathe (`slant-lathe-tracon`: TRAANG
//! data set 2 always active, TRANSMIT data set 1 chained in front of it by TRACON data set 3).
//!
//! A tool selected with the persistent TRAANG active is taken into that transformation in the
//! main run by a switch of its own. That switch used to end preprocessing's wait for the
//! TRANSMIT selection further down the queue, handing back the machine position before the
//! move in between (MU = MZ = 0): the block after TRANSMIT then started from there, a jump of
//! 120/cos 30° = 138.56 mm in one IPO cycle. The wait now ends when the selection's own
//! block executes.

use crate::settle;
use settle::channel;

/// Runs `program` to its end; returns the machine positions (axis name, value) of every IPO
/// cycle, the starting position first, and the IPO cycle in seconds.
fn machine_samples(program: &str) -> (Vec<Vec<(String, f64)>>, f64) {
    let mut ch = channel("slant-lathe-tracon", "");
    let ipo = ch.config().ipo_cycle;
    let mut samples = vec![ch.snapshot().machine];
    ch.run_program(program).unwrap();
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            let s = ch.snapshot();
            assert!(s.alarms.is_empty(), "{program:?}: {:?}", s.alarms);
            return (samples, ipo);
        }
        ch.step();
        samples.push(ch.snapshot().machine);
    }
    panic!("{program:?} never came to rest");
}

#[test]
fn no_machine_axis_steps_faster_than_its_velocity_allows() {
    // IPO cycle: $MN_SYSCLOCK_CYCLE_TIME 2 ms × $MN_IPO_SYSCLOCK_TIME_RATIO 2 = 4 ms. Per cycle
    // an axis can travel at most MD32000 × 4 ms:
    //   MU, MZ: 15000 mm/min = 250 mm/s → 1.0 mm;
    //   CM: 100 rev/min = 600°/s → 2.4°;  ASM: 6000 rev/min = 36000°/s → 144°.
    let limit = |axis: &str| match axis {
        "MU" | "MZ" => 1.0,
        "CM" => 2.4,
        "ASM" => 144.0,
        other => panic!("unexpected machine axis {other}"),
    };
    let programs = [
        // The selection straight after a move, with the tool taken into the transformations.
        "G17 G90 G94 T1 D1\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nTRAFOOF\nM30",
        "G17 G90 G94 T1 D1\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nM30",
        // The variants that never jumped: G18 (length 1 along Y, outside TRAANG), a
        // preprocessing stop before the selection, no tool.
        "G18 G90 G94 T1 D1\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nTRAFOOF\nM30",
        "G17 G90 G94 T1 D1\nG0 X120 Z50\nSTOPRE\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nTRAFOOF\nM30",
        "G17 G90 G94\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nTRAFOOF\nM30",
        // The same selection again after a move.
        "G17 G90 G94 T1 D1\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nTRANSMIT\nG1 X30 F1000\nTRAFOOF\nM30",
    ];
    for program in programs {
        let (samples, ipo) = machine_samples(program);
        assert!((ipo - 0.004).abs() < 1e-12, "IPO cycle {ipo}");
        for (i, w) in samples.windows(2).enumerate() {
            for ((name, a), (_, b)) in w[0].iter().zip(&w[1]) {
                let step = (b - a).abs();
                assert!(step <= limit(name) + 1e-9, "{program:?}: {name} steps {step} in cycle {i}");
            }
        }
    }
}

#[test]
fn the_block_after_the_selection_ends_where_the_chain_puts_it() {
    // G17, T1 D1: length 30 along Z, taken into the chain; the flange stands 30 above the tip.
    // G0 X120 Z50 under TRAANG 30° (MU = X/cos30, MZ = Z_flange − X·tan30):
    //   MU = 120/0.866025 = 138.564, MZ = 80 − 69.282 = 10.718.
    // G1 X40 Y10 Z5 under TRANSMIT → TRAANG: radius r = √(40² + 10²) = √1700 = 41.2311,
    //   C = atan2(10, 40) = 14.0362°, then MU = r/cos30 = 47.6095,
    //   MZ = (5 + 30) − r·tan30 = 35 − 23.8048 = 11.1952.
    let (samples, _) = machine_samples("G17 G90 G94 T1 D1\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nM30");
    let end = samples.last().unwrap();
    let at = |name: &str| end.iter().find(|(n, _)| n == name).unwrap().1;
    let (cos30, tan30) = (30f64.to_radians().cos(), 30f64.to_radians().tan());
    let r = 1700f64.sqrt();
    let expected = [("MU", r / cos30), ("CM", 10f64.atan2(40.0).to_degrees()), ("MZ", 35.0 - r * tan30)];
    for (name, want) in expected {
        assert!((at(name) - want).abs() < 1e-6, "{name} {} ≠ {want}", at(name));
    }
    assert!((at("MU") - 47.6095).abs() < 1e-4 && (at("MZ") - 11.1952).abs() < 1e-4, "{end:?}");
    // The G0 ended where TRAANG puts X120 Z50 with the tool: the last sample before the
    // selection's block started (it is reached before any cycle of the G1).
    let reached = samples.iter().any(|s| {
        let v = |name: &str| s.iter().find(|(n, _)| n == name).unwrap().1;
        (v("MU") - 120.0 / cos30).abs() < 1e-6 && (v("MZ") - (80.0 - 120.0 * tan30)).abs() < 1e-6
    });
    assert!(reached, "the G0 end MU 138.564 MZ 10.718 is never reached");
}
#[test]
fn selecting_the_chain_again_waits_for_its_own_block() {
    // The second TRANSMIT leaves the offsets as they were; preparation still waits for it and
    // goes on from the end of the first G1. G1 X30 (Y10 Z5 modal): r = √(30² + 10²) = √1000
    //   = 31.6228, C = atan2(10, 30) = 18.4349°, MU = r/cos30 = 36.5148,
    //   MZ = 35 − r·tan30 = 35 − 18.2574 = 16.7426.
    let program = "G17 G90 G94 T1 D1\nG0 X120 Z50\nTRANSMIT\nG1 X40 Y10 Z5 F1000\nTRANSMIT\nG1 X30 F1000\nTRAFOOF\nM30";
    let (samples, _) = machine_samples(program);
    let end = samples.last().unwrap();
    let at = |name: &str| end.iter().find(|(n, _)| n == name).unwrap().1;
    let (cos30, tan30) = (30f64.to_radians().cos(), 30f64.to_radians().tan());
    let r = 1000f64.sqrt();
    let expected = [("MU", r / cos30), ("CM", 10f64.atan2(30.0).to_degrees()), ("MZ", 35.0 - r * tan30)];
    for (name, want) in expected {
        assert!((at(name) - want).abs() < 1e-6, "{name} {} ≠ {want}", at(name));
    }
}
