//! Manual operation, the selectable parts: the reference systems and orientation kinds of
//! Cartesian JOG from SD42650/SD42660, the JOG rapid traverse overlay, the REPOS target modes
//! (RMI, RMB, RME, RMN) and the reference point approach of incremental encoders.
//!
//! Expected values are written out here from plain rotation matrices, path geometry and the
//! machine data's velocities, independently of the engine.

use nctwin_engine::channel::{JogSystem, OrientationJogKind, ReferencePhase, ReposApproach, ReposMode};
use nctwin_engine::{Channel, CommandError, JogRequest, Mode, Overrides, Snapshot, Status};

use crate::settle;
use settle::{channel, settle};

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn jog(axis: &str, direction: i8, increment: Option<f64>) -> JogRequest {
    JogRequest { axis: axis.into(), direction, increment, rapid: false }
}

// --- Cartesian JOG from the setting data ---------------------------------------------------------

/// The CA head of `mill5-head-ca`: tool direction `o = (sin C·sin A, −cos C·sin A, cos A)` and
/// tool tip `P = M + (0, 0, 150) − 250·o` (pivot 150 above the nose, T1 100 long).
fn head_tip(m: &[f64]) -> [f64; 3] {
    let o = head_orientation(m);
    [m[0] - 250.0 * o[0], m[1] - 250.0 * o[1], m[2] + 150.0 - 250.0 * o[2]]
}

fn head_orientation(m: &[f64]) -> [f64; 3] {
    let (sa, ca) = m[3].to_radians().sin_cos();
    let (sc, cc) = m[4].to_radians().sin_cos();
    [sc * sa, -cc * sa, ca]
}

/// TRAORI active (kept over program end by RESET_MODE_MASK bit 7), head at A30 C0, tip at
/// (0, 0, 50), JOG mode; `md` adds setting data.
fn head_at_a30(md: &str) -> Channel {
    let mut ch = channel("mill5-head-ca", &format!("$MC_RESET_MODE_MASK='H81'\n{md}"));
    ch.run_program("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\nM30").unwrap();
    settle(&mut ch);
    ch.set_mode(Mode::Jog).unwrap();
    ch
}

/// Asserts the tool orientation reached `want` (unit vector) with the tip held at (0, 0, 50)
/// in every sample.
fn assert_orientation(ch: &Channel, samples: &[Vec<f64>], want: [f64; 3]) {
    let o = head_orientation(ch.axis_positions());
    assert!((0..3).all(|i| close(o[i], want[i], 1e-6)), "orientation {o:?}, want {want:?}");
    assert!(samples.len() > 5);
    for p in samples {
        let tip = head_tip(p);
        assert!(close(tip[0], 0.0, 1e-6) && close(tip[1], 0.0, 1e-6) && close(tip[2], 50.0, 1e-6), "tip {tip:?}");
    }
}

#[test]
fn sd42650_chooses_the_system_of_a_jog_that_names_none() {
    // Bit 2: translation in the TCS. Z moves 10 along o = (0, −sin 30°, cos 30°).
    let mut ch = head_at_a30("$SC_CART_JOG_MODE='H4'");
    let before = ch.axis_positions().to_vec();
    ch.jog_with(&jog("Z", 1, Some(10.0)), None, None).unwrap();
    settle(&mut ch);
    let after = ch.axis_positions();
    assert!(close(after[0] - before[0], 0.0, 1e-9), "{after:?}");
    assert!(close(after[1] - before[1], -5.0, 1e-9), "{after:?}");
    assert!(close(after[2] - before[2], 10.0 * 30f64.to_radians().cos(), 1e-9), "{after:?}");
    assert!(close(after[3], 30.0, 1e-9));
    // 0 (the default): the machine axis Z alone.
    let mut ch = head_at_a30("");
    let before = ch.axis_positions().to_vec();
    ch.jog_with(&jog("Z", 1, Some(10.0)), None, None).unwrap();
    settle(&mut ch);
    let after = ch.axis_positions();
    assert!(close(after[2] - before[2], 10.0, 1e-9) && after[1] == before[1] && after[0] == before[0], "{after:?}");
    // A named system wins over the setting.
    let mut ch = head_at_a30("$SC_CART_JOG_MODE='H4'");
    let before = ch.axis_positions().to_vec();
    ch.jog_with(&jog("Z", 1, Some(10.0)), Some(JogSystem::Machine), None).unwrap();
    settle(&mut ch);
    assert!(close(ch.axis_positions()[2] - before[2], 10.0, 1e-9));
}

#[test]
fn sd42650_orientation_bit_for_tcs_turns_about_the_tool_axes() {
    // Bit 10: orientation in the TCS. The tool's X axis at A30 C0 is (1, 0, 0) (X in the old
    // X-Z plane), so A2 turns about X like in the BCS, but C2 turns about the tool axis itself:
    // nothing changes in the orientation vector, so the rotary axes stay (a 5-axis head).
    let mut ch = head_at_a30("$SC_CART_JOG_MODE='H400'");
    ch.jog_with(&jog("A2", 1, Some(10.0)), None, None).unwrap();
    let samples = settle(&mut ch);
    // Rx(10°)·(0, −sin 30°, cos 30°) = (0, −sin 40°, cos 40°).
    let a40 = 40f64.to_radians();
    assert_orientation(&ch, &samples, [0.0, -a40.sin(), a40.cos()]);
}

#[test]
fn orientation_jog_with_euler_angles_changes_the_euler_angles() {
    // SD42660 = 1 (ORIEULER, o = Rz(A2)·Rx(B2)·ez = (sin A2·sin B2, −cos A2·sin B2, cos B2)).
    // At A30 C0: o = (0, −0.5, 0.866), so A2 = 0, B2 = 30.
    let mut ch = head_at_a30("$SC_ORI_JOG_MODE=1");
    ch.jog_with(&jog("A2", 1, Some(10.0)), None, None).unwrap();
    let samples = settle(&mut ch);
    // A2 = 10, B2 = 30: (sin 10°·sin 30°, −cos 10°·sin 30°, cos 30°), i.e. machine C10 A30
    // (rotations about X would have given A40 C0).
    let (s10, c10) = 10f64.to_radians().sin_cos();
    assert_orientation(&ch, &samples, [s10 * 0.5, -c10 * 0.5, 30f64.to_radians().cos()]);
    assert!(close(machine(&ch.snapshot(), "C"), 10.0, 1e-6) && close(machine(&ch.snapshot(), "A"), 30.0, 1e-6));
    // B2 now turns about Rz(10°)·X: B2 = 45 gives (sin 10°·sin 45°, −cos 10°·sin 45°, cos 45°).
    ch.jog_with(&jog("B2", 1, Some(15.0)), None, None).unwrap();
    let samples = settle(&mut ch);
    let (s45, c45) = 45f64.to_radians().sin_cos();
    assert_orientation(&ch, &samples, [s10 * s45, -c10 * s45, c45]);
    // C2 (the last Z turn) does not change the orientation vector of a 5-axis machine.
    assert!(matches!(ch.jog_with(&jog("C2", 1, Some(5.0)), None, None), Err(CommandError::Invalid(_))));
}

#[test]
fn orientation_jog_with_rpy_angles_turns_about_the_turned_axis() {
    // ORIRPY: o = Rz(C2)·Ry(B2)·Rx(A2)·ez, C2 taken as 0: o = (sin B·cos A, −sin A, cos B·cos A).
    // At A30 C0: A2 = 30, B2 = 0.
    let mut ch = head_at_a30("");
    ch.jog_with(&jog("B2", 1, Some(20.0)), Some(JogSystem::Basic), Some(OrientationJogKind::Rpy)).unwrap();
    settle(&mut ch);
    ch.jog_with(&jog("A2", 1, Some(10.0)), Some(JogSystem::Basic), Some(OrientationJogKind::Rpy)).unwrap();
    let samples = settle(&mut ch);
    // A2 = 40, B2 = 20: (sin 20°·cos 40°, −sin 40°, cos 20°·cos 40°). A turn about the fixed X
    // axis would have given Rx(10°)·(sin 20°·cos 30°, −sin 30°, cos 20°·cos 30°) instead.
    let (s20, c20) = 20f64.to_radians().sin_cos();
    let (s40, c40) = 40f64.to_radians().sin_cos();
    assert_orientation(&ch, &samples, [s20 * c40, -s40, c20 * c40]);
}

#[test]
fn orientation_jog_in_the_wcs_reckons_the_angles_in_the_rotated_frame() {
    // ROT Z90 active (stopped at M0 after a move under it), SD42650 bit 9: orientation in the
    // WCS, RPY angles. The frame maps WCS (x, y) to BCS (−y, x), so the tool
    // o = (0, −0.5, cos 30°) is (−0.5, 0, cos 30°) in the WCS: RPY A2 = 0, B2 = −30.
    let mut ch = channel("mill5-head-ca", "$SC_CART_JOG_MODE='H200'\n$SC_ORI_JOG_MODE=2");
    ch.run_program("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\nROT Z90\nG1 Z50.5\nM0\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), nctwin_engine::Status::Stopped);
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog_with(&jog("A2", 1, Some(10.0)), None, None).unwrap();
    let samples = settle(&mut ch);
    // A2 = 10 in the WCS: Ry(−30°)·Rx(10°)·ez = (−0.5·cos 10°, −sin 10°, cos 30°·cos 10°);
    // in the BCS (−y, x, z): (sin 10°, −0.5·cos 10°, cos 30°·cos 10°).
    let (s10, c10) = 10f64.to_radians().sin_cos();
    let want = [s10, -0.5 * c10, 30f64.to_radians().cos() * c10];
    let o = head_orientation(ch.axis_positions());
    assert!((0..3).all(|i| close(o[i], want[i], 1e-6)), "orientation {o:?}, want {want:?}");
    for p in &samples {
        let tip = head_tip(p);
        assert!(close(tip[0], 0.0, 1e-6) && close(tip[1], 0.0, 1e-6) && close(tip[2], 50.5, 1e-6), "tip {tip:?}");
    }
}

#[test]
fn orientation_jog_with_orivirt1_follows_oriax_turn_tab_1() {
    // ORIAX_TURN_TAB_1 = (X, Y, Z): o = Rx(A2)·Ry(B2)·Rz(C2)·ez = (sin B, −sin A·cos B,
    // cos A·cos B). At A30 C0: A2 = 30, B2 = 0. B2 turns about Rx(30°)·Y.
    let md = "$MC_ORIAX_TURN_TAB_1[0]=1\n$MC_ORIAX_TURN_TAB_1[1]=2\n$MC_ORIAX_TURN_TAB_1[2]=3\n$SC_ORI_JOG_MODE=4";
    let mut ch = head_at_a30(md);
    ch.jog_with(&jog("B2", 1, Some(20.0)), None, None).unwrap();
    let samples = settle(&mut ch);
    let (s20, c20) = 20f64.to_radians().sin_cos();
    assert_orientation(&ch, &samples, [s20, -0.5 * c20, 30f64.to_radians().cos() * c20]);
}

// --- Rapid traverse overlay ----------------------------------------------------------------------

/// Continuous JOG of X for 300 cycles; the speed of the last cycle, mm/s.
fn steady_jog_speed(ch: &mut Channel, rapid: bool) -> f64 {
    ch.jog(&JogRequest { axis: "X".into(), direction: 1, increment: None, rapid }).unwrap();
    let dt = ch.config().ipo_cycle;
    let mut last = ch.axis_positions()[0];
    let mut v = 0.0;
    for _ in 0..300 {
        ch.step();
        v = (ch.axis_positions()[0] - last) / dt;
        last = ch.axis_positions()[0];
    }
    ch.jog_stop();
    settle(ch);
    v
}

#[test]
fn rapid_overlay_runs_at_jog_velo_rapid_under_the_rapid_override() {
    // MD32010 JOG_VELO_RAPID 6000 mm/min = 100 mm/s, MD32020 JOG_VELO 2000 mm/min = 33.33 mm/s.
    let mut ch = channel("mill-3axis", "$MA_JOG_VELO_RAPID[X]=6000");
    ch.set_mode(Mode::Jog).unwrap();
    ch.set_overrides(Overrides { feed: 50.0, rapid: 30.0, spindle: 100.0 }).unwrap();
    // Rapid key: 100 mm/s × 30 % = 30 mm/s; the feed override does not act.
    assert!(close(steady_jog_speed(&mut ch, true), 30.0, 1e-6));
    // Without it: 33.33 mm/s × 50 % = 16.67 mm/s; the rapid override does not act.
    assert!(close(steady_jog_speed(&mut ch, false), 2000.0 / 60.0 * 0.5, 1e-6));
    // Feed override 120 % leaves the rapid JOG at 30 mm/s.
    ch.set_overrides(Overrides { feed: 120.0, rapid: 30.0, spindle: 100.0 }).unwrap();
    assert!(close(steady_jog_speed(&mut ch, true), 30.0, 1e-6));
}

// --- REPOS target modes --------------------------------------------------------------------------

/// Runs `program` for `cycles`, stops, jogs X by `dx` and Y by `dy` (MCS) and changes back to
/// AUTO; returns the interruption point and the point the axes were jogged to.
fn interrupt_and_jog(ch: &mut Channel, program: &str, cycles: usize, dx: f64, dy: f64) -> ([f64; 3], [f64; 3]) {
    ch.run_program(program).unwrap();
    for _ in 0..cycles {
        ch.step();
    }
    ch.stop();
    settle(ch);
    assert_eq!(ch.status(), Status::Stopped);
    let p = ch.axis_positions();
    let interrupted = [p[0], p[1], p[2]];
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog(&jog("X", if dx > 0.0 { 1 } else { -1 }, Some(dx.abs()))).unwrap();
    settle(ch);
    ch.jog(&jog("Y", if dy > 0.0 { 1 } else { -1 }, Some(dy.abs()))).unwrap();
    settle(ch);
    ch.set_mode(Mode::Auto).unwrap();
    let p = ch.axis_positions();
    (interrupted, [p[0], p[1], p[2]])
}

/// NC start with `mode`; checks the return runs on the straight line from `from` to `target`
/// and returns the samples from the arrival on.
fn repos_to(ch: &mut Channel, mode: ReposMode, from: [f64; 3], target: [f64; 3]) -> Vec<Vec<f64>> {
    ch.start_with_repos(mode).unwrap();
    let samples = settle(ch);
    let at = |s: &Vec<f64>| (0..3).all(|i| close(s[i], target[i], 1e-6));
    let arrival = samples.iter().position(at).unwrap_or_else(|| panic!("{mode:?} never reached {target:?}"));
    let d: Vec<f64> = (0..3).map(|i| target[i] - from[i]).collect();
    let len = d.iter().map(|x| x * x).sum::<f64>().sqrt();
    for s in &samples[..arrival] {
        // Distance of the sample from the line from → target: |(s − from) × d| / |d|.
        let r: Vec<f64> = (0..3).map(|i| s[i] - from[i]).collect();
        let c = [r[1] * d[2] - r[2] * d[1], r[2] * d[0] - r[0] * d[2], r[0] * d[1] - r[1] * d[0]];
        let off = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() / len;
        assert!(off < 1e-6, "{mode:?}: {s:?} is {off} off the straight return");
    }
    assert_eq!(ch.status(), Status::Idle, "the program ran to its end");
    samples[arrival..].to_vec()
}

const LINE_THEN_Y: &str = "G1 X100 F6000\nG1 Y50\nM30";

#[test]
fn repos_rmi_rmb_rme_and_rmn_on_a_straight_block() {
    // Interrupted on G1 X100 (from X0) at xi, jogged to (xi + 5, 10).
    for mode in [ReposMode::Interruption, ReposMode::BlockStart, ReposMode::BlockEnd, ReposMode::Nearest] {
        let mut ch = channel("mill-3axis", "");
        let (p, here) = interrupt_and_jog(&mut ch, LINE_THEN_Y, 120, 5.0, 10.0);
        assert!(p[0] > 10.0 && p[0] < 80.0 && p[1] == 0.0, "{p:?}");
        let target = match mode {
            ReposMode::Interruption => p,
            ReposMode::BlockStart => [0.0, 0.0, 0.0],
            ReposMode::BlockEnd => [100.0, 0.0, 0.0],
            // The foot of the perpendicular from (xi + 5, 10) on the X axis.
            ReposMode::Nearest => [p[0] + 5.0, 0.0, 0.0],
        };
        let rest = repos_to(&mut ch, mode, here, target);
        // From the target on: the rest of G1 X100 (Y = 0, X rising to 100), then G1 Y50 at X100.
        let turn = rest.iter().position(|s| s[0] == 100.0).expect("reaches X100");
        for w in rest[..=turn].windows(2) {
            assert!(w[1][1] == 0.0 && w[1][0] >= w[0][0], "{mode:?}: {w:?}");
        }
        assert!(rest[turn..].iter().all(|s| s[0] == 100.0), "{mode:?}");
        if mode == ReposMode::BlockStart {
            // The whole block again: X from 0.
            assert!(rest[..turn].len() as f64 * 0.004 * 100.0 > 99.0, "{mode:?}: too few cycles for 100 mm");
        }
        assert_eq!(ch.axis_positions(), &[100.0, 50.0, 0.0], "{mode:?}");
    }
}

#[test]
fn repos_rmn_on_an_arc_returns_to_the_radial_foot_and_finishes_the_arc() {
    // G2 from (0, 0) about (50, 0), R50, to (100, 0). Jogged by (+10, +10) from the
    // interruption point; the nearest arc point is C + 50·(here − C)/|here − C|.
    let mut ch = channel("mill-3axis", "");
    let (p, here) = interrupt_and_jog(&mut ch, "G2 X100 Y0 I50 J0 F6000\nM30", 250, 10.0, 10.0);
    assert!(((p[0] - 50.0).hypot(p[1]) - 50.0).abs() < 1e-6 && p[1] > 10.0, "on the arc: {p:?}");
    let r = (here[0] - 50.0).hypot(here[1]);
    let target = [50.0 + 50.0 * (here[0] - 50.0) / r, 50.0 * here[1] / r, 0.0];
    let rest = repos_to(&mut ch, ReposMode::Nearest, here, target);
    for s in &rest {
        assert!(((s[0] - 50.0).hypot(s[1]) - 50.0).abs() < 1e-6, "off the arc: {s:?}");
    }
    let end = ch.axis_positions();
    assert!(close(end[0], 100.0, 1e-9) && close(end[1], 0.0, 1e-9), "{end:?}");
}

#[test]
fn repos_mode_names_are_the_g_functions_of_group_26() {
    assert_eq!(ReposMode::from_name("rmb"), Some(ReposMode::BlockStart));
    assert_eq!(ReposMode::from_name("RMN").map(ReposMode::name), Some("RMN"));
    assert_eq!(ReposMode::from_name("RMX"), None);
    assert_eq!(ReposMode::default(), ReposMode::Interruption);
}

// --- Reference point approach ------------------------------------------------------------------

/// Steps until the approach leaves `phase` (or ends); returns the time and the X position of
/// the first cycle in the next phase, and the highest X speed seen during `phase`.
fn run_phase(ch: &mut Channel, phase: ReferencePhase) -> (f64, f64, f64) {
    let dt = ch.config().ipo_cycle;
    let mut peak: f64 = 0.0;
    let mut last = ch.axis_positions()[0];
    for _ in 0..100_000 {
        ch.step();
        let x = ch.axis_positions()[0];
        if ch.snapshot().referencing.map(|(_, p)| p) != Some(phase) {
            return (ch.time(), x, peak);
        }
        peak = peak.max((x - last).abs() / dt);
        last = x;
    }
    panic!("phase {phase:?} never ended");
}

#[test]
fn an_incremental_axis_travels_to_cam_zero_mark_and_reference_point() {
    // X at 0, approach in plus: reference point REFP_SET_POS 100, zero mark 100 − (−2) = 102,
    // cam edge 102 − 10 = 92. Cam search 5000 mm/min = 83.33 mm/s, zero mark search 300 mm/min
    // = 5 mm/s, acceleration 1 m/s².
    let md = "$MA_ENC_REFP_STATE[X]=0\n$MA_MAX_AX_ACCEL[X]=1\n$MA_REFP_SET_POS[0,X]=100";
    let mut ch = channel("mill-3axis", md);
    ch.set_mode(Mode::Jog).unwrap();
    let (v, a, dt) = (5000.0 / 60.0, 1000.0, ch.config().ipo_cycle);
    ch.reference_axes(Some("X")).unwrap();
    assert_eq!(ch.snapshot().referencing, Some(("X".to_string(), ReferencePhase::Cam)));
    assert_eq!(ch.status(), Status::Running);
    assert!(ch.jog(&jog("Y", 1, Some(1.0))).is_err(), "no JOG while referencing");
    // Phase 1: ramp up (v/a, v²/2a = 3.47 mm), cruise to the cam at 92, brake v²/2a past it.
    let t0 = ch.time();
    let (t1, x1, peak1) = run_phase(&mut ch, ReferencePhase::Cam);
    let t_cam = v / a + (92.0 - v * v / (2.0 * a)) / v;
    assert!(close(peak1, v, 1e-6), "cam search speed {peak1}");
    assert!(
        close(t1 - t0, t_cam + v / a, 4.0 * dt),
        "cam found and braked after {} s, want {} s",
        t1 - t0,
        t_cam + v / a
    );
    // Braking in cycles from v covers v²/2a − v·dt/2; the cam is seen up to one cycle late.
    let x_stop = 92.0 + v * v / (2.0 * a) - v * dt / 2.0;
    assert!(x1 >= x_stop - 1e-9 && x1 <= x_stop + v * dt, "stood at {x1}, want {x_stop} + up to {}", v * dt);
    // Phase 2: to the zero mark at 102 at 5 mm/s.
    let (t2, x2, peak2) = run_phase(&mut ch, ReferencePhase::Marker);
    assert!(close(peak2, 5.0, 1e-6), "zero mark search speed {peak2}");
    assert!(close(x2, 102.0, 1e-9), "{x2}");
    let t_marker = (102.0 - x1) / 5.0 + 5.0 / a;
    assert!(close(t2 - t1, t_marker, 3.0 * dt), "zero mark after {} s, want {t_marker} s", t2 - t1);
    // Phase 3: 2 mm back to the reference point: a triangle, 2·√(2/1000) s.
    let (t3, _, peak3) = run_phase(&mut ch, ReferencePhase::Position);
    assert!(peak3 <= (a * 2.0).sqrt() + 1e-6, "{peak3}");
    assert!(close(t3 - t2, 2.0 * (2.0 / a).sqrt(), 3.0 * dt), "{}", t3 - t2);
    settle(&mut ch);
    assert_eq!(ch.axis_positions()[0], 100.0);
    assert_eq!(ch.snapshot().referencing, None);
    assert!(ch.snapshot().referenced[0].1);
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn stop_and_reset_abort_the_approach_and_an_axis_on_the_cam_searches_the_zero_mark_at_once() {
    let md = "$MA_ENC_REFP_STATE[X]=0\n$MA_REFP_SET_POS[0,X]=100";
    let mut ch = channel("mill-3axis", md);
    ch.set_mode(Mode::Jog).unwrap();
    ch.reference_axes(Some("X")).unwrap();
    for _ in 0..50 {
        ch.step();
    }
    ch.stop();
    settle(&mut ch);
    assert_eq!(
        (ch.status(), ch.snapshot().referencing.clone(), ch.snapshot().referenced[0].1),
        (Status::Idle, None, false)
    );
    let x = ch.axis_positions()[0];
    assert!(x > 0.0 && x < 92.0, "{x}");
    ch.reference_axes(Some("X")).unwrap();
    ch.step();
    ch.reset();
    assert_eq!((ch.status(), ch.snapshot().referencing, ch.snapshot().referenced[0].1), (Status::Idle, None, false));
    // REFP_SET_POS 0 (default): zero mark at 2, cam edge at −8; X at 0 is already on the cam.
    let mut ch = channel("mill-3axis", "$MA_ENC_REFP_STATE[X]=0");
    ch.set_mode(Mode::Jog).unwrap();
    ch.reference_axes(Some("X")).unwrap();
    assert_eq!(ch.snapshot().referencing, Some(("X".to_string(), ReferencePhase::Marker)));
    settle(&mut ch);
    assert_eq!(ch.axis_positions()[0], 0.0);
    assert!(ch.snapshot().referenced[0].1);
}

#[test]
fn referencing_every_axis_follows_md34110_and_md34200_0_references_at_once() {
    // Y (REFP_CYCLE_NR 1) before X (2); Z has no approach (ENC_REFP_MODE 0).
    let md = "$MA_ENC_REFP_STATE[X]=0\n$MA_ENC_REFP_STATE[Y]=0\n$MA_ENC_REFP_STATE[Z]=0\n\
              $MA_REFP_CYCLE_NR[X]=2\n$MA_REFP_CYCLE_NR[Y]=1\n$MA_ENC_REFP_MODE[Z]=0";
    let mut ch = channel("mill-3axis", md);
    ch.set_mode(Mode::Jog).unwrap();
    ch.reference_axes(None).unwrap();
    let s = ch.snapshot();
    assert_eq!(s.referencing.map(|(a, _)| a), Some("Y".to_string()));
    assert_eq!(s.referenced, vec![("X".into(), false), ("Y".into(), false), ("Z".into(), true)]);
    let mut order = Vec::new();
    while ch.is_busy() {
        ch.step();
        if let Some((axis, _)) = ch.snapshot().referencing
            && order.last() != Some(&axis)
        {
            order.push(axis);
        }
    }
    assert_eq!(order, ["Y", "X"]);
    assert!(ch.snapshot().referenced.iter().all(|(_, r)| *r));
}

// --- REPOS approach shapes -----------------------------------------------------------------------

/// Interrupted on G1 X100 at (xi, 0), jogged to (xi + 5, 10): the circle of REPOSQ/REPOSH ends
/// in the interruption point running along +X, in the plane of X and the side the tool stands
/// on (+Y): centre (xi, r). REPOSQ DISR=4 starts at (xi − 4, 4), REPOSH DISR=8 at (xi, 8).
#[test]
fn reposq_and_reposh_enter_the_contour_tangentially_on_a_circle() {
    for (approach, r) in
        [(ReposApproach::QuarterCircle { radius: 4.0 }, 4.0), (ReposApproach::SemiCircle { diameter: 8.0 }, 4.0)]
    {
        let mut ch = channel("mill-3axis", "");
        let (p, here) = interrupt_and_jog(&mut ch, LINE_THEN_Y, 120, 5.0, 10.0);
        let xi = p[0];
        let circle_start = match approach {
            ReposApproach::QuarterCircle { .. } => [xi - r, r],
            _ => [xi, 2.0 * r],
        };
        ch.start_with_repos_approach(ReposMode::Interruption, approach).unwrap();
        let samples = settle(&mut ch);
        let at = |s: &Vec<f64>, q: [f64; 2]| close(s[0], q[0], 1e-9) && close(s[1], q[1], 1e-9);
        let s_idx = samples.iter().position(|s| at(s, circle_start)).expect("reaches the circle start");
        let t_idx = samples.iter().position(|s| at(s, [xi, 0.0])).expect("reaches the interruption point");
        assert!(s_idx < t_idx);
        // Straight to the circle start: collinear with here → start.
        let d = [circle_start[0] - here[0], circle_start[1] - here[1]];
        for s in &samples[..s_idx] {
            let cross = (s[0] - here[0]) * d[1] - (s[1] - here[1]) * d[0];
            assert!(cross.abs() < 1e-6, "{approach:?}: {s:?} off the straight line");
        }
        // On the circle about (xi, r), left of the interruption point.
        for s in &samples[s_idx..=t_idx] {
            assert!(close((s[0] - xi).hypot(s[1] - r), r, 1e-6), "{approach:?}: {s:?} off the circle");
            assert!(s[0] <= xi + 1e-9 && s[1] >= -1e-9, "{approach:?}: {s:?}");
        }
        // Tangential entry: the last circle cycles move along +X.
        let w = &samples[t_idx - 1];
        assert!(w[1] < 0.05 && w[0] < xi, "{approach:?}: {w:?}");
        // Then the rest of the block and the next one.
        assert!(samples[t_idx..].iter().take_while(|s| s[0] < 100.0).all(|s| s[1] == 0.0));
        assert_eq!(ch.axis_positions(), &[100.0, 50.0, 0.0]);
    }
    let mut ch = channel("mill-3axis", "");
    interrupt_and_jog(&mut ch, LINE_THEN_Y, 120, 5.0, 10.0);
    let bad = ch.start_with_repos_approach(ReposMode::Interruption, ReposApproach::QuarterCircle { radius: 0.0 });
    assert!(matches!(bad, Err(CommandError::Invalid(_))));
}
