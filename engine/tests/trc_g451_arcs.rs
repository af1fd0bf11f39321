//! G451 at outer corners with arcs (issue 25, item 2) and MD20210 CUTCOM_CORNER_LIMIT: the
//! tool centre goes to the intersection of the equidistants nearest the corner for line-arc,
//! arc-line and arc-arc transitions too; where they do not meet, or the change of direction
//! reaches MD20210 (default 100 deg), it takes the transition circle about the corner (Function
//! Manual W1, "Outside corners"). The mill's T1 D1 has radius 5. Expected points are worked
//! out here from the circle and line equations, not taken from the engine.

use crate::trc_support;

use nctwin_engine::Status;
use trc_support::{alarm_of, go_on, passes_near, run_all, run_all_on, run_to_stop};

const ISSUE_LINE_ARC: &str = "G17 G90 T1 D1 G451\nG0 X-20 Y20 Z0\nG41 G1 X0 Y0 F1000\nG1 X30 Y0\nM0\nG3 X50 Y0 I10 J10\nG1 X60 Y-10\nG40 G1 X80 Y-10\nM30";

/// Line (0,0)→(30,0) then G3 about (40,10), radius √200, from 225° to 315° (through the bottom
/// of the circle): the arc starts heading (1,−1)/√2, a right turn of 45°, and G41 is left of
/// the path, so the corner is outer. The line's equidistant is y = 5, the arc's (inside the
/// counter-clockwise arc) the circle of radius ρ = √200 − 5 about (40,10); they meet where
/// (x−40)² = ρ² − 25, the root nearest the corner x = 40 − √(ρ² − 25) = 32.346331.
/// After the arc, the line to (60,−10) heads (1,−1)/√2 from heading (1,1)/√2: another right
/// turn (outer). Its equidistant is x + y = 50 + 5√2; with u = x − 40, w = y − 10:
/// u + w = 5√2, u² + w² = ρ², u = (5√2 + √(2ρ² − 50))/2 = 8.947495 (the root nearest (50,0)).
#[test]
fn line_arc_and_arc_line_outer_corners_meet_at_the_intersection() {
    let rho = 200f64.sqrt() - 5.0;
    let x1 = 40.0 - (rho * rho - 25.0).sqrt();
    assert!((x1 - 32.346331).abs() < 1e-6, "hand value {x1}");
    let (mut ch, samples) = run_to_stop("mill-3axis", "", ISSUE_LINE_ARC);
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    let at = ch.axis_positions();
    assert!((at[0] - x1).abs() < 1e-6 && (at[1] - 5.0).abs() < 1e-6, "at the M0: {at:?}");
    // Up to the corner the centre stays on y = 5 after the approach.
    assert!(samples.iter().filter(|p| p[0] > 0.0).all(|p| (p[1] - 5.0).abs() < 1e-9), "on y = 5");
    ch.start().unwrap();
    let rest = go_on(&mut ch);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let s2 = 2f64.sqrt();
    let u = (5.0 * s2 + (2.0 * rho * rho - 50.0).sqrt()) / 2.0;
    let corner2 = (40.0 + u, 10.0 + 5.0 * s2 - u);
    assert!((corner2.0 - 48.947495).abs() < 1e-6 && (corner2.1 - 8.123573).abs() < 1e-6);
    assert!(passes_near(&rest, corner2.0, corner2.1, 1e-6), "arc-line corner {corner2:?}");
    // On the arc every sample lies on the circle of radius ρ about (40,10) (no transition
    // circle about (30,0) or (50,0)).
    let on_arc: Vec<_> = rest.iter().filter(|p| p[1] < 5.0 - 1e-6 && p[0] < corner2.0 - 1e-6).collect();
    assert!(!on_arc.is_empty());
    for p in on_arc {
        assert!(((p[0] - 40.0).hypot(p[1] - 10.0) - rho).abs() < 1e-6, "{p:?}");
    }
    assert_eq!(&ch.axis_positions()[..2], &[80.0, -10.0]);
}

/// The issue's second case: line (0,30)→(0,50) then G2 to (80,50) about (40, 50 − 44.72136),
/// radius √(40² + 44.72136²) = 60. The arc starts heading (44.72136, 40)/60, a right turn from
/// +Y, so with G41 the corner is outer; the line's equidistant is x = −5, the arc's (left of a
/// clockwise arc: outside) the circle of radius 65. They meet at
/// y = 5.27864 + √(65² − 45²) = 52.183.
#[test]
fn line_into_a_clockwise_arc_meets_the_larger_circle() {
    let prog = "G17 G90 T1 D1\nG0 X-20 Y0 Z0\nG41 G451 G1 X0 Y30 F1000\nG1 X0 Y50\nM0\nG2 X80 Y50 I40 J-44.72136\nG40 G1 X100 Y80\nM30";
    let (ch, _) = run_to_stop("mill-3axis", "", prog);
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    let cy = 50.0 - 44.72136;
    let r = (40f64.powi(2) + 44.72136f64.powi(2)).sqrt();
    let y = cy + ((r + 5.0).powi(2) - 45f64.powi(2)).sqrt();
    assert!((y - 52.183).abs() < 1e-3);
    let at = ch.axis_positions();
    assert!((at[0] + 5.0).abs() < 1e-6 && (at[1] - y).abs() < 1e-6, "{at:?} expected (-5, {y})");
}

/// Arc-arc: two clockwise arcs (0,0)→(20,0) about (10,−30) and (20,0)→(40,0) about (30,−30),
/// radius √1000, with G42 (right of a clockwise arc: inside, radius √1000 − 5). At (20,0) the
/// path turns left by 2·atan(10/30) = 36.9°, an outer corner for G42. By symmetry the circles
/// meet on x = 20 at y = −30 + √((√1000 − 5)² − 10²).
#[test]
fn arc_arc_outer_corner_meets_at_the_intersection() {
    let prog = "G17 G90 T1 D1 G451\nG0 X-20 Y20 Z0\nG42 G1 X0 Y0 F1000\nG2 X20 Y0 I10 J-30\nM0\nG2 X40 Y0 I10 J-30\nG40 G1 X60 Y20\nM30";
    let (ch, _) = run_to_stop("mill-3axis", "", prog);
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    let rho = 1000f64.sqrt() - 5.0;
    let y = -30.0 + (rho * rho - 100.0).sqrt();
    let at = ch.axis_positions();
    assert!((at[0] - 20.0).abs() < 1e-6 && (at[1] - y).abs() < 1e-6, "{at:?} expected (20, {y})");
}

/// Arc-arc without an intersection: the same arcs with radius √200 about (10,−10) and (30,−10);
/// the inner equidistants (radius √200 − 5 = 9.14 < 10, half the distance of the centres) do
/// not meet, so G451 falls back to the transition circle about the corner (20,0): from
/// (20,0) + 5·(−1,−1)/√2 round through (20,−5) to (20,0) + 5·(1,−1)/√2.
#[test]
fn arc_arc_without_an_intersection_takes_the_transition_circle() {
    let prog = "G17 G90 T1 D1 G451\nG0 X-20 Y20 Z0\nG42 G1 X0 Y0 F1000\nG2 X20 Y0 I10 J-10\nG2 X40 Y0 I10 J-10\nG40 G1 X60 Y20\nM30";
    let (ch, samples) = run_all(prog);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let h = 5.0 / 2f64.sqrt();
    for (x, y) in [(20.0 - h, -h), (20.0 + h, -h)] {
        assert!(passes_near(&samples, x, y, 1e-6), "({x}, {y})");
    }
    let round: Vec<_> = samples.iter().filter(|p| (p[0] - 20.0).abs() < h - 1e-3 && p[1] < 0.0).collect();
    assert!(!round.is_empty());
    for p in round {
        assert!(((p[0] - 20.0).hypot(p[1]) - 5.0).abs() < 1e-6, "{p:?}");
    }
}

/// MD20210 (issue 25, item 6): `G41 G451`, line (0,0)→(100,0) then to (56.699,−25), heading
/// (−0.866, −0.5): a right turn of 150°, outer for G41. The intersection of the equidistants
/// would be at X118.660 Y5; 150° ≥ 100° (the default), so the tool stops at X100 Y5 (the
/// perpendicular point) and goes round the tip on the circle of radius 5 about (100,0).
#[test]
fn a_pointed_corner_beyond_md20210_takes_the_transition_circle() {
    let prog =
        "G17 G90 T1 D1\nG0 X-20 Y20 Z0\nG41 G451 G1 X0 Y0 F1000\nG1 X100 Y0\nM0\nG1 X56.699 Y-25\nG40 G1 X40 Y-40\nM30";
    let (mut ch, _) = run_to_stop("mill-3axis", "", prog);
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    let at = ch.axis_positions();
    assert!((at[0] - 100.0).abs() < 1e-6 && (at[1] - 5.0).abs() < 1e-6, "{at:?}");
    ch.start().unwrap();
    let rest = go_on(&mut ch);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert!(rest.iter().all(|p| p[0] < 105.0 + 1e-9), "never beyond the circle about the tip");
    // Away from the joins (continuous-path mode may blend them within its tolerance).
    let round: Vec<_> = rest.iter().filter(|p| p[0] > 100.0 + 1e-6 && p[1].abs() < 4.0).collect();
    assert!(round.iter().any(|p| p[0] > 104.9), "round the tip");
    for p in round {
        assert!(((p[0] - 100.0).hypot(p[1]) - 5.0).abs() < 1e-6, "{p:?} on the circle about the tip");
    }
}

/// With MD20210 raised to 150° (the upper limit), a 140° turn uses the intersection again:
/// G41, line (0,0)→(100,0) then heading 220° (a right turn of 140°). Two equidistants at
/// distance r of lines turning by θ meet r·tan(θ/2) beyond the perpendicular point on the
/// first: at x = 100 + 5·tan 70°, y = 5.
#[test]
fn md20210_decides_from_which_angle_the_circle_is_used() {
    let end = (100.0 - 50.0 * 40f64.to_radians().cos(), -50.0 * 40f64.to_radians().sin());
    let prog = format!(
        "G17 G90 T1 D1\nG0 X-20 Y20 Z0\nG41 G451 G1 X0 Y0 F1000\nG1 X100 Y0\nM0\nG1 X{:.6} Y{:.6}\nG40 G1 X40 Y-60\nM30",
        end.0, end.1
    );
    let (ch, _) = run_to_stop("mill-3axis", "$MC_CUTCOM_CORNER_LIMIT=150", &prog);
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    let at = ch.axis_positions();
    let x = 100.0 + 5.0 * 70f64.to_radians().tan();
    assert!((at[0] - x).abs() < 1e-4 && (at[1] - 5.0).abs() < 1e-6, "{at:?} expected ({x}, 5)");
    let (ch, _) = run_to_stop("mill-3axis", "", &prog);
    let at = ch.axis_positions();
    assert!((at[0] - 100.0).abs() < 1e-6 && (at[1] - 5.0).abs() < 1e-6, "default 100°: {at:?}");
    let _ = (alarm_of, run_all_on);
}
