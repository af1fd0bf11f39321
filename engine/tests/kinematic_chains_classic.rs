//! TRANSMIT_K, TRACYL_K and TRAANG_K (K12): each chain-defined transformation against the
//! machine-data transformation of the same geometry over random poses (forward and inverse),
//! one pose per machine worked out by hand from the chain's geometry (rigid motions, no
//! transformation code), and the selection in a program by TRAFOON and by the classic command.
//! The machine-data equivalents' BASE_TOOL, ROT_AX_OFFSET and sign are derived by hand in the
//! comment of each machine.

use nctwin_engine::kinematics::{self, ActiveTrafo, SelectArgs};
use nctwin_engine::machine_data::{MachineConfig, MachineData};
use nctwin_engine::{Channel, Snapshot, Status};
use proptest::prelude::*;

use crate::chain_support;
use chain_support::{SIX, axes, elements, near};

/// Record n: name, type, tool and workpiece chain ends, rotary axis [n,1], geometry axes.
fn record(n: usize, name: &str, ty: &str, ends: [&str; 2], rot: &str, geo: [&str; 3], extra: &str) -> String {
    let mut out = format!(
        "$NT_NAME[{n}]=\"{name}\"\n$NT_TRAFO_TYPE[{n}]=\"{ty}\"\n$NT_T_CHAIN_LAST_ELEM[{n}]=\"{}\"\n\
         $NT_P_CHAIN_LAST_ELEM[{n}]=\"{}\"\n",
        ends[0], ends[1]
    );
    if !rot.is_empty() {
        out += &format!("$NT_ROT_AX_NAME[{n},1]=\"{rot}\"\n");
    }
    for (k, g) in geo.iter().enumerate().filter(|(_, g)| !g.is_empty()) {
        out += &format!("$NT_GEO_AX_NAME[{n},{k}]=\"{g}\"\n");
    }
    out + extra
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];
const NX: [f64; 3] = [-1.0, 0.0, 0.0];
const NZ: [f64; 3] = [0.0, 0.0, -1.0];

/// TRANSMIT 257 on a lathe: Z, X, Y carry the turret (tool reference (12, −3, 40) at the
/// kinematic zero); the spindle C turns the workpiece about −Z (DIN: the tool turns positively
/// about +Z relative to it) at p_C = (0, 0, −50), workpiece reference (0, 0, 70) on its axis.
/// BCS: e_z = +Z (the Z axis), e_x = +X, e_y = +Y, origin (0, 0, 70) ⇒ BASE_TOOL = (12, −3,
/// 40 − 70) = (12, −3, −30); C's effective angle C − 5 + 15 ⇒ ROT_AX_OFFSET = 5 − 15 = −10;
/// e_z opposes C's direction ⇒ ROT_SIGN_IS_PLUS = TRUE.
fn transmit() -> (String, String) {
    let chain = elements(&[
        ("ROOT", "OFFSET", "Z axis", "Spindle", [0.0; 3], "", 0.0),
        ("Z axis", "AXIS_LIN", "X axis", "", Z, "Z1", 0.0),
        ("X axis", "AXIS_LIN", "Y axis", "", X, "X1", 0.0),
        ("Y axis", "AXIS_LIN", "Turret", "", Y, "Y1", 0.0),
        ("Turret", "OFFSET", "", "", [12.0, -3.0, 40.0], "", 0.0),
        ("Spindle", "OFFSET", "C axis", "", [0.0, 0.0, -50.0], "", 0.0),
        ("C axis", "AXIS_ROT", "Chuck", "", NZ, "C1", 15.0),
        ("Chuck", "OFFSET", "", "", [0.0, 0.0, 120.0], "", 0.0),
    ]) + &record(
        1,
        "Face",
        "TRANSMIT_K",
        ["Turret", "Chuck"],
        "C axis",
        ["X axis", "Y axis", "Z axis"],
        "$NT_CNTRL[1]='H200'\n$NT_ROT_AX_OFFSET[1,1]=5\n",
    );
    let md = "$MC_TRAFO_TYPE_1=257\n$MC_TRAFO_AXES_IN_1[0]=1\n$MC_TRAFO_AXES_IN_1[1]=6\n$MC_TRAFO_AXES_IN_1[2]=3\n\
              $MC_TRAFO_AXES_IN_1[3]=2\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=6\n\
              $MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3\n$MC_TRANSMIT_BASE_TOOL_1[0]=12\n$MC_TRANSMIT_BASE_TOOL_1[1]=-3\n\
              $MC_TRANSMIT_BASE_TOOL_1[2]=-30\n$MC_TRANSMIT_ROT_AX_OFFSET_1=-10\n";
    (chain, md.into())
}

/// TRACYL 514 (bit 10, default groove-wall offset on by bit 9) with the direction inverted by
/// bit 11. The radial slide's positive direction is world −X, the Z slide moves the workpiece
/// (effective direction −Z), C turns about +Z at (0, 0, 10) above the Z slide, the workpiece
/// reference 30 further. BCS: e_z = −Z (the Z axis' effective direction, parallel to C),
/// e_x = −X, e_y = e_z × e_x = +Y (the Y slide), origin (0, 0, 40); tool reference (5, 0, 60)
/// ⇒ v = (5, 0, 20), BASE_TOOL = (−5, 0, −20). e_z opposes C's direction ⇒ positive, inverted by
/// bit 11 ⇒ ROT_SIGN_IS_PLUS = FALSE.
fn tracyl() -> (String, String) {
    let chain = elements(&[
        ("ROOT", "OFFSET", "X axis", "Z axis", [0.0; 3], "", 0.0),
        ("X axis", "AXIS_LIN", "Y axis", "", NX, "X1", 0.0),
        ("Y axis", "AXIS_LIN", "Tool", "", Y, "Y1", 0.0),
        ("Tool", "OFFSET", "", "", [5.0, 0.0, 60.0], "", 0.0),
        ("Z axis", "AXIS_LIN", "C offset", "", Z, "Z1", 0.0),
        ("C offset", "OFFSET", "C axis", "", [0.0, 0.0, 10.0], "", 0.0),
        ("C axis", "AXIS_ROT", "WP", "", Z, "C1", 0.0),
        ("WP", "OFFSET", "", "", [0.0, 0.0, 30.0], "", 0.0),
    ]) + &record(
        2,
        "Cylinder",
        "TRACYL_K",
        ["Tool", "WP"],
        "C axis",
        ["X axis", "Y axis", "Z axis"],
        "$NT_CNTRL[2]='HE00'\n",
    );
    let md = "$MC_TRAFO_TYPE_1=514\n$MC_TRAFO_AXES_IN_1[0]=1\n$MC_TRAFO_AXES_IN_1[1]=6\n$MC_TRAFO_AXES_IN_1[2]=3\n\
              $MC_TRAFO_AXES_IN_1[3]=2\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=6\n\
              $MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3\n$MC_TRACYL_BASE_TOOL_1[0]=-5\n$MC_TRACYL_BASE_TOOL_1[2]=-20\n\
              $MC_TRACYL_DEFAULT_MODE_1=1\n$MC_TRACYL_ROT_SIGN_IS_PLUS_1=FALSE\n";
    (chain, md.into())
}

/// TRAANG: the infeed slide U (channel axis X) runs along (√3, 0, 1)/2, 30° towards the
/// longitudinal Z slide it rides on; Y passes through; wheel reference (40, 0, −15), workpiece
/// reference (0, 0, 100) ⇒ e_z = +Z, e_x = +X, α = 30°, BASE_TOOL = (40, 0, −115).
fn traang() -> (String, String) {
    let chain = elements(&[
        ("ROOT", "OFFSET", "Z axis", "WP", [0.0; 3], "", 0.0),
        ("Z axis", "AXIS_LIN", "U axis", "", Z, "Z1", 0.0),
        ("U axis", "AXIS_LIN", "Y axis", "", [3f64.sqrt(), 0.0, 1.0], "X1", 0.0),
        ("Y axis", "AXIS_LIN", "Wheel", "", Y, "Y1", 0.0),
        ("Wheel", "OFFSET", "", "", [40.0, 0.0, -15.0], "", 0.0),
        ("WP", "OFFSET", "", "", [0.0, 0.0, 100.0], "", 0.0),
    ]) + &record(3, "Inclined", "TRAANG_K", ["Wheel", "WP"], "", ["U axis", "Y axis", "Z axis"], "");
    let md = "$MC_TRAFO_TYPE_1=1024\n$MC_TRAFO_AXES_IN_1[0]=1\n$MC_TRAFO_AXES_IN_1[1]=3\n$MC_TRAFO_AXES_IN_1[2]=2\n\
              $MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3\n\
              $MC_TRAANG_ANGLE_1=30\n$MC_TRAANG_BASE_TOOL_1[0]=40\n$MC_TRAANG_BASE_TOOL_1[2]=-115\n";
    (chain, md.into())
}

fn config(text: &str) -> MachineConfig {
    MachineData::default().apply_text(&format!("{SIX}{text}")).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The chain-defined and the machine-data transformation, with tool `tool` and `args`.
fn pair(machine: fn() -> (String, String), tool: [f64; 3], args: SelectArgs) -> (ActiveTrafo, ActiveTrafo) {
    let (chain, md) = machine();
    let (ccfg, mcfg) = (config(&chain), config(&md));
    let cset = ccfg.trafos.iter().find(|s| s.chain.is_some()).expect("chain transformation");
    let mset = &mcfg.trafos[0];
    assert_eq!((cset.trafo_type, cset.geo_axes, cset.axes_in), (mset.trafo_type, mset.geo_axes, mset.axes_in));
    let build = |set, cfg| ActiveTrafo { trafo: kinematics::build(set, cfg, &args).unwrap(), tool, number: 1 };
    (build(cset, &ccfg), build(mset, &mcfg))
}

const MACHINES: [fn() -> (String, String); 3] = [transmit, tracyl, traang];

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, .. ProptestConfig::default() })]

    /// Forward and inverse agree with the machine-data transformation to 1e-9 over random
    /// poses, tool lengths and (TRACYL) working diameters.
    #[test]
    fn chain_defined_classic_transformations_equal_the_machine_data_ones(
        machine in 0..3usize,
        lin in prop::array::uniform3(-200.0f64..200.0),
        c in -720.0f64..720.0,
        tool in prop::array::uniform3(0.0f64..80.0),
        d in 2.0f64..300.0,
    ) {
        let args = SelectArgs { diameter: Some(d), ..SelectArgs::default() };
        let (ct, mt) = pair(MACHINES[machine], tool, args);
        let pose = axes(&[lin[0], lin[1], lin[2], 0.0, 0.0, c]);
        let (fc, fm) = (ct.forward(&pose), mt.forward(&pose));
        prop_assert!(near(&fc[..6], &fm[..6], 1e-9), "forward {:?} vs {:?}", &fc[..6], &fm[..6]);
        let prev = axes(&[lin[0] + 1.0, lin[1] - 2.0, lin[2] + 0.5, 0.0, 0.0, c + 3.0]);
        let (ic, im) = (ct.inverse(&fc, &prev).unwrap(), mt.inverse(&fm, &prev).unwrap());
        prop_assert!(near(&ic[..6], &im[..6], 1e-8), "inverse {:?} vs {:?}", &ic[..6], &im[..6]);
        prop_assert!(near(&ct.forward(&ic)[..6], &fc[..6], 1e-8));
    }
}

/// Rotation of `v` by `deg` about +Z.
fn rot_z(v: [f64; 3], deg: f64) -> [f64; 3] {
    let (s, c) = deg.to_radians().sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}

#[test]
fn transmit_k_gives_the_hand_computed_face_position() {
    // X30 Y2 Z4 C80, tool length 25 along Z: turret reference (42, −1, 44) in the world,
    // relative to the BCS origin (0, 0, 70): (42, −1, −26); the tool tip 25 lower in BCS Z.
    // C turns the workpiece by 80 − 5 + 15 = 90° about −Z, so the tool, seen from the
    // workpiece, has turned +90° about +Z: (42, −1) → (1, 42).
    let (c, _) = pair(transmit, [0.0, 0.0, 25.0], SelectArgs::default());
    let bcs = c.forward(&axes(&[30.0, 2.0, 4.0, 0.0, 0.0, 80.0]));
    let expected = rot_z([42.0, -1.0, -26.0 - 25.0], 90.0);
    assert!(near(&[bcs[0], bcs[5], bcs[2]], &expected, 1e-9), "{:?} vs {expected:?}", &bcs[..6]);
}

#[test]
fn tracyl_k_gives_the_hand_computed_unrolled_position() {
    // X20 Y2 Z7 C45, d = 60, no tool: tool reference (5 − 20, 2, 60); the workpiece moved +7
    // along Z, so the origin is (0, 0, 47) and the reference relative to it (−15, 2, 13).
    // BCS X = −(−15) = 15, Z = −13; the unrolled Y: the workpiece turned 45° about +Z = the
    // tool +45° about e_z = −Z, inverted by bit 11 ⇒ φ = −45°: Y = 30·(−π/4) + 2 (Y slide).
    let args = SelectArgs { diameter: Some(60.0), ..SelectArgs::default() };
    let (c, _) = pair(tracyl, [0.0; 3], args);
    let bcs = c.forward(&axes(&[20.0, 2.0, 7.0, 0.0, 0.0, 45.0]));
    let expected = [15.0, 30.0 * -std::f64::consts::FRAC_PI_4 + 2.0, -13.0];
    assert!(near(&[bcs[0], bcs[5], bcs[2]], &expected, 1e-9), "{:?} vs {expected:?}", &bcs[..6]);
}

#[test]
fn traang_k_gives_the_hand_computed_position() {
    // U = 10, Z = 5, Y = 3: wheel reference (40, 0, −15) + 5·Z + 10·(√3/2, 0, 1/2)
    // = (40 + 5√3, 3, −5) in the world; relative to the workpiece (0, 0, 100): (40 + 5√3, ·, −105).
    let (c, _) = pair(traang, [0.0; 3], SelectArgs::default());
    let bcs = c.forward(&axes(&[10.0, 3.0, 5.0]));
    let expected = [40.0 + 5.0 * 3f64.sqrt(), 3.0, -105.0];
    assert!(near(&bcs[..3], &expected, 1e-9), "{:?} vs {expected:?}", &bcs[..3]);
}

#[test]
fn nt_pole_side_fix_keeps_transmit_k_on_one_side_of_the_pole() {
    // $NT_POLE_SIDE_FIX[1] = 2 is TRANSMIT_POLE_SIDE_FIX_1 = 2: leaving the pole (previous
    // radial position X + 12 = 0, C = 0) the radial axis goes negative (C = 180°), even where
    // the positive side is nearer (C = 0). Standing on the excluded side (X = +40, as after a
    // selection outside the pole, which does not evaluate the fixed side) it stays there.
    let (chain, md) = transmit();
    let (chain, md) = (chain + "$NT_POLE_SIDE_FIX[1]=2\n", md + "$MC_TRANSMIT_POLE_SIDE_FIX_1=2\n");
    let (ccfg, mcfg) = (config(&chain), config(&md));
    let cset = ccfg.trafos.iter().find(|s| s.chain.is_some()).unwrap();
    let build = |set, cfg| ActiveTrafo {
        trafo: kinematics::build(set, cfg, &SelectArgs::default()).unwrap(),
        tool: [0.0; 3],
        number: 1,
    };
    let (ct, mt) = (build(cset, &ccfg), build(&mcfg.trafos[0], &mcfg));
    let prev = axes(&[-12.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let bcs = axes(&[30.0, 0.0, 0.0, 0.0, 0.0, 20.0]);
    let (ic, im) = (ct.inverse(&bcs, &prev).unwrap(), mt.inverse(&bcs, &prev).unwrap());
    // Radial position of the tool: X + 12 (base tool) < 0 on the negative side.
    assert!(ic[0] + 12.0 < 0.0 && near(&ic[..6], &im[..6], 1e-9), "{:?} vs {:?}", &ic[..6], &im[..6]);
    let prev = axes(&[40.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let (ic, im) = (ct.inverse(&bcs, &prev).unwrap(), mt.inverse(&bcs, &prev).unwrap());
    assert!(ic[0] + 12.0 > 0.0 && near(&ic[..6], &im[..6], 1e-9), "{:?} vs {:?}", &ic[..6], &im[..6]);
}

#[test]
fn bad_classic_records_are_rejected_at_activation() {
    let (t, _) = transmit();
    let (a, _) = traang();
    for (text, needle) in [
        (t.replace("$NT_ROT_AX_NAME[1,1]=\"C axis\"", ""), "$NT_ROT_AX_NAME[1,1] must name the rotary axis"),
        (t.replace("$NT_GEO_AX_NAME[1,1]=\"Y axis\"", ""), "needs $NT_GEO_AX_NAME[1,1]"),
        (
            a.replace("$NK_NEXT[3]=\"Wheel\"", "$NK_NEXT[3]=\"Dresser\"")
                + "$NK_NAME[6]=\"Dresser\"\n$NK_TYPE[6]=\"AXIS_ROT\"\n$NK_OFF_DIR[6,2]=1\n$NK_AXIS[6]=\"C1\"\n\
                   $NK_NEXT[6]=\"Wheel\"\n",
            "rotary axis element \"Dresser\" lies on a subchain but is no axis",
        ),
        (
            t.replace("$NT_GEO_AX_NAME[1,0]=\"X axis\"", "$NT_GEO_AX_NAME[1,0]=\"Z axis\"")
                .replace("$NT_GEO_AX_NAME[1,2]=\"Z axis\"", "$NT_GEO_AX_NAME[1,2]=\"X axis\""),
            "longitudinal axis \"X axis\" is not parallel to the rotary axis",
        ),
        (t.replace("$NK_OFF_DIR[2,2]=0.0", "$NK_OFF_DIR[2,2]=1.0"), "\"X axis\" is not perpendicular"),
        (t.replace("$NK_OFF_DIR[3,1]=1.0", "$NK_OFF_DIR[3,1]=-1.0"), "Z × X of the transformation"),
        (t.replace("$NT_CNTRL[1]='H200'", "$NT_CNTRL[1]='H60200'"), "order of the geometry axes is 0..5"),
        (t + "$NT_POLE_SIDE_FIX[1]=3\n", "$NT_POLE_SIDE_FIX[1]=3: allowed are 0..2"),
        (a.replace("$NK_OFF_DIR[2,0]=1.7320508075688772", "$NK_OFF_DIR[2,0]=0.0"), "parallel to the longitudinal"),
        (a.replace("$NK_OFF_DIR[2,2]=1.0", "$NK_OFF_DIR[2,2]=0.0"), "TRAANG needs an angle other than 0"),
        (a.replace("[40.0, 0.0, -15.0]", "").replace("$NK_OFF_DIR[4,1]=0.0", "$NK_OFF_DIR[4,1]=2.0"), "off the plane"),
    ] {
        let mut md = MachineData::default();
        md.apply_text(SIX).unwrap();
        let e = md.apply_text(&text).unwrap_err();
        assert!(e.message.contains(needle), "{needle}\n→ {}", e.message);
    }
}

// ---------------------------------------------------------------------------------------------
// Selection in a program, on the TRACYL example machine XC, YC, ZC, CC (data set 1: TRACYL 513)
// ---------------------------------------------------------------------------------------------

/// The geometry of the preset's data set 1 as a chain: X, Y, Z on the tool side, tool reference
/// at the world origin, C about −Z through the origin (so the tool turns positively about +Z),
/// workpiece reference at the origin.
const TRACYL_CHAIN: &str = r#"
$NK_NAME[0]="ROOT"
$NK_TYPE[0]="OFFSET"
$NK_NEXT[0]="X axis"
$NK_PARALLEL[0]="C axis"
$NK_NAME[1]="X axis"
$NK_TYPE[1]="AXIS_LIN"
$NK_NEXT[1]="Y axis"
$NK_OFF_DIR[1,0]=1
$NK_AXIS[1]="XM"
$NK_NAME[2]="Y axis"
$NK_TYPE[2]="AXIS_LIN"
$NK_NEXT[2]="Z axis"
$NK_OFF_DIR[2,1]=1
$NK_AXIS[2]="YM"
$NK_NAME[3]="Z axis"
$NK_TYPE[3]="AXIS_LIN"
$NK_NEXT[3]="Tool"
$NK_OFF_DIR[3,2]=1
$NK_AXIS[3]="ZM"
$NK_NAME[4]="Tool"
$NK_TYPE[4]="OFFSET"
$NK_NAME[5]="C axis"
$NK_TYPE[5]="AXIS_ROT"
$NK_NEXT[5]="WP"
$NK_OFF_DIR[5,2]=-1
$NK_AXIS[5]="CM"
$NK_NAME[6]="WP"
$NK_TYPE[6]="OFFSET"
$NT_NAME[1]="Surface"
$NT_TRAFO_TYPE[1]="TRACYL_K"
$NT_T_CHAIN_LAST_ELEM[1]="Tool"
$NT_P_CHAIN_LAST_ELEM[1]="WP"
$NT_ROT_AX_NAME[1,1]="C axis"
$NT_GEO_AX_NAME[1,0]="X axis"
$NT_GEO_AX_NAME[1,1]="Y axis"
$NT_GEO_AX_NAME[1,2]="Z axis"
$NT_CNTRL[1]='H200'
"#;

const GROOVE: &str = "G0 X20 Y0 Z0\n{SELECT}\nG1 F1000 Y31.4159265358979 Z-10\nY-20 Z5\nM30";

fn run(extra: &str, select: &str) -> Snapshot {
    let mut ch = Channel::from_preset("tracyl-xyzc", extra).unwrap_or_else(|e| panic!("{e}"));
    ch.run_program(&GROOVE.replace("{SELECT}", select)).unwrap();
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < 1_000_000, "program does not end");
    }
    ch.snapshot()
}

fn machine(s: &Snapshot) -> Vec<f64> {
    s.machine.iter().map(|(_, v)| *v).collect()
}

#[test]
fn trafoon_and_the_classic_command_select_tracyl_k_like_the_machine_data_tracyl() {
    let md = run(TRACYL_CHAIN, "TRACYL(40)");
    let named = run(TRACYL_CHAIN, "TRAFOON(\"Surface\", 40)");
    let indexed = run(&format!("{TRACYL_CHAIN}$NT_TRAFO_INDEX[1]=10\n"), "TRACYL(40)");
    for s in [&md, &named, &indexed] {
        assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    }
    // Y−20 on d = 40: C = −20/20 rad = −57.2958°, shown modulo 360; X20, Z5 straight through.
    let expected = [20.0, 0.0, 5.0, 360.0 - 1f64.to_degrees()];
    for s in [&md, &named, &indexed] {
        assert!(near(&machine(s), &expected, 1e-6), "{:?}", s.machine);
    }
}

#[test]
fn tracyl_k_cannot_be_the_reset_transformation() {
    // TRACYL needs its working diameter from the program, so a reset cannot select it.
    let Err(e) = Channel::from_preset("tracyl-xyzc", &format!("{TRACYL_CHAIN}$MC_TRAFO_RESET_NAME=\"Surface\"\n"))
    else {
        panic!("TRACYL_K as reset transformation is rejected")
    };
    assert!(e.to_string().contains("$MC_TRAFO_RESET_NAME=\"Surface\": TRACYL needs a working diameter"), "{e}");
}

#[test]
fn tracyl_k_needs_the_diameter_at_trafoon() {
    let s = run(TRACYL_CHAIN, "TRAFOON(\"Surface\")");
    assert_eq!(s.status, Status::Alarm);
    assert!(s.alarms.iter().any(|a| a.message.contains("TRACYL needs the working diameter")), "{:?}", s.alarms);
}

#[test]
fn transmit_selects_transmit_k_through_its_trafo_index() {
    // The TRANSMIT example machine (XM radial, CM, ZM) as a chain, linked to TRANSMIT(1) by
    // $NT_TRAFO_INDEX = 12 (tens digit 1); the same face contour as with the machine data:
    // X20 Y20 is the radial position √800 at C = 45°.
    let chain = "$NK_NAME[0]=\"ROOT\"\n$NK_TYPE[0]=\"OFFSET\"\n$NK_NEXT[0]=\"X\"\n$NK_PARALLEL[0]=\"C\"\n\
                 $NK_NAME[1]=\"X\"\n$NK_TYPE[1]=\"AXIS_LIN\"\n$NK_OFF_DIR[1,0]=1\n$NK_AXIS[1]=\"XM\"\n$NK_NEXT[1]=\"Z\"\n\
                 $NK_NAME[2]=\"Z\"\n$NK_TYPE[2]=\"AXIS_LIN\"\n$NK_OFF_DIR[2,2]=1\n$NK_AXIS[2]=\"ZM\"\n\
                 $NK_NAME[3]=\"C\"\n$NK_TYPE[3]=\"AXIS_ROT\"\n$NK_OFF_DIR[3,2]=-1\n$NK_AXIS[3]=\"CM\"\n\
                 $NT_NAME[1]=\"Face\"\n$NT_TRAFO_TYPE[1]=\"TRANSMIT_K\"\n$NT_T_CHAIN_LAST_ELEM[1]=\"Z\"\n\
                 $NT_P_CHAIN_LAST_ELEM[1]=\"C\"\n$NT_ROT_AX_NAME[1,1]=\"C\"\n$NT_GEO_AX_NAME[1,0]=\"X\"\n\
                 $NT_GEO_AX_NAME[1,2]=\"Z\"\n";
    let program = "G0 X40 Z10\nTRANSMIT\nG1 F1000 X20 Y20 Z5\nM0\nM30";
    let run = |extra: &str| {
        let mut ch = Channel::from_preset("transmit-example", extra).unwrap();
        ch.run_program(program).unwrap();
        while ch.is_busy() {
            ch.step();
        }
        ch.snapshot()
    };
    let (md, indexed) = (run(chain), run(&format!("{chain}$NT_TRAFO_INDEX[1]=12\n")));
    assert_eq!(indexed.transformation.as_ref().map(|t| t.index), Some(101), "the chain's data set");
    assert_eq!(md.transformation.as_ref().map(|t| t.index), Some(1), "the machine data's");
    let expected = [800f64.sqrt(), 45.0, 5.0];
    for s in [&md, &indexed] {
        assert!(s.alarms.is_empty(), "{:?}", s.alarms);
        assert!(near(&machine(s)[..3], &expected, 1e-6), "{:?}", s.machine);
    }
}
