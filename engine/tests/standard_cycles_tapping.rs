//! The tapping cycles CYCLE84 (rigid tapping, G331/G332) and CYCLE840 (with compensating
//! chuck, G63 or G33) on the 3-axis mill, checked on the Z path and the spindle S1 cycle by
//! cycle, against values worked out by hand from the documented parameter lists
//! (RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1 / SDR, SDAC, ENC).

use crate::cycles_support;
use cycles_support::close;

use nctwin_engine::{Channel, SpindleMode, SpindleState};

/// One IPO cycle: time, Z (WCS) and the spindle S1.
#[derive(Clone, Copy, Debug)]
struct Tick {
    t: f64,
    z: f64,
    s: SpindleState,
}

struct Run {
    ticks: Vec<Tick>,
    ch: Channel,
}

fn run(program: &str) -> Run {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap_or_else(|e| panic!("{e}"));
    let mut ticks = Vec::new();
    while ch.is_busy() {
        ch.step();
        let s = ch.snapshot();
        let z = s.workpiece.iter().find(|(n, _)| n == "Z").unwrap().1;
        let sp = s.spindle_states.iter().find(|(n, _)| n == "S1").unwrap().1;
        ticks.push(Tick { t: s.time, z, s: sp });
        assert!(ticks.len() < 2_000_000, "program does not end");
    }
    Run { ticks, ch }
}

fn run_clean(program: &str) -> Run {
    let r = run(program);
    let alarms = r.ch.snapshot().alarms;
    assert!(alarms.is_empty(), "{alarms:?}");
    r
}

impl Run {
    /// Z where it reverses (and where it starts and ends), consecutive equal values merged:
    /// the start Z0, the approach height, the bottoms and the end. RFP+SDIS is no reversal
    /// (G0 down to it, then tapping on down), so the tests check it by the spindle there.
    fn z_turns(&self) -> Vec<f64> {
        let mut v: Vec<f64> = Vec::new();
        for t in &self.ticks {
            if v.last().is_none_or(|l| (l - t.z).abs() > 1e-9) {
                v.push(t.z);
            }
        }
        (0..v.len())
            .filter(|&i| i == 0 || i + 1 == v.len() || (v[i] - v[i - 1]).signum() != (v[i + 1] - v[i]).signum())
            .map(|i| v[i])
            .collect()
    }

    /// The first tick at which Z is at `z`.
    fn first_at(&self, z: f64) -> &Tick {
        self.ticks.iter().find(|t| (t.z - z).abs() < 1e-9).unwrap_or_else(|| panic!("Z never at {z}"))
    }

    /// The highest Z speed (mm/min) between ticks while Z lies strictly between `lo` and `hi`
    /// and moves down (`down`) or up.
    fn z_speed(&self, lo: f64, hi: f64, down: bool) -> f64 {
        // Down: from the highest point to the deepest; up: after the deepest (so the first
        // approach from Z0 does not count).
        let top = self.ticks.iter().enumerate().fold(0, |m, (i, t)| if t.z > self.ticks[m].z { i } else { m });
        let bottom = self.ticks.iter().enumerate().fold(0, |m, (i, t)| if t.z < self.ticks[m].z { i } else { m });
        let range = if down { &self.ticks[top..=bottom] } else { &self.ticks[bottom..] };
        range
            .windows(2)
            .filter(|w| w[0].z > lo && w[0].z < hi && w[1].z > lo && w[1].z < hi && (w[1].z < w[0].z) == down)
            .map(|w| (w[1].z - w[0].z).abs() / (w[1].t - w[0].t) * 60.0)
            .fold(0.0, f64::max)
    }

    fn last(&self) -> SpindleState {
        self.ticks.last().unwrap().s
    }
}

fn assert_turns(got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(close(*g, *w, 1e-6), "{got:?} vs {want:?}");
    }
}

fn angle_close(a: f64, b: f64) -> bool {
    let d = (a - b).rem_euclid(360.0);
    d < 1e-6 || 360.0 - d < 1e-6
}

#[test]
fn cycle84_taps_m10_rigidly_and_turns_the_spindle_in_and_out() {
    // M10: ISO coarse pitch 1.5 mm, right-hand. From RFP+SDIS = 2 to DP -15: 17 mm = 11.333
    // revolutions = +4080° from POSS 90° in: 90 + 4080 = 4170 ≡ 210° at the bottom; G332
    // turns back by −4080° to 90°. Feed in SST 200 · 1.5 = 300 mm/min, out SST1 500 · 1.5 =
    // 750 mm/min. SDAC 3: M3 again at the caller's S800 afterwards.
    let r = run_clean("G17 G90 G0 X10 Y10 Z50 S800 M3\nCYCLE84(10,0,2,-15,,0,3,10,,90,200,500)\nG4 F1\nM30");
    assert_turns(&r.z_turns(), &[0.0, 50.0, -15.0, 10.0]);
    let bottom = r.first_at(-15.0).s;
    assert_eq!(bottom.mode, SpindleMode::Positioning);
    assert!(angle_close(bottom.position, 210.0), "{bottom:?}");
    // Back at RFP+SDIS on the way out (after the bottom): the spindle at POSS again.
    let bottom_i = r.ticks.iter().position(|t| (t.z + 15.0).abs() < 1e-9).unwrap();
    let out = r.ticks[bottom_i..].iter().find(|t| (t.z - 2.0).abs() < 1e-9).unwrap();
    assert!(angle_close(out.s.position, 90.0), "{out:?}");
    assert!((r.z_speed(-14.0, 1.0, true) - 300.0).abs() < 1e-6);
    assert!((r.z_speed(-14.0, 1.0, false) - 750.0).abs() < 1e-6);
    let end = r.last();
    assert_eq!((end.mode, end.speed), (SpindleMode::M3, 800.0), "{end:?}");
}

#[test]
fn cycle84_left_hand_turns_m4_going_in_and_sdac_5_stops_after() {
    // MPIT -10: left-hand, the spindle turns negative going in: 0 − 4080 = −4080 ≡ 240°
    // at the bottom (POSS 0), back to 0° out. SDAC 5: M5 after the cycle.
    let r = run_clean("G17 G90 G0 X0 Y0 Z20 S600 M3\nCYCLE84(10,0,2,-15,,0,5,-10,,0,300)\nM30");
    assert_turns(&r.z_turns(), &[0.0, 20.0, -15.0, 10.0]);
    assert!(angle_close(r.first_at(-15.0).s.position, 240.0), "{:?}", r.first_at(-15.0));
    // SST1 0: out at SST too, 300 · 1.5 = 450 mm/min both ways.
    assert!((r.z_speed(-14.0, 1.0, true) - 450.0).abs() < 1e-6);
    assert!((r.z_speed(-14.0, 1.0, false) - 450.0).abs() < 1e-6);
    assert_eq!(r.last().mode, SpindleMode::M5);
}

#[test]
fn cycle84_with_pit_and_dpr_dwells_at_depth() {
    // PIT 1.25 (DPR 10 below RFP 5: depth -5), DTB 0.5 s at the depth: from Z7 12 mm =
    // 9.6 revolutions = 3456° ≡ 216° from POSS 0.
    let r = run_clean("G17 G90 G0 X0 Y0 Z20 S600 M3\nCYCLE84(20,5,2,,10,0.5,3,,1.25,0,400)\nM30");
    assert_turns(&r.z_turns(), &[0.0, 20.0, -5.0, 20.0]);
    assert!(angle_close(r.first_at(-5.0).s.position, 216.0));
    let at_depth: Vec<&Tick> = r.ticks.iter().filter(|t| (t.z + 5.0).abs() < 1e-9).collect();
    let dwell = at_depth.last().unwrap().t - at_depth[0].t;
    assert!((dwell - 0.5).abs() < 0.02, "{dwell} s at the depth");
}

#[test]
fn cycle84_chip_breaking_goes_back_by_one_pitch_after_each_infeed() {
    // _VARI 1, _DAM 6: infeeds from 2 to -4, -10, then -15; after each (but the last) back by
    // _VRT 0 → one pitch 1.5: up to -2.5 and -8.5.
    let r = run_clean("G17 G90 G0 X0 Y0 Z20 S600 M3\nCYCLE84(10,0,2,-15,,0,3,10,,0,400,,0,0,0,1,6,0)\nM30");
    assert_turns(&r.z_turns(), &[0.0, 20.0, -4.0, -2.5, -10.0, -8.5, -15.0, 10.0]);
    // The spindle stays in step with the thread: at every visit of Z the same angle.
    let at = |z: f64| -> Vec<f64> { r.ticks.iter().filter(|t| (t.z - z).abs() < 1e-9).map(|t| t.s.position).collect() };
    // 2 - (-4) = 6 mm = 4 revolutions: 0°; at -10 12 mm = 8 revolutions: 0°.
    assert!(at(-4.0).iter().all(|a| angle_close(*a, 0.0)), "{:?}", at(-4.0));
    assert!(at(-10.0).iter().all(|a| angle_close(*a, 0.0)), "{:?}", at(-10.0));
}

#[test]
fn mcall_cycle84_taps_at_every_position() {
    let r = run_clean(
        "G17 G90 G0 X0 Y0 Z20 S600 M3\nMCALL CYCLE84(10,0,2,-8,,0,3,6,,0,500)\nX10 Y10\nX30\nX50 Y20\nMCALL\nM30",
    );
    let bottoms = r.z_turns().iter().filter(|z| close(**z, -8.0, 1e-9)).count();
    assert_eq!(bottoms, 3, "{:?}", r.z_turns());
    let end = r.ch.snapshot();
    let x = end.workpiece.iter().find(|(n, _)| n == "X").unwrap().1;
    assert_eq!(x, 50.0);
}

#[test]
fn cycle84_without_a_standard_size_raises_61001_at_the_call() {
    let r = run("G17 G0 X0 Y0 Z20 S600 M3\nCYCLE84(10,0,2,-15,,0,3,7,,0,400)\nM30");
    let alarms = r.ch.snapshot().alarms;
    assert_eq!(alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(61001, Some(2))], "{alarms:?}");
}

#[test]
fn cycle84_with_sdac_6_raises_61102() {
    let r = run("G17 G0 X0 Y0 Z20 S600 M3\nCYCLE84(10,0,2,-15,,0,6,10,,0,400)\nM30");
    assert_eq!(r.ch.snapshot().alarms.first().map(|a| a.number), Some(61102));
}

#[test]
fn cycle840_without_encoder_taps_with_g63_at_the_callers_feed() {
    // ENC 1: G63 at F750 (S500 · pitch 1.5) in and out, the spindle reversed for the way out
    // (SDR 0: M3 → M4), dwell DTB 0.5 s at the depth; SDAC 3: M3 after.
    let r = run_clean("G17 G90 G0 X0 Y0 Z20 S500 M3 F750\nG4 F1\nCYCLE840(10,0,2,-12,,0.5,0,3,1)\nG4 F1\nM30");
    assert_turns(&r.z_turns(), &[0.0, 20.0, -12.0, 10.0]);
    assert!((r.z_speed(-11.0, 1.0, true) - 750.0).abs() < 1e-6);
    assert!((r.z_speed(-11.0, 1.0, false) - 750.0).abs() < 1e-6);
    // Going in the spindle turns M3, coming out M4.
    let mid_in = r.ticks.iter().find(|t| t.z < -5.0).unwrap();
    assert_eq!(mid_in.s.mode, SpindleMode::M3);
    let bottom_i = r.ticks.iter().rposition(|t| (t.z + 12.0).abs() < 1e-9).unwrap();
    let mid_out = r.ticks[bottom_i..].iter().find(|t| t.z > -5.0).unwrap();
    assert_eq!(mid_out.s.mode, SpindleMode::M4);
    let end = r.last();
    assert_eq!((end.mode, end.speed), (SpindleMode::M3, 500.0));
}

#[test]
fn cycle840_with_encoder_follows_the_spindle_with_g33() {
    // ENC 0, MPIT 8 (pitch 1.25) at S400: Z follows the spindle at 400 · 1.25 = 500 mm/min
    // in, and out with the spindle reversed (SDR 4); SDAC 5 stops it after.
    let r = run_clean("G17 G90 G0 X0 Y0 Z20 S400 M3\nG4 F1\nCYCLE840(10,0,2,-10,,0,4,5,0,8)\nM30");
    assert_turns(&r.z_turns(), &[0.0, 20.0, -10.0, 10.0]);
    assert!((r.z_speed(-9.0, 1.0, true) - 500.0).abs() < 1e-6, "{}", r.z_speed(-9.0, 1.0, true));
    assert!((r.z_speed(-9.0, 1.0, false) - 500.0).abs() < 1e-6, "{}", r.z_speed(-9.0, 1.0, false));
    assert_eq!(r.last().mode, SpindleMode::M5);
}

#[test]
fn cycle840_with_the_spindle_stopped_raises_61102() {
    let r = run("G17 G0 X0 Y0 Z20 F750\nCYCLE840(10,0,2,-12,,0,0,3,1)\nM30");
    assert_eq!(r.ch.snapshot().alarms.first().map(|a| (a.number, a.line)), Some((61102, Some(2))));
}

#[test]
fn p_s_and_p_sdir_read_the_programmed_spindle() {
    // $P_S / $P_SDIR: the last programmed speed and direction of the master spindle (and of
    // spindle 1 by number).
    run_clean(
        "S750 M4\nR1=$P_S\nR2=$P_SDIR\nR3=$P_SDIR[1]\nM5\nR4=$P_SDIR\n\
         IF (R1<>750) OR (R2<>4) OR (R3<>4) OR (R4<>5)\nSETAL(61000)\nENDIF\nM30",
    );
}
