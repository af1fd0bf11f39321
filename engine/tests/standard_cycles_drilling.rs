//! The drilling cycles CYCLE82..CYCLE89 of the standard cycle library, checked on the path they
//! produce: depths, pecks and retraction heights worked out by hand from the documented
//! parameter lists (Cycles Programming Manual: RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB,
//! DTS, FRF, VARI, _AXN, _MDEP, _VRT, _DTD, _DIS1).

use crate::cycles_support;
use cycles_support::*;

const Z: usize = 2;

fn assert_points(got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(close(*g, *w, 1e-6), "{got:?} vs {want:?}");
    }
}

/// The highest speed (mm/s) along `k` between consecutive samples while `k` lies in (lo, hi),
/// moving down (`down`) or up.
fn top_speed(t: &Trace, k: usize, lo: f64, hi: f64, down: bool) -> f64 {
    // From the first arrival at the start height 50 on (the approach from 0 is no part of it).
    let from = t.samples.iter().position(|s| s.p[k] >= 50.0).map_or(0, |i| i.min(t.samples.len() - 1));
    t.samples[from..]
        .windows(2)
        .filter(|w| w[0].p[k] > lo && w[0].p[k] < hi && w[1].t > w[0].t && (w[1].p[k] < w[0].p[k]) == down)
        .map(|w| (w[1].p[k] - w[0].p[k]).abs() / (w[1].t - w[0].t))
        .fold(0.0, f64::max)
}

#[test]
fn cycle82_dwells_at_the_final_depth() {
    // DTB 2 s at Z-5; up to RTP 10 after it.
    let t = run_clean("G17 G90 F200\nG0 X10 Y20 Z50\nCYCLE82(10,0,2,-5,,2)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[50.0, -5.0, 10.0]);
    let dwell = t.dwell_at(Z, -5.0);
    assert!(close(dwell, 2.0, 0.01), "dwell {dwell}");
}

#[test]
fn cycle83_chip_removal_pecks_with_degression_and_leaves_the_hole_each_time() {
    // First depth 8 below RFP 0. DAM 3: strokes 8, 5, then 3 (5-3 < 3), then the 4 left are
    // less than 2 x 3 and split 2 + 2: depths -8, -13, -16, -18, -20. VARI 1: G0 up to
    // RFP+SDIS = 2 after each depth; back in at G0 to 0.6 above the last depth (depth <= 30 mm).
    let t = run_clean("G17 G90 F200\nG0 X10 Y10 Z50\nCYCLE83(50,0,2,-20,,-8,,3,0,0,1,1)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[50.0, -8.0, 2.0, -13.0, 2.0, -16.0, 2.0, -18.0, 2.0, -20.0, 50.0]);
    // The second plunge (from RFP+SDIS 2 down to -13): rapid down to -8 + 0.6 = -7.4, then
    // feed (200 mm/min = 3.33 mm/s) to -13.
    let to13 = t.samples.iter().position(|s| s.p[Z] <= -13.0 + 1e-9).unwrap();
    let from2 = t.samples[..to13].iter().rposition(|s| s.p[Z] >= 2.0 - 1e-9).unwrap();
    let plunge = Trace {
        ch: nctwin_engine::Channel::from_preset("mill-3axis", "").unwrap(),
        samples: t.samples[from2..=to13].to_vec(),
        alarms: vec![],
    };
    let feed = 200.0 / 60.0;
    let v = top_speed(&plunge, Z, -12.9, -7.45, true);
    assert!(v <= feed * 1.001, "feed after the anticipation point: {v}");
    assert!(top_speed(&plunge, Z, -7.0, 1.0, true) > 2.0 * feed, "rapid back into the hole");
    assert_eq!(t.end(), [10.0, 10.0, 50.0]);
}

#[test]
fn cycle83_chip_breaking_retracts_by_one_millimetre_at_each_depth() {
    // VARI 0, _VRT 0: 1 mm back at each depth, same depths as above.
    let t = run_clean("G17 G90 F200\nG0 X10 Y10 Z50\nCYCLE83(50,0,2,-20,,-8,,3,0,0,1,0)\nM30");
    assert_points(
        &t.turning_points(Z)[1..],
        &[50.0, -8.0, -7.0, -13.0, -12.0, -16.0, -15.0, -18.0, -17.0, -20.0, 50.0],
    );
}

#[test]
fn cycle83_relative_first_depth_feed_factor_dwells_and_variable_retraction() {
    // RFP 5, DPR 12 → depth -7; FDPR 6 → first depth -1 (FDPR wins over FDEP -3). DAM 0: every
    // stroke 6 deep: -1, -7. FRF 0.5: the first stroke at 100 mm/min. _VRT 2.5: back to 1.5.
    // DTB 0.4 s at -1, _DTD 1.2 s at the final depth.
    let t = run_clean("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE83(20,5,1,,12,-3,6,0,0.4,0,0.5,0,0,0,2.5,1.2)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[50.0, -1.0, 1.5, -7.0, 20.0]);
    assert!(top_speed(&t, Z, 1.6, 5.9, true) <= 100.0 / 60.0 * 1.001);
    assert!(top_speed(&t, Z, -6.9, -1.1, true) > 150.0 / 60.0);
    let (d1, d2) = (t.dwell_at(Z, -1.0), t.dwell_at(Z, -7.0));
    assert!(close(d1, 0.4, 0.01) && close(d2, 1.2, 0.01), "dwells {d1} {d2}");
}

#[test]
fn cycle83_first_depth_beyond_the_final_depth_drills_in_one_stroke() {
    let t = run_clean("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE83(10,0,2,-6,,-9,,2,0,0,1,1)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[50.0, -6.0, 10.0]);
}

#[test]
fn cycle83_in_g18_drills_along_y_and_axn_picks_another_axis() {
    // G18: the applicate is Y. With _AXN 3 the drilling axis is Z whatever the plane.
    let t = run_clean("G18 G90 F300\nG0 X0 Y40 Z0\nCYCLE83(30,0,1,-10,,-5,,0,0,0,1,0)\nM30");
    assert_points(&t.turning_points(1)[1..], &[40.0, -5.0, -4.0, -10.0, 30.0]);
    let t = run_clean("G18 G90 F300\nG0 X0 Y0 Z40\nCYCLE83(30,0,1,-10,,-5,,0,0,0,1,0,3)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[40.0, -5.0, -4.0, -10.0, 30.0]);
}

#[test]
fn cycle83_restores_the_callers_feed() {
    // FRF 0.5 halves the first stroke's feed; the caller's F200 is in force afterwards:
    // 10 mm at 200 mm/min = 3 s.
    let t = run_clean("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE83(10,0,2,-6,,-3,,0,0,0,0.5,1)\nG1 X10\nM30");
    let start = t.samples.iter().rev().find(|s| s.p[0] == 0.0).unwrap().t;
    let stop = t.samples.iter().find(|s| s.p[0] == 10.0).unwrap().t;
    assert!((stop - start - 3.0).abs() < 0.1, "{}", stop - start);
}

#[test]
fn bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // Depth above the reference plane: 61101; first depth above it: 61107; VARI 2: 61002.
    for (call, number) in [
        ("CYCLE82(10,0,2,5)", 61101),
        ("CYCLE83(10,0,2,-20,,4,,2,0,0,1,1)", 61107),
        ("CYCLE83(10,0,2,-20,,-4,,2,0,0,1,2)", 61002),
        ("CYCLE86(10,0,2,-5,,0,5)", 61102),
    ] {
        let t = run(&format!("G17 G90 F200\nG0 X0 Y0 Z50\n{call}\nM30"));
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(3)), "{call}");
        assert!(!t.alarms[0].message.ends_with("cycle alarm"), "the manual's text: {}", t.alarms[0].message);
        assert_eq!(t.end()[Z], 50.0, "{call}: nothing moved");
    }
    let t = run("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE82(10,0,2,5)\nM30");
    assert!(t.alarms[0].message.contains("reference plane defined incorrectly"), "{}", t.alarms[0].message);
}

#[test]
fn cycle85_feeds_in_and_out_at_its_own_feeds() {
    // FFR 120 in, RFF 600 out to RFP+SDIS = 2, then G0 to RTP 50; the caller's F comes back.
    let t = run_clean("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE85(50,0,2,-10,,0,120,600)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[50.0, -10.0, 50.0]);
    assert!(top_speed(&t, Z, -9.9, 1.9, false) <= 600.0 / 60.0 * 1.001);
    let down = t.samples.windows(2).filter(|w| w[1].p[Z] < w[0].p[Z] && w[0].p[Z] < 1.9 && w[0].p[Z] > -9.9);
    assert!(down.map(|w| (w[0].p[Z] - w[1].p[Z]) / (w[1].t - w[0].t)).fold(0.0, f64::max) <= 2.0 * 1.001);
    assert!(top_speed(&t, Z, -9.0, -1.0, false) > 9.0, "out at 10 mm/s");
}

#[test]
fn cycle89_dwells_and_feeds_back_out() {
    let t = run_clean("G17 G90 F300\nG0 X0 Y0 Z50\nCYCLE89(50,0,2,-10,,1)\nM30");
    assert_points(&t.turning_points(Z)[1..], &[50.0, -10.0, 50.0]);
    assert!(top_speed(&t, Z, -9.0, 1.0, false) <= 5.0 * 1.001, "out at the feed 300 mm/min");
    assert!(close(t.dwell_at(Z, -10.0), 1.0, 0.01));
}

#[test]
fn cycle86_stops_the_spindle_oriented_and_lifts_off_before_leaving() {
    // RPA 1, RPO -0.5, RPAP 0.2: from the bottom (10, 20, -10) to (11, 19.5, -9.8), out to
    // RFP+SDIS = 2 with the offset kept, back over the centre, then up to RTP 30.
    let t = run_on(
        "tracyl-xyzac",
        "G17 G90 F200 M3 S500\nG0 X10 Y20 Z50\nCYCLE86(30,0,2,-10,,0,3,1,-0.5,0.2,90)\nM30",
        &[],
    );
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    assert_points(&t.turning_points(Z)[1..], &[50.0, -10.0, 30.0]);
    let lifted = |s: &Sample| close(s.p[0], 11.0, 1e-6) && close(s.p[1], 19.5, 1e-6);
    assert!(t.samples.iter().any(|s| lifted(s) && close(s.p[2], -9.8, 1e-6)));
    assert!(t.samples.iter().any(|s| lifted(s) && close(s.p[2], 2.0, 1e-6)));
    assert!(!t.samples.iter().any(|s| lifted(s) && s.p[2] > 2.0 + 1e-6), "back over the centre before RTP");
    assert_eq!(t.end(), [10.0, 20.0, 30.0]);
}

#[test]
fn cycle87_and_cycle88_stop_at_depth_until_nc_start() {
    for call in ["CYCLE87(30,0,2,-8,,3)", "CYCLE88(30,0,2,-8,,0.5,4)"] {
        let mut ch = nctwin_engine::Channel::from_preset("mill-3axis", "").unwrap();
        ch.run_program(&format!("G17 G90 F300 M3 S500\nG0 X0 Y0 Z50\n{call}\nM30")).unwrap();
        let mut stops = 0;
        for _ in 0..2_000_000 {
            ch.step();
            if !ch.is_busy() {
                let s = ch.snapshot();
                assert!(s.alarms.is_empty(), "{call}: {:?}", s.alarms);
                let z = s.workpiece.iter().find(|(n, _)| n == "Z").unwrap().1;
                if s.status == nctwin_engine::Status::Idle {
                    assert!(close(z, 30.0, 1e-9), "{call}: ends at RTP");
                    break;
                }
                assert!(close(z, -8.0, 1e-9), "{call}: M0 at the depth, {z}");
                stops += 1;
                ch.start().unwrap();
            }
        }
        assert_eq!(stops, 1, "{call}");
    }
}
