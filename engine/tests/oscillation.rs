//! Asynchronous oscillation (Function Manual P5, `OS`/`OSP1`/`OSP2`/`OST1`/`OST2`/`FA`/
//! `OSCTRL`/`OSNSC`/`OSE`/`OSB`): the axis reverses exactly at its reversal points, keeps its
//! stop times, and ends as the control bits say. The 3-axis mill: X accelerates with
//! 3000 mm/s², IPO cycle 4 ms.

use nctwin_engine::{Channel, Status};

const DT: f64 = 0.004;

/// Runs `program` on the 3-axis mill; returns the X position of every IPO cycle and the
/// channel at the end.
fn run(program: &str) -> (Vec<f64>, Channel) {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(program).unwrap();
    let mut xs = Vec::new();
    while ch.is_busy() {
        ch.step();
        xs.push(ch.axis_positions()[0]);
        assert!(xs.len() < 200_000, "the program does not end");
    }
    (xs, ch)
}

/// The cycles in which X lands on a reversal point (a stroke's last cycle: X there, the cycle
/// before not).
fn landings(xs: &[f64], points: [f64; 2]) -> Vec<(usize, f64)> {
    xs.windows(2)
        .enumerate()
        .filter(|(_, w)| points.contains(&w[1]) && w[0] != w[1])
        .map(|(i, w)| (i + 1, w[1]))
        .collect()
}

#[test]
fn the_axis_reverses_exactly_at_its_points_with_the_stroke_time_of_its_feed() {
    // Strokes of 50 mm at FA 3000 mm/min = 50 mm/s with 3000 mm/s²: the ramps take
    // 50/3000 s and the stroke lasts 50/50 + 50/3000 = 1.0167 s, 254.2 cycles. Point 2 has
    // OST2 = 0.5 s, 125 cycles more for the stroke that leaves it. Y travels 100 mm at
    // F600 (10 s) meanwhile; OS=0 lets X stop at the next reversal point.
    let program = "G0 X0 Y0\nOSP1[X]=10 OSP2[X]=60 OST1[X]=0 OST2[X]=0.5 FA[X]=3000\nOS[X]=1\n\
                   G1 Y100 F600\nOS[X]=0\nR1=$AA_IM[Y]\nM30";
    let (xs, ch) = run(program);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    assert!(xs.iter().all(|x| (0.0..=60.0).contains(x)), "never beyond its points");
    let lands = landings(&xs, [10.0, 60.0]);
    assert!(lands.len() >= 8, "{lands:?}");
    assert_eq!(lands[0].1, 10.0, "to reversal point 1 first");
    for w in lands.windows(2) {
        assert_ne!(w[0].1, w[1].1, "alternating: {lands:?}");
        let cycles = (w[1].0 - w[0].0) as f64;
        // Leaving point 2 it stood 0.5 s first.
        let expected = 50.0 / 50.0 + 50.0 / 3000.0 + if w[0].1 == 60.0 { 0.5 } else { 0.0 };
        assert!((cycles * DT - expected).abs() <= 2.0 * DT, "{} s between {w:?}", cycles * DT);
    }
    // The block after OS=0 ran once X stood on a reversal point, after Y's 10 s.
    let last = *xs.last().unwrap();
    assert!(last == 10.0 || last == 60.0, "{last}");
    assert_eq!(ch.r_param(1), 100.0);
    assert!(ch.time() >= 10.0);
}

#[test]
fn ending_goes_to_reversal_point_2_then_sparks_out_and_travels_to_the_end_position() {
    // OSCTRL 2 + 4: stop at point 2, then the end position; two one-way spark-out strokes
    // from point 2: to 1 and back to 2, then to OSE 70. No stop times. Without path motion
    // OS=0 is read at once: X is on its way to point 1 (at 10 from 0), goes on to 1, then to 2
    // (the stop point), strokes to 1 and 2, then 70: the landings 10, 60, 10, 60, then 70.
    let program = "G0 X0\nOSP1[X]=10 OSP2[X]=60 FA[X]=3000 OSCTRL[X]=(2+4,0) OSNSC[X]=2 OSE[X]=70\n\
                   OS[X]=1\nOS[X]=0\nR1=$AA_IM[X]\nG91 G1 X-5 F3000\nM30";
    let (xs, ch) = run(program);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    let lands: Vec<f64> = landings(&xs, [10.0, 60.0]).into_iter().map(|(_, x)| x).collect();
    assert_eq!(lands, [10.0, 60.0, 10.0, 60.0]);
    assert_eq!(ch.r_param(1), 70.0, "the block after OS=0 sees the end position");
    // Preparation went on from there: the incremental move ends at 65.
    assert_eq!(*xs.last().unwrap(), 65.0);
}

#[test]
fn a_start_position_first_with_bit_512() {
    // OSB 35 with OSCTRL 512: from 0 to 35, then to point 1 (10); OSCTRL 1: ends at point 1.
    let program = "G0 X0\nOSP1[X]=10 OSP2[X]=60 OSB[X]=35 FA[X]=3000 OSCTRL[X]=(512+1,0)\nOS[X]=1\n\
                   G4 F1\nOS[X]=0\nM30";
    let (xs, ch) = run(program);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    let first_35 = xs.iter().position(|&x| x == 35.0).expect("reaches the start position");
    assert!(xs[..first_35].iter().all(|x| (0.0..35.0).contains(x)));
    assert!(xs[first_35..].iter().all(|&x| x <= 35.0), "then down to point 1, never to 60 within 1 s");
    assert_eq!(*xs.last().unwrap(), 10.0);
}

#[test]
fn a_path_block_programming_the_oscillating_axis_is_alarm_14092() {
    let (_, ch) = run("OSP1[X]=10 OSP2[X]=60 FA[X]=3000\nOS[X]=1\nG1 X20 F1000\nM30");
    let alarms = ch.snapshot().alarms;
    assert_eq!(alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(14092, Some(3))]);
}

#[test]
fn the_program_end_brakes_an_oscillation_left_on() {
    // No OS=0: M30 brakes X where it is; the program ends. After 0.5 s X has passed point 1
    // (10 mm from 0 take 0.2 s) and is on its way to point 2: it brakes within 0.42 mm.
    let (xs, ch) = run("G0 X0\nOSP1[X]=10 OSP2[X]=60 FA[X]=3000\nOS[X]=1\nG4 F0.5\nM30");
    assert_eq!(ch.snapshot().status, Status::Idle);
    assert!(ch.snapshot().alarms.is_empty());
    let last = *xs.last().unwrap();
    assert!(last > 10.0 && last < 60.0, "braked on the way to point 2: {last}");
}

#[test]
fn equal_reversal_points_and_bad_values_are_refused() {
    let (_, ch) = run("OSP1[X]=10 OSP2[X]=10\nOS[X]=1\nM30");
    assert_eq!(ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(12560, Some(2))]);
    for (program, line) in
        [("OS[X]=2\nM30", 1), ("OSNSC[X]=-1\nM30", 1), ("OST1[X]=-3\nM30", 1), ("OSCTRL[X]=5\nM30", 1)]
    {
        let (_, ch) = run(program);
        let alarms = ch.snapshot().alarms;
        assert_eq!(alarms.first().and_then(|a| a.line), Some(line), "{program}: {alarms:?}");
    }
}
