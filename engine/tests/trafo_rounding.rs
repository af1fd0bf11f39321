//! Corner rounding under kinematic transformations (Function Manual B1, G642 with the contour
//! tolerance CTOL and the orientation tolerance OTOL): the tool tip's corner is rounded in the
//! BCS within CTOL, the orientation within OTOL, and every machine axis keeps its limits. The
//! TRAORI tests run on the CA head preset
//! (`mill5-head-ca`: C about Z carrying A about X, pivot 150 mm above the spindle nose, T1 of
//! 100 mm), whose closed form gives the tip and the orientation of every machine sample:
//! `o = (sin C·sin A, −cos C·sin A, cos A)`, tip `P = M − 250·o + (0, 0, 150)`.

use crate::head_support;
use head_support::*;

/// The tool tilted 20° (A20 C0), TRAORI, the tip to X0 Y0 Z50. (Z reverses between the
/// positioning before TRAORI and the first move under it: the stop's cycle at rest keeps it
/// within its acceleration, which `assert_machine_limits` checks too.)
const START: &str = "T1 D1\nG0 X0 Y0 Z100 A20 C0\nTRAORI\nG0 X0 Y0 Z50\n";

#[test]
fn a_square_with_a_fixed_tilted_orientation_is_rounded_at_its_corners_within_ctol() {
    // The tool tilted 20° (A20 C0: o = (0, −0.342, 0.940)) and left so (ORIAXES, the rotary
    // axes stand): the tip runs a 20 mm square at Z50 under G642 CTOL=0.05. In the BCS the
    // corners are rounded as without a transformation: the tip passes each of the three inner
    // corners at no more than 0.05 mm (a search within 2 % below the tolerance: at least
    // 0.049 on the element; the samples 0.004 mm apart at F60 join by chords whose sagitta is
    // below 1e-4 mm), and the machine's linear axes, which carry the tip plus the fixed
    // 250·o, follow it.
    let program = format!("{START}G642 CTOL=0.05 G1 F60 X20\nY20\nX0\nY0\nM30");
    let (ch, samples) = run(&program);
    for c in [[20.0, 0.0, 50.0], [20.0, 20.0, 50.0], [0.0, 20.0, 50.0]] {
        let (d, angle) = deviations(&samples, c, [0.0, -20f64.to_radians().sin(), 20f64.to_radians().cos()]);
        assert!((0.049..=0.05 + 1e-4).contains(&d), "corner {c:?}: the tip passes at {d} mm");
        assert!(angle < 1e-9, "the orientation stays: {angle}°");
    }
    let end = tip(samples.last().unwrap());
    assert!(end.iter().zip([0.0, 0.0, 50.0]).all(|(a, b)| (a - b).abs() < 1e-9), "{end:?}");
    assert_machine_limits(&ch, &samples);
}

/// The orientation with A20 and angle C (degrees) on the head.
fn cone(c: f64) -> [f64; 3] {
    orientation(&[0.0, 0.0, 0.0, 20.0, c])
}

#[test]
fn a_corner_where_the_orientation_turns_too_is_rounded_within_otol() {
    // X0→20 while the orientation turns on the great circle from C0 to C90 (both A20), then
    // Y0→20 while it turns on from C90 to C180 (ORIWKS ORIVECT): the two great circles meet at the
    // C90 orientation at an angle, a corner of the orientation at the tip's corner. The
    // element turns the tool from the orientation where it leaves the first block to the one
    // where it joins the second, taking over both blocks' rates there, and passes the C90
    // orientation at an angle that grows with the cut-back. G642 CTOL=0.05: with OTOL=10° the contour bounds the element alone; with
    // OTOL=0.01° the orientation does, and the element is cut back until the orientation
    // passes C90 within 0.01° (and still > 0), the tip then nearer than 0.05 to its corner.
    let run_with = |otol: f64| {
        let program = format!(
            "{START}ORIWKS ORIVECT G642 CTOL=0.05 OTOL={otol} G1 F60 X20 {}\nY20 {}\nM30",
            vector(cone(90.0)),
            vector(cone(180.0))
        );
        let (ch, samples) = run(&program);
        assert_machine_limits(&ch, &samples);
        deviations(&samples, [20.0, 0.0, 50.0], cone(90.0))
    };
    let (wide_tip, wide_ori) = run_with(10.0);
    let (tip_d, ori) = run_with(0.01);
    assert!((0.049..=0.05 + 1e-4).contains(&wide_tip), "OTOL=10: the tip passes at {wide_tip} mm");
    assert!(wide_ori > 0.01, "OTOL=10: the orientation passes at {wide_ori}°, more than 0.01°");
    // The element's orientation bends (it takes over both blocks' rates at its ends), and
    // the chords between the samples lie on the inner side of that bend, farther from the
    // corner orientation than the curve (the element itself passes at 0.00998°): 2 % allowed
    // for that.
    assert!(ori <= 0.01 * 1.02 && ori > 0.0, "OTOL=0.01: the orientation passes at {ori}°");
    assert!(tip_d < wide_tip && tip_d > 0.0, "OTOL=0.01: the tip passes at {tip_d} mm");
}

#[test]
fn a_square_on_the_face_under_transmit_is_rounded_within_ctol() {
    // The manual's TRANSMIT square (Transformations FM, M1 §2.1.5: T1, the face milled with the
    // radial axis XC and C) under G642 CTOL=0.05 at F60: the face corners (−10, −10),
    // (−10, 10) and (10, 10), 14.1 mm from the centre, are rounded in the BCS as on a
    // Cartesian machine: each passed at 0.049..0.05 mm (the samples 0.004 mm apart, the
    // chords' sagitta below 1e-4 mm). Polar: x = XC·cos C, y = XC·sin C.
    let program = "T1 D1 G17 G90 G94\nG0 X20 Z10\nTRANSMIT\nG1 F60 X10 Y-10\n\
        G642 CTOL=0.05 X-10\nY10\nX10\nY-10\nM30";
    let (_, face) = run_on("transmit-example", program, |p| {
        let c = p[1].to_radians();
        [p[0] * c.cos(), p[0] * c.sin(), 0.0]
    });
    for c in [[-10.0, -10.0, 0.0], [-10.0, 10.0, 0.0], [10.0, 10.0, 0.0]] {
        let d = to_polyline(c, &face);
        assert!((0.049..=0.05 + 1e-4).contains(&d), "corner {c:?}: passed at {d} mm");
    }
}
