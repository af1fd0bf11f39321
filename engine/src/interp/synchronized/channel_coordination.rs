//! The program coordination words that name other channels or hand axes between channels
//! (Programming Manual Job planning, "Program coordination" and "Axis replacement"), in a
//! control with one channel: NCTwin runs one channel per session.
//!
//! - `WAITE(n, ..)`: wait for the end of the program in channels n, ... Channel 1 is the
//!   program's own: waiting for its own end would never end, and any other channel does not
//!   exist; both give 12560 (the manual's alarm for a wait on a channel not configured). The
//!   Job planning text names no alarm number for the own channel; NCTwin's decision is the
//!   same 12560 as for a missing channel, as `WAITM` gives for a channel other than 1.
//! - `GET(ax, ..)`, `GETD(ax, ..)`: fetch axes into the channel (GETD directly, without the
//!   other channel's RELEASE); `RELEASE(ax, ..)`: give them free for another channel. An axis
//!   of the channel is already there and no other channel can take it: no effect, and no
//!   preprocessing stop. A name that is no channel axis: 12550.

use crate::alarm::Alarm;
use crate::interp::eval::eval_f64;
use crate::interp::eval::scope::Ctx;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;

/// Whether `name` is one of WAITE, GET, GETD, RELEASE.
pub(in crate::interp) fn is_keyword(name: &str) -> bool {
    matches!(name, "WAITE" | "GET" | "GETD" | "RELEASE")
}

/// Checks a WAITE, GET, GETD or RELEASE statement (see the module doc); nothing to do after.
pub(in crate::interp) fn statement(
    name: &str,
    args: &[Expr],
    cfg: &MachineConfig,
    ctx: &Ctx,
    line: u32,
) -> Result<(), Alarm> {
    if args.is_empty() {
        let what = if name == "WAITE" { "channel numbers" } else { "axis names" };
        return Err(Alarm::syntax(line, &format!("{name} needs {what}")));
    }
    for e in args {
        if name == "WAITE" {
            let n = eval_f64(e, ctx, line)?;
            let why = if n == 1.0 { "the program's own channel" } else { "no such channel" };
            return Err(Alarm::value_out_of_range(line, &format!("WAITE({}): {why}", Alarm::shown(n))));
        }
        let axis = match e {
            Expr::Var { name, indices } if indices.is_empty() => cfg.program_axis(name).map(|_| ()),
            _ => None,
        };
        if axis.is_none() {
            return Err(Alarm::unknown_name(line, &format!("{name}: not an axis of the channel")));
        }
    }
    Ok(())
}
