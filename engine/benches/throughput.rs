//! Throughput of a whole channel in fast pace: blocks prepared, planned and interpolated per
//! second of CPU, and IPO cycles per second. Run: `cargo bench -p nctwin-engine`.
//! Optional argument: a program file (e.g. from ../shared/bench/gen_program.py).

use std::time::Instant;

use nctwin_engine::Channel;

fn synthetic_program(blocks: usize) -> String {
    let mut p = String::from("G64 T1 D1 F3000\nG0 X0 Y0 Z5\nG1 Z-1\n");
    for i in 0..blocks / 5 {
        let r = 5.0 + (i % 20) as f64;
        p += &format!("G1 X{r} Y0\nG3 X0 Y{r} CR={r}\nG1 X-{r} Y{r}\nG3 X-{r} Y-{r} I0 J-{r}\nG1 X0 Y0\n");
    }
    p + "M30\n"
}

fn main() {
    let program = match std::env::args().nth(1).filter(|a| !a.starts_with("--")) {
        Some(path) => std::fs::read_to_string(path).expect("readable program file"),
        None => synthetic_program(20_000),
    };
    let blocks = program.lines().count();
    let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
    let started = Instant::now();
    ch.run_program(&program).expect("program parses");
    while ch.is_busy() {
        ch.step();
    }
    let secs = started.elapsed().as_secs_f64();
    println!(
        "{blocks} blocks, {} IPO cycles ({:.1} s simulated) in {secs:.3} s: {:.0} blocks/s, {:.0} cycles/s, {:.2} µs/cycle; alarms: {:?}",
        ch.ticks(),
        ch.time(),
        blocks as f64 / secs,
        ch.ticks() as f64 / secs,
        secs * 1e6 / ch.ticks() as f64,
        ch.alarms().iter().map(|a| a.number).collect::<Vec<_>>()
    );
}
