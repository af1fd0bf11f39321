//! TRAORI run through a whole channel on the 5-axis presets: the tool tip stays on the
//! programmed path while the orientation changes, orientation programming by vector and angles,
//! the interpolation types, and the tool direction in the state. Expected values come from the
//! head's closed form, written out here: with C about Z carrying A about X, pivot 150 above the
//! spindle nose and a 100 mm tool, the machine position of tip P with orientation
//! `o = (sin C·sin A, −cos C·sin A, cos A)` is `M = P − (0, 0, 150) + 250·o`.

use nctwin_engine::{Channel, Snapshot, Status};

const MAX_TICKS: usize = 1_000_000;

struct Sample {
    axes: Vec<f64>,
}

fn run(preset: &str, program: &str) -> (Channel, Vec<Sample>) {
    run_with(preset, "", program)
}

fn run_with(preset: &str, md: &str, program: &str) -> (Channel, Vec<Sample>) {
    let mut ch = Channel::from_preset(preset, md).unwrap();
    ch.run_program(program).unwrap();
    let mut samples = Vec::new();
    while ch.is_busy() {
        ch.step();
        samples.push(Sample { axes: ch.axis_positions().to_vec() });
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    (ch, samples)
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn head_orientation(a: f64, c: f64) -> [f64; 3] {
    let (sa, ca) = a.to_radians().sin_cos();
    let (sc, cc) = c.to_radians().sin_cos();
    [sc * sa, -cc * sa, ca]
}

/// The tool tip of the CA head at machine position (X, Y, Z, A, C).
fn head_tip(m: &[f64]) -> [f64; 3] {
    let o = head_orientation(m[3], m[4]);
    [m[0] - 250.0 * o[0], m[1] - 250.0 * o[1], m[2] + 150.0 - 250.0 * o[2]]
}

fn close3(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
}

fn assert_machine(s: &Snapshot, expected: [f64; 5]) {
    for (name, v) in ["X", "Y", "Z", "A", "C"].iter().zip(expected) {
        let got = machine(s, name);
        let diff = if *name == "C" { (got - v + 180.0).rem_euclid(360.0) - 180.0 } else { got - v };
        assert!(diff.abs() < 1e-6, "{name}: {got} vs {v} ({:?})", s.machine);
    }
}

const START: &str = "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000\n";

#[test]
fn a_rotary_axis_move_keeps_the_tool_tip_where_it_is() {
    let (ch, samples) = run("mill5-head-ca", &format!("{START}A30\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let o = head_orientation(30.0, 0.0);
    assert_machine(&s, [250.0 * o[0], 250.0 * o[1], 50.0 - 150.0 + 250.0 * o[2], 30.0, 0.0]);
    let after_selection: Vec<&Sample> = samples.iter().filter(|p| p.axes[3].abs() > 1e-9).collect();
    assert!(after_selection.len() > 10);
    for p in after_selection {
        assert!(close3(head_tip(&p.axes), [0.0, 0.0, 50.0], 1e-6), "tip {:?} at {:?}", head_tip(&p.axes), p.axes);
    }
    // The state shows the tool direction in the WCS.
    let shown = s.orientation.expect("orientation");
    assert!(close3(shown, o, 1e-9), "{shown:?}");
    assert_eq!(s.transformation.map(|t| (t.name, t.trafo_type)), Some(("TRAORI".to_string(), 20)));
}

#[test]
fn a_direction_vector_picks_the_solution_nearest_the_current_axes() {
    // o = (1, 0, 1)/√2: A = 45, C = 90, or A = −45, C = 270; from C = 80 the first is nearer.
    let (ch, _) = run("mill5-head-ca", &format!("{START}C80\nA3=1 B3=0 C3=1\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let o = head_orientation(45.0, 90.0);
    assert_machine(&s, [250.0 * o[0], 250.0 * o[1], -100.0 + 250.0 * o[2], 45.0, 90.0]);
}

#[test]
fn euler_angles_define_the_orientation() {
    // ORIEULER: A2 = 90, B2 = 30 gives (sin 30°, 0, cos 30°): the head at A = 30, C = 90.
    let (ch, _) = run("mill5-head-ca", &format!("{START}A30\nA2=90 B2=30\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let o = head_orientation(30.0, 90.0);
    assert_machine(&s, [250.0 * o[0], 250.0 * o[1], -100.0 + 250.0 * o[2], 30.0, 90.0]);
}

/// From A30 C0 to A30 C90: interpolating the axes keeps the tilt at 30°; the great circle of
/// ORIWKS passes nearer the vertical, at the normalised midpoint of the two vectors (22.21°).
#[test]
fn oriwks_interpolates_a_great_circle_and_orimks_the_axes() {
    let great_circle_mid_tilt = {
        let (s, e) = (head_orientation(30.0, 0.0), head_orientation(30.0, 90.0));
        let m = [s[0] + e[0], s[1] + e[1], s[2] + e[2]];
        (m[2] / (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt()).acos().to_degrees()
    };
    for (mode, lowest_tilt) in [("ORIMKS", 30.0), ("ORIWKS", great_circle_mid_tilt)] {
        let program = format!("{START}A30\n{mode}\nA3=0.5 B3=0 C3={}\nM0\nM30", 0.75f64.sqrt());
        let (ch, samples) = run("mill5-head-ca", &program);
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{mode}: {:?}", s.alarms);
        assert!((machine(&s, "A") - 30.0).abs() < 1e-6 && (machine(&s, "C") - 90.0).abs() < 1e-6, "{mode}");
        let swing: Vec<&Sample> = samples.iter().filter(|p| p.axes[4] > 1e-6).collect();
        let min_a = swing.iter().map(|p| p.axes[3]).fold(f64::MAX, f64::min);
        assert!((min_a - lowest_tilt).abs() < 0.05, "{mode}: lowest A {min_a} vs {lowest_tilt}");
        let normal = {
            let (a, b) = (head_orientation(30.0, 0.0), head_orientation(30.0, 90.0));
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        };
        for p in swing {
            assert!(close3(head_tip(&p.axes), [0.0, 0.0, 50.0], 1e-6), "{mode}: tip at {:?}", p.axes);
            if mode == "ORIWKS" {
                let o = head_orientation(p.axes[3], p.axes[4]);
                let off_plane = o[0] * normal[0] + o[1] * normal[1] + o[2] * normal[2];
                assert!(off_plane.abs() < 1e-9, "not on the great circle: {o:?}");
            }
        }
    }
}

#[test]
fn under_oriwks_the_vector_turns_with_the_frame() {
    // ROT Z90: the programmed (1, 0, 1)/√2 is (0, 1, 1)/√2 in the BCS: A = −45 with C = 0.
    let program = format!("{START}ORIWKS\nROT Z90\nA3=1 B3=0 C3=1\nM0\nM30");
    let (ch, _) = run("mill5-head-ca", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let o = head_orientation(-45.0, 0.0);
    assert_machine(&s, [250.0 * o[0], 250.0 * o[1], -100.0 + 250.0 * o[2], -45.0, 0.0]);
    // Shown in the WCS: the programmed direction again.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(close3(s.orientation.unwrap(), [h, 0.0, h], 1e-9), "{:?}", s.orientation);
}

#[test]
fn the_path_and_the_orientation_move_together() {
    // X travels 100 while A swings 0 → 30: every sample's tip lies on the line Y0 Z50.
    let (ch, samples) = run("mill5-head-ca", &format!("{START}X100 A30\nM0\nM30"));
    assert_eq!(ch.snapshot().status, Status::Stopped);
    let moving: Vec<&Sample> = samples.iter().filter(|p| p.axes[3] > 1e-9).collect();
    assert!(moving.len() > 10);
    let mut last_x = f64::MIN;
    for p in moving {
        let tip = head_tip(&p.axes);
        assert!(tip[1].abs() < 1e-6 && (tip[2] - 50.0).abs() < 1e-6, "tip {tip:?}");
        assert!(tip[0] >= last_x - 1e-9, "tip goes back");
        last_x = tip[0];
    }
    assert!((last_x - 100.0).abs() < 1e-6);
}

#[test]
fn orientation_words_need_an_orientation_transformation() {
    let (ch, _) = run("mill5-head-ca", "A3=0 B3=0 C3=1\nM30");
    assert_eq!(ch.snapshot().alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [14110]);
    let (ch, _) = run("mill5-head-ca", &format!("{START}A30 A3=1 C3=1\nM30"));
    assert_eq!(ch.snapshot().status, Status::Alarm);
}

#[test]
fn trafoof_and_reset_return_to_machine_axes() {
    let (ch, _) = run("mill5-head-ca", &format!("{START}A30\nTRAFOOF\nG0 X10\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(s.transformation.is_none());
    // Without the transformation X is the machine axis again, with the tool length on Z.
    assert!((machine(&s, "X") - 10.0).abs() < 1e-9);
}

/// The Transformations Function Manual's orientation-vector example (F2, 3.13: N100..N170) on
/// the example machine data of the same pages: a head with A about X carrying B about Y
/// (type 16), BASE_TOOL (0, 0, 5), no other offsets; T1 is 100 long. M0 after each block lets
/// the test look. For this head `o = Rx(A)·Ry(B)·ez = (sin B, −sin A·cos B, cos A·cos B)` and the
/// machine point is `M = P − Rx(A)·Ry(B)·(0, 0, 5 − 100)`. The chain is not closed (BASE_TOOL
/// without PART_OFFSET): the spindle nose at Z100 of N100 is the tool tip P = (0, 0, 5) for
/// TRAORI, which the example's later blocks keep.
#[test]
fn the_manuals_orientation_vector_example() {
    let md = "\
$MN_AXCONF_MACHAX_NAME_TAB[4]=\"B\"
$MC_AXCONF_CHANAX_NAME_TAB[4]=\"B\"
$MA_ROT_IS_MODULO[B]=FALSE
$MA_POS_LIMIT_MINUS[B]=-120
$MA_POS_LIMIT_PLUS[B]=120
$MC_TRAFO_TYPE_1=16
$MC_TRAFO_AXES_IN_1[3]=4
$MC_TRAFO_AXES_IN_1[4]=5
$MC_TRAFO5_PART_OFFSET_1[2]=0
$MC_TRAFO5_BASE_TOOL_1[2]=5";
    let program = "\
N100 G1 x1 y0 z0 a0 b0 F20000 G90 G64 T1 D1 G17 ADIS=.5 ADISPOS=3
N110 TRAORI(1)
N120 ORIWKS
N130 G1 G90
N140 a3 = 0 b3 = 0 c3 = 1 x0
M0
N150 a3 = 0 b3 =-1 c3 = 0
M0
N160 a3 = 1 b3 = 0 c3 = 0
M0
N170 a3 = 1 b3 = 0 c3 = 1
M0
M30";
    let mut ch = Channel::from_preset("mill5-head-ca", md).unwrap();
    ch.run_program(program).unwrap();
    let machine_point = |a: f64, b: f64| {
        let (sa, ca) = a.to_radians().sin_cos();
        let (sb, cb) = b.to_radians().sin_cos();
        // Rx(A)·Ry(B)·(0, 0, −95).
        let v = [-95.0 * sb, 95.0 * sa * cb, -95.0 * ca * cb];
        [-v[0], -v[1], 5.0 - v[2]]
    };
    // (A, B) after each block; in N160 B = 90 puts the tool along X whatever A is (a pole):
    // A keeps its position. N170 from there: B = 45 with A = 0 (A = 180 is beyond the limit).
    for (block, (a, b)) in [("N140", (0.0, 0.0)), ("N150", (90.0, 0.0)), ("N160", (90.0, 90.0)), ("N170", (0.0, 45.0))]
    {
        let mut ticks = 0;
        while ch.is_busy() {
            ch.step();
            ticks += 1;
            assert!(ticks < MAX_TICKS);
        }
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{block}: {:?}", s.alarms);
        let m = machine_point(a, b);
        for (name, v) in ["X", "Y", "Z", "A", "B"].iter().zip([m[0], m[1], m[2], a, b]) {
            assert!(
                (machine(&s, name) - v).abs() < 1e-6,
                "{block} {name}: {} vs {v} ({:?})",
                machine(&s, name),
                s.machine
            );
        }
        ch.start().unwrap();
    }
}

#[test]
fn orireset_moves_the_orientation_axes_to_their_rest_or_given_positions() {
    // The 1st orientation axis of the head is C (TRAFO_AXES_IN_1[3]), the 2nd A.
    for (call, (a, c)) in
        [("ORIRESET()", (0.0, 0.0)), ("ORIRESET(10, 20)", (20.0, 10.0)), ("ORIRESET(, 5)", (5.0, 0.0))]
    {
        let (ch, samples) = run("mill5-head-ca", &format!("{START}A30 C45\n{call}\nM0\nM30"));
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{call}: {:?}", s.alarms);
        let o = head_orientation(a, c);
        assert_machine(&s, [250.0 * o[0], 250.0 * o[1], -100.0 + 250.0 * o[2], a, c]);
        for p in samples.iter().filter(|p| p.axes[3].abs() > 1e-9) {
            assert!(close3(head_tip(&p.axes), [0.0, 0.0, 50.0], 1e-6), "{call}: tip at {:?}", p.axes);
        }
    }
    let (ch, _) = run("mill5-head-ca", "ORIRESET()\nM30");
    assert_eq!(ch.snapshot().alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [14110]);
}

/// PTP: the end point is transformed once and the machine axes travel linearly together, so
/// the tool tip leaves the straight line; STAT= picks the orientation solution (bit 0 = 0 the
/// one nearer to the start; from A0 C0 both are 135° away and the lower C stays STAT=0), TU=
/// the turn ranges (bit 3: A negative, bit 4 clear: C in 0..360).
#[test]
fn ptp_moves_the_machine_axes_linearly_to_the_chosen_solution() {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (words, a_end, c_travel) in [("STAT=1", 45.0, 90.0), ("STAT=0", -45.0, -90.0), ("STAT=0 TU=8", -45.0, 270.0)] {
        let program = format!("{START}PTP\nG0 X100 A3=1 B3=0 C3=1 {words}\nM0\nM30");
        let (ch, samples) = run("mill5-head-ca", &program);
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{words}: {:?}", s.alarms);
        let o = head_orientation(a_end, c_travel);
        assert!(close3(o, [h, 0.0, h], 1e-12));
        let end = [100.0 + 250.0 * h, 0.0, -100.0 + 250.0 * h, a_end, c_travel];
        assert_machine(&s, end);
        // Linear in machine space: every sample is start + u·(end − start) for one u.
        let start = [0.0, 0.0, 150.0, 0.0, 0.0];
        let moving: Vec<&Sample> = samples.iter().filter(|p| (p.axes[0] - 0.0).abs() > 1e-9).collect();
        assert!(moving.len() > 10, "{words}");
        let mut off_line = 0.0f64;
        for p in &moving {
            let u = p.axes[0] / end[0];
            for k in 1..5 {
                let expect = start[k] + u * (end[k] - start[k]);
                assert!((p.axes[k] - expect).abs() < 1e-6, "{words}: axis {k} {} vs {expect}", p.axes[k]);
            }
            off_line = off_line.max(head_tip(&p.axes)[2] - 50.0).max(50.0 - head_tip(&p.axes)[2]);
        }
        // The tip does not follow the Cartesian line in between (it would under CP).
        assert!(off_line > 1.0, "{words}: tip stayed on the line ({off_line})");
    }
}

/// Programming Manual, Job planning, Cartesian PTP travel, generic 5/6-axis transformation:
/// STAT=0 (the default) approaches the rotary-axis positions at the shorter distance from the
/// start positions, STAT=1 those at the greater distance. From A5 C10 the orientation
/// (1, 0, 1)/√2 has C90 A45 at |90 − 10| + |45 − 5| = 120° and C−90 (= 270) A−45 at
/// |−90 − 10| + |−45 − 5| = 150°. The tip X10 Y0 Z20 with 250·(1, 0, 1)/√2 = (176.7767, 0,
/// 176.7767) gives X186.7767 Y0 Z(20 − 150 + 176.7767) = 46.7767 for either solution.
#[test]
fn ptp_stat_picks_the_solution_nearer_to_or_farther_from_the_start() {
    let h = 250.0 * std::f64::consts::FRAC_1_SQRT_2;
    for (stat, a, c) in [("STAT=0", 45.0, 90.0), ("", 45.0, 90.0), ("STAT=1", -45.0, 270.0)] {
        let program = format!(
            "G17 G90 T1 D1\nG0 X0 Y0 Z50 A5 C10\nTRAORI\nPTP\nG1 X10 Y0 Z20 A3=1 B3=0 C3=1 {stat} F2000\nM0\nM30"
        );
        let (ch, _) = run("mill5-head-ca", &program);
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{stat}: {:?}", s.alarms);
        assert_machine(&s, [10.0 + h, 0.0, 20.0 - 150.0 + h, a, c]);
    }
    // From A−5 C−10 the nearer one is the other: C−90 A−45 (120°) for STAT=0.
    let program =
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 A-5 C-10\nTRAORI\nPTP\nG1 X10 Y0 Z20 A3=1 B3=0 C3=1 STAT=0 F2000\nM0\nM30";
    let (ch, _) = run("mill5-head-ca", program);
    assert_machine(&ch.snapshot(), [10.0 + h, 0.0, 20.0 - 150.0 + h, -45.0, -90.0]);
}

#[test]
fn ptp_is_refused_with_radius_compensation_and_cp_keeps_the_path() {
    let (ch, _) = run("mill5-head-ca", &format!("{START}PTP G41\nX10\nX20\nM30"));
    assert_eq!(ch.snapshot().alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [10753]);
    // PTPG0 leaves G1 blocks on the Cartesian path.
    let (ch, samples) = run("mill5-head-ca", &format!("{START}PTPG0\nX100 A30\nM0\nM30"));
    assert_eq!(ch.snapshot().status, Status::Stopped);
    for p in samples.iter().filter(|p| p.axes[3] > 1e-9) {
        let tip = head_tip(&p.axes);
        assert!(tip[1].abs() < 1e-6 && (tip[2] - 50.0).abs() < 1e-6, "tip {tip:?}");
    }
}

/// LEAD and TILT against the path tangent and the surface normal (+Z): travelling +X, LEAD=20
/// leans the tool 20° forward, o = (sin 20°, 0, cos 20°), the head at A20 C90; TILT=20 turns it
/// about the tangent, o = Rx(20°)·z = (0, −sin 20°, cos 20°), the head at A20 C0. Under ORIPATH
/// the next block (travelling +Y) keeps the lead: o = (0, sin 20°, cos 20°), A20 C180.
#[test]
fn lead_and_tilt_orient_the_tool_against_the_path() {
    let (s20, c20) = 20f64.to_radians().sin_cos();
    let (ch, _) = run("mill5-head-ca", &format!("{START}C80\nLEAD=20 X100\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert_machine(&s, [100.0 + 250.0 * s20, 0.0, -100.0 + 250.0 * c20, 20.0, 90.0]);

    let (ch, _) = run("mill5-head-ca", &format!("{START}TILT=20 X100\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert_machine(&s, [100.0, -250.0 * s20, -100.0 + 250.0 * c20, 20.0, 0.0]);

    let (ch, samples) = run("mill5-head-ca", &format!("{START}C80\nORIPATH\nLEAD=20 X100\nY100\nM0\nM30"));
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert_machine(&s, [100.0, 100.0 + 250.0 * s20, -100.0 + 250.0 * c20, 20.0, 180.0]);
    // The tip stays on the programmed lines throughout.
    for p in samples.iter().filter(|p| p.axes[3] > 1e-9) {
        let tip = head_tip(&p.axes);
        assert!((tip[2] - 50.0).abs() < 1e-6 && (tip[1].abs() < 1e-6 || (tip[0] - 100.0).abs() < 1e-6), "tip {tip:?}");
    }
}

/// ORIPATH holds LEAD/TILT relative to the path inside the block (Programming Manual,
/// orientation relative to the path). On the CCW quarter circle about (0, 0) of radius 40 from
/// (40, 0) to (0, 40) the tangent at angle a is t = (−sin a, cos a, 0); with LEAD=20 TILT=0 and
/// the normal +Z the tool is o = (−sin a·sin 20°, cos a·sin 20°, cos 20°) at every point:
/// o·t = sin 20° = 0.342020, o_z = cos 20° = 0.939693 (a great circle between the ends would
/// give 0.249 and 0.968 mid-arc).
#[test]
fn oripath_holds_lead_and_tilt_at_every_point_of_an_arc() {
    let program = "G17 G90 T1 D1\nG0 X40 Y-10 Z10 A20 C90\nTRAORI\nORIWKS\nG0 X40 Y-10 Z10\nORIPATH\n\
                   G1 X40 Y0 Z10 LEAD=20 TILT=0 F2000\nG3 X0 Y40 CR=40 LEAD=20 TILT=0\nM0\nM30";
    let (ch, samples) = run_with("mill5-head-ca", "$MC_ORI_IPO_WITH_G_CODE=1", program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let (s20, c20) = 20f64.to_radians().sin_cos();
    let mut angles = Vec::new();
    for p in &samples {
        let tip = head_tip(&p.axes);
        // On the arc: 40 from the centre at Z10, Y ≥ 0 (the line before it runs at X40, Y < 0).
        if (tip[0].hypot(tip[1]) - 40.0).abs() > 1e-6 || (tip[2] - 10.0).abs() > 1e-6 || tip[1] < -1e-9 {
            continue;
        }
        let a = tip[1].atan2(tip[0]);
        let t = [-a.sin(), a.cos(), 0.0];
        let o = head_orientation(p.axes[3], p.axes[4]);
        let along = o[0] * t[0] + o[1] * t[1] + o[2] * t[2];
        assert!((along - s20).abs() < 1e-6 && (o[2] - c20).abs() < 1e-6, "at {:.2}°: o {o:?}", a.to_degrees());
        angles.push(a.to_degrees());
    }
    // Checked over the whole arc, not only at its ends: samples in every tenth of it.
    for tenth in 0..9 {
        let (lo, hi) = (tenth as f64 * 9.0, tenth as f64 * 9.0 + 9.0);
        assert!(angles.iter().any(|&a| a > lo && a < hi), "no sample between {lo}° and {hi}°: {angles:?}");
    }
    // The end: tangent −X, o = (−sin 20°, 0, cos 20°) = head A20 C−90 (= 270).
    assert_machine(&s, [-250.0 * s20, 40.0, 10.0 - 150.0 + 250.0 * c20, 20.0, 270.0]);
}

#[test]
fn lead_beyond_md21090_is_refused() {
    let (ch, _) = run("mill5-head-ca", &format!("{START}LEAD=70 X100\nM30"));
    assert_eq!(ch.snapshot().alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [14113]);
}

/// From A10 C0 to the orientation of A10 C170 the great circle passes 0.87° beside the pole
/// (+Z), inside TRAFO5_NON_POLE_LIMIT (2°). Moving the end onto the start's meridian (the Y-Z
/// plane) changes it by asin(sin 170°·sin 10°) = 1.73°, inside TRAFO5_POLE_LIMIT (2°): the
/// orientation goes exactly through the pole, C stays at 0 and A ends at −asin(y)
/// of the moved end. With POLE_LIMIT 1° the programmed end is kept and C turns to 170°.
#[test]
fn a_great_circle_near_the_pole_goes_through_it() {
    let o = head_orientation(10.0, 170.0);
    let program = format!("{START}A10\nORIWKS\nA3={} B3={} C3={}\nM0\nM30", o[0], o[1], o[2]);
    let (ch, samples) = run("mill5-head-ca", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let n = o[1].hypot(o[2]);
    let a_end = -(o[1] / n).asin().to_degrees();
    assert!((machine(&s, "A") - a_end).abs() < 1e-6 && machine(&s, "C").abs() < 1e-6, "{:?}", s.machine);
    assert!(a_end < -9.0);
    let tilted = samples.iter().position(|p| (p.axes[3] - 10.0).abs() < 1e-9).expect("reaches A10");
    for p in &samples[tilted..] {
        assert!(p.axes[4].abs() < 1e-9, "C moved: {:?}", p.axes);
        assert!(close3(head_tip(&p.axes), [0.0, 0.0, 50.0], 1e-6), "tip at {:?}", p.axes);
    }

    let (ch, _) = run_with("mill5-head-ca", "$MC_TRAFO5_POLE_LIMIT_1=1", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!((machine(&s, "A") - 10.0).abs() < 1e-6 && (machine(&s, "C") - 170.0).abs() < 1e-6, "{:?}", s.machine);
}
