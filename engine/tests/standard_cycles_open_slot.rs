//! CYCLE899 (open slot, NCTwin's parameter list) on the 3-axis mill with T1 D1, an end mill of
//! radius 5, checked on every sampled point against the path worked out by hand.
//!
//! The slot: length 40 along X (STA 0), width 16, centre (50, 30), from the top face Z0 to Z-6.
//! The tool centre may come at most 16/2 - 5 = 3 off the slot's axis Y30 (less _FAL when
//! roughing). Its infeeds run in the air at X 50 - 20 - 5 - SDIS 2 = 23 and it leaves the slot
//! behind its other end at X 77; the vortex circles about those two points reach 3 further
//! (X 20 and X 80), in the air.

use crate::cycles_support;
use cycles_support::*;

const Z: usize = 2;

/// RTP 10, RFP 0, SDIS 2, DP -6, LENG 40, WID 16, centre (50, 30), STA 0, then `rest`.
fn run_slot(rest: &str) -> Trace {
    run_clean(&format!("G17 G90 G94 T1 D1 S4000 M3\nG0 X0 Y0 Z20\nCYCLE899(10,0,2,-6,40,16,50,30,0,{rest}\nM30"))
}

/// The samples from the arrival at Z20 on, below the top face.
fn below(t: &Trace) -> Vec<[f64; 3]> {
    let from = t.samples.iter().position(|p| p.b[Z] >= 20.0 - 1e-9).unwrap();
    t.samples[from..].iter().filter(|p| p.b[Z] < -1e-9).map(|p| p.b).collect()
}

#[test]
fn cycle899_roughs_by_vortex_circles_within_the_slot_in_two_infeeds() {
    // MID 3: 6 / 3 = 2 infeeds, Z-3 and Z-6; _MIDA 2: circles of radius 3 about X 23, 25, ..,
    // 77 on Y30 (slot axis), joined along Y27 (climb, G3: starting at the bottom of each).
    let t = run_slot("3,0,0,500,100,0,1,2,0,0,0)");
    let b = below(&t);
    assert!(!b.is_empty());
    let mut levels: Vec<f64> = Vec::new();
    for p in &b {
        let (u, v) = (p[0] - 50.0, p[1] - 30.0);
        assert!(v.abs() <= 3.0 + 1e-6 && (-30.0 - 1e-9..=30.0 + 1e-9).contains(&u), "{p:?} outside the slot");
        let on_level = close(p[Z], -3.0, 1e-9) || close(p[Z], -6.0, 1e-9);
        if !on_level {
            // The infeed in the air in front of the slot, the lift behind it.
            assert!((close(u, -27.0, 1e-9) || close(u, 27.0, 1e-9)) && close(v, -3.0, 1e-9), "{p:?}");
            continue;
        }
        if !levels.iter().any(|z| close(*z, p[Z], 1e-9)) {
            levels.push(p[Z]);
        }
        let on_circle = (0..28).any(|i| close((u - (-27.0 + 2.0 * i as f64)).hypot(v), 3.0, 1e-6));
        assert!(close(v, -3.0, 1e-6) || on_circle, "{p:?} off the vortex path");
    }
    assert_eq!(levels, vec![-3.0, -6.0]);
    // The walls are reached: the tool's edge at 3 + 5 = 8 off the axis inside the slot.
    assert!(b.iter().any(|p| close(p[1], 33.0, 1e-6) && (30.0..=70.0).contains(&p[0])));
    // The last circle about X77 ends at its bottom (77, 27); up to RTP.
    let end = t.end();
    assert!(close(end[0], 77.0, 1e-9) && close(end[1], 27.0, 1e-9) && close(end[Z], 10.0, 1e-9), "{end:?}");
}

#[test]
fn cycle899_roughing_keeps_the_wall_allowance_and_finishing_runs_along_both_walls() {
    // _FAL 0.5: circles of radius 2.5.
    let t = run_slot("3,0.5,0,500,100,0,1,2,0,0,0)");
    assert!(below(&t).iter().all(|p| (p[1] - 30.0).abs() <= 2.5 + 1e-6));
    assert!(below(&t).iter().any(|p| close((p[1] - 30.0).abs(), 2.5, 1e-6)));
    // Finishing, one infeed (MID 0) to Z-6: forwards along Y27 (climb: the wall on the right),
    // across behind the slot at X77, back along Y33, up at X23.
    let t = run_slot("0,0,0,500,100,0,2,0,0,0,0)");
    for p in below(&t) {
        let on_path = close(p[1], 27.0, 1e-9) || close(p[1], 33.0, 1e-9) || close(p[0], 77.0, 1e-9);
        assert!(on_path && (close(p[Z], -6.0, 1e-9) || close(p[0], 23.0, 1e-9)), "{p:?}");
    }
    let end = t.end();
    assert!(close(end[0], 23.0, 1e-9) && close(end[1], 33.0, 1e-9) && close(end[Z], 10.0, 1e-9), "{end:?}");
}

#[test]
fn cycle899_refuses_a_tool_too_wide_and_what_it_does_not_model() {
    let run_alarm = |call: &str| {
        let t = run(&format!("G17 G90 G94 T1 D1 S4000 M3\nG0 X0 Y0 Z20\n{call}\nM30"));
        t.alarms.first().map(|a| (a.number, a.line))
    };
    // Width 8 < the tool's diameter 10: 61105; plunge cutting (_VARI 11): 61002; _MIDA 12 >
    // the diameter: 61111.
    assert_eq!(run_alarm("CYCLE899(10,0,2,-6,40,8,50,30,0,3,0,0,500,100,0,1,2,0,0,0)"), Some((61105, Some(3))));
    assert_eq!(run_alarm("CYCLE899(10,0,2,-6,40,16,50,30,0,3,0,0,500,100,0,11,2,0,0,0)"), Some((61002, Some(3))));
    assert_eq!(run_alarm("CYCLE899(10,0,2,-6,40,16,50,30,0,3,0,0,500,100,0,1,12,0,0,0)"), Some((61111, Some(3))));
}
