//! Block preparation's fast lane for plain motion lines gives exactly what the general path
//! gives: the same items (bit for bit) for random programs that mix plain lines with the
//! functions the lane refuses, and the hand-computed geometry of a circle through a frame
//! and a tool length. (In debug builds the lane also checks itself against the general path
//! block by block; these tests compare whole programs with the lane switched off.)

use nctwin_engine::Channel;
use nctwin_engine::interp::{Interpreter, Item, Prep, Programs};
use nctwin_engine::machine_data::MachineConfig;
use nctwin_engine::machine_data::registry::MAX_CHANNEL_AXES;

fn mill() -> MachineConfig {
    Channel::from_preset("mill-3axis", "").unwrap().config().clone()
}

/// Every item the interpreter prepares for `program`, with the lane on or off.
fn prepare(cfg: &MachineConfig, program: &str, lane: bool) -> Vec<Item> {
    let mut interp = Interpreter::new(cfg);
    interp.set_fast_lane(lane);
    interp.begin_program(program, &[0.0; MAX_CHANNEL_AXES]);
    let (mut items, mut out) = (Vec::new(), Vec::new());
    for _ in 0..10_000 {
        out.clear();
        let prep = interp.prepare_next(cfg, &Programs::new(), true, &mut out);
        items.append(&mut out);
        if prep == Prep::Done {
            return items;
        }
    }
    panic!("the program does not end");
}

fn moves(items: &[Item]) -> Vec<&nctwin_engine::motion::Move> {
    items
        .iter()
        .filter_map(|i| match i {
            Item::Move { mv, .. } => Some(mv),
            _ => None,
        })
        .collect()
}

/// T1 D1 (length 100 along Z under G17), TRANS X10 Y20, then a clockwise half circle from
/// the WCS origin round the centre I10 J0 to X20 Y0.
///
/// By hand: the machine position is WCS + (10, 20, 0) + (0, 0, 100). Start (10, 20, 100),
/// end (30, 20, 100), centre (20, 20), radius 10; the start lies at angle π from the centre
/// and G2 turns clockwise through the top point (20, 30, 100) to angle 0: sweep −π, length
/// 10π mm, F600 = 10 mm/s.
#[test]
fn a_g2_from_i_j_through_a_translation_and_the_tool_length_ends_where_worked_out_by_hand() {
    let cfg = mill();
    let program = "T1 D1\nTRANS X10 Y20\nG0 X0 Y0 Z0\nG2 X20 Y0 I10 J0 F600\nM30\n";
    let items = prepare(&cfg, program, true);
    assert_eq!(items, prepare(&cfg, program, false));
    let arc = *moves(&items).last().unwrap();
    assert_eq!(&arc.path.start[..3], &[10.0, 20.0, 100.0]);
    assert_eq!(&arc.path.end[..3], &[30.0, 20.0, 100.0]);
    let a = arc.path.arc.as_ref().expect("a circle");
    assert!((a.radius - 10.0).abs() < 1e-12);
    assert!((a.sweep + std::f64::consts::PI).abs() < 1e-12, "sweep {}", a.sweep);
    assert!((arc.length - 10.0 * std::f64::consts::PI).abs() < 1e-9);
    assert!((arc.feed - 10.0).abs() < 1e-12);
    let mut top = [0.0; MAX_CHANNEL_AXES];
    arc.path.at(0.5, &mut top);
    for (got, want) in top[..3].iter().zip([20.0, 30.0, 100.0]) {
        assert!((got - want).abs() < 1e-9, "{top:?}");
    }
}

/// Incremental G91 lines and a full circle from I/J alone (end = start) under a rotation.
/// By hand: ROT RPL=90 turns the WCS by 90° about Z, so WCS X+10 is machine Y+10, WCS Y+5 is
/// machine X−5. From the origin: G91 X10 → (0, 10), Y5 → (−5, 10); the full circle's centre
/// I5 (WCS +5 in X) lies at machine (−5, 15), radius 5.
#[test]
fn incremental_lines_and_a_full_circle_under_a_rotation_end_where_worked_out_by_hand() {
    let cfg = mill();
    let program = "ROT RPL=90\nG0 X0 Y0 Z0\nG91 G1 X10 F1000\nY5\nG3 I5\nM30\n";
    let items = prepare(&cfg, program, true);
    assert_eq!(items, prepare(&cfg, program, false));
    let m = moves(&items);
    let close = |p: &[f64], want: [f64; 2]| (p[0] - want[0]).abs() < 1e-9 && (p[1] - want[1]).abs() < 1e-9;
    assert!(close(&m[1].path.end, [0.0, 10.0]), "{:?}", &m[1].path.end[..3]);
    assert!(close(&m[2].path.end, [-5.0, 10.0]), "{:?}", &m[2].path.end[..3]);
    let circle = m[3];
    assert!(close(&circle.path.end, [-5.0, 10.0]));
    let a = circle.path.arc.as_ref().unwrap();
    assert!((a.sweep - std::f64::consts::TAU).abs() < 1e-12 && (a.radius - 5.0).abs() < 1e-12);
    let mut half = [0.0; MAX_CHANNEL_AXES];
    circle.path.at(0.5, &mut half);
    assert!(close(&half, [-5.0, 20.0]), "opposite the start across the centre: {:?}", &half[..3]);
}

/// Errors on plain lines come from the general path: the same alarm with the lane on.
#[test]
fn alarms_on_plain_lines_are_the_general_paths() {
    let cfg = mill();
    for program in ["G1 X10\n", "G1 X10 F0\n", "G2 X10 Y0 F100\n", "G2 X10 Y0 I1 F100\n", "G0 X600\n"] {
        let items = prepare(&cfg, program, true);
        assert!(matches!(items.last(), Some(Item::Alarm(_))), "{program}: {items:?}");
        assert_eq!(items, prepare(&cfg, program, false), "{program}");
    }
}

mod random_programs {
    use super::*;
    use proptest::prelude::*;

    /// One program line: plain motion lines (what the lane takes) and the functions around
    /// them that it refuses or that change what the plain lines mean.
    fn line() -> impl Strategy<Value = String> {
        let v = || (-400i32..400).prop_map(|x| f64::from(x) / 8.0);
        let plain = prop_oneof![
            (v(), v()).prop_map(|(x, y)| format!("G1 X{x} Y{y}")),
            (v(), v(), v()).prop_map(|(x, y, z)| format!("G0 X{x} Y{y} Z{z}")),
            (v(), 1u32..5000).prop_map(|(z, f)| format!("N{f} G01 Z{z} F{f}")),
            (v(), v()).prop_map(|(i, j)| format!("G3 I{i} J{j} ; full circle")),
            (v(), v()).prop_map(|(i, k)| format!("g2 i{i} k{k}")),
            // Incremental half circles: the end point lies on the circle in every plane.
            (v(), v()).prop_map(|(i, j)| format!("G91 G2 X{} Y{} I{i} J{j}", 2.0 * i, 2.0 * j)),
            (v(), v()).prop_map(|(i, k)| format!("G91 G3 X{} Z{} I{i} K{k}", 2.0 * i, 2.0 * k)),
            (v(), v()).prop_map(|(y, z)| format!("G91 G1 Y{y} Z{z}")),
            v().prop_map(|x| format!("G90 G0 X{x}")),
            (1u32..3000).prop_map(|f| format!("F{f}")),
        ];
        // Without a G function: a line (or, after a circle, a circle that fails with 14040).
        let bare = v().prop_map(|x| format!("X{x}"));
        let other = prop_oneof![
            Just("G17".to_string()),
            Just("G18".to_string()),
            Just("G19".to_string()),
            Just("G91".to_string()),
            Just("G90".to_string()),
            Just("G1".to_string()),
            Just("G70".to_string()),
            Just("G71".to_string()),
            Just("G64".to_string()),
            Just("G60".to_string()),
            Just("G54".to_string()),
            Just("G500".to_string()),
            Just("T1 D1".to_string()),
            Just("T2".to_string()),
            Just("D0".to_string()),
            Just("G40 G1 X0 Y0".to_string()),
            Just("M3 S1000".to_string()),
            Just("".to_string()),
            Just("; comment".to_string()),
            (v(), v()).prop_map(|(x, y)| format!("TRANS X{x} Y{y}")),
            (v(), v()).prop_map(|(x, y)| format!("ATRANS X{x} Y{y}")),
            (-180i32..180).prop_map(|a| format!("ROT RPL={a}")),
            (-180i32..180).prop_map(|a| format!("AROT Z{a}")),
            (v(), v()).prop_map(|(x, y)| format!("G41 G1 X{x} Y{y}")),
            (v(), v()).prop_map(|(x, y)| format!("G1 X{x} Y{y} RND=2")),
            (1i32..80).prop_map(|d| format!("G91 G2 X{d} CR=40")),
            (v(), 1u32..100).prop_map(|(x, r)| format!("R1={r} X=R1+{x}")),
            v().prop_map(|x| format!("X{x} G9")),
        ];
        // Random end points rarely lie on the circle (alarm 14040 ends the program): seldom.
        let arc = (v(), v(), v(), v()).prop_map(|(x, y, i, j)| format!("G2 X{x} Y{y} I{i} J{j}"));
        prop_oneof![72 => plain, 2 => bare, 1 => arc, 25 => other]
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 96, .. ProptestConfig::default() })]

        #[test]
        fn the_lane_prepares_what_the_general_path_prepares(lines in prop::collection::vec(line(), 1..40)) {
            let cfg = mill();
            let program = format!("G0 X0 Y0 Z0 F500\n{}\nM30\n", lines.join("\n"));
            prop_assert_eq!(prepare(&cfg, &program, true), prepare(&cfg, &program, false), "{}", program);
        }
    }
}
