//! Orientable toolholders and the CYCLE800 swivel run through a whole channel on the 5-axis
//! presets. Expected values are worked out here with plain rotation matrices, independently
//! of the engine's vector chain:
//! * head C/A (`mill5-head-ca`): the tool (100 mm) hangs 250 mm from the A pivot, which lies
//!   150 mm above the spindle nose, so for a tool tip P with orientation
//!   `o = Rz(C)·Rx(A)·ez` the machine position is `M = P − (0, 0, 150) + 250·o`;
//! * table A/C (`mill5-table-ac`, DIN-reversed axes): the table reference point moves to
//!   `Δ = l2 + Rx(−A)·(l3 + Rz(−C)·l4) − (l2 + l3 + l4)`.

use nctwin_engine::{Channel, Snapshot, Status};

type M3 = [[f64; 3]; 3];

fn rx(d: f64) -> M3 {
    let (s, c) = d.to_radians().sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

fn ry(d: f64) -> M3 {
    let (s, c) = d.to_radians().sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn rz(d: f64) -> M3 {
    let (s, c) = d.to_radians().sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn about(axis: usize, d: f64) -> M3 {
    [rx, ry, rz][axis](d)
}

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn apply(a: &M3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

fn run(preset: &str, extra: &str, program: &str) -> Channel {
    let mut ch = Channel::from_preset(preset, extra).unwrap();
    ch.run_program(program).unwrap();
    let mut n = 0;
    while ch.is_busy() {
        ch.step();
        n += 1;
        assert!(n < 2_000_000, "program does not end");
    }
    ch
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn assert_axes(ch: &Channel, expected: &[(&str, f64)]) {
    let s = ch.snapshot();
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    for (name, v) in expected {
        let got = machine(&s, name);
        let diff = if *name == "C" { (got - v + 180.0).rem_euclid(360.0) - 180.0 } else { got - v };
        assert!(diff.abs() < 1e-6, "{name}: {got} vs {v} ({:?})", s.machine);
    }
}

fn head_o(a: f64, c: f64) -> [f64; 3] {
    apply(&mul(&rz(c), &rx(a)), [0.0, 0.0, 1.0])
}

/// Machine X, Y, Z of the CA head for tool tip `p` at (A, C).
fn head_machine(p: [f64; 3], a: f64, c: f64) -> [f64; 3] {
    let o = head_o(a, c);
    [p[0] + 250.0 * o[0], p[1] + 250.0 * o[1], p[2] - 150.0 + 250.0 * o[2]]
}

fn xyz(m: [f64; 3]) -> [(&'static str, f64); 3] {
    [("X", m[0]), ("Y", m[1]), ("Z", m[2])]
}

const W1_TABLE: &str = "$MN_MM_NUM_TOOL_CARRIER=1\n$TC_CARR8[1]=1\n$TC_CARR20[1]=15\n$TC_CARR13[1]=45\n\
                        $TC_CARR23[1]=\"P\"\n$TC_DP3[1,1]=13";

#[test]
fn the_w1_example_approaches_x0_y10_z0_at_x10_607_y10_z8_607() {
    // W1 p.4-3 (REFERENCE §7.3): table axis along +Y at 45°, l4 = (0, 0, 15), 13 mm tool.
    let ch = run("mill-3axis", W1_TABLE, "T1 D1\nTCARR=1\nG0 X0 Y10 Z0\nM30");
    let s = 45f64.to_radians().sin();
    assert_axes(&ch, &[("X", 15.0 * s), ("Y", 10.0), ("Z", -15.0 * (1.0 - s) + 13.0)]);
    // The manual's figures, to its three decimals.
    let snap = ch.snapshot();
    let round = |n: &str| (machine(&snap, n) * 1000.0).round() / 1000.0;
    assert_eq!((round("X"), round("Y"), round("Z")), (10.607, 10.0, 8.607));
}

#[test]
fn tcarr_zero_and_tcarr_by_name_select_and_deselect() {
    let text = format!("{W1_TABLE}\n$TC_CARR34[1]=\"W1\"");
    let ch = run("mill-3axis", &text, "T1 D1\nTCARR=\"W1\"\nG0 X0 Y10 Z0\nTCARR=0\nG0 X0 Y10 Z0\nM30");
    assert_axes(&ch, &[("X", 0.0), ("Y", 10.0), ("Z", 13.0)]);
    // MD18088 = 1: holder 2 does not exist (holder 1 would, even without data).
    let ch = run("mill-3axis", W1_TABLE, "T1 D1\nTCARR=2\nM30");
    assert_eq!(ch.alarms().first().map(|a| a.number), Some(14150));
}

#[test]
fn a_head_holder_turns_the_tool_length_with_the_axis_positions() {
    // TCOABS with $TC_CARR21/22 naming C and A: the angles are the axis positions.
    let ch =
        run("mill5-head-ca", "", "T1 D1\nG0 A30 C0\nTCARR=1 TCOABS\nG0 X0 Y0 Z0\nR1=$P_TCANG[1] R2=$P_TCANG[2]\nM30");
    assert_axes(&ch, &xyz(head_machine([0.0; 3], 30.0, 0.0)));
    assert_eq!((ch.r_param(1), ch.r_param(2)), (0.0, 30.0));
}

#[test]
fn tcofr_turns_the_tool_along_the_frames_z_and_reports_both_solutions() {
    // ROT X30: the frame's Z is Rx(30)·ez; the CA head reaches it with C 0 / A 30 or C 180 /
    // A −30; TCOFR takes the pair nearest the axis positions (0, 0).
    let ch = run(
        "mill5-head-ca",
        "",
        "T1 D1\nROT X30\nTCARR=1 TCOFR\nR1=$P_TCANG[1] R2=$P_TCANG[2] R3=$P_TCANG[3] R4=$P_TCANG[4] R5=$P_TCSOL\nM30",
    );
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let r: Vec<f64> = (1..=5).map(|n| ch.r_param(n)).collect();
    assert!((r[0]).abs() < 1e-9 && (r[1] - 30.0).abs() < 1e-9, "{r:?}");
    assert!(((r[2] - 180.0).abs() < 1e-9 || (r[2] + 180.0).abs() < 1e-9) && (r[3] + 30.0).abs() < 1e-9, "{r:?}");
    assert_eq!(r[4], 2.0);
}

/// CYCLE800 on the CA head, new plane, no retraction, axis by axis.
fn swivel_head(mode: u32, a: f64, b: f64, c: f64, dir: i32) -> String {
    format!("CYCLE800(0,\"HEAD_CA\",0,{mode},0,0,0,{a},{b},{c},0,0,0,{dir},0,1)")
}

#[test]
fn minus_and_plus_pick_the_lower_and_the_higher_value_of_the_reference_axis() {
    // Rotation about X by 30°: C 0 / A 30 or C 180 / A −30; the head's direction reference
    // is A ($TC_CARR37 thousands digit 2).
    for (dir, a, c) in [(-1, -30.0, 180.0), (1, 30.0, 0.0)] {
        let ch =
            run("mill5-head-ca", "", &format!("T1 D1\nG0 X0 Y0 Z100\n{}\nM30", swivel_head(57, 30.0, 0.0, 0.0, dir)));
        // Without TRAORI only the rotary axes move (Z: 100 + the 100 mm tool).
        assert_axes(&ch, &[("A", a), ("C", c), ("X", 0.0), ("Y", 0.0), ("Z", 200.0)]);
    }
}

#[test]
fn every_axis_sequence_gives_its_frame_and_rotary_positions() {
    // (mode, sequence): XYZ, XZY, YXZ, YZX, ZXY, ZYX.
    let angles = [20.0, -15.0, 35.0];
    let p = [10.0, 20.0, 30.0];
    for (mode, seq) in
        [(57, [0, 1, 2]), (45, [0, 2, 1]), (54, [1, 0, 2]), (30, [1, 2, 0]), (39, [2, 0, 1]), (27, [2, 1, 0])]
    {
        let r = (0..3).fold(rx(0.0), |r, i| mul(&r, &about(seq[i], angles[i])));
        let ch = run(
            "mill5-head-ca",
            "",
            &format!(
                "T1 D1\n{}\nG0 X{} Y{} Z{}\nR1=$P_TCANG[1] R2=$P_TCANG[2]\nM30",
                swivel_head(mode, angles[0], angles[1], angles[2], 1),
                p[0],
                p[1],
                p[2]
            ),
        );
        assert!(ch.alarms().is_empty(), "{mode}: {:?}", ch.alarms());
        let (c, a) = (ch.r_param(1), ch.r_param(2));
        // The tool is the new Z, "plus" gives A ≥ 0.
        let o = head_o(a, c);
        let z = apply(&r, [0.0, 0.0, 1.0]);
        assert!((0..3).all(|i| (o[i] - z[i]).abs() < 1e-9), "{mode}: {o:?} vs {z:?}");
        assert!(a >= 0.0, "{mode}: A = {a}");
        assert_axes(&ch, &[("A", a), ("C", c)]);
        assert_axes(&ch, &xyz(head_machine(apply(&r, p), a, c)));
    }
}

#[test]
fn solid_angle_turns_about_z_then_about_the_new_y() {
    let r = mul(&rz(40.0), &ry(25.0));
    let ch = run(
        "mill5-head-ca",
        "",
        &format!("T1 D1\n{}\nG0 X5 Y-5 Z20\nR1=$P_TCANG[1] R2=$P_TCANG[2]\nM30", swivel_head(64, 40.0, 25.0, 0.0, 1)),
    );
    let (c, a) = (ch.r_param(1), ch.r_param(2));
    assert_axes(&ch, &xyz(head_machine(apply(&r, [5.0, -5.0, 20.0]), a, c)));
}

#[test]
fn projection_angles_build_the_plane_from_its_traces() {
    // Xα = 30, Yα = 20 (G17): new X = Ry(20)·ex in the old Z-X plane, the trace in the Y-Z
    // plane Rx(30)·ey, normal = their cross product, then Zβ = 10 about the new Z.
    let x = apply(&ry(20.0), [1.0, 0.0, 0.0]);
    let y0 = apply(&rx(30.0), [0.0, 1.0, 0.0]);
    let n = [x[1] * y0[2] - x[2] * y0[1], x[2] * y0[0] - x[0] * y0[2], x[0] * y0[1] - x[1] * y0[0]];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let z = n.map(|v| v / len);
    let y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]];
    let base: M3 = std::array::from_fn(|i| [x[i], y[i], z[i]]);
    let r = mul(&base, &rz(10.0));
    let ch = run(
        "mill5-head-ca",
        "",
        &format!(
            "T1 D1\n{}\nG0 X10 Y10 Z10\nR1=$P_TCANG[1] R2=$P_TCANG[2]\nM30",
            swivel_head(128 + 57, 30.0, 20.0, 10.0, 1)
        ),
    );
    let (c, a) = (ch.r_param(1), ch.r_param(2));
    assert_axes(&ch, &xyz(head_machine(apply(&r, [10.0, 10.0, 10.0]), a, c)));
}

#[test]
fn direct_swivelling_positions_the_axes_and_aligns_z_with_the_tool() {
    // Rotary axis 1 is C, axis 2 is A: C = 90, A = 30 gives o = Rz(90)·Rx(30)·ez; the frame is
    // the head's rotation Rz(90)·Rx(30).
    let r = mul(&rz(90.0), &rx(30.0));
    let ch = run("mill5-head-ca", "", &format!("T1 D1\n{}\nG0 X10 Y0 Z5\nM30", swivel_head(192, 90.0, 30.0, 0.0, 0)));
    assert_axes(&ch, &[("A", 30.0), ("C", 90.0)]);
    assert_axes(&ch, &xyz(head_machine(apply(&r, [10.0, 0.0, 5.0]), 30.0, 90.0)));
}

#[test]
fn reference_and_zero_point_shift_the_swivelled_plane() {
    // TRANS(X0..) : ROT : TRANS(X1..): the new origin is p0 + R·p1.
    let r = rx(30.0);
    let (p0, p1, p) = ([10.0, 20.0, 0.0], [0.0, 5.0, 2.0], [1.0, 2.0, 3.0]);
    let q = apply(&r, [p1[0] + p[0], p1[1] + p[1], p1[2] + p[2]]);
    let bcs = [p0[0] + q[0], p0[1] + q[1], p0[2] + q[2]];
    let call = format!(
        "CYCLE800(0,\"HEAD_CA\",0,57,{},{},{},30,0,0,{},{},{},1,0,1)",
        p0[0], p0[1], p0[2], p1[0], p1[1], p1[2]
    );
    let ch = run("mill5-head-ca", "", &format!("T1 D1\n{call}\nG0 X{} Y{} Z{}\nM30", p[0], p[1], p[2]));
    assert_axes(&ch, &xyz(head_machine(bcs, 30.0, 0.0)));
}

#[test]
fn an_additive_swivel_composes_with_the_previous_one() {
    let r = mul(&rx(20.0), &rx(10.0));
    let call2 = "CYCLE800(0,\"HEAD_CA\",1,57,0,0,0,10,0,0,0,0,0,1,0,1)";
    let ch = run(
        "mill5-head-ca",
        "",
        &format!("T1 D1\n{}\n{call2}\nG0 X0 Y10 Z10\nM30", swivel_head(57, 20.0, 0.0, 0.0, 1)),
    );
    assert_axes(&ch, &[("A", 30.0), ("C", 0.0)]);
    assert_axes(&ch, &xyz(head_machine(apply(&r, [0.0, 10.0, 10.0]), 30.0, 0.0)));
}

#[test]
fn a_pocket_on_the_inclined_plane_runs_in_the_swivelled_coordinates() {
    // Swivel 30° about X, then a square pocket contour at depth Z−2 with G17 on the plane.
    let r = rx(30.0);
    let prog = format!(
        "T1 D1\nG0 X0 Y0 Z100\n{}\nG0 X0 Y0 Z5\nG1 Z-2 F500\nX20\nY15\nX0\nY0\nR10=$AA_IM[X] R11=$AA_IM[Y] R12=$AA_IM[Z]\nG1 X20 Y15\nM30",
        swivel_head(57, 30.0, 0.0, 0.0, 1)
    );
    let ch = run("mill5-head-ca", "", &prog);
    let corner = head_machine(apply(&r, [0.0, 0.0, -2.0]), 30.0, 0.0);
    assert!(
        (0..3).all(|i| (ch.r_param(10 + i) - corner[i]).abs() < 1e-6),
        "{:?} vs {corner:?}",
        (10..13).map(|i| ch.r_param(i)).collect::<Vec<_>>()
    );
    assert_axes(&ch, &xyz(head_machine(apply(&r, [20.0, 15.0, -2.0]), 30.0, 0.0)));
}

#[test]
fn retraction_to_the_holder_position_comes_before_the_swivel() {
    let call = "CYCLE800(1,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,1,0,1)";
    let ch = run("mill5-head-ca", "", &format!("T1 D1\nG0 X10 Y20 Z50\n{call}\nM30"));
    assert_axes(&ch, &[("X", 10.0), ("Y", 20.0), ("Z", 250.0), ("A", 30.0)]);
    let call = "CYCLE800(5,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,1,40,1)";
    let ch = run("mill5-head-ca", "", &format!("T1 D1\nG0 X10 Y20 Z50\n{call}\nM30"));
    // 40 mm up along the tool (still vertical) from Z 50 + 100.
    assert_axes(&ch, &[("X", 10.0), ("Y", 20.0), ("Z", 190.0)]);
    // Mode 2: machine Z to $TC_CARR40 = 250, then X/Y to $TC_CARR38/39 = 0.
    let call = "CYCLE800(2,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,1,0,1)";
    let ch = run("mill5-head-ca", "", &format!("T1 D1\nG0 X10 Y20 Z50\n{call}\nM30"));
    assert_axes(&ch, &[("X", 0.0), ("Y", 0.0), ("Z", 250.0), ("A", 30.0)]);
    // Mode 4: as far as possible along the (vertical) tool: Z up to its software limit 300.
    let call = "CYCLE800(4,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,1,0,1)";
    let ch = run("mill5-head-ca", "", &format!("T1 D1\nG0 X10 Y20 Z50\n{call}\nM30"));
    assert_axes(&ch, &[("X", 10.0), ("Y", 20.0), ("Z", 300.0), ("A", 30.0)]);
}

#[test]
fn toframe_and_torot_after_a_swivel_keep_the_tool_as_z() {
    let r = rx(30.0);
    // TOROTOF drops the swivel, TOFRAME rebuilds the same rotation from the tool direction
    // (SD42980 = 2000: the smallest turn of Z onto the tool is Rx(30) here).
    let prog = format!("T1 D1\n{}\nTOROTOF\nTOFRAME\nG0 X10 Y5 Z20\nM30", swivel_head(57, 30.0, 0.0, 0.0, 1));
    let ch = run("mill5-head-ca", "", &prog);
    assert_axes(&ch, &xyz(head_machine(apply(&r, [10.0, 5.0, 20.0]), 30.0, 0.0)));
    // TOROT keeps the swivel's zero point, TOFRAME does not.
    let call = "CYCLE800(0,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,7,1,0,1)";
    let ch = run("mill5-head-ca", "", &format!("T1 D1\n{call}\nTOROT\nG0 X0 Y0 Z0\nR1=$P_GG[53]\nM30"));
    assert_axes(&ch, &xyz(head_machine(apply(&r, [0.0, 0.0, 7.0]), 30.0, 0.0)));
    assert_eq!(ch.r_param(1), 2.0);
}

#[test]
fn toframe_without_a_holder_follows_the_plane() {
    // G18: the tool is along Y; TOFRAME makes it the new Z (new Z = old Y).
    let ch = run("mill-3axis", "", "G18\nTOFRAME\nG17\nG0 X0 Y0 Z10\nM30");
    assert_axes(&ch, &[("X", 0.0), ("Y", 10.0), ("Z", 0.0)]);
}

#[test]
fn deselection_restores_the_plain_tool_and_frames() {
    let prog = format!("T1 D1\n{}\nCYCLE800()\nG0 X1 Y2 Z3\nM30", swivel_head(57, 30.0, 0.0, 0.0, 1));
    let ch = run("mill5-head-ca", "", &prog);
    // No holder: machine = point + tool length along Z, the head stays where it is.
    assert_axes(&ch, &[("X", 1.0), ("Y", 2.0), ("Z", 103.0), ("A", 30.0)]);
}

#[test]
fn a_swivel_table_turns_the_workpiece_and_the_wcs_with_it() {
    // Rotation about X by 30°, plus: A = 30, C = 0; the table's rotation Rx(−30) undoes the
    // swivel, so the WCS axes are parallel to the machine's again, shifted by Δ.
    let call = "CYCLE800(0,\"TABLE_AC\",0,57,0,0,0,30,0,0,0,0,0,1,0,1)";
    let ch = run("mill5-table-ac", "", &format!("T1 D1\n{call}\nG0 X10 Y20 Z30\nM30"));
    let (l2, l3, l4) = ([0.0, 20.0, -100.0], [0.0, -20.0, 80.0], [0.0, 0.0, 20.0]);
    let inner = apply(&rx(-30.0), [l3[0] + l4[0], l3[1] + l4[1], l3[2] + l4[2]]);
    let delta: Vec<f64> = (0..3).map(|i| l2[i] + inner[i] - (l2[i] + l3[i] + l4[i])).collect();
    assert_axes(&ch, &[("A", 30.0), ("C", 0.0)]);
    assert_axes(&ch, &[("X", 10.0 + delta[0]), ("Y", 20.0 + delta[1]), ("Z", 30.0 + delta[2] + 100.0)]);
    // Direct swivelling to A = 30, C = 0 gives the same plane and the same machine position.
    let call = "CYCLE800(0,\"TABLE_AC\",0,192,0,0,0,30,0,0,0,0,0,0,0,1)";
    let direct = run("mill5-table-ac", "", &format!("T1 D1\n{call}\nG0 X10 Y20 Z30\nM30"));
    assert_axes(&direct, &[("X", 10.0 + delta[0]), ("Y", 20.0 + delta[1]), ("Z", 30.0 + delta[2] + 100.0)]);
    // Minus takes the other solution (A = −30, C = 180): the same plane.
    let call = "CYCLE800(0,\"TABLE_AC\",0,57,0,0,0,30,0,0,0,0,0,-1,0,1)";
    let ch = run("mill5-table-ac", "", &format!("T1 D1\n{call}\nM30"));
    assert_axes(&ch, &[("A", -30.0), ("C", 180.0)]);
}

#[test]
fn a_mixed_machine_tilts_the_head_and_turns_the_table() {
    // Rotation about Y by 30°: B = 30 tilts the tool onto the new Z with C at 0 (B is the
    // direction reference, plus); the tool length turns about the B pivot 120 mm up.
    let call = "CYCLE800(0,\"MIXED_BC\",0,57,0,0,0,0,30,0,0,0,0,1,0,1)";
    let ch = run("mill5-mixed-bc", "", &format!("T1 D1\n{call}\nG0 X0 Y0 Z10\nM30"));
    let o = apply(&ry(30.0), [0.0, 0.0, 1.0]);
    // Tool tip 220 below the pivot along the tool: M = P − (0,0,120) + 220·o.
    let p = apply(&ry(30.0), [0.0, 0.0, 10.0]);
    assert_axes(&ch, &[("B", 30.0), ("C", 0.0)]);
    assert_axes(&ch, &[("X", p[0] + 220.0 * o[0]), ("Y", p[1]), ("Z", p[2] - 120.0 + 220.0 * o[2])]);
}

#[test]
fn with_traori_the_swivel_tracks_the_tool_tip() {
    let prog = format!("T1 D1\nG0 X10 Y20 Z50\nTRAORI\n{}\nG0 X0 Y0 Z10\nM30", swivel_head(57, 30.0, 0.0, 0.0, 1));
    let ch = run("mill5-head-ca", "", &prog);
    let tip = apply(&rx(30.0), [0.0, 0.0, 10.0]);
    assert_axes(&ch, &[("A", 30.0), ("C", 0.0)]);
    assert_axes(&ch, &xyz(head_machine(tip, 30.0, 0.0)));
}

#[test]
fn bad_parameters_raise_alarms_without_motion() {
    for (call, number) in [
        ("CYCLE800(0,\"HEAD_CA\",0,21,0,0,0,30,0,0,0,0,0,1,0,1)", 61182),
        ("CYCLE800(3,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,1,0,1)", 61183),
        ("CYCLE800(5,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,1,-5,1)", 61183),
        ("CYCLE800(0,\"NO_SUCH\",0,57,0,0,0,30,0,0,0,0,0,1,0,1)", 61181),
        ("CYCLE800(0,\"HEAD_CA\",0,57,0,0,0,120,0,0,0,0,0,1,0,1)", 61184),
        ("CYCLE800(0,\"HEAD_CA\",0,57,0,0,0,30,0,0,0,0,0,2,0,1)", 61182),
        ("CYCLE800(0,\"HEAD_CA\",0,192,0,0,0,0,130,0,0,0,0,0,0,1)", 61184),
    ] {
        let ch = run("mill5-head-ca", "", &format!("T1 D1\nG0 X10 Y20 Z50\nM0\n{call}\nM30"));
        // The M0 stop: continue into the cycle.
        let mut ch = ch;
        ch.start().unwrap();
        while ch.is_busy() {
            ch.step();
        }
        assert_eq!(ch.status(), Status::Alarm, "{call}");
        assert_eq!(ch.alarms().first().map(|a| a.number), Some(number), "{call}: {:?}", ch.alarms());
        let s = ch.snapshot();
        for (name, v) in [("X", 10.0), ("Y", 20.0), ("Z", 150.0), ("A", 0.0), ("C", 0.0)] {
            assert!((machine(&s, name) - v).abs() < 1e-9, "{call}: {name} moved: {:?}", s.machine);
        }
    }
}

#[test]
fn rotations_in_the_work_offset_raise_61186_when_md55410_asks() {
    let extra = "$P_UIFR[1,Z,RT]=10\n$MC_MILL_SWIVEL_ALARM_MASK=1";
    let ch = run("mill5-head-ca", extra, &format!("T1 D1\nG54\n{}\nM30", swivel_head(57, 30.0, 0.0, 0.0, 1)));
    assert_eq!(ch.alarms().first().map(|a| a.number), Some(61186));
    let ch =
        run("mill5-head-ca", "$P_UIFR[1,Z,RT]=10", &format!("T1 D1\nG54\n{}\nM30", swivel_head(57, 30.0, 0.0, 0.0, 1)));
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
}

#[test]
fn holder_data_written_by_a_program_acts_from_the_next_block() {
    let ch = run(
        "mill-3axis",
        "$MN_MM_NUM_TOOL_CARRIER=1",
        "$TC_DP3[1,1]=13\n$TC_CARR8[1]=1\n$TC_CARR20[1]=15\n$TC_CARR13[1]=45\n$TC_CARR23[1]=\"p\"\nT1 D1\nTCARR=1\nG0 X0 Y10 Z0\nR1=$TC_CARR20[1]\nM30",
    );
    assert_axes(&ch, &[("Y", 10.0)]);
    assert!((machine(&ch.snapshot(), "X") - 10.606601717798213).abs() < 1e-9);
    assert_eq!(ch.r_param(1), 15.0);
    // Fine offsets read back as written and act only with SD42974.
    let ch = run(
        "mill-3axis",
        "$MN_MM_NUM_TOOL_CARRIER=1\n$TC_CARR20[1]=15\n$TC_CARR60[1]=0.5",
        "R1=$TC_CARR20[1] R2=$TC_CARR60[1] R3=$TC_CARR23[1]\nM30",
    );
    assert_eq!((ch.r_param(1), ch.r_param(2)), (15.0, 0.5));
    let ch = run("mill-3axis", "$MN_MM_NUM_TOOL_CARRIER=1", "$TC_CARR23[1]=\"Q\"\nM30");
    assert_eq!(ch.alarms().first().map(|a| a.number), Some(14153));
}

#[test]
fn the_compensation_type_words_are_modal_g_group_22() {
    let ch = run("mill-3axis", "", "CUT2DF\nR1=$P_GG[22]\nCUT2D\nR2=$P_GG[22]\nCUT3DFS\nCUT3DFF\nR3=$P_GG[22]\nM30");
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!((ch.r_param(1), ch.r_param(2), ch.r_param(3)), (6.0, 1.0, 5.0));
}

#[test]
fn tcofr_and_parot_reproduce_the_w1_table_example() {
    // W1 p.2-98: with ROT Y−45 and TCOFR the table axis along +Y gets +45°; PAROT then turns
    // the WCS by 45° about Y ($P_PARTFRAME), PAROTOF keeps only the offset.
    let ch = run(
        "mill-3axis",
        W1_TABLE,
        "T1 D1\nROT Y-45\nTCARR=1 TCOFR\nR1=$P_TCANG[1] R2=$P_TCSOL\nPAROT\nR3=$P_PARTFRAME[Y,RT] R4=$P_GG[52]\n\
         PAROTOF\nR5=$P_PARTFRAME[Y,RT] R6=$P_PARTFRAME[X,TR]\nM30",
    );
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert!((ch.r_param(1) - 45.0).abs() < 1e-9, "{}", ch.r_param(1));
    assert_eq!(ch.r_param(2), 1.0, "one axis: one solution");
    assert!((ch.r_param(3) - 45.0).abs() < 1e-9, "{}", ch.r_param(3));
    assert_eq!((ch.r_param(4), ch.r_param(5)), (1.0, 0.0));
    assert!((ch.r_param(6) - 15.0 * 45f64.to_radians().sin()).abs() < 1e-9);
}

#[test]
fn cut2d_compensates_in_the_plane_of_the_turned_tool_and_cut2df_in_the_frames() {
    // A B head turned to 90° ($TC_CARR13, no axis named): the tool lies along +X, so its
    // length (100) acts on X. G41 along +Y with a 5 mm radius: CUT2DF offsets in the frame's
    // X-Y plane (−X), CUT2D in the plane perpendicular to the tool (Rx-turned: +Z).
    let holder = "$MN_MM_NUM_TOOL_CARRIER=1\n$TC_CARR8[1]=1\n$TC_CARR13[1]=90\n$TC_DP6[1,1]=5\n$TC_DP3[1,1]=100";
    let prog = |cut: &str| format!("T1 D1\nTCARR=1\n{cut}\nG0 X0 Y0 Z0\nG41 G1 Y50 F1000\nY100\nM0\nM30");
    let ch = run("mill-3axis", holder, &prog("CUT2DF"));
    assert_axes(&ch, &[("X", 100.0 - 5.0), ("Y", 100.0), ("Z", 0.0)]);
    let ch = run("mill-3axis", holder, &prog("CUT2D"));
    assert_axes(&ch, &[("X", 100.0), ("Y", 100.0), ("Z", 5.0)]);
}

#[test]
fn toframex_and_toframey_make_the_tool_the_new_x_or_y() {
    // G17 without a holder: the tool is the old Z. TOFRAMEX turns X onto it (Ry(−90)), so
    // Z10 in the new frame is X−10; TOFRAMEY turns Y onto it (Rx(90)): Z10 is Y−10.
    let ch = run("mill-3axis", "", "R1=$P_GG[53]\nTOFRAMEX\nR2=$P_GG[53]\nG0 X0 Y0 Z10\nM30");
    assert_axes(&ch, &[("X", -10.0), ("Y", 0.0), ("Z", 0.0)]);
    assert_eq!((ch.r_param(1), ch.r_param(2)), (1.0, 9.0));
    let ch = run("mill-3axis", "", "TOFRAMEY\nG0 X0 Y0 Z10\nTOROTOF\nR1=$P_GG[53]\nM30");
    assert_axes(&ch, &[("X", 0.0), ("Y", -10.0), ("Z", 0.0)]);
    assert_eq!(ch.r_param(1), 1.0);
}

#[test]
fn hirth_teeth_round_the_tcofr_angles_to_their_pitch() {
    // ROT X32 would need A 32 (or −32); a 5° Hirth pitch on the 2nd holder axis (A,
    // $TC_CARR29) takes the nearest tooth, 30 (or −30).
    let ch = run(
        "mill5-head-ca",
        "$TC_CARR29[1]=5",
        "T1 D1\nROT X32\nTCARR=1 TCOFR\nR1=$P_TCANG[1] R2=$P_TCANG[2] R3=$P_TCANG[3] R4=$P_TCANG[4]\nM30",
    );
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let r: Vec<f64> = (1..=4).map(|n| ch.r_param(n)).collect();
    assert!(r[0].abs() < 1e-9 && (r[1] - 30.0).abs() < 1e-9, "{r:?}");
    assert!((r[3] + 30.0).abs() < 1e-9, "{r:?}");
}
