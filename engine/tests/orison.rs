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

use crate::head_support;
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

/// MD28590 10 (sections reach up to 4 blocks either side), SD42678 1°, SD42680 1 mm.
const DATA: &str = "$MC_MM_ORISON_BLOCKS=10\n$SC_ORISON_TOL=1\n$SC_ORISON_DIST=1\n";

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
    // ORISON with SD42678 1° and SD42680 1 mm: each block end's step (±8°/mm: from +4°/mm to
    // −4°/mm or back) is smoothed over r = 0.5 mm each side (half of SD42680; the sections of
    // neighbouring steps just touch). At distance x from the nearest block end the correction
    // is 8°/mm·bump(x, r) with bump = (r/3 + x²/r − |x|³/(3r²) − |x|)/2: 8·r/6 = 0.667° at
    // the block end (θ = ±1.333° against the programmed ±2°), 0 at the block middles. Its
    // second derivative 8·(1/r − |x|/r²) is at most 16°/mm² (at the block end): the rate
    // changes by 0.32°/mm between samples 0.02 mm apart (F600, 2 ms), never the ORISOF jump.
    let (ch, samples) = run_with(DATA, &program(|i| if i == 1 { "ORISON " } else { "" }));
    let z = on_zigzag(&samples);
    // No section before X0.5 or after X19.5 (the run starts and ends with an exact stop).
    for &(x, _, dev) in &z {
        let d = (x - x.round()).abs();
        let expected = if x < 0.5 || x > BLOCKS as f64 - 0.5 {
            0.0
        } else {
            let r = 0.5;
            8.0 * 0.5 * (r / 3.0 + d * d / r - d.powi(3) / (3.0 * r * r) - d)
        };
        assert!((dev - expected).abs() < 2e-3, "X{x}: {dev}° against {expected}°");
    }
    let dev = z.iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(dev <= 2.0 / 3.0 + 1e-3 && dev > 0.6, "largest deviation {dev}°");
    for i in 2..BLOCKS - 1 {
        let near = z.iter().min_by(|a, b| (a.0 - i as f64).abs().total_cmp(&(b.0 - i as f64).abs())).unwrap();
        assert!((near.1.abs() - 4.0 / 3.0).abs() < 0.01, "block end {i}: θ {}", near.1);
    }
    let r = rates(&z);
    let worst = r.windows(2).map(|w| (w[1].1 - w[0].1).abs()).fold(0.0, f64::max);
    assert!(worst < 0.5, "the rate jumps by {worst}°/mm");
    // The tip stays on the programmed line, as without ORISON.
    assert!(off_line(&samples) < 1e-6, "{}", off_line(&samples));
    assert_machine_limits(&ch, &samples);
}

#[test]
fn a_tighter_tolerance_keeps_the_orientation_closer() {
    // SD42678 0.5°: the sections shrink until the deviation (8°/mm·r/6 = 1.333° per mm of
    // half section) keeps 0.5°: at most 0.5°, more than 0.4° (one shortening step from
    // r = 0.5 by 0.95·0.4995/0.667 lands at r = 0.356 mm, 0.474°).
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
    // ORISON for blocks 1..10, ORISOF from block 11: the last section is the one at X9 (X 8.5
    // to 9.5; none at X10, whose next block is not smoothed); from X9.5 on the orientation is
    // the programmed one.
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
    assert!(before > 0.6, "{before}°");
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

/// A run under ORISON along X from X0 at θ `start`: block i ends at `ends[i]` = (X, θ).
fn profile_program(start: f64, ends: &[(f64, f64)]) -> String {
    let mut p = String::from("T1 D1\nG0 X0 Y0 Z100 A20 C90\nTRAORI\nG4 F0.02\n");
    p += &format!("ORIWKS ORIVECT G0 X0 Y0 Z50 {}\nG4 F0.02\nORISON G64 G1 F600\n", vector(o(start)));
    for &(x, theta) in ends {
        p += &format!("X{x} {}\n", vector(o(theta)));
    }
    p + "M30"
}

/// (x, θ, angle from the programmed orientation in degrees) of the samples on that run.
fn on_profile(samples: &[[f64; 5]], start: f64, ends: &[(f64, f64)]) -> Vec<(f64, f64, f64)> {
    let programmed = |x: f64| {
        let mut prev = (0.0, start);
        for &e in ends {
            if x <= e.0 {
                return prev.1 + (x - prev.0) / (e.0 - prev.0) * (e.1 - prev.1);
            }
            prev = e;
        }
        prev.1
    };
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

/// The bump of `motion::orison` (degrees per °/mm of step): (r/3 + x²/r − |x|³/(3r²) − |x|)/2.
fn bump(x: f64, r: f64) -> f64 {
    let a = x.abs();
    if a >= r { 0.0 } else { 0.5 * (r / 3.0 + x * x / r - a.powi(3) / (3.0 * r * r) - a) }
}

#[test]
fn a_section_reaches_over_several_short_blocks_as_far_as_md28590_allows() {
    // 0.25 mm blocks, θ rising 0.1° per block to 1° at X2.5, then falling back: one step of
    // −0.8°/mm at X2.5 (every other block end has no kink: nothing to smooth there). With
    // SD42680 1 mm and MD28590 10 (4 blocks either side) the section is r = 0.5 mm, over the
    // four blocks X2..X3: the deviation 0.8·bump(x − 2.5, 0.5), 0.8·0.5/6 = 0.0667° at the
    // step. MD28590 4 (the least) lets a section reach one block either side: r = 0.25 mm,
    // 0.0333° at the step, nothing before X2.25 or after X2.75.
    let ends: Vec<(f64, f64)> = (1..=20)
        .map(|i| (0.25 * f64::from(i), if i <= 10 { 0.1 * f64::from(i) } else { 0.1 * f64::from(20 - i) }))
        .collect();
    for (blocks, r) in [(10, 0.5), (4, 0.25)] {
        let data = format!("$MC_MM_ORISON_BLOCKS={blocks}\n$SC_ORISON_TOL=1\n$SC_ORISON_DIST=1\n");
        let (ch, samples) = run_with(&data, &profile_program(0.0, &ends));
        let z = on_profile(&samples, 0.0, &ends);
        for &(x, _, dev) in &z {
            let expected = 0.8 * bump(x - 2.5, r);
            assert!((dev - expected).abs() < 1e-4, "MD28590 {blocks}, X{x}: {dev}° against {expected}°");
        }
        // The sample nearest the step is at most 0.01 mm off (F600: 0.02 mm per cycle), where
        // bump's slope of −½ takes 0.8·0.01/2 = 0.004° off the peak.
        let largest = z.iter().map(|s| s.2).fold(0.0, f64::max);
        assert!(largest <= 0.8 * r / 6.0 + 1e-4 && largest > 0.8 * r / 6.0 - 0.0045, "MD28590 {blocks}: {largest}°");
        // The section spans 2r of path: deviations over 4 (2) blocks, none beyond.
        let span = z.iter().filter(|s| s.2 > 1e-6).map(|s| s.0);
        let (lo, hi) = span.fold((f64::INFINITY, 0.0f64), |(lo, hi), x| (lo.min(x), hi.max(x)));
        assert!(lo > 2.5 - r - 0.03 && hi < 2.5 + r + 0.03 && hi - lo > 2.0 * r - 0.1, "{lo}..{hi}");
        let worst = rates(&z).windows(2).map(|w| (w[1].1 - w[0].1).abs()).fold(0.0, f64::max);
        assert!(worst < 0.1, "MD28590 {blocks}: the rate jumps by {worst}°/mm");
        assert!(off_line(&samples) < 1e-6);
        assert_machine_limits(&ch, &samples);
    }
}

/// 0.25 mm blocks whose θ zig-zags ±0.1° (the tool vector alternating every block, as in
/// the manual's example), from X0 at −0.1°.
fn wobble(blocks: usize) -> Vec<(f64, f64)> {
    (1..=blocks).map(|i| (0.25 * i as f64, if i % 2 == 1 { 0.1 } else { -0.1 })).collect()
}

#[test]
fn a_wobble_on_short_blocks_is_flattened_over_many_blocks() {
    // SD42678 0.2°, SD42680 1 mm, MD28590 10: every step (±1.6°/mm) gets r = 0.5 mm, two
    // blocks either side (the first, at X0.25, 0.25: the run starts at X0; the last likewise).
    // Where only full sections overlap (X0.75 to X5.25 of 6 mm) their sum is the zig-zag
    // averaged twice over 0.5 mm, its period: the mean, θ = 0 (`motion::orison`'s test): the
    // tool stands still over 18 blocks of the programmed ±0.8°/mm, 0.1° from the programmed
    // orientation at every block end. Everywhere within 0.2°, and the rate never jumps (the
    // largest change between samples 0.02 mm apart: 1.6°/mm·(1/0.25)·0.02 = 0.128°/mm at the
    // first section; without ORISON 1.6°/mm at every block end).
    let ends = wobble(24);
    let data = "$MC_MM_ORISON_BLOCKS=10\n$SC_ORISON_TOL=0.2\n$SC_ORISON_DIST=1\n";
    let (ch, samples) = run_with(data, &profile_program(-0.1, &ends));
    let z = on_profile(&samples, -0.1, &ends);
    let largest = z.iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(largest <= 0.2, "{largest}°");
    for &(x, theta, dev) in z.iter().filter(|s| (0.75..=5.25).contains(&s.0)) {
        assert!(theta.abs() < 2e-3, "X{x}: θ {theta}°");
        // So the deviation is the programmed |θ|: 0.1° less 0.8°/mm per mm to the block end.
        let to_end = (x / 0.25 - (x / 0.25).round()).abs() * 0.25;
        assert!((dev - (0.1 - 0.8 * to_end)).abs() < 2e-3, "X{x}: {dev}°");
    }
    let worst = rates(&z).windows(2).map(|w| (w[1].1 - w[0].1).abs()).fold(0.0, f64::max);
    assert!(worst < 0.2, "the rate jumps by {worst}°/mm");
    assert!(off_line(&samples) < 1e-6);
    assert_machine_limits(&ch, &samples);
}

#[test]
fn a_block_longer_than_md20178_interrupts_the_smoothing() {
    // The wobble of 8 blocks, a 2 mm block (X2 to X4, −0.1° to +0.1°) and 8 more; MD20178
    // 1 mm: the long block is not smoothed and no step at its ends is: its orientation is the
    // programmed one over the whole block and its rate steps at X2 (−0.8 to +0.1°/mm) and X4
    // (+0.1 to −0.8°/mm) as programmed. Each short run is smoothed on its own: flat (θ = 0)
    // where only full sections overlap, X0.75 to X1.25 and X4.75 to X5.25.
    let mut ends = wobble(8);
    ends.push((4.0, 0.1));
    ends.extend(wobble(8).into_iter().map(|(x, t)| (x + 4.0, -t)));
    let data = "$MC_MM_ORISON_BLOCKS=10\n$SC_ORISON_TOL=0.2\n$SC_ORISON_DIST=1\n$MC_ORISON_BLOCK_PATH_LIMIT=1\n";
    let (_, samples) = run_with(data, &profile_program(-0.1, &ends));
    let z = on_profile(&samples, -0.1, &ends);
    let on_long = z.iter().filter(|s| (2.0..=4.0).contains(&s.0)).map(|s| s.2).fold(0.0, f64::max);
    assert!(on_long < 1e-6, "{on_long}°");
    let r = rates(&z);
    for x in [2.0, 4.0] {
        let jump = rate_jump_near(&r, x);
        assert!(jump > 0.4, "X{x}: {jump}°/mm");
    }
    for &(x, theta, _) in z.iter().filter(|s| (0.75..=1.25).contains(&s.0) || (4.75..=5.25).contains(&s.0)) {
        assert!(theta.abs() < 2e-3, "X{x}: θ {theta}°");
    }
    assert!(z.iter().map(|s| s.2).fold(0.0, f64::max) <= 0.2);
}

#[test]
fn single_block_smooths_into_no_block_not_yet_released() {
    // In single block each block is released alone, after the last has stopped: no step is
    // decided (its section would reach into the next block, not released), so the wobble
    // runs as programmed, with every block's stop.
    let ends = wobble(8);
    let data = "$MC_MM_ORISON_BLOCKS=10\n$SC_ORISON_TOL=0.2\n$SC_ORISON_DIST=1\n";
    let mut ch = Channel::from_preset("mill5-head-ca", data).unwrap();
    ch.single_block = true;
    ch.run_program(&profile_program(-0.1, &ends)).unwrap();
    let mut samples = Vec::new();
    while ch.is_busy() || ch.status() == nctwin_engine::Status::Stopped {
        if ch.status() == nctwin_engine::Status::Stopped {
            ch.start().unwrap();
        }
        ch.step();
        let p = ch.axis_positions();
        samples.push([p[0], p[1], p[2], p[3], p[4]]);
        assert!(samples.len() < 2_000_000, "the program does not end");
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let z = on_profile(&samples, -0.1, &ends);
    assert!(z.last().is_some_and(|s| (s.0 - 2.0).abs() < 1e-9), "{:?}", z.last());
    let dev = z.iter().map(|s| s.2).fold(0.0, f64::max);
    assert!(dev < 1e-6, "{dev}°");
}
