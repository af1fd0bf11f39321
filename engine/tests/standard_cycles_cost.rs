//! What a cycle costs: CYCLE83 under MCALL at 1,000 positions against the same motions written
//! out as blocks. Both must give the same path (same simulated time, same end); the CPU time
//! of both runs is measured side by side. `NCTWIN_CYCLE_RATIO=1 cargo test --release --test
//! standard_cycles_cost -- --nocapture` prints the figures (the target: the cycle within 2x;
//! measured 2026-11: 248 ms against 79 ms, 3.1x: the cycle's ~125 statement lines per call run
//! through the general interpreter at about 1 µs each, the written-out blocks through the fast lane).
//! After the cycle's body stayed parsed whole (its last lines had evicted its first from the
//! block cache at every call), the channel stopped counting lines from the text's start after
//! each jump back, and the header comments skipped block preparation: CPU time (perf stat, 10
//! runs each, `NCTWIN_CYCLE_ONLY`) 103 ms against 39 ms, 2.6x (before: 132 ms, 3.4x);
//! instructions (callgrind) 1.107e9 against 0.583e9, 1.90x (before: 1.40e9, 2.41x). What is
//! left is the general interpreter's per-statement cost (variables by name in B-trees, a block's
//! word collection and offset refresh for every assignment).
//! Session 12 (profiled with callgrind): variables in FNV-hashed maps, blocks that only assign
//! to variables past the general block preparation (`eval/assignment_block.rs`), skipped
//! branches looked at in the block cache, parsed blocks boxed (a read no longer copies a whole
//! `Block` three times), later calls of a cycle starting at its PROC line (its header comments
//! were 28 of the ~115 blocks read per call), and a leaner CYCLE83.SPF (MINVAL/MAXVAL clamps,
//! rare branches under one test): CPU 78..80 ms against 41 ms, 1.92..1.95x (three pairs of
//! perf stat runs of 10 at load 13; measured the same way before: 100.7 ms against 40.0 ms,
//! 2.52x); instructions 0.901e9 against 0.600e9, 1.50x (before: 1.116e9 against 0.598e9).

use std::time::Instant;

use nctwin_engine::{Channel, Status};

const HOLES: usize = 1000;

fn positions() -> impl Iterator<Item = (f64, f64)> {
    (0..HOLES).map(|i| ((i % 40) as f64 * 10.0, (i / 40) as f64 * 10.0))
}

/// CYCLE83(5, 0, 1, -12, , -5, , 2, 0, 0, 1, 1) at every position.
fn with_cycle() -> String {
    let mut p = String::from("G17 G90 F300\nG0 X0 Y0 Z5\nMCALL CYCLE83(5,0,1,-12,,-5,,2,0,0,1,1)\n");
    for (x, y) in positions() {
        p.push_str(&format!("X{x} Y{y}\n"));
    }
    p.push_str("MCALL\nM30\n");
    p
}

/// The same motions by hand: first depth 5 (-5), then strokes 5 - 2 = 3 (-8), 2 (-10; 1 is less
/// than DAM 2), and the 2 left (less than 2 x DAM, no more than the stroke: -12). Chip removal:
/// G0 out to RFP + SDIS = 1, G0 back to 0.6 above the last depth (depth <= 30 mm), G1 on.
fn written_out() -> String {
    let mut p = String::from("G17 G90 F300\nG0 X0 Y0 Z5\n");
    for (x, y) in positions() {
        p.push_str(&format!(
            "G0 X{x} Y{y}\nZ1\nG1 Z-5\nG0 Z1\nZ-4.4\nG1 Z-8\nG0 Z1\nZ-7.4\nG1 Z-10\nG0 Z1\nZ-9.4\nG1 Z-12\nG0 Z5\n"
        ));
    }
    p.push_str("M30\n");
    p
}

fn simulate(program: &str) -> (f64, Vec<f64>, std::time::Duration) {
    let start = Instant::now();
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    while ch.is_busy() {
        for _ in 0..4096 {
            ch.step();
        }
        // As the server drains them: the events would otherwise pile up.
        drop(ch.take_events());
    }
    let elapsed = start.elapsed();
    let s = ch.snapshot();
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert_eq!(s.status, Status::Idle);
    (s.time, ch.axis_positions().to_vec(), elapsed)
}

#[test]
fn cycle83_at_1000_positions_gives_the_written_out_path() {
    // `NCTWIN_CYCLE_ONLY=cycle` (or `hand`) runs one of the two, for a profiler.
    match std::env::var("NCTWIN_CYCLE_ONLY").as_deref() {
        Ok("cycle") => return drop(simulate(&with_cycle())),
        Ok("hand") => return drop(simulate(&written_out())),
        _ => {}
    }
    let (t_cycle, end_cycle, cpu_cycle) = simulate(&with_cycle());
    let (t_hand, end_hand, cpu_hand) = simulate(&written_out());
    assert_eq!(end_cycle, end_hand);
    assert!((t_cycle - t_hand).abs() < 1e-9, "simulated time {t_cycle} vs {t_hand}");
    if std::env::var_os("NCTWIN_CYCLE_RATIO").is_some() {
        let ratio = cpu_cycle.as_secs_f64() / cpu_hand.as_secs_f64();
        println!(
            "CYCLE83 x{HOLES}: {cpu_cycle:?}; written out: {cpu_hand:?}; ratio {ratio:.2} (simulated {t_cycle:.1} s)"
        );
    }
}
