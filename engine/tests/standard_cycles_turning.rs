//! The turning cycles of the standard cycle library (CYCLE93 grooving, CYCLE94/CYCLE96
//! undercuts, CYCLE97 threads), checked on the path they produce on the 2-axis lathe (X is a
//! radius, DIAMOF): groove bases and flanks, undercut profiles and thread cuts worked out by
//! hand from the documented parameter lists in each test's comments.

use crate::turning_support;

use turning_support::{Sample, Trace, close, run_lathe, shaft_radius, unwrapped};

/// Runs `main` on the 2-axis lathe with the machine data `md` added (tool data).
fn run(md: &str, main: &str) -> Trace {
    run_lathe(md, main, &[])
}

/// [`run`] with subprograms `subs` (name, text) stored first.
fn run_with(md: &str, main: &str, subs: &[(&str, &str)]) -> Trace {
    run_lathe(md, main, subs)
}

fn run_clean(md: &str, main: &str) -> Trace {
    run(md, main).clean()
}

/// The samples from the tool's arrival at the approach point on: the program's last
/// `G0 X.. Z..` block before the cycle's call.
fn cycle(t: &Trace, main: &str) -> Trace {
    let approach = main.lines().rfind(|l| l.starts_with("G0 X")).expect("an approach block");
    let words: Vec<f64> = approach[3..].split(' ').map(|w| w[1..].parse().unwrap()).collect();
    assert!(
        t.samples.iter().any(|s| close(s.x, words[0], 1e-9) && close(s.z, words[1], 1e-9)),
        "reaches the approach point"
    );
    Trace { samples: t.samples.clone(), alarms: t.alarms.clone(), r: t.r.clone() }.after_reaching(words[0], words[1])
}

/// Runs `main` without alarms and keeps the samples of the cycle.
fn run_clean_cycle(md: &str, main: &str) -> Trace {
    cycle(&run_clean(md, main), main)
}

/// The values where `f` of the samples reverses direction (or starts or ends), consecutive
/// equal values merged.
fn turning_points(t: &Trace, f: impl Fn(&Sample) -> f64) -> Vec<f64> {
    let mut v: Vec<f64> = Vec::new();
    for s in &t.samples {
        let x = f(s);
        if v.last().is_none_or(|l| (l - x).abs() > 1e-9) {
            v.push(x);
        }
    }
    (0..v.len())
        .filter(|&i| i == 0 || i + 1 == v.len() || (v[i] - v[i - 1]).signum() != (v[i + 1] - v[i]).signum())
        .map(|i| v[i])
        .collect()
}

fn assert_points(got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(close(*g, *w, 1e-6), "{got:?} vs {want:?}");
    }
}

/// A grooving tool T1 with two edges and no nose radius: D1 and D2 lie 3 mm apart along Z
/// (lengths along Z 60 and 57: the D2 tip is 3 mm towards +Z of the D1 tip) and along X
/// (lengths along X 40 and 37) for the face grooves.
const GROOVER: &str = "$TC_DP1[1,1]=520\n$TC_DP2[1,1]=3\n$TC_DP3[1,1]=40.\n$TC_DP4[1,1]=60.\n$TC_DP6[1,1]=0\n\
                       $TC_DP1[1,2]=520\n$TC_DP2[1,2]=4\n$TC_DP3[1,2]=37.\n$TC_DP4[1,2]=57.\n$TC_DP6[1,2]=0\n";

#[test]
fn cycle93_longitudinal_outside_groove_has_its_base_and_width_and_the_tool_stays_inside() {
    // SPD 40 (radius 20), SPL -20, VARI 1 (longitudinal, outside, left): the groove runs from
    // Z-20 to Z-10 (WIDG 10), base at radius 20 - 5 = 15. The tool is 3 wide with D1 at its
    // low (-Z) corner, so while in the groove the D1 tip stays in [-20, -13].
    let t = run_clean_cycle(
        GROOVER,
        "G18 G90 G94 F200\nT1 D1\nS500 M3\nG0 X30 Z10\nCYCLE93(40,-20,10,5,0,0,0,0,0,0,0,0.2,0.2,2,0,1,0)\nM30",
    );
    let min_x = t.samples.iter().map(|s| s.x).fold(f64::INFINITY, f64::min);
    assert!(close(min_x, 15.0, 1e-6), "base {min_x}");
    let inside: Vec<_> = t.samples.iter().filter(|s| s.x < 20.0 - 1e-6).collect();
    let zmin = inside.iter().map(|s| s.z).fold(f64::INFINITY, f64::min);
    let zmax = inside.iter().map(|s| s.z).fold(f64::NEG_INFINITY, f64::max);
    assert!(close(zmin, -20.0, 1e-6) && close(zmax, -13.0, 1e-6), "flanks {zmin} {zmax}");
    // The finishing pass along the base covers the whole base: the D1 tip from -20 to -13.
    let base: Vec<_> = t.samples.iter().filter(|s| close(s.x, 15.0, 1e-6)).map(|s| s.z).collect();
    assert!(base.iter().any(|&z| close(z, -20.0, 1e-6)) && base.iter().any(|&z| close(z, -13.0, 1e-6)));
    // Roughing: base less FAL2 0.2 on each side, tool low corner from -19.8 to -10.2 - 3 =
    // -13.2: 6.6 mm at most 0.95 * 3 = 2.85 apart gives 3 steps of 2.2, so 4 plunges at -19.8,
    // -17.6, -15.4, -13.2, each to 20 - 5 + 0.2 = 15.2. IDEP 2: 18, back 1 mm to 19, 16, back to
    // 17, 15.2, then out to 1 mm above the surface (21).
    let mut plunges: Vec<f64> = Vec::new();
    for w in t.samples.windows(3) {
        // Arriving at 15.2 and going no deeper (the finishing pass only runs through it).
        if close(w[1].x, 15.2, 1e-9) && !close(w[0].x, 15.2, 1e-9) && w[2].x >= w[1].x - 1e-9 {
            plunges.push(w[1].z);
        }
    }
    assert_points(&plunges, &[-19.8, -17.6, -15.4, -13.2]);
    let first = t.samples.iter().position(|s| close(s.x, 21.0, 1e-9) && close(s.z, -19.8, 1e-9)).unwrap();
    let out = t.samples[first..].iter().position(|s| close(s.z, -17.6, 1e-9)).unwrap() + first;
    let sub = Trace { samples: t.samples[first..out].to_vec(), alarms: vec![], r: vec![] };
    assert_points(&turning_points(&sub, |s| s.x), &[21.0, 18.0, 19.0, 16.0, 17.0, 15.2, 21.0]);
}

#[test]
fn cycle93_flank_angles_keep_the_tool_off_both_flanks() {
    // ANG1 = ANG2 = 15, WIDG 10 at the base: base corners at Z -20 + 5 tan 15 = -18.6603 and
    // -8.6603; at radius x the flanks lie at Z -20 + (20 - x) tan 15 and
    // -8.6603 + (x - 15) tan 15. The tool (D1 tip and D1 tip + 3) stays between them.
    let t = run_clean_cycle(
        GROOVER,
        "G18 G90 G94 F200\nT1 D1\nG0 X30 Z10\nCYCLE93(40,-20,10,5,0,15,15,0,0,0,0,0,0,0,0,1,0)\nM30",
    );
    let tan = 15f64.to_radians().tan();
    let (b1, b2) = (-20.0 + 5.0 * tan, -20.0 + 5.0 * tan + 10.0);
    let mut touched = (false, false);
    for s in t.samples.iter().filter(|s| s.x < 20.0 - 1e-6) {
        let lo = -20.0 + (20.0 - s.x) * tan;
        let hi = b2 + (s.x - 15.0) * tan;
        assert!(s.z >= lo - 1e-6 && s.z + 3.0 <= hi + 1e-6, "violates a flank at {s:?}");
        touched.0 |= close(s.z, lo, 1e-6) && s.x < 16.0;
        touched.1 |= close(s.z + 3.0, hi, 1e-6) && s.x < 16.0;
        assert!(s.x >= 15.0 - 1e-9);
    }
    assert!(touched.0 && touched.1, "both flanks finished down to the base");
    assert!(t.samples.iter().any(|s| close(s.x, 15.0, 1e-9) && close(s.z, b1, 1e-6)));
}

#[test]
fn cycle93_face_groove_goes_into_the_face_and_inside_grooves_away_from_the_axis() {
    // VARI 2 (face, outside, left): face at Z0 (SPL), groove from radius 20 (SPD 40) to 26
    // (WIDG 6), 4 deep: base at Z-4. The tool's width lies along X: D1 tip and D1 + 3 in X.
    let t = run_clean_cycle(
        GROOVER,
        "G18 G90 G94 F200\nT1 D1\nG0 X30 Z10\nCYCLE93(40,0,6,4,0,0,0,0,0,0,0,0,0,0,0,2,0)\nM30",
    );
    let inside: Vec<_> = t.samples.iter().filter(|s| s.z < -1e-6).collect();
    let zmin = inside.iter().map(|s| s.z).fold(f64::INFINITY, f64::min);
    assert!(close(zmin, -4.0, 1e-6), "base {zmin}");
    assert!(inside.iter().all(|s| s.x >= 20.0 - 1e-6 && s.x + 3.0 <= 26.0 + 1e-6));
    // VARI 7 (longitudinal, inside, right): bore radius 15 (SPD 30), groove from Z-10 towards
    // -Z over 8, 2 deep: base at radius 17 from Z-18 to -10.
    let t = run_clean_cycle(
        GROOVER,
        "G18 G90 G94 F200\nT1 D1\nG0 X10 Z10\nCYCLE93(30,-10,8,2,0,0,0,0,0,0,0,0,0,0,0,7,0)\nM30",
    );
    let inside: Vec<_> = t.samples.iter().filter(|s| s.x > 15.0 + 1e-6).collect();
    let xmax = inside.iter().map(|s| s.x).fold(f64::NEG_INFINITY, f64::max);
    assert!(close(xmax, 17.0, 1e-6), "base {xmax}");
    assert!(inside.iter().all(|s| s.z >= -18.0 - 1e-6 && s.z + 3.0 <= -10.0 + 1e-6));
}

#[test]
fn cycle93_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // A 2 mm base for a 3 mm tool: 61602; VARI 9: 61002; no depth: 61603; an outside groove
    // deeper than the radius: 61601.
    for (call, number) in [
        ("CYCLE93(40,-20,2,5,0,0,0,0,0,0,0,0,0,0,0,1,0)", 61602),
        ("CYCLE93(40,-20,10,5,0,0,0,0,0,0,0,0,0,0,0,9,0)", 61002),
        ("CYCLE93(40,-20,10,0,0,0,0,0,0,0,0,0,0,0,0,1,0)", 61603),
        ("CYCLE93(40,-20,10,25,0,0,0,0,0,0,0,0,0,0,0,1,0)", 61601),
    ] {
        let t = run(GROOVER, &format!("G18 G90 G94 F200\nT1 D1\nG0 X30 Z10\n{call}\nM30"));
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(4)), "{call}");
        let end = t.samples.last().unwrap();
        assert!(close(end.x, 30.0, 1e-9) && close(end.z, 10.0, 1e-9), "{call}: nothing moved");
    }
}

/// The runs of samples below the radius `surface` (cutting) with Z inside (lo, hi).
fn passes(t: &Trace, surface: f64, lo: f64, hi: f64) -> Vec<Vec<Sample>> {
    t.passes(|_| surface, lo, hi)
}

const THREAD: &str = "G18 G90 G95 F0.2\nT1 D1\nS300 M3\nG4 F1\nG0 X20 Z10\n";

#[test]
fn cycle97_degressive_radial_infeed_cuts_at_the_pitch_from_the_same_spindle_angle() {
    // M20x2 outside, SPL 0 to FPL -30, APP 4, ROP 2: every cut runs from Z4 to Z-32. TDEP 1.23,
    // FAL 0.05, NRC 4, VARI 3 (constant cross-section): cut i reaches 1.18 * SQRT(i / 4) =
    // 0.59, 0.834386, 1.021909, 1.18; then the finishing cut to 1.23 and NID 2 idle passes
    // there: radii 10 - depth.
    let t = run_clean_cycle("", &format!("{THREAD}CYCLE97(2,,0,-30,20,20,4,2,1.23,0.05,0,0,4,2,3,1,0)\nM30"));
    let cuts = passes(&t, 10.0, -31.9, 3.9);
    let radii: Vec<f64> = cuts.iter().map(|c| c[c.len() / 2].x).collect();
    let q = |i: f64| 10.0 - 1.18 * (i / 4.0).sqrt();
    assert_points(&radii, &[q(1.0), q(2.0), q(3.0), q(4.0), 8.77, 8.77, 8.77]);
    for c in &cuts {
        assert!(c.iter().all(|s| close(s.x, c[0].x, 1e-9)), "each cut at one depth");
    }
    let min_x = t.samples.iter().map(|s| s.x).fold(f64::INFINITY, f64::min);
    assert!(close(min_x, 8.77, 1e-9), "final depth {min_x}");
    // Pitch: 2 mm of Z per spindle revolution between any two samples in the steady part.
    let step = 300.0 * 6.0 * (t.samples[1].t - t.samples[0].t);
    let mut starts = Vec::new();
    for c in &cuts {
        let a = unwrapped(c);
        for i in 1..c.len() {
            if c[i - 1].z < -5.0 && c[i].z > -25.0 && c[i].t > c[i - 1].t {
                let pitch = (c[i - 1].z - c[i].z) / (a[i] - a[i - 1]) * 360.0;
                assert!(close(pitch, 2.0, 1e-6), "pitch {pitch}");
            }
        }
        starts.push(c[0].sp);
    }
    // Every cut starts at the same spindle angle (within one IPO cycle's turn, 300 rev/min).
    for s in &starts {
        let d = (s - starts[0] + 180.0).rem_euclid(360.0) - 180.0;
        assert!(d.abs() <= step + 1e-6, "start angles {starts:?}");
    }
}

#[test]
fn cycle97_flank_and_alternating_infeed_move_the_start_along_the_flank() {
    // Constant infeed (VARI 1) NRC 3 of TDEP 0.9: depths 0.3, 0.6, 0.9. IANG 30: each start
    // moves back (towards +Z, against the cut along -Z) by depth * TAN(30) = 0.173205,
    // 0.346410, 0.519615. IANG -30 alternates: +0.173205, -0.346410, +0.519615.
    let tan = 30f64.to_radians().tan();
    for (iang, signs) in [(30.0, [1.0, 1.0, 1.0]), (-30.0, [1.0, -1.0, 1.0])] {
        let t = run_clean_cycle("", &format!("{THREAD}CYCLE97(2,,0,-30,20,20,4,2,0.9,0,{iang},0,3,0,1,1,0)\nM30"));
        // A cut's start: the highest Z while the tool stands at its depth.
        let cuts = passes(&t, 10.0, -31.9, 5.0);
        let got: Vec<f64> = cuts.iter().map(|c| c.iter().map(|s| s.z).fold(f64::NEG_INFINITY, f64::max)).collect();
        let want: Vec<f64> = (1..=3).map(|i| 4.0 + signs[i - 1] * 0.3 * i as f64 * tan).collect();
        assert_points(&got, &want);
        let radii: Vec<f64> = cuts.iter().map(|c| c.iter().map(|s| s.x).fold(f64::INFINITY, f64::min)).collect();
        assert_points(&radii, &[9.7, 9.4, 9.1]);
    }
}

#[test]
fn cycle97_multi_start_threads_start_half_a_turn_apart_and_mpit_gives_the_pitch() {
    // NUMT 2 from NSP 0: the second turn's cuts start 180 degrees after the first's. MPIT 10
    // (PIT 0): pitch 1.5 mm. NRC 2, no allowance, no idle pass: 2 cuts per turn.
    let t = run_clean_cycle("", &format!("{THREAD}CYCLE97(0,10,0,-30,20,20,4,2,0.9,0,0,0,2,0,1,2,0)\nM30"));
    let cuts = passes(&t, 10.0, -31.9, 3.9);
    assert_eq!(cuts.len(), 4);
    let step = 300.0 * 6.0 * (t.samples[1].t - t.samples[0].t);
    let turn = |i: usize| (cuts[i][0].sp - cuts[0][0].sp).rem_euclid(360.0);
    for (i, want) in [(1, 0.0), (2, 180.0), (3, 180.0)] {
        let d = (turn(i) - want + 180.0).rem_euclid(360.0) - 180.0;
        assert!(d.abs() <= step + 1e-6, "cut {i}: {}", turn(i));
    }
    let c = &cuts[0];
    let a = unwrapped(c);
    let (i, j) = (c.iter().position(|s| s.z < -5.0).unwrap(), c.iter().position(|s| s.z < -25.0).unwrap());
    let pitch = (c[i].z - c[j].z) / (a[j] - a[i]) * 360.0;
    assert!(close(pitch, 1.5, 1e-6), "pitch {pitch}");
}

#[test]
fn cycle97_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // PIT 2 disagrees with M10's 1.5: 61001; no pitch at all: 61001; VARI 5: 61002.
    for (call, number) in [
        ("CYCLE97(2,10,0,-30,20,20,4,2,0.9,0,0,0,2,0,1,1,0)", 61001),
        ("CYCLE97(0,0,0,-30,20,20,4,2,0.9,0,0,0,2,0,1,1,0)", 61001),
        ("CYCLE97(2,,0,-30,20,20,4,2,0.9,0,0,0,2,0,5,1,0)", 61002),
    ] {
        let t = run("", &format!("{THREAD}{call}\nM30"));
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(6)), "{call}");
    }
}

/// Distance from `p` to the segment `a`-`b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let k = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (p[0] - a[0] - k * dx).hypot(p[1] - a[1] - k * dy)
}

/// A DIN 509 undercut's profile in local coordinates: u from the shoulder's face along the
/// cylinder, v above the cylinder. Depth `t1`, radius `r`, face depth `t2` (0: form E).
struct Undercut {
    t1: f64,
    r: f64,
    t2: f64,
}

impl Undercut {
    /// Distance from `p` to the profile: face, (form F: the 8 degree line), the radius, the
    /// 15 degree run-out and the cylinder. Worked out from DIN 509: the radius's centre lies r
    /// above the depth t1 and r - t2 from the face; the 8 and 15 degree lines are tangent to it.
    fn distance(&self, p: [f64; 2]) -> f64 {
        let c = [self.r - self.t2, self.r - self.t1];
        let (s15, c15) = (15f64.to_radians().sin(), 15f64.to_radians().cos());
        let p15 = [c[0] + self.r * s15, c[1] - self.r * c15];
        let end = [p15[0] - p15[1] / 15f64.to_radians().tan(), 0.0];
        let (start_angle, mut best) = if self.t2 == 0.0 {
            (180f64, to_segment(p, [0.0, 10.0], [0.0, c[1]]))
        } else {
            let (s8, c8) = (8f64.to_radians().sin(), 8f64.to_radians().cos());
            let t = [c[0] - self.r * c8, c[1] + self.r * s8];
            let vm = t[1] - t[0] / 8f64.to_radians().tan();
            (172.0, to_segment(p, [0.0, 10.0], [0.0, vm]).min(to_segment(p, [0.0, vm], t)))
        };
        let a = (p[1] - c[1]).atan2(p[0] - c[0]).to_degrees().rem_euclid(360.0);
        let on_arc = if a >= start_angle && a <= 285.0 {
            ((p[0] - c[0]).hypot(p[1] - c[1]) - self.r).abs()
        } else {
            f64::INFINITY
        };
        let ends = |deg: f64| {
            let q = [c[0] + self.r * deg.to_radians().cos(), c[1] + self.r * deg.to_radians().sin()];
            (p[0] - q[0]).hypot(p[1] - q[1])
        };
        best = best.min(on_arc).min(ends(start_angle)).min(ends(285.0));
        best.min(to_segment(p, p15, end)).min(to_segment(p, end, [10.0, 0.0]))
    }
}

#[test]
fn cycle94_form_e_profile_is_the_din_form_offset_by_the_nose_radius() {
    // SPD 40 (18 < d <= 80): DIN 509 E 0.6 x 0.3. T2 (nose radius 0.4, edge position 3): the
    // shoulder's face at Z-30, the cylinder towards +Z. The nose centre lies 0.4 above and 0.4
    // to +Z of the theoretical tip; it never comes nearer than 0.4 to the profile and runs at
    // exactly 0.4 while cutting, reaching the base (tip at X 20 - 0.3) and the run-out's end.
    let t = run_clean_cycle("", "G18 G90 G95 F0.1\nT2 D1\nS800 M3\nG0 X30 Z10\nCYCLE94(40,-30,\"E\",3)\nM30");
    let form = Undercut { t1: 0.3, r: 0.6, t2: 0.0 };
    let centre = |s: &Sample| [s.z + 0.4 + 30.0, s.x + 0.4 - 20.0];
    let mut on = 0;
    for s in &t.samples {
        let d = form.distance(centre(s));
        assert!(d >= 0.4 - 1e-6, "gouges at {s:?}: {d}");
        if d < 0.4 + 1e-6 {
            on += 1;
        }
    }
    assert!(on > 20, "cuts along the profile: {on}");
    // The base lies mid-arc: the samples (5.3 µm apart at 80 mm/min) come within 6 µm of it.
    let min_x = t.samples.iter().map(|s| s.x).fold(f64::INFINITY, f64::min);
    assert!(min_x >= 19.7 - 1e-9 && close(min_x, 19.7, 1e-5), "base {min_x}");
    // The run-out ends on the cylinder 0.6 + 0.6 sin 15 + (0.3 - 0.6 (1 - cos 15)) / tan 15 from
    // the face; the nose centre there stands 0.4 off the 15 degree line.
    let (s15, c15) = (15f64.to_radians().sin(), 15f64.to_radians().cos());
    let end = 0.6 + 0.6 * s15 + (0.3 - 0.6 * (1.0 - c15)) / 15f64.to_radians().tan();
    let want = [end - 0.4 * s15, 0.4 * c15];
    assert!(t.samples.iter().any(|s| {
        let c = centre(s);
        close(c[0], want[0], 1e-6) && close(c[1], want[1], 1e-6)
    }));
}

#[test]
fn cycle94_form_f_recesses_the_face_and_mirrors_for_edge_position_4() {
    // A tool without nose radius: the tip runs on the profile. SPD 16 (10 < d <= 18): F 0.6 x
    // 0.2 with t2 0.1. Edge position 4: the cylinder lies towards -Z of the face at Z-10, so
    // u = -10 - Z. The tip reaches 0.1 behind the face (Z -9.9) and the base at X 8 - 0.2.
    let md = "$TC_DP6[1,1]=0\n$TC_DP2[1,1]=4\n";
    let t = run_clean_cycle(md, "G18 G90 G95 F0.1\nT1 D1\nS800 M3\nG0 X30 Z-40\nCYCLE94(16,-10,\"F\",0)\nM30");
    let form = Undercut { t1: 0.2, r: 0.6, t2: 0.1 };
    // Every sample behind the face or below the cylinder lies on the profile (within 1 µm).
    let mut on = 0;
    for s in &t.samples {
        let p = [-10.0 - s.z, s.x - 8.0];
        if p[0] < 0.0 || p[1] < 0.0 {
            assert!(form.distance(p) < 1e-6, "off the profile at {s:?}: {}", form.distance(p));
            on += 1;
        }
    }
    assert!(on > 20, "cuts along the profile: {on}");
    // The deepest points lie mid-arc: the samples come within 6 µm of them.
    let zmax = t.samples.iter().map(|s| s.z).fold(f64::NEG_INFINITY, f64::max);
    let min_x = t.samples.iter().map(|s| s.x).fold(f64::INFINITY, f64::min);
    assert!(zmax <= -9.9 + 1e-9 && close(zmax, -9.9, 1e-5), "face depth {zmax}");
    assert!(min_x >= 7.8 - 1e-9 && close(min_x, 7.8, 1e-5), "base {min_x}");
}

#[test]
fn cycle94_refuses_an_edge_position_without_undercut_and_a_nose_larger_than_the_radius() {
    // Edge position 8 (axis-parallel): 61608. T1's nose radius 0.8 in an E 0.6 x 0.3: 61105.
    for (md, call, number) in [
        ("", "CYCLE94(40,-30,\"E\",8)", 61608),
        ("", "CYCLE94(40,-30,\"E\",3)", 61105),
        ("", "CYCLE94(40,-30,\"G\",3)", 61002),
    ] {
        let t = run(md, &format!("G18 G90 G95 F0.1\nT1 D1\nG0 X30 Z10\n{call}\nM30"));
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(4)), "{call}");
    }
}

#[test]
fn cycle93_chamfers_at_the_edges_and_radii_at_the_base() {
    // The groove of the first test without allowances, RCO1 = RCO2 = -1 with VARI 11 (chamfer
    // legs of 1: the edge at Z-20 is cut from (Z-21, X20) to (Z-20, X19), the one at Z-10 from
    // (Z-10, X19) to (Z-9, X20)), RCI1 = RCI2 = 0.5 (radii at the base: centres (Z-19.5,
    // X15.5) and (Z-10.5, X15.5)). The D1 tip follows the low side, the tip + 3 the high side.
    let t = run_clean_cycle(
        GROOVER,
        "G18 G90 G94 F200\nT1 D1\nG0 X30 Z10\nCYCLE93(40,-20,10,5,0,0,0,-1,-1,0.5,0.5,0,0,0,0,11,0)\nM30",
    );
    let (mut chamfer, mut radius) = (0, 0);
    for s in t.samples.iter().filter(|s| s.x < 20.0 - 1e-6) {
        // Outside the chamfers' reach nothing lies beyond the flanks.
        let lo = if s.x > 19.0 { -20.0 - (s.x - 19.0) } else { -20.0 };
        let hi = if s.x > 19.0 { -10.0 + (s.x - 19.0) } else { -10.0 };
        assert!(s.z >= lo - 1e-6 && s.z + 3.0 <= hi + 1e-6, "{s:?}");
        if s.x > 19.0 && (close(s.z, lo, 1e-6) || close(s.z + 3.0, hi, 1e-6)) {
            chamfer += 1;
        }
        // In the base's corners the tool stays on or inside the radius.
        for (cz, zc) in [(-19.5, s.z), (-10.5, s.z + 3.0)] {
            let beyond = if cz < -15.0 { zc < cz } else { zc > cz };
            if s.x < 15.5 && beyond {
                let d = (zc - cz).hypot(s.x - 15.5);
                assert!(d <= 0.5 + 1e-6, "cuts into the radius at {s:?}: {d}");
                if close(d, 0.5, 1e-6) {
                    radius += 1;
                }
            }
        }
    }
    assert!(chamfer > 10 && radius > 10, "chamfer {chamfer}, radius {radius}");
    let min_x = t.samples.iter().map(|s| s.x).fold(f64::INFINITY, f64::min);
    assert!(close(min_x, 15.0, 1e-6));
}

#[test]
fn a_rounding_waits_for_the_next_motion_across_statements() {
    // The cycles write RND= in one branch of an IF: the ELSE/ENDIF lines between the two
    // straight blocks make no motion, and the corner (Z-20 X15, RND 0.5) is still rounded:
    // the tool leaves X to the arc at X15.5 and never passes Z-20 X15.
    let t = run_clean(
        "",
        "G18 G90 G94 F200\nG0 X20 Z-20\nIF 1 == 1\nG1 X15 RND=0.5\nELSE\nG1 X15\nENDIF\nR1=2\nG1 Z-13\nM30",
    );
    assert!(!t.samples.iter().any(|s| close(s.z, -20.0, 1e-9) && s.x < 15.5 - 1e-6), "sharp corner");
    let on_arc = t.samples.iter().filter(|s| close((s.z + 19.5).hypot(s.x - 15.5), 0.5, 1e-6) && s.x < 15.5).count();
    assert!(on_arc > 5, "{on_arc}");
}

/// A shaft's contour as a subprogram: from the face at diameter 20 along Z, a CW arc R5, a
/// shoulder and a taper (X a radius).
const SHAFT: &str = "G18 G90\nG1 X10 Z0\nG1 Z-20\nG2 X15 Z-25 CR=5\nG1 X20\nG1 X25 Z-40\nM17\n";

#[test]
fn contour_capture_records_the_elements_in_the_plane_and_nothing_moves() {
    // Five elements from the start X30 Z10 (G18: abscissa Z, ordinate X): the G1 to X10 Z0,
    // the line to Z-20, the CW arc to X15 Z-25 (radius 5 from both ends: centre Z-20 X15 or
    // Z-25 X10; clockwise with Z to the right and X up, from below the centre to its left, is
    // the first: a fillet into the shoulder), the shoulder to X20, the taper to X25 Z-40.
    let t = run_with(
        "",
        "DEF REAL TAB[8,7]\nDEF INT NN\nG18 G90 G94 F200\nG0 X30 Z10\nCONTCAPON(TAB, NN)\nCALL \"SHAFT\"\n\
         CONTCAPOF\nR1=NN R2=TAB[2,0] R3=TAB[2,5] R4=TAB[2,6] R5=TAB[4,3] R6=TAB[0,1]\nG1 X31\nM30",
        &[("SHAFT", SHAFT)],
    );
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    assert_eq!(t.r, vec![5.0, 2.0, -20.0, 15.0, -40.0, 10.0]);
    // The machine went from X30 Z10 straight to X31: Z never left 10 after the approach.
    let from = t.samples.iter().position(|s| close(s.x, 30.0, 1e-9) && close(s.z, 10.0, 1e-9)).unwrap();
    assert!(t.samples[from..].iter().all(|s| close(s.z, 10.0, 1e-9) && s.x >= 30.0 - 1e-9));
    assert!(close(t.samples.last().unwrap().x, 31.0, 1e-9));
    // With G42 selected in the contour (T1 has a nose radius) the elements stay as programmed
    // and nothing moves either.
    let t = run_with(
        "",
        "DEF REAL TAB[8,7]\nDEF INT NN\nG18 G90 G94 F200\nT1 D1\nG0 X30 Z10\nCONTCAPON(TAB, NN)\nCALL \"SHAFTC\"\n\
         CONTCAPOF\nR1=NN R2=TAB[2,0] R3=TAB[2,5] R4=TAB[2,6] R5=TAB[4,3] R6=TAB[0,1]\nG1 X31\nM30",
        &[("SHAFTC", &SHAFT.replace("G18 G90\n", "G18 G90 G42\n"))],
    );
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    assert_eq!(t.r, vec![5.0, 2.0, -20.0, 15.0, -40.0, 10.0]);
    let from = t.samples.iter().position(|s| close(s.x, 30.0, 1e-9) && close(s.z, 10.0, 1e-9)).unwrap();
    assert!(t.samples[from..].iter().all(|s| close(s.z, 10.0, 1e-9) && s.x >= 30.0 - 1e-9));
}

#[test]
fn cycle95_roughs_in_cuts_of_at_most_mid_leaving_the_allowance_and_finishes_on_the_contour() {
    // VARI 9: longitudinal outside, complete. A tool without nose radius. MID 2, FALZ 0.2,
    // FALX 0.1: the roughing boundary is the contour moved by +0.2 in Z and +0.1 in X. Levels
    // from the top X25 down to 10.1: 14.9 / 2 gives 8 cuts of 1.8625. Roughing never enters
    // the boundary; finishing (from Z1 X10 on) runs on the contour within 1 µm to Z-40 X25.
    let md = "$TC_DP6[1,1]=0\n";
    let t = run_with(
        md,
        "G18 G90 G94\nT1 D1\nS800 M3\nG0 X30 Z10\nCYCLE95(\"SHAFT\",2,0.2,0.1,0,300,0,100,9,0,0,0)\nM30",
        &[("SHAFT", SHAFT)],
    );
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    let t = cycle(&t, "G0 X30 Z10\n");
    let finish = t.samples.iter().rposition(|s| close(s.x, 10.0, 1e-9) && close(s.z, 1.0, 1e-9)).expect("finishing");
    let (rough, fin) = t.samples.split_at(finish);
    let boundary = |z: f64| if z > 0.2 { f64::NEG_INFINITY } else { shaft_radius((z - 0.2).max(-40.0)) + 0.1 };
    for s in rough {
        assert!(s.z < -40.0 + 0.2 - 1e-9 || s.x >= boundary(s.z) - 1e-6, "roughing enters the allowance at {s:?}");
    }
    // The cuts follow the boundary up the taper and the fillet (no residual corners left).
    let touching =
        |lo: f64, hi: f64| rough.iter().filter(|s| s.z > lo && s.z < hi && close(s.x, boundary(s.z), 1e-6)).count();
    assert!(
        touching(-39.8, -24.8) > 20 && touching(-24.8, -19.8) > 5,
        "{} {}",
        touching(-39.8, -24.8),
        touching(-24.8, -19.8)
    );
    // The roughing cuts: X levels of the feed moves along Z.
    let mut levels: Vec<f64> = Vec::new();
    for w in rough.windows(2) {
        let cut = close(w[0].x, w[1].x, 1e-12) && w[1].z < w[0].z - 1e-9 && w[0].z > 0.0 && w[0].z < 1.2 + 1e-9;
        if cut && levels.last().is_none_or(|l| !close(*l, w[0].x, 1e-9)) {
            levels.push(w[0].x);
        }
    }
    let want: Vec<f64> = (1..=8).map(|k| 25.0 - k as f64 * 1.8625).collect();
    assert_points(&levels, &want);
    // Finishing: on the contour from Z0 to Z-40.
    let mut on = 0;
    for s in fin.iter().filter(|s| s.z <= 0.0 && s.z >= -40.0 && s.x <= 25.0 + 1e-9) {
        let r = shaft_radius(s.z);
        let on_shoulder = close(s.z, -25.0, 1e-6) && s.x >= 15.0 - 1e-6 && s.x <= 20.0 + 1e-6;
        assert!(on_shoulder || close(s.x, r, 1e-6), "off the contour at {s:?}: {r}");
        on += 1;
    }
    assert!(on > 100);
    assert!(fin.iter().any(|s| close(s.z, -40.0, 1e-9) && close(s.x, 25.0, 1e-9)), "reaches the end");
}

#[test]
fn cycle95_face_roughing_cuts_along_x_in_levels_of_z() {
    // VARI 2 (face, outside, roughing) without allowances on a stepped face: Z-6 from X25 to
    // X15, up to Z-3, a slope to X5 Z0, then Z0 to the axis. The blank reaches Z0: 6 / MID 1.5
    // gives cuts at Z-1.5, -3, -4.5, -6 along -X; the tool never enters the part.
    let face = "G18 G90\nG1 X25 Z-6\nG1 X15\nG1 Z-3\nG1 X5 Z0\nG1 X0\nM17\n";
    let part = |x: f64| {
        if x >= 15.0 {
            -6.0
        } else if x >= 5.0 {
            -3.0 + (15.0 - x) / 10.0 * 3.0
        } else {
            0.0
        }
    };
    let t = run_with(
        "$TC_DP6[1,1]=0\n",
        "G18 G90 G94\nT1 D1\nG0 X40 Z10\nCYCLE95(\"FACE\",1.5,0,0,0,300,0,100,2,0,0,0)\nM30",
        &[("FACE", face)],
    );
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    let t = cycle(&t, "G0 X40 Z10\n");
    for s in t.samples.iter().filter(|s| s.x <= 25.0 && s.x >= 0.0) {
        // At the step X15 the part's face is the segment Z-6..-3.
        let floor = if close(s.x, 15.0, 1e-9) { -6.0 } else { part(s.x) };
        assert!(s.z >= floor - 1e-6, "inside the part at {s:?}");
    }
    let mut levels: Vec<f64> = Vec::new();
    for w in t.samples.windows(2) {
        let cut = close(w[0].z, w[1].z, 1e-12) && w[1].x < w[0].x - 1e-9 && w[0].x > 25.0 && w[0].x <= 26.0 + 1e-9;
        if cut && levels.last().is_none_or(|l| !close(*l, w[0].z, 1e-9)) {
            levels.push(w[0].z);
        }
    }
    assert_points(&levels, &[-1.5, -3.0, -4.5, -6.0]);
    // The last cut ends at the step (X15) and climbs it.
    assert!(t.samples.iter().any(|s| close(s.x, 15.0, 1e-9) && close(s.z, -4.5, 1e-9)));
}

#[test]
fn cycle95_refuses_backward_contours_sections_and_missing_feeds() {
    // A contour that goes back along the cut (Z-10 to Z-8 on the way): 61605. "A:B" (a
    // labelled section the calling program does not hold): 14080. VARI 13: 61002. Roughing
    // without FF1: 61003.
    let relief = "G18 G90\nG1 X10 Z0\nG1 Z-10\nG1 X12 Z-8\nG1 X20\nM17\n";
    for (call, number) in [
        ("CYCLE95(\"RELIEF\",2,0,0,0,300,0,100,9,0,0,0)", 61605),
        ("CYCLE95(\"A:B\",2,0,0,0,300,0,100,9,0,0,0)", 14080),
        ("CYCLE95(\"RELIEF\",2,0,0,0,300,0,100,13,0,0,0)", 61002),
        ("CYCLE95(\"RELIEF\",2,0,0,0,0,0,100,1,0,0,0)", 61003),
    ] {
        let t = run_with("", &format!("G18 G90 G94\nT1 D1\nG0 X30 Z10\n{call}\nM30"), &[("RELIEF", relief)]);
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(4)), "{call}");
    }
}

#[test]
fn cycle95_finishing_compensates_the_nose_radius() {
    // VARI 5 (finishing only) with T2: nose radius 0.4, edge position 3, so the nose's centre
    // lies 0.4 above and 0.4 towards +Z of the theoretical tip. Along the contour the centre
    // keeps exactly 0.4 from it (the compensated path), and never comes nearer.
    let t = run_with(
        "",
        "G18 G90 G94\nT2 D1\nS800 M3\nG0 X30 Z10\nCYCLE95(\"SHAFT\",2,0,0,0,300,0,100,5,0,0,0)\nM30",
        &[("SHAFT", SHAFT)],
    );
    assert!(t.alarms.is_empty(), "{:?}", t.alarms);
    let t = cycle(&t, "G0 X30 Z10\n");
    // Distance from a point to the shaft's outline (the face Z0 below X10 excluded: the tool
    // comes from +Z there).
    let dist = |z: f64, x: f64| {
        let mut d = f64::INFINITY;
        let seg = |a: [f64; 2], b: [f64; 2]| to_segment([z, x], a, b);
        d = d.min(seg([0.0, 10.0], [-20.0, 10.0]));
        let a = (x - 15.0).atan2(z + 20.0).to_degrees();
        if (-180.0..=-90.0).contains(&a) {
            d = d.min(((z + 20.0).hypot(x - 15.0) - 5.0).abs());
        }
        d = d.min(seg([-25.0, 15.0], [-25.0, 20.0])).min(seg([-25.0, 20.0], [-40.0, 25.0]));
        d
    };
    let mut on = 0;
    for s in &t.samples {
        let (cz, cx) = (s.z + 0.4, s.x + 0.4);
        if (-40.0..=0.0).contains(&cz) {
            let d = dist(cz, cx);
            assert!(d >= 0.4 - 1e-6, "the nose cuts into the part at {s:?}: {d}");
            if d < 0.4 + 1e-6 {
                on += 1;
            }
        }
    }
    assert!(on > 200, "finishes along the contour: {on}");
}

#[test]
fn cycle97_taper_and_face_threads_keep_depth_and_pitch_along_their_lead_axis() {
    // Taper: DM1 20 at Z0 to DM2 24 at Z-30 (radius +2 over 30 mm), APP 4, ROP 2: the cut runs
    // from Z4 to Z-32 on the taper extended, one cut to the full depth 1 (NRC 1, FAL 0): X =
    // 10 - Z * 2 / 30 - 1; the lead 2 mm along Z per revolution.
    let t = run_clean_cycle("", &format!("{THREAD}CYCLE97(2,,0,-30,20,24,4,2,1,0,0,0,1,0,1,1,0)\nM30"));
    let cut: Vec<Sample> =
        t.samples.iter().filter(|s| s.z < 3.9 && s.z > -31.9 && s.x < 10.0 - s.z * 2.0 / 30.0 - 0.5).copied().collect();
    assert!(cut.len() > 100);
    for s in &cut {
        assert!(close(s.x, 10.0 - s.z * 2.0 / 30.0 - 1.0, 1e-6), "off the taper at {s:?}");
    }
    let a = unwrapped(&cut);
    let (i, j) = (cut.iter().position(|s| s.z < -5.0).unwrap(), cut.iter().position(|s| s.z < -25.0).unwrap());
    assert!(close((cut[i].z - cut[j].z) / (a[j] - a[i]) * 360.0, 2.0, 1e-6));
    // Face thread: SPL = FPL = Z0, DM1 40 to DM2 10 (steeper than 45 degrees): the lead runs
    // along X from radius 20 + APP 2 to 5 - ROP 2 = 3, the depth 1 into the face (Z-1), 2 mm
    // of X per revolution.
    let t = run_clean_cycle("", &format!("{THREAD}CYCLE97(2,,0,0,40,10,2,2,1,0,0,0,1,0,1,1,0)\nM30"));
    let cut: Vec<Sample> =
        t.samples.iter().filter(|s| close(s.z, -1.0, 1e-9) && s.x < 21.9 && s.x > 3.1).copied().collect();
    assert!(cut.len() > 100);
    let a = unwrapped(&cut);
    let (i, j) = (cut.iter().position(|s| s.x < 18.0).unwrap(), cut.iter().position(|s| s.x < 6.0).unwrap());
    assert!(close((cut[i].x - cut[j].x) / (a[j] - a[i]) * 360.0, 2.0, 1e-6), "face pitch");
    assert!(t.samples.iter().all(|s| s.z >= -1.0 - 1e-9), "no deeper than the thread");
}

#[test]
fn cycle94_inside_undercut_lies_beyond_the_bore() {
    // Edge position 2 (inside, the bore towards +Z of the face at Z-15), SPD 30 (d 18..80:
    // E 0.6 x 0.3), a tool without nose radius: the undercut goes 0.3 deep into the bore wall
    // (radius 15 to 15.3) and never past its face (Z >= -15).
    let md = "$TC_DP6[1,1]=0\n$TC_DP2[1,1]=2\n";
    let t = run_clean_cycle(md, "G18 G90 G95 F0.1\nT1 D1\nS800 M3\nG0 X5 Z10\nCYCLE94(30,-15,\"E\",0)\nM30");
    let form = Undercut { t1: 0.3, r: 0.6, t2: 0.0 };
    let mut on = 0;
    for s in &t.samples {
        let p = [s.z + 15.0, 15.0 - s.x];
        assert!(p[0] >= -1e-9, "behind the face at {s:?}");
        if p[1] < 0.0 {
            assert!(form.distance(p) < 1e-6, "off the profile at {s:?}");
            on += 1;
        }
    }
    assert!(on > 20);
    let max_x = t.samples.iter().map(|s| s.x).fold(f64::NEG_INFINITY, f64::max);
    assert!(max_x <= 15.3 + 1e-9 && close(max_x, 15.3, 1e-5), "{max_x}");
}

/// Runs `main` twice, once in radius programming and once with `diameter` (the same program
/// with DIAMON and every transverse value doubled), and checks that the tool takes the same
/// machine path: the cycles' parameters are diameters either way, so only the display differs.
/// Cycles in which the tool stands still (waiting for the spindle's start angle) are left out.
fn assert_same_path_in_diameter_programming(radius: Trace, diameter: Trace) {
    assert!(radius.alarms.is_empty() && diameter.alarms.is_empty(), "{:?} {:?}", radius.alarms, diameter.alarms);
    let path = |t: &Trace| {
        let mut points: Vec<(f64, f64)> = Vec::new();
        for s in &t.samples {
            if points.last().is_none_or(|p| !close(p.0, s.mx, 1e-12) || !close(p.1, s.z, 1e-12)) {
                points.push((s.mx, s.z));
            }
        }
        points
    };
    let (r, d) = (path(&radius), path(&diameter));
    for (r, d) in r.iter().zip(&d) {
        assert!(close(d.0, r.0, 1e-9) && close(d.1, r.1, 1e-9), "radius run {r:?} against diameter run {d:?}");
    }
    assert_eq!(r.len(), d.len(), "the same number of positions");
}

/// The machine X of every cut along Z: runs of more than 20 IPO cycles in which X stays and Z
/// moves.
fn cut_radii(t: &Trace) -> Vec<f64> {
    let mut radii = Vec::new();
    let mut run = 0;
    for w in t.samples.windows(2) {
        if close(w[0].mx, w[1].mx, 1e-12) && !close(w[0].z, w[1].z, 1e-12) {
            run += 1;
            if run == 20 {
                radii.push(w[1].mx);
            }
        } else {
            run = 0;
        }
    }
    radii
}

#[test]
fn cycle97_under_diamon_cuts_the_same_thread_as_in_radius_programming() {
    // M20x2: DM1/DM2 are diameters in both modes. The approach X20 (radius) is X40 under DIAMON.
    // The cuts run at the same machine radii (seven: four roughing, finishing, two idle; each
    // followed by the return along Z at the retraction radius).
    let call = "CYCLE97(2,,0,-30,20,20,4,2,1.23,0.05,0,0,4,2,3,1,0)\nG0 X25\nM30";
    let radius = run("", &format!("{}{call}", THREAD.replace("G0 X20", "DIAMOF\nG0 X20")));
    let diameter =
        run("", &format!("{}{call}", THREAD.replace("G0 X20", "DIAMON\nG0 X40")).replace("G0 X25", "G0 X50"));
    assert!(radius.alarms.is_empty() && diameter.alarms.is_empty(), "{:?} {:?}", radius.alarms, diameter.alarms);
    let (r, d) = (cut_radii(&radius), cut_radii(&diameter));
    assert_eq!(r.len(), 14, "{r:?}");
    assert_points(&d, &r);
}

#[test]
fn cycle95_under_diamon_reads_the_contour_in_diameters_and_turns_the_same_shaft() {
    // The contour subprogram of a DIAMON program is written in diameters (CR stays a radius).
    let shaft_in_diameters = "G18 G90\nG1 X20 Z0\nG1 Z-20\nG2 X30 Z-25 CR=5\nG1 X40\nG1 X50 Z-40\nM17\n";
    let md = "$TC_DP6[1,1]=0\n";
    let main = "G18 G90 G94\nT1 D1\nS800 M3\nG0 X30 Z10\nCYCLE95(\"SHAFT\",2,0.2,0.1,0,300,0,100,9,0,0,0)\nM30";
    let radius = run_with(md, &main.replace("G0 X30", "DIAMOF\nG0 X30"), &[("SHAFT", SHAFT)]);
    let diameter = run_with(md, &main.replace("G0 X30", "DIAMON\nG0 X60"), &[("SHAFT", shaft_in_diameters)]);
    assert_same_path_in_diameter_programming(radius, diameter);
}
