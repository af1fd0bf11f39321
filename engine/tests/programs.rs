//! Part programs run through a whole channel, checked against values worked out by hand.

use nctwin_engine::{Channel, CommandError, JogRequest, Mode, Snapshot, Status};

const MAX_TICKS: usize = 2_000_000;

fn channel(preset: &str, md: &str) -> Channel {
    Channel::from_preset(preset, md).unwrap()
}

/// Steps until the channel rests; returns the channel-axis samples of every cycle.
fn settle(ch: &mut Channel) -> Vec<Vec<f64>> {
    let mut samples = vec![ch.axis_positions().to_vec()];
    while ch.is_busy() {
        ch.step();
        samples.push(ch.axis_positions().to_vec());
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    samples
}

fn run(preset: &str, md: &str, program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = channel(preset, md);
    ch.run_program(program).unwrap();
    let samples = settle(&mut ch);
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

#[test]
fn rapid_move_reaches_its_end_point_and_the_program_ends() {
    let (ch, _) = run("mill-3axis", "", "G0 X10 Y20 Z30\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Idle);
    assert_eq!((machine(&s, "X"), machine(&s, "Y"), machine(&s, "Z")), (10.0, 20.0, 30.0));
    assert_eq!(s.block, None);
}

#[test]
fn rapid_traverse_takes_the_trapezoid_time_of_the_axis() {
    // 100 mm with 500 mm/s and 3000 mm/s²: 2 × 1/6 s ramps (83.3 mm) + 16.7 mm cruise (1/30 s).
    let (ch, _) = run("mill-3axis", "", "G0 X100");
    assert!(close(ch.time(), 1.0 / 3.0 + 1.0 / 30.0, 0.008), "{}", ch.time());
}

#[test]
fn feed_motion_takes_length_over_feed_plus_one_ramp() {
    // 100 mm at F3000 = 50 mm/s: 2 s plus v/a = 50/3000 s for the ramps.
    let (ch, _) = run("mill-3axis", "", "G1 X100 F3000");
    assert!(close(ch.time(), 2.0 + 50.0 / 3000.0, 0.008), "{}", ch.time());
}

#[test]
fn incremental_dimensions_add_to_the_last_end_point() {
    let (ch, _) = run("mill-3axis", "", "G91 G0 X10 Y-5\nX10\nY=IC(1) X=AC(3)\nM30");
    let s = ch.snapshot();
    assert_eq!((machine(&s, "X"), machine(&s, "Y")), (3.0, -4.0));
}

#[test]
fn inch_dimensions_are_converted_to_millimetres() {
    let (ch, _) = run("mill-3axis", "", "G70 G0 X1\nG71 Y1\nM30");
    let s = ch.snapshot();
    assert!(close(machine(&s, "X"), 25.4, 1e-12));
    assert_eq!(machine(&s, "Y"), 1.0);
}

#[test]
fn tool_length_lifts_the_machine_position_by_l1_in_g17() {
    // T1 D1 of the mill: length 100 along Z (L1 → 3rd geometry axis in G17).
    let (ch, _) = run("mill-3axis", "", "T1 D1\nG0 X0 Y0 Z5\nM30");
    let s = ch.snapshot();
    assert_eq!(machine(&s, "Z"), 105.0);
    assert_eq!(pos(&s.basic, "Z"), 5.0);
    assert_eq!(pos(&s.workpiece, "Z"), 5.0);
    assert_eq!(s.tool, (1, 1));
}

#[test]
fn wear_and_adapter_lengths_add_to_the_geometry_length() {
    let md = "$TC_DP12[1,1]=-0.5\n$TC_DP21[1,1]=10";
    let (ch, _) = run("mill-3axis", md, "T1\nG0 Z0\nM30");
    assert!(close(machine(&ch.snapshot(), "Z"), 109.5, 1e-12));
}

#[test]
fn work_offset_g54_shifts_the_workpiece_zero() {
    let md = "$P_UIFR[1,X,TR]=100\n$P_UIFR[1,Z,TR]=-50\n$P_UIFR[1,Z,FI]=0.5";
    let (ch, _) = run("mill-3axis", md, "G54 G0 X10 Z5\nM30");
    let s = ch.snapshot();
    assert_eq!(machine(&s, "X"), 110.0);
    assert!(close(machine(&s, "Z"), -44.5, 1e-12));
    // Program end resets G54 to the reset value G500: the WCS display follows.
    assert_eq!(pos(&s.workpiece, "X"), 110.0);
    let (ch, _) = run("mill-3axis", md, "G54 G0 X10 Z5\nM0\nM30");
    assert_eq!(pos(&ch.snapshot().workpiece, "X"), 10.0);
}

#[test]
fn g53_suppresses_the_work_offset_for_one_block() {
    let md = "$P_UIFR[1,X,TR]=100";
    let (ch, _) = run("mill-3axis", md, "G54 G0 X10\nG53 X20\nM0\nX30\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped);
    assert_eq!(machine(&s, "X"), 20.0);
}

#[test]
fn a_counter_clockwise_arc_stays_on_its_circle_and_ends_on_the_end_point() {
    let (ch, samples) = run("mill-3axis", "", "G0 X10 Y0\nG3 X0 Y10 I-10 J0 F1000\nM30");
    let s = ch.snapshot();
    assert!(close(machine(&s, "X"), 0.0, 1e-12) && close(machine(&s, "Y"), 10.0, 1e-12));
    let on_arc: Vec<_> = samples.iter().filter(|p| p[1] > 1e-6).collect();
    assert!(on_arc.len() > 100);
    for p in on_arc {
        assert!(close(p[0].hypot(p[1]), 10.0, 1e-9), "{p:?}");
        assert!(p[0] >= -1e-9, "a G3 quarter from +X to +Y never crosses X<0: {p:?}");
    }
}

#[test]
fn a_clockwise_helix_over_a_full_circle_takes_its_path_length_over_feed() {
    let (ch, samples) = run("mill-3axis", "", "G0 X10 Y0 Z0\nG2 X10 Y0 Z-5 I-10 F1000\nM30");
    let s = ch.snapshot();
    assert!(close(machine(&s, "Z"), -5.0, 1e-12));
    let helix: Vec<_> = samples.iter().filter(|p| p[2] < 0.0).collect();
    for w in helix.windows(2) {
        assert!(close(w[1][0].hypot(w[1][1]), 10.0, 1e-9));
        assert!(w[1][2] <= w[0][2], "Z falls monotonically");
    }
    // Clockwise from +X goes through -Y first.
    assert!(helix[helix.len() / 4][1] < -5.0);
    // Path length sqrt((2π·10)² + 5²) = 63.03 mm at 1000 mm/min = 3.782 s.
    let feed_time = helix.len() as f64 * 0.004;
    let expected = ((20.0 * std::f64::consts::PI).powi(2) + 25.0).sqrt() / (1000.0 / 60.0);
    assert!(close(feed_time, expected, 0.03), "{feed_time} vs {expected}");
}

#[test]
fn positive_cr_takes_the_short_arc_and_negative_cr_the_long_one() {
    // Chord 20 with radius 20: the short arc rises 20 - sqrt(300) = 2.68 above the chord,
    // the long clockwise arc from left to right dips 2.68 below it and rises to 37.32.
    let max_y = |cr: &str| {
        let (_, samples) = run("mill-3axis", "", &format!("G0 X0 Y0\nG2 X20 Y0 CR={cr} F2000\nM30"));
        samples.iter().map(|p| p[1]).fold(f64::MIN, f64::max)
    };
    assert!(close(max_y("20"), 20.0 - 300f64.sqrt(), 1e-3));
    assert!(close(max_y("-20"), 20.0 + 300f64.sqrt(), 1e-3));
}

#[test]
fn an_arc_whose_end_point_is_off_the_circle_raises_14040() {
    let (ch, _) = run("mill-3axis", "", "G0 X10 Y0\nG3 X0 Y11 I-10 F1000\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm);
    assert_eq!((s.alarms[0].number, s.alarms[0].line), (14040, Some(2)));
}

#[test]
fn a_block_beyond_the_software_limit_raises_10720_and_the_machine_stops_before_it() {
    let (ch, _) = run("mill-3axis", "", "G0 X400\nG0 X600\nM30");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm);
    let a = &s.alarms[0];
    assert_eq!((a.number, a.line), (10720, Some(2)));
    assert!(a.message.contains("axis X") && a.message.contains('+'), "{}", a.message);
    assert_eq!(machine(&s, "X"), 400.0);
}

#[test]
fn an_arc_bulging_past_the_limit_is_caught_even_if_its_end_points_are_inside() {
    // Y limit is 300: a half circle from (0,250) to (0,150)... centre (0,200), radius 50,
    // clockwise from top bulges to X = +50 only; counter-clockwise through Y ≤ 300 is fine,
    // but a circle centred at Y 280 with radius 30 reaches Y 310.
    let (ch, _) = run("mill-3axis", "", "G0 X30 Y280\nG3 X-30 Y280 I-30 F1000\nM30");
    let s = ch.snapshot();
    assert_eq!(s.alarms[0].number, 10720);
    assert!(s.alarms[0].message.contains("axis Y"));
}

#[test]
fn an_arc_close_to_the_limit_but_inside_runs() {
    // Counter-clockwise half circle from (30, 250) about (0, 250), radius 30: its top is at
    // Y 280, 20 mm inside the Y limit of 300 (the quick bound |e − s| + 4·r = 120 does not
    // decide it, so the exact extremes are checked).
    let (ch, _) = run("mill-3axis", "", "G0 X30 Y250\nG3 X-30 Y250 I-30 F1000\nM30");
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert!((machine(&s, "X") + 30.0).abs() < 1e-9 && (machine(&s, "Y") - 250.0).abs() < 1e-9);
}

#[test]
fn a_feed_motion_without_f_raises_10860() {
    let (ch, _) = run("mill-3axis", "", "G1 X10\nM30");
    assert_eq!(ch.snapshot().alarms[0].number, 10860);
}

#[test]
fn an_unknown_g_function_raises_12470_with_its_line() {
    let (ch, _) = run("mill-3axis", "", "G0 X1\nG123 X2\nM30");
    let s = ch.snapshot();
    assert_eq!((s.alarms[0].number, s.alarms[0].line), (12470, Some(2)));
    assert_eq!(machine(&s, "X"), 1.0);
}

#[test]
fn unknown_tools_raise_17190_and_unknown_edges_17180() {
    assert_eq!(run("mill-3axis", "", "T7\nM30").0.snapshot().alarms[0].number, 17190);
    assert_eq!(run("mill-3axis", "", "T1 D5\nM30").0.snapshot().alarms[0].number, 17180);
}

#[test]
fn a_reset_clears_alarms_and_the_program() {
    let (mut ch, _) = run("mill-3axis", "", "G1 X10\nM30");
    ch.reset();
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Idle);
    assert!(s.alarms.is_empty());
}

#[test]
fn a_syntax_error_rejects_the_program_and_nothing_moves() {
    let mut ch = channel("mill-3axis", "");
    let err = ch.run_program("G0 X10\nG1 X=\nM30").unwrap_err();
    assert!(matches!(err, CommandError::Syntax { line: 2, .. }), "{err:?}");
    assert_eq!(ch.status(), Status::Idle);
    assert_eq!(ch.axis_positions(), &[0.0, 0.0, 0.0]);
}

#[test]
fn m0_stops_the_program_and_start_continues_it() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X10 F1000\nM0\nG1 X20\nM30").unwrap();
    settle(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped);
    assert_eq!(s.block.as_ref().map(|b| b.line), Some(2));
    assert_eq!(machine(&s, "X"), 10.0);
    ch.start().unwrap();
    settle(&mut ch);
    assert_eq!(machine(&ch.snapshot(), "X"), 20.0);
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn m1_stops_only_with_optional_stop_selected() {
    let (ch, _) = run("mill-3axis", "", "G0 X1\nM1\nG0 X2\nM30");
    assert_eq!(ch.status(), Status::Idle);
    let mut ch = channel("mill-3axis", "");
    ch.optional_stop = true;
    ch.run_program("G0 X1\nM1\nG0 X2\nM30").unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
}

#[test]
fn nc_stop_brakes_on_the_path_and_start_continues_to_the_end_point() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X100 Y100 F3000\nM30").unwrap();
    for _ in 0..200 {
        ch.step();
    }
    ch.stop();
    settle(&mut ch);
    let p = ch.axis_positions().to_vec();
    assert_eq!(ch.status(), Status::Stopped);
    assert!(p[0] > 0.0 && p[0] < 100.0 && close(p[0], p[1], 1e-9), "stopped on the path: {p:?}");
    ch.start().unwrap();
    settle(&mut ch);
    assert_eq!(ch.axis_positions(), &[100.0, 100.0, 0.0]);
}

#[test]
fn dwell_g4_waits_the_programmed_seconds() {
    let (ch, _) = run("mill-3axis", "", "G4 F1.5\nM30");
    assert!(close(ch.time(), 1.5, 0.008), "{}", ch.time());
}

#[test]
fn the_move_after_a_dwell_starts_when_the_dwell_has_run_out() {
    // G0 X10 ends at once on the mill's scale of things; G4 F1 holds X at 10 for 1 s; only
    // then does G1 X20 F600 (10 mm/s) start. Before, the move ran during the dwell and the
    // standstill came after it.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G0 X10\nG4 F1\nG1 X20 F600\nM30").unwrap();
    let samples = settle(&mut ch);
    let arrived = samples.iter().position(|p| p[0] == 10.0).expect("reaches X10");
    let leaves = samples[arrived..].iter().position(|p| p[0] > 10.0).expect("moves on") + arrived;
    let still = (leaves - arrived) as f64 * 0.004;
    assert!(close(still, 1.0, 0.009), "X stands still at 10 for {still} s");
}

#[test]
fn feed_per_revolution_follows_the_spindle_speed_on_the_lathe() {
    // S1000 with F0.1 mm/rev = 100 mm/min: 10 mm take 6 s at speed. The feed follows the
    // actual speed, which ramps 0 → 1000 rev/min in 1000/(30·60) = 0.556 s (MD35200 30 rev/s²)
    // while the axis starts at once: half the ramp, 0.278 s, is lost.
    let mut ch = channel("lathe-2axis", "");
    ch.run_program("S1000 M3\nG95 G1 Z-10 F0.1\nM30").unwrap();
    let samples = settle(&mut ch);
    let moving = samples.windows(2).filter(|w| w[0][1] != w[1][1]).count() as f64 * 0.004;
    assert!(close(moving, 6.0 + 0.5 * 1000.0 / 1800.0, 0.02), "{moving}");
    let s = ch.snapshot();
    assert_eq!(s.spindles, vec![("SP".to_string(), 1000.0)]);
}

#[test]
fn r_parameters_and_functions_compute_positions() {
    let (ch, _) = run("mill-3axis", "", "R1=30 R2=10\nG0 X=R2*COS(R1*2) Y=SQRT(16)+R2\nM30");
    let s = ch.snapshot();
    assert!(close(machine(&s, "X"), 5.0, 1e-12));
    assert_eq!(machine(&s, "Y"), 14.0);
}

#[test]
fn modulo_rotary_axes_take_the_short_way_and_acp_acn_force_the_direction() {
    let md = "$MC_AXCONF_MACHAX_USED[3]=4\n$MC_AXCONF_MACHAX_USED[4]=0\n$MN_AXCONF_MACHAX_NAME_TAB[3]=\"C\"\n$MC_AXCONF_CHANAX_NAME_TAB[3]=\"C\"\n$MA_IS_ROT_AX[AX4]=TRUE\n$MA_ROT_IS_MODULO[AX4]=TRUE\n$MA_SPIND_ASSIGN_TO_MACHAX[AX4]=0";
    // The preset's 4th machine axis is its tool spindle: made a plain modulo axis C here.
    let (ch, samples) = run("mill-3axis", md, "G0 C350\nM30");
    // 0 → 350 the short way is -10°: the axis never passes 180°.
    assert!(samples.iter().all(|p| p[3] <= 0.0 && p[3] >= -10.0));
    assert_eq!(machine(&ch.snapshot(), "C"), 350.0);
    let (_, samples) = run("mill-3axis", md, "G0 C=ACP(350)\nM30");
    assert!(samples.iter().any(|p| p[3] > 180.0));
}

#[test]
fn continuous_path_mode_is_faster_than_exact_stop() {
    let program = |g: &str| format!("{g} G1 F6000\nX10\nX20\nX30\nX40\nX50\nM30");
    let (exact, _) = run("mill-3axis", "", &program("G60"));
    let (cont, _) = run("mill-3axis", "", &program("G64"));
    assert!(cont.time() < exact.time() - 0.05, "{} vs {}", cont.time(), exact.time());
}

#[test]
fn no_axis_exceeds_its_velocity_or_acceleration_over_a_mixed_program() {
    let program = "G64 G0 X-50 Y-40 Z10\nG1 Z-2 F800\nX50 F5000\nG3 X50 Y40 CR=40\nG1 X-50\nG2 X-50 Y-40 CR=-40\nG1 X0 Y0 Z5\nM30";
    let (ch, samples) = run("mill-3axis", "", program);
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let dt = ch.config().ipo_cycle;
    let v: Vec<Vec<f64>> = samples.windows(2).map(|w| (0..3).map(|k| (w[1][k] - w[0][k]) / dt).collect()).collect();
    // X, Y, Z (the 4th machine axis is the tool spindle, not moved here).
    for (k, ax) in ch.config().machine_axes.iter().enumerate().take(3) {
        for vi in &v {
            assert!(vi[k].abs() <= ax.max_velocity * (1.0 + 1e-9), "{} at {}", ax.name, vi[k]);
        }
        for w in v.windows(2) {
            let a = (w[1][k] - w[0][k]).abs() / dt;
            assert!(a <= ax.max_accel * ax.accel_overload * (1.0 + 1e-6), "{} accelerates at {a}", ax.name);
        }
    }
}

#[test]
fn the_same_program_gives_identical_ipo_samples_twice() {
    let program =
        "G64 T1 D1\nG0 X10 Y10 Z5\nG1 Z-1 F500\nG2 X30 Y10 CR=10 F1200\nG3 X10 Y10 I-10 J0\nG1 X0 Y0 Z2\nG4 F0.2\nM30";
    let (_, a) = run("mill-3axis", "", program);
    let (_, b) = run("mill-3axis", "", program);
    let bits = |s: &Vec<Vec<f64>>| s.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
}

#[test]
fn incremental_jog_moves_by_the_increment() {
    let mut ch = channel("mill-3axis", "");
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog(&JogRequest { axis: "X".into(), direction: -1, increment: Some(5.0), rapid: false }).unwrap();
    assert_eq!(ch.status(), Status::Running);
    settle(&mut ch);
    assert_eq!(ch.axis_positions()[0], -5.0);
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn continuous_jog_runs_at_jog_velocity_until_released() {
    let mut ch = channel("mill-3axis", "");
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog(&JogRequest { axis: "Y".into(), direction: 1, increment: None, rapid: false }).unwrap();
    for _ in 0..500 {
        ch.step();
    }
    // JOG_VELO 2000 mm/min = 33.3 mm/s, reached after 11 ms: about 2 s × 33.3 mm/s.
    let y = ch.axis_positions()[1];
    assert!(close(y, 2.0 * 2000.0 / 60.0, 0.5), "{y}");
    ch.jog_stop();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Idle);
    assert!(ch.axis_positions()[1] < y + 1.0);
}

#[test]
fn jog_stops_at_the_software_limit_with_10621() {
    let mut ch = channel("mill-3axis", "$MA_POS_LIMIT_PLUS[X]=20");
    ch.set_mode(Mode::Jog).unwrap();
    ch.jog(&JogRequest { axis: "X".into(), direction: 1, increment: None, rapid: true }).unwrap();
    settle(&mut ch);
    assert_eq!(ch.axis_positions()[0], 20.0);
    assert_eq!(ch.alarms()[0].number, 10621);
    ch.cancel_alarms();
    assert!(ch.alarms().is_empty());
}

#[test]
fn jog_is_refused_outside_jog_mode() {
    let mut ch = channel("mill-3axis", "");
    let err = ch.jog(&JogRequest { axis: "X".into(), direction: 1, increment: Some(1.0), rapid: false });
    assert!(matches!(err, Err(CommandError::WrongMode(..))));
}

#[test]
fn mda_runs_single_blocks_in_mda_mode() {
    let mut ch = channel("mill-3axis", "");
    ch.mda("G0 X5 Y-5").unwrap();
    assert_eq!(ch.mode(), Mode::Mda);
    settle(&mut ch);
    assert_eq!(ch.axis_positions(), &[5.0, -5.0, 0.0]);
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn the_transmit_machine_moves_x_and_z_and_refuses_its_spindle_as_an_axis_without_spos() {
    let (ch, _) = run("transmit-example", "", "G0 X20 Z10\nM30");
    let s = ch.snapshot();
    assert_eq!((machine(&s, "XM"), machine(&s, "ZM")), (20.0, 10.0));
    let (ch, _) = run("transmit-example", "", "G0 C90\nM30");
    let a = &ch.snapshot().alarms[0];
    assert_eq!(a.number, 12550);
    assert!(a.message.contains("SPOS"), "{}", a.message);
}

#[test]
fn a_mirrored_counter_clockwise_arc_runs_clockwise_in_the_machine() {
    // MIRROR X0: the WCS quarter circle from (10,0) to (0,10) around the origin is the BCS
    // quarter from (-10,0) to (0,10), travelled clockwise through the second quadrant.
    let (_, samples) = run("mill-3axis", "", "MIRROR X0\nG0 X10 Y0\nG3 X0 Y10 I-10 J0 F1000\nM30");
    let arc: Vec<_> = samples.iter().filter(|p| p[1] > 1e-6).collect();
    assert!(arc.len() > 50);
    for p in arc {
        assert!(p[0] <= 1e-9 && close(p[0].hypot(p[1]), 10.0, 1e-9), "{p:?}");
    }
}

#[test]
fn an_arc_under_rot_x90_runs_in_the_machine_x_z_plane() {
    let (_, samples) = run("mill-3axis", "", "ROT X90\nG0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0 F1000\nM30");
    let arc: Vec<_> = samples.iter().filter(|p| p[2] > 1e-6).collect();
    assert!(arc.len() > 50);
    for p in arc {
        assert!(p[1].abs() < 1e-9 && close(p[0].hypot(p[2]), 10.0, 1e-9), "{p:?}");
    }
}

#[test]
fn an_opening_angle_of_90_degrees_bulges_by_the_sagitta() {
    // Chord 20, AR=90: radius 14.142, the clockwise arc from (0,0) to (20,0) rises
    // r - r·cos 45° = 4.142 above the chord.
    let (_, samples) = run("mill-3axis", "", "G0 X0 Y0\nG2 X20 Y0 AR=90 F1000\nM30");
    let top = samples.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
    let r = 20.0 / 2f64.sqrt();
    assert!(close(top, r - r * (std::f64::consts::FRAC_PI_4).cos(), 1e-3), "{top}");
}

#[test]
fn a_helix_with_turn_takes_three_circles_of_path() {
    let (ch, samples) = run("mill-3axis", "", "G0 X10 Y0 Z0\nG3 X10 Y0 Z-6 I-10 J0 TURN=2 F3000\nM30");
    let moving = samples.iter().filter(|p| p[2] < 0.0 && p[2] > -6.0).count() as f64 * ch.config().ipo_cycle;
    let length = ((3.0 * 2.0 * std::f64::consts::PI * 10.0).powi(2) + 36.0).sqrt();
    assert!(close(moving, length / 50.0, 0.05), "{moving} s for {length} mm at 50 mm/s");
}

#[test]
fn rnd_rounds_a_right_angle_corner_on_a_circle_tangent_to_both_lines() {
    let (ch, samples) = run("mill-3axis", "", "G64 G1 X0 Y0 F2000\nG1 X20 RND=5\nY20\nM30");
    assert_eq!(ch.status(), Status::Idle, "{:?}", ch.alarms());
    let fillet: Vec<_> = samples.iter().filter(|p| p[0] > 15.0 + 1e-9 && p[1] < 5.0 - 1e-9).collect();
    assert!(fillet.len() > 5, "the path runs on the fillet");
    for p in fillet {
        assert!(close((p[0] - 15.0).hypot(p[1] - 5.0), 5.0, 1e-9), "{p:?}");
    }
    assert_eq!(ch.axis_positions()[..2], [20.0, 20.0]);
}

#[test]
fn chf_cuts_the_corner_with_a_chamfer_of_the_given_length() {
    // CHF = 2·sqrt(2) at a right angle: legs of 2 mm, the chamfer from (18,0) to (20,2).
    let (_, samples) = run("mill-3axis", "", "G1 X0 Y0 F2000\nG1 X20 CHF=2.8284271247461903\nY20\nM30");
    let cut: Vec<_> = samples.iter().filter(|p| p[0] > 18.0 + 1e-9 && p[1] < 2.0 - 1e-9).collect();
    assert!(!cut.is_empty());
    for p in cut {
        assert!(close(p[0] - p[1], 18.0, 1e-9), "{p:?}");
    }
}

#[test]
fn a_rounding_larger_than_the_blocks_allow_is_an_alarm() {
    let (ch, _) = run("mill-3axis", "", "G1 X0 Y0 F2000\nG1 X3 RND=5\nY20\nM30");
    assert_eq!(ch.snapshot().alarms[0].number, 12560);
}

#[test]
fn the_feed_override_scales_the_path_speed_and_zero_stops_on_the_path() {
    use nctwin_engine::Overrides;
    let mut ch = channel("mill-3axis", "");
    ch.set_overrides(Overrides { feed: 50.0, ..Overrides::default() }).unwrap();
    ch.run_program("G1 X100 F3000\nM30").unwrap();
    settle(&mut ch);
    // 100 mm at 1500 mm/min = 25 mm/s: 4 s plus 25/3000 s of ramps.
    assert!(close(ch.time(), 4.0 + 25.0 / 3000.0, 0.01), "{}", ch.time());

    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X100 F3000\nM30").unwrap();
    for _ in 0..100 {
        ch.step();
    }
    ch.set_overrides(Overrides { feed: 0.0, ..Overrides::default() }).unwrap();
    for _ in 0..100 {
        ch.step();
    }
    let x = ch.axis_positions()[0];
    ch.step();
    assert_eq!(ch.axis_positions()[0], x, "standing still at 0 %");
    assert_eq!(ch.status(), Status::Running);
    ch.set_overrides(Overrides::default()).unwrap();
    settle(&mut ch);
    assert_eq!(ch.axis_positions()[0], 100.0);
}

#[test]
fn overrides_outside_their_range_are_refused() {
    use nctwin_engine::Overrides;
    let mut ch = channel("mill-3axis", "");
    assert!(ch.set_overrides(Overrides { feed: 130.0, ..Overrides::default() }).is_err());
    assert!(ch.set_overrides(Overrides { rapid: 110.0, ..Overrides::default() }).is_err());
    assert!(ch.set_overrides(Overrides { spindle: 10.0, ..Overrides::default() }).is_err());
}

#[test]
fn single_block_stops_after_each_moving_block() {
    let mut ch = channel("mill-3axis", "");
    ch.single_block = true;
    ch.run_program("G0 X10\nR1=5\nG0 Y10\nG0 Z10\nM30").unwrap();
    let mut stops = Vec::new();
    for _ in 0..10 {
        settle(&mut ch);
        if ch.status() != Status::Stopped {
            break;
        }
        stops.push((ch.snapshot().block.map(|b| b.line), ch.axis_positions().to_vec()));
        ch.start().unwrap();
    }
    assert_eq!(stops.len(), 3, "{stops:?}");
    assert_eq!(stops[0], (Some(1), vec![10.0, 0.0, 0.0]));
    assert_eq!(stops[1], (Some(3), vec![10.0, 10.0, 0.0]));
    assert_eq!(stops[2], (Some(4), vec![10.0, 10.0, 10.0]));
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn spos_stops_the_spindle_and_makes_it_a_rotary_axis_until_m3() {
    let (ch, _) = run("lathe-2axis", "", "S600 M3\nG4 F1\nSPOS=90\nR1=$AA_IM[SP]\nG0 SP=180\nM0");
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(close(ch.r_param(1), 90.0, 1e-9), "{}", ch.r_param(1));
    assert!(close(machine(&s, "SP1"), 180.0, 1e-9));
    assert_eq!(s.spindles[0].1, 0.0, "the spindle stands");
    // Without SPOS the spindle cannot be programmed as an axis.
    let (ch, _) = run("lathe-2axis", "", "G0 SP=180\nM30");
    assert_eq!(ch.snapshot().alarms[0].number, 12550);
}

#[test]
fn the_state_shows_the_g_functions_of_the_block_in_execution() {
    let mut ch = channel("mill-3axis", "");
    assert_eq!(ch.snapshot().gcodes[..8], ["G1", "G17", "G40", "G500", "G60", "G71", "G90", "G94"].map(String::from));
    // Stopped at M0 after G0/G18/G91/G54/G64 were prepared: they show; the next block's G3 and
    // G70 are prepared already but not executed, so they do not.
    ch.run_program("G0 G18 G91 G54 G64 X1\nM0\nG70 G3 X1 Z1 CR=2 F100\nM30").unwrap();
    settle(&mut ch);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped);
    assert_eq!(s.gcodes[..8], ["G0", "G18", "G40", "G54", "G64", "G71", "G91", "G94"].map(String::from));
}
