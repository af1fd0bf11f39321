//! A whole program straight on the engine, for instruction-count profiling
//! (`valgrind --tool=callgrind`): builds in a fraction of the server binary's time.
//!
//! `cargo run --release -p nctwin-engine --example profile_run -- PRESET FILE [--interpret-only]
//! [--no-fast-lane] [--md=DATA_FILE] [--trace]` prints the blocks prepared (moves) or the IPO cycles run;
//! `--no-fast-lane` sends every block the general way (the figure before the lane); `--md=`
//! loads machine and setting data text over the preset (e.g. ORISON's MD28590/SD42678);
//! `--trace` also prints the cycles run until the program ended and a hash of every cycle's
//! axis positions (two builds that sample a path alike print the same line). `nctwin simulate` is the measuring
//! tool with timing and RSS; this one only drives the same engine calls.

use std::sync::Arc;

use nctwin_engine::alarm::Clear;
use nctwin_engine::interp::{Interpreter, Item, Prep, Programs};
use nctwin_engine::machine_data::registry::MAX_CHANNEL_AXES;
use nctwin_engine::{Channel, Status};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(preset), Some(file)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: profile_run PRESET FILE [--interpret-only]");
        std::process::exit(1);
    };
    let text: Arc<str> = Arc::from(std::fs::read_to_string(file).expect("readable program"));
    let data = args
        .iter()
        .find_map(|a| a.strip_prefix("--md="))
        .map(|f| std::fs::read_to_string(f).expect("readable machine data"))
        .unwrap_or_default();
    let mut channel = Channel::from_preset(preset, &data).expect("known preset");
    if args.iter().any(|a| a == "--interpret-only") {
        let cfg = channel.config();
        let mut interp = Interpreter::new(cfg);
        interp.set_fast_lane(!args.iter().any(|a| a == "--no-fast-lane"));
        let mut position = [0.0; MAX_CHANNEL_AXES];
        position[..channel.axis_positions().len()].copy_from_slice(channel.axis_positions());
        assert!(nctwin_engine::lang::check(&text).is_empty(), "syntax errors");
        interp.begin_program(text, &position);
        let (mut moves, mut out) = (0u64, Vec::new());
        loop {
            out.clear();
            let prep = interp.prepare_next(cfg, &Programs::new(), true, &mut out);
            drop(interp.take_data_writes());
            moves += out.iter().filter(|i| matches!(i, Item::Move { .. })).count() as u64;
            if let Some(Item::Alarm(a)) = out.iter().find(|i| matches!(i, Item::Alarm(_))) {
                panic!("alarm {a:?}");
            }
            if prep == Prep::Done {
                break;
            }
        }
        println!("moves {moves}");
    } else {
        channel.run_program_shared(text).expect("program starts");
        let trace = args.iter().any(|a| a == "--trace");
        // FNV-1a over the bits of every cycle's axis positions.
        let (mut hash, mut running) = (0xcbf2_9ce4_8422_2325_u64, 0u64);
        while channel.status() == Status::Running {
            for _ in 0..4096 {
                channel.step();
                if trace && channel.status() == Status::Running {
                    running += 1;
                    for p in channel.axis_positions() {
                        for b in p.to_bits().to_le_bytes() {
                            hash = (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
                        }
                    }
                }
            }
            drop(channel.take_events());
        }
        if trace {
            println!("trace: {running} cycles running, positions hash {hash:016x}");
        }
        // Alarms the cancel key clears only inform (10910 feed reduced): the run went on.
        let stopping: Vec<_> = channel.alarms().iter().filter(|a| a.clear == Clear::Reset).collect();
        assert!(stopping.is_empty(), "alarms: {stopping:?}");
        println!("ipo cycles {}", channel.ticks());
        // The end position's bits: two builds that run a program alike print the same line.
        let bits: Vec<String> = channel.axis_positions().iter().map(|p| format!("{:016x}", p.to_bits())).collect();
        println!("end position {}", bits.join(" "));
        if let Some(s) = channel.stock_info() {
            let warnings = channel.stock_warnings();
            println!(
                "stock: removed {:.1} of {:.1} mm3 at {} mm, {} warnings {:?}",
                s.removed,
                s.initial_volume,
                s.resolution,
                s.warnings,
                warnings.iter().take(5).map(|w| (w.check, w.line)).collect::<Vec<_>>()
            );
        }
    }
}
