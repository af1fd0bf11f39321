//! Shared harness of the turning-cycle tests on the 2-axis lathe (X a radius): runs a program,
//! records the workpiece position, the machine X and the spindle angle of every IPO cycle, and
//! offers the views the tests check (the cycle's part of a run, the cutting passes, the
//! unwrapped spindle angle).
#![allow(dead_code)]

use nctwin_engine::Channel;
use nctwin_engine::alarm::Alarm;

const MAX_TICKS: usize = 5_000_000;

/// One IPO cycle: simulated time, WCS X (radius), WCS Z, the spindle's machine angle (degrees),
/// machine X (the radius, whatever the programming mode) and machine Z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub t: f64,
    pub x: f64,
    pub z: f64,
    pub sp: f64,
    pub mx: f64,
    pub mz: f64,
}

/// What a run leaves: every cycle's sample, the alarms raised and R1..R6 at the end.
pub struct Trace {
    pub samples: Vec<Sample>,
    pub alarms: Vec<Alarm>,
    pub r: Vec<f64>,
}

/// Runs `main` on `lathe-2axis` with the machine data `md` added (tool data) and the
/// subprograms `subs` (name, text) stored; records every IPO cycle until the channel rests.
pub fn run_lathe(md: &str, main: &str, subs: &[(&str, &str)]) -> Trace {
    let mut ch = Channel::from_preset("lathe-2axis", md).unwrap();
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
    let r = (1..=6).map(|i| ch.r_param(i)).collect();
    Trace { samples, alarms: ch.snapshot().alarms, r }
}

fn sample(ch: &Channel) -> Sample {
    let s = ch.snapshot();
    let get = |l: &[(String, f64)], n: &str| l.iter().find(|(a, _)| a == n).map_or(f64::NAN, |a| a.1);
    Sample {
        t: s.time,
        x: get(&s.workpiece, "X"),
        z: get(&s.workpiece, "Z"),
        sp: get(&s.machine, "SP1"),
        mx: get(&s.machine, "X1"),
        mz: get(&s.machine, "Z1"),
    }
}

impl Trace {
    /// Fails the test on any alarm.
    pub fn clean(self) -> Trace {
        assert!(self.alarms.is_empty(), "alarms: {:?}", self.alarms);
        self
    }

    /// The samples from the tool's first arrival at the approach point (`x`, `z`) on, or all
    /// of them if it never gets there (a cycle refused before it moves). The snapshot's block
    /// line runs ahead of the motion, so a cycle's samples are cut by position.
    pub fn after_reaching(mut self, x: f64, z: f64) -> Trace {
        let from = self.samples.iter().position(|s| close(s.x, x, 1e-9) && close(s.z, z, 1e-9));
        self.samples.drain(..from.unwrap_or(0));
        self
    }

    /// The runs of samples below `surface(z)` (cutting) with Z inside (lo, hi).
    pub fn passes(&self, surface: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Vec<Vec<Sample>> {
        let mut out: Vec<Vec<Sample>> = Vec::new();
        let mut open = false;
        for s in &self.samples {
            let cutting = s.x < surface(s.z) - 1e-6 && s.z > lo && s.z < hi;
            match out.last_mut() {
                Some(pass) if cutting && open => pass.push(*s),
                _ if cutting => out.push(vec![*s]),
                _ => {}
            }
            open = cutting;
        }
        out
    }
}

pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// The spindle's angle unwrapped along the samples (SP1 is a modulo axis turning forward).
pub fn unwrapped(samples: &[Sample]) -> Vec<f64> {
    let mut turns = 0.0;
    let mut out: Vec<f64> = Vec::new();
    for (i, s) in samples.iter().enumerate() {
        if i > 0 && s.sp < samples[i - 1].sp - 180.0 {
            turns += 360.0;
        }
        out.push(s.sp + turns);
    }
    out
}

/// The radius of the shaft the CYCLE95 tests turn: X10 from Z0 to Z-20, a fillet R5 (centre
/// Z-20 X15) to Z-25, the shoulder up to X20, a taper to X25 at Z-40.
pub fn shaft_radius(z: f64) -> f64 {
    if z >= -20.0 {
        10.0
    } else if z >= -25.0 {
        15.0 - (25.0 - (z + 20.0) * (z + 20.0)).max(0.0).sqrt()
    } else {
        20.0 + (-25.0 - z) / 15.0 * 5.0
    }
}
