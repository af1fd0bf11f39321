//! The generic 7-axis transformation of `mill7-generic`: the 6-axis head C/B/A of
//! `mill6-generic` plus the rotary table C1 about +Z through the BCS zero point, which turns
//! the workpiece. Programmed tip and orientation are relative to the workpiece.
//!
//! Closed forms written out here (not taken from the engine):
//! * head orientation in the machine frame `o_m = (cos C·sin B, sin C·sin B, cos B)`;
//! * machine axes of a tip `P_m` in the machine frame: `M = P_m − (0, 0, 200) + 300·o_m`
//!   (pivots 200 mm and 120 mm above the spindle nose, 100 mm tool; see traori_six_axis.rs);
//! * a workpiece point `p` lies at `P_m = Rz(C1)·p`, a workpiece orientation `o` is
//!   `o_m = Rz(C1)·o`; backwards `p = Rz(−C1)·P_m`.

use nctwin_engine::kinematics::{self, ActiveTrafo, SelectArgs};
use nctwin_engine::machine_data::{MachineData, presets};
use nctwin_engine::{Channel, Snapshot, Status};
use proptest::prelude::*;

use crate::settle;

fn run_on(md: &str, program: &str) -> (Channel, Vec<Snapshot>) {
    settle::run_snapshots("mill7-generic", md, program)
}

fn run(program: &str) -> (Channel, Vec<Snapshot>) {
    run_on("", program)
}

use settle::machine_axis as machine;

fn rz(deg: f64, v: [f64; 3]) -> [f64; 3] {
    let (s, c) = deg.to_radians().sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}

fn head(b: f64, c: f64) -> [f64; 3] {
    let (sb, cb) = b.to_radians().sin_cos();
    let (sc, cc) = c.to_radians().sin_cos();
    [cc * sb, sc * sb, cb]
}

/// Tool tip and orientation relative to the workpiece from the machine axes (closed forms).
fn workpiece_pose(s: &Snapshot) -> ([f64; 3], [f64; 3]) {
    let o_m = head(machine(s, "B"), machine(s, "C"));
    let m = ["X", "Y", "Z"].map(|n| machine(s, n));
    let p_m = [m[0] - 300.0 * o_m[0], m[1] - 300.0 * o_m[1], m[2] + 200.0 - 300.0 * o_m[2]];
    let c2 = machine(s, "C1");
    (rz(-c2, p_m), rz(-c2, o_m))
}

fn near(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < tol)
}

const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
const START: &str = "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000\n";

#[test]
fn the_tip_stays_on_the_workpiece_point_while_the_table_turns() {
    // Tool 45° towards +X of the workpiece at workpiece point (100, 0, 50); the table then
    // turns 90°: under ORIWKS (vector interpolation) tip and orientation stay fixed relative to
    // the workpiece at every IPO point, so the head's C follows the table to 90.
    let (ch, samples) = run(&format!("{START}ORIWKS\nX100 Y0 Z50 A3=1 B3=0 C3=1\nC1=90\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let turning: Vec<&Snapshot> = samples.iter().filter(|s| machine(s, "C1") > 1e-6).collect();
    assert!(turning.len() > 10, "the table turned in {} cycles", turning.len());
    for s in &turning {
        let (p, o) = workpiece_pose(s);
        assert!(near(p, [100.0, 0.0, 50.0], 1e-6), "tip {p:?} at C1 = {}", machine(s, "C1"));
        assert!(near(o, [H, 0.0, H], 1e-9), "orientation {o:?} at C1 = {}", machine(s, "C1"));
    }
    // End: C1 = 90 puts the workpiece point at machine-frame (0, 100, 50) and the orientation at
    // (0, 1, 1)/√2: B = 45, C = 90; M = (0, 100, 50) − (0, 0, 200) + 300·(0, H, H).
    let end = ch.snapshot();
    assert!((machine(&end, "B") - 45.0).abs() < 1e-6 && (machine(&end, "C") - 90.0).abs() < 1e-6, "{:?}", end.machine);
    let want = [0.0, 100.0 + 300.0 * H, 50.0 - 200.0 + 300.0 * H];
    assert!(near(["X", "Y", "Z"].map(|n| machine(&end, n)), want, 1e-6), "{:?}", end.machine);
    let c1 = end.workpiece.iter().find(|(n, _)| n == "C1").expect("C1 in the WCS display").1;
    assert!((c1 - 90.0).abs() < 1e-9, "{:?}", end.workpiece);
    let o = end.orientation.expect("orientation in the WCS");
    assert!(near(o, [H, 0.0, H], 1e-9), "displayed orientation {o:?}");
}

#[test]
fn under_orimks_the_table_leaves_the_tool_axes_alone() {
    // ORIMKS (the reset setting; axis interpolation without MD21104): C1 turns, B/C keep 45/0, so the orientation
    // relative to the workpiece turns by −90° about Z; the tip is still held on the workpiece.
    let (ch, samples) = run(&format!("{START}X100 Y0 Z50 A3=1 B3=0 C3=1\nORIMKS\nC1=90\nM30"));
    assert_eq!(ch.snapshot().status, Status::Idle, "{:?}", ch.snapshot().alarms);
    for s in samples.iter().filter(|s| machine(s, "C1") > 1e-6) {
        assert!((machine(s, "B") - 45.0).abs() < 1e-9 && machine(s, "C").abs() < 1e-9, "{:?}", s.machine);
        let (p, _) = workpiece_pose(s);
        assert!(near(p, [100.0, 0.0, 50.0], 1e-6), "tip {p:?}");
    }
    let (_, o) = workpiece_pose(&ch.snapshot());
    assert!(near(o, rz(-90.0, [H, 0.0, H]), 1e-9), "{o:?}");
}

#[test]
fn orimks_with_oriaxes_under_md21104_leaves_the_tool_axes_alone() {
    // F2 §3.7.6: with MD21104 = 1 the G groups 25 and 51 must be ORIMKS and ORIAXES.
    let (ch, samples) = run_on(
        "$MC_ORI_IPO_WITH_G_CODE=1\n",
        &format!("{START}X100 Y0 Z50 A3=1 B3=0 C3=1\nORIMKS ORIAXES\nC1=90\nM30"),
    );
    assert_eq!(ch.snapshot().status, Status::Idle, "{:?}", ch.snapshot().alarms);
    for s in samples.iter().filter(|s| machine(s, "C1") > 1e-6) {
        assert!((machine(s, "B") - 45.0).abs() < 1e-9 && machine(s, "C").abs() < 1e-9, "{:?}", s.machine);
    }
}

#[test]
fn four_quarter_circles_against_the_table_keep_the_machine_still() {
    // In the spirit of the manual's 7-axis example (p.246: "while traversing the quadrant only
    // the 7th axis turns by 360 degrees, the machine remains in the fixed position"): the tip
    // runs clockwise round the table axis on the workpiece while C1 turns counter-clockwise by
    // the same angle, so Rz(C1)·p stays at (100, 0, 50) and X, Y, Z, B, C do not move.
    let program = format!(
        "{START}X100 Y0 Z50 A3=0 B3=0 C3=1\n\
         G2 X0 Y-100 I-100 J0 C1=IC(90)\nG2 X-100 Y0 I0 J100 C1=IC(90)\n\
         G2 X0 Y100 I100 J0 C1=IC(90)\nG2 X100 Y0 I0 J-100 C1=IC(90)\nM30"
    );
    let (ch, samples) = run(&program);
    assert_eq!(ch.snapshot().status, Status::Idle, "{:?}", ch.snapshot().alarms);
    let first = samples.iter().position(|s| machine(s, "C1") > 1e-6).expect("the table turns");
    let fixed = ["X", "Y", "Z"].map(|n| machine(&samples[first - 1], n));
    assert!(near(fixed, [100.0, 0.0, 50.0 - 200.0 + 300.0], 1e-6), "{fixed:?}");
    for s in &samples[first..] {
        let m = ["X", "Y", "Z"].map(|n| machine(s, n));
        assert!(near(m, fixed, 1e-6), "machine moved to {m:?} at C1 = {}", machine(s, "C1"));
    }
    let turned: f64 = samples
        .windows(2)
        .map(|w| {
            let d = machine(&w[1], "C1") - machine(&w[0], "C1");
            (d + 180.0).rem_euclid(360.0) - 180.0
        })
        .sum();
    assert!((turned - 360.0).abs() < 1e-6, "C1 turned {turned}");
}

fn trafo(tool: [f64; 3]) -> ActiveTrafo {
    let mut data = MachineData::default();
    let cfg = data.apply_text(presets::find("mill7-generic").unwrap().text).unwrap();
    let trafo = kinematics::build(&cfg.trafos[0], &cfg, &SelectArgs::default()).unwrap();
    ActiveTrafo { trafo, tool, number: 1 }
}

/// Channel slots of mill7-generic: X, Y, Z, A, B, C, C1.
const SLOTS: [&str; 7] = ["X", "Y", "Z", "A", "B", "C", "C1"];

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, .. ProptestConfig::default() })]

    /// Forward against the closed forms, inverse and inverse_oriented back to the same machine
    /// axes (tolerances: 1e-9 mm and 1e-9° on poses within the working area).
    #[test]
    fn random_poses_round_trip(
        x in -300.0..300.0f64, y in -300.0..300.0f64, z in -200.0..200.0f64,
        a in -180.0..180.0f64, b in -90.0..90.0f64, c in 0.0..360.0f64, c2 in 0.0..360.0f64,
    ) {
        prop_assume!(b.abs() > 1.0);
        let t = trafo([0.0, 0.0, 100.0]);
        let mut m = [0.0; 20];
        m[..7].copy_from_slice(&[x, y, z, a, b, c, c2]);
        let bcs = t.forward(&m);
        // Closed form: P_m = M + (0, 0, 200) − 300·o_m, p = Rz(−C1)·P_m.
        let o_m = head(b, c);
        let p = rz(-c2, [x - 300.0 * o_m[0], y - 300.0 * o_m[1], z + 200.0 - 300.0 * o_m[2]]);
        prop_assert!(near([bcs[0], bcs[1], bcs[2]], p, 1e-9), "forward {:?} vs {p:?}", &bcs[..7]);
        prop_assert!((bcs[6] - c2).abs() < 1e-12 && (bcs[3] - a).abs() < 1e-12);
        let back = t.inverse(&bcs, &m).unwrap();
        for (k, name) in SLOTS.iter().enumerate() {
            prop_assert!((back[k] - m[k]).abs() < 1e-9, "inverse {name}: {} vs {}", back[k], m[k]);
        }
        let o = rz(-c2, o_m);
        let again = t.inverse_oriented(&bcs, &o, &m).unwrap();
        for (k, name) in SLOTS.iter().enumerate() {
            prop_assert!((again[k] - m[k]).abs() < 1e-7, "inverse_oriented {name}: {} vs {}", again[k], m[k]);
        }
    }
}

#[test]
fn a_seventh_axis_needs_the_generic_tool_type_and_a_direction() {
    let base = presets::find("mill7-generic").unwrap().text;
    let err = MachineData::default().apply_text(&format!("{base}$MC_TRAFO7_EXT_AXIS1_1[2]=0.\n")).unwrap_err();
    assert!(err.to_string().contains("4342") && err.to_string().contains("TRAFO7_EXT_AXIS1_1"), "{err}");
    let err = MachineData::default()
        .apply_text(&format!("{base}$MC_TRAFO_TYPE_1=40\n$MC_TRAFO_AXES_IN_1[5]=0\n"))
        .unwrap_err();
    assert!(err.to_string().contains("TRAFO_AXES_IN[6]"), "{err}");
}

#[test]
fn a_table_move_under_a_cone_interpolation_also_holds_the_orientation() {
    // MD21104 = 1, ORICONCW modal, ORIWKS: a block moving only C1 needs no cone axis; the
    // orientation stays (1, 0, 1)/√2 on the workpiece.
    let (ch, samples) = run_on(
        "$MC_ORI_IPO_WITH_G_CODE=1\n",
        &format!("{START}ORIWKS\nX100 Y0 Z50 A3=1 B3=0 C3=1\nORICONCW\nC1=45\nM0\nM30"),
    );
    assert_eq!(ch.snapshot().status, Status::Stopped, "{:?}", ch.snapshot().alarms);
    let turning: Vec<&Snapshot> = samples.iter().filter(|s| machine(s, "C1") > 1e-6).collect();
    assert!(turning.len() > 10);
    for s in turning {
        let (p, o) = workpiece_pose(s);
        assert!(near(p, [100.0, 0.0, 50.0], 1e-6) && near(o, [H, 0.0, H], 1e-9), "{p:?} {o:?}");
    }
}

#[test]
fn ptp_stat_picks_among_the_solutions_of_the_turned_workpiece() {
    // With C1 = 90 the workpiece orientation (1, 0, 1)/√2 is (0, 1, 1)/√2 in the machine frame:
    // C90 B45 or C−90 (= 270) B−45; STAT bit 0 picks the lower (0) or higher (1) position of
    // the first axis C within ±180°. Either way the tip lands on workpiece point (100, 0, 50)
    // with that orientation. (Without the 7th axis in the choice, the solutions would be those
    // of (1, 0, 1)/√2 in the machine frame: C0 B45 / C180 B−45.)
    for (stat, b, c) in [(0, -45.0, 270.0), (1, 45.0, 90.0)] {
        let (ch, _) = run(&format!("{START}C1=90\nPTP\nG0 X100 Y0 Z50 A3=1 B3=0 C3=1 STAT={stat}\nM0\nM30"));
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
        let dc = (machine(&s, "C") - c + 180.0).rem_euclid(360.0) - 180.0;
        assert!((machine(&s, "B") - b).abs() < 1e-6 && dc.abs() < 1e-6, "STAT={stat}: {:?}", s.machine);
        let (p, o) = workpiece_pose(&s);
        assert!(near(p, [100.0, 0.0, 50.0], 1e-6) && near(o, [H, 0.0, H], 1e-9), "STAT={stat}: {p:?} {o:?}");
    }
}

#[test]
fn the_pole_is_found_in_the_frame_of_the_head_when_the_table_is_turned() {
    // Table axis along +X (TRAFO7_EXT_AXIS1 = X) at C1 = 90: the workpiece direction +Y is the
    // machine's +Z, the pole of the head's C. With POLE_ORI_MODE = 1 a great circle that starts
    // in the pole runs as rotary-axis interpolation, so B and C move in proportion. The end
    // (0.25, 0.866, −0.433) on the workpiece is Rx(90)·that = (0.25, 0.433, 0.866) =
    // (cos 60·sin 30, sin 60·sin 30, cos 30) for the head: B30 C60 (the nearer solution).
    let md = "$MC_TRAFO7_EXT_AXIS1_1[0]=1.\n$MC_TRAFO7_EXT_AXIS1_1[2]=0.\n$MC_POLE_ORI_MODE=1\n";
    let o = [0.25, 0.75f64.sqrt(), -0.75f64.sqrt() / 2.0];
    let program = format!("{START}C1=90\nORIWKS\nA3={} B3={} C3={}\nM0\nM30", o[0], o[1], o[2]);
    let (ch, samples) = run_on(md, &program);
    let end = ch.snapshot();
    assert_eq!(end.status, Status::Stopped, "{:?}", end.alarms);
    assert!((machine(&end, "B") - 30.0).abs() < 1e-6 && (machine(&end, "C") - 60.0).abs() < 1e-6, "{:?}", end.machine);
    let block: Vec<&Snapshot> = samples.iter().filter(|s| s.block.as_ref().is_some_and(|b| b.line == 7)).collect();
    assert!(block.len() > 10);
    for s in block {
        let (b, c) = (machine(s, "B"), machine(s, "C"));
        assert!((c - 2.0 * b).abs() < 1e-6, "B {b} and C {c} do not move in proportion");
    }
}
