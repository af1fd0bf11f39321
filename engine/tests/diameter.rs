//! Diameter programming on the lathe (G group 29: DIAMOF 1, DIAMON 2, DIAM90 3, DIAMCYCOF 4;
//! MD20100 `$MC_DIAMETER_AX_DEF` = X on the lathe presets), worked out by hand from the
//! Programming Manual's description: under DIAMON X values are diameters (absolute and
//! incremental), under DIAM90 only absolute ones, DIAMCYCOF computes in radii while the
//! display keeps the diameter, and the WCS display shows the diameter when it is active.
//! Display checks stop at M0: after M30 the G functions are back at their reset values.

use crate::settle;

use nctwin_engine::Channel;

use settle::ran as run;

fn lathe(program: &str) -> Channel {
    let ch = run("lathe-2axis", "", program);
    assert!(ch.snapshot().alarms.is_empty(), "{:?}", ch.snapshot().alarms);
    ch
}

fn wcs(ch: &Channel, axis: &str) -> f64 {
    ch.snapshot().workpiece.iter().find(|(n, _)| n == axis).unwrap().1
}

fn machine_x(ch: &Channel) -> f64 {
    ch.axis_positions()[0]
}

/// `$P_GG[29]` at the end of `program` (written to R1 and read back through an alarm-free
/// comparison: the program raises 61000 when R1 differs from `want`).
fn gg29(program: &str, want: i64) {
    let text = format!("{program}\nR1=$P_GG[29]\nIF R1<>{want}\nSETAL(61000)\nENDIF\nM30");
    lathe(&text);
}

#[test]
fn diamon_halves_absolute_and_incremental_x_and_shows_the_diameter() {
    // DIAMON X40: radius 20. G91 X-10: a diameter step of 10 is 5 in the radius: 15.
    let ch = lathe("DIAMON\nG0 X40 Z5\nM0\nM30");
    assert!((machine_x(&ch) - 20.0).abs() < 1e-9);
    assert!((wcs(&ch, "X") - 40.0).abs() < 1e-9, "display {}", wcs(&ch, "X"));
    assert!((wcs(&ch, "Z") - 5.0).abs() < 1e-9);
    let ch = lathe("DIAMON\nG0 X40 Z5\nG91 X-10\nM0\nM30");
    assert!((machine_x(&ch) - 15.0).abs() < 1e-9);
    assert!((wcs(&ch, "X") - 30.0).abs() < 1e-9);
}

#[test]
fn diam90_takes_absolute_x_as_diameter_and_increments_as_radius() {
    // DIAM90 X40: radius 20; G91 X-10: radius 10.
    let ch = lathe("DIAM90\nG0 X40 Z5\nG91 X-10\nM0\nM30");
    assert!((machine_x(&ch) - 10.0).abs() < 1e-9);
    assert!((wcs(&ch, "X") - 20.0).abs() < 1e-9);
    // X=IC(-10) under G90 is an increment: radius too.
    let ch = lathe("DIAM90\nG0 X40 Z5\nX=IC(-10)\nM30");
    assert!((machine_x(&ch) - 10.0).abs() < 1e-9);
}

#[test]
fn diamof_is_radius_programming_again() {
    let ch = lathe("DIAMON\nG0 X40\nDIAMOF\nX30\nM0\nM30");
    assert!((machine_x(&ch) - 30.0).abs() < 1e-9);
    assert!((wcs(&ch, "X") - 30.0).abs() < 1e-9);
}

#[test]
fn diamcycof_computes_in_radius_and_keeps_the_diameter_display() {
    // After DIAMON, DIAMCYCOF: X30 is a radius (30), the display shows the diameter 60.
    let ch = lathe("DIAMON\nG0 X40\nDIAMCYCOF\nX30\nM0\nM30");
    assert!((machine_x(&ch) - 30.0).abs() < 1e-9);
    assert!((wcs(&ch, "X") - 60.0).abs() < 1e-9);
    // After DIAMOF it shows the radius.
    let ch = lathe("DIAMOF\nDIAMCYCOF\nG0 X30\nM0\nM30");
    assert!((wcs(&ch, "X") - 30.0).abs() < 1e-9);
}

#[test]
fn p_gg_29_reads_the_position_in_the_group() {
    gg29("", 1);
    gg29("DIAMOF", 1);
    gg29("DIAMON", 2);
    gg29("DIAM90", 3);
    gg29("DIAMON\nDIAMCYCOF", 4);
}

#[test]
fn the_g_code_display_names_group_29() {
    let ch = lathe("DIAMON\nG0 X40\nM0\nM30");
    assert!(ch.snapshot().gcodes.iter().any(|g| g == "DIAMON"), "{:?}", ch.snapshot().gcodes);
}

#[test]
fn md20150_gives_the_reset_value_of_group_29() {
    // MD20150[28] = 2: DIAMON after reset, X40 is the diameter.
    let ch = run("lathe-2axis", "$MC_GCODE_RESET_VALUES[28]=2", "G0 X40\nM0\nM30");
    assert!((machine_x(&ch) - 20.0).abs() < 1e-9);
    assert!((wcs(&ch, "X") - 40.0).abs() < 1e-9);
}

#[test]
fn diamon_without_a_transverse_axis_raises_16510() {
    // The mill has no MD20100.
    let ch = run("mill-3axis", "", "DIAMON\nG0 X40\nM30");
    let alarms = ch.snapshot().alarms;
    assert_eq!(alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), [(16510, Some(1))]);
}

#[test]
fn md20100_must_name_a_geometry_axis() {
    assert!(Channel::from_preset("lathe-2axis", "$MC_DIAMETER_AX_DEF=\"Q\"").is_err());
    assert!(Channel::from_preset("lathe-2axis", "$MC_GCODE_RESET_VALUES[28]=5").is_err());
}

#[test]
fn g96_under_diamon_follows_the_radius() {
    // G96 S200 at programmed diameter 50 (radius 25): n = 200000 / (π · 50) = 1273.2 rev/min.
    let ch = run("lathe-2axis", "", "DIAMON\nG0 X50 Z2\nG96 S200 M3 LIMS=3000\nG4 F3\nM30");
    let n = ch.snapshot().spindles.iter().find(|(n, _)| n == "SP").unwrap().1;
    assert!((n - 200_000.0 / (std::f64::consts::PI * 50.0)).abs() < 0.01, "{n}");
}

#[test]
fn g4_s_under_g96_counts_revolutions_at_the_speed_of_the_diameter() {
    // At diameter 50 G96 S200 gives n = 200000 / (π · 50) = 1273.24 rev/min; G4 S10 takes
    // 10 / 1273.24 min = 0.4712 s more than the same program without it.
    let with = run("lathe-2axis", "", "DIAMON\nG0 X50 Z2\nG96 S200 M3 LIMS=3000\nG4 F2\nG4 S10\nM5\nM30");
    let without = run("lathe-2axis", "", "DIAMON\nG0 X50 Z2\nG96 S200 M3 LIMS=3000\nG4 F2\nM5\nM30");
    assert!(with.snapshot().alarms.is_empty(), "{:?}", with.snapshot().alarms);
    let dt = with.time() - without.time();
    let want = 10.0 * 60.0 / (200_000.0 / (std::f64::consts::PI * 50.0));
    assert!((dt - want).abs() <= 2.0 * with.config().ipo_cycle, "{dt} s, want {want} s");
}

#[test]
fn md20150_5_gives_the_reset_plane() {
    // The lathe preset sets G18 (2); on the mill MD20150[5] = 3 makes G19 the reset plane.
    let check = |preset: &str, md: &str, want: i64| {
        let text = format!("R1=$P_GG[6]\nIF R1<>{want}\nSETAL(61000)\nENDIF\nM30");
        let ch = run(preset, md, &text);
        assert!(ch.snapshot().alarms.is_empty(), "{preset} {md}: {:?}", ch.snapshot().alarms);
    };
    check("lathe-2axis", "", 2);
    check("mill-3axis", "", 1);
    check("mill-3axis", "$MC_GCODE_RESET_VALUES[5]=3", 3);
    assert!(Channel::from_preset("mill-3axis", "$MC_GCODE_RESET_VALUES[5]=4").is_err());
}
