//! Benchmarks of the engine's pipeline, one group per stage (divan):
//!
//! - `parse`: `lang::check` (the syntax check before a run) and `lang::read_block` (how the
//!   interpreter walks a program) over a generated mill3-like program; per block and per byte.
//! - `prepare`: block preparation, blocks → prepared items (moves) with the modal state.
//! - `interpolate`: one IPO cycle of the planner (look-ahead, stepping, path evaluation) on
//!   lines, arcs and helices, with the queue kept as full as the channel keeps it.
//! - `channel_step`: one `Channel::step` in the middle of a running program (everything above,
//!   amortised, plus the channel's bookkeeping).
//! - `transform`: one `Channel::step` with each transformation family active (none, TRANSMIT,
//!   TRACYL, TRAANG) on its preset: interpolation plus the inverse transformation per cycle.
//! - `traori_point`: one TRAORI IPO point, `ActiveTrafo::inverse_oriented` (orientation →
//!   rotary axes with both solutions, limits and nearest choice, then the linear axes) on each
//!   5-axis preset; throughput in transforms/s.
//! - `whole_program`: a whole fast-pace run, `run_program` until the motion ends; per block.
//!   `NCTWIN_BENCH_PROGRAM=file.mpf` adds a case for that file (e.g. from
//!   ../shared/bench/gen_program.py), on `NCTWIN_BENCH_MACHINE` (default mill-3axis).
//!
//! `cargo bench -p nctwin-engine` measures; `cargo test -p nctwin-engine --benches` runs every
//! case once on small programs (the CI smoke run). Whole-process figures with peak RSS:
//! `scripts/bench.sh`.

use std::sync::Arc;

use divan::counter::{BytesCount, ItemsCount};
use divan::{Bencher, black_box};
use nctwin_engine::Channel;
use nctwin_engine::interp::{Interpreter, Item, Prep, Programs};
use nctwin_engine::lang;
use nctwin_engine::machine_data::MachineConfig;
use nctwin_engine::motion::{AxisLimit, Move, Planner};

fn main() {
    divan::main();
}

/// `cargo bench` passes `--bench`; without it (`cargo test --benches`) every case runs once,
/// so programs are kept small.
fn smoke() -> bool {
    !std::env::args().any(|a| a == "--bench")
}

/// Program length for a case: `blocks`, or a few hundred in the smoke run.
fn size(blocks: usize) -> usize {
    if smoke() { blocks.min(300) } else { blocks }
}

/// A deterministic 3-axis program in the style of gen_program.py's mill3: circular pockets
/// with helical infeed, rounded-rectangle contours (G1/G2/G3), and a 3D raster finish.
fn mill3(blocks: usize) -> String {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut out: Vec<String> = ["; mill3-like benchmark program", "G71 G17 G90 G94 G40 G54", "T1 D1", "S12000 M3"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let foot = ["G0 Z25", "M5", "G0 X0 Y0", "M30"];
    let mut part = 0;
    while out.len() + foot.len() < blocks {
        part += 1;
        let (ox, oy) = (f64::from(part % 7) * 60.0, f64::from(part / 7 % 5) * 60.0);
        out.push(format!("; part {part}"));
        // Circular pocket, helical infeed.
        let (cx, cy, rmax, sr) = (ox + 15.0 + rng.unit() * 2.0, oy + 20.0, 8.0 + rng.unit() * 4.0, 1.0);
        out.push("G0 Z5".into());
        out.push(format!("G0 X{:.4} Y{cy:.4}", cx + sr));
        out.push("G1 Z0 F400".into());
        out.push(format!("G3 X{:.4} Y{cy:.4} Z-0.5 I{:.4} J0 F600", cx - sr, -sr));
        out.push(format!("G3 X{:.4} Y{cy:.4} Z-1 I{sr:.4} J0", cx + sr));
        let mut r = sr;
        while r < rmax {
            r = (r + sr).min(rmax);
            out.push(format!("G1 X{:.4} Y{cy:.4} F1000", cx + r));
            out.push(format!("G3 X{cx:.4} Y{:.4} I{:.4} J0", cy + r, -r));
            out.push(format!("X{:.4} Y{cy:.4} I0 J{:.4}", cx - r, -r));
            out.push(format!("X{cx:.4} Y{:.4} I{r:.4} J0", cy - r));
            out.push(format!("X{:.4} Y{cy:.4} I0 J{r:.4}", cx + r));
        }
        out.push("G0 Z5".into());
        // Rounded rectangle.
        let (x0, y0, w, h, rc) = (ox + 2.0, oy + 2.0, 50.0, 40.0 + rng.unit() * 5.0, 3.0 + rng.unit() * 3.0);
        out.push(format!("G0 X{:.4} Y{y0:.4}", x0 + rc));
        out.push("G1 Z-2 F300".into());
        out.push(format!("G1 X{:.4} F1000", x0 + w - rc));
        out.push(format!("G3 X{:.4} Y{:.4} I0 J{rc:.4}", x0 + w, y0 + rc));
        out.push(format!("G1 Y{:.4}", y0 + h - rc));
        out.push(format!("G3 X{:.4} Y{:.4} I{:.4} J0", x0 + w - rc, y0 + h, -rc));
        out.push(format!("G1 X{:.4}", x0 + rc));
        out.push(format!("G3 X{x0:.4} Y{:.4} I0 J{:.4}", y0 + h - rc, -rc));
        out.push(format!("G1 Y{:.4}", y0 + rc));
        out.push(format!("G3 X{:.4} Y{y0:.4} I{rc:.4} J0", x0 + rc));
        out.push("G0 Z5".into());
        // 3D raster.
        let amp = 0.5 + rng.unit() * 1.5;
        out.push(format!("G0 X{:.4} Y{:.4}", ox + 5.0, oy + 5.0));
        out.push("G1 Z0 F400".into());
        out.push("G1 F1800".into());
        for j in 0..=20 {
            let y = oy + 5.0 + f64::from(j) * 2.0;
            let cols: Vec<i32> = if j % 2 == 0 { (0..=40).collect() } else { (0..=40).rev().collect() };
            for (k, i) in cols.into_iter().enumerate() {
                let x = ox + 5.0 + f64::from(i);
                let z = -amp * (1.0 + (f64::from(i) / 7.0).sin() * (f64::from(j) * 2.0 / 5.0).cos());
                out.push(if k == 0 { format!("G1 X{x:.4} Y{y:.4} Z{z:.4}") } else { format!("X{x:.4} Z{z:.4}") });
            }
        }
        out.push("G0 Z5".into());
    }
    out.truncate(blocks.saturating_sub(foot.len()).max(4));
    out.extend(foot.iter().map(|s| s.to_string()));
    out.join("\n") + "\n"
}

/// Programs of one motion family for the interpolation cases: many consecutive blocks.
fn family(kind: &str, blocks: usize) -> String {
    let mut p = String::from("G71 G17 G90 G94 G54 T1 D1 F3000\nG0 X0 Y0 Z0\n");
    for i in 0..blocks {
        let r = 5.0 + (i % 20) as f64;
        let z = -((i % 10) as f64) * 0.2;
        match kind {
            // A zig-zag of short segments, like a finishing raster.
            "line" => p += &format!("G1 X{:.3} Y{:.3} Z{:.3}\n", (i % 50) as f64, (i / 50 % 2) as f64 * 0.5, z),
            // Full circles, alternating radius.
            "arc" => p += &format!("G1 X{r}\nG2 X{r} Y0 I{} J0\n", -r),
            // Helix: a circle with an infeed in Z.
            "helix" => p += &format!("G1 X{r} Z0\nG2 X{r} Y0 Z-1 I{} J0\n", -r),
            _ => unreachable!("unknown family {kind}"),
        }
    }
    p + "M30\n"
}

/// xorshift64*: the benchmarks' only source of variety.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn channel(machine: &str) -> Channel {
    Channel::from_preset(machine, "").expect("built-in preset")
}

fn config() -> MachineConfig {
    channel("mill-3axis").config().clone()
}

fn non_empty_lines(text: &str) -> usize {
    text.lines().filter(|l| !l.trim().is_empty()).count()
}

/// Prepares `text` completely (as if the main run were always idle) and returns the items;
/// `lane`: plain motion lines take the fast lane (the default).
fn prepare_all(cfg: &MachineConfig, text: &str, keep: &mut Vec<Item>, lane: bool) -> usize {
    let programs = Programs::new();
    let mut interp = Interpreter::new(cfg);
    interp.set_fast_lane(lane);
    interp.begin_program(Arc::from(text), &[0.0; nctwin_engine::machine_data::registry::MAX_CHANNEL_AXES]);
    let mut out = Vec::new();
    let mut prepared = 0;
    loop {
        out.clear();
        let prep = interp.prepare_next(cfg, &programs, true, &mut out);
        prepared += 1;
        keep.append(&mut out);
        if prep == Prep::Done {
            return prepared;
        }
    }
}

mod parse {
    use super::*;

    #[divan::bench(args = [20_000])]
    fn check(bencher: Bencher, blocks: usize) {
        let text = mill3(size(blocks));
        bencher
            .counter(ItemsCount::new(non_empty_lines(&text)))
            .counter(BytesCount::of_str(&text))
            .bench(|| lang::check(black_box(&text)));
    }

    #[divan::bench(args = [20_000])]
    fn read_block(bencher: Bencher, blocks: usize) {
        let text = mill3(size(blocks));
        bencher.counter(ItemsCount::new(non_empty_lines(&text))).counter(BytesCount::of_str(&text)).bench(|| {
            let (mut offset, mut line, mut n) = (0, 1, 0usize);
            while let Some((block, next_offset, next_line)) = lang::read_block(black_box(&text), offset, line) {
                n += usize::from(block.is_ok());
                (offset, line) = (next_offset, next_line);
            }
            n
        });
    }
}

mod prepare {
    use super::*;

    /// Blocks → items (moves with their offsets), the interpreter alone: plain motion lines
    /// on the fast lane (`mill3`) and every block the general way (`mill3_general`).
    #[divan::bench(args = [20_000])]
    fn mill3(bencher: Bencher, blocks: usize) {
        prepare_mill3(bencher, blocks, true);
    }

    #[divan::bench(args = [20_000])]
    fn mill3_general(bencher: Bencher, blocks: usize) {
        prepare_mill3(bencher, blocks, false);
    }

    fn prepare_mill3(bencher: Bencher, blocks: usize, lane: bool) {
        let text = super::mill3(size(blocks));
        let cfg = config();
        bencher.counter(ItemsCount::new(non_empty_lines(&text))).bench(|| {
            let mut items = Vec::new();
            let n = prepare_all(&cfg, black_box(&text), &mut items, lane);
            (n, items.len())
        });
    }
}

mod interpolate {
    use super::*;

    /// Moves of one family, prepared by the interpreter.
    fn moves(kind: &str) -> (Vec<Move>, Vec<AxisLimit>, f64) {
        let cfg = config();
        let mut items = Vec::new();
        prepare_all(&cfg, &family(kind, 400), &mut items, true);
        let moves: Vec<Move> = items
            .into_iter()
            .filter_map(|i| match i {
                Item::Move { mv, .. } => Some(mv),
                _ => None,
            })
            .collect();
        assert!(moves.len() > 100, "{kind}: {} moves", moves.len());
        (moves, AxisLimit::for_channel(&cfg).to_vec(), cfg.ipo_cycle)
    }

    /// One IPO cycle: the planner keeps `LOOKAHEAD` moves queued, as the channel does, so the
    /// cost of a push (the backward look-ahead pass) is amortised over the cycles of a block.
    #[divan::bench(args = ["line", "arc", "helix"], sample_size = 2000, sample_count = 200)]
    fn cycle(bencher: Bencher, kind: &str) {
        let (moves, limits, dt) = moves(kind);
        let mut planner = Planner::new(dt, limits, [0.0; nctwin_engine::machine_data::registry::MAX_CHANNEL_AXES]);
        let mut next = 0;
        bencher.bench_local(|| {
            while planner.len() < nctwin_engine::channel::LOOKAHEAD {
                planner.push(moves[next % moves.len()].clone());
                next += 1;
            }
            planner.step();
            black_box(planner.take_finished());
            black_box(planner.position()[0])
        });
    }
}

mod channel_step {
    use super::*;

    /// One `Channel::step` inside a running mill3 program (restarted when it ends).
    #[divan::bench(sample_size = 2000, sample_count = 200)]
    fn mill3(bencher: Bencher) {
        let text = super::mill3(size(20_000));
        bench_steps(bencher, channel("mill-3axis"), &text);
    }
}

/// Benches one `Channel::step` of `text` on `ch`, restarting the program whenever it ends.
fn bench_steps(bencher: Bencher, mut ch: nctwin_engine::Channel, text: &str) {
    ch.run_program(text).expect("program loads");
    bencher.bench_local(|| {
        if !ch.is_busy() {
            ch.reset();
            ch.run_program(text).expect("program loads");
        }
        ch.step();
        if ch.ticks().is_multiple_of(1024) {
            black_box(ch.take_events());
        }
    });
}

mod transform {
    use super::*;

    /// (preset, program head, one repeated pass, program foot) per transformation family.
    fn case(family: &str) -> (&'static str, &'static str, &'static str, &'static str) {
        match family {
            "none" => {
                ("mill-3axis", "T1 D1 G17 G90 G94 F5000\nG0 X10 Y-10 Z5\n", "G1 X10 Y-10\nX-10\nY10\nX10\n", "M30\n")
            }
            "transmit" => (
                "transmit-example",
                "T1 D1 G17 G90 G94 F5000\nG0 X20 Z10\nTRANSMIT\n",
                "G1 X10 Y-10\nX-10\nY10\nX10\n",
                "TRAFOOF\nM30\n",
            ),
            "tracyl" => (
                "tracyl-xyzc",
                "G0 X20 Y0 Z0\nTRACYL(40)\nG1 F1000\n",
                "Y31.4159 Z-10\nY-31.4159 Z0\n",
                "TRAFOOF\nM30\n",
            ),
            "traang" => ("traang-grinder", "G0 X0 Z0\nTRAANG\nG1 F2000\n", "X10 Z-5\nX0 Z0\n", "TRAFOOF\nM30\n"),
            _ => unreachable!("unknown family {family}"),
        }
    }

    fn program(family: &str, passes: usize) -> (&'static str, String) {
        let (preset, head, pass, foot) = case(family);
        (preset, format!("{head}{}{foot}", pass.repeat(passes)))
    }

    /// One `Channel::step` with the transformation active (the program restarts when it ends).
    #[divan::bench(args = ["none", "transmit", "tracyl", "traang"], sample_size = 2000, sample_count = 200)]
    fn cycle(bencher: Bencher, family: &str) {
        let (preset, text) = program(family, if smoke() { 3 } else { 200 });
        let mut ch = channel(preset);
        // The program must run to its end without an alarm, or the figure means nothing.
        ch.run_program(&text).expect("program loads");
        while ch.is_busy() {
            ch.step();
        }
        assert!(ch.alarms().is_empty(), "{family}: {:?}", ch.alarms());
        ch.reset();
        bench_steps(bencher, ch, &text);
    }
}

mod traori_point {
    use super::*;
    use nctwin_engine::kinematics::{self, ActiveTrafo, SelectArgs};

    /// One IPO point per iteration along a precomputed ring of 1024 TCP/orientation pairs
    /// (a tilted cone sweep), each continuous with the previous machine position.
    #[divan::bench(args = ["mill5-head-ca", "mill5-table-ac", "mill5-mixed-bc"])]
    fn inverse_oriented(bencher: Bencher, preset: &str) {
        let cfg = channel(preset).config().clone();
        let trafo = kinematics::build(&cfg.trafos[0], &cfg, &SelectArgs::default()).expect("TRAORI data set 1");
        let t = ActiveTrafo { trafo, tool: [0.0, 0.0, 100.0], number: 1 };
        let ring: Vec<([f64; 20], [f64; 3])> = (0..1024)
            .map(|i| {
                let u = i as f64 / 1024.0 * std::f64::consts::TAU;
                let mut p = [0.0; 20];
                (p[0], p[1], p[2]) = (40.0 * u.cos(), 40.0 * u.sin(), -5.0);
                let tilt = 0.4f64;
                (p, [tilt.sin() * u.cos(), tilt.sin() * u.sin(), tilt.cos()])
            })
            .collect();
        let mut prev = t.inverse_oriented(&ring[0].0, &ring[0].1, &[0.0; 20]).expect("reachable");
        let mut i = 0;
        bencher.counter(ItemsCount::new(1usize)).bench_local(|| {
            let (p, o) = &ring[i & 1023];
            i += 1;
            prev = t.inverse_oriented(black_box(p), black_box(o), &prev).expect("reachable");
            black_box(&prev);
        });
    }
}

mod whole_program {
    use super::*;

    fn run(machine: &str, text: &str) -> u64 {
        let mut ch = channel(machine);
        ch.run_program(text).expect("program loads");
        while ch.is_busy() {
            ch.step();
            if ch.ticks().is_multiple_of(1024) {
                black_box(ch.take_events());
            }
        }
        assert!(ch.alarms().is_empty(), "alarms: {:?}", ch.alarms());
        ch.ticks()
    }

    /// A whole fast-pace run of a generated mill3 program, per block.
    #[divan::bench(args = [2_000, 20_000], sample_count = 5)]
    fn mill3(bencher: Bencher, blocks: usize) {
        let text = super::mill3(size(blocks));
        bencher.counter(ItemsCount::new(non_empty_lines(&text))).bench(|| run("mill-3axis", black_box(&text)));
    }

    /// The program in `NCTWIN_BENCH_PROGRAM`, if set.
    #[divan::bench(sample_count = 3)]
    fn file(bencher: Bencher) {
        let Ok(path) = std::env::var("NCTWIN_BENCH_PROGRAM") else {
            bencher.bench(|| ());
            return;
        };
        let machine = std::env::var("NCTWIN_BENCH_MACHINE").unwrap_or_else(|_| "mill-3axis".into());
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        bencher.counter(ItemsCount::new(non_empty_lines(&text))).bench(|| run(&machine, black_box(&text)));
    }
}
