//! Tool radius compensation never gouges (issue 25, item 6): an element shorter than the tool
//! needs between two corners is skipped, a slot narrower than the tool stops with alarm 10751
//! before the tool enters it (CDOF) or is bridged (CDON), and every corner is resolved before
//! any of its motion is released. Each test checks every IPO sample of the tool centre against
//! the programmed contour (distance of a point from segments, written here): none may come
//! closer than the radius 5 of the mill's T1 D1.
//!
//! Decisions (Function Manual W1, "Collision detection and bottleneck detection"; Programming
//! Manual, "Collision monitoring CDON, CDOF"): with CDOF (the reset value) the search for the
//! intersection at an inside corner goes back over earlier blocks (up to MD20240
//! $MC_CUTCOM_MAXNUM_CHECK_BLOCKS), so a too short element between two inside corners is
//! omitted; the transition circle inserted at an outer corner counts as such a block. Only
//! CDON also joins non-consecutive equidistants across an outer corner (the circle about it),
//! which bridges a slot narrower than the tool; under CDOF that slot is alarm 10751. The
//! omitted blocks' other motions and functions (M0 here) run at the intersection. Warning
//! 10763 (block omitted) is not shown.

use crate::trc_support;

use nctwin_engine::Status;
use trc_support::{alarm_of, first_gouge, go_on, run_all, run_all_on, run_to_stop};

/// The chamfer program of the issue: pocket wall X70 up to Y(50 − c), a chamfer of legs c to
/// (70 − c, 50), then the wall Y50 to the left (G41: the tool is inside). The equidistants
/// x = 65 of the wall and y = 45 of the top meet at (65,45). The chamfer's equidistant
/// x + y = 120 − c − 5√2 meets them at (65, 55 − c − 5√2) and (75 − c − 5√2, 45): while
/// 75 − c − 5√2 > 65 (c < 2.93) it would run backwards (the 1.5–2.9 mm chamfers of the
/// issue gouged): the chamfer is omitted and the M0 after it
/// runs at (65,45). A 3.5 mm chamfer stays: the M0 finds the tool at (75 − 3.5 − 5√2, 45).
#[test]
fn a_short_chamfer_between_two_inside_corners_is_skipped() {
    for chamfer in [1.0, 1.5, 2.0, 2.9, 3.5] {
        let (y, x) = (50.0 - chamfer, 70.0 - chamfer);
        let prog = format!(
            "G17 G90 T1 D1\nG0 X40 Y30 Z0\nG41 G1 X40 Y0 F1000\nG1 X70 Y0\nG1 X70 Y{y}\nG1 X{x} Y50\nM0\nG1 X0 Y50\nG40 G1 X20 Y30\nM30"
        );
        let contour = [(40.0, 0.0), (70.0, 0.0), (70.0, y), (x, 50.0), (0.0, 50.0)];
        let (mut ch, mut samples) = run_to_stop("mill-3axis", "", &prog);
        assert_eq!(ch.status(), Status::Stopped, "chamfer {chamfer}: {:?}", ch.alarms());
        let at = ch.axis_positions().to_vec();
        let x_end = (75.0 - chamfer - 5.0 * 2f64.sqrt()).min(65.0);
        assert!((at[0] - x_end).abs() < 1e-9 && (at[1] - 45.0).abs() < 1e-9, "chamfer {chamfer}: {at:?}");
        ch.start().unwrap();
        samples.extend(go_on(&mut ch));
        assert_eq!(ch.status(), Status::Idle, "chamfer {chamfer}: {:?}", ch.alarms());
        assert_eq!(first_gouge(&samples, &contour, 5.0), None, "chamfer {chamfer}");
    }
}

fn slot(select: &str) -> String {
    format!(
        "G17 G90 T1 D1 {select}\nG0 X-10 Y75 Z0\nG41 G1 X0 Y60 F1000\nG1 X47 Y60\nG1 X47 Y50\nG1 X53 Y50\nM0\nG1 X53 Y60\nG1 X100 Y60\nG40 G1 X110 Y75\nM30"
    )
}

const SLOT: [(f64, f64); 6] = [(0.0, 60.0), (47.0, 60.0), (47.0, 50.0), (53.0, 50.0), (53.0, 60.0), (100.0, 60.0)];

/// A 6 mm slot and a tool of 10 mm diameter, CDOF (the reset value): the walls' equidistants
/// x = 52 and x = 48 cross, the bottom's would run backwards; no inner-corner intersection
/// within MD20240 blocks, so alarm 10751 — and the tool has not entered the slot.
#[test]
fn a_slot_narrower_than_the_tool_is_alarm_10751_before_the_tool_enters_it() {
    let (ch, samples) = run_to_stop("mill-3axis", "", &slot(""));
    assert_eq!(alarm_of(&ch), Some(10751), "{:?}", ch.alarms());
    assert_eq!(first_gouge(&samples, &SLOT, 5.0), None);
    let low = samples.iter().filter(|p| p[0] > 0.0).map(|p| p[1]).fold(f64::MAX, f64::min);
    assert!(low > 65.0 - 1e-9, "never below Y65 right of X0: {low}");
}

/// The same slot with CDON: the equidistant y = 65 of the line before the slot meets the
/// circle of radius 5 about the slot's far upper corner (53,60) at its top, (53,65) (the line
/// touches it): the walls and the bottom are omitted and the tool stays on y = 65; the M0
/// between them runs at the join. The join lies four blocks ahead (three omitted), so MD20240
/// must allow that look-ahead; with the default 3 it is alarm 10751 as under CDOF.
#[test]
fn cdon_bridges_the_slot_within_md20240_blocks() {
    let (ch, samples) = run_all_on("mill-3axis", "$MC_CUTCOM_MAXNUM_CHECK_BLOCKS=5", &slot("CDON"));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    assert_eq!(first_gouge(&samples, &SLOT, 5.0), None);
    let low = samples.iter().filter(|p| p[0] > 40.0 && p[0] < 60.0).map(|p| p[1]).fold(f64::MAX, f64::min);
    assert!((low - 65.0).abs() < 1e-6, "lowest centre in the slot {low}");
    assert_eq!(&ch.axis_positions()[..2], &[110.0, 75.0]);
    let (ch, samples) = run_to_stop("mill-3axis", "", &slot("CDON"));
    assert_eq!(alarm_of(&ch), Some(10751), "{:?}", ch.alarms());
    assert_eq!(first_gouge(&samples, &SLOT, 5.0), None);
}

/// A 2 mm step down (shorter than the radius) after an outer corner: line y = 60 to X50,
/// down to Y58, on to X100. The step's equidistant x = 55 would have to run up from (55,60)
/// to (55,63) to meet y = 63; instead the transition circle about (50,60) is cut by y = 63 at
/// (50 + √(25 − 9), 63) = (54,63). Nothing is released before that is known: no sample below
/// the Y58 face's equidistant, no alarm.
#[test]
fn a_step_shorter_than_the_radius_is_resolved_before_its_corner_moves() {
    let prog =
        "G17 G90 T1 D1\nG0 X-10 Y75 Z0\nG41 G1 X0 Y60 F1000\nG1 X50 Y60\nG1 X50 Y58\nG1 X100 Y58\nG40 G1 X110 Y75\nM30";
    let (ch, samples) = run_all(prog);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let contour = [(0.0, 60.0), (50.0, 60.0), (50.0, 58.0), (100.0, 58.0)];
    assert_eq!(first_gouge(&samples, &contour, 5.0), None);
    assert!(
        samples.iter().any(|p| (p[0] - 54.0).abs() < 1e-6 && (p[1] - 63.0).abs() < 1e-6),
        "leaves the circle at (54,63)"
    );
}

/// RND between a line and an arc (issue 25, item 6): G42, line (0,0)→(30,0) with RND=3, then
/// G2 to (50,0) about (40,0) (radius 10, over the top). The rounding circle (radius 3) touches
/// y = 0 from above and the arc's circle from outside: centre (40 − √(13² − 3²), 3) =
/// (27.351, 3). The tool (right of the path: below the line, inside the clockwise arc) runs on
/// y = −5 to x = 27.351, round the rounding's equidistant (radius 3 + 5 = 8 about its centre)
/// and on along the arc's equidistant (radius 10 − 5 = 5 about (40,0)); every sample keeps 5
/// from the rounded contour.
#[test]
fn rnd_between_a_line_and_an_arc_is_compensated_on_the_rounded_contour() {
    let prog =
        "G17 G90 T1 D1\nG0 X-20 Y-20 Z0\nG42 G1 X0 Y0 F1000\nG1 X30 Y0 RND=3\nG2 X50 Y0 I10 J0\nG40 G1 X60 Y-20\nM30";
    let (ch, samples) = run_all(prog);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let c = (40.0 - 160f64.sqrt(), 3.0);
    // Distance from the rounded contour: the line up to c.x, the rounding arc (from straight
    // below its centre to the tangent point towards (40,0)), the arc from there over the top.
    let t = (40.0 + 10.0 * (c.0 - 40.0) / 13.0, 10.0 * 3.0 / 13.0);
    let on_round = |p: (f64, f64)| {
        // Angles of the rounding arc run from −90° to the direction of t, counter-clockwise.
        let a = (p.1 - c.1).atan2(p.0 - c.0);
        let (a0, a1) = (-std::f64::consts::FRAC_PI_2, (t.1 - c.1).atan2(t.0 - c.0));
        if a >= a0 && a <= a1 { ((p.0 - c.0).hypot(p.1 - c.1) - 3.0).abs() } else { f64::INFINITY }
    };
    let on_arc = |p: (f64, f64)| {
        let a = p.1.atan2(p.0 - 40.0);
        let at = t.1.atan2(t.0 - 40.0);
        if (0.0..=at).contains(&a) { ((p.0 - 40.0).hypot(p.1) - 10.0).abs() } else { f64::INFINITY }
    };
    let ends = |p: (f64, f64)| (p.0 - t.0).hypot(p.1 - t.1).min((p.0 - 50.0).hypot(p.1));
    let dist =
        |p: (f64, f64)| trc_support::seg_dist(p, (0.0, 0.0), (c.0, 0.0)).min(on_round(p)).min(on_arc(p)).min(ends(p));
    // Up to the end of the arc's equidistant (45,0): the G40 block then travels uncompensated
    // to its end point and may pass the contour's end closer than the radius.
    let run = trc_support::after_reaching(&samples, -20.0, -20.0);
    let end = run.iter().rposition(|p| (p[0] - 45.0).abs() < 1e-9 && p[1].abs() < 1e-9).expect("arc end");
    for s in &run[..=end] {
        assert!(dist((s[0], s[1])) > 5.0 - 1e-6, "{s:?} closer than the radius to the rounded contour");
    }
    // On y = −5 up to below the rounding's centre.
    for p in run[..=end].iter().filter(|p| p[0] > 1e-3 && p[0] < c.0 - 1e-3 && p[1] < 0.0) {
        assert!((p[1] + 5.0).abs() < 1e-6, "{p:?}");
    }
    let round: Vec<_> = samples.iter().filter(|p| p[0] > c.0 + 1e-3 && p[1] < -1e-3 && p[0] < 35.0).collect();
    assert!(!round.is_empty());
    for p in round {
        let r = (p[0] - c.0).hypot(p[1] - c.1);
        let r_arc = (p[0] - 40.0).hypot(p[1]);
        assert!(
            (r - 8.0).abs() < 1e-6 || (r_arc - 5.0).abs() < 1e-6,
            "{p:?}: on the rounding's or the arc's equidistant"
        );
    }
}
