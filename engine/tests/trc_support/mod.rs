//! Shared helpers of the tool radius compensation tests (`trc_*.rs`): run a program on a preset
//! and record every IPO sample of the axes, stop at M0, read the first alarm.
#![allow(dead_code)]

use nctwin_engine::alarm::Clear;
use nctwin_engine::{Channel, Status};

/// Runs `program` on `preset` until the channel stops (M0, alarm) or ends; every IPO sample.
pub fn run_to_stop(preset: &str, extra: &str, program: &str) -> (Channel, Vec<Vec<f64>>) {
    let mut ch = Channel::from_preset(preset, extra).unwrap();
    ch.run_program(program).unwrap();
    let samples = go_on(&mut ch);
    (ch, samples)
}

/// Steps the channel until it stops or ends; every IPO sample (the first is where it stands).
pub fn go_on(ch: &mut Channel) -> Vec<Vec<f64>> {
    let mut samples = vec![ch.axis_positions().to_vec()];
    for _ in 0..2_000_000 {
        if !ch.is_busy() || ch.status() == Status::Stopped {
            break;
        }
        ch.step();
        samples.push(ch.axis_positions().to_vec());
    }
    samples
}

/// The whole program on `mill-3axis`, resuming after each M0.
pub fn run_all(program: &str) -> (Channel, Vec<Vec<f64>>) {
    run_all_on("mill-3axis", "", program)
}

pub fn run_all_on(preset: &str, extra: &str, program: &str) -> (Channel, Vec<Vec<f64>>) {
    let (mut ch, mut samples) = run_to_stop(preset, extra, program);
    // Warnings (cleared by the cancel key, such as 10763) do not keep the program stopped.
    while ch.status() == Status::Stopped && ch.alarms().iter().all(|a| a.clear == Clear::Cancel) {
        ch.start().unwrap();
        samples.extend(go_on(&mut ch));
    }
    (ch, samples)
}

/// The first alarm that stops the program (warnings left out).
pub fn alarm_of(ch: &Channel) -> Option<u32> {
    ch.alarms().iter().find(|a| a.clear != Clear::Cancel).map(|a| a.number)
}

/// The warnings shown (alarms cleared by the cancel key), by number and line.
pub fn warnings_of(ch: &Channel) -> Vec<(u32, Option<u32>)> {
    ch.alarms().iter().filter(|a| a.clear == Clear::Cancel).map(|a| (a.number, a.line)).collect()
}

/// Whether some sample lies within `tol` of (x, y).
pub fn passes_near(samples: &[Vec<f64>], x: f64, y: f64, tol: f64) -> bool {
    samples.iter().any(|p| (p[0] - x).hypot(p[1] - y) < tol)
}

/// Distance of p from the segment a–b.
pub fn seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let d = (b.0 - a.0, b.1 - a.1);
    let l2 = d.0 * d.0 + d.1 * d.1;
    let t = if l2 > 0.0 { (((p.0 - a.0) * d.0 + (p.1 - a.1) * d.1) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (p.0 - a.0 - t * d.0).hypot(p.1 - a.1 - t * d.1)
}

/// The smallest distance of the tool centre (x, y) from a programmed polyline.
pub fn polyline_dist(p: (f64, f64), pts: &[(f64, f64)]) -> f64 {
    pts.windows(2).map(|w| seg_dist(p, w[0], w[1])).fold(f64::INFINITY, f64::min)
}

/// The first sample closer than `r − 1e-6` to the polyline, if any.
pub fn first_gouge(samples: &[Vec<f64>], pts: &[(f64, f64)], r: f64) -> Option<Vec<f64>> {
    samples.iter().find(|s| polyline_dist((s[0], s[1]), pts) < r - 1e-6).cloned()
}

/// The samples from the first one at (x, y) on (the program's first position).
pub fn after_reaching(samples: &[Vec<f64>], x: f64, y: f64) -> &[Vec<f64>] {
    let i = samples.iter().position(|p| (p[0] - x).abs() < 1e-9 && (p[1] - y).abs() < 1e-9).expect("reached");
    &samples[i..]
}
