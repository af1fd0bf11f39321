//! The single-axis interpolator of positioning axes (POS/POSA/FA in programs, the command axes
//! of synchronized actions, RTLIOF's rapid) follows the exact discrete trapezoid: it speeds up
//! by a·dt per IPO cycle, cruises at the feed and brakes by a·dt per cycle so that the last
//! cycle's travel lands on the end point; no cycle changes speed by more than a·dt, the stop
//! after the last cycle included (the path planner's `stop_speed`).
//!
//! mill-3axis: IPO cycle 4 ms, MD32300 3000 mm/s² on Z, so a·dt = 12 mm/s per cycle.
//! `POS[Z]=-9.6 FA[Z]=7200` (120 mm/s = 10·a·dt), worked by hand as speeds per cycle:
//! 12, 24, .., 108 (9 cycles, 4.32/2 = 2.16 mm), 120 for m cycles (0.48 mm each),
//! 108, 96, .., 12 (9 cycles, 2.16 mm), then rest. 2.16 + 0.48·m + 2.16 = 9.6 gives m = 11:
//! 29 moving cycles (L/(V·dt) + V/(a·dt) − 1 = 20 + 10 − 1), against 30 of the continuous
//! L/V + V/a = 0.12 s.

use crate::settle;

use settle::{channel, settle};

/// The per-cycle travel of channel axis `k` while it moves (speeds in units/s).
fn speeds(samples: &[Vec<f64>], k: usize, dt: f64) -> Vec<f64> {
    let mut v: Vec<f64> = samples.windows(2).map(|w| (w[1][k] - w[0][k]) / dt).collect();
    let first = v.iter().position(|x| *x != 0.0).expect("the axis moves");
    let last = v.iter().rposition(|x| *x != 0.0).unwrap();
    v.truncate(last + 1);
    v.drain(..first);
    v
}

#[test]
fn pos_follows_the_exact_trapezoid_and_lands_on_its_end_point() {
    let mut ch = channel("mill-3axis", "");
    let dt = ch.config().ipo_cycle;
    assert_eq!(dt, 0.004);
    ch.run_program("POS[Z]=-9.6 FA[Z]=7200\nM30\n").unwrap();
    let mut samples = vec![ch.axis_positions().to_vec()];
    samples.extend(settle(&mut ch));
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(samples.last().unwrap()[2], -9.6, "the end point exactly");
    let v: Vec<f64> = speeds(&samples, 2, dt).iter().map(|v| -v).collect();
    assert_eq!(v.len(), 29, "moving cycles: {v:?}");
    let mut hand: Vec<f64> = (1..=9).map(|i| 12.0 * i as f64).collect();
    hand.extend([120.0; 11]);
    hand.extend((1..=9).rev().map(|i| 12.0 * i as f64));
    for (i, (v, h)) in v.iter().zip(&hand).enumerate() {
        assert!((v - h).abs() < 1e-6, "cycle {i}: {v} mm/s, by hand {h}");
    }
}

#[test]
fn no_cycle_of_a_positioning_axis_accelerates_beyond_its_limit() {
    // Lengths and feeds that are no multiples of a·dt: the sampled acceleration (the change of
    // speed from cycle to cycle, from and to rest included) stays within 3000 mm/s², the end
    // point is reached exactly, and the time is the trapezoid's L/V + V/a within one cycle
    // (the discrete profile is up to one cycle shorter than the continuous one).
    for (length, fa) in [(5.0, 1000.0), (7.31, 5555.0), (0.37, 9000.0), (23.456, 8000.0)] {
        let mut ch = channel("mill-3axis", "");
        let dt = ch.config().ipo_cycle;
        ch.run_program(&format!("POS[Z]={length} FA[Z]={fa}\nM30\n")).unwrap();
        let mut samples = vec![ch.axis_positions().to_vec()];
        samples.extend(settle(&mut ch));
        assert_eq!(samples.last().unwrap()[2], length, "the end point exactly");
        let mut v = vec![0.0];
        v.extend(speeds(&samples, 2, dt));
        v.push(0.0);
        for w in v.windows(2) {
            let a = (w[1] - w[0]) / dt;
            assert!(a.abs() <= 3000.0 * (1.0 + 1e-9), "{length} mm at F{fa}: {a} mm/s² in {v:?}");
        }
        let feed = fa / 60.0;
        // A triangle where the feed is not reached: 2·√(L/a).
        let ideal =
            if feed * feed / 3000.0 < length { length / feed + feed / 3000.0 } else { 2.0 * (length / 3000.0).sqrt() };
        let t = (v.len() - 2) as f64 * dt;
        assert!(t <= ideal + 1e-9 && t > ideal - 2.0 * dt, "{length} mm at F{fa}: {t} s, by hand {ideal} s");
    }
}
