//! Acceleration, jerk and the servo model: BRISK/SOFT (G group 21), the dynamic response modes
//! (G group 59), ACC/VELOLIM/JERKLIM, FFWON/FFWOF (G group 24) with the position loop.
//! Expected values are worked out by hand in each test's comment.

use nctwin_engine::Channel;

/// The 3-axis mill's IPO cycle (4 ms).
const DT: f64 = 0.004;

/// Runs `program` on the 3-axis mill with `md` on top; the channel-axis setpoints of every
/// IPO cycle.
fn run(md: &str, program: &str) -> (Channel, Vec<[f64; 3]>) {
    let mut ch = Channel::from_preset("mill-3axis", md).unwrap();
    ch.run_program(program).unwrap();
    let mut out = vec![pos(&ch)];
    while ch.is_busy() {
        ch.step();
        out.push(pos(&ch));
        assert!(out.len() < 2_000_000, "runs away");
    }
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    (ch, out)
}

fn pos(ch: &Channel) -> [f64; 3] {
    let p = ch.axis_positions();
    [p[0], p[1], p[2]]
}

/// The k-th finite difference of the samples divided by `dt^k`, per axis.
fn diff(samples: &[[f64; 3]], k: usize) -> Vec<[f64; 3]> {
    let mut d = samples.to_vec();
    for _ in 0..k {
        d = d.windows(2).map(|w| std::array::from_fn(|i| (w[1][i] - w[0][i]) / DT)).collect();
    }
    d
}

fn max_abs(d: &[[f64; 3]], axis: usize) -> f64 {
    d.iter().map(|v| v[axis].abs()).fold(0.0, f64::max)
}

/// Jerk 20 m/s³ on every axis, so the 3 m/s² of the preset take 0.15 s (37 cycles) to build.
const SOFT_MD: &str = "$MA_MAX_AX_JERK[X]=20\n$MA_MAX_AX_JERK[Y]=20\n$MA_MAX_AX_JERK[Z]=20\n";

#[test]
fn soft_keeps_every_axis_within_its_jerk() {
    // A square, a diagonal and short blocks, exact stop and continuous path. No axis' third
    // difference of the sampled positions may exceed 20 m/s³ = 20 000 mm/s³; the bound
    // allows 10 % for the discretisation.
    let program = "SOFT F6000\nG1 X100\nY50\nX0 Y0\nG64 X10\nX20 Y1\nX30 Y3\nX40 Y2\nG0 X80 Y40 Z-20\nM30";
    let (_, s) = run(SOFT_MD, program);
    let jerk = diff(&s, 3);
    for axis in 0..3 {
        let j = max_abs(&jerk, axis);
        assert!(j <= 22_000.0, "axis {axis}: jerk {j} mm/s³");
    }
    assert_eq!(s.last().unwrap(), &[80.0, 40.0, -20.0]);
}

#[test]
fn brisk_has_the_acceleration_steps_soft_removes() {
    // The same 100 mm line: under BRISK the acceleration jumps from 0 to 3000 mm/s² in one
    // cycle (jerk 3000/0.004 = 750 000 mm/s³); under SOFT it builds up over 0.15 s.
    let program = |p: &str| format!("{p} G1 X100 F6000\nM30");
    let (_, brisk) = run(SOFT_MD, &program("BRISK"));
    let (_, soft) = run(SOFT_MD, &program("SOFT"));
    assert!(max_abs(&diff(&brisk, 3), 0) > 500_000.0);
    assert!(max_abs(&diff(&soft, 3), 0) <= 22_000.0);
    // Time: BRISK takes L/v + v/a = 100/100 + 100/3000 = 1.0333 s. Under SOFT the jerk
    // would need a/j = 0.15 s to reach 3000 mm/s², but the 100 mm/s are gained before that:
    // the acceleration rises to sqrt(j·Δv) = sqrt(20000·100) = 1414 mm/s² and falls again,
    // 2·sqrt(Δv/j) = 0.1414 s per speed change, and a symmetric change covers v·t/2, so the
    // move takes L/v + 0.1414 = 1.1414 s: 0.1081 s more, allowing 3 cycles.
    let extra = (soft.len() as f64 - brisk.len() as f64) * DT;
    assert!((extra - 0.1081).abs() <= 3.0 * DT, "SOFT took {extra} s more");
}

