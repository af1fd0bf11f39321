//! Bottleneck detection between elements that are not neighbours (issue 25: MD20240
//! CUTCOM_MAXNUM_CHECK_BLOCKS look-ahead) and warning 10763 for blocks the compensation omits.
//!
//! The contour: a mushroom-shaped pocket whose neck (x = 20 … 28, 8 mm) is narrower than the
//! tool (T1 D1: radius 5) and whose chamber is one long arc, so no element is too short on its
//! own: the neck's walls are two blocks apart. G41 (tool left, material right):
//! e1 (0,0)→(20,0), e2 down the neck to (20,−10), e3 G3 about (24,−20) (radius √116 = 10.770)
//! round the chamber to (28,−10), e4 up the neck to (28,0), e5 on to (60,0).
//! With G451 the outer corner e4→e5 lies where e4's equidistant x = 28 − 5 = 23 meets e5's
//! y = 5: (23,5), on e1's equidistant y = 5 before its own corner at (25,5) — the tool paths of
//! e1 and e4 cross there (Function Manual W1, collision detection).
//! Decisions (named in `compensation/distant.rs`): CDON cuts the tool path at the crossing and
//! skips e2…e4 (warning 10763 for each, the program goes on); CDOF, the reset value, stops
//! with alarm 10751 before the tool moves along e1.

use crate::trc_support;

use nctwin_engine::Status;
use trc_support::{alarm_of, run_to_stop, warnings_of};

fn mushroom(mode: &str) -> String {
    format!(
        "G17 G90 T1 D1 G451 {mode}\nG0 X-10 Y20 Z0\nG41 G1 X0 Y0 F1000\nG1 X20 Y0\nG1 X20 Y-10\n\
         G3 X28 Y-10 I4 J-10\nG1 X28 Y0\nG1 X60 Y0\nG40 G1 X70 Y20\nM30"
    )
}

/// CDON: from the first element's perpendicular start (0,5) to the last one's end (60,5) the
/// tool centre stays on y = 5 (the neck bridged at (23,5)), and the three skipped blocks
/// (lines 5, 6, 7) are shown as warning 10763 without stopping the program.
#[test]
fn cdon_bridges_a_neck_between_elements_two_blocks_apart() {
    // Run once to the end: the warnings do not stop the program.
    let (ch, samples) = run_to_stop("mill-3axis", "", &mushroom("CDON"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert_eq!(alarm_of(&ch), None, "{:?}", ch.alarms());
    let first = samples.iter().position(|p| p[0].abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9).expect("reaches (0,5)");
    let last = samples.iter().position(|p| (p[0] - 60.0).abs() < 1e-9 && (p[1] - 5.0).abs() < 1e-9).expect("(60,5)");
    for p in &samples[first..=last] {
        assert!((p[1] - 5.0).abs() < 1e-9, "off y = 5: {p:?}");
    }
    assert_eq!(&ch.axis_positions()[..2], &[70.0, 20.0]);
    let warnings = warnings_of(&ch);
    assert!(!warnings.is_empty() && warnings.iter().all(|w| w.0 == 10763), "{warnings:?}");
    // The channel shows one entry per alarm number; the first omitted block is line 5.
    assert_eq!(warnings[0].1, Some(5));
}

/// CDOF: the crossing is alarm 10751 on e4's block (line 7), raised while preparing e5 —
/// before anything of e1 (or of the approach held back with it) has moved.
#[test]
fn cdof_stops_with_alarm_10751_before_the_tool_moves_into_the_neck() {
    let (ch, samples) = run_to_stop("mill-3axis", "", &mushroom("CDOF"));
    assert_eq!(alarm_of(&ch), Some(10751), "{:?}", ch.alarms());
    assert_eq!(ch.alarms().iter().find(|a| a.number == 10751).unwrap().line, Some(7));
    // From the machine zero the G0 goes to (−10,20); nothing moves right of x = 0.
    assert!(samples.iter().all(|p| p[0] <= 1e-9), "no motion along e1");
}

/// G450 (transition circles): e1's circle about (20,0) and e5's about (28,0) cross at (24,3),
/// a point 3 from both neck walls, and e4's equidistant x = 23 passes 3 from e1's end (20,0).
/// The tool paths do not cross on e1's equidistant, so there is nothing to cut: alarm 10751
/// with CDON too, before the tool moves.
#[test]
fn a_neck_reached_without_crossing_the_held_equidistant_is_alarm_10751_under_cdon() {
    let prog = mushroom("CDON").replace("G451", "G450");
    let (ch, samples) = run_to_stop("mill-3axis", "", &prog);
    assert_eq!(alarm_of(&ch), Some(10751), "{:?}", ch.alarms());
    assert!(samples.iter().all(|p| p[0] <= 1e-9), "no motion along e1");
}

/// Warning 10763 also for an element omitted by the neighbour look-ahead: the issue's
/// chamfer between two inside corners (`G1 X70 Y48` / `G1 X68 Y50`, 2.83 mm, shorter than its
/// corners need) is skipped, the program goes on to its end.
#[test]
fn an_omitted_short_element_is_warning_10763_and_the_program_goes_on() {
    let prog = "G17 G90 T1 D1\nG0 X40 Y30 Z0\nG41 G1 X40 Y0 F1000\nG1 X70 Y0\nG1 X70 Y48\nG1 X68 Y50\n\
                G1 X0 Y50\nG40 G1 X20 Y30\nM30";
    let (ch, samples) = run_to_stop("mill-3axis", "", prog);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert_eq!(warnings_of(&ch), vec![(10763, Some(6))]);
    // The chamfer's corner is skipped: the centre reaches the inner corner (65,45) of the walls.
    assert!(samples.iter().any(|p| (p[0] - 65.0).abs() < 1e-9 && (p[1] - 45.0).abs() < 1e-9));
}
