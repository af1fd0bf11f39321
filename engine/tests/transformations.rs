//! Kinematic transformations (TRANSMIT, TRACYL, TRAANG) run through a whole channel on the
//! manual's example machines. Expected machine positions are worked out here with simpler
//! formulas (polar coordinates, unrolled arc length, a 2×2 linear system), not with the
//! engine's own code.

use nctwin_engine::kinematics::{self, ActiveTrafo, SelectArgs};
use nctwin_engine::machine_data::{MachineConfig, MachineData, presets};
use nctwin_engine::{Channel, Snapshot, Status};
use proptest::prelude::*;

const MAX_TICKS: usize = 2_000_000;

/// One IPO cycle as seen from outside: machine positions by channel axis and the block shown.
struct Sample {
    axes: Vec<f64>,
    line: Option<u32>,
}

fn run(preset: &str, md: &str, program: &str) -> (Channel, Vec<Sample>) {
    let mut ch = Channel::from_preset(preset, md).unwrap();
    ch.run_program(program).unwrap();
    let mut samples = Vec::new();
    while ch.is_busy() {
        ch.step();
        let s = ch.snapshot();
        samples.push(Sample { axes: ch.axis_positions().to_vec(), line: s.block.map(|b| b.line) });
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    (ch, samples)
}

fn pos(list: &[(String, f64)], name: &str) -> f64 {
    list.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name} in {list:?}")).1
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    pos(&s.machine, name)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// Angle difference modulo 360°, in −180..180.
fn angle_diff(a: f64, b: f64) -> f64 {
    (a - b + 180.0).rem_euclid(360.0) - 180.0
}

fn alarm_numbers(s: &Snapshot) -> Vec<u32> {
    s.alarms.iter().map(|a| a.number).collect()
}

/// Polar coordinates of a face point: radial axis = distance from the centre, C = polar angle
/// (TRANSMIT with no offsets, ROT_SIGN_IS_PLUS = TRUE).
fn polar(x: f64, y: f64) -> (f64, f64) {
    (x.hypot(y), y.atan2(x).to_degrees())
}

// ---------------------------------------------------------------------------------------------
// TRANSMIT
// ---------------------------------------------------------------------------------------------

/// The manual's TRANSMIT example (Transformations FM, M1 §2.1.5) without the parts this product
/// does not model yet (ROT/ATRANS frames, G41 with OFFN): a square on the face, T1 of length 30
/// along Z.
const TRANSMIT_SQUARE: &str = "\
N10 T1 D1 G17 G90 F5000 G94
N20 G0 X20 Z10
N30 TRANSMIT
N40 G1 X10 Y-10
N50 X-10
N60 Y10
N70 X10
N80 Y-10
N90 G0 Z20
N100 TRAFOOF
N110 G0 X20 Z10
N120 M30";

#[test]
fn transmit_mills_a_square_on_the_face_with_radial_axis_and_c() {
    let (ch, samples) = run("transmit-example", "", TRANSMIT_SQUARE);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert_eq!(s.transformation, None);
    // After TRAFOOF: X20, Z10 + tool length 30; C stays where the square left it (at (10, −10)).
    assert!(close(machine(&s, "XM"), 20.0, 1e-9));
    assert!(close(machine(&s, "ZM"), 40.0, 1e-9));
    assert!(close(angle_diff(machine(&s, "CM"), -45.0), 0.0, 1e-6), "{}", machine(&s, "CM"));

    // Channel axes: XC, C, ZC, ASC. Every sample of a square edge (text lines 5..8 = N50..N80)
    // lies on that edge.
    let edge = |line: u32| -> Option<(char, f64)> {
        match line {
            5 => Some(('y', -10.0)),
            6 => Some(('x', -10.0)),
            7 => Some(('y', 10.0)),
            8 => Some(('x', 10.0)),
            _ => None,
        }
    };
    let mut checked = 0;
    for s in &samples {
        let Some((axis, value)) = s.line.and_then(edge) else { continue };
        let (r, c) = (s.axes[0], s.axes[1].to_radians());
        let (x, y) = (r * c.cos(), r * c.sin());
        let v = if axis == 'x' { x } else { y };
        assert!(close(v, value, 1e-6), "line {:?}: ({x}, {y})", s.line);
        checked += 1;
    }
    assert!(checked > 100, "{checked} samples checked");
}

#[test]
fn transmit_checkpoints_follow_the_polar_formula() {
    // Stop at each corner (M0) and compare with the polar coordinates of the corner.
    let program = "T1 D1 G17 F5000\nG0 X20 Z10\nTRANSMIT\nG1 X10 Y-10\nM0\nX-10\nM0\nY10\nM0\nM30";
    let mut ch = Channel::from_preset("transmit-example", "").unwrap();
    ch.run_program(program).unwrap();
    for (x, y) in [(10.0, -10.0), (-10.0, -10.0), (-10.0, 10.0)] {
        while ch.is_busy() {
            ch.step();
        }
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
        let (r, c) = polar(x, y);
        assert!(close(machine(&s, "XM"), r, 1e-9), "{x},{y}: XM {}", machine(&s, "XM"));
        assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-9), "{x},{y}: CM {}", machine(&s, "CM"));
        assert!(close(machine(&s, "ZM"), 40.0, 1e-9));
        // BCS shows the tool tip in X, Y, Z while TRANSMIT is active.
        assert!(close(pos(&s.basic, "X"), x, 1e-9) && close(pos(&s.basic, "Y"), y, 1e-9), "{:?}", s.basic);
        assert!(close(pos(&s.basic, "Z"), 10.0, 1e-9));
        let t = s.transformation.clone().expect("TRANSMIT active");
        assert_eq!((t.name.as_str(), t.trafo_type, t.index), ("TRANSMIT", 256, 1));
        ch.start().unwrap();
    }
}

#[test]
fn c_cannot_be_programmed_while_transmit_is_active() {
    let (ch, _) = run("transmit-example", "", "G0 X20\nTRANSMIT\nC90\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [12550]);
    // Y exists only with TRANSMIT.
    let (ch, _) = run("transmit-example", "", "G0 X20 Y10\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [12550]);
}

#[test]
fn a_missing_data_set_raises_14401_and_a_turning_spindle_14092() {
    let (ch, _) = run("transmit-example", "", "TRANSMIT(2)\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [14401]);
    let (ch, _) = run("transmit-example", "", "M3 S100\nTRANSMIT\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [14092]);
}

#[test]
fn transmit_takes_over_the_angle_of_the_stopped_spindle() {
    // The spindle turns, stops; TRANSMIT waits for standstill and starts from its angle.
    let program = "M3 S60\nG4 F1\nM5\nTRANSMIT\nG1 F1000 X20 Y0\nM0\nM30";
    let mut ch = Channel::from_preset("transmit-example", "").unwrap();
    ch.run_program(program).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    // X20 Y0 is polar angle 0: C returned to 0 (modulo 360) whatever the spindle's angle was.
    assert!(close(angle_diff(machine(&s, "CM"), 0.0), 0.0, 1e-9), "{}", machine(&s, "CM"));
    assert!(close(machine(&s, "XM"), 20.0, 1e-9));
}

#[test]
fn a_line_through_the_pole_reverses_the_radial_axis_and_keeps_c() {
    let (ch, samples) = run("transmit-example", "", "G0 X10\nTRANSMIT\nG1 F2000 X-10 Y0\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(close(machine(&s, "XM"), -10.0, 1e-9));
    for s in &samples {
        assert!(close(s.axes[1], 0.0, 1e-9), "C moved: {}", s.axes[1]);
    }
}

#[test]
fn pole_side_fix_rotates_c_by_180_degrees_in_the_pole() {
    let md = "$MC_TRANSMIT_POLE_SIDE_FIX_1=1";
    let (ch, samples) = run("transmit-example", md, "G0 X10\nTRANSMIT\nG1 F2000 X-10 Y0\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    // The radial axis stays in its positive range; C has turned half a revolution.
    assert!(close(machine(&s, "XM"), 10.0, 1e-9), "{}", machine(&s, "XM"));
    assert!(close(angle_diff(machine(&s, "CM"), 180.0), 0.0, 1e-9), "{}", machine(&s, "CM"));
    assert!(samples.iter().all(|s| s.axes[0] >= -1e-9));
    // The rotation happened with X at the pole.
    let turning: Vec<&Sample> =
        samples.windows(2).filter(|w| (w[1].axes[1] - w[0].axes[1]).abs() > 1e-9).map(|w| &w[1]).collect();
    assert!(!turning.is_empty() && turning.iter().all(|s| s.axes[0].abs() < 1e-6));
}

#[test]
fn a_corner_in_the_pole_turns_c_before_leaving_it() {
    let (ch, samples) = run("transmit-example", "", "G0 X10\nTRANSMIT\nG1 F2000 X0 Y0\nX0 Y10\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let (r, c) = polar(0.0, 10.0);
    // Leaving along +Y: either C = 90° with X positive, or C = −90° with X negative; the
    // product prefers the positive side on a tie.
    assert!(close(machine(&s, "XM"), r, 1e-9) && close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-9));
    // No jump of C between two cycles beyond its velocity limit (100 rpm = 600°/s, 4 ms).
    for w in samples.windows(2) {
        assert!((w[1].axes[1] - w[0].axes[1]).abs() <= 600.0 * 0.004 * (1.0 + 1e-9));
    }
}

#[test]
fn the_working_area_limitation_rejects_the_block_with_21619() {
    // A base tool 5 mm off the radial line leaves a cylinder of radius 5 unmachinable.
    let md = "$MC_TRANSMIT_BASE_TOOL_1[1]=5";
    let (ch, _) = run("transmit-example", md, "G0 X20\nTRANSMIT\nG1 F1000 X10 Y3\nX-10 Y3\nM30");
    let s = ch.snapshot();
    assert_eq!(alarm_numbers(&s), [21619]);
    assert_eq!(s.alarms[0].line, Some(4));
    // The block before it was executed, the rejected one not at all: r never fell below 5.
    let (x, y) = (pos(&s.basic, "X"), pos(&s.basic, "Y"));
    assert!(close(x, 10.0, 1e-9) && close(y, 3.0, 1e-9), "{x} {y}");
}

#[test]
fn a_lateral_offset_follows_the_reference_test_vector() {
    // REFERENCE §10: e = 5, target (30, −40) ⇒ qx = +49.749, φ = −58.869° (positive side).
    let md = "$MC_TRANSMIT_BASE_TOOL_1[1]=5";
    let (ch, _) = run("transmit-example", md, "G0 X60\nTRANSMIT\nG1 F3000 X30 Y-40\nM0\nM30");
    let s = ch.snapshot();
    let (r, e) = (50.0f64, 5.0f64);
    let qx = (r * r - e * e).sqrt();
    let phi = (-40.0f64).atan2(30.0) - e.atan2(qx);
    assert!(close(machine(&s, "XM"), qx, 1e-9), "{}", machine(&s, "XM"));
    assert!(close(angle_diff(machine(&s, "CM"), phi.to_degrees()), 0.0, 1e-9), "{}", machine(&s, "CM"));
    assert!(close(qx, 49.749, 1e-3) && close(phi.to_degrees(), -58.869, 1e-3));
}

/// Velocities and accelerations of every machine axis over a run.
fn check_limits(samples: &[Sample], limits: &[(f64, f64)], dt: f64, overload: f64) {
    let vel: Vec<Vec<f64>> =
        samples.windows(2).map(|w| w[1].axes.iter().zip(&w[0].axes).map(|(b, a)| (b - a) / dt).collect()).collect();
    for v in &vel {
        for (k, &(vmax, _)) in limits.iter().enumerate() {
            assert!(v[k].abs() <= vmax * (1.0 + 1e-6), "axis {k}: {} > {vmax}", v[k]);
        }
    }
    for w in vel.windows(2) {
        for (k, &(_, amax)) in limits.iter().enumerate() {
            let a = (w[1][k] - w[0][k]).abs() / dt;
            assert!(a <= amax * overload * (1.0 + 1e-6), "axis {k}: accel {a} > {}", amax * overload);
        }
    }
}

#[test]
fn near_the_pole_the_rotary_axis_limits_the_feed() {
    // A line 0.5 mm past the centre: C turns half a revolution within a few millimetres.
    let program = "G0 X20\nTRANSMIT\nG1 F6000 X20 Y0.5\nX-20 Y0.5\nM0\nM30";
    let (ch, samples) = run("transmit-example", "", program);
    assert_eq!(ch.snapshot().status, Status::Stopped, "{:?}", ch.snapshot().alarms);
    // XM 15000 mm/min, CM 100 rpm; accelerations: defaults 1 m/s² and 2.77 rev/s².
    let limits = [(250.0, 1000.0), (600.0, 2.77 * 360.0), (250.0, 1000.0)];
    check_limits(&samples, &limits, 0.004, 1.2);
    // At F6000 (100 mm/s) 40 mm take 0.4 s; C at most 600°/s needs far longer near the pole.
    let cycles = samples.iter().filter(|s| s.line == Some(4)).count();
    assert!(cycles as f64 * 0.004 > 0.6, "{cycles} cycles");
}

// ---------------------------------------------------------------------------------------------
// TRACYL
// ---------------------------------------------------------------------------------------------

#[test]
fn tracyl_unrolls_y_onto_the_working_diameter() {
    // Working diameter 40: an arc length of Y on the surface is C = Y / (π·40) · 360°.
    let program = "G0 X20 Y0 Z0\nTRACYL(40)\nG1 F1000 Y31.4159265358979 Z-10\nM0\nY-62.8318530717959\nM0\nM30";
    let mut ch = Channel::from_preset("tracyl-xyzc", "").unwrap();
    ch.run_program(program).unwrap();
    for (y, z) in [(31.4159265358979, -10.0), (-62.8318530717959, -10.0)] {
        while ch.is_busy() {
            ch.step();
        }
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
        let c = y / (std::f64::consts::PI * 40.0) * 360.0;
        assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-6), "C {} vs {c}", machine(&s, "CM"));
        assert!(close(machine(&s, "ZM"), z, 1e-9) && close(machine(&s, "XM"), 20.0, 1e-9));
        // The real Y axis keeps its position (no groove-wall offset without OFFN).
        assert!(close(machine(&s, "YM"), 0.0, 1e-12));
        assert!(close(pos(&s.basic, "Y"), y, 1e-9), "{:?}", s.basic);
        let t = s.transformation.clone().expect("TRACYL active");
        assert_eq!((t.name.as_str(), t.trafo_type, t.index), ("TRACYL", 513, 1));
        ch.start().unwrap();
    }
}

#[test]
fn tracyl_turns_c_continuously_over_several_revolutions() {
    // 3 turns on d = 20: Y = 3·π·20; C ends at 1080° (shown modulo 360 = 0).
    let program = "G0 X10\nTRACYL(20)\nG1 F3000 Y188.495559215388\nM0\nM30";
    let (ch, samples) = run("tracyl-xyzc", "", program);
    let c_max = samples.iter().map(|s| s.axes[3]).fold(f64::MIN, f64::max);
    assert!(close(c_max, 1080.0, 1e-6), "{c_max}");
    assert!(close(angle_diff(machine(&ch.snapshot(), "CM"), 0.0), 0.0, 1e-6));
}

/// Groove-wall offset (type 513): the centre line of a groove along Z and then around the
/// periphery, cut with T1 (radius 6) and OFFN = 8 (groove width 16). The tool centre runs
/// `OFFN − r` = 2 beside the centre line; along Z that offset is across the periphery and is
/// travelled by the real Y axis (C stays on the centre line), around the periphery it is along Z.
const GROOVE: &str = "T1 D1\nG0 X20 Y0 Z10\nTRACYL(40)\nG19 G1 F1000 G41 OFFN=8 Y0 Z0\nZ-30\n";

#[test]
fn tracyl_groove_wall_offset_keeps_c_on_the_centre_line() {
    let program = format!("{GROOVE}M0\nM30");
    let (ch, samples) = run("tracyl-xyzc", "", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    // G41 travelling −Z in the Y-Z plane (seen from +X): left is +Y.
    assert!(close(angle_diff(machine(&s, "CM"), 0.0), 0.0, 1e-6), "C {}", machine(&s, "CM"));
    assert!(close(machine(&s, "YM"), 2.0, 1e-9), "YM {}", machine(&s, "YM"));
    assert!(close(machine(&s, "ZM"), -30.0, 1e-9));
    // All along the groove (away from its ends) C and YM hold still: the wall is parallel.
    let (y, z, c) = (1, 2, 3);
    let inside: Vec<&Sample> = samples.iter().filter(|p| p.axes[z] < -1.0 && p.axes[z] > -29.0).collect();
    assert!(!inside.is_empty());
    for p in inside {
        assert!(close(p.axes[y], 2.0, 1e-9) && close(angle_diff(p.axes[c], 0.0), 0.0, 1e-6), "{:?}", p.axes);
    }
}

/// A radial infeed (X only) inside the groove is a block without motion in the compensation
/// plane: it runs at the corner point with the real Y axis holding the wall offset (2), and the
/// groove goes on to Z−60 on the same wall.
#[test]
fn tracyl_groove_wall_offset_holds_y_through_an_infeed() {
    let program = format!("{GROOVE}X18\nZ-60\nM0\nM30");
    let (ch, samples) = run("tracyl-xyzc", "", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    // XM ends where X18 puts the radial axis with the tool's length on it.
    let (x, y, z) = (0, 1, 2);
    let x_end = machine(&s, "XM");
    assert!(x_end > 20.0 + 1e-6, "{x_end}");
    let infeed: Vec<&Sample> = samples.iter().filter(|p| p.axes[x] > 20.0 + 1e-6 && p.axes[x] < x_end - 1e-6).collect();
    assert!(!infeed.is_empty());
    for p in infeed {
        assert!(close(p.axes[y], 2.0, 1e-9) && close(p.axes[z], -30.0, 1e-9), "{:?}", p.axes);
    }
    assert!(close(machine(&s, "YM"), 2.0, 1e-9) && close(machine(&s, "ZM"), -60.0, 1e-9));
}

#[test]
fn tracyl_groove_wall_offset_around_the_periphery_moves_z_and_hands_back_y() {
    // Around a quarter of the circumference on d = 40 (arc length 10π): the offset now lies
    // along Z (left of +Y is +Z), so Z = −28, YM returns to 0 and C = 90°.
    let program = format!("{GROOVE}Y31.4159265358979\nM0\nM30");
    let (ch, _) = run("tracyl-xyzc", "", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(close(angle_diff(machine(&s, "CM"), 90.0), 0.0, 1e-6), "C {}", machine(&s, "CM"));
    assert!(close(machine(&s, "YM"), 0.0, 1e-9), "YM {}", machine(&s, "YM"));
    assert!(close(machine(&s, "ZM"), -28.0, 1e-9), "ZM {}", machine(&s, "ZM"));
}

#[test]
fn tracyl_groove_wall_offset_on_an_arc_splits_along_the_radius() {
    // Centre line: arc about (Y20, Z0) of radius 20 from (0, 0) counter-clockwise to the 225°
    // point (20 − 10√2, −10√2). G41 lies towards the centre: the tool centre is 2 inside, along
    // the unit radial (cos 45°, sin 45°); its periphery share √2 is travelled by YM and C
    // follows the centre line's Y = 20 − 10√2 on d = 40.
    let r2 = std::f64::consts::SQRT_2;
    let (yc, zc) = (20.0 - 10.0 * r2, -10.0 * r2);
    let program =
        format!("T1 D1\nG0 X20 Y0 Z10\nTRACYL(40)\nG19 G1 F1000 G41 OFFN=8 Y0 Z0\nG3 Y={yc} Z={zc} J20 K0\nM0\nM30");
    let (ch, _) = run("tracyl-xyzc", "", &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let c = yc / 20.0 * 180.0 / std::f64::consts::PI;
    assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-6), "C {} vs {c}", machine(&s, "CM"));
    assert!(close(machine(&s, "YM"), r2, 1e-9), "YM {}", machine(&s, "YM"));
    assert!(close(machine(&s, "ZM"), zc + r2, 1e-9), "ZM {}", machine(&s, "ZM"));
}

#[test]
fn tracyl_groove_wall_with_negative_offn_cuts_the_other_wall() {
    let program = GROOVE.replace("OFFN=8", "OFFN=-8") + "M0\nM30";
    let (ch, _) = run("tracyl-xyzc", "", &program);
    let s = ch.snapshot();
    assert!(close(machine(&s, "YM"), -2.0, 1e-9), "YM {}", machine(&s, "YM"));
    assert!(close(angle_diff(machine(&s, "CM"), 0.0), 0.0, 1e-6));
}

#[test]
fn tracyl_groove_wall_refuses_a_tool_wider_than_the_groove() {
    let program = GROOVE.replace("OFFN=8", "OFFN=5") + "M30";
    let (ch, _) = run("tracyl-xyzc", "", &program);
    assert_eq!(alarm_numbers(&ch.snapshot()), [12560]);
}

#[test]
fn tracyl_512_offsets_by_rotation_instead() {
    // Without groove-wall offset the whole compensation (r + OFFN = 6 + 1) turns C.
    let md = "$MC_TRAFO_TYPE_1=512\n$MC_TRAFO_AXES_IN_1[3]=0";
    let program = GROOVE.replace("OFFN=8", "OFFN=1") + "M0\nM30";
    let (ch, _) = run("tracyl-xyzc", md, &program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let c = 7.0 / 20.0 * 180.0 / std::f64::consts::PI;
    assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-6), "C {} vs {c}", machine(&s, "CM"));
    assert!(close(machine(&s, "YM"), 0.0, 1e-12));
}

#[test]
fn tracyl_needs_a_working_diameter_above_1() {
    let (ch, _) = run("tracyl-xyzc", "", "TRACYL(1)\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [12560]);
    let (ch, _) = run("tracyl-xyzc", "", "TRACYL(40)\nCC10\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [12550]);
}

// ---------------------------------------------------------------------------------------------
// TRAANG
// ---------------------------------------------------------------------------------------------

/// Machine positions of the inclined axis MU (unit vector (cos α, sin α) in X/Z) and the
/// longitudinal axis MZ that reach Cartesian (x, z): Cramer's rule on
/// `MU·cos α = x`, `MU·sin α + MZ = z`.
fn traang_axes(alpha_deg: f64, x: f64, z: f64) -> (f64, f64) {
    let (s, c) = alpha_deg.to_radians().sin_cos();
    let det = c * 1.0 - 0.0 * s;
    let mu = (x * 1.0 - 0.0 * z) / det;
    let mz = (c * z - s * x) / det;
    (mu, mz)
}

#[test]
fn traang_moves_the_inclined_and_the_parallel_axis() {
    for (select, alpha) in [("TRAANG", 45.0f64), ("TRAANG(30)", 30.0), ("TRAANG(-20,1)", -20.0), ("TRAANG(,1)", 45.0)] {
        let program = format!("G0 X0 Z0\n{select}\nG1 F2000 X10 Z-5\nM0\nM30");
        let (ch, samples) = run("traang-grinder", "", &program);
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{select}: {:?}", s.alarms);
        let (mu, mz) = traang_axes(alpha, 10.0, -5.0);
        assert!(close(machine(&s, "MU"), mu, 1e-9) && close(machine(&s, "MZ"), mz, 1e-9), "{select}: {:?}", s.machine);
        assert_eq!(s.transformation.as_ref().map(|t| t.trafo_type), Some(1024));
        // The Cartesian path is a straight line: every sample satisfies the line equation.
        let (sn, cs) = alpha.to_radians().sin_cos();
        for smp in samples.iter().filter(|s| s.line == Some(3)) {
            let (x, z) = (smp.axes[0] * cs, smp.axes[1] + smp.axes[0] * sn);
            assert!(close(z, -0.5 * x, 1e-9), "{select}: ({x}, {z})");
        }
    }
}

#[test]
fn traang_rejects_angles_outside_its_range() {
    for select in ["TRAANG(0)", "TRAANG(90)", "TRAANG(-95)"] {
        let (ch, _) = run("traang-grinder", "", &format!("{select}\nM30"));
        assert_eq!(alarm_numbers(&ch.snapshot()), [12560], "{select}");
    }
}

#[test]
fn traang_keeps_the_velocity_reserve_on_the_parallel_axis() {
    // A pure Z move at high feed: only MZ moves; it may use 80 % of its 200 mm/s.
    let (ch, samples) = run("traang-grinder", "", "TRAANG\nG1 F60000 Z200\nM0\nM30");
    assert_eq!(ch.snapshot().status, Status::Stopped);
    let vmax = samples.windows(2).map(|w| (w[1].axes[1] - w[0].axes[1]).abs() / 0.004).fold(0.0, f64::max);
    assert!(vmax <= 160.0 * (1.0 + 1e-9) && vmax > 150.0, "{vmax}");
}

// ---------------------------------------------------------------------------------------------
// Selection rules
// ---------------------------------------------------------------------------------------------

/// The TRANSMIT machine with a second data set: TRACYL 512 on the same axes.
const TRACYL_ON_TRANSMIT: &str = "\
$MC_TRAFO_TYPE_2=512
$MC_TRAFO_AXES_IN_2[0]=1
$MC_TRAFO_AXES_IN_2[1]=2
$MC_TRAFO_AXES_IN_2[2]=3
$MC_TRAFO_GEOAX_ASSIGN_TAB_2[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_2[1]=2
$MC_TRAFO_GEOAX_ASSIGN_TAB_2[2]=3";

#[test]
fn selecting_one_transformation_deselects_the_other_and_reset_ends_both() {
    let program = "G0 X20\nTRANSMIT\nG1 F1000 X20 Y5\nTRACYL(40)\nM0\nTRAFOOF\nM0\nM30";
    let mut ch = Channel::from_preset("transmit-example", TRACYL_ON_TRANSMIT).unwrap();
    ch.run_program(program).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let t = s.transformation.clone().expect("TRACYL active");
    assert_eq!((t.name.as_str(), t.trafo_type, t.index), ("TRACYL", 512, 2));
    // Machine unchanged by the switch: XM = r of (20, 5), C its polar angle.
    let (r, c) = polar(20.0, 5.0);
    assert!(close(machine(&s, "XM"), r, 1e-9) && close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-9));
    // In TRACYL's BCS, Y is the arc length of C on d = 40.
    assert!(close(pos(&s.basic, "Y"), c.to_radians() * 20.0, 1e-9), "{:?}", s.basic);
    ch.start().unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert_eq!(ch.snapshot().transformation, None);
    ch.reset();
    assert_eq!(ch.snapshot().transformation, None);
}

#[test]
fn reset_deselects_the_transformation_and_the_axes_stay() {
    let mut ch = Channel::from_preset("transmit-example", "").unwrap();
    ch.run_program("G0 X20\nTRANSMIT\nG1 F1000 X0 Y20\nM0\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let before = ch.snapshot().machine.clone();
    ch.reset();
    let s = ch.snapshot();
    assert_eq!(s.transformation, None);
    assert_eq!(s.machine, before);
    // Without TRANSMIT the BCS is the machine again: X is the radial axis.
    assert!(close(pos(&s.basic, "X"), 20.0, 1e-9));
    // A new program starts from there.
    ch.run_program("G0 X30\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(close(machine(&ch.snapshot(), "XM"), 30.0, 1e-9));
}

#[test]
fn transformations_are_deterministic() {
    let a = run("transmit-example", "", TRANSMIT_SQUARE).1;
    let b = run("transmit-example", "", TRANSMIT_SQUARE).1;
    assert!(a.len() == b.len() && a.iter().zip(&b).all(|(p, q)| p.axes == q.axes));
}

#[test]
fn bad_transformation_data_is_rejected_with_its_line() {
    let mut md = MachineData::default();
    md.apply_text(presets::find("transmit-example").unwrap().text).unwrap();
    // The rotary role must be a rotary axis.
    let e = md.apply_text("$MC_TRAFO_AXES_IN_1[1]=3\n$MC_TRAFO_AXES_IN_1[2]=2").unwrap_err();
    assert!(e.message.contains("rotary"), "{e}");
    let e = md.apply_text("$MC_TRAFO_TYPE_3=2048").unwrap_err();
    assert_eq!(e.line, Some(1));
}

// ---------------------------------------------------------------------------------------------
// Round trips
// ---------------------------------------------------------------------------------------------

fn config(preset: &str, md: &str) -> MachineConfig {
    let mut data = MachineData::default();
    data.apply_text(presets::find(preset).unwrap().text).unwrap();
    data.apply_text(md).unwrap()
}

fn active(cfg: &MachineConfig, set: usize, args: SelectArgs, tool: [f64; 3]) -> ActiveTrafo {
    let trafo = kinematics::build(&cfg.trafos[set], cfg, &args).unwrap();
    ActiveTrafo { trafo, tool, number: cfg.trafos[set].number }
}

fn axes(values: &[f64]) -> [f64; 20] {
    let mut v = [0.0; 20];
    v[..values.len()].copy_from_slice(values);
    v
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, .. ProptestConfig::default() })]

    /// Machine → BCS → machine returns the same machine position (tolerance 1e-9 mm / 1e-9°)
    /// for both pole sides, lateral offsets and tool lengths.
    #[test]
    fn transmit_round_trips(x in -150.0f64..150.0, c in -720.0f64..720.0, z in -100.0f64..100.0,
                            e in -8.0f64..8.0, lx in -20.0f64..20.0, lz in 0.0f64..50.0, fix in 0u8..3) {
        let cfg = config("transmit-example", &format!("$MC_TRANSMIT_BASE_TOOL_1[1]={e}\n$MC_TRANSMIT_POLE_SIDE_FIX_1={fix}"));
        let t = active(&cfg, 0, SelectArgs::default(), [lx, 0.0, lz]);
        let qx = x - lx;
        prop_assume!(qx.hypot(e) > 1e-3);
        prop_assume!(fix == 0 || (fix == 1) == (qx > 0.0));
        let m = axes(&[x, c, z, 0.0]);
        let b = t.forward(&m);
        let back = t.inverse(&b, &m).unwrap();
        prop_assert!((back[0] - m[0]).abs() < 1e-9 && (back[1] - m[1]).abs() < 1e-9 && (back[2] - m[2]).abs() < 1e-9,
            "{m:?} -> {b:?} -> {back:?}");
    }

    /// BCS → machine → BCS reproduces the point (1e-9 mm) wherever it is reachable.
    #[test]
    fn transmit_inverse_then_forward(x in -150.0f64..150.0, y in -150.0f64..150.0, e in -8.0f64..8.0, c0 in -360.0f64..360.0) {
        let cfg = config("transmit-example", &format!("$MC_TRANSMIT_BASE_TOOL_1[1]={e}"));
        let t = active(&cfg, 0, SelectArgs::default(), [0.0; 3]);
        let b = axes(&[x, y, 5.0]);
        let prev = axes(&[0.0, c0, 0.0]);
        match t.inverse(&b, &prev) {
            Ok(m) => {
                let f = t.forward(&m);
                prop_assert!((f[0] - x).abs() < 1e-9 && (f[1] - y).abs() < 1e-9 && (f[2] - 5.0).abs() < 1e-9);
                prop_assert!((m[1] - c0).abs() <= 180.0 + 1e-9, "C {} not the turn closest to {c0}", m[1]);
            }
            Err(_) => prop_assert!(x.hypot(y) < e.abs()),
        }
    }

    #[test]
    fn tracyl_round_trips(x in 0.0f64..100.0, c in -1000.0f64..1000.0, z in -100.0f64..100.0, d in 1.5f64..300.0,
                          ly in -5.0f64..5.0, ym in -20.0f64..20.0) {
        let cfg = config("tracyl-xyzc", "$MC_TRACYL_ROT_SIGN_IS_PLUS_1=FALSE\n$MC_TRACYL_ROT_AX_OFFSET_1=30");
        let t = active(&cfg, 0, SelectArgs { diameter: Some(d), ..SelectArgs::default() }, [0.0, ly, 0.0]);
        let m = axes(&[x, ym, z, c]);
        let back = t.inverse(&t.forward(&m), &m).unwrap();
        prop_assert!(m.iter().zip(&back).all(|(a, b)| (a - b).abs() < 1e-9), "{m:?} {back:?}");
    }

    /// The chain TRANSMIT → TRAANG: machine → BCS → machine, and the BCS point against the
    /// members' formulas written out (polar coordinates of the slide's Cartesian X).
    #[test]
    fn tracon_round_trips(mu in 1.0f64..200.0, c in -360.0f64..360.0, mz in -200.0f64..200.0, lz in 0.0f64..50.0) {
        let cfg = config("slant-lathe-tracon", "");
        let t = active(&cfg, 2, SelectArgs::default(), [0.0, 0.0, lz]);
        let m = axes(&[mu, c, mz, 0.0]);
        let b = t.forward(&m);
        let (sn, cs) = 30f64.to_radians().sin_cos();
        let (x, z) = (mu * cs, mz + mu * sn);
        let phi = c.to_radians();
        prop_assert!((b[0] - x * phi.cos()).abs() < 1e-9 && (b[1] - x * phi.sin()).abs() < 1e-9, "{b:?}");
        prop_assert!((b[2] - (z - lz)).abs() < 1e-9, "{b:?}");
        let back = t.inverse(&b, &m).unwrap();
        prop_assert!(m[..3].iter().zip(&back[..3]).all(|(a, b)| (a - b).abs() < 1e-9), "{m:?} {back:?}");
    }

    #[test]
    fn traang_round_trips(mu in -300.0f64..300.0, mz in -300.0f64..300.0, alpha in -89.0f64..89.0, lx in -20.0f64..20.0) {
        prop_assume!(alpha.abs() > 0.1);
        let cfg = config("traang-grinder", "$MC_TRAANG_BASE_TOOL_1[0]=3\n$MC_TRAANG_BASE_TOOL_1[2]=-7");
        let t = active(&cfg, 0, SelectArgs { angle: Some(alpha), ..SelectArgs::default() }, [lx, 0.0, 0.0]);
        let m = axes(&[mu, mz, 0.0]);
        let back = t.inverse(&t.forward(&m), &m).unwrap();
        prop_assert!((back[0] - mu).abs() < 1e-9 * (1.0 + mu.abs()) && (back[1] - mz).abs() < 1e-8, "{m:?} {back:?}");
    }
}

#[test]
fn transmit_after_spos_starts_from_the_positioned_spindle() {
    // The manual's example positions the spindle with SPOS before TRANSMIT.
    let (ch, _) = run("transmit-example", "", "G0 X20 Z10\nSPOS=45\nTRANSMIT\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let (x, y) = (20.0 * 45f64.to_radians().cos(), 20.0 * 45f64.to_radians().sin());
    assert!(close(pos(&s.basic, "X"), x, 1e-9) && close(pos(&s.basic, "Y"), y, 1e-9), "{:?}", s.basic);
}

// ---------------------------------------------------------------------------------------------
// Reset transformation and persistent transformation
// ---------------------------------------------------------------------------------------------

/// TRAANG data set 1 of the grinder as the persistent transformation, with the reset mode the
/// manual requires.
const PERSISTENT_TRAANG: &str = "\
$MC_TRAFO_MODE_MASK=1
$MC_TRAFO_RESET_VALUE=1
$MC_RESET_MODE_MASK=1
$MC_GEOAX_CHANGE_RESET=TRUE";

fn transformation_type(ch: &Channel) -> Option<u32> {
    ch.snapshot().transformation.map(|t| t.trafo_type)
}

#[test]
fn a_persistent_transformation_is_active_from_power_on_and_survives_trafoof_and_program_end() {
    let mut ch = Channel::from_preset("traang-grinder", PERSISTENT_TRAANG).unwrap();
    assert_eq!(transformation_type(&ch), Some(1024));
    // Cartesian X/Z from the first block, through TRAFOOF and after M30.
    let (ch2, _) = run("traang-grinder", PERSISTENT_TRAANG, "G0 X10 Z-5\nTRAFOOF\nG0 X20 Z0\nM30");
    let s = ch2.snapshot();
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    let (mu, mz) = traang_axes(45.0, 20.0, 0.0);
    assert!(close(machine(&s, "MU"), mu, 1e-9) && close(machine(&s, "MZ"), mz, 1e-9), "{:?}", s.machine);
    assert_eq!(transformation_type(&ch2), Some(1024));
    ch.reset();
    assert_eq!(transformation_type(&ch), Some(1024));
}

#[test]
fn another_transformation_next_to_a_persistent_one_needs_a_chain() {
    let md = format!(
        "{PERSISTENT_TRAANG}\n$MC_TRAFO_TYPE_2=1024\n$MC_TRAFO_AXES_IN_2[0]=1\n$MC_TRAFO_AXES_IN_2[1]=2\n$MC_TRAFO_AXES_IN_2[2]=0\n$MC_TRAFO_GEOAX_ASSIGN_TAB_2[0]=1\n$MC_TRAFO_GEOAX_ASSIGN_TAB_2[2]=2"
    );
    let (ch, _) = run("traang-grinder", &md, "TRAANG(30,2)\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [14401]);
}

#[test]
fn a_persistent_transformation_needs_the_reset_mode_the_manual_names() {
    for md in [
        "$MC_TRAFO_MODE_MASK=1\n$MC_TRAFO_RESET_VALUE=1",
        "$MC_TRAFO_MODE_MASK=1\n$MC_TRAFO_RESET_VALUE=1\n$MC_GEOAX_CHANGE_RESET=TRUE\n$MC_RESET_MODE_MASK='H81'",
        "$MC_TRAFO_MODE_MASK=1\n$MC_GEOAX_CHANGE_RESET=TRUE",
    ] {
        let err = Channel::from_preset("traang-grinder", md).expect_err(md);
        assert!(err.to_string().contains("14404"), "{md}: {err}");
    }
}

#[test]
fn the_reset_value_selects_a_transformation_at_reset_and_trafoof_still_ends_it() {
    // Stopped at M0: without transformation X and Z are the machine axes MU and MZ themselves.
    let (mut ch, _) = run("traang-grinder", "$MC_TRAFO_RESET_VALUE=1", "TRAFOOF\nG0 X20 Z0\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped);
    assert_eq!(transformation_type(&ch), None);
    assert!(close(machine(&s, "MU"), 20.0, 1e-9), "{:?}", s.machine);
    ch.reset();
    assert_eq!(transformation_type(&ch), Some(1024));
}

#[test]
fn reset_mode_bit_7_keeps_the_active_transformation() {
    let (ch, _) = run("traang-grinder", "$MC_RESET_MODE_MASK='H81'", "TRAANG(30)\nM30");
    assert_eq!(ch.snapshot().status, Status::Idle);
    assert_eq!(transformation_type(&ch), Some(1024));
    let (ch, _) = run("traang-grinder", "", "TRAANG(30)\nM30");
    assert_eq!(transformation_type(&ch), None);
}

// ---------------------------------------------------------------------------------------------
// Chained transformation (TRACON)
// ---------------------------------------------------------------------------------------------

/// The slide of the slant-bed lathe preset: MU inclined by 30° towards Z. Cartesian (x, z) of
/// the slide and MZ: `MU·cos 30° = x`, `MZ + MU·sin 30° = z`.
fn slant(x: f64, z: f64) -> (f64, f64) {
    let (s, c) = 30f64.to_radians().sin_cos();
    (x / c, z - x / c * s)
}

#[test]
fn tracon_chains_transmit_in_front_of_the_persistent_traang() {
    let program = "G0 X20 Z10\nM0\nTRANSMIT\nG1 F1000 X10 Y10\nM0\nTRAFOOF\nG0 X30\nM0\nM30";
    let mut ch = Channel::from_preset("slant-lathe-tracon", "").unwrap();
    ch.run_program(program).unwrap();
    // Under the persistent TRAANG alone; then TRANSMIT's polar radius √200 and angle 45° on the
    // slide; then TRAANG alone again.
    let r = 200f64.sqrt();
    let checks = [(20.0, 10.0, None, "TRAANG"), (r, 10.0, Some(45.0), "TRACON"), (30.0, 10.0, None, "TRAANG")];
    for (x, z, c, name) in checks {
        while ch.is_busy() {
            ch.step();
        }
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{name}: {:?}", s.alarms);
        assert_eq!(s.transformation.as_ref().map(|t| t.name.as_str()), Some(name));
        let (mu, mz) = slant(x, z);
        assert!(close(machine(&s, "MU"), mu, 1e-9) && close(machine(&s, "MZ"), mz, 1e-9), "{name}: {:?}", s.machine);
        if let Some(c) = c {
            assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-9), "{name}: {:?}", s.machine);
        }
        ch.start().unwrap();
    }
}

#[test]
fn tracon_by_number_and_its_parameters() {
    // TRACON(1, 40): the chain with a TRAANG angle of 40° instead of the machine data's 30°.
    let (ch, _) = run("slant-lathe-tracon", "", "TRACON(1,40)\nG1 F1000 X10 Y0 Z5\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert_eq!(s.transformation.clone().map(|t| (t.name, t.trafo_type)), Some(("TRACON".to_string(), 8192)));
    let (sn, cs) = 40f64.to_radians().sin_cos();
    assert!(close(machine(&s, "MU"), 10.0 / cs, 1e-9) && close(machine(&s, "MZ"), 5.0 - 10.0 / cs * sn, 1e-9));
    assert!(close(angle_diff(machine(&s, "CM"), 0.0), 0.0, 1e-9));
    let (ch, _) = run("slant-lathe-tracon", "", "TRACON(2)\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [14401]);
}

#[test]
fn a_chain_needs_traang_as_its_second_member_defined_before_it() {
    for (md, needle) in
        [("$MC_TRACON_CHAIN_1[1]=1", "second member"), ("$MC_TRACON_CHAIN_1[0]=5", "configured before data set 3")]
    {
        let err = Channel::from_preset("slant-lathe-tracon", md).expect_err(md);
        assert!(err.to_string().contains(needle), "{md}: {err}");
    }
}

/// Oblique plunging with TRAANG at 45°: G07 moves only along Z to the start point on the line
/// through the end point along the inclined axis, S = (50, −20 + (50 − 10)·tan 45°) = (50, 20);
/// G05 then plunges with the inclined axis MU alone to (10, −20).
#[test]
fn traang_g07_approaches_and_g05_plunges_along_the_inclined_axis() {
    let program = "TRAANG\nG0 X50 Z0\nG1 F1000 G07 X10 Z-20\nM0\nG05 X10\nM0\nM30";
    let mut ch = Channel::from_preset("traang-grinder", "").unwrap();
    ch.run_program(program).unwrap();
    let mut mz_during_plunge = Vec::new();
    for (i, (x, z)) in [(50.0, 20.0), (10.0, -20.0)].into_iter().enumerate() {
        while ch.is_busy() {
            ch.step();
            if i == 1 {
                mz_during_plunge.push(ch.axis_positions()[1]);
            }
        }
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
        let (mu, mz) = traang_axes(45.0, x, z);
        assert!(close(machine(&s, "MU"), mu, 1e-9) && close(machine(&s, "MZ"), mz, 1e-9), "{x},{z}: {:?}", s.machine);
        ch.start().unwrap();
    }
    // MZ = Z − X·tan 45° stays at −30 while only MU moves.
    assert!(mz_during_plunge.iter().all(|v| close(*v, -30.0, 1e-9)), "{mz_during_plunge:?}");
    let (ch, _) = run("traang-grinder", "", "G05 X10\nM30");
    assert_eq!(alarm_numbers(&ch.snapshot()), [14401]);
}

#[test]
fn chain_layers_and_machine_axes_are_readable_under_tracon() {
    // TRANSMIT → TRAANG 30° at X10 Y0 Z5 (C = 0): the first member's output is the slide's
    // Cartesian X = 10, Z = 5; the machine layer MU = 10/cos 30°, MZ = 5 − MU·sin 30°.
    let program = "TRACON(1)\nG1 F1000 X10 Y0 Z5\nR1=$AA_ITR[X,1]\nR2=$AA_ITR[X,2]\nR3=$AA_IBC[Z]\nR4=$AA_IM[Z]\nM30";
    let (ch, _) = run("slant-lathe-tracon", "", program);
    assert_eq!(ch.snapshot().status, Status::Idle, "{:?}", ch.snapshot().alarms);
    let (mu, mz) = slant(10.0, 5.0);
    for (r, want) in [(1, 10.0), (2, mu), (3, 5.0), (4, mz)] {
        assert!(close(ch.r_param(r), want, 1e-9), "R{r} = {} vs {want}", ch.r_param(r));
    }
}

/// Radius compensation works in TRANSMIT's Cartesian plane: the square's sides at x = 10 and
/// y = 10 with G41 and T1 (radius 4) become x = 6 and y = 6; the last side ends perpendicular at
/// (−10, 6), which the machine reaches at the polar radius √136 and angle atan2(6, −10).
#[test]
fn transmit_with_radius_compensation_offsets_in_the_cartesian_plane() {
    let program = "T1 D1\nG0 X20 Z10\nTRANSMIT\nG17 G1 F1000 G41 X10 Y-10\nX10 Y10\nX-10 Y10\nM0\nM30";
    let (ch, samples) = run("transmit-example", "", program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    let (r, c) = polar(-10.0, 6.0);
    assert!(close(machine(&s, "XM"), r, 1e-9), "{:?}", s.machine);
    assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-9), "{:?}", s.machine);
    // On the first compensated side the tool centre runs on x = 6 from y = −10 to the inner
    // corner at y = 6.
    let on_side: Vec<&Sample> = samples.iter().filter(|p| p.line == Some(5)).collect();
    assert!(!on_side.is_empty());
    for p in on_side {
        let x = p.axes[0] * p.axes[1].to_radians().cos();
        let y = p.axes[0] * p.axes[1].to_radians().sin();
        assert!(close(x, 6.0, 1e-6) && y > -10.0 - 1e-6 && y < 6.0 + 1e-6, "({x}, {y})");
    }
}

// ---------------------------------------------------------------------------------------------
// The manual's TRANSMIT example as a whole, TRANSMIT pole-side and velocity alarms
// ---------------------------------------------------------------------------------------------

/// The manual's TRANSMIT example (Transformations FM, M1 §2.1.5): the milling spindle becomes
/// the master (SETMS(2)), TRANSMIT, a frame rotated by −45° and shifted additively, then a
/// square roughed with G41 and 1 mm allowance (OFFN=1) by T1 and finished by T2. The seed
/// gives the program from the finishing pass on; the lines before follow the same manual page.
/// T2 (radius 3, length 30) is added to the preset's tool data here.
const TRANSMIT_EXAMPLE_PROGRAM: &str = "\
N10 T1 D1 F400 G94 G54 G17
N20 G0 X20 Z10 SPOS=45
N30 SETMS(2)
N40 M3 S1000
N50 TRANSMIT
N60 ROT RPL=-45
N70 ATRANS X-2 Y10
N80 G1 X10 Y-10 G41 OFFN=1
N90 X-10
N100 Y10
N110 X10
N120 Y-10
N130 G0 Z20 G40 OFFN=0
N140 T2 D1 X15 Y-15
N150 Z10 G41
N160 G1 X10 Y-10
N170 X-10
N180 Y10
N190 X10
N200 Y-10
N210 Z20 G40
N220 TRAFOOF
N230 G0 X20 Z10 SPOS=45
N240 M30";

/// Distance of point (x, y) from the square −10..10 × −10..10 (outside points only).
fn distance_from_square(x: f64, y: f64) -> f64 {
    let dx = (x.abs() - 10.0).max(0.0);
    let dy = (y.abs() - 10.0).max(0.0);
    dx.hypot(dy)
}

#[test]
fn the_manual_transmit_example_keeps_the_offset_square_in_the_rotated_frame() {
    let md = "$TC_DP1[2,1]=120\n$TC_DP3[2,1]=30.\n$TC_DP6[2,1]=3.";
    let (ch, samples) = run("transmit-example", md, TRANSMIT_EXAMPLE_PROGRAM);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    // TRAFOOF deselects the frame: X20, Z10 + T2's length 30 in the machine. SPOS acts on the
    // master spindle, which SETMS(2) made the milling spindle ASM.
    assert!(close(machine(&s, "XM"), 20.0, 1e-9) && close(machine(&s, "ZM"), 40.0, 1e-9), "{:?}", s.machine);
    assert!(close(angle_diff(machine(&s, "ASM"), 45.0), 0.0, 1e-9), "{:?}", s.machine);

    // Tool centre in the WCS from the machine axes: polar → face (BCS), then undo the frame
    // BCS = Rot(−45°)·(WCS + (−2, 10)) by hand.
    let wcs = |p: &Sample| -> (f64, f64) {
        let (r, c) = (p.axes[0], p.axes[1].to_radians());
        let (bx, by) = (r * c.cos(), r * c.sin());
        let (sin, cos) = 45f64.to_radians().sin_cos();
        (cos * bx - sin * by + 2.0, sin * bx + cos * by - 10.0)
    };
    // Roughing (text lines 9..12 = N90..N120): T1 radius 4 + OFFN 1 around the square; G450
    // rounds the outer corners, so the distance from the square is 5 all the way round.
    // Finishing (lines 17..20 = N170..N200): T2 radius 3, no allowance.
    let mut checked = [0, 0];
    for p in &samples {
        let (want, pass) = match p.line {
            Some(9..=12) => (5.0, 0),
            Some(17..=20) => (3.0, 1),
            _ => continue,
        };
        let (x, y) = wcs(p);
        assert!(close(distance_from_square(x, y), want, 1e-6), "line {:?}: ({x}, {y})", p.line);
        checked[pass] += 1;
    }
    assert!(checked.iter().all(|&n| n > 100), "{checked:?} samples checked");

    // During the cut the milling spindle turns at S1000 (M3 after SETMS(2)); C does not.
    let mut ch = Channel::from_preset("transmit-example", md).unwrap();
    ch.run_program(TRANSMIT_EXAMPLE_PROGRAM).unwrap();
    while ch.snapshot().block.map(|b| b.line) != Some(10) {
        ch.step();
    }
    let spindles = ch.snapshot().spindles;
    assert!(
        spindles.contains(&("ASC".to_string(), 1000.0)) && spindles.contains(&("C".to_string(), 0.0)),
        "{spindles:?}"
    );
}

#[test]
fn transmit_selected_outside_the_pole_ignores_pole_side_fix_until_the_pole() {
    // Transformations FM, TRANSMIT, "Transformation selection outside pole": the control
    // traverses the axes without evaluating MD24911 $MC_TRANSMIT_POLE_SIDE_FIX_1. The issue's
    // case: POLE_SIDE_FIX = 2 (radial axis negative only), the machine at XM = +60, C = 0.
    let md = "$MC_TRANSMIT_POLE_SIDE_FIX_1=2";
    let (ch, _) = run("transmit-example", md, "G90 G0 X60 Z5\nSPOS=0\nTRANSMIT\nG1 X15 Y20 F800\nM0\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    // On the side it stands on: r = √(15² + 20²) = 25, C = atan2(20, 15) = 53.130102°.
    assert!(close(machine(&s, "XM"), 25.0, 1e-9), "{:?}", s.machine);
    assert!(close(angle_diff(machine(&s, "CM"), 53.130102354), 0.0, 1e-6), "{:?}", s.machine);

    // Through the pole along X the radial axis crosses zero into its allowed negative range
    // (C keeps 0°); from there the fixed side holds: back to X10 it rotates C by 180° in the
    // pole and ends at XM = −10, C = 180°, never positive again after the first pole passage.
    let program = "G0 X20\nTRANSMIT\nG1 F1000 X10 Y0\nM0\nX-10 Y0\nM0\nX10 Y0\nM0\nM30";
    let mut ch = Channel::from_preset("transmit-example", md).unwrap();
    ch.run_program(program).unwrap();
    let mut stops = Vec::new();
    let mut went_negative = false;
    while ch.is_busy() {
        ch.step();
        let s = ch.snapshot();
        let x = machine(&s, "XM");
        went_negative |= x < -1e-6;
        assert!(!(went_negative && x > 1e-6), "positive again after the pole: {x}");
        if s.status == Status::Stopped {
            stops.push((x, machine(&s, "CM")));
            ch.start().unwrap();
        }
        assert!(stops.len() < 4, "program does not end");
    }
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    let want = [(10.0, 0.0), (-10.0, 0.0), (-10.0, 180.0)];
    assert_eq!(stops.len(), 3, "{stops:?}");
    for ((x, c), (wx, wc)) in stops.iter().zip(want) {
        assert!(close(*x, wx, 1e-9) && close(angle_diff(*c, wc), 0.0, 1e-9), "{stops:?}");
    }
}

/// TRANSMIT data set 1 of the TRANSMIT example as the persistent transformation.
const PERSISTENT_TRANSMIT: &str = "\
$MC_TRAFO_MODE_MASK=1
$MC_TRAFO_RESET_VALUE=1
$MC_RESET_MODE_MASK=1
$MC_GEOAX_CHANGE_RESET=TRUE";

#[test]
fn a_persistent_transmit_keeps_refusing_the_excluded_pole_side() {
    // The manual's persistent-transformation example: "$MC_TRANSMIT_POLE_SIDE_FIX_1 = 1 ; also
    // 2, causes alarm 21617". Persistent TRANSMIT is not selected by a program outside the
    // pole, so the fixed side is evaluated: with the machine at XM = +20 and POLE_SIDE_FIX = 2
    // the reset cannot take the transformation over (the channel stays without it), with
    // POLE_SIDE_FIX = 1 it does.
    for (fix, taken) in [(2, false), (1, true)] {
        let md = format!("{PERSISTENT_TRANSMIT}\n$MC_TRANSMIT_POLE_SIDE_FIX_1={fix}");
        let mut ch = Channel::from_preset("transmit-example", &md).unwrap();
        // Power on with the machine in the pole: nothing to refuse.
        assert_eq!(transformation_type(&ch), Some(256), "fix {fix}");
        let mut positions = ch.axis_positions().to_vec();
        positions[0] = 20.0;
        ch.restore_positions(&positions).unwrap();
        ch.reset();
        assert_eq!(transformation_type(&ch).is_some(), taken, "fix {fix}");
        if !taken {
            // TRAFOOF returns to the persistent transformation: refused on its line with 21617,
            // the machine where it stands.
            ch.run_program("TRAFOOF\nM30").unwrap();
            while ch.is_busy() {
                ch.step();
            }
            let s = ch.snapshot();
            assert_eq!(alarm_numbers(&s), [21617]);
            assert_eq!(s.alarms[0].line, Some(1));
            assert!(close(machine(&s, "XM"), 20.0, 1e-12), "{:?}", s.machine);
        }
    }
}

#[test]
fn a_feed_cut_unevenly_near_the_pole_reports_10910_and_goes_on() {
    // 0.5 mm past the centre at F6000: C limits the feed to a fraction near the pole.
    let program = "G0 X20\nTRANSMIT\nG1 F6000 X20 Y0.5\nX-20 Y0.5\nM0\nM30";
    let (ch, _) = run("transmit-example", "", program);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "the program went on: {:?}", s.alarms);
    assert_eq!(alarm_numbers(&s), [10910]);
    assert_eq!(s.alarms[0].line, Some(4));

    // Far from the pole (the square at radius 10..14) the same C allows the feed everywhere.
    let (ch, _) = run("transmit-example", "", TRANSMIT_SQUARE);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
}

// ---------------------------------------------------------------------------------------------
// TRACYL on the X-Y-Z-A-C milling machine
// ---------------------------------------------------------------------------------------------

/// A groove along the cylinder and then around a quarter of it, on a cylinder clamped on the C
/// table tilted by A = −90°. T1: radius 4, length 80 along ZM (radial). OFFN = 5: the tool
/// centre runs 1 mm beside the centre line.
const XYZAC_GROOVE: &str = "\
T1 D1 G17 G90
G0 A-90 C0
G0 X0 Y10 Z30
TRACYL(40)
G19 G0 X20 Y0 Z10
G1 F1000 G41 OFFN=5 Y0 Z0
Z-30
M0
Y31.4159265358979
M0
M30";

#[test]
fn tracyl_on_the_xyzac_machine_unrolls_onto_c_with_the_groove_wall_on_xm() {
    let mut ch = Channel::from_preset("tracyl-xyzac", "").unwrap();
    ch.run_program(XYZAC_GROOVE).unwrap();
    // (C, XM, YM) at the two stops: along the cylinder (BCS −Z = −YM) the wall offset lies
    // across the periphery and is travelled by XM (left of −Z seen from +X is +Y_bcs, the
    // supplementary axis' direction). The compensation looks across M0 to the next move, a
    // left turn onto +Y: an inner corner, so the tool stops at the intersection of the two
    // offset lines, 1 mm short of Z−30 (YM −29) with XM = 1 and C on the centre line.
    // After a quarter turn on d = 40 (arc 10π) the offset lies along the cylinder: YM = −29,
    // XM back to 0, C = 90°.
    for (c, xm, ym) in [(0.0, 1.0, -29.0), (90.0, 0.0, -29.0)] {
        while ch.is_busy() {
            ch.step();
        }
        let s = ch.snapshot();
        assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
        assert!(close(angle_diff(machine(&s, "CM"), c), 0.0, 1e-6), "C {} vs {c}", machine(&s, "CM"));
        assert!(close(machine(&s, "XM"), xm, 1e-9), "XM {}", machine(&s, "XM"));
        assert!(close(machine(&s, "YM"), ym, 1e-9), "YM {}", machine(&s, "YM"));
        // The radial infeed X20 is the tool tip; ZM carries the tool: 20 + 80.
        assert!(close(machine(&s, "ZM"), 100.0, 1e-9), "ZM {}", machine(&s, "ZM"));
        // The trunnion is not part of the transformation and stays where it was put.
        assert!(close(machine(&s, "AM"), -90.0, 1e-9));
        let t = s.transformation.clone().expect("TRACYL active");
        assert_eq!((t.name.as_str(), t.trafo_type), ("TRACYL", 513));
        ch.start().unwrap();
    }
}

#[test]
fn setms_needs_a_spindle_of_the_channel_and_program_end_restores_the_configured_master() {
    let (ch, _) = run("transmit-example", "", "SETMS(3)\nM30");
    let s = ch.snapshot();
    assert_eq!(alarm_numbers(&s), [12560], "{:?}", s.alarms);
    // SETMS(2) then M3: the milling spindle turns; after M30, S/M3 address spindle 1 again.
    let (ch, _) = run("transmit-example", "", "SETMS(2)\nM3 S500\nG4 F10\nM30");
    assert!(ch.snapshot().spindles.contains(&("ASC".to_string(), 500.0)), "{:?}", ch.snapshot().spindles);
    let mut ch = ch;
    ch.run_program("M4 S80\nG4 F10\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let spindles = ch.snapshot().spindles;
    assert!(
        spindles.contains(&("C".to_string(), -80.0)) && spindles.contains(&("ASC".to_string(), 500.0)),
        "{spindles:?}"
    );
}
