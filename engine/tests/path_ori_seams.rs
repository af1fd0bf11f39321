//! The orientation's rate at the seams of an ORIVECT rounding element (Function Manual B1,
//! G642 under TRAORI with OTOL): where the element takes over from a block and hands over to
//! the next, the tool vector's angular velocity goes on without a jump, so the rotary axes
//! need no more than their acceleration there. On the CA head (`head_support`).

use crate::head_support;
use head_support::*;

const START: &str = "T1 D1\nG0 X0 Y0 Z100 A20 C0\nTRAORI\nG4 F0.02\nG0 X0 Y0 Z50\n";

/// The orientation with A20 and angle C (degrees) on the head.
fn cone(c: f64) -> [f64; 3] {
    orientation(&[0.0, 0.0, 0.0, 20.0, c])
}

/// The largest change per IPO cycle of the tool vector's velocity `do/dt`, divided by the
/// cycle: the tool vector's angular acceleration in rad/s².
fn largest_orientation_acceleration(samples: &[[f64; 5]], dt: f64) -> f64 {
    let rates: Vec<[f64; 3]> = samples
        .windows(2)
        .map(|w| {
            let (a, b) = (orientation(&w[0]), orientation(&w[1]));
            [(b[0] - a[0]) / dt, (b[1] - a[1]) / dt, (b[2] - a[2]) / dt]
        })
        .collect();
    rates.windows(2).map(|w| dot(sub(w[1], w[0]), sub(w[1], w[0])).sqrt() / dt).fold(0.0, f64::max)
}

#[test]
fn the_orientation_rate_has_no_jump_at_the_seams_of_the_rounding_element() {
    // X0→20 turning the tool from C0 to C90 (A20, ORIVECT great circle), then Y0→20 from C90
    // to C180, G642 CTOL=0.05 OTOL=10° at F3000 (the rotary axes limit the path velocity).
    // The element's orientation takes over each block's rate at its seams (unit test
    // `the_element_takes_over_the_orientation_rate_of_both_blocks`), so no cycle changes the
    // tool vector's velocity by more than the rotary axes' acceleration allows: A and C
    // 720°/s² = 12.57 rad/s², and the tool vector on the head moves by Ȧ (|∂o/∂A| = 1) and
    // sin A·Ċ (|∂o/∂C| = sin A), so a change of the vector's velocity beyond 12.57 rad/s²
    // per second would need more than that of A or C. A jump at a seam (the earlier great
    // circle between the cut points) showed as one cycle's spike; the planner had to slow
    // the path until it fitted.
    let program = format!(
        "{START}ORIWKS ORIVECT G642 CTOL=0.05 OTOL=10 G1 F3000 X20 {}\nY20 {}\nM30",
        vector(cone(90.0)),
        vector(cone(180.0))
    );
    let (ch, samples) = run(&program);
    assert_machine_limits(&ch, &samples);
    let dt = ch.config().ipo_cycle;
    let bound = ch.config().axis(3).max_accel.min(ch.config().axis(4).max_accel).to_radians();
    assert!((bound - 720f64.to_radians()).abs() < 1e-9, "the preset's A/C acceleration: {bound}");
    // From the G1 block on: the positioning before (G0, its own dynamics) is not the subject.
    let from = samples.iter().rposition(|m| (tip(m)[0]).abs() < 1e-9 && (tip(m)[2] - 50.0).abs() < 1e-9).unwrap();
    let acc = largest_orientation_acceleration(&samples[from..], dt);
    assert!(acc <= bound, "the tool vector accelerates at {acc} rad/s², the axes allow {bound}");
    assert!(acc > 0.5, "the orientation does turn: {acc}");
}
