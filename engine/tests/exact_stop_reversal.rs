//! A move that starts after an exact stop starts from rest (Function Manual B1 "Exact stop":
//! the block change waits until the axes stand; B2: every axis accelerates with at most
//! MD32300 `$MA_MAX_AX_ACCEL`, the overload of MD32310 is for a velocity jump at a block
//! transition in continuous-path mode only). The sampled acceleration, the second difference of
//! the IPO setpoints over T², stays within MD32300 in every cycle, the stop's own cycles and a
//! reversal of an axis right after it included: the cycle that lands on the end point moved
//! the axis by up to a·T², so the next one may not move it back by another a·T². The stop
//! therefore has one IPO cycle at rest before the next move begins.

use crate::path_support;

use nctwin_engine::Channel;
use path_support::{A_MAX, DT};

/// The largest |Δv|/T per axis over the samples.
fn max_accel<const N: usize>(samples: &[[f64; N]], dt: f64) -> [f64; N] {
    let vel: Vec<[f64; N]> = samples.windows(2).map(|w| std::array::from_fn(|k| (w[1][k] - w[0][k]) / dt)).collect();
    let mut worst = [0.0; N];
    for w in vel.windows(2) {
        for k in 0..N {
            worst[k] = f64::max(worst[k], ((w[1][k] - w[0][k]) / dt).abs());
        }
    }
    worst
}

/// X, Y, Z setpoints of every cycle of `program` on the 3-axis mill with `md` on top.
fn mill(md: &str, program: &str) -> Vec<[f64; 3]> {
    path_support::samples::<3>(md, program, 1_000_000).1
}

#[test]
fn no_axis_exceeds_its_acceleration_when_it_reverses_after_an_exact_stop() {
    // Every program reverses an axis at a programmed or implicit exact stop, with end points
    // that are no whole number of braking cycles (the last cycle before the stop runs between
    // 0 and a·T = 12 mm/s). No program has a continuous-path corner, so nothing may use the
    // overload: |Δv|/T ≤ 3000 mm/s² on every axis in every cycle.
    for (md, program) in [
        ("", "G60 G1 X100 F6000\nX0\nM30"),
        ("", "G60 G1 X33.3 F6000\nX-7.77\nM30"),
        ("", "G64 G1 X50.123 F6000 G9\nX0\nM30"),
        ("", "G60 G601 G1 X41.7 F6000\nX0\nM30"),
        ("", "G60 G602 G1 X41.7 F6000\nX0\nM30"),
        ("", "G60 G603 G1 X41.7 F6000\nX0\nM30"),
        ("", "FFWOF G60 G603 G1 X41.7 F6000\nX0\nM30"),
        ("", "FFWOF G60 G601 G1 X41.7 F6000\nX0\nM30"),
        // Y reverses while X goes on at the stop.
        ("", "G60 G1 X10.3 Y10.3 F6000\nX20.9 Y0\nM30"),
        // G0 to G1 in the reset mode (G60), and rapid traverse itself.
        ("", "G0 X100.3\nG1 X0 F6000\nM30"),
        ("", "G0 X100.3 Z-20.77\nG0 X0 Z0\nM30"),
        // An implicit stop: a block without motion between the moves.
        ("", "G64 G1 X30.37 F6000\nM8\nX0\nM30"),
        ("", "G64 G1 X30.37 F6000\nG4 F0.004\nX0\nM30"),
        // SOFT brakes and starts with the jerk: the acceleration is far below the limit.
        ("$MA_MAX_AX_JERK[X]=20\n$MA_MAX_AX_JERK[Y]=20\n$MA_MAX_AX_JERK[Z]=20", "SOFT G60 G1 X20.3 F6000\nX0\nM30"),
    ] {
        let worst = max_accel(&mill(md, program), DT);
        for (axis, a) in worst.iter().enumerate() {
            assert!(*a <= A_MAX * (1.0 + 1e-9), "{program:?}: axis {axis} at {a} mm/s²");
        }
    }
}

#[test]
fn the_stop_has_one_cycle_at_rest_between_the_last_step_and_the_first_step_back() {
    // X100 at F6000 = 100 mm/s from rest, as in `path_end_braking.rs`: up 12, 24, ..., 96, then
    // 242 cycles at 100 mm/s, down 88, 76, ..., 4 mm/s, landing on X100. Then one cycle at
    // rest (velocity 0), and X0 starts back from rest: −12, −24, ... mm/s. Without the rest
    // the step of 4 mm/s was followed by −12 mm/s: 16 mm/s in a cycle, 4000 mm/s².
    let s = mill("", "G60 G1 X100 F6000\nX0\nM30");
    let v: Vec<f64> = s.windows(2).map(|w| (w[1][0] - w[0][0]) / DT).collect();
    let arrive = v.iter().position(|&x| x < 4.0 + 1e-6 && x > 0.0).expect("the last step of 4 mm/s");
    let want = [16.0, 4.0, 0.0, -12.0, -24.0, -36.0];
    for (i, w) in want.iter().enumerate() {
        let got = v[arrive - 1 + i];
        assert!((got - w).abs() < 1e-6, "cycle {i} around the stop: {got} mm/s, want {w}");
    }
    assert_eq!(s[arrive + 1][0], 100.0, "the stop lands on X100 exactly");
    assert_eq!(s[arrive + 2][0], 100.0, "and stands there for a cycle");
}

/// The machine positions of the five axes of the CA head (X, Y, Z, A, C) in every cycle of
/// `program`, and the channel.
fn head(program: &str) -> (Channel, Vec<[f64; 5]>) {
    let mut ch = Channel::from_preset("mill5-head-ca", "").unwrap();
    ch.run_program(program).unwrap();
    let xyzac = |ch: &Channel| -> [f64; 5] { std::array::from_fn(|k| ch.axis_positions()[k]) };
    let mut out = vec![xyzac(&ch)];
    while ch.is_busy() {
        ch.step();
        out.push(xyzac(&ch));
        assert!(out.len() < 1_000_000, "the program does not end");
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    (ch, out)
}

#[test]
fn under_traori_the_first_move_after_the_positioning_starts_from_rest() {
    // The CA head tilted 20° (A20 C0) by a G0 in machine axes, Z up to 100; TRAORI, and the
    // tip down to Z50: machine Z reverses at the change of transformation (an implicit stop).
    // Every machine axis keeps its MD32300 in every cycle (a straight line of the tip with a
    // fixed orientation is a straight line of the machine's linear axes: no corner, no
    // overload). Before the rest cycle, Z stepped back 5711 mm/s² against its 4000 mm/s².
    let (ch, s) = head("T1 D1\nG0 X0 Y0 Z100 A20 C0\nTRAORI\nG0 X0 Y0 Z50\nM30");
    let dt = ch.config().ipo_cycle;
    let worst = max_accel(&s, dt);
    for (k, a) in worst.iter().enumerate() {
        let limit = ch.config().axis(k).max_accel;
        assert!(*a <= limit * (1.0 + 1e-9), "axis {k}: {a} > {limit}");
    }
    // Z went up first and then down: the reversal is in the samples.
    let z_top = s.iter().map(|p| p[2]).fold(f64::MIN, f64::max);
    assert!(z_top > s.last().unwrap()[2] + 10.0, "Z reverses: top {z_top}, end {}", s.last().unwrap()[2]);
}
