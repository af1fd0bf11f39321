//! CIP: circular interpolation through an intermediate point (Programming Manual Fundamentals,
//! "Circular interpolation with intermediate and end point"): the start, the intermediate point
//! `I1=/J1=/K1=` and the end point fix the circle; G90/G91 and AC/IC apply to the intermediate
//! point as to the end point; the circle may lie obliquely in space. Expected centres and radii
//! are worked out by hand in each test, and every IPO sample is checked against them.

use crate::trc_support;

use trc_support::{alarm_of, passes_near, run_all, run_to_stop};

/// Every sample after the first `skip` (the approach) up to the end lies on the circle about
/// `c` with radius `r` in the X/Y plane at height `z`.
fn on_plane_circle(samples: &[Vec<f64>], from: usize, c: (f64, f64), r: f64, z: f64) {
    for p in &samples[from..] {
        let d = (p[0] - c.0).hypot(p[1] - c.1);
        assert!((d - r).abs() < 1e-6, "sample {p:?} is {d} from {c:?}, not {r}");
        assert!((p[2] - z).abs() < 1e-9, "sample {p:?} left Z {z}");
    }
}

/// The index of the first sample at the circle's start `(x, y)` (the approach ends there).
fn start_index(samples: &[Vec<f64>], x: f64, y: f64) -> usize {
    samples.iter().position(|p| (p[0] - x).hypot(p[1] - y) < 1e-9).expect("the start is reached")
}

#[test]
fn the_manual_example_runs_over_the_short_arc_through_the_intermediate_point() {
    // From (30,40) through (40,45) to (50,40): the centre lies on the chord's bisector X = 40 at
    // (40, c) with 10² + (40 − c)² = (45 − c)², so c = 32.5 and the radius 12.5. The arc runs
    // clockwise over the top (Y ≥ 40 between the ends).
    let (ch, samples) = run_all("G17 G90 G0 X30 Y40 Z-5\nG1 F3000\nCIP X50 Y40 I1=40 J1=45\nR1=$P_GG[1]\nM30");
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    let from = start_index(&samples, 30.0, 40.0);
    on_plane_circle(&samples, from, (40.0, 32.5), 12.5, -5.0);
    assert!(samples[from..].iter().all(|p| p[1] > 40.0 - 1e-9), "the arc stays above Y 40");
    assert!(passes_near(&samples, 40.0, 45.0, 0.2), "through the intermediate point");
    let end = samples.last().unwrap();
    assert!((end[0] - 50.0).abs() < 1e-9 && (end[1] - 40.0).abs() < 1e-9, "ends at (50,40): {end:?}");
    // G group 1 reads CIP (5) in the program, and the display names it (at the M0 after it).
    assert_eq!(ch.r_param(1), 5.0);
    let (ch, _) = run_to_stop("mill-3axis", "", "G17 G90 G0 X30 Y40\nG1 F3000\nCIP X50 Y40 I1=40 J1=45\nM0\nM30");
    assert!(ch.snapshot().gcodes.iter().any(|g| g == "CIP"), "{:?}", ch.snapshot().gcodes);
}

#[test]
fn incremental_values_count_from_the_start_and_cip_is_modal() {
    // G91: the same circle as above from (30,40), then a second CIP block back to (30,40)
    // through (40,20) (incremental from (50,40): −10, −20): the lower part of the same circle
    // (about (40,32.5): (40,20) is 12.5 below the centre), clockwise on.
    let (ch, samples) = run_all("G17 G90 G0 X30 Y40 Z0\nG91 G1 F3000\nCIP X20 Y0 I1=10 J1=5\nX-20 I1=-10 J1=-20\nM30");
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    let from = start_index(&samples, 30.0, 40.0);
    on_plane_circle(&samples, from, (40.0, 32.5), 12.5, 0.0);
    assert!(passes_near(&samples, 40.0, 45.0, 0.2) && passes_near(&samples, 40.0, 20.0, 0.2));
    assert!(passes_near(&samples, 52.5, 32.5, 0.2), "clockwise past the rightmost point");
}

#[test]
fn points_off_the_working_plane_give_a_circle_in_space() {
    // Centre (0,0,0), radius 10 in the plane Y = Z: u = (1,0,0), v = (0,1,1)/√2. Start 10·u =
    // (10,0,0), intermediate 10·(u + v)/√2 = (7.0711, 5, 5), end 10·v = (0, 7.0711, 7.0711).
    let h = 10.0 / 2f64.sqrt();
    let program = format!("G17 G90 G0 X10 Y0 Z0\nG1 F2000\nCIP X0 Y{h} Z{h} I1={h} J1=5 K1=5\nM30");
    let (ch, samples) = run_all(&program);
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    let from = samples.iter().position(|p| (p[0] - 10.0).abs() < 1e-9 && p[1].abs() < 1e-9).expect("the start");
    for p in &samples[from..] {
        let d = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((d - 10.0).abs() < 1e-6, "sample {p:?} is {d} from the centre");
        assert!((p[1] - p[2]).abs() < 1e-6, "sample {p:?} off the plane Y = Z");
    }
    assert!(passes_near(&samples, h, 5.0, 0.2), "through the intermediate point");
    let end = samples.last().unwrap();
    assert!(end[0].abs() < 1e-9 && (end[1] - h).abs() < 1e-9 && (end[2] - h).abs() < 1e-9, "{end:?}");
}

#[test]
fn a_quarter_in_space_takes_the_time_of_its_arc_length() {
    // The quarter above is 10·π/2 = 15.708 mm long: at F600 (10 mm/s) 1.571 s plus a few
    // milliseconds of acceleration and braking (the chord, 14.142 mm, would take 1.414 s):
    // the program's time with the CIP block less its time without it.
    let h = 10.0 / 2f64.sqrt();
    let time = |cip: &str| {
        let (ch, _) = run_all(&format!("G17 G90 G0 X10 Y0 Z0\nG1 F600\n{cip}\nM30"));
        assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
        ch.time()
    };
    let travel = time(&format!("CIP X0 Y{h} Z{h} I1={h} J1=5 K1=5")) - time("");
    assert!((std::f64::consts::FRAC_PI_2..1.62).contains(&travel), "{travel} s for 15.708 mm at 10 mm/s");
}

#[test]
fn three_points_on_a_line_are_alarm_14040_and_space_circles_refuse_radius_compensation() {
    let (ch, _) = run_all("G17 G90 G0 X0 Y0 Z0\nG1 F1000\nCIP X20 Y0 I1=10 J1=0\nM30");
    assert_eq!(alarm_of(&ch), Some(14040), "{:?}", ch.alarms());
    assert_eq!(ch.alarms()[0].line, Some(3));
    let (ch, _) = run_all(
        "$TC_DP1[1,1]=120\n$TC_DP6[1,1]=2\nT1 D1\nG17 G90 G0 X0 Y0 Z0\nG41 G1 X10 F1000\nCIP X0 Y7 Z7 I1=7 J1=5 K1=5\nM30",
    );
    let alarm = ch.alarms().iter().find(|a| a.line == Some(6)).unwrap_or_else(|| panic!("{:?}", ch.alarms()));
    assert!(alarm.message.contains("CIP"), "{}", alarm.message);
}
