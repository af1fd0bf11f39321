//! Cartesian PTP with TRANSMIT: `STAT=` resolves the ambiguity of the pole (Transformations
//! FM, Cartesian PTP travel, TRANSMIT; issue 25). On the manual's example lathe (radial axis
//! XM, C axis CM, no offsets, ROT_SIGN_IS_PLUS) the face point (x, y) is XM = ±r with
//! CM = polar angle (+180° for the negative side). From X10 C0 to the opposite point X−10 Y0
//! the CP line passes the pole, and the end has two machine positions:
//! - through the pole: XM −10, CM 0 (STAT bit 1 = 0 with POLE_SIDE_FIX 0, as CP would go);
//! - rotation in the pole: XM +10, CM ±180 (bit 1 = 1, or POLE_SIDE_FIX 1/2), bit 0 choosing
//!   +180° (0) or −180° (1).
//!
//! Bit 1's meaning is not in the manual's excerpt: decided as above (README, limits).

use nctwin_engine::{Channel, Snapshot, Status};

/// Runs to the M0; the C positions of every cycle and the final snapshot.
fn run(md: &str, ptp_block: &str) -> (Snapshot, Vec<f64>) {
    let program = format!("G0 X10\nTRANSMIT\nPTP\n{ptp_block}\nM0\nM30");
    let mut ch = Channel::from_preset("transmit-example", md).unwrap();
    ch.run_program(&program).unwrap();
    let mut c = Vec::new();
    while ch.is_busy() && ch.status() != Status::Stopped {
        ch.step();
        c.push(ch.axis_positions()[1]);
        assert!(c.len() < 1_000_000);
    }
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    (s, c)
}

fn machine(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap().1
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn stat_0_travels_through_the_pole_without_pole_side_fix() {
    let (s, c) = run("", "G1 F2000 X-10 Y0 STAT=0");
    assert!(close(machine(&s, "XM"), -10.0), "{}", machine(&s, "XM"));
    assert!(c.iter().all(|&c| close(c, 0.0)), "C keeps its angle");
}

#[test]
fn stat_bit_1_rotates_in_the_pole_in_the_sense_of_bit_0() {
    let (s, c) = run("", "G1 F2000 X-10 Y0 STAT=2");
    assert!(close(machine(&s, "XM"), 10.0), "{}", machine(&s, "XM"));
    assert!(close(*c.last().unwrap(), 180.0), "{c:?}");
    assert!(c.windows(2).all(|w| w[1] >= w[0] - 1e-12), "C turns positive");
    let (s, c) = run("", "G1 F2000 X-10 Y0 STAT=3");
    assert!(close(machine(&s, "XM"), 10.0));
    assert!(close(*c.last().unwrap(), -180.0), "{c:?}");
    assert!(c.windows(2).all(|w| w[1] <= w[0] + 1e-12), "C turns negative");
}

#[test]
fn with_pole_side_fix_bit_0_alone_chooses_the_direction() {
    let md = "$MC_TRANSMIT_POLE_SIDE_FIX_1=1";
    let (s, c) = run(md, "G1 F2000 X-10 Y0 STAT=0");
    assert!(close(machine(&s, "XM"), 10.0) && close(*c.last().unwrap(), 180.0), "{c:?}");
    let (s, c) = run(md, "G1 F2000 X-10 Y0 STAT=1");
    assert!(close(machine(&s, "XM"), 10.0) && close(*c.last().unwrap(), -180.0), "{c:?}");
}

/// Away from the pole the point has the one position the block reaches anyway: (0, 10) from
/// X10 C0 is XM 10, CM 90 (the other side, XM −10 CM −90, moves the radial axis 20 mm more).
#[test]
fn away_from_the_pole_stat_changes_nothing() {
    for stat in ["", " STAT=0", " STAT=2", " STAT=3"] {
        let (s, c) = run("", &format!("G1 F2000 X0 Y10{stat}"));
        assert!(close(machine(&s, "XM"), 10.0) && close(*c.last().unwrap(), 90.0), "{stat}: {c:?}");
    }
}
