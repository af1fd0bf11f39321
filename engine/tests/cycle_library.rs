//! The standard cycle library (`engine/cycles/`, the control's CST directory): its cycles are
//! called like any subprogram, MCALL repeats them, and a session's own program of the same name
//! takes precedence. Depths are worked out by hand from the documented parameter list of CYCLE81
//! (RTP, RFP, SDIS, DP, DPR).

use nctwin_engine::{Channel, Status};

const MAX_TICKS: usize = 2_000_000;

/// Runs `main` on the 3-axis mill with `subs` stored; returns the channel at rest and each
/// hole's bottom: the lowest position of `axis` (WCS) in every dip below `below`.
fn run_holes(main: &str, subs: &[(&str, &str)], axis: &str, below: f64) -> (Channel, Vec<f64>) {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    for (name, text) in subs {
        ch.store_program(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    ch.run_program(main).unwrap_or_else(|e| panic!("not started: {e}"));
    let (mut holes, mut dip): (Vec<f64>, Option<f64>) = (Vec::new(), None);
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        let v = wcs(&ch, axis);
        match (v < below, dip) {
            (true, d) => dip = Some(d.map_or(v, |d: f64| d.min(v))),
            (false, Some(d)) => {
                holes.push(d);
                dip = None;
            }
            (false, None) => {}
        }
        ticks += 1;
        assert!(ticks < MAX_TICKS, "program does not end");
    }
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert_eq!(s.status, Status::Idle);
    (ch, holes)
}

fn wcs(ch: &Channel, axis: &str) -> f64 {
    ch.snapshot().workpiece.iter().find(|(n, _)| n == axis).unwrap().1
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

#[test]
fn cycle81_drills_to_the_absolute_depth_and_retracts_to_the_retraction_plane() {
    // RTP 10, RFP 0, SDIS 2, DP -5: down to Z-5, up to Z10, the hole position unchanged.
    let (ch, holes) = run_holes("G17 G90 G54 F200\nG0 X10 Y20 Z50\nCYCLE81(10,0,2,-5)\nM30", &[], "Z", 0.0);
    assert_eq!(holes.len(), 1);
    assert!(close(holes[0], -5.0), "{holes:?}");
    assert!(close(wcs(&ch, "Z"), 10.0) && close(wcs(&ch, "X"), 10.0) && close(wcs(&ch, "Y"), 20.0));
}

#[test]
fn a_relative_depth_takes_precedence_over_the_absolute_one() {
    // DPR 8 below RFP 1: Z = 1 - 8 = -7, although DP says -5.
    let (_, holes) = run_holes("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE81(10,1,2,-5,8)\nM30", &[], "Z", 0.0);
    assert!(close(holes[0], -7.0), "{holes:?}");
}

#[test]
fn mcall_drills_at_every_following_position() {
    let main = "G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE81(5,0,1,-3)\nX10\nX20 Y5\nX30\nMCALL\nG0 X40\nM30";
    let (ch, holes) = run_holes(main, &[], "Z", 0.0);
    assert_eq!(holes.len(), 3, "one hole per position while MCALL is active: {holes:?}");
    assert!(holes.iter().all(|&h| close(h, -3.0)), "{holes:?}");
    assert!(close(wcs(&ch, "X"), 40.0) && close(wcs(&ch, "Z"), 5.0));
}

#[test]
fn in_g18_the_drilling_axis_is_y() {
    let (ch, holes) = run_holes("G18 G90 F200\nG0 X0 Y50 Z0\nCYCLE81(10,0,2,-4)\nM30", &[], "Y", 0.0);
    assert!(close(holes[0], -4.0), "{holes:?}");
    assert!(close(wcs(&ch, "Y"), 10.0) && close(wcs(&ch, "Z"), 0.0));
}

#[test]
fn the_callers_g_functions_come_back_after_the_cycle() {
    // The cycle ends in G0; PROC ... SAVE gives the caller back its G1 ($P_GG[1]: G0 = 1, G1 = 2).
    let (ch, _) = run_holes("G17 G90 F200\nG0 X0 Y0 Z50\nG1 Z20\nCYCLE81(10,0,2,-1)\nR1=$P_GG[1]\nM30", &[], "Z", 0.0);
    assert_eq!(ch.r_param(1), 2.0);
}

#[test]
fn a_session_program_of_the_same_name_overrides_the_library() {
    let own = "PROC CYCLE81(REAL RTP, REAL RFP, REAL SDIS, REAL DP) SAVE\nG1 Z=DP-1\nG0 Z=RTP\nM17";
    let (_, holes) = run_holes("G17 G90 F200\nG0 X0 Y0 Z50\nCYCLE81(10,0,2,-5)\nM30", &[("CYCLE81", own)], "Z", 0.0);
    assert!(close(holes[0], -6.0), "the session's CYCLE81 ran: {holes:?}");
}

// --- CYCLE832: high-speed settings -----------------------------------------------------------

/// Runs `program` on the 3-axis mill; returns the channel and every sampled WCS (X, Y).
fn run_xy(program: &str) -> (Channel, Vec<(f64, f64)>) {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap_or_else(|e| panic!("not started: {e}"));
    let mut samples = Vec::new();
    while ch.is_busy() {
        ch.step();
        samples.push((wcs(&ch, "X"), wcs(&ch, "Y")));
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    (ch, samples)
}

/// How close the sampled path comes to the corner (10, 0).
fn corner_gap(samples: &[(f64, f64)]) -> f64 {
    samples.iter().map(|(x, y)| ((x - 10.0).powi(2) + y.powi(2)).sqrt()).fold(f64::INFINITY, f64::min)
}

#[test]
fn cycle832_sets_the_functions_of_each_machining_type() {
    // $P_GG positions in their G groups (Programming Manual's lists): group 10 G60 1, G64 2,
    // G641 3, G642 4; group 21 BRISK 1, SOFT 2; group 24 FFWOF 1, FFWON 2; group 59 DYNNORM 1,
    // DYNPOS 2, DYNROUGH 3, DYNSEMIFIN 4, DYNFINISH 5.
    let program = "G17 G90 F2000\nG0 X0 Y0 Z0\n\
        CYCLE832(0.01,_FINISH,1)\nR1=$P_GG[10] R2=$P_GG[21] R3=$P_GG[24] R4=$P_GG[59]\n\
        CYCLE832(0.05,_SEMIFIN,1)\nR5=$P_GG[59]\n\
        CYCLE832(0.1,3,1)\nR6=$P_GG[59]\n\
        CYCLE832(0.01,_OFF)\nR7=$P_GG[10] R8=$P_GG[59] R9=$P_GG[21]\nM30";
    let (ch, _) = run_xy(program);
    let r: Vec<f64> = (1..=9).map(|n| ch.r_param(n)).collect();
    assert_eq!(r, [4.0, 2.0, 2.0, 5.0, 4.0, 3.0, 2.0, 1.0, 2.0], "R1..R9");
}

#[test]
fn cycle832_tolerance_bounds_the_rounded_corner() {
    // A square corner at (10, 0) under the settings of each type: the path passes the corner
    // within the tolerance, and really cuts it (more than a tenth of it away). At F60 the IPO
    // samples lie 0.004 mm apart, fine enough to see the rounding of a 0.01 mm tolerance.
    let square = |settings: &str| format!("G17 G90 G0 X0 Y0 Z0\n{settings}\nG1 X10 F60\nY10\nM30");
    let (_, fine) = run_xy(&square("CYCLE832(0.01,_FINISH,1)"));
    let (_, rough) = run_xy(&square("CYCLE832(0.1,_ROUGH,1)"));
    let (_, off) = run_xy(&square("CYCLE832(0.1,_OFF)"));
    let (f, r, o) = (corner_gap(&fine), corner_gap(&rough), corner_gap(&off));
    // The samples, 0.004 mm apart, need not hit the path's point nearest the corner (at the
    // tolerance): one within s = 0.002 mm of it along the path is about s²/(2·tol) farther
    // from the corner (the path bends away from it), 0.0002 mm for 0.01: allowed 0.0005.
    assert!(f <= 0.01 + 5e-4 && f > 0.001, "finishing: {f}");
    assert!(r <= 0.1 + 5e-4 && r > 0.01, "roughing: {r}");
    // Deselected: G64 without rounding runs into the corner point (the last IPO sample before
    // the standstill may stop a few µm short of it under SOFT).
    assert!(o < 0.0005, "deselected: {o}");
}
