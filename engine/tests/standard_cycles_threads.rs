//! The chained thread cycle CYCLE98 on the 2-axis lathe (X is a radius, DIAMOF), checked on the
//! path and the spindle angle of every IPO cycle against values worked out by hand from the
//! documented parameter list (PO1..PO4, DM1..DM4, APP, ROP, TDEP, FAL, IANG, NSP, NRC, NID,
//! PP1..PP3, VARI, NUMTH, _VRT).

use crate::turning_support;

use turning_support::{Sample, Trace, close, run_lathe, unwrapped};

/// Runs `main` on the 2-axis lathe and keeps the cycle's samples: from the tool's arrival at
/// the approach point (X30 Z10) on.
fn run(main: &str) -> Trace {
    run_lathe("", main, &[]).after_reaching(30.0, 10.0)
}

fn run_clean(main: &str) -> Trace {
    run(main).clean()
}

fn passes(t: &Trace, surface: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Vec<Vec<Sample>> {
    t.passes(surface, lo, hi)
}

/// The Z travel per spindle revolution between every two samples with Z in (lo, hi).
fn leads(cut: &[Sample], lo: f64, hi: f64) -> Vec<f64> {
    let a = unwrapped(cut);
    (1..cut.len())
        .filter(|&i| cut[i - 1].z < hi && cut[i].z > lo && cut[i].t > cut[i - 1].t && a[i] > a[i - 1])
        .map(|i| (cut[i - 1].z - cut[i].z) / (a[i] - a[i - 1]) * 360.0)
        .collect()
}

/// The spindle angle (degrees, 0..360) where the cut passes Z = `z` (interpolated).
fn angle_at(cut: &[Sample], z: f64) -> f64 {
    let a = unwrapped(cut);
    let i = cut.iter().position(|s| s.z <= z).expect("the cut passes z");
    let u = (cut[i - 1].z - z) / (cut[i - 1].z - cut[i].z);
    (a[i - 1] + u * (a[i] - a[i - 1])).rem_euclid(360.0)
}

const SETUP: &str = "G18 G90 G95 F0.2\nT1 D1\nS300 M3\nG4 F1\nG0 X30 Z10\n";

/// The thread's surface (radius) of the chain below: a cylinder of radius 20 from Z0 to Z-20,
/// then a taper to radius 25 at Z-30, extended beyond.
fn surface(z: f64) -> f64 {
    if z >= -20.0 { 20.0 } else { 20.0 + (-20.0 - z) * 0.5 }
}

#[test]
fn cycle98_chains_a_cylindrical_and_a_tapered_section_at_their_pitches() {
    // PO1 Z0 DM1 40, PO2 Z-20 DM2 40 (cylinder, PP1 2), PO3 = PO2 (no second section), PO4
    // Z-30 DM4 50 (taper from radius 20 to 25 over 10 mm: 26.6 degrees, lead along Z, PP3 3).
    // APP 4: the cuts start at Z4 on the cylinder extended (radius 20); ROP 2: they end at
    // Z-32 on the taper extended, radius 25 + 2 * 0.5 = 26. TDEP 1, NRC 2, VARI 1 (constant
    // infeed, outside): depths 0.5 and 1.0. The safe level: 1 mm (_VRT 0) beyond the highest
    // radius, the run-out's 26: X27. Each cut: G0 to X27, to Z4, down to 20 - d, G33 to Z-20
    // (K2, SF 0), G33 on to Z-32 X26 - d (K3), G0 out to X27. At the end: Z4, then X21.
    let t = run_clean(&format!("{SETUP}CYCLE98(0,40,-20,40,-20,40,-30,50,4,2,1,0,0,0,2,0,2,0,3,1,1,0)\nM30"));
    let cuts = passes(&t, surface, -31.9, 3.9);
    assert_eq!(cuts.len(), 2, "two roughing cuts");
    for (cut, d) in cuts.iter().zip([0.5, 1.0]) {
        // Every sample of the cut lies d below the surface, on both sections.
        for s in cut {
            assert!(close(s.x, surface(s.z) - d, 1e-6), "depth {d} at Z{}: X{}", s.z, s.x);
        }
        // The first section at 2 mm, the taper at 3 mm of Z per revolution.
        let (first, second) = (leads(cut, -18.0, 1.0), leads(cut, -30.0, -22.0));
        assert!(!first.is_empty() && !second.is_empty());
        assert!(first.iter().all(|l| close(*l, 2.0, 1e-6)), "first section {first:?}");
        assert!(second.iter().all(|l| close(*l, 3.0, 1e-6)), "taper {second:?}");
        // The chain runs through: the cut passes Z-20 and covers both sections without a gap.
        assert!(cut.first().unwrap().z > 3.0 && cut.last().unwrap().z < -31.0);
    }
    // Both cuts meet the same groove on the taper: the spindle synchronised once per cut (at
    // SF 0) and the chained block followed; within one IPO cycle's turn (300 rev/min).
    let step = 300.0 * 6.0 * (t.samples[1].t - t.samples[0].t);
    let (a, b) = (angle_at(&cuts[0], -26.0), angle_at(&cuts[1], -26.0));
    let d = (a - b + 180.0).rem_euclid(360.0) - 180.0;
    assert!(d.abs() <= step + 1e-6, "angles at Z-26: {a} {b}");
    // Out to the safe level (X27) after each cut, and back to the start (Z4 X21).
    let end = t.samples.last().unwrap();
    assert!(close(end.z, 4.0, 1e-9) && close(end.x, 21.0, 1e-9), "end {end:?}");
    let xmax = t.samples.iter().filter(|s| s.z < -31.9).map(|s| s.x).fold(f64::NEG_INFINITY, f64::max);
    assert!(close(xmax, 27.0, 1e-9), "retraction {xmax}");
}

#[test]
fn cycle98_three_sections_with_flank_infeed_and_two_starts() {
    // Three cylindrical sections (radius 20, Z0 .. -10 .. -20 .. -30) at PP1 1, PP2 2, PP3 1.5;
    // APP 2, ROP 2: cuts from Z2 to Z-32. TDEP 0.6, NRC 2 (0.3, 0.6), IANG 30 (flank infeed):
    // each cut starts back (towards +Z) by d * TAN(30): at Z2 + 0.173205 and Z2 + 0.346410, and
    // ends so much behind Z-32. NUMTH 2 from NSP 90: the second start's cuts begin 180 degrees
    // after the first's.
    let t = run_clean(&format!("{SETUP}CYCLE98(0,40,-10,40,-20,40,-30,40,2,2,0.6,0,30,90,2,0,1,2,1.5,1,2,0)\nM30"));
    let cyl = |_: f64| 20.0;
    let cuts = passes(&t, cyl, -40.0, 10.0);
    assert_eq!(cuts.len(), 4, "two cuts for each of two starts");
    let tan = 30f64.to_radians().tan();
    for (i, cut) in cuts.iter().enumerate() {
        let d = [0.3, 0.6][i % 2];
        // The run includes the infeed (at its start) and the retraction (at its end).
        let zmax = cut.iter().map(|s| s.z).fold(f64::NEG_INFINITY, f64::max);
        let zmin = cut.iter().map(|s| s.z).fold(f64::INFINITY, f64::min);
        let mut along = cut.iter().filter(|s| s.z < zmax - 1e-9 && s.z > zmin + 1e-9);
        assert!(along.all(|s| close(s.x, 20.0 - d, 1e-6)), "cut {i} at depth {d}");
        assert!(close(zmax, 2.0 + d * tan, 1e-6), "cut {i} starts at {zmax}");
        assert!(close(zmin, -32.0 + d * tan, 1e-6), "cut {i} ends at {zmin}");
        for (lo, hi, lead) in [(-8.0, 0.0, 1.0), (-18.0, -12.0, 2.0), (-28.0, -22.0, 1.5)] {
            let l = leads(cut, lo, hi);
            assert!(!l.is_empty() && l.iter().all(|v| close(*v, lead, 1e-6)), "cut {i} Z{lo}..{hi}: {l:?}");
        }
    }
    // The starts: the angle where each cut passes Z-5, less what the flank shift adds there
    // (the start moved back by d * TAN(30) along the 1 mm lead: d * TAN(30) * 360 degrees).
    let step = 300.0 * 6.0 * (t.samples[1].t - t.samples[0].t);
    let groove = |i: usize| {
        let d = [0.3, 0.6][i % 2];
        (angle_at(&cuts[i], -5.0) - d * tan * 360.0).rem_euclid(360.0)
    };
    for (i, want) in [(1, 0.0), (2, 180.0), (3, 180.0)] {
        let diff = (groove(i) - groove(0) - want + 180.0).rem_euclid(360.0) - 180.0;
        assert!(diff.abs() <= step + 1e-6, "cut {i}: {} vs {}", groove(i), groove(0));
    }
}

#[test]
fn cycle98_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // VARI 5: 61002; PP1 0 for a section with a length: 61001; all four points equal: 61001.
    for (call, number) in [
        ("CYCLE98(0,40,-20,40,-20,40,-30,50,4,2,1,0,0,0,2,0,2,0,3,5,1,0)", 61002),
        ("CYCLE98(0,40,-20,40,-20,40,-30,50,4,2,1,0,0,0,2,0,0,0,3,1,1,0)", 61001),
        ("CYCLE98(0,40,0,40,0,40,0,40,4,2,1,0,0,0,2,0,2,2,2,1,1,0)", 61001),
    ] {
        let t = run(&format!("{SETUP}{call}\nM30"));
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(6)), "{call}");
    }
}

/// The machine X (always a radius) and Z of every IPO cycle, consecutive repeats merged.
fn machine_path(main: &str) -> Vec<(f64, f64)> {
    let t = run_lathe("", main, &[]).clean();
    let mut points: Vec<(f64, f64)> = Vec::new();
    for p in t.samples.iter().skip(1).map(|s| (s.mx, s.z)) {
        if points.last().is_none_or(|q| !close(q.0, p.0, 1e-12) || !close(q.1, p.1, 1e-12)) {
            points.push(p);
        }
    }
    points
}

#[test]
fn cycle98_under_diamon_cuts_the_same_chain_as_in_radius_programming() {
    // DM1..DM4 are diameters in both modes; only the caller's approach X30 (radius) is X60
    // under DIAMON. The cycle works in radii (DIAMCYCOF), so the machine path is the same.
    let call = "CYCLE98(0,40,-20,40,-20,40,-30,50,4,2,1,0,0,0,2,0,2,0,3,1,1,0)\nM30";
    let radius = machine_path(&format!("{}{call}", SETUP.replace("G0 X30", "DIAMOF\nG0 X30")));
    let diameter = machine_path(&format!("{}{call}", SETUP.replace("G0 X30", "DIAMON\nG0 X60")));
    assert!(radius.len() > 1000);
    assert_eq!(radius.len(), diameter.len());
    for (r, d) in radius.iter().zip(&diameter) {
        assert!(close(r.0, d.0, 1e-9) && close(r.1, d.1, 1e-9), "radius run {r:?} against diameter run {d:?}");
    }
}

#[test]
fn cycle98_a_section_steeper_than_45_degrees_takes_its_lead_along_x() {
    // Z0..Z-10 at radius 20 (PP1 2), a step up to radius 30 between Z-10 and Z-12 (10 mm of X
    // over 2 mm of Z: steeper than 45 degrees, so its lead PP2 1.5 runs along X), then radius 30
    // to Z-22 (PP3 2); APP 2, ROP 2. One cut to TDEP 0.5 (NRC 1): the surface less 0.5 radially.
    let t = run_clean(&format!("{SETUP}CYCLE98(0,40,-10,40,-12,60,-22,60,2,2,0.5,0,0,0,1,0,2,1.5,2,1,1,0)\nM30"));
    let step_surface = |z: f64| {
        if z >= -10.0 {
            20.0
        } else if z >= -12.0 {
            20.0 + (-10.0 - z) * 5.0
        } else {
            30.0
        }
    };
    let cuts = passes(&t, step_surface, -23.9, 1.9);
    assert_eq!(cuts.len(), 1, "the way back runs outside the step");
    // Back at the safe level: 1 mm beyond the highest radius 30 (and the run-out's 30), X31.
    let back: Vec<&Sample> = t.samples.iter().filter(|s| s.z > -23.9 && s.z < 1.9 && s.x > 30.0).collect();
    assert!(back.len() > 10 && back.iter().all(|s| close(s.x, 31.0, 1e-9)), "the safe level");
    let cut = &cuts[0];
    assert!(cut.iter().all(|s| close(s.x, step_surface(s.z) - 0.5, 1e-6)), "depth 0.5 everywhere");
    // On the step: 1.5 mm of X per revolution; before and after it 2 mm of Z.
    let a = unwrapped(cut);
    let on_step: Vec<f64> = (1..cut.len())
        .filter(|&i| cut[i - 1].x > 21.0 && cut[i].x < 28.0 && a[i] > a[i - 1])
        .map(|i| (cut[i].x - cut[i - 1].x) / (a[i] - a[i - 1]) * 360.0)
        .collect();
    assert!(!on_step.is_empty() && on_step.iter().all(|l| close(*l, 1.5, 1e-6)), "{on_step:?}");
    let before = leads(cut, -8.0, 1.0);
    let after = leads(cut, -22.0, -14.0);
    assert!(!before.is_empty() && before.iter().all(|l| close(*l, 2.0, 1e-6)), "{before:?}");
    assert!(!after.is_empty() && after.iter().all(|l| close(*l, 2.0, 1e-6)), "{after:?}");
}
