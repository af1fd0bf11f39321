//! Shared harness of the standard-cycle tests: runs a program on a preset and records the
//! workpiece position of every IPO cycle, so that tests check the path a cycle produces.
#![allow(dead_code)]

use nctwin_engine::Channel;
use nctwin_engine::alarm::Alarm;

const MAX_TICKS: usize = 5_000_000;

/// One IPO cycle: simulated time, the WCS positions X, Y, Z (in the frame in force, which
/// inside a cycle may be the cycle's own) and the BCS positions (the caller's WCS while it has
/// no frame).
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub t: f64,
    pub p: [f64; 3],
    pub b: [f64; 3],
}

/// What a run leaves: the channel at rest, every cycle's sample and the alarms raised.
pub struct Trace {
    pub ch: Channel,
    pub samples: Vec<Sample>,
    pub alarms: Vec<Alarm>,
}

/// Runs `main` on `preset` with `subs` stored; steps until the channel rests.
pub fn run_on(preset: &str, main: &str, subs: &[(&str, &str)]) -> Trace {
    let mut ch = Channel::from_preset(preset, "").unwrap();
    for (name, text) in subs {
        ch.store_program(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
    ch.run_program(main).unwrap_or_else(|e| panic!("not started: {e}"));
    let mut samples = vec![sample(&ch)];
    while ch.is_busy() {
        ch.step();
        samples.push(sample(&ch));
        assert!(samples.len() < MAX_TICKS, "program does not end");
    }
    let alarms = ch.snapshot().alarms;
    Trace { ch, samples, alarms }
}

/// Runs `main` on the 3-axis mill (T1 D1: end mill R5, T2 D1: drill R4).
pub fn run(main: &str) -> Trace {
    run_on("mill-3axis", main, &[])
}

/// Runs `main` and fails the test on any alarm.
pub fn run_clean(main: &str) -> Trace {
    let t = run(main);
    assert!(t.alarms.is_empty(), "alarms: {:?}", t.alarms);
    t
}

fn sample(ch: &Channel) -> Sample {
    let s = ch.snapshot();
    let get = |l: &[(String, f64)], n: &str| l.iter().find(|(a, _)| a == n).map_or(f64::NAN, |a| a.1);
    let w = |n| get(&s.workpiece, n);
    let b = |n| get(&s.basic, n);
    Sample { t: s.time, p: [w("X"), w("Y"), w("Z")], b: [b("X"), b("Y"), b("Z")] }
}

impl Trace {
    /// The positions where axis `k` reverses direction (or starts or ends), with consecutive
    /// equal values merged: the bottoms of pecks and the heights of retractions.
    pub fn turning_points(&self, k: usize) -> Vec<f64> {
        let mut v: Vec<f64> = Vec::new();
        for s in &self.samples {
            let x = s.p[k];
            if v.last().is_none_or(|l| (l - x).abs() > 1e-9) {
                v.push(x);
            }
        }
        let mut out = Vec::new();
        for (i, &x) in v.iter().enumerate() {
            let turn = i == 0 || i + 1 == v.len() || (x - v[i - 1]).signum() != (v[i + 1] - x).signum();
            if turn {
                out.push(x);
            }
        }
        out
    }

    /// The longest time the tool stands still at a position where axis `k` is within 1e-6 of `at`.
    pub fn dwell_at(&self, k: usize, at: f64) -> f64 {
        let (mut best, mut start): (f64, Option<(f64, [f64; 3])>) = (0.0, None);
        for s in &self.samples {
            match start {
                Some((t0, p0)) if p0.iter().zip(&s.p).all(|(a, b)| (a - b).abs() < 1e-9) => {
                    best = best.max(s.t - t0);
                }
                _ => start = ((s.p[k] - at).abs() < 1e-6).then_some((s.t, s.p)),
            }
        }
        best
    }

    /// The final WCS position.
    pub fn end(&self) -> [f64; 3] {
        self.samples.last().unwrap().p
    }

    /// The (X, Y) positions where the tool reaches its lowest Z within each dip below `below`.
    pub fn holes(&self, below: f64) -> Vec<[f64; 3]> {
        let mut out = Vec::new();
        let mut dip: Option<[f64; 3]> = None;
        for s in &self.samples {
            if s.p[2] < below {
                dip = Some(match dip {
                    Some(d) if d[2] <= s.p[2] => d,
                    _ => s.p,
                });
            } else if let Some(d) = dip.take() {
                out.push(d);
            }
        }
        out.extend(dip);
        out
    }
}

/// Whether `a` and `b` agree within `tol`.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}
