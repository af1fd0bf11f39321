//! Directly programmed rotary axes under vector interpolation (MD21104 = 1, ORIVECT) on
//! `mill5-head-ca`: the block must end on exactly the programmed positions, also when the great
//! circle, followed continuously, would end on the other of the two solutions
//! (A, C) ≡ (−A, C + 180°) of the CA head (o = (sin C·sin A, −cos C·sin A, cos A)).

use crate::settle;
use nctwin_engine::{Snapshot, Status};

fn run(program: &str) -> (Snapshot, Vec<Snapshot>) {
    let (ch, samples) = settle::run_snapshots("mill5-head-ca", "$MC_ORI_IPO_WITH_G_CODE=1\n", program);
    (ch.snapshot(), samples)
}

use settle::machine_axis as axis;

#[test]
fn a_direct_a_c_block_ends_on_the_programmed_solution() {
    // From A40 C0 the great circle to the orientation of A−10 C170 stays on the A > 0 branch
    // (it does not pass the pole A = 0) and would end at A10 C350, the same orientation.
    for (from, to) in [((40.0, 0.0), (-10.0, 170.0)), ((-20.0, 0.0), (30.0, 90.0)), ((10.0, 0.0), (80.0, 180.0))] {
        let program = format!(
            "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F2000 ORIVECT\nA{} C{}\nA{} C{}\nM0\nM30",
            from.0, from.1, to.0, to.1
        );
        let (end, _) = run(&program);
        assert_eq!(end.status, Status::Stopped, "{:?}", end.alarms);
        assert!((axis(&end, "A") - to.0).abs() < 1e-9, "{from:?} → {to:?}: A = {}", axis(&end, "A"));
        let dc = (axis(&end, "C") - to.1 + 180.0).rem_euclid(360.0) - 180.0;
        assert!(dc.abs() < 1e-9, "{from:?} → {to:?}: C = {}", axis(&end, "C"));
    }
}

#[test]
fn a_direct_block_on_the_same_branch_keeps_the_great_circle() {
    // A20 C0 → A30 C90 stays on the A > 0 branch: vector interpolation, so halfway the
    // orientation is the normalised sum of start and end orientation (the great circle's middle).
    let (end, samples) = run("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F2000 ORIVECT\nA20 C0\nA30 C90\nM0\nM30");
    assert_eq!(end.status, Status::Stopped, "{:?}", end.alarms);
    let o = |a: f64, c: f64| {
        let (sa, ca) = a.to_radians().sin_cos();
        let (sc, cc) = c.to_radians().sin_cos();
        [sc * sa, -cc * sa, ca]
    };
    let (os, oe) = (o(20.0, 0.0), o(30.0, 90.0));
    let mid: Vec<f64> = (0..3).map(|i| os[i] + oe[i]).collect();
    let n = mid.iter().map(|v| v * v).sum::<f64>().sqrt();
    let on_circle = samples.iter().filter(|s| s.block.as_ref().is_some_and(|b| b.line == 6)).any(|s| {
        let got = o(axis(s, "A"), axis(s, "C"));
        (0..3).all(|i| (got[i] - mid[i] / n).abs() < 2e-3)
    });
    assert!(on_circle, "no sample near the middle of the great circle");
    assert!((axis(&end, "A") - 30.0).abs() < 1e-9 && (axis(&end, "C") - 90.0).abs() < 1e-9);
}
