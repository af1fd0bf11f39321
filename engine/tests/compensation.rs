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
fn an_inner_rounding_smaller_than_the_tool_is_an_alarm_at_its_block() {
    // RND=5 at the inner corners of a pocket outline with a radius-5 tool: the centre path's
    // arc would have radius 5 − 5 = 0. The alarm names the block with the RND (line 4), not
    // line 0 (found by probing: the bottleneck check raised it without a line).
    let program = "T1 D1\nG17 G0 X-10 Y-10 Z-1\nG41 G1 X0 Y0 F600\nX50 RND=5\nY30\nX0\nY0\nG40 X-10 Y-10\nM30";
    let (ch, _) = run(program);
    let alarm = ch.snapshot().alarms.first().cloned().expect("an alarm");
    assert_eq!((alarm.number, alarm.line), (10751, Some(4)), "{alarm:?}");
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
fn between(samples: &[Vec<f64>], on: impl Fn(&Vec<f64>) -> bool) -> &[Vec<f64>] {
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

    /// A 30° spike, outer corner at (100, 0) for G42: +X, then back at 150°. The change of
    /// direction (150°) reaches MD20210 CUTCOM_CORNER_LIMIT (default 100°), so G451 does not
    /// go to the intersection of the equidistants 5/tan(15°) = 18.66 beyond the corner but,
    /// like G450, round the transition circle (x ≤ 105); with MD20210 at 150° a 140° spike
    /// still uses it (`trc_g451_arcs.rs`).
    #[test]
    fn g450_and_g451_at_a_sharp_corner() {
        let (ex, ey) = (100.0 - 60.0 * 30f64.to_radians().cos(), 60.0 * 30f64.to_radians().sin());
        let program = |mode: &str| {
            format!("T1 D1\nG0 X-20 Y-20 Z-1\n{mode} G42 G1 X0 Y0 F2000\nX100\nX{ex} Y{ey}\nG40 X{ex} Y60\nM30")
        };
        let (ch, samples) = run(&program("G451"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let max_x = samples.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
        assert!(max_x <= 105.0 + 1e-9 && max_x > 104.99, "{max_x}");
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

mod turning {
    //! lathe-2axis: T1 D1 is a turning tool (type 500) with cutting edge position 3 and nose
    //! radius 0.8, lengths L1 = 40 (X) and L2 = 60 (Z) to the theoretical tip P. Channel axes:
    //! X (radius), Z. Working plane G18: abscissa Z, ordinate X.
    use super::*;

    /// Tool carrier position → theoretical tip (X, Z).
    fn tip(p: &[f64]) -> (f64, f64) {
        (p[0] - 40.0, p[1] - 60.0)
    }

    fn at(samples: &[Vec<f64>], x: f64, z: f64) -> bool {
        samples.iter().any(|p| {
            let (tx, tz) = tip(p);
            (tx - x).abs() < 1e-9 && (tz - z).abs() < 1e-9
        })
    }

    /// The example of seeds/001 in this dialect: G0 X10 Z10, G42 G0 Z20, G1 X20, G40 G0 X30
    /// Z30 (a face at Z20 cut upwards, material at Z < 20, so the tool is right of the
    /// direction of travel). The nose centre S runs at Z20.8; with position 3 the tip is
    /// P = S + 0.8·(−1, −1) in (Z, X): P = (X9.2, Z20) after the selection block and
    /// (X19.2, Z20) at the end of the face, so the tip's Z stays on the programmed face.
    #[test]
    fn the_seed_example_moves_the_tip_with_the_nose_centre_on_the_equidistant() {
        let (ch, samples) =
            run_on("lathe-2axis", "", "T1 D1\nG18 G0 X10 Z10\nG42 G0 Z20\nG1 X20 F200\nG40 G0 X30 Z30\nM30");
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        assert!(at(&samples, 10.0, 10.0), "without compensation the tip is on the programmed point");
        assert!(at(&samples, 9.2, 20.0) && at(&samples, 19.2, 20.0));
        let face = between(&samples, |p| {
            let (x, z) = tip(p);
            ((x - 9.2).abs() < 1e-9 || (x - 19.2).abs() < 1e-9) && (z - 20.0).abs() < 1e-9
        });
        for p in face {
            assert!((tip(p).1 - 20.0).abs() < 1e-9, "{p:?}");
        }
        assert_eq!(tip(ch.axis_positions()), (30.0, 30.0));
    }

    /// External turning of a shoulder: along X10 towards the chuck, then up the face Z−30.
    /// G42 keeps the nose above the diameter and right of the face; at the inner corner the
    /// nose centre stops at (X10.8, Z−29.2), which puts the tip exactly on the programmed
    /// corner (X10, Z−30). While cutting, the tip stays on X10, then on Z−30.
    #[test]
    fn the_tip_of_a_position_3_tool_reproduces_a_shoulder() {
        let program = "T1 D1\nG0 X15 Z5\nG42 G1 X10 Z0 F300\nZ-30\nX20\nG40 G0 X25 Z5\nM30";
        let (ch, samples) = run_on("lathe-2axis", "", program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        // Selection (NORM): S at (X10.8, Z0), P = (X10, Z−0.8).
        assert!(at(&samples, 10.0, -0.8));
        assert!(at(&samples, 10.0, -30.0), "the tip reaches the programmed corner");
        assert!(at(&samples, 19.2, -30.0), "the face ends perpendicular: S (X20, Z−29.2)");
        let cut = between(&samples, |p| {
            let (x, z) = tip(p);
            (x - 10.0).abs() < 1e-9 && (z + 0.8).abs() < 1e-9 || (x - 19.2).abs() < 1e-9 && (z + 30.0).abs() < 1e-9
        });
        assert!(cut.len() > 50);
        for p in cut {
            let (x, z) = tip(p);
            assert!((x - 10.0).abs() < 1e-9 || (z + 30.0).abs() < 1e-9, "tip ({x}, {z}) off the contour");
        }
    }

    /// Cutting edge position 9 makes the nose centre the reference: the tool then behaves
    /// like a milling cutter of radius 0.8 (reference on the equidistant).
    #[test]
    fn position_9_puts_the_reference_on_the_equidistant() {
        let program = "T1 D1\nG0 X15 Z5\nG42 G1 X10 Z0 F300\nZ-30\nX20\nG40 G0 X25 Z5\nM30";
        let (ch, samples) = run_on("lathe-2axis", "$TC_DP2[1,1]=9", program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        assert!(at(&samples, 10.8, 0.0) && at(&samples, 10.8, -29.2) && at(&samples, 20.0, -29.2));
    }
}

mod planes {
    use super::*;

    /// The square of the G17 test in the Z-X plane (G18: abscissa Z, ordinate X) and the Y-Z
    /// plane (G19: abscissa Y, ordinate Z), counter-clockwise in plane coordinates, G41:
    /// the centre runs on the square shrunk by 5 in those axes. `a`, `o`: axis indices.
    fn square_in(plane: &str, an: &str, on: &str, nn: &str, a: usize, o: usize) {
        let program = format!(
            "T1 D1\n{plane} G0 {an}-20 {on}-20 {nn}5\nG1 {nn}-1 F1000\nG41 G1 {an}0 {on}0\n{an}50\n{on}50\n{an}0\n{on}0\nG40 G1 {an}-20 {on}-20\nM30"
        );
        let (ch, samples) = run(&program);
        assert_eq!(ch.status(), Status::Idle, "{plane}: {:?}", ch.alarms());
        // The milling tool's length acts on the plane normal (Y in G18, X in G19), so the plane
        // axes show the tool centre directly; the deselection ends on the programmed point.
        let last = samples.last().unwrap();
        assert_eq!((last[a], last[o]), (-20.0, -20.0), "{plane}");
        let pt = |p: &Vec<f64>| (p[a], p[o]);
        let cut = between(&samples, |p| {
            let (x, y) = pt(p);
            (x - 45.0).abs() < 1e-9 && (y - 5.0).abs() < 1e-9 || (x - 5.0).abs() < 1e-9 && (y - 45.0).abs() < 1e-9
        });
        assert!(cut.len() > 50, "{plane}");
        for p in cut {
            let (x, y) = pt(p);
            assert!(off_square(x, y, 5.0, 45.0) < 1e-9, "{plane}: {p:?}");
        }
    }

    #[test]
    fn g18_and_g19_compensate_in_their_planes() {
        square_in("G18", "Z", "X", "Y", 2, 0);
        square_in("G19", "Y", "Z", "X", 1, 2);
    }
}

mod arcs {
    use super::*;

    /// Path speed of the samples on a circle of radius `r` about (cx, cy) in mm/min (the
    /// highest, i.e. the cruise feed).
    fn cruise_on_circle(ch: &Channel, samples: &[Vec<f64>], r: f64, cx: f64, cy: f64) -> f64 {
        let dt = ch.config().ipo_cycle;
        let on = |p: &Vec<f64>| ((p[0] - cx).hypot(p[1] - cy) - r).abs() < 1e-9;
        samples
            .windows(2)
            .filter(|w| on(&w[0]) && on(&w[1]))
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]) / dt * 60.0)
            .fold(0.0, f64::max)
    }

    /// A boss of radius 20 milled outside (G42 on a counter-clockwise circle): the centre
    /// runs on radius 25. CFC keeps F at the contour, so the centre runs at F·(20 + 5)/20;
    /// CFIN corrects inner arcs only and leaves F on the centre path here.
    #[test]
    fn outer_arcs_run_faster_with_cfc_and_at_f_with_cfin() {
        let program = |mode: &str| {
            format!("T1 D1\nG0 X40 Y0 Z-1\n{mode} G42 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X40 Y0\nM30")
        };
        let (ch, samples) = run(&program("CFC"));
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let f = cruise_on_circle(&ch, &samples, 25.0, 0.0, 0.0);
        assert!((f - 1200.0 * 25.0 / 20.0).abs() < 1.0, "CFC outer {f}");
        let (_, samples) = run(&program("CFIN"));
        let f = cruise_on_circle(&ch, &samples, 25.0, 0.0, 0.0);
        assert!((f - 1200.0).abs() < 1.0, "CFIN outer {f}");
    }

    #[test]
    fn inner_arcs_are_slowed_with_cfin() {
        let program = "T1 D1\nG0 X0 Y0 Z-1\nCFIN G41 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30";
        let (ch, samples) = run(program);
        let f = cruise_on_circle(&ch, &samples, 15.0, 0.0, 0.0);
        assert!((f - 1200.0 * 15.0 / 20.0).abs() < 1.0, "{f}");
    }

    /// A helix (G3 with Z) in a pocket: the plane part is offset like the circle, Z descends
    /// linearly with the angle (the helix axis is the plane normal).
    #[test]
    fn a_helix_is_compensated_in_the_plane_and_keeps_its_lead() {
        let program = "T1 D1\nG0 X0 Y0 Z0\nG41 G1 X20 Y0 F1200\nG3 X20 Y0 Z-4 I-20 J0\nG40 G1 X0 Y0\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let helix: Vec<_> = samples
            .iter()
            .filter(|p| (p[0].hypot(p[1]) - 15.0).abs() < 1e-9 && p[2] < 100.0 - 1e-9 && p[2] > 96.0 + 1e-9)
            .collect();
        assert!(helix.len() > 100);
        for p in helix {
            // Angle travelled from (15, 0) counter-clockwise, Z = 100 − 4·angle/2π.
            let angle = p[1].atan2(p[0]).rem_euclid(std::f64::consts::TAU);
            assert!((p[2] - (100.0 - 4.0 * angle / std::f64::consts::TAU)).abs() < 1e-6, "{p:?}");
        }
    }
}

mod pocket {
    use super::*;
    use proptest::prelude::*;

    /// Distance from a point inside a rounded rectangle (half sizes hx, hy, corner radius rr,
    /// centred at the origin) to its boundary: the signed-distance formula of a rounded box.
    fn inside_distance(x: f64, y: f64, hx: f64, hy: f64, rr: f64) -> f64 {
        let (qx, qy) = (x.abs() - (hx - rr), y.abs() - (hy - rr));
        let outside = qx.max(0.0).hypot(qy.max(0.0));
        let sd = outside + qx.max(qy).min(0.0) - rr;
        -sd
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]

        /// A pocket with inner arcs (rounded rectangle, corner radius ≥ the tool's 5): every
        /// sample of the compensated path lies exactly one tool radius inside the contour.
        #[test]
        fn a_rounded_pocket_keeps_the_radius_everywhere(hx in 15.0f64..40.0, hy in 15.0f64..40.0, rr in 6.0f64..14.0) {
            let program = format!(
                "T1 D1\nG0 X0 Y0 Z-1\nG41 G1 X0 Y{my} F3000\nX{b}\nG3 X{hx} Y{c} CR={rr}\nG1 Y{d}\nG3 X{b} Y{hy} CR={rr}\nG1 X{mb}\nG3 X{mx} Y{d} CR={rr}\nG1 Y{c}\nG3 X{mb} Y{my} CR={rr}\nG1 X0\nG40 G1 X0 Y0\nM30",
                b = hx - rr, mb = -(hx - rr), c = -(hy - rr), d = hy - rr, mx = -hx, my = -hy, hx = hx, hy = hy, rr = rr
            );
            let (ch, samples) = run(&program);
            prop_assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
            let on: Vec<usize> = (0..samples.len())
                .filter(|&i| (inside_distance(samples[i][0], samples[i][1], hx, hy, rr) - 5.0).abs() < 1e-6)
                .collect();
            prop_assert!(on.len() > 50);
            for p in &samples[on[0]..=*on.last().unwrap()] {
                let d = inside_distance(p[0], p[1], hx, hy, rr);
                prop_assert!((d - 5.0).abs() < 1e-6, "{:?} is {} inside", p, d);
            }
        }
    }
}

/// KONTC: approach and retract on a polynomial that joins the equidistant with continuous
/// tangent and curvature, run as straight chords within 1 µm of the polynomial. The expected
/// values come from the contour alone: the curve leaves the programmed start point and meets
/// the equidistant at its first point Q with the equidistant's direction and curvature (0 on a
/// line, 1/(R − r) inside a pocket of radius R). Near Q the samples are compared with the
/// equidistant continued beyond Q: a path that arrives at Q with the same tangent and with a
/// curvature within δκ of the contour's over the last s millimetres lies within δκ·s²/2 of that
/// continuation, plus the chord tolerance. A tangent kink of α would show as α·s, KONTT's
/// curvature jump (1/20.5 onto the line, 2/15 − 1/15 into the pocket) as about 0.006 and
/// 0.008 mm at s = 0.5.
mod kontc {
    use super::*;

    /// Chord tolerance of the approach polynomial (mm).
    const CHORD: f64 = 1e-3;
    /// Curvature agreement asserted at Q (1/mm).
    const D_KAPPA: f64 = 0.02;
    /// How far before (approach) or after (retract) Q the samples are compared (mm).
    const WINDOW: f64 = 0.5;
    /// T1 D1 of the preset is 100 long: Z−1 is machine Z 99.
    const LENGTH: f64 = 100.0;

    /// The samples from where the tool stands at the start point (x, y, z) of the program's
    /// approach (the end of the exact-stop rapid before it).
    fn from_start(samples: &[Vec<f64>], start: (f64, f64, f64)) -> &[Vec<f64>] {
        let at = |p: &Vec<f64>| plane_dist(p, (start.0, start.1)) < 1e-9 && (p[2] - start.2 - LENGTH).abs() < 1e-9;
        // The last sample there: the stop before the approach stands for a cycle.
        let first = samples.iter().position(at).expect("stands at the start point");
        &samples[first + samples[first..].iter().take_while(|p| at(p)).count() - 1..]
    }

    fn plane_dist(p: &[f64], q: (f64, f64)) -> f64 {
        (p[0] - q.0).hypot(p[1] - q.1)
    }

    /// The samples within WINDOW of `q` on the approach (up to the first sample that reaches
    /// `q` within one cycle's travel `step`) or on the retract (from the last such sample on).
    fn window(samples: &[Vec<f64>], q: (f64, f64), step: f64, approach: bool) -> Vec<Vec<f64>> {
        let at = |p: &Vec<f64>| plane_dist(p, q) <= step;
        let side = if approach {
            &samples[..=samples.iter().position(at).expect("reaches Q")]
        } else {
            &samples[samples.iter().rposition(at).expect("leaves Q")..]
        };
        side.iter().filter(|p| plane_dist(p, q) <= WINDOW).cloned().collect()
    }

    /// Every sample near `q` lies within the chord tolerance plus δκ·s²/2 of the contour's
    /// continuation (`off` is the distance from it).
    fn joins(samples: &[Vec<f64>], q: (f64, f64), step: f64, approach: bool, off: impl Fn(&[f64]) -> f64) {
        let near = window(samples, q, step, approach);
        assert!(near.len() >= 3, "{} samples near {q:?}", near.len());
        for p in &near {
            let s = plane_dist(p, q);
            let bound = CHORD + D_KAPPA * s * s / 2.0;
            assert!(off(p) <= bound, "{p:?} is {} off the contour at {s} from {q:?} (bound {bound})", off(p));
        }
    }

    /// No sample moves further than the feed allows in one cycle.
    fn no_jumps(ch: &Channel, samples: &[Vec<f64>], feed: f64) {
        let step = feed / 60.0 * ch.config().ipo_cycle;
        for w in samples.windows(2) {
            let d = (0..3).map(|k| (w[1][k] - w[0][k]).powi(2)).sum::<f64>().sqrt();
            assert!(d <= step * (1.0 + 1e-9), "{:?} → {:?}: {d} > {step}", w[0], w[1]);
        }
    }

    /// Contour (0,0) → (50,0) with G41 (tool at y = 5) in continuous-path mode. Approach from
    /// (−20, −20) onto Q = (0, 5) heading +X, curvature 0; retract from Q' = (50, 5) to
    /// (50, 20). The continuation of the equidistant is the line y = 5.
    #[test]
    fn a_line_is_approached_and_left_with_its_tangent_and_zero_curvature() {
        let program = "T1 D1\nG0 X-20 Y-20 Z-1 G9\nG64 KONTC G41 G1 X0 Y0 F2000\nX50\nG40 G1 X50 Y20\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let samples = from_start(&samples, (-20.0, -20.0, -1.0));
        let step = 2000.0 / 60.0 * ch.config().ipo_cycle;
        joins(samples, (0.0, 5.0), step, true, |p| (p[1] - 5.0).abs());
        joins(samples, (50.0, 5.0), step, false, |p| (p[1] - 5.0).abs());
        // Between the two, the tool runs on y = 5 exactly.
        let on = between(samples, |p| (p[1] - 5.0).abs() < 1e-9 && (0.0..=50.0).contains(&p[0]));
        assert!(on.iter().all(|p| (p[1] - 5.0).abs() < 1e-9));
        assert_eq!(&ch.axis_positions()[..3], &[50.0, 20.0, -1.0 + LENGTH]);
        no_jumps(&ch, samples, 2000.0);
    }

    /// A circular pocket of radius 20 about the origin, G3, G41 with radius 5: the centre runs
    /// on radius 15 (curvature 1/15). KONTC from and back to the pocket centre: Q = (15, 0)
    /// heading +Y both times. KONTC's curve stays inside radius 15 (no cut into the wall).
    #[test]
    fn a_pocket_is_approached_and_left_with_the_curvature_of_its_equidistant() {
        let program = "T1 D1\nG0 X0 Y0 Z-1 G9\nG64 KONTC G41 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let samples = from_start(&samples, (0.0, 0.0, -1.0));
        let step = 1200.0 / 60.0 * ch.config().ipo_cycle;
        let off = |p: &[f64]| (p[0].hypot(p[1]) - 15.0).abs();
        joins(samples, (15.0, 0.0), step, true, off);
        joins(samples, (15.0, 0.0), step, false, off);
        assert!(samples.iter().all(|p| p[0].hypot(p[1]) <= 15.0 + CHORD), "the tool never passes radius 15");
        // Approach and retract are real curves, not the half circles of KONTT (radius 7.5
        // about (7.5, 0)): somewhere they leave that circle by more than a millimetre.
        assert!(samples.iter().any(|p| ((p[0] - 7.5).hypot(p[1]) - 7.5).abs() > 1.0));
        assert_eq!(&ch.axis_positions()[..2], &[0.0, 0.0]);
        no_jumps(&ch, samples, 1200.0);
    }

    /// The same pocket with G42: the centre runs outside on radius 25, curvature still 1/25
    /// turning left (G3). Approach from (40, 0) outside the pocket onto Q = (25, 0).
    #[test]
    fn an_outer_arc_is_joined_with_the_curvature_one_over_r_plus_the_radius() {
        let program = "T1 D1\nG0 X40 Y0 Z-1 G9\nG64 KONTC G42 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X40 Y0\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let samples = from_start(&samples, (40.0, 0.0, -1.0));
        let step = 1200.0 / 60.0 * ch.config().ipo_cycle;
        let off = |p: &[f64]| (p[0].hypot(p[1]) - 25.0).abs();
        joins(samples, (25.0, 0.0), step, true, off);
        joins(samples, (25.0, 0.0), step, false, off);
        // CFC: the feed holds at the contour, the centre runs at F·25/20.
        no_jumps(&ch, samples, 1200.0 * 25.0 / 20.0);
    }

    /// An infeed in Z during the approach: Z arrives at Q with zero velocity and
    /// acceleration, so the path in space also meets the equidistant (y = 5, z = −1) with
    /// continuous tangent and curvature.
    #[test]
    fn an_infeed_arrives_at_the_contour_tangentially() {
        let program = "T1 D1\nG0 X-20 Y-20 Z5 G9\nG64 KONTC G41 G1 X0 Y0 Z-1 F2000\nX50\nG40 G1 X50 Y20 Z5\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let samples = from_start(&samples, (-20.0, -20.0, 5.0));
        let step = 2000.0 / 60.0 * ch.config().ipo_cycle;
        let off = |p: &[f64]| (p[1] - 5.0).hypot(p[2] + 1.0 - LENGTH);
        joins(samples, (0.0, 5.0), step, true, off);
        joins(samples, (50.0, 5.0), step, false, off);
        assert_eq!(&ch.axis_positions()[..3], &[50.0, 20.0, 5.0 + LENGTH]);
        no_jumps(&ch, samples, 2000.0);
    }

    /// In exact-stop mode (G60) the chords of the polynomial still run without stopping: the
    /// path velocity stays above zero from leaving the start point until Q.
    #[test]
    fn the_chords_do_not_stop_under_g60() {
        let program = "T1 D1\nG0 X-20 Y-20 Z-1\nG60 KONTC G41 G1 X0 Y0 F2000\nX50\nG40 G1 X50 Y20\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let samples = from_start(&samples, (-20.0, -20.0, -1.0));
        let arrive = samples.iter().position(|p| plane_dist(p, (0.0, 5.0)) < 1e-9).expect("stops at Q");
        for w in samples[..=arrive].windows(2) {
            assert!(plane_dist(&w[0], (w[1][0], w[1][1])) > 1e-9, "standstill at {:?}", w[0]);
        }
    }

    /// G450/G451 decide KONT's way round the contour start; KONTC does not go round a corner,
    /// so the path is the same with either.
    #[test]
    fn g451_gives_the_same_curve() {
        let program =
            |g: &str| format!("T1 D1\nG0 X-20 Y-20 Z-1\n{g} KONTC G41 G1 X0 Y0 F2000\nX50\nG40 G1 X60 Y20\nM30");
        let (a, with_450) = run(&program("G450"));
        let (b, with_451) = run(&program("G451"));
        assert_eq!(a.status(), Status::Idle, "{:?}", a.alarms());
        assert_eq!(b.status(), Status::Idle, "{:?}", b.alarms());
        assert_eq!(with_450, with_451);
    }

    /// The selection and the deselection block must be straight with KONTC too (10753, 10754).
    #[test]
    fn kontc_needs_a_straight_selection_and_deselection_block() {
        let (ch, _) = run("T1 D1\nG0 X20 Y0 Z-1\nKONTC G41 G3 X-20 Y0 I-20 J0 F1000\nM30");
        assert_eq!(alarm_of(&ch), Some(10753));
        let (ch, _) = run("T1 D1\nG0 X-20 Y-20 Z-1\nKONTC G41 G1 X0 Y0 F1000\nX50\nG40 G3 X50 Y20 I0 J10\nM30");
        assert_eq!(alarm_of(&ch), Some(10754));
    }

    /// A start point on the tangent ahead of Q leaves no curve that reaches Q in its
    /// direction without a loop: like KONTT, KONTC then moves straight (NORM).
    #[test]
    fn a_start_point_on_the_tangent_ahead_moves_straight() {
        let (ch, samples) = run("T1 D1\nG0 X30 Y5 Z-1\nKONTC G41 G1 X0 Y0 F2000\nX50\nG40 G1 X50 Y20\nM30");
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let to_q = between(&samples, |p| plane_dist(p, (30.0, 5.0)) < 1e-9 || plane_dist(p, (0.0, 5.0)) < 1e-9);
        assert!(to_q.iter().all(|p| (p[1] - 5.0).abs() < 1e-9));
    }
}

mod bottleneck {
    use super::*;

    /// Distance from a point to the polyline through `pts`.
    fn polyline_distance(p: &[f64], pts: &[(f64, f64)]) -> f64 {
        pts.windows(2).map(|w| seg_dist((p[0], p[1]), w[0], w[1])).fold(f64::MAX, f64::min)
    }

    /// A 2 mm step towards the tool (G41, radius 5): the equidistant of the step (x = 45)
    /// ends below the intersection (45, 5) with the first one, so the step is bridged. The
    /// tool leaves y = 5 where the circle of radius 5 about the step's top corner (50, 2)
    /// meets it, x = 50 − √(25 − 9) = 46, follows that circle to (50, 7) and runs on y = 7.
    #[test]
    fn a_step_shorter_than_the_radius_is_bridged_round_its_corner() {
        let contour = [(0.0, 0.0), (50.0, 0.0), (50.0, 2.0), (100.0, 2.0)];
        let program = "T1 D1\nG0 X-20 Y20 Z-1\nG41 G1 X0 Y0 F2000\nX50\nY2\nX100\nG40 G1 X120 Y20\nM30";
        let (ch, samples) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        assert!(passes(&samples, 46.0, 5.0) && passes(&samples, 50.0, 7.0) && passes(&samples, 100.0, 7.0));
        let cut = between(&samples, |p| {
            p[0].abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9 || (p[0] - 100.0).abs() < 1e-9 && (p[1] - 7.0).abs() < 1e-9
        });
        for p in cut {
            assert!((polyline_distance(p, &contour) - 5.0).abs() < 1e-6, "{p:?}");
        }
        // With MD20240 = 1 no block beyond the next is examined: alarm 10751.
        let (ch, _) = run_on("mill-3axis", "$MC_CUTCOM_MAXNUM_CHECK_BLOCKS=1", program);
        assert_eq!(alarm_of(&ch), Some(10751));
    }
}

/// KONTT onto and off a circular pocket (radius 20, G41: the centre runs on radius 15) from
/// and back to the pocket centre: the approach arc starts at (0, 0) and meets (15, 0) heading
/// +Y, so its centre lies on the x axis midway, (7.5, 0), radius 7.5 (the classic half-circle
/// approach, below the x axis); the retract mirrors it above the x axis.
#[test]
fn kontt_enters_and_leaves_a_circular_pocket_on_half_circles() {
    let program = "T1 D1\nG0 X0 Y0 Z-1\nKONTT G41 G1 X20 Y0 F1200\nG3 X20 Y0 I-20 J0\nG40 G1 X0 Y0\nM30";
    let (ch, samples) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let start = samples.iter().position(|p| p[2] == 99.0).unwrap();
    let moving: Vec<_> = samples[start..].iter().filter(|p| (p[0].hypot(p[1]) - 15.0).abs() > 1e-6).collect();
    assert!(moving.len() > 20);
    for p in &moving {
        // Off the pocket circle the tool is on one of the half circles.
        assert!(((p[0] - 7.5).hypot(p[1]) - 7.5).abs() < 1e-6, "{p:?}");
    }
    assert!(moving.iter().any(|p| p[1] < -7.0) && moving.iter().any(|p| p[1] > 7.0));
    assert_eq!(&ch.axis_positions()[..2], &[0.0, 0.0]);
}

/// G41 → G42 without G40: the left equidistant ends perpendicular at (50, 5), a straight line
/// crosses to the right one's perpendicular start (50, −5), which runs on to (100, −5).
#[test]
fn changing_the_side_without_g40_ends_and_restarts_perpendicular() {
    let (ch, samples) = run("T1 D1\nG0 X-20 Y20 Z-1\nG41 G1 X0 Y0 F2000\nX50\nG42 X100\nG40 X120 Y-20\nM30");
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    for (x, y) in [(0.0, 5.0), (50.0, 5.0), (50.0, -5.0), (100.0, -5.0)] {
        assert!(passes(&samples, x, y), "({x}, {y})");
    }
    // Between (50, 5) and (50, −5) the tool moves on x = 50 only.
    let cross = between(&samples, |p| (p[0] - 50.0).abs() < 1e-9 && (p[1].abs() - 5.0).abs() < 1e-9);
    assert!(cross.iter().all(|p| (p[0] - 50.0).abs() < 1e-9), "{cross:?}");
}

/// The radius is geometry plus wear: $TC_DP15 = −0.5 makes T1 a 4.5 mm cutter.
#[test]
fn the_wear_value_adds_to_the_radius() {
    let (ch, samples) = run_on("mill-3axis", "$TC_DP15[1,1]=-0.5", &SQUARE.replace("{sel}", "G41"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    for (x, y) in [(45.5, 4.5), (45.5, 45.5), (4.5, 45.5)] {
        assert!(passes(&samples, x, y), "({x}, {y})");
    }
}

#[test]
fn g41_without_a_cutting_edge_is_alarm_10750() {
    let (ch, _) = run("T1 D0\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F1000\nX50\nM30");
    assert_eq!(alarm_of(&ch), Some(10750));
}

/// RND=10 at the inner corner (50, 0) of the G41 square: the rounding belongs to the contour
/// (centre (40, 10), radius 10), so the tool centre runs on the concentric arc of radius 5
/// from (40, 5) to (45, 10).
#[test]
fn a_rounding_is_part_of_the_compensated_contour() {
    let program = "T1 D1\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F3000\nX50 RND=10\nY50\nX0\nY0\nG40 X-20 Y-20\nM30";
    let (ch, samples) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    // The rounding is travelled without a stop (G64 between it and its neighbours), so the
    // samples pass its ends without landing on them; all of them stay on the equidistants.
    let cut = between(&samples, |p| {
        (p[0] - 20.0).abs() < 0.5 && (p[1] - 5.0).abs() < 1e-9
            || (p[0] - 45.0).abs() < 1e-9 && (p[1] - 30.0).abs() < 0.5
    });
    assert!(cut.iter().all(|p| (p[1] - 5.0).abs() < 1e-9 && p[0] <= 40.0 + 1e-9
        || (p[0] - 45.0).abs() < 1e-9 && p[1] >= 10.0 - 1e-9
        || ((p[0] - 40.0).hypot(p[1] - 10.0) - 5.0).abs() < 1e-9));
    let corner: Vec<_> = samples.iter().filter(|p| p[0] > 40.0 + 1e-6 && p[1] < 10.0 - 1e-6 && p[1] > 4.0).collect();
    assert!(corner.len() > 5);
    for p in corner {
        assert!(((p[0] - 40.0).hypot(p[1] - 10.0) - 5.0).abs() < 1e-9, "{p:?}");
    }
}

/// M0 between two contour elements is a block without plane motion: the program stops with
/// the tool at the inner corner's intersection (45, 5), not at a perpendicular end, and NC
/// start goes on along the second equidistant.
#[test]
fn m0_inside_the_contour_stops_at_the_corner_point() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("T1 D1\nG0 X-20 Y-20 Z-1\nG41 G1 X0 Y0 F2000\nX50\nM0\nY50\nX0\nG40 X-20 Y-20\nM30").unwrap();
    for _ in 0..200_000 {
        if ch.status() == Status::Stopped {
            break;
        }
        ch.step();
    }
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    assert_eq!(&ch.axis_positions()[..2], &[45.0, 5.0]);
    ch.start().unwrap();
    let mut samples = vec![];
    while ch.is_busy() {
        ch.step();
        samples.push(ch.axis_positions().to_vec());
    }
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert!(passes(&samples, 45.0, 45.0));
}

/// SPOS inside a compensated contour is a block without motion in the plane: it neither ends
/// the compensation nor the look-ahead. The shoulder of `turning` with SPOS between the
/// longitudinal cut and the face: the tip still reaches the programmed corner (X10, Z−30)
/// (carrier X50, Z30 with the lengths 40 and 60), the spindle positions there.
#[test]
fn spos_inside_the_contour_keeps_the_compensation() {
    let program = "T1 D1\nG0 X15 Z5\nS1000 M3\nG42 G1 X10 Z0 F300\nZ-30\nSPOS=90\nX20\nG40 G0 X25 Z5\nM30";
    let mut ch = Channel::from_preset("lathe-2axis", "").unwrap();
    ch.run_program(program).unwrap();
    let mut at_corner = None;
    while ch.is_busy() {
        ch.step();
        let p = ch.axis_positions();
        if (p[0] - 50.0).abs() < 1e-9 && (p[1] - 30.0).abs() < 1e-9 {
            at_corner = Some(p[2]);
        }
    }
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    // The last sample at the corner is where the spindle has reached 90° (modulo a turn).
    let angle = at_corner.expect("the tip reaches the programmed corner");
    assert!((angle.rem_euclid(360.0) - 90.0).abs() < 1e-9, "{angle}");
}
