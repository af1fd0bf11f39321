//! `Channel::refresh_snapshot` writes over a snapshot kept from earlier frames, possibly of
//! another machine; after every IPO cycle of several programs (more and fewer axes, a
//! transformation switched on and off, spindles, messages, a runtime alarm) it must equal a new
//! `Channel::snapshot`.

use nctwin_engine::{Channel, Snapshot};

/// What the runs went through, so the test proves it compared those states.
#[derive(Default)]
struct Seen {
    steps: usize,
    block: bool,
    alarm: bool,
    transformation: bool,
    message: bool,
    spindle: bool,
    gcode_changes: usize,
}

/// Runs `program` on `preset`, refreshing `kept` after each cycle and comparing it with a new
/// snapshot.
fn run_and_compare(preset: &str, program: &str, kept: &mut Snapshot, seen: &mut Seen) -> Channel {
    let mut ch = Channel::from_preset(preset, "").expect("preset");
    ch.run_program(program).expect("program");
    let mut last_gcodes = kept.gcodes.clone();
    for _ in 0..20_000 {
        if !ch.is_busy() {
            break;
        }
        ch.step();
        ch.refresh_snapshot(kept);
        let fresh = ch.snapshot();
        assert_eq!(*kept, fresh, "{preset} at tick {}", fresh.tick);
        seen.steps += 1;
        seen.block |= fresh.block.is_some();
        seen.alarm |= !fresh.alarms.is_empty();
        seen.transformation |= fresh.transformation.is_some();
        seen.message |= fresh.message.is_some();
        seen.spindle |= fresh.spindles.iter().any(|(_, speed)| *speed != 0.0);
        if fresh.gcodes != last_gcodes {
            seen.gcode_changes += 1;
            last_gcodes = fresh.gcodes;
        }
    }
    ch
}

#[test]
fn a_refreshed_snapshot_equals_a_new_one_through_several_programs() {
    let mut kept = Channel::from_preset("mill7-generic", "").expect("preset").snapshot();
    let mut seen = Seen::default();

    // Three axes, G0/G1/G2/G3 and G54/G500 changes, a spindle, a message set and cleared.
    let mill = "G54 T1 D1 S1000 M3\nMSG(\"roughing\")\nG0 X10 Y10 Z5\nG1 Z-1 F600\n\
                G2 X20 Y10 I5 J0\nG3 X10 Y10 I-5 J0\nMSG()\nG500 G1 X20\nM5\nG0 Z10\nM30";
    run_and_compare("mill-3axis", mill, &mut kept, &mut seen);

    // TRANSMIT on and off: BCS names and order change, the C axis drops out of the BCS.
    let transmit = "T1 D1 G17 F5000\nG0 X20 Z10\nTRANSMIT\nG1 X10 Y-10\nX-10\nY10\nTRAFOOF\nG0 X30\nM30";
    run_and_compare("transmit-example", transmit, &mut kept, &mut seen);

    // A runtime alarm (jump to a label that does not exist) stops the program; the alarm
    // stays in the snapshot until reset.
    let alarm = "G1 X5 F3000\nGOTOF NOWHERE\nM30";
    let mut ch = run_and_compare("mill-3axis", alarm, &mut kept, &mut seen);
    assert!(!ch.snapshot().alarms.is_empty(), "the jump raises an alarm");
    ch.reset();
    ch.refresh_snapshot(&mut kept);
    assert_eq!(kept, ch.snapshot(), "after reset");

    // Fewer axes again (a 2-axis lathe with its spindle), then the 7-axis machine as at the start.
    run_and_compare("lathe-2axis", "T1 D1 S500 M4\nG0 X40 Z5\nG1 Z-20 F200\nG0 X50\nM5\nM30", &mut kept, &mut seen);
    run_and_compare("mill7-generic", "G1 X10 Y5 Z-2 F2000\nG0 Z20\nM30", &mut kept, &mut seen);

    assert!(seen.steps > 500, "{} steps", seen.steps);
    assert!(seen.block && seen.alarm && seen.transformation && seen.message && seen.spindle);
    assert!(seen.gcode_changes >= 4, "{} G code changes", seen.gcode_changes);
}
