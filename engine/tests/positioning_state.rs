//! The positioning axes in the state (`Snapshot::positioning`) and in a checkpoint
//! (`ResumeState::positioning`). mill-3axis: IPO cycle 4 ms, 3 m/s²; `FA[Z]=300` is 5 mm/s, so
//! Z is at full speed after one cycle and 100 cycles take it about 2 mm.

use crate::settle;

use nctwin_engine::channel::PositioningInfo;
use nctwin_engine::{Channel, Status};
use settle::{channel, run_to_end, steps};

fn z(ch: &Channel) -> f64 {
    ch.axis_positions()[2]
}

#[test]
fn a_posa_axis_on_its_way_is_listed_with_target_speed_and_kind() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nG4 F5\nM30").unwrap();
    assert!(ch.snapshot().positioning.is_empty(), "nothing before the main run starts it");
    steps(&mut ch, 100);
    let s = ch.snapshot();
    // The dwell runs; nothing waits for Z. Velocity 300 mm/min towards −5.
    assert_eq!(
        s.positioning,
        vec![PositioningInfo { axis: "Z".into(), target: Some(-5.0), velocity: -300.0, kind: "POSA", waiting: false }]
    );
    run_to_end(&mut ch);
    assert!(ch.snapshot().positioning.is_empty(), "gone once arrived");
}

#[test]
fn a_pos_block_waits_for_its_axis_and_the_state_says_so() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("POS[Z]=-5 FA[Z]=300\nPOSP[Y]=(3, 1) FA[Y]=600\nM30").unwrap();
    steps(&mut ch, 50);
    let p = ch.snapshot().positioning;
    assert_eq!(p.len(), 1, "{p:?}");
    assert_eq!((p[0].axis.as_str(), p[0].kind, p[0].waiting), ("Z", "POS", true));
    // Z arrives after about 250 cycles; then Y's POSP runs (parts of 1 mm at 10 mm/s).
    steps(&mut ch, 230);
    let p = ch.snapshot().positioning;
    assert_eq!(p.len(), 1, "{p:?}");
    assert_eq!((p[0].axis.as_str(), p[0].kind, p[0].target, p[0].waiting), ("Y", "POSP", Some(3.0), true));
    run_to_end(&mut ch);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
}

#[test]
fn a_restart_mid_posa_takes_the_axis_on_to_its_target_at_nc_start() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nG4 F5\nM30").unwrap();
    steps(&mut ch, 100);
    let at = z(&ch);
    assert!(at < -1.8 && at > -2.2, "Z = {at}");
    let saved = ch.resume_state();
    assert_eq!(saved.positioning.len(), 1, "{saved:?}");
    assert_eq!((saved.positioning[0].axis.as_str(), saved.positioning[0].end), ("Z", -5.0));

    // The restart: positions and the channel state on a new channel of the same data.
    let mut new = channel("mill-3axis", "");
    new.restore_positions(ch.axis_positions()).unwrap();
    new.restore_resume_state(&saved).unwrap();
    let s = new.snapshot();
    assert_eq!(s.status, Status::Stopped, "{:?}", s.alarms);
    assert_eq!(s.block.map(|b| b.line), Some(2));
    assert_eq!(s.positioning.len(), 1, "{:?}", s.positioning);
    assert_eq!((s.positioning[0].kind, s.positioning[0].target, s.positioning[0].velocity), ("POSA", Some(-5.0), 0.0));
    steps(&mut new, 20);
    assert_eq!(z(&new), at, "Z stands until NC start");
    // NC start: Z travels the remaining 3 mm at 5 mm/s (0.6 s = 150 cycles) while G4 dwells.
    new.start().unwrap();
    steps(&mut new, 160);
    assert_eq!(z(&new), -5.0);
    run_to_end(&mut new);
    assert!(new.alarms().is_empty(), "{:?}", new.alarms());
    assert_eq!(z(&new), -5.0);
}

#[test]
fn a_checkpoint_without_positioning_axes_has_none() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X5 F600\nM0\nM30").unwrap();
    run_to_end(&mut ch);
    assert!(ch.resume_state().positioning.is_empty());
}

#[test]
fn a_preprocessing_stop_behind_a_posa_axis_is_shown_while_the_path_stands() {
    // Programming Manual, POSA: a block after an (implicit or STOPRE) preprocessing stop runs
    // only once the positioning axes have arrived. Z needs 5 mm at 5 mm/s: about 250 cycles
    // (4 ms), so after 100 cycles the path stands at the STOPRE with X still at 0.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("POSA[Z]=-5 FA[Z]=300\nSTOPRE\nG1 X10 F1000\nM30").unwrap();
    steps(&mut ch, 100);
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Running);
    assert!(s.preprocessing_stop_wait, "the path waits for Z: {:?}", s.positioning);
    assert_eq!(ch.axis_positions()[0], 0.0, "X has not started");
    // Z arrives at cycle ~250; X then runs (10 mm at 1000 mm/min = 0.6 s = 150 cycles).
    steps(&mut ch, 200);
    let s = ch.snapshot();
    assert!(ch.axis_positions()[0] > 0.0, "X runs after the stop");
    assert!(!s.preprocessing_stop_wait, "the path moves: no wait");
    run_to_end(&mut ch);
    assert!(!ch.snapshot().preprocessing_stop_wait);
}

#[test]
fn a_path_decelerating_into_a_stopre_or_a_dwell_is_no_preprocessing_stop_wait() {
    // G1 into STOPRE: the path runs the block before the stop until its end, then the next
    // block follows in the same cycle: never a standing wait. A dwell is its own reason.
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G1 X2 F600\nSTOPRE\nG4 F0.5\nR1=$AA_IM[X]\nG1 X4\nM30").unwrap();
    let mut ticks = 0;
    while ch.status() == Status::Running && ticks < 2000 {
        ch.step();
        ticks += 1;
        assert!(!ch.snapshot().preprocessing_stop_wait, "cycle {ticks}");
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    assert_eq!(ch.axis_positions()[0], 4.0);
}
