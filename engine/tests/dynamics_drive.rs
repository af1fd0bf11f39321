//! DRIVE (G group 21): the knee-shaped acceleration of Function Manual B2. Above the switching
//! speed MD35220 · MD32000 an axis accelerates with less than MD32300, down to
//! (1 − MD35230) · MD32300 at MD32000; MD35242 picks the shape (0 constant, 1 hyperbolic,
//! 2 linear). Expected values worked out by hand in each test's comment.

use crate::path_support;

use path_support::{A_MAX, DT, V_MAX};

/// X switches at 0.4 · 500 = 200 mm/s and keeps 40 % (1200 mm/s²) at 500 mm/s; `kind` is
/// MD35242.
fn reduction_md(kind: u8) -> String {
    format!(
        "$MA_ACCEL_REDUCTION_SPEED_POINT[X]=0.4\n$MA_ACCEL_REDUCTION_FACTOR[X]=0.6\n$MA_ACCEL_REDUCTION_TYPE[X]={kind}\n"
    )
}

const V_RED: f64 = 200.0;
const A_RED: f64 = 1200.0;

/// The hand formula of B2's linear characteristic for X.
fn linear(v: f64) -> f64 {
    if v <= V_RED { A_MAX } else { A_MAX - (A_MAX - A_RED) * (v - V_RED) / (V_MAX - V_RED) }
}

/// The hyperbola through (200, 3000) and (500, 1200): a = c0 + c1/v with
/// c1 = 1800 / (1/200 − 1/500) = 600 000 and c0 = 3000 − 600 000/200 = 0.
fn hyperbolic(v: f64) -> f64 {
    if v <= V_RED { A_MAX } else { 600_000.0 / v }
}

/// X's velocity in every IPO cycle of `program` (X only moves).
fn x_velocities(md: &str, program: &str) -> (Vec<[f64; 3]>, Vec<f64>) {
    let (_, s) = path_support::samples::<3>(md, program, 100_000);
    let v = s.windows(2).map(|w| (w[1][0] - w[0][0]) / DT).collect();
    (s, v)
}

#[test]
fn drive_accelerates_along_the_characteristic_and_brakes_within_it() {
    // G1 X400 at the axis' 500 mm/s. Every cycle that speeds up ends at a speed v whose
    // allowed acceleration a(v) it used: (v − v_prev)/T = a(v), by the hand formulas above,
    // but the cycle that reaches the feed (it may use less). Braking never loses more per
    // cycle than a(v) at the cycle's higher speed allows (and loses just that but at the
    // ends), and the move ends on X400 exactly.
    for (kind, a_of) in [(2u8, linear as fn(f64) -> f64), (1, hyperbolic)] {
        let (s, v) = x_velocities(&reduction_md(kind), "DRIVE G1 X400 F30000\nM30");
        assert_eq!(s.last().unwrap(), &[400.0, 0.0, 0.0]);
        let (mut rising, mut reduced, mut braking, mut exact_braking) = (0, 0, 0, 0);
        let mut prev = 0.0;
        for (i, &w) in v.iter().enumerate() {
            assert!(w <= V_MAX * (1.0 + 1e-12), "type {kind} cycle {i}: {w} mm/s");
            let acc = (w - prev) / DT;
            if acc > 1e-6 && w < V_MAX - 1e-9 {
                assert!(
                    (acc - a_of(w)).abs() <= 1e-6 * A_MAX,
                    "type {kind} cycle {i} at {w} mm/s: {acc} vs {}",
                    a_of(w)
                );
                rising += 1;
                reduced += usize::from(w > V_RED);
            } else if acc < -1e-6 {
                assert!(-acc <= a_of(prev) * (1.0 + 1e-9), "type {kind} cycle {i} from {prev} mm/s: {}", -acc);
                braking += 1;
                exact_braking += usize::from((-acc - a_of(prev)).abs() <= 1e-6 * A_MAX);
            }
            prev = w;
        }
        assert!(rising > 50 && reduced > 30 && braking > 50, "type {kind}: {rising} {reduced} {braking}");
        // Braking runs the curve backwards: every cycle but the stop's last (partial) one loses
        // exactly a(v)·T from its speed v.
        assert!(exact_braking + 2 >= braking, "type {kind}: {exact_braking} of {braking} braking cycles on the curve");
    }
}

#[test]
fn the_time_to_full_speed_is_the_integral_of_one_over_a() {
    // t = ∫ dv / a(v) from 0 to 500 mm/s. Linear: 200/3000 + ∫ dv/(3000 − 6(v − 200)) over
    // 200..500 = 0.066667 + ln(3000/1200)/6 = 0.066667 + 0.152715 = 0.219382 s. Hyperbolic
    // (a = 600 000/v above 200): 0.066667 + (500² − 200²)/(2 · 600 000) = 0.241667 s. BRISK:
    // 500/3000 = 0.166667 s. Counted: the cycles until X first moves at 500 mm/s. Each cycle
    // uses the acceleration of its end speed, the lowest of its range, so the discrete ramp is
    // never faster than the integral; it is slower by the last partial cycle (< 1 cycle) and,
    // on the linear curve, by the implicit step: ln(1 + 6·T)/(6·T) = 0.988 of the continuous
    // rate over 0.1527 s, 0.45 cycle. So t ≤ time < t + 1.5 cycles.
    for (md, words, t) in [
        (reduction_md(1), "DRIVE", 0.241667),
        (reduction_md(2), "DRIVE", 0.219382),
        (reduction_md(2), "BRISK", 0.166667),
        (String::new(), "DRIVE", 0.166667),
    ] {
        let (_, v) = x_velocities(&md, &format!("{words} G1 X400 F30000\nM30"));
        let cycles = v.iter().position(|&w| w >= V_MAX - 1e-9).unwrap() + 1;
        let time = cycles as f64 * DT;
        assert!(time >= t - 1e-9 && time < t + 1.5 * DT, "{words} {md:?}: {time} s, by hand {t}");
    }
}

#[test]
fn brisk_and_drive_without_a_reduction_run_bit_for_bit_as_before() {
    // The reduction data act only under DRIVE, and DRIVE with the data's defaults (MD35220 = 1,
    // MD35230 = 0) is BRISK: the same setpoints to the bit.
    let program = |w: &str| format!("{w} G1 X100 Y20 F6000\nG64 X150 Y80\nG2 X200 Y30 CR=40\nG0 X0 Y0\nM30");
    let (_, plain) = path_support::samples::<3>("", &program("BRISK"), 100_000);
    let (_, with_md) = path_support::samples::<3>(&reduction_md(2), &program("BRISK"), 100_000);
    let (_, drive) = path_support::samples::<3>("", &program("DRIVE"), 100_000);
    assert_eq!(plain, with_md);
    assert_eq!(plain, drive);
    // DRIVE with the reduction on X takes longer (the same end point).
    let (_, reduced) = path_support::samples::<3>(&reduction_md(2), &program("DRIVE"), 100_000);
    assert!(reduced.len() > plain.len());
    assert_eq!(reduced.last(), plain.last());
}

#[test]
fn drive_on_a_contour_stays_within_the_axes_and_ends_on_its_points() {
    // Diagonals, an arc and a rapid move under DRIVE with the reduction on X: no axis above
    // 500 mm/s or 1.2 · 3000 mm/s² in any cycle, and the end on the programmed point.
    let program = "DRIVE F30000\nG1 X300 Y40\nG64 X320 Y200\nG2 X100 Y200 CR=110\nG1 X0 Y0\nG0 X250 Z-10\nM30";
    let (_, s) = path_support::samples::<3>(&reduction_md(2), program, 100_000);
    path_support::assert_dynamics(&s);
    assert_eq!(s.last().unwrap(), &[250.0, 0.0, -10.0]);
}
