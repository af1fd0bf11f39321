//! Data a part program reads and writes besides its own variables: machine and setting data
//! (`$MN_`/`$MC_`/`$MA_`/`$SN_`/`$SC_`/`$SA_`), the digital inputs and outputs (`$A_IN`,
//! `$A_OUT`), and the M and H functions it hands to the PLC. Expected values come from the
//! mill-3axis preset's machine data (engine/src/machine_data/presets.rs) and the registry's
//! defaults, worked out at each test.

use crate::settle;

use nctwin_engine::interp::auxiliary::AuxFunction;
use nctwin_engine::interp::eval::value::Value;
use nctwin_engine::{Channel, Event, Status};

const MAX_TICKS: usize = 2_000_000;

fn channel() -> Channel {
    Channel::from_preset("mill-3axis", "").unwrap()
}

/// Runs `program` on `ch` to its end; returns the events it produced.
fn run_on(ch: &mut Channel, program: &str) -> Vec<Event> {
    ch.take_events();
    ch.run_program(program).unwrap_or_else(|e| panic!("not started: {e}"));
    let mut events = Vec::new();
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        events.extend(ch.take_events());
        ticks += 1;
        assert!(ticks < MAX_TICKS, "program does not end");
    }
    events.extend(ch.take_events());
    events
}

use settle::assert_ok as ok;

fn alarm(ch: &Channel) -> (u32, Option<u32>) {
    let s = ch.snapshot();
    assert_eq!(s.status, Status::Alarm, "expected an alarm");
    (s.alarms[0].number, s.alarms[0].line)
}

fn aux(events: &[Event]) -> Vec<(String, u32)> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::AuxFunction { function, line } => Some((function.text(), *line)),
            _ => None,
        })
        .collect()
}

// --- Machine and setting data reads ---------------------------------------------------------

#[test]
fn axial_machine_data_read_by_channel_name_axn_and_machine_name() {
    // Preset: MAX_AX_VELO 30000 mm/min on X; POS_LIMIT_PLUS[Y] = 300; POS_LIMIT_MINUS[Z] = -400.
    // On mill-3axis the machine axes are named X, Y, Z like the channel axes, so AX2 is Y.
    let mut ch = channel();
    run_on(
        &mut ch,
        "R1=$MA_MAX_AX_VELO[X]\nR2=$MA_POS_LIMIT_PLUS[AX2]\nR3=$MA_POS_LIMIT_MINUS[Z]\nR4=$MA_MAX_AX_ACCEL[AX1]\nM30",
    );
    ok(&ch);
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3), ch.r_param(4)], [30000.0, 300.0, -400.0, 3.0]);
}

#[test]
fn general_and_channel_data_read_with_defaults_and_strings() {
    // Registry defaults: MD10070 IPO_SYSCLOCK_TIME_RATIO = 2, MD20250 CUTCOM_MAXNUM_DUMMY_BLOCKS
    // = 3, MD20060 AXCONF_GEOAX_NAME_TAB[1] = "Y"; preset: MACHAX_NAME_TAB[2] = "Z".
    let mut ch = channel();
    run_on(
        &mut ch,
        "DEF STRING[8] GEO, MACH\nR1=$MN_IPO_SYSCLOCK_TIME_RATIO\nR2=$MC_CUTCOM_MAXNUM_DUMMY_BLOCKS\n\
         GEO=$MC_AXCONF_GEOAX_NAME_TAB[1]\nMACH=$MN_AXCONF_MACHAX_NAME_TAB[2]\n\
         IF (GEO==\"Y\") AND (MACH==\"Z\")\nR3=1\nENDIF\nR4=$SC_TOFRAME_MODE\nM30",
    );
    ok(&ch);
    assert_eq!([ch.r_param(1), ch.r_param(2), ch.r_param(3)], [2.0, 3.0, 1.0]);
    // SD42980's default is 2000.
    assert_eq!(ch.r_param(4), 2000.0);
    assert_eq!(ch.variable("GEO", 0), Some(Value::Str("Y".into())));
}

#[test]
fn bad_machine_data_reads_are_alarms_at_their_line() {
    let cases = [
        // GEOAX_NAME_TAB has 3 elements: index 3 is outside (17020).
        ("G0 X1\nR1=$MC_AXCONF_GEOAX_NAME_TAB[3]\nM30", 17020, 2),
        // Axial data needs its axis.
        ("R1=$MA_MAX_AX_VELO\nM30", 17020, 1),
        // No such axis.
        ("R1=$MA_MAX_AX_VELO[Q]\nM30", 17020, 1),
        // No such datum.
        ("N10 R1=0\nR1=$MC_NO_SUCH_DATUM\nM30", 12550, 2),
    ];
    for (program, number, line) in cases {
        let mut ch = channel();
        run_on(&mut ch, program);
        assert_eq!(alarm(&ch), (number, Some(line)), "{program}");
    }
}

// --- Writes -----------------------------------------------------------------------------------

#[test]
fn setting_data_written_in_a_program_act_at_once_and_reach_the_config() {
    // SD42980 TOFRAME_MODE is setting data: writable, effective immediately.
    let mut ch = channel();
    run_on(&mut ch, "$SC_TOFRAME_MODE=2001\nR1=$SC_TOFRAME_MODE\nM30");
    ok(&ch);
    assert_eq!(ch.r_param(1), 2001.0);
    assert_eq!(ch.config().toframe_mode, 2001);
}

#[test]
fn machine_data_written_read_back_as_stored_and_act_after_newconf() {
    // The written limit reads back at once (the stored value) but limits travel only after
    // NEWCONF: G0 X60 runs before it; after NEWCONF G0 X70 is beyond +50 (10720).
    let mut ch = channel();
    run_on(&mut ch, "$MA_POS_LIMIT_PLUS[X]=50\nR1=$MA_POS_LIMIT_PLUS[AX1]\nG0 X60\nNEWCONF\nG0 X70\nM30");
    assert_eq!(ch.r_param(1), 50.0);
    assert_eq!(alarm(&ch), (10720, Some(5)));
}

#[test]
fn axial_data_written_by_channel_axis_name_on_a_lathe_reaches_the_machine_axis() {
    // lathe-2axis: channel axis Z runs on machine axis Z1 (AX2).
    let mut ch = Channel::from_preset("lathe-2axis", "").unwrap();
    run_on(&mut ch, "$MA_POS_LIMIT_PLUS[Z]=123\nR1=$MA_POS_LIMIT_PLUS[Z1]\nR2=$MA_POS_LIMIT_PLUS[AX2]\nM30");
    ok(&ch);
    assert_eq!([ch.r_param(1), ch.r_param(2)], [123.0, 123.0]);
}

// --- M and H functions --------------------------------------------------------------------------

#[test]
fn m_and_h_functions_reach_the_main_run_in_block_order() {
    // On the lathe: `M1=3` addresses its spindle 1 (the 3-axis mill has no spindle yet).
    let mut ch = Channel::from_preset("lathe-2axis", "").unwrap();
    let events = run_on(&mut ch, "G0 X10 M8\nH2=1.5 H7\nM1=3 S1000\nG4 F0.1\nM9 M5\nM30");
    ok(&ch);
    let want: Vec<(String, u32)> = [("M8", 1), ("H2=1.5", 2), ("H7", 2), ("M1=3", 3), ("M9", 5), ("M5", 5), ("M30", 6)]
        .iter()
        .map(|(t, l)| (t.to_string(), *l))
        .collect();
    assert_eq!(aux(&events), want);
}

#[test]
fn program_end_is_output_after_the_motion_of_its_block() {
    // M8 comes before the block's motion, M30 after it: the block change to line 1 and the
    // M8 event precede any later event; M30 is the last auxiliary function, just before the end.
    let mut ch = channel();
    let events = run_on(&mut ch, "G1 X10 F1000 M8 M30");
    ok(&ch);
    let kinds: Vec<&str> = events
        .iter()
        .filter_map(|e| match e {
            Event::AuxFunction { function: AuxFunction { value, .. }, .. } if *value == 8.0 => Some("M8"),
            Event::AuxFunction { .. } => Some("M30"),
            Event::ProgramEnded => Some("end"),
            _ => None,
        })
        .collect();
    assert_eq!(kinds, ["M8", "M30", "end"]);
}

// --- Digital inputs and outputs -----------------------------------------------------------------

#[test]
fn a_program_branches_on_an_input_and_sets_an_output() {
    let mut ch = channel();
    ch.set_signals(&[(3, true)], &[]).unwrap();
    let events = run_on(&mut ch, "IF $A_IN[3]==1 GOTOF YES\nR1=0\nGOTOF END\nYES: R1=1\nEND: $A_OUT[2]=1\nM30");
    ok(&ch);
    assert_eq!(ch.r_param(1), 1.0);
    assert_eq!(ch.digital_io().output(2), Some(true));
    assert!(events.iter().any(|e| matches!(e, Event::DigitalOutput { signal: 2, on: true, line: 5 })));
    // The program reads its own output back, after the main run set it.
    run_on(&mut ch, "$A_OUT[2]=0\nR2=$A_OUT[2]\n$A_OUT[4]=TRUE\nR3=$A_OUT[4]\nM30");
    ok(&ch);
    assert_eq!([ch.r_param(2), ch.r_param(3)], [0.0, 1.0]);
}

#[test]
fn an_output_is_set_after_the_motion_before_it() {
    // G1 X10 at 600 mm/min takes 1 s; the output of the next block is set only then.
    let mut ch = channel();
    ch.run_program("G1 X10 F600\n$A_OUT[1]=1\nM30").unwrap();
    for _ in 0..200 {
        ch.step();
    }
    assert_eq!(ch.digital_io().output(1), Some(false), "after 0.8 s the axis still moves");
    while ch.is_busy() {
        ch.step();
    }
    assert_eq!(ch.digital_io().output(1), Some(true));
}

#[test]
fn inputs_are_write_protected_and_signals_bounded() {
    let mut ch = channel();
    run_on(&mut ch, "G0 X1\n$A_IN[1]=1\nM30");
    assert_eq!(alarm(&ch), (17070, Some(2)));
    let mut ch = channel();
    run_on(&mut ch, "$A_OUT[17]=1\nM30");
    assert_eq!(alarm(&ch), (17020, Some(1)));
    let mut ch = channel();
    assert!(ch.set_signals(&[(1, true)], &[(0, true)]).is_err());
    assert_eq!(ch.digital_io().input(1), Some(false), "all or nothing");
}

// --- Words accepted without effect on motion ------------------------------------------------

#[test]
fn workpiece_and_actblocno_are_accepted_without_effect_on_motion() {
    // The blank of a ShopMill-style header (empty arguments included) and ACTBLOCNO in a block.
    let mut ch = channel();
    run_on(&mut ch, "WORKPIECE(,\"\",,\"RECTANGLE\",0,0,-20,-80,0,0,120,80)\nACTBLOCNO\nG0 X12 Y7\nM30");
    ok(&ch);
    let s = ch.snapshot();
    let x = s.workpiece.iter().find(|(n, _)| n == "X").unwrap().1;
    let y = s.workpiece.iter().find(|(n, _)| n == "Y").unwrap().1;
    assert_eq!((x, y), (12.0, 7.0));
}

// --- CALLPATH -------------------------------------------------------------------------------

/// A channel holding HOLE in the workpiece folder FIXTURE and in the manufacturer cycles
/// (CMA), each moving to a different X, and SLOT only in FIXTURE.
fn with_fixture_programs() -> Channel {
    use nctwin_engine::programs::{Dir, StoredProgram};
    let mut ch = channel();
    let fixture = || Some(Dir::Workpiece("FIXTURE".into()));
    let store = ch.program_store_mut();
    store.add(StoredProgram::checked("HOLE".into(), fixture(), None, "G0 X1\nM17\n".into()));
    store.add(StoredProgram::checked("SLOT".into(), fixture(), None, "G0 Y2\nM17\n".into()));
    store.add(StoredProgram::checked("HOLE".into(), Some(Dir::Cma), None, "G0 X9\nM17\n".into()));
    ch
}

#[test]
fn callpath_searches_its_directory_after_spf_and_before_the_cycle_directories() {
    // Without CALLPATH the main program (flat store) finds HOLE only in CMA (X9) and no SLOT
    // (14011). With CALLPATH to the workpiece folder, HOLE comes from there (X1) and SLOT too.
    let mut ch = with_fixture_programs();
    run_on(&mut ch, "HOLE\nM30");
    ok(&ch);
    assert_eq!(ch.snapshot().workpiece[0].1, 9.0);
    let mut ch = with_fixture_programs();
    run_on(&mut ch, "G0 X0\nSLOT\nM30");
    assert_eq!(alarm(&ch), (14011, Some(2)));
    let mut ch = with_fixture_programs();
    run_on(&mut ch, "CALLPATH(\"/_N_WKS_DIR/_N_FIXTURE_WPD\")\nHOLE\nSLOT\nM30");
    ok(&ch);
    let s = ch.snapshot();
    assert_eq!((s.workpiece[0].1, s.workpiece[1].1), (1.0, 2.0));
}

#[test]
fn callpath_without_a_path_ends_the_extension() {
    let mut ch = with_fixture_programs();
    run_on(&mut ch, "CALLPATH(\"/_N_WKS_DIR/_N_FIXTURE_WPD\")\nCALLPATH()\nHOLE\nM30");
    ok(&ch);
    assert_eq!(ch.snapshot().workpiece[0].1, 9.0);
}
