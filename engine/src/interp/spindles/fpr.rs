//! `FPR(axis)`: the rotary axis or spindle a feed per revolution refers to (Programming
//! Manual "Job planning", "Revolutional feed rate with reference to a rotary axis or spindle";
//! Function Manual V1 "Feedrates"). Under G95 (and G96/G97, G33 threads keep the master
//! spindle) the path moves F mm per revolution of that axis instead of the master spindle:
//! `FPR(C)` names a rotary axis, `FPR(SPI(2))` spindle 2 (a spindle with an axis name also
//! by that name).
//!
//! Decisions where the manuals leave it open: the reference stays until reset or program end
//! (then the master spindle again); a rotary axis that is no spindle counts by its actual
//! speed in the main run, and as it can only move on the path in NCTwin (no positioning
//! axes), a per-revolution block that moves that axis itself is refused (12560); a linear axis
//! is refused (12560).

use super::axis_of;
use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::Ctx;
use crate::interp::{Interpreter, Item};
use crate::lang::Expr;
use crate::machine_data::MachineConfig;
use crate::motion::Move;

/// The channel axis `FPR(arg)` names.
pub(in crate::interp) fn statement(args: &[Expr], ctx: &Ctx, cfg: &MachineConfig, line: u32) -> Result<usize, Alarm> {
    let [arg] = args else { return Err(Alarm::syntax(line, "FPR(rotary axis or SPI(n))")) };
    let spindle = |n: f64| -> Result<usize, Alarm> {
        if (1.0..=32.0).contains(&n) && n.fract() == 0.0 {
            axis_of(cfg, n as u32, line, "FPR")
        } else {
            Err(Alarm::value_out_of_range(line, &format!("FPR(SPI({n}))")))
        }
    };
    let k = match arg {
        Expr::Call(f, a) if f == "SPI" && a.len() == 1 => {
            spindle(eval(&a[0], ctx, line)?.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?)?
        }
        e => {
            let name = eval(e, ctx, line)?.as_text().to_ascii_uppercase();
            cfg.program_axis(&name).ok_or_else(|| Alarm::unknown_name(line, &format!("FPR({name})")))?
        }
    };
    if !cfg.axis(k).rotary {
        return Err(Alarm::value_out_of_range(line, &format!("FPR({}): no rotary axis", cfg.program_axis_name(k))));
    }
    Ok(k)
}

impl Interpreter {
    /// FPR in a block: the reference changes for the main run before the block's motion.
    pub(in crate::interp) fn select_fpr(&mut self, k: usize, cfg: &MachineConfig, line: u32, out: &mut Vec<Item>) {
        self.spindles.fpr = Some(k);
        self.spindles.fpr_axis_max = cfg.axis(k).spindle.is_none().then(|| cfg.axis(k).max_velocity * 60.0 / 360.0);
        let ctl = super::Control::FeedReference { axis: k };
        self.trc.emit_or_defer(Item::SpindleControl { ctl, line }, out);
    }

    /// A per-revolution move may not move its own FPR axis (its speed would be the feed's).
    pub(in crate::interp) fn check_fpr_move(&self, mv: &Move, cfg: &MachineConfig, line: u32) -> Result<(), Alarm> {
        match self.spindles.fpr {
            Some(k) if (mv.path.end[k] - mv.path.start[k]).abs() > 1e-9 => Err(Alarm::value_out_of_range(
                line,
                &format!("FPR({0}): a feed per revolution of {0} cannot move {0}", cfg.program_axis_name(k)),
            )),
            _ => Ok(()),
        }
    }
}
