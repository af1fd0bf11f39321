//! Manual operation on the engine: incremental and handwheel JOG, JOG in the WCS, JOG in an
//! interrupted program with REPOS (also with TRANSMIT), block search with calculation, and the
//! reference point state with the NC start lock.

use nctwin_engine::channel::JogSystem;
use nctwin_engine::{Channel, CommandError, JogRequest, Mode, Snapshot, Status};

use crate::settle;
use settle::{channel, settle};

fn pos(list: &[(String, f64)], name: &str) -> f64 {
    list.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name} in {list:?}")).1
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    pos(&s.machine, name)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn jog(axis: &str, direction: i8, increment: Option<f64>) -> JogRequest {
    JogRequest { axis: axis.into(), direction, increment, rapid: false }
}

// --- Incremental and handwheel JOG ------------------------------------------------------------

#[test]
fn inc_steps_are_weighted_by_md31090() {
    let mut ch = channel("mill-3axis", "$MA_JOG_INCR_WEIGHT[0,Y]=0.01");
    ch.set_mode(Mode::Jog).unwrap();
    // INC1000 at the default weight 0.001 mm is 1 mm; INC10 on Y at 0.01 mm is 0.1 mm.
    assert_eq!(ch.increment_distance("X", 1000).unwrap(), 1.0);
    assert!(close(ch.increment_distance("Y", 10).unwrap(), 0.1, 1e-12));
    let x = ch.increment_distance("X", 1000).unwrap();
    ch.jog(&jog("X", 1, Some(x))).unwrap();
    settle(&mut ch);
    let y = ch.increment_distance("Y", 10).unwrap();
    ch.jog(&jog("Y", -1, Some(y))).unwrap();
    settle(&mut ch);
    assert!(close(ch.axis_positions()[0], 1.0, 1e-12));
    assert!(close(ch.axis_positions()[1], -0.1, 1e-12));
    assert!(matches!(ch.increment_distance("Q", 1), Err(CommandError::UnknownAxis(_))));
}

#[test]
fn handwheel_pulses_add_up_while_the_axis_moves() {
    let mut ch = channel("mill-3axis", "");
    ch.set_mode(Mode::Jog).unwrap();
    // 3 detents at INC100 = 0.3 mm, then while moving 5 detents back at INC10 = 0.05 mm.
    ch.handwheel("X", 3, 100, JogSystem::Machine).unwrap();
    ch.step();
    assert_eq!(ch.status(), Status::Running);
    ch.handwheel("X", -5, 10, JogSystem::Machine).unwrap();
    let samples = settle(&mut ch);
    assert!(close(ch.axis_positions()[0], 0.25, 1e-9), "{}", ch.axis_positions()[0]);
    let peak = samples.iter().map(|s| s[0]).fold(f64::MIN, f64::max);
    // The reversal blends within one IPO cycle (MD32310 overload), so the peak is a hair short.
    assert!(close(peak, 0.3, 1e-3), "the first pulses are travelled: {peak}");
    assert_eq!(ch.status(), Status::Idle);
    assert!(ch.handwheel("X", 0, 10, JogSystem::Machine).is_err());
}

#[test]
fn jog_in_the_wcs_follows_the_rotated_frame_and_repos_returns() {
    // ROT Z=90: the WCS X axis points along the BCS Y axis.
    let program = "G1 X10 Y0 F3000\nROT Z=90\nG1 X5\nM0\nG1 X8\nM30";
    let mut ch = channel("mill-3axis", "");
    ch.run_program(program).unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
    // WCS X5 = BCS (10, 5).
    assert!(close(ch.axis_positions()[0], 10.0, 1e-9) && close(ch.axis_positions()[1], 5.0, 1e-9));
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog_in(&jog("X", 1, Some(2.0)), JogSystem::Workpiece).unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped, "JOG keeps the program interrupted");
    let p = ch.axis_positions().to_vec();
    assert!(close(p[0], 10.0, 1e-9) && close(p[1], 7.0, 1e-9), "{p:?}");
    // The same key in the MCS, and in the BCS (where the frame does not act), moves machine X.
    ch.jog_in(&jog("X", 1, Some(1.0)), JogSystem::Machine).unwrap();
    settle(&mut ch);
    ch.jog_in(&jog("X", 1, Some(1.0)), JogSystem::Basic).unwrap();
    settle(&mut ch);
    assert!(close(ch.axis_positions()[0], 12.0, 1e-9) && close(ch.axis_positions()[1], 7.0, 1e-9));
    assert!(ch.snapshot().repos_pending);
    ch.set_mode(Mode::Auto).unwrap();
    ch.start().unwrap();
    let samples = settle(&mut ch);
    // REPOS: a straight line from (12, 7) back to (10, 5), then WCS X8 = BCS (10, 8).
    let back = samples.iter().position(|s| close(s[0], 10.0, 1e-9) && close(s[1], 5.0, 1e-9)).expect("back");
    for s in &samples[..back] {
        assert!(close(s[0] - 12.0, s[1] - 7.0, 1e-9), "on the line x - 12 = y - 7: {s:?}");
    }
    assert_eq!(ch.status(), Status::Idle);
    assert!(close(ch.axis_positions()[0], 10.0, 1e-9) && close(ch.axis_positions()[1], 8.0, 1e-9));
}

// --- REPOS --------------------------------------------------------------------------------------

#[test]
fn repos_returns_on_a_straight_line_with_the_interrupted_feed_and_finishes_the_block() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X100 F6000\nM30").unwrap();
    for _ in 0..200 {
        ch.step();
    }
    ch.stop();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
    let xi = ch.axis_positions()[0];
    assert!(xi > 10.0 && xi < 90.0, "{xi}");
    ch.set_mode(Mode::Jog).unwrap();
    assert!(ch.set_mode(Mode::Mda).is_err(), "only JOG or the program's mode while interrupted");
    ch.jog(&jog("Y", 1, Some(10.0))).unwrap();
    settle(&mut ch);
    ch.jog(&jog("Z", 1, Some(5.0))).unwrap();
    settle(&mut ch);
    assert!(ch.start().is_err(), "NC start in JOG does not continue the program");
    ch.set_mode(Mode::Auto).unwrap();
    ch.start().unwrap();
    let samples = settle(&mut ch);
    let back = samples.iter().position(|s| s[1] == 0.0 && s[2] == 0.0).expect("back on the contour");
    for w in samples[..=back].windows(2) {
        // The straight line from (xi, 10, 5) to (xi, 0, 0): X stays, Y = 2 Z.
        assert_eq!(w[1][0], xi);
        assert!(close(w[1][1], 2.0 * w[1][2], 1e-9), "{:?}", w[1]);
        // At most F6000 = 100 mm/s along the path (plus rounding), more than JOG_VELO (33.3 mm/s).
        let v = ((w[1][1] - w[0][1]).powi(2) + (w[1][2] - w[0][2]).powi(2)).sqrt() / 0.004;
        assert!(v <= 100.0 + 1e-6, "{v}");
    }
    let peak = samples[..=back]
        .windows(2)
        .map(|w| ((w[1][1] - w[0][1]).powi(2) + (w[1][2] - w[0][2]).powi(2)).sqrt() / 0.004)
        .fold(0.0, f64::max);
    assert!(peak > 2000.0 / 60.0 + 1.0, "the interrupted block's feed, not the JOG velocity: {peak}");
    // Then the rest of the block: X only.
    assert!(samples[back..].iter().all(|s| s[1] == 0.0 && s[2] == 0.0));
    assert_eq!(ch.axis_positions(), &[100.0, 0.0, 0.0]);
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn nc_stop_during_repos_and_start_again_still_return() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X50 F3000\nM0\nG1 Y5\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog(&jog("X", -1, Some(40.0))).unwrap();
    settle(&mut ch);
    ch.set_mode(Mode::Auto).unwrap();
    ch.start().unwrap();
    for _ in 0..100 {
        ch.step();
    }
    ch.stop();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
    let x = ch.axis_positions()[0];
    assert!(x > 10.0 && x < 50.0, "{x}");
    ch.start().unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Idle);
    assert_eq!(ch.axis_positions(), &[50.0, 5.0, 0.0]);
}

#[test]
fn repos_with_transmit_travels_cartesian_and_continues_the_contour() {
    let program = "T1 D1 G17 F5000\nG0 X20 Z10\nTRANSMIT\nG1 X10 Y-10\nM0\nX-10\nM0\nM30";
    let mut ch = channel("transmit-example", "");
    ch.run_program(program).unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
    let s = ch.snapshot();
    assert!(close(pos(&s.basic, "X"), 10.0, 1e-9) && close(pos(&s.basic, "Y"), -10.0, 1e-9));
    ch.set_mode(Mode::Jog).unwrap();
    // Cartesian JOG of Y in the WCS: the tool tip moves along Y, XM and CM follow.
    ch.jog_in(&jog("Y", 1, Some(5.0)), JogSystem::Workpiece).unwrap();
    settle(&mut ch);
    let s = ch.snapshot();
    assert!(s.transformation.is_some(), "TRANSMIT stays active in JOG");
    assert!(close(pos(&s.basic, "X"), 10.0, 1e-6) && close(pos(&s.basic, "Y"), -5.0, 1e-6), "{:?}", s.basic);
    // Polar: r = sqrt(10² + 5²).
    assert!(close(machine(&s, "XM"), 125f64.sqrt(), 1e-6), "{:?}", s.machine);
    // A machine-axis JOG of XM (MCS) with the transformation active: XM alone moves.
    let cm = machine(&s, "CM");
    ch.jog_in(&jog("XM", 1, Some(3.0)), JogSystem::Machine).unwrap();
    settle(&mut ch);
    let s = ch.snapshot();
    assert!(close(machine(&s, "XM"), 125f64.sqrt() + 3.0, 1e-9) && close(machine(&s, "CM"), cm, 1e-9));
    ch.set_mode(Mode::Auto).unwrap();
    ch.start().unwrap();
    settle(&mut ch);
    // REPOS back to (10, -10), then the next block to (-10, -10) and its M0.
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(close(pos(&s.basic, "X"), -10.0, 1e-6) && close(pos(&s.basic, "Y"), -10.0, 1e-6), "{:?}", s.basic);
    assert!(close(machine(&s, "XM"), 200f64.sqrt(), 1e-6));
    ch.start().unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Idle);
}

// --- Block search -------------------------------------------------------------------------------

const SEARCH_PROGRAM: &str = "G0 X0 Y0\nG1 X10 F1000\nM3 S1000\nG1 Y20\nX30 Y25\nM30";

#[test]
fn block_search_collects_the_state_and_approaches_the_target_block() {
    let mut ch = channel("mill-3axis", "");
    ch.block_search(Some(SEARCH_PROGRAM), 5).unwrap();
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped);
    assert_eq!(s.block.as_ref().map(|b| (b.line, b.text.as_str())), Some((5, "X30 Y25")));
    assert_eq!(ch.axis_positions(), &[0.0, 0.0, 0.0], "a search does not move");
    assert!(s.spindles.iter().all(|(_, rpm)| *rpm == 0.0), "M3 is output at NC start");
    ch.start().unwrap();
    let samples = settle(&mut ch);
    // The approach: a straight line from (0, 0) to the start of line 5, (10, 20), at F1000.
    let at = samples.iter().position(|s| s[0] == 10.0 && s[1] == 20.0).expect("reaches (10, 20)");
    for w in samples[..=at].windows(2) {
        assert!(close(w[1][1], 2.0 * w[1][0], 1e-9), "on y = 2x: {:?}", w[1]);
        let v = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt() / 0.004;
        assert!(v <= 1000.0 / 60.0 + 1e-6, "{v}");
    }
    assert_eq!(ch.axis_positions(), &[30.0, 25.0, 0.0]);
    assert_eq!(ch.status(), Status::Idle);
    let rpm = ch.snapshot().spindles.first().map(|s| s.1);
    assert!(rpm.is_none() || rpm == Some(1000.0), "{rpm:?}");
}

#[test]
fn block_search_refuses_lines_that_do_not_exist_and_alarms_on_a_target_never_reached() {
    let mut ch = channel("mill-3axis", "");
    let err = ch.block_search(Some(SEARCH_PROGRAM), 99).unwrap_err();
    assert!(err.to_string().contains("line 99 does not exist: the program has 6 lines"), "{err}");
    assert!(matches!(ch.block_search(Some(SEARCH_PROGRAM), 0), Err(CommandError::Invalid(_))));
    assert!(matches!(ch.block_search(Some("G0 X1\n; note\nM30"), 2), Err(CommandError::Invalid(_))));
    assert!(matches!(ch.block_search(None, 1), Err(CommandError::Invalid(_))), "no program loaded");
    assert_eq!(ch.status(), Status::Idle);
    // After M30: never reached.
    ch.block_search(Some("G0 X1\nM30\nG0 X5"), 3).unwrap();
    assert_eq!(ch.status(), Status::Alarm);
    assert_eq!(ch.alarms()[0].number, 15370);
    ch.reset();
    ch.set_mode(Mode::Jog).unwrap();
    assert!(matches!(ch.block_search(Some(SEARCH_PROGRAM), 2), Err(CommandError::WrongMode(..))));
}

#[test]
fn block_search_keeps_incremental_positions_and_frames_of_skipped_blocks() {
    // G91 and TRANS before the target: the target's start is where the skipped blocks end.
    let program = "G91 G1 X5 F2000\nX5\nTRANS Y10\nG90 X2 Y0\nG1 X4\nM30";
    let mut ch = channel("mill-3axis", "");
    ch.block_search(Some(program), 5).unwrap();
    ch.start().unwrap();
    let samples = settle(&mut ch);
    // Line 4 ends at WCS (2, 0) = BCS (2, 10); the approach goes there straight from (0, 0).
    assert!(samples.iter().any(|s| s[0] == 2.0 && s[1] == 10.0));
    assert!(samples.iter().all(|s| s[0] <= 4.0), "X10 of the skipped blocks is never travelled");
    assert_eq!(ch.axis_positions(), &[4.0, 10.0, 0.0]);
}

// --- Reference point state --------------------------------------------------------------------

#[test]
fn presets_start_referenced() {
    let ch = channel("mill-3axis", "");
    assert!(ch.snapshot().referenced.iter().all(|(_, r)| *r));
    assert_eq!(ch.snapshot().referenced.len(), 3);
}

#[test]
fn an_unreferenced_axis_locks_nc_start_until_it_is_referenced() {
    let mut ch = channel("mill-3axis", "$MA_ENC_REFP_STATE[Y]=0");
    assert_eq!(ch.snapshot().referenced, vec![("X".into(), true), ("Y".into(), false), ("Z".into(), true)]);
    let err = ch.run_program("G0 X1\nM30").unwrap_err();
    assert!(err.to_string().contains("16905"), "{err}");
    assert_eq!(ch.alarms()[0].number, 16905);
    assert!(ch.alarms()[0].message.contains("axis Y"), "{}", ch.alarms()[0].message);
    assert_eq!(ch.status(), Status::Idle);
    assert_eq!(ch.mode(), Mode::Auto);
    assert!(ch.mda("G0 X1").is_err());
    // JOG of the unreferenced axis works; referencing is a JOG function.
    assert!(ch.reference_axes(Some("Y")).is_err(), "not in AUTO");
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog(&jog("Y", 1, Some(1.0))).unwrap();
    settle(&mut ch);
    assert!(matches!(ch.reference_axes(Some("Q")), Err(CommandError::UnknownAxis(_))));
    ch.reference_axes(Some("Y")).unwrap();
    // An incremental encoder (MD34200 = 1): the reference point approach ends at REFP_SET_POS 0.
    settle(&mut ch);
    assert!(ch.snapshot().referenced.iter().all(|(_, r)| *r));
    ch.cancel_alarms();
    ch.set_mode(Mode::Auto).unwrap();
    ch.run_program("G0 X1\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(ch.axis_positions(), &[1.0, 0.0, 0.0]);
}

#[test]
fn the_start_lock_follows_md20700_and_md34110() {
    for md in
        ["$MA_ENC_REFP_STATE[Z]=1\n$MC_REFP_NC_START_LOCK=FALSE", "$MA_ENC_REFP_STATE[Z]=0\n$MA_REFP_CYCLE_NR[Z]=-1"]
    {
        let mut ch = channel("mill-3axis", md);
        assert!(!ch.snapshot().referenced[2].1);
        ch.run_program("G0 X1\nM30").unwrap();
        settle(&mut ch);
        assert_eq!(ch.axis_positions()[0], 1.0, "{md}");
    }
}

#[test]
fn new_machine_data_keeps_referenced_axes_referenced() {
    let mut ch = channel("mill-3axis", "$MA_ENC_REFP_STATE[X]=0\n$MA_ENC_REFP_STATE[Y]=0");
    ch.set_mode(Mode::Jog).unwrap();
    ch.reference_axes(Some("X")).unwrap();
    settle(&mut ch);
    ch.apply_machine_data("$MA_JOG_VELO[X]=1000.").unwrap();
    let r = ch.snapshot().referenced;
    assert_eq!((r[0].1, r[1].1), (true, false));
}

#[test]
fn block_search_outputs_the_collected_spindle_command_at_nc_start() {
    // S1000 M3 before the target: G95 F0.1 mm/rev in the target is 100 mm/min once it runs.
    let mut ch = channel("lathe-2axis", "");
    ch.block_search(Some("G0 X50 Z10\nS1000 M3\nG95 G1 Z-10 F0.1\nM30"), 3).unwrap();
    assert_eq!(ch.snapshot().spindles, vec![("SP".to_string(), 0.0)]);
    ch.start().unwrap();
    let samples = settle(&mut ch);
    assert_eq!(ch.snapshot().spindles, vec![("SP".to_string(), 1000.0)]);
    let p = ch.axis_positions();
    assert!(close(p[0], 50.0, 1e-9) && close(p[1], -10.0, 1e-9), "{p:?}");
    // Approach (0, 0) → (50, 10) and the 20 mm of the block, both at 100 mm/min.
    let moving = samples.windows(2).filter(|w| w[0] != w[1]).count() as f64 * 0.004;
    let expected = (2600f64.sqrt() + 20.0) / (100.0 / 60.0);
    assert!(close(moving, expected, 0.1), "{moving} s, expected {expected} s");
}

#[test]
fn block_search_over_a_transmit_selection_approaches_in_the_bcs_with_transmit_active() {
    let mut ch = channel("transmit-example", "");
    ch.mda("G0 X20 Z10").unwrap();
    settle(&mut ch);
    ch.set_mode(Mode::Auto).unwrap();
    let program = "T1 D1 G17 F5000\nG0 X20 Z10\nTRANSMIT\nG1 X10 Y-10\nX-10\nM0\nY10\nM30";
    ch.block_search(Some(program), 5).unwrap();
    assert!(ch.snapshot().transformation.is_none(), "selected at NC start");
    ch.start().unwrap();
    let samples = settle(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(s.transformation.is_some());
    assert!(close(pos(&s.basic, "X"), -10.0, 1e-6) && close(pos(&s.basic, "Y"), -10.0, 1e-6), "{:?}", s.basic);
    // Tool length 30 of T1 D1 (collected) along Z: ZM = 10 + 30.
    assert!(close(machine(&s, "ZM"), 40.0, 1e-9), "{:?}", s.machine);
    // The approach ended at the start of line 5, BCS (10, -10): XM = √200 at CM = 315°.
    assert!(
        samples.iter().any(|m| close(m[0], 200f64.sqrt(), 1e-6) && close(m[1].rem_euclid(360.0), 315.0, 1e-6)),
        "never at (10, -10)"
    );
}

#[test]
fn cartesian_jog_and_repos_past_the_transmit_pole_keep_the_rotary_axis_within_its_velocity() {
    let program = "T1 D1 G17 F5000\nG0 X20 Z10\nTRANSMIT\nG1 X10 Y-10\nM0\nM30";
    let mut ch = channel("transmit-example", "");
    ch.run_program(program).unwrap();
    settle(&mut ch);
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog_in(&jog("Y", 1, Some(9.5)), JogSystem::Workpiece).unwrap();
    let mut samples = settle(&mut ch);
    // 0.5 mm beside the pole: C turns by about 180° within a few mm of X.
    ch.jog_in(&jog("X", -1, Some(20.0)), JogSystem::Workpiece).unwrap();
    samples.extend(settle(&mut ch));
    let s = ch.snapshot();
    assert!(close(pos(&s.basic, "X"), -10.0, 1e-6) && close(pos(&s.basic, "Y"), -0.5, 1e-6), "{:?}", s.basic);
    ch.set_mode(Mode::Auto).unwrap();
    ch.start().unwrap();
    samples.extend(settle(&mut ch));
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    // CM: MAX_AX_VELO 100 rev/min = 600°/s, i.e. 2.4° per 4 ms cycle.
    let max_step = samples.windows(2).map(|w| (w[1][1] - w[0][1]).abs()).fold(0.0, f64::max);
    assert!(max_step <= 2.4 * (1.0 + 1e-6), "CM moved {max_step}° in one cycle");
}

/// The CA head of `mill5-head-ca` (C about Z carrying A about X, pivot 150 above the spindle
/// nose, T1 100 long): tool direction `o = (sin C·sin A, −cos C·sin A, cos A)` and tool tip
/// `P = M + (0, 0, 150) − 250·o`, written out here independently of the engine.
fn head_tip(m: &[f64]) -> [f64; 3] {
    let (sa, ca) = m[3].to_radians().sin_cos();
    let (sc, cc) = m[4].to_radians().sin_cos();
    let o = [sc * sa, -cc * sa, ca];
    [m[0] - 250.0 * o[0], m[1] - 250.0 * o[1], m[2] + 150.0 - 250.0 * o[2]]
}

/// TRAORI stays active after program end (RESET_MODE_MASK bit 7) with the head at A30 and the
/// tool tip at (0, 0, 50); then JOG mode.
fn head_at_a30() -> Channel {
    let mut ch = channel("mill5-head-ca", "$MC_RESET_MODE_MASK='H81'");
    ch.run_program("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(ch.snapshot().transformation.map(|t| t.name), Some("TRAORI".to_string()));
    ch.set_mode(Mode::Jog).unwrap();
    ch
}

#[test]
fn jog_in_the_tcs_moves_the_tool_along_its_own_axis_and_keeps_the_orientation() {
    let mut ch = head_at_a30();
    ch.jog_in(&jog("Z", 1, Some(10.0)), JogSystem::Tool).unwrap();
    let samples = settle(&mut ch);
    let s = ch.snapshot();
    // o = (0, −sin 30°, cos 30°): the tip and every machine linear axis move by 10·o.
    let (x, y, z) = (0.0, -5.0, 10.0 * 30f64.to_radians().cos());
    assert!(close(machine(&s, "X"), x, 1e-9) && close(machine(&s, "Y"), -125.0 + y, 1e-9), "{:?}", s.machine);
    assert!(close(machine(&s, "Z"), 50.0 - 150.0 + 250.0 * 30f64.to_radians().cos() + z, 1e-9), "{:?}", s.machine);
    for p in &samples {
        assert!(close(p[3], 30.0, 1e-9) && close(p[4], 0.0, 1e-9), "orientation moved: {p:?}");
        let tip = head_tip(p);
        // On the tool axis through the old tip: tip = (0, 0, 50) + t·o.
        assert!(
            close(tip[0], 0.0, 1e-9) && close(tip[1] * 30f64.to_radians().cos(), -(tip[2] - 50.0) * 0.5, 1e-9),
            "{tip:?}"
        );
    }
}

#[test]
fn orientation_jog_turns_the_tool_about_z_with_the_tip_standing_still() {
    let mut ch = head_at_a30();
    ch.jog_in(&jog("C2", 1, Some(90.0)), JogSystem::Basic).unwrap();
    let samples = settle(&mut ch);
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    // (0, −0.5, 0.866) turned by 90° about Z is (0.5, 0, 0.866): A30 with C90.
    assert!(close(machine(&s, "A"), 30.0, 1e-6) && close(machine(&s, "C"), 90.0, 1e-6), "{:?}", s.machine);
    assert!(samples.len() > 10);
    for p in &samples {
        let tip = head_tip(p);
        assert!(
            close(tip[0], 0.0, 1e-6) && close(tip[1], 0.0, 1e-6) && close(tip[2], 50.0, 1e-6),
            "tip {tip:?} at {p:?}"
        );
        // A turn about Z keeps the tilt.
        assert!(close(p[3], 30.0, 1e-6), "A {p:?}");
    }
    // Without an orientation transformation there is nothing to turn.
    let mut plain = channel("mill-3axis", "");
    plain.set_mode(Mode::Jog).unwrap();
    assert!(matches!(plain.jog_in(&jog("B2", 1, Some(5.0)), JogSystem::Basic), Err(CommandError::Invalid(_))));
}

#[test]
fn block_search_finds_the_main_program_line_not_the_same_line_of_a_subprogram() {
    // The subprogram's 2nd line moves to X5; the search target is the main program's line 2.
    let mut ch = channel("mill-3axis", "");
    ch.store_program("SUB1", "G0 Y1\nG0 X5\nM17").unwrap();
    ch.block_search(Some("SUB1\nG0 X30\nM30"), 2).unwrap();
    let s = ch.snapshot();
    assert_eq!(s.block.as_ref().map(|b| (b.line, b.text.as_str())), Some((2, "G0 X30")));
    ch.start().unwrap();
    settle(&mut ch);
    // The subprogram ran during the search (Y1 collected), the target block ends at X30.
    assert_eq!(ch.axis_positions(), &[30.0, 1.0, 0.0]);
}
