//! The thread turning cycle CYCLE99 with the current cycle package's parameter list (_SPL,
//! _SPD, _FPL, _FPD, _APP, _ROP, _TDEP, _FAL, _IANG, _NSP, _NRC, _NID, _PIT, _VARI, _NUMTH,
//! _SDIS, _MID, ...) on the 2-axis lathe (X a radius, DIAMOF): number of cuts, depth of each
//! cut, its start along the flank and the lead, worked out by hand in each test.

use crate::turning_support;

use turning_support::{Sample, Trace, close, run_lathe, unwrapped};

const SETUP: &str = "G18 G90 G95 F0.2\nT1 D1\nS300 M3\nG4 F1\nG0 X30 Z10\n";

fn run(call: &str) -> Trace {
    run_lathe("", &format!("{SETUP}{call}\nM30"), &[])
}

fn run_clean(call: &str) -> Trace {
    run(call).clean().after_reaching(30.0, 10.0)
}

/// The cuts below the thread's surface (radius 20) between Z 3 and Z-32.
fn cuts(t: &Trace) -> Vec<Vec<Sample>> {
    t.passes(|_| 20.0, -32.0, 3.0)
}

/// The depth of a cut: the surface less the X of its G33 part (the samples with Z in
/// (-28, 0)), checked to be one value.
fn depth(cut: &[Sample]) -> f64 {
    let inner: Vec<&Sample> = cut.iter().filter(|s| s.z < 0.0 && s.z > -28.0).collect();
    assert!(!inner.is_empty());
    let x = inner[0].x;
    assert!(inner.iter().all(|s| close(s.x, x, 1e-9)), "one depth along the cut");
    20.0 - x
}

/// The Z travel per spindle revolution along the cut's G33 part.
fn leads(cut: &[Sample]) -> Vec<f64> {
    let a = unwrapped(cut);
    (1..cut.len())
        .filter(|&i| cut[i].z < 0.0 && cut[i - 1].z > -28.0 && a[i] > a[i - 1] && cut[i].z < cut[i - 1].z)
        .map(|i| (cut[i - 1].z - cut[i].z) / (a[i] - a[i - 1]) * 360.0)
        .collect()
}

fn assert_depths(got: &[Vec<Sample>], want: &[f64]) {
    let d: Vec<f64> = got.iter().map(|c| depth(c)).collect();
    assert_eq!(d.len(), want.len(), "{d:?} vs {want:?}");
    for (g, w) in d.iter().zip(want) {
        assert!(close(*g, *w, 1e-6), "{d:?} vs {want:?}");
    }
}

#[test]
fn cycle99_roughing_and_finishing_with_degressive_radial_infeed() {
    // M40x2 outside, Z0 to Z-30 (_FPD 0: a cylinder), run-in 2, run-out 1, H1 1, U 0.1, radial
    // (alpha 0), 4 roughing cuts, 1 idle pass, pitch 2, _VARI 303: degressive outside (units
    // 3), one flank (tens 0), roughing and finishing (hundreds 3). Roughing 0.9 deep in cuts
    // reaching 0.9 * SQRT(i / 4): 0.45, 0.636396, 0.779423, 0.9; the finishing cut at 1.0 and
    // the idle pass at 1.0: six cuts, each at 2 mm per revolution.
    let t = run_clean("CYCLE99(0,40,-30,0,2,1,1,0.1,0,0,4,1,2,303,1,0,0,0,0,0,0,0)");
    let c = cuts(&t);
    assert_depths(&c, &[0.45, 0.9 * 0.5f64.sqrt(), 0.9 * 0.75f64.sqrt(), 0.9, 1.0, 1.0]);
    for cut in &c {
        let l = leads(cut);
        assert!(!l.is_empty() && l.iter().all(|v| close(*v, 2.0, 1e-6)), "{l:?}");
        // Radial infeed: every cut starts at the run-in's Z2.
        assert!(close(cut[0].z, 2.0, 1e-9), "start Z{}", cut[0].z);
    }
}

#[test]
fn cycle99_roughing_only_takes_the_cut_count_from_the_first_depth_and_infeeds_along_the_flank() {
    // The call Operate writes for M40x1.5 (H1 0.92 = 0.6134 P, U 0.05, alpha 30), with ND 0
    // and D1 0.3: linear infeed (units 1), roughing only (hundreds 1): 0.87 to rough, 0.87 /
    // 0.3 = 2.9 -> 3 cuts of 0.29: depths 0.29, 0.58, 0.87, no finishing, no idle pass. Along
    // the flank each cut starts d * TAN(30) back against the cutting direction (towards +Z):
    // Z 2 + 0.167432, 2 + 0.334863, 2 + 0.502295.
    let t = run_clean("CYCLE99(0,40,-30,40,2,1,0.92,0.05,30,0,0,1,1.5,1300101,1,0,0.3,0,0,0,0,0)");
    let c = cuts(&t);
    assert_depths(&c, &[0.29, 0.58, 0.87]);
    for (cut, d) in c.iter().zip([0.29, 0.58, 0.87]) {
        let start = 2.0 + d * 30f64.to_radians().tan();
        assert!(close(cut[0].z, start, 1e-6), "start Z{} for depth {d}", cut[0].z);
        let l = leads(cut);
        assert!(!l.is_empty() && l.iter().all(|v| close(*v, 1.5, 1e-6)), "{l:?}");
    }
}

#[test]
fn cycle99_finishing_only_is_one_radial_cut_at_depth_and_the_idle_passes() {
    // Finishing only (hundreds 2), alternating flanks asked (tens 1) but the finishing cut is
    // radial: H1 0.92 once and NN 2 idle passes: three cuts at 0.92, all starting at Z2.
    let t = run_clean("CYCLE99(0,40,-30,40,2,1,0.92,0.05,30,0,5,2,1.5,211,1,0,0,0,0,0,0,0)");
    let c = cuts(&t);
    assert_depths(&c, &[0.92, 0.92, 0.92]);
    assert!(c.iter().all(|cut| close(cut[0].z, 2.0, 1e-9)));
}

#[test]
fn cycle99_alternating_flanks_move_every_second_cut_forward() {
    // Linear outside (units 1), alternating (tens 1), roughing only: H1 0.6, U 0, 2 cuts of
    // 0.3 and 0.6, alpha 30: the first starts 0.3 * TAN(30) = 0.173205 back (Z 2.173205), the
    // second 0.6 * TAN(30) = 0.346410 forward (Z 1.653590).
    let t = run_clean("CYCLE99(0,40,-30,40,2,1,0.6,0,30,0,2,0,1,111,1,0,0,0,0,0,0,0)");
    let c = cuts(&t);
    assert_depths(&c, &[0.3, 0.6]);
    assert!(close(c[0][0].z, 2.0 + 0.3 * 30f64.to_radians().tan(), 1e-6), "Z{}", c[0][0].z);
    assert!(close(c[1][0].z, 2.0 - 0.6 * 30f64.to_radians().tan(), 1e-6), "Z{}", c[1][0].z);
}

#[test]
fn cycle99_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // Units 5: 61002; hundreds 4: 61002; no cuts and no first depth: 61002; pitch 0: 61001; a
    // pitch change that leaves no pitch at the run-in's start (1.5^2 - 2 * 0.6 * 2 < 0): 61001.
    for (call, number) in [
        ("CYCLE99(0,40,-30,40,2,1,0.92,0.05,0,0,5,1,1.5,105,1,0,0,0,0,0,0,0)", 61002),
        ("CYCLE99(0,40,-30,40,2,1,0.92,0.05,0,0,5,1,1.5,401,1,0,0,0,0,0,0,0)", 61002),
        ("CYCLE99(0,40,-30,40,2,1,0.92,0.05,0,0,0,1,1.5,101,1,0,0,0,0,0,0,0)", 61002),
        ("CYCLE99(0,40,-30,40,2,1,0.92,0.05,0,0,5,1,0,101,1,0,0,0,0,0,0,0)", 61001),
        ("CYCLE99(0,40,-30,40,2,1,0.92,0.05,0,0,5,1,1.5,101,1,0,0,0,0.6,0,0,0)", 61001),
    ] {
        let t = run(call);
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(6)), "{call}");
        let end = t.samples.last().unwrap();
        assert!(close(end.x, 30.0, 1e-9) && close(end.z, 10.0, 1e-9), "{call}: nothing moved");
    }
}

#[test]
fn cycle99_with_a_pitch_change_cuts_the_pitch_growing_from_the_run_in() {
    // One radial cut 1 deep (_NRC 1, _VARI 101: outside, constant infeed, roughing only) from
    // Z0 to Z-30, run-in 2, run-out 1, pitch 2 at Z0 growing by G = 0.05 mm/rev per revolution
    // (_PIT1). Along the cut (from Z2) the pitch after s mm is SQRT(P0^2 + 2 G s) with
    // P0^2 = 4 - 2 * 0.05 * 2 = 3.8: 2 at Z0, SQRT(4 + 0.1 z) z mm past Z0. The first s mm
    // take n(s) revolutions, s = P0 n + G n^2 / 2: n(s) = (SQRT(3.8 + 0.1 s) - SQRT(3.8)) / 0.05,
    // so Z0 to Z-30 (s 2 to 32) take n(32) - n(2) = (SQRT(7) - 2) / 0.05 = 12.9150 revolutions
    // (at the constant pitch 2: 15).
    let t = run_clean("CYCLE99(0,40,-30,0,2,1,1,0,0,0,1,0,2,101,1,0,0,0,0.05,0,0,0)");
    let c = cuts(&t);
    assert_depths(&c, &[1.0]);
    let cut: Vec<Sample> = c[0].iter().filter(|s| close(s.x, 19.0, 1e-9)).cloned().collect();
    let a = unwrapped(&cut);
    // The spindle angle where the cut passes `z`, between the samples either side.
    let angle_at = |z: f64| {
        let i = (1..cut.len()).find(|&i| cut[i - 1].z >= z && cut[i].z < z).expect("the cut passes z");
        let f = (cut[i - 1].z - z) / (cut[i - 1].z - cut[i].z);
        a[i - 1] + f * (a[i] - a[i - 1])
    };
    let revolutions = (angle_at(-30.0) - angle_at(0.0)) / 360.0;
    assert!(close(revolutions, 12.9150, 0.005), "{revolutions}");
    // Each revolution runs at its mean pitch (within G / 2 = 0.025 of the exact one).
    let mut checked = 0;
    for i in 1..cut.len() {
        let (z0, z1) = (cut[i - 1].z, cut[i].z);
        if z1 < -28.0 || z0 > 0.0 || a[i] <= a[i - 1] || z1 >= z0 {
            continue;
        }
        let pitch = (z0 - z1) / (a[i] - a[i - 1]) * 360.0;
        let past = -(z0 + z1) / 2.0;
        assert!(close(pitch, (4.0 + 0.1 * past).sqrt(), 0.03), "Z{z1}: {pitch}");
        checked += 1;
    }
    assert!(checked > 100, "{checked} samples along the thread");
}
