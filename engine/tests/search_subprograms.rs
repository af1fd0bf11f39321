//! Block search and restart inside subprograms (issue 20, defect 6; the current block of
//! defect 11). Expected values are worked out by hand from the programs.

use nctwin_engine::channel::PathStep;
use nctwin_engine::{Channel, CommandError, Status};

use crate::settle;
use settle::{channel, settle};

/// Main program: X1, then the subprogram HOLE, then M30 (3 lines, fewer than HOLE has).
const MAIN: &str = "G0 X1\nHOLE\nM30";
/// HOLE: Y1, R5 and R6 computed, a programmed stop at line 4, then Z-5.
const HOLE: &str = "G0 Y1\nR5=7\nR6=R5+1\nM0\nG0 Z-5\nM17";

fn with_hole() -> Channel {
    let mut ch = channel("mill-3axis", "");
    ch.store_program("HOLE", HOLE).unwrap();
    ch
}

fn block(ch: &Channel) -> Option<(u32, String)> {
    ch.snapshot().block.map(|b| (b.line, b.text))
}

fn step(program: &str, line: u32) -> PathStep {
    PathStep { program: program.into(), line }
}

fn block_in(ch: &Channel) -> Option<(u32, String, Option<String>)> {
    ch.snapshot().block.map(|b| (b.line, b.text, b.program))
}

#[test]
fn a_search_to_a_line_that_calls_a_subprogram_stops_before_the_call() {
    let mut ch = with_hole();
    ch.block_search(Some(MAIN), 2).unwrap();
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.status(), Status::Stopped);
    assert_eq!(block(&ch), Some((2, "HOLE".to_string())));
    // Nothing of HOLE ran in the search: R5 is not set yet.
    assert_eq!(ch.r_param(5), 0.0);
    assert_eq!(ch.axis_positions(), &[0.0, 0.0, 0.0]);
    ch.start().unwrap();
    settle(&mut ch);
    // HOLE runs from its start: Y1, stops at its M0 (line 4) with R5=7, R6=8.
    assert_eq!(ch.status(), Status::Stopped);
    assert_eq!(block(&ch), Some((4, "M0".to_string())));
    assert_eq!((ch.r_param(5), ch.r_param(6)), (7.0, 8.0));
    ch.start().unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Idle);
    // The approach went to X1 (the start of HOLE's first move), then Y1, Z-5.
    assert_eq!(ch.axis_positions(), &[1.0, 1.0, -5.0]);
}

#[test]
fn the_current_block_inside_a_subprogram_shows_the_subprograms_text() {
    let mut ch = with_hole();
    ch.run_program(MAIN).unwrap();
    settle(&mut ch);
    assert_eq!(ch.status(), Status::Stopped);
    // Line 4 of HOLE, not line 4 of the main program (which has 3 lines).
    assert_eq!(block(&ch), Some((4, "M0".to_string())));
    assert_eq!(ch.snapshot().block.and_then(|b| b.program).as_deref(), Some("HOLE"));
    // NC start: HOLE's line 5, then the program ends.
    let mut seen: Vec<_> = block_in(&ch).into_iter().collect();
    ch.start().unwrap();
    while ch.is_busy() || ch.status() == Status::Running {
        ch.step();
        if let Some(b) = block_in(&ch)
            && seen.last() != Some(&b)
        {
            seen.push(b);
        }
    }
    let hole = |l: u32, t: &str| (l, t.to_string(), Some("HOLE".to_string()));
    assert_eq!(seen, [hole(4, "M0"), hole(5, "G0 Z-5")]);
    let events: Vec<_> = ch
        .take_events()
        .into_iter()
        .filter_map(|e| match e {
            nctwin_engine::Event::BlockChanged(b) => Some((b.line, b.text, b.program)),
            _ => None,
        })
        .collect();
    assert!(events.contains(&hole(5, "G0 Z-5")), "{events:?}");
}

/// SUB2 switches to G91 and a feed, sets R7, and moves; its line 5 is the search target.
const SUB2: &str = "G91\nG1 X2 F500\nR7=3\nG1 Y4\nG1 X1\nM17";

#[test]
fn a_search_into_a_subprogram_computes_its_blocks_before_the_target() {
    let mut ch = channel("mill-3axis", "");
    ch.store_program("SUB2", SUB2).unwrap();
    ch.block_search_at(Some("G0 X10\nSUB2\nM0\nM30"), 2, &[step("sub2.spf", 5)]).unwrap();
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.status(), Status::Stopped);
    assert_eq!(block_in(&ch), Some((5, "G1 X1".to_string(), Some("SUB2".to_string()))));
    // R7 is set by SUB2's line 3, before the target; nothing moved.
    assert_eq!(ch.r_param(7), 3.0);
    assert_eq!(ch.axis_positions(), &[0.0, 0.0, 0.0]);
    // The checkpoint names the block by its chain of calls.
    let saved = ch.resume_state().program.expect("a program");
    assert_eq!((saved.line, saved.path), (Some(2), vec![step("SUB2", 5)]));
    ch.start().unwrap();
    let samples = settle(&mut ch);
    // Skipped: X10 (main), X+2, Y+4 (SUB2, G91): the target starts at (12, 4). The approach goes
    // there straight from (0, 0) with the target's feed F500 (G1, collected from line 2).
    let at = samples.iter().position(|s| s[0] == 12.0 && s[1] == 4.0).expect("reaches (12, 4)");
    for w in samples[..=at].windows(2) {
        assert!((w[1][1] * 3.0 - w[1][0]).abs() < 1e-9, "on y = x/3: {:?}", w[1]);
        let v = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt() / 0.004;
        assert!(v <= 500.0 / 60.0 + 1e-6, "{v}");
    }
    // The target X1 is incremental (G91 from SUB2's line 1): X13. Then the main program's M0.
    assert_eq!(ch.axis_positions(), &[13.0, 4.0, 0.0]);
    assert_eq!((ch.status(), block_in(&ch)), (Status::Stopped, Some((3, "M0".to_string(), None))));
    assert!(ch.snapshot().gcodes.iter().any(|g| g == "G91"), "{:?}", ch.snapshot().gcodes);
}

#[test]
fn a_search_into_a_subprogram_stops_in_the_call_the_path_names() {
    // SUB3 is called twice: the target is its line 2 in the second call.
    let mut ch = channel("mill-3axis", "");
    ch.store_program("SUB3", "R8=R8+1\nG91 G0 X1\nM17").unwrap();
    let main = "SUB3\nSUB3\nM30";
    ch.block_search_at(Some(main), 2, &[step("SUB3", 2)]).unwrap();
    assert_eq!(block_in(&ch), Some((2, "G91 G0 X1".to_string(), Some("SUB3".to_string()))));
    // Both calls' line 1 ran: R8 = 2. The first call's X+1 was skipped: the target starts at X1.
    assert_eq!(ch.r_param(8), 2.0);
    ch.start().unwrap();
    settle(&mut ch);
    assert_eq!(ch.axis_positions(), &[2.0, 0.0, 0.0]);

    // A path the program does not take: 15370; a program not stored or a line it does not
    // have: refused.
    ch.reset();
    ch.store_program("OTHER", "G0 Y1\nM17").unwrap();
    ch.block_search_at(Some(main), 2, &[step("OTHER", 1)]).unwrap();
    assert_eq!(ch.alarms().iter().map(|a| a.number).collect::<Vec<_>>(), [15370]);
    ch.reset();
    let refused = |r: Result<(), CommandError>| matches!(r, Err(CommandError::Invalid(_)));
    assert!(refused(ch.block_search_at(Some(main), 2, &[step("NOPE", 1)])));
    assert!(refused(ch.block_search_at(Some(main), 2, &[step("SUB3", 4)])));
    assert!(refused(ch.block_search_at(Some(main), 2, &[step("bad name!", 1)])));
    assert_eq!(ch.status(), Status::Idle);
}

#[test]
fn a_search_follows_two_levels_of_calls_and_a_restart_resumes_there() {
    let programs = |ch: &mut Channel| {
        ch.store_program("OUTER", "G0 X3\nINNER\nM17").unwrap();
        ch.store_program("INNER", "G0 Y7\nG0 Z-2\nM0\nG0 X9\nM17").unwrap();
    };
    let mut ch = channel("mill-3axis", "");
    programs(&mut ch);
    ch.block_search_at(Some("OUTER\nM30"), 1, &[step("OUTER", 2), step("INNER", 2)]).unwrap();
    assert_eq!(block_in(&ch), Some((2, "G0 Z-2".to_string(), Some("INNER".to_string()))));
    ch.start().unwrap();
    settle(&mut ch);
    // Approach to (3, 7, 0), Z-2, then INNER's M0.
    assert_eq!(ch.axis_positions(), &[3.0, 7.0, -2.0]);
    assert_eq!(block_in(&ch), Some((3, "M0".to_string(), Some("INNER".to_string()))));
    let saved = ch.resume_state();
    let program = saved.program.clone().expect("a program");
    assert_eq!((program.line, program.path), (Some(1), vec![step("OUTER", 2), step("INNER", 3)]));
    let mut new = channel("mill-3axis", "");
    programs(&mut new);
    new.restore_positions(ch.axis_positions()).unwrap();
    new.restore_resume_state(&saved).unwrap();
    assert_eq!(
        (new.status(), block_in(&new)),
        (Status::Stopped, Some((3, "M0".to_string(), Some("INNER".to_string()))))
    );
    new.start().unwrap();
    settle(&mut new);
    assert_eq!(new.status(), Status::Idle);
    assert_eq!(new.axis_positions(), &[9.0, 7.0, -2.0]);
}

#[test]
fn a_program_stopped_inside_a_subprogram_resumes_there_after_a_restart() {
    let mut ch = with_hole();
    ch.run_program(MAIN).unwrap();
    settle(&mut ch);
    assert_eq!((ch.status(), block(&ch)), (Status::Stopped, Some((4, "M0".to_string()))));
    let saved = ch.resume_state();

    let mut new = with_hole();
    new.restore_positions(ch.axis_positions()).unwrap();
    new.restore_resume_state(&saved).expect("restore");
    assert!(new.alarms().is_empty(), "{:?}", new.alarms());
    assert_eq!((new.status(), block(&new)), (Status::Stopped, Some((4, "M0".to_string()))));
    // The search computed HOLE's R parameters before its M0 again.
    assert_eq!((new.r_param(5), new.r_param(6)), (7.0, 8.0));
    // The M0 was executed before the restart: one NC start goes on behind it, Z-5 in HOLE,
    // then back in the main program to M30.
    new.start().unwrap();
    settle(&mut new);
    assert_eq!(new.status(), Status::Idle, "{:?}", new.alarms());
    assert_eq!(new.axis_positions(), &[1.0, 1.0, -5.0]);
}

/// 100,000 passes of a three-block loop (WHILE, R1=R1+1, ENDWHILE): 300,000 blocks before the
/// target.
const LONG: &str = "R1=0\nWHILE R1<100000\nR1=R1+1\nENDWHILE\nG0 X5\nG0 Y5\nM30";

#[test]
fn a_search_finds_a_target_after_more_than_200000_blocks() {
    let mut ch = channel("mill-3axis", "");
    ch.block_search(Some(LONG), 6).unwrap();
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!((ch.status(), block(&ch)), (Status::Stopped, Some((6, "G0 Y5".to_string()))));
    assert_eq!(ch.r_param(1), 100_000.0);
    ch.start().unwrap();
    settle(&mut ch);
    // The approach goes to the target's start (5, 0), then Y5.
    assert_eq!(ch.axis_positions(), &[5.0, 5.0, 0.0]);
}

#[test]
fn a_program_stopped_after_more_than_200000_blocks_resumes_after_a_restart() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program(&LONG.replace("G0 Y5", "M0\nG0 Y5")).unwrap();
    settle(&mut ch);
    assert_eq!((ch.status(), block(&ch)), (Status::Stopped, Some((6, "M0".to_string()))));
    let saved = ch.resume_state();
    let mut new = channel("mill-3axis", "");
    new.restore_positions(ch.axis_positions()).unwrap();
    new.restore_resume_state(&saved).expect("restore");
    assert!(new.alarms().is_empty(), "{:?}", new.alarms());
    assert_eq!((new.status(), block(&new)), (Status::Stopped, Some((6, "M0".to_string()))));
    new.start().unwrap();
    settle(&mut new);
    assert_eq!(new.axis_positions(), &[5.0, 5.0, 0.0]);
}

#[test]
fn a_search_that_never_reaches_its_target_ends_where_its_caller_says_with_15370() {
    use nctwin_engine::channel::SEARCH_ASK_EVERY;
    let mut ch = channel("mill-3axis", "");
    let mut asked = Vec::new();
    let mut go_on = |blocks: usize| {
        asked.push(blocks);
        blocks < 2 * SEARCH_ASK_EVERY
    };
    ch.block_search_with(Some("LOOP\nR1=R1+1\nENDLOOP\nM30"), None, 4, &[], &mut go_on).unwrap();
    assert_eq!(asked, [SEARCH_ASK_EVERY, 2 * SEARCH_ASK_EVERY]);
    assert_eq!(ch.status(), Status::Alarm);
    let alarm = &ch.alarms()[0];
    assert_eq!(alarm.number, 15370);
    assert!(alarm.message.contains(&format!("after {} blocks", 2 * SEARCH_ASK_EVERY)), "{}", alarm.message);
}
