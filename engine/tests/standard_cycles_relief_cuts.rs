//! CYCLE95 with relief cuts (a contour that falls again in the infeed direction) on the 2-axis
//! lathe (X a radius), checked on every IPO sample against the part worked out by hand: the
//! roughing keeps the allowances off every wall and floor, reaches the relief's floor, enters
//! the relief down its falling wall; the finishing runs on the contour.

use crate::turning_support;

use turning_support::{Trace, close, run_lathe};

/// A shaft with a groove (relief cut): X10 from Z0 to Z-10, a shoulder up to X15, X15 to Z-15,
/// down into the groove to X12, its floor to Z-20, up to X15, X15 to Z-30, a shoulder to X20.
const GROOVED: &str = "G18 G90\nG1 X10 Z0\nG1 Z-10\nG1 X15\nG1 Z-15\nG1 X12\nG1 Z-20\nG1 X15\nG1 Z-30\nG1 X20\nM17\n";

/// The part's radius at `z` (the walls belong to both sides: the larger value).
fn part(z: f64) -> f64 {
    let at = |z: f64| -> f64 {
        if z > -10.0 {
            10.0
        } else if z > -15.0 {
            15.0
        } else if z > -20.0 {
            12.0
        } else if z > -30.0 {
            15.0
        } else {
            20.0
        }
    };
    let walls: [f64; 4] = [-10.0, -15.0, -20.0, -30.0];
    let mut r = at(z);
    for w in walls {
        if close(z, w, 1e-9) {
            r = at(w - 1e-6).max(at(w + 1e-6));
        }
    }
    r
}

/// The roughing boundary: the part grown by `fz` along Z and `fx` in X (the highest point of
/// the part nearer than `fz` along Z, plus `fx`; a point exactly `fz` from a wall lies on the
/// boundary's face).
fn boundary(z: f64, fz: f64, fx: f64) -> f64 {
    let mut r = part(z - fz + 1e-7).max(part(z + fz - 1e-7));
    for w in [-10.0, -15.0, -20.0, -30.0] {
        if (w - z).abs() < fz - 1e-7 {
            r = r.max(part(w));
        }
    }
    r + fx
}

fn run(call: &str) -> Trace {
    let t = run_lathe(
        "$TC_DP6[1,1]=0\n",
        &format!("G18 G90 G94\nT1 D1\nS800 M3\nG0 X30 Z10\n{call}\nM30"),
        &[("GROOVED", GROOVED)],
    );
    t.clean().after_reaching(30.0, 10.0)
}

#[test]
fn cycle95_roughs_a_relief_cut_down_to_its_floor_keeping_the_allowances_off_its_walls() {
    // VARI 1 (roughing, longitudinal outside), MID 2.5, FALZ 0.2, FALX 0.1, FF1 300, FF2 50.
    // Levels: the top X20 + 0.1 down to the lowest point X10 + 0.1 in 4 steps of 2.5 (17.6,
    // 15.1, 12.6, 10.1) and the groove's floor X12 + 0.1 = 12.1. The groove is cut on 12.6 and
    // 12.1 from Z-15 - 0.2 to Z-20 + 0.2, entered from above down its falling wall at
    // Z-15.2 (from X15 + 0.1 on 12.6, from 12.5 + 0.1 on 12.1).
    let t = run("CYCLE95(\"GROOVED\",2.5,0.2,0.1,0,300,50,100,1,0,0,0)");
    for s in &t.samples {
        if s.z < 0.2 && s.z > -30.2 {
            let b = boundary(s.z, 0.2, 0.1);
            assert!(s.x >= b - 1e-6, "inside the allowance at Z{} X{}: {b}", s.z, s.x);
        }
    }
    // The groove's floor: cut along X12.1 from Z-15.2 to Z-19.8, and along X12.6 too.
    for level in [12.1, 12.6] {
        let along: Vec<f64> =
            t.samples.iter().filter(|s| close(s.x, level, 1e-9) && s.z < -15.0 && s.z > -20.0).map(|s| s.z).collect();
        assert!(!along.is_empty(), "level {level} in the groove");
        let (hi, lo) = along.iter().fold((f64::MIN, f64::MAX), |(h, l), z| (h.max(*z), l.min(*z)));
        assert!(close(hi, -15.2, 1e-9) && close(lo, -19.8, 1e-9), "level {level}: Z{hi} .. Z{lo}");
    }
    // Entry down the falling wall at Z-15.2 at FF2 (50 mm/min): from X15.1 to X12.6 (level
    // 12.6), from X13.6 (_VRT above 12.6) on to X12.1 (level 12.1); above X13.6 the G0 from the
    // safe height X21.1 comes down.
    let down: Vec<_> = t
        .samples
        .windows(2)
        .filter(|w| close(w[0].z, -15.2, 1e-9) && close(w[1].z, -15.2, 1e-9) && w[1].x < w[0].x - 1e-9)
        .filter(|w| w[1].x > 12.7 && w[0].x < 13.5)
        .map(|w| (w[0].x - w[1].x) / (w[1].t - w[0].t) * 60.0)
        .collect();
    assert!(!down.is_empty());
    let bad: Vec<_> = down.iter().filter(|v| !close(**v, 50.0, 1e-6)).take(5).collect();
    assert!(bad.is_empty(), "insertion feed {bad:?}");
    // The floor in front of the groove is cut on the lowest level, 10.1, up to Z-9.8.
    assert!(t.samples.iter().any(|s| close(s.x, 10.1, 1e-9) && close(s.z, -9.8, 1e-9)));
    // The first shoulder's land (X15 from Z-10 to Z-15) is cut on 15.1 all along.
    assert!(t.samples.iter().any(|s| close(s.x, 15.1, 1e-9) && close(s.z, -12.5, 1e-6)));
}

#[test]
fn cycle95_finishes_a_relief_cut_along_the_contour() {
    // VARI 9 (complete) without allowances: after the roughing the finishing runs from Z1 X10
    // along the whole contour, into the groove and out, within 1 µm of the part.
    let t = run("CYCLE95(\"GROOVED\",2.5,0,0,0,300,0,100,9,0,0,0)");
    let from = t.samples.iter().rposition(|s| close(s.x, 10.0, 1e-9) && close(s.z, 1.0, 1e-9)).expect("finishing");
    let fin = &t.samples[from..];
    let mut on = 0;
    for s in fin.iter().filter(|s| s.z <= 0.0 && s.z >= -30.0 && s.x <= 20.0 + 1e-9) {
        let wall = [-10.0, -15.0, -20.0, -30.0].iter().any(|w| close(s.z, *w, 1e-6));
        assert!(wall || close(s.x, part(s.z), 1e-6), "off the contour at Z{} X{}", s.z, s.x);
        on += 1;
    }
    assert!(on > 100);
    assert!(fin.iter().any(|s| close(s.z, -17.5, 1e-6) && close(s.x, 12.0, 1e-9)), "the groove's floor");
    // Without allowances the roughing reached the floor itself: X12 between Z-15 and Z-20.
    let rough = &t.samples[..from];
    assert!(rough.iter().any(|s| close(s.z, -17.5, 1e-6) && close(s.x, 12.0, 1e-9)));
}

#[test]
fn cycle95_inside_relief_cut_is_the_outside_one_mirrored() {
    // The bore X20 (Z0..-10), X15 (to Z-15), an internal groove out to X18 (to Z-20), X15 (to
    // Z-30), X10: the outside shaft above mirrored about X15 (x -> 30 - x). Roughing inside
    // (VARI 3) from X0 Z10 runs every sample at the mirror of the outside roughing (VARI 1)
    // from X30 Z10: the same levels, reliefs and walls.
    let bore = "G18 G90\nG1 X20 Z0\nG1 Z-10\nG1 X15\nG1 Z-15\nG1 X18\nG1 Z-20\nG1 X15\nG1 Z-30\nG1 X10\nM17\n";
    let outside = run("CYCLE95(\"GROOVED\",2.5,0.2,0.1,0,300,50,100,1,0,0,0)");
    let inside = run_lathe(
        "$TC_DP6[1,1]=0\n",
        "G18 G90 G94\nT1 D1\nS800 M3\nG0 X0 Z10\nCYCLE95(\"BORE\",2.5,0.2,0.1,0,300,50,100,3,0,0,0)\nM30",
        &[("BORE", bore)],
    )
    .clean()
    .after_reaching(0.0, 10.0);
    assert_eq!(inside.samples.len(), outside.samples.len());
    for (i, o) in inside.samples.iter().zip(&outside.samples) {
        assert!(
            close(i.z, o.z, 1e-9) && close(i.x, 30.0 - o.x, 1e-9),
            "inside Z{} X{} vs outside Z{} X{}",
            i.z,
            i.x,
            o.z,
            o.x
        );
    }
    // The groove's floor inside: X18 - 0.1.
    assert!(inside.samples.iter().any(|s| close(s.x, 17.9, 1e-9) && close(s.z, -17.5, 1e-6)));
}

#[test]
fn cycle95_round_relief_is_followed_down_its_arcs_to_the_floor() {
    // A round groove R3 about (Z-17, X15) in the land X15 (Z-10..-30): G2 from Z-14 X15 to the
    // floor Z-17 X12 and G2 on to Z-20 X15. No allowances, MID 2: the levels from X20 down to
    // X10 in 5 steps of 2 (18, 16, 14, 12, 10) and the floor X12 (already one of them). The
    // roughing never enters the part, follows both arcs (samples on the circle) and reaches
    // the floor's lowest point.
    let round =
        "G18 G90\nG1 X10 Z0\nG1 Z-10\nG1 X15\nG1 Z-14\nG2 Z-17 X12 CR=3\nG2 Z-20 X15 CR=3\nG1 Z-30\nG1 X20\nM17\n";
    let t = run_lathe(
        "$TC_DP6[1,1]=0\n",
        "G18 G90 G94\nT1 D1\nS800 M3\nG0 X30 Z10\nCYCLE95(\"ROUND\",2,0,0,0,300,50,100,1,0,0,0)\nM30",
        &[("ROUND", round)],
    )
    .clean()
    .after_reaching(30.0, 10.0);
    let surface = |z: f64| -> f64 {
        if z < -14.0 && z > -20.0 { 15.0 - (9.0 - (z + 17.0) * (z + 17.0)).max(0.0).sqrt() } else { part(z) }
    };
    // (A point on a shoulder's face, Z-10 or Z-30, lies on the part: the face's lower end counts.)
    let face = |z: f64| surface(z - 1e-7).min(surface(z + 1e-7));
    for s in t.samples.iter().filter(|s| s.z < 0.0 && s.z > -30.0) {
        assert!(s.x >= face(s.z) - 1e-6, "inside the part at Z{} X{}", s.z, s.x);
    }
    let on_arc = t
        .samples
        .iter()
        .filter(|s| s.z < -14.1 && s.z > -19.9 && close((s.z + 17.0).hypot(s.x - 15.0), 3.0, 1e-6))
        .count();
    assert!(on_arc > 20, "follows the arcs: {on_arc}");
    assert!(t.samples.iter().any(|s| close(s.z, -17.0, 1e-6) && close(s.x, 12.0, 1e-6)), "the floor");
}
