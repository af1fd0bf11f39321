//! The thread milling cycle CYCLE70 (NCTwin's parameter list: _RTP, _RFP, _SDIS, _DP, _PA, _PO,
//! _DIATH, _PIT, _TDEP, _STA, _NT, _MID, _FAL, _FFR, _VARI) on the 3-axis mill (T1 D1: radius
//! 5), checked on every sampled IPO point: the helix radius of each cut, its pitch and sense,
//! the number of turns and a comb's bands, worked out by hand in each test.

use crate::cycles_support;
use cycles_support::*;

const START: &str = "G17 G90 T1 D1\nG0 X0 Y0 Z50 M3 S2000\n";

/// The BCS samples (the cycle works in its own frame) relative to the centre `c`, from the
/// tool's arrival at Z50 on, below `below`.
fn local(t: &Trace, c: (f64, f64), below: f64) -> Vec<[f64; 3]> {
    let from = t.samples.iter().position(|s| s.b[2] >= 50.0).unwrap();
    t.samples[from..].iter().filter(|s| s.b[2] < below).map(|s| [s.b[0] - c.0, s.b[1] - c.1, s.b[2]]).collect()
}

/// The runs of consecutive samples on the circle of radius `r` that move in Z (the helices).
fn helices(pts: &[[f64; 3]], r: f64) -> Vec<Vec<[f64; 3]>> {
    let mut out: Vec<Vec<[f64; 3]>> = Vec::new();
    let mut open = false;
    for p in pts {
        let on = close(p[0].hypot(p[1]), r, 1e-6);
        match out.last_mut() {
            Some(h) if on && open => h.push(*p),
            _ if on => out.push(vec![*p]),
            _ => {}
        }
        open = on;
    }
    out.retain(|h| h.len() > 20 && (h[0][2] - h.last().unwrap()[2]).abs() > 1e-3);
    out
}

/// The angle (degrees) along the samples, unwrapped from the first.
fn unwrapped(pts: &[[f64; 3]]) -> Vec<f64> {
    let mut out = vec![0.0];
    for w in pts.windows(2) {
        let d = (w[1][1].atan2(w[1][0]) - w[0][1].atan2(w[0][0])).to_degrees();
        out.push(out.last().unwrap() + (d + 180.0).rem_euclid(360.0) - 180.0);
    }
    out
}

/// Checks a helix: Z = `z0` + `lead` per turn of the (signed) angle, over `turns` turns.
fn check_helix(h: &[[f64; 3]], z0: f64, lead_per_ccw_turn: f64, turns: f64) {
    let w = unwrapped(h);
    for (p, a) in h.iter().zip(&w) {
        assert!(close(p[2], z0 + lead_per_ccw_turn * a / 360.0, 1e-6), "helix at {p:?}, angle {a}");
    }
    assert!(close(w.last().unwrap().abs() / 360.0, turns, 1e-6), "turns {}", w.last().unwrap() / 360.0);
}

#[test]
fn cycle70_internal_right_hand_bottom_up_roughs_in_radial_cuts_and_finishes() {
    // M20 x 2.5 internal at (30, 30), H1 1.5 (core Ø17), 10 long from RFP 0 down to -10, bottom
    // up (thousands 1), right-hand, roughing and finishing (units 3), U 0.1, XY infeed at most
    // 0.8: 1.4 to rough in 2 cuts of 0.7. The helix radius (tool R5): 8.5 + d - 5: 4.2, 4.9 and
    // finishing 5.0 (the tip at the major radius 10). Each: 4 turns counter-clockwise (G3)
    // from -10 up to 0, Z = -10 + 2.5 per turn.
    let t = run_clean(&format!("{START}CYCLE70(50,0,2,-10,30,30,20,2.5,1.5,0,1,0.8,0.1,400,1003)\nM30"));
    let pts = local(&t, (30.0, 30.0), 1e-3);
    for r in [4.2, 4.9, 5.0] {
        let h = helices(&pts, r);
        assert_eq!(h.len(), 1, "one helix of radius {r}");
        check_helix(&h[0], -10.0, 2.5, 4.0);
        assert!(close(h[0][0][2], -10.0, 1e-9) && close(h[0].last().unwrap()[2], 0.0, 1e-9));
    }
    let outer = pts.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
    assert!(close(outer, 5.0, 1e-6), "never beyond the major diameter: {outer}");
    let e = t.samples.last().unwrap().b;
    assert!(close(e[0], 30.0, 1e-9) && close(e[1], 30.0, 1e-9) && close(e[2], 50.0, 1e-9), "{e:?}");
}

#[test]
fn cycle70_external_left_hand_top_down_finishes_outside_the_root() {
    // M30 x 2 external at (0, 0), H1 1.2 (root Ø27.6), 6 long from RFP 0 to -6, top down
    // (thousands 0), left-hand (hundreds 1), external (tens 1), finishing (units 2): VARI 112.
    // A left-hand thread top down turns counter-clockwise (G3) with Z falling 2 per turn: 3
    // turns at radius 15 - 1.2 + 5 = 18.8. The tool never comes nearer the axis than that.
    let t = run_clean(&format!("{START}CYCLE70(50,0,2,-6,0,0,30,2,1.2,0,1,0,0,400,112)\nM30"));
    let pts = local(&t, (0.0, 0.0), 1e-3);
    let h = helices(&pts, 18.8);
    assert_eq!(h.len(), 1);
    check_helix(&h[0], 0.0, -2.0, 3.0);
    assert!(unwrapped(&h[0]).last().unwrap() > &0.0, "counter-clockwise");
    let inner = pts.iter().map(|p| p[0].hypot(p[1])).fold(f64::MAX, f64::min);
    assert!(close(inner, 18.8, 1e-6), "never inside the root plus the tool radius: {inner}");
}

#[test]
fn cycle70_comb_mills_one_turn_per_band_of_its_teeth() {
    // M16 x 2 internal, H1 1 (core Ø14), a comb of 3 teeth, finishing, bottom up, right-hand
    // (VARI 1002), 10 long: bands of 3 x 2 = 6: ceil(10 / 6) = 2, the lowest tooth from -10
    // and from -4, one counter-clockwise turn each rising 2: -10 to -8 and -4 to -2. Radius
    // 7 + 1 - 5 = 3. Start angle 90: each turn starts and ends on +Y.
    let t = run_clean(&format!("{START}CYCLE70(50,0,2,-10,0,0,16,2,1,90,3,0,0,400,1002)\nM30"));
    let pts = local(&t, (0.0, 0.0), 1e-3);
    let h = helices(&pts, 3.0);
    assert_eq!(h.len(), 2, "two bands");
    for (band, z0) in h.iter().zip([-10.0, -4.0]) {
        check_helix(band, z0, 2.0, 1.0);
        assert!(close(band[0][0], 0.0, 1e-6) && close(band[0][1], 3.0, 1e-6), "start on +Y: {:?}", band[0]);
    }
}

#[test]
fn cycle70_bad_parameters_raise_the_cycle_alarms_at_the_calling_line() {
    for (call, number) in [
        ("CYCLE70(50,0,2,-10,0,0,20,0,1.5,0,1,0,0.1,400,1003)", 61001),
        ("CYCLE70(50,0,2,-10,0,0,20,2.5,1.5,0,1,0,0.1,0,1003)", 61003),
        ("CYCLE70(50,0,2,-10,0,0,20,2.5,1.5,0,1,0,0.1,400,1004)", 61002),
        ("CYCLE70(50,0,2,-10,0,0,20,2.5,1.5,0,1,0,1.5,400,1003)", 61010),
        ("CYCLE70(50,0,2,-10,0,0,12,1.75,1,0,1,0,0.1,400,1003)", 61105),
        ("CYCLE70(50,0,2,5,0,0,20,2.5,1.5,0,1,0,0.1,400,1003)", 61101),
    ] {
        let t = run(&format!("{START}{call}\nM30"));
        let got: Vec<_> = t.alarms.iter().map(|a| (a.number, a.line)).collect();
        assert_eq!(got, vec![(number, Some(3))], "{call}");
    }
}
