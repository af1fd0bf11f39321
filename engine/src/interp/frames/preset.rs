//! `PRESETON(ax, v, ..)` in a part program block (Programming Manual Job Planning, "Actual value
//! setting with loss of reference"): the machine position of each named axis becomes `v`, without
//! motion, as a machine builder's program resets an endless rotary axis
//! (`PRESETON(A, $AA_IM[A] MOD 360)`) or a slide after a mechanical stop.
//!
//! Preparation knows where the axis will stand when the block is reached (the end of the block
//! before), so it takes the new machine position over at once and the blocks after it are
//! prepared from there; the main run sets the axis when the block is reached, after the motion
//! before it ([`crate::interp::synchronized::MainRunWrite::Preset`]). The frames stay, so the
//! workpiece position moves by the same amount.
//!
//! Decisions where the manual leaves room: the axis stays referenced (a simulated axis has no
//! encoder to lose its reference on); a spindle, an axis while a transformation is active
//! (whose machine positions follow from the geometry axes) and PRESETON under G41/G42 (whose
//! look-ahead holds blocks computed from the old position) are refused with 12550 naming the
//! case.

use crate::alarm::Alarm;
use crate::interp::eval::eval_f64;
use crate::interp::eval::indirect_axis;
use crate::interp::eval::scope::{Ctx, SysView};
use crate::interp::eval::vars::Variables;
use crate::lang::Expr;

/// The axes and machine positions of `PRESETON(ax, v, ax, v, ..)`.
pub(in crate::interp) fn preset_pairs(
    args: &[Expr],
    vars: &Variables,
    sys: &SysView,
    line: u32,
) -> Result<Vec<(usize, f64)>, Alarm> {
    if args.is_empty() || !args.len().is_multiple_of(2) {
        return Err(Alarm::syntax(line, "PRESETON(axis, value, ..) needs pairs of an axis and a value"));
    }
    let mut pairs = Vec::with_capacity(args.len() / 2);
    for pair in args.chunks(2) {
        let k = match &pair[0] {
            Expr::Str(s) => sys.cfg.program_axis(s).ok_or_else(|| Alarm::unknown_name(line, s))?,
            e => indirect_axis::resolve(e, vars, sys, line)?,
        };
        let name = sys.cfg.program_axis_name(k);
        if sys.cfg.axis(k).spindle.is_some() {
            return Err(Alarm::unknown_name(line, &format!("PRESETON({name}) on a spindle")));
        }
        if sys.trafo.machine().is_some() {
            return Err(Alarm::unknown_name(line, &format!("PRESETON({name}) while a transformation is active")));
        }
        if sys.modal.trc.is_some() {
            return Err(Alarm::unknown_name(line, &format!("PRESETON({name}) under tool radius compensation")));
        }
        let v = eval_f64(&pair[1], &Ctx { vars, sys }, line)?;
        if !v.is_finite() {
            return Err(Alarm::value_out_of_range(line, &format!("PRESETON({name}, {v})")));
        }
        pairs.push((k, v));
    }
    Ok(pairs)
}
