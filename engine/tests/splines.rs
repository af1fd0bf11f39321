//! Spline and polynomial interpolation (ASPLINE, BSPLINE, CSPLINE, POLY; Programming Manual
//! Job planning) run through a whole channel on the 3-axis mill preset (30 m/min, 3 m/s²,
//! overload 1.2, IPO cycle 4 ms; no tool, so the axis positions are the WCS points), and the
//! geometry module checked on its own. Expected values are worked out by hand in the comments.

use crate::path_support;

use nctwin_engine::Channel;
use nctwin_engine::motion::AxisVec;
use nctwin_engine::motion::spline::{self, BSpline, EndCondition};
use path_support::{DT, assert_dynamics};

fn run(program: &str) -> Vec<[f64; 3]> {
    path_support::samples("", program, 3_000_000).1
}

fn first_alarm(program: &str) -> Option<u32> {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ch.snapshot().alarms.first().map(|a| a.number)
}

fn passes(samples: &[[f64; 3]], x: f64, y: f64) -> bool {
    samples.iter().any(|p| (p[0] - x).abs() < 1e-9 && (p[1] - y).abs() < 1e-9)
}

/// The largest turn of the direction of travel from one IPO step to the next (radians),
/// over steps longer than `min` (a tangent kink shows as a turn of its full angle).
fn largest_turn(samples: &[[f64; 3]], min: f64) -> f64 {
    let steps: Vec<[f64; 2]> =
        samples.windows(2).map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]]).filter(|d| d[0].hypot(d[1]) > min).collect();
    steps
        .windows(2)
        .map(|w| (w[0][0] * w[1][1] - w[0][1] * w[1][0]).atan2(w[0][0] * w[1][0] + w[0][1] * w[1][1]).abs())
        .fold(0.0, f64::max)
}

fn pt(x: f64, y: f64) -> AxisVec {
    let mut p: AxisVec = std::array::from_fn(|_| 0.0);
    p[0] = x;
    p[1] = y;
    p
}

const POINTS: [(f64, f64); 4] = [(10.0, 5.0), (20.0, 0.0), (30.0, 5.0), (40.0, 0.0)];

fn spline_program(kind: &str, exact_stop: &str) -> String {
    let mut text = format!("G0 X0 Y0 Z0\nG1 F3000 {exact_stop}\n{kind}");
    for (x, y) in POINTS {
        text.push_str(&format!(" X{x} Y{y}\n"));
    }
    text.push_str("G1 X50\nM30\n");
    text
}

/// With exact stop (G60) every block ends on its programmed point, so the IPO samples hit
/// each point of the C spline and of the A spline exactly.
#[test]
fn cspline_and_aspline_pass_through_every_programmed_point() {
    for kind in ["CSPLINE", "ASPLINE"] {
        let s = run(&spline_program(kind, "G60"));
        for (x, y) in POINTS {
            assert!(passes(&s, x, y), "{kind} misses ({x}, {y})");
        }
        // Not the polyline: between (0,0) and (10,5) the path leaves the chord Y = X/2.
        let off = s.iter().filter(|p| p[0] > 0.5 && p[0] < 9.5).map(|p| (p[1] - p[0] / 2.0).abs()).fold(0.0, f64::max);
        assert!(off > 0.1, "{kind}: {off}");
    }
}

/// Under G64 the C spline runs without a kink: the direction of travel turns by little from
/// one IPO cycle to the next (at 3 m/min a step is 0.2 mm; the tightest bend of this spline
/// has a radius of some millimetres, so a few hundredths of a radian), while the polyline of
/// the same points turns by atan(1/2)+atan(1/2) = 53° at its corners.
#[test]
fn cspline_runs_with_a_continuous_tangent_in_the_ipo_samples() {
    let s = run(&spline_program("CSPLINE", ""));
    assert!(largest_turn(&s, 0.05) < 0.1, "{}", largest_turn(&s, 0.05));
    assert_dynamics(&s);
    assert!(passes(&s, 50.0, 0.0));
}

/// The C spline's pieces meet with equal first and second derivative with respect to the
/// path parameter (chord lengths): the tangent and the curvature are continuous at every
/// programmed point; ENAT/BNAT give zero curvature at the ends.
#[test]
fn cspline_pieces_join_with_continuous_tangent_and_curvature() {
    let pts: Vec<AxisVec> = [(0.0, 0.0)].iter().chain(POINTS.iter()).map(|&(x, y)| pt(x, y)).collect();
    let h: Vec<f64> = pts.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).collect();
    let pieces = spline::cubic(&pts, &h, EndCondition::Natural, EndCondition::Natural);
    assert_eq!(pieces.len(), 4);
    for i in 0..3 {
        let (end, next) = (pieces[i][1], pieces[i + 1][0]);
        for k in 0..2 {
            assert!((end.0[k] - next.0[k]).abs() < 1e-12);
            assert!((end.1[k] / h[i] - next.1[k] / h[i + 1]).abs() < 1e-9, "tangent at point {}", i + 1);
            assert!(
                (end.2[k] / (h[i] * h[i]) - next.2[k] / (h[i + 1] * h[i + 1])).abs() < 1e-9,
                "curvature at point {}",
                i + 1
            );
        }
    }
    assert!(pieces[0][0].2.iter().chain(pieces[3][1].2.iter()).all(|x| x.abs() < 1e-12));
}

/// The A spline is tangent-continuous at its points (its curvature may jump).
#[test]
fn aspline_pieces_join_with_continuous_tangent() {
    let pts: Vec<AxisVec> = [(0.0, 0.0)].iter().chain(POINTS.iter()).map(|&(x, y)| pt(x, y)).collect();
    let h: Vec<f64> = pts.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).collect();
    let pieces = spline::akima(&pts, &h, EndCondition::Auto, EndCondition::Auto);
    for i in 0..3 {
        for k in 0..2 {
            assert!((pieces[i][1].1[k] / h[i] - pieces[i + 1][0].1[k] / h[i + 1]).abs() < 1e-9);
        }
    }
}

/// B spline of degree 3 with weights 1 and four control points (the start (0,0) and three
/// programmed): one span, the cubic Bézier curve of the control polygon. It starts at (0,0),
/// ends at (40,0), passes through C(½) = (P0 + 3P1 + 3P2 + P3)/8 = (20, 15) and stays inside
/// the control polygon's convex hull (the quadrilateral (0,0), (10,20), (30,20), (40,0)).
#[test]
fn bspline_of_degree_3_stays_in_the_convex_hull_and_ends_on_the_last_point() {
    let s = run("G0 X0 Y0 Z0\nG1 F3000\nBSPLINE SD=3 X10 Y20 PW=1\nX30 Y20\nX40 Y0\nG1 X50\nM30");
    let hull = [[0.0, 0.0], [40.0, 0.0], [30.0, 20.0], [10.0, 20.0]];
    for p in &s {
        if p[0] > 40.0 {
            continue; // the G1 X50 after it
        }
        for i in 0..4 {
            let (a, b) = (hull[i], hull[(i + 1) % 4]);
            let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            assert!(cross >= -1e-9, "{p:?} outside the hull edge {a:?}–{b:?}");
        }
    }
    assert!(passes(&s, 40.0, 0.0) || s.iter().any(|p| p[0] > 40.0));
    let step = 3000.0 / 60.0 * DT;
    let near = s.iter().map(|p| (p[0] - 20.0).hypot(p[1] - 15.0)).fold(f64::INFINITY, f64::min);
    assert!(near <= step / 2.0 + 1e-9, "{near}");
    assert_eq!(&s.last().unwrap()[..2], &[50.0, 0.0]);
    assert_dynamics(&s);
}

/// With exact stop the B spline's last block ends on its last point, and the curve is
/// tangent to the control polygon there (last step along (30,20)→(40,0), direction (1, −2)).
#[test]
fn bspline_ends_on_its_last_point_tangent_to_the_polygon() {
    let s = run("G0 X0 Y0 Z0\nG1 F3000 G60\nBSPLINE X10 Y20\nX30 Y20\nX40 Y0\nM30");
    let i = s.iter().position(|p| (p[0] - 40.0).abs() < 1e-9 && p[1].abs() < 1e-9).expect("ends at (40, 0)");
    let j = (0..i).rev().find(|&j| (s[i][0] - s[j][0]).hypot(s[i][1] - s[j][1]) > 0.5).unwrap();
    let d = [s[i][0] - s[j][0], s[i][1] - s[j][1]];
    assert!((d[1] / d[0] + 2.0).abs() < 0.05, "{d:?}");
}

/// A point weight pulls the curve towards its point: with degree 2 (SD=2) over (0,0),
/// (10,20), (20,0) the curve's middle is (P0 + 2w·P1 + P2)/(2 + 2w): (10, 10) for w = 1 and
/// (10, 15) for w = 3.
#[test]
fn bspline_point_weight_and_degree_2() {
    for (w, y) in [(1.0, 10.0), (3.0, 15.0)] {
        let s = run(&format!("G0 X0 Y0 Z0\nG1 F3000\nBSPLINE SD=2 X10 Y20 PW={w}\nX20 Y0\nM30"));
        let top = s.iter().map(|p| p[1]).fold(0.0, f64::max);
        assert!((top - y).abs() < 1e-3, "PW={w}: highest Y {top}");
        assert_eq!(&s.last().unwrap()[..2], &[20.0, 0.0]);
    }
    let control = [pt(0.0, 0.0), pt(10.0, 20.0), pt(20.0, 0.0)];
    let b = BSpline { control: &control, weights: &[1.0, 3.0, 1.0], degree: 2, spans: &[1.0] };
    // The rational span is approximated by quintic pieces that join end to end.
    let pieces = &b.pieces()[0];
    assert!(!pieces.is_empty());
    for w in pieces.windows(2) {
        assert_eq!(w[0][1].0, w[1][0].0);
    }
}

/// POLY: x(p) = x0 + a1·p + 2p² with PO[X]=(10, 2) and PL=1 from x0 = 0 gives a1 = 8;
/// y(p) = b1·p + p² + p³ with PO[Y]=(0, 1, 1) gives b1 = −2. Every sample lies on that curve:
/// p from x by the positive root of 2p² + 8p − x = 0, then y = −2p + p² + p³.
#[test]
fn poly_evaluates_the_programmed_polynomial() {
    let s = run("G0 X0 Y0 Z0\nG1 F3000\nPOLY PO[X]=(10, 2) PO[Y]=(0, 1, 1) PL=1\nG1 X20\nM30");
    let on = s.iter().filter(|p| p[0] <= 10.0 && p[0] > 0.0);
    let mut n = 0;
    for p in on {
        let u = (-8.0 + (64.0 + 8.0 * p[0]).sqrt()) / 4.0;
        assert!((p[1] - (-2.0 * u + u * u + u * u * u)).abs() < 1e-6, "{p:?}");
        n += 1;
    }
    assert!(n > 10);
    assert!(s.iter().any(|p| p[1] < -0.6), "the path dips (y(½) = −0.625)");
    assert_dynamics(&s);
    assert_eq!(&s.last().unwrap()[..2], &[20.0, 0.0]);
}

/// PL scales the parameter: PO[X]=(10, 1) PL=2 is x = a1·p + p², x(2) = 10 → a1 = 3, so at
/// mid-parameter p = 1 x = 4 (not 5): with Y linear in p (Y programmed plainly, 0 → 10) the
/// path passes (4, 5).
#[test]
fn poly_with_pl_and_a_linear_axis() {
    let s = run("G0 X0 Y0 Z0\nG1 F3000\nPOLY PO[X]=(10, 1) Y10 PL=2\nM30");
    let near = s.iter().map(|p| (p[0] - 4.0).hypot(p[1] - 5.0)).fold(f64::INFINITY, f64::min);
    assert!(near < 0.06, "{near}");
    assert_eq!(&s.last().unwrap()[..2], &[10.0, 10.0]);
}

/// A POLY block whose end points lie within the software limits can run out between them: with
/// both ends at X0 PO[X]=(0, 0, c) is x = a1·p + c·p³ with a1 = −c, so x(p) = c·(p³ − p), least
/// at p = 1/√3: x = −2c/(3√3) = −0.3849·c. Below X−500 (the mill's limit) for c > 1299:
/// c = 1250 dips to −481.1, c = 1350 to −519.6 (10720 at the block, as for a circle that
/// leaves the range, instead of running into the limit). Found by `robustness_language.rs`:
/// c = 1EX300 overflowed, the positions became NaN and the block never ended.
#[test]
fn poly_beyond_the_software_limit_between_its_end_points_is_alarm_10720() {
    let alarm = |c: &str| {
        let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
        ch.run_program(&format!("G0 X0 Y0 Z0\nG1 F3000\nPOLY PO[X]=(0, 0, {c}) Y1\nM30")).unwrap();
        for _ in 0..200_000 {
            if !ch.is_busy() {
                break;
            }
            ch.step();
        }
        assert!(!ch.is_busy(), "PO[X]=(0, 0, {c}) did not end");
        assert!(ch.axis_positions().iter().all(|p| p.is_finite()), "{:?}", ch.axis_positions());
        ch.snapshot().alarms.first().map(|a| (a.number, a.line, a.message.ends_with("software limit switch -")))
    };
    assert_eq!(alarm("1250"), None);
    assert_eq!(alarm("1350"), Some((10720, Some(3), true)));
    // Overflowed: no side to name, but the block is refused all the same.
    assert_eq!(alarm("1EX300").map(|(n, line, _)| (n, line)), Some((10720, Some(3))));
}

#[test]
fn invalid_spline_words_are_alarms() {
    // SD only 2 or 3, PW only 0..3: 12560 (programmed value exceeds allowed limits).
    assert_eq!(first_alarm("G1 F1000\nBSPLINE SD=4 X10\nM30"), Some(12560));
    assert_eq!(first_alarm("G1 F1000\nBSPLINE X10 PW=5\nM30"), Some(12560));
    // A spline under tool radius compensation is not modelled: 12550.
    assert_eq!(first_alarm("T1 D1\nG1 F1000 G41 X10 Y0\nCSPLINE X20 Y5\nX30 Y0\nG40 X40\nM30"), Some(12550));
}

/// At a feed near the axes' limit on a tight zig-zag (bends of a few millimetres' radius) the
/// path speed must drop on the bends: no axis exceeds 30 m/min or 3 m/s² (×1.2 at block
/// transitions) in any IPO cycle, for every spline type and POLY.
#[test]
fn every_spline_type_keeps_the_axis_limits_in_every_ipo_cycle() {
    for kind in ["ASPLINE", "BSPLINE", "CSPLINE", "BSPLINE SD=2"] {
        let mut text = format!("G0 X0 Y0 Z0\nG1 F30000\n{kind}");
        for i in 1..=12 {
            text.push_str(&format!(" X{} Y{}\n", 4 * i, if i % 2 == 1 { 3 } else { 0 }));
        }
        text.push_str("G1 X60\nM30\n");
        let s = run(&text);
        assert_dynamics(&s);
        assert_eq!(&s.last().unwrap()[..2], &[60.0, 0.0], "{kind}");
    }
    let s = run(
        "G0 X0 Y0 Z0\nG1 F30000\nPOLY PO[X]=(10, 2, -3) PO[Y]=(0, 20, -20) PL=1\nPOLY PO[X]=(20, -1) PO[Y]=(0, -5)\nM30",
    );
    assert_dynamics(&s);
    assert_eq!(&s.last().unwrap()[..2], &[20.0, 0.0]);
}

/// `$P_GG` reads the spline types in G group 1 (ASPLINE 6, BSPLINE 7, CSPLINE 8, POLY 9) and
/// G groups 19/20 (BNAT/ENAT 1, BTAN/ETAN 2 = reset value, BAUTO/EAUTO 3); a wrong value
/// raises the cycle alarm 65000 through SETAL.
#[test]
fn p_gg_reads_the_spline_groups() {
    let program = "G0 X0 Y0 Z0\nIF ($P_GG[19]<>2) OR ($P_GG[20]<>2)\nSETAL(65000)\nENDIF\nG1 F3000\nCSPLINE BNAT EAUTO X10 Y5\nIF ($P_GG[1]<>8) OR ($P_GG[19]<>1) OR ($P_GG[20]<>3)\nSETAL(65000)\nENDIF\nX20 Y0\nBSPLINE X30\nIF $P_GG[1]<>7\nSETAL(65000)\nENDIF\nASPLINE X40\nIF $P_GG[1]<>6\nSETAL(65000)\nENDIF\nPOLY X50\nIF $P_GG[1]<>9\nSETAL(65000)\nENDIF\nG1 X60\nIF $P_GG[1]<>2\nSETAL(65000)\nENDIF\nM30";
    let s = run(program);
    assert_eq!(&s.last().unwrap()[..2], &[60.0, 0.0]);
}
