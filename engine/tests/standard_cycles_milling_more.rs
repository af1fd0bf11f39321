//! The milling cycles added to the library after the pockets (spigots CYCLE76/CYCLE77, face
//! milling CYCLE61/CYCLE71, circumferential slots SLOT2, helical insertion of POCKET3/POCKET4),
//! checked on every sampled IPO point of their path. The expected geometry is worked out by
//! hand from the documented parameters in each test's comments. The tool is T1 D1 of the
//! 3-axis mill: radius 5.

use crate::cycles_support;
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
    let t =
        run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE77(10,0,2,-6,,40,10,20,3,0.5,0.2,500,150,0,1,60)\nM30");
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
    let t =
        run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE77(10,0,2,,6,40,10,20,0,0.5,0.2,500,150,1,2,60)\nM30");
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

/// The points of the face `[x0, x1] x [y0, y1]` (every `step` mm) farther than the tool radius
/// 5 (+ `tol`) from the path at height `z` (the straight pieces between consecutive samples
/// both at `z`).
fn uncovered(pts: &[[f64; 3]], z: f64, (x0, x1, y0, y1): (f64, f64, f64, f64), step: f64, tol: f64) -> Vec<(f64, f64)> {
    let segs: Vec<_> = pts.windows(2).filter(|w| close(w[0][2], z, 1e-9) && close(w[1][2], z, 1e-9)).collect();
    let dist = |w: &[[f64; 3]], x: f64, y: f64| {
        let (ax, ay, bx, by) = (w[0][0], w[0][1], w[1][0], w[1][1]);
        let (dx, dy) = (bx - ax, by - ay);
        let l2 = dx * dx + dy * dy;
        let s = if l2 > 0.0 { (((x - ax) * dx + (y - ay) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
        (ax + s * dx - x).hypot(ay + s * dy - y)
    };
    let mut out = Vec::new();
    let (nx, ny) = (((x1 - x0) / step).round() as usize, ((y1 - y0) / step).round() as usize);
    for i in 0..=nx {
        for j in 0..=ny {
            let (x, y) = (x0 + i as f64 * step, y0 + j as f64 * step);
            if !segs.iter().any(|w| dist(w, x, y) <= 5.0 + tol) {
                out.push((x, y));
            }
        }
    }
    out
}

#[test]
fn cycle61_roughing_meander_covers_the_face_and_stops_at_the_allowance() {
    // Face 0..100 x 0..60 at Z0 0, finished height -3, DZ 2, width of cut 8, UZ 0.5, SC 1,
    // VARI 31 (roughing, along the abscissa alternating), no limits. Depth -2.5 in
    // ceil(2.5 / 2) = 2 levels: -1.25, -2.5. Lines from 0 + 5 - 8 = -3 to 60 - 5 + 8 = 63: 66 in
    // ceil(66 / 8) = 9 steps of 7.333; each line from -5 - 1 = -6 to 100 + 5 = 105.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE61(10,0,1,-3,0,0,100,60,2,8,0.5,1000,31,0)\nM30");
    let pts = local(&t, (0.0, 0.0), 0.0, 0.0);
    let floor = min_of(pts.iter().map(|p| p[2]));
    assert!(close(floor, -2.5, 1e-9), "never below -3 + UZ: {floor}");
    assert!(pts.iter().any(|p| close(p[2], -1.25, 1e-9)), "first level");
    for z in [-1.25, -2.5] {
        let gaps = uncovered(&pts, z, (0.0, 100.0, 0.0, 60.0), 2.0, 0.0);
        assert!(gaps.is_empty(), "not milled at {z}: {gaps:?}");
    }
    let deep: Vec<_> = pts.iter().filter(|p| close(p[2], -2.5, 1e-9)).collect();
    let (lo, hi) = (min_of(deep.iter().map(|p| p[0])), -min_of(deep.iter().map(|p| -p[0])));
    assert!(close(lo, -6.0, 1e-6) && close(hi, 105.0, 1e-6), "lines run out of the face: {lo} {hi}");
    for k in 0..=9 {
        let v = -3.0 + k as f64 * 66.0 / 9.0;
        assert!(deep.iter().any(|p| close(p[1], v, 1e-6) && close(p[0], 50.0, 0.5)), "line at {v}");
    }
    // Alternating: the step-overs run at depth, at the line ends outside the face.
    assert!(deep.iter().any(|p| close(p[0], 105.0, 1e-6) && close(p[1], -3.0 + 33.0 / 9.0, 1.0)));
    assert!(close(t.end()[Z], 10.0, 1e-9));
}

#[test]
fn cycle61_finishing_one_direction_against_a_wall() {
    // Finishing (VARI 22: along the ordinate, one way) of 0..100 x 0..60 to -3 with a wall at X0
    // (LIM 1): the tool centre keeps 5 from X0, lines at X = 5 .. 100 - 5 + 8 = 103 in
    // ceil(98 / 8) = 13 steps, each from Y -6 to 65, all in +Y; the face still fully covered.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE61(10,0,1,-3,0,0,100,60,2,8,0.5,1000,22,1)\nM30");
    let pts = local(&t, (0.0, 0.0), 0.0, 0.0);
    let at: Vec<_> = pts.iter().filter(|p| close(p[2], -3.0, 1e-9)).collect();
    assert!(close(min_of(pts.iter().map(|p| p[2])), -3.0, 1e-9), "exactly the finished height");
    assert!(close(min_of(at.iter().map(|p| p[0])), 5.0, 1e-6), "the wall at X0 is not touched");
    assert!(uncovered(&pts, -3.0, (0.0, 100.0, 0.0, 60.0), 2.0, 1e-6).is_empty());
    for w in at.windows(2) {
        assert!(w[1][1] >= w[0][1] - 1e-9 || !close(w[0][0], w[1][0], 1e-9), "one way: {w:?}");
    }
    for k in 0..=13 {
        let x = 5.0 + k as f64 * 98.0 / 13.0;
        assert!(at.iter().any(|p| close(p[0], x, 1e-6) && close(p[1], 65.0, 1e-6)), "line at {x}");
    }
}

#[test]
fn cycle71_older_list_mills_a_turned_face_from_its_corner() {
    // Corner (10, 20), 50 x 30 turned by 30°, depth -1 from RFP 0 in one level, width 80 % of
    // Ø10 = 8, VARI 41 (roughing along the ordinate, alternating), FALD 0: in the face's own
    // coordinates every point of 0..50 x 0..30 lies within 5 of the path at -1.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE71(10,0,2,-1,10,20,50,30,30,0,0,5,0,800,41,5)\nM30");
    let pts = local(&t, (10.0, 20.0), 30.0, 0.0);
    assert!(close(min_of(pts.iter().map(|p| p[2])), -1.0, 1e-9));
    let gaps = uncovered(&pts, -1.0, (0.0, 50.0, 0.0, 30.0), 2.0, 0.0);
    assert!(gaps.is_empty(), "{gaps:?}");
    assert_eq!(t.end(), [t.end()[0], t.end()[1], 10.0]);
}

#[test]
fn cycle61_alarms_at_the_calling_line() {
    // Width of cut 12 > Ø10; finished height above the face.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE61(10,0,1,-3,0,0,100,60,2,12,0,1000,31,0)\nM30");
    assert_eq!(alarms(&t), vec![(61111, Some(3))]);
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nN7 CYCLE71(10,0,2,1,0,0,50,30,0,0,0,5,0,800,11,5)\nM30");
    assert_eq!(alarms(&t), vec![(61101, Some(3))]);
    // No feed: 61003.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE61(10,0,1,-3,0,0,100,60,2,8,0,0,31,0)\nM30");
    assert_eq!(alarms(&t), vec![(61003, Some(3))]);
}

#[test]
fn cycle90_alarms_for_no_pitch_and_a_tool_too_large_for_the_core() {
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE90(10,0,2,-10,,20,17.294,0,300,3,0,0,0)\nM30");
    assert_eq!(alarms(&t), vec![(61001, Some(3))]);
    // M8 internal: core 6.647 < the tool's Ø10.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE90(10,0,2,-10,,8,6.647,1.25,300,3,0,0,0)\nM30");
    assert_eq!(alarms(&t), vec![(61105, Some(3))]);
}

/// Distance of (x, y) from the arc of radius `rad` around the origin from `a0`° through `len`°.
fn arc_distance(x: f64, y: f64, rad: f64, a0: f64, len: f64) -> f64 {
    let w = (y.atan2(x).to_degrees() - a0).rem_euclid(360.0);
    if w <= len {
        return (x.hypot(y) - rad).abs();
    }
    let end = |a: f64| {
        let (s, c) = a.to_radians().sin_cos();
        (x - rad * c).hypot(y - rad * s)
    };
    end(a0).min(end(a0 + len))
}

#[test]
fn slot2_slots_lie_on_the_circle_and_end_at_their_angles() {
    // 3 slots Ø16 wide, 60° long, on R40 around (10, 0), the first from 30°, 120° apart; depth
    // -4 in MID 2 steps; FAL 0.5; complete machining (VARI 0), CDIR 3. Tool R5: the tool centre
    // stays within 8 - 5 = 3 of each slot's middle arc (roughing within 2.5) and the finishing
    // contour reaches exactly 3: along the circle beyond each end by 3, i.e. the slot's end half
    // circle of radius 8 around the end at 30 + 60 = 90° (then 210°, 330°).
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nSLOT2(10,0,2,-4,,3,60,16,10,0,40,30,120,100,500,2,3,0.5,0,0,400)\nM30",
    );
    let pts = local(&t, (10.0, 0.0), 0.0, 0.0);
    assert!(pts.len() > 100);
    let starts = [30.0, 150.0, 270.0];
    for p in &pts {
        let d = starts.iter().map(|a| arc_distance(p[0], p[1], 40.0, *a, 60.0)).fold(f64::MAX, f64::min);
        assert!(d <= 3.0 + 1e-6, "outside every slot minus the tool radius: {p:?}");
    }
    assert!(close(min_of(pts.iter().map(|p| p[2])), -4.0, 1e-9));
    for a0 in starts {
        for (end, sign) in [(a0 + 60.0, 1.0), (a0, -1.0)] {
            // Reach along the circle's tangent beyond the end, at the end's middle.
            let (s, c) = f64::to_radians(end).sin_cos();
            let reach = pts
                .iter()
                .filter(|p| (p[0] - 40.0 * c).hypot(p[1] - 40.0 * s) < 8.0)
                .map(|p| sign * (-(p[0] - 40.0 * c) * s + (p[1] - 40.0 * s) * c))
                .fold(f64::MIN, f64::max);
            // The apex of the end half circle lies between two IPO samples: within 1e-4.
            assert!(close(reach, 3.0, 1e-4), "slot from {a0}: the end at {end}° reached {reach}");
            assert!(
                pts.iter()
                    .any(|p| close(p[0], 40.0 * c, 1e-6) && close(p[1], 40.0 * s, 1e-6) && close(p[2], -4.0, 1e-9)),
                "the middle of the end at {end}° at depth"
            );
        }
        // Roughing arcs leave FAL: some arc at 40 + 2.5 and 40 - 2.5 in the slot's middle.
        let mid = (a0 + 30.0f64).to_radians();
        for r in [42.5, 37.5, 43.0, 37.0] {
            assert!(
                pts.iter().any(|p| close(p[0].hypot(p[1]), r, 1e-6) && (p[1].atan2(p[0]) - mid).sin().abs() < 0.05),
                "arc at R{r} in the slot from {a0}"
            );
        }
    }
}

#[test]
fn slot2_alarms_for_overlapping_slots() {
    // 4 slots of 80° (plus the ends) on a full circle overlap: 61104 at the calling line.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nSLOT2(10,0,2,-4,,4,80,16,0,0,40,0,0,100,500,2,3,0.5,0)\nM30");
    assert_eq!(alarms(&t), vec![(61104, Some(3))]);
    // A circle of radius 0: no division by it, the same alarm.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nSLOT2(10,0,2,-4,,1,80,16,0,0,0,0,0,100,500,2,3,0.5,0)\nM30");
    assert_eq!(alarms(&t), vec![(61104, Some(3))]);
}

/// The samples of the first descent from `from` (exclusive) to `to`: from the first sample
/// below `from` up to and including the first one at `to`.
fn descent(pts: &[[f64; 3]], from: f64, to: f64) -> Vec<[f64; 3]> {
    let start = pts.iter().position(|p| p[2] < from - 1e-9).unwrap();
    let end = start + pts[start..].iter().position(|p| close(p[2], to, 1e-9)).unwrap();
    pts[start..=end].to_vec()
}

/// The angle (degrees) turned counter-clockwise round the origin along `pts`, unwrapped.
fn unwrapped(pts: &[[f64; 3]]) -> Vec<f64> {
    let mut out = vec![pts[0][1].atan2(pts[0][0]).to_degrees()];
    for w in pts.windows(2) {
        let d = (w[1][1].atan2(w[1][0]) - w[0][1].atan2(w[0][0])).to_degrees();
        out.push(out.last().unwrap() + (d + 180.0).rem_euclid(360.0) - 180.0);
    }
    out
}

#[test]
fn pocket4_helical_insertion_descends_on_a_helix_of_rad1_and_dp1() {
    // R25 pocket at (10, 10), depth -6 in MID 3 levels (-3, -6), VARI 11 (roughing, helical
    // insertion), climb (G3: counter-clockwise), _RAD1 4, _DP1 2, SDIS 2. First level: from
    // RFP + SDIS = 2 round the centre at radius 4, Z = 2 - 2 * turns, 5 / 2 = 2.5 turns down to
    // -3, then one full circle at -3. Second level: from -3, 1.5 turns down to -6.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET4(10,0,2,-6,25,10,10,3,0.5,0,500,150,0,11,8,0,0,4,2)\nM30",
    );
    let pts = local(&t, (10.0, 10.0), 0.0, 2.0 + 2e-9);
    for (top, bottom, turns) in [(2.0, -3.0, 2.5), (-3.0, -6.0, 1.5)] {
        let helix = descent(&pts, top, bottom);
        assert!(helix.len() > 50);
        let w = unwrapped(&helix);
        for (p, a) in helix.iter().zip(&w) {
            assert!(close(p[0].hypot(p[1]), 4.0, 1e-6), "radius _RAD1: {p:?}");
            // Each helix starts at (_RAD1, 0): angle 0.
            let turned = a / 360.0;
            assert!(close(p[2], top - 2.0 * turned, 1e-6), "Z per turn _DP1 2: {p:?} after {turned} turns");
        }
        let total = w.last().unwrap() / 360.0;
        assert!(close(total, turns, 1e-6), "{total} turns from {top} to {bottom}");
    }
    // The full circle at -3 after the helix: the samples at -3 and radius 4 turn a whole turn.
    let at = pts.iter().position(|p| close(p[2], -3.0, 1e-9)).unwrap();
    let ring: Vec<_> = pts[at..].iter().take_while(|p| close(p[0].hypot(p[1]), 4.0, 1e-6)).copied().collect();
    let w = unwrapped(&ring);
    assert!(close(w.last().unwrap() - w[0], 360.0, 0.5), "one circle at depth");
    assert!(close(min_of(pts.iter().map(|p| p[2])), -6.0, 1e-9));
    assert!(pts.iter().all(|p| p[0].hypot(p[1]) <= 19.5 + 1e-6), "still inside the pocket");
}

#[test]
fn pocket3_oscillating_insertion_stays_on_the_axis_within_the_angle() {
    // 60 x 40 pocket at (50, 30), depth -4 in one level, VARI 21 (roughing, oscillating), _RAD1
    // 5°: along the pocket's length between u = ±(30 - 5) = ±25, from Z 2, at most tan 5° =
    // 0.08749 steep: 25 * 0.08749 = 2.187 down to u 25 (Z -0.187), then the 3.813 left to -4
    // need 3.813 / 0.08749 = 43.58 back: the bottom -4 at u 25 - 43.58 = -18.58.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET3(10,0,2,-4,60,40,0,50,30,0,0,0,0,500,150,0,21,6,0,0,0,5,0)\nM30",
    );
    let pts = local(&t, (50.0, 30.0), 0.0, 2.0 + 2e-9);
    let ins = descent(&pts, 2.0, -4.0);
    assert!(ins.len() > 50);
    let tan = 5f64.to_radians().tan();
    for p in &ins {
        assert!(p[1].abs() < 1e-9 && p[0].abs() <= 25.0 + 1e-6, "on the central axis: {p:?}");
    }
    for w in ins.windows(2) {
        let (du, dz) = ((w[1][0] - w[0][0]).abs(), (w[1][2] - w[0][2]).abs());
        assert!(dz <= du * tan + 1e-9, "steeper than 5°: {w:?}");
    }
    assert!(ins.iter().any(|p| close(p[0], 25.0, 1e-6)), "turns at the end of the axis");
    let last = ins.last().unwrap();
    assert!(close(last[0], 25.0 - (6.0 - 25.0 * tan) / tan, 1e-6) && close(last[0], -18.58, 0.01), "{last:?}");
}

#[test]
fn helical_insertion_alarms_for_a_helix_wider_than_the_pocket() {
    // _RAD1 20 in a 60 x 40 pocket: the tool centre travels only 20 - 5 = 15 across.
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nPOCKET3(10,0,2,-4,60,40,0,0,0,0,0,0,0,500,150,0,11,6,0,0,0,20,2)\nM30");
    assert_eq!(alarms(&t), vec![(61108, Some(3))]);
}

#[test]
fn cycle77_in_g18_mills_round_the_y_axis() {
    // G18: abscissa Z, ordinate X, depth along Y. Ø20 spigot finished at (Z 0, X 0), depth -3
    // from RFP 0: the tool centre keeps 10 + 5 = 15 from the Y axis, at Y -3.
    let t = run_clean("G18 G90 T1 D1\nG0 X0 Y50 Z0\nCYCLE77(10,0,2,-3,,20,0,0,0,0,0,500,150,0,2)\nM30");
    let from = t.samples.iter().position(|p| p.b[1] >= 50.0).unwrap();
    let below: Vec<_> = t.samples[from..].iter().filter(|s| s.b[1] < -1e-9).collect();
    assert!(below.len() > 50);
    let r = |s: &&Sample| s.b[2].hypot(s.b[0]);
    assert!(close(below.iter().map(r).fold(f64::MAX, f64::min), 15.0, 1e-6));
    assert!(close(below.iter().map(|s| s.b[1]).fold(f64::MAX, f64::min), -3.0, 1e-9));
}

#[test]
fn spigot_cycles_give_the_caller_its_frame_and_g91_back() {
    // CYCLE76 shifts and turns its own frame; afterwards X10 Y10 is the caller's.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50\nCYCLE76(10,0,2,-2,,40,30,0,50,50,45,0,0,0,500,150,0,2)\nG0 X10 Y10\nM30",
    );
    assert_eq!(t.end(), [10.0, 10.0, 10.0]);
    // The caller's G91 survives the cycle's G90. CYCLE77 (finishing Ø40 at (10, 20), climb)
    // ends at its own (25, 25 + SDIS 2) at RTP 10. With SD42440 = 1 (the default: offsets are
    // traversed by the first incremental move after a frame change) G91 X5 Y5 adds to that
    // programmed position in the caller's frame: (30, 32); under G90 it would end at (5, 5).
    let t =
        run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50\nG91\nCYCLE77(10,0,2,-6,,40,10,20,0,0,0,500,150,0,2)\nG0 X5 Y5\nM30");
    let e = t.end();
    assert!(close(e[0], 30.0, 1e-9) && close(e[1], 32.0, 1e-9) && close(e[2], 10.0, 1e-9), "{e:?}");
}

#[test]
fn cycle90_internal_thread_climbs_a_helix_of_the_pitch() {
    // M20 x 2.5 internal (core 17.294), 10 deep from RFP 0, G3 (right-hand), at (30, 30), tool
    // R5: the helix radius 10 - 5 = 5, from -10 up to 0 in 10 / 2.5 = 4 turns, Z = -10 + 2.5 per
    // turn; in on a half circle from the centre and out again to it.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE90(10,0,2,-10,,20,17.294,2.5,300,3,0,30,30)\nM30");
    // The samples up to RFP 0 included (the helix ends there).
    let pts = local(&t, (30.0, 30.0), 0.0, 1e-3);
    assert!(close(min_of(pts.iter().map(|p| p[2])), -10.0, 1e-9));
    assert!(pts.iter().all(|p| p[0].hypot(p[1]) <= 5.0 + 1e-6), "never beyond the major diameter");
    // The helix: from the first sample above -10 after the bottom, while on radius 5.
    let bottom = pts.iter().position(|p| close(p[2], -10.0, 1e-9)).unwrap();
    let start = bottom + pts[bottom..].iter().position(|p| p[2] > -10.0 + 1e-9).unwrap();
    let helix: Vec<_> = pts[start..].iter().take_while(|p| close(p[0].hypot(p[1]), 5.0, 1e-6)).copied().collect();
    assert!(helix.len() > 100);
    let w = unwrapped(&helix);
    for (p, a) in helix.iter().zip(&w) {
        assert!(close(p[2], -10.0 + 2.5 * a / 360.0, 1e-6), "pitch 2.5: {p:?}");
    }
    assert!(close(w.last().unwrap() / 360.0, 4.0, 1e-6), "4 turns counter-clockwise");
    assert!(close(helix.last().unwrap()[2], 0.0, 1e-9));
    let e = t.end();
    assert!(close(e[0], 30.0, 1e-9) && close(e[1], 30.0, 1e-9) && close(e[2], 10.0, 1e-9), "{e:?}");
}

#[test]
fn cycle90_external_thread_stays_outside_the_core() {
    // M30 x 2 external (core 27.546), 6 deep, G2 (left-hand bottom up), at (0, 0): the helix
    // radius 13.773 + 5 = 18.773, 3 turns clockwise; no point nearer the axis.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE90(10,0,2,-6,,30,27.546,2,300,2,1,0,0)\nM30");
    let pts = local(&t, (0.0, 0.0), 0.0, 1e-3);
    let r = |p: &[f64; 3]| p[0].hypot(p[1]);
    assert!(close(min_of(pts.iter().map(r)), 18.773, 1e-6));
    let helix: Vec<_> = pts.iter().filter(|p| close(r(p), 18.773, 1e-6) && p[2] > -6.0 + 1e-9).copied().collect();
    let w = unwrapped(&helix);
    for (p, a) in helix.iter().zip(&w) {
        assert!(close(p[2], -6.0 - 2.0 * a / 360.0, 1e-6), "pitch 2, clockwise: {p:?}");
    }
    assert!(close(-w.last().unwrap() / 360.0, 3.0, 1e-6));
}

#[test]
fn pocket3_helical_insertion_conventional_turns_clockwise() {
    // 60 x 40 pocket at (0, 0), depth -3 in one level, VARI 11 (roughing, helical), CDIR 1
    // (conventional: G2), _RAD1 6, _DP1 2.5, SDIS 2: from Z 2 clockwise at radius 6, 5 / 2.5 =
    // 2 turns down to -3 (the tool centre travels 25 x 15 across: 6 fits).
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET3(10,0,2,-3,60,40,0,0,0,0,0,0,0,500,150,1,11,6,0,0,0,6,2.5)\nM30",
    );
    let pts = local(&t, (0.0, 0.0), 0.0, 2.0 + 2e-9);
    let helix = descent(&pts, 2.0, -3.0);
    let w = unwrapped(&helix);
    for (p, a) in helix.iter().zip(&w) {
        assert!(close(p[0].hypot(p[1]), 6.0, 1e-6), "{p:?}");
        assert!(close(p[2], 2.0 + 2.5 * a / 360.0, 1e-6), "clockwise, 2.5 per turn: {p:?}");
    }
    assert!(close(w.last().unwrap() / 360.0, -2.0, 1e-6));
}

#[test]
fn cycle61_in_g18_faces_the_zx_plane() {
    // G18: abscissa Z, ordinate X, depth along Y. Face Z 0..40 x X 0..30 from Y 0 to -1 in one
    // level (DZ 0), width 8, meander along Z: every point within 5 of the path at Y -1.
    let t = run_clean("G18 G90 T1 D1\nG0 X0 Y50 Z0\nCYCLE61(10,0,1,-1,0,0,40,30,0,8,0,1000,31,0)\nM30");
    let from = t.samples.iter().position(|p| p.b[1] >= 50.0).unwrap();
    let pts: Vec<[f64; 3]> =
        t.samples[from..].iter().filter(|s| s.b[1] < -1e-9).map(|s| [s.b[2], s.b[0], s.b[1]]).collect();
    assert!(close(min_of(pts.iter().map(|p| p[2])), -1.0, 1e-9));
    assert!(uncovered(&pts, -1.0, (0.0, 40.0, 0.0, 30.0), 2.0, 0.0).is_empty());
}

/// The longest run of consecutive samples for which `pred` holds.
fn longest_run(pts: &[[f64; 3]], pred: impl Fn(&[f64; 3]) -> bool) -> Vec<[f64; 3]> {
    let mut best: &[[f64; 3]] = &[];
    let mut i = 0;
    while i < pts.len() {
        let n = pts[i..].iter().take_while(|p| pred(p)).count();
        if n > best.len() {
            best = &pts[i..i + n];
        }
        i += n.max(1);
    }
    best.to_vec()
}

#[test]
fn slot2_finishing_a_long_slot_clockwise() {
    // One slot 12 wide from -10° through 200° on R30 around (0, 0), finishing only (VARI 2),
    // CDIR 2 (G2), depth -2 in one level: the tool centre within 6 - 5 = 1 of the middle arc;
    // the arcs of more than 180° run clockwise round the slot: the outer arc (R31) backwards.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nSLOT2(10,0,2,-2,,1,200,12,0,0,30,-10,0,100,500,0,2,0.5,2)\nM30",
    );
    let pts = local(&t, (0.0, 0.0), 0.0, 0.0);
    for p in &pts {
        assert!(arc_distance(p[0], p[1], 30.0, -10.0, 200.0) <= 1.0 + 1e-6, "{p:?}");
    }
    let outer = longest_run(&pts, |p| close(p[0].hypot(p[1]), 31.0, 1e-6));
    let w = unwrapped(&outer);
    assert!(
        close(w[0] - w.last().unwrap(), 200.0, 0.5),
        "the outer arc backwards through 200°: {}",
        w[0] - w.last().unwrap()
    );
    let inner = longest_run(&pts, |p| close(p[0].hypot(p[1]), 29.0, 1e-6));
    let w = unwrapped(&inner);
    assert!(close(w.last().unwrap() - w[0], 200.0, 0.5), "the inner arc forwards");
    assert!(close(min_of(pts.iter().map(|p| p[2])), -2.0, 1e-9));
}

#[test]
fn cycle61_one_way_along_the_abscissa_stops_short_of_a_wall_at_x1() {
    // Roughing (VARI 11: along the abscissa, one way) of 0..80 x 0..40 from Z0 0 to -2 + UZ 0
    // in one level, wall at X1 (LIM 10): lines from -5 - 1 = -6 to 80 - 5 = 75, all in +X. The
    // round tool leaves cusps at the wall between the lines: the face is covered up to X 75.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nCYCLE61(10,0,1,-2,0,0,80,40,0,8,0,1000,11,10)\nM30");
    let pts = local(&t, (0.0, 0.0), 0.0, 0.0);
    let at: Vec<_> = pts.iter().filter(|p| close(p[2], -2.0, 1e-9)).collect();
    assert!(close(-min_of(at.iter().map(|p| -p[0])), 75.0, 1e-6), "the wall at X80 keeps the tool radius");
    assert!(close(min_of(at.iter().map(|p| p[0])), -6.0, 1e-6));
    for w in at.windows(2) {
        assert!(w[1][0] >= w[0][0] - 1e-9 || !close(w[0][1], w[1][1], 1e-9), "one way: {w:?}");
    }
    assert!(uncovered(&pts, -2.0, (0.0, 74.0, 0.0, 40.0), 2.0, 1e-6).is_empty());
}
