//! The lift-off after a compensated contour on the lathe (issue 25's TRC part, seen with
//! CYCLE95): T2 D1 of `lathe-2axis` has nose radius 0.4 and cutting edge position 3, so the
//! nose centre S lies 0.4 towards +Z and +X of the theoretical tip P (carrier X = P.x + 42,
//! Z = P.z + 58). Contour: G42 along X20 from Z0 to Z−20, then a lift-off to X30.
//!
//! - A lift-off block that is still compensated (G0 or G1): the contour turns from −Z to +X,
//!   an inner corner for G42, so S stops at the intersection of the equidistants X20.4 and
//!   Z−19.6 and lifts off on Z−19.6: P reaches (X20, Z−20) exactly — no blend into the
//!   compensated block — and S never comes nearer than 0.4 to the contour.
//! - G40 on the lift-off block (Function Manual W1, deselection with NORM): the last
//!   compensated block ends at its normal end point, S at (X20.4, Z−20) perpendicular above the
//!   contour's end (P at X20 Z−20.4); the G40 block starts there and travels to its
//!   uncompensated end point (P at X30 Z−20).

use crate::trc_support;
use trc_support::run_all_on;

/// The nose centre (z, x) of a sample.
fn centre(s: &[f64]) -> (f64, f64) {
    (s[1] - 58.0 + 0.4, s[0] - 42.0 + 0.4)
}

fn contour_dist(c: (f64, f64)) -> f64 {
    trc_support::seg_dist(c, (0.0, 20.0), (-20.0, 20.0))
}

#[test]
fn a_compensated_lift_off_turns_at_the_inner_corner_without_a_blend() {
    for lift in ["G0 X30", "G1 X30"] {
        let prog = format!("G18 G90 G94 T2 D1\nG0 X30 Z5\nG42 G1 X20 Z0 F300\nG1 Z-20\n{lift}\nG40 G0 X40 Z10\nM30");
        let (ch, samples) = run_all_on("lathe-2axis", "", &prog);
        assert!(ch.alarms().is_empty(), "{lift}: {:?}", ch.alarms());
        let corner = samples.iter().position(|s| {
            let (z, x) = centre(s);
            (z + 19.6).abs() < 1e-9 && (x - 20.4).abs() < 1e-9
        });
        assert!(corner.is_some(), "{lift}: the nose centre reaches (Z−19.6, X20.4)");
        // From the start point X30 Z5 on (carrier X72 Z63).
        let from =
            samples.iter().position(|s| (s[0] - 72.0).abs() < 1e-9 && (s[1] - 63.0).abs() < 1e-9).expect("start");
        for s in &samples[from..] {
            let c = centre(s);
            if c.0 < 0.0 && c.1 < 25.0 {
                assert!(contour_dist(c) > 0.4 - 1e-6, "{lift}: the nose cuts in at {c:?}");
            }
        }
        // After the corner S lifts off on Z−19.6 (the lift-off's equidistant).
        for s in &samples[corner.unwrap()..] {
            let c = centre(s);
            if c.1 < 30.0 {
                assert!((c.0 + 19.6).abs() < 1e-9, "{lift}: lifts off on Z−19.6, at {c:?}");
            }
        }
    }
}

#[test]
fn g40_on_the_lift_off_ends_the_contour_at_its_normal_end_point() {
    for lift in ["G40 G0 X30", "G40 G1 X30"] {
        let prog = format!("G18 G90 G94 T2 D1\nG0 X30 Z5\nG42 G1 X20 Z0 F300\nG1 Z-20\n{lift}\nG0 X40 Z10\nM30");
        let (ch, samples) = run_all_on("lathe-2axis", "", &prog);
        assert!(ch.alarms().is_empty(), "{lift}: {:?}", ch.alarms());
        let normal = samples.iter().position(|s| (s[0] - 62.0).abs() < 1e-9 && (s[1] - (58.0 - 20.4)).abs() < 1e-9);
        let normal = normal.unwrap_or_else(|| panic!("{lift}: P reaches X20 Z−20.4 (S perpendicular above the end)"));
        // From there straight to P = (X30, Z−20): S on the line from (X20.4, Z−20) to (X30.4, Z−19.6).
        let end = samples.iter().position(|s| (s[0] - 72.0).abs() < 1e-9 && (s[1] - 38.0).abs() < 1e-9);
        let end = end.unwrap_or_else(|| panic!("{lift}: the G40 block ends at its programmed point"));
        for s in &samples[normal..=end] {
            let c = centre(s);
            assert!(
                trc_support::seg_dist(c, (-20.0, 20.4), (-19.6, 30.4)) < 1e-6,
                "{lift}: {c:?} off the straight G40 move"
            );
        }
    }
}
