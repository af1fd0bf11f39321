//! The block display names the block whose move runs, not only its line number: a subprogram's
//! line 1 right after the caller's line 1 is another block (the fix of `enter_block`, which
//! compared line numbers only). Expected values worked out by hand from the programs.

use nctwin_engine::{Channel, Event, Status};

#[allow(dead_code)] // the shared helpers this file does not use
mod settle;
use settle::channel;

type Shown = (u32, String, Option<String>);

fn shown(ch: &Channel) -> Option<Shown> {
    ch.snapshot().block.map(|b| (b.line, b.text, b.program))
}

fn block_events(ch: &mut Channel) -> Vec<Shown> {
    ch.take_events()
        .into_iter()
        .filter_map(|e| match e {
            Event::BlockChanged(b) => Some((b.line, b.text, b.program)),
            _ => None,
        })
        .collect()
}

/// Runs until the end; returns every cycle's X position with the block shown then.
fn run(ch: &mut Channel, main: &str) -> Vec<(f64, Option<Shown>)> {
    ch.run_program(main).unwrap();
    let mut samples = Vec::new();
    for _ in 0..1_000_000 {
        if !ch.is_busy() && ch.status() != Status::Running {
            return samples;
        }
        ch.step();
        samples.push((ch.axis_positions()[0], shown(ch)));
    }
    panic!("the program never ended");
}

#[test]
fn a_subprograms_line_1_after_the_callers_line_1_is_shown_while_its_move_runs() {
    let mut ch = channel("mill-3axis", "");
    ch.store_program("SUB", "G0 X10\nM17").unwrap();
    // Main line 1 moves to X5, line 2 calls SUB, whose line 1 moves on to X10.
    let samples = run(&mut ch, "G0 X5\nSUB\nM30");
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let main1 = (1, "G0 X5".to_string(), None);
    let sub1 = (1, "G0 X10".to_string(), Some("SUB".to_string()));
    // Between X5 and X10 only SUB's move runs: the display names SUB's line 1 every cycle.
    let during_sub: Vec<_> = samples.iter().filter(|(x, _)| *x > 5.001 && *x < 9.999).collect();
    assert!(!during_sub.is_empty(), "the move to X10 takes several cycles");
    for (x, b) in &during_sub {
        assert_eq!(b.as_ref(), Some(&sub1), "at X{x}");
    }
    // Before X5 the caller's line 1.
    let (x, b) = samples.iter().find(|(x, _)| *x > 0.001 && *x < 4.999).expect("a cycle on the way to X5");
    assert_eq!(b.as_ref(), Some(&main1), "at X{x}");
    // The stream hears of both blocks, in order.
    let events = block_events(&mut ch);
    let first = events.iter().position(|e| *e == main1).expect("main line 1 announced");
    let second = events.iter().position(|e| *e == sub1).expect("SUB line 1 announced");
    assert!(first < second, "{events:?}");
}

#[test]
fn a_one_line_subprogram_called_twice_is_announced_for_each_call() {
    let mut ch = channel("mill-3axis", "");
    // G91: each call moves X by +3; the calls are lines 2 and 3 of the main program.
    ch.store_program("STEP3", "G91 G0 X3\nM17").unwrap();
    let samples = run(&mut ch, "G0 X0\nSTEP3\nSTEP3\nM30");
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.axis_positions()[0], 6.0);
    let step3 = (1, "G91 G0 X3".to_string(), Some("STEP3".to_string()));
    // Both moves (0 → 3 and 3 → 6) show STEP3's line 1.
    for (x, b) in samples.iter().filter(|(x, _)| (*x > 0.001 && *x < 2.999) || (*x > 3.001 && *x < 5.999)) {
        assert_eq!(b.as_ref(), Some(&step3), "at X{x}");
    }
    // Two calls are two blocks: the display announces the block twice.
    let events = block_events(&mut ch);
    assert_eq!(events.iter().filter(|e| **e == step3).count(), 2, "{events:?}");
}
