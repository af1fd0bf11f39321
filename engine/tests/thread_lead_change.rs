//! G34/G35: threads with increasing or decreasing lead (Programming Manual "Fundamentals").
//! K is the lead at the start, F the change per revolution (mm/rev²): after n revolutions the
//! lead is P0 ± F·n and the tool has travelled P0·n ± F·n²/2.
//!
//! Worked by hand on the lathe (S600 = 10 rev/s): `G34 Z-12 K2 F0.5` from Z0 takes
//! 2n + n²/4 = 12, n = 4 revolutions, and ends with the lead 2 + 0.5·4 = 4 mm (the manual's
//! F = (Pe² − P0²)/(2·Z) = (16 − 4)/24 = 0.5). At Z-6 it has turned n = 2·(√10 − 2) = 2.3246
//! revolutions and the lead is 2 + 0.5·2.3246 = √10 = 3.1623 mm, so the tool moves
//! 31.623 mm/s there. `G35 Z-12 K4 F0.5` is the same thread backwards in its lead: 4
//! revolutions, lead 4 at the start and 2 at the end, again √10 at Z-6.
//!
//! NCTwin runs the block as one move per revolution (`lead_change.rs`): revolution k has the
//! mean lead P0 ± F·(k + ½) and ends exactly where z(k + 1) says. For G34 the revolutions end
//! at Z0, -2.25, -5, -8.25, -12 (leads 2.25, 2.75, 3.25, 3.75); for G35 at Z0, -3.75, -7,
//! -9.75, -12 (leads 3.75, 3.25, 2.75, 2.25). The assertions take those values; each lies
//! within F/2 = 0.25 of the exact lead.

use nctwin_engine::Channel;

fn channel(program: &str) -> Channel {
    let mut ch = Channel::from_preset("lathe-2axis", "").unwrap();
    ch.run_program(program).unwrap();
    ch
}

fn z(ch: &Channel) -> f64 {
    ch.axis_positions()[1]
}

fn spindle_angle(ch: &Channel) -> f64 {
    ch.snapshot().spindle_states.iter().find(|(_, s)| s.number == 1).unwrap().1.position
}

/// Lead (mm/rev) where the tool passes `at`: path speed over spindle speed (10 rev/s).
fn lead_at(program: &str, at: f64) -> f64 {
    let mut ch = channel(program);
    for _ in 0..2_000_000 {
        ch.step();
        if z(&ch) < at {
            break;
        }
    }
    let z0 = z(&ch);
    ch.step();
    (z0 - z(&ch)) / ch.config().ipo_cycle / 10.0
}

/// Spindle revolutions while Z travels from `from` to `to` (both inside the thread), the
/// angle interpolated within the cycles that cross them.
fn revolutions_between(program: &str, from: f64, to: f64) -> f64 {
    let mut ch = channel(program);
    // Unwrapped spindle angle (degrees) and Z after each cycle.
    let (mut turned, mut last_angle, mut last_z) = (0.0, spindle_angle(&ch), z(&ch));
    let mut at_from = None;
    for _ in 0..2_000_000 {
        ch.step();
        let a = spindle_angle(&ch);
        let step = (a - last_angle).rem_euclid(360.0);
        let zn = z(&ch);
        // The angle where the cycle's Z crosses `target`.
        let cross = |target: f64| turned + step * (last_z - target) / (last_z - zn);
        if at_from.is_none() && zn < from {
            at_from = Some(cross(from));
        }
        if zn <= to {
            return (cross(to) - at_from.unwrap()) / 360.0;
        }
        turned += step;
        last_angle = a;
        last_z = zn;
    }
    panic!("Z never reached {to}");
}

const G34: &str = "S600 M3\nG0 X20 Z5\nG4 F1\nG1 Z0 F1000\nG34 Z-12 K2 F0.5\nG0 X30\nM30\n";
const G35: &str = "S600 M3\nG0 X20 Z5\nG4 F1\nG1 Z0 F1000\nG35 Z-12 K4 F0.5\nG0 X30\nM30\n";

#[test]
fn g34_lead_grows_by_f_per_revolution() {
    // Z-6 lies in revolution 2 (exact lead √10 = 3.162): 2 + 0.5·2.5 = 3.25.
    for (at, lead) in [(-0.5, 2.25), (-3.5, 2.75), (-6.0, 3.25), (-11.5, 3.75)] {
        let p = lead_at(G34, at);
        assert!((p - lead).abs() < 1e-6, "lead at Z{at}: {p}, want {lead}");
    }
}

#[test]
fn g35_lead_shrinks_by_f_per_revolution() {
    for (at, lead) in [(-0.5, 3.75), (-6.0, 3.25), (-8.0, 2.75), (-11.5, 2.25)] {
        let p = lead_at(G35, at);
        assert!((p - lead).abs() < 1e-6, "lead at Z{at}: {p}, want {lead}");
    }
}

#[test]
fn the_spindle_turns_the_revolutions_of_the_lead_law() {
    // From Z-2 to Z-10 under G34. Exactly: n(z) = 2(√(4 + z) − 2), n(10) − n(2) =
    // 2(√14 − √6) = 2.5843. By revolutions: Z-2 is 2/2.25 = 0.8889 into revolution 0, Z-10 is
    // 1.75/3.75 = 0.4667 into revolution 3: 3.4667 − 0.8889 = 2.5778 (equal at the seams).
    // The planner slows for about one IPO cycle at every crossing from one move into the next
    // (chained G1 and G33 blocks too), while the spindle turns on: two seams here cost up to
    // 2 · 0.004 s · 10 rev/s = 0.08 revolutions more.
    let n = revolutions_between(G34, -2.0, -10.0);
    let want = 3.0 + 1.75 / 3.75 - 2.0 / 2.25;
    assert!(n >= want - 1e-3 && n < want + 0.08, "revolutions {n}, want {want}");
}

#[test]
fn g35_whose_lead_falls_to_zero_is_refused() {
    // K1 F0.5 over 12 mm: P² = 1 − 2·0.5·12 < 0 (the lead is 0 after 1 mm).
    let mut ch = channel("S600 M3\nG0 X20 Z5\nG35 Z-12 K1 F0.5\nM30\n");
    for _ in 0..100_000 {
        if !ch.is_busy() {
            break;
        }
        ch.step();
    }
    let alarms: Vec<_> = ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect();
    assert_eq!(alarms, vec![(12560, Some(3))]);
}
