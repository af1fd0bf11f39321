//! The turning cycles of the standard cycle library (CYCLE93 grooving, CYCLE94/CYCLE96
//! undercuts, CYCLE97 threads), checked on the path they produce on the 2-axis lathe (X is a
//! radius, DIAMOF): groove bases and flanks, undercut profiles and thread cuts worked out by
//! hand from the documented parameter lists in each test's comments.

use nctwin_engine::Channel;
use nctwin_engine::alarm::Alarm;

const MAX_TICKS: usize = 5_000_000;

/// One IPO cycle: WCS X (radius), WCS Z, the spindle's machine angle (degrees) and the line of
/// the block in force.
#[derive(Clone, Copy, Debug)]
struct Sample {
    x: f64,
    z: f64,
    sp: f64,
    line: Option<u32>,
}

struct Trace {
    samples: Vec<Sample>,
    alarms: Vec<Alarm>,
}

/// Runs `main` on the 2-axis lathe with the machine data `md` added (tool data) and records
/// every IPO cycle until the channel rests.
fn run(md: &str, main: &str) -> Trace {
    let mut ch = Channel::from_preset("lathe-2axis", md).unwrap();
    ch.run_program(main).unwrap_or_else(|e| panic!("not started: {e}"));
    let mut samples = vec![sample(&ch)];
    while ch.is_busy() {
        ch.step();
        samples.push(sample(&ch));
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    Trace { samples, alarms: ch.snapshot().alarms }
}

fn run_clean(md: &str, main: &str) -> Trace {
    let t = run(md, main);
    assert!(t.alarms.is_empty(), "alarms: {:?}", t.alarms);
    t
}

/// The samples of the cycle's own blocks: the snapshot shows the line of the cycle's block in
/// force, and every cycle's blocks stand after its header comment (past line `from`), while the
/// test programs are a few lines long.
fn cycle(t: &Trace, from: u32) -> Trace {
    let samples: Vec<Sample> = t.samples.iter().filter(|s| s.line.is_some_and(|l| l > from)).copied().collect();
    assert!(!samples.is_empty(), "the cycle never ran");
    Trace { samples, alarms: t.alarms.clone() }
}

/// Runs `main` (at most 20 lines) without alarms and keeps the samples of the cycle's blocks.
fn run_clean_cycle(md: &str, main: &str) -> Trace {
    cycle(&run_clean(md, main), 20)
}

fn sample(ch: &Channel) -> Sample {
    let s = ch.snapshot();
    let get = |l: &[(String, f64)], n: &str| l.iter().find(|(a, _)| a == n).map_or(f64::NAN, |a| a.1);
    Sample {
        x: get(&s.workpiece, "X"),
        z: get(&s.workpiece, "Z"),
        sp: get(&s.machine, "SP1"),
        line: s.block.map(|b| b.line),
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
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
    let sub = Trace { samples: t.samples[first..out].to_vec(), alarms: vec![] };
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
