//! The manual's example programs for transformations defined by kinematic chains (Transformations
//! FM, K12 4.4.2–4.4.5) as fixtures in `programs/k12/`. The manual summary quotes them only in
//! part, so each fixture keeps the quoted lines and completes the machine (see its header); they
//! run unchanged through a channel, with the positions at each M0 worked out by hand below.

use nctwin_engine::machine_data::MachineData;
use nctwin_engine::{Channel, Snapshot, Status};

/// Channel axes X, Y, Z, A, B, C on machine axes X1..C1, C modulo.
const SIX: &str =
    "$MA_IS_ROT_AX[A1]=TRUE\n$MA_IS_ROT_AX[B1]=TRUE\n$MA_IS_ROT_AX[C1]=TRUE\n$MA_ROT_IS_MODULO[C1]=TRUE\n";

fn six() -> Channel {
    let mut md = MachineData::default();
    md.apply_text(SIX).unwrap();
    Channel::new(md).unwrap()
}

/// Steps until the channel rests (an M0 or the end) and returns the snapshot.
fn rest(ch: &mut Channel) -> Snapshot {
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < 2_000_000, "program does not come to rest");
    }
    ch.snapshot()
}

/// Machine positions of the named axes at the current rest.
fn at(s: &Snapshot, names: &[&str]) -> Vec<f64> {
    names
        .iter()
        .map(|n| s.machine.iter().find(|(a, _)| a == n).unwrap_or_else(|| panic!("no axis {n}: {:?}", s.machine)).1)
        .collect()
}

fn near(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
}

/// Runs `program` and checks the machine positions of `names` at each M0, then the end.
fn check(mut ch: Channel, program: &str, names: &[&str], stops: &[(&[f64], Option<u32>)]) {
    ch.run_program(program).unwrap();
    for (i, (expected, trafo_type)) in stops.iter().enumerate() {
        if i > 0 {
            ch.start().unwrap();
        }
        let s = rest(&mut ch);
        assert!(s.alarms.is_empty(), "stop {i}: {:?}", s.alarms);
        let got = at(&s, names);
        assert!(near(&got, expected), "stop {i}: {got:?} vs {expected:?}");
        assert_eq!(s.transformation.map(|t| t.trafo_type), *trafo_type, "stop {i}");
    }
    ch.start().unwrap();
    let s = rest(&mut ch);
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
}

#[test]
fn traori_dyn_c_b_example() {
    // Tool reference point at C = B = 0: M + (200, 0, 300) + (0, 0, −100) + (0, 0, −50), so the
    // tip (10, 0, 0) needs M = (−190, 0, −150). B90 with the tip held: the 50 below B turn to
    // (−50, 0, 0) (R_y(90°)·(0, 0, −50)), so M + (200, 0, 200) + (−50, 0, 0) = (10, 0, 0)
    // ⇒ M = (−140, 0, −200). The head of B and C is the generic type 24.
    let program = include_str!("programs/k12/traori_dyn_cb.mpf");
    check(
        six(),
        program,
        &["X1", "Y1", "Z1", "B1", "C1"],
        &[(&[-190.0, 0.0, -150.0, 0.0, 0.0], Some(24)), (&[-140.0, 0.0, -200.0, 90.0, 0.0], Some(24))],
    );
}

#[test]
fn transmit_example() {
    // Transmit_1 (256): the tool turns +C about +Z relative to the workpiece (C1 turns it about
    // −Z), no offsets: X20 Y20 is the radial position √800 = 28.2843 at C = 45°, Y1 stays 0.
    // Transmit_2 (257) with the real Y at 5 (G0 Y5 before): X0 Y30 needs √(30² − 5²) = √875 on
    // the radial axis at φ = 90° − atan2(5, √875) = 80.4059° (the side nearer C = 45°).
    let program = include_str!("programs/k12/transmit.mpf");
    let phi = 90.0 - 5f64.atan2(875f64.sqrt()).to_degrees();
    check(
        six(),
        program,
        &["X1", "Y1", "Z1", "C1"],
        &[(&[800f64.sqrt(), 0.0, 5.0, 45.0], Some(256)), (&[875f64.sqrt(), 5.0, 5.0, phi], Some(257))],
    );
}

#[test]
fn tracyl_example() {
    // d = 40: Y31.4159 is a quarter of the circumference, C = 90°; X20 radial, Z−10, YM stays 0.
    let program = include_str!("programs/k12/tracyl.mpf");
    let ch = Channel::from_preset("tracyl-xyzc", "").unwrap();
    check(ch, program, &["XM", "YM", "ZM", "CM"], &[(&[20.0, 0.0, -10.0, 90.0], Some(513))]);
}

#[test]
fn traang_example() {
    // MU runs along (1, 0, 1)/√2 (45°): X50 needs MU = 50/cos 45° = 70.7107, which also moves
    // Z by 50, so MZ = 20 − 50 = −30.
    let program = include_str!("programs/k12/traang.mpf");
    let ch = Channel::from_preset("traang-grinder", "").unwrap();
    check(ch, program, &["MU", "MZ"], &[(&[50.0 * 2f64.sqrt(), -30.0], Some(1024))]);
}
