//! The online tool offset `$AA_TOFF` seen outside the program's own motion: `$AA_IM` in
//! preparation and Cartesian JOG on the CA head of `mill5-head-ca`.
//!
//! Closed form (as in online_tool_offset.rs): `M = P − (0, 0, 150) + (250 + ΔL)·o`,
//! `o = (sin C·sin A, −cos C·sin A, cos A)`.

use nctwin_engine::channel::JogSystem;
use nctwin_engine::{Channel, JogRequest, Mode};

use crate::settle;
use settle::{channel, settle};

fn head_machine(p: [f64; 3], a: f64, dl: f64) -> [f64; 3] {
    let (sa, ca) = a.to_radians().sin_cos();
    let o = [0.0, -sa, ca];
    let l = 250.0 + dl;
    [p[0] + l * o[0], p[1] + l * o[1], p[2] - 150.0 + l * o[2]]
}

#[test]
fn aa_im_reads_the_machine_position_with_the_offset() {
    // Tip (50, 0, 50) at A30 with ΔL = 10: M = (50, −130, 50 − 150 + 260·cos 30°).
    let mut ch = channel("mill5-head-ca", "");
    ch.run_program(
        "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\n$AA_TOFF[Z]=10\nX50\nR1=$AA_IM[X]\nR2=$AA_IM[Y]\nR3=$AA_IM[Z]\nM30",
    )
    .unwrap();
    settle(&mut ch);
    let want = head_machine([50.0, 0.0, 50.0], 30.0, 10.0);
    for (i, w) in want.iter().enumerate() {
        assert!((ch.r_param(i + 1) - w).abs() < 1e-9, "R{}: {} vs {w}", i + 1, ch.r_param(i + 1));
    }
    // Without a transformation the offset adds to Z: tool 100 + 10.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("T1 D1\nG0 X0 Y0 Z50\n$AA_TOFF[Z]=10\nX50\nR3=$AA_IM[Z]\nM30").unwrap();
    settle(&mut ch);
    assert!((ch.r_param(3) - 160.0).abs() < 1e-9, "{}", ch.r_param(3));
}

fn jogged(ch: &mut Channel) -> Vec<Vec<f64>> {
    ch.set_mode(Mode::Jog).unwrap();
    let req = JogRequest { axis: "X".into(), direction: 1, increment: Some(10.0), rapid: false };
    ch.jog_with(&req, Some(JogSystem::Basic), None).unwrap();
    settle(ch)
}

#[test]
fn cartesian_jog_starts_where_the_lengthened_tool_stands() {
    // TRAORI kept over program end (RESET_MODE_MASK bit 7); the offset survives it too.
    let mut ch = channel("mill5-head-ca", "$MC_RESET_MODE_MASK='H81'\n");
    ch.run_program("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\n$AA_TOFF[Z]=10\nM30").unwrap();
    settle(&mut ch);
    let samples = jogged(&mut ch);
    assert!(samples.len() > 5);
    // Every sample: the tip (with the 260 mm tool) on the line (x, 0, 50), x from 0 to 10.
    let start = head_machine([0.0, 0.0, 50.0], 30.0, 10.0);
    for s in &samples {
        let x = s[0] - start[0];
        let want = head_machine([x, 0.0, 50.0], 30.0, 10.0);
        assert!((0..3).all(|i| (s[i] - want[i]).abs() < 1e-6), "{s:?} vs {want:?}");
        assert!((-1e-9..=10.0 + 1e-9).contains(&x), "x = {x}");
    }
    let end = ch.axis_positions();
    let want = head_machine([10.0, 0.0, 50.0], 30.0, 10.0);
    assert!((0..3).all(|i| (end[i] - want[i]).abs() < 1e-6), "{end:?} vs {want:?}");
}

#[test]
fn a_machine_axis_jog_then_a_cartesian_jog_keep_the_lengthened_tool() {
    // JOG in the MCS moves machine X by 5 (the tip with it); the following Cartesian JOG must
    // start from the tip the lengthened tool gives there, (5, 0, 50), without a jump.
    let mut ch = channel("mill5-head-ca", "$MC_RESET_MODE_MASK='H81'\n");
    ch.run_program("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F3000 A30\n$AA_TOFF[Z]=10\nM30").unwrap();
    settle(&mut ch);
    ch.set_mode(Mode::Jog).unwrap();
    let req = JogRequest { axis: "X".into(), direction: 1, increment: Some(5.0), rapid: false };
    ch.jog_with(&req, Some(JogSystem::Machine), None).unwrap();
    settle(&mut ch);
    let samples = jogged(&mut ch);
    let start = head_machine([0.0, 0.0, 50.0], 30.0, 10.0);
    for s in &samples {
        let x = s[0] - start[0];
        let want = head_machine([x, 0.0, 50.0], 30.0, 10.0);
        assert!((0..3).all(|i| (s[i] - want[i]).abs() < 1e-6), "{s:?} vs {want:?}");
    }
    let want = head_machine([15.0, 0.0, 50.0], 30.0, 10.0);
    let end = ch.axis_positions();
    assert!((0..3).all(|i| (end[i] - want[i]).abs() < 1e-6), "{end:?} vs {want:?}");
}
