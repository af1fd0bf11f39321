//! The spindles as block preparation sees them (Function Manual S1, Programming Manual
//! "Fundamentals": feed types, threads, tapping).
//!
//! - which spindle is the master spindle (MD20090, changed by SETMS), each spindle's
//!   programmed speed and direction (`S`, `S<n>=`, `M3`/`M4`/`M5`, `M<n>=3/4/5`);
//! - the feed type of G group 15 (`G93`, `G94`, `G95`, `G96`, `G961`, `G97`, `G971`) and the
//!   speed limits `G25`/`G26`/`LIMS`;
//! - thread cutting `G33` (with `SF=`) and rigid tapping `G331`/`G332`, `G63`.
//!
//! `words.rs` sorts a block's spindle words out, `block.rs` turns them into main-run items,
//! `motion.rs` gives a block's move its feed per revolution, inverse-time feed, thread start
//! or the interpolated spindle of rigid tapping. The main run's model is
//! `channel/spindle.rs`: it receives [`Control`] items for what is more than a speed.

mod block;
pub mod diameter;
mod diameter_axes;
mod fpr;
mod gears;
pub mod lead_change;
mod motion;
pub(super) mod position_control;
pub(super) mod vars;
pub(super) mod words;
pub(super) use diameter_axes::{is_keyword as is_diameter_axis_keyword, word as diameter_axis_word};
pub(super) use fpr::statement as fpr_statement;

/// The channel axis of `SCC[axis]` (Programming Manual "Constant cutting speed"): a linear
/// axis of the channel; anything else 12550 (unknown) or 12560.
pub(super) fn css_axis_word(args: &[crate::lang::Expr], cfg: &MachineConfig, line: u32) -> Result<usize, Alarm> {
    let [crate::lang::Expr::Var { name, indices }] = args else {
        return Err(Alarm::syntax(line, "SCC[axis]"));
    };
    let k = cfg
        .program_axis(name)
        .filter(|_| indices.is_empty())
        .ok_or_else(|| Alarm::unknown_name(line, &format!("SCC[{name}]")))?;
    if cfg.axis(k).rotary || cfg.axis(k).spindle.is_some() {
        return Err(Alarm::value_out_of_range(line, &format!("SCC[{name}]: no linear axis")));
    }
    Ok(k)
}

use crate::alarm::Alarm;
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;

/// A spindle command for the main run beyond a plain speed ([`super::Item::Spindle`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// G25/G26 lower and upper speed limit and LIMS (rev/min; infinite: none).
    Limits { axis: usize, lower: f64, upper: f64, lims: f64 },
    /// G96/G961: constant cutting speed `cutting_speed` (m/min) in `direction` (+1 M3, −1 M4),
    /// the diameter measured on channel axis `transverse` from machine position `centre`.
    Css { axis: usize, cutting_speed: f64, direction: i8, transverse: usize, centre: f64 },
    /// G33: the thread's move starts when the spindle passes `angle` degrees (SF).
    ThreadStart { axis: usize, angle: f64 },
    /// FPR(axis): a feed per revolution follows the rotary axis or spindle on channel axis
    /// `axis` instead of the master spindle (`fpr.rs`).
    FeedReference { axis: usize },
    /// M40..M45: the spindle changes to gear stage `stage` (`gears.rs`); the block change
    /// waits until it has.
    Gear { axis: usize, stage: u8 },
    /// SETMS: the spindle on channel axis `axis` is the master spindle from here on (a feed
    /// per revolution follows it in the main run, the state marks it).
    Master { axis: usize },
    /// SPCON (`on`) / SPCOF: the spindle changes to position control or back to speed
    /// control (`position_control.rs`).
    PositionControl { axis: usize, on: bool },
}

impl Control {
    /// The channel axis of the spindle the command is for.
    pub fn axis(&self) -> usize {
        match *self {
            Control::Limits { axis, .. }
            | Control::Css { axis, .. }
            | Control::ThreadStart { axis, .. }
            | Control::FeedReference { axis }
            | Control::Gear { axis, .. }
            | Control::Master { axis }
            | Control::PositionControl { axis, .. } => axis,
        }
    }
}

/// G group 15: how F is read and whether S is a speed or a cutting speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FeedType {
    /// Inverse time: F is 1/min, the block takes 1/F minutes.
    G93,
    /// mm/min.
    #[default]
    G94,
    /// mm per master spindle revolution.
    G95,
    /// Constant cutting speed (S in m/min), feed per revolution.
    G96,
    /// Constant cutting speed, feed per minute.
    G961,
    /// Constant cutting speed off (speed frozen), feed per revolution.
    G97,
    /// Constant cutting speed off, feed per minute.
    G971,
}

impl FeedType {
    pub fn per_rev(self) -> bool {
        matches!(self, FeedType::G95 | FeedType::G96 | FeedType::G97)
    }

    pub fn css(self) -> bool {
        matches!(self, FeedType::G96 | FeedType::G961)
    }

    /// The name shown in the G-code display.
    pub fn name(self) -> &'static str {
        match self {
            FeedType::G93 => "G93",
            FeedType::G94 => "G94",
            FeedType::G95 => "G95",
            FeedType::G96 => "G96",
            FeedType::G961 => "G961",
            FeedType::G97 => "G97",
            FeedType::G971 => "G971",
        }
    }
}

/// Thread and tapping functions of G group 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Thread {
    /// G33: thread with constant lead, the path follows the spindle.
    G33,
    /// G34/G35: thread with increasing/decreasing lead, F the change (`lead_change.rs`).
    G34,
    G35,
    /// G331: rigid tapping in, the spindle interpolates with the axis.
    G331,
    /// G332: rigid tapping out (the spindle reversed).
    G332,
}

#[derive(Debug, Clone)]
pub(in crate::interp) struct Spindles {
    /// Channel axis of the master spindle.
    master: Option<usize>,
    /// Programmed speed (rev/min) by channel axis.
    speed: [f64; MAX_CHANNEL_AXES],
    /// Programmed direction by channel axis: +1 M3, −1 M4, 0 M5 or positioned.
    direction: [i8; MAX_CHANNEL_AXES],
    /// G group 15.
    pub feed_type: FeedType,
    /// The cutting speed of G96/G961 (m/min).
    pub cutting_speed: f64,
    /// G25, G26, LIMS (rev/min).
    pub lower: f64,
    pub upper: f64,
    pub lims: f64,
    /// The thread function of G group 1 while one is active (G33, G34, G35, G331, G332).
    pub thread: Option<Thread>,
    /// SF: start angle offset of G33 threads (degrees).
    pub start_angle: f64,
    /// The block before was a G33 block: a chained thread block starts without a new sync.
    pub thread_chained: bool,
    /// G group 29: diameter programming of the transverse axis.
    pub diameter: diameter::Diameter,
    /// FPR(axis): the channel axis a feed per revolution refers to (`None`: the master
    /// spindle).
    pub fpr: Option<usize>,
    /// SCC[axis]: the transverse axis G96/G961 reckon the diameter on (`None`: MD20100's).
    pub css_axis: Option<usize>,
    /// `fpr`'s rotary axis is no spindle: its speed is unknown to preparation.
    fpr_axis_max: Option<f64>,
    /// The G34/G35 lead of the block being prepared: its move goes out in segments.
    pub variable_lead: Option<lead_change::LeadChange>,
    /// Gear stage by channel axis as preparation selected it (1..=5), and whether M40
    /// (automatic selection) is on.
    gear: [u8; MAX_CHANNEL_AXES],
    gear_auto: [bool; MAX_CHANNEL_AXES],
}

impl Spindles {
    pub fn new(cfg: &MachineConfig) -> Spindles {
        Spindles {
            master: cfg.master_spindle,
            speed: [0.0; MAX_CHANNEL_AXES],
            direction: [0; MAX_CHANNEL_AXES],
            feed_type: FeedType::G94,
            cutting_speed: 0.0,
            lower: 0.0,
            upper: f64::INFINITY,
            lims: f64::INFINITY,
            thread: None,
            start_angle: 0.0,
            thread_chained: false,
            diameter: diameter::Diameter::reset(cfg),
            fpr: None,
            css_axis: None,
            fpr_axis_max: None,
            variable_lead: None,
            gear: [1; MAX_CHANNEL_AXES],
            gear_auto: [true; MAX_CHANNEL_AXES],
        }
    }

    /// Reset: the configured master spindle again and the reset feed type; with `stop`,
    /// every spindle stopped (a reset), else the directions stay (program end: spindles turn
    /// on until M5 or reset).
    pub fn reset(&mut self, cfg: &MachineConfig, stop: bool) {
        self.master = cfg.master_spindle;
        self.feed_type = FeedType::G94;
        self.thread = None;
        self.thread_chained = false;
        self.start_angle = 0.0;
        self.diameter = diameter::Diameter::reset(cfg);
        self.fpr = None;
        self.css_axis = None;
        self.fpr_axis_max = None;
        // The stage engaged stays (it is mechanical); selection is automatic (M40) again.
        self.gear_auto = [true; MAX_CHANNEL_AXES];
        if stop {
            self.direction = [0; MAX_CHANNEL_AXES];
        }
    }

    pub fn master(&self) -> Option<usize> {
        self.master
    }

    /// SETMS(n) (`Some(n)`) or SETMS (`None`, back to the configured master spindle).
    pub fn set_master(&mut self, spindle: Option<u32>, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        self.master = match spindle {
            None => cfg.master_spindle,
            Some(n) => Some(axis_of(cfg, n, line, "SETMS")?),
        };
        Ok(())
    }

    /// Speed of the master spindle (0 without one).
    pub fn master_speed(&self) -> f64 {
        self.master.map_or(0.0, |k| self.speed[k])
    }

    /// The speed a feed per revolution refers to in the look-ahead: the programmed speed, or
    /// under constant cutting speed the highest the limits allow (the main run follows the
    /// actual speed; this only bounds the planned velocity).
    pub fn reference_speed(&self) -> f64 {
        if let Some(k) = self.fpr {
            // FPR: the programmed speed of that spindle, or a rotary axis' highest speed.
            return self.fpr_axis_max.unwrap_or(self.speed[k]);
        }
        if self.feed_type.css() || self.feed_type == FeedType::G97 {
            self.lims.min(self.upper).min(100_000.0)
        } else {
            self.master_speed()
        }
    }

    /// Whether the spindle on channel axis `axis` was programmed to turn.
    pub fn turns(&self, axis: usize) -> bool {
        self.direction[axis] != 0
    }

    /// The programmed speed of the spindle on channel axis `axis` (rev/min).
    pub fn speed_of(&self, axis: usize) -> f64 {
        self.speed[axis]
    }

    /// The programmed direction of the spindle on channel axis `axis`: +1 M3, −1 M4, 0 M5 or
    /// positioned.
    pub fn direction_of(&self, axis: usize) -> i8 {
        self.direction[axis]
    }

    /// Stops the spindle on `axis` in preparation's view (SPOS puts it in position control).
    pub fn stop(&mut self, axis: usize) {
        self.direction[axis] = 0;
    }
}

/// The channel axis of spindle number `n`, or alarm 14060-style "no spindle n" for `what`.
pub(super) fn axis_of(cfg: &MachineConfig, n: u32, line: u32, what: &str) -> Result<usize, Alarm> {
    cfg.channel_axes
        .iter()
        .position(|c| cfg.machine_axes[c.machine_axis].spindle == Some(n))
        .ok_or_else(|| Alarm::value_out_of_range(line, &format!("{what}: no spindle {n} in the channel")))
}
