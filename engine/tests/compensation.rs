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

fn run_on(preset: &str, extra: &str, program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset(preset, extra).unwrap();
    ch.run_program(program).unwrap();
    let mut samples = vec![ch.axis_positions().to_vec()];
    while ch.is_busy() {
        ch.step();
        samples.push(ch.axis_positions().to_vec());
        assert!(samples.len() < 2_000_000);
    }
    (ch, samples)
}

fn alarm_of(ch: &Channel) -> Option<u32> {
    ch.snapshot().alarms.first().map(|a| a.number)
}

/// The samples from the first to the last one on which `on` holds.
fn between<'a>(samples: &'a [Vec<f64>], on: impl Fn(&Vec<f64>) -> bool) -> &'a [Vec<f64>] {
    let first = samples.iter().position(&on).expect("reached");
    let last = samples.iter().rposition(&on).unwrap();
    &samples[first..=last]
}

mod lookahead {
    use super::*;

    /// An infeed (Z only) and a dwell between two contour elements do not end the first
    /// equidistant perpendicular: the tool stops at the inner corner's intersection (45, 5),
    /// feeds in there and goes on along x = 45.
    #[test]
    fn blocks_without_plane_motion_run_at_the_corner_point() {
        let program =
            "T1 D1\nG0 X-20 Y-20 Z5\nG1 Z-1 F1000\nG41 G1 X0 Y0\nX50\nZ-2\nG4 F0.05\nY50\nX0\nG40 X-20 Y-20\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        // While Z travels from -1 to -2 the tool stands at the corner point (Z shows the tool
        // carrier: T1 is 100 long).
        let on_contour = samples.iter().position(|p| p[0].abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9).unwrap();
        let infeed: Vec<_> =
            samples[on_contour..].iter().filter(|p| p[2] < 99.0 - 1e-9 && p[2] > 98.0 + 1e-9).collect();
        assert!(!infeed.is_empty());
        for p in infeed {
            assert!((p[0] - 45.0).abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9, "{p:?}");
        }
        // The perpendicular end (50 - 0, 5) of the old behaviour is never reached.
        assert!(samples.iter().all(|p| p[0] <= 45.0 + 1e-9 || p[1] < 4.0), "x beyond 45 on the inner corner");
    }

    /// MD20250 CUTCOM_MAXNUM_DUMMY_BLOCKS (default 3): three blocks without plane motion are
    /// looked across, a fourth is alarm 10762 in the block that exceeds the limit.
    #[test]
    fn more_dummy_blocks_than_md20250_is_alarm_10762() {
        let dummies = |n: usize| (0..n).map(|i| format!("Z{}\n", -2.0 - i as f64)).collect::<String>();
        let program = |n: usize| {
            format!("T1 D1\nG0 X-20 Y-20 Z5\nG1 Z-1 F1000\nG41 G1 X0 Y0\nX50\n{}Y50\nG40 X-20 Y-20\nM30", dummies(n))
        };
        let (ch, _) = run(&program(3));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let (ch, _) = run(&program(4));
        assert_eq!(alarm_of(&ch), Some(10762));
        // The 4th dummy block is on line 9 (lines 6..9 are the infeeds).
        assert_eq!(ch.snapshot().alarms[0].line, Some(9));
        let (ch, _) = run_on("mill-3axis", "$MC_CUTCOM_MAXNUM_DUMMY_BLOCKS=1", &program(2));
        assert_eq!(alarm_of(&ch), Some(10762));
    }
}

mod corners {
    use super::*;

    /// DISC=50 at the square's corner (50, 0) with G42 (outside, radius 5): the G450 circle
    /// about the corner, scaled by 1 − 50/100 about the intersection (55, −5) of the
    /// equidistants: centre (52.5, −2.5), radius 2.5, from (52.5, −5) to (55, −2.5).
    #[test]
    fn disc_pulls_the_transition_circle_towards_the_intersection() {
        let (ch, samples) = run(&SQUARE.replace("{sel}", "G42 G450 DISC=50"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        assert!(passes(&samples, 52.5, -5.0) && passes(&samples, 55.0, -2.5));
        let round: Vec<_> = samples.iter().filter(|p| p[0] > 52.5 + 1e-6 && p[1] < -2.5 - 1e-6).collect();
        assert!(!round.is_empty());
        for p in round {
            assert!(((p[0] - 52.5).hypot(p[1] + 2.5) - 2.5).abs() < 1e-9, "{p:?}");
        }
        // DISC=100 is the intersection, like G451.
        let (_, samples) = run(&SQUARE.replace("{sel}", "G42 G450 DISC=100"));
        assert!(passes(&samples, 55.0, -5.0));
        let (ch, _) = run(&SQUARE.replace("{sel}", "G42 DISC=101"));
        assert_eq!(alarm_of(&ch), Some(12560), "DISC is 0..100");
    }

    /// A 30° spike, outer corner at (100, 0) for G42: +X, then back at 150°. G451 goes to the
    /// intersection of the equidistants y = −5 and the second one, 5/tan(15°) = 18.66 beyond
    /// the corner in X; G450 stays within the radius of the corner (x ≤ 105).
    #[test]
    fn g450_and_g451_at_a_sharp_corner() {
        let (ex, ey) = (100.0 - 60.0 * 30f64.to_radians().cos(), 60.0 * 30f64.to_radians().sin());
        let program = |mode: &str| {
            format!("T1 D1\nG0 X-20 Y-20 Z-1\n{mode} G42 G1 X0 Y0 F2000\nX100\nX{ex} Y{ey}\nG40 X{ex} Y60\nM30")
        };
        let reach = 100.0 + 5.0 / 15f64.to_radians().tan();
        let (ch, samples) = run(&program("G451"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        assert!(samples.iter().any(|p| (p[0] - reach).abs() < 1e-6 && (p[1] + 5.0).abs() < 1e-6));
        let max_x = samples.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
        assert!((max_x - reach).abs() < 1e-6, "{max_x}");
        let (ch, samples) = run(&program("G450"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let max_x = samples.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
        assert!(max_x <= 105.0 + 1e-9 && max_x > 104.99, "{max_x}");
        // The second equidistant starts perpendicular to the corner: (100, 0) + 5·(sin 30°, cos 30°).
        let n = (30f64.to_radians().sin(), 30f64.to_radians().cos());
        assert!(samples.iter().any(|p| (p[0] - 100.0 - 5.0 * n.0).abs() < 1e-6 && (p[1] - 5.0 * n.1).abs() < 1e-6));
    }

    #[test]
    fn negative_offn_shrinks_the_offset() {
        let (ch, samples) = run(&SQUARE.replace("{sel}", "G41 OFFN=-1"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        for (x, y) in [(46.0, 4.0), (46.0, 46.0), (4.0, 46.0)] {
            assert!(passes(&samples, x, y), "({x}, {y})");
        }
    }
}

mod approach {
    use super::*;

    /// Contour: (0,0) → (50,0) with G41 (tool at y = +5). The start point (10, −10) lies
    /// behind the contour start and on the other side: NORM's straight line to (0, 5) cuts
    /// through the contour, KONT goes round (0, 0) on the circle of radius 5.
    const AHEAD: &str = "T1 D1\nG0 X10 Y-10 Z-1\n{mode} G41 G1 X0 Y0 F2000\nX50\nG40 G1 X50 Y20\nM30";

    fn contour_distance(p: &[f64]) -> f64 {
        seg_dist((p[0], p[1]), (0.0, 0.0), (50.0, 0.0))
    }

    #[test]
    fn kont_goes_round_the_contour_start_when_the_start_point_is_behind_it() {
        let (ch, samples) = run(&AHEAD.replace("{mode}", "NORM"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let closest = samples.iter().map(|p| contour_distance(p)).fold(f64::MAX, f64::min);
        assert!(closest < 1e-6, "NORM crosses the contour: {closest}");

        let (ch, samples) = run(&AHEAD.replace("{mode}", "KONT"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        assert!(passes(&samples, 0.0, 5.0));
        // Tangent from (10, −10) onto the circle r = 5 about the origin: the touching point
        // is at the angle of the start point (−45°) minus acos(5 / |start|).
        let beta = (5.0 / 200f64.sqrt()).acos();
        let a = -45f64.to_radians() - beta;
        assert!(
            passes(&samples, 5.0 * a.cos(), 5.0 * a.sin()),
            "touching point ({}, {})",
            5.0 * a.cos(),
            5.0 * a.sin()
        );
        // Until the tool leaves the contour at its end it never comes closer than the radius.
        let cut = between(&samples, |p| {
            (p[0] - 10.0).abs() < 1e-9 && (p[1] + 10.0).abs() < 1e-9
                || (p[0] - 50.0).abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9
        });
        for p in cut {
            assert!(contour_distance(p) > 5.0 - 1e-6, "{p:?}");
        }
    }

    #[test]
    fn kont_with_the_start_point_inside_the_tool_radius_is_alarm_10755() {
        let (ch, _) = run("T1 D1\nG0 X3 Y-2 Z-1\nKONT G41 G1 X0 Y0 F2000\nX50\nG40 G1 X50 Y20\nM30");
        assert_eq!(alarm_of(&ch), Some(10755));
    }

    /// G451 with KONT: the tangent line from the start point runs on to its intersection with
    /// the first equidistant y = 5 instead of rounding the corner.
    #[test]
    fn kont_with_g451_meets_the_first_equidistant_at_the_intersection() {
        let (ch, samples) = run(&AHEAD.replace("{mode}", "KONT G451"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let beta = (5.0 / 200f64.sqrt()).acos();
        let a = -45f64.to_radians() - beta;
        let t = (5.0 * a.cos(), 5.0 * a.sin());
        // Line (10, −10) → t, continued to y = 5.
        let s = (5.0 + 10.0) / (t.1 + 10.0);
        let x = (10.0 + s * (t.0 - 10.0), 5.0);
        assert!(passes(&samples, x.0, x.1), "{x:?}");
        assert!(samples.iter().all(|p| p[1] <= 5.0 + 1e-9 || p[0] > 49.0));
    }

    /// Retract: the contour (0,0) → (50,0) with G41 ends at (50, 0); the G40 end point
    /// (40, −10) lies behind the end on the other side. It is the mirror image (x → 50 − x,
    /// travelled backwards) of the approach above: KONT goes round (50, 0) and leaves on the
    /// tangent through (50 + 2.058.., −4.557..).
    #[test]
    fn kont_retract_goes_round_the_contour_end() {
        let program =
            |mode: &str| format!("T1 D1\nG0 X-20 Y20 Z-1\nG41 G1 X0 Y0 F2000\nX50\n{mode} G40 G1 X40 Y-10\nM30");
        let (_, samples) = run(&program("NORM"));
        let closest = samples.iter().skip(1).map(|p| contour_distance(p)).fold(f64::MAX, f64::min);
        assert!(closest < 1e-6, "NORM cuts the contour on the way out: {closest}");
        let (ch, samples) = run(&program("KONT"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let beta = (5.0 / 200f64.sqrt()).acos();
        let a = -45f64.to_radians() - beta;
        assert!(passes(&samples, 50.0 - 5.0 * a.cos(), 5.0 * a.sin()));
        assert!(passes(&samples, 50.0, 5.0));
        assert_eq!(&ch.axis_positions()[..2], &[40.0, -10.0]);
        let after = samples.iter().position(|p| (p[0] - 0.0).abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9).unwrap();
        for p in &samples[after..] {
            assert!(contour_distance(p) > 5.0 - 1e-6, "{p:?}");
        }
    }

    /// KONTT: one arc from the start point (−20, −20) that reaches (0, 5) heading +X. Its
    /// centre lies on x = 0 (perpendicular to the direction at (0, 5)) at the same distance
    /// from both points: (0, 5 − λ) with λ² = 20² + (25 − λ)², λ = 20.5.
    #[test]
    fn kontt_joins_the_first_equidistant_tangentially() {
        let (ch, samples) = run("T1 D1\nG0 X-20 Y-20 Z-1\nKONTT G41 G1 X0 Y0 F2000\nX50\nG40 G1 X50 Y20\nM30");
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let start = samples.iter().position(|p| (p[0] + 20.0).abs() < 1e-9 && (p[1] + 20.0).abs() < 1e-9).unwrap();
        let arc = between(&samples[start..], |p| p[1] < 5.0 - 1e-9 && p[0] < -1e-9 && p[1] > -20.0 + 1e-9);
        assert!(arc.len() > 10);
        for p in arc {
            assert!((p[0].hypot(p[1] + 15.5) - 20.5).abs() < 1e-6, "{p:?}");
        }
        assert!(passes(&samples, 0.0, 5.0) && passes(&samples, 50.0, 5.0));
    }

    #[test]
    fn selection_and_deselection_need_a_straight_block() {
        let (ch, _) = run("T1 D1\nG0 X20 Y0 Z-1\nG41 G3 X-20 Y0 I-20 J0 F1000\nM30");
        assert_eq!(alarm_of(&ch), Some(10753));
        let (ch, _) = run("T1 D1\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F1000\nX50\nG40 G3 X50 Y20 I0 J10\nM30");
        assert_eq!(alarm_of(&ch), Some(10754));
    }

    #[test]
    fn changing_the_plane_with_compensation_active_is_alarm_10757() {
        let (ch, _) = run("T1 D1\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F1000\nX50\nG18 X60\nM30");
        assert_eq!(alarm_of(&ch), Some(10757));
        let (ch, _) = run("T1 D1\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F1000\nX50\nG40 G18 X60\nM30");
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    }
}
