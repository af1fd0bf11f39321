//! The multi-edge cycle CYCLE79 (NCTwin's parameter list: _RTP, _RFP, _SDIS, _DP, _PA, _PO,
//! _STA, _DIAM, _NUM, _SWL, _RC, _MID, _FAL, _FALD, _FFP1, _FFD, _CDIR, _VARI) on the 3-axis
//! mill (T1 D1: radius 5), checked on every sampled IPO point against the polygon worked out by
//! hand in each test.

use crate::cycles_support;
use cycles_support::*;

/// A regular polygon with `n` edges, the first edge's normal at `sta` degrees, the edges
/// `apothem` from `c`, the corners rounded by `rc`.
struct Polygon {
    c: (f64, f64),
    n: usize,
    sta: f64,
    apothem: f64,
    rc: f64,
}

impl Polygon {
    /// The distance of (x, y) outside the polygon: the distance to the sharp polygon shrunk by
    /// `rc`, less `rc`.
    fn distance(&self, x: f64, y: f64) -> f64 {
        let half = 180.0 / self.n as f64;
        let rho = (self.apothem - self.rc) / half.to_radians().cos();
        let v = |k: usize| {
            let w = (self.sta + half + 2.0 * half * k as f64).to_radians();
            [self.c.0 + rho * w.cos(), self.c.1 + rho * w.sin()]
        };
        let mut best = f64::MAX;
        for k in 0..self.n {
            let (a, b) = (v(k), v(k + 1));
            let d = [b[0] - a[0], b[1] - a[1]];
            let u = (((x - a[0]) * d[0] + (y - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
            best = best.min((x - a[0] - u * d[0]).hypot(y - a[1] - u * d[1]));
        }
        best - self.rc
    }
}

/// The BCS samples (the caller's WCS: the cycle works in its own frame) below Z0, the part's
/// top at RFP 0, after the tool's arrival at Z50.
fn cutting(t: &Trace) -> Vec<[f64; 3]> {
    let from = t.samples.iter().position(|s| s.b[2] >= 50.0).unwrap();
    t.samples[from..].iter().filter(|s| s.b[2] < -1e-9).map(|s| s.b).collect()
}

const START: &str = "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\n";

#[test]
fn cycle79_finishing_a_rounded_hexagon_keeps_the_tool_radius_from_every_edge_and_corner() {
    // Hexagon at (10, 20), width across flats 40 (edges 20 from the centre), first edge's
    // normal along +X, corners R3, depth -4 in one level, finishing. The tool centre runs at
    // the tool radius 5 from the part: edges 25 from the centre, corners R8 about the part's
    // corner centres. It never comes nearer than 5.
    let t = run_clean(&format!("{START}CYCLE79(50,0,2,-4,10,20,0,60,6,40,3,0,0,0,800,200,0,2)\nM30"));
    let hex = Polygon { c: (10.0, 20.0), n: 6, sta: 0.0, apothem: 20.0, rc: 3.0 };
    let pts = cutting(&t);
    assert!(pts.len() > 100);
    assert!(pts.iter().all(|p| close(p[2], -4.0, 1e-9) || p[2] > -4.0), "depth -4");
    assert!(close(pts.iter().map(|p| p[2]).fold(f64::MAX, f64::min), -4.0, 1e-9));
    for p in &pts {
        assert!(hex.distance(p[0], p[1]) >= 5.0 - 1e-6, "gouges at {p:?}: {}", hex.distance(p[0], p[1]));
    }
    // On the contour at every corner: the part's corner at 30 + 60 k degrees, its rounding's
    // centre 17 / cos 30 = 19.630 from the centre; the tool centre passes 8 from it on the
    // bisector, at 27.630.
    for k in 0..6 {
        let w = (30.0 + 60.0 * k as f64).to_radians();
        let corner = (10.0 + 27.630_07 * w.cos(), 20.0 + 27.630_07 * w.sin());
        let nearest = pts.iter().map(|p| (p[0] - corner.0).hypot(p[1] - corner.1)).fold(f64::MAX, f64::min);
        assert!(nearest < 0.05, "corner {k}: {nearest}");
    }
    let on = pts.iter().filter(|p| close(hex.distance(p[0], p[1]), 5.0, 1e-6)).count();
    assert!(on > 100, "the contour pass runs at the tool radius: {on}");
    // Climb milling (clockwise): from the first edge's middle (35, 20) the tool goes towards -Y.
    // (The first sample that leaves it: the tool may stand there a cycle after a stop.)
    let at = |p: &[f64; 3]| close(p[0], 35.0, 1e-6) && close(p[1], 20.0, 1e-6);
    let i = pts.iter().position(at).unwrap();
    assert!(pts[i..].iter().find(|p| !at(p)).unwrap()[1] < 20.0, "clockwise");
    assert!(close(t.samples.last().unwrap().b[2], 50.0, 1e-9), "back at the retraction plane");
}

#[test]
fn cycle79_roughing_passes_in_from_the_blank_and_leaves_the_allowances() {
    // The same hexagon (sharp corners), blank Ø60, roughing with FAL 0.5 and FALD 0.2, MID 3,
    // depth -6. The blank stands 30 - 20 - 0.5 = 9.5 over the last pass: ceil(9.5 / 8) = 2
    // passes, at 5.5 + 4.75 = 10.25 and 5.5 from the part's edges. Levels: 5.8 in ceil(5.8 / 3)
    // = 2 steps: -2.9 and -5.8.
    let t = run_clean(&format!("{START}CYCLE79(50,0,2,-6,10,20,0,60,6,40,0,3,0.5,0.2,800,200,0,1)\nM30"));
    let hex = Polygon { c: (10.0, 20.0), n: 6, sta: 0.0, apothem: 20.0, rc: 0.0 };
    let pts = cutting(&t);
    let nearest = pts.iter().map(|p| hex.distance(p[0], p[1])).fold(f64::MAX, f64::min);
    assert!(close(nearest, 5.5, 1e-6), "FAL 0.5 left: {nearest}");
    for level in [-2.9, -5.8] {
        for off in [10.25, 5.5] {
            // On the edges' middles: the edge normal at 0 degrees, the pass 20 + off out.
            let n = pts
                .iter()
                .filter(|p| close(p[2], level, 1e-9) && close(p[0], 30.0 + off, 1e-6) && (p[1] - 20.0).abs() < 5.0)
                .count();
            assert!(n > 0, "pass {off} on level {level}");
        }
    }
    let floor = pts.iter().map(|p| p[2]).fold(f64::MAX, f64::min);
    assert!(close(floor, -5.8, 1e-9), "FALD 0.2 left: {floor}");
}

#[test]
fn cycle79_edge_length_gives_the_square_and_its_sharp_corners_are_gone_round() {
    // _SWL -20: edge length 20 of a square (N 4): edges 20 / (2 tan 45) = 10 from the centre
    // (0, 0); turned by 45 degrees (the first edge's normal at 45): its corners on the axes at
    // 14.142. The tool centre's square: edges 15 out, corners at 15 / cos 45 = 21.213 on the axes.
    let t = run_clean(&format!("{START}CYCLE79(50,0,2,-3,0,0,45,30,4,-20,0,0,0,0,800,200,0,2)\nM30"));
    let sq = Polygon { c: (0.0, 0.0), n: 4, sta: 45.0, apothem: 10.0, rc: 0.0 };
    let pts = cutting(&t);
    assert!(pts.iter().all(|p| sq.distance(p[0], p[1]) >= 5.0 - 1e-6));
    for corner in [(21.2132, 0.0), (0.0, 21.2132), (-21.2132, 0.0), (0.0, -21.2132)] {
        assert!(pts.iter().any(|p| close(p[0], corner.0, 1e-3) && close(p[1], corner.1, 1e-3)), "corner {corner:?}");
    }
}

#[test]
fn cycle79_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    for (call, number) in [
        ("CYCLE79(50,0,2,-4,10,20,0,60,2,40,0,0,0,0,800,200,0,2)", 61106),
        ("CYCLE79(50,0,2,-4,10,20,0,60,6,40,0,0,0,0,800,200,0,3)", 61002),
        ("CYCLE79(50,0,2,-4,10,20,0,60,6,40,25,0,0,0,800,200,0,2)", 61113),
        ("CYCLE79(50,0,2,-4,10,20,0,60,6,0,0,0,0,0,800,200,0,2)", 61118),
    ] {
        let t = run(&format!("{START}{call}\nM30"));
        let got: Vec<_> = t.alarms.iter().map(|a| (a.number, a.line)).collect();
        assert_eq!(got, vec![(number, Some(3))], "{call}");
    }
}
