//! The milling cycles (POCKET3) checked on every sampled point of their path: inside the pocket
//! minus the tool radius (and the finishing allowance when roughing), the floor at depth, and
//! the allowance roughing leaves. The pocket geometry is worked out by hand from the documented
//! parameters (_LENG, _WID, _CRAD, _PA, _PO, _STA, _DP, _MID, _FAL, _FALD). The tool is T1 D1 of
//! the 3-axis mill: radius 5.

use crate::cycles_support;
use cycles_support::*;

const Z: usize = 2;

/// The samples below `rfp`, in the pocket's own coordinates (centre `c`, turned by `sta`°).
fn local(t: &Trace, c: (f64, f64), sta: f64, rfp: f64) -> Vec<[f64; 3]> {
    let (s, co) = sta.to_radians().sin_cos();
    // From the first arrival at the start height Z50 on (before it the tool's length offset
    // puts the tip below the part).
    let from = t.samples.iter().position(|p| p.b[Z] >= 50.0).unwrap();
    t.samples[from..]
        .iter()
        .filter(|p| p.b[Z] < rfp - 1e-9)
        .map(|p| {
            let (dx, dy) = (p.b[0] - c.0, p.b[1] - c.1);
            [dx * co + dy * s, -dx * s + dy * co, p.b[Z]]
        })
        .collect()
}

/// Whether (u, v) lies in the rectangle of half sizes hx, hy with corner radius rc (+ tol).
fn inside(u: f64, v: f64, hx: f64, hy: f64, rc: f64, tol: f64) -> bool {
    let (u, v) = (u.abs(), v.abs());
    if u > hx + tol || v > hy + tol {
        return false;
    }
    if u > hx - rc && v > hy - rc {
        return ((u - hx + rc).powi(2) + (v - hy + rc).powi(2)).sqrt() <= rc + tol;
    }
    true
}

#[test]
fn pocket3_roughing_stays_inside_the_pocket_minus_radius_and_allowance() {
    // 60 x 40 pocket, corner radius 8, centre (50, 30), depth -10 from RFP 0, MID 4, FAL 1,
    // FALD 0.5. Tool centre: |u| <= 30 - 5 - 1 = 24, |v| <= 20 - 6 = 14, corner radius 8 - 6 = 2.
    // Depth levels: 9.5 mm in ceil(9.5 / 4) = 3 equal infeeds: -3.1667, -6.3333, -9.5.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET3(10,0,2,-10,60,40,8,50,30,0,4,1,0.5,500,150,0,1,6)\nM30",
    );
    let pts = local(&t, (50.0, 30.0), 0.0, 0.0);
    assert!(pts.len() > 100);
    for p in &pts {
        assert!(inside(p[0], p[1], 24.0, 14.0, 2.0, 1e-6), "outside the roughing region: {p:?}");
    }
    let floor = pts.iter().map(|p| p[2]).fold(f64::MAX, f64::min);
    assert!(close(floor, -9.5, 1e-9), "floor {floor}: FALD 0.5 left");
    let reach_u = pts.iter().map(|p| p[0].abs()).fold(0.0, f64::max);
    let reach_v = pts.iter().map(|p| p[1].abs()).fold(0.0, f64::max);
    assert!(
        close(reach_u, 24.0, 1e-6) && close(reach_v, 14.0, 1e-6),
        "the wall pass leaves exactly FAL: {reach_u} {reach_v}"
    );
    // The heights at which the tool moves in the plane below RFP.
    let mut levels: Vec<f64> = pts
        .windows(2)
        .filter(|w| w[0][2] == w[1][2] && (w[0][0] != w[1][0] || w[0][1] != w[1][1]))
        .map(|w| w[0][2])
        .collect();
    levels.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    for (got, want) in levels.iter().zip([-9.5 / 3.0, -19.0 / 3.0, -9.5]) {
        assert!(close(*got, want, 1e-6), "{levels:?}");
    }
    assert_eq!(levels.len(), 3, "{levels:?}");
    // Lines of the meander no more than _MIDA = 6 apart: every v in [-14, 14] lies within 3 of
    // a sample on each level's floor (checked on the last level).
    let last: Vec<_> = pts.iter().filter(|p| close(p[2], -9.5, 1e-9)).collect();
    for k in 0..=28 {
        let v = -14.0 + k as f64;
        assert!(last.iter().any(|p| (p[1] - v).abs() <= 3.0 + 1e-6 && p[0].abs() < 1.0), "gap at v {v}");
    }
    assert!(close(t.end()[Z], 10.0, 1e-9));
}

#[test]
fn pocket3_finishing_reaches_the_walls_and_floor_of_a_turned_pocket() {
    // Turned by 30°, centre (20, -10), 50 x 30, corner radius 6, depth -4 in one infeed (MID 0),
    // finishing (VARI 2) with FALD 0.2: the floor at -4 (meander), walls at 25 - 5 = 20 and
    // 15 - 5 = 10, corner radius 6 - 5 = 1; climb milling (CDIR 0).
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET3(10,0,2,-4,50,30,6,20,-10,30,0,0.5,0.2,500,150,0,2)\nM30",
    );
    let pts = local(&t, (20.0, -10.0), 30.0, 0.0);
    for p in &pts {
        assert!(inside(p[0], p[1], 20.0, 10.0, 1.0, 1e-6), "outside the pocket minus radius: {p:?}");
    }
    let floor = pts.iter().map(|p| p[2]).fold(f64::MAX, f64::min);
    assert!(close(floor, -4.0, 1e-9), "{floor}");
    assert!(pts.iter().any(|p| close(p[0], 20.0, 1e-6) && p[1].abs() < 8.0), "right wall");
    assert!(pts.iter().any(|p| close(p[1], -10.0, 1e-6) && p[0].abs() < 18.0), "near wall");
}

#[test]
fn pocket3_in_g18_mills_in_the_zx_plane() {
    // G18: abscissa Z, ordinate X, depth along Y. 30 x 20 pocket at (Z 0, X 0), depth -3.
    let t = run_clean("G18 G90 T1 D1\nG0 X0 Y50 Z0\nPOCKET3(10,0,2,-3,30,20,0,0,0,0,0,0,0,500,150,0,1,8)\nM30");
    let from = t.samples.iter().position(|p| p.b[1] >= 50.0).unwrap();
    let below: Vec<_> = t.samples[from..].iter().filter(|s| s.b[1] < -1e-9).collect();
    assert!(!below.is_empty());
    for s in &below {
        assert!(s.b[2].abs() <= 10.0 + 1e-6 && s.b[0].abs() <= 5.0 + 1e-6, "{s:?}");
    }
    assert!(close(below.iter().map(|s| s.b[1]).fold(f64::MAX, f64::min), -3.0, 1e-9));
}

#[test]
fn pocket3_alarms_for_a_tool_too_large_or_no_tool() {
    let t = run("G17 G90 T1 D1\nG0 X0 Y0 Z50\nPOCKET3(10,0,2,-4,10,30,0,0,0,0,0,1,0,500,150,0,1)\nM30");
    assert_eq!(t.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), vec![(61105, Some(3))]);
    let t = run("G17 G90\nG0 X0 Y0 Z50\nPOCKET3(10,0,2,-4,40,30,0,0,0,0,0,1,0,500,150,0,1)\nM30");
    assert_eq!(t.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), vec![(61000, Some(3))]);
}

#[test]
fn pocket3_gives_the_caller_its_frame_back() {
    // The cycle shifts and turns its own frame; afterwards X10 is X10 of the caller.
    let t = run_clean(
        "G17 G90 T1 D1\nG0 X0 Y0 Z50\nPOCKET3(10,0,2,-2,40,30,0,50,50,45,0,0,0,500,150,0,1)\nG0 X10 Y10\nM30",
    );
    assert_eq!(t.end(), [10.0, 10.0, 10.0]);
}

#[test]
fn pocket4_roughs_in_rings_inside_the_circle_minus_radius_and_allowance() {
    // R 25 pocket at (10, 10), depth -6 in MID 3 steps (FALD 0: -3, -6), FAL 0.5, MIDA 8:
    // tool centre within 25 - 5 - 0.5 = 19.5; ceil(19.5 / 8) = 3 rings at 6.5, 13, 19.5.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET4(10,0,2,-6,25,10,10,3,0.5,0,500,150,0,1,8)\nM30");
    let pts = local(&t, (10.0, 10.0), 0.0, 0.0);
    let radius = |p: &[f64; 3]| p[0].hypot(p[1]);
    assert!(pts.iter().all(|p| radius(p) <= 19.5 + 1e-6), "inside the pocket minus radius and FAL");
    assert!(close(pts.iter().map(radius).fold(0.0, f64::max), 19.5, 1e-6));
    assert!(close(pts.iter().map(|p| p[2]).fold(f64::MAX, f64::min), -6.0, 1e-9));
    for ring in [6.5, 13.0] {
        assert!(pts.iter().any(|p| close(radius(p), ring, 1e-6) && p[1].abs() > 1.0), "ring {ring}");
    }
}

#[test]
fn pocket4_finishing_mills_the_wall_at_the_tool_radius() {
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nPOCKET4(10,0,2,-6,25,10,10,0,0.5,0,500,150,1,2)\nM30");
    let pts = local(&t, (10.0, 10.0), 0.0, 0.0);
    let radius = |p: &[f64; 3]| p[0].hypot(p[1]);
    assert!(pts.iter().all(|p| radius(p) <= 20.0 + 1e-6));
    assert!(pts.iter().filter(|p| close(radius(p), 20.0, 1e-6)).count() > 50, "the wall at 25 - 5");
}

#[test]
fn longhole_mills_radial_holes_in_a_pendulum_infeed() {
    // 3 holes 20 long on R 40 around (0, 0), first at 90°, 120° apart; tool R5: the tool centre
    // runs from radius 40 - (10 - 5) = 35 to 45 along each radius. Depth -6 in MID 2.5 steps:
    // ceil(6 / 2.5) = 3 infeeds of 2: -2 at the inner end, -4 at the outer, -6 at the inner.
    let t = run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nLONGHOLE(5,0,1,-6,,3,20,0,0,40,90,120,100,400,2.5)\nM30");
    let from = t.samples.iter().position(|p| p.b[Z] >= 50.0).unwrap();
    let cut: Vec<_> = t.samples[from..].iter().filter(|s| s.b[Z] < -1e-9).collect();
    for s in &cut {
        let (r, w) = (s.b[0].hypot(s.b[1]), s.b[1].atan2(s.b[0]).to_degrees().rem_euclid(360.0));
        assert!((35.0 - 1e-6..=45.0 + 1e-6).contains(&r), "{s:?}");
        assert!([90.0, 210.0, 330.0].iter().any(|a| close(w, *a, 1e-6)), "on a radius: {w} {s:?}");
    }
    for a in [90.0f64, 210.0, 330.0] {
        let (sn, cs) = a.to_radians().sin_cos();
        let at = |r: f64, z: f64| {
            cut.iter().any(|s| close(s.b[0], r * cs, 1e-6) && close(s.b[1], r * sn, 1e-6) && close(s.b[Z], z, 1e-6))
        };
        assert!(
            at(35.0, -2.0) && at(45.0, -2.0) && at(45.0, -4.0) && at(35.0, -4.0) && at(35.0, -6.0) && at(45.0, -6.0),
            "hole at {a}°"
        );
    }
    assert!(close(cut.iter().map(|s| s.b[Z]).fold(f64::MAX, f64::min), -6.0, 1e-9));
}

#[test]
fn slot1_rough_and_finish_stay_inside_each_slot() {
    // 2 slots 30 x 14 on R 30 around (10, 0) at 0° and 180°: each a pocket with corner radius 7.
    // Finishing reaches the walls: tool centre |u| <= 15 - 5 = 10, |v| <= 7 - 5 = 2, corners 2.
    let t =
        run_clean("G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\nSLOT1(5,0,1,-4,,2,30,14,10,0,30,0,0,100,400,2,0,0.5,0)\nM30");
    for (cx, sta) in [(40.0, 0.0), (-20.0, 180.0)] {
        let pts: Vec<_> =
            local(&t, (cx, 0.0), sta, 0.0).into_iter().filter(|p| p[0].abs() < 20.0 && p[1].abs() < 20.0).collect();
        assert!(pts.len() > 50, "slot at {cx}");
        for p in &pts {
            assert!(inside(p[0], p[1], 10.0, 2.0, 2.0, 1e-6), "outside the slot at {cx}: {p:?}");
        }
        assert!(pts.iter().any(|p| close(p[0].abs(), 10.0, 1e-6)), "finished to the end of the slot at {cx}");
        assert!(close(pts.iter().map(|p| p[2]).fold(f64::MAX, f64::min), -4.0, 1e-9));
    }
}
