//! SOFT where a line runs tangentially into an arc (Function Manual B2 "Acceleration and jerk":
//! jerk limitation at block transitions without constant curvature, MD32432
//! `$MA_PATH_TRANS_JERK_LIM`). There is no corner, but the centripetal acceleration v²/r of
//! the axis across the seam jumps within one IPO cycle: a jerk of v²/(r·T). Under SOFT the path
//! velocity at the seam is limited so that this jerk stays within MD32431 (or MD32432 where
//! that is higher), and inside the arc the axes' jerk from the turning (v³/r² along the
//! tangent, 3·v·a/r along the radius) stays within MD32431 too (`motion/soft_curvature.rs`).
//! The 3-axis mill: 3000 mm/s², T = 4 ms.

use crate::path_support;

use path_support::DT;

/// The k-th finite difference of the samples divided by `dt^k`, per axis.
fn diff(samples: &[[f64; 3]], k: usize) -> Vec<[f64; 3]> {
    let mut d = samples.to_vec();
    for _ in 0..k {
        d = d.windows(2).map(|w| std::array::from_fn(|i| (w[1][i] - w[0][i]) / DT)).collect();
    }
    d
}

/// X10 along +X, the quarter circle R5 about (10, 5) to (15, 5) (it leaves along +Y), then Y20.
const PROGRAM: &str = "SOFT G64 G1 X10 Y0 F6000\nG3 X15 Y5 CR=5\nG1 Y20\nM30";

/// MD32431 = 100 m/s³ on X, Y, Z, and `extra` on top.
fn run(extra: &str) -> Vec<[f64; 3]> {
    let md = format!("$MA_MAX_AX_JERK[X]=100\n$MA_MAX_AX_JERK[Y]=100\n$MA_MAX_AX_JERK[Z]=100\n{extra}");
    path_support::samples::<3>(&md, PROGRAM, 100_000).1
}

/// The cycle that crosses from the line onto the arc (the first sample past X10), and the path
/// speed (mm/s) of that cycle.
fn seam(s: &[[f64; 3]]) -> (usize, f64) {
    let i = s.iter().position(|p| p[0] > 10.0).unwrap();
    (i, (s[i][0] - s[i - 1][0]).hypot(s[i][1] - s[i - 1][1]) / DT)
}

#[test]
fn every_axis_keeps_its_jerk_at_the_seam_and_on_the_arc() {
    // MD32431 = 100 m/s³ = 100 000 mm/s³. At the seam Y's acceleration jumps by v²/r within a
    // cycle: v² ≤ J·T·r = 100 000 · 0.004 · 5 = 2000, v ≤ 44.72 mm/s (the arc alone would
    // allow √(0.5·3000·5) = 86.6 mm/s, the feed 100). The S curve arrives at or below the
    // planned speed. Every cycle's third difference stays within 100 000 mm/s³ on every axis.
    let s = run("");
    let (_, v) = seam(&s);
    assert!(v <= 2000f64.sqrt() + 1e-9 && v > 5.0, "crosses the seam at {v} mm/s");
    for (i, j) in diff(&s, 3).iter().enumerate() {
        for (axis, jk) in j.iter().enumerate() {
            assert!(jk.abs() <= 100_000.0 * (1.0 + 1e-6), "axis {axis} jerk {jk} in cycle {i}");
        }
    }
    assert_eq!(s.last().unwrap(), &[15.0, 20.0, 0.0]);
}

#[test]
fn path_trans_jerk_lim_raises_the_seam_speed_and_bounds_the_jump() {
    // MD32432 = 200 m/s³ on X and Y: v² ≤ 200 000 · 0.004 · 5 = 4000, v ≤ 63.25 mm/s at the
    // seam: faster than with MD32431 alone, and the cycles at the seams (the line into the arc
    // and the arc into the line along +Y) stay within 200 000 mm/s³; every other cycle within
    // MD32431's 100 000.
    let s = run("$MA_PATH_TRANS_JERK_LIM[X]=200\n$MA_PATH_TRANS_JERK_LIM[Y]=200");
    let (at, v) = seam(&s);
    assert!(v <= 4000f64.sqrt() + 1e-9, "crosses the seam at {v} mm/s");
    let (_, v_low) = seam(&run(""));
    assert!(v > v_low, "MD32432 lets the path cross faster: {v} vs {v_low} mm/s");
    let out = s.iter().position(|p| p[1] > 5.0).unwrap();
    for (i, j) in diff(&s, 3).iter().enumerate() {
        // A third difference spans four samples: those of cycles i..=i+3.
        let near = |c: usize| (i..=i + 3).contains(&c) || (i..=i + 3).contains(&(c - 1));
        let limit = if near(at) || near(out) { 200_000.0 } else { 100_000.0 };
        for (axis, jk) in j.iter().enumerate() {
            assert!(jk.abs() <= limit * (1.0 + 1e-6), "axis {axis} jerk {jk} in cycle {i} (seams at {at}, {out})");
        }
    }
}

/// Jerk 20 m/s³ on every axis.
const SOFT_MD: &str = "$MA_MAX_AX_JERK[X]=20\n$MA_MAX_AX_JERK[Y]=20\n$MA_MAX_AX_JERK[Z]=20\n";

#[test]
fn soft_ramps_its_acceleration_down_before_a_move_with_less() {
    // A short move at 3 m/s² (ACC 100 %) into a collinear one at ACC[X]=30 (900 mm/s²) or
    // ACC[X]=10 (300 mm/s²) while the path still speeds up to F6000: the acceleration of the
    // first move (up to sqrt(j·Δv) = 1414 mm/s² with j = 20 m/s³) must be down to the second
    // move's before the path enters it, one jerk step j·T per cycle: the third difference of
    // X stays within 20 000 mm/s³ in every cycle (it went to 62 000 and 245 000 before), and
    // the acceleration never exceeds the second move's once the path is in it.
    for (program, a_next) in [("X2 F6000\nACC[X]=30 X100", 900.0), ("X1 F6000\nACC[X]=10 X100", 300.0)] {
        let (_, s) = path_support::samples::<3>(SOFT_MD, &format!("SOFT G64 G1 {program}\nM30"), 100_000);
        let cube = DT * DT * DT;
        let jerk = s
            .windows(4)
            .map(|w| ((w[3][0] - 3.0 * w[2][0] + 3.0 * w[1][0] - w[0][0]) / cube).abs())
            .fold(0.0, f64::max);
        assert!(jerk <= 20_000.0 * (1.0 + 1e-6), "{program}: jerk {jerk} mm/s³");
        let seam: f64 = program[1..program.find(' ').unwrap()].parse().unwrap();
        for (i, w) in s.windows(3).enumerate() {
            let acc = (w[2][0] - 2.0 * w[1][0] + w[0][0]) / (DT * DT);
            if w[0][0] >= seam {
                assert!(acc.abs() <= a_next * (1.0 + 1e-6), "{program}: {acc} mm/s² in cycle {i} past the seam");
            }
        }
        assert_eq!(s.last().unwrap(), &[100.0, 0.0, 0.0]);
    }
}
