//! The generic 6-axis transformation of `mill6-generic` run through a whole channel: THETA and
//! the rotation references ORIROTA/ORIROTR/ORIROTT/ORIROTC.
//!
//! Closed forms of the head (written out here, not taken from the engine): C about Z carries B
//! about Y carries A about the tool axis; the tool normal in the zero position is +X.
//! * orientation `o = Rz(C)·Ry(B)·Rz(A)·ez = (cos C·sin B, sin C·sin B, cos B)`;
//! * the plane perpendicular to `o` has the right-handed basis `e1 = Rz(C)·Ry(B)·ex =
//!   (cos C·cos B, sin C·cos B, −sin B)`, `e2 = Rz(C)·ey = (−sin C, cos C, 0)` (e1 × e2 = o), and
//!   the rotation vector is `r = cos A·e1 + sin A·e2`; so a wanted `r` gives
//!   `A = atan2(r·e2, r·e1)`, and THETA measured from a reference direction adds to that angle;
//! * the tool tip: pivots 200 mm (B) and 120 mm (A bearing) above the spindle nose, 100 mm tool,
//!   so `M = P − (0, 0, 200) + 300·o`.

use nctwin_engine::{Channel, Snapshot, Status};

const MAX_TICKS: usize = 1_000_000;

fn run(program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset("mill6-generic", "").unwrap();
    ch.run_program(program).unwrap();
    let mut samples = Vec::new();
    while ch.is_busy() {
        ch.step();
        samples.push(ch.axis_positions().to_vec());
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    (ch, samples)
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn orientation(b: f64, c: f64) -> [f64; 3] {
    let (sb, cb) = b.to_radians().sin_cos();
    let (sc, cc) = c.to_radians().sin_cos();
    [cc * sb, sc * sb, cb]
}

/// A of the rotation vector `r` at head angles B, C (see the module comment).
fn a_for(r: [f64; 3], b: f64, c: f64) -> f64 {
    let (sb, cb) = b.to_radians().sin_cos();
    let (sc, cc) = c.to_radians().sin_cos();
    let e1 = [cc * cb, sc * cb, -sb];
    let e2 = [-sc, cc, 0.0];
    let d = |u: [f64; 3]| u[0] * r[0] + u[1] * r[1] + u[2] * r[2];
    d(e2).atan2(d(e1)).to_degrees()
}

fn angle_diff(a: f64, b: f64) -> f64 {
    (a - b + 180.0).rem_euclid(360.0) - 180.0
}

/// Checks the rotary axes and that the tool tip is at `p`.
fn assert_pose(s: &Snapshot, p: [f64; 3], abc: [f64; 3]) {
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    for (name, v) in ["A", "B", "C"].iter().zip(abc) {
        let got = machine(s, name);
        assert!(angle_diff(got, v).abs() < 1e-6, "{name}: {got} vs {v} ({:?})", s.machine);
    }
    let o = orientation(abc[1], abc[2]);
    let m = [p[0] + 300.0 * o[0], p[1] + 300.0 * o[1], p[2] - 200.0 + 300.0 * o[2]];
    for (name, v) in ["X", "Y", "Z"].iter().zip(m) {
        let got = machine(s, name);
        assert!((got - v).abs() < 1e-6, "{name}: {got} vs {v} ({:?})", s.machine);
    }
}

const START: &str = "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000\n";

#[test]
fn theta_in_the_zero_orientation_turns_only_the_tool_axis() {
    // o = Z is the pole of C (C stays at 0); the reference X turned by 90° about Z is Y, which
    // the A axis reaches at A = 90.
    let (ch, _) = run(&format!("{START}A3=0 B3=0 C3=1 THETA=90\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert_pose(&s, [0.0, 0.0, 50.0], [90.0, 0.0, 0.0]);
}

#[test]
fn orirota_measures_theta_from_the_basic_normal_projected_onto_the_tool_plane() {
    // o of C = 60, B = 30. The reference +X projected perpendicular to o gives
    // A = atan2(X·e2, X·e1) = atan2(−sin C, cos C·cos B) = −63.4349°; THETA = 30 adds 30.
    let o = orientation(30.0, 60.0);
    let a0 = (-(60f64.to_radians().sin())).atan2(60f64.to_radians().cos() * 30f64.to_radians().cos()).to_degrees();
    assert!((a0 - -63.434_948_822_922).abs() < 1e-9);
    let prog = format!("{START}ORIROTA\nX10 A3={} B3={} C3={} THETA=30\nM0\nM30", o[0], o[1], o[2]);
    let (ch, _) = run(&prog);
    assert_pose(&ch.snapshot(), [10.0, 0.0, 50.0], [a0 + 30.0, 30.0, 60.0]);
    // The same rotation vector checked the long way: r = R(o, 30°)·normalize(X − (X·o)·o).
    let x_perp = {
        let v = [1.0 - o[0] * o[0], -o[0] * o[1], -o[0] * o[2]];
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|c| c / n)
    };
    let oxr =
        [o[1] * x_perp[2] - o[2] * x_perp[1], o[2] * x_perp[0] - o[0] * x_perp[2], o[0] * x_perp[1] - o[1] * x_perp[0]];
    let (s30, c30) = 30f64.to_radians().sin_cos();
    let r: [f64; 3] = std::array::from_fn(|i| c30 * x_perp[i] + s30 * oxr[i]);
    assert!((a_for(r, 30.0, 60.0) - (a0 + 30.0)).abs() < 1e-9);
}

#[test]
fn incremental_theta_adds_to_the_rotation_in_force() {
    let (ch, _) = run(&format!("{START}THETA=30\nTHETA=IC(20)\nM0\nM30"));
    assert_pose(&ch.snapshot(), [0.0, 0.0, 50.0], [50.0, 0.0, 0.0]);
}

#[test]
fn orirotr_and_orirott_refer_to_the_plane_of_the_orientation_change() {
    // From Z to (1, 0, 1)/√2 (B = 45, C = 0): the plane normal Z × o is +Y, so ORIROTR with
    // THETA = 0 wants r = Y = sin A·e2 ⇒ A = 90. ORIROTT measures from the direction of the
    // change at the end, Y × o = (1, 0, −1)/√2 = e1 ⇒ A = 0; THETA = 10 then gives A = 10.
    let (ch, _) = run(&format!("{START}ORIROTR\nA3=1 B3=0 C3=1 THETA=0\nM0\nM30"));
    assert_pose(&ch.snapshot(), [0.0, 0.0, 50.0], [90.0, 45.0, 0.0]);
    let (ch, _) = run(&format!("{START}THETA=70\nORIROTT\nA3=1 B3=0 C3=1 THETA=10\nM0\nM30"));
    assert_pose(&ch.snapshot(), [0.0, 0.0, 50.0], [10.0, 45.0, 0.0]);
}

#[test]
fn orirotc_turns_the_tool_with_the_path_tangent() {
    // In the zero orientation the reference is the path tangent itself: along +X A = THETA,
    // along +Y A = 90 + THETA (C stays in its pole position).
    let (ch, _) = run(&format!("{START}ORIROTC THETA=5\nX100\nY100\nM0\nM30"));
    let s = ch.snapshot();
    assert_pose(&s, [100.0, 100.0, 50.0], [95.0, 0.0, 0.0]);
    let mut first = Channel::from_preset("mill6-generic", "").unwrap();
    first.run_program(&format!("{START}ORIROTC THETA=5\nX100\nM0\nM30")).unwrap();
    while first.is_busy() {
        first.step();
    }
    assert_pose(&first.snapshot(), [100.0, 0.0, 50.0], [5.0, 0.0, 0.0]);
}

#[test]
fn a_direct_tool_axis_position_under_orirotc_is_alarm_14128() {
    let (ch, _) = run(&format!("{START}ORIROTC\nN70 X10 A20\nM30"));
    let s = ch.snapshot();
    assert!(s.alarms.iter().any(|a| a.number == 14128 && a.line == Some(6)), "{:?}", s.alarms);
}

#[test]
fn theta_without_a_third_rotary_axis_is_refused_at_its_block() {
    let mut ch = Channel::from_preset("mill5-head-ca", "").unwrap();
    ch.run_program(&format!("{START}X10 THETA=20\nM30")).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let s = ch.snapshot();
    assert!(s.alarms.iter().any(|a| a.number == 12560 && a.line == Some(5)), "{:?}", s.alarms);
}

#[test]
fn the_tool_axis_follows_linearly_while_the_tip_holds_under_vector_interpolation() {
    // ORIWKS great circle from Z to (1, 0, 1)/√2 with THETA from 0 to 90 under ORIROTA: the
    // end is B = 45, A = atan2(r·e2, r·e1) with r = R(o, 90°)·(1, 0, −1)/√2 = (0, 1, 0) ⇒ A = 90.
    // Every sample keeps the tip at (0, 0, 50) (M = P − (0,0,200) + 300·o with its own B, C).
    let (ch, samples) = run(&format!("{START}ORIWKS\nA3=1 B3=0 C3=1 THETA=90\nM0\nM30"));
    assert_pose(&ch.snapshot(), [0.0, 0.0, 50.0], [90.0, 45.0, 0.0]);
    let moving: Vec<&Vec<f64>> = samples.iter().filter(|m| m[4] > 1e-6 && m[4] < 45.0 - 1e-6).collect();
    assert!(moving.len() > 5);
    for m in moving {
        let o = orientation(m[4], m[5]);
        let tip = [m[0] - 300.0 * o[0], m[1] - 300.0 * o[1], m[2] + 200.0 - 300.0 * o[2]];
        assert!(tip.iter().zip([0.0, 0.0, 50.0]).all(|(a, b)| (a - b).abs() < 1e-6), "{m:?}");
        // A goes linearly with B's progress along the great circle (both with the path
        // parameter): A/90 = (angle turned)/45.
        assert!((m[3] / 90.0 - m[4] / 45.0).abs() < 1e-6, "{m:?}");
    }
}

#[test]
fn the_orientation_variables_read_the_tool_and_rotation_vectors() {
    // After C = 60, B = 30 and THETA = 30 (ORIROTA): o = (cos60·sin30, sin60·sin30, cos30) =
    // (0.25, 0.4330, 0.8660); r = cos A·e1 + sin A·e2 with A = −63.4349 + 30 (see above).
    let o = orientation(30.0, 60.0);
    let prog = format!(
        "{START}ORIROTA\nX10 A3={} B3={} C3={} THETA=30\n\
         R1=$AC_TOOLO_ACT[1] R2=$AC_TOOLO_ACT[2] R3=$AC_TOOLO_ACT[3]\n\
         R4=$P_TOOLO[1] R5=$VC_TOOLO[3] R6=$AC_TOOLO_END[2]\n\
         R7=$AC_TOOLR_ACT[1] R8=$AC_TOOLR_ACT[2] R9=$P_TOOLROT[3]\nM30",
        o[0], o[1], o[2]
    );
    let (ch, _) = run(&prog);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    let a = (-63.434_948_822_922 + 30.0f64).to_radians();
    let (sb, cb) = 30f64.to_radians().sin_cos();
    let (sc, cc) = 60f64.to_radians().sin_cos();
    let r = [a.cos() * cc * cb - a.sin() * sc, a.cos() * sc * cb + a.sin() * cc, -a.cos() * sb];
    let expected = [
        (1, 0.25),
        (2, 0.75f64.sqrt() / 2.0),
        (3, 0.75f64.sqrt()),
        (4, 0.25),
        (5, 0.75f64.sqrt()),
        (6, 0.75f64.sqrt() / 2.0),
        (7, r[0]),
        (8, r[1]),
        (9, r[2]),
    ];
    for (n, v) in expected {
        assert!((ch.r_param(n) - v).abs() < 1e-9, "R{n} = {} vs {v}", ch.r_param(n));
    }
}

#[test]
fn without_a_transformation_the_tool_points_along_the_plane_applicate() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("G18\nR1=$AC_TOOLO_ACT[2] R2=$P_TOOLO[3]\nR3=$AC_TOOLO_ACT[4]\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert_eq!((ch.r_param(1), ch.r_param(2)), (1.0, 0.0));
    assert!(ch.snapshot().alarms.iter().any(|a| a.line == Some(3)), "{:?}", ch.snapshot().alarms);
    // A rotation vector needs the 6-axis kinematics.
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("R1=$AC_TOOLR_ACT[1]\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(ch.snapshot().alarms.iter().any(|a| a.line == Some(1)), "{:?}", ch.snapshot().alarms);
}

/// Tool T2: an angle head whose tool points along +X in the zero position ($TC_DPV3..5).
const ANGLE_HEAD: &str = "$TC_DP1[2,1]=120\n$TC_DP3[2,1]=100.\n$TC_DPV3[2,1]=1.\n$TC_DPV4[2,1]=0.\n$TC_DPV5[2,1]=0.";

fn run_md(md: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset("mill6-generic", md).unwrap();
    ch.run_program(program).unwrap();
    let mut n = 0;
    while ch.is_busy() {
        ch.step();
        n += 1;
        assert!(n < 1_000_000);
    }
    ch
}

#[test]
fn the_active_tools_own_orientation_is_the_basic_orientation() {
    // Basic orientation +X: with A = 0, C·B·A turn X into (cos C·cos B, sin C·cos B, −sin B);
    // the wanted +Z needs B = −90 (C stays in its pole position 0).
    let ch = run_md(ANGLE_HEAD, "T2 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A3=0 B3=0 C3=1\nR1=$TC_DPV3[2,1]\nM30");
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert!(
        (machine(&s, "B") + 90.0).abs() < 1e-6 && machine(&s, "C").abs() < 1e-6 && machine(&s, "A").abs() < 1e-6,
        "{:?}",
        s.machine
    );
    assert_eq!(ch.r_param(1), 1.0);
    // A vector passed with TRAORI(1, x, y, z) comes first: the basic orientation is +Z again.
    let ch = run_md(ANGLE_HEAD, "T2 D1\nG0 X0 Y0 Z50\nTRAORI(1, 0, 0, 1)\nG1 F3000 A3=0 B3=0 C3=1\nM30");
    assert!(machine(&ch.snapshot(), "B").abs() < 1e-6, "{:?}", ch.snapshot().machine);
}

#[test]
fn the_tools_orientation_normal_replaces_the_machine_datas() {
    // $TC_DPVN4 = 1: the tool normal (the rotation vector at A = 0) is +Y instead of the
    // machine data's +X. Under ORIROTC with THETA = 0 along +X the rotation vector must be +X:
    // Rz(A)·Y = (−sin A, cos A, 0) = X ⇒ A = −90 (with the machine data's +X it is A = 0).
    let md = "$TC_DP1[3,1]=120\n$TC_DP3[3,1]=100.\n$TC_DPVN4[3,1]=1.";
    let ch = run_md(md, "T3 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 ORIROTC THETA=0\nX100\nM30");
    assert_pose(&ch.snapshot(), [100.0, 0.0, 50.0], [-90.0, 0.0, 0.0]);
}

#[test]
fn p_gg_54_reports_the_rotation_reference() {
    let ch = run_md("", "R1=$P_GG[54]\nORIROTR\nR2=$P_GG[54]\nORIROTT\nR3=$P_GG[54]\nORIROTC\nR4=$P_GG[54]\nM30");
    assert_eq!([1, 2, 3, 4].map(|n| ch.r_param(n)), [1.0, 2.0, 3.0, 4.0]);
}

#[test]
fn the_g_code_display_lists_group_54() {
    // Reset value ORIROTA; after ORIROTT the display of the executing block shows it.
    let (ch, _) = run(&format!("{START}ORIROTT\nX10\nM0\nM30"));
    let g = ch.snapshot().gcodes;
    assert!(g.contains(&"ORIROTT".to_string()) && !g.contains(&"ORIROTA".to_string()), "{g:?}");
    let (ch, _) = run(&format!("{START}X10\nM0\nM30"));
    assert!(ch.snapshot().gcodes.contains(&"ORIROTA".to_string()), "{:?}", ch.snapshot().gcodes);
}
