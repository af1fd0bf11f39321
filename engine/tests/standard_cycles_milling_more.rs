//! The milling cycles added to the library after the pockets (spigots CYCLE76/CYCLE77, face
//! milling CYCLE61/CYCLE71, circumferential slots SLOT2, helical insertion of POCKET3/POCKET4),
//! checked on every sampled IPO point of their path. The expected geometry is worked out by
//! hand from the documented parameters in each test's comments. The tool is T1 D1 of the
//! 3-axis mill: radius 5.

mod cycles_support;
use cycles_support::*;

const Z: usize = 2;

/// The BCS samples below `below`, from the first arrival at the start height Z50 on (before it
/// the tool's length offset puts the tip below the part), in the coordinates of a feature
/// centred at `c` and turned by `sta`°.
fn local(t: &Trace, c: (f64, f64), sta: f64, below: f64) -> Vec<[f64; 3]> {
    let (s, co) = sta.to_radians().sin_cos();
    let from = t.samples.iter().position(|p| p.b[Z] >= 50.0).unwrap();
    t.samples[from..]
        .iter()
        .filter(|p| p.b[Z] < below - 1e-9)
        .map(|p| {
            let (dx, dy) = (p.b[0] - c.0, p.b[1] - c.1);
            [dx * co + dy * s, -dx * s + dy * co, p.b[Z]]
        })
        .collect()
}

/// Signed distance of (u, v) from a rectangle of half sizes hx, hy with corner radius rc
/// (positive outside).
fn rect_distance(u: f64, v: f64, hx: f64, hy: f64, rc: f64) -> f64 {
    let (qx, qy) = (u.abs() - (hx - rc), v.abs() - (hy - rc));
    qx.max(0.0).hypot(qy.max(0.0)) + qx.max(qy).min(0.0) - rc
}

fn min_of(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(f64::MAX, f64::min)
}

fn alarms(t: &Trace) -> Vec<(u32, Option<u32>)> {
    t.alarms.iter().map(|a| (a.number, a.line)).collect()
}

#[test]
fn cycle77_roughing_circles_in_from_the_blank_and_leaves_the_allowance() {
    // Spigot Ø40 at (10, 20), depth -6 from RFP 0, MID 3, FAL 0.5, FALD 0.2, blank Ø60, climb.
    // Last circle of the tool centre: 20 + 5 + 0.5 = 25.5. The blank stands 30 - 20 - 0.5 = 9.5
    // over it: ceil(9.5 / 8) = 2 circles, at 25.5 + 4.75 = 30.25 and 25.5. Depth to -6 + 0.2 =
    // -5.8 in ceil(5.8 / 3) = 2 levels: -2.9 and -5.8.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE77(10,0,2,-6,,40,10,20,3,0.5,0.2,500,150,0,1,60)\nM30");
    let pts = local(&t, (10.0, 20.0), 0.0, 0.0);
    assert!(pts.len() > 100);
    let r = |p: &[f64; 3]| p[0].hypot(p[1]);
    let nearest = min_of(pts.iter().map(r));
    assert!(close(nearest, 25.5, 1e-6), "roughing leaves FAL 0.5 beyond the tool radius: {nearest}");
    assert!(pts.iter().filter(|p| close(r(p), 30.25, 1e-6)).count() > 20, "the first circle from the blank");
    let floor = min_of(pts.iter().map(|p| p[2]));
    assert!(close(floor, -5.8, 1e-9), "FALD 0.2 left: {floor}");
    assert!(pts.iter().any(|p| close(p[2], -2.9, 1e-9) && close(r(p), 25.5, 1e-6)), "level -2.9");
    // Climb milling around an outside contour with M3 is clockwise: the angle falls.
    let ring: Vec<_> = pts.iter().filter(|p| close(r(p), 25.5, 1e-6) && close(p[2], -5.8, 1e-9)).collect();
    let turn = ring.windows(2).map(|w| w[0][0] * w[1][1] - w[0][1] * w[1][0]).sum::<f64>();
    assert!(turn < 0.0, "G2");
    assert!(close(t.end()[Z], 10.0, 1e-9));
}

#[test]
fn cycle77_finishing_leaves_exactly_the_programmed_diameter() {
    // Ø40 finished (VARI 2), conventional (CDIR 1: G3), depth DPR 6 from RFP 0 in one level:
    // the tool centre comes no nearer than 20 + 5 = 25 and runs a circle at exactly 25, -6.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE77(10,0,2,,6,40,10,20,0,0.5,0.2,500,150,1,2,60)\nM30");
    let pts = local(&t, (10.0, 20.0), 0.0, 0.0);
    let r = |p: &[f64; 3]| p[0].hypot(p[1]);
    assert!(close(min_of(pts.iter().map(r)), 25.0, 1e-6));
    let ring: Vec<_> = pts.iter().filter(|p| close(r(p), 25.0, 1e-6)).collect();
    assert!(ring.len() > 50);
    assert!(ring.iter().all(|p| close(p[2], -6.0, 1e-9)), "finished at the depth");
    let turn = ring.windows(2).map(|w| w[0][0] * w[1][1] - w[0][1] * w[1][0]).sum::<f64>();
    assert!(turn > 0.0, "G3");
}

#[test]
fn cycle76_roughing_stays_outside_the_spigot_plus_radius_and_allowance() {
    // 40 x 30 spigot, corner radius 5, centre (50, 40), turned 30°, depth -5 in one level (MID
    // 0), FAL 1, FALD 0, blank 60 x 44. Last contour: half sizes 20 + 6 = 26 and 15 + 6 = 21.
    // The blank stands max(60 - 40, 44 - 30) / 2 - 1 = 9 over it: ceil(9 / 8) = 2 contours,
    // 4.5 and 0 further out. Every point stays at least 5 + 1 = 6 from the spigot.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE76(10,0,2,-5,,40,30,5,50,40,30,0,1,0,500,150,0,1,60,44)\nM30",
    );
    let pts = local(&t, (50.0, 40.0), 30.0, 0.0);
    assert!(pts.len() > 100);
    let d = |p: &[f64; 3]| rect_distance(p[0], p[1], 20.0, 15.0, 5.0);
    let nearest = min_of(pts.iter().map(d));
    assert!(close(nearest, 6.0, 1e-6), "tool radius + FAL: {nearest}");
    assert!(pts.iter().filter(|p| close(d(p), 10.5, 1e-6)).count() > 20, "the first contour, 4.5 further out");
    assert!(close(min_of(pts.iter().map(|p| p[2])), -5.0, 1e-9));
    // Each side of the last contour is milled: the middle of each side at distance 6.
    for (u, v) in [(26.0, 0.0), (-26.0, 0.0), (0.0, 21.0), (0.0, -21.0)] {
        assert!(pts.iter().any(|p| close(p[0], u, 1e-6) && close(p[1], v, 1e-6)), "side at ({u}, {v})");
    }
}

#[test]
fn cycle76_finishing_leaves_exactly_the_programmed_size_at_depth() {
    // Finishing (VARI 2) of the same spigot, depth -5 in MID 2.5 steps: levels -2.5 and -5. The
    // tool centre never comes nearer than 5 and follows the contour at 5 at each level: the
    // spigot is 40 x 30 with R5 corners.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE76(10,0,2,-5,,40,30,5,50,40,30,2.5,1,0,500,150,0,2,60,44)\nM30",
    );
    let pts = local(&t, (50.0, 40.0), 30.0, 0.0);
    let d = |p: &[f64; 3]| rect_distance(p[0], p[1], 20.0, 15.0, 5.0);
    assert!(close(min_of(pts.iter().map(d)), 5.0, 1e-6));
    for z in [-2.5, -5.0] {
        let at: Vec<_> = pts.iter().filter(|p| close(p[2], z, 1e-9) && close(d(p), 5.0, 1e-6)).collect();
        assert!(at.len() > 50, "contour at {z}");
        // The corner arcs too: a point beyond both half sizes minus the corner radius.
        assert!(at.iter().any(|p| p[0].abs() > 16.0 && p[1].abs() > 11.0), "corner at {z}");
    }
    assert!(close(min_of(pts.iter().map(|p| p[2])), -5.0, 1e-9));
}

#[test]
fn cycle76_alarms_at_the_calling_line() {
    // Corner radius 20 on a 40 x 30 spigot: larger than half the width.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE76(10,0,2,-5,,40,30,20,0,0,0,0,1,0,500,150,0,1)\nM30");
    assert_eq!(alarms(&t), vec![(61113, Some(3))]);
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE77(10,0,2,-5,,40,0,0,0,1,0,500,150,0,3)\nM30");
    assert_eq!(alarms(&t), vec![(61002, Some(3))]);
}
