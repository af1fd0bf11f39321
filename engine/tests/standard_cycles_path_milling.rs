//! CYCLE72 (path milling) along a rectangle, with its contour named directly or through
//! CYCLE62, checked on every sampled point against positions worked out by hand. The tool is
//! T1 D1 of the 3-axis mill: an end mill of radius 5.
//!
//! The contour: the rectangle X0..60, Y0..40, starting at (30, 0) in the middle of its lower
//! edge and running clockwise (-X first, then up the left edge, along the top, down the right
//! edge and back to (30, 0)). Left of it (G41) is outside: the tool centre runs 5 (the radius)
//! outside the rectangle on the straight edges and on arcs of radius 5 about its corners (G450).

use crate::cycles_support;
use cycles_support::*;

const Z: usize = 2;

/// The contour as a labelled section behind M30, with labels `a` and `e`.
fn section(a: &str, e: &str) -> String {
    format!("{a}: G1 X30 Y0\nG1 X0\nG1 Y40\nG1 X60\nG1 Y0\n{e}: G1 X30\n")
}

const SETUP: &str = "G17 G90 G94 T1 D1 S3000 M3\nG0 X80 Y-30 Z20\n";

/// CYCLE72 roughing left of the contour: RTP 10, RFP 0, SDIS 2, DP -10, MID 4, no
/// allowances, FFP1 300, FFD 100, _VARI 1 (roughing, G0 between, retract to RTP), _RL 41,
/// _AS1 1 (tangential line, infeed in the plane) with _LP1 5, FF3 1000, _AS2 1 with _LP2 5.
const ARGS: &str = "10,0,2,-10,4,0,0,300,100,1,41,1,5,1000,1,5,0,0,0,0,0,0)";

/// Distance of (x, y) from the rectangle X0..60, Y0..40 (0 inside).
fn off_rectangle(x: f64, y: f64) -> f64 {
    let dx = (-x).max(0.0).max(x - 60.0);
    let dy = (-y).max(0.0).max(y - 40.0);
    dx.hypot(dy)
}

/// The samples from the arrival at the start height Z20 on (before it, the length offset's
/// first cycle puts the tip below the part).
fn after_start(t: &Trace) -> &[Sample] {
    let from = t.samples.iter().position(|p| p.b[Z] >= 20.0 - 1e-9).unwrap();
    &t.samples[from..]
}

fn main_with(call: &str, contour: &str) -> String {
    format!("{SETUP}{call}\nM30\n{contour}")
}

#[test]
fn cycle72_left_of_a_rectangle_runs_the_tool_centre_5_outside_in_three_depth_infeeds() {
    let t = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{ARGS}"), &section("CONT_A", "CONT_E")));
    let s = after_start(&t);
    // Below the surface the tool is always beside the contour at the radius: on the approach
    // line (40, -5) → (30, -5), around the rectangle, on the retraction (30, -5) → (20, -5),
    // and in the infeed at (40, -5). Never inside the allowance, never off the path.
    let below: Vec<&Sample> = s.iter().filter(|p| p.b[Z] < -1e-9).collect();
    assert!(!below.is_empty());
    for p in &below {
        let d = off_rectangle(p.b[0], p.b[1]);
        assert!((d - 5.0).abs() < 1e-6, "({}, {}, {}) is {d} off the rectangle", p.b[0], p.b[1], p.b[Z]);
    }
    // Depth infeeds: (0 - -10) / 4 = 2.5, so 3 equal infeeds of 10/3: Z -3.333, -6.667, -10.
    // The left edge's tool centre X-5 is passed once at each depth.
    let mut levels: Vec<f64> = Vec::new();
    for p in s.iter().filter(|p| (p.b[0] + 5.0).abs() < 1e-6 && p.b[1] > 5.0 && p.b[1] < 35.0) {
        if !levels.iter().any(|z| (z - p.b[Z]).abs() < 1e-6) {
            levels.push(p.b[Z]);
        }
    }
    assert_eq!(levels.len(), 3, "{levels:?}");
    for (z, want) in levels.iter().zip([-10.0 / 3.0, -20.0 / 3.0, -10.0]) {
        assert!(close(*z, want, 1e-6), "{levels:?}");
    }
    // Each level's approach: G341 infeeds at (40, -5), the tangent line's start (DISR 5 plus
    // the radius 5 back from the compensated start (30, -5)); the top edge's centre (30, 45).
    for z in [-10.0 / 3.0, -20.0 / 3.0, -10.0] {
        let at = |x: f64, y: f64| {
            s.iter().any(|p| close(p.b[0], x, 1e-6) && close(p.b[1], y, 1e-6) && close(p.b[Z], z, 1e-6))
        };
        assert!(at(40.0, -5.0), "no infeed at (40, -5, {z})");
        assert!(at(30.0, 45.0) && at(65.0, 20.0) && at(15.0, -5.0), "edges at {z}");
    }
    // The retraction leaves along the last edge's direction (-X) by DISR 5 + radius 5 from
    // (30, -5) to (20, -5), rises to the safety plane and on to RTP Z10.
    let end = t.end();
    assert!(close(end[0], 20.0, 1e-9) && close(end[1], -5.0, 1e-9) && close(end[Z], 10.0, 1e-9), "{end:?}");
}

#[test]
fn cycle72_finishing_is_one_pass_at_depth_and_roughing_keeps_the_allowances() {
    // Finishing (_VARI 2): one pass at Z-10 on the radius.
    let args = ARGS.replacen(",1,41,", ",2,41,", 1);
    let t = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{args}"), &section("CONT_A", "CONT_E")));
    let below: Vec<&Sample> = after_start(&t).iter().filter(|p| p.b[Z] < -1e-9).collect();
    let lowest = below.iter().map(|p| p.b[Z]).fold(f64::INFINITY, f64::min);
    assert!(close(lowest, -10.0, 1e-9));
    assert!(!below.iter().any(|p| (p.b[0] + 5.0).abs() < 1e-6 && p.b[Z] > -10.0 + 1e-6), "left edge above depth");
    // Roughing with _FAL 0.5, _FALD 1: the tool centre 5.5 off the edges, the infeeds from 0
    // down to -9: 9 / 4 = 2.25, so 3 of 3 mm; the lowest level is Z-9.
    let args = ARGS.replacen("4,0,0,300", "4,0.5,1,300", 1);
    let t = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{args}"), &section("CONT_A", "CONT_E")));
    let below: Vec<&Sample> = after_start(&t).iter().filter(|p| p.b[Z] < -1e-9).collect();
    for p in &below {
        assert!((off_rectangle(p.b[0], p.b[1]) - 5.5).abs() < 1e-6, "({}, {}, {})", p.b[0], p.b[1], p.b[Z]);
    }
    let lowest = below.iter().map(|p| p.b[Z]).fold(f64::INFINITY, f64::min);
    assert!(close(lowest, -9.0, 1e-9), "{lowest}");
    assert!(below.iter().any(|p| close(p.b[Z], -3.0, 1e-9)) && below.iter().any(|p| close(p.b[Z], -6.0, 1e-9)));
}

#[test]
fn cycle62_names_the_contour_in_its_four_forms_and_cycle72_follows_it() {
    let direct = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{ARGS}"), &section("CONT_A", "CONT_E")));
    let sub = format!("{}M17\n", section("SUB_A", "SUB_E"));
    let forms = [
        // 0: the contour calculator's labels E_LAB_A_<name> .. E_LAB_E_<name>.
        ("CYCLE62(\"RECT\",0,,)".to_string(), section("E_LAB_A_RECT", "E_LAB_E_RECT")),
        // 1: a subprogram.
        ("CYCLE62(\"RECT_SUB\",1,,)".to_string(), String::new()),
        // 2: labels of the calling program.
        ("CYCLE62(,2,\"CONT_A\",\"CONT_E\")".to_string(), section("CONT_A", "CONT_E")),
        // 3: labels in a subprogram.
        ("CYCLE62(\"RECT_SUB\",3,\"SUB_A\",\"SUB_E\")".to_string(), String::new()),
    ];
    for (call, contour) in forms {
        let main = main_with(&format!("{call}\nCYCLE72(\"\",{ARGS}"), &contour);
        let t = run_on("mill-3axis", &main, &[("RECT_SUB", &sub)]);
        assert!(t.alarms.is_empty(), "{call}: {:?}", t.alarms);
        assert_eq!(t.end(), direct.end(), "{call}");
        assert_eq!(after_start(&t).len(), after_start(&direct).len(), "{call}: another path");
    }
}

#[test]
fn cycle72_refuses_a_missing_contour_and_wrong_parameters() {
    // A label that is not there: 14080; no contour at all: 61605; _RL 43: 61002; no feed: 61003.
    let t = run(&main_with(&format!("CYCLE72(\"NO_A:NO_E\",{ARGS}"), &section("CONT_A", "CONT_E")));
    assert_eq!(t.alarms.first().map(|a| a.number), Some(14080), "{:?}", t.alarms);
    let t = run(&main_with(&format!("CYCLE72(\"\",{ARGS}"), ""));
    assert_eq!(t.alarms.first().map(|a| a.number), Some(61605), "{:?}", t.alarms);
    let t = run(&main_with(
        &format!("CYCLE72(\"CONT_A:CONT_E\",{}", ARGS.replacen(",41,", ",43,", 1)),
        &section("CONT_A", "CONT_E"),
    ));
    assert_eq!(t.alarms.first().map(|a| (a.number, a.line)), Some((61002, Some(3))), "{:?}", t.alarms);
    let t = run(&main_with(
        &format!("CYCLE72(\"CONT_A:CONT_E\",{}", ARGS.replacen("300,100", "0,100", 1)),
        &section("CONT_A", "CONT_E"),
    ));
    assert_eq!(t.alarms.first().map(|a| a.number), Some(61003), "{:?}", t.alarms);
}

/// The same rectangle counter-clockwise: from (30, 0) along +X first.
fn ccw_section(a: &str, e: &str) -> String {
    format!("{a}: G1 X30 Y0\nG1 X60\nG1 Y40\nG1 X0\nG1 Y0\n{e}: G1 X30\n")
}

#[test]
fn cycle72_right_of_a_counter_clockwise_contour_approaches_on_a_quadrant() {
    // _RL 42, _AS1 2 / _AS2 2 (quadrants of radius 5), one infeed (_MID 0) to Z-10. Right of
    // +X is -Y: the compensated start is (30, -5); the quadrant's centre lies 5 further right,
    // (30, -10), and it starts a quarter turn back along the tangent at (25, -10), where the
    // infeed runs. The retraction: the quadrant about (30, -10) from (30, -5) to (35, -10).
    let args = ARGS.replacen(",4,0,0,", ",0,0,0,", 1).replacen(",41,1,5,1000,1,5,", ",42,2,5,1000,2,5,", 1);
    let t = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{args}"), &ccw_section("CONT_A", "CONT_E")));
    let s = after_start(&t);
    let below: Vec<&Sample> = s.iter().filter(|p| p.b[Z] < -1e-9).collect();
    for p in &below {
        assert!(off_rectangle(p.b[0], p.b[1]) >= 5.0 - 1e-6, "({}, {}, {}) cuts into the part", p.b[0], p.b[1], p.b[Z]);
        // One level: off Z-10 only the infeed at (25, -10) and the lift at (35, -10).
        let (infeed, lift) = ((25.0, -10.0), (35.0, -10.0));
        let on = |(x, y): (f64, f64)| close(p.b[0], x, 1e-9) && close(p.b[1], y, 1e-9);
        assert!(close(p.b[Z], -10.0, 1e-9) || on(infeed) || on(lift), "({}, {}, {})", p.b[0], p.b[1], p.b[Z]);
    }
    let at = |x: f64, y: f64| {
        below.iter().any(|p| close(p.b[0], x, 1e-6) && close(p.b[1], y, 1e-6) && close(p.b[Z], -10.0, 1e-9))
    };
    assert!(at(25.0, -10.0) && at(45.0, -5.0) && at(65.0, 20.0) && at(30.0, 45.0) && at(-5.0, 20.0));
    // The approach quadrant: 5 from (30, -10) between (25, -10) and (30, -5).
    let arc: Vec<&&Sample> = below.iter().filter(|p| p.b[0] < 30.0 - 1e-6 && p.b[1] < -5.0 - 1e-6).collect();
    assert!(!arc.is_empty());
    for p in arc {
        assert!(close((p.b[0] - 30.0).hypot(p.b[1] + 10.0), 5.0, 1e-6), "({}, {})", p.b[0], p.b[1]);
    }
    let end = t.end();
    assert!(close(end[0], 35.0, 1e-9) && close(end[1], -10.0, 1e-9) && close(end[Z], 10.0, 1e-9), "{end:?}");
}

#[test]
fn cycle72_on_the_contour_runs_the_tool_centre_on_it_with_straight_approach_and_retraction() {
    // _RL 40: no compensation. The approach line starts _LP1 5 back along the first edge's
    // direction (-X) from (30, 0): at (35, 0); the retraction ends 5 on along the last edge's
    // direction at (25, 0). Everything below the surface lies on the rectangle's outline.
    let args = ARGS.replacen(",41,", ",40,", 1);
    let t = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{args}"), &section("CONT_A", "CONT_E")));
    let s = after_start(&t);
    for p in s.iter().filter(|p| p.b[Z] < -1e-9) {
        let (x, y) = (p.b[0], p.b[1]);
        let to_edge = x.min(60.0 - x).min(y).min(40.0 - y).abs().max(off_rectangle(x, y));
        assert!(to_edge < 1e-6, "({x}, {y}, {}) off the outline", p.b[Z]);
    }
    let infeeds = s
        .windows(2)
        .filter(|w| close(w[0].b[0], 35.0, 1e-9) && w[1].b[Z] < w[0].b[Z] - 1e-9 && w[0].b[Z] <= 0.0)
        .count();
    assert!(infeeds > 0, "the infeed runs at (35, 0)");
    let end = t.end();
    assert!(close(end[0], 25.0, 1e-9) && close(end[1], 0.0, 1e-9) && close(end[Z], 10.0, 1e-9), "{end:?}");
}

#[test]
fn cycle72_approach_in_space_descends_along_the_approach_line() {
    // _AS1 11: the tangential line in space (G340). The tool comes down at (40, -5) only to
    // the safety plane Z2 and descends along the line to the compensated start (30, -5) at
    // the first depth -10/3: Z = 2 + (-10/3 - 2) · (40 - X) / 10.
    let args = ARGS.replacen(",41,1,5,", ",41,11,5,", 1);
    let t = run_clean(&main_with(&format!("CYCLE72(\"CONT_A:CONT_E\",{args}"), &section("CONT_A", "CONT_E")));
    let s = after_start(&t);
    let first = -10.0 / 3.0;
    let arrive = s
        .iter()
        .position(|p| close(p.b[0], 30.0, 1e-9) && close(p.b[1], -5.0, 1e-9) && close(p.b[Z], first, 1e-9))
        .unwrap();
    let leave = s[..arrive].iter().rposition(|p| close(p.b[0], 40.0, 1e-9) && close(p.b[Z], 2.0, 1e-9)).unwrap();
    for p in &s[leave..=arrive] {
        let want = 2.0 + (first - 2.0) * (40.0 - p.b[0]) / 10.0;
        assert!(close(p.b[1], -5.0, 1e-9) && close(p.b[Z], want, 1e-6), "({}, {}, {})", p.b[0], p.b[1], p.b[Z]);
    }
    assert!(!s[..arrive].iter().any(|p| close(p.b[0], 40.0, 1e-9) && p.b[Z] < 2.0 - 1e-6), "no infeed at (40, -5)");
}
