//! The table of every machine datum the product knows: name, number, scope, type, size,
//! default and valid range, in one place. Adding a datum is adding one row here.

use super::Value;

/// Where a datum lives: NCK-wide (`$MN_`/`$SN_`), per channel (`$MC_`/`$SC_`), per axis (`$MA_`/`$SA_`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Scope {
    Nck,
    Channel,
    Axis,
}

/// The value type of a datum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Bool,
    Int,
    Real,
    Str,
}

/// How a datum's default is computed for an array index (and, for axial data, the axis type).
#[derive(Debug, Clone, Copy)]
pub enum Default {
    Bool(bool),
    Int(i64),
    Real(f64),
    /// Axial data whose default depends on `$MA_IS_ROT_AX` (the control's units differ).
    RealByAxisType {
        linear: f64,
        rotary: f64,
    },
    Str(&'static str),
    /// A different default per array index.
    Indexed(fn(usize) -> Value),
}

/// One machine datum.
#[derive(Debug, Clone, Copy)]
pub struct Def {
    /// Name without prefix, e.g. `AXCONF_MACHAX_NAME_TAB`.
    pub name: &'static str,
    /// Machine data number as in the Siemens lists (0 for non-MD data).
    pub number: u32,
    pub scope: Scope,
    /// Setting data (`$S?_`) rather than machine data (`$M?_`).
    pub setting: bool,
    pub kind: Kind,
    /// Number of array elements; 1 for a scalar.
    pub len: usize,
    pub default: Default,
    /// Inclusive valid range for numbers.
    pub min: f64,
    pub max: f64,
}

impl Def {
    /// The full name with its prefix, as written in NC data text.
    pub fn full_name(&self) -> String {
        let prefix = match (self.setting, self.scope) {
            (false, Scope::Nck) => "$MN_",
            (false, Scope::Channel) => "$MC_",
            (false, Scope::Axis) => "$MA_",
            (true, Scope::Nck) => "$SN_",
            (true, Scope::Channel) => "$SC_",
            (true, Scope::Axis) => "$SA_",
        };
        format!("{prefix}{}", self.name)
    }

    /// The default of element `index`; `rotary` is the axis type for axial data.
    pub fn default_value(&self, index: usize, rotary: bool) -> Value {
        match self.default {
            Default::Bool(b) => Value::Bool(b),
            Default::Int(i) => Value::Int(i),
            Default::Real(r) => Value::Real(r),
            Default::RealByAxisType { linear, rotary: rot } => Value::Real(if rotary { rot } else { linear }),
            Default::Str(s) => Value::Str(s.to_string()),
            Default::Indexed(f) => f(index),
        }
    }
}

/// Maximum numbers of axes this product models (a real 840D sl NCU allows 31 machine axes and
/// 20 channel axes per channel).
pub const MAX_MACHINE_AXES: usize = 31;
pub const MAX_CHANNEL_AXES: usize = 20;

#[allow(clippy::too_many_arguments, reason = "one positional row per datum keeps the table readable")]
const fn def(
    name: &'static str,
    number: u32,
    scope: Scope,
    kind: Kind,
    len: usize,
    default: Default,
    min: f64,
    max: f64,
) -> Def {
    Def { name, number, scope, setting: false, kind, len, default, min, max }
}

/// A setting datum (`$SN_`/`$SC_`/`$SA_`).
const fn sd(name: &'static str, number: u32, scope: Scope, kind: Kind, default: Default, min: f64, max: f64) -> Def {
    Def { name, number, scope, setting: true, kind, len: 1, default, min, max }
}

const INF: f64 = f64::INFINITY;
const N: Scope = Scope::Nck;
const C: Scope = Scope::Channel;
const A: Scope = Scope::Axis;

fn default_machax_name(i: usize) -> Value {
    const FIRST: [&str; 8] = ["X1", "Y1", "Z1", "A1", "B1", "C1", "U1", "V1"];
    Value::Str(FIRST.get(i).map_or_else(|| format!("AX{}", i + 1), |s| s.to_string()))
}

fn default_chanax_name(i: usize) -> Value {
    const FIRST: [&str; 8] = ["X", "Y", "Z", "A", "B", "C", "U", "V"];
    Value::Str(FIRST.get(i).map_or_else(|| format!("CH{}", i + 1), |s| s.to_string()))
}

fn default_geoax_name(i: usize) -> Value {
    Value::Str(["X", "Y", "Z"][i].to_string())
}

fn default_geoax_assign(i: usize) -> Value {
    Value::Int(i as i64 + 1)
}

fn default_machax_used(i: usize) -> Value {
    Value::Int(if i < 6 { i as i64 + 1 } else { 0 })
}

/// G group reset values: the first function of each group, except group 24, whose reset value
/// is FFWON (2) here where the control's factory value is FFWOF: NCTwin's presets model a
/// machine that runs with feed-forward, as CAM programs expect, so the actual value follows the
/// setpoint unless a program or the machine data says FFWOF.
fn default_gcode_reset(i: usize) -> Value {
    Value::Int(if i + 1 == 24 { 2 } else { 1 })
}

/// Number of dynamic response modes (G group 59, DYNNORM..DYNFINISH): the size of the per-mode
/// axial data MD32300, MD32310, MD32431.
pub const DYN_MODES: usize = 5;

/// Number of transformation data sets per channel (`$MC_TRAFO_TYPE_1` .. `_10`).
pub const MAX_TRAFO_SETS: usize = 10;

fn default_trafo_axes_in(i: usize) -> Value {
    // The control's default: channel axes 1..5 in order, then none.
    Value::Int(if i < 5 { i as i64 + 1 } else { 0 })
}

fn default_unit_z(i: usize) -> Value {
    Value::Real(if i == 2 { 1.0 } else { 0.0 })
}

fn default_unit_x(i: usize) -> Value {
    Value::Real(if i == 0 { 1.0 } else { 0.0 })
}

/// ORIVIRT1 default: the orientation axes turn about X, Y, Z in this order ([I], unverified).
fn default_turn_tab_1(i: usize) -> Value {
    Value::Int(i as i64 + 1)
}

/// ORIVIRT2 default: Z, X, Z (the Euler sequence) ([I], unverified).
fn default_turn_tab_2(i: usize) -> Value {
    Value::Int([3, 1, 3][i])
}

/// Every datum, in Siemens number order.
pub static DEFS: &[Def] = &[
    def(
        "AXCONF_MACHAX_NAME_TAB",
        10000,
        N,
        Kind::Str,
        MAX_MACHINE_AXES,
        Default::Indexed(default_machax_name),
        0.0,
        0.0,
    ),
    def("SYSCLOCK_CYCLE_TIME", 10050, N, Kind::Real, 1, Default::Real(0.002), 0.000125, 0.031),
    def("IPO_SYSCLOCK_TIME_RATIO", 10070, N, Kind::Int, 1, Default::Int(2), 1.0, 100.0),
    // Angles of frame rotations: 1 = RPY (Z, Y', X''), 2 = Euler (Z, X', Z'') (K2).
    def("FRAME_ANGLE_INPUT_MODE", 10600, N, Kind::Int, 1, Default::Int(1), 1.0, 2.0),
    // Subprograms called instead of M functions (MD10715 the M numbers, -1 = none, MD10716 the
    // names) and instead of T (MD10717), K1/W1; ten pairs, as on the control.
    def("M_NO_FCT_CYCLE", 10715, N, Kind::Int, 10, Default::Int(-1), -1.0, 2147483647.0),
    def("M_NO_FCT_CYCLE_NAME", 10716, N, Kind::Str, 10, Default::Str(""), 0.0, 0.0),
    def("T_NO_FCT_CYCLE_NAME", 10717, N, Kind::Str, 1, Default::Str(""), 0.0, 0.0),
    // NCU-global basic frames $P_NCBFR[n] (K2; 0 = none, the control's default).
    def("MM_NUM_GLOBAL_BASE_FRAMES", 18602, N, Kind::Int, 1, Default::Int(0), 0.0, 16.0),
    // The fast NCK I/Os (`sync_sizes.rs`): digital ones in bytes of 8 signals, analog ones
    // in signals; NCTwin's defaults are its sizes of before (5 bytes, 4 signals).
    def("FASTIO_ANA_NUM_INPUTS", 10300, N, Kind::Int, 1, Default::Int(4), 0.0, 8.0),
    def("FASTIO_ANA_NUM_OUTPUTS", 10310, N, Kind::Int, 1, Default::Int(4), 0.0, 8.0),
    def("FASTIO_DIG_NUM_INPUTS", 10350, N, Kind::Int, 1, Default::Int(2), 0.0, 5.0),
    def("FASTIO_DIG_NUM_OUTPUTS", 10360, N, Kind::Int, 1, Default::Int(2), 0.0, 5.0),
    // Number of orientable toolholders $TC_CARR[1..n] (W1; 0 = none, as on the control).
    // MD18102: 1 = flat D numbers (flat_d.rs).
    def("MM_TYPE_OF_CUTTING_EDGE", 18102, N, Kind::Int, 1, Default::Int(0), 0.0, 1.0),
    def("MM_NUM_TOOL_CARRIER", 18088, N, Kind::Int, 1, Default::Int(0), 0.0, 99.0),
    // Largest file WRITE appends to, in kilobytes (file functions: error 10 beyond it).
    def("LEN_PROTOCOL_FILE", 11420, N, Kind::Int, 1, Default::Int(1), 1.0, 1_000_000.0),
    def("ENABLE_CHAN_AX_GAP", 11640, N, Kind::Int, 1, Default::Int(0), 0.0, 1.0),
    // Kinematic chains (K12): root element name and the sizes of the $NK_/$NT_ data. The
    // defaults are this product's choice (the manual names the data, not their defaults).
    def("ROOT_KIN_ELEM_NAME", 16800, N, Kind::Str, 1, Default::Str("ROOT"), 0.0, 0.0),
    def("MM_NUM_KIN_TRAFOS", 18866, N, Kind::Int, 1, Default::Int(10), 0.0, 64.0),
    def("MM_MAXNUM_KIN_CHAIN_ELEM", 18880, N, Kind::Int, 1, Default::Int(64), 0.0, 256.0),
    def(
        "AXCONF_GEOAX_ASSIGN_TAB",
        20050,
        C,
        Kind::Int,
        3,
        Default::Indexed(default_geoax_assign),
        0.0,
        MAX_CHANNEL_AXES as f64,
    ),
    def("AXCONF_GEOAX_NAME_TAB", 20060, C, Kind::Str, 3, Default::Indexed(default_geoax_name), 0.0, 0.0),
    def(
        "AXCONF_MACHAX_USED",
        20070,
        C,
        Kind::Int,
        MAX_CHANNEL_AXES,
        Default::Indexed(default_machax_used),
        0.0,
        MAX_MACHINE_AXES as f64,
    ),
    def(
        "AXCONF_CHANAX_NAME_TAB",
        20080,
        C,
        Kind::Str,
        MAX_CHANNEL_AXES,
        Default::Indexed(default_chanax_name),
        0.0,
        0.0,
    ),
    def("RESET_MODE_MASK", 20110, C, Kind::Int, 1, Default::Int(1), 0.0, 65535.0),
    def("GEOAX_CHANGE_RESET", 20118, C, Kind::Bool, 1, Default::Bool(false), 0.0, 1.0),
    def("TRAFO_RESET_VALUE", 20140, C, Kind::Int, 1, Default::Int(0), 0.0, MAX_TRAFO_SETS as f64),
    // With kinematic chains the reset transformation is named ($NT_NAME) instead (K12 §4.2.2.2).
    def("TRAFO_RESET_NAME", 20142, C, Kind::Str, 1, Default::Str(""), 0.0, 0.0),
    def("TRAFO_MODE_MASK", 20144, C, Kind::Int, 1, Default::Int(0), 0.0, 255.0),
    // Reset values of the G groups, [group - 1] = position in the group (1 = first). NCTwin
    // reads the groups of the dynamics (21, 24, 59); see `default_gcode_reset`.
    def("GCODE_RESET_VALUES", 20150, C, Kind::Int, 60, Default::Indexed(default_gcode_reset), 1.0, 99.0),
    // Path jerk under SOFT in m/s³ (on top of each axis' MD32431).
    def("MAX_PATH_JERK", 20600, C, Kind::Real, 1, Default::Real(100_000.0), 1e-6, 1e9),
    def("SPIND_DEF_MASTER_SPIND", 20090, C, Kind::Int, 1, Default::Int(1), 1.0, 20.0),
    // MD20100: the transverse axis for DIAMON/G96 ("": the first geometry axis, X).
    def("DIAMETER_AX_DEF", 20100, C, Kind::Str, 1, Default::Str(""), 0.0, 0.0),
    // Orientation programming (TRAORI), REFERENCE §6.2.
    def("MAX_LEAD_ANGLE", 21090, C, Kind::Real, 1, Default::Real(60.0), 0.0, 89.999),
    def("MAX_TILT_ANGLE", 21092, C, Kind::Real, 1, Default::Real(60.0), 0.0, 89.999),
    def("ORIPATH_MODE", 21094, C, Kind::Int, 1, Default::Int(0), 0.0, 9999.0),
    def("ORIENTATION_IS_EULER", 21100, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("ORI_DEF_WITH_G_CODE", 21102, C, Kind::Bool, 1, Default::Bool(false), 0.0, 1.0),
    def("ORI_IPO_WITH_G_CODE", 21104, C, Kind::Bool, 1, Default::Bool(false), 0.0, 1.0),
    // Online tool length offset $AA_TOFF (F2 §3.12): mode 0 absolute, 1 integrating; velocity
    // in mm/min and acceleration in m/s² of the compensating motion (defaults chosen here).
    def("TOFF_MODE", 21190, C, Kind::Int, 1, Default::Int(0), 0.0, 1.0),
    def("TOFF_VELO", 21194, C, Kind::Real, 1, Default::Real(1000.0), 0.001, 1e6),
    def("TOFF_ACCEL", 21196, C, Kind::Real, 1, Default::Real(1.0), 0.001, 1e3),
    def("POLE_ORI_MODE", 21108, C, Kind::Int, 1, Default::Int(0), 0.0, 99.0),
    def("X_AXIS_IN_OLD_X_Z_PLANE", 21110, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("ORIAX_TURN_TAB_1", 21120, C, Kind::Int, 3, Default::Indexed(default_turn_tab_1), 0.0, 3.0),
    def("ORIAX_TURN_TAB_2", 21130, C, Kind::Int, 3, Default::Indexed(default_turn_tab_2), 0.0, 3.0),
    // NC start refused while an axis is not referenced (alarm 16905).
    // MD20210: from this change of direction (degrees) G451 takes the transition circle at an
    // outer corner instead of the far intersection of the equidistants.
    def("CUTCOM_CORNER_LIMIT", 20210, C, Kind::Real, 1, Default::Real(100.0), 0.0, 150.0),
    def("CUTCOM_MAXNUM_CHECK_BLOCKS", 20240, C, Kind::Int, 1, Default::Int(3), 1.0, 100.0),
    def("CUTCOM_MAXNUM_DUMMY_BLOCKS", 20250, C, Kind::Int, 1, Default::Int(3), 0.0, 100.0),
    // Continuous-path mode and compressor (Function Manual B1): MD20170 the longest block the
    // compressor joins (mm), MD20172 the feed change it tolerates (mm/min), MD20480 which
    // tolerances G642..G645 use (units digit: 0 axial MD33100, 1 contour SD42465 for the
    // geometry axes, 2 orientation SD42466, 3 both); defaults as in the lists.
    def("COMPRESS_BLOCK_PATH_LIMIT", 20170, C, Kind::Real, 1, Default::Real(20.0), 0.0, 1e9),
    def("COMPRESS_VELO_TOL", 20172, C, Kind::Real, 1, Default::Real(60000.0), 0.0, 1e9),
    def("SMOOTHING_MODE", 20480, C, Kind::Int, 1, Default::Int(0), 0.0, 99999.0),
    // Smoothing of the orientation characteristic (F2 3.9.4, ORISON): MD20178 the longest
    // block (mm) it smooths, MD28590 the blocks it may consider (memory; below 4 ORISON has
    // no effect; a section reaches (MD28590 − 2)/2 blocks either side, `motion::orison`). Defaults from memory of the lists (not in the consulted sources).
    def("ORISON_BLOCK_PATH_LIMIT", 20178, C, Kind::Real, 1, Default::Real(50.0), 0.0, 1e9),
    def("MM_ORISON_BLOCKS", 28590, C, Kind::Int, 1, Default::Int(0), 0.0, 100.0),
    // MD20550 EXACT_POS_MODE: the exact-stop window G0 (units digit) and the other G group 1
    // functions (tens digit) use whatever is programmed: 0 the programmed G601..G603, 1 G601,
    // 2 G602, 3 G603.
    def("EXACT_POS_MODE", 20550, C, Kind::Int, 1, Default::Int(0), 0.0, 33.0),
    def("REFP_NC_START_LOCK", 20700, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    // Transformation data sets 1..10: type, axes, geometry axes, tool handling (M1 data lists).
    // Tool change (W1): 0 = T changes at once, 1 = T prepares and the M function of MD22560
    // changes. TOOL_CHANGE_TIME is this product's datum (no number; on a machine the PLC's
    // change takes this long): seconds the program waits at each change.
    def("TOOL_CHANGE_MODE", 22550, C, Kind::Int, 1, Default::Int(0), 0.0, 1.0),
    def("TOOL_CHANGE_M_CODE", 22560, C, Kind::Int, 1, Default::Int(6), 0.0, 99999.0),
    def("TOOL_CHANGE_TIME", 0, C, Kind::Real, 1, Default::Real(0.0), 0.0, 3600.0),
    // This product's datum (no number): the spindle housing round the spindle nose for the
    // stock's collision check, [0] diameter, [1] length up from the nose (mm); 0: none.
    def("SPINDLE_HOUSING", 0, C, Kind::Real, 2, Default::Real(0.0), 0.0, 1e5),
    def("TRAFO_TYPE_1", 24100, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_1", 24110, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_1", 24120, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_1", 24130, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_2", 24200, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_2", 24210, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_2", 24220, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_2", 24230, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_3", 24300, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_3", 24310, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_3", 24320, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_3", 24330, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_4", 24400, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_4", 24410, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_4", 24420, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_4", 24426, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_5", 24430, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_5", 24432, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_5", 24434, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_5", 24436, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_6", 24440, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_6", 24442, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_6", 24444, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_6", 24446, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_7", 24450, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_7", 24452, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_7", 24454, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_7", 24456, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_8", 24460, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_8", 24462, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_8", 24464, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_8", 24466, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_9", 24470, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_9", 24472, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_9", 24474, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_9", 24476, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRAFO_TYPE_10", 24480, C, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("TRAFO_AXES_IN_10", 24482, C, Kind::Int, MAX_CHANNEL_AXES, Default::Indexed(default_trafo_axes_in), 0.0, 20.0),
    def("TRAFO_GEOAX_ASSIGN_TAB_10", 24484, C, Kind::Int, 3, Default::Int(0), 0.0, 20.0),
    def("TRAFO_INCLUDES_TOOL_10", 24486, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    // Orientation transformation data set 1 (TRAFO5_/TRAFO6_, REFERENCE §6.2; set 2 = set 1 + 100).
    def("TRAFO5_PART_OFFSET_1", 24500, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_ROT_AX_OFFSET_1", 24510, C, Kind::Real, 3, Default::Real(0.0), -360.0, 360.0),
    def("TRAFO5_ROT_SIGN_IS_PLUS_1", 24520, C, Kind::Bool, 3, Default::Bool(true), 0.0, 1.0),
    def("TRAFO5_NON_POLE_LIMIT_1", 24530, C, Kind::Real, 1, Default::Real(2.0), 0.0, 90.0),
    def("TRAFO5_POLE_LIMIT_1", 24540, C, Kind::Real, 1, Default::Real(2.0), 0.0, 90.0),
    def("TRAFO5_BASE_TOOL_1", 24550, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_JOINT_OFFSET_PART_1", 24558, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_JOINT_OFFSET_1", 24560, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO6_JOINT_OFFSET_2_3_1", 24561, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_TOOL_ROT_AX_OFFSET_1", 24562, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_NUTATOR_AX_ANGLE_1", 24564, C, Kind::Real, 1, Default::Real(45.0), 0.0, 89.0),
    def("TRAFO5_AXIS1_1", 24570, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_AXIS2_1", 24572, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_AXIS3_1", 24573, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_BASE_ORIENT_1", 24574, C, Kind::Real, 3, Default::Indexed(default_unit_z), -INF, INF),
    def("TRAFO6_BASE_ORIENT_NORMAL_1", 24576, C, Kind::Real, 3, Default::Indexed(default_unit_x), -INF, INF),
    def("TRAFO5_TCARR_NO_1", 24582, C, Kind::Int, 1, Default::Int(0), 0.0, 9999.0),
    def("TRAFO5_ORIAX_ASSIGN_TAB_1", 24585, C, Kind::Int, 3, Default::Int(0), 0.0, MAX_CHANNEL_AXES as f64),
    // 7th axis of the generic 7-axis transformation: angle offset and direction. The data list
    // names set 4 as 25394/25395; sets 1 and 2 follow the 245xx/246xx pattern of TRAFO5_.
    def("TRAFO7_EXT_ROT_AX_OFFSET_1", 24594, C, Kind::Real, 1, Default::Real(0.0), -360.0, 360.0),
    def("TRAFO7_EXT_AXIS1_1", 24595, C, Kind::Real, 3, Default::Indexed(default_unit_z), -INF, INF),
    // Orientation transformation data set 2 (TRAFO5_/TRAFO6_, REFERENCE §6.2; set 2 = set 1 + 100).
    def("TRAFO5_PART_OFFSET_2", 24600, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_ROT_AX_OFFSET_2", 24610, C, Kind::Real, 3, Default::Real(0.0), -360.0, 360.0),
    def("TRAFO5_ROT_SIGN_IS_PLUS_2", 24620, C, Kind::Bool, 3, Default::Bool(true), 0.0, 1.0),
    def("TRAFO5_NON_POLE_LIMIT_2", 24630, C, Kind::Real, 1, Default::Real(2.0), 0.0, 90.0),
    def("TRAFO5_POLE_LIMIT_2", 24640, C, Kind::Real, 1, Default::Real(2.0), 0.0, 90.0),
    def("TRAFO5_BASE_TOOL_2", 24650, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_JOINT_OFFSET_PART_2", 24658, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_JOINT_OFFSET_2", 24660, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO6_JOINT_OFFSET_2_3_2", 24661, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_TOOL_ROT_AX_OFFSET_2", 24662, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_NUTATOR_AX_ANGLE_2", 24664, C, Kind::Real, 1, Default::Real(45.0), 0.0, 89.0),
    def("TRAFO5_AXIS1_2", 24670, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_AXIS2_2", 24672, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_AXIS3_2", 24673, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAFO5_BASE_ORIENT_2", 24674, C, Kind::Real, 3, Default::Indexed(default_unit_z), -INF, INF),
    def("TRAFO6_BASE_ORIENT_NORMAL_2", 24676, C, Kind::Real, 3, Default::Indexed(default_unit_x), -INF, INF),
    def("TRAFO5_TCARR_NO_2", 24682, C, Kind::Int, 1, Default::Int(0), 0.0, 9999.0),
    def("TRAFO5_ORIAX_ASSIGN_TAB_2", 24685, C, Kind::Int, 3, Default::Int(0), 0.0, MAX_CHANNEL_AXES as f64),
    def("TRAFO7_EXT_ROT_AX_OFFSET_2", 24694, C, Kind::Real, 1, Default::Real(0.0), -360.0, 360.0),
    def("TRAFO7_EXT_AXIS1_2", 24695, C, Kind::Real, 3, Default::Indexed(default_unit_z), -INF, INF),
    // TRAANG data sets 1 and 2 (angle of the inclined axis, base tool, reserves of the parallel axis).
    def("TRAANG_ANGLE_1", 24700, C, Kind::Real, 1, Default::Real(0.0), -90.0, 90.0),
    def("TRAANG_BASE_TOOL_1", 24710, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAANG_PARALLEL_VELO_RES_1", 24720, C, Kind::Real, 1, Default::Real(0.0), 0.0, 1.0),
    def("TRAANG_PARALLEL_ACCEL_RES_1", 24721, C, Kind::Real, 1, Default::Real(0.0), 0.0, 1.0),
    def("TRAANG_ANGLE_2", 24750, C, Kind::Real, 1, Default::Real(0.0), -90.0, 90.0),
    def("TRAANG_BASE_TOOL_2", 24760, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRAANG_PARALLEL_VELO_RES_2", 24770, C, Kind::Real, 1, Default::Real(0.0), 0.0, 1.0),
    def("TRAANG_PARALLEL_ACCEL_RES_2", 24771, C, Kind::Real, 1, Default::Real(0.0), 0.0, 1.0),
    // TRACYL data sets 1 and 2.
    def("TRACYL_ROT_AX_OFFSET_1", 24800, C, Kind::Real, 1, Default::Real(0.0), -360.0, 360.0),
    def("TRACYL_ROT_AX_FRAME_1", 24805, C, Kind::Int, 1, Default::Int(0), 0.0, 2.0),
    def("TRACYL_DEFAULT_MODE_1", 24808, C, Kind::Int, 1, Default::Int(0), 0.0, 1.0),
    def("TRACYL_ROT_SIGN_IS_PLUS_1", 24810, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRACYL_BASE_TOOL_1", 24820, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRACYL_ROT_AX_OFFSET_2", 24850, C, Kind::Real, 1, Default::Real(0.0), -360.0, 360.0),
    def("TRACYL_ROT_AX_FRAME_2", 24855, C, Kind::Int, 1, Default::Int(0), 0.0, 2.0),
    def("TRACYL_DEFAULT_MODE_2", 24858, C, Kind::Int, 1, Default::Int(0), 0.0, 1.0),
    def("TRACYL_ROT_SIGN_IS_PLUS_2", 24860, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRACYL_BASE_TOOL_2", 24870, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    // TRANSMIT data sets 1 and 2.
    def("TRANSMIT_ROT_AX_OFFSET_1", 24900, C, Kind::Real, 1, Default::Real(0.0), -360.0, 360.0),
    def("TRANSMIT_ROT_AX_FRAME_1", 24905, C, Kind::Int, 1, Default::Int(0), 0.0, 2.0),
    def("TRANSMIT_ROT_SIGN_IS_PLUS_1", 24910, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRANSMIT_POLE_SIDE_FIX_1", 24911, C, Kind::Int, 1, Default::Int(0), 0.0, 2.0),
    def("TRANSMIT_BASE_TOOL_1", 24920, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    def("TRANSMIT_ROT_AX_OFFSET_2", 24950, C, Kind::Real, 1, Default::Real(0.0), -360.0, 360.0),
    def("TRANSMIT_ROT_AX_FRAME_2", 24955, C, Kind::Int, 1, Default::Int(0), 0.0, 2.0),
    def("TRANSMIT_ROT_SIGN_IS_PLUS_2", 24960, C, Kind::Bool, 1, Default::Bool(true), 0.0, 1.0),
    def("TRANSMIT_POLE_SIDE_FIX_2", 24961, C, Kind::Int, 1, Default::Int(0), 0.0, 2.0),
    def("TRANSMIT_BASE_TOOL_2", 24970, C, Kind::Real, 3, Default::Real(0.0), -INF, INF),
    // Chained transformations: the data-set numbers of the members of chain 1..4.
    def("TRACON_CHAIN_1", 24995, C, Kind::Int, 4, Default::Int(0), 0.0, MAX_TRAFO_SETS as f64),
    def("TRACON_CHAIN_2", 24996, C, Kind::Int, 4, Default::Int(0), 0.0, MAX_TRAFO_SETS as f64),
    def("TRACON_CHAIN_3", 24997, C, Kind::Int, 4, Default::Int(0), 0.0, MAX_TRAFO_SETS as f64),
    def("TRACON_CHAIN_4", 24998, C, Kind::Int, 4, Default::Int(0), 0.0, MAX_TRAFO_SETS as f64),
    // Program runtimes and workpiece counters (`process_counting.rs`).
    def("PROCESSTIMER_MODE", 27860, C, Kind::Int, 1, Default::Int(0x177), 0.0, 2047.0),
    def("PART_COUNTER", 27880, C, Kind::Int, 1, Default::Int(0x901), 0.0, 268_435_455.0),
    def("PART_COUNTER_MCODE", 27882, C, Kind::Int, 3, Default::Int(2), 0.0, 99999.0),
    def("MM_NUM_USER_FRAMES", 28080, C, Kind::Int, 1, Default::Int(5), 5.0, 100.0),
    // Synchronized actions' memory in elements (`interp/synchronized/elements.rs`) and data
    // (`sync_sizes.rs`): `$AC_PARAM`, `$AC_MARKER`, `$AC_TIMER`.
    def("MM_NUM_SYNC_ELEMENTS", 28250, C, Kind::Int, 1, Default::Int(159), 0.0, 32000.0),
    def("MM_NUM_AC_PARAM", 28254, C, Kind::Int, 1, Default::Int(50), 0.0, 20000.0),
    def("MM_NUM_AC_MARKER", 28256, C, Kind::Int, 1, Default::Int(8), 0.0, 20000.0),
    def("MM_NUM_AC_TIMER", 28258, C, Kind::Int, 1, Default::Int(8), 0.0, 10000.0),
    def("MM_NUM_BASE_FRAMES", 28081, C, Kind::Int, 1, Default::Int(1), 0.0, 16.0),
    def("IS_ROT_AX", 30300, A, Kind::Bool, 1, Default::Bool(false), 0.0, 1.0),
    def("ROT_IS_MODULO", 30310, A, Kind::Bool, 1, Default::Bool(false), 0.0, 1.0),
    // MD30460 axis functions; bit 2: the axis may be diameter-programmed on its own (DIAMONA[ax]..).
    def("BASE_FUNCTION_MASK", 30460, A, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("MODULO_RANGE", 30330, A, Kind::Real, 1, Default::Real(360.0), 1.0, 360_000.0),
    def("MODULO_RANGE_START", 30340, A, Kind::Real, 1, Default::Real(0.0), -360_000.0, 360_000.0),
    // G75 FP=n: the fixed points of the axis (MD30600, 4 per axis) and how many are in use
    // (MD30610, 0 by default: G75 is refused until the data define one).
    def("FIX_POINT_POS", 30600, A, Kind::Real, 4, Default::Real(0.0), -1e9, 1e9),
    def("NUM_FIX_POINT_POS", 30610, A, Kind::Int, 1, Default::Int(0), 0.0, 4.0),
    // Distance of one increment (INC1, handwheel detent): [0] metric system, [1] inch system.
    def("JOG_INCR_WEIGHT", 31090, A, Kind::Real, 2, Default::Real(0.001), 1e-6, 1000.0),
    // Linear axes: mm/min and m/s²; rotary axes: rev/min and rev/s², as on the control.
    def("MAX_AX_VELO", 32000, A, Kind::Real, 1, Default::RealByAxisType { linear: 10000.0, rotary: 27.77 }, 1e-6, 1e9),
    def(
        "JOG_VELO_RAPID",
        32010,
        A,
        Kind::Real,
        1,
        Default::RealByAxisType { linear: 10000.0, rotary: 27.77 },
        0.0,
        1e9,
    ),
    // MD32060: the feed of a positioning axis (POS/POSA, command axes) while no FA[ax] is programmed.
    def("POS_AX_VELO", 32060, A, Kind::Real, 1, Default::RealByAxisType { linear: 10000.0, rotary: 27.77 }, 0.0, 1e9),
    def("JOG_VELO", 32020, A, Kind::Real, 1, Default::RealByAxisType { linear: 2000.0, rotary: 5.55 }, 0.0, 1e9),
    // Servo: position control gain Kv in (m/min)/mm per parameter set (set 0 is the one in
    // use); Kv = 1 means a following error of 1 mm at 1 m/min without feed-forward.
    def("POSCTRL_GAIN", 32200, A, Kind::Real, 6, Default::Real(1.0), 1e-3, 2000.0),
    // Per dynamic response mode (G group 59): [0] DYNNORM, [1] DYNPOS, [2] DYNROUGH,
    // [3] DYNSEMIFIN, [4] DYNFINISH. `$MA_MAX_AX_ACCEL[X]` names [0].
    def(
        "MAX_AX_ACCEL",
        32300,
        A,
        Kind::Real,
        DYN_MODES,
        Default::RealByAxisType { linear: 1.0, rotary: 2.77 },
        1e-6,
        1e6,
    ),
    def("MAX_ACCEL_OVL_FACTOR", 32310, A, Kind::Real, DYN_MODES, Default::Real(1.2), 1.0, 10.0),
    // Axial jerk under SOFT: m/s³ (rotary rev/s³), per dynamic response mode as MAX_AX_ACCEL.
    def(
        "MAX_AX_JERK",
        32431,
        A,
        Kind::Real,
        DYN_MODES,
        Default::RealByAxisType { linear: 1000.0, rotary: 2777.0 },
        1e-6,
        1e9,
    ),
    // Jerk at block transitions without constant curvature (Function Manual B2): m/s³, the
    // seam's limit under SOFT where it exceeds MD32431; 0 (NCTwin's reset value): MD32431.
    def("PATH_TRANS_JERK_LIM", 32432, A, Kind::Real, 1, Default::Real(0.0), 0.0, 1e9),
    // Feed-forward: 0 none, 1/3 speed, 2/4 torque feed-forward (the model treats 1..4 alike);
    // activation 0: MD32620 always, 1: FFWON/FFWOF at once, 2: FFWON/FFWOF at the next standstill.
    def("FFW_MODE", 32620, A, Kind::Int, 1, Default::Int(1), 0.0, 4.0),
    def("FFW_ACTIVATION_MODE", 32630, A, Kind::Int, 1, Default::Int(1), 0.0, 2.0),
    // MD33100 COMPRESS_POS_TOL: how far an axis may leave the programmed path under G642..G645
    // and the compressors (mm or degrees).
    def("COMPRESS_POS_TOL", 33100, A, Kind::Real, 1, Default::Real(0.1), 1e-9, 1e9),
    // MD33120 PATH_TRANS_POS_TOL: G645's deviation at tangential transitions with a curvature
    // jump (mm or degrees).
    def("PATH_TRANS_POS_TOL", 33120, A, Kind::Real, 1, Default::Real(0.005), 1e-9, 1e9),
    // Reference point approach (incremental measuring system), see channel/reference/approach.rs.
    // Velocities in mm/min (rotary rev/min) with the control's defaults.
    def("REFP_CAM_DIR_IS_MINUS", 34010, A, Kind::Bool, 1, Default::Bool(false), 0.0, 1.0),
    def(
        "REFP_VELO_SEARCH_CAM",
        34020,
        A,
        Kind::Real,
        1,
        Default::RealByAxisType { linear: 5000.0, rotary: 13.89 },
        0.0,
        1e9,
    ),
    def(
        "REFP_VELO_SEARCH_MARKER",
        34040,
        A,
        Kind::Real,
        1,
        Default::RealByAxisType { linear: 300.0, rotary: 0.83 },
        0.0,
        1e9,
    ),
    def("REFP_VELO_POS", 34070, A, Kind::Real, 1, Default::RealByAxisType { linear: 10000.0, rotary: 27.77 }, 0.0, 1e9),
    def("REFP_MOVE_DIST", 34080, A, Kind::Real, 1, Default::Real(-2.0), -1e9, 1e9),
    def("REFP_MOVE_DIST_CORR", 34090, A, Kind::Real, 1, Default::Real(0.0), -1e9, 1e9),
    // On the control a measured display value (cam to zero mark); the simulation places the cam
    // edge this far before the zero mark. Default chosen: 10 mm (or degrees).
    def("REFP_CAM_MARKER_DIST", 34093, A, Kind::Real, 1, Default::Real(10.0), 0.0, 1e9),
    def("REFP_SET_POS", 34100, A, Kind::Real, 4, Default::Real(0.0), -1e9, 1e9),
    // Channel-specific referencing order; -1: the axis need not be referenced for NC start.
    def("REFP_CYCLE_NR", 34110, A, Kind::Int, 1, Default::Int(0), -1.0, 31.0),
    // 1 (the control's default): reference cam and zero mark; 0: no approach, referenced at once.
    def("ENC_REFP_MODE", 34200, A, Kind::Int, 1, Default::Int(1), 0.0, 8.0),
    // 2: absolute encoder adjusted, the axis is referenced from power on. The control's default
    // is 0 (not adjusted); the simulation starts referenced unless this is set below 2.
    def("ENC_REFP_STATE", 34210, A, Kind::Int, 1, Default::Int(2), 0.0, 2.0),
    def("SPIND_ASSIGN_TO_MACHAX", 35000, A, Kind::Int, 1, Default::Int(0), 0.0, 20.0),
    // Spindle data (S1). Defaults from memory of the control's lists (not in the seeds):
    // MD35100 highest spindle speed (rev/min); MD35130 highest speed per gear stage 0..5
    // (stage 1 is the one NCTwin runs: no gear stages are modelled); MD35200 acceleration in
    // speed control per gear stage (rev/s²); MD35300 speed of SPOS/M19 positioning (rev/min).
    def("SPIND_VELO_LIMIT", 35100, A, Kind::Real, 1, Default::Real(10000.0), 0.0, 1e6),
    // Gear stages (machine_data/gears.rs): MD35010 bit 0 enables them, MD35090 stages in use,
    // MD35110/35120 M40's switching range, MD35140 the lowest speed per stage.
    def("GEAR_STEP_CHANGE_ENABLE", 35010, A, Kind::Int, 1, Default::Int(0), 0.0, 65535.0),
    def("NUM_GEAR_STEPS", 35090, A, Kind::Int, 1, Default::Int(5), 1.0, 5.0),
    def("GEAR_STEP_MAX_VELO", 35110, A, Kind::Real, 6, Default::Real(10000.0), 0.0, 1e6),
    def("GEAR_STEP_MIN_VELO", 35120, A, Kind::Real, 6, Default::Real(0.0), 0.0, 1e6),
    def("GEAR_STEP_MAX_VELO_LIMIT", 35130, A, Kind::Real, 6, Default::Real(10000.0), 0.0, 1e6),
    def("GEAR_STEP_MIN_VELO_LIMIT", 35140, A, Kind::Real, 6, Default::Real(0.0), 0.0, 1e6),
    def("GEAR_STEP_SPEEDCTRL_ACCEL", 35200, A, Kind::Real, 6, Default::Real(30.0), 1e-3, 1e6),
    // DRIVE's knee-shaped acceleration (Function Manual B2): the switching speed as a fraction
    // of MD32000, the reduction reached at MD32000, the shape (0 constant, 1 hyperbolic,
    // 2 linear). The defaults reduce nothing.
    def("ACCEL_REDUCTION_SPEED_POINT", 35220, A, Kind::Real, 1, Default::Real(1.0), 0.0, 1.0),
    def("ACCEL_REDUCTION_FACTOR", 35230, A, Kind::Real, 1, Default::Real(0.0), 0.0, 0.95),
    def("ACCEL_REDUCTION_TYPE", 35242, A, Kind::Int, 1, Default::Int(1), 0.0, 2.0),
    def("SPIND_POSCTRL_VELO", 35300, A, Kind::Real, 1, Default::Real(500.0), 1e-3, 1e6),
    // Exact-stop windows of G602 (coarse, MD36000) and G601 (fine, MD36010), mm or degrees.
    def("STOP_LIMIT_COARSE", 36000, A, Kind::Real, 1, Default::Real(0.04), 0.0, 1e9),
    def("STOP_LIMIT_FINE", 36010, A, Kind::Real, 1, Default::Real(0.01), 0.0, 1e9),
    def("POS_LIMIT_MINUS", 36100, A, Kind::Real, 1, Default::Real(-1e8), -INF, INF),
    def("POS_LIMIT_PLUS", 36110, A, Kind::Real, 1, Default::Real(1e8), -INF, INF),
    // Setting data. SD42650 CART_JOG_MODE: reference systems of Cartesian manual travel, bits
    // 0/1/2 translation in BCS/WCS/TCS, bits 8/9/10 orientation in BCS/WCS/TCS (bit layout from
    // memory, REFERENCE §9.4). SD42660 ORI_JOG_MODE: 0 = as the transformation defines, 1 Euler
    // ZX'Z'', 2 RPY XY'Z'', 3 RPY ZY'X'', 4/5 ORIAX_TURN_TAB_1/2 (seed 003, F2 3.8).
    // SD42465/SD42466: contour (mm) and orientation (degrees) tolerance of G642..G645 when
    // MD20480 SMOOTHING_MODE selects them; CTOL=/OTOL= override them in a program.
    sd("SMOOTH_CONTUR_TOL", 42465, C, Kind::Real, Default::Real(0.05), 0.0, 1e9),
    sd("SMOOTH_ORI_TOL", 42466, C, Kind::Real, Default::Real(0.05), 0.0, 360.0),
    // SD42100 DRY_RUN_FEED (mm/min) and SD42101 DRY_RUN_FEED_MODE: the feed of DRY and how it
    // combines with the programmed one (0 max, 1 min, 2 direct; 10/11/12 the same but threads
    // as programmed; `interp/program_control.rs`).
    sd("DRY_RUN_FEED", 42100, C, Kind::Real, Default::Real(5000.0), 0.0, INF),
    sd("DRY_RUN_FEED_MODE", 42101, C, Kind::Int, Default::Int(0), 0.0, 12.0),
    // SD42678/SD42680: ORISON's largest angle from the programmed orientation (degrees) and
    // the longest path (mm) one step's smoothing spans (828D Programming Manual 6.7 names SD42680
    // ORISON_DIST); 0 smooths nothing. Defaults from memory.
    sd("ORISON_TOL", 42678, C, Kind::Real, Default::Real(0.0), 0.0, 90.0),
    sd("ORISON_DIST", 42680, C, Kind::Real, Default::Real(0.0), 0.0, 1e9),
    sd("CART_JOG_MODE", 42650, C, Kind::Int, Default::Int(0), 0.0, 1799.0),
    sd("ORI_JOG_MODE", 42660, C, Kind::Int, Default::Int(0), 0.0, 5.0),
    // SD41610/SD41611: the largest change CORRTRAFO makes to an offset vector (mm) / turns a
    // direction (degrees) unless Corr_Mode's thousands digit suppresses the check. SD41611 and
    // its meaning are the manual's (K12 §4.3.2); SD41610's number and both defaults are this
    // product's choice (from memory / not in the consulted sources).
    sd("FRAME_OFFSET_INCR_PROG", 42440, C, Kind::Bool, Default::Bool(true), 0.0, 1.0),
    sd("TOOL_OFFSET_INCR_PROG", 42442, C, Kind::Bool, Default::Bool(true), 0.0, 1.0),
    sd("CORR_TRAFO_LIN_MAX", 41610, N, Kind::Real, Default::Real(1.0), 0.0, INF),
    sd("CORR_TRAFO_DIR_MAX", 41611, N, Kind::Real, Default::Real(1.0), 0.0, 180.0),
    // SD42974: add the fine offsets $TC_CARR41.. to the toolholder vectors.
    // SD43400..43430: working-area limitation per axis (G25/G26 with axes write the limits;
    // WALIMON/WALIMOF, `interp/path_control/work_area.rs`); disabled by default.
    sd("WORKAREA_PLUS_ENABLE", 43400, A, Kind::Bool, Default::Bool(false), 0.0, 1.0),
    sd("WORKAREA_MINUS_ENABLE", 43410, A, Kind::Bool, Default::Bool(false), 0.0, 1.0),
    sd("WORKAREA_LIMIT_PLUS", 43420, A, Kind::Real, Default::Real(1e8), -1e9, 1e9),
    sd("WORKAREA_LIMIT_MINUS", 43430, A, Kind::Real, Default::Real(-1e8), -1e9, 1e9),
    sd("TOCARR_FINE_CORRECTION", 42974, C, Kind::Bool, Default::Bool(false), 0.0, 1.0),
    // SD42980 TOFRAME_MODE: 0/1 as MD21110; 2000 X/Y compromise, 2001 new X in the old X-Z
    // plane, 2002 new Y in the old Y-Z plane (808D list manual p.360). Default 2000, the value
    // the IM9 commissioning manual (12/2017 p.566) prescribes for swivelling.
    sd("TOFRAME_MODE", 42980, C, Kind::Int, Default::Int(2000), 0.0, 2002.0),
    // Cycle machine datum MD55410 MILL_SWIVEL_ALARM_MASK: bit 0 shows CYCLE800 alarm 61186,
    // bit 1 alarm 61187 (IM9 06/2019 p.581).
    def("MILL_SWIVEL_ALARM_MASK", 55410, C, Kind::Int, 1, Default::Int(0), 0.0, 3.0),
];

/// Looks a datum up by its full name (`$MC_TRAFO_TYPE_1`).
pub fn lookup(full_name: &str) -> Option<&'static Def> {
    let (prefix, rest) = full_name.split_at_checked(4)?;
    let (setting, scope) = match prefix {
        "$MN_" => (false, Scope::Nck),
        "$MC_" => (false, Scope::Channel),
        "$MA_" => (false, Scope::Axis),
        "$SN_" => (true, Scope::Nck),
        "$SC_" => (true, Scope::Channel),
        "$SA_" => (true, Scope::Axis),
        _ => return None,
    };
    DEFS.iter().find(|d| d.name == rest && d.scope == scope && d.setting == setting)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_default_lies_in_its_range() {
        for d in DEFS {
            for i in 0..d.len {
                for rotary in [false, true] {
                    if let Some(v) = d.default_value(i, rotary).as_f64() {
                        assert!(v >= d.min && v <= d.max || d.kind == Kind::Str, "{} [{i}] = {v}", d.name);
                    }
                }
            }
        }
    }

    #[test]
    fn names_are_unique() {
        for (i, a) in DEFS.iter().enumerate() {
            assert!(DEFS[i + 1..].iter().all(|b| b.full_name() != a.full_name()), "{}", a.name);
        }
    }

    #[test]
    fn lookup_needs_the_right_prefix() {
        assert!(lookup("$MA_IS_ROT_AX").is_some());
        assert!(lookup("$MC_IS_ROT_AX").is_none());
        assert!(lookup("$MA_NO_SUCH_DATUM").is_none());
    }
}
