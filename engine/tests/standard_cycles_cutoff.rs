//! The cut-off cycle CYCLE92 on the 2-axis lathe (X a radius, DIAMOF), checked on the path,
//! the feed per revolution and the spindle speed of every IPO cycle against values worked out
//! by hand from the parameter list (SPD, SPL, DIAG1, DIAG2, RC, SDIS, SV1, SV2, SDAC, FF1, FF2,
//! SS2, _VRT, _VARI, _DN, _DMODE, _AMODE).

use crate::turning_support;

use turning_support::{Sample, Trace, close, run_lathe, unwrapped};

const SETUP: &str = "G18 G90 G95 F0.3\nT1 D1\nS500 M3\nG4 F1\nG0 X40 Z10\n";

fn run(call: &str) -> Trace {
    run_lathe("", &format!("{SETUP}{call}\nM30"), &[])
}

fn run_clean(call: &str) -> Trace {
    run(call).clean().after_reaching(40.0, 10.0)
}

/// The X travel per spindle revolution, the spindle speed (rev/min) and the mean X between
/// consecutive samples at Z = `z` while X falls through (lo, hi).
fn feed_and_speed(t: &Trace, z: f64, lo: f64, hi: f64) -> Vec<(f64, f64, f64)> {
    let a = unwrapped(&t.samples);
    let s: &[Sample] = &t.samples;
    (1..s.len())
        .filter(|&i| close(s[i].z, z, 1e-9) && s[i].x < s[i - 1].x - 1e-9 && s[i - 1].x < hi && s[i].x > lo)
        .map(|i| {
            let rev = (a[i] - a[i - 1]) / 360.0;
            ((s[i - 1].x - s[i].x) / rev, rev / (s[i].t - s[i - 1].t) * 60.0, (s[i - 1].x + s[i].x) / 2.0)
        })
        .collect()
}

/// The lowest and highest X of the samples.
fn x_extremes(t: &Trace) -> (f64, f64) {
    let xs = t.samples.iter().map(|s| s.x);
    (xs.clone().fold(f64::INFINITY, f64::min), xs.fold(f64::NEG_INFINITY, f64::max))
}

#[test]
fn cycle92_cuts_a_chamfer_at_constant_cutting_rate_and_holds_the_limited_speed_near_the_centre() {
    // SPD 60 (radius 30), cut at Z-20, DIAG1 20 (radius 10), DIAG2 -1 (radius -0.5, past the
    // centre), chamfer (_VARI units 1) RC 2, SDIS 1, cutting rate (tens 1) V 100 m/min limited to
    // SV2 1000 rev/min, M3, FF1 0.2 mm/rev, FF2 0.05, SS2 0 (the speed at DIAG1 held).
    // Path: G0 X31 (30 + SDIS), G0 Z-18 (SPL + RC), G1 X30, chamfer to X28 Z-20, G1 X10, then
    // G97 at the speed at DIAG1 and on to at 0.05 mm/rev, G0 back to X31.
    // G96: n = 100000 / (2 pi r): r 25 -> 636.6 rev/min; below r 15.92 the limit 1000; the
    // speed at DIAG1 (r 10, 1591.5) is limited: 1000 held to the end. (At r 25 the spindle
    // must change by 25 rev/min per mm, 50 rev/min per second: it follows without lag.)
    let t = run_clean("CYCLE92(60,-20,20,-1,2,1,100,1000,3,0.2,0.05,0,0,11,0,0,0)");
    let (xmin, xmax) = x_extremes(&t);
    assert!(close(xmin, -0.5, 1e-6), "final depth {xmin}");
    assert!(close(xmax, 40.0, 1e-9));
    // The chamfer: every sample with Z in (-20, -18) lies on the 45 degree line from (Z-18, X30)
    // to (Z-20, X28): X = 30 + (Z + 18).
    let chamfer: Vec<&Sample> = t.samples.iter().filter(|s| s.z < -18.0 - 1e-6 && s.z > -20.0 + 1e-6).collect();
    assert!(chamfer.len() > 3, "the chamfer is cut");
    for s in &chamfer {
        assert!(close(s.x, 30.0 + (s.z + 18.0), 1e-6), "chamfer at Z{} X{}", s.z, s.x);
    }
    // Approach at X31 only: before the chamfer nothing lies below X31 at another Z than -18.
    let off: Vec<_> = t.samples.iter().filter(|s| s.x < 31.0 - 1e-9 && s.z > -18.0 + 1e-9).collect();
    assert!(off.is_empty(), "{:?}", &off[..off.len().min(3)]);
    // Feed and speed along the cut-off.
    let outer = feed_and_speed(&t, -20.0, 16.5, 27.0);
    assert!(outer.len() > 100);
    for (f, n, x) in outer {
        assert!(close(f, 0.2, 1e-3), "feed at r{x} {f}");
        let want = 100_000.0 / (2.0 * std::f64::consts::PI * x);
        assert!((n - want).abs() < want * 2e-3, "speed at r{x}: {n}, not {want}");
    }
    let below = feed_and_speed(&t, -20.0, 11.0, 15.0);
    assert!(!below.is_empty());
    for (f, n, _) in below {
        assert!(close(f, 0.2, 1e-3), "feed above DIAG1 {f}");
        assert!(close(n, 1000.0, 1.0), "limited speed {n}");
    }
    let centre = feed_and_speed(&t, -20.0, 0.0, 9.0);
    assert!(!centre.is_empty());
    for (f, n, _) in centre {
        assert!(close(f, 0.05, 1e-4), "reduced feed {f}");
        assert!(close(n, 1000.0, 1.0), "speed at DIAG1 held {n}");
    }
    // The end: back out to X31 at Z-20.
    let end = t.samples.last().unwrap();
    assert!(close(end.x, 31.0, 1e-9) && close(end.z, -20.0, 1e-9), "end X{} Z{}", end.x, end.z);
}

#[test]
fn cycle92_rounds_the_edge_and_reduces_the_speed_beyond_diag1() {
    // SPD 50 (radius 25), Z-10, DIAG1 10 (radius 5), DIAG2 0, rounding (_VARI 2) RC 3, SDIS 2,
    // speed 800 rev/min (tens 0), FF1 0.15, FF2 0.1, SS2 400, _VRT 1.
    // Path: G0 X27, Z-7, G1 X25, G3 quarter circle about (Z-7, X22) to (Z-10, X22), G1 X5 at
    // 800 rev/min and 0.15 mm/rev, X0 at 400 rev/min and 0.1 mm/rev, G0 X28 (27 + _VRT).
    let t = run_clean("CYCLE92(50,-10,10,0,3,2,800,0,3,0.15,0.1,400,1,2,0,0,0)");
    let arc: Vec<&Sample> = t.samples.iter().filter(|s| s.z < -7.0 - 1e-6 && s.z > -10.0 + 1e-6).collect();
    assert!(arc.len() > 3, "the rounding is cut");
    for s in &arc {
        let d = (s.z + 7.0).hypot(s.x - 22.0);
        assert!(close(d, 3.0, 1e-4), "rounding at Z{} X{}: {d}", s.z, s.x);
        // The quarter towards the corner (Z-10, X25): above X22 and before Z-7.
        assert!(s.x >= 22.0 - 1e-6);
    }
    for (f, n, _) in feed_and_speed(&t, -10.0, 6.0, 20.0) {
        assert!(close(f, 0.15, 1e-3), "feed {f}");
        assert!(close(n, 800.0, 1.0), "speed {n}");
    }
    // The spindle slows from 800 to 400 rev/min at 30 rev/s^2 (0.22 s): check the reduced
    // values beyond that, below X4.
    let centre = feed_and_speed(&t, -10.0, 0.0, 4.0);
    assert!(!centre.is_empty());
    for (f, n, _) in centre {
        assert!(close(f, 0.1, 1e-4), "reduced feed {f}");
        assert!(close(n, 400.0, 1.0), "reduced speed {n}");
    }
    let (xmin, _) = x_extremes(&t);
    assert!(close(xmin, 0.0, 1e-6), "to the centre {xmin}");
    let end = t.samples.last().unwrap();
    assert!(close(end.x, 28.0, 1e-9) && close(end.z, -10.0, 1e-9), "end X{} Z{}", end.x, end.z);
}

#[test]
fn cycle92_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // No feed: 61003; DIAG1 above SPD: 61601; _VARI 3 (no such edge form): 61002; cutting rate
    // without a limit to the centre (DIAG1 0, SV2 0): 61002.
    for (call, number) in [
        ("CYCLE92(60,-20,20,0,0,1,800,0,3,0,0,0,0,0,0,0,0)", 61003),
        ("CYCLE92(60,-20,70,0,0,1,800,0,3,0.1,0,0,0,0,0,0,0)", 61601),
        ("CYCLE92(60,-20,20,0,1,1,800,0,3,0.1,0,0,0,3,0,0,0)", 61002),
        ("CYCLE92(60,-20,0,0,0,1,100,0,3,0.1,0,0,0,10,0,0,0)", 61002),
    ] {
        let t = run(call);
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(6)), "{call}");
        let end = t.samples.last().unwrap();
        assert!(close(end.x, 40.0, 1e-9) && close(end.z, 10.0, 1e-9), "{call}: nothing moved");
    }
}

#[test]
fn cycle92_under_diamon_parts_off_on_the_same_machine_path() {
    // The cycle's diameters are diameters in both modes; the approach X40 (radius) is X80 under
    // DIAMON. Every sample's machine X and Z agree, and so does the spindle (G96 reads the
    // radius either way).
    let main = |mode: &str, x: &str| {
        format!(
            "G18 G90 G95 F0.3\nT1 D1\nS500 M3\nG4 F1\n{mode}\nG0 {x} Z10\n\
             CYCLE92(60,-20,20,-1,2,1,100,1000,3,0.2,0.05,0,0,11,0,0,0)\nM30"
        )
    };
    let radius = run_lathe("", &main("DIAMOF", "X40"), &[]).clean();
    let diameter = run_lathe("", &main("DIAMON", "X80"), &[]).clean();
    assert_eq!(radius.samples.len(), diameter.samples.len());
    for (r, d) in radius.samples.iter().zip(&diameter.samples) {
        assert!(close(r.mx, d.mx, 1e-9) && close(r.z, d.z, 1e-9) && close(r.sp, d.sp, 1e-9), "{r:?} {d:?}");
    }
}

#[test]
fn cycle92_with_a_second_edge_parts_with_that_edge_at_z0_and_gives_the_callers_edge_back() {
    // T1's D2: the blade's other corner, 3 mm further along Z than D1 (L2 63 against 60).
    // Without a chamfer, at the speed 500 rev/min, to the centre: the plunge runs at Z-20 with
    // the cutting edge in use; with _DN 2 that is D2, so the machine Z is 3 mm more than with
    // D1 (_DN 0) while the workpiece Z is -20 in both. R1 = $P_TOOL after the cycle: D1 again.
    let md = "$TC_DP1[1,2]=500\n$TC_DP2[1,2]=4\n$TC_DP3[1,2]=40\n$TC_DP4[1,2]=63\n$TC_DP6[1,2]=0\n";
    let plunge = |dn: u32| {
        let call = format!("CYCLE92(60,-20,0,0,0,1,500,0,3,0.2,0,0,0,0,{dn},0,0)\nR1=$P_TOOL");
        let t = run_lathe(md, &format!("{SETUP}{call}\nM30"), &[]).clean();
        // The plunge: the samples at workpiece Z-20 on the way from X29 to the centre.
        let cut: Vec<Sample> =
            t.samples.iter().filter(|s| s.x < 29.0 && s.x > 0.5 && close(s.z, -20.0, 1e-9)).copied().collect();
        assert!(cut.len() > 100, "the plunge is sampled");
        let mz = cut[0].mz;
        assert!(cut.iter().all(|s| close(s.mz, mz, 1e-9)), "one machine Z along the plunge");
        assert_eq!(t.r[0], 1.0, "D1 is active after the cycle");
        mz
    };
    assert!(close(plunge(2) - plunge(0), 3.0, 1e-9));
}
