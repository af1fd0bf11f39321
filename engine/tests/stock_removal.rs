//! Material removal (issue 28): volumes worked out by hand, and the checks while cutting.
//!
//! Presets (presets.rs): `mill-3axis` T1 D1 end mill R5 (type 120), T2 D1 twist drill R4
//! (type 200, 118° point); `lathe-2axis` T1 D1 roughing tool SL3 nose 0.8, X as a radius.
//! The default resolution is 0.25 mm. Milling volumes are sampled at the cells' centres, so
//! the bound on the error is half the volume of the cells a curved rim crosses (straight
//! walls on cell edges are exact); turning slabs tile the blank, so a face on a slab boundary
//! is exact in Z and radii are exact.

use crate::stl_support;
use crate::stock_support;

use std::f64::consts::PI;

use nctwin_engine::Channel;
use nctwin_engine::channel::{StockCheck, StockInfo, StockOptions, StockWarning};
use stl_support::box_stl;
use stock_support::run;

fn mill(program: &str) -> (StockInfo, Vec<StockWarning>, Channel) {
    run("mill-3axis", "", StockOptions::default(), program)
}

/// A 60 x 50 x 20 block, X−10..50, Y−10..40, Z−20..0; the tool is above it first (at power on
/// the tip stands at Z−100, the tool's length below the spindle's zero).
const BLOCK: &str = "G17 G90 G94\nT1 D1\nG0 X-30 Y15 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\n";

#[test]
fn the_blank_of_workpiece_holds_its_volume() {
    let (info, warnings, _) = mill(&format!("{BLOCK}M30"));
    assert!((info.initial_volume - 60.0 * 50.0 * 20.0).abs() < 1e-6, "{info:?}");
    assert_eq!((info.removed, warnings.len()), (0.0, 0));
}

#[test]
fn a_pocket_40_by_30_by_5_removes_6000_less_its_corners() {
    // The end mill R5 clears X0..40, Y0..30, 5 deep: its centre runs the raster Y5/12/19/25
    // (rows 7 apart, less than the diameter) from X5 to X35 and the contour at 5 from the walls.
    // The pocket's corners keep the tool's radius: 40·30·5 − 4·(1 − π/4)·5²·5 = 5892.70 mm³.
    let program = format!(
        "{BLOCK}S3000 M3\nG0 X5 Y5 Z2\nG1 Z-5 F200\nG1 X35 F1000\nY12\nX5\nY19\nX35\nY25\nX5\nY5\nX35\nY25\nX5\nG0 Z10\nM30"
    );
    let (info, warnings, _) = mill(&program);
    let expected = 6000.0 - 4.0 * (1.0 - PI / 4.0) * 25.0 * 5.0;
    // The corner arcs (4 · π/2 · 5 mm) cross 126 cells of 0.0625 mm²; half of them, 5 deep.
    let bound = 0.5 * (4.0 * PI / 2.0 * 5.0 / 0.25) * 0.0625 * 5.0;
    assert!((info.removed - expected).abs() < bound, "removed {} vs {expected} ± {bound}", info.removed);
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn a_drilled_hole_removes_the_cylinder_and_the_point_cone() {
    // Drill R4, 118° point: the cone is h = 4 / tan 59° = 2.4034 high. Tip at Z−10:
    // π·4²·(10 − h) + π·4²·h/3 = 422.12 mm³.
    let program = "G17 G90 G94\nT2 D1\nG0 X20 Y15 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,-10,-10,50,40)\nS1000 M3\nG0 Z2\nG1 Z-10 F100\nG0 Z10\nM30";
    let (info, warnings, _) = mill(program);
    let h = 4.0 / 59f64.to_radians().tan();
    let expected = PI * 16.0 * (10.0 - h) + PI * 16.0 * h / 3.0;
    // The rim (2π·4) crosses about 101 cells: half of them over the 10 mm.
    let bound = 0.5 * (2.0 * PI * 4.0 / 0.25) * 0.0625 * 10.0;
    assert!((info.removed - expected).abs() < bound, "removed {} vs {expected} ± {bound}", info.removed);
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn rapid_through_the_blank_is_reported_at_its_line_and_above_it_not() {
    // Line 7 travels G0 at Z−3 through the block (X−20 → X60 at Y15).
    let through = format!("{BLOCK}S3000 M3\nG0 X-20 Y15 Z-3\nG0 X60\nG0 Z50\nM30");
    let (info, warnings, _) = mill(&through);
    assert!(info.removed > 0.0);
    assert_eq!(warnings.iter().map(|w| (w.check, w.line)).collect::<Vec<_>>(), vec![(StockCheck::RapidIntoStock, 7)]);
    // The same at Z3, above the top at Z0: nothing removed, nothing reported.
    let above = through.replace("Z-3", "Z3");
    let (info, warnings, _) = mill(&above);
    assert_eq!((info.removed, warnings.len()), (0.0, 0));
}

#[test]
fn cutting_without_the_spindle_is_reported_once_per_block() {
    // No M3: the slot of line 6 (and only it) cuts with the spindle at rest.
    let program = format!("{BLOCK}G0 X-20 Y15 Z-2\nG1 X60 F500\nG0 Z50\nM30");
    let (info, warnings, _) = mill(&program);
    // A slot 10 wide (R5) through the 60 mm block, 2 deep, with round ends outside it: 1200 mm³.
    assert!((info.removed - 1200.0).abs() < 1e-6, "{info:?}");
    assert_eq!(warnings.iter().map(|w| (w.check, w.line)).collect::<Vec<_>>(), vec![(StockCheck::NoSpindle, 6)]);
}

#[test]
fn a_depth_of_cut_beyond_the_limit_is_reported() {
    let options = StockOptions { depth_limit: Some(3.0), ..StockOptions::default() };
    // Line 7 cuts 2 deep (within), line 9 cuts 4 deep (beyond the 3 mm limit).
    let program = format!("{BLOCK}S3000 M3\nG0 X-20 Y0 Z-2\nG1 X60 F500\nG0 Y25 Z-4\nG1 X-20\nG0 Z50\nM30");
    let (_, warnings, _) = run("mill-3axis", "", options, &program);
    assert_eq!(warnings.iter().map(|w| (w.check, w.line)).collect::<Vec<_>>(), vec![(StockCheck::DepthOfCut, 9)]);
    assert!((warnings[0].depth - 4.0).abs() < 1e-4);
}

#[test]
fn the_blank_lies_in_the_wcs_of_its_block() {
    // G54 moves X by 100: the blank is at BCS X90..150. A slot under G54 at WCS Y15 cuts it;
    // the same slot under G500 passes BCS X−20..60, beside it, and cuts nothing.
    let md = "$P_UIFR[1,X,TR]=100\n";
    let options = StockOptions::default();
    let slot = "S3000 M3\nG0 X-20 Y15 Z-2\nG1 X60 F500\nG0 Z50\n";
    let program = format!("G54\n{BLOCK}{slot}M30");
    let (info, _, _) = run("mill-3axis", md, options, &program);
    assert!((info.removed - 1200.0).abs() < 1e-6, "{info:?}");
    let program = format!("G54\n{BLOCK}G500\n{slot}M30");
    let (info, _, _) = run("mill-3axis", md, options, &program);
    assert_eq!(info.removed, 0.0);
}

#[test]
fn a_bad_blank_raises_an_alarm_at_its_line() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("G0 X0\nWORKPIECE(,\"\",,\"SPHERE\",0,0,-10)\nM30").unwrap();
    for _ in 0..1000 {
        ch.step();
    }
    let alarm = &ch.alarms()[0];
    assert_eq!((alarm.number, alarm.line), (12560, Some(2)), "{alarm:?}");
}

/// A tube Ø50/Ø30 (X absolute: flags 80), 60 long, Z−60..0, on the lathe; the tool far off.
const TUBE: &str = "G18 G90 G94\nT1 D1\nG0 X60 Z50\nWORKPIECE(,\"\",,\"PIPE\",80,0,-60,-80,50,30)\nS1000 M3\n";

#[test]
fn facing_a_tube_removes_the_ring() {
    // SL3 nose 0.8: the nose's lowest Z is the tip's, Z−1; the nose passes the inner radius
    // 15 (to X14), so the whole end ring goes: π (25² − 15²) · 1 = 1256.64 mm³.
    let program = format!("{TUBE}G0 X27 Z-1\nG1 X14 F200\nG0 Z5\nX60 Z50\nM30");
    let (info, warnings, _) = run("lathe-2axis", "", StockOptions::default(), &program);
    assert!(info.turning);
    assert!((info.initial_volume - PI * 400.0 * 60.0).abs() < 1e-6);
    assert!((info.removed - PI * 400.0).abs() < 1e-6, "{info:?}");
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn turning_the_outside_removes_the_ring_of_the_diameters() {
    // T3: a sharp tool (nose radius 0). Ø50 → Ø46 over the 20 mm from the end:
    // π (25² − 23²) · 20 = 6031.86 mm³.
    let md = "$TC_DP1[3,1]=500\n$TC_DP2[3,1]=3\n$TC_DP3[3,1]=40.\n$TC_DP4[3,1]=60.\n";
    let program = format!("{}G0 X23 Z2\nG1 Z-20 F200\nG1 X30\nG0 X60 Z50\nM30", TUBE.replace("T1 D1", "T3 D1"));
    let (info, _, _) = run("lathe-2axis", md, StockOptions::default(), &program);
    assert!((info.removed - PI * 96.0 * 20.0).abs() < 1e-6, "{info:?}");
}

#[test]
fn without_a_blank_nothing_is_kept() {
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program("G0 X10\nM30").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(ch.stock_info().is_none() && ch.snapshot().stock.is_none());
}

#[test]
fn a_blank_defined_under_a_rotation_lies_turned_in_the_bcs() {
    // Under ROT Z90 the WCS box X0..40, Y0..10 lies at BCS X−10..0, Y0..40. With the frame
    // cleared, a slot along Y at BCS X−5 (R5: X−10..0) takes the whole 10 mm width over the
    // 40 mm, 2 deep: 800 mm³. Without the rotation the box would start at X0, beside the slot.
    let program = "G17 G90 G94\nT1 D1\nG0 X-30 Y15 Z50\nROT Z90\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,,0,0,40,10)\nROT\nS3000 M3\nG0 X-5 Y-20 Z-2\nG1 Y60 F500\nG0 Z50\nM30";
    let (info, _, _) = mill(program);
    assert!((info.initial_volume - 8000.0).abs() < 1e-6, "{info:?}");
    assert!((info.removed - 800.0).abs() < 1e-6, "{info:?}");
    let (info, _, _) = mill(&program.replace("ROT Z90\n", ""));
    assert_eq!(info.removed, 0.0);
}

#[test]
fn the_same_program_cuts_the_same_stock_bit_for_bit() {
    let program =
        format!("{BLOCK}S3000 M3\nG0 X5 Y5 Z2\nG1 Z-3 F200\nG2 X25 Y15 CR=12 F900\nG3 X5 Y5 CR=15\nG0 Z10\nM30");
    let (_, _, mut a) = mill(&program);
    let (_, _, mut b) = mill(&program);
    assert_eq!(a.stock_stl().unwrap(), b.stock_stl().unwrap());
}

#[test]
fn a_block_search_past_the_blank_keeps_it_uncut() {
    // The search to line 9 passes the blank's line 4 and the cut of line 7: the blank is
    // defined, the skipped cut does not run; line 11 then slots 2 deep: 1200 mm³.
    let program =
        format!("{BLOCK}S3000 M3\nG0 X-20 Y0 Z-4\nG1 X60 F500\nG0 Z50\nG0 X-20 Y15\nG0 Z-2\nG1 X60\nG0 Z50\nM30");
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    // The axes high above the blank first, so the search's approach passes over it.
    ch.mda("T1 D1\nG0 Z150").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    ch.set_mode(nctwin_engine::Mode::Auto).unwrap();
    ch.block_search(Some(&program), 9).unwrap();
    ch.start().unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!(ch.alarms().is_empty(), "{:?}", ch.alarms());
    let info = ch.stock_info().expect("the blank of the skipped line 4");
    assert!((info.removed - 1200.0).abs() < 1e-6, "{info:?}");
}

#[test]
fn a_tool_change_moves_the_tip_without_cutting() {
    // The blank first, at the spindle's zero; T1 D1 then puts the tip 100 below it, inside the
    // blank's place, without motion: nothing is cut and nothing reported until the tool moves.
    let program = "G17 G90 G94\nWORKPIECE(,\"\",,\"BOX\",112,0,-200,-80,-10,-10,50,40)\nT1 D1\nG4 F0.1\nM30";
    let (info, warnings, _) = mill(program);
    assert_eq!((info.removed, warnings.len()), (0.0, 0), "{warnings:?}");
}

#[test]
fn a_short_tool_plunging_deep_brings_its_holder_into_the_stock() {
    // T3 D1: an end mill R5 only 30 long (`$TC_DP3`), in a holder Ø40 × 50 above its gauge
    // line. A plunge at X20 Y15 into a block Z−40..0: to Z−20 the holder's face stays at
    // Z10, above the top: no collision. To Z−35 the face goes to Z−5: the holder's ring
    // between radius 5 (the hole the tool made) and 20 holds the material of Z−5..0, 5 thick,
    // π(20² − 5²)·5 = 5890.49 mm³ (the ring lies inside the block, X0..40, Y−5..35), at the
    // plunge's line 7 with the tip at Z−35.
    let md = "$TC_DP1[3,1]=120\n$TC_DP3[3,1]=30.\n$TC_DP6[3,1]=5.\n";
    let holder = nctwin_engine::stock::holder::Holder::new(&[[40.0, 50.0]]).unwrap();
    let options = StockOptions { holder: Some(holder), ..StockOptions::default() };
    let program = |depth: f64| {
        format!(
            "G17 G90 G94\nT3 D1\nG0 X20 Y15 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-40,-80,-10,-10,50,40)\nS1000 M3\nG0 Z2\nG1 Z{depth} F300\nG0 Z80\nM30"
        )
    };
    let (_, warnings, _) = run("mill-3axis", md, options, &program(-20.0));
    assert!(warnings.is_empty(), "{warnings:?}");
    let (_, warnings, _) = run("mill-3axis", md, options, &program(-35.0));
    // The retract of line 8 starts with the holder still in the material: reported too
    // (the model removes nothing with the holder, so it stays a collision until it is out).
    assert_eq!(warnings.iter().map(|w| w.line).collect::<Vec<_>>(), vec![7, 8], "{warnings:?}");
    let w = warnings[0];
    assert_eq!((w.check, w.line), (StockCheck::HolderCollision, 7));
    assert!((w.depth - 5.0).abs() < 1e-4, "{w:?}");
    assert!((w.position[2] + 35.0).abs() < 1e-6, "{w:?}");
    // The ring's two rims (2π·25 mm round) cross 628 cells; half a cell 5 deep each at most.
    let expected = PI * (400.0 - 25.0) * 5.0;
    let bound = 0.5 * (2.0 * PI * 25.0 / 0.25) * 0.0625 * 5.0;
    assert!((w.volume - expected).abs() < bound, "{w:?} vs {expected} ± {bound}");
    // Without a holder set, no check and no cost.
    let (_, warnings, _) = run("mill-3axis", md, StockOptions::default(), &program(-35.0));
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
fn an_stl_blank_is_cut_and_compared_with_a_target_stl() {
    use nctwin_engine::stock::target::Mesh;
    // The blank as an STL: the block X−10..50, Y−10..40, Z−20..0 (60 000 mm³). The target:
    // the same block faced to Z−1. The program slots Z−2 deep along Y15 with the R5 end mill:
    // 10 mm wide (the 40 rows of cells within 5 of Y15) over the 60 mm: the slot is 1 mm below
    // the target, 600 mm³ overcut; the rest of the top keeps 1 mm above it, (3000 − 600)·1 =
    // 2400 mm³ undercut.
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.mda("T1 D1\nG0 X-30 Y15 Z50").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    let blank = Mesh::from_stl(&box_stl([-10.0, -10.0, -20.0], [50.0, 40.0, 0.0])).unwrap();
    ch.define_stock_mesh(&blank).unwrap();
    assert!((ch.stock_info().unwrap().initial_volume - 60_000.0).abs() < 1e-6);
    ch.mda("S3000 M3\nG0 Z-2\nG1 X60 F2000\nG0 Z50").unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert!((ch.stock_info().unwrap().removed - 1200.0).abs() < 1e-6);
    let target = Mesh::from_stl(&box_stl([-10.0, -10.0, -20.0], [50.0, 40.0, -1.0])).unwrap();
    let c = ch.compare_stock(&target).unwrap();
    assert!((c.overcut - 1.0).abs() < 1e-6 && (c.overcut_volume - 600.0).abs() < 1e-6, "{c:?}");
    assert!((c.overcut_at[1] - 15.0).abs() <= 5.0 && (c.overcut_at[2] + 1.5).abs() < 1e-6, "{c:?}");
    assert!((c.undercut - 1.0).abs() < 1e-6 && (c.undercut_volume - 2400.0).abs() < 1e-6, "{c:?}");
    // A lathe refuses an STL blank, naming why.
    let mut lathe = Channel::from_preset("lathe-2axis", "").unwrap();
    let e = lathe.define_stock_mesh(&blank).unwrap_err();
    assert!(e.to_string().contains("lathe"), "{e}");
}

#[test]
fn a_restart_from_the_checkpoint_keeps_the_cut_part() {
    // Line 7 slots Y15 2 deep (1200 mm³), M0 at line 9; the checkpoint there is restored in a
    // new channel: the search back to the M0 passes the WORKPIECE of line 4, which must not
    // replace the saved, cut stock. After the restart line 11 slots Y0 2 deep: 1200 more.
    let program =
        format!("{BLOCK}S3000 M3\nG0 X-20 Y15 Z-2\nG1 X60 F2000\nG0 Z50\nM0\nG0 X-20 Y0 Z-2\nG1 X60\nG0 Z50\nM30");
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(&program).unwrap();
    while ch.is_busy() {
        ch.step();
    }
    assert_eq!(ch.status(), nctwin_engine::Status::Stopped);
    assert!((ch.stock_info().unwrap().removed - 1200.0).abs() < 1e-6);
    let saved = ch.resume_state();
    assert!(saved.stock.is_some());

    let mut new = Channel::from_preset("mill-3axis", "").unwrap();
    new.restore_positions(ch.axis_positions()).unwrap();
    new.restore_resume_state(&saved).unwrap();
    let info = new.stock_info().expect("the saved stock");
    assert!((info.initial_volume - 60_000.0).abs() < 1e-6 && (info.removed - 1200.0).abs() < 1e-6, "{info:?}");
    assert_eq!(new.stock_stl(), ch.stock_stl());
    new.start().unwrap();
    while new.is_busy() {
        new.step();
    }
    assert!(new.alarms().is_empty(), "{:?}", new.alarms());
    assert!((new.stock_info().unwrap().removed - 2400.0).abs() < 1e-6, "{:?}", new.stock_info());
}

/// The pens (attribute bytes) of a binary STL's triangles.
fn pens(stl: &[u8]) -> std::collections::BTreeSet<u16> {
    let n = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
    (0..n).map(|t| u16::from_le_bytes(stl[84 + 50 * t + 48..84 + 50 * t + 50].try_into().unwrap())).collect()
}

#[test]
fn the_hmi_fetches_only_the_tiles_a_cut_changed_coloured_by_tool() {
    // The 60 x 50 block from X−10 Y−10 at 0.25 mm: 240 x 200 cells, tiles of 64 cells (16 mm):
    // 4 x 4. A plunge of T1 (R5) at X5 Y5 reaches X0..10, Y0..10: tiles 0..1 in X and in Y
    // ((0 + 10) / 16 = 0.6, (10 + 10) / 16 = 1.25). T2 (R4) drilled at X40 Y30 reaches
    // X36..44 (tiles 2, 3), Y26..34 (tile 2).
    let program =
        format!("{BLOCK}S3000 M3\nG0 X5 Y5 Z2\nG1 Z-2 F500\nG0 Z50\nT2 D1\nG0 X40 Y30 Z2\nG1 Z-5 F300\nG0 Z50\nM30");
    let mut ch = Channel::from_preset("mill-3axis", "").unwrap();
    ch.run_program(&program).unwrap();
    let mut first = None;
    while ch.is_busy() {
        ch.step();
        if first.is_none() && ch.stock_info().is_some() {
            first = ch.stock_changes(0);
        }
    }
    let first = first.expect("the blank's tiles");
    assert_eq!((first.version, first.tiles.len(), nctwin_engine::channel::STOCK_TILE), (1, 16, 64));
    let all = ch.stock_changes(first.version).unwrap();
    assert_eq!(all.tiles, vec![[0, 0], [1, 0], [0, 1], [1, 1], [2, 2], [3, 2]]);
    assert_eq!(all.pens, vec![(1, 1), (2, 1)]);
    assert!(ch.stock_changes(all.version).unwrap().tiles.is_empty());
    // Tile (0, 0) holds the end mill's hole (pen 1) and the blank's faces (0); tile (3, 2)
    // the drill's (pen 2).
    assert_eq!(pens(&ch.stock_tile_stl(0, 0).unwrap()), [0, 1].into());
    assert!(pens(&ch.stock_tile_stl(3, 2).unwrap()).contains(&2));
    assert_eq!(ch.stock_tile_stl(4, 0), None);
}
