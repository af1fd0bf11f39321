//! Braking to a standstill keeps every axis within its acceleration, the last cycle that lands
//! on the end point and the first cycle at rest after it included (Function Manual B1: the
//! axes brake with the acceleration of MD32300 `$MA_MAX_AX_ACCEL`; nothing allows more at a
//! stop). Run through a whole channel on the 3-axis mill preset (X, Y, Z: 30 m/min, 3 m/s²,
//! IPO cycle 4 ms): a cycle may change an axis' speed by at most a·T = 12 mm/s.

use nctwin_engine::Channel;

const DT: f64 = 0.004;
/// MD32300 of the preset's axes, mm/s².
const ACCEL: f64 = 3000.0;

/// The X, Y, Z setpoints of every IPO cycle of `program`, and of five cycles at rest after it.
fn run(program: &str) -> Vec<[f64; 3]> {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    let xyz = |ch: &Channel| {
        let p = ch.axis_positions();
        [p[0], p[1], p[2]]
    };
    let mut out = vec![xyz(&ch)];
    while ch.is_busy() {
        ch.step();
        out.push(xyz(&ch));
        assert!(out.len() < 1_000_000, "the program does not end");
    }
    for _ in 0..5 {
        ch.step();
        out.push(xyz(&ch));
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    out
}

/// The k-th difference of the samples over `DT^k`, per axis.
fn diff(samples: &[[f64; 3]], k: usize) -> Vec<[f64; 3]> {
    let mut d = samples.to_vec();
    for _ in 0..k {
        d = d.windows(2).map(|w| std::array::from_fn(|i| (w[1][i] - w[0][i]) / DT)).collect();
    }
    d
}

/// The largest sampled acceleration of each axis over the whole program.
fn max_accel(program: &str) -> [f64; 3] {
    let acc = diff(&run(program), 2);
    std::array::from_fn(|i| acc.iter().map(|a| a[i].abs()).fold(0.0, f64::max))
}

#[test]
fn a_full_feed_move_brakes_to_its_end_point_in_whole_steps_of_a_t() {
    // X100 at F6000 = 100 mm/s from rest. Up: 12, 24, ..., 96 mm/s (8 cycles) and 100 in the
    // 9th: 0.004·(432 + 100) = 2.128 mm. Down: the fastest stop from 100 mm/s loses 12 mm/s per
    // cycle, 88, 76, ..., 4 and then rest; with the cycle at 100 it covers
    // 0.004·(100 + 88 + ... + 4) = 0.004·468 = 1.872 mm. 2.128 + 1.872 = 4 mm is ten cycles
    // of 0.4 mm, so the other 96 mm are 240 cycles at 100 mm/s exactly: 242 cycles at the
    // feed in all (the last of the ramp up and the first of the stop), then 88, ..., 4, 0. (Before the fix the path braked on v² = 2a·s plus
    // half a cycle, an eighth of a·T² short of the discrete stop: its last two cycles ran
    // 16.17 and 2.81 mm/s, a step of 13.4 mm/s = 3340 mm/s².)
    let v: Vec<f64> = diff(&run("G1 X100 F6000\nM30"), 1).iter().map(|s| s[0]).collect();
    let moving: Vec<f64> = v.iter().copied().skip_while(|&x| x == 0.0).collect();
    let mut want: Vec<f64> = (1..=8).map(|k| 12.0 * f64::from(k)).collect();
    want.extend(std::iter::repeat_n(100.0, 242));
    want.extend((1..=8).map(|k| 100.0 - 12.0 * f64::from(k)));
    assert!(moving.len() > want.len(), "{} cycles", moving.len());
    for (i, (got, want)) in moving.iter().zip(&want).enumerate() {
        assert!((got - want).abs() < 1e-6, "cycle {i}: {got} mm/s, want {want}");
    }
    assert!(moving[want.len()..].iter().all(|&x| x == 0.0), "at rest after 4 mm/s: {:?}", &moving[want.len()..]);
}

#[test]
fn no_axis_exceeds_its_acceleration_when_a_program_stops() {
    // End points that are no whole number of cycles of braking (the fastest stop then ends
    // with a cycle slower than a·T), a diagonal (X and Y brake with a share of the path's
    // deceleration each: 3000 mm/s² for X, the longer one), a G64 chain whose last move
    // carries the stop, an exact stop between two moves (G60), rapid traverse at 30 m/min and
    // SOFT with the preset's jerk: in every cycle, the last one on the end point and the first
    // at rest included, |Δv|/T ≤ 3000 mm/s² on every axis.
    for program in [
        "G1 X100.1234 F6000\nM30",
        "G1 X100 Y37.3 F6000\nM30",
        "G64 G1 X50 F6000\nX100.37\nM30",
        "G60 G1 X33.3 F6000\nX71.77\nM30",
        "G0 X123.456\nM30",
        "SOFT G1 X100.1234 F6000\nM30",
        "G1 X-7.77 F4321\nM30",
    ] {
        let worst = max_accel(program);
        for (axis, a) in worst.iter().enumerate() {
            assert!(*a <= ACCEL * (1.0 + 1e-9), "{program:?}: axis {axis} at {a} mm/s²");
        }
        assert!(worst[0] > 0.99 * ACCEL, "{program:?}: X brakes at its limit ({} mm/s²)", worst[0]);
    }
}
