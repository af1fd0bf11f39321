//! Transformations defined by kinematic chains (K12): `$NK_`/`$NT_` data in and out as NC data
//! text, validation of the element graph, TRAORI_DYN built from a chain against the matching
//! machine-data TRAORI (the offsets of the chains are worked out by hand from the machine's
//! geometry below each test), and TRAFOON in a program.

use nctwin_engine::kinematics::{self, ActiveTrafo, SelectArgs, Transformation};
use nctwin_engine::machine_data::{MachineConfig, MachineData, presets};
use nctwin_engine::{Channel, Snapshot, Status};
use proptest::prelude::*;

use crate::chain_support;
use chain_support::{SIX, axes, elements, near};

/// Machine-data TRAORI set 1 of type `t` with rotary roles `rot` on the SIX machine.
fn md_traori(t: u32, rot: [u32; 2], md: &str) -> String {
    format!(
        "$MC_TRAFO_TYPE_1={t}\n$MC_TRAFO_AXES_IN_1[0]=1\n$MC_TRAFO_AXES_IN_1[1]=2\n$MC_TRAFO_AXES_IN_1[2]=3\n\
         $MC_TRAFO_AXES_IN_1[3]={}\n$MC_TRAFO_AXES_IN_1[4]={}\n$MC_TRAFO_AXES_IN_1[5]=0\n\
         $MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2\n$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3\n{md}",
        rot[0], rot[1]
    )
}

fn vec_md(name: &str, v: [f64; 3]) -> String {
    (0..3).map(|i| format!("{name}[{i}]={:?}\n", v[i])).collect()
}

/// A TRAORI_DYN record n with the given subchains, rotary and geometry element names.
fn trafo(n: usize, name: &str, t: [&str; 2], p: [&str; 2], rot: &[&str], geo: [&str; 3]) -> String {
    let mut out = format!(
        "$NT_NAME[{n}]=\"{name}\"\n$NT_TRAFO_TYPE[{n}]=\"TRAORI_DYN\"\n\
         $NT_T_CHAIN_FIRST_ELEM[{n}]=\"{}\"\n$NT_T_CHAIN_LAST_ELEM[{n}]=\"{}\"\n\
         $NT_P_CHAIN_FIRST_ELEM[{n}]=\"{}\"\n$NT_P_CHAIN_LAST_ELEM[{n}]=\"{}\"\n",
        t[0], t[1], p[0], p[1]
    );
    for (k, r) in rot.iter().enumerate() {
        out += &format!("$NT_ROT_AX_NAME[{n},{k}]=\"{r}\"\n");
    }
    for (k, g) in geo.iter().enumerate() {
        out += &format!("$NT_GEO_AX_NAME[{n},{k}]=\"{g}\"\n");
    }
    out
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];
const NX: [f64; 3] = [-1.0, 0.0, 0.0];
const NY: [f64; 3] = [0.0, -1.0, 0.0];
const NZ: [f64; 3] = [0.0, 0.0, -1.0];

/// Head: X, Y, Z, then an inclined B' built with constant rotations about Y by ±45° around
/// it, turning about the world direction R_y(45°)·x = (√½, 0, −√½), then C... no: C (about Z)
/// first, then B' — a cardan-like head C-B'. World geometry at the kinematic zero, with a
/// workpiece reference 5 mm along +X of the world origin (part chain: one offset):
/// p_C = (10, 20, 300) + (0,0,0) → l1 = p_C − x_p = (5, 20, 300);
/// offset C→B' (in the frame rotated by +45° about Y) (0, 0, 40) → world R_y(45)·(0,0,40)
/// = (40·√½, 0, 40·√½) = l2; B' direction v2 = (√½, 0, −√½);
/// tool offset after B' (frame rotated back) (3, 2, −150) = l3 — the constant rotations cancel.
fn head_chain() -> (String, String) {
    let s = 0.5f64.sqrt();
    let chain =
        elements(&[
            ("ROOT", "OFFSET", "X axis", "WP", [0.0; 3], "", 0.0),
            ("X axis", "AXIS_LIN", "Y axis", "", X, "X1", 0.0),
            ("Y axis", "AXIS_LIN", "Z axis", "", Y, "Y1", 0.0),
            ("Z axis", "AXIS_LIN", "C offset", "", Z, "Z1", 0.0),
            ("C offset", "OFFSET", "C axis", "", [10.0, 20.0, 300.0], "", 0.0),
            ("C axis", "AXIS_ROT", "tilt", "", Z, "C1", 0.0),
            ("tilt", "ROT_CONST", "B offset", "", Y, "", 45.0),
            ("B offset", "OFFSET", "B axis", "", [0.0, 0.0, 40.0], "", 0.0),
            ("B axis", "AXIS_ROT", "untilt", "", X, "B1", 0.0),
            ("untilt", "ROT_CONST", "Tool", "", Y, "", -45.0),
            ("Tool", "OFFSET", "", "", [3.0, 2.0, -150.0], "", 0.0),
            ("WP", "OFFSET", "", "", [5.0, 0.0, 0.0], "", 0.0),
        ]) + &trafo(1, "Head", ["ROOT", "Tool"], ["ROOT", "WP"], &["C axis", "B axis"], ["X axis", "Y axis", "Z axis"]);
    let md = md_traori(
        24,
        [6, 5],
        &(vec_md("$MC_TRAFO5_AXIS1_1", Z)
            + &vec_md("$MC_TRAFO5_AXIS2_1", [s, 0.0, -s])
            + &vec_md("$MC_TRAFO5_PART_OFFSET_1", [5.0, 20.0, 300.0])
            + &vec_md("$MC_TRAFO5_JOINT_OFFSET_1", [40.0 * s, 0.0, 40.0 * s])
            + &vec_md("$MC_TRAFO5_BASE_TOOL_1", [3.0, 2.0, -150.0])),
    );
    (chain, md)
}

/// Table: Z on the tool side with the spindle nose x_t = (0, 0, 200); X, Y move the table
/// (directions −X, −Y), which carries A (about −X, DIN) at q1 = (5, 30, −100), then C (about
/// −Z) at q2 = q1 + (1, −2, 40) = (6, 28, −60), workpiece reference x_p = q2 + (−6, −28, 70)
/// = (0, 0, 10). MD type 40: l2 = BASE_TOOL = q1 − x_t = (5, 30, −300), l3 = JOINT_OFFSET =
/// (1, −2, 40), l4 = PART_OFFSET = (−6, −28, 70). A has $NK_A_OFF = 10 (its zero 10° further),
/// which the MD expresses as TRAFO5_ROT_AX_OFFSET = −10.
fn table_chain() -> (String, String) {
    let chain =
        elements(&[
            ("ROOT", "OFFSET", "Z axis", "X axis", [0.0; 3], "", 0.0),
            ("Z axis", "AXIS_LIN", "Spindle", "", Z, "Z1", 0.0),
            ("Spindle", "OFFSET", "", "", [0.0, 0.0, 200.0], "", 0.0),
            ("X axis", "AXIS_LIN", "Y axis", "", NX, "X1", 0.0),
            ("Y axis", "AXIS_LIN", "A offset", "", NY, "Y1", 0.0),
            ("A offset", "OFFSET", "A axis", "", [5.0, 30.0, -100.0], "", 0.0),
            ("A axis", "AXIS_ROT", "C offset", "", NX, "A1", 10.0),
            ("C offset", "OFFSET", "C axis", "", [1.0, -2.0, 40.0], "", 0.0),
            ("C axis", "AXIS_ROT", "WP", "", NZ, "C1", 0.0),
            ("WP", "OFFSET", "", "", [-6.0, -28.0, 70.0], "", 0.0),
        ]) + &trafo(3, "Table", ["", "Spindle"], ["ROOT", "WP"], &["A axis", "C axis"], ["X axis", "Y axis", "Z axis"]);
    let md = md_traori(
        40,
        [4, 6],
        &(vec_md("$MC_TRAFO5_AXIS1_1", NX)
            + &vec_md("$MC_TRAFO5_AXIS2_1", NZ)
            + &vec_md("$MC_TRAFO5_BASE_TOOL_1", [5.0, 30.0, -300.0])
            + &vec_md("$MC_TRAFO5_JOINT_OFFSET_1", [1.0, -2.0, 40.0])
            + &vec_md("$MC_TRAFO5_PART_OFFSET_1", [-6.0, -28.0, 70.0])
            + "$MC_TRAFO5_ROT_AX_OFFSET_1[0]=-10\n"),
    );
    (chain, md)
}

/// Mixed: head B (about Y) at p1 = (0, 0, 350) on X, Y, Z, spindle nose 120 below it
/// (x_t = (0, 0, 230)); table C (about −Z) at q2 = (100, 50, 0) beside the root, workpiece
/// reference x_p = q2 + (−100, −50, 20) = (0, 0, 20). MD type 56: l1 = JOINT_OFFSET = p1,
/// l2 = BASE_TOOL = (0, 0, −120), l3 = JOINT_OFFSET_PART = q2, l4 = PART_OFFSET = (−100, −50, 20).
/// $NT_ROT_AX_OFFSET[.,1] = 25 is TRAFO5_ROT_AX_OFFSET[1] = 25.
fn mixed_chain() -> (String, String) {
    let chain = elements(&[
        ("ROOT", "OFFSET", "X axis", "C offset", [0.0; 3], "", 0.0),
        ("X axis", "AXIS_LIN", "Y axis", "", X, "X1", 0.0),
        ("Y axis", "AXIS_LIN", "Z axis", "", Y, "Y1", 0.0),
        ("Z axis", "AXIS_LIN", "B offset", "", Z, "Z1", 0.0),
        ("B offset", "OFFSET", "B axis", "", [0.0, 0.0, 350.0], "", 0.0),
        ("B axis", "AXIS_ROT", "Spindle", "", Y, "B1", 0.0),
        ("Spindle", "OFFSET", "", "", [0.0, 0.0, -120.0], "", 0.0),
        ("C offset", "OFFSET", "C axis", "", [100.0, 50.0, 0.0], "", 0.0),
        ("C axis", "AXIS_ROT", "WP", "", NZ, "C1", 0.0),
        ("WP", "OFFSET", "", "", [-100.0, -50.0, 20.0], "", 0.0),
    ]) + &trafo(
        2,
        "Mixed",
        ["ROOT", "Spindle"],
        ["ROOT", "WP"],
        &["B axis", "C axis"],
        ["X axis", "Y axis", "Z axis"],
    ) + "$NT_ROT_AX_OFFSET[2,1]=25\n";
    let md = md_traori(
        56,
        [5, 6],
        &(vec_md("$MC_TRAFO5_AXIS1_1", Y)
            + &vec_md("$MC_TRAFO5_AXIS2_1", NZ)
            + &vec_md("$MC_TRAFO5_JOINT_OFFSET_1", [0.0, 0.0, 350.0])
            + &vec_md("$MC_TRAFO5_BASE_TOOL_1", [0.0, 0.0, -120.0])
            + &vec_md("$MC_TRAFO5_JOINT_OFFSET_PART_1", [100.0, 50.0, 0.0])
            + &vec_md("$MC_TRAFO5_PART_OFFSET_1", [-100.0, -50.0, 20.0])
            + "$MC_TRAFO5_ROT_AX_OFFSET_1[1]=25\n"),
    );
    (chain, md)
}

fn config(text: &str) -> MachineConfig {
    MachineData::default().apply_text(&format!("{SIX}{text}")).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The chain-defined and the machine-data transformation of a machine, with `tool`.
fn pair(machine: fn() -> (String, String), tool: [f64; 3]) -> (ActiveTrafo, ActiveTrafo) {
    let (chain, md) = machine();
    let ccfg = config(&chain);
    let mcfg = config(&md);
    let cset = ccfg.trafos.iter().find(|s| s.chain.is_some()).expect("chain transformation");
    let mset = &mcfg.trafos[0];
    let build =
        |set, cfg| ActiveTrafo { trafo: kinematics::build(set, cfg, &SelectArgs::default()).unwrap(), tool, number: 1 };
    (build(cset, &ccfg), build(mset, &mcfg))
}

const MACHINES: [fn() -> (String, String); 3] = [head_chain, table_chain, mixed_chain];

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, .. ProptestConfig::default() })]

    /// Forward (tool tip and orientation), position inverse and oriented inverse agree with the
    /// machine-data TRAORI to 1e-9 mm / 1e-9 over random poses of each machine.
    #[test]
    fn a_chain_defined_traori_equals_the_machine_data_one(
        machine in 0..3usize,
        lin in prop::array::uniform3(-300.0f64..300.0),
        rot in prop::array::uniform3(-170.0f64..170.0),
        tool in 0.0f64..150.0,
    ) {
        let (c, m) = pair(MACHINES[machine], [0.0, 0.0, tool]);
        let pose = axes(&[lin[0], lin[1], lin[2], rot[0], rot[1], rot[2]]);
        let (fc, fm) = (c.forward(&pose), m.forward(&pose));
        prop_assert!(near(&fc[..6], &fm[..6], 1e-9), "forward {:?} vs {:?}", &fc[..6], &fm[..6]);
        let (oc, om) = (c.trafo.orientation(&pose).unwrap(), m.trafo.orientation(&pose).unwrap());
        prop_assert!(near(&oc, &om, 1e-12), "orientation {oc:?} vs {om:?}");
        let (ic, im) = (c.inverse(&fc, &pose).unwrap(), m.inverse(&fm, &pose).unwrap());
        prop_assert!(near(&ic[..6], &im[..6], 1e-9) && near(&ic[..6], &pose[..6], 1e-8));
        // The oriented inverse from a neighbouring pose picks the same solution in both.
        let prev = axes(&[lin[0], lin[1], lin[2], rot[0] + 3.0, rot[1] - 2.0, rot[2] + 1.0]);
        let (rc, rm) = (c.inverse_oriented(&fc, &oc, &prev), m.inverse_oriented(&fm, &om, &prev));
        match (rc, rm) {
            (Ok(rc), Ok(rm)) => prop_assert!(near(&rc[..6], &rm[..6], 1e-8), "{:?} vs {:?}", &rc[..6], &rm[..6]),
            (rc, rm) => prop_assert!(rc.is_err() && rm.is_err(), "{rc:?} vs {rm:?}"),
        }
        prop_assert_eq!(c.trafo.orientation_slots(), m.trafo.orientation_slots());
        prop_assert_eq!(c.trafo.geo_slots(), m.trafo.geo_slots());
    }
}

#[test]
fn the_head_chain_gives_the_hand_computed_tool_tip() {
    // Independent check of one pose of the head (C = 90°, B' = 0): the tool offset (3, 2, −150)
    // and the offset to B' turn by 90° about Z: world tip = M + p_C + R_z(90)·(l2 + l3 + t)
    // − x_p with l2 + l3 + t = (40√½ + 3, 2, 40√½ − 150 − 50).
    let (c, _) = pair(head_chain, [0.0, 0.0, 50.0]);
    let s = 0.5f64.sqrt();
    let (u, v, w) = (40.0 * s + 3.0, 2.0, 40.0 * s - 200.0);
    let tip = c.forward(&axes(&[1.0, 2.0, 3.0, 0.0, 0.0, 90.0]));
    let expected = [1.0 + 10.0 - v - 5.0, 2.0 + 20.0 + u, 3.0 + 300.0 + w];
    assert!(near(&tip[..3], &expected, 1e-9), "{:?} vs {expected:?}", &tip[..3]);
}

#[test]
fn chain_data_round_trips_as_text_and_through_every_preset() {
    let (chain, _) = mixed_chain();
    let mut md = MachineData::default();
    md.apply_text(&format!("{SIX}{chain}$NT_TRAFO_INCLUDES_TOOL[2]=0\n$NT_BASE_ORIENT[2,0]=0.5\n")).unwrap();
    let text = md.to_text();
    assert!(
        text.contains("$NK_NAME[4]=\"B offset\"\n") && text.contains("$NT_ROT_AX_NAME[2,1]=\"C axis\"\n"),
        "{text}"
    );
    // Defaults are not exported: the default (0, 0, 1) keeps its Z component out.
    assert!(text.contains("$NT_BASE_ORIENT[2,0]=0.5\n") && !text.contains("$NT_BASE_ORIENT[2,2]"), "{text}");
    let mut again = MachineData::default();
    again.apply_text(&text).unwrap();
    assert_eq!(again, md);
    let set = again.activate().unwrap().trafos.into_iter().find(|s| s.chain.is_some()).unwrap();
    assert!(!set.includes_tool);
    assert_eq!(set.number, 102);
}

#[test]
fn bad_chain_data_is_rejected_with_its_line() {
    let mut md = MachineData::default();
    for (text, needle) in [
        ("$NK_NAME[64]=\"A\"", "index out of range 0..63"),
        ("$NK_OFF_DIR[0]=1", "needs two indices"),
        ("$NK_OFF_DIR[0,3]=1", "component 3 out of range"),
        ("$NT_NAME[10]=\"T\"", "$MN_MM_NUM_KIN_TRAFOS"),
        ("$NK_NAME[0]=5", "expected a string"),
        ("$NK_NAME[0]=\"ABCDEFGHIJABCDEFGHIJABCDEFGHIJAB\"", "longer than 31"),
        ("$NK_FOO[0]=1", "unknown name $NK_FOO"),
    ] {
        let e = md.apply_text(&format!("; x\n{text}")).unwrap_err();
        assert_eq!(e.line, Some(2), "{text}");
        assert!(e.message.contains(needle), "{text}: {}", e.message);
    }
    assert_eq!(md, MachineData::default());
}

#[test]
fn the_element_graph_is_checked_at_activation() {
    let root = |next: &str| format!("$NK_NAME[0]=\"ROOT\"\n$NK_TYPE[0]=\"OFFSET\"\n$NK_NEXT[0]=\"{next}\"\n");
    let el = |i: usize, name: &str, next: &str| {
        format!("$NK_NAME[{i}]=\"{name}\"\n$NK_TYPE[{i}]=\"OFFSET\"\n$NK_NEXT[{i}]=\"{next}\"\n")
    };
    let head = head_chain().0;
    for (text, needle) in [
        (root("Nowhere"), "$NK_NEXT names \"Nowhere\", which is no element"),
        (el(0, "Base", ""), "no element is named \"ROOT\""),
        (root("") + &el(1, "A", "B") + &el(2, "B", "A"), "lies on a cycle"),
        (root("A") + &el(1, "A", "ROOT"), "root element \"ROOT\" cannot follow \"A\""),
        (root("A") + &el(1, "A", "") + &el(2, "B", "A"), "\"A\" follows both \"ROOT\" and \"B\""),
        (root("") + "$NK_TYPE[1]=\"OFFSET\"\n", "element 1 has data but no $NK_NAME"),
        (root("") + "$NK_NAME[1]=\"ROOT\"\n$NK_TYPE[1]=\"OFFSET\"\n", "two elements have this name"),
        (root("") + "$NK_NAME[1]=\"Q\"\n$NK_TYPE[1]=\"SPRING\"\n", "\"SPRING\" is not an element type"),
        (root("") + "$NK_NAME[1]=\"Q\"\n$NK_TYPE[1]=\"AXIS_ROT\"\n$NK_OFF_DIR[1,2]=1\n", "needs $NK_AXIS"),
        (
            root("") + "$NK_NAME[1]=\"Q\"\n$NK_TYPE[1]=\"AXIS_ROT\"\n$NK_OFF_DIR[1,2]=1\n$NK_AXIS[1]=\"X1\"\n",
            "is a linear axis",
        ),
        (root("") + "$NK_NAME[1]=\"Q\"\n$NK_TYPE[1]=\"AXIS_LIN\"\n$NK_AXIS[1]=\"X1\"\n", "is the zero vector"),
        (
            root("") + "$NK_NAME[1]=\"Q\"\n$NK_TYPE[1]=\"AXIS_LIN\"\n$NK_OFF_DIR[1,0]=1\n$NK_AXIS[1]=\"W9\"\n",
            "\"W9\" is no machine or channel axis",
        ),
        // Transformation records.
        (
            head.replace("$NT_T_CHAIN_LAST_ELEM[1]=\"Tool\"", "$NT_T_CHAIN_LAST_ELEM[1]=\"Tol\""),
            "LAST_ELEM \"Tol\" is no element",
        ),
        (
            head.replace("$NT_T_CHAIN_FIRST_ELEM[1]=\"ROOT\"", "$NT_T_CHAIN_FIRST_ELEM[1]=\"WP\""),
            "FIRST_ELEM \"WP\" does not lie on the way from the root to \"Tool\"",
        ),
        (
            head.replace("$NT_T_CHAIN_FIRST_ELEM[1]=\"ROOT\"", "$NT_T_CHAIN_FIRST_ELEM[1]=\"C offset\""),
            "axis element \"X axis\" lies between the root and FIRST_ELEM",
        ),
        (
            head.replace("$NT_ROT_AX_NAME[1,1]=\"B axis\"", ""),
            "$NT_ROT_AX_NAME[1,1] must name rotary axis element \"B axis\"",
        ),
        (
            head.replace("$NT_GEO_AX_NAME[1,2]=\"Z axis\"", ""),
            "$NT_GEO_AX_NAME[1,2] must name the linear axis element \"Z axis\"",
        ),
        (
            head.replace("$NK_A_OFF[9]=-45.0", "$NK_A_OFF[9]=-40.0"),
            "constant rotations (ROT_CONST) of a subchain must cancel",
        ),
        (head.replace("\"TRAORI_DYN\"", "\"TRAORI_XYZ\""), "\"TRAORI_XYZ\" is not a transformation type"),
        (head.replace("$NT_NAME[1]=\"Head\"", ""), "transformation 1 has data but no $NT_NAME"),
        (head.replace("$NK_OFF_DIR[2,1]=1.0", "$NK_OFF_DIR[2,1]=-1.0"), "\"Y axis\" must point along +X, +Y or +Z"),
    ] {
        let mut md = MachineData::default();
        md.apply_text(SIX).unwrap();
        let before = md.clone();
        let e = md.apply_text(&text).unwrap_err();
        assert!(e.message.contains(needle), "{text}\n→ {}", e.message);
        assert_eq!(md, before, "all or nothing");
    }
}

#[test]
fn other_transformation_types_are_stored_but_not_built() {
    let text = format!("{}$NT_NAME[4]=\"Static\"\n$NT_TRAFO_TYPE[4]=\"TRAORI_STAT\"\n", head_chain().0);
    let cfg = config(&text);
    let chain: Vec<_> = cfg.trafos.iter().filter_map(|s| s.chain.as_ref().map(|c| c.name.as_str())).collect();
    assert_eq!(chain, ["Head"]);
}

// ---------------------------------------------------------------------------------------------
// TRAFOON in a program on the head preset (C about Z carrying A about X, pivot 150 above the
// spindle nose, TRAORI type 20)
// ---------------------------------------------------------------------------------------------

const HEAD_CHAIN: &str = r#"
$NK_NAME[0]="ROOT"
$NK_TYPE[0]="OFFSET"
$NK_NEXT[0]="X axis"
$NK_NAME[1]="X axis"
$NK_TYPE[1]="AXIS_LIN"
$NK_NEXT[1]="Y axis"
$NK_OFF_DIR[1,0]=1
$NK_AXIS[1]="X"
$NK_NAME[2]="Y axis"
$NK_TYPE[2]="AXIS_LIN"
$NK_NEXT[2]="Z axis"
$NK_OFF_DIR[2,1]=1
$NK_AXIS[2]="Y"
$NK_NAME[3]="Z axis"
$NK_TYPE[3]="AXIS_LIN"
$NK_NEXT[3]="C offset"
$NK_OFF_DIR[3,2]=1
$NK_AXIS[3]="Z"
$NK_NAME[4]="C offset"
$NK_TYPE[4]="OFFSET"
$NK_NEXT[4]="C axis"
$NK_OFF_DIR[4,2]=150
$NK_NAME[5]="C axis"
$NK_TYPE[5]="AXIS_ROT"
$NK_NEXT[5]="A axis"
$NK_OFF_DIR[5,2]=1
$NK_AXIS[5]="C"
$NK_NAME[6]="A axis"
$NK_TYPE[6]="AXIS_ROT"
$NK_NEXT[6]="Spindle"
$NK_OFF_DIR[6,0]=1
$NK_AXIS[6]="A"
$NK_NAME[7]="Spindle"
$NK_TYPE[7]="OFFSET"
$NK_OFF_DIR[7,2]=-150
$NT_NAME[1]="Fork head C-A"
$NT_TRAFO_TYPE[1]="TRAORI_DYN"
$NT_T_CHAIN_LAST_ELEM[1]="Spindle"
$NT_ROT_AX_NAME[1,0]="C axis"
$NT_ROT_AX_NAME[1,1]="A axis"
$NT_GEO_AX_NAME[1,0]="X axis"
$NT_GEO_AX_NAME[1,1]="Y axis"
$NT_GEO_AX_NAME[1,2]="Z axis"
"#;

const MOVES: &str = "G1 F3000\nA30 C40\nX10 Y-5 Z20\nA3=1 B3=0 C3=1\nX-20\nM30";

fn run(extra: &str, program: &str) -> Snapshot {
    let mut ch = Channel::from_preset("mill5-head-ca", extra).unwrap_or_else(|e| panic!("{e}"));
    ch.run_program(program).unwrap();
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < 1_000_000, "program does not end");
    }
    ch.snapshot()
}

fn machine_axes(s: &Snapshot) -> Vec<f64> {
    s.machine.iter().map(|(_, v)| *v).collect()
}

#[test]
fn trafoon_in_a_program_moves_the_machine_like_traori() {
    let start = "T1 D1\nG0 X0 Y0 Z50\n";
    let md = run(HEAD_CHAIN, &format!("{start}TRAORI\n{MOVES}"));
    let chain = run(HEAD_CHAIN, &format!("{start}TRAFOON(\"Fork head C-A\")\n{MOVES}"));
    assert_eq!(md.status, Status::Idle, "{:?}", md.alarms);
    assert_eq!(chain.status, Status::Idle, "{:?}", chain.alarms);
    let (a, b) = (machine_axes(&md), machine_axes(&chain));
    assert!(near(&a, &b, 1e-6), "{a:?} vs {b:?}");
    // The last orientation (1, 0, 1)/√2 from A30 C40: A = 45, C = 90 (nearest).
    assert!((a[3] - 45.0).abs() < 1e-6 && (a[4] - 90.0).abs() < 1e-6, "{a:?}");
}

#[test]
fn a_program_writes_the_chain_and_selects_it_after_newconf() {
    let writes: String = HEAD_CHAIN.lines().filter(|l| !l.is_empty()).map(|l| format!("{l}\n")).collect();
    let program = format!("T1 D1\nG0 X0 Y0 Z50\n{writes}NEWCONF\nTRAFOON(\"Fork head C-A\")\nG1 F3000\nA30 C40\nM30");
    let s = run("", &program);
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    // Tool tip held at (0, 0, 50) with o = (sin C·sin A, −cos C·sin A, cos A), L = 100, pivot
    // 150 above the nose: M = P − (0, 0, 150) + 250·o.
    let (sa, ca) = 30f64.to_radians().sin_cos();
    let (sc, cc) = 40f64.to_radians().sin_cos();
    let o = [sc * sa, -cc * sa, ca];
    let expected = [250.0 * o[0], 250.0 * o[1], 50.0 - 150.0 + 250.0 * o[2], 30.0, 40.0];
    assert!(near(&machine_axes(&s), &expected, 1e-6), "{:?} vs {expected:?}", s.machine);
}

#[test]
fn trafo_index_makes_traori_select_the_chain_and_unknown_names_raise_14401() {
    let s = run(&format!("{HEAD_CHAIN}$NT_TRAFO_INDEX[1]=10\n"), "TRAORI\nM0\nM30");
    assert_eq!(s.transformation.map(|t| t.trafo_type), Some(24), "the chain's generic head type");
    let s = run(HEAD_CHAIN, "TRAORI\nM0\nM30");
    assert_eq!(s.transformation.map(|t| t.trafo_type), Some(20), "the machine data's type");
    let s = run(HEAD_CHAIN, "TRAFOON(\"Nope\")\nM30");
    assert!(s.alarms.iter().any(|a| a.number == 14401), "{:?}", s.alarms);
}

#[test]
fn the_presets_still_activate_with_chain_data_beside_them() {
    for preset in presets::PRESETS {
        let mut md = MachineData::default();
        md.apply_text(preset.text).unwrap();
        md.apply_text("$NK_NAME[0]=\"ROOT\"\n$NK_TYPE[0]=\"OFFSET\"\n")
            .unwrap_or_else(|e| panic!("{}: {e}", preset.id));
    }
}

#[test]
fn delobj_deletes_the_chain_data_with_the_next_newconf() {
    // With the transformation records deleted, TRAFOON no longer finds the head: 14401.
    let s = run(HEAD_CHAIN, "DELOBJ(\"TRAFO_DATA\")\nNEWCONF\nTRAFOON(\"Fork head C-A\")\nM30");
    assert_eq!(s.alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [14401], "{:?}", s.alarms);
    // Deleting the elements too leaves a valid (empty) configuration.
    let s = run(HEAD_CHAIN, "DELOBJ(\"TRAFO_DATA\")\nDELOBJ(\"KIN_CHAIN_ELEM\")\nNEWCONF\nM30");
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    let s = run(HEAD_CHAIN, "DELOBJ(\"TOOLS\")\nM30");
    assert_eq!(s.status, Status::Alarm);
}

// ---------------------------------------------------------------------------------------------
// The remaining $NT_ fields: stored, checked, effective where the manual says what they do
// ---------------------------------------------------------------------------------------------

/// Every further `$NT_` field of record 1 of the head chain, with values other than the defaults.
const MORE_FIELDS: &str = "$NT_ROT_OFFSET_FROM_FRAME[1]=2\n$NT_CLOSE_CHAIN_P[1]=\"WP\"\n\
    $NT_CLOSE_CHAIN_T[1]=\"B offset\"\n$NT_AUX_POS[1,1]=1.5\n$NT_IDENT[1,0]=1000\n$NT_IDENT[1,1]=100\n\
    $NT_BASE_TOOL_COMP[1]=5\n$NT_ROT_AX_POS[1,2]=30.0\n$NT_POLE_LIMIT[1]=3.5\n$NT_POLE_TOL[1]=1.25\n\
    $NT_IGNORE_TOOL_ORIENT[1]=1\n$NT_CORR_ELEM_T[1,2]=\"B offset\"\n$NT_CORR_ELEM_P[1,0]=\"WP\"\n\
    $NT_POLE_SIDE_FIX[1]=1\n";

#[test]
fn the_further_nt_fields_round_trip_as_text() {
    let mut md = MachineData::default();
    md.apply_text(&format!("{SIX}{}{MORE_FIELDS}", head_chain().0)).unwrap();
    let text = md.to_text();
    for line in MORE_FIELDS.lines() {
        assert!(text.contains(&format!("{line}\n")), "{line} missing in\n{text}");
    }
    let mut again = MachineData::default();
    again.apply_text(&text).unwrap();
    assert_eq!(again, md);
}

#[test]
fn the_pole_limits_of_a_chain_record_reach_traori() {
    let pole_limits = |extra: &str| {
        let cfg = config(&format!("{}{extra}", head_chain().0));
        let set = cfg.trafos.iter().find(|s| s.chain.is_some()).unwrap();
        match kinematics::build(set, &cfg, &SelectArgs::default()).unwrap() {
            kinematics::AnyTrafo::Traori(t) => t.pole_limits(),
            other => panic!("{other:?}"),
        }
    };
    // $NT_POLE_TOL is the tolerance circle about the pole (TRAFO5_NON_POLE_LIMIT), $NT_POLE_LIMIT
    // the end angle tolerance through the pole (TRAFO5_POLE_LIMIT); unset: the MD defaults 2°.
    assert_eq!(pole_limits(MORE_FIELDS), (1.25, 3.5));
    assert_eq!(pole_limits(""), (2.0, 2.0));
}

#[test]
fn the_further_nt_fields_are_checked_at_activation() {
    let head = head_chain().0;
    for (extra, needle) in [
        ("$NT_CORR_ELEM_T[1,0]=\"B axis\"\n", "a correction element must be of type OFFSET"),
        ("$NT_CORR_ELEM_P[1,3]=\"Tool\"\n", "\"Tool\" is no element of the subchain ending at $NT_P_CHAIN_LAST_ELEM"),
        ("$NT_CLOSE_CHAIN_T[1]=\"Nowhere\"\n", "$NT_CLOSE_CHAIN_T[1] \"Nowhere\" is no element of the subchain"),
        ("$NT_IGNORE_TOOL_ORIENT[1]=2\n", "FALSE or TRUE"),
        ("$NT_POLE_LIMIT[1]=200\n", "an angle 0..180 degrees"),
        ("$NT_ROT_OFFSET_FROM_FRAME[1]=3\n", "allowed are 0..2"),
        ("$NT_BASE_TOOL_COMP[1]=8\n", "allowed are 0..7"),
        (
            "$NT_NAME[2]=\"S\"\n$NT_TRAFO_TYPE[2]=\"TRAORI_STAT\"\n$NT_T_CHAIN_LAST_ELEM[2]=\"Tool\"\n\
             $NT_ROT_AX_NAME[2,0]=\"X axis\"\n",
            "$NT_ROT_AX_NAME[2,0] \"X axis\" is no rotary axis element",
        ),
    ] {
        let mut md = MachineData::default();
        md.apply_text(SIX).unwrap();
        let e = md.apply_text(&format!("{head}{extra}")).unwrap_err();
        assert!(e.message.contains(needle), "{extra}→ {}", e.message);
    }
    // A complete TRAORI_STAT record is accepted (stored, not built).
    let cfg = config(&format!(
        "{head}$NT_NAME[2]=\"S\"\n$NT_TRAFO_TYPE[2]=\"TRAORI_STAT\"\n$NT_T_CHAIN_LAST_ELEM[2]=\"Tool\"\n\
         $NT_ROT_AX_NAME[2,0]=\"C axis\"\n"
    ));
    assert_eq!(cfg.trafos.iter().filter(|s| s.chain.is_some()).count(), 1);
}

// ---------------------------------------------------------------------------------------------
// Reading chain data in programs; the reset transformation by name (MD20142)
// ---------------------------------------------------------------------------------------------

#[test]
fn a_program_reads_chain_data_including_its_own_writes() {
    // $NK_OFF_DIR[4,2] = 150 (the C offset of HEAD_CHAIN); written 60 in the program, read back
    // in the next block; the name comparison and a default ($NT_BASE_ORIENT[1,2] = 1) too.
    let program = "G0 X=$NK_OFF_DIR[4,2]\n$NK_OFF_DIR[4,2]=60\nG0 Y=$NK_OFF_DIR[4,2]\n\
                   IF $NT_NAME[1]==\"Fork head C-A\"\nG0 Z=$NT_BASE_ORIENT[1,2]\nENDIF\nM30";
    let s = run(HEAD_CHAIN, program);
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert!(near(&machine_axes(&s)[..3], &[150.0, 60.0, 1.0], 1e-9), "{:?}", s.machine);
    let s = run(HEAD_CHAIN, "R1=$NK_OFF_DIR[64,0]\nM30");
    assert_eq!(s.status, Status::Alarm);
    assert!(s.alarms[0].message.contains("index out of range 0..63"), "{:?}", s.alarms);
}

#[test]
fn trafo_reset_name_selects_the_chain_transformation_at_reset() {
    let s = run(&format!("{HEAD_CHAIN}$MC_TRAFO_RESET_NAME=\"Fork head C-A\"\n"), "G0 X0\nM30");
    assert_eq!(s.transformation.map(|t| t.trafo_type), Some(24), "the chain's generic head type after M30");
    let Err(e) = Channel::from_preset("mill5-head-ca", &format!("{HEAD_CHAIN}$MC_TRAFO_RESET_NAME=\"Nope\"\n")) else {
        panic!("an unknown reset name is rejected")
    };
    assert!(e.to_string().contains("$MC_TRAFO_RESET_NAME=\"Nope\" names no transformation"), "{e}");
}

// ---------------------------------------------------------------------------------------------
// Export and import of the chain data as a part program
// ---------------------------------------------------------------------------------------------

#[test]
fn the_chain_program_round_trips_and_runs_as_a_part_program() {
    let source = Channel::from_preset("mill5-head-ca", HEAD_CHAIN).unwrap();
    let program = source.export_kinematic_chains();
    assert!(program.starts_with("; Kinematic chain elements"), "{program}");
    assert!(program.contains("DELOBJ(\"TRAFO_DATA\")\nDELOBJ(\"KIN_CHAIN_ELEM\")\n$NK_NAME[0]=\"ROOT\"\n"));
    assert!(program.ends_with("$NT_ROT_AX_NAME[1,1]=\"A axis\"\nNEWCONF\n"), "{program}");
    // Imported into a session with other chain data: that data is gone, the head is there.
    let stale = "$NK_NAME[0]=\"ROOT\"\n$NK_TYPE[0]=\"OFFSET\"\n$NK_PARALLEL[0]=\"Stale\"\n\
                 $NK_NAME[9]=\"Stale\"\n$NK_TYPE[9]=\"OFFSET\"\n";
    let mut target = Channel::from_preset("mill5-head-ca", stale).unwrap();
    target.import_kinematic_chains(&program).unwrap();
    assert_eq!(target.machine_data().kin(), source.machine_data().kin());
    assert!(target.config().trafos.iter().any(|s| s.chain.as_ref().is_some_and(|c| c.name == "Fork head C-A")));
    // The same text as a part program, then TRAFOON: the control accepts it unchanged.
    let s = run("", &format!("{program}TRAFOON(\"Fork head C-A\")\nM0\nM30"));
    assert!(s.alarms.is_empty(), "{:?}", s.alarms);
    assert_eq!(s.transformation.map(|t| t.trafo_type), Some(24));
}

#[test]
fn a_bad_chain_program_names_its_line_and_changes_nothing() {
    let mut ch = Channel::from_preset("mill5-head-ca", HEAD_CHAIN).unwrap();
    let before = ch.machine_data().clone();
    for (program, line, needle) in [
        ("DELOBJ(\"TRAFO_DATA\")\n; comment\nG0 X10\n", Some(3), "holds only $NK_/$NT_ assignments"),
        ("N10 DELOBJ(\"KIN_CHAIN_ELEM\")\nN20 $NK_FOO[0]=1\n", Some(2), "unknown name $NK_FOO"),
        ("$MC_TRAFO_TYPE_1=0\n", Some(1), "holds only"),
        // Deleting the elements but not the records leaves the records without their chain.
        ("DELOBJ(\"KIN_CHAIN_ELEM\")\nNEWCONF\n", None, "is no element of the kinematic chain"),
    ] {
        let e = ch.import_kinematic_chains(program).unwrap_err().to_string();
        assert!(e.contains(needle), "{program}→ {e}");
        if let Some(line) = line {
            assert!(e.contains(&format!("line {line}")), "{program}→ {e}");
        }
        assert_eq!(ch.machine_data(), &before);
    }
}

#[test]
fn delobj_as_a_function_deletes_and_returns_zero() {
    // The manual's form R2 = DELOBJ("TRAFO_DATA"): R2 becomes 0 (X = R2 + 7 = 7), the records
    // are gone after NEWCONF.
    let s = run(HEAD_CHAIN, "R2=5\nR2 = DELOBJ(\"TRAFO_DATA\")\nNEWCONF\nG0 X=R2+7\nTRAFOON(\"Fork head C-A\")\nM30");
    assert_eq!(s.alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [14401], "{:?}", s.alarms);
    assert!((machine_axes(&s)[0] - 7.0).abs() < 1e-9, "{:?}", s.machine);
}
