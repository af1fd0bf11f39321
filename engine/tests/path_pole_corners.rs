//! Continuous-path rounding at and next to the pole of a transformation (Function Manual B1
//! G642 with F2 "Behavior at pole" and the TRANSMIT pole of M1).
//!
//! Decision: where the control turns a pole axis alone (TRAORI: MD21108 POLE_ORI_MODE units
//! digit 0, "the pole axis is traversed to its end position at the start of the block while
//! the orientation stays in the pole"; TRANSMIT: leaving the pole at another angle than the
//! path arrived, the rotary axis turns in the pole), the path stands while that axis turns,
//! so the corner before it cannot be rounded: it stays sharp, the tool tip passes the
//! programmed corner exactly. A corner beside the pole, whose rounding passes the pole at a
//! distance, is rounded like any other within CTOL (the machine axes' limits then slow the
//! path near the pole).

use crate::head_support;
use head_support::*;

/// The TRANSMIT face: x = XC·cos C, y = XC·sin C.
fn face(program: &str) -> Vec<[f64; 3]> {
    run_on("transmit-example", program, |m| {
        let c = m[1].to_radians();
        [m[0] * c.cos(), m[0] * c.sin(), 0.0]
    })
    .1
}

#[test]
fn a_corner_in_the_transmit_pole_stays_sharp() {
    // X10 → X0 (the pole) along the X axis, then → Y10: the path arrives with C at 0° and
    // leaves with C at 90°; C turns in the pole while XC stands at 0. Under G642 CTOL=0.05 the
    // tip reaches the pole (0, 0) exactly.
    let samples = face("T1 D1 G17 G90 G94\nG0 X20 Z10\nTRANSMIT\nG1 F300 X10 Y0\nG642 CTOL=0.05 X0 Y0\nY10\nM30");
    let d = to_polyline([0.0, 0.0, 0.0], &samples);
    assert!(d < 1e-6, "the corner in the pole is passed at {d} mm");
    let end = samples.last().unwrap();
    assert!((end[0]).abs() < 1e-6 && (end[1] - 10.0).abs() < 1e-6, "{end:?}");
}

#[test]
fn a_corner_beside_the_transmit_pole_is_rounded_within_ctol() {
    // X10 Y-1 → X1 Y-1 → X1 Y10: the corner (1, −1), 1.41 mm from the pole, rounded under
    // G642 CTOL=0.05 as on a Cartesian machine: passed at 0.049..0.05 mm (the search stops
    // within 2 % below the tolerance). F60 (1 mm/s: C turns at most 1 rad/s = 57°/s at 1 mm
    // from the pole), so that the feed is not limited unevenly by C (alarm 10910).
    let samples = face("T1 D1 G17 G90 G94\nG0 X20 Z10\nTRANSMIT\nG1 F60 X10 Y-1\nG642 CTOL=0.05 X1\nY10\nM30");
    let d = to_polyline([1.0, -1.0, 0.0], &samples);
    assert!((0.049..=0.05 + 1e-4).contains(&d), "the corner beside the pole is passed at {d} mm");
}

#[test]
fn a_corner_before_the_pole_axis_turns_under_traori_stays_sharp() {
    // The CA head: the tool vertical (A0: the orientation in the pole, C free) at the corner
    // (20, 0, 50); the next block tilts it to A20 C90 as a vector (ORIVECT) while the tip
    // runs to (20, 20, 50). C must stand at the great circle's azimuth from the start: it
    // turns alone first (MD21108 units digit 0), so the corner stays sharp: the tip reaches
    // (20, 0, 50) exactly under G642 CTOL=0.05.
    let program = format!(
        "T1 D1\nG0 X0 Y0 Z100 A0 C0\nTRAORI\nG4 F0.02\nG0 X0 Y0 Z50\nORIWKS ORIVECT G642 CTOL=0.05 G1 F600 X20 {}\nY20 {}\nM30",
        vector([0.0, 0.0, 1.0]),
        vector(orientation(&[0.0, 0.0, 0.0, 20.0, 90.0]))
    );
    let (ch, samples) = run(&program);
    assert_machine_limits(&ch, &samples);
    let tips: Vec<[f64; 3]> = samples.iter().map(tip).collect();
    let d = to_polyline([20.0, 0.0, 50.0], &tips);
    assert!(d < 1e-6, "the corner before the pole turn is passed at {d} mm");
}
