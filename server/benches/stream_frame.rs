//! What one real-time session costs the server per state frame (divan), stage by stage:
//!
//! - `step_frame`: the IPO cycles of one 50 ms frame (12.5 on average at 4 ms) of a running
//!   mill3-like program on mill-3axis (pockets of G3 circles, as scripts/load.sh runs);
//! - `snapshot_build`: `Channel::snapshot`, a new `Snapshot` per frame;
//! - `snapshot_refresh`: `Channel::refresh_snapshot` into the previous frame's snapshot;
//! - `encode_state`: the `{"type": "state", ...}` JSON of a running snapshot;
//! - `encode_serde`: the same through serde_json into a new buffer (the encoder before);
//! - `frame`: all of it as the actor and one viewer do it per frame (step, refresh into a
//!   spare, compare with the published one, encode), and `frame_before`: the same the way it
//!   was done before (a new snapshot, serde).
//!
//! `cargo bench -p nctwin-server --bench stream_frame` measures; `cargo test -p nctwin-server
//! --benches` runs every case once.

use divan::{Bencher, black_box};
use nctwin_engine::{Channel, Snapshot};
use nctwin_server::api::stream_frame::{StateEncoder, encode_state};

fn main() {
    divan::main();
}

/// IPO cycles per 50 ms frame at 4 ms, alternating 12 and 13.
const CYCLES: [usize; 2] = [12, 13];

/// Circular pockets with helical infeed and rings of G3 quarter circles, about 40,000 blocks
/// (longer than any bench run).
fn pocket_program() -> String {
    let mut out = String::from("G71 G17 G90 G94 G40 G54\nT1 D1\nS12000 M3\n");
    for part in 0..1000 {
        let (cx, cy) = (f64::from(part % 7) * 60.0 + 15.0, f64::from(part / 7 % 5) * 60.0 + 20.0);
        out += &format!("G0 Z5\nG0 X{:.4} Y{cy:.4}\nG1 Z0 F400\n", cx + 1.0);
        out += &format!("G3 X{:.4} Y{cy:.4} Z-0.5 I-1 J0 F600\nF1000\n", cx - 1.0);
        for r in 1..8 {
            let r = f64::from(r);
            out += &format!("G1 X{:.4} Y{cy:.4}\n", cx + r);
            out += &format!("G3 X{cx:.4} Y{:.4} I{:.4} J0\n", cy + r, -r);
            out += &format!("X{:.4} Y{cy:.4} I0 J{:.4}\n", cx - r, -r);
            out += &format!("X{cx:.4} Y{:.4} I{r:.4} J0\n", cy - r);
            out += &format!("X{:.4} Y{cy:.4} I0 J{r:.4}\n", cx + r);
        }
    }
    out + "G0 Z25\nM30\n"
}

/// A channel one second into the pocket program.
fn running() -> Channel {
    let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
    channel.run_program(&pocket_program()).expect("program");
    for _ in 0..250 {
        channel.step();
    }
    channel
}

fn step_frame(channel: &mut Channel, frame: &mut usize) {
    *frame += 1;
    for _ in 0..CYCLES[*frame % 2] {
        channel.step();
    }
}

#[divan::bench]
fn step_frame_only(bencher: Bencher) {
    let mut channel = running();
    let mut frame = 0;
    bencher.bench_local(|| step_frame(&mut channel, &mut frame));
}

#[divan::bench]
fn snapshot_build(bencher: Bencher) {
    let mut channel = running();
    let mut frame = 0;
    bencher.bench_local(|| {
        step_frame(&mut channel, &mut frame);
        black_box(channel.snapshot());
    });
}

#[divan::bench]
fn snapshot_refresh(bencher: Bencher) {
    let mut channel = running();
    let mut frame = 0;
    let mut snapshot = channel.snapshot();
    bencher.bench_local(|| {
        step_frame(&mut channel, &mut frame);
        channel.refresh_snapshot(&mut snapshot);
        black_box(&snapshot);
    });
}

/// The old encoder: a new buffer and a full serde pass per frame.
#[divan::bench]
fn encode_serde(bencher: Bencher) {
    let snapshot = running().snapshot();
    bencher.bench_local(|| black_box(encode_state(black_box(&snapshot))));
}

/// The frame encoder on a changing snapshot (step between frames, not timed).
#[divan::bench]
fn encode_state_frames(bencher: Bencher) {
    let mut channel = running();
    let mut frame = 0;
    let mut encoder = StateEncoder::default();
    bencher
        .with_inputs(|| {
            step_frame(&mut channel, &mut frame);
            channel.snapshot()
        })
        .bench_local_refs(|snapshot: &mut Snapshot| black_box(encoder.encode(snapshot)));
}

/// One frame of one session with one viewer: step, refresh into the spare, compare, encode.
#[divan::bench]
fn frame(bencher: Bencher) {
    let mut channel = running();
    let mut frame = 0;
    let mut published = channel.snapshot();
    let mut spare = published.clone();
    let mut encoder = StateEncoder::default();
    bencher.bench_local(|| {
        step_frame(&mut channel, &mut frame);
        channel.refresh_snapshot(&mut spare);
        if spare != published {
            std::mem::swap(&mut spare, &mut published);
            black_box(encoder.encode(&published));
        }
    });
}

/// One frame as before: step, a new snapshot, compare, encode through serde.
#[divan::bench]
fn frame_before(bencher: Bencher) {
    let mut channel = running();
    let mut frame = 0;
    let mut published = channel.snapshot();
    bencher.bench_local(|| {
        step_frame(&mut channel, &mut frame);
        let next = channel.snapshot();
        if next != published {
            published = next;
            black_box(encode_state(&published));
        }
    });
}
