//! Material removal under TRANSMIT, TRACYL and TRAANG (issue 28): the blank in the work
//! spindle turns with C, so the cut follows the transformed motion in the workpiece's frame;
//! volumes worked out by hand.
//!
//! Presets (presets.rs): `transmit-example` T1 D1 end mill R4, length 30 (along Z in G17);
//! `tracyl-xyzc` T1 D1 slot mill R6, length 9 (along the radial X in G19); both with C as the
//! spindle holding the blank. Resolution 0.25 mm: the milled grid samples the cells' centres,
//! so a volume is right to half the cells its rims cross.

use std::f64::consts::PI;

use nctwin_engine::Channel;
use nctwin_engine::channel::{StockInfo, StockOptions};
use nctwin_engine::stock::Stock;

use crate::stock_support;

/// Runs `program` on `preset` to its end (no alarm); the stock summary and the channel.
fn run(preset: &str, md: &str, program: &str) -> (StockInfo, Channel) {
    let (info, _, ch) = stock_support::run(preset, md, StockOptions::default(), program);
    (info, ch)
}

/// The top of the material of the cell whose centre is nearest to (x, y) (workpiece frame).
fn top_at(ch: &mut Channel, x: f64, y: f64) -> Option<f32> {
    stock_support::cell(ch, x, y).last().map(|v| v[1])
}

#[test]
fn a_transmit_slot_across_the_face_removes_the_chord_strip() {
    // A bar Ø50, Z−40..0, in the spindle. Under TRANSMIT the end mill R4 (tip at Z−2) runs
    // along Y10 from X40 to X−35 across the whole face while C turns under it: the slot is the
    // strip 6 ≤ y ≤ 14 of the face's disc, 2 deep. Area ∫₆¹⁴ 2√(625 − y²) dy with
    // F(y) = y√(625 − y²) + 625·asin(y/25): F(14) − F(6) = 661.463 − 297.095 = 364.369;
    // volume 2 · 364.369 = 728.74 mm³. The strip's walls lie on cell edges (the grid is
    // centred on the axis), its two rims on the disc cross about 64 cells: ±64·0.0625·2/2.
    let program = "G17 G90 G94 T1 D1\nG0 X120 Z50\nWORKPIECE(,\"\",,\"CYLINDER\",0,0,-40,-80,50)\n\
                   TRANSMIT\nG1 X40 Y10 Z5 F1000\nG1 Z-2\nG1 X-35\nG1 Z5\nTRAFOOF\nM30";
    let (info, mut ch) = run("transmit-example", "", program);
    assert!((info.removed - 728.74).abs() < 4.0, "{info:?}");
    assert_eq!(info.skipped, 0);
    assert!(!info.turning, "the face slot made the bar dexels");
    // In the workpiece (TRANSMIT's X/Y) the slot lies at Y10, not mirrored to Y−10.
    assert_eq!(top_at(&mut ch, 0.0, 10.0), Some(-2.0));
    assert_eq!(top_at(&mut ch, 20.0, 12.0), Some(-2.0));
    assert_eq!(top_at(&mut ch, 0.0, -10.0), Some(0.0));
    assert_eq!(top_at(&mut ch, 0.0, 0.0), Some(0.0));
}

#[test]
fn a_tracyl_groove_on_the_periphery_removes_its_stadium_under_the_surface() {
    // A bar Ø60, Z−50..0. TRACYL(60): Y is the arc on Ø60, so Y23.5619 = 30·π/4 is 45°. The
    // radial slot mill R6 (tip at radius 27: 3 deep) runs 20 mm along Z (Z−10 → −30). In the
    // tool's frame (u radial, v across, w along Z) it removes, over the stadium of its axis
    // (|v| ≤ 6 around the 20 mm line), the material between u = 27 and the surface √(900 − v²):
    // 20·A + D with A = ∫₋₆⁶ (√(900 − v²) − 27) dv = 2(3√864 + 450·asin 0.2) − 324 = 33.585
    // and the two half discs D = ∫₋₆⁶ 2√(36 − v²)(√(900 − v²) − 27) dv = 322.24 (Simpson):
    // 671.71 + 322.24 = 993.95 mm³. The groove's footprint (12 wide, 3 deep, walls at 45°)
    // has about 60 rim cells of up to 0.0625·20 mm³ each, half of it the bound: ±15.
    let program = "G19 G90 G94 T1 D1\nG0 X50 Y0 Z10\nWORKPIECE(,\"\",,\"CYLINDER\",0,0,-50,-80,60)\n\
                   TRACYL(60)\nG0 X40 Y23.5619449 Z-10\nG1 X27 F1000\nG1 Z-30\nG0 X50\nTRAFOOF\nM30";
    let (info, mut ch) = run("tracyl-xyzc", "", program);
    assert!((info.removed - 993.95).abs() < 15.0, "{info:?}");
    assert_eq!(info.skipped, 0);
    // The groove's floor at 45°: the cell at radius 28.5 on the diagonal has lost Z−30..−10
    // (−4 to −36 with the tool's radius along Z, which the plunge at Z−10 and the end at Z−30
    // round off: at the axis's line the full 6 mm beyond each end).
    let d = 28.5 / 2f64.sqrt();
    let Some(Stock::Milling(g)) = ch.stock() else { panic!() };
    let (x0, y0) = g.origin();
    let (i, j) = (((d - x0) / 0.25) as usize, ((d - y0) / 0.25) as usize);
    let mut iv = Vec::new();
    g.intervals(i, j, &mut iv);
    assert_eq!(iv.len(), 2, "{iv:?}");
    assert!((iv[0][1] + 36.0).abs() < 0.3 && (iv[1][0] + 4.0).abs() < 0.3, "{iv:?}");
    // At 0° and at −45° the surface is whole.
    assert_eq!(top_at(&mut ch, 28.5, 0.0), Some(0.0));
    assert_eq!(top_at(&mut ch, d, -d), Some(0.0));
}

#[test]
fn turning_on_the_slant_bed_under_its_persistent_traang_removes_the_ring() {
    // The slant-bed lathe keeps TRAANG (30°) active: X and Z are Cartesian, the slide MU moves
    // both. A sharp external tool (T2, position 3, radius 0) turns a bar Ø50 down to Ø46 over
    // 20 mm: π (25² − 23²) · 20 = 6031.86 mm³, exact on the profile's slabs (X is a radius
    // until DIAMON).
    let md = "$TC_DP1[2,1]=500\n$TC_DP2[2,1]=3\n$TC_DP3[2,1]=0.\n$TC_DP4[2,1]=0.\n";
    let program = "G18 G90 G95 T2 D1\nG0 X120 Z50\nWORKPIECE(,\"\",,\"CYLINDER\",0,0,-60,-80,50)\n\
                   S1000 M3\nG0 X23 Z2\nG1 Z-20 F0.2\nG1 X30\nG0 X120 Z50\nM30";
    let (info, _) = run("slant-lathe-tracon", md, program);
    assert!(info.turning);
    assert_eq!(info.skipped, 0);
    assert!((info.removed - PI * 96.0 * 20.0).abs() < 1e-6, "{info:?}");
}

#[test]
fn turning_after_the_face_slot_removes_the_ring_from_the_dexels() {
    // The slot of the TRANSMIT test, then TRAFOOF and a sharp turning tool (T2, position 3)
    // with the spindle turning: Ø50 → Ø46 over Z0..−10, the ring π (25² − 23²) · 10 = 3015.93
    // less what the slot already took of it: the strip 6 ≤ y ≤ 14 between R23 and R25, 2 deep.
    // With G(y) = y√(529 − y²) + 529·asin(y/23): G(14) − G(6) = 601.532 − 272.834 = 328.698
    // of the strip lies within R23, 364.369 within R25: 2 · 35.671 = 71.34 counted once.
    // Slot 728.74 + ring 2944.59 = 3673.33; the ring's rims cross ~1200 cells whose sampling
    // errors mostly cancel: within 1 %.
    let md = "$TC_DP1[2,1]=500\n$TC_DP2[2,1]=3\n$TC_DP3[2,1]=0.\n$TC_DP4[2,1]=0.\n";
    let program = "G17 G90 G94 T1 D1\nG0 X120 Z50\nWORKPIECE(,\"\",,\"CYLINDER\",0,0,-40,-80,50)\n\
                   TRANSMIT\nG1 X40 Y10 Z5 F1000\nG1 Z-2\nG1 X-35\nG1 Z5\nTRAFOOF\n\
                   G18 T2 D1\nS1000 M3\nG0 X23 Z2\nG1 Z-10 F200\nG1 X30\nG0 X120 Z50\nM30";
    let (info, mut ch) = run("transmit-example", md, program);
    assert!((info.removed - 3673.33).abs() < 37.0, "{info:?}");
    assert_eq!(info.skipped, 0);
    // Outside R23 down to Z−10 wherever the cell lies round the axis; the slot at Y10 inside
    // R23 stays 2 deep, the face elsewhere whole.
    assert_eq!(top_at(&mut ch, 0.0, 24.0), Some(-10.0));
    assert_eq!(top_at(&mut ch, -17.0, -17.0), Some(-10.0));
    assert_eq!(top_at(&mut ch, 0.0, 10.0), Some(-2.0));
    assert_eq!(top_at(&mut ch, 0.0, -10.0), Some(0.0));
}
