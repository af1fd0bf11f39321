//! Tool radius compensation checked against an independent construction of the offset path.
//! The mill's T1 D1 has radius 5.

use nctwin_engine::{Channel, Status};

fn run(program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    let mut samples = vec![ch.axis_positions().to_vec()];
    while ch.is_busy() {
        ch.step();
        samples.push(ch.axis_positions().to_vec());
        assert!(samples.len() < 2_000_000);
    }
    (ch, samples)
}

fn passes(samples: &[Vec<f64>], x: f64, y: f64) -> bool {
    samples.iter().any(|p| (p[0] - x).abs() < 1e-9 && (p[1] - y).abs() < 1e-9)
}

/// Distance of (x, y) from the boundary of the axis-parallel rectangle [lo, hi]².
fn off_square(x: f64, y: f64, lo: f64, hi: f64) -> f64 {
    let inside = (lo..=hi).contains(&x) && (lo..=hi).contains(&y);
    let d = (x - lo).abs().min((x - hi).abs()).min((y - lo).abs()).min((y - hi).abs());
    if inside { d } else { f64::INFINITY }
}

const SQUARE: &str = "T1 D1\nG0 X-20 Y-20 Z5\nG1 Z-1 F1000\n{sel} G1 X0 Y0\nG1 X50\nY50\nX0\nY0\nG40 G1 X-20 Y-20\nM30";

#[test]
fn g41_inside_a_counter_clockwise_square_runs_on_the_square_shrunk_by_the_radius() {
    let (ch, samples) = run(&SQUARE.replace("{sel}", "G41"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    for (x, y) in [(0.0, 5.0), (45.0, 5.0), (45.0, 45.0), (5.0, 45.0), (5.0, 0.0)] {
        assert!(passes(&samples, x, y), "the tool centre stops at ({x}, {y})");
    }
    // Between reaching (45,5) and leaving (5,45) every point lies on the inner square.
    let first = samples.iter().position(|p| (p[0] - 45.0).abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9).unwrap();
    let last = samples.iter().rposition(|p| (p[0] - 5.0).abs() < 1e-9 && (p[1] - 45.0).abs() < 1e-9).unwrap();
    for p in &samples[first..=last] {
        assert!(off_square(p[0], p[1], 5.0, 45.0) < 1e-9, "{p:?}");
    }
    assert_eq!(&ch.axis_positions()[..2], &[-20.0, -20.0]);
}

#[test]
fn g42_outside_with_g450_goes_round_each_outer_corner_on_the_radius() {
    let (ch, samples) = run(&SQUARE.replace("{sel}", "G42 G450"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    // The corner (50,0): from (50,-5) round to (55,0) on a circle of radius 5.
    assert!(passes(&samples, 50.0, -5.0) && passes(&samples, 55.0, 0.0));
    let round: Vec<_> = samples.iter().filter(|p| p[0] > 50.0 + 1e-6 && p[1] < -1e-6).collect();
    assert!(!round.is_empty());
    for p in round {
        assert!(((p[0] - 50.0).hypot(p[1]) - 5.0).abs() < 1e-9, "{p:?}");
    }
}

#[test]
fn g451_meets_at_the_intersection_of_the_equidistants() {
    let (ch, samples) = run(&SQUARE.replace("{sel}", "G42 G451"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    for (x, y) in [(55.0, -5.0), (55.0, 55.0), (-5.0, 55.0)] {
        assert!(passes(&samples, x, y), "corner point ({x}, {y})");
    }
}

#[test]
fn offn_adds_to_the_tool_radius() {
    let (ch, samples) = run(&SQUARE.replace("{sel}", "G41 OFFN=1"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    for (x, y) in [(44.0, 6.0), (44.0, 44.0), (6.0, 44.0)] {
        assert!(passes(&samples, x, y), "({x}, {y})");
    }
}

#[test]
fn a_circle_pocket_runs_on_the_smaller_circle_at_the_contour_feed_ratio() {
    // Contour: a full circle of radius 20 about the origin, counter-clockwise, G41 (inside):
    // the centre runs on radius 15 at F·15/20 (CFC: the feed holds at the contour).
    let program = "T1 D1\nG0 X0 Y0 Z-1\nG41 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30";
    let (ch, samples) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let dt = ch.config().ipo_cycle;
    let on_circle: Vec<_> = samples
        .windows(2)
        .filter(|w| (w[0][0].hypot(w[0][1]) - 15.0).abs() < 1e-9 && (w[1][0].hypot(w[1][1]) - 15.0).abs() < 1e-9)
        .collect();
    assert!(on_circle.len() > 100, "the centre runs on radius 15");
    let speeds: Vec<f64> = on_circle.iter().map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]) / dt * 60.0).collect();
    let cruise = speeds.iter().cloned().fold(0.0, f64::max);
    assert!((cruise - 1200.0 * 15.0 / 20.0).abs() < 1.0, "centre path feed {cruise} mm/min");
}

#[test]
fn a_slot_narrower_than_the_tool_is_an_alarm_not_a_gouge() {
    // An inner step of 4 mm with a radius-5 tool: the equidistants cross behind each other.
    let program = "T1 D1\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F1000\nX50\nY4\nX0\nG40 X-20 Y-20\nM30";
    let (ch, _) = run(program);
    assert_eq!(ch.snapshot().alarms.first().map(|a| a.number), Some(10751));
}

#[test]
fn a_tool_larger_than_an_inner_arc_is_an_alarm() {
    let program = "T1 D1\nG0 X0 Y0 Z-1\nG41 G1 X4 Y0 F1000\nG3 X4 Y0 I-4 J0\nG40 G1 X0 Y0\nM30";
    let (ch, _) = run(program);
    assert_eq!(ch.snapshot().alarms.first().map(|a| a.number), Some(10751));
}

#[test]
fn without_g41_nothing_is_compensated() {
    let (_, samples) = run(&SQUARE.replace("{sel}", ""));
    assert!(passes(&samples, 50.0, 0.0) && passes(&samples, 50.0, 50.0));
}

#[test]
fn cftcp_keeps_the_programmed_feed_on_the_centre_path() {
    let program = "T1 D1\nG0 X0 Y0 Z-1\nCFTCP G41 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30";
    let (ch, samples) = run(program);
    let dt = ch.config().ipo_cycle;
    let cruise = samples
        .windows(2)
        .filter(|w| (w[0][0].hypot(w[0][1]) - 15.0).abs() < 1e-9 && (w[1][0].hypot(w[1][1]) - 15.0).abs() < 1e-9)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]) / dt * 60.0)
        .fold(0.0, f64::max);
    assert!((cruise - 1200.0).abs() < 1.0, "{cruise}");
}

/// Distance from a point to a segment.
fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

mod polygons {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 40, .. ProptestConfig::default() })]

        /// Inside a convex polygon (G41 on a counter-clockwise contour) every point of the
        /// compensated path lies exactly one tool radius from the nearest edge.
        #[test]
        fn the_inset_of_a_convex_polygon_keeps_the_radius_everywhere(
            n in 3usize..8, size in 30.0f64..60.0, turn in 0.0f64..360.0, side_g42 in any::<bool>()
        ) {
            let pts: Vec<(f64, f64)> = (0..n)
                .map(|i| {
                    let a = (turn + 360.0 * i as f64 / n as f64).to_radians();
                    (100.0 + size * a.cos(), 100.0 + size * a.sin())
                })
                .collect();
            // G42 on the clockwise contour is the same inset.
            let order: Vec<(f64, f64)> = if side_g42 { pts.iter().rev().cloned().collect() } else { pts.clone() };
            let mut program = format!("T1 D1\nG0 X100 Y100 Z-1\n{} G1 X{} Y{} F3000\n", if side_g42 { "G42" } else { "G41" }, order[0].0, order[0].1);
            for p in order.iter().skip(1).chain(std::iter::once(&order[0])) {
                program += &format!("X{} Y{}\n", p.0, p.1);
            }
            program += "G40 G1 X100 Y100\nM30";
            let (ch, samples) = run(&program);
            prop_assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
            let edges: Vec<_> = (0..n).map(|i| (pts[i], pts[(i + 1) % n])).collect();
            let near = |p: &Vec<f64>| edges.iter().map(|(a, b)| seg_dist((p[0], p[1]), *a, *b)).fold(f64::MAX, f64::min);
            // From the first sample one radius from the contour to the last one.
            let on: Vec<usize> = (0..samples.len()).filter(|&i| (near(&samples[i]) - 5.0).abs() < 1e-6).collect();
            prop_assert!(on.len() > 20);
            for p in &samples[on[0]..=*on.last().unwrap()] {
                prop_assert!((near(p) - 5.0).abs() < 1e-6, "{:?} is {} from the contour", p, near(p));
            }
        }
    }
}
