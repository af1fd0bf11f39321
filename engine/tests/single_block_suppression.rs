//! Single block suppression (SBLOF/SBLON) and block display suppression (DISPLOF/DISPLON) as
//! PROC attributes and as block commands (Programming Manual, Job planning). Expected stops and
//! displayed blocks worked out by hand from the programs.

use nctwin_engine::{Channel, Status};

use crate::settle;
use settle::{channel, settle};

/// Runs `main` in single block mode, starting again after each stop: the shown block's line
/// and the axis positions at every stop.
fn stops(ch: &mut Channel, main: &str) -> Vec<(Option<u32>, Vec<f64>)> {
    ch.single_block = true;
    ch.run_program(main).unwrap();
    let mut stops = Vec::new();
    for _ in 0..20 {
        settle(ch);
        if ch.status() != Status::Stopped {
            break;
        }
        stops.push((ch.snapshot().block.map(|b| b.line), ch.axis_positions().to_vec()));
        ch.start().unwrap();
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.status(), Status::Idle);
    stops
}

#[test]
fn a_standard_cycle_stops_once_after_the_cycle_in_single_block() {
    let mut ch = channel("mill-3axis", "");
    // CYCLE81 (PROC .. SBLOF DISPLOF): G0 Z1 (RFP + SDIS), G1 Z-3, G0 Z5 (RTP) are one step
    // with the calling line 3, shown as that line.
    let stops = stops(&mut ch, "G17 G90 F300\nG0 X10 Y10 Z5\nCYCLE81(5,0,1,-3)\nG0 X20\nM30");
    assert_eq!(
        stops,
        [(Some(2), vec![10.0, 10.0, 5.0]), (Some(3), vec![10.0, 10.0, 5.0]), (Some(4), vec![20.0, 10.0, 5.0])]
    );
}

#[test]
fn under_mcall_each_position_and_its_cycle_are_one_step() {
    let mut ch = channel("mill-3axis", "");
    // Lines 4 and 5: the move to the position and the drilling there, then the stop.
    let program = "G17 G90 F300\nG0 X10 Y10 Z5\nMCALL CYCLE81(5,0,1,-3)\nX20\nX30\nMCALL\nM30";
    let stops = stops(&mut ch, program);
    assert_eq!(
        stops,
        [(Some(2), vec![10.0, 10.0, 5.0]), (Some(4), vec![20.0, 10.0, 5.0]), (Some(5), vec![30.0, 10.0, 5.0])]
    );
}

#[test]
fn the_blocks_between_sblof_and_sblon_are_one_step() {
    let mut ch = channel("mill-3axis", "");
    // Lines 3 and 4 run without a stop between them; line 1 and line 6 are steps of their own.
    let stops = stops(&mut ch, "G0 X10\nSBLOF\nG0 Y10\nG0 Z10\nSBLON\nG0 X0\nM30");
    assert_eq!(
        stops,
        [(Some(1), vec![10.0, 0.0, 0.0]), (Some(4), vec![10.0, 10.0, 10.0]), (Some(6), vec![0.0, 10.0, 10.0])]
    );
}

#[test]
fn a_subprogram_with_sblof_in_its_proc_line_is_one_step_shown_block_by_block() {
    let mut ch = channel("mill-3axis", "");
    // No DISPLOF: the display follows SUB's lines; the stop comes after SUB's last move, at
    // its return (the M17 block, line 4, as the manual has the stop "with the return").
    ch.store_program("SUB", "PROC SUB SBLOF\nG0 X10\nG0 Y10\nM17").unwrap();
    let stops = stops(&mut ch, "G0 X5\nSUB\nG0 Z5\nM30");
    assert_eq!(
        stops,
        [(Some(1), vec![5.0, 0.0, 0.0]), (Some(4), vec![10.0, 10.0, 0.0]), (Some(3), vec![10.0, 10.0, 5.0])]
    );
}

/// The block shown: its line and program (`None`: the main program).
type Shown = (u32, Option<String>);

/// Runs `main` to its end; the shown block at every cycle with its X.
fn shown_by_x(ch: &mut Channel, main: &str) -> Vec<(f64, Option<Shown>)> {
    ch.run_program(main).unwrap();
    let mut samples = Vec::new();
    for _ in 0..1_000_000 {
        if !ch.is_busy() {
            assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
            return samples;
        }
        ch.step();
        samples.push((ch.axis_positions()[0], ch.snapshot().block.map(|b| (b.line, b.program))));
    }
    panic!("the program never ended");
}

/// The block shown at every sample strictly between `from` and `to` in X: one block, checked.
fn shown_between(samples: &[(f64, Option<Shown>)], from: f64, to: f64) -> Shown {
    let inside: Vec<_> = samples.iter().filter(|(x, _)| *x > from + 1e-3 && *x < to - 1e-3).collect();
    assert!(!inside.is_empty(), "no cycle between X{from} and X{to}");
    let first = inside[0].1.clone().expect("a block is shown");
    assert!(inside.iter().all(|(_, b)| b.as_ref() == Some(&first)), "{inside:?}");
    first
}

#[test]
fn displof_and_displon_in_a_block_hide_and_show_the_blocks_after_them() {
    let mut ch = channel("mill-3axis", "");
    ch.store_program("SUB", "PROC SUB\nG0 X10\nDISPLOF\nG0 X20\nDISPLON\nG0 X30\nM17").unwrap();
    let samples = shown_by_x(&mut ch, "G0 X0\nSUB\nM30");
    let sub = Some("SUB".to_string());
    // SUB's line 2 is shown; after DISPLOF the calling block (main line 2); after DISPLON SUB's
    // line 6.
    assert_eq!(shown_between(&samples, 0.0, 10.0), (2, sub.clone()));
    assert_eq!(shown_between(&samples, 10.0, 20.0), (2, None));
    assert_eq!(shown_between(&samples, 20.0, 30.0), (6, sub));
}

#[test]
fn displon_in_a_proc_line_shows_a_subprogram_called_from_a_hidden_one() {
    let mut ch = channel("mill-3axis", "");
    ch.store_program("OUTER", "PROC OUTER DISPLOF\nG0 X10\nINNER\nM17").unwrap();
    ch.store_program("INNER", "PROC INNER DISPLON\nG0 X20\nM17").unwrap();
    ch.store_program("QUIET", "PROC QUIET\nG0 X30\nM17").unwrap();
    ch.store_program("OUTER2", "PROC OUTER2 DISPLOF\nQUIET\nM17").unwrap();
    let samples = shown_by_x(&mut ch, "G0 X0\nOUTER\nOUTER2\nM30");
    // OUTER's move shows its call (main line 2); INNER's own line 2 is shown (DISPLON); a
    // subprogram without DISPLON called from a hidden one is hidden with it (main line 3).
    assert_eq!(shown_between(&samples, 0.0, 10.0), (2, None));
    assert_eq!(shown_between(&samples, 10.0, 20.0), (2, Some("INNER".to_string())));
    assert_eq!(shown_between(&samples, 20.0, 30.0), (3, None));
}
