//! The rules of Function Manual B1 "Continuous-path mode" on where no rounding element is
//! inserted although G641..G645 is active, beyond those of `path_control.rs` (a dwell or G9
//! between the blocks): a change of the acceleration profile between BRISK and SOFT.

use crate::path_support;

#[test]
fn a_change_between_brisk_and_soft_keeps_the_corner_sharp() {
    // G642 CTOL=0.05 on a square at F6000: the block after the corner at (20, 0) switches to
    // SOFT, so that corner is not rounded: every sample within 2 mm of it lies on the two
    // programmed lines (a rounding element would leave them by up to 0.05). The corner at
    // (20, 20), between two SOFT blocks, is rounded: passed at 0.049..0.05 mm (within 2 %
    // below the tolerance; the samples, at most 0.4 mm apart, pass it no nearer).
    let (_, samples) = path_support::samples::<3>(
        "",
        "G0 X0 Y0 Z0\nBRISK G642 CTOL=0.05\nG1 F6000 X20\nSOFT Y20\nX0\nY0\nM30\n",
        100_000,
    );
    let dist = |p: &[f64; 3], c: [f64; 2]| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt();
    let near: Vec<&[f64; 3]> = samples.iter().filter(|p| dist(p, [20.0, 0.0]) < 2.0).collect();
    assert!(near.len() > 5, "{} samples near (20, 0)", near.len());
    for p in near {
        let off = p[1].abs().min((p[0] - 20.0).abs());
        assert!(off < 1e-9 && p[0] <= 20.0 + 1e-9, "{p:?} leaves the lines by {off} mm");
    }
    // The nearest sample to (20, 20) and the chords between samples: the path bends away
    // from the corner, so the nearest sample lies at least at the element's distance.
    let nearest = samples.iter().map(|p| dist(p, [20.0, 20.0])).fold(f64::INFINITY, f64::min);
    assert!((0.049..0.06).contains(&nearest), "the corner (20, 20) is passed at {nearest} mm");
    path_support::assert_dynamics(&samples);
}
