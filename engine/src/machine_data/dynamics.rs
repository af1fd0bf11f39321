//! The machine data of acceleration, jerk and the position loop, typed in engine units.
//!
//! Input: MD32300 `MAX_AX_ACCEL`, MD32310 `MAX_ACCEL_OVL_FACTOR` and MD32431 `MAX_AX_JERK`,
//! each with one entry per dynamic response mode (G group 59), MD32200 `POSCTRL_GAIN`,
//! MD32620 `FFW_MODE`, MD32630 `FFW_ACTIVATION_MODE`, MD20600 `MAX_PATH_JERK` and the reset
//! values of G groups 21, 24 and 59 (MD20150). Output: [`AxisDynamics`] per machine axis and
//! [`ChannelDynamics`] per channel, read by the interpreter (`interp/dynamics.rs`), the planner
//! (jerk under SOFT) and the servo model (`channel/servo.rs`).

use super::MachineData;
use super::registry::DYN_MODES;
use crate::motion::drive::{Knee, ReductionKind};

/// Dynamic response modes of G group 59 in the control's index order of the per-mode data.
pub const DYN_MODE_NAMES: [&str; DYN_MODES] = ["DYNNORM", "DYNPOS", "DYNROUGH", "DYNSEMIFIN", "DYNFINISH"];

/// One machine axis' dynamics in engine units (mm or degrees, seconds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisDynamics {
    /// Acceleration per dynamic response mode (mm/s² or deg/s²); `[0]` is `max_accel`.
    pub accel: [f64; DYN_MODES],
    /// MD32310 per dynamic response mode.
    pub overload: [f64; DYN_MODES],
    /// Jerk per dynamic response mode (mm/s³ or deg/s³), the SOFT limit.
    pub jerk: [f64; DYN_MODES],
    /// MD32432 PATH_TRANS_JERK_LIM (mm/s³ or deg/s³): the higher jerk allowed at a block
    /// transition where the curvature jumps (line into arc) under SOFT; 0 none above `jerk`.
    pub trans_jerk: f64,
    /// Position control gain Kv in 1/s (MD32200 set 0 converted: 1 (m/min)/mm = 1000/60 1/s).
    pub kv: f64,
    /// MD32620 is not 0: the axis has a feed-forward control to switch.
    pub ffw_available: bool,
    /// MD32630: 0 the MD32620 state always, 1 FFWON/FFWOF at once, 2 at the next standstill.
    pub ffw_activation: u8,
    /// MD35220 ACCEL_REDUCTION_SPEED_POINT: DRIVE's switching speed as a fraction of MD32000.
    pub reduction_point: f64,
    /// MD35230 ACCEL_REDUCTION_FACTOR: the share of the acceleration lost at MD32000 (DRIVE).
    pub reduction_factor: f64,
    /// MD35242 ACCEL_REDUCTION_TYPE.
    pub reduction_kind: ReductionKind,
}

impl AxisDynamics {
    /// A virtual axis whose dynamics the real axes behind it decide (a transformation's
    /// Cartesian axis): no limit of its own, feed-forward like an ideal axis.
    pub const UNLIMITED: AxisDynamics = AxisDynamics {
        accel: [f64::INFINITY; DYN_MODES],
        overload: [1.0; DYN_MODES],
        jerk: [f64::INFINITY; DYN_MODES],
        trans_jerk: 0.0,
        kv: f64::INFINITY,
        ffw_available: true,
        ffw_activation: 0,
        reduction_point: 1.0,
        reduction_factor: 0.0,
        reduction_kind: ReductionKind::Hyperbolic,
    };

    /// Reads the data of machine axis `ax`; `accel_unit`/`jerk_unit` convert the control's
    /// m/s² and m/s³ (rev/s², rev/s³ for rotary axes) into engine units.
    pub(super) fn read(md: &MachineData, ax: usize, accel_unit: f64) -> AxisDynamics {
        let per_mode =
            |name: &str, unit: f64| -> [f64; DYN_MODES] { std::array::from_fn(|n| md.num(name, ax, n) * unit) };
        AxisDynamics {
            accel: per_mode("$MA_MAX_AX_ACCEL", accel_unit),
            overload: per_mode("$MA_MAX_ACCEL_OVL_FACTOR", 1.0),
            // Jerk has the acceleration's unit conversion (m → mm, rev → degrees).
            jerk: per_mode("$MA_MAX_AX_JERK", accel_unit),
            trans_jerk: md.num("$MA_PATH_TRANS_JERK_LIM", ax, 0) * accel_unit,
            kv: md.num("$MA_POSCTRL_GAIN", ax, 0) * 1000.0 / 60.0,
            ffw_available: md.num("$MA_FFW_MODE", ax, 0) != 0.0,
            ffw_activation: md.num("$MA_FFW_ACTIVATION_MODE", ax, 0) as u8,
            reduction_point: md.num("$MA_ACCEL_REDUCTION_SPEED_POINT", ax, 0),
            reduction_factor: md.num("$MA_ACCEL_REDUCTION_FACTOR", ax, 0),
            // The registry keeps the value within 0..=2.
            reduction_kind: ReductionKind::from_md(md.num("$MA_ACCEL_REDUCTION_TYPE", ax, 0) as i64)
                .unwrap_or(ReductionKind::Hyperbolic),
        }
    }

    /// DRIVE's characteristic with acceleration `a_max` (the mode's, ACC applied) and
    /// MD32000 `v_max`; `None` when the data reduce nothing.
    pub fn knee(&self, a_max: f64, v_max: f64) -> Option<Knee> {
        let knee = Knee {
            kind: self.reduction_kind,
            v_red: self.reduction_point * v_max,
            v_max,
            a_max,
            a_red: (1.0 - self.reduction_factor) * a_max,
        };
        knee.reduces().then_some(knee)
    }
}

/// BRISK, SOFT, DRIVE: G group 21, the acceleration profile of path and positioning axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Profile {
    /// Acceleration-limited (trapezoidal velocity), the reset value.
    #[default]
    Brisk,
    /// Jerk-limited (MD32431, MD20600).
    Soft,
    /// DRIVE: BRISK with the reduced acceleration above the switching speed of MD35220/MD35230
    /// (`motion/drive.rs`).
    Drive,
}

/// The channel's dynamics data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChannelDynamics {
    /// MD20600 MAX_PATH_JERK in mm/s³.
    pub path_jerk: f64,
    /// Reset value of G group 21.
    pub reset_profile: Profile,
    /// Reset value of G group 24: FFWON.
    pub reset_ffw: bool,
    /// Reset value of G group 59: index of the dynamic response mode (0 DYNNORM).
    pub reset_mode: usize,
}

impl ChannelDynamics {
    /// Reads the channel data; an out-of-range reset value is named in the error.
    pub(super) fn read(md: &MachineData) -> Result<ChannelDynamics, String> {
        let reset = |group: usize| md.num("$MC_GCODE_RESET_VALUES", 0, group - 1) as usize;
        let reset_profile = match reset(21) {
            1 => Profile::Brisk,
            2 => Profile::Soft,
            3 => Profile::Drive,
            n => return Err(format!("$MC_GCODE_RESET_VALUES[20]={n}: G group 21 has 1 BRISK, 2 SOFT, 3 DRIVE")),
        };
        let reset_ffw = match reset(24) {
            1 => false,
            2 => true,
            n => return Err(format!("$MC_GCODE_RESET_VALUES[23]={n}: G group 24 has 1 FFWOF, 2 FFWON")),
        };
        let reset_mode = match reset(59) {
            n @ 1..=DYN_MODES => n - 1,
            n => return Err(format!("$MC_GCODE_RESET_VALUES[58]={n}: G group 59 has 1 DYNNORM .. 5 DYNFINISH")),
        };
        Ok(ChannelDynamics {
            path_jerk: md.num("$MC_MAX_PATH_JERK", 0, 0) * 1000.0,
            reset_profile,
            reset_ffw,
            reset_mode,
        })
    }
}
