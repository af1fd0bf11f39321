//! Running a channel in the tests of manual operation: create it from a preset, step it until
//! nothing moves.

use nctwin_engine::{Channel, Snapshot};

pub fn channel(preset: &str, md: &str) -> Channel {
    Channel::from_preset(preset, md).expect("preset")
}

/// Steps until nothing moves; returns the channel-axis positions of every cycle.
pub fn settle(ch: &mut Channel) -> Vec<Vec<f64>> {
    let mut samples = Vec::new();
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            return samples;
        }
        ch.step();
        samples.push(ch.axis_positions().to_vec());
    }
    panic!("the channel never came to rest");
}

/// Steps `n` IPO cycles.
pub fn steps(ch: &mut Channel, n: usize) {
    for _ in 0..n {
        ch.step();
    }
}

/// Steps until nothing moves (a program's end).
pub fn run_to_end(ch: &mut Channel) {
    settle(ch);
}

/// Creates a channel from a preset, starts `program` and steps it until nothing moves; returns
/// the channel and the snapshot of every cycle.
pub fn run_snapshots(preset: &str, md: &str, program: &str) -> (Channel, Vec<Snapshot>) {
    let mut ch = channel(preset, md);
    ch.run_program(program).expect("program starts");
    let mut samples = Vec::new();
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            return (ch, samples);
        }
        ch.step();
        samples.push(ch.snapshot());
    }
    panic!("the program never came to rest");
}

/// The machine position of the channel axis `name` in a snapshot.
pub fn machine_axis(s: &Snapshot, name: &str) -> f64 {
    s.machine.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("no axis {name}")).1
}

/// Runs `program` on `ch` until nothing moves; panics when it does not start or does not end
/// within two million IPO cycles (it may end with an alarm).
pub fn finish(ch: &mut Channel, program: &str) {
    ch.run_program(program).unwrap_or_else(|e| panic!("not started: {e}"));
    for _ in 0..2_000_000 {
        if !ch.is_busy() {
            return;
        }
        ch.step();
    }
    panic!("the program does not end");
}

/// A channel of `preset` with `md` on top that ran `program` to its end (see [`finish`]).
pub fn ran(preset: &str, md: &str, program: &str) -> Channel {
    let mut ch = channel(preset, md);
    finish(&mut ch, program);
    ch
}

/// Asserts that the channel stands idle without an alarm.
pub fn assert_ok(ch: &Channel) {
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert_eq!(s.status, nctwin_engine::Status::Idle);
}
