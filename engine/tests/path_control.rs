//! Continuous-path mode with corner rounding (G641 ADIS, G642, G645; Function Manual B1) run
//! through a whole channel on the 3-axis mill preset (X, Y, Z: 30 m/min, 3 m/s², overload
//! factor 1.2, IPO cycle 4 ms). Checked on the IPO samples:
//! - every sample lies within the tolerance of the programmed contour, and near each corner
//!   the path really leaves the corner (G642/G645: by nearly the whole tolerance, since the
//!   blocks are long enough for the rounding the tolerance allows);
//! - no axis exceeds its velocity, and no axis' velocity changes by more than its
//!   acceleration (times the overload factor MD32310 at block transitions) in one cycle, so
//!   the velocity is continuous;
//! - rounding makes the program faster than G64's corners and much faster than G60.

use crate::path_support;

use nctwin_engine::Channel;
use path_support::{DT, assert_dynamics};

/// Runs `program` on the 3-axis mill; the X, Y, Z samples of every IPO cycle.
fn run(program: &str) -> Vec<[f64; 3]> {
    path_support::samples("", program, 3_000_000).1
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Distance of `p` from the segment `a`–`b`.
fn to_segment(p: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
    let ap: [f64; 3] = std::array::from_fn(|k| p[k] - a[k]);
    let len2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if len2 > 0.0 { (ab.iter().zip(&ap).map(|(x, y)| x * y).sum::<f64>() / len2).clamp(0.0, 1.0) } else { 0.0 };
    dist(p, &std::array::from_fn(|k| a[k] + t * ab[k]))
}

/// Distance of `p` from the programmed polyline.
fn to_contour(p: &[f64; 3], contour: &[[f64; 3]]) -> f64 {
    contour.windows(2).map(|w| to_segment(p, &w[0], &w[1])).fold(f64::INFINITY, f64::min)
}

/// The largest distance from the programmed contour of the samples within `radius` of the
/// corner `c`: how far the path really leaves the corner (the samples lie on the path).
fn corner_deviation(samples: &[[f64; 3]], contour: &[[f64; 3]], c: &[f64; 3], radius: f64) -> f64 {
    samples.iter().filter(|p| dist(p, c) <= radius).map(|p| to_contour(p, contour)).fold(0.0, f64::max)
}

/// The program's contour: the start point and the end points of `moves` (X, Y) at Z0.
fn program(header: &str, start: [f64; 2], moves: &[[f64; 2]], feed: f64) -> (String, Vec<[f64; 3]>) {
    let mut text = format!("G0 X{} Y{} Z0\n{header}\nG1 F{feed}\n", start[0], start[1]);
    let mut contour = vec![[start[0], start[1], 0.0]];
    for m in moves {
        text.push_str(&format!("X{} Y{}\n", m[0], m[1]));
        contour.push([m[0], m[1], 0.0]);
    }
    text.push_str("M30\n");
    (text, contour)
}

fn square() -> Vec<[f64; 2]> {
    vec![[20.0, 0.0], [20.0, 20.0], [0.0, 20.0], [0.0, 0.0]]
}

/// 30 blocks of 2 mm in X rising and falling 1.5 mm in Y: corners of ±73.7° (the direction
/// turns between atan(0.75) and −atan(0.75)).
fn zigzag() -> Vec<[f64; 2]> {
    (1..=30).map(|i| [2.0 * f64::from(i), if i % 2 == 1 { 1.5 } else { 0.0 }]).collect()
}

/// Checks the samples of a rounded contour: all within `tol` of the programmed contour, near
/// each inner corner some farther than `min_dev` from it (really rounded), dynamics kept.
fn check_rounded(samples: &[[f64; 3]], contour: &[[f64; 3]], tol: f64, min_dev: f64) {
    let worst = samples.iter().map(|p| to_contour(p, contour)).fold(0.0, f64::max);
    assert!(worst <= tol * (1.0 + 1e-9), "a sample is {worst} from the contour (tolerance {tol})");
    for c in &contour[1..contour.len() - 1] {
        let dev = corner_deviation(samples, contour, c, 1.0);
        assert!(dev > min_dev, "corner {c:?}: the path leaves the contour by {dev} at most (tolerance {tol})");
    }
    assert_dynamics(samples);
}

#[test]
fn g642_rounds_the_corners_of_a_square_within_the_contour_tolerance() {
    // CTOL=0.05 and 0.01, and the machine data's MD33100 (0.1 mm) with no CTOL: the blocks are
    // 20 mm long, so the element passes the corner at nearly the whole tolerance (the search
    // stops within 2 % of it). At 90° its middle then lies tol·sin 45° ≈ 0.707·tol from both
    // lines. The samples straddle that peak: at 0.01 the element is only ~0.05 mm long and
    // crossed in two or three cycles, so the check asks for 0.15·tol (the unit tests of
    // `motion::blend` check the element itself within 2 %).
    for (header, tol) in [("G642 CTOL=0.05", 0.05), ("G642 CTOL=0.01", 0.01), ("G642", 0.1)] {
        let (text, contour) = program(header, [0.0, 0.0], &square(), 6000.0);
        let samples = run(&text);
        check_rounded(&samples, &contour, tol, 0.15 * tol);
    }
}

#[test]
fn g645_and_g642_round_a_zigzag_of_short_blocks_within_the_tolerance() {
    for (header, tol) in [("G642 CTOL=0.02", 0.02), ("G645 CTOL=0.005", 0.005), ("G642 CTOL=0.2", 0.2)] {
        let (text, contour) = program(header, [0.0, 0.0], &zigzag(), 3000.0);
        let samples = run(&text);
        // The 2.5 mm blocks leave 36 % = 0.9 mm to each rounding: enough for the whole
        // tolerance at 0.005 and 0.02, not for 0.2. With the whole tolerance the element's
        // middle lies tol·sin 53.1° = 0.8·tol from both lines (half the opening angle of
        // 106.3°); the samples straddle it (see the square), so more than 0.15·tol. At 0.005
        // the element is only ~0.03 mm long and crossed at its curvature's low speed in one or
        // two cycles, one sample inside it at most, anywhere along it: more than 0.05·tol (a
        // sharp corner's samples all lie on the contour, within 1e-12).
        let min_dev = match tol {
            t if t < 0.01 => 0.05 * t,
            t if t < 0.1 => 0.15 * t,
            _ => 0.01,
        };
        check_rounded(&samples, &contour, tol, min_dev);
    }
}

#[test]
fn g641_rounds_within_adis_of_each_corner_and_follows_the_blocks_elsewhere() {
    // ADIS=0.5: the rounding starts 0.5 mm before each corner of the square and ends 0.5 mm
    // after it; every sample farther than that from all corners lies on the programmed lines.
    let (text, contour) = program("G641 ADIS=0.5", [0.0, 0.0], &square(), 6000.0);
    let samples = run(&text);
    for p in &samples {
        let near = contour[1..4].iter().any(|c| dist(p, c) <= 0.5 + 1e-9);
        if !near {
            assert!(to_contour(p, &contour) < 1e-9, "{p:?} leaves the contour away from the corners");
        }
    }
    for c in &contour[1..4] {
        // The element between (c − 0.5 along a) and (c + 0.5 along b) at 90° leaves the lines
        // by clearly more than 0.05 mm, and by less than the chord's middle does (0.5/√2 ≈
        // 0.354 mm from the corner, 0.25 mm from either line).
        let dev = corner_deviation(&samples, &contour, c, 1.0);
        assert!(dev > 0.05 && dev < 0.25, "corner {c:?}: deviation {dev}");
    }
    assert_dynamics(&samples);
    // Without ADIS (0 after reset) G641 rounds nothing: every sample lies on the contour.
    let (text, contour) = program("G641", [0.0, 0.0], &square(), 6000.0);
    let samples = run(&text);
    assert!(samples.iter().all(|p| to_contour(p, &contour) < 1e-9));
}

#[test]
fn the_g_group_10_and_12_functions_read_back_through_p_gg() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("R1=$P_GG[10]\nG645\nR2=$P_GG[10]\nG602\nR3=$P_GG[12]\nG60\nR4=$P_GG[10]\nM30\n").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    // Reset: G60 (1); G645 is the 7th function of group 10; G602 the 2nd of group 12.
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4)], [1.0, 7.0, 2.0, 1.0]);
}

#[test]
fn a_negative_adis_is_refused_with_its_line() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("G1 F100 X1\nG641 ADIS=-1 X2\nM30\n").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let alarm = ch.alarms().first().expect("an alarm");
    assert_eq!(alarm.line, Some(2), "{alarm:?}");
}

/// A CAM-style finishing program of a curved surface: 100 raster rows of 200 chords of
/// 0.5 mm in X (back and forth, 0.5 mm apart in Y) on z = 8·sin(x/8)·cos(y/20), 20,000 G1
/// chords in all after `header`, at F10000. The chords' directions turn by up to
/// 8/8²·0.5 ≈ 3.6° at each point; a chord leaves the surface by at most 0.5²·κ/8 ≈ 4 µm.
fn surface_program(header: &str) -> String {
    let z = |x: f64, y: f64| 8.0 * (x / 8.0).sin() * (y / 20.0).cos();
    let mut text = format!("G0 X0 Y0 Z{:.4}\n{header}\nG1 F10000\n", z(0.0, 0.0));
    for row in 0..100 {
        let y = 0.5 * f64::from(row);
        for i in 1..=200 {
            let i = if row % 2 == 0 { i } else { 200 - i };
            let x = 0.5 * f64::from(i);
            // The first chord of a row after the first is the step in Y.
            text.push_str(&format!("X{x:.4} Y{y:.4} Z{:.4}\n", z(x, y)));
        }
    }
    text.push_str("M30\n");
    text
}

#[test]
fn a_cam_surface_of_20000_chords_runs_fastest_with_g642_and_compcad() {
    let cycles = |header: &str| {
        let samples = run(&surface_program(header));
        // The dynamics of the rounded and compressed path (G60's and G64's are the
        // planner's own, tested there).
        if header.starts_with("G642") {
            assert_dynamics(&samples);
        }
        samples.len() - 1
    };
    let (g60, g64, g642) = (cycles("G60"), cycles("G64"), cycles("G642 COMPCAD CTOL=0.01"));
    let g642_only = cycles("G642 CTOL=0.01");
    // No two chords of the surface meet tangentially: G645 rounds each transition as a corner,
    // exactly as G642 does.
    let g645 = cycles("G645 CTOL=0.01");
    // The header a CAM system writes (issue 22's check): jerk-limited, with feed-forward.
    let cam = cycles("G642 COMPCAD SOFT FFWON CTOL=0.01");
    eprintln!(
        "surface program, 20,000 chords: G60 {:.1} s, G64 {:.1} s, G642 {:.1} s, G645 {:.1} s, G642+COMPCAD {:.1} s, \
         G642+COMPCAD+SOFT+FFWON {:.1} s",
        g60 as f64 * DT,
        g64 as f64 * DT,
        g642_only as f64 * DT,
        g645 as f64 * DT,
        g642 as f64 * DT,
        cam as f64 * DT
    );
    assert!(cam < g64, "G642+COMPCAD+SOFT+FFWON {cam}, G64 {g64} cycles");
    assert_eq!(g645, g642_only, "G645 differs from G642 on a surface without tangential transitions");
    assert!(g642 < g64 && 2 * g64 < g60, "G642+COMPCAD {g642}, G64 {g64}, G60 {g60} cycles");
    assert!(g642 <= g642_only, "the compressor helps: {g642} vs {g642_only}");
}

#[test]
fn a_dwell_or_g9_between_two_blocks_keeps_the_corner_sharp() {
    // G642 with CTOL=0.05; the corner at X20 has a dwell after its block (the axes stop), the
    // one at X20 Y20 an exact stop G9 in its block: both are met exactly. The third corner
    // (X0 Y20) is rounded.
    let text = "G0 X0 Y0 Z0\nG642 CTOL=0.05\nG1 F6000 X20\nG4 F0.1\nY20 G9\nX0\nY0\nM30\n";
    let contour = [[0.0, 0.0, 0.0], [20.0, 0.0, 0.0], [20.0, 20.0, 0.0], [0.0, 20.0, 0.0], [0.0, 0.0, 0.0]];
    let samples = run(text);
    for c in &contour[1..3] {
        assert!(samples.iter().any(|p| dist(p, c) < 1e-9), "the path passes {c:?}");
    }
    assert!(corner_deviation(&samples, &contour, &contour[3], 1.0) > 0.005);
    assert!(samples.iter().all(|p| to_contour(p, &contour) <= 0.05 * (1.0 + 1e-9)));
    assert_dynamics(&samples);
}

#[test]
fn programs_without_continuous_path_words_are_not_changed() {
    // The same square under G64 with the compressor off and ADIS programmed but G641 not
    // selected: every sample lies on the programmed contour (no rounding element), as before
    // these words.
    let (text, contour) = program("G64 ADIS=0.5 COMPOF", [0.0, 0.0], &square(), 6000.0);
    let samples = run(&text);
    assert!(samples.iter().all(|p| to_contour(p, &contour) < 1e-9));
}

#[test]
fn g642_rounds_the_corners_of_a_radius_compensated_contour_within_the_tolerance() {
    // T1 D1 (radius 5) G41 on the square run counter-clockwise: the tool centre runs on the
    // equidistant 5 mm inside (at Z100, the tool length), the square from (5, 5) to
    // (15, 15) (entered from the approach point (0, 5), left towards (5, 0)), whose inner
    // corners are
    // the intersections of the offset lines. G642 rounds them within CTOL=0.02: every
    // sample inside that square's band lies within 0.02 of it, and its corners (15, 5),
    // (15, 15), (5, 15) are really left.
    let text = "T1 D1\nG0 X-10 Y-10 Z0\nG642 CTOL=0.02\nG1 F3000 G41 X0 Y0\nX20\nY20\nX0\nY0\nG40 X-10 Y-10\nM30\n";
    let samples = run(text);
    let offset = [[0.0, 5.0, 100.0], [15.0, 5.0, 100.0], [15.0, 15.0, 100.0], [5.0, 15.0, 100.0], [5.0, 0.0, 100.0]];
    let inside: Vec<[f64; 3]> =
        samples.iter().copied().filter(|p| (4.9..=15.1).contains(&p[0]) && (4.9..=15.1).contains(&p[1])).collect();
    assert!(inside.len() > 100, "{} samples on the offset square", inside.len());
    for p in &inside {
        let d = to_contour(p, &offset);
        assert!(d <= 0.02 * (1.0 + 1e-9), "{p:?} is {d} from the offset contour");
    }
    for c in &offset[1..4] {
        let dev = corner_deviation(&inside, &offset, c, 1.0);
        assert!(dev > 0.003, "corner {c:?}: deviation {dev}");
    }
    assert_dynamics(&samples);
}

#[test]
fn under_soft_the_rounded_square_and_zigzag_keep_every_axis_jerk() {
    // Issue 22's geometric check with SOFT: MD32431 20 m/s³ on X, Y, Z (the 3000 mm/s² take
    // 0.15 s to build), so the jerk limit, not the acceleration, shapes every ramp. The third
    // difference of the sampled positions is the jerk of a cycle. The rounding elements keep
    // the axes' jerk as an arc does (`motion/soft_curvature.rs`), and the path acceleration
    // does not rise in the two cycles after entering or leaving one (`motion/soft.rs`), where
    // the turning acceleration begins or ends. The square keeps J in every cycle; the zigzag
    // came to 1.012 J at most (20 239 mm/s³, CTOL=0.2: the cycle that enters an element while
    // the line's braking eases), hence 1.02 J there. Before session 16 the elements ran with
    // no jerk limit: 11.3 J (225 953 mm/s³) on the square.
    const MD: &str = "$MA_MAX_AX_JERK[X]=20\n$MA_MAX_AX_JERK[Y]=20\n$MA_MAX_AX_JERK[Z]=20\n";
    for (header, moves, feed, tol, bound) in [
        ("SOFT G642 CTOL=0.05", square(), 6000.0, 0.05, 1.0),
        ("SOFT G641 ADIS=0.5", square(), 6000.0, 0.5, 1.0),
        ("SOFT G642 CTOL=0.02", zigzag(), 3000.0, 0.02, 1.02),
        ("SOFT G645 CTOL=0.02", zigzag(), 3000.0, 0.02, 1.02),
        ("SOFT G642 CTOL=0.2", zigzag(), 3000.0, 0.2, 1.02),
        ("SOFT G641 ADIS=0.3", zigzag(), 3000.0, 0.3, 1.02),
    ] {
        let (text, contour) = program(header, [0.0, 0.0], &moves, feed);
        let samples = path_support::samples::<3>(MD, &text, 3_000_000).1;
        let worst = samples.iter().map(|p| to_contour(p, &contour)).fold(0.0, f64::max);
        assert!(worst <= tol * (1.0 + 1e-9), "{header}: a sample is {worst} from the contour");
        assert_dynamics(&samples);
        let d = |s: &[[f64; 3]]| -> Vec<[f64; 3]> {
            s.windows(2).map(|w| std::array::from_fn(|k| (w[1][k] - w[0][k]) / DT)).collect()
        };
        let jerk = d(&d(&d(&samples)));
        for (i, j) in jerk.iter().enumerate() {
            for (k, jk) in j.iter().enumerate() {
                assert!(jk.abs() <= 20_000.0 * bound * (1.0 + 1e-6), "{header}: axis {k} jerk {jk} mm/s³ in cycle {i}");
            }
        }
    }
}
