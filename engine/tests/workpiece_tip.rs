//! The tool tip on the workpiece (`channel/workpiece_tip.rs`): what the executed path and the
//! limit marks are drawn with. Values worked out by hand from the presets' machine data.

use crate::settle;

use nctwin_engine::channel::workpiece_tip::TipProbe;
use settle::{channel, finish};

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-6)
}

fn basic(ch: &nctwin_engine::Channel) -> [f64; 3] {
    let s = ch.snapshot();
    std::array::from_fn(|g| s.basic.iter().find(|(n, _)| *n == ["X", "Y", "Z"][g]).map_or(f64::NAN, |(_, v)| *v))
}

#[test]
fn a_three_axis_mill_gives_the_bcs_tip() {
    // T1 D1 (L100): machine Z 130 is the tip at Z30.
    let mut ch = channel("mill-3axis", "");
    finish(&mut ch, "T1 D1\nG0 X10 Y20 Z30\nM30");
    let t = TipProbe::default().tip(&ch);
    assert!(close(t.tip, [10.0, 20.0, 30.0]), "{t:?}");
    assert!(t.exact && t.tracyl_diameter.is_none());
}

#[test]
fn a_trunnion_table_turned_without_traori_gives_the_tip_on_the_turned_table() {
    // mill5-table-ac: machine reference = table centre at A = C = 0; the C axis is vertical
    // through it (BASE_TOOL + JOINT_OFFSET = (0, 0, −20)). Type 33 reverses the directions
    // (DIN): C = +90° turns the tool relative to the part by +90° about +Z. The tip at machine
    // X10 Y0 Z50 (T1 L100: machine Z 150) is at X0 Y10 Z50 on the table. The BCS still reads
    // X10 Y0 Z50: drawn there, the path would be false.
    let mut ch = channel("mill5-table-ac", "");
    finish(&mut ch, "T1 D1\nG0 X10 Y0 Z50\nG1 C90 F5000\nM30");
    assert!(close(basic(&ch), [10.0, 0.0, 50.0]), "{:?}", basic(&ch));
    let t = TipProbe::default().tip(&ch);
    assert!(close(t.tip, [0.0, 10.0, 50.0]), "{t:?}");
    assert!(t.exact);
}

#[test]
fn the_tip_without_traori_is_where_traori_would_put_it() {
    // The same machine positions with and without TRAORI: the TRAORI BCS is the table's frame,
    // so the probe's tip without TRAORI equals the BCS display under TRAORI.
    let mut plain = channel("mill5-table-ac", "");
    finish(&mut plain, "T1 D1\nG0 X10 Y20 Z50\nG1 A30 C45 F5000\nM30");
    let t = TipProbe::default().tip(&plain);
    let mut ori = channel("mill5-table-ac", "");
    finish(&mut ori, "T1 D1\nG0 X10 Y20 Z50\nG1 A30 C45 F5000\nTRAORI\nM0\nM30");
    assert_eq!(plain.axis_positions()[..5], ori.axis_positions()[..5]);
    let under = TipProbe::default().tip(&ori);
    assert!(close(t.tip, basic(&ori)), "{t:?} vs {:?}", basic(&ori));
    assert!(close(under.tip, basic(&ori)), "{under:?} vs {:?}", basic(&ori));
}

#[test]
fn a_tilted_rotary_table_without_traori_gives_the_tip_on_the_table() {
    // tracyl-xyzac: the trunnion A (about X) carries C, the blank is clamped on the table
    // (channel/stock/table.rs): machine = R_x(A)·R_z(−C)·p. The tip at machine (20, 10, 5) with A−90,
    // C0 lies on the table at p = R_x(90)·(20, 10, 5) = (20, 10·cos 90° − 5·sin 90°,
    // 10·sin 90° + 5·cos 90°) = (20, −5, 10). At A0 C0 the table's frame is the BCS.
    let mut ch = channel("tracyl-xyzac", "");
    finish(&mut ch, "T1 D1\nG0 X20 Y10 Z5\nM30");
    let t = TipProbe::default().tip(&ch);
    assert!(t.exact && close(t.tip, [20.0, 10.0, 5.0]), "{t:?}");
    finish(&mut ch, "G1 A-90 F5000\nM30");
    let t = TipProbe::default().tip(&ch);
    assert!(t.exact && close(t.tip, [20.0, -5.0, 10.0]), "{t:?}");
}

#[test]
fn a_rotary_axis_the_machine_data_do_not_describe_is_marked_not_exact() {
    // mill-3axis with a rotary axis A (5th machine axis) and no transformation data: where A turns the
    // workpiece is unknown, so off 0° the BCS tip is not known to be on the part.
    let md = "$MN_AXCONF_MACHAX_NAME_TAB[4]=\"A1\"\n$MC_AXCONF_MACHAX_USED[4]=5\n$MC_AXCONF_CHANAX_NAME_TAB[4]=\"A\"\n$MA_IS_ROT_AX[A1]=TRUE";
    let mut ch = channel("mill-3axis", md);
    finish(&mut ch, "T1 D1\nG0 X20 Y0 Z0\nM30");
    assert!(TipProbe::default().tip(&ch).exact);
    finish(&mut ch, "G0 A30\nM30");
    assert!(!TipProbe::default().tip(&ch).exact, "{:?} {:?}", ch.axis_positions(), ch.alarms());
}

#[test]
fn under_tracyl_the_tip_is_on_the_unrolled_surface_with_its_diameter() {
    // TRACYL(40): the BCS is radial, arc length on d = 40, axial; the diameter goes along.
    let mut ch = channel("tracyl-xyzac", "");
    finish(&mut ch, "T1 D1\nG0 X20 Y0 Z0\nG1 A-90 F5000\nTRACYL(40)\nG1 X20 Y10 Z5 F1000\nM0\nM30");
    let t = TipProbe::default().tip(&ch);
    assert_eq!(t.tracyl_diameter, Some(40.0));
    assert!(close(t.tip, basic(&ch)), "{t:?} vs {:?}", basic(&ch));
}
