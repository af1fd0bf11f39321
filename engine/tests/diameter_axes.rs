//! Axis-specific diameter programming on the lathe (Programming Manual "Fundamentals":
//! DIAMONA[ax], DIAM90A[ax], DIAMOFA[ax], DIACYCOFA[ax], DIAMCHANA[ax], DIAMCHAN; MD30460
//! `$MA_BASE_FUNCTION_MASK` bit 2 releases an axis for it). Worked out by hand: under
//! DIAMONA[X] the X values are diameters (absolute and incremental) whatever the channel's
//! G group 29 says, DIAM90A[X] only absolute ones, DIAMOFA[X] radii; DIAMCHANA[X] links the
//! axis to the channel's group 29 again and DIAMCHAN links every released axis. The
//! lathe-2axis preset releases X (MD30460 bit 2), not Z; its reset value is DIAMOF.

use crate::settle;

use nctwin_engine::Channel;

fn channel(md: &str) -> Channel {
    Channel::from_preset("lathe-2axis", md).unwrap()
}

use settle::finish;

fn lathe_md(md: &str, program: &str) -> Channel {
    let mut ch = channel(md);
    finish(&mut ch, program);
    assert!(ch.snapshot().alarms.is_empty(), "{program}: {:?}", ch.snapshot().alarms);
    ch
}

fn lathe(program: &str) -> Channel {
    lathe_md("", program)
}

fn wcs(ch: &Channel, axis: &str) -> f64 {
    ch.snapshot().workpiece.iter().find(|(n, _)| n == axis).unwrap().1
}

fn machine(ch: &Channel, k: usize) -> f64 {
    ch.axis_positions()[k]
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn diamona_makes_x_a_diameter_under_channel_diamof() {
    // X40: radius 20, shown as the diameter 40. G91 X-10: a diameter step, 5 in the radius.
    let ch = lathe("DIAMONA[X]\nG0 X40 Z5\nM0\nM30");
    assert!(close(machine(&ch, 0), 20.0), "{}", machine(&ch, 0));
    assert!(close(wcs(&ch, "X"), 40.0), "display {}", wcs(&ch, "X"));
    let ch = lathe("DIAMONA[X]\nG0 X40 Z5\nG91 X-10\nM0\nM30");
    assert!(close(machine(&ch, 0), 15.0));
    assert!(close(wcs(&ch, "X"), 30.0));
}

#[test]
fn diam90a_takes_absolute_values_as_diameters_and_increments_as_radii() {
    // X40: radius 20; G91 X-10: radius 10; X=IC(-4) under G90: radius 6.
    let ch = lathe("DIAM90A[X]\nG0 X40 Z5\nG91 X-10\nM0\nM30");
    assert!(close(machine(&ch, 0), 10.0));
    let ch = lathe("DIAM90A[X]\nG0 X40 Z5\nX=IC(-4)\nM0\nM30");
    assert!(close(machine(&ch, 0), 16.0));
}

#[test]
fn an_axis_with_its_own_mode_ignores_the_channel_until_diamchana() {
    // DIAMOFA[X] then the channel's DIAMON: X30 stays a radius (30) and is shown as one.
    let ch = lathe("DIAMOFA[X]\nDIAMON\nG0 X30 Z5\nM0\nM30");
    assert!(close(machine(&ch, 0), 30.0));
    assert!(close(wcs(&ch, "X"), 30.0));
    // DIAMONA[X] then the channel's DIAMOF: X40 is still a diameter (radius 20).
    let ch = lathe("DIAMONA[X]\nDIAMOF\nG0 X40 Z5\nM0\nM30");
    assert!(close(machine(&ch, 0), 20.0));
    // DIAMCHANA[X] links X to the channel's DIAMON again: X40 radius 20.
    let ch = lathe("DIAMOFA[X]\nDIAMON\nDIAMCHANA[X]\nG0 X40 Z5\nM0\nM30");
    assert!(close(machine(&ch, 0), 20.0));
    assert!(close(wcs(&ch, "X"), 40.0));
}

#[test]
fn diamchan_links_every_released_axis_to_the_channel() {
    // Z released by MD30460 bit 2. Under the channel's DIAMON, Z40 is a radius (40) until
    // DIAMCHAN links Z: then Z40 is a diameter, radius 20 (Z is machine axis 2 here).
    let md = "$MA_BASE_FUNCTION_MASK[Z1]=4";
    let ch = lathe_md(md, "DIAMON\nG0 X40 Z40\nM0\nM30");
    assert!(close(machine(&ch, 1), 40.0), "{}", machine(&ch, 1));
    let ch = lathe_md(md, "DIAMON\nDIAMCHAN\nG0 X40 Z40\nM0\nM30");
    assert!(close(machine(&ch, 1), 20.0), "{}", machine(&ch, 1));
    assert!(close(machine(&ch, 0), 20.0));
    // DIAMONA[Z]: Z alone is a diameter, X follows the channel's DIAMOF.
    let ch = lathe_md(md, "DIAMONA[Z]\nG0 X40 Z40\nM0\nM30");
    assert!(close(machine(&ch, 1), 20.0));
    assert!(close(machine(&ch, 0), 40.0));
}

#[test]
fn diacycofa_computes_in_radius_and_keeps_the_diameter_display() {
    // After DIAMONA[X], DIACYCOFA[X]: X30 is the radius 30, the display shows 60.
    let ch = lathe("DIAMONA[X]\nDIACYCOFA[X]\nG0 X30 Z5\nM0\nM30");
    assert!(close(machine(&ch, 0), 30.0));
    assert!(close(wcs(&ch, "X"), 60.0));
}

#[test]
fn the_channel_group_29_is_unchanged_by_the_axis_words() {
    // $P_GG[29] reads the channel's mode: DIAMOF (1) after DIAMONA[X].
    let ch = lathe("DIAMONA[X]\nR1=$P_GG[29]\nIF R1<>1\nSETAL(61000)\nENDIF\nM30");
    assert!(ch.snapshot().alarms.is_empty());
}

#[test]
fn program_end_returns_to_the_reset_state() {
    // DIAMONA[X] ends with M30: the next program's X40 is a radius again.
    let mut ch = channel("");
    finish(&mut ch, "DIAMONA[X]\nG0 X40 Z5\nM30");
    finish(&mut ch, "G0 X40 Z5\nM30");
    assert!(ch.snapshot().alarms.is_empty());
    assert!(close(machine(&ch, 0), 40.0));
}

#[test]
fn an_axis_not_released_by_md30460_raises_16510_and_an_unknown_axis_12550() {
    for (program, number) in [("G0 X0\nDIAMONA[Z]\nM30", 16510), ("G0 X0\nDIAMONA[Q]\nM30", 12550)] {
        let mut ch = channel("");
        finish(&mut ch, program);
        let alarms: Vec<_> = ch.snapshot().alarms.iter().map(|a| (a.number, a.line)).collect();
        assert_eq!(alarms, vec![(number, Some(2))], "{program}");
    }
    // On the mill nothing is released.
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    finish(&mut ch, "DIAMONA[X]\nM30");
    assert_eq!(ch.snapshot().alarms.iter().map(|a| a.number).collect::<Vec<_>>(), vec![16510]);
}

#[test]
fn an_axis_with_its_own_diameter_programming_shows_its_diameter_in_the_wcs() {
    // Z released (MD30460 bit 2): DIAMONA[Z], Z40 is the radius 20 (machine Z20) and the WCS
    // display shows the diameter 40, as for the transverse axis; X (channel DIAMOF) shows its
    // radius 40. DIAMOFA[Z] afterwards: Z30 is a radius again and shows 30.
    let md = "$MA_BASE_FUNCTION_MASK[Z1]=4";
    let ch = lathe_md(md, "DIAMONA[Z]\nG0 X40 Z40\nM0\nM30");
    assert!(close(machine(&ch, 1), 20.0));
    assert!(close(wcs(&ch, "Z"), 40.0), "Z shows {}", wcs(&ch, "Z"));
    assert!(close(wcs(&ch, "X"), 40.0), "X shows {}", wcs(&ch, "X"));
    let ch = lathe_md(md, "DIAMONA[Z]\nG0 X40 Z40\nDIAMOFA[Z]\nG0 Z30\nM0\nM30");
    assert!(close(wcs(&ch, "Z"), 30.0), "Z shows {}", wcs(&ch, "Z"));
    // Linked to the channel by DIAMCHAN under DIAMON: Z shows its diameter with X.
    let ch = lathe_md(md, "DIAMON\nDIAMCHAN\nG0 X40 Z40\nM0\nM30");
    assert!(close(wcs(&ch, "Z"), 40.0) && close(wcs(&ch, "X"), 40.0));
}
