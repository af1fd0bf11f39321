//! The blank on a turning table or spindle (issue 28): TRACYL on the trunnion table of
//! `tracyl-xyzac`, TRANSMIT chained before the slant bed's TRAANG (TRACON) on
//! `slant-lathe-tracon`, and the probe of MEAS against a blank the table has turned. Volumes
//! and switching positions worked out by hand.
//!
//! Presets (presets.rs): `tracyl-xyzac` T1 D1 slot mill R4, length 80 along ZM, the trunnion A
//! about X carrying the table C (A −90° lays C onto +Y), TRACYL type 513 with ZM radial and YM
//! along the cylinder; `slant-lathe-tracon` T1 D1 end mill R4, length 30 (along Z in G17),
//! the slide MU inclined by 30°, TRANSMIT data set 1 chained before TRAANG; `mill5-table-ac`
//! the trunnion A carrying C, TRAORI type 33 (DIN-reversed: C+90 turns the part by −90° about
//! Z), the table zero at the machine zero.

use nctwin_engine::Channel;
use nctwin_engine::channel::{StockInfo, StockOptions};

use crate::stock_support;

/// Runs `program` on `preset` to its end (no alarm); the stock summary and the channel.
fn run(preset: &str, md: &str, program: &str) -> (StockInfo, Channel) {
    let (info, _, ch) = stock_support::run(preset, md, StockOptions::default(), program);
    (info, ch)
}

use stock_support::cell;

#[test]
fn a_tracyl_groove_on_the_trunnion_table_removes_its_stadium_where_the_table_put_it() {
    // A bar Ø60, Z−50..0 of the table's frame (standing on C at A = C = 0); A−90 lays it along
    // +Y (machine Y −50..0). TRACYL(60): Y23.5619 = 30·π/4 is C = 45°. The slot mill R4 stands
    // radial (tip at radius 27: 3 deep) and runs 20 mm along the bar (Z−10 → −30, YM). In the
    // tool's frame (u radial, v across, w along the bar) it removes over the stadium of its
    // axis (|v| ≤ 4 around the 20 mm line) the material between u = 27 and √(900 − v²):
    // 20·A + D with A = ∫₋₄⁴ (√(900 − v²) − 27) dv = (4√884 + 900·asin(4/30)) − 216 = 23.287
    // and the two half discs D = ∫₋₄⁴ 2√(16 − v²)(√(900 − v²) − 27) dv = 147.44 (Simpson):
    // 465.74 + 147.44 = 613.18 mm³. About 40 rim cells of up to 0.0625·20 mm³: ±10.
    let program = "T1 D1 G17 G90 G94\nG0 A-90 C0\nG0 X0 Y10 Z130\n\
                   WORKPIECE(,\"\",,\"CYLINDER\",0,0,-50,-80,60)\nTRACYL(60)\n\
                   G19 G0 X40 Y23.5619449 Z-10\nG1 X27 F1000\nG1 Z-30\nG0 X40\nTRAFOOF\nM30";
    let (info, mut ch) = run("tracyl-xyzac", "", program);
    assert_eq!(info.skipped, 0, "{info:?}");
    assert!((info.removed - 613.18).abs() < 10.0, "{info:?}");
    // Where: the tool at C = 45° stands over the table's direction (sin 45°, −cos 45°) (the
    // table turns by −C about its Z, which A−90 lays onto +Y: the tool's +ZM is the table's
    // −Y at C = 0). The cell at radius 28.5 on that diagonal lost Z−34..−6 (the groove plus
    // the cutter's radius round its ends); the diagonal at +45° is whole.
    let d = 28.5 / 2f64.sqrt();
    let iv = cell(&mut ch, d, -d);
    assert_eq!(iv.len(), 2, "{iv:?}");
    assert_eq!(iv[0][0], -50.0);
    assert!((f64::from(iv[0][1]) + 34.0).abs() < 0.3 && (f64::from(iv[1][0]) + 6.0).abs() < 0.3, "{iv:?}");
    assert_eq!(iv[1][1], 0.0);
    assert_eq!(cell(&mut ch, d, d), vec![[-50.0, 0.0]]);
}

#[test]
fn positioning_the_trunnion_table_directly_carries_the_blank_too() {
    // The same bar, no transformation: A−90 C90. A table point p lies at machine
    // R_x(−90)·R_z(−90)·p: R_z(−90)·(x, y, z) = (y, −x, z), then R_x(−90)·(a, b, c) = (a, c, −b),
    // so machine (X, Y, Z) = (y, z, x): the bar lies along +Y and the table's +x points up.
    // A flat R4 end mill plunged 2 mm below the top (tip at Z28) at X0 Y−20 takes off the cap
    // of the bar over its disc: v = X across the bar, w = Y + 20 along it, the material
    // between Z28 and √(900 − v²): ∫₋₄⁴ 2√(16 − v²)(√(900 − v²) − 28) dv = 97.17 mm³ (Simpson;
    // ≈ π·16·(30 − 4/60 − 28) = 97.2 with the disc's mean v² = 4). About 50 rim cells: ±3.
    let program = "T1 D1 G17 G90 G94\nG0 A-90 C90\nG0 X0 Y-20 Z130\n\
                   WORKPIECE(,\"\",,\"CYLINDER\",0,0,-50,-80,60)\nS1000 M3\nG1 Z28 F500\nG0 Z130\nM30";
    let (info, mut ch) = run("tracyl-xyzac", "", program);
    let expected = simpson(|v| 2.0 * (16.0 - v * v).max(0.0).sqrt() * ((900.0 - v * v).sqrt() - 28.0), -4.0, 4.0);
    assert!((expected - 97.17).abs() < 0.01, "{expected}");
    assert!((info.removed - expected).abs() < 3.0, "{info:?} vs {expected}");
    // The cap lies on the table's +x round z −20: the cell at x 29.125, y 0.125 lost
    // z −20 ± √(16 − 0.125²) = −24.0..−16.0; the opposite side (−x, down) is whole.
    let iv = cell(&mut ch, 29.125, 0.125);
    assert_eq!(iv.len(), 2, "{iv:?}");
    assert!((f64::from(iv[0][1]) + 24.0).abs() < 0.01 && (f64::from(iv[1][0]) + 16.0).abs() < 0.01, "{iv:?}");
    assert_eq!(cell(&mut ch, -29.125, 0.125), vec![[-50.0, 0.0]]);
}

fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 2000;
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n).map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + i as f64 * h)).sum();
    (f(a) + f(b) + inner) * h / 3.0
}

#[test]
fn a_tracon_face_slot_on_the_slant_bed_removes_the_chord_strip() {
    // The slant-bed lathe keeps TRAANG active; TRANSMIT selects the chain TRANSMIT → TRAANG
    // (TRACON). The face slot of the TRANSMIT example: a bar Ø50, Z−40..0; the end mill R4
    // (tip at Z−2) runs along Y10 from X40 to X−35 across the face while C turns under it:
    // the strip 6 ≤ y ≤ 14 of the face's disc, 2 deep. Area ∫₆¹⁴ 2√(625 − y²) dy with
    // F(y) = y√(625 − y²) + 625·asin(y/25): F(14) − F(6) = 661.463 − 297.095 = 364.369;
    // volume 728.74 mm³, its two rims on the disc about 64 cells: ±4.
    let program = "G17 G90 G94 T1 D1\nG0 X120 Z50\nWORKPIECE(,\"\",,\"CYLINDER\",0,0,-40,-80,50)\n\
                   TRANSMIT\nG1 X40 Y10 Z5 F1000\nG1 Z-2\nG1 X-35\nG1 Z5\nTRAFOOF\nM30";
    let (info, mut ch) = run("slant-lathe-tracon", "", program);
    assert_eq!(info.skipped, 0, "{info:?}");
    assert!((info.removed - 728.74).abs() < 4.0, "{info:?}");
    assert!(!info.turning, "the face slot made the bar dexels");
    // In the workpiece (TRANSMIT's X/Y) the slot lies at Y10.
    assert_eq!(cell(&mut ch, 0.0, 10.0).last().map(|v| v[1]), Some(-2.0));
    assert_eq!(cell(&mut ch, 0.0, -10.0).last().map(|v| v[1]), Some(0.0));
}

/// A touch probe (type 710) as T1 D1: length 100 to the ball's centre, ball radius 3.
const PROBE: &str = "$TC_DP1[1,1]=710\n$TC_DP3[1,1]=100\n$TC_DP6[1,1]=3\n";

#[test]
fn meas_finds_the_face_where_the_turned_table_has_put_it() {
    // A box X0..40, Y−10..10, Z−20..0 on the table of mill5-table-ac; C90 (DIN-reversed)
    // turns it by −90° about Z through the table zero: (x, y) → (y, −x), so it covers machine
    // X−10..10, Y−40..0, its face x = 40 now at machine Y−40 looking towards −Y. The ball (R3)
    // at X5 Z−5 travels +Y from Y−60: it touches when its centre is at Y = −40 − 3 = −43.
    // (Unturned, the box would be at Y−10..10 and the switch at Y−13.) MCS = BCS here: the
    // table zero is the machine zero and the tool points down along Z (MM[Z] = −5 + 100).
    let program = "G17 G90 G94\nT1 D1\nG0 X5 Y-60 Z50\n\
                   WORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,0,-10,40,10)\nG0 C90\nG0 Z-5\n\
                   MEAS=1 G1 Y0 F500\nR1=$AC_MEA[1] R2=$AA_MM[Y] R3=$AA_MM[Z] R4=$AA_IW[Y]\nM30";
    let (_, ch) = run("mill5-table-ac", PROBE, program);
    let r = |n| ch.r_param(n);
    assert_eq!(r(1), 1.0, "the probe switched");
    assert!((r(2) + 43.0).abs() < 1e-6, "switched at Y {}", r(2));
    assert!((r(3) - 95.0).abs() < 1e-6, "Z {}", r(3));
    assert!((r(4) + 43.0).abs() < 1e-6, "stopped at Y {}", r(4));
}

#[test]
fn meas_finds_the_face_where_the_spindle_has_turned_a_milled_blank() {
    // tracyl-xyzc: a lathe with Y, so the box is milled as dexels clamped in the spindle C.
    // SPOS=90 turns the part with it: TRACYL's sign (plus, offset 0) puts a workpiece point p
    // at R_z(−90)·p in the machine, (x, y) → (y, −x), as on the table above: the face x = 40
    // at machine Y−40, the ball (R3, its centre 50 below the holder) at X5 Z−5 travelling +Y
    // switches at Y = −40 − 3 = −43.
    let program = "G17 G90 G94\nT1 D1\nG0 X5 Y-55 Z50\n\
                   WORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,0,-10,40,10)\nSPOS=90\nG0 Z-5\n\
                   MEAS=1 G1 Y0 F500\nR1=$AC_MEA[1] R2=$AA_MM[Y] R3=$AA_IW[Y]\nM30";
    let md = "$TC_DP1[1,1]=710\n$TC_DP3[1,1]=50\n$TC_DP6[1,1]=3\n";
    let (info, ch) = run("tracyl-xyzc", md, program);
    assert!(!info.turning);
    let r = |n| ch.r_param(n);
    assert_eq!(r(1), 1.0, "the probe switched");
    assert!((r(2) + 43.0).abs() < 1e-6 && (r(3) + 43.0).abs() < 1e-6, "switched at Y {}, stopped at {}", r(2), r(3));
}

/// `frame` against the rows of `[R | t]` expected, to 1e-9.
fn assert_frame(info: &StockInfo, expected: [[f64; 4]; 3]) {
    let frame = info.frame.expect("the blank moves with a table");
    for (row, want) in frame.iter().zip(&expected) {
        for (a, b) in row.iter().zip(want) {
            assert!((a - b).abs() < 1e-9, "{frame:?} vs {expected:?}");
        }
    }
}

#[test]
fn the_state_carries_the_tables_pose_for_the_hmi() {
    // mill5-table-ac, C90 by the axis (no TRAORI): type 33 turns the part by −90° about Z
    // through the table zero, the machine zero: machine = R_z(−90)·p, (x, y) → (y, −x).
    let program = "G17 G90 G94\nT1 D1\nG0 X0 Y0 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,0,-10,40,10)\nG0 C90\nM30";
    let (info, _) = run("mill5-table-ac", "", program);
    assert_frame(&info, [[0.0, 1.0, 0.0, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
    // Tilted too: A30 turns the part by −30° about X about the A axis 100 below and 20 behind
    // the table zero (the table zero at A0 C0 is the machine zero). With C0: a table point p
    // lies at q + R_x(−30)·(p − q), q = (0, 20, −100): the translation q − R_x(−30)·q with
    // R_x(−30)·(0, 20, −100) = (0, 20·cos30 − 100·sin30, −20·sin30 − 100·cos30)
    // = (0, −32.6795, −96.6025): t = (0, 52.6795, −3.3975).
    let program = "G17 G90 G94\nT1 D1\nG0 X0 Y0 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,0,-10,40,10)\nG0 A30\nM30";
    let (info, _) = run("mill5-table-ac", "", program);
    let (s, c) = 30f64.to_radians().sin_cos();
    let t = [0.0, 20.0 - (20.0 * c - 100.0 * s), -100.0 - (-20.0 * s - 100.0 * c)];
    assert!((t[1] - 52.6795).abs() < 1e-4 && (t[2] + 3.3975).abs() < 1e-4, "{t:?}");
    assert_frame(&info, [[1.0, 0.0, 0.0, t[0]], [0.0, c, s, t[1]], [0.0, -s, c, t[2]]]);
    // tracyl-xyzac, A−90 C90: machine (X, Y, Z) = (y, z, x) of the table's point (see above).
    let program = "T1 D1 G17 G90 G94\nG0 A-90 C90\nG0 X0 Y10 Z130\nWORKPIECE(,\"\",,\"CYLINDER\",0,0,-50,-80,60)\nM30";
    let (info, _) = run("tracyl-xyzac", "", program);
    assert_frame(&info, [[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0]]);
    // A swivel head turns the tool, not the blank: no frame.
    let program = "G17 G90 G94\nT1 D1\nG0 Z80\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,-80,0,-10,40,10)\nG0 A30 C45\nM30";
    let (info, _) = run("mill5-head-ca", "", program);
    assert_eq!(info.frame, None);
    // A 3-axis mill's blank does not move: no frame.
    let (info, _) = run("mill-3axis", "", "T1 D1\nG0 Z50\nWORKPIECE(,\"\",,\"BOX\",112,0,-20,,-10,-10,50,40)\nM30");
    assert_eq!(info.frame, None);
}
