//! Words of shop and machine-builder programs that need more than a fixture program to check:
//! a block search (`$P_SEARCH`), the feed of chamfers read from the IPO samples (`FRC`).

use crate::settle;

use nctwin_engine::{Channel, Status};
use settle::{channel, settle};

/// Runs `program` on the 3-axis mill to its end without an alarm; the channel and the
/// channel-axis samples of every IPO cycle.
fn run_clean(program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = channel("mill-3axis", "");
    ch.run_program(program).unwrap();
    let samples = settle(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    (ch, samples)
}

/// The (number, line) of the alarms `program` ends with on the 3-axis mill.
fn alarms_of(program: &str) -> Vec<(u32, Option<u32>)> {
    let mut ch = channel("mill-3axis", "");
    ch.run_program(program).unwrap();
    settle(&mut ch);
    ch.alarms().iter().map(|a| (a.number, a.line)).collect()
}

/// A tool-change program's guard: `IF $P_SEARCH GOTOF` skips the change during a search.
const GUARDED: &str = "G0 X0 Y0
R1=$P_SEARCH R2=$P_SEARCHL
IF $P_SEARCH GOTOF SKIP
R3=7
SKIP:
G0 X5
R4=$P_SEARCH R5=$P_SEARCHL
M30";

#[test]
fn p_search_is_one_only_while_a_block_search_prepares_the_blocks_before_its_target() {
    // A plain run: no search, so the guarded block runs and both variables read 0.
    let mut ch = channel("mill-3axis", "");
    ch.run_program(GUARDED).unwrap();
    settle(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let r = |ch: &Channel| [1, 2, 3, 4, 5].map(|n| ch.r_param(n));
    assert_eq!(r(&ch), [0.0, 0.0, 7.0, 0.0, 0.0]);

    // A search to line 6 (G0 X5): lines 1..5 are computed with $P_SEARCH = 1 and the type of
    // the search, 2 (with calculation to the contour), in $P_SEARCHL; R3=7 is jumped over.
    // After NC start line 7 reads $P_SEARCH 0 while $P_SEARCHL keeps 2 until the next start.
    let mut ch = channel("mill-3axis", "");
    ch.block_search(Some(GUARDED), 6).unwrap();
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    assert_eq!(r(&ch), [1.0, 2.0, 0.0, 0.0, 0.0]);
    ch.start().unwrap();
    settle(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(r(&ch), [1.0, 2.0, 0.0, 0.0, 2.0]);
    assert_eq!(ch.axis_positions()[0], 5.0);

    // The next program starts without a search: both read 0 again.
    ch.run_program("R4=$P_SEARCH R5=$P_SEARCHL\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(r(&ch)[3..], [0.0, 0.0]);
}

/// The mill's tool spindle S1 (master spindle 1, 3000 rev/min per second).
fn s1(ch: &Channel) -> nctwin_engine::SpindleState {
    ch.snapshot().spindle_states.iter().find(|(n, _)| n == "S1").expect("S1").1
}

#[test]
fn spcon_puts_the_turning_spindle_into_position_control_until_spcof() {
    use nctwin_engine::SpindleMode;
    // M3 S1000 reaches 1000 rev/min in 1/3 s; SPCON keeps it turning (speed control in a
    // position loop), the state shows position control; SPCOF ends it, still at M3.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("M3 S1000\nG4 F0.5\nSPCON\nM0\nSPCOF\nM0\nSPOS=90\nSPCOF(1)\nM0\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped, "{:?}", ch.alarms());
    let s = s1(&ch);
    assert!(s.position_control);
    assert_eq!((s.mode, s.speed), (SpindleMode::M3, 1000.0));
    ch.start().unwrap();
    settle(&mut ch);
    let s = s1(&ch);
    assert!(!s.position_control);
    assert_eq!((s.mode, s.speed), (SpindleMode::M3, 1000.0));
    // SPOS=90 stops the spindle at 90° in position control; SPCOF(1) returns it to speed
    // control where it stands: M5, 90°.
    ch.start().unwrap();
    settle(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let s = s1(&ch);
    assert!(!s.position_control);
    assert_eq!(s.mode, SpindleMode::M5);
    assert!((s.position - 90.0).abs() < 1e-6, "{}", s.position);
}

#[test]
fn spcon_of_a_spindle_the_channel_does_not_have_is_12560() {
    assert_eq!(alarms_of("SPCON(2)\nM30"), [(12560, Some(1))]);
}

#[test]
fn ct_continues_a_line_along_x_on_the_circle_about_10_10() {
    // G1 to (10,0) heading +X, then CT X20 Y10: centre (10,10), radius 10, counter-clockwise
    // (worked out in tests/programs/lang/161_ct_tangential_circle.mpf). Under G60 (exact stop,
    // the reset state) every sample past X10 lies on that circle.
    let (_, samples) = run_clean("G0 X0 Y0\nG1 X10 F3000\nCT X20 Y10\nM30");
    let on_arc: Vec<_> = samples.iter().filter(|p| p[0] > 10.0 + 1e-6).collect();
    assert!(on_arc.len() > 50, "{}", on_arc.len());
    for p in &on_arc {
        let r = (p[0] - 10.0).hypot(p[1] - 10.0);
        assert!((r - 10.0).abs() < 1e-6, "{p:?}: r = {r}");
        assert!(p[1] <= 10.0 + 1e-9, "{p:?} beyond the quarter");
    }
    let end = samples.last().unwrap();
    assert!((end[0] - 20.0).abs() < 1e-9 && (end[1] - 10.0).abs() < 1e-9, "{end:?}");
}

#[test]
fn ct_with_its_end_point_straight_ahead_is_14040() {
    // The end point on the tangent leaves no circle: 14040 at the CT block.
    assert_eq!(alarms_of("G1 X10 F3000\nCT X30\nM30"), [(14040, Some(2))]);
}

/// The highest path speed (mm/s, X and Y) between consecutive samples for which `inside`
/// holds at both ends.
fn top_speed(samples: &[Vec<f64>], dt: f64, inside: impl Fn(&[f64]) -> bool) -> f64 {
    samples
        .windows(2)
        .filter(|w| inside(&w[0]) && inside(&w[1]))
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]) / dt)
        .fold(0.0, f64::max)
}

#[test]
fn frc_gives_the_chamfer_its_own_feed_and_the_blocks_keep_f() {
    // G1 X20 at F600 (10 mm/s) with CHF=2√2 at the corner to +Y: the chamfer cuts 2 mm off
    // each block (leg = CHF / (2 cos 45°)), from (18,0) to (20,2). FRC=120 → 2 mm/s on the
    // chamfer only; the Y block runs at F again (10 mm/s).
    let (ch, samples) = run_clean("G0 X0 Y0\nG1 X20 F600 CHF=2.8284271 FRC=120\nY20\nM30");
    let dt = ch.time() / ch.ticks() as f64;
    let chamfer = top_speed(&samples, dt, |p| p[0] > 18.0 + 1e-6 && p[1] > 1e-6 && p[1] < 2.0 - 1e-6);
    assert!((chamfer - 2.0).abs() < 0.02, "chamfer at {chamfer} mm/s");
    let first = top_speed(&samples, dt, |p| p[0] < 18.0 && p[1] == 0.0);
    let second = top_speed(&samples, dt, |p| p[1] > 2.0 + 1e-6);
    assert!((first - 10.0).abs() < 0.05 && (second - 10.0).abs() < 0.05, "{first} {second}");
}

#[test]
fn frcm_is_modal_per_revolution_under_g95_and_frcm_0_returns_to_f() {
    // G95 with S1000: F0.6 = 600 mm/min (10 mm/s), FRCM=0.12 = 120 mm/min (2 mm/s) on each
    // following corner. Corner 1 at (20,0), CHF as above: 2 mm/s. Corner 2 at (20,20) (Y+ then
    // X−), RND=2: an arc of radius 2 from (20,18) to (18,20), still at FRCM. FRCM=0 in the X
    // block: corner 3 at (0,20) (X− then Y−), RND=2, runs at the block's F, 10 mm/s.
    let (ch, samples) = run_clean(
        "G0 X0 Y0\nM3 S1000\nG4 F1\nG95 G1 X20 F0.6 CHF=2.8284271 FRCM=0.12\nY20 RND=2\nX0 RND=2 FRCM=0\nY0\nM30",
    );
    let dt = ch.time() / ch.ticks() as f64;
    let corner1 = top_speed(&samples, dt, |p| p[0] > 18.0 + 1e-6 && p[1] > 1e-6 && p[1] < 2.0 - 1e-6);
    let corner2 = top_speed(&samples, dt, |p| p[0] > 18.0 + 1e-6 && p[1] > 18.0 + 1e-6 && p[0] < 20.0 - 1e-6);
    let corner3 = top_speed(&samples, dt, |p| p[0] < 2.0 - 1e-6 && p[1] > 18.0 + 1e-6 && p[0] > 1e-6);
    assert!((corner1 - 2.0).abs() < 0.02, "corner 1 at {corner1} mm/s");
    assert!((corner2 - 2.0).abs() < 0.02, "corner 2 at {corner2} mm/s");
    assert!((corner3 - 10.0).abs() < 0.1, "corner 3 at {corner3} mm/s");
}
