//! The compressor under kinematic transformations (Function Manual F2 "Orientation
//! compression", B1 "Compressor functions"): a 5-axis CAM program's short chords under
//! TRAORI with COMPCAD become a smooth curve whose tool tip stays within CTOL of the programmed
//! polyline and whose orientation stays within OTOL of the programmed one (direction vectors:
//! the great circles between them; rotary axis positions: each axis' linear motion), every
//! machine axis within its velocity and acceleration limits, in fewer IPO cycles than
//! without the compressor. Under TRANSMIT and TRACYL the face or the unrolled surface path
//! is compressed the same way.
//!
//! The part: the tip on a circle of radius 30 about the origin at Z50, 45 chords of 2° (each
//! 60·sin 1° = 1.0471 mm long, below MD20170's 10 mm), the tool tilted 20° outwards and
//! turning with the point: at polar angle φ the orientation (sin 20°·cos φ, sin 20°·sin φ,
//! cos 20°), on the CA head A20 and C = φ + 90°.

use crate::head_support;
use head_support::*;

/// The polar angle (degrees) of point `i`.
fn phi(i: usize) -> f64 {
    2.0 * i as f64
}

fn point(i: usize) -> [f64; 3] {
    let (s, c) = phi(i).to_radians().sin_cos();
    [30.0 * c, 30.0 * s, 50.0]
}

fn radial(i: usize) -> [f64; 3] {
    let (s, c) = phi(i).to_radians().sin_cos();
    let (s20, c20) = 20f64.to_radians().sin_cos();
    [s20 * c, s20 * s, c20]
}

/// The program: positioning to point 0 with the radial orientation, then the chords with
/// the orientation as vectors (`vectors`) or as rotary axis positions, after `header`.
fn program(header: &str, vectors: bool) -> String {
    let mut p = String::from("T1 D1\nG0 X0 Y0 Z100 A20 C90\nTRAORI\nG4 F0.02\nG0 X30 Y0 Z50\nG4 F0.02\n");
    p += header;
    p += if vectors { " ORIWKS ORIVECT G64 G1 F10000\n" } else { " ORIAXES G64 G1 F10000\n" };
    for i in 1..=45 {
        let [x, y, z] = point(i);
        let ori = if vectors { vector(radial(i)) } else { format!("A20 C{:.12}", phi(i) + 90.0) };
        p += &format!("X{x:.12} Y{y:.12} Z{z:.12} {ori}\n");
    }
    p + "M30"
}

/// The largest distance of the samples' tips from the programmed polyline.
fn tip_deviation(samples: &[[f64; 5]]) -> f64 {
    let pts: Vec<[f64; 3]> = (0..=45).map(point).collect();
    samples.iter().map(|m| to_polyline(tip(m), &pts)).fold(0.0, f64::max)
}

/// The largest angle (degrees) of the samples' orientations from the programmed great
/// circles (each drawn with 32 chords: their sag, 2°/32 apart, is below 1e-7°).
fn vector_deviation(samples: &[[f64; 5]]) -> f64 {
    let mut arc = vec![radial(0)];
    for i in 0..45 {
        let (a, b) = (radial(i), radial(i + 1));
        let omega = dot(a, b).clamp(-1.0, 1.0).acos();
        for j in 1..=32 {
            let u = f64::from(j) / 32.0;
            let (fa, fb) = (((1.0 - u) * omega).sin() / omega.sin(), (u * omega).sin() / omega.sin());
            arc.push([fa * a[0] + fb * b[0], fa * a[1] + fb * b[1], fa * a[2] + fb * b[2]]);
        }
    }
    samples
        .iter()
        .map(|m| 2.0 * (0.5 * to_polyline(orientation(m), &arc)).min(1.0).asin().to_degrees())
        .fold(0.0, f64::max)
}

/// The largest difference (degrees) of the samples' C from its programmed linear motion at
/// the point of the chord nearest to the tip, and of A from 20°.
fn axis_deviation(samples: &[[f64; 5]]) -> f64 {
    samples
        .iter()
        .map(|m| {
            let p = tip(m);
            let (i, t) = (0..45)
                .map(|i| {
                    let (a, b) = (point(i), point(i + 1));
                    let d = sub(b, a);
                    let t = (dot(sub(p, a), d) / dot(d, d)).clamp(0.0, 1.0);
                    let q = [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]];
                    (i, t, dot(sub(q, p), sub(q, p)))
                })
                .min_by(|x, y| x.2.total_cmp(&y.2))
                .map(|(i, t, _)| (i, t))
                .unwrap();
            let c = phi(i) + 90.0 + 2.0 * t;
            (m[4] - c).abs().max((m[3] - 20.0).abs())
        })
        .fold(0.0, f64::max)
}

/// The samples of the chords alone: from the cycle before C first turns past 90° (point 0's
/// C; the positioning before stands at it).
fn chords(samples: &[[f64; 5]]) -> &[[f64; 5]] {
    let first = samples.iter().position(|m| m[4] > 90.0 + 1e-9).unwrap();
    &samples[first - 1..]
}

#[test]
fn vector_orientation_chords_are_compressed_within_ctol_and_otol() {
    // CTOL 0.01: the curve runs close to the circle, 30·(1 − cos 1°) = 4.57 µm outside the
    // chords at their middles, so the tip's largest distance from the polyline is about that
    // (> 0.004: really a curve; ≤ 0.01). OTOL 0.05°: the quintic through the vectors runs
    // close to the cone they lie on, which leaves a great circle between two vectors 2° apart
    // by about sin 20°·cos 20°·(1°)²/2 = 0.0028° at its middle (≤ 0.05°, > 0.001°).
    let (ch, compressed) = run(&program("COMPCAD CTOL=0.01 OTOL=0.05", true));
    let (_, plain) = run(&program("COMPOF", true));
    assert_machine_limits(&ch, &compressed);
    let (tip_d, ori_d) = (tip_deviation(chords(&compressed)), vector_deviation(chords(&compressed)));
    assert!((0.004..=0.01).contains(&tip_d), "the tip leaves the polyline by {tip_d} mm");
    assert!((0.001..=0.05).contains(&ori_d), "the orientation leaves the great circles by {ori_d}°");
    let end = tip(compressed.last().unwrap());
    assert!((0..3).all(|k| (end[k] - point(45)[k]).abs() < 1e-6), "ends at {end:?}");
    assert!(
        compressed.len() < plain.len(),
        "{} IPO cycles compressed, {} without the compressor",
        compressed.len(),
        plain.len()
    );
}

#[test]
fn rotary_axis_chords_are_compressed_within_ctol_and_the_axes_tolerance() {
    // The orientation as A20 C=φ+90 (ORIAXES): the rotary axes' positions are compressed as
    // axial polynomials within OTOL 0.05° of their programmed linear motion (C turns evenly
    // with the tip: the parabola through three positions is that line), the tip as above.
    let (ch, compressed) = run(&program("COMPCAD CTOL=0.01 OTOL=0.05", false));
    let (_, plain) = run(&program("COMPOF", false));
    assert_machine_limits(&ch, &compressed);
    let tip_d = tip_deviation(chords(&compressed));
    assert!((0.004..=0.01).contains(&tip_d), "the tip leaves the polyline by {tip_d} mm");
    let axis_d = axis_deviation(chords(&compressed));
    assert!(axis_d <= 0.05, "a rotary axis leaves its programmed motion by {axis_d}°");
    assert!(
        compressed.len() < plain.len(),
        "{} IPO cycles compressed, {} without the compressor",
        compressed.len(),
        plain.len()
    );
}

#[test]
fn a_tolerance_too_small_for_the_chords_leaves_them_as_programmed() {
    // CTOL 0.001 is below the 4.57 µm the curve needs beside each chord: every block stays
    // its line, and the path is the polyline (deviation below a micrometre).
    let (_, samples) = run(&program("COMPCAD CTOL=0.001 OTOL=0.05", true));
    let d = tip_deviation(chords(&samples));
    assert!(d < 1e-6, "the tip leaves the polyline by {d} mm");
}

/// A circle of radius 10 in 45 chords of 2° in the plane of a 2-axis transformation: `at(i)`
/// the programmed point `i` (its plane's two coordinates), `words` the block that goes there,
/// `sample` the plane point of a machine sample. Runs the chords after `start` under COMPCAD
/// CTOL=0.01 and under COMPOF; returns the compressed path's largest distance from the chords
/// (from the last sample at point 0 on: the approach ends there) and both cycle counts.
fn plane_circle(
    preset: &str,
    start: &str,
    at: impl Fn(usize) -> [f64; 2],
    words: impl Fn([f64; 2]) -> String,
    sample: impl Fn(&[f64]) -> [f64; 3] + Copy,
) -> (f64, usize, usize) {
    let run_with = |header: &str| {
        let mut p = format!("{start}{header} G64\n");
        for i in 1..=45 {
            p += &words(at(i));
            p += "\n";
        }
        p += "M30";
        run_on(preset, &p, sample).1
    };
    let (compressed, plain) = (run_with("COMPCAD CTOL=0.01"), run_with("COMPOF"));
    let pts: Vec<[f64; 3]> = (0..=45).map(|i| [at(i)[0], at(i)[1], 0.0]).collect();
    let from = compressed.iter().rposition(|&p| dot(sub(p, pts[0]), sub(p, pts[0])) < 1e-12).unwrap();
    let d = compressed[from..].iter().map(|&p| to_polyline(p, &pts)).fold(0.0, f64::max);
    (d, compressed.len(), plain.len())
}

#[test]
fn face_chords_under_transmit_are_compressed_within_ctol() {
    // TRANSMIT (transmit-example: the face milled with XC and C; x = XC·cos C, y = XC·sin C):
    // a circle of radius 10 about the centre at F3000. The manual (B1) compresses the
    // geometry axes' path, which TRANSMIT maps: the face path stays within CTOL 0.01 of the
    // chords, 10·(1 − cos 1°) = 1.52 µm outside them at their middles, and the program takes
    // fewer cycles than without the compressor.
    let (d, compressed, plain) = plane_circle(
        "transmit-example",
        "T1 D1 G17 G90 G94\nG0 X20 Z10\nTRANSMIT\nG1 F3000 X10 Y0\n",
        |i| {
            let (s, c) = phi(i).to_radians().sin_cos();
            [10.0 * c, 10.0 * s]
        },
        |[x, y]| format!("X{x:.12} Y{y:.12}"),
        |m| {
            let c = m[1].to_radians();
            [m[0] * c.cos(), m[0] * c.sin(), 0.0]
        },
    );
    assert!((0.0013..=0.01).contains(&d), "the face path leaves the chords by {d} mm");
    assert!(compressed < plain, "{compressed} cycles against {plain}");
}

#[test]
fn surface_chords_under_tracyl_are_compressed_within_ctol() {
    // TRACYL(40) (tracyl-xyzc: the surface unrolled, y = C·π·40/360 along the periphery, z =
    // Z): a circle of radius 10 about (y, z) = (0, −10) at F3000. As under TRANSMIT the
    // unrolled path is compressed: within CTOL 0.01 of the chords and 1.52 µm outside them at
    // their middles, in fewer cycles than without.
    let (d, compressed, plain) = plane_circle(
        "tracyl-xyzc",
        "G0 X20 Y0 Z0\nTRACYL(40)\nG1 F3000 Y0 Z0\n",
        |i| {
            let (s, c) = phi(i).to_radians().sin_cos();
            [10.0 * s, -10.0 + 10.0 * c]
        },
        |[y, z]| format!("Y{y:.12} Z{z:.12}"),
        |m| [m[3] * std::f64::consts::PI * 40.0 / 360.0, m[2], 0.0],
    );
    assert!((0.0013..=0.01).contains(&d), "the unrolled path leaves the chords by {d} mm");
    assert!(compressed < plain, "{compressed} cycles against {plain}");
}
