//! ORICURVE with XH/YH/ZH on `mill5-head-ca` (MD21104 = 1): the orientation at every IPO point
//! is the direction from the tool tip to the upper curve, both straight lines run through with
//! the same path parameter. Expected values come from the head's closed form (REFERENCE §6.4.5,
//! type 20: o = (sin C·sin A, −cos C·sin A, cos A)) and `normalize(upper(t) − tip(t))` computed
//! here.

use crate::settle;
use nctwin_engine::{Channel, Snapshot, Status};

fn run(program: &str) -> (Channel, Vec<Snapshot>) {
    settle::run_snapshots("mill5-head-ca", "$MC_ORI_IPO_WITH_G_CODE=1\n", program)
}

fn value(list: &[(String, f64)], name: &str) -> f64 {
    list.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

fn head(s: &Snapshot) -> [f64; 3] {
    let (sa, ca) = value(&s.machine, "A").to_radians().sin_cos();
    let (sc, cc) = value(&s.machine, "C").to_radians().sin_cos();
    [sc * sa, -cc * sa, ca]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / n)
}

fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    std::array::from_fn(|i| a[i] + t * (b[i] - a[i]))
}

#[test]
fn the_orientation_points_from_the_tip_line_to_the_upper_line() {
    // N10 starts the upper curve on the start orientation (+Z) 100 mm above the tip and moves
    // both lines 10 mm along X; N20 runs the tip (10,0,50) → (60,0,50) while the upper line goes
    // (10,0,150) → (40,20,130).
    let (ch, samples) = run("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F2000\nORICURVE\n\
         N10 X10 XH=10 YH=0 ZH=150\nN20 X60 XH=40 YH=20 ZH=130\nM0\nM30");
    let end = ch.snapshot();
    assert_eq!(end.status, Status::Stopped, "{:?}", end.alarms);
    let (tip0, tip1) = ([10.0, 0.0, 50.0], [60.0, 0.0, 50.0]);
    let (up0, up1) = ([10.0, 0.0, 150.0], [40.0, 20.0, 130.0]);
    let mut checked = 0;
    for s in samples.iter().filter(|s| s.block.as_ref().is_some_and(|b| b.text.starts_with("N20"))) {
        let tip = ["X", "Y", "Z"].map(|n| value(&s.workpiece, n));
        assert!(tip[1].abs() < 1e-6 && (tip[2] - 50.0).abs() < 1e-6, "tip off the line: {tip:?}");
        let t = (tip[0] - 10.0) / 50.0;
        let want = unit(std::array::from_fn(|i| lerp(up0, up1, t)[i] - lerp(tip0, tip1, t)[i]));
        let got = head(s);
        assert!(got.iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-7), "t = {t}: {got:?} vs {want:?}");
        checked += 1;
    }
    assert!(checked > 20, "only {checked} samples in N20");
    // The end: (40,20,130) − (60,0,50) = (−20, 20, 80).
    let want = unit([-20.0, 20.0, 80.0]);
    assert!(head(&end).iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-9), "{:?}", head(&end));
}

#[test]
fn oricurve_refuses_circles_and_a_first_block_without_all_three_coordinates() {
    let (ch, _) = run("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F2000\nORICURVE\nN10 X10 ZH=150\nM30");
    assert!(
        ch.snapshot().alarms.iter().any(|a| a.line == Some(6) && a.message.contains("XH, YH and ZH")),
        "{:?}",
        ch.snapshot().alarms
    );
    let (ch, _) = run("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F2000\nORICURVE\nN10 G2 X20 I10 XH=20 YH=0 ZH=150\nM30");
    assert!(ch.snapshot().alarms.iter().any(|a| a.message.contains("straight")), "{:?}", ch.snapshot().alarms);
    let (ch, _) = run("T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F2000\nORIVECT\nN10 X10 XH=10 YH=0 ZH=150\nM30");
    assert!(ch.snapshot().alarms.iter().any(|a| a.message.contains("ORICURVE")), "{:?}", ch.snapshot().alarms);
}
