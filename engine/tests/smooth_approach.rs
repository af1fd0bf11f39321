//! Smooth approach and retract (SAR: G147/G148, G247/G248, G347/G348, G140..G143, G340/G341,
//! DISR, DISCL, FAD) checked against points, centres and radii worked out by hand from the
//! Programming Manual Fundamentals ("Approach and retraction") and the Function Manual W1.
//! The mill's T1 D1 has radius 5; every contour below starts at (40, −10) heading +X, so with
//! G41 the tool centre joins it at P4c = (40, −5) and with G42 at (40, −15).

use nctwin_engine::{Channel, Status};

/// Length of the mill's T1 D1.
const LENGTH: f64 = 100.0;

fn run(program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    // Z as the tool tip in the WCS: the tool's length (100) off the axis position.
    let tip = |ch: &Channel| {
        let mut p = ch.axis_positions().to_vec();
        p[2] -= LENGTH;
        p
    };
    let mut samples = vec![tip(&ch)];
    while ch.is_busy() {
        ch.step();
        samples.push(tip(&ch));
        assert!(samples.len() < 2_000_000);
    }
    (ch, samples)
}

fn first_alarm(program: &str) -> Option<(u32, Option<u32>)> {
    let (ch, _) = run(program);
    ch.snapshot().alarms.first().map(|a| (a.number, a.line))
}

/// Index of the first sample at (x, y, z).
fn at(samples: &[Vec<f64>], x: f64, y: f64, z: f64) -> Option<usize> {
    samples.iter().position(|p| (p[0] - x).abs() < 1e-9 && (p[1] - y).abs() < 1e-9 && (p[2] - z).abs() < 1e-9)
}

fn must(samples: &[Vec<f64>], x: f64, y: f64, z: f64) -> usize {
    at(samples, x, y, z).unwrap_or_else(|| panic!("the tool centre never stands at ({x}, {y}, {z})"))
}

/// Highest path speed (mm/min) between samples `a` and `b`.
fn top_speed(ch: &Channel, samples: &[Vec<f64>], a: usize, b: usize) -> f64 {
    let dt = ch.config().ipo_cycle;
    samples[a..=b]
        .windows(2)
        .map(|w| {
            ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2) + (w[1][2] - w[0][2]).powi(2)).sqrt() / dt * 60.0
        })
        .fold(0.0, f64::max)
}

/// The manual's example with the mill's tool: G41, G341 (infeed in the plane), G247 with
/// DISR=13 (radius of the tool centre path), DISCL=AC(5), FAD=500, F200.
/// By hand: P4c = (40, −5); G140 with G41 approaches from the left, so the quadrant's centre
/// lies 13 to the left of P4c, C = (40, 8), and it starts a quarter turn before P4c, back
/// along the tangent: P3 = C − 13·(1, 0) = (27, 8). G341: P1 = (27, 8, 20) at the start
/// height, P2 = (27, 8, 5) on the DISCL plane (both at the velocity before: G0), P3 = (27, 8,
/// 0) at FAD, then the quadrant in the plane at F.
const QUADRANT_IN_PLANE: &str =
    "T1 D1\nG0 X0 Y0 Z20\nG1 G41 G341 G247 DISCL=AC(5) DISR=13 FAD=500 X40 Y-10 Z0 F200\nX60\nG40 X70 Y-30\nM30";

#[test]
fn g247_g341_runs_p1_p2_p3_then_the_quadrant_of_radius_disr_about_its_centre() {
    let (ch, s) = run(QUADRANT_IN_PLANE);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p1, p2, p3, p4) =
        (must(&s, 27.0, 8.0, 20.0), must(&s, 27.0, 8.0, 5.0), must(&s, 27.0, 8.0, 0.0), must(&s, 40.0, -5.0, 0.0));
    assert!(p1 < p2 && p2 < p3 && p3 < p4);
    // From P0 to P1 the tool stays at Z20 (parallel to the plane), then only Z moves.
    let p0 = must(&s, 0.0, 0.0, 20.0);
    assert!(s[p0..=p1].iter().all(|p| (p[2] - 20.0).abs() < 1e-9));
    assert!(s[p1..=p3].iter().all(|p| (p[0] - 27.0).abs() < 1e-9 && (p[1] - 8.0).abs() < 1e-9));
    // The quadrant: every sample 13 from (40, 8) at Z0, in the quarter below-left of it.
    for p in &s[p3..=p4] {
        assert!(((p[0] - 40.0).hypot(p[1] - 8.0) - 13.0).abs() < 1e-9, "{p:?}");
        assert!(p[2].abs() < 1e-12 && p[0] <= 40.0 + 1e-9 && p[1] <= 8.0 + 1e-9, "{p:?}");
    }
    // It arrives heading +X (tangent to the contour): the last step before P4c is along X.
    let (a, b) = (&s[p4 - 1], &s[p4]);
    assert!((b[1] - a[1]).abs() < 1e-3 * (b[0] - a[0]), "{a:?} → {b:?}");
    // Feeds: G0 to P2 (far above 500), FAD on the slow infeed, F200 on the quadrant.
    assert!(top_speed(&ch, &s, p0, p2) > 5000.0);
    let fad = top_speed(&ch, &s, p2, p3);
    assert!((fad - 500.0).abs() < 0.5, "slow infeed at {fad} mm/min");
    let f = top_speed(&ch, &s, p3, p4);
    assert!((f - 200.0).abs() < 0.5, "quadrant at {f} mm/min");
    // The contour follows on the equidistant.
    must(&s, 60.0, -5.0, 0.0);
}

/// G340 (in space): P1 = (27, 8, 20), the fast infeed straight down to the DISCL plane at
/// P3 = (27, 8, 3) (DISCL=3 above the plane through P4 at Z0), and from there a helix about
/// (40, 8) of radius 13 down to P4c at Z0, at FAD: along it Z falls linearly with the angle.
#[test]
fn g247_g340_descends_on_a_helix_from_the_discl_plane_at_fad() {
    let program = QUADRANT_IN_PLANE.replace("G341", "G340").replace("DISCL=AC(5)", "DISCL=3");
    let (ch, s) = run(&program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p1, p3, p4) = (must(&s, 27.0, 8.0, 20.0), must(&s, 27.0, 8.0, 3.0), must(&s, 40.0, -5.0, 0.0));
    assert!(p1 < p3 && p3 < p4);
    assert!(at(&s, 27.0, 8.0, 0.0).is_none(), "no infeed to the contour height before the helix");
    for p in &s[p3..=p4] {
        assert!(((p[0] - 40.0).hypot(p[1] - 8.0) - 13.0).abs() < 1e-9, "{p:?}");
        // Angle from the start (π) towards P4c (3π/2): Z = 3·(1 − φ/(π/2)).
        let phi = (p[1] - 8.0).atan2(p[0] - 40.0).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
        assert!((p[2] - 3.0 * (1.0 - phi / std::f64::consts::FRAC_PI_2)).abs() < 1e-9, "{p:?}");
    }
    let fad = top_speed(&ch, &s, p3, p4);
    assert!((fad - 500.0).abs() < 0.5, "helix at {fad} mm/min (FAD)");
}

/// G147: a straight line whose length is DISR plus the tool radius: DISR=10 gives 15, so
/// P3 = (40 − 15, −5) = (25, −5); G340 with DISCL=2 runs it from Z2 to Z0 at FAD=300.
#[test]
fn g147_approaches_on_the_tangent_from_disr_plus_the_tool_radius() {
    let program = "T1 D1\nG0 X0 Y0 Z20\nG1 G41 G147 DISR=10 DISCL=2 FAD=300 X40 Y-10 Z0 F1000\nX60\nG40 X70 Y-30\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p1, p3, p4) = (must(&s, 25.0, -5.0, 20.0), must(&s, 25.0, -5.0, 2.0), must(&s, 40.0, -5.0, 0.0));
    assert!(p1 < p3 && p3 < p4);
    for p in &s[p3..=p4] {
        assert!((p[1] + 5.0).abs() < 1e-9 && (p[2] - 2.0 * (40.0 - p[0]) / 15.0).abs() < 1e-9, "{p:?}");
    }
    assert!((top_speed(&ch, &s, p3, p4) - 300.0).abs() < 0.5);
    // The contour after P4 at F1000.
    let p5 = must(&s, 60.0, -5.0, 0.0);
    assert!((top_speed(&ch, &s, p4, p5) - 1000.0).abs() < 0.5);
}

/// G347 with G42: P4c = (40, −15); G140 with G42 approaches from the right, so the centre is
/// DISR=10 to the right, C = (40, −25), and the semicircle starts two radii to the right of
/// P4c, P3 = (40, −35), running clockwise through (30, −25).
#[test]
fn g347_with_g42_is_a_semicircle_from_the_right() {
    let program = "T1 D1\nG0 X0 Y0 Z20\nG1 G42 G341 G347 DISR=10 X40 Y-10 Z0 F1000\nX60\nG40 X70 Y0\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p3, p4) = (must(&s, 40.0, -35.0, 0.0), must(&s, 40.0, -15.0, 0.0));
    assert!(p3 < p4);
    for p in &s[p3..=p4] {
        assert!(((p[0] - 40.0).hypot(p[1] + 25.0) - 10.0).abs() < 1e-9 && p[0] <= 40.0 + 1e-9, "{p:?}");
    }
    // No DISCL: the fast infeed goes down to the contour's height (P2 in the plane).
    assert!(must(&s, 40.0, -35.0, 20.0) < p3);
    must(&s, 60.0, -15.0, 0.0);
}

/// G143 decides by the start point: (0, −40) lies right of the tangent line Y=−10 (heading
/// +X), so the quadrant comes from the right even under G41: C = (40, −5 − 13) = (40, −18),
/// P3 = (27, −18).
#[test]
fn g143_approaches_from_the_side_of_the_start_point() {
    let program = "T1 D1\nG0 X0 Y-40 Z20\nG1 G41 G143 G341 G247 DISR=13 X40 Y-10 Z0 F1000\nX60\nG40 X70 Y-30\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p3, p4) = (must(&s, 27.0, -18.0, 0.0), must(&s, 40.0, -5.0, 0.0));
    for p in &s[p3..=p4] {
        assert!(((p[0] - 40.0).hypot(p[1] + 18.0) - 13.0).abs() < 1e-9, "{p:?}");
    }
}

/// G141 forces the left side under G42: P4c = (40, −15), C = (40, −15 + 8) = (40, −7) for
/// DISR=8, P3 = (32, −7).
#[test]
fn g141_approaches_from_the_left_whatever_the_compensation_side() {
    let program = "T1 D1\nG0 X0 Y0 Z20\nG1 G42 G141 G341 G247 DISR=8 X40 Y-10 Z0 F1000\nX60\nG40 X70 Y-30\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p3, p4) = (must(&s, 32.0, -7.0, 0.0), must(&s, 40.0, -15.0, 0.0));
    for p in &s[p3..=p4] {
        assert!(((p[0] - 40.0).hypot(p[1] + 7.0) - 8.0).abs() < 1e-9, "{p:?}");
    }
}

/// Retract with G248 G341 from the contour's end (60, −10) heading +X, G41: P4c = (60, −5);
/// G140 leaves to the left on a quadrant of radius 8 about (60, 3) to P3 = (68, 3) in the
/// plane at the contour's feed (F200 before the block), up at FAD=400 to the DISCL plane
/// P2 = (68, 3, 4), at the block's F3000 up to P1 = (68, 3, 30) and on to P0 = (90, 20, 30).
#[test]
fn g248_g341_retracts_on_a_quadrant_then_lifts_at_fad_and_f() {
    let program = "T1 D1\nG0 X0 Y-10 Z0\nG1 G41 X40 Y-10 F200\nX60\nG40 G248 G341 DISR=8 DISCL=AC(4) FAD=400 X90 Y20 Z30 F3000\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let p4 = must(&s, 60.0, -5.0, 0.0);
    let (p3, p2, p1) = (must(&s, 68.0, 3.0, 0.0), must(&s, 68.0, 3.0, 4.0), must(&s, 68.0, 3.0, 30.0));
    assert!(p4 < p3 && p3 < p2 && p2 < p1);
    for p in &s[p4..=p3] {
        assert!(((p[0] - 60.0).hypot(p[1] - 3.0) - 8.0).abs() < 1e-9 && p[2].abs() < 1e-12, "{p:?}");
    }
    assert!((top_speed(&ch, &s, p4, p3) - 200.0).abs() < 0.5);
    assert!((top_speed(&ch, &s, p3, p2) - 400.0).abs() < 0.5);
    assert!((top_speed(&ch, &s, p2, p1) - 3000.0).abs() < 1.0);
    assert_eq!(&s.last().unwrap()[..3], &[90.0, 20.0, 30.0]);
}

/// G148 under G340: the line of DISR + radius = 3 + 5 = 8 from P4c = (60, −5) along +X to
/// P3 = (68, −5), rising to DISCL=2 on the way (in space), then up to Z30 and to P0.
#[test]
fn g148_g340_leaves_on_the_tangent_rising_to_the_discl_plane() {
    let program = "T1 D1\nG0 X0 Y-10 Z0\nG1 G41 X40 Y-10 F1000\nX60\nG40 G148 G340 DISR=3 DISCL=2 X80 Y-5 Z30\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p4, p3, p1) = (must(&s, 60.0, -5.0, 0.0), must(&s, 68.0, -5.0, 2.0), must(&s, 68.0, -5.0, 30.0));
    assert!(p4 < p3 && p3 < p1);
    for p in &s[p4..=p3] {
        assert!((p[1] + 5.0).abs() < 1e-9 && (p[2] - 2.0 * (p[0] - 60.0) / 8.0).abs() < 1e-9, "{p:?}");
    }
    assert_eq!(&s.last().unwrap()[..3], &[80.0, -5.0, 30.0]);
}

/// DISCL=AC(..) is a WCS position: under TRANS Z10 the plane AC(5) lies at Z15 of the basic
/// system, the start height Z20 at Z30 and the contour (Z0) at Z10.
#[test]
fn discl_ac_is_a_position_in_the_workpiece_coordinate_system() {
    let program = QUADRANT_IN_PLANE.replace("T1 D1\n", "T1 D1\nTRANS Z10\n");
    let (ch, s) = run(&program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p1, p2, p3) = (must(&s, 27.0, 8.0, 30.0), must(&s, 27.0, 8.0, 15.0), must(&s, 27.0, 8.0, 10.0));
    assert!(p1 < p2 && p2 < p3);
}

/// FAD=PM(..) is a feed per minute whatever G group 15 says; under G94 it equals FAD=..
#[test]
fn fad_pm_is_a_feed_per_minute() {
    let (ch, s) = run(&QUADRANT_IN_PLANE.replace("FAD=500", "FAD=PM(450)"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p2, p3) = (must(&s, 27.0, 8.0, 5.0), must(&s, 27.0, 8.0, 0.0));
    assert!((top_speed(&ch, &s, p2, p3) - 450.0).abs() < 0.5);
}

#[test]
fn invalid_sar_blocks_are_alarms_with_their_numbers() {
    let base = "T1 D1\nG0 X0 Y0 Z20\n{b}\nX60\nG40 X70 Y-30\nM30";
    let case = |b: &str| first_alarm(&base.replace("{b}", b));
    // DISR missing, or not positive for a circle: 10742.
    assert_eq!(case("G1 G41 G247 X40 Y-10 Z0 F200"), Some((10742, Some(3))));
    assert_eq!(case("G1 G41 G247 DISR=0 X40 Y-10 Z0 F200"), Some((10742, Some(3))));
    assert_eq!(case("G1 G41 G147 DISR=-1 X40 Y-10 Z0 F200"), Some((10742, Some(3))));
    // Two contours in one block: 10743.
    assert_eq!(case("G1 G41 G147 G247 DISR=5 X40 Y-10 Z0 F200"), Some((10743, Some(3))));
    // The clearance plane above the start point: the infeed would turn back, 10741.
    assert_eq!(case("G1 G41 G247 DISR=5 DISCL=AC(30) X40 Y-10 Z0 F200"), Some((10741, Some(3))));
    // G143 with the start point on the tangent line Y=−10: no side, 10744.
    let on_tangent = "T1 D1\nG0 X0 Y-10 Z20\nG1 G41 G143 G247 DISR=5 X40 Y-10 Z0 F200\nX60\nM30";
    assert_eq!(first_alarm(on_tangent), Some((10744, Some(3))));
    // SAR words in a block without motion and without TRC: 10744.
    assert_eq!(case("G247 DISR=5 F200"), Some((10744, Some(3))));
    // Retract with G143 and no end point in the plane: 10747.
    let implicit = "T1 D1\nG0 X0 Y-10 Z0\nG1 G41 X40 F200\nX60\nG40 G143 G248 DISR=5 Z30\nM30";
    assert_eq!(first_alarm(implicit), Some((10747, Some(5))));
}

/// A retract without an end point in the plane ends where the retract contour ends (P0 = P3
/// in the plane): from P4c = (60, −5) a semicircle of radius 6 to the left ends at (60, 7).
#[test]
fn a_retract_without_plane_end_point_ends_above_p3() {
    let program = "T1 D1\nG0 X0 Y-10 Z0\nG1 G41 X40 F200\nX60\nG40 G348 DISR=6 Z30\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    must(&s, 60.0, 7.0, 0.0);
    assert_eq!(&s.last().unwrap()[..3], &[60.0, 7.0, 30.0]);
}

/// Without TRC the tool centre joins the contour point itself, and G140 decides like G143:
/// the start (0, 0) lies left of the tangent at (40, −10) heading +X, so the quadrant of
/// radius DISR=10 has its centre at (40, 0) and starts at P3 = (30, 0). The contour goes on
/// uncompensated, an arc included.
#[test]
fn without_trc_the_quadrant_ends_on_the_contour_point() {
    let program = "T1 D1\nG0 X0 Y0 Z20\nG1 G341 G247 DISR=10 X40 Y-10 Z0 F1000\nX60\nG3 X60 Y10 CR=10\nM30";
    let (ch, s) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p3, p4) = (must(&s, 30.0, 0.0, 0.0), must(&s, 40.0, -10.0, 0.0));
    for p in &s[p3..=p4] {
        assert!(((p[0] - 40.0).hypot(p[1]) - 10.0).abs() < 1e-9, "{p:?}");
    }
    let p5 = must(&s, 60.0, -10.0, 0.0);
    assert!(s[p4..=p5].iter().all(|p| (p[1] + 10.0).abs() < 1e-9));
    assert_eq!(&s.last().unwrap()[..3], &[60.0, 10.0, 0.0]);
    assert!(s[p5..].iter().all(|p| ((p[0] - 60.0).hypot(p[1]) - 10.0).abs() < 1e-9));
}

/// A retract needs the contour's last element: without TRC there is none held (10744).
#[test]
fn a_retract_without_trc_is_refused() {
    let program = "T1 D1\nG0 X0 Y-10 Z0\nG1 X60 F1000\nG148 DISR=5 X80 Y0 Z30\nM30";
    assert_eq!(first_alarm(program), Some((10744, Some(4))));
}

/// The manual's example of P4 from the next block: `N30 G41 G147 DISCL=3 DISR=13 Z=0 F1000`
/// then `N40 G1 X40 Y-10`, or `N30 G41 G147 DISCL=3 DISR=13 F1000` then `N40 G1 X40 Y-10 Z0`,
/// run as `N30 G41 G147 DISCL=3 DISR=13 X40 Y-10 Z0 F1000`. With the
/// tool radius 5: P4c = (40, −5), the line 13 + 5 = 18 long from P3 = (22, −5); G340: P1 =
/// (22, −5, 30), P3 at the DISCL height 3, then the line down to Z0 at F1000.
#[test]
fn p4_from_the_next_block_gives_the_same_approach() {
    let split =
        "G90 G0 X0 Y0 Z30 D1 T1\nX10\nG41 G147 DISCL=3 DISR=13 Z=0 F1000\nG1 X40 Y-10\nG1 X50\nG40 X60 Y-30\nM30";
    let joined = "G90 G0 X0 Y0 Z30 D1 T1\nX10\nG41 G147 DISCL=3 DISR=13 X40 Y-10 Z0 F1000\nG1 X50\nG40 X60 Y-30\nM30";
    // The third form of the manual: the SAR block without any motion, the next block with P4.
    let words_only =
        "G90 G0 X0 Y0 Z30 D1 T1\nX10\nG41 G147 DISCL=3 DISR=13 F1000\nG1 X40 Y-10 Z0\nG1 X50\nG40 X60 Y-30\nM30";
    for program in [split, joined, words_only] {
        let (ch, s) = run(program);
        assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
        let (p0, p1, p3, p4) = (
            must(&s, 10.0, 0.0, 30.0),
            must(&s, 22.0, -5.0, 30.0),
            must(&s, 22.0, -5.0, 3.0),
            must(&s, 40.0, -5.0, 0.0),
        );
        assert!(p0 < p1 && p1 < p3 && p3 < p4, "{program}");
        for p in &s[p3..=p4] {
            assert!((p[1] + 5.0).abs() < 1e-9 && (p[2] - 3.0 * (40.0 - p[0]) / 18.0).abs() < 1e-9, "{p:?}");
        }
        assert!((top_speed(&ch, &s, p3, p4) - 1000.0).abs() < 0.5);
        must(&s, 50.0, -5.0, 0.0);
    }
}

/// `$P_GG[43]` (G140..G143 → 1..4, G140 the reset value) and `$P_GG[44]` (G340 1, G341 2).
#[test]
fn p_gg_reads_the_sar_groups() {
    let program = "IF ($P_GG[43]<>1) OR ($P_GG[44]<>1)\nSETAL(65000)\nENDIF\nG143 G341\nIF ($P_GG[43]<>4) OR ($P_GG[44]<>2)\nSETAL(65000)\nENDIF\nG142\nIF $P_GG[43]<>3\nSETAL(65000)\nENDIF\nM30";
    let (ch, _) = run(program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.alarms());
}

/// Under TRANSMIT the approach runs in the face's Cartesian plane like any compensated path:
/// tool radius 5 (written in the program), contour from X10 Y−10 heading −X, G41: the tool
/// centre joins it at P4c = (10, −15); G140 approaches from the left of −X (towards −Y), so the
/// quadrant of radius DISR=5 has its centre at (10, −20) and starts at P3 = (15, −20). Every
/// sample of the SAR block after P3, turned from (radial X, C) into the face's X/Y, lies on
/// that circle.
#[test]
fn under_transmit_the_quadrant_lies_in_the_face_plane() {
    let program = "$TC_DP6[1,1]=5\nT1 D1 G17 G90 F3000 G94\nG0 X40 Z10\nTRANSMIT\nG0 X20 Y-20\nG1 G41 G341 G247 DISR=5 X10 Y-10\nX-10\nY10\nG40 X-20 Y20\nTRAFOOF\nM30";
    let mut ch = Channel::from_preset("transmit-example", "").unwrap();
    ch.run_program(program).unwrap();
    let mut on_arc = 0;
    let mut seen_p3 = false;
    while ch.is_busy() {
        ch.step();
        let s = ch.snapshot();
        let (r, c) = (ch.axis_positions()[0], ch.axis_positions()[1].to_radians());
        let (x, y) = (r * c.cos(), r * c.sin());
        if s.block.map(|b| b.line) == Some(6) {
            seen_p3 |= (x - 15.0).hypot(y + 20.0) < 1e-6;
            if seen_p3 {
                assert!(((x - 10.0).hypot(y + 20.0) - 5.0).abs() < 1e-6, "({x}, {y})");
                on_arc += 1;
            }
        }
    }
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert!(seen_p3 && on_arc > 5, "{on_arc}");
}

/// DISRP puts P1 on the retraction plane: with DISRP=10 the approach of the manual's example
/// goes from P0 (0, 0, 20) in a straight line down to P1 = (27, 8, 10) (not parallel to the
/// plane), then on as before to P2 = (27, 8, 5). A DISRP below the DISCL plane is 10748.
#[test]
fn disrp_sets_the_height_of_p1() {
    let (ch, s) = run(&QUADRANT_IN_PLANE.replace("DISR=13", "DISR=13 DISRP=10"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let (p0, p1, p2) = (must(&s, 0.0, 0.0, 20.0), must(&s, 27.0, 8.0, 10.0), must(&s, 27.0, 8.0, 5.0));
    assert!(p0 < p1 && p1 < p2);
    for p in &s[p0..=p1] {
        // On the line from (0, 0, 20) to (27, 8, 10): X/27 = Y/8 = (20 − Z)/10.
        let u = p[0] / 27.0;
        assert!((p[1] - 8.0 * u).abs() < 1e-9 && (p[2] - (20.0 - 10.0 * u)).abs() < 1e-9, "{p:?}");
    }
    assert!(at(&s, 27.0, 8.0, 20.0).is_none());
    assert_eq!(first_alarm(&QUADRANT_IN_PLANE.replace("DISR=13", "DISR=13 DISRP=3")), Some((10748, Some(3))));
}
