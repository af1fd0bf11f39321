//! The hole pattern cycles HOLES1, HOLES2, CYCLE801 and CYCLE802: the drilling cycle selected
//! with MCALL runs at every position of the pattern. Positions worked out by hand from the
//! documented parameters (reference point, angle, distances, number of holes).

use crate::cycles_support;
use cycles_support::*;

/// The (X, Y) of every hole drilled below Z0 and its depth.
fn holes(main: &str) -> Vec<[f64; 3]> {
    run_clean(main).holes(0.0)
}

fn assert_holes(got: &[[f64; 3]], want: &[(f64, f64)], depth: f64) {
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!(close(g[0], w.0, 1e-6) && close(g[1], w.1, 1e-6) && close(g[2], depth, 1e-6), "{got:?} vs {want:?}");
    }
}

#[test]
fn holes1_drills_a_row_at_an_angle() {
    // Reference (10, 5), 30°, first hole 20 from it, 15 apart, 3 holes: at distance 20, 35, 50
    // along (cos 30°, sin 30°) = (0.866025, 0.5).
    let main = "G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE81(10,0,2,-4)\nHOLES1(10,5,30,20,15,3)\nMCALL\nM30";
    let c = 3f64.sqrt() / 2.0;
    let want: Vec<_> = [20.0, 35.0, 50.0].iter().map(|d| (10.0 + d * c, 5.0 + d * 0.5)).collect();
    assert_holes(&holes(main), &want, -4.0);
}

#[test]
fn holes2_drills_a_circle_and_divides_it_evenly_without_inda() {
    // Centre (50, 40), R 20, first hole at 45°, INDA 0 and 4 holes: every 90°.
    let main = "G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE82(10,0,2,-3,,0.2)\nHOLES2(50,40,20,45,0,4)\nMCALL\nM30";
    let r = 20.0 / 2f64.sqrt();
    assert_holes(
        &holes(main),
        &[(50.0 + r, 40.0 + r), (50.0 - r, 40.0 + r), (50.0 - r, 40.0 - r), (50.0 + r, 40.0 - r)],
        -3.0,
    );
    // INDA -30: 3 holes at 0°, -30°, -60°.
    let main = "G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE81(10,0,2,-3)\nHOLES2(0,0,10,0,-30,3)\nMCALL\nM30";
    let (s, c) = (0.5, 3f64.sqrt() / 2.0);
    assert_holes(&holes(main), &[(10.0, 0.0), (10.0 * c, -10.0 * s), (10.0 * s, -10.0 * c)], -3.0);
}

#[test]
fn cycle801_drills_a_grid_in_a_meander_and_a_frame_only_on_its_border() {
    // 3 columns 10 apart, 2 rows 8 apart, from (0, 0), angle 0: row 0 left to right, row 1 back.
    let main = "G17 G90 F300\nG0 X-10 Y-10 Z50\nMCALL CYCLE81(10,0,2,-2)\nCYCLE801(0,0,0,10,8,3,2)\nMCALL\nM30";
    assert_holes(&holes(main), &[(0.0, 0.0), (10.0, 0.0), (20.0, 0.0), (20.0, 8.0), (10.0, 8.0), (0.0, 8.0)], -2.0);
    // A 3 x 3 frame at 90°: the rows run along +Y, the row distance along -X; the centre hole is left out.
    let main = "G17 G90 F300\nG0 X-10 Y-10 Z50\nMCALL CYCLE81(10,0,2,-2)\nCYCLE801(0,0,90,5,5,3,3,1)\nMCALL\nM30";
    let got = holes(main);
    assert_holes(
        &got,
        &[(0.0, 0.0), (0.0, 5.0), (0.0, 10.0), (-5.0, 10.0), (-5.0, 0.0), (-10.0, 0.0), (-10.0, 5.0), (-10.0, 10.0)],
        -2.0,
    );
}

#[test]
fn cycle802_drills_the_chosen_positions() {
    // _ROW 101000000: positions 0 and 2 only.
    let main =
        "G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE81(10,0,2,-2)\nCYCLE802(111111111,101000000,5,6,7,8,9,10)\nMCALL\nM30";
    assert_holes(&holes(main), &[(5.0, 6.0), (9.0, 10.0)], -2.0);
    // Without _ROW: every position up to the last one given.
    let main = "G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE81(10,0,2,-2)\nCYCLE802(,,5,6,7,8,9,10)\nMCALL\nM30";
    assert_holes(&holes(main), &[(5.0, 6.0), (7.0, 8.0), (9.0, 10.0)], -2.0);
}

#[test]
fn a_pattern_without_mcall_only_positions() {
    let t = run_clean("G17 G90 F300\nG0 X0 Y0 Z50\nHOLES1(0,0,0,10,10,2)\nM30");
    assert!(t.holes(0.0).is_empty());
    assert_eq!(t.end(), [20.0, 0.0, 50.0]);
}

#[test]
fn patterns_with_no_holes_raise_61103_or_61106_at_the_call() {
    for (call, number) in
        [("HOLES1(0,0,0,10,10,0)", 61103), ("HOLES2(0,0,10,0,90,5)", 61106), ("CYCLE801(0,0,0,5,5,0,2)", 61106)]
    {
        let t = run(&format!("G17 G90 F300\nG0 X0 Y0 Z50\nMCALL CYCLE81(10,0,2,-2)\n{call}\nM30"));
        assert_eq!(t.alarms.iter().map(|a| (a.number, a.line)).collect::<Vec<_>>(), vec![(number, Some(4))], "{call}");
    }
}
