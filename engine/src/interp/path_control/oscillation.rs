//! Asynchronous oscillation in a program (Function Manual P5 "Oscillation", Programming Manual
//! Job planning "Oscillation"): an axis travels to and fro between two reversal points on its
//! own interpolator, asynchronous to the path, as grinding machines move the wheel across the
//! work while the infeed axis moves on the path.
//!
//! - `OSP1[ax]=`, `OSP2[ax]=`: the reversal points (positions like `POSA` values: absolute,
//!   through the frame); `OST1[ax]=`, `OST2[ax]=`: the stop there (seconds: > 0 the dwell after
//!   the exact stop, 0/−1/−2 the exact stop fine/coarse/none, which NCTwin's single-axis
//!   interpolator does not tell apart: it lands exactly and goes on);
//! - `FA[ax]=`: the feed (as for positioning axes; MD32060 without it);
//! - `OSE[ax]=`: the end position, `OSB[ax]=` the start position, `OSNSC[ax]=` the number of
//!   spark-out strokes, `OSCTRL[ax]=(set, reset)` the control bits (below);
//! - `OS[ax]=1` starts the oscillation, `OS[ax]=0` ends it.
//!
//! OSCTRL bits read (P5's table): 1 stop at reversal point 1, 2 at reversal point 2 (neither:
//! the next one), 3 no reversal point when there are no spark-out strokes, 4 approach the end
//! position after the spark-out strokes, 256 a spark-out stroke is a double stroke (there and
//! back; else one way), 512 travel to the start position first. The others (delete distance
//! to go, feed changes from the next reversal point, DC for rotary axes) are kept but not
//! acted on.
//!
//! Modelled as follows where the manuals leave room:
//! - Without OSB the oscillation starts towards reversal point 1.
//! - The settings are modal per axis until the program's end or a reset, in program units;
//!   they are taken into machine positions through the frame when `OS[ax]=1` is read, and a
//!   setting programmed while the axis oscillates acts from its next reversal.
//! - `OS[ax]=0` ends the oscillation in the main run; the blocks after it are prepared once
//!   the axis stands (its end depends on where it was), so the program goes on from there.
//! - A path block that programs the oscillating axis is alarm 14092 (as for a POSA axis still
//!   travelling); `WAITP(ax)` waits for the end of the oscillation.
//! - The program's end brakes an oscillation that was not ended, as a reset does (P5: "the
//!   options selected subsequently are not processed").
//! - Synchronous oscillation (`OSCILL`, infeed at the reversal points) is not modelled.

use super::positioning::{Kind, Motion, PosWord};
use crate::alarm::Alarm;
use crate::interp::Item;
use crate::interp::eval::eval_f64;
use crate::interp::eval::indirect_axis;
use crate::interp::eval::scope::{Ctx, SysView};
use crate::interp::eval::vars::Variables;
use crate::lang::{COEFFICIENTS, CoordMode, Expr};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// OSCTRL bits NCTwin acts on.
pub mod ctrl {
    /// Stop at reversal point 1.
    pub const STOP_AT_1: u32 = 1;
    /// Stop at reversal point 2.
    pub const STOP_AT_2: u32 = 2;
    /// Both: no reversal point without spark-out strokes.
    pub const NO_REVERSAL: u32 = 3;
    /// Approach the end position after the spark-out strokes.
    pub const TO_END: u32 = 4;
    /// A spark-out stroke is a double stroke.
    pub const DOUBLE_STROKE: u32 = 256;
    /// Travel to the start position first.
    pub const FROM_START: u32 = 512;
}

/// Which oscillation word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::interp) enum Key {
    On,
    Point1,
    Point2,
    Stop1,
    Stop2,
    End,
    Start,
    Strokes,
    Control,
}

/// One oscillation word of a block, evaluated (`Control`: `value` the bits set, `reset` the
/// bits cleared).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct OscWord {
    pub key: Key,
    pub axis: usize,
    pub value: f64,
    pub reset: u32,
}

/// The programmed settings of one axis, in program units (positions in the WCS).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(in crate::interp) struct Settings {
    pub point1: f64,
    pub point2: f64,
    pub stop1: f64,
    pub stop2: f64,
    pub end: Option<f64>,
    pub start: Option<f64>,
    pub strokes: u32,
    pub control: u32,
}

/// The interpreter's oscillation state: every axis' settings and the axes oscillating.
#[derive(Debug, Clone, PartialEq, Default)]
pub(in crate::interp) struct Oscillations {
    pub settings: [Settings; MAX_CHANNEL_AXES],
    /// Bit k: channel axis k oscillates (OS=1 read, OS=0 not yet).
    pub on: u32,
    /// Bit k: the oscillation of channel axis k has ended; its position is taken from the main
    /// run before the next block.
    pub adopt: u32,
}

/// An oscillation as the main run performs it (`Item::Positioning` with
/// `Motion::Oscillate`): machine positions, dwell seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oscillation {
    pub point1: f64,
    pub point2: f64,
    /// Dwell at each reversal point after landing (seconds, 0: none).
    pub dwell1: f64,
    pub dwell2: f64,
    pub end: Option<f64>,
    pub start: Option<f64>,
    pub strokes: u32,
    pub control: u32,
}

/// Whether `name[..]=` is a word of this module.
pub(in crate::interp) fn is_word(name: &str) -> bool {
    matches!(name, "OS" | "OSP1" | "OSP2" | "OST1" | "OST2" | "OSE" | "OSB" | "OSNSC" | "OSCTRL")
}

/// Evaluates one oscillation word into `out`.
pub(in crate::interp) fn word(
    out: &mut Vec<OscWord>,
    name: &str,
    index: &Expr,
    expr: &Expr,
    vars: &Variables,
    sys: &SysView,
    line: u32,
) -> Result<(), Alarm> {
    let axis = indirect_axis::resolve(index, vars, sys, line)?;
    if sys.cfg.axis(axis).spindle.is_some() {
        return Err(Alarm::wrong_axis_type(line, sys.cfg.program_axis_name(axis)));
    }
    let key = match name {
        "OS" => Key::On,
        "OSP1" => Key::Point1,
        "OSP2" => Key::Point2,
        "OST1" => Key::Stop1,
        "OST2" => Key::Stop2,
        "OSE" => Key::End,
        "OSB" => Key::Start,
        "OSNSC" => Key::Strokes,
        _ => Key::Control,
    };
    let ctx = Ctx { vars, sys };
    let label = |v: f64| format!("{name}[{}]={v}", sys.cfg.program_axis_name(axis));
    let (value, reset) = match (key, expr) {
        (Key::Control, Expr::Call(f, items)) if f == COEFFICIENTS && (1..=2).contains(&items.len()) => {
            let set = eval_f64(&items[0], &ctx, line)?;
            let reset = items.get(1).map(|e| eval_f64(e, &ctx, line)).transpose()?.unwrap_or(0.0);
            (set, bits(reset).ok_or_else(|| Alarm::value_out_of_range(line, &label(reset)))?)
        }
        (Key::Control, _) => return Err(Alarm::syntax(line, "OSCTRL[axis]=(set options, reset options)")),
        _ => (eval_f64(expr, &ctx, line)?, 0),
    };
    let valid = match key {
        Key::On => value == 0.0 || value == 1.0,
        Key::Stop1 | Key::Stop2 => value.is_finite() && value >= -2.0,
        Key::Strokes => value.is_finite() && value >= 0.0 && value.fract() == 0.0 && value <= 1e6,
        Key::Control => bits(value).is_some(),
        _ => value.is_finite(),
    };
    if !valid {
        return Err(Alarm::value_out_of_range(line, &label(value)));
    }
    if out.iter().any(|w| w.axis == axis && w.key == key) {
        return Err(Alarm::syntax(line, &label(value)));
    }
    out.push(OscWord { key, axis, value, reset });
    Ok(())
}

/// A whole number of OSCTRL bits (0 ..= 1023).
fn bits(v: f64) -> Option<u32> {
    (v.is_finite() && v.fract() == 0.0 && (0.0..1024.0).contains(&v)).then_some(v as u32)
}

impl Settings {
    /// Stores a setting word (not `OS`).
    pub fn set(&mut self, w: &OscWord) {
        match w.key {
            Key::Point1 => self.point1 = w.value,
            Key::Point2 => self.point2 = w.value,
            Key::Stop1 => self.stop1 = w.value,
            Key::Stop2 => self.stop2 = w.value,
            Key::End => self.end = Some(w.value),
            Key::Start => self.start = Some(w.value),
            Key::Strokes => self.strokes = w.value as u32,
            Key::Control => self.control = (self.control | w.value as u32) & !w.reset,
            Key::On => {}
        }
    }
}

impl crate::interp::Interpreter {
    /// The block's oscillation words before its path motion: settings stored, `OS[ax]=1`
    /// started, `OS[ax]=0` ended (the blocks after it wait for the axis to stand), and new
    /// settings of an oscillating axis handed to the main run.
    pub(in crate::interp) fn oscillation_block(
        &mut self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let path_axes = words.axes.iter().fold(0u32, |m, a| m | 1 << a.0);
        let mut touched = 0u32;
        for w in &words.oscillation {
            self.positioning_axes.oscillation.settings[w.axis].set(w);
            touched |= 1 << w.axis;
        }
        for k in (0..MAX_CHANNEL_AXES).filter(|&k| touched & (1 << k) != 0) {
            let on = words.oscillation.iter().find(|w| w.axis == k && w.key == Key::On).map(|w| w.value == 1.0);
            let oscillating = self.positioning_axes.oscillation.on & (1 << k) != 0;
            let velocity = self.positioning_axes.velocity(cfg, k);
            match (on, oscillating) {
                (Some(true), _) | (None, true) => {
                    if path_axes & (1 << k) != 0 {
                        return Err(Alarm::repeated_address(line, cfg.program_axis_name(k)));
                    }
                    super::positioning::refused(k, self.offsets.trafo.as_ref(), &self.offsets.frame, cfg, line)?;
                    let osc = self.oscillation_in_machine(cfg, k, line)?;
                    let first = match osc.start {
                        Some(start) if osc.control & ctrl::FROM_START != 0 => start,
                        _ => osc.point1,
                    };
                    let motion = Motion::Oscillate(osc);
                    self.trc.emit_or_defer(Item::Positioning { axis: k, target: first, velocity, motion, line }, out);
                    self.positioning_axes.oscillation.on |= 1 << k;
                    self.positioning_axes.posa_open |= 1 << k;
                }
                (Some(false), true) => {
                    let motion = Motion::EndOscillation;
                    let target = self.pos[k];
                    self.trc.emit_or_defer(Item::Positioning { axis: k, target, velocity, motion, line }, out);
                    self.positioning_axes.oscillation.on &= !(1 << k);
                    self.positioning_axes.oscillation.adopt |= 1 << k;
                    self.sync_wait = crate::interp::synchronized::PrepWait::UntilIdle;
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Axis `k`'s settings in machine positions, through the frame as POSA values.
    fn oscillation_in_machine(&mut self, cfg: &MachineConfig, k: usize, line: u32) -> Result<Oscillation, Alarm> {
        let s = self.positioning_axes.oscillation.settings[k];
        let mut machine = |value: f64| -> Result<f64, Alarm> {
            let word = PosWord { kind: Kind::Posa, axis: k, value, mode: Some(CoordMode::Ac), parts: None };
            Ok(self.positioning_targets(&[word], cfg, line)?.0[k])
        };
        let (point1, point2) = (machine(s.point1)?, machine(s.point2)?);
        let end = s.end.map(&mut machine).transpose()?;
        let start = s.start.map(&mut machine).transpose()?;
        if point1 == point2 {
            let name = cfg.program_axis_name(k);
            return Err(Alarm::value_out_of_range(line, &format!("OSP1[{name}] = OSP2[{name}] = {}", s.point1)));
        }
        let dwell = |t: f64| t.max(0.0);
        Ok(Oscillation {
            point1,
            point2,
            dwell1: dwell(s.stop1),
            dwell2: dwell(s.stop2),
            end,
            start,
            strokes: s.strokes,
            control: s.control,
        })
    }

    /// The axes whose oscillation ended and whose position preparation takes from the main run
    /// once it stands (bit k: channel axis k).
    pub fn axes_to_adopt(&self) -> u32 {
        self.positioning_axes.oscillation.adopt
    }

    /// Takes the main run's `machine` positions of [`Interpreter::axes_to_adopt`] as the
    /// programmed ones (the main run is idle: every oscillation has ended).
    pub fn adopt_axes(&mut self, machine: &AxisVec) {
        let adopt = std::mem::take(&mut self.positioning_axes.oscillation.adopt);
        for k in (0..MAX_CHANNEL_AXES).filter(|&k| adopt & (1 << k) != 0) {
            self.pos[k] = machine[k];
        }
        self.before_change = None;
    }
}
