//! MD20480 `$MC_SMOOTHING_MODE` (Function Manual B1 "Continuous-path mode", "Rounding
//! behavior"): its units digit says what G643 rounds by, its tens digit what G642 (and G645,
//! which rounds corners as G642) rounds by: 0 every axis by MD33100, 1 the geometry axes by the
//! contour tolerance SD42465, 2 the orientation by SD42466 (the geometry axes by MD33100),
//! 3 both. Expected values are worked out by hand in each test's comment.

use crate::path_support;

/// MD33100 = 0.1 mm on X and Y (the preset's), SD42465 = 0.02 mm, and `mode` for MD20480.
fn md(mode: u32) -> String {
    format!(
        "$MA_COMPRESS_POS_TOL[X]=0.1\n$MA_COMPRESS_POS_TOL[Y]=0.1\n$SC_SMOOTH_CONTUR_TOL=0.02\n$MC_SMOOTHING_MODE={mode}"
    )
}

/// The closest any sample comes to the corner (10, 0) of +X then +Y under `g`, at 1 mm/s
/// (samples 0.004 mm apart).
fn closest(mode: u32, g: &str) -> f64 {
    let program = format!("G90 G0 X0 Y0 Z0\n{g} G1 X10 F60\nY10\nM30");
    let (_, s) = path_support::samples::<3>(&md(mode), &program, 100_000);
    assert_eq!(s.last().unwrap(), &[10.0, 10.0, 0.0]);
    s.iter().map(|p| (10.0 - p[0]).hypot(p[1])).fold(f64::INFINITY, f64::min)
}

/// `d` is the rounding's distance `want` from the corner, within the 2 % the element may
/// stay short of its tolerance and 1 % for the sampling (the nearest sample lies up to
/// 0.002 mm beside the apex, where the element curves sharply: 0.1 mm long at 0.02).
fn assert_near(d: f64, want: f64, what: &str) {
    assert!((0.97 * want..=1.01 * want).contains(&d), "{what}: passes {d} from the corner, expected {want}");
}

#[test]
fn the_tens_digit_picks_g642s_tolerance_and_the_units_digit_g643s() {
    // G642 passes a right-angle corner at its tolerance t (the element's apex). G643 keeps
    // each axis within t, both at the corner (B1: 3/16·d·|Δ| = t with Δ = 1): it passes
    // (10 − t, t), √2·t from the corner (symmetric, both axes alike).
    //   mode  0: G642 by MD33100 0.1, G643 by MD33100: √2·0.1 = 0.1414
    //   mode  1: G642 by MD33100 0.1, G643 by SD42465: √2·0.02 = 0.0283
    //   mode 10: G642 by SD42465 0.02, G643 by MD33100 0.1414
    //   mode 11: G642 0.02, G643 0.0283
    //   mode 30: G642 0.02 (3: contour and orientation tolerance)
    //   mode 20: G642 0.1 (2 names the orientation only; no orientation on the 3-axis mill)
    let r2 = std::f64::consts::SQRT_2;
    for (mode, g642, g643) in [(0, 0.1, r2 * 0.1), (1, 0.1, r2 * 0.02), (10, 0.02, r2 * 0.1), (11, 0.02, r2 * 0.02)] {
        assert_near(closest(mode, "G642"), g642, &format!("G642 MD20480={mode}"));
        assert_near(closest(mode, "G643"), g643, &format!("G643 MD20480={mode}"));
    }
    assert_near(closest(30, "G642"), 0.02, "G642 MD20480=30");
    assert_near(closest(20, "G642"), 0.1, "G642 MD20480=20");
}

#[test]
fn g645_rounds_its_corners_by_the_tens_digit_and_ctol_comes_first() {
    // G645 rounds a corner as G642: MD20480 = 10 gives SD42465 (0.02), = 1 MD33100 (0.1).
    // A programmed CTOL=0.05 wins over either datum.
    assert_near(closest(10, "G645"), 0.02, "G645 MD20480=10");
    assert_near(closest(1, "G645"), 0.1, "G645 MD20480=1");
    assert_near(closest(10, "G642 CTOL=0.05"), 0.05, "G642 CTOL MD20480=10");
    assert_near(closest(0, "G645 CTOL=0.05"), 0.05, "G645 CTOL MD20480=0");
}
