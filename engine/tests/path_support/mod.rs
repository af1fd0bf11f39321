//! Running a program on the 3-axis mill and reading its path, for the tests of path motion
//! (continuous-path mode, seams, splines, exact stop, dynamics): the one set-up they share and
//! the dynamic limits they check against. The preset's data: X, Y, Z at 30 m/min (500 mm/s),
//! 3 m/s², overload factor 1.2 (MD32310), IPO cycle 4 ms.

use nctwin_engine::Channel;

/// The 3-axis mill's IPO cycle (4 ms).
pub const DT: f64 = 0.004;
/// Its axes' velocity limit (mm/s).
pub const V_MAX: f64 = 500.0;
/// Its axes' acceleration limit (mm/s²).
pub const A_MAX: f64 = 3000.0;
/// The factor by which a corner may exceed `A_MAX` for one cycle.
pub const OVERLOAD: f64 = 1.2;

/// Runs `program` on the 3-axis mill with `md` on top: the channel and the first `N` channel
/// axes' setpoints of every IPO cycle, the start position first. Panics when the program does
/// not end within `max_cycles` or ends with an alarm.
pub fn samples<const N: usize>(md: &str, program: &str, max_cycles: usize) -> (Channel, Vec<[f64; N]>) {
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    assert!((ch.config().ipo_cycle - DT).abs() < 1e-12);
    ch.run_program(program).unwrap();
    let first = |ch: &Channel| -> [f64; N] { std::array::from_fn(|k| ch.axis_positions()[k]) };
    let mut out = vec![first(&ch)];
    while ch.is_busy() {
        ch.step();
        out.push(first(&ch));
        assert!(out.len() <= max_cycles, "the program does not end within {max_cycles} cycles");
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    (ch, out)
}

/// Asserts velocity at most `V_MAX` per axis and a velocity change per cycle of at most
/// `A_MAX`·`OVERLOAD`·`DT`.
pub fn assert_dynamics(samples: &[[f64; 3]]) {
    let vel: Vec<[f64; 3]> = samples.windows(2).map(|w| std::array::from_fn(|k| (w[1][k] - w[0][k]) / DT)).collect();
    for (i, v) in vel.iter().enumerate() {
        for (k, vk) in v.iter().enumerate() {
            assert!(vk.abs() <= V_MAX * (1.0 + 1e-9), "axis {k} velocity {vk} in cycle {i}");
        }
    }
    for (i, w) in vel.windows(2).enumerate() {
        for (k, (v0, v1)) in w[0].iter().zip(&w[1]).enumerate() {
            let acc = (v1 - v0).abs() / DT;
            assert!(acc <= A_MAX * OVERLOAD * (1.0 + 1e-6), "axis {k} acceleration {acc} in cycle {i}");
        }
    }
}
