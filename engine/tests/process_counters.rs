//! Workpiece counters, program runtimes and the clock (Function Manual K1, "Program runtime /
//! workpiece counter"): what programs read and write and what the main run counts, with the
//! values worked out from the programs' own times (a dwell of G4 F2 is 2 s, 60 mm at F600 is
//! 6 s plus the ramps) and the machine data bits as the manual numbers them.

use crate::settle::{self, channel, steps};
use nctwin_engine::{Channel, Overrides};

const CYCLE: f64 = 0.004;

fn run(ch: &mut Channel, program: &str) {
    settle::finish(ch, program);
}

fn alarms(ch: &Channel) -> Vec<u32> {
    ch.snapshot().alarms.iter().map(|a| a.number).collect()
}

#[test]
fn the_cycle_time_is_the_programs_time_and_starts_again_with_the_next_program() {
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, "G4 F2\nR1=$AC_CYCLE_TIME R2=$AC_OPERATING_TIME R3=$AC_CUTTING_TIME\nM30");
    // The dwell is 2 s; the read waits for the main run, a few cycles after it.
    let (cycle, operating) = (ch.r_param(1), ch.r_param(2));
    assert!((2.0 - 1e-9..2.0 + 5.0 * CYCLE).contains(&cycle), "{cycle}");
    assert_eq!(operating, cycle, "both run from the program's start");
    assert_eq!(ch.r_param(3), 0.0, "a dwell is no cutting time");
    let first = ch.runtimes();
    run(&mut ch, "G4 F1\nR1=$AC_CYCLE_TIME R2=$AC_OPERATING_TIME\nM30");
    let (cycle, operating) = (ch.r_param(1), ch.r_param(2));
    assert!((1.0 - 1e-9..1.0 + 5.0 * CYCLE).contains(&cycle), "the second program's own time: {cycle}");
    assert!((operating - (first.operating + cycle)).abs() < 1e-9, "the operating time sums both: {operating}");
}

#[test]
fn the_cutting_time_counts_feed_motion_with_a_tool_and_leaves_out_rapid_traverse() {
    let program = |tool: &str| format!("{tool}\nG0 X-100 Y0 Z5\nG1 X-40 F600\nG0 X100\nR1=$AC_CUTTING_TIME\nM30");
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, &program("T1 D1 M6"));
    // 60 mm at 600 mm/min is 6 s, plus the acceleration ramps (10 mm/s at 3 m/s²: about
    // 3 ms more); the two rapid moves do not count.
    let cutting = ch.r_param(1);
    assert!((6.0 - 1e-9..6.05).contains(&cutting), "{cutting}");
    assert!(ch.runtimes().cycle > cutting + 0.1, "the rapid moves are in the cycle time");
    // Without an active tool it does not count (MD27860 bit 7 clear) ...
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, &program("T0 D0"));
    assert_eq!(ch.r_param(1), 0.0);
    // ... unless MD27860 bit 7 says so: 'H177' + bit 7 = 'H1F7'.
    let mut ch = channel("mill-3axis", "$MC_PROCESSTIMER_MODE='H1F7'");
    run(&mut ch, &program("T0 D0"));
    assert!((6.0 - 1e-9..6.05).contains(&ch.r_param(1)));
}

#[test]
fn a_stopped_program_and_a_feed_override_of_zero_stop_the_clocks() {
    let mut ch = channel("mill-3axis", "");
    ch.run_program("G4 F1\nM0\nG4 F1\nR1=$AC_CYCLE_TIME\nM30").unwrap();
    for _ in 0..1000 {
        ch.step();
        if ch.snapshot().status == nctwin_engine::Status::Stopped {
            break;
        }
    }
    // Two seconds at M0, then two seconds at feed override 0 during the second dwell: a
    // dwell runs on (it is no path motion), but the clocks stand.
    steps(&mut ch, 500);
    ch.start().unwrap();
    ch.set_overrides(Overrides { feed: 0.0, ..ch.overrides() }).unwrap();
    steps(&mut ch, 100);
    ch.set_overrides(Overrides { feed: 100.0, ..ch.overrides() }).unwrap();
    settle::settle(&mut ch);
    let cycle = ch.r_param(1);
    // Both dwells (2 s) less the 100 cycles at override 0 the second dwell ran through.
    let expected = 2.0 - 100.0 * CYCLE;
    assert!((expected - 1e-9..expected + 5.0 * CYCLE).contains(&cycle), "{cycle} against {expected}");
}

#[test]
fn m30_counts_the_actual_parts_and_the_required_count_resets_them_with_alarm_21800() {
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, "$AC_REQUIRED_PARTS=3\nM30");
    assert_eq!(ch.part_counts().actual, 1, "the default MD27880 'H901' counts actual parts on M30");
    run(&mut ch, "M30");
    assert_eq!(ch.part_counts().actual, 2);
    assert!(alarms(&ch).is_empty());
    run(&mut ch, "R1=$AC_ACTUAL_PARTS\nM2");
    assert_eq!(ch.r_param(1), 2.0, "read before its own M2");
    assert_eq!(ch.part_counts().actual, 0, "the third part reached the setpoint: counted from 0 again");
    assert_eq!(alarms(&ch), [21800], "information only: the program ended normally");
    assert_eq!(ch.part_counts().total, 0, "the total count is off by default");
    // A program end without M2/M30 (the end of the text) is no output of either.
    run(&mut ch, "G4 F0.1");
    assert_eq!(ch.part_counts().actual, 0);
}

#[test]
fn the_machine_data_choose_the_counters_and_their_m_functions() {
    // 'H3313' with M80, M17, M77 (the manual's "all counters"): total on M2/M30 (bit 5 clear),
    // actual on M17, special on M77, the required count watched against the special one.
    let md = "$MC_PART_COUNTER='H3313'\n$MC_PART_COUNTER_MCODE[0]=80\n$MC_PART_COUNTER_MCODE[1]=17\n$MC_PART_COUNTER_MCODE[2]=77";
    let mut ch = channel("mill-3axis", md);
    run(&mut ch, "$AC_REQUIRED_PARTS=2\nM77\nM80\nM30");
    let p = ch.part_counts();
    assert_eq!((p.total, p.actual, p.special), (1, 0, 1));
    run(&mut ch, "M77\nM17");
    let p = ch.part_counts();
    assert_eq!((p.total, p.actual, p.special), (1, 1, 2), "M17 ends a main program without M2/M30");
    assert_eq!(alarms(&ch), [21800], "special reached the setpoint of 2");
    assert_eq!(p.special, 2, "the special count is the user's to reset");
    // Bit 20: the actual count does not run in MDA mode.
    let mut ch = channel("mill-3axis", "$MC_PART_COUNTER='H100100'");
    ch.mda("M30").unwrap();
    settle::settle(&mut ch);
    assert_eq!(ch.part_counts().actual, 0);
    run(&mut ch, "M30");
    assert_eq!(ch.part_counts().actual, 1);
}

#[test]
fn gotos_counts_a_part_and_clears_the_cycle_time() {
    // Two jumps back to the start and one M30: three parts (MD27880 bit 11 of 'H901').
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, "R1=R1+1\nG4 F0.5\nR2=$AC_CYCLE_TIME\nIF R1<3 GOTOS\nM30");
    assert_eq!(ch.part_counts().actual, 3);
    // MD27860 bit 8 ('H177'): the cycle time starts again at each GOTOS, so the last pass
    // read its own half second (to the IPO cycle: the GOTOS's own cycle belongs to the pass
    // before).
    let cycle = ch.r_param(2);
    assert!((0.5 - CYCLE - 1e-9..0.5 + 5.0 * CYCLE).contains(&cycle), "{cycle}");
}

#[test]
fn programs_write_the_counters_markers_and_parameters_in_block_order() {
    let mut ch = channel("mill-3axis", "");
    run(
        &mut ch,
        "$AC_TOTAL_PARTS=41 $AC_SPECIAL_PARTS=7.6\n$AC_MARKER[1]=2.6 $AC_PARAM[3]=1.25\n\
         R1=$AC_TOTAL_PARTS R2=$AC_SPECIAL_PARTS R3=$AC_MARKER[1] R4=$AC_PARAM[3]\nM30",
    );
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4)], [41.0, 8.0, 3.0, 1.25]);
    let p = ch.part_counts();
    assert_eq!((p.total, p.special, p.actual), (41, 8, 1));
    // A reset keeps them.
    ch.reset();
    assert_eq!(ch.part_counts(), p);
}

#[test]
fn writes_outside_the_counters_range_or_to_a_runtime_are_alarms_at_their_block() {
    for (program, number) in [
        ("G4 F0.1\n$AC_ACTUAL_PARTS=-1\nM30", 12560),
        ("G4 F0.1\n$AC_REQUIRED_PARTS=1000000000\nM30", 12560),
        ("G4 F0.1\n$AC_CYCLE_TIME=0\nM30", 17070),
        ("G4 F0.1\n$AC_MARKER[8]=1\nM30", 17020),
        ("G4 F0.1\n$AC_ACTUAL_PARTS[1]=1\nM30", 17020),
    ] {
        let mut ch = channel("mill-3axis", "");
        run(&mut ch, program);
        let s = ch.snapshot();
        assert_eq!(s.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(number, Some(2))], "{program}");
        assert_eq!(ch.part_counts().actual, 0, "{program}: the M30 was not reached");
    }
}

#[test]
fn the_clock_runs_from_the_wall_time_the_shell_gave_with_the_simulated_time() {
    let mut ch = channel("mill-3axis", "");
    // 2026-11-27 23:59:58.500 UTC (20,784 days after 1970-01-01).
    ch.set_clock((20_784 * 86_400 + 86_398) * 1000 + 500);
    run(&mut ch, "R1=$A_SECOND\nG4 F2\nR2=$A_YEAR R3=$A_MONTH R4=$A_DAY R5=$A_HOUR R6=$A_MINUTE R7=$A_SECOND\nM30");
    assert_eq!(ch.r_param(1), 58.0);
    // Two seconds later it is the next day.
    let read: Vec<f64> = (2..=7).map(|n| ch.r_param(n)).collect();
    assert_eq!(read, [2026.0, 11.0, 28.0, 0.0, 0.0, 0.0]);
}

#[test]
fn channel_number_spindles_and_dry_run_read_as_the_channel_has_them() {
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, "R1=$P_CHANNO R2=$P_NUM_SPINDLES R3=$P_DRYRUN\nM30");
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3)], [1.0, 1.0, 0.0]);
    let mut ch = channel("lathe-counter-spindle", "");
    ch.dry_run = true;
    run(&mut ch, "R1=$P_NUM_SPINDLES R2=$P_DRYRUN\nM30");
    assert_eq!([ch.r_param(1), ch.r_param(2)], [2.0, 1.0]);
}

#[test]
fn a_checkpoint_keeps_the_counters_and_runtimes() {
    let mut ch = channel("mill-3axis", "");
    run(&mut ch, "$AC_REQUIRED_PARTS=10 $AC_TOTAL_PARTS=5\nG4 F1\nM30");
    let saved = ch.resume_state();
    assert!(saved.counters.is_some());
    let mut restored = channel("mill-3axis", "");
    restored.restore_resume_state(&saved).unwrap();
    assert_eq!(restored.part_counts(), ch.part_counts());
    assert_eq!(restored.runtimes(), ch.runtimes());
    // A fresh channel writes none.
    assert!(channel("mill-3axis", "").resume_state().counters.is_none());
}

#[test]
fn a_program_resumed_after_a_restart_counts_on_from_its_checkpoints_cycle_time() {
    // The program stops at M0 after a dwell of 1 s; the checkpoint has that second. A new
    // channel takes the checkpoint back (block search to the M0), NC start runs the second
    // dwell: the cycle time reads 2 s at the end, the operating time likewise.
    let program = "G4 F1\nM0\nG4 F1\nR1=$AC_CYCLE_TIME\nM30";
    let mut ch = channel("mill-3axis", "");
    ch.run_program(program).unwrap();
    for _ in 0..1000 {
        ch.step();
        if ch.snapshot().status == nctwin_engine::Status::Stopped {
            break;
        }
    }
    let saved = ch.resume_state();
    let mut restored = channel("mill-3axis", "");
    restored.restore_resume_state(&saved).unwrap();
    restored.start().unwrap();
    settle::settle(&mut restored);
    let cycle = restored.r_param(1);
    assert!((2.0 - 1e-9..2.0 + 10.0 * CYCLE).contains(&cycle), "{cycle}");
    assert!((restored.runtimes().operating - restored.runtimes().cycle).abs() < 1e-9);
}
