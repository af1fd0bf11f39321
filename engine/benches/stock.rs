//! The cost of material removal (divan): `cargo bench -p nctwin-engine --bench stock`.
//!
//! - `step`: one `Channel::step` in the middle of a running mill3-like program (pockets with
//!   helical infeed, contours, arcs; end mill R5), without a blank and with one that holds the
//!   toolpath (0.25 mm cells), 1000 cycles per sample: the difference is material removal's
//!   cost per IPO cycle.
//! - `segment`: one straight segment of the R5 end mill cut into a fresh 100 x 100 mm blank,
//!   1 mm and 8 mm long (the longest segment the channel cuts at once), level and ramping:
//!   the cost of one cut at the default resolution.
//! - `tilted`: one IPO cycle's stretch (0.2 mm: 1000 mm/min at 12 ms) of an R5 tool 100 long
//!   tilted 30° about Y, its tip 2 mm deep at the end of a slot it has cut 20 mm into a
//!   100 x 100 x 20 blank: a flat end mill and a ball nose (its tip a staircase of cylinders):
//!   the 5-axis cost per cutting cycle.
//!
//! `cargo test -p nctwin-engine --benches` runs every case once (the smoke run).

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use nctwin_engine::Channel;
use nctwin_engine::stock::blank::{Blank, Placement, Shape};
use nctwin_engine::stock::cutter::Cutter;
use nctwin_engine::stock::{DEFAULT_RESOLUTION, Stock};

fn main() {
    divan::main();
}

/// Pockets and contours in a 200 x 100 area, 2..3 mm deep, the tool R5 (`mill-3axis` T1).
fn program(parts: usize) -> String {
    let mut out = String::from("G17 G90 G94\nT1 D1\nG0 Z50\n");
    out.push_str("WORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,210,110)\nS6000 M3\n");
    for p in 0..parts {
        let (ox, oy) = ((p % 4) as f64 * 50.0, (p / 4 % 2) as f64 * 50.0);
        out.push_str(&format!("G0 X{} Y{} Z2\nG1 Z0 F400\n", ox + 21.0, oy + 20.0));
        out.push_str(&format!(
            "G3 X{} Y{} Z-1.5 I-1 J0 F600\nG3 X{} Y{} Z-3 I1 J0\n",
            ox + 19.0,
            oy + 20.0,
            ox + 21.0,
            oy + 20.0
        ));
        for r in 2..=8 {
            let r = f64::from(r);
            out.push_str(&format!(
                "G1 X{} F1000\nG3 X{} I{} J0\nG3 X{} I{} J0\n",
                ox + 20.0 + r,
                ox + 20.0 - r,
                -r,
                ox + 20.0 + r,
                r
            ));
        }
        out.push_str(&format!(
            "G0 Z2\nG0 X{} Y{}\nG1 Z-2 F300\nG1 X{} F1200\nY{}\nX{}\nY{}\nG0 Z5\n",
            ox + 2.0,
            oy + 2.0,
            ox + 45.0,
            oy + 45.0,
            ox + 2.0,
            oy + 2.0
        ));
    }
    out.push_str("M30\n");
    out
}

/// A channel running `program` some way in (so the queue and the stock are in mid-run).
fn running(with_blank: bool) -> Channel {
    let text = program(8);
    let text = if with_blank { text } else { text.replace("WORKPIECE", ";WORKPIECE") };
    let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
    ch.run_program(&text).expect("program");
    for _ in 0..20_000 {
        ch.step();
    }
    ch
}

#[divan::bench(args = [false, true])]
fn step(bencher: Bencher, with_blank: bool) {
    bencher.counter(ItemsCount::new(1000usize)).with_inputs(|| running(with_blank)).bench_local_refs(|ch| {
        for _ in 0..1000 {
            ch.step();
        }
    });
}

#[divan::bench(args = [1.0, 8.0])]
fn segment(bencher: Bencher, length: f64) {
    let blank = Blank { shape: Shape::Box { x: [0.0, 100.0], y: [0.0, 100.0] }, top: 0.0, bottom: -20.0 };
    let fresh = Stock::new(&blank, &Placement::default(), false, DEFAULT_RESOLUTION).expect("stock");
    let cutter = Cutter::end_mill(5.0);
    bencher.with_inputs(|| fresh.clone()).bench_local_refs(|s| {
        black_box(s.cut(&cutter, [50.0, 50.0, -2.0], [50.0 + length, 50.0, -2.0]));
        black_box(s.cut(&cutter, [50.0, 60.0, -2.0], [50.0 + length, 60.0, -2.0 - length / 4.0]));
    });
}

#[divan::bench(args = [0.0, 5.0])]
fn tilted(bencher: Bencher, corner: f64) {
    let blank = Blank { shape: Shape::Box { x: [0.0, 100.0], y: [0.0, 100.0] }, top: 0.0, bottom: -20.0 };
    let fresh = Stock::new(&blank, &Placement::default(), false, DEFAULT_RESOLUTION).expect("stock");
    let cutter = Cutter { radius: 5.0, kind: nctwin_engine::stock::cutter::Kind::Mill { corner } };
    let (s, c) = 30f64.to_radians().sin_cos();
    let axis = [s, 0.0, c];
    // Steady state: the slot cut from X10 to X30 already, then one cycle's 0.2 mm further.
    let mut slot = fresh.clone();
    slot.cut_oriented(&cutter, [10.0, 50.0, -2.0], [30.0, 50.0, -2.0], axis, 100.0);
    bencher.with_inputs(|| slot.clone()).bench_local_refs(|st| {
        black_box(st.cut_oriented(&cutter, [30.0, 50.0, -2.0], [30.2, 50.0, -2.0], axis, 100.0));
    });
}
