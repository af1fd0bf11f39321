//! ORISON (F2 3.9.4, smoothing of the orientation characteristic) on the CA head under
//! TRAORI: a straight tool tip path along X whose programmed orientation zig-zags ±2° from
//! block to block (1 mm blocks, the kinks of a CAM program's orientation), the orientation
//! turning on one great circle: o(θ) = (cos θ·sin 20°, −sin θ, cos θ·cos 20°), the tool
//! tilted 20° towards +X and swung by θ towards −Y (on the head A ≈ 20°, C ≈ 90°, far from
//! the pole).
//!
//! What is measured from the machine axes of every IPO cycle (the head's closed form in
//! `head_support`): θ of the sampled orientation against the programmed θ at the tip's X (the
//! zig-zag, linear within each block), its rate per mm of path between successive cycles, the
//! tip's distance from the programmed line, and the machine axes' limits.

mod head_support;
use head_support::*;
use nctwin_engine::Channel;

/// Blocks of the zig-zag: block i (1..=BLOCKS) runs from X i−1 to X i.
const BLOCKS: usize = 20;

fn o(theta: f64) -> [f64; 3] {
    let (s, c) = theta.to_radians().sin_cos();
    let (s20, c20) = 20f64.to_radians().sin_cos();
    [c * s20, -s, c * c20]
}

fn theta(v: [f64; 3]) -> f64 {
    let (s20, c20) = 20f64.to_radians().sin_cos();
    (-v[1]).atan2(v[0] * s20 + v[2] * c20).to_degrees()
}

/// The programmed θ at block end i: −2° at even i, +2° at odd.
fn theta_at_end(i: usize) -> f64 {
    if i.is_multiple_of(2) { -2.0 } else { 2.0 }
}

/// The programmed θ at tip position x in 0..=BLOCKS (linear within each block).
fn programmed(x: f64) -> f64 {
    let i = (x.floor() as usize).min(BLOCKS - 1);
    let f = x - i as f64;
    theta_at_end(i) + f * (theta_at_end(i + 1) - theta_at_end(i))
}

/// The program: to X0 Y0 Z50 at θ = −2°, then the zig-zag at F600, `word(i)` written
/// before block i's coordinates.
fn program(word: impl Fn(usize) -> &'static str) -> String {
    let mut p = String::from("T1 D1\nG0 X0 Y0 Z100 A20 C90\nTRAORI\nG4 F0.02\n");
    p += &format!("ORIWKS ORIVECT G0 X0 Y0 Z50 {}\nG4 F0.02\nG64 G1 F600\n", vector(o(-2.0)));
    for i in 1..=BLOCKS {
        p += &format!("{}X{i} {}\n", word(i), vector(o(theta_at_end(i))));
    }
    p + "M30"
}

/// The machine positions of every IPO cycle of `program` on the CA head with `data`.
fn run_with(data: &str, program: &str) -> (Channel, Vec<[f64; 5]>) {
    let mut ch = Channel::from_preset("mill5-head-ca", data).unwrap();
    ch.run_program(program).unwrap();
    let mut out = Vec::new();
    while ch.is_busy() {
        ch.step();
        let p = ch.axis_positions();
        out.push([p[0], p[1], p[2], p[3], p[4]]);
        assert!(out.len() < 2_000_000, "the program does not end");
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    (ch, out)
}

const DATA: &str = "$MC_MM_ORISON_BLOCKS=10\n$SC_ORISON_TOL=1\n$SC_ORISON_DIST=5\n";

/// (x, θ, angle from the programmed orientation in degrees) of the samples on the zig-zag.
fn on_zigzag(samples: &[[f64; 5]]) -> Vec<(f64, f64, f64)> {
    samples
        .iter()
        .map(|m| (tip(m), orientation(m)))
        .filter(|(t, _)| t[0] > 1e-6)
        .map(|(t, v)| {
            let p = o(programmed(t[0]));
            let angle = 2.0 * (0.5 * dot(sub(v, p), sub(v, p)).sqrt()).asin();
            (t[0], theta(v), angle.to_degrees())
        })
        .collect()
}

/// θ's rate per mm of path between successive samples (where the tip moved 0.1 µm or more),
/// at the middle X of the two.
fn rates(z: &[(f64, f64, f64)]) -> Vec<(f64, f64)> {
    z.windows(2)
        .filter(|w| w[1].0 - w[0].0 > 1e-4)
        .map(|w| (0.5 * (w[0].0 + w[1].0), (w[1].1 - w[0].1) / (w[1].0 - w[0].0)))
        .collect()
}

/// The largest change of the rate between successive rates within 0.1 mm of X = `x`.
fn rate_jump_near(r: &[(f64, f64)], x: f64) -> f64 {
    r.windows(2).filter(|w| (w[0].0 - x).abs() < 0.1).map(|w| (w[1].1 - w[0].1).abs()).fold(0.0, f64::max)
}

/// The tip's largest distance from the line Y0 Z50.
fn off_line(samples: &[[f64; 5]]) -> f64 {
    samples
        .iter()
        .map(tip)
        .filter(|t| t[0] > 1e-6)
        .map(|t| (t[1] * t[1] + (t[2] - 50.0).powi(2)).sqrt())
        .fold(0.0, f64::max)
}

#[test]
fn without_orison_the_orientation_rate_jumps_at_every_block_end() {
    // ORISOF: θ turns at +4°/mm, then −4°/mm: a jump of 8°/mm at each block end, which the
    // successive rates show as jumps of several °/mm (the sample straddling the end takes a
    // mixed rate); the orientation is the programmed one at every sample.
    let (_, samples) = run_with(DATA, &program(|_| ""));
    let z = on_zigzag(&samples);
    let r = rates(&z);
    for i in 1..BLOCKS {
        let jump = rate_jump_near(&r, i as f64);
        assert!(jump > 3.0, "block end {i}: rate jump {jump}°/mm");
    }
    let dev = z.iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(dev < 1e-6, "{dev}°");
    assert!(off_line(&samples) < 1e-6);
}

#[test]
fn orison_turns_the_tool_smoothly_within_the_tolerance_on_the_same_tip_path() {
    // ORISON with SD42678 1° and SD42680 5 mm: each block end gets a zone of 0.5 mm each side
    // (half a block); over it θ follows the quintic with the programmed rates ±4°/mm at its
    // ends: θ = ±4·(w − 2w³ + w⁴) from the middle of a block (w in 0..1 over the 1 mm zone),
    // 1.25° at the block end against the programmed 2°: the largest deviation 0.75°, inside
    // the 1° (see `motion::orison`'s test for the derivation). Its rate changes by at most
    // |d/dw 4·(1 − 6w² + 4w³)| = 12°/mm² (at the block end): between samples 0.02 mm apart
    // (F600, 2 ms) 0.24°/mm, never the ORISOF jump.
    let (ch, samples) = run_with(DATA, &program(|i| if i == 1 { "ORISON " } else { "" }));
    let z = on_zigzag(&samples);
    // Every sample's deviation is the formula's: 4·(2w³ − w⁴) at w = ½ − its distance from
    // the nearest block end (every block end 1..19 has its zone; none before X0.5 or after
    // X19.5, where the run starts and ends with an exact stop).
    for &(x, _, dev) in &z {
        let d = (x - x.round()).abs();
        let expected = if x < 0.5 || x > BLOCKS as f64 - 0.5 {
            0.0
        } else {
            let w = 0.5 - d;
            4.0 * (2.0 * w.powi(3) - w.powi(4))
        };
        assert!((dev - expected).abs() < 2e-3, "X{x}: {dev}° against {expected}°");
    }
    let dev = z.iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(dev <= 0.75 + 1e-3 && dev > 0.7, "largest deviation {dev}°");
    // At the middle of the inner block ends: 1.25° from the axis of the zig-zag.
    for i in 2..BLOCKS - 1 {
        let near = z.iter().min_by(|a, b| (a.0 - i as f64).abs().total_cmp(&(b.0 - i as f64).abs())).unwrap();
        assert!((near.1.abs() - 1.25).abs() < 0.01, "block end {i}: θ {}", near.1);
    }
    let r = rates(&z);
    let worst = r.windows(2).map(|w| (w[1].1 - w[0].1).abs()).fold(0.0, f64::max);
    assert!(worst < 1.0, "the rate jumps by {worst}°/mm");
    // The tip stays on the programmed line, as without ORISON.
    assert!(off_line(&samples) < 1e-6, "{}", off_line(&samples));
    assert_machine_limits(&ch, &samples);
}

#[test]
fn a_tighter_tolerance_keeps_the_orientation_closer() {
    // SD42678 0.5°: the zones shrink until the deviation (1.5° per mm of half zone) keeps
    // 0.5°: at most 0.5°, more than 0.4° (one shortening step lands at 0.475°).
    let data = DATA.replace("$SC_ORISON_TOL=1", "$SC_ORISON_TOL=0.5");
    let (ch, samples) = run_with(&data, &program(|i| if i == 1 { "ORISON " } else { "" }));
    let z = on_zigzag(&samples);
    let dev = z.iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(dev <= 0.5 && dev > 0.4, "largest deviation {dev}°");
    assert!(off_line(&samples) < 1e-6);
    assert_machine_limits(&ch, &samples);
}

#[test]
fn orisof_returns_to_the_programmed_orientation() {
    // ORISON for blocks 1..10, ORISOF from block 11: the last zone is the one at X9 (X 8.5 to
    // 9.5); from X9.5 on the orientation is the programmed one.
    let (_, samples) = run_with(
        DATA,
        &program(|i| match i {
            1 => "ORISON ",
            11 => "ORISOF ",
            _ => "",
        }),
    );
    let z = on_zigzag(&samples);
    let before = z.iter().filter(|s| s.0 < 9.5).map(|s| s.2).fold(0.0, f64::max);
    let after = z.iter().filter(|s| s.0 > 9.5 + 1e-6).map(|s| s.2).fold(0.0, f64::max);
    assert!(before > 0.7, "{before}°");
    assert!(after < 1e-6, "{after}°");
}

#[test]
fn without_memory_for_orison_or_a_tolerance_nothing_is_smoothed() {
    // MD28590 below 4 (the default 0) or SD42678 0 (its default): the programmed orientation.
    for data in ["$SC_ORISON_TOL=1\n$SC_ORISON_DIST=5\n", "$MC_MM_ORISON_BLOCKS=10\n$SC_ORISON_DIST=5\n"] {
        let (_, samples) = run_with(data, &program(|i| if i == 1 { "ORISON " } else { "" }));
        let dev = on_zigzag(&samples).iter().map(|s| s.2).fold(0.0, f64::max);
        assert!(dev < 1e-6, "{data}: {dev}°");
    }
}

#[test]
fn corners_of_the_tip_path_are_still_rounded_by_g642() {
    // The tip zig-zags too: Y ±0.1 mm at every block end (a corner of about 11.3° each), under
    // G642 CTOL=0.01 OTOL=0.5 with ORISON: the corners are rounded within CTOL of the
    // programmed polyline (the tip does not leave it by more), the smoothed orientation goes
    // through the rounding element (within ORISON_TOL + OTOL of the programmed one), and every
    // machine axis keeps its limits.
    let y = |i: usize| if i.is_multiple_of(2) { 0.0 } else { 0.1 };
    let mut p = String::from("T1 D1\nG0 X0 Y0 Z100 A20 C90\nTRAORI\nG4 F0.02\n");
    p +=
        &format!("ORIWKS ORIVECT G0 X0 Y0 Z50 {}\nG4 F0.02\nORISON G642 CTOL=0.01 OTOL=0.5 G1 F600\n", vector(o(-2.0)));
    for i in 1..=BLOCKS {
        p += &format!("X{i} Y{} {}\n", y(i), vector(o(theta_at_end(i))));
    }
    p += "M30";
    let (ch, samples) = run_with(DATA, &p);
    let pts: Vec<[f64; 3]> = (0..=BLOCKS).map(|i| [i as f64, y(i), 50.0]).collect();
    let tips: Vec<[f64; 3]> = samples.iter().map(tip).filter(|t| t[0] > 1e-6).collect();
    let off = tips.iter().map(|&t| to_polyline(t, &pts)).fold(0.0, f64::max);
    assert!(off <= 0.01 + 1e-6, "{off}");
    // The rounding really happened: some tip passes a corner at more than 1 µm.
    let at_corners = (1..BLOCKS)
        .map(|i| {
            tips.iter()
                .map(|t| ((t[0] - i as f64).powi(2) + (t[1] - y(i)).powi(2)).sqrt())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    assert!(at_corners > 1e-3, "{at_corners}");
    let dev = on_zigzag(&samples).iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(dev <= 1.5 + 1e-6 && dev > 0.5, "{dev}°");
    assert_machine_limits(&ch, &samples);
}

#[test]
fn osof_is_accepted_and_the_other_functions_of_g_group_34_are_refused_by_name() {
    // G group 34 (orientation smoothing at block transitions): OSOF, its reset value, runs
    // the zig-zag exactly as without it (bit for bit); OSC, OSS, OSSE, OSD and OST are not
    // modelled: the run stops with 12550 naming the function at its line (2), as a control
    // without the function does, and the static name check flags the same line beforehand.
    let (_, plain) = run_with(DATA, &program(|_| ""));
    let (_, osof) = run_with(DATA, &program(|i| if i == 1 { "OSOF " } else { "" }));
    assert!(plain == osof, "OSOF changed the motion");
    for f in ["OSC", "OSS", "OSSE", "OSD", "OST"] {
        let text = format!("G1 X1 F600\n{f}\nG1 X2\nM30");
        let mut ch = Channel::from_preset("mill5-head-ca", DATA).unwrap();
        let flagged: Vec<(u32, u32)> =
            nctwin_engine::check::names(&text, &ch.name_context()).iter().map(|d| (d.alarm, d.line)).collect();
        assert_eq!(flagged, vec![(12550, 2)], "{f}");
        ch.run_program(&text).unwrap();
        for _ in 0..100_000 {
            if !ch.is_busy() {
                break;
            }
            ch.step();
        }
        let alarm = ch.alarms().first().unwrap_or_else(|| panic!("{f} ran"));
        assert_eq!((alarm.number, alarm.line), (12550, Some(2)), "{f}");
        assert!(alarm.message.contains(&format!("name {f} not defined")), "{}", alarm.message);
    }
    // And OSOF is known to the name check.
    let ch = Channel::from_preset("mill5-head-ca", DATA).unwrap();
    assert!(nctwin_engine::check::names("OSOF\nG1 X1 F600\nM30", &ch.name_context()).is_empty());
}
