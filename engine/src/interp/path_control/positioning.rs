//! Positioning axes in a program (Function Manual P2 "Positioning axes", Programming Manual
//! "POS, POSA, FA, WAITP"): an axis that travels on its own interpolator, outside the path.
//!
//! - `POS[ax]=v`: the axis starts at the block's start; the block ends when the path and the
//!   axis have both arrived (an [`Item::WaitPositioning`] after the block's motion).
//! - `POSA[ax]=v`: the axis travels across block boundaries until `WAITP(ax)`.
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

use crate::alarm::Alarm;
use crate::interp::Item;
use crate::interp::eval::eval_f64;
use crate::interp::eval::indirect_axis;
use crate::interp::eval::scope::{Ctx, SysView};
use crate::interp::eval::vars::Variables;
use crate::lang::{CoordMode, Expr};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::AxisVec;

/// Which positioning word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::interp) enum Kind {
    Pos,
    Posa,
    Fa,
}

/// One `POS[ax]=`, `POSA[ax]=` or `FA[ax]=` word of a block, evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) struct PosWord {
    pub kind: Kind,
    pub axis: usize,
    pub value: f64,
    pub mode: Option<CoordMode>,
}

/// The interpreter's positioning state: the modal FA per axis and the POSA axes without a
/// WAITP yet (bit k: channel axis k).
#[derive(Debug, Clone, Default, PartialEq)]
pub(in crate::interp) struct Positioning {
    /// `FA[ax]` in mm/s (deg/s); 0 = MD32060.
    feed: [f64; MAX_CHANNEL_AXES],
    /// Axes commanded by POSA and not yet waited for.
    pub posa_open: u32,
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
    matches!(name, "POS" | "POSA" | "FA")
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
        _ => Kind::Fa,
    };
    let value = eval_f64(expr, &Ctx { vars, sys }, line)?;
    let label = || format!("{name}[{}]={value}", sys.cfg.program_axis_name(axis));
    if !value.is_finite() || kind == Kind::Fa && (value <= 0.0 || mode.is_some()) {
        return Err(Alarm::value_out_of_range(line, &label()));
    }
    if sys.cfg.axis(axis).spindle.is_some() {
        return Err(Alarm::wrong_axis_type(line, sys.cfg.program_axis_name(axis)));
    }
    // One positioning word per axis and kind in a block.
    if out.iter().any(|w| w.axis == axis && (w.kind == kind || w.kind != Kind::Fa && kind != Kind::Fa)) {
        return Err(Alarm::syntax(line, &label()));
    }
    out.push(PosWord { kind, axis, value, mode });
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
        if sys.cfg.axis(k).spindle.is_some() {
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
        let end = self.positioning_targets(words, cfg, line)?;
        let mut pos_mask = 0;
        for w in words.positioning.iter().filter(|w| w.kind != Kind::Fa) {
            let k = w.axis;
            let velocity = self.positioning_axes.velocity(cfg, k);
            self.trc.emit_or_defer(Item::Positioning { axis: k, target: end[k], velocity, line }, out);
            self.pos[k] = end[k];
            match w.kind {
                Kind::Pos => {
                    pos_mask |= 1 << k;
                    self.positioning_axes.posa_open &= !(1 << k);
                }
                _ => self.positioning_axes.posa_open |= 1 << k,
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

    /// The machine end positions of the block's POS/POSA words: each value in the WCS (G90/G91,
    /// AC/IC, DC/ACP/ACN on modulo axes, diameter programming) through the frame and the tool
    /// offset, like a path word of that axis.
    fn positioning_targets(
        &mut self,
        words: &crate::interp::modal::Words,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<AxisVec, Alarm> {
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
        for w in words.positioning.iter().filter(|w| w.kind != Kind::Fa) {
            let k = w.axis;
            target[k] = self.axis_word_target(cfg, k, (w.value, w.mode), current[k], current[k], line)?;
            programmed[k] = true;
        }
        // Only the positioning axes' own components are used: a frame that couples the
        // geometry axes (a rotation) would move the others too, which a positioning axis cannot.
        let mut only = programmed;
        let end = crate::interp::block_end(frame, geo, n, &start, &tool, &target, &mut only);
        let mut result = start;
        for k in (0..n).filter(|&k| programmed[k]) {
            result[k] = end[k];
        }
        Ok(result)
    }
}
