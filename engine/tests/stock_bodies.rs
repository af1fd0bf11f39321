//! The collision check of material removal with the tool's own data (issue 28): the shank
//! above the cutting length (a default per tool type, `stock/body.rs`) and the spindle housing
//! of `$MC_SPINDLE_HOUSING`. Volumes by hand; `mill-3axis`, resolution 0.25 mm.

use std::f64::consts::PI;

use nctwin_engine::channel::{StockCheck, StockOptions};

use crate::stock_support;

/// A 60 x 50 x 40 block X−10..50, Y−10..40, Z−40..0, and a plunge at X20 Y15 to `depth` with
/// T3 D1 (line 7), then the retract (line 8).
fn plunge(depth: f64) -> String {
    format!(
        "G17 G90 G94\nT3 D1\nG0 X20 Y15 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-40,-80,-10,-10,50,40)\nS1000 M3\nG0 Z2\nG1 Z{depth} F300\nG0 Z80\nM30"
    )
}

#[test]
fn a_short_tool_plunging_deeper_than_its_flutes_brings_its_shank_into_the_stock() {
    // T3: end mill R3 (D6), 40 long. It cuts over 3·D = 18 mm; above, shank and chuck are a
    // Ø12 body up to the gauge line. To Z−15 the body's bottom stays at Z3: nothing. To Z−20
    // it goes to Z−2: the ring between the hole (R3) and R6 holds Z−2..0, 2 thick:
    // π (6² − 3²) · 2 = 169.65 mm³ at the plunge's line 7 with the tip at Z−20 (the check
    // reports a block's first contact: the plunge is cut in pieces of at most 8 mm, Z2..−6,
    // −6..−14, −14..−20, and only the last reaches below Z−18); the retract (line 8) starts
    // with the body still in: reported too. The ring's two rims, 2π·9 mm, cross 226 cells:
    // at most half a cell 2 deep each, ±14.
    let md = "$TC_DP1[3,1]=120\n$TC_DP3[3,1]=40.\n$TC_DP6[3,1]=3.\n";
    let (_, warnings, _) = stock_support::run("mill-3axis", md, StockOptions::default(), &plunge(-15.0));
    assert!(warnings.is_empty(), "{warnings:?}");
    let (info, warnings, _) = stock_support::run("mill-3axis", md, StockOptions::default(), &plunge(-20.0));
    assert_eq!(
        warnings.iter().map(|w| (w.check, w.line)).collect::<Vec<_>>(),
        vec![(StockCheck::HolderCollision, 7), (StockCheck::HolderCollision, 8)]
    );
    let w = warnings[0];
    assert!((w.depth - 2.0).abs() < 1e-4 && (w.position[2] + 20.0).abs() < 1e-6, "{w:?}");
    let bound = 0.5 * (2.0 * PI * 9.0 / 0.25) * 0.0625 * 2.0;
    assert!((w.volume - PI * 27.0 * 2.0).abs() < bound, "{w:?}");
    // The shank removes nothing: the hole is the flutes' (π·9·20 within its rim's cells).
    assert!((info.removed - PI * 9.0 * 20.0).abs() < 0.5 * (2.0 * PI * 3.0 / 0.25) * 0.0625 * 20.0, "{info:?}");
}

#[test]
fn the_spindle_housing_of_the_machine_data_touches_the_top_of_the_block() {
    // T3: end mill R5, 30 long: it cuts over its whole length (3·D = 30), no shank. The
    // housing Ø100 × 150 from the gauge line up: a plunge to Z−32 brings its face to Z−2.
    // Centred on X20 Y15 with radius 50 it covers the whole top of the block (the farthest
    // corner, X−10 Y−10, lies 39 mm away): (60·50 − π·5²) · 2 = 5842.92 mm³ at line 7; the
    // hole's rim crosses 126 cells, half a cell 2 deep each at most: ±7.9. To Z−29 it stays
    // above the top, and without the datum nothing is checked.
    let tool = "$TC_DP1[3,1]=120\n$TC_DP3[3,1]=30.\n$TC_DP6[3,1]=5.\n";
    let md = format!("{tool}$MC_SPINDLE_HOUSING[0]=100\n$MC_SPINDLE_HOUSING[1]=150\n");
    let (_, warnings, _) = stock_support::run("mill-3axis", &md, StockOptions::default(), &plunge(-32.0));
    let w = warnings[0];
    assert_eq!((w.check, w.line), (StockCheck::HolderCollision, 7), "{warnings:?}");
    assert!((w.depth - 2.0).abs() < 1e-4, "{w:?}");
    let bound = 0.5 * (2.0 * PI * 5.0 / 0.25) * 0.0625 * 2.0;
    assert!((w.volume - (3000.0 - 25.0 * PI) * 2.0).abs() < bound, "{w:?}");
    let (_, warnings, _) = stock_support::run("mill-3axis", &md, StockOptions::default(), &plunge(-29.0));
    assert!(warnings.is_empty(), "{warnings:?}");
    let (_, warnings, _) = stock_support::run("mill-3axis", tool, StockOptions::default(), &plunge(-32.0));
    assert!(warnings.is_empty(), "{warnings:?}");
}
