//! `Channel::progress_mark`: a channel that cannot go on on its own (a thread with the spindle
//! stopped, as the control stands without an alarm) keeps the same mark; one that dwells, moves
//! or waits on a spindle that turns changes it.

use crate::settle;

use settle::{channel, steps};

/// Steps `seconds` of simulated time (lathe-2axis: its IPO cycle) and tells whether the
/// progress mark changed over it.
fn changes_over(ch: &mut nctwin_engine::Channel, seconds: f64) -> bool {
    let before = ch.progress_mark();
    let n = (seconds / ch.config().ipo_cycle).round() as usize;
    steps(ch, n);
    ch.progress_mark() != before
}

#[test]
fn a_thread_with_the_spindle_stopped_makes_no_progress() {
    let mut ch = channel("lathe-2axis", "");
    // M5: no speed. G33 needs the spindle's revolutions: the axes wait for ever (the control
    // stands, no alarm), and the channel stays busy.
    ch.run_program("G0 X20 Z5\nM5\nG33 Z-20 K1.5\nM30\n").unwrap();
    steps(&mut ch, 5000);
    assert!(ch.is_busy());
    assert!(!changes_over(&mut ch, 30.0), "nothing can change: same mark");
    assert!(ch.is_busy());
}

#[test]
fn a_long_dwell_and_a_turning_spindle_are_progress() {
    let mut ch = channel("lathe-2axis", "");
    // G4 F100: the dwell counts down for 100 s; the mark changes though nothing moves.
    ch.run_program("G4 F100\nM30\n").unwrap();
    steps(&mut ch, 10);
    assert!(changes_over(&mut ch, 30.0));
    let mut ch = channel("lathe-2axis", "");
    // The same thread with S500 M3 runs: 25 mm at 1.5 mm/rev and 500 rev/min = 2 s.
    ch.run_program("G0 X20 Z5\nS500 M3\nG33 Z-20 K1.5\nM30\n").unwrap();
    steps(&mut ch, 10);
    assert!(changes_over(&mut ch, 1.0));
}
