//! RTLIOF: G0 with each axis at its own rapid velocity; RTLION: linear G0. mill-3axis: X and Y
//! rapid 30000 mm/min = 500 mm/s, acceleration 3 m/s² = 3000 mm/s² (the preset's MD32000/32300).
//!
//! `G0 X100 Y10` from the origin, worked by hand:
//! - RTLIOF: Y (10 mm) never reaches 500 mm/s (that takes 41.7 mm): a triangle of
//!   2·√(10/3000) = 0.1155 s. X reaches 500 mm/s after 0.1667 s and 41.67 mm, so it passes 50 at
//!   0.1833 s, when Y has long arrived: Y = 10 there. X alone takes 2·0.1667 + 16.67/500 =
//!   0.3667 s, the block's time.
//! - RTLION: Y = X/10 all along, 5 at X = 50; the path (100.499 mm) is limited by X: v =
//!   502.5 mm/s, a = 3015 mm/s², time 100.499/502.5 + 502.5/3015 = 0.3667 s, the same.

use crate::settle;

use settle::{channel, settle};

/// The Y of the first IPO sample at which X has passed 50, and the samples until rest.
fn y_at_x50(rapid_mode: &str) -> (f64, usize) {
    let mut ch = channel("mill-3axis", "");
    ch.run_program(&format!("G0 X0 Y0 Z0\n{rapid_mode}\nG4 F0.1\nG0 X100 Y10\nM30\n")).unwrap();
    let samples = settle(&mut ch);
    let first = samples.iter().position(|s| s[0] > 0.0).expect("X moves");
    let at = samples.iter().find(|s| s[0] >= 50.0).expect("X passes 50");
    let last = samples.iter().rposition(|s| (s[0] - 100.0).abs() > 1e-9 || (s[1] - 10.0).abs() > 1e-9).unwrap();
    assert!((samples.last().unwrap()[1] - 10.0).abs() < 1e-9);
    (at[1], last - first + 1)
}

#[test]
fn rtliof_moves_each_axis_at_its_own_rapid() {
    let ipo = channel("mill-3axis", "").config().ipo_cycle;
    let (y, cycles) = y_at_x50("RTLIOF");
    assert!((y - 10.0).abs() < 1e-9, "Y at X=50: {y}");
    // The single-axis interpolator of POS (channel/positioning_axes.rs) runs the exact discrete
    // trapezoid, which is L/(V·dt) + V/(a·dt) − 1 = 50 + 41.67 − 1 = 90.67 cycles of 4 ms with
    // a·dt = 12 mm/s: 91 moving cycles, the last one landing on X100; counted here from the
    // first sample past 0 to the last one short of the end, 90.
    assert_eq!(cycles, 90, "block time {} s", cycles as f64 * ipo);
}

#[test]
fn rtlion_interpolates_rapid_linearly() {
    let ipo = channel("mill-3axis", "").config().ipo_cycle;
    let (y, cycles) = y_at_x50("RTLION");
    // The first sample past X=50 is at most one cycle's travel (500 mm/s) beyond it.
    assert!((5.0..=5.0 + 50.0 * ipo).contains(&y), "Y at X=50: {y}");
    let t = cycles as f64 * ipo;
    assert!((t - 0.3667).abs() < 3.0 * ipo, "block time {t}");
}
