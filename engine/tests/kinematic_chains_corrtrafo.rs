//! CORRTRAFO (K12 §4.3.2) on a chain-defined C-A head, DELOBJ as a function, `$NT_ROT_AX_CNT`
//! and the refusal of TRACON_K. Expected machine positions come from the head's geometry
//! written out by hand below (not from the transformation code): with C about +Z, A about +X,
//! the tool length L = 100 (T1 D1) and the tool tip P held,
//!   P = M + (0, 0, 150) + R_C·w + R_C·R_A·(0, 0, −150 + c − L),
//! where M are the linear axes, w the world vector of the correction element between C and A,
//! c the z of the correction element after the spindle offset; o = R_C·R_A·(0, 0, 1) =
//! (sin C·sin A, −cos C·sin A, cos A).

use nctwin_engine::{Channel, Snapshot, Status};

use crate::chain_support;
use chain_support::{El, elements, near};

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// The head on the mill5-head-ca axes (X, Y, Z, A, C): C offset 150 above the linear axes,
/// C, then a correction element between C and A inside a constant rotation of +90° about Z
/// (so its world vector is its own turned by 90°), A, the spindle 150 below A, and a second
/// correction element at the end. Tool chain sections: 0 = start..C, 1 = C..A, 2 = A..end.
fn head() -> String {
    let els: &[El] = &[
        ("ROOT", "OFFSET", "X axis", "", [0.0; 3], "", 0.0),
        ("X axis", "AXIS_LIN", "Y axis", "", X, "X", 0.0),
        ("Y axis", "AXIS_LIN", "Z axis", "", Y, "Y", 0.0),
        ("Z axis", "AXIS_LIN", "C offset", "", Z, "Z", 0.0),
        ("C offset", "OFFSET", "C axis", "", [0.0, 0.0, 150.0], "", 0.0),
        ("C axis", "AXIS_ROT", "Tilt", "", Z, "C", 0.0),
        ("Tilt", "ROT_CONST", "Corr CA", "", Z, "", 90.0),
        ("Corr CA", "OFFSET", "Untilt", "", [0.0; 3], "", 0.0),
        ("Untilt", "ROT_CONST", "A axis", "", Z, "", -90.0),
        ("A axis", "AXIS_ROT", "Spindle", "", X, "A", 0.0),
        ("Spindle", "OFFSET", "Corr tool", "", [0.0, 0.0, -150.0], "", 0.0),
        ("Corr tool", "OFFSET", "", "", [0.0; 3], "", 0.0),
    ];
    elements(els)
        + "$NT_NAME[1]=\"Head\"\n$NT_TRAFO_TYPE[1]=\"TRAORI_DYN\"\n$NT_T_CHAIN_LAST_ELEM[1]=\"Corr tool\"\n\
           $NT_ROT_AX_NAME[1,0]=\"C axis\"\n$NT_ROT_AX_NAME[1,1]=\"A axis\"\n\
           $NT_GEO_AX_NAME[1,0]=\"X axis\"\n$NT_GEO_AX_NAME[1,1]=\"Y axis\"\n$NT_GEO_AX_NAME[1,2]=\"Z axis\"\n\
           $NT_CORR_ELEM_T[1,1]=\"Corr CA\"\n$NT_CORR_ELEM_T[1,2]=\"Corr tool\"\n"
}

/// Record indices of the correction elements in `head`.
const CORR_CA: usize = 7;
const CORR_TOOL: usize = 11;

/// Declares V, sets it, starts with T1 D1 at the tool tip (0, 0, 50) and selects the head.
fn start(v: [f64; 3]) -> String {
    format!(
        "DEF REAL VEC[3]\nVEC[0]={:?}\nVEC[1]={:?}\nVEC[2]={:?}\nT1 D1\nG0 X0 Y0 Z50\nTRAFOON(\"Head\")\n",
        v[0], v[1], v[2]
    )
}

fn channel(extra: &str) -> Channel {
    Channel::from_preset("mill5-head-ca", &format!("{}{extra}", head())).unwrap_or_else(|e| panic!("{e}"))
}

/// The snapshot at the end of a run and R0..R99.
struct Done {
    s: Snapshot,
    r: Vec<f64>,
}

impl std::ops::Deref for Done {
    type Target = Snapshot;
    fn deref(&self) -> &Snapshot {
        &self.s
    }
}

fn run_on(ch: &mut Channel, program: &str) -> Done {
    ch.run_program(program).unwrap();
    let mut ticks = 0;
    while ch.is_busy() {
        ch.step();
        ticks += 1;
        assert!(ticks < 2_000_000, "program does not end");
    }
    Done { s: ch.snapshot(), r: (0..100).map(|n| ch.r_param(n)).collect() }
}

fn run(program: &str) -> Done {
    run_on(&mut channel(""), program)
}

/// X, Y, Z, A, C.
fn machine(s: &Snapshot) -> Vec<f64> {
    s.machine.iter().map(|(_, v)| *v).collect()
}

fn r(d: &Done, n: usize) -> f64 {
    d.r[n]
}

/// The linear axes for tip `p` at A, C (degrees) with world correction `w` between C and A and
/// `c` at the end of the tool chain, from the formula in the file header.
fn expected(p: [f64; 3], a: f64, c: f64, w: [f64; 3], corr_end: f64) -> Vec<f64> {
    let (sa, ca) = a.to_radians().sin_cos();
    let (sc, cc) = c.to_radians().sin_cos();
    let o = [sc * sa, -cc * sa, ca];
    let rw = [cc * w[0] - sc * w[1], sc * w[0] + cc * w[1], w[2]];
    let reach = 150.0 - corr_end + 100.0;
    let m: Vec<f64> = (0..3).map(|i| p[i] - [0.0, 0.0, 150.0][i] - rw[i] + reach * o[i]).collect();
    vec![m[0], m[1], m[2], a, c]
}

#[test]
fn an_offset_correction_of_a_section_moves_the_machine_and_is_stored() {
    // Section 2 (A .. end) is (0, 0, −150) + Corr tool; absolute section length (0, 0, −150.2)
    // leaves Corr tool = (0, 0, −0.2): the pivot-to-tip reach grows from 250 to 250.2.
    let program = format!(
        "{}R1=CORRTRAFO(2, 20, VEC)\nR2=$NK_OFF_DIR[{CORR_TOOL},2]\nG1 F3000 X0 Y0 Z50 A30 C40\nM30",
        start([0.0, 0.0, -150.2])
    );
    let mut ch = channel("");
    let s = run_on(&mut ch, &program);
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert_eq!(r(&s, 1), 0.0);
    assert!((r(&s, 2) + 0.2).abs() < 1e-9, "{}", r(&s, 2));
    let want = expected([0.0, 0.0, 50.0], 30.0, 40.0, [0.0; 3], -0.2);
    assert!(near(&machine(&s), &want, 1e-6), "{:?} vs {want:?}", machine(&s));
    // Without the correction the reach would be 250: the difference is 0.2·o, not nothing.
    let uncorrected = expected([0.0, 0.0, 50.0], 30.0, 40.0, [0.0; 3], 0.0);
    assert!(!near(&machine(&s), &uncorrected, 1e-3));
    // The corrected value is stored: in the export, and for the next selection after NEWCONF.
    let export = ch.export_kinematic_chains();
    let key = format!("$NK_OFF_DIR[{CORR_TOOL},2]=");
    let stored = export.lines().find_map(|l| l.strip_prefix(&key)).and_then(|v| v.parse::<f64>().ok());
    assert!(stored.is_some_and(|v| (v + 0.2).abs() < 1e-9), "{export}");
    let again = "T1 D1\nNEWCONF\nTRAFOON(\"Head\")\nG1 F3000 X0 Y0 Z50 A-20 C10\nM30";
    let s = run_on(&mut ch, again);
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    let want = expected([0.0, 0.0, 50.0], -20.0, 10.0, [0.0; 3], -0.2);
    assert!(near(&machine(&s), &want, 1e-6), "{:?} vs {want:?}", machine(&s));
}

#[test]
fn direct_and_world_corrections_differ_by_the_constant_rotation() {
    // Corr CA sits inside +90° about Z. Direct (tens 0): the element takes V = (0.3, 0, 0), its
    // world vector is R_z(90°)·V = (0, 0.3, 0). World (tens 1): the world vector is V, the
    // element takes R_z(−90°)·V = (0, −0.3, 0).
    let read = format!("R10=$NK_OFF_DIR[{CORR_CA},0]\nR11=$NK_OFF_DIR[{CORR_CA},1]\nR12=$NK_OFF_DIR[{CORR_CA},2]\n");
    let direct =
        run(&format!("{}R1=CORRTRAFO(1, 0, VEC)\n{read}G1 F3000 X0 Y0 Z50 A30 C40\nM30", start([0.3, 0.0, 0.0])));
    assert_eq!(direct.status, Status::Idle, "{:?}", direct.alarms);
    assert!(near(&[r(&direct, 10), r(&direct, 11), r(&direct, 12)], &[0.3, 0.0, 0.0], 1e-12));
    let want = expected([0.0, 0.0, 50.0], 30.0, 40.0, [0.0, 0.3, 0.0], 0.0);
    assert!(near(&machine(&direct), &want, 1e-6), "{:?} vs {want:?}", machine(&direct));
    let world =
        run(&format!("{}R1=CORRTRAFO(1, 10, VEC)\n{read}G1 F3000 X0 Y0 Z50 A30 C40\nM30", start([0.3, 0.0, 0.0])));
    assert_eq!(world.status, Status::Idle, "{:?}", world.alarms);
    assert!(near(&[r(&world, 10), r(&world, 11), r(&world, 12)], &[0.0, -0.3, 0.0], 1e-12));
    let want = expected([0.0, 0.0, 50.0], 30.0, 40.0, [0.3, 0.0, 0.0], 0.0);
    assert!(near(&machine(&world), &want, 1e-6), "{:?} vs {want:?}", machine(&world));
}

#[test]
fn incremental_corrections_add_to_the_element() {
    // Two incremental direct corrections of Corr tool by (0, 0, −0.1): −0.2 in all.
    let s = run(&format!(
        "{}R1=CORRTRAFO(2, 100, VEC)\nR2=CORRTRAFO(2, 100, VEC)\nR3=$NK_OFF_DIR[{CORR_TOOL},2]\nM30",
        start([0.0, 0.0, -0.1])
    ));
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert_eq!((r(&s, 1), r(&s, 2)), (0.0, 0.0));
    assert!((r(&s, 3) + 0.2).abs() < 1e-12, "{}", r(&s, 3));
}

#[test]
fn a_direction_correction_tilts_the_axis() {
    // A's direction becomes u = (1, 0.01, 0)/|…| (0.573° off X, inside SD41611's 1°). With C = 0
    // the tool turns about u by A: o = R(u, A)·(0, 0, 1), P = M + (0, 0, 150) − 250·o.
    let s = run(&format!("{}CORRTRAFO(1, 1, VEC)\nG1 F3000 X0 Y0 Z50 A30 C0\nM30", start([1.0, 0.01, 0.0])));
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    let n = (1.0f64 + 0.0001).sqrt();
    let u = [1.0 / n, 0.01 / n, 0.0];
    let (sa, ca) = 30f64.to_radians().sin_cos();
    // Rodrigues on (0, 0, 1): v·c + (u × v)·s + u·(u·v)(1 − c), u·v = 0, u × v = (u_y, −u_x, 0).
    let o = [u[1] * sa, -u[0] * sa, ca];
    let want = [250.0 * o[0], 250.0 * o[1], 50.0 - 150.0 + 250.0 * o[2], 30.0, 0.0];
    assert!(near(&machine(&s), &want, 1e-6), "{:?} vs {want:?}", machine(&s));
}

#[test]
fn the_status_codes_and_alarm_14103() {
    let v = start([0.0, 0.0, 5.0]);
    let status = |program: &str| -> f64 {
        let s = run(program);
        assert_eq!(s.status, Status::Idle, "{program}: {:?}", s.alarms);
        r(&s, 1)
    };
    // 1: no transformation active.
    assert_eq!(status("DEF REAL VEC[3]\nR1=CORRTRAFO(2, 0, VEC, , TRUE)\nM30"), 1.0);
    // 2: TRANSMIT is no orientation transformation.
    let mut lathe = Channel::from_preset("transmit-example", "").unwrap();
    let s = run_on(&mut lathe, "DEF REAL VEC[3]\nTRANSMIT\nR1=CORRTRAFO(0, 0, VEC, , TRUE)\nM30");
    assert_eq!((s.status, r(&s, 1)), (Status::Idle, 2.0), "{:?}", s.alarms);
    // 3: the machine data's TRAORI (the preset's data set 1) is not defined by chains.
    assert_eq!(status("DEF REAL VEC[3]\nT1 D1\nTRAORI\nR1=CORRTRAFO(2, 0, VEC, , TRUE)\nM30"), 3.0);
    // 4: tens digit 3, or a section of a direction.
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(2, 30, VEC, , TRUE)\nM30")), 4.0);
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(1, 21, VEC, , TRUE)\nM30")), 4.0);
    // 5: no correction element at position 3, no chain 2, no orientation axis 2.
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(3, 0, VEC, , TRUE)\nM30")), 5.0);
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(2, 0, VEC, 2, TRUE)\nM30")), 5.0);
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(2, 1, VEC, , TRUE)\nM30")), 5.0);
    // 41: a change of 5 mm exceeds SD41610's 1 mm; suppressed (thousands digit 1) it is done,
    // and with the setting datum raised to 10 mm too.
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(2, 0, VEC, , TRUE)\nM30")), 41.0);
    assert_eq!(status(&format!("{v}R1=CORRTRAFO(2, 1000, VEC, , TRUE)\nM30")), 0.0);
    assert_eq!(status(&format!("{v}$SN_CORR_TRAFO_LIN_MAX=10\nR1=CORRTRAFO(2, 0, VEC, , TRUE)\nM30")), 0.0);
    // 42: A's direction turned by atan(0.05) = 2.86° > SD41611's 1°.
    let tilt = start([1.0, 0.05, 0.0]);
    assert_eq!(status(&format!("{tilt}R1=CORRTRAFO(1, 1, VEC, , TRUE)\nM30")), 42.0);
    assert_eq!(status(&format!("{tilt}R1=CORRTRAFO(1, 1001, VEC, , TRUE)\nM30")), 0.0);
    // In a condition, as a statement's value.
    assert_eq!(status(&format!("{v}IF CORRTRAFO(2, 0, VEC, , TRUE)==41\nR1=99\nENDIF\nM30")), 99.0);
    // No_Alarm FALSE (omitted): alarm 14103 in the block's line, and the data stays.
    let s = run(&format!("{v}R1=CORRTRAFO(2, 0, VEC)\nM30"));
    let alarm = s.alarms.iter().find(|a| a.number == 14103).unwrap_or_else(|| panic!("{:?}", s.alarms));
    assert_eq!(alarm.line, Some(8), "{alarm:?}");
    let s = run(&format!("{v}CORRTRAFO(2, 0, VEC)\nM30"));
    assert!(s.alarms.iter().any(|a| a.number == 14103), "{:?}", s.alarms);
}

#[test]
fn the_section_must_hold_its_correction_element() {
    // Corr tool listed at position 0 lies in section 2: the whole-section mode refuses (6);
    // the direct mode writes it.
    let mut ch = channel("$NT_CORR_ELEM_T[1,0]=\"Corr tool\"\n");
    let s = run_on(&mut ch, &format!("{}R1=CORRTRAFO(0, 20, VEC, , TRUE)\nM30", start([0.0, 0.0, -0.5])));
    assert_eq!(r(&s, 1), 6.0, "{:?}", s.alarms);
    let s = run_on(&mut ch, &format!("{}R1=CORRTRAFO(0, 0, VEC, , TRUE)\nM30", start([0.0, 0.0, -0.5])));
    assert_eq!(r(&s, 1), 0.0, "{:?}", s.alarms);
}

#[test]
fn nt_rot_ax_cnt_counts_the_rotary_axes_of_each_subchain() {
    // Workpiece chain: none (0); tool chain: C and A (2); record 2 is empty (0); the same
    // while the head is active.
    let s = run("R1=$NT_ROT_AX_CNT[1,0]\nR2=$NT_ROT_AX_CNT[1,1]\nR3=$NT_ROT_AX_CNT[2,1]\n\
                 TRAFOON(\"Head\")\nR4=$NT_ROT_AX_CNT[1,1]\nM30");
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert_eq!((r(&s, 1), r(&s, 2), r(&s, 3), r(&s, 4)), (0.0, 2.0, 0.0, 2.0));
    let s = run("$NT_ROT_AX_CNT[1,1]=3\nM30");
    assert_eq!(s.status, Status::Alarm, "read only");
}

#[test]
fn delobj_works_as_a_function_in_expressions() {
    // 0 when it deletes, −1 for an unknown object type (no alarm in the function form).
    let s = run("R1=DELOBJ(\"NOPE\")\nIF (DELOBJ(\"TRAFO_DATA\") < 0) GOTOF FAIL\nR2=1\nNEWCONF\n\
                 TRAFOON(\"Head\")\nM30\nFAIL: R2=-1\nM30");
    assert_eq!(r(&s, 1), -1.0);
    assert_eq!(r(&s, 2), 1.0);
    // The records are gone after NEWCONF: the selection raises 14401.
    assert_eq!(s.alarms.iter().map(|a| a.number).collect::<Vec<_>>(), [14401], "{:?}", s.alarms);
    let s = run("R1=DELOBJ(\"TOOLCARRIER\", 5, 2) + 10\nM30");
    assert_eq!((s.status, r(&s, 1)), (Status::Idle, 8.0), "{:?}", s.alarms);
}

#[test]
fn tracon_k_is_refused_with_the_reason() {
    let tracon = "$NT_NAME[2]=\"Chain\"\n$NT_TRAFO_TYPE[2]=\"TRACON_K\"\n\
                  $NT_TRACON_CHAIN[2,0]=\"OA\"\n$NT_TRACON_CHAIN[2,1]=\"Head\"\n";
    let mut ch = channel(tracon);
    let s = run_on(&mut ch, "TRAFOON(\"Chain\")\nM30");
    let alarm = s.alarms.iter().find(|a| a.number == 14401).unwrap_or_else(|| panic!("{:?}", s.alarms));
    assert!(alarm.message.contains("Open Architecture"), "{}", alarm.message);
    // The member names are stored and go out with the chain data.
    assert!(ch.export_kinematic_chains().contains("$NT_TRACON_CHAIN[2,1]=\"Head\"\n"));
}

#[test]
fn the_workpiece_chain_is_corrected_with_corr_chain_1() {
    // A workpiece chain beside the head: ROOT ∥ WP base (5, 0, 0) → Corr WP. It has no rotary
    // axis, so its only section 0 is the whole chain: absolute section (5.3, 0, 0) leaves
    // Corr WP = (0.3, 0, 0), and the workpiece reference (the BCS origin) moves to (5.3, 0, 0):
    // the tip programmed at (0, 0, 50) is at (5.3, 0, 50) in the world.
    let wp = "$NK_PARALLEL[0]=\"WP base\"\n$NK_NAME[12]=\"WP base\"\n$NK_TYPE[12]=\"OFFSET\"\n\
              $NK_NEXT[12]=\"Corr WP\"\n$NK_OFF_DIR[12,0]=5\n$NK_NAME[13]=\"Corr WP\"\n$NK_TYPE[13]=\"OFFSET\"\n\
              $NT_P_CHAIN_LAST_ELEM[1]=\"Corr WP\"\n$NT_CORR_ELEM_P[1,0]=\"Corr WP\"\n";
    let mut ch = channel(wp);
    let program = format!(
        "{}R1=CORRTRAFO(0, 20, VEC, 1)\nR2=$NK_OFF_DIR[13,0]\nG1 F3000 X0 Y0 Z50 A30 C40\nM30",
        start([5.3, 0.0, 0.0])
    );
    let s = run_on(&mut ch, &program);
    assert_eq!(s.status, Status::Idle, "{:?}", s.alarms);
    assert_eq!(r(&s, 1), 0.0);
    assert!((r(&s, 2) - 0.3).abs() < 1e-9, "{}", r(&s, 2));
    let want = expected([5.3, 0.0, 50.0], 30.0, 40.0, [0.0; 3], 0.0);
    assert!(near(&machine(&s), &want, 1e-6), "{:?} vs {want:?}", machine(&s));
    // The same element is no tool-chain correction element: Corr_Chain 0 finds nothing at 0.
    let s = run_on(&mut ch, &format!("{}R1=CORRTRAFO(0, 20, VEC, 0, TRUE)\nM30", start([5.3, 0.0, 0.0])));
    assert_eq!(r(&s, 1), 5.0, "{:?}", s.alarms);
}
