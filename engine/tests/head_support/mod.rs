//! Running a program on the CA head (`mill5-head-ca`: C about Z carrying A about X, pivot
//! 150 mm above the spindle nose, T1 of 100 mm) and reading the tool tip and orientation of
//! every IPO cycle from the machine axes by the head's closed form
//! `o = (sin C·sin A, −cos C·sin A, cos A)`, tip `P = M − 250·o + (0, 0, 150)`; shared by
//! the tests of rounding and compression under transformations.
#![allow(dead_code)]

use nctwin_engine::Channel;

/// `sample` of the channel axes' positions in every IPO cycle of `program` on `preset`.
pub fn run_on<T>(preset: &str, program: &str, sample: impl Fn(&[f64]) -> T) -> (Channel, Vec<T>) {
    let mut ch = Channel::from_preset(preset, "").unwrap();
    ch.run_program(program).unwrap();
    let mut out = Vec::new();
    while ch.is_busy() {
        ch.step();
        out.push(sample(ch.axis_positions()));
        assert!(out.len() < 2_000_000, "the program does not end");
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    (ch, out)
}

/// The machine positions (X, Y, Z, A, C) of every IPO cycle of `program` on the CA head.
pub fn run(program: &str) -> (Channel, Vec<[f64; 5]>) {
    run_on("mill5-head-ca", program, |p| [p[0], p[1], p[2], p[3], p[4]])
}

pub fn orientation(m: &[f64; 5]) -> [f64; 3] {
    let (sa, ca) = m[3].to_radians().sin_cos();
    let (sc, cc) = m[4].to_radians().sin_cos();
    [sc * sa, -cc * sa, ca]
}

pub fn tip(m: &[f64; 5]) -> [f64; 3] {
    let o = orientation(m);
    [m[0] - 250.0 * o[0], m[1] - 250.0 * o[1], m[2] + 150.0 - 250.0 * o[2]]
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The distance of point `c` from the polyline through `pts` (the samples joined by chords).
pub fn to_polyline(c: [f64; 3], pts: &[[f64; 3]]) -> f64 {
    pts.windows(2)
        .map(|w| {
            let d = sub(w[1], w[0]);
            let len2 = dot(d, d);
            let t = if len2 > 0.0 { (dot(sub(c, w[0]), d) / len2).clamp(0.0, 1.0) } else { 0.0 };
            let q = [w[0][0] + t * d[0], w[0][1] + t * d[1], w[0][2] + t * d[2]];
            dot(sub(q, c), sub(q, c)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The tip's distance from corner `c` and the orientation's angle (degrees) from `o` at the
/// nearest sampled orientation (the chords between unit samples, normalised).
pub fn deviations(samples: &[[f64; 5]], c: [f64; 3], o: [f64; 3]) -> (f64, f64) {
    let tips: Vec<[f64; 3]> = samples.iter().map(tip).collect();
    let oris: Vec<[f64; 3]> = samples.iter().map(orientation).collect();
    // The chord distance from `o` gives the angle: 2·asin(chord/2) (the chord inside the
    // sphere: a little more than the arc's).
    let chord = to_polyline(o, &oris);
    (to_polyline(c, &tips), 2.0 * (0.5 * chord).asin().to_degrees())
}

/// Every machine axis within its velocity and (with MD32310's one-cycle overload at a
/// transition) its acceleration in every IPO cycle.
pub fn assert_machine_limits(ch: &Channel, samples: &[[f64; 5]]) {
    let dt = ch.config().ipo_cycle;
    for k in 0..5 {
        let ax = ch.config().axis(k);
        let v: Vec<f64> = samples.windows(2).map(|w| (w[1][k] - w[0][k]) / dt).collect();
        let vmax = v.iter().map(|x| x.abs()).fold(0.0, f64::max);
        assert!(vmax <= ax.max_velocity * (1.0 + 1e-6), "axis {k}: {vmax} > {}", ax.max_velocity);
        let amax = v.windows(2).map(|w| ((w[1] - w[0]) / dt).abs()).fold(0.0, f64::max);
        assert!(amax <= ax.max_accel * ax.accel_overload * (1.0 + 1e-6), "axis {k}: {amax} > {}", ax.max_accel);
    }
}

/// The orientation words of unit vector `o`.
pub fn vector(o: [f64; 3]) -> String {
    format!("A3={:.12} B3={:.12} C3={:.12}", o[0], o[1], o[2])
}
