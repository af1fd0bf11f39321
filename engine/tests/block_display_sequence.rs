//! The block display names the block whose move runs, not only its line number: a subprogram's
//! line 1 right after the caller's line 1 is another block (the fix of `enter_block`, which
//! compared line numbers only). Expected values worked out by hand from the programs.

use nctwin_engine::{Channel, Event, Status};

use crate::settle;
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

#[test]
fn a_displof_subprogram_shows_its_call_while_its_blocks_run() {
    // Programming Manual, "DISPLOF": the blocks of a subprogram whose PROC line says DISPLOF are
    // not displayed; the calling block stays in the display until the return. Main line 2
    // calls DRILLIT, whose two moves take Z from 10 down to -5 and back to 10; line 3 moves X.
    let mut ch = channel("mill-3axis", "");
    ch.store_program("DRILLIT", "PROC DRILLIT(REAL DEPTH) DISPLOF\nG1 Z=-DEPTH F3000\nG0 Z10\nRET").unwrap();
    let main = "G0 X0 Y0 Z10\nDRILLIT(5)\nG0 X20\nM30";
    ch.run_program(main).unwrap();
    let call = (2, "DRILLIT(5)".to_string(), None);
    let (mut seen_down, mut line1_done) = (false, false);
    for _ in 0..100_000 {
        if !ch.is_busy() && ch.status() != Status::Running {
            break;
        }
        ch.step();
        let z = ch.axis_positions()[2];
        let x = ch.axis_positions()[0];
        // Line 1 ends at Z10 (from the machine zero, Z0).
        line1_done |= z >= 10.0 - 1e-9;
        if line1_done && x < 1e-9 && z < 9.999 {
            // Inside DRILLIT (down or up again): the call is shown, never DRILLIT's lines.
            seen_down |= z < 0.0;
            assert_eq!(shown(&ch), Some(call.clone()), "at Z{z}");
        }
    }
    assert!(seen_down, "DRILLIT's feed move ran");
    assert_eq!(ch.axis_positions()[0], 20.0);
    // The stream hears of the call once and of no block of DRILLIT.
    let events = block_events(&mut ch);
    assert_eq!(events.iter().filter(|e| **e == call).count(), 1, "{events:?}");
    assert!(events.iter().all(|e| e.2.is_none()), "a block of DRILLIT was announced: {events:?}");
}

#[test]
fn without_displof_the_subprograms_blocks_are_shown() {
    // The same subprogram without DISPLOF: its feed move shows its own line 2.
    let mut ch = channel("mill-3axis", "");
    ch.store_program("DRILLIT", "PROC DRILLIT(REAL DEPTH)\nG1 Z=-DEPTH F3000\nG0 Z10\nRET").unwrap();
    run(&mut ch, "G0 X0 Y0 Z10\nDRILLIT(5)\nG0 X20\nM30");
    let events = block_events(&mut ch);
    let feed = (2, "G1 Z=-DEPTH F3000".to_string(), Some("DRILLIT".to_string()));
    assert!(events.contains(&feed), "{events:?}");
}

#[test]
fn a_standard_cycle_is_shown_as_its_calling_block() {
    // The cycle library's CYCLE81 is written with DISPLOF, as the control's: while it drills,
    // the display shows the call (line 3), as Operate does.
    let mut ch = channel("mill-3axis", "");
    let main = "G17 G90 T1 D1 S1000 M3\nG0 X10 Y10 Z20 F500\nCYCLE81(10,0,2,-5)\nG0 Z50\nM30";
    let samples = run(&mut ch, main);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let events = block_events(&mut ch);
    assert!(events.iter().all(|e| e.2.is_none()), "a block of CYCLE81 was announced: {events:?}");
    let call = (3, "CYCLE81(10,0,2,-5)".to_string(), None);
    assert!(events.contains(&call), "{events:?}");
    // A sample below the reference plane (Z < 0: the tool tip drills, Z with T1's length) shows it.
    let drilling = samples.iter().filter(|(_, b)| b.as_ref() == Some(&call)).count();
    assert!(drilling > 0, "the call was never shown while the cycle ran");
}
