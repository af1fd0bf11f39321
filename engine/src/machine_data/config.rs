//! The activated, typed configuration derived from [`MachineData`]: what the interpreter, the
//! planner and the channel read. Built once per activation (session start, reset after new data).

use std::collections::BTreeMap;

use super::trafo::{self, TrafoDataSet, TrafoKind};
use super::traori::OriSettings;
use super::{EdgeParams, FrameComponent, FrameFamily, MachineData, registry};

/// Inconsistent machine data found at activation; `datum` names the datum to blame.
#[derive(Debug, Clone, PartialEq)]
pub struct ActivationError {
    pub datum: Option<&'static str>,
    pub message: String,
}

fn fail<T>(datum: &'static str, message: String) -> Result<T, ActivationError> {
    Err(ActivationError { datum: Some(datum), message })
}

/// One machine axis with its dynamics in engine units (mm or degrees, seconds).
#[derive(Debug, Clone, PartialEq)]
pub struct MachineAxis {
    pub name: String,
    pub rotary: bool,
    /// Modulo range `(start, size)` for modulo rotary axes.
    pub modulo: Option<(f64, f64)>,
    /// Spindle number when the axis is a spindle (`$MA_SPIND_ASSIGN_TO_MACHAX`).
    pub spindle: Option<u32>,
    /// A spindle without axis function: its channel axis has no name
    /// (`$MC_AXCONF_CHANAX_NAME_TAB` empty), so programs reach it only through S, M3/M4/M5,
    /// SPOS and the like, and the state shows it under `spindles` as `S<n>`, never among the
    /// positions (the tool spindle of a mill, which the contract lists as X, Y, Z).
    pub spindle_only: bool,
    /// MD35300 `$MA_SPIND_POSCTRL_VELO`: speed of positioning in position control (SPOS,
    /// M19), rev/min.
    pub spindle_posctrl_velo: f64,
    /// Maximum velocity in mm/s or deg/s.
    pub max_velocity: f64,
    /// Maximum acceleration in mm/s² or deg/s².
    pub max_accel: f64,
    /// Factor by which a velocity jump at a block transition may exceed `max_accel` for one cycle.
    pub accel_overload: f64,
    /// Per dynamic response mode acceleration and jerk, position loop and feed-forward.
    pub dynamics: super::dynamics::AxisDynamics,
    /// JOG velocities in mm/s or deg/s.
    pub jog_velocity: f64,
    pub jog_rapid_velocity: f64,
    /// MD32060 `$MA_POS_AX_VELO`: feed of a positioning axis without `FA[ax]`, mm/s or deg/s.
    pub pos_velocity: f64,
    /// Software limit switches (MCS).
    pub limit_minus: f64,
    pub limit_plus: f64,
}

/// One channel axis and the machine axis it drives.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelAxis {
    pub name: String,
    pub machine_axis: usize,
}

/// The typed configuration of one channel.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineConfig {
    /// Interpolation cycle in seconds (`$MN_SYSCLOCK_CYCLE_TIME * $MN_IPO_SYSCLOCK_TIME_RATIO`).
    pub ipo_cycle: f64,
    /// The machine axes used by the channel, in machine-axis-number order.
    pub machine_axes: Vec<MachineAxis>,
    /// Channel axes in channel order; `machine_axis` indexes `machine_axes`.
    pub channel_axes: Vec<ChannelAxis>,
    /// Channel axis index of the 1st/2nd/3rd geometry axis (no transformation active).
    pub geo_axes: [Option<usize>; 3],
    pub geo_names: [String; 3],
    /// Channel axis of the master spindle, if the channel has one.
    pub master_spindle: Option<usize>,
    /// Channel axis of the transverse axis (MD20100 `$MC_DIAMETER_AX_DEF`), if one is named:
    /// the axis of diameter programming and constant cutting speed.
    pub transverse_axis: Option<usize>,
    /// Reset position of G group 29 (MD20150 `$MC_GCODE_RESET_VALUES[28]`): 1 DIAMOF,
    /// 2 DIAMON, 3 DIAM90, 4 DIAMCYCOF.
    pub diameter_reset: u8,
    /// Channel axes released for axis-specific diameter programming (DIAMONA[ax], DIAMCHAN):
    /// MD30460 `$MA_BASE_FUNCTION_MASK` bit 2, one bit per channel axis.
    pub diameter_axes: u32,
    /// MD18102 `$MN_MM_TYPE_OF_CUTTING_EDGE` = 1: flat D numbers (`flat_d.rs`).
    pub flat_d: bool,
    /// The gear stages of each spindle by channel axis (`gears.rs`).
    pub gears: BTreeMap<usize, super::gears::Gears>,
    /// Reset position of G group 6 (MD20150 `$MC_GCODE_RESET_VALUES[5]`): 1 G17, 2 G18, 3 G19.
    pub plane_reset: u8,
    /// Cutting edges `(T, D)` → `$TC_DP1..25`.
    pub tools: BTreeMap<(u32, u32), EdgeParams>,
    /// The tool list: names, duplo numbers, states, magazines and places.
    pub tool_list: std::sync::Arc<super::tools_list::ToolList>,
    /// Tool change: MD22550 TOOL_CHANGE_MODE (0 T changes, 1 M6 changes), MD22560
    /// TOOL_CHANGE_M_CODE and the time a change takes.
    pub tool_change: ToolChange,
    /// Orientable toolholders `$TC_CARR..[m]` by number m.
    pub carriers: BTreeMap<u32, super::Carrier>,
    /// SD42980 TOFRAME_MODE.
    pub toframe_mode: i64,
    /// SD42100 `$SC_DRY_RUN_FEED` (mm/min) and SD42101 `$SC_DRY_RUN_FEED_MODE`: DRY's feed.
    pub dry_run_feed: (f64, i64),
    /// MD55410 MILL_SWIVEL_ALARM_MASK (CYCLE800 alarms 61186/61187).
    pub swivel_alarm_mask: i64,
    /// Settable frames G500, G54.. (`$P_UIFR[n]`).
    pub work_offsets: Vec<FrameData>,
    /// Channel basic frames (`$P_CHBFR[n]`), chained in order into `$P_ACTBFRAME`.
    pub base_frames: Vec<FrameData>,
    /// NCU-global basic frames (`$P_NCBFR[n]`, MD18602), chained before the channel ones.
    pub ncu_base_frames: Vec<FrameData>,
    /// MD10600 FRAME_ANGLE_INPUT_MODE: how frame rotation angles are written and read.
    pub frame_angles: FrameAngles,
    /// Configured transformation data sets in data-set order (`$MC_TRAFO_TYPE_1..10`).
    pub trafos: Vec<TrafoDataSet>,
    /// How orientations are programmed and interpolated (MD21090..21130).
    pub ori: OriSettings,
    /// The kinematic chain data `$NK_`/`$NT_` as stored (programs read them; the built
    /// transformations are in `trafos`), with MD18880 and MD18866 bounding their indices.
    pub kin: super::chains::KinData,
    pub kin_counts: (usize, usize),
    /// What rebuilding one chain record needs (CORRTRAFO): root name and pole defaults.
    pub kin_build: super::chains::BuildContext,
    /// SD41610/SD41611: the limits CORRTRAFO monitors (setting data, acting at once).
    pub corr_limits: super::chains::correct::Limits,
    /// SD42440/SD42442: whether the first incremental move after a change of frame (work
    /// offset) or tool offset also travels that change (setting data, acting at once).
    pub incremental_travels: IncrementalTravels,
    /// Which transformation is active after reset and program end.
    pub reset_trafo: ResetTrafo,
    /// MD20250 CUTCOM_MAXNUM_DUMMY_BLOCKS: blocks without motion in the compensation plane the
    /// radius compensation looks across before alarm 10762.
    pub cutcom_max_dummy_blocks: usize,
    /// MD20240 CUTCOM_MAXNUM_CHECK_BLOCKS: blocks the bottleneck detection examines.
    pub cutcom_max_check_blocks: usize,
    /// MD20210 CUTCOM_CORNER_LIMIT in radians: from this change of direction at an outer
    /// corner G451 inserts the transition circle.
    pub cutcom_corner_limit: f64,
    /// Path jerk and the reset values of the dynamics G groups 21, 24, 59.
    pub dynamics: super::dynamics::ChannelDynamics,
    /// Tolerances of continuous-path mode, exact-stop windows and compressor limits.
    pub path_control: super::path_control::PathControlData,
    /// Sizes of the synchronized actions' data and the NCK signals (MD28254.., MD10300..).
    pub sync_sizes: super::sync_sizes::SyncSizes,
    /// Which program runtimes and workpiece counters run, and how (MD27860, MD27880/27882).
    pub process_counting: super::process_counting::ProcessCounting,
}

/// How a tool change is triggered and how long it takes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ToolChange {
    /// MD22550 TOOL_CHANGE_MODE = 1: T prepares, the M function of MD22560 changes.
    pub with_m: bool,
    /// MD22560 TOOL_CHANGE_M_CODE (6).
    pub m_code: u32,
    /// `$MC_TOOL_CHANGE_TIME` (this product's datum): seconds the change takes.
    pub seconds: f64,
    /// The subprogram MD10715/MD10716 have the change M function call instead (upper case).
    pub m_cycle: Option<String>,
}

/// MD10600 FRAME_ANGLE_INPUT_MODE: the convention of frame rotation angles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrameAngles {
    /// 1: RPY, rotations about Z, then the new Y, then the new X.
    #[default]
    Rpy,
    /// 2: Euler, rotations about Z, then the new X, then the new Z.
    Euler,
}

/// The transformation after reset and program end (MD20110 RESET_MODE_MASK bits 0 and 7,
/// MD20140 TRAFO_RESET_VALUE, MD20144 TRAFO_MODE_MASK bit 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ResetTrafo {
    /// RESET_MODE_MASK bits 0 and 7 set: the active transformation stays.
    pub keep_active: bool,
    /// Data-set number selected at reset (TRAFO_RESET_VALUE, 0 = none).
    pub data_set: Option<usize>,
    /// TRAFO_MODE_MASK bit 0: that data set is persistent, TRAFOOF returns to it.
    pub persistent: bool,
}

impl ResetTrafo {
    fn build(md: &MachineData, trafos: &[TrafoDataSet]) -> Result<ResetTrafo, ActivationError> {
        let mask = md.num("$MC_RESET_MODE_MASK", 0, 0) as u32;
        let value = md.num("$MC_TRAFO_RESET_VALUE", 0, 0) as usize;
        let persistent = md.num("$MC_TRAFO_MODE_MASK", 0, 0) as u32 & 1 != 0;
        let reset_name = md.string("$MC_TRAFO_RESET_NAME", 0);
        let data_set = if reset_name.is_empty() {
            (value != 0).then_some(value)
        } else {
            // MD20142 names a transformation defined by kinematic chains; it wins over MD20140.
            let named = trafos.iter().find(|s| s.chain.as_ref().is_some_and(|c| c.name == reset_name));
            let Some(set) = named else {
                return fail(
                    "TRAFO_RESET_NAME",
                    format!(
                        "$MC_TRAFO_RESET_NAME=\"{reset_name}\" names no transformation defined by kinematic chains of a modelled type"
                    ),
                );
            };
            Some(set.number)
        };
        if let Some(n) = data_set {
            let Some(set) = trafos.iter().find(|s| s.number == n) else {
                return fail("TRAFO_RESET_VALUE", format!("$MC_TRAFO_RESET_VALUE={n}: data set {n} is not configured"));
            };
            if set.kind == TrafoKind::Tracyl {
                let (datum, what) = match reset_name.is_empty() {
                    true => ("TRAFO_RESET_VALUE", format!("$MC_TRAFO_RESET_VALUE={n}")),
                    false => ("TRAFO_RESET_NAME", format!("$MC_TRAFO_RESET_NAME=\"{reset_name}\"")),
                };
                return fail(datum, format!("{what}: TRACYL needs a working diameter and cannot be selected by reset"));
            }
        }
        // Alarm 14404: the persistent transformation needs reset mode bit 0 = 1, bit 7 = 0 and
        // MD20118 GEOAX_CHANGE_RESET = TRUE (Transformations FM, persistent transformation).
        if persistent {
            let problem = if data_set.is_none() {
                Some("$MC_TRAFO_RESET_VALUE names no data set")
            } else if mask & 1 == 0 || mask & 0x80 != 0 {
                Some("$MC_RESET_MODE_MASK needs bit 0 = 1 and bit 7 = 0")
            } else if md.num("$MC_GEOAX_CHANGE_RESET", 0, 0) == 0.0 {
                Some("$MC_GEOAX_CHANGE_RESET must be TRUE")
            } else {
                None
            };
            if let Some(p) = problem {
                return fail("TRAFO_MODE_MASK", format!("alarm 14404: persistent transformation: {p}"));
            }
        }
        Ok(ResetTrafo { keep_active: mask & 1 != 0 && mask & 0x80 != 0, data_set, persistent })
    }
}

/// A stored frame as the data management holds it, by channel axis: translation (coarse plus
/// fine), rotation of the geometry axes (RPY angles about X, Y, Z in degrees), scale and mirror.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameData {
    pub trans: Vec<f64>,
    pub rot: [f64; 3],
    pub scale: Vec<f64>,
    pub mirror: Vec<bool>,
}

impl FrameData {
    /// The neutral frame for `n` channel axes.
    pub fn neutral(n: usize) -> FrameData {
        FrameData { trans: vec![0.0; n], rot: [0.0; 3], scale: vec![1.0; n], mirror: vec![false; n] }
    }

    /// True for a frame that changes nothing.
    pub fn is_neutral(&self) -> bool {
        self.trans.iter().all(|t| *t == 0.0)
            && self.rot == [0.0; 3]
            && self.scale.iter().all(|s| *s == 1.0)
            && !self.mirror.iter().any(|m| *m)
    }
}

impl MachineConfig {
    pub(super) fn build(md: &MachineData) -> Result<Self, ActivationError> {
        let ipo_cycle = md.num("$MN_SYSCLOCK_CYCLE_TIME", 0, 0) * md.num("$MN_IPO_SYSCLOCK_TIME_RATIO", 0, 0);
        if ipo_cycle > 0.1 {
            return fail("IPO_SYSCLOCK_TIME_RATIO", format!("IPO cycle {:.4} s is longer than 100 ms", ipo_cycle));
        }
        let gaps_allowed = md.num("$MN_ENABLE_CHAN_AX_GAP", 0, 0) != 0.0;

        // Channel axes and the machine axes they use.
        let mut machine_numbers = Vec::new();
        let mut channel_slots = Vec::new();
        for k in 0..registry::MAX_CHANNEL_AXES {
            let m = md.num("$MC_AXCONF_MACHAX_USED", 0, k) as usize;
            if m == 0 {
                if gaps_allowed {
                    continue;
                }
                break;
            }
            if machine_numbers.contains(&m) {
                return fail(
                    "AXCONF_MACHAX_USED",
                    format!("$MC_AXCONF_MACHAX_USED[{k}]: machine axis {m} is used twice"),
                );
            }
            machine_numbers.push(m);
            channel_slots.push(k);
        }
        if channel_slots.is_empty() {
            return fail("AXCONF_MACHAX_USED", "$MC_AXCONF_MACHAX_USED assigns no machine axis to the channel".into());
        }
        let mut order = machine_numbers.clone();
        order.sort_unstable();
        let machine_axes = order.iter().map(|&m| machine_axis(md, m - 1)).collect::<Result<Vec<_>, _>>()?;
        let channel_axes: Vec<ChannelAxis> = channel_slots
            .iter()
            .zip(&machine_numbers)
            .map(|(&k, m)| ChannelAxis {
                name: md.string("$MC_AXCONF_CHANAX_NAME_TAB", k),
                machine_axis: order.iter().position(|o| o == m).expect("machine axis listed"),
            })
            .collect();
        let (mut machine_axes, mut channel_axes) = (machine_axes, channel_axes);
        unique_names(&machine_axes.iter().map(|a| a.name.as_str()).collect::<Vec<_>>(), "AXCONF_MACHAX_NAME_TAB")?;
        // A spindle's channel axis may go without a name: a spindle without axis function. It
        // goes by its machine axis name inside (frames and stored data list every channel axis).
        for c in channel_axes.iter_mut().filter(|c| c.name.is_empty()) {
            let m = &mut machine_axes[c.machine_axis];
            if m.spindle.is_some() {
                m.spindle_only = true;
                c.name = m.name.clone();
            }
        }
        unique_names(&channel_axes.iter().map(|a| a.name.as_str()).collect::<Vec<_>>(), "AXCONF_CHANAX_NAME_TAB")?;

        // Geometry axes.
        let geo_names: [String; 3] = std::array::from_fn(|g| md.string("$MC_AXCONF_GEOAX_NAME_TAB", g));
        let mut geo_axes = [None; 3];
        for (g, slot) in geo_axes.iter_mut().enumerate() {
            let k = md.num("$MC_AXCONF_GEOAX_ASSIGN_TAB", 0, g) as usize;
            if k == 0 {
                continue;
            }
            let idx = channel_slots.iter().position(|&s| s == k - 1).ok_or_else(|| ActivationError {
                datum: Some("AXCONF_GEOAX_ASSIGN_TAB"),
                message: format!("$MC_AXCONF_GEOAX_ASSIGN_TAB[{g}]={k}: channel axis {k} does not exist"),
            })?;
            if machine_axes[channel_axes[idx].machine_axis].rotary {
                return fail(
                    "AXCONF_GEOAX_ASSIGN_TAB",
                    format!("geometry axis {} cannot be the rotary axis {}", geo_names[g], channel_axes[idx].name),
                );
            }
            *slot = Some(idx);
        }
        let assigned: Vec<usize> = geo_axes.iter().flatten().copied().collect();
        if (1..assigned.len()).any(|i| assigned[..i].contains(&assigned[i])) {
            return fail(
                "AXCONF_GEOAX_ASSIGN_TAB",
                "$MC_AXCONF_GEOAX_ASSIGN_TAB assigns one channel axis to two geometry axes".into(),
            );
        }
        let active_geo: Vec<&str> =
            geo_axes.iter().zip(&geo_names).filter(|(a, _)| a.is_some()).map(|(_, n)| n.as_str()).collect();
        unique_names(&active_geo, "AXCONF_GEOAX_NAME_TAB")?;

        let transverse_name = md.string("$MC_DIAMETER_AX_DEF", 0);
        let transverse_axis = if transverse_name.is_empty() {
            None
        } else {
            let g = geo_names.iter().position(|n| n.eq_ignore_ascii_case(&transverse_name)).ok_or_else(|| {
                ActivationError {
                    datum: Some("DIAMETER_AX_DEF"),
                    message: format!("$MC_DIAMETER_AX_DEF=\"{transverse_name}\" is no geometry axis"),
                }
            })?;
            Some(geo_axes[g].ok_or_else(|| ActivationError {
                datum: Some("DIAMETER_AX_DEF"),
                message: format!("$MC_DIAMETER_AX_DEF: geometry axis {transverse_name} is not assigned"),
            })?)
        };
        let diameter_reset = md.num("$MC_GCODE_RESET_VALUES", 0, 28) as u8;
        let gears = channel_axes
            .iter()
            .enumerate()
            .filter(|(_, c)| machine_axes[c.machine_axis].spindle.is_some())
            .map(|(k, c)| (k, super::gears::Gears::read(md, order[c.machine_axis] - 1)))
            .collect();
        let diameter_axes = channel_axes
            .iter()
            .enumerate()
            .filter(|(_, c)| md.num("$MA_BASE_FUNCTION_MASK", order[c.machine_axis] - 1, 0) as i64 & 4 != 0)
            .fold(0u32, |mask, (k, _)| mask | 1 << k);
        if !(1..=4).contains(&diameter_reset) {
            return fail(
                "GCODE_RESET_VALUES",
                format!("$MC_GCODE_RESET_VALUES[28]={diameter_reset}: G group 29 has 1 DIAMOF .. 4 DIAMCYCOF"),
            );
        }
        let plane_reset = md.num("$MC_GCODE_RESET_VALUES", 0, 5) as u8;
        if !(1..=3).contains(&plane_reset) {
            return fail(
                "GCODE_RESET_VALUES",
                format!("$MC_GCODE_RESET_VALUES[5]={plane_reset}: G group 6 has 1 G17, 2 G18, 3 G19"),
            );
        }
        let master = md.num("$MC_SPIND_DEF_MASTER_SPIND", 0, 0) as u32;
        let master_spindle = channel_axes.iter().position(|c| machine_axes[c.machine_axis].spindle == Some(master));

        let resolve = |k: usize| channel_slots.iter().position(|&s| s + 1 == k);
        let mut trafos = trafo::build(md, &resolve, &channel_axes, &machine_axes)?;
        // Chain-defined orientation transformations take the defaults of MD24530/MD24540.
        let default_of =
            |name: &str| registry::lookup(name).and_then(|d| d.default_value(0, false).as_f64()).unwrap_or(2.0);
        let pole = (default_of("$MC_TRAFO5_NON_POLE_LIMIT_1"), default_of("$MC_TRAFO5_POLE_LIMIT_1"));
        trafos.extend(super::chains::build(md, &channel_axes, &machine_axes, pole)?);
        let kin_build = super::chains::BuildContext { root: md.string("$MN_ROOT_KIN_ELEM_NAME", 0), pole };

        let mut cfg = MachineConfig {
            ipo_cycle,
            machine_axes,
            channel_axes,
            geo_axes,
            geo_names,
            master_spindle,
            transverse_axis,
            diameter_reset,
            diameter_axes,
            flat_d: md.num("$MN_MM_TYPE_OF_CUTTING_EDGE", 0, 0) == 1.0,
            gears,
            plane_reset,
            tools: BTreeMap::new(),
            tool_list: Default::default(),
            tool_change: ToolChange {
                with_m: md.num("$MC_TOOL_CHANGE_MODE", 0, 0) as i64 == 1,
                m_code: md.num("$MC_TOOL_CHANGE_M_CODE", 0, 0) as u32,
                seconds: md.num("$MC_TOOL_CHANGE_TIME", 0, 0),
                m_cycle: {
                    let m = md.num("$MC_TOOL_CHANGE_M_CODE", 0, 0);
                    (0..10)
                        .find(|&i| md.num("$MN_M_NO_FCT_CYCLE", 0, i) == m)
                        .map(|i| md.string("$MN_M_NO_FCT_CYCLE_NAME", i).to_ascii_uppercase())
                        .filter(|n| !n.is_empty())
                },
            },
            carriers: BTreeMap::new(),
            toframe_mode: md.num("$SC_TOFRAME_MODE", 0, 0) as i64,
            dry_run_feed: (0.0, 0),
            swivel_alarm_mask: md.num("$MC_MILL_SWIVEL_ALARM_MASK", 0, 0) as i64,
            work_offsets: Vec::new(),
            base_frames: Vec::new(),
            ncu_base_frames: Vec::new(),
            frame_angles: if md.num("$MN_FRAME_ANGLE_INPUT_MODE", 0, 0) as i64 == 2 {
                FrameAngles::Euler
            } else {
                FrameAngles::Rpy
            },
            reset_trafo: ResetTrafo::build(md, &trafos)?,
            trafos,
            ori: OriSettings::read(md),
            kin: Default::default(),
            kin_counts: (
                md.num("$MN_MM_MAXNUM_KIN_CHAIN_ELEM", 0, 0) as usize,
                md.num("$MN_MM_NUM_KIN_TRAFOS", 0, 0) as usize,
            ),
            kin_build,
            corr_limits: Default::default(),
            incremental_travels: IncrementalTravels::default(),
            cutcom_max_dummy_blocks: md.num("$MC_CUTCOM_MAXNUM_DUMMY_BLOCKS", 0, 0) as usize,
            cutcom_max_check_blocks: md.num("$MC_CUTCOM_MAXNUM_CHECK_BLOCKS", 0, 0) as usize,
            cutcom_corner_limit: md.num("$MC_CUTCOM_CORNER_LIMIT", 0, 0).to_radians(),
            dynamics: super::dynamics::ChannelDynamics::read(md)
                .map_err(|m| ActivationError { datum: Some("GCODE_RESET_VALUES"), message: m })?,
            path_control: super::path_control::PathControlData::read(md, &machine_numbers),
            sync_sizes: super::sync_sizes::SyncSizes::read(md),
            process_counting: super::process_counting::ProcessCounting::read(md),
        };
        cfg.refresh_data(md)?;
        Ok(cfg)
    }

    /// Takes over tool data, toolholders and settable frames from `md`, which act at once (unlike machine
    /// data, which waits for NEWCONF or a reset).
    pub fn refresh_data(&mut self, md: &MachineData) -> Result<(), ActivationError> {
        if self.kin != *md.kin() {
            self.kin = md.kin().clone();
        }
        self.toframe_mode = md.num("$SC_TOFRAME_MODE", 0, 0) as i64;
        self.dry_run_feed = (md.num("$SC_DRY_RUN_FEED", 0, 0), md.num("$SC_DRY_RUN_FEED_MODE", 0, 0) as i64);
        self.path_control.refresh_settings(md);
        self.corr_limits = super::chains::correct::Limits {
            lin_max: md.num("$SN_CORR_TRAFO_LIN_MAX", 0, 0),
            dir_max: md.num("$SN_CORR_TRAFO_DIR_MAX", 0, 0),
        };
        self.incremental_travels = IncrementalTravels {
            frame: md.num("$SC_FRAME_OFFSET_INCR_PROG", 0, 0) != 0.0,
            tool: md.num("$SC_TOOL_OFFSET_INCR_PROG", 0, 0) != 0.0,
        };
        let n = self.channel_axes.len();
        let user = md.num("$MC_MM_NUM_USER_FRAMES", 0, 0) as usize;
        let base = md.num("$MC_MM_NUM_BASE_FRAMES", 0, 0) as usize;
        let mut work_offsets = vec![FrameData::neutral(n); user];
        let mut base_frames = vec![FrameData::neutral(n); base];
        let ncu = md.num("$MN_MM_NUM_GLOBAL_BASE_FRAMES", 0, 0) as usize;
        let mut ncu_base_frames = vec![FrameData::neutral(n); ncu];
        for ((family, frame, axis, component), value) in md.frames() {
            let (list, var, count) = match family {
                FrameFamily::Settable => (&mut work_offsets, "$P_UIFR", "MM_NUM_USER_FRAMES"),
                FrameFamily::Base => (&mut base_frames, "$P_CHBFR", "MM_NUM_BASE_FRAMES"),
                FrameFamily::NcuBase => (&mut ncu_base_frames, "$P_NCBFR", "MM_NUM_GLOBAL_BASE_FRAMES"),
            };
            let scope = if *family == FrameFamily::NcuBase { "MN" } else { "MC" };
            let at = format!("{var}[{frame},{axis},{}]", component.code());
            let idx = self.program_axis(axis).ok_or_else(|| ActivationError {
                datum: None,
                message: format!("{at}: {axis} is not an axis of this channel"),
            })?;
            let Some(f) = list.get_mut(*frame) else {
                return fail(count, format!("{at}: frame {frame} exceeds ${scope}_{count}={}", list.len()));
            };
            match component {
                FrameComponent::Translation | FrameComponent::Fine => f.trans[idx] += value,
                FrameComponent::Rotation => {
                    let g = self.geo_axes.iter().position(|a| *a == Some(idx)).ok_or_else(|| ActivationError {
                        datum: None,
                        message: format!("{at}: rotations are about geometry axes, {axis} is none"),
                    })?;
                    f.rot[g] = *value;
                }
                FrameComponent::Scale => f.scale[idx] = *value,
                FrameComponent::Mirror => f.mirror[idx] = *value != 0.0,
            }
        }
        self.work_offsets = work_offsets;
        self.base_frames = base_frames;
        self.ncu_base_frames = ncu_base_frames;
        self.tools = md.tools().clone();
        let list = super::tools_list::ToolList::build(md.tool_mgmt(), md.tools())?;
        if *self.tool_list != list {
            self.tool_list = std::sync::Arc::new(list);
        }
        self.carriers = md.carriers();
        Ok(())
    }

    /// The channel axis a program addresses by `name`: a geometry axis name first, then a
    /// channel axis name.
    pub fn program_axis(&self, name: &str) -> Option<usize> {
        resolve_program_axis(name, &self.geo_axes, &self.geo_names, &self.channel_axes)
    }

    /// Channel axis by any name the control's axial variables take: geometry, channel or
    /// machine axis name (`$AA_IM[X1]` on a machine whose channel calls X1 `X`).
    pub fn axis_by_any_name(&self, name: &str) -> Option<usize> {
        self.program_axis(name).or_else(|| {
            self.channel_axes.iter().position(|c| self.machine_axes[c.machine_axis].name.eq_ignore_ascii_case(name))
        })
    }

    /// The name under which the program and the state show channel axis `idx`.
    pub fn program_axis_name(&self, idx: usize) -> &str {
        match self.geo_axes.iter().position(|g| *g == Some(idx)) {
            Some(g) => &self.geo_names[g],
            None => &self.channel_axes[idx].name,
        }
    }

    /// The number of channel axes without the trailing spindles without axis function: the
    /// axes a program moves by name (the mill's X, Y, Z without its tool spindle).
    pub fn axes_len(&self) -> usize {
        let n = self.channel_axes.len();
        n - (0..n).rev().take_while(|&k| !self.shown(k)).count()
    }

    /// Whether channel axis `idx` is shown among the positions (every axis but a spindle
    /// without axis function, see [`MachineAxis::spindle_only`]).
    pub fn shown(&self, idx: usize) -> bool {
        !self.axis(idx).spindle_only
    }

    /// The name the state gives the spindle on channel axis `idx`: its channel axis name, or
    /// `S<n>` for a spindle without axis function.
    pub fn spindle_name(&self, idx: usize) -> &str {
        const NAMES: [&str; 20] = [
            "S1", "S2", "S3", "S4", "S5", "S6", "S7", "S8", "S9", "S10", "S11", "S12", "S13", "S14", "S15", "S16",
            "S17", "S18", "S19", "S20",
        ];
        let a = self.axis(idx);
        match a.spindle.filter(|_| a.spindle_only).and_then(|n| NAMES.get((n as usize).wrapping_sub(1))) {
            Some(name) => name,
            None => self.program_axis_name(idx),
        }
    }

    /// The machine axis driving channel axis `idx`.
    pub fn axis(&self, idx: usize) -> &MachineAxis {
        &self.machine_axes[self.channel_axes[idx].machine_axis]
    }
}

fn resolve_program_axis(
    name: &str,
    geo_axes: &[Option<usize>; 3],
    geo_names: &[String; 3],
    channel_axes: &[ChannelAxis],
) -> Option<usize> {
    geo_axes
        .iter()
        .zip(geo_names)
        .find_map(|(a, n)| a.filter(|_| n.eq_ignore_ascii_case(name)))
        .or_else(|| channel_axes.iter().position(|c| c.name.eq_ignore_ascii_case(name)))
}

fn unique_names(names: &[&str], datum: &'static str) -> Result<(), ActivationError> {
    for (i, n) in names.iter().enumerate() {
        if n.is_empty() {
            return fail(
                datum,
                format!("${}{datum}: empty axis name", if datum.starts_with("AXCONF_MACHAX") { "MN_" } else { "MC_" }),
            );
        }
        if names[..i].iter().any(|m| m.eq_ignore_ascii_case(n)) {
            return fail(datum, format!("axis name {n} is used twice"));
        }
    }
    Ok(())
}

fn machine_axis(md: &MachineData, ax: usize) -> Result<MachineAxis, ActivationError> {
    let num = |name: &str| md.num(name, ax, 0);
    let rotary = num("$MA_IS_ROT_AX") != 0.0;
    // The control's units: linear mm/min and m/s², rotary rev/min and rev/s².
    let (velo, accel) = if rotary { (360.0 / 60.0, 360.0) } else { (1.0 / 60.0, 1000.0) };
    let name = md.string("$MN_AXCONF_MACHAX_NAME_TAB", ax);
    let (minus, plus) = (num("$MA_POS_LIMIT_MINUS"), num("$MA_POS_LIMIT_PLUS"));
    if minus >= plus {
        return fail(
            "POS_LIMIT_MINUS",
            format!("axis {name}: $MA_POS_LIMIT_MINUS ({minus}) must be below $MA_POS_LIMIT_PLUS ({plus})"),
        );
    }
    let modulo_flag = num("$MA_ROT_IS_MODULO") != 0.0;
    if modulo_flag && !rotary {
        return fail("ROT_IS_MODULO", format!("axis {name}: $MA_ROT_IS_MODULO needs $MA_IS_ROT_AX=TRUE"));
    }
    let spindle = num("$MA_SPIND_ASSIGN_TO_MACHAX") as u32;
    if spindle != 0 && !rotary {
        return fail(
            "SPIND_ASSIGN_TO_MACHAX",
            format!("axis {name}: a spindle must be a rotary axis ($MA_IS_ROT_AX=TRUE)"),
        );
    }
    Ok(MachineAxis {
        name,
        rotary,
        modulo: modulo_flag.then(|| (num("$MA_MODULO_RANGE_START"), num("$MA_MODULO_RANGE"))),
        spindle: (spindle != 0).then_some(spindle),
        spindle_only: false,
        spindle_posctrl_velo: num("$MA_SPIND_POSCTRL_VELO"),
        max_velocity: num("$MA_MAX_AX_VELO") * velo,
        max_accel: num("$MA_MAX_AX_ACCEL") * accel,
        accel_overload: num("$MA_MAX_ACCEL_OVL_FACTOR"),
        dynamics: super::dynamics::AxisDynamics::read(md, ax, accel),
        jog_velocity: num("$MA_JOG_VELO") * velo,
        jog_rapid_velocity: num("$MA_JOG_VELO_RAPID") * velo,
        pos_velocity: num("$MA_POS_AX_VELO") * velo,
        limit_minus: minus,
        limit_plus: plus,
    })
}

impl MachineConfig {
    /// Replaces the data set of TRAORI_DYN record `n` by one built from the chain data as it
    /// is now (after CORRTRAFO wrote `$NK_OFF_DIR`), leaving every other data set as activated.
    pub fn rebuild_chain_trafo(&mut self, n: usize) -> Result<(), ActivationError> {
        let set = super::chains::rebuild_traori(&self.kin, &self.kin_build, &self.channel_axes, &self.machine_axes, n)?;
        match self.trafos.iter_mut().find(|s| s.number == set.number) {
            Some(slot) => *slot = set,
            None => self.trafos.push(set),
        }
        Ok(())
    }
}

/// SD42440 `$SC_FRAME_OFFSET_INCR_PROG` and SD42442 `$SC_TOOL_OFFSET_INCR_PROG`: an incremental
/// move after a change of the frame or of the tool offset ends where the programmed increment
/// says from the position programmed before the change (the change is travelled, `true`, the
/// control's default), or from the old machine position seen through the new offsets (`false`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IncrementalTravels {
    pub frame: bool,
    pub tool: bool,
}

impl Default for IncrementalTravels {
    fn default() -> Self {
        IncrementalTravels { frame: true, tool: true }
    }
}
