//! The two-block contour definition with ANG (Programming Manual Fundamentals, "Contour
//! definitions: two straight lines"): the corner between a line leaving the start at α1 and a
//! line into the end point at α2 is worked out by hand in each test, and every IPO sample is
//! checked against the expected lines.

use crate::trc_support;

use trc_support::{alarm_of, passes_near, polyline_dist, run_all};

#[test]
fn the_corner_is_where_the_two_lines_meet() {
    // From (10,0) at 45° to the line into (40,10) at 0° (Y = 10): the corner (20,10).
    let (ch, samples) = run_all("G17 G90 G0 X10 Y0 Z0\nG1 F1000\nANG=45\nX40 Y10 ANG=0\nM30");
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    let path = [(10.0, 0.0), (20.0, 10.0), (40.0, 10.0)];
    let from = samples.iter().position(|p| (p[0] - 10.0).abs() < 1e-9 && p[1].abs() < 1e-9).expect("the start");
    for p in &samples[from..] {
        assert!(polyline_dist((p[0], p[1]), &path) < 1e-6, "sample {p:?} off the two lines");
    }
    assert!(passes_near(&samples, 20.0, 10.0, 1e-6), "the corner is travelled");
    // The second angle may come first in the drawing's sense too: into (40,10) from below at
    // 90° after a first line along 0°: the corner (40,0).
    let (ch, samples) = run_all("G17 G90 G0 X10 Y0 Z0\nG1 F1000\nANG=0\nX40 Y10 ANG=90\nM30");
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    assert!(passes_near(&samples, 40.0, 0.0, 1e-6));
}

#[test]
fn rnd_in_the_first_block_rounds_the_corner() {
    // RND=2 at the 45° corner (interior angle 135°): the fillet keeps r/sin(67.5°) − r =
    // 2/0.92388 − 2 = 0.16478 mm from the corner at its middle.
    let (ch, samples) = run_all("G17 G90 G0 X10 Y0 Z0\nG1 F600\nANG=45 RND=2\nX40 Y10 ANG=0\nM30");
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    let nearest = samples.iter().map(|p| (p[0] - 20.0).hypot(p[1] - 10.0)).fold(f64::INFINITY, f64::min);
    assert!((nearest - 0.16478).abs() < 0.01, "nearest sample {nearest} mm from the corner");
}

#[test]
fn lines_that_do_not_meet_and_three_block_forms_are_refused_at_the_second_block() {
    for (second, why) in [
        ("X40 Y10 ANG=45", "parallel"),
        // y = x − 10 meets X = 40 at (40,30): above (40,10), which a line at 90° reaches
        // upwards, so the corner lies beyond its end.
        ("X40 Y10 ANG=90", "meet beyond the end"),
        ("X40 ANG=0", "one end coordinate"),
        ("X40 Y10", "no second angle"),
    ] {
        let (ch, _) = run_all(&format!("G17 G90 G0 X10 Y0 Z0\nG1 F1000\nANG=45\n{second}\nM30"));
        let alarm = ch.alarms().first().unwrap_or_else(|| panic!("{why}: no alarm"));
        assert_eq!((alarm.number, alarm.line), (12560, Some(4)), "{why}: {alarm:?}");
    }
}

#[test]
fn the_corner_is_compensated_like_a_programmed_one() {
    // Under G41 with a radius-5 tool the same contour as a programmed corner (20,10): the
    // centre paths agree sample for sample.
    let run = |contour: &str| {
        let program = format!("T1 D1\nG17 G90 G0 X0 Y-10 Z0\nG41 G1 X10 Y0 F1000\n{contour}\nG40 G1 X50 Y20\nM30");
        let (ch, samples) = run_all(&program);
        assert_eq!(alarm_of(&ch), None, "{contour}: {:?}", ch.alarms());
        samples
    };
    let defined = run("ANG=45\nX40 Y10 ANG=0");
    let programmed = run("X20 Y10\nX40");
    assert_eq!(defined.len(), programmed.len());
    for (a, b) in defined.iter().zip(&programmed) {
        assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9, "{a:?} vs {b:?}");
    }
}
