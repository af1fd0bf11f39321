//! Positioning axes in a program (Function Manual P2 "Positioning axes", Programming Manual
//! "POS, POSA, FA, WAITP"): an axis that travels on its own interpolator, outside the path.
//!
//! - `POS[ax]=v`: the axis starts at the block's start; the block ends when the path and the
//!   axis have both arrived (an [`Item::WaitPositioning`] after the block's motion).
//! - `POSA[ax]=v`: the axis travels across block boundaries until `WAITP(ax)`.
//! - `POSP[ax]=(end, part length, mode)`: like POS, but the axis reaches its end in parts of
//!   the given length, standing still at the end of each; mode 0 (default) splits the last
//!   stretch longer than one part into two equal halves, mode 1 shortens every part equally so
//!   that a whole number of parts ends on the end point (Programming Manual "Positioning in
//!   parts"). 10 mm in parts of 3: mode 0 3, 3, 2, 2; mode 1 4 × 2.5.
//! - `FA[ax]=f`: the axis' feed (mm/min, rotary deg/min), modal per axis; without it MD32060
//!   `$MA_POS_AX_VELO`. Reset returns every axis to MD32060.
//! - Values take `AC`/`IC` and on modulo rotary axes `DC`/`ACP`/`ACN`, with G90/G91 as the
//!   default, and go through the frame like the axis' path words (only that axis' component).
//!
//! Modelled as follows where the manuals leave room:
//! - A path block that programs an axis commanded by `POSA` without a `WAITP` since waits for
//!   the path before it (the axis can only be checked in the main run) and then raises alarm
//!   14092 if the axis is still travelling; if it has arrived the block runs. The fast lane
//!   steps aside while a POSA axis has no WAITP yet.
//! - `POS`/`POSA` again on a travelling POSA axis retargets it from where it is.
//! - POSP ends its block like POS (the manuals give it no block change of its own); its end
//!   takes G90/G91 only (the list leaves no room for `AC(..)`), and its parts are counted in the
//!   WCS, so a scale or inch programming scales them with the axis.
//! - Under a transformation an axis the transformation drives (or a geometry axis) cannot be a
//!   positioning axis: alarm 17610 (F2: the transformation does not act on positioning axes).
//!   Under a frame with a rotation a geometry axis cannot be one: alarm 16430 (its direction in
//!   the rotated system would move several machine axes; the control does not take only the
//!   axis' own component). Other axes (a rotary axis, an axis outside the geometry) position
//!   through their own frame component as before.

use crate::alarm::Alarm;
use crate::interp::Item;
use crate::interp::eval::eval_f64;
use crate::interp::eval::indirect_axis;
use crate::interp::eval::scope::{Ctx, SysView};
use crate::interp::eval::vars::Variables;
use crate::kinematics::Transformation;
use crate::lang::{COEFFICIENTS, CoordMode, Expr};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// Which positioning word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::interp) enum Kind {
    Pos,
    Posa,
    Posp,
    Fa,
}

/// How a program's positioning axis travels (the main run's `Item::Positioning`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// POS: the block waits for it.
    Pos,
    /// POSA: it runs on across blocks until WAITP.
    Posa,
    /// POSP: like POS, in parts.
    Posp(Parts),
    /// OS[ax]=1: to and fro between the reversal points (`oscillation.rs`); `target` is the
    /// first point it travels to. Again while it oscillates: the new settings.
    Oscillate(super::oscillation::Oscillation),
    /// OS[ax]=0: the oscillation ends as its control bits say.
    EndOscillation,
}

/// The parts of a POSP motion: every part `length` long (machine units, > 0), except that with
/// `halves` the last stretch longer than one part is halved (mode 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parts {
    pub length: f64,
    pub halves: bool,
}

impl Parts {
    /// The parts for the whole way from `start` to `end`: mode 1 (`!halves`) shortens the part
    /// so that a whole number of them fits; mode 0 keeps it.
    pub fn for_way(self, start: f64, end: f64) -> Parts {
        if self.halves {
            return self;
        }
        let distance = (end - start).abs();
        // The relative tolerance keeps 9/3 at three parts despite rounding in the division.
        let n = (distance / self.length * (1.0 - 1e-12)).ceil().max(1.0);
        Parts { length: distance / n, halves: false }
    }

    /// Where the part that starts at `at` ends, on the way to `end`.
    pub fn next_end(self, at: f64, end: f64) -> f64 {
        let rest = end - at;
        let tolerance = self.length * 1e-9;
        if rest.abs() <= self.length + tolerance {
            end
        } else if self.halves && rest.abs() <= 2.0 * self.length + tolerance {
            at + rest / 2.0
        } else {
            at + rest.signum() * self.length
        }
    }
}

/// One `POS[ax]=`, `POSA[ax]=` or `FA[ax]=` word of a block, evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct PosWord {
    pub kind: Kind,
    pub axis: usize,
    pub value: f64,
    pub mode: Option<CoordMode>,
    /// POSP: the part length in program units and whether mode 0 halves the last stretch.
    pub parts: Option<(f64, bool)>,
}

/// The interpreter's positioning state: the modal FA per axis and the POSA axes without a
/// WAITP yet (bit k: channel axis k).
#[derive(Debug, Clone, Default, PartialEq)]
pub(in crate::interp) struct Positioning {
    /// `FA[ax]` in mm/s (deg/s); 0 = MD32060.
    feed: [f64; MAX_CHANNEL_AXES],
    /// Axes commanded by POSA (or oscillating) and not yet waited for.
    pub posa_open: u32,
    /// OS, OSP1, ... per axis (`oscillation.rs`).
    pub oscillation: super::oscillation::Oscillations,
}

impl Positioning {
    /// The feed an axis positions with, in mm/s or deg/s.
    pub fn velocity(&self, cfg: &MachineConfig, k: usize) -> f64 {
        let ax = cfg.axis(k);
        let f = if self.feed[k] > 0.0 { self.feed[k] } else { ax.pos_velocity };
        f.min(ax.max_velocity)
    }
}

/// Whether `name[..]=` is a word of this module.
pub(in crate::interp) fn is_word(name: &str) -> bool {
    matches!(name, "POS" | "POSA" | "POSP" | "FA")
}

/// Evaluates `POS[ax]=`/`POSA[ax]=`/`FA[ax]=` into `out`.
#[allow(clippy::too_many_arguments)]
pub(in crate::interp) fn word(
    out: &mut Vec<PosWord>,
    name: &str,
    index: &Expr,
    expr: &Expr,
    mode: Option<CoordMode>,
    vars: &Variables,
    sys: &SysView,
    line: u32,
) -> Result<(), Alarm> {
    let axis = indirect_axis::resolve(index, vars, sys, line)?;
    let kind = match name {
        "POS" => Kind::Pos,
        "POSA" => Kind::Posa,
        "POSP" => Kind::Posp,
        _ => Kind::Fa,
    };
    let (expr, parts) = match kind {
        Kind::Posp => {
            let (end, length, halves) = posp_list(expr, vars, sys, line)?;
            (end, Some((length, halves)))
        }
        _ => (expr, None),
    };
    let value = eval_f64(expr, &Ctx { vars, sys }, line)?;
    let label = || format!("{name}[{}]={value}", sys.cfg.program_axis_name(axis));
    if !value.is_finite() || kind == Kind::Fa && (value <= 0.0 || mode.is_some()) {
        return Err(Alarm::value_out_of_range(line, &label()));
    }
    // A spindle is a positioning axis only in position control (after SPOS, M19 or M70).
    if sys.cfg.axis(axis).spindle.is_some() && !sys.positioned[axis] {
        return Err(Alarm::wrong_axis_type(line, sys.cfg.program_axis_name(axis)));
    }
    // One positioning word per axis and kind in a block.
    if out.iter().any(|w| w.axis == axis && (w.kind == kind || w.kind != Kind::Fa && kind != Kind::Fa)) {
        return Err(Alarm::syntax(line, &label()));
    }
    out.push(PosWord { kind, axis, value, mode, parts });
    Ok(())
}

/// `POSP[ax]=(end, part length[, mode])`: the end's expression and the part length and mode,
/// checked (a length above 0, mode 0 or 1).
fn posp_list<'a>(expr: &'a Expr, vars: &Variables, sys: &SysView, line: u32) -> Result<(&'a Expr, f64, bool), Alarm> {
    let items = match expr {
        Expr::Call(name, items) if name == COEFFICIENTS && (2..=3).contains(&items.len()) => items,
        _ => return Err(Alarm::syntax(line, "POSP[axis]=(end position, part length, mode)")),
    };
    let ctx = Ctx { vars, sys };
    let length = eval_f64(&items[1], &ctx, line)?;
    let mode = items.get(2).map(|e| eval_f64(e, &ctx, line)).transpose()?.unwrap_or(0.0);
    if !(length.is_finite() && length > 0.0) {
        return Err(Alarm::value_out_of_range(line, &format!("POSP part length {length}")));
    }
    if mode != 0.0 && mode != 1.0 {
        return Err(Alarm::value_out_of_range(line, &format!("POSP mode {mode}")));
    }
    Ok((&items[0], length, mode == 0.0))
}

/// Whether channel axis `k` may not be a positioning (or command) axis now: an axis of the
/// active transformation `trafo` (its geometry, orientation and `TRAFO_AXES_IN_n` axes) is
/// alarm 17610, a geometry axis under a `frame` with a rotation 16430.
pub(crate) fn refused(
    k: usize,
    trafo: Option<&crate::kinematics::ActiveTrafo>,
    frame: &crate::interp::Frame,
    cfg: &MachineConfig,
    line: u32,
) -> Result<(), Alarm> {
    if let Some(t) = trafo {
        let slots = t.trafo.geo_slots().into_iter().chain(t.trafo.orientation_slots()).flatten();
        let in_set =
            cfg.trafos.iter().find(|s| s.number == t.number).into_iter().flat_map(|s| s.axes_in.iter().flatten());
        if slots.chain(t.trafo.machine_slots()).chain(in_set.copied()).any(|a| a == k) {
            return Err(Alarm::positioning_trafo_axis(line, cfg.program_axis_name(k)));
        }
    }
    if frame.couples_axes() && cfg.geo_axes.contains(&Some(k)) {
        return Err(Alarm::positioning_rotated(line, cfg.program_axis_name(k)));
    }
    Ok(())
}

/// `WAITP(ax, ...)`: the axes as a bit mask.
pub(in crate::interp) fn waitp(args: &[Expr], vars: &Variables, sys: &SysView, line: u32) -> Result<u32, Alarm> {
    if args.is_empty() {
        return Err(Alarm::syntax(line, "WAITP needs at least one axis"));
    }
    let mut mask = 0;
    for a in args {
        let k = match a {
            Expr::Str(s) => sys.cfg.program_axis(s).ok_or_else(|| Alarm::unknown_name(line, s))?,
            e => indirect_axis::resolve(e, vars, sys, line)?,
        };
        if sys.cfg.axis(k).spindle.is_some() && !sys.positioned[k] {
            return Err(Alarm::wrong_axis_type(line, sys.cfg.program_axis_name(k)));
        }
        mask |= 1 << k;
    }
    Ok(mask)
}

/// The value a `FA` word stores, mm/s (deg/s) from mm/min (deg/min) in program units.
pub(in crate::interp) fn feed_of(value: f64, rotary: bool, length_factor: f64) -> f64 {
    if rotary { value / 60.0 } else { value * length_factor / 60.0 }
}

impl Positioning {
    /// Stores `FA[ax]`.
    pub fn set_feed(&mut self, k: usize, v: f64) {
        self.feed[k] = v;
    }
}

impl crate::interp::Interpreter {
    /// The block's positioning words before its path motion: FA stored, a path axis that is
    /// still an open POSA axis checked, POS/POSA started, WAITP waited for. Returns the POS
    /// axes (bit mask) the block's end waits for ([`Interpreter::end_positioning_block`]).
    pub(in crate::interp) fn positioning_block(
        &mut self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<u32, Alarm> {
        if words.positioning.is_empty() && words.waitp == 0 && self.positioning_axes.posa_open == 0 {
            return Ok(0);
        }
        let path_axes = words.axes.iter().fold(0u32, |m, a| m | 1 << a.0);
        // An axis is either a path axis or a positioning axis of a block, not both (12000).
        if let Some(w) = words.positioning.iter().find(|w| w.kind != Kind::Fa && path_axes & (1 << w.axis) != 0) {
            return Err(Alarm::repeated_address(line, cfg.program_axis_name(w.axis)));
        }
        let open = self.positioning_axes.posa_open & path_axes;
        if open != 0 {
            self.trc.emit_or_defer(Item::WaitPositioning { axes: open, strict: true, line }, out);
            self.positioning_axes.posa_open &= !open;
        }
        if words.waitp != 0 {
            self.trc.emit_or_defer(Item::WaitPositioning { axes: words.waitp, strict: false, line }, out);
            self.positioning_axes.posa_open &= !words.waitp;
        }
        let f = self.modal.length_factor();
        for w in words.positioning.iter().filter(|w| w.kind == Kind::Fa) {
            self.positioning_axes.set_feed(w.axis, feed_of(w.value, cfg.axis(w.axis).rotary, f));
        }
        if words.positioning.iter().all(|w| w.kind == Kind::Fa) {
            return Ok(0);
        }
        self.check_positioning_axes(words, cfg, line)?;
        let (end, scale) = self.positioning_targets(&words.positioning, cfg, line)?;
        let mut pos_mask = 0;
        for w in words.positioning.iter().filter(|w| w.kind != Kind::Fa) {
            let k = w.axis;
            let velocity = self.positioning_axes.velocity(cfg, k);
            let motion = match (w.kind, w.parts) {
                (Kind::Posa, _) => Motion::Posa,
                (Kind::Posp, Some((length, halves))) => {
                    let factor = if cfg.axis(k).rotary { 1.0 } else { self.modal.length_factor() };
                    Motion::Posp(Parts { length: length * factor * scale[k], halves })
                }
                _ => Motion::Pos,
            };
            self.trc.emit_or_defer(Item::Positioning { axis: k, target: end[k], velocity, motion, line }, out);
            self.pos[k] = end[k];
            match w.kind {
                Kind::Posa => self.positioning_axes.posa_open |= 1 << k,
                _ => {
                    pos_mask |= 1 << k;
                    self.positioning_axes.posa_open &= !(1 << k);
                }
            }
        }
        Ok(pos_mask)
    }

    /// After the block's motion: a POS block ends when its positioning axes have arrived.
    pub(in crate::interp) fn end_positioning_block(&mut self, pos_mask: u32, line: u32, out: &mut Vec<Item>) {
        if pos_mask != 0 {
            self.trc.emit_or_defer(Item::WaitPositioning { axes: pos_mask, strict: false, line }, out);
        }
    }

    /// An axis of the active transformation (17610) or a geometry axis in a rotated frame
    /// (16430) cannot be a positioning axis.
    fn check_positioning_axes(
        &self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let offsets = &self.offsets;
        words
            .positioning
            .iter()
            .filter(|w| w.kind != Kind::Fa)
            .try_for_each(|w| refused(w.axis, offsets.trafo.as_ref(), &offsets.frame, cfg, line))
    }

    /// The machine end positions of the block's POS/POSA/POSP words: each value in the WCS
    /// (G90/G91, AC/IC, DC/ACP/ACN on modulo axes, diameter programming) through the frame and
    /// the tool offset, like a path word of that axis; and per axis the factor from WCS to
    /// machine distances (the frame's scale, 1 where the axis does not move).
    pub(super) fn positioning_targets(
        &mut self,
        words: &[PosWord],
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(AxisVec, AxisVec), Alarm> {
        let n = cfg.channel_axes.len();
        let geo = &cfg.geo_axes;
        let start = self.pos;
        let tool = self.offsets.tool;
        let frame = &self.offsets.frame;
        let mut basic = start;
        for k in 0..n {
            basic[k] -= tool[k];
        }
        let current =
            frame.unapply(geo, &basic).ok_or_else(|| Alarm::value_out_of_range(line, "frame with scale 0"))?;
        let mut target = current;
        let mut programmed = [false; MAX_CHANNEL_AXES];
        for w in words.iter().filter(|w| w.kind != Kind::Fa) {
            let k = w.axis;
            target[k] = self.axis_word_target(cfg, k, (w.value, w.mode), current[k], current[k], line)?;
            programmed[k] = true;
        }
        // Only the positioning axes' own components are used (a geometry axis in a rotated
        // frame was refused above).
        let mut only = programmed;
        let end = crate::interp::block_end(frame, geo, n, &start, &tool, &target, &mut only);
        let mut result = start;
        let mut scale = [1.0; MAX_CHANNEL_AXES];
        for k in (0..n).filter(|&k| programmed[k]) {
            result[k] = end[k];
            if target[k] != current[k] {
                scale[k] = ((end[k] - start[k]) / (target[k] - current[k])).abs();
            }
        }
        Ok((result, scale))
    }
}
