//! Built-in machines, each written as NC data text and applied like any user's text, so a
//! preset can never hold what the text format cannot express.

/// A built-in machine.
#[derive(Debug, Clone, Copy)]
pub struct Preset {
    pub id: &'static str,
    pub name: &'static str,
    pub description: &'static str,
    /// NC data text applied on top of the defaults.
    pub text: &'static str,
}

/// Every preset; the first is the default.
pub static PRESETS: &[Preset] = &[
    Preset {
        id: "mill-3axis",
        name: "3-axis vertical mill",
        description: "Linear axes X, Y, Z (no transformation), 30 m/min rapid, 3 m/s²; tools T1 (end mill R5), T2 (drill R4).",
        text: MILL_3AXIS,
    },
    Preset {
        id: "lathe-2axis",
        name: "2-axis lathe",
        description: "Geometry axes X (radius programming) and Z, main spindle SP (spindle 1); turning tools T1, T2.",
        text: LATHE_2AXIS,
    },
    Preset {
        id: "lathe-counter-spindle",
        name: "Lathe with counter spindle",
        description: "Geometry axes X (diameter programming) and Z on the turret, main spindle SP1 (spindle 1, master), counter spindle SP2 (spindle 2) on its own slide Z2 (program Z2=..); SETMS(2) makes the counter spindle the master for S, G95 and G96; turning tools T1, T2.",
        text: LATHE_COUNTER_SPINDLE,
    },
    Preset {
        id: "transmit-example",
        name: "Lathe with driven tools (TRANSMIT example axis configuration)",
        description: "The axis configuration of the Transformations Function Manual's TRANSMIT example: XM, CM (spindle 1 / C axis), ZM, ASM (driven tool spindle 2); TRANSMIT data set 1 (type 256).",
        text: TRANSMIT_EXAMPLE,
    },
    Preset {
        id: "slant-lathe-tracon",
        name: "Slant-bed lathe with driven tools (persistent TRAANG, chained TRANSMIT)",
        description: "X slide MU inclined by 30° towards Z, MZ, main spindle C (spindle 1), driven tools ASC; TRAANG (data set 2) always active as persistent transformation, TRANSMIT (data set 1) chained in front of it by TRACON (data set 3).",
        text: SLANT_LATHE_TRACON,
    },
    Preset {
        id: "tracyl-xyzc",
        name: "Lathe with Y axis (TRACYL X-Y-Z-C example)",
        description: "The Transformations Function Manual's TRACYL example machine: XM, YM, ZM, CM (spindle 1 / C axis); TRACYL data set 1 of type 513 (groove-wall offset with the real Y axis).",
        text: TRACYL_XYZC,
    },
    Preset {
        id: "tracyl-xyzac",
        name: "5-axis mill with trunnion table A/C (TRACYL X-Y-Z-A-C example)",
        description: "Milling machine XM, YM, ZM with tool spindle SPM and a trunnion table: A about X carries the rotary table C. With A at −90° the C axis lies along +Y and grooves are milled on the periphery of a cylinder clamped on C: TRACYL data set 1 of type 513 (radial axis ZM, rotary axis CM, axial axis YM, groove-wall offset by XM).",
        text: TRACYL_XYZAC,
    },
    Preset {
        id: "traang-grinder",
        name: "Grinding machine with inclined infeed axis (TRAANG example)",
        description: "Inclined infeed axis MU at 45° and longitudinal axis MZ, work spindle C; TRAANG data set 1 (type 1024) with 20 % velocity and acceleration reserve on the parallel axis.",
        text: TRAANG_GRINDER,
    },
    Preset {
        id: "mill5-head-ca",
        name: "5-axis mill with swivel head C/A (TRAORI type 20)",
        description: "Linear axes X, Y, Z (40 m/min, 4 m/s²); fork head with C about Z (modulo) carrying A about X (−110..+110°), 14400°/min; A pivot 150 mm above the spindle nose; TRAORI data set 1 (type 20, tool side) and swivel data set 1 \"HEAD_CA\" (toolholder type T, CYCLE800); tool T1 (end mill L100 R5).",
        text: MILL5_HEAD_CA,
    },
    Preset {
        id: "mill5-table-ac",
        name: "5-axis mill with trunnion table A/C (TRAORI type 33)",
        description: "Linear axes X, Y, Z (50 m/min, 5 m/s²); trunnion A about X (−120..+120°, 10800°/min) carrying the rotary table C about Z (modulo, 18000°/min); TRAORI data set 1 (type 33, workpiece side, DIN-reversed axes) and swivel data set 1 \"TABLE_AC\" (toolholder type P, CYCLE800); tool T1 (end mill L100 R5).",
        text: MILL5_TABLE_AC,
    },
    Preset {
        id: "mill5-mixed-bc",
        name: "5-axis mill with swivel head B and rotary table C (TRAORI type 51)",
        description: "Linear axes X, Y, Z (30 m/min, 3 m/s²); head B about Y (−100..+100°, 10800°/min), pivot 120 mm above the spindle nose; rotary table C about Z (modulo, 18000°/min); TRAORI data set 1 (type 51, mixed) and swivel data set 1 \"MIXED_BC\" (toolholder type M, CYCLE800); tool T1 (end mill L100 R5).",
        text: MILL5_MIXED_BC,
    },
    Preset {
        id: "mill6-generic",
        name: "6-axis mill with a three-axis head C/B/A (generic TRAORI type 24)",
        description: "Linear axes X, Y, Z (40 m/min, 4 m/s²); head with C about Z (modulo, 14400°/min) carrying B about Y (−100..+100°, 10800°/min) carrying A, which turns the tool about its own axis (−200..+200°, 18000°/min); B pivot 200 mm above the spindle nose; generic 6-axis TRAORI data set 1 (type 24, tool normal +X for THETA); tool T1 (end mill L100 R5).",
        text: MILL6_GENERIC,
    },
    Preset {
        id: "mill7-generic",
        name: "7-axis mill: three-axis head C/B/A and rotary table C1 (generic TRAORI type 24 + 7th axis)",
        description: "The 6-axis head of mill6-generic (X, Y, Z 40 m/min, 4 m/s²; C about Z, B about Y, A turning the tool) plus a rotary table C1 about Z through the BCS zero point (modulo, 10800°/min, 1.5 rev/s²) as 7th axis: programmed positions and orientations are relative to the workpiece on C1 (program C1=…); generic 7-axis TRAORI data set 1 (type 24, TRAFO_AXES_IN_1[6] = C1, TRAFO7_EXT_AXIS1_1 = +Z); tool T1 (end mill L100 R5).",
        text: MILL7_GENERIC,
    },
];

/// Looks a preset up by id.
pub fn find(id: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.id == id)
}

/// The tool spindle S1 of the mills (a spindle without axis function, machine axis SP1): its
/// machine data, shared by every mill preset; each preset names the machine axis itself.
macro_rules! tool_spindle_sp1 {
    () => {
        r#"$MA_IS_ROT_AX[SP1]=TRUE
$MA_ROT_IS_MODULO[SP1]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[SP1]=1
; 12000 rev/min, 50 rev/s² (3000 rev/min per second) in speed control; position control
; (SPOS, M19, G331) at up to 1000 rev/min (MD35300), 100 rev/s² as an axis.
$MA_SPIND_VELO_LIMIT[SP1]=12000.
$MA_GEAR_STEP_MAX_VELO_LIMIT[1,SP1]=12000.
$MA_GEAR_STEP_SPEEDCTRL_ACCEL[1,SP1]=50.
$MA_SPIND_POSCTRL_VELO[SP1]=1000.
$MA_MAX_AX_VELO[SP1]=12000.
$MA_MAX_AX_ACCEL[SP1]=100.
"#
    };
}

/// The chain magazine (magazine 1, 12 places) and the spindle's buffer place (magazine 9998)
/// every preset's tool management starts from; each preset loads its own tools.
macro_rules! chain_magazine {
    () => {
        r#"$TC_MAP1[1]=1
$TC_MAP2[1]="CHAIN"
$TC_MAP7[1]=12
$TC_MAP1[9998]=7
$TC_MPP1[9998,1]=2
"#
    };
}

const MILL_3AXIS: &str = concat!(
    r#"; 3-axis vertical milling machine
$MN_AXCONF_MACHAX_NAME_TAB[0]="X"
$MN_AXCONF_MACHAX_NAME_TAB[1]="Y"
$MN_AXCONF_MACHAX_NAME_TAB[2]="Z"
$MN_AXCONF_MACHAX_NAME_TAB[3]="SP1"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="X"
$MC_AXCONF_CHANAX_NAME_TAB[1]="Y"
$MC_AXCONF_CHANAX_NAME_TAB[2]="Z"
; The tool spindle S1: a spindle without axis function (no channel axis name), so the
; positions show X, Y, Z only and the spindle appears under the state's spindles as S1.
$MC_AXCONF_CHANAX_NAME_TAB[3]=""
$MC_SPIND_DEF_MASTER_SPIND=1
"#,
    tool_spindle_sp1!(),
    r#"$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MA_MAX_AX_VELO[X]=30000.
$MA_MAX_AX_VELO[Y]=30000.
$MA_MAX_AX_VELO[Z]=30000.
$MA_MAX_AX_ACCEL[X]=3.
$MA_MAX_AX_ACCEL[Y]=3.
$MA_MAX_AX_ACCEL[Z]=3.
$MA_POS_LIMIT_MINUS[X]=-500.
$MA_POS_LIMIT_PLUS[X]=500.
$MA_POS_LIMIT_MINUS[Y]=-300.
$MA_POS_LIMIT_PLUS[Y]=300.
$MA_POS_LIMIT_MINUS[Z]=-400.
$MA_POS_LIMIT_PLUS[Z]=300.
; T1 D1: end mill, length 100, radius 5
$TC_DP1[1,1]=120
$TC_DP3[1,1]=100.
$TC_DP6[1,1]=5.
; T2 D1: twist drill, length 120, radius 4
$TC_DP1[2,1]=200
$TC_DP3[2,1]=120.
$TC_DP6[2,1]=4.
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
$MC_TOOL_CHANGE_TIME=2.
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D10"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
$TC_TP1[2]=1
$TC_TP2[2]="DRILL_8"
$TC_TP8[2]=2
$TC_MPP6[1,2]=2
"#
);

/// The 2-axis lathe's data, a macro so that the counter-spindle lathe can be written as this
/// machine plus its differences (`concat!` takes literals and macros only).
macro_rules! lathe_2axis {
    () => {
        concat!(
            r#"; 2-axis lathe: X radial, Z along the spindle, main spindle as channel axis SP
$MN_AXCONF_MACHAX_NAME_TAB[0]="X1"
$MN_AXCONF_MACHAX_NAME_TAB[1]="Z1"
$MN_AXCONF_MACHAX_NAME_TAB[2]="SP1"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="X"
$MC_AXCONF_CHANAX_NAME_TAB[1]="Z"
$MC_AXCONF_CHANAX_NAME_TAB[2]="SP"
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=2
$MA_IS_ROT_AX[SP1]=TRUE
$MA_ROT_IS_MODULO[SP1]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[SP1]=1
$MA_MAX_AX_VELO[SP1]=1440000.
; X is the transverse axis (diameter programming, constant cutting speed).
$MC_DIAMETER_AX_DEF="X"
; X may also be diameter-programmed on its own (DIAMONA[X], MD30460 bit 2).
$MA_BASE_FUNCTION_MASK[X1]=4
; A lathe starts in G18 (MD20150[5]); radius programming (MD20150[28] = 1, DIAMOF) as the
; preset has always been; `$MC_GCODE_RESET_VALUES[28]=2` makes DIAMON the reset value.
$MC_GCODE_RESET_VALUES[5]=2
$MA_MAX_AX_ACCEL[SP1]=30.
; Main spindle: 4000 rev/min, 30 rev/s² in speed control.
$MA_SPIND_VELO_LIMIT[SP1]=4000.
$MA_GEAR_STEP_MAX_VELO_LIMIT[1,SP1]=4000.
$MA_GEAR_STEP_SPEEDCTRL_ACCEL[1,SP1]=30.
$MA_MAX_AX_VELO[X1]=20000.
$MA_MAX_AX_VELO[Z1]=24000.
$MA_MAX_AX_ACCEL[X1]=4.
$MA_MAX_AX_ACCEL[Z1]=4.
$MA_POS_LIMIT_MINUS[X1]=-20.
$MA_POS_LIMIT_PLUS[X1]=250.
$MA_POS_LIMIT_MINUS[Z1]=-300.
$MA_POS_LIMIT_PLUS[Z1]=400.
; T1 D1: roughing tool, cutting edge position 3, nose radius 0.8
$TC_DP1[1,1]=500
$TC_DP2[1,1]=3
$TC_DP3[1,1]=40.
$TC_DP4[1,1]=60.
$TC_DP6[1,1]=0.8
; T2 D1: finishing tool, nose radius 0.4
$TC_DP1[2,1]=510
$TC_DP2[2,1]=3
$TC_DP3[2,1]=42.
$TC_DP4[2,1]=58.
$TC_DP6[2,1]=0.4
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
            chain_magazine!(),
            r#"$TC_TP1[1]=1
$TC_TP2[1]="ROUGH_R0_8"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
$TC_TP1[2]=1
$TC_TP2[2]="FINISH_R0_4"
$TC_TP8[2]=2
$TC_MPP6[1,2]=2
"#
        )
    };
}

const LATHE_2AXIS: &str = lathe_2axis!();

/// A lathe with a counter spindle: the turret (X, Z) works on the main spindle SP1 or, after
/// SETMS(2), on the counter spindle SP2, which faces the main spindle on its own slide Z2
/// (machine travel −600..0; 0 is its stop nearest the main spindle). Spindle transfer with
/// coupled spindles (COUPON) is not modelled: the slide and both spindles are programmed on
/// their own.
///
/// Written as the 2-axis lathe plus its differences: data text applies line by line, so a
/// later line replaces an earlier value, as on the control.
const LATHE_COUNTER_SPINDLE: &str = concat!(
    lathe_2axis!(),
    r#"; Lathe with counter spindle: the 2-axis lathe above, plus the counter spindle SP2
; (spindle 2) on its slide Z2; the main spindle's channel axis is SP1.
$MN_AXCONF_MACHAX_NAME_TAB[3]="Z2"
$MN_AXCONF_MACHAX_NAME_TAB[4]="SP2"
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=5
$MC_AXCONF_MACHAX_USED[5]=0
$MC_AXCONF_CHANAX_NAME_TAB[2]="SP1"
$MC_AXCONF_CHANAX_NAME_TAB[3]="Z2"
$MC_AXCONF_CHANAX_NAME_TAB[4]="SP2"
; Spindle 1 is the master spindle after reset (MD20090); SETMS(2) selects the counter spindle.
$MC_SPIND_DEF_MASTER_SPIND=1
; The counter spindle: smaller, faster.
$MA_IS_ROT_AX[SP2]=TRUE
$MA_ROT_IS_MODULO[SP2]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[SP2]=2
$MA_MAX_AX_VELO[SP2]=1800000.
$MA_MAX_AX_ACCEL[SP2]=40.
$MA_SPIND_VELO_LIMIT[SP2]=5000.
$MA_GEAR_STEP_MAX_VELO_LIMIT[1,SP2]=5000.
$MA_GEAR_STEP_SPEEDCTRL_ACCEL[1,SP2]=40.
; Diameter programming (DIAMON) at reset.
$MC_GCODE_RESET_VALUES[28]=2
$MA_MAX_AX_VELO[Z2]=20000.
$MA_MAX_AX_ACCEL[Z2]=3.
$MA_POS_LIMIT_MINUS[Z2]=-600.
$MA_POS_LIMIT_PLUS[Z2]=0.
; T2 D1 replaces the finishing tool: a roughing tool for the counter spindle (cutting edge
; position 4: it cuts towards +Z)
$TC_DP1[2,1]=500
$TC_DP2[2,1]=4
$TC_DP3[2,1]=40.
$TC_DP4[2,1]=-60.
$TC_DP6[2,1]=0.8
$TC_TP2[1]="ROUGH_MAIN"
$TC_TP2[2]="ROUGH_COUNTER"
"#
);

const TRANSMIT_EXAMPLE: &str = concat!(
    r#"; Axis configuration of the TRANSMIT example (Transformations Function Manual, M1)
$MN_AXCONF_MACHAX_NAME_TAB[0]="XM"
$MN_AXCONF_MACHAX_NAME_TAB[1]="CM"
$MN_AXCONF_MACHAX_NAME_TAB[2]="ZM"
$MN_AXCONF_MACHAX_NAME_TAB[3]="ASM"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="XC"
$MC_AXCONF_CHANAX_NAME_TAB[1]="C"
$MC_AXCONF_CHANAX_NAME_TAB[2]="ZC"
$MC_AXCONF_CHANAX_NAME_TAB[3]="ASC"
$MC_AXCONF_GEOAX_NAME_TAB[0]="X"
$MC_AXCONF_GEOAX_NAME_TAB[1]="Y"
$MC_AXCONF_GEOAX_NAME_TAB[2]="Z"
; without transformation: X and Z only (TRANSMIT will map Y onto channel axis 2)
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MA_IS_ROT_AX[CM]=TRUE
$MA_ROT_IS_MODULO[CM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[CM]=1
; X is the transverse axis (diameter programming, constant cutting speed); G18 at reset.
$MC_DIAMETER_AX_DEF="X"
$MC_GCODE_RESET_VALUES[5]=2
$MA_IS_ROT_AX[ASM]=TRUE
$MA_ROT_IS_MODULO[ASM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[ASM]=2
$MA_MAX_AX_VELO[XM]=15000.
$MA_MAX_AX_VELO[ZM]=15000.
$MA_MAX_AX_VELO[CM]=100.
$MA_MAX_AX_VELO[ASM]=6000.
$MA_POS_LIMIT_MINUS[XM]=-50.
$MA_POS_LIMIT_PLUS[XM]=200.
$MA_POS_LIMIT_MINUS[ZM]=-200.
$MA_POS_LIMIT_PLUS[ZM]=300.
; T1 D1: end mill on the driven tool spindle, length 30 (along Z in G17), radius 4
$TC_DP1[1,1]=120
$TC_DP3[1,1]=30.
$TC_DP6[1,1]=4.
; TRANSMIT data set 1 (Transformations FM, M1 TRANSMIT example)
$MC_TRAFO_TYPE_1=256
$MC_TRAFO_AXES_IN_1[0]=1      ; XC: linear axis perpendicular to the rotary axis
$MC_TRAFO_AXES_IN_1[1]=2      ; C: rotary axis
$MC_TRAFO_AXES_IN_1[2]=3      ; ZC: linear axis parallel to the rotary axis
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1   ; X
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2   ; Y on the rotary axis' channel slot
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3   ; Z
$MC_TRANSMIT_ROT_AX_OFFSET_1=0
$MC_TRANSMIT_ROT_SIGN_IS_PLUS_1=TRUE
$MC_TRANSMIT_BASE_TOOL_1[0]=0
$MC_TRANSMIT_BASE_TOOL_1[1]=0
$MC_TRANSMIT_BASE_TOOL_1[2]=0
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D8"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const SLANT_LATHE_TRACON: &str = concat!(
    r#"; Slant-bed lathe with driven tools: the X slide MU is inclined by 30° towards Z, so a
; TRAANG data set is always active (persistent); TRANSMIT is chained in front of it (TRACON).
$MN_AXCONF_MACHAX_NAME_TAB[0]="MU"
$MN_AXCONF_MACHAX_NAME_TAB[1]="CM"
$MN_AXCONF_MACHAX_NAME_TAB[2]="MZ"
$MN_AXCONF_MACHAX_NAME_TAB[3]="ASM"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="MU"
$MC_AXCONF_CHANAX_NAME_TAB[1]="C"
$MC_AXCONF_CHANAX_NAME_TAB[2]="MZ"
$MC_AXCONF_CHANAX_NAME_TAB[3]="ASC"
$MC_AXCONF_GEOAX_NAME_TAB[0]="X"
$MC_AXCONF_GEOAX_NAME_TAB[1]="Y"
$MC_AXCONF_GEOAX_NAME_TAB[2]="Z"
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MA_IS_ROT_AX[CM]=TRUE
$MA_ROT_IS_MODULO[CM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[CM]=1
; X is the transverse axis (diameter programming, constant cutting speed); G18 at reset.
$MC_DIAMETER_AX_DEF="X"
$MC_GCODE_RESET_VALUES[5]=2
$MA_IS_ROT_AX[ASM]=TRUE
$MA_ROT_IS_MODULO[ASM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[ASM]=2
$MA_MAX_AX_VELO[MU]=15000.
$MA_MAX_AX_VELO[MZ]=15000.
$MA_MAX_AX_VELO[CM]=100.
$MA_MAX_AX_VELO[ASM]=6000.
$MA_POS_LIMIT_MINUS[MU]=-50.
$MA_POS_LIMIT_PLUS[MU]=250.
$MA_POS_LIMIT_MINUS[MZ]=-300.
$MA_POS_LIMIT_PLUS[MZ]=300.
; T1 D1: end mill on the driven tool spindle, length 30, radius 4
$TC_DP1[1,1]=120
$TC_DP3[1,1]=30.
$TC_DP6[1,1]=4.
; data set 1: TRANSMIT (the first member of the chain)
$MC_TRAFO_TYPE_1=256
$MC_TRAFO_AXES_IN_1[0]=1
$MC_TRAFO_AXES_IN_1[1]=2
$MC_TRAFO_AXES_IN_1[2]=3
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3
$MC_TRANSMIT_ROT_SIGN_IS_PLUS_1=TRUE
; data set 2: TRAANG for the inclined slide (persistent)
$MC_TRAFO_TYPE_2=1024
$MC_TRAFO_AXES_IN_2[0]=1      ; MU: inclined axis
$MC_TRAFO_AXES_IN_2[1]=3      ; MZ: axis parallel to Z
$MC_TRAFO_AXES_IN_2[2]=0
$MC_TRAFO_GEOAX_ASSIGN_TAB_2[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_2[1]=0
$MC_TRAFO_GEOAX_ASSIGN_TAB_2[2]=3
$MC_TRAANG_ANGLE_1=30.
$MC_TRAANG_PARALLEL_VELO_RES_1=0.1
$MC_TRAANG_PARALLEL_ACCEL_RES_1=0.1
; data set 3: the chain TRANSMIT → TRAANG
$MC_TRAFO_TYPE_3=8192
$MC_TRACON_CHAIN_1[0]=1
$MC_TRACON_CHAIN_1[1]=2
; the persistent transformation and the reset mode it needs
$MC_TRAFO_MODE_MASK=1
$MC_TRAFO_RESET_VALUE=2
$MC_RESET_MODE_MASK=1
$MC_GEOAX_CHANGE_RESET=TRUE
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D8"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const TRACYL_XYZC: &str = concat!(
    r#"; TRACYL example machine X-Y-Z-C (Transformations FM, M1 TRACYL examples)
$MN_AXCONF_MACHAX_NAME_TAB[0]="XM"
$MN_AXCONF_MACHAX_NAME_TAB[1]="YM"
$MN_AXCONF_MACHAX_NAME_TAB[2]="ZM"
$MN_AXCONF_MACHAX_NAME_TAB[3]="CM"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="XC"
$MC_AXCONF_CHANAX_NAME_TAB[1]="YC"
$MC_AXCONF_CHANAX_NAME_TAB[2]="ZC"
$MC_AXCONF_CHANAX_NAME_TAB[3]="CC"
$MC_AXCONF_GEOAX_NAME_TAB[0]="X"
$MC_AXCONF_GEOAX_NAME_TAB[1]="Y"
$MC_AXCONF_GEOAX_NAME_TAB[2]="Z"
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MA_IS_ROT_AX[CM]=TRUE
$MA_ROT_IS_MODULO[CM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[CM]=1
; X is the transverse axis, as on any lathe: DIAMON programs it in diameters (the reset
; value stays DIAMOF), G96 keeps the cutting speed on it
$MC_DIAMETER_AX_DEF="X"
$MA_MAX_AX_VELO[XM]=15000.
$MA_MAX_AX_VELO[YM]=10000.
$MA_MAX_AX_VELO[ZM]=15000.
$MA_MAX_AX_VELO[CM]=100.
$MA_POS_LIMIT_MINUS[XM]=-50.
$MA_POS_LIMIT_PLUS[XM]=200.
$MA_POS_LIMIT_MINUS[YM]=-60.
$MA_POS_LIMIT_PLUS[YM]=60.
$MA_POS_LIMIT_MINUS[ZM]=-200.
$MA_POS_LIMIT_PLUS[ZM]=300.
; T1 D1: slot cutter (milling tool), length 9 along the radial axis in G19, radius 6
$TC_DP1[1,1]=120
$TC_DP3[1,1]=9.
$TC_DP6[1,1]=6.
; TRACYL data set 1: type 513, with groove-wall offset by the real Y axis
$MC_TRAFO_TYPE_1=513
$MC_TRAFO_AXES_IN_1[0]=1      ; XC: radial to the rotary axis
$MC_TRAFO_AXES_IN_1[1]=4      ; CC: rotary axis
$MC_TRAFO_AXES_IN_1[2]=3      ; ZC: parallel to the rotary axis
$MC_TRAFO_AXES_IN_1[3]=2      ; YC: real Y axis for the groove-wall offset
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1   ; X
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=4   ; Y: unrolled surface, on the rotary axis' channel slot
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3   ; Z
$MC_TRACYL_ROT_AX_OFFSET_1=0
$MC_TRACYL_ROT_SIGN_IS_PLUS_1=TRUE
$MC_TRACYL_BASE_TOOL_1[0]=0
$MC_TRACYL_BASE_TOOL_1[1]=0
$MC_TRACYL_BASE_TOOL_1[2]=0
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D12"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const TRACYL_XYZAC: &str = concat!(
    r#"; TRACYL on an X-Y-Z-A-C milling machine (Transformations FM, M1 TRACYL examples): the
; trunnion A (about X) carries the rotary table C. The TRACYL data assume A = -90°, which turns
; the C axis onto +Y: the vertical tool then stands radial to the cylinder clamped on C.
$MN_AXCONF_MACHAX_NAME_TAB[0]="XM"
$MN_AXCONF_MACHAX_NAME_TAB[1]="YM"
$MN_AXCONF_MACHAX_NAME_TAB[2]="ZM"
$MN_AXCONF_MACHAX_NAME_TAB[3]="SPM"
$MN_AXCONF_MACHAX_NAME_TAB[4]="AM"
$MN_AXCONF_MACHAX_NAME_TAB[5]="CM"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=5
$MC_AXCONF_MACHAX_USED[5]=6
$MC_AXCONF_MACHAX_USED[6]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="XC"
$MC_AXCONF_CHANAX_NAME_TAB[1]="YC"
$MC_AXCONF_CHANAX_NAME_TAB[2]="ZC"
$MC_AXCONF_CHANAX_NAME_TAB[3]="SP"
$MC_AXCONF_CHANAX_NAME_TAB[4]="A"
$MC_AXCONF_CHANAX_NAME_TAB[5]="C"
$MC_AXCONF_GEOAX_NAME_TAB[0]="X"
$MC_AXCONF_GEOAX_NAME_TAB[1]="Y"
$MC_AXCONF_GEOAX_NAME_TAB[2]="Z"
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MA_MAX_AX_VELO[XM]=30000.
$MA_MAX_AX_VELO[YM]=30000.
$MA_MAX_AX_VELO[ZM]=30000.
$MA_MAX_AX_ACCEL[XM]=3.
$MA_MAX_AX_ACCEL[YM]=3.
$MA_MAX_AX_ACCEL[ZM]=3.
$MA_POS_LIMIT_MINUS[XM]=-400.
$MA_POS_LIMIT_PLUS[XM]=400.
$MA_POS_LIMIT_MINUS[YM]=-300.
$MA_POS_LIMIT_PLUS[YM]=300.
$MA_POS_LIMIT_MINUS[ZM]=-100.
$MA_POS_LIMIT_PLUS[ZM]=400.
$MA_IS_ROT_AX[SPM]=TRUE
$MA_ROT_IS_MODULO[SPM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[SPM]=1
$MA_MAX_AX_VELO[SPM]=12000.
$MA_IS_ROT_AX[AM]=TRUE
$MA_MAX_AX_VELO[AM]=10800.
$MA_MAX_AX_ACCEL[AM]=1.5
$MA_POS_LIMIT_MINUS[AM]=-120.
$MA_POS_LIMIT_PLUS[AM]=120.
$MA_IS_ROT_AX[CM]=TRUE
$MA_ROT_IS_MODULO[CM]=TRUE
$MA_MAX_AX_VELO[CM]=18000.
$MA_MAX_AX_ACCEL[CM]=3.
; T1 D1: slot mill, length 80 (along ZM), radius 4
$TC_DP1[1,1]=120
$TC_DP3[1,1]=80.
$TC_DP6[1,1]=4.
; TRACYL data set 1: type 513, groove-wall offset travelled by XM
$MC_TRAFO_TYPE_1=513
$MC_TRAFO_AXES_IN_1[0]=3      ; ZC: radial to the rotary axis (the tool's infeed)
$MC_TRAFO_AXES_IN_1[1]=6      ; C: rotary axis
$MC_TRAFO_AXES_IN_1[2]=2      ; YC: parallel to the rotary axis
$MC_TRAFO_AXES_IN_1[3]=1      ; XC: perpendicular to both, for the groove-wall offset
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=3   ; X: radial, on ZC
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=6   ; Y: unrolled surface, on the rotary axis' channel slot
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=2   ; Z: along the cylinder, on YC
$MC_TRACYL_ROT_AX_OFFSET_1=0
$MC_TRACYL_ROT_SIGN_IS_PLUS_1=TRUE
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D8"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const TRAANG_GRINDER: &str = concat!(
    r#"; Grinding machine with an inclined infeed axis (Transformations FM, M1 TRAANG)
$MN_AXCONF_MACHAX_NAME_TAB[0]="MU"
$MN_AXCONF_MACHAX_NAME_TAB[1]="MZ"
$MN_AXCONF_MACHAX_NAME_TAB[2]="CM"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=0
$MC_AXCONF_CHANAX_NAME_TAB[0]="MU"
$MC_AXCONF_CHANAX_NAME_TAB[1]="MZ"
$MC_AXCONF_CHANAX_NAME_TAB[2]="C"
$MC_AXCONF_GEOAX_NAME_TAB[0]="X"
$MC_AXCONF_GEOAX_NAME_TAB[1]="Y"
$MC_AXCONF_GEOAX_NAME_TAB[2]="Z"
; without TRAANG the inclined axis moves as X, the longitudinal axis as Z
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=2
$MA_IS_ROT_AX[CM]=TRUE
$MA_ROT_IS_MODULO[CM]=TRUE
$MA_SPIND_ASSIGN_TO_MACHAX[CM]=1
$MA_MAX_AX_VELO[MU]=10000.
$MA_MAX_AX_VELO[MZ]=12000.
$MA_MAX_AX_ACCEL[MU]=2.
$MA_MAX_AX_ACCEL[MZ]=2.
$MA_POS_LIMIT_MINUS[MU]=-100.
$MA_POS_LIMIT_PLUS[MU]=300.
$MA_POS_LIMIT_MINUS[MZ]=-300.
$MA_POS_LIMIT_PLUS[MZ]=500.
; T1 D1: grinding wheel
$TC_DP1[1,1]=400
$TC_DP3[1,1]=0.
$TC_DP6[1,1]=200.
; TRAANG data set 1
$MC_TRAFO_TYPE_1=1024
$MC_TRAFO_AXES_IN_1[0]=1      ; MU: inclined axis
$MC_TRAFO_AXES_IN_1[1]=2      ; MZ: axis parallel to Z
$MC_TRAFO_AXES_IN_1[2]=0
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1   ; X on the inclined axis' channel slot
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=0
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=2   ; Z
$MC_TRAANG_ANGLE_1=45.
$MC_TRAANG_PARALLEL_VELO_RES_1=0.2
$MC_TRAANG_PARALLEL_ACCEL_RES_1=0.2
$MC_TRAANG_BASE_TOOL_1[0]=0
$MC_TRAANG_BASE_TOOL_1[1]=0
$MC_TRAANG_BASE_TOOL_1[2]=0
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="WHEEL_D400"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const MILL5_HEAD_CA: &str = concat!(
    r#"; 5-axis vertical mill with a fork head: C turns about Z and carries A, which turns about X.
$MN_AXCONF_MACHAX_NAME_TAB[0]="X"
$MN_AXCONF_MACHAX_NAME_TAB[1]="Y"
$MN_AXCONF_MACHAX_NAME_TAB[2]="Z"
$MN_AXCONF_MACHAX_NAME_TAB[3]="A"
$MN_AXCONF_MACHAX_NAME_TAB[4]="C"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=5
; The tool spindle S1: a spindle without axis function, as on mill-3axis.
$MN_AXCONF_MACHAX_NAME_TAB[5]="SP1"
$MC_AXCONF_MACHAX_USED[5]=6
$MC_AXCONF_CHANAX_NAME_TAB[5]=""
"#,
    tool_spindle_sp1!(),
    r#"$MC_AXCONF_MACHAX_USED[6]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MC_AXCONF_CHANAX_NAME_TAB[0]="X"
$MC_AXCONF_CHANAX_NAME_TAB[1]="Y"
$MC_AXCONF_CHANAX_NAME_TAB[2]="Z"
$MC_AXCONF_CHANAX_NAME_TAB[3]="A"
$MC_AXCONF_CHANAX_NAME_TAB[4]="C"
$MA_MAX_AX_VELO[X]=40000.
$MA_MAX_AX_ACCEL[X]=4.
$MA_POS_LIMIT_MINUS[X]=-800.
$MA_POS_LIMIT_PLUS[X]=800.
$MA_MAX_AX_VELO[Y]=40000.
$MA_MAX_AX_ACCEL[Y]=4.
$MA_POS_LIMIT_MINUS[Y]=-600.
$MA_POS_LIMIT_PLUS[Y]=600.
$MA_MAX_AX_VELO[Z]=40000.
$MA_MAX_AX_ACCEL[Z]=4.
$MA_POS_LIMIT_MINUS[Z]=-400.
$MA_POS_LIMIT_PLUS[Z]=300.
$MA_IS_ROT_AX[A]=TRUE
$MA_MAX_AX_VELO[A]=40.
$MA_MAX_AX_ACCEL[A]=2.
$MA_POS_LIMIT_MINUS[A]=-110.
$MA_POS_LIMIT_PLUS[A]=110.
$MA_IS_ROT_AX[C]=TRUE
$MA_ROT_IS_MODULO[C]=TRUE
$MA_MAX_AX_VELO[C]=40.
$MA_MAX_AX_ACCEL[C]=2.
; T1 D1: end mill, length 100, radius 5
$TC_DP1[1,1]=120
$TC_DP3[1,1]=100.
$TC_DP6[1,1]=5.
; TRAORI data set 1: head CA (type 20), both rotary axes turn the tool.
$MC_TRAFO_TYPE_1=20
$MC_TRAFO_AXES_IN_1[0]=1      ; X
$MC_TRAFO_AXES_IN_1[1]=2      ; Y
$MC_TRAFO_AXES_IN_1[2]=3      ; Z
$MC_TRAFO_AXES_IN_1[3]=5      ; C: 1st rotary axis (outer, about Z)
$MC_TRAFO_AXES_IN_1[4]=4      ; A: 2nd rotary axis (inner, about X)
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3
; A pivot 150 mm above the spindle nose (l3 = BASE_TOOL, pivot → tool reference); the machine
; position is the spindle nose at A = C = 0 (l1 = PART_OFFSET = −(JOINT_OFFSET + BASE_TOOL)).
$MC_TRAFO5_BASE_TOOL_1[2]=-150.
$MC_TRAFO5_PART_OFFSET_1[2]=150.
$MC_TRAFO5_ROT_AX_OFFSET_1[0]=0
$MC_TRAFO5_ROT_AX_OFFSET_1[1]=0
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[0]=TRUE
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[1]=TRUE
$MC_TRAFO5_NON_POLE_LIMIT_1=2.
$MC_TRAFO5_POLE_LIMIT_1=2.
; Swivel data set 1 (toolholder type T) with the same head for TCARR and CYCLE800: C carries A,
; l1 = (0, 0, 150) from the spindle nose to the A pivot, l3 = −l1 back to the tool reference.
$MN_MM_NUM_TOOL_CARRIER=1
$TC_CARR3[1]=150.
$TC_CARR17[1]=-150.
$TC_CARR9[1]=1.               ; v1 = Z (C)
$TC_CARR10[1]=1.              ; v2 = X (A)
$TC_CARR21[1]=C
$TC_CARR22[1]=A
$TC_CARR23[1]="T"
$TC_CARR31[1]=-110.
$TC_CARR33[1]=110.
$TC_CARR34[1]="HEAD_CA"
$TC_CARR35[1]="C"
$TC_CARR36[1]="A"
$TC_CARR37[1]=2005            ; all swivel modes; direction reference: rotary axis 2 (A)
$TC_CARR38[1]=0.
$TC_CARR39[1]=0.
$TC_CARR40[1]=250.            ; retraction position Z (machine)
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D10"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const MILL5_TABLE_AC: &str = concat!(
    r#"; 5-axis mill with a trunnion table: A tilts about X and carries the rotary table C.
$MN_AXCONF_MACHAX_NAME_TAB[0]="X"
$MN_AXCONF_MACHAX_NAME_TAB[1]="Y"
$MN_AXCONF_MACHAX_NAME_TAB[2]="Z"
$MN_AXCONF_MACHAX_NAME_TAB[3]="A"
$MN_AXCONF_MACHAX_NAME_TAB[4]="C"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=5
; The tool spindle S1: a spindle without axis function, as on mill-3axis.
$MN_AXCONF_MACHAX_NAME_TAB[5]="SP1"
$MC_AXCONF_MACHAX_USED[5]=6
$MC_AXCONF_CHANAX_NAME_TAB[5]=""
"#,
    tool_spindle_sp1!(),
    r#"$MC_AXCONF_MACHAX_USED[6]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MC_AXCONF_CHANAX_NAME_TAB[0]="X"
$MC_AXCONF_CHANAX_NAME_TAB[1]="Y"
$MC_AXCONF_CHANAX_NAME_TAB[2]="Z"
$MC_AXCONF_CHANAX_NAME_TAB[3]="A"
$MC_AXCONF_CHANAX_NAME_TAB[4]="C"
$MA_MAX_AX_VELO[X]=50000.
$MA_MAX_AX_ACCEL[X]=5.
$MA_POS_LIMIT_MINUS[X]=-600.
$MA_POS_LIMIT_PLUS[X]=600.
$MA_MAX_AX_VELO[Y]=50000.
$MA_MAX_AX_ACCEL[Y]=5.
$MA_POS_LIMIT_MINUS[Y]=-600.
$MA_POS_LIMIT_PLUS[Y]=600.
$MA_MAX_AX_VELO[Z]=50000.
$MA_MAX_AX_ACCEL[Z]=5.
$MA_POS_LIMIT_MINUS[Z]=-300.
$MA_POS_LIMIT_PLUS[Z]=400.
$MA_IS_ROT_AX[A]=TRUE
$MA_MAX_AX_VELO[A]=30.
$MA_MAX_AX_ACCEL[A]=1.5
$MA_POS_LIMIT_MINUS[A]=-120.
$MA_POS_LIMIT_PLUS[A]=120.
$MA_IS_ROT_AX[C]=TRUE
$MA_ROT_IS_MODULO[C]=TRUE
$MA_MAX_AX_VELO[C]=50.
$MA_MAX_AX_ACCEL[C]=3.
; T1 D1: end mill, length 100, radius 5
$TC_DP1[1,1]=120
$TC_DP3[1,1]=100.
$TC_DP6[1,1]=5.
; TRAORI data set 1: table AC (type 33), both rotary axes turn the workpiece; the type
; reverses the axis directions (DIN: positive motion turns the tool relative to the part).
$MC_TRAFO_TYPE_1=33
$MC_TRAFO_AXES_IN_1[0]=1      ; X
$MC_TRAFO_AXES_IN_1[1]=2      ; Y
$MC_TRAFO_AXES_IN_1[2]=3      ; Z
$MC_TRAFO_AXES_IN_1[3]=4      ; A: 1st rotary axis (trunnion)
$MC_TRAFO_AXES_IN_1[4]=5      ; C: 2nd rotary axis (table on the trunnion)
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3
; Machine reference = table zero (centre of the table surface) at A = C = 0. The A axis lies
; 100 mm below and 20 mm behind it (l2 = BASE_TOOL), the C axis crosses the A axis' plane
; 20 mm below the surface (l3 = JOINT_OFFSET), closing with l4 = PART_OFFSET = −(l2 + l3).
$MC_TRAFO5_BASE_TOOL_1[1]=20.
$MC_TRAFO5_BASE_TOOL_1[2]=-100.
$MC_TRAFO5_JOINT_OFFSET_1[1]=-20.
$MC_TRAFO5_JOINT_OFFSET_1[2]=80.
$MC_TRAFO5_PART_OFFSET_1[2]=20.
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[0]=TRUE
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[1]=TRUE
$MC_TRAFO5_NON_POLE_LIMIT_1=2.
$MC_TRAFO5_POLE_LIMIT_1=2.
; Swivel data set 1 (toolholder type P) with the same table: A (reversed, DIN) carries C
; (reversed); l2 = BASE_TOOL, l3 = JOINT_OFFSET, l4 = PART_OFFSET of the TRAORI data.
$MN_MM_NUM_TOOL_CARRIER=1
$TC_CARR5[1]=20.
$TC_CARR6[1]=-100.
$TC_CARR16[1]=-20.
$TC_CARR17[1]=80.
$TC_CARR20[1]=20.
$TC_CARR7[1]=-1.              ; v1 = −X (A turns the workpiece)
$TC_CARR12[1]=-1.             ; v2 = −Z (C turns the workpiece)
$TC_CARR21[1]=A
$TC_CARR22[1]=C
$TC_CARR23[1]="P"
$TC_CARR30[1]=-120.
$TC_CARR32[1]=120.
$TC_CARR34[1]="TABLE_AC"
$TC_CARR35[1]="A"
$TC_CARR36[1]="C"
$TC_CARR37[1]=1005            ; all swivel modes; direction reference: rotary axis 1 (A)
$TC_CARR40[1]=350.            ; retraction position Z (machine)
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D10"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

const MILL5_MIXED_BC: &str = concat!(
    r#"; 5-axis mill with a swivel head B (about Y) and a rotary table C (about Z).
$MN_AXCONF_MACHAX_NAME_TAB[0]="X"
$MN_AXCONF_MACHAX_NAME_TAB[1]="Y"
$MN_AXCONF_MACHAX_NAME_TAB[2]="Z"
$MN_AXCONF_MACHAX_NAME_TAB[3]="B"
$MN_AXCONF_MACHAX_NAME_TAB[4]="C"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=5
; The tool spindle S1: a spindle without axis function, as on mill-3axis.
$MN_AXCONF_MACHAX_NAME_TAB[5]="SP1"
$MC_AXCONF_MACHAX_USED[5]=6
$MC_AXCONF_CHANAX_NAME_TAB[5]=""
"#,
    tool_spindle_sp1!(),
    r#"$MC_AXCONF_MACHAX_USED[6]=0
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MC_AXCONF_CHANAX_NAME_TAB[0]="X"
$MC_AXCONF_CHANAX_NAME_TAB[1]="Y"
$MC_AXCONF_CHANAX_NAME_TAB[2]="Z"
$MC_AXCONF_CHANAX_NAME_TAB[3]="B"
$MC_AXCONF_CHANAX_NAME_TAB[4]="C"
$MA_MAX_AX_VELO[X]=30000.
$MA_MAX_AX_ACCEL[X]=3.
$MA_POS_LIMIT_MINUS[X]=-800.
$MA_POS_LIMIT_PLUS[X]=800.
$MA_MAX_AX_VELO[Y]=30000.
$MA_MAX_AX_ACCEL[Y]=3.
$MA_POS_LIMIT_MINUS[Y]=-600.
$MA_POS_LIMIT_PLUS[Y]=600.
$MA_MAX_AX_VELO[Z]=30000.
$MA_MAX_AX_ACCEL[Z]=3.
$MA_POS_LIMIT_MINUS[Z]=-400.
$MA_POS_LIMIT_PLUS[Z]=400.
$MA_IS_ROT_AX[B]=TRUE
$MA_MAX_AX_VELO[B]=30.
$MA_MAX_AX_ACCEL[B]=1.5
$MA_POS_LIMIT_MINUS[B]=-100.
$MA_POS_LIMIT_PLUS[B]=100.
$MA_IS_ROT_AX[C]=TRUE
$MA_ROT_IS_MODULO[C]=TRUE
$MA_MAX_AX_VELO[C]=50.
$MA_MAX_AX_ACCEL[C]=3.
; T1 D1: end mill, length 100, radius 5
$TC_DP1[1,1]=120
$TC_DP3[1,1]=100.
$TC_DP6[1,1]=5.
; TRAORI data set 1: mixed BC (type 51): B turns the tool, C (DIN-reversed) the workpiece.
$MC_TRAFO_TYPE_1=51
$MC_TRAFO_AXES_IN_1[0]=1      ; X
$MC_TRAFO_AXES_IN_1[1]=2      ; Y
$MC_TRAFO_AXES_IN_1[2]=3      ; Z
$MC_TRAFO_AXES_IN_1[3]=4      ; B: 1st rotary axis (head)
$MC_TRAFO_AXES_IN_1[4]=5      ; C: 2nd rotary axis (table)
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3
; Head: B pivot 120 mm above the spindle nose (l2 = BASE_TOOL, l1 = JOINT_OFFSET = −l2).
; Table: the C axis crosses the plane 80 mm below the table zero point
; (l3 = JOINT_OFFSET_PART, l4 = PART_OFFSET = −l3).
$MC_TRAFO5_BASE_TOOL_1[2]=-120.
$MC_TRAFO5_JOINT_OFFSET_1[2]=120.
$MC_TRAFO5_JOINT_OFFSET_PART_1[2]=-80.
$MC_TRAFO5_PART_OFFSET_1[2]=80.
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[0]=TRUE
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[1]=TRUE
$MC_TRAFO5_NON_POLE_LIMIT_1=2.
$MC_TRAFO5_POLE_LIMIT_1=2.
; Swivel data set 1 (toolholder type M): head B (axis 1) and table C (axis 2, reversed);
; l1 = JOINT_OFFSET, l2 = BASE_TOOL, l3 = JOINT_OFFSET_PART, l4 = PART_OFFSET.
$MN_MM_NUM_TOOL_CARRIER=1
$TC_CARR3[1]=120.
$TC_CARR6[1]=-120.
$TC_CARR17[1]=-80.
$TC_CARR20[1]=80.
$TC_CARR8[1]=1.               ; v1 = Y (B turns the tool)
$TC_CARR12[1]=-1.             ; v2 = −Z (C turns the workpiece)
$TC_CARR21[1]=B
$TC_CARR22[1]=C
$TC_CARR23[1]="M"
$TC_CARR30[1]=-100.
$TC_CARR32[1]=100.
$TC_CARR34[1]="MIXED_BC"
$TC_CARR35[1]="B"
$TC_CARR36[1]="C"
$TC_CARR37[1]=1005            ; all swivel modes; direction reference: rotary axis 1 (B)
$TC_CARR40[1]=350.            ; retraction position Z (machine)
; Tool management: a chain magazine with 12 places holding the tools, the spindle
; place in the buffer magazine 9998
"#,
    chain_magazine!(),
    r#"$TC_TP1[1]=1
$TC_TP2[1]="MILL_D10"
$TC_TP8[1]=2
$TC_MPP6[1,1]=1
"#
);

/// The text of `mill6-generic`, a macro so that `mill7-generic` can be built on it with `concat!`.
macro_rules! mill6_generic_text {
    () => {
        r#"; 6-axis mill with a three-axis head: C turns about Z and carries B (about Y), which carries
; A, the rotation of the tool about its own axis (generic 6-axis transformation, F2 §3.7.5).
$MN_AXCONF_MACHAX_NAME_TAB[0]="X"
$MN_AXCONF_MACHAX_NAME_TAB[1]="Y"
$MN_AXCONF_MACHAX_NAME_TAB[2]="Z"
$MN_AXCONF_MACHAX_NAME_TAB[3]="A"
$MN_AXCONF_MACHAX_NAME_TAB[4]="B"
$MN_AXCONF_MACHAX_NAME_TAB[5]="C"
$MC_AXCONF_MACHAX_USED[0]=1
$MC_AXCONF_MACHAX_USED[1]=2
$MC_AXCONF_MACHAX_USED[2]=3
$MC_AXCONF_MACHAX_USED[3]=4
$MC_AXCONF_MACHAX_USED[4]=5
$MC_AXCONF_MACHAX_USED[5]=6
$MC_AXCONF_GEOAX_ASSIGN_TAB[0]=1
$MC_AXCONF_GEOAX_ASSIGN_TAB[1]=2
$MC_AXCONF_GEOAX_ASSIGN_TAB[2]=3
$MC_AXCONF_CHANAX_NAME_TAB[0]="X"
$MC_AXCONF_CHANAX_NAME_TAB[1]="Y"
$MC_AXCONF_CHANAX_NAME_TAB[2]="Z"
$MC_AXCONF_CHANAX_NAME_TAB[3]="A"
$MC_AXCONF_CHANAX_NAME_TAB[4]="B"
$MC_AXCONF_CHANAX_NAME_TAB[5]="C"
$MA_MAX_AX_VELO[X]=40000.
$MA_MAX_AX_ACCEL[X]=4.
$MA_POS_LIMIT_MINUS[X]=-800.
$MA_POS_LIMIT_PLUS[X]=800.
$MA_MAX_AX_VELO[Y]=40000.
$MA_MAX_AX_ACCEL[Y]=4.
$MA_POS_LIMIT_MINUS[Y]=-600.
$MA_POS_LIMIT_PLUS[Y]=600.
$MA_MAX_AX_VELO[Z]=40000.
$MA_MAX_AX_ACCEL[Z]=4.
$MA_POS_LIMIT_MINUS[Z]=-400.
$MA_POS_LIMIT_PLUS[Z]=300.
$MA_IS_ROT_AX[A]=TRUE
$MA_MAX_AX_VELO[A]=50.
$MA_MAX_AX_ACCEL[A]=3.
$MA_POS_LIMIT_MINUS[A]=-200.
$MA_POS_LIMIT_PLUS[A]=200.
$MA_IS_ROT_AX[B]=TRUE
$MA_MAX_AX_VELO[B]=30.
$MA_MAX_AX_ACCEL[B]=2.
$MA_POS_LIMIT_MINUS[B]=-100.
$MA_POS_LIMIT_PLUS[B]=100.
$MA_IS_ROT_AX[C]=TRUE
$MA_ROT_IS_MODULO[C]=TRUE
$MA_MAX_AX_VELO[C]=40.
$MA_MAX_AX_ACCEL[C]=2.
; T1 D1: end mill, length 100, radius 5
$TC_DP1[1,1]=120
$TC_DP3[1,1]=100.
$TC_DP6[1,1]=5.
; TRAORI data set 1: generic 6-axis, all three rotary axes turn the tool.
$MC_TRAFO_TYPE_1=24
$MC_TRAFO_AXES_IN_1[0]=1      ; X
$MC_TRAFO_AXES_IN_1[1]=2      ; Y
$MC_TRAFO_AXES_IN_1[2]=3      ; Z
$MC_TRAFO_AXES_IN_1[3]=6      ; C: 1st rotary axis (about Z)
$MC_TRAFO_AXES_IN_1[4]=5      ; B: 2nd rotary axis (about Y)
$MC_TRAFO_AXES_IN_1[5]=4      ; A: 3rd rotary axis (about the tool axis)
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[0]=1
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[1]=2
$MC_TRAFO_GEOAX_ASSIGN_TAB_1[2]=3
$MC_TRAFO5_AXIS1_1[2]=1.
$MC_TRAFO5_AXIS2_1[1]=1.
$MC_TRAFO5_AXIS3_1[2]=1.
$MC_TRAFO5_BASE_ORIENT_1[2]=1.
$MC_TRAFO6_BASE_ORIENT_NORMAL_1[0]=1.
; C and B intersect; the B pivot lies 80 mm above the A bearing, which lies 120 mm above the
; spindle nose: l2 = JOINT_OFFSET = 0, l23 = JOINT_OFFSET_2_3, l3 = BASE_TOOL, and the machine
; position is the spindle nose at A = B = C = 0 (l1 = PART_OFFSET = −(l2 + l23 + l3)).
$MC_TRAFO6_JOINT_OFFSET_2_3_1[2]=-80.
$MC_TRAFO5_BASE_TOOL_1[2]=-120.
$MC_TRAFO5_PART_OFFSET_1[2]=200.
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[0]=TRUE
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[1]=TRUE
$MC_TRAFO5_ROT_SIGN_IS_PLUS_1[2]=TRUE
$MC_TRAFO5_NON_POLE_LIMIT_1=2.
$MC_TRAFO5_POLE_LIMIT_1=2.
"#
    };
}

const MILL6_GENERIC: &str = concat!(
    mill6_generic_text!(),
    r#"; The tool spindle S1: a spindle without axis function, as on mill-3axis.
$MN_AXCONF_MACHAX_NAME_TAB[6]="SP1"
$MC_AXCONF_MACHAX_USED[6]=7
$MC_AXCONF_CHANAX_NAME_TAB[6]=""
"#,
    tool_spindle_sp1!()
);

const MILL7_GENERIC: &str = concat!(
    mill6_generic_text!(),
    r#"; 7-axis mill: the head of mill6-generic (above) and a rotary table C1 about Z that turns the
; workpiece: the 7th axis of the generic 7-axis transformation (F2 §3.7.6).
$MN_AXCONF_MACHAX_NAME_TAB[6]="C1"
$MC_AXCONF_MACHAX_USED[6]=7
$MC_AXCONF_CHANAX_NAME_TAB[6]="C1"
$MA_IS_ROT_AX[C1]=TRUE
$MA_ROT_IS_MODULO[C1]=TRUE
$MA_MAX_AX_VELO[C1]=30.
$MA_MAX_AX_ACCEL[C1]=1.5
$MC_TRAFO_AXES_IN_1[6]=7      ; C1: 7th axis (rotary table)
; The table axis runs through the BCS zero point (machine X0 Y0) along +Z.
$MC_TRAFO7_EXT_AXIS1_1[2]=1.
$MC_TRAFO7_EXT_ROT_AX_OFFSET_1=0.
"#,
    r#"; The tool spindle S1: a spindle without axis function, as on mill-3axis.
$MN_AXCONF_MACHAX_NAME_TAB[7]="SP1"
$MC_AXCONF_MACHAX_USED[7]=8
$MC_AXCONF_CHANAX_NAME_TAB[7]=""
"#,
    tool_spindle_sp1!()
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::MachineData;

    #[test]
    fn every_preset_activates() {
        for p in PRESETS {
            MachineData::default().apply_text(p.text).unwrap_or_else(|e| panic!("{}: {e}", p.id));
        }
    }

    #[test]
    fn the_mill_has_three_linear_geometry_axes_and_a_4ms_ipo_cycle() {
        let cfg = MachineData::default().apply_text(find("mill-3axis").unwrap().text).unwrap();
        let names: Vec<_> = cfg.machine_axes.iter().map(|a| a.name.as_str()).collect();
        // The 4th machine axis is the tool spindle, a spindle without axis function.
        assert_eq!(names, ["X", "Y", "Z", "SP1"]);
        assert!(cfg.machine_axes[..3].iter().all(|a| !a.rotary));
        assert_eq!((cfg.machine_axes[3].spindle, cfg.machine_axes[3].spindle_only), (Some(1), true));
        assert_eq!(cfg.master_spindle, Some(3));
        assert_eq!(cfg.geo_axes, [Some(0), Some(1), Some(2)]);
        assert!((cfg.ipo_cycle - 0.004).abs() < 1e-12);
        // 30000 mm/min = 500 mm/s, 3 m/s² = 3000 mm/s².
        assert_eq!((cfg.machine_axes[0].max_velocity, cfg.machine_axes[0].max_accel), (500.0, 3000.0));
    }

    #[test]
    fn the_transmit_machine_has_x_and_z_geometry_axes_and_two_spindles() {
        let cfg = MachineData::default().apply_text(find("transmit-example").unwrap().text).unwrap();
        assert_eq!(cfg.geo_axes, [Some(0), None, Some(2)]);
        assert_eq!(cfg.program_axis("C"), Some(1));
        assert_eq!(cfg.machine_axes[1].spindle, Some(1));
        assert_eq!(cfg.machine_axes[3].spindle, Some(2));
        assert_eq!(cfg.master_spindle, Some(1));
    }

    #[test]
    fn the_six_axis_machine_has_a_generic_traori_with_three_rotary_axes() {
        let cfg = MachineData::default().apply_text(find("mill6-generic").unwrap().text).unwrap();
        assert_eq!((cfg.trafos.len(), cfg.trafos[0].trafo_type), (1, 24));
        let [a, b, c] = ["A", "B", "C"].map(|n| cfg.program_axis(n).unwrap());
        assert_eq!(cfg.trafos[0].axes_in[3..6], [Some(c), Some(b), Some(a)]);
        assert_eq!(cfg.axis(c).modulo, Some((0.0, 360.0)));
        assert_eq!((cfg.axis(a).limit_minus, cfg.axis(a).limit_plus), (-200.0, 200.0));
    }

    #[test]
    fn the_five_axis_machines_have_traori_data_set_1_and_a_modulo_c() {
        for (id, t) in [("mill5-head-ca", 20), ("mill5-table-ac", 33), ("mill5-mixed-bc", 51)] {
            let cfg = MachineData::default().apply_text(find(id).unwrap().text).unwrap();
            assert_eq!((cfg.trafos.len(), cfg.trafos[0].trafo_type), (1, t), "{id}");
            assert_eq!(cfg.trafos[0].kind, crate::machine_data::TrafoKind::Traori);
            let c = cfg.program_axis("C").unwrap();
            assert_eq!(cfg.axis(c).modulo, Some((0.0, 360.0)), "{id}");
            assert_eq!(cfg.geo_axes, [Some(0), Some(1), Some(2)]);
        }
    }
}
