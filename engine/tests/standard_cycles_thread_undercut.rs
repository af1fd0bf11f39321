//! The thread undercut cycle CYCLE96 (DIN 76-1 forms A..D) on the 2-axis lathe (X a radius,
//! DIAMOF), checked on the path of the tool's nose against the DIN profile worked out by hand in
//! each test from the standard's table (DIATH, SPL, FORM, VARI).

use crate::turning_support;

use turning_support::{Trace, close, run_lathe};

/// T3: an inside tool without nose radius, edge position 2.
const INSIDE: &str = "$TC_DP1[3,1]=500\n$TC_DP2[3,1]=2\n$TC_DP3[3,1]=0\n$TC_DP4[3,1]=0\n$TC_DP6[3,1]=0\n";

fn run(md: &str, tool: &str, call: &str) -> Trace {
    run_lathe(md, &format!("G18 G90 G95 F0.1\n{tool}\nS800 M3\nG0 X40 Z10\n{call}\nM30"), &[])
}

fn run_clean(md: &str, tool: &str, call: &str) -> Trace {
    run(md, tool, call).clean().after_reaching(40.0, 10.0)
}

fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let u = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
    (p[0] - a[0] - u * d[0]).hypot(p[1] - a[1] - u * d[1])
}

/// An outside undercut's profile (Z, X) with the face at `z0` and the thread towards +Z: the
/// face down from X 40, the radius `r` tangent to face and base, the base at `r0 - t` to the
/// width `g1`, the run-out to the surface `r0` at `g2`, the surface on to Z 10.
struct Outside {
    z0: f64,
    r0: f64,
    t: f64,
    r: f64,
    g1: f64,
    g2: f64,
}

impl Outside {
    fn distance(&self, p: [f64; 2]) -> f64 {
        let (z0, r0, t, r) = (self.z0, self.r0, self.t, self.r);
        let face = to_segment(p, [z0, 40.0], [z0, r0 - t + r]);
        let c = [z0 + r, r0 - t + r];
        // The quarter of the radius between the face (180 degrees) and the base (270).
        let a = (p[1] - c[1]).atan2(p[0] - c[0]).to_degrees().rem_euclid(360.0);
        let arc =
            if (180.0..=270.0).contains(&a) { ((p[0] - c[0]).hypot(p[1] - c[1]) - r).abs() } else { f64::INFINITY };
        let base = to_segment(p, [z0 + r, r0 - t], [z0 + self.g1, r0 - t]);
        let run_out = to_segment(p, [z0 + self.g1, r0 - t], [z0 + self.g2, r0]);
        let surface = to_segment(p, [z0 + self.g2, r0], [10.0, r0]);
        face.min(arc).min(base).min(run_out).min(surface)
    }

    /// Checks the nose (radius `rn`, centre `rn` above and to +Z of the tip, edge position 3):
    /// never nearer than `rn` to the profile, exactly `rn` while deep in the cut, and the tip
    /// at the base's depth and on the face.
    fn check(&self, t: &Trace, rn: f64) {
        let mut cutting = 0;
        for s in &t.samples {
            let d = self.distance([s.z + rn, s.x + rn]);
            assert!(d >= rn - 1e-6, "gouges at Z{} X{}: {d}", s.z, s.x);
            // Below the surface by more than half the nose radius the nose touches the profile
            // (past the run-out's end the nose rounds the corner and lifts off it).
            if s.x < self.r0 - rn / 2.0 && s.z > self.z0 - 1.0 && s.z < self.z0 + self.g2 {
                assert!(close(d, rn, 1e-6), "off the profile at Z{} X{}: {d}", s.z, s.x);
                cutting += 1;
            }
        }
        assert!(cutting > 20, "cuts along the profile");
        let xmin = t.samples.iter().map(|s| s.x).fold(f64::INFINITY, f64::min);
        assert!(close(xmin, self.r0 - self.t, 1e-6), "base {xmin}");
        let zmin = t.samples.iter().map(|s| s.z).fold(f64::INFINITY, f64::min);
        assert!(close(zmin, self.z0, 1e-6), "face {zmin}");
    }
}

#[test]
fn cycle96_form_a_is_the_din_76_undercut_of_the_coarse_thread_offset_by_the_nose_radius() {
    // M10: coarse pitch 1.5. DIN 76-1 form A for P 1.5: g1 3.2, g2 5.2, dg = d - 2.3 = 7.7,
    // r 0.8. Radius 5, depth t = 1.15. T2: nose radius 0.4, edge position 3 (thread towards +Z
    // of the face at Z-20). The retraction: the tip 1 mm above the surface, X6.
    let t = run_clean("", "T2 D1", "CYCLE96(10,-20,\"A\",3)");
    let profile = Outside { z0: -20.0, r0: 5.0, t: 1.15, r: 0.8, g1: 3.2, g2: 5.2 };
    profile.check(&t, 0.4);
    let end = t.samples.last().unwrap();
    assert!(close(end.x, 6.0, 1e-9), "retracted to X{}", end.x);
}

#[test]
fn cycle96_form_b_is_shorter_and_the_edge_position_comes_from_the_tool() {
    // M16: pitch 2. Form B: g1 3.4, g2 5, dg = 16 - 3 = 13, r 1: radius 8, depth 1.5. VARI 0:
    // T2's edge position 3.
    let t = run_clean("", "T2 D1", "CYCLE96(16,-20,\"B\",0)");
    let profile = Outside { z0: -20.0, r0: 8.0, t: 1.5, r: 1.0, g1: 3.4, g2: 5.0 };
    profile.check(&t, 0.4);
}

#[test]
fn cycle96_form_d_inside_lies_beyond_the_bore() {
    // M20: pitch 2.5. Inside short form D (the decisions of the cycle's header): g1 = 2.5 P =
    // 6.25, g2 = g1 + 1.2 P = 9.25, dg = d + 0.5 P = 21.25 (radius 10.625), r = 0.5 P = 1.25;
    // the bore is the minor diameter 20 - 1.0825 * 2.5 = 17.29375 (radius 8.646875). T3 (no
    // nose radius, edge position 2: the thread towards +Z of the face at Z-30). Path: G0 X7.646875
    // (1 mm inside the bore), Z-30, G1 X9.375 (the radius's start on the face), the radius
    // about (Z-28.75, X9.375) to (Z-28.75, X10.625), the base to Z-23.75, the run-out to Z-20.75
    // X8.646875, G0 X7.646875.
    let t = run_clean(INSIDE, "T3 D1", "CYCLE96(20,-30,\"D\",2)");
    let xmax = t.samples.iter().map(|s| s.x).fold(f64::NEG_INFINITY, f64::max);
    assert!(close(xmax, 40.0, 1e-9));
    let inner: Vec<_> = t.samples.iter().filter(|s| s.x > 8.646875 + 1e-6 && s.x < 20.0 && s.z < -20.0).collect();
    assert!(inner.len() > 20);
    let deepest = inner.iter().map(|s| s.x).fold(f64::NEG_INFINITY, f64::max);
    assert!(close(deepest, 10.625, 1e-6), "undercut radius {deepest}");
    for s in &inner {
        let on_face = close(s.z, -30.0, 1e-6) && s.x <= 9.375 + 1e-6;
        let on_arc = s.z < -28.75 && close((s.z + 28.75).hypot(s.x - 9.375), 1.25, 1e-6);
        let on_base = close(s.x, 10.625, 1e-6) && s.z >= -28.75 - 1e-6 && s.z <= -23.75 + 1e-6;
        let run_out = (s.z + 23.75) / 3.0 * -1.978125 + 10.625;
        let on_run_out = s.z >= -23.75 - 1e-6 && s.z <= -20.75 + 1e-6 && close(s.x, run_out, 1e-6);
        assert!(on_face || on_arc || on_base || on_run_out, "off the profile at Z{} X{}", s.z, s.x);
    }
    let end = t.samples.last().unwrap();
    assert!(close(end.x, 7.646875, 1e-9) && close(end.z, -20.75, 1e-9), "end Z{} X{}", end.z, end.x);
}

#[test]
fn cycle96_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    // Form G: 61609; M11 is no coarse thread size: 61001; edge position 5: 61608; T1's nose
    // radius 0.8 in M6's undercut (P 1: r 0.6): 61105.
    for (tool, call, number) in [
        ("T2 D1", "CYCLE96(10,-20,\"G\",3)", 61609),
        ("T2 D1", "CYCLE96(11,-20,\"A\",3)", 61001),
        ("T2 D1", "CYCLE96(10,-20,\"A\",5)", 61608),
        ("T1 D1", "CYCLE96(6,-20,\"A\",3)", 61105),
    ] {
        let t = run("", tool, call);
        assert_eq!(t.alarms.len(), 1, "{call}: {:?}", t.alarms);
        assert_eq!((t.alarms[0].number, t.alarms[0].line), (number, Some(5)), "{call}");
        let end = t.samples.last().unwrap();
        assert!(close(end.x, 40.0, 1e-9) && close(end.z, 10.0, 1e-9), "{call}: nothing moved");
    }
}

#[test]
fn cycle96_under_diamon_cuts_the_same_undercut() {
    // DIATH is a diameter in both modes; the approach X40 (radius) is X80 under DIAMON: every
    // sample's machine X and Z agree.
    let main = |mode: &str, x: &str| {
        format!("G18 G90 G95 F0.1\nT2 D1\nS800 M3\n{mode}\nG0 {x} Z10\nCYCLE96(10,-20,\"A\",3)\nM30")
    };
    let radius = run_lathe("", &main("DIAMOF", "X40"), &[]).clean();
    let diameter = run_lathe("", &main("DIAMON", "X80"), &[]).clean();
    assert_eq!(radius.samples.len(), diameter.samples.len());
    for (r, d) in radius.samples.iter().zip(&diameter.samples) {
        assert!(close(r.mx, d.mx, 1e-9) && close(r.z, d.z, 1e-9), "{r:?} {d:?}");
    }
}
