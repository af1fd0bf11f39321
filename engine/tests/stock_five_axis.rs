//! Material removal on 5-axis machines (issue 28): the blank sits on the workpiece side of the
//! kinematic chain, so a trunnion table carries it, and a tilted tool cuts along its axis.
//!
//! Presets: `mill5-table-ac` (trunnion A carrying C, TRAORI type 33) and `mill5-head-ca`
//! (fork head C/A, TRAORI type 20), both with T1 D1 an end mill L100 R5. Resolution 0.25 mm.

use std::f64::consts::PI;

use nctwin_engine::Channel;
use nctwin_engine::channel::StockOptions;
use nctwin_engine::stock::Stock;

use crate::stock_support;

/// Runs `program` on `preset` to its end; the channel and the checks raised.
fn run(preset: &str, program: &str) -> (Channel, usize) {
    let (_, warnings, ch) = stock_support::run(preset, "", StockOptions::default(), program);
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    (ch, warnings.len())
}

/// The material intervals of the cell whose centre is (x, y) (a 0.25 mm grid from X−30 Y−30).
fn cell(ch: &mut Channel, x: f64, y: f64) -> Vec<[f32; 2]> {
    let Some(Stock::Milling(g)) = ch.stock() else { panic!("a milling stock") };
    let (x0, y0) = g.origin();
    let (i, j) = (((x - x0) / 0.25 - 0.5).round() as usize, ((y - y0) / 0.25 - 0.5).round() as usize);
    let mut out = Vec::new();
    g.intervals(i, j, &mut out);
    out
}

/// A hole drilled with the end mill under 30°: the tool axis tilted from Z towards −Y
/// (o = (0, −sin 30°, cos 30°), tip → holder), entering the top Z0 at E = (0, 0, 0) and
/// plunging 10 mm along its axis to F = E − 10·o = (0, 5, −8.660254). The blank: a box
/// X−30..30, Y−30..30, Z−20..0, on the table.
const TILTED_HOLE: &str = "G17 G90 G94\nT1 D1\nG0 X0 Y0 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-30,-30,30,30)\nS2000 M3\nTRAORI\nG1 X0 Y-15 Z25.980762 A3=0 B3=-0.5 C3=0.866025404 F2000\nG1 X0 Y5 Z-8.660254 F300\nG1 X0 Y-15 Z25.980762 F2000\nTRAFOOF\nM30";

#[test]
fn a_hole_under_30_degrees_on_the_trunnion_table_matches_the_head_machine_and_the_hand_values() {
    let (mut table, checks) = run("mill5-table-ac", TILTED_HOLE);
    assert_eq!(checks, 0);
    let table_info = table.stock_info().unwrap();
    // A cylinder of radius 5 cut by the top plane (which it crosses obliquely) and by its own
    // end face (fully below the top: the face's highest point is −8.660 + 5·sin 30° = −6.16):
    // the volume is the cross-section times the length along the axis, π·5²·10 = 785.40 mm³.
    // The grid samples the hole's outline (a stadium about 44 mm round, 176 rim cells of
    // 0.0625 mm² up to 10 mm deep); the error stays well inside 1.5 %.
    let expected = PI * 25.0 * 10.0;
    assert!((table_info.removed - expected).abs() < 0.015 * expected, "{table_info:?} vs {expected}");
    // Where: the vertical line through (0.125, 0.125), by the entry point, leaves the tool's
    // cylinder at z = (−qb − sqrt(qb² − 4·qa·qc)) / 2qa with the tip F: w = (0.125, −4.875,
    // 8.660254), w·o = 9.9375, qa = 1 − cos²30° = 0.25, qb = 2(8.660254 − 9.9375·0.866025)
    // = 0.108253, qc = |w|² − (w·o)² − 25 = −24.972656: z = −10.21338 (the end face only
    // bounds it at −11.47). The cell keeps Z−20..−10.21338.
    let v = cell(&mut table, 0.125, 0.125);
    assert_eq!(v.len(), 1, "{v:?}");
    assert!((v[0][1] as f64 + 10.21338).abs() < 1e-3, "{v:?}");
    // 4.75 mm either side of E along Y: towards +Y the line runs into the end face (h = −10
    // from E: z = (−10 + 2.4375) / 0.866025 = −8.73242), towards −Y it leaves the cylinder
    // near the top: w = (0.125, −4.875, 0) from E, w·o = 2.4375, qb = −4.221874, qc =
    // −7.160156: z = (4.221874 − 4.998438) / 0.5 = −1.55313.
    let plus = cell(&mut table, 0.125, 4.875);
    assert!((plus[0][1] as f64 + 8.73242).abs() < 1e-3, "{plus:?}");
    let minus = cell(&mut table, 0.125, -4.875);
    assert!((minus[0][1] as f64 + 1.55313).abs() < 1e-3, "{minus:?}");
    // Beyond the radius nothing: 5.125 from the axis sideways.
    assert_eq!(cell(&mut table, 5.125, 0.125), vec![[-20.0, 0.0]]);

    // The same program on the head machine: the same stock, the same place.
    let (mut head, checks) = run("mill5-head-ca", TILTED_HOLE);
    assert_eq!(checks, 0);
    let head_info = head.stock_info().unwrap();
    assert!((head_info.removed - table_info.removed).abs() < 0.01, "{head_info:?} vs {table_info:?}");
    for (x, y) in [(0.125, 0.125), (0.125, 4.875), (0.125, -4.875), (2.125, 2.125)] {
        let (a, b) = (cell(&mut table, x, y), cell(&mut head, x, y));
        assert_eq!(a.len(), b.len());
        for (p, q) in a.iter().zip(&b) {
            assert!((p[0] - q[0]).abs() < 1e-3 && (p[1] - q[1]).abs() < 1e-3, "({x}, {y}): {a:?} vs {b:?}");
        }
    }
}

#[test]
fn the_table_tilted_without_traori_carries_the_blank() {
    // The blank on mill5-table-ac at A = C = 0, then the table turned C90 by the axis itself
    // (no transformation): a slot cut along machine X at Y0 lies along the blank's Y. Type 33
    // reverses the axes (DIN), so C+90 turns the part by −90° about Z: the machine's X axis
    // is the blank's −Y... either way a line through the table's centre along Y.
    // The slot: R5 end mill at depth 2 from X−40 to X40 (machine): in the blank's frame the
    // strip |x| <= 5 over the full 60 mm length in Y, 2 deep: 10·60·2 = 1200 mm³, and the
    // strip |y| <= 5 along X untouched beyond the centre.
    let program = "G17 G90 G94\nT1 D1\nG0 X-50 Y0 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-30,-30,30,30)\nS2000 M3\nG0 C90\nG0 Z-2\nG1 X50 F2000\nG0 Z80\nM30";
    let (mut ch, _) = run("mill5-table-ac", program);
    let info = ch.stock_info().unwrap();
    assert!((info.removed - 1200.0).abs() < 1e-3, "{info:?}");
    assert_eq!(cell(&mut ch, 20.125, 0.125), vec![[-20.0, 0.0]]);
    assert_eq!(cell(&mut ch, 0.125, 20.125), vec![[-20.0, -2.0]]);
}
