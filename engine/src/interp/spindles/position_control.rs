//! `SPCON` / `SPCOF` (Programming Manual Fundamentals, "Switching over to position control";
//! Function Manual S1): `SPCON` switches the master spindle, `SPCON(n, m, ..)` spindles n, m,
//! from speed control to position control; `SPCOF` (or `SPCOF(n, ..)`) back. Modal: the
//! spindle keeps turning at its speed (M3/M4/S act as before) but in a closed position loop,
//! so a later SPOS needs no switch-over. NCTwin's spindle model follows the programmed speed
//! either way; the switch shows in the state (`SpindleState::position_control`). SPCOF also
//! ends an axis mode of SPOS/M19/M70: the spindle is in speed control again, stopped.
//! A spindle number the channel does not have: 12560; more than one SPCON/SPCOF per block:
//! 12080 (the manual allows one of them in a block).

use super::{Control, axis_of};
use crate::alarm::Alarm;
use crate::interp::eval::eval_f64;
use crate::interp::eval::scope::Ctx;
use crate::interp::{Interpreter, Item};
use crate::lang::Expr;
use crate::machine_data::MachineConfig;

/// The block's SPCON or SPCOF: position control on or off for the spindles numbered (empty:
/// the master spindle).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Switch {
    pub on: bool,
    pub spindles: Vec<u32>,
}

/// Reads `SPCON`, `SPCON(n, ..)`, `SPCOF`, `SPCOF(n, ..)`.
pub(in crate::interp) fn statement(name: &str, args: &[Expr], ctx: &Ctx, line: u32) -> Result<Switch, Alarm> {
    let mut spindles = Vec::with_capacity(args.len());
    for e in args {
        let n = eval_f64(e, ctx, line)?;
        if !(1.0..=32.0).contains(&n) || n.fract() != 0.0 {
            return Err(Alarm::value_out_of_range(line, &format!("{name}({})", Alarm::shown(n))));
        }
        spindles.push(n as u32);
    }
    Ok(Switch { on: name == "SPCON", spindles })
}

impl Interpreter {
    /// The block's SPCON/SPCOF to the main run, in order with the block's other spindle items.
    pub(in crate::interp) fn position_control_block(
        &mut self,
        switch: Option<&Switch>,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let Some(sw) = switch else { return Ok(()) };
        let name = if sw.on { "SPCON" } else { "SPCOF" };
        let mut axes = Vec::with_capacity(sw.spindles.len().max(1));
        for &n in &sw.spindles {
            axes.push(axis_of(cfg, n, line, &format!("{name}({n})"))?);
        }
        if sw.spindles.is_empty() {
            // Without a spindle number: the master spindle; a machine without one ignores it.
            axes.extend(self.spindles.master());
        }
        for axis in axes {
            if !sw.on {
                // Speed control again: axis words need SPOS before they position it.
                self.positioned[axis] = false;
            }
            self.trc
                .emit_or_defer(Item::SpindleControl { ctl: Control::PositionControl { axis, on: sw.on }, line }, out);
        }
        Ok(())
    }
}
