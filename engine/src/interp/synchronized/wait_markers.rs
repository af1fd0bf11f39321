//! `WAITM(n, ch, ..)` and `WAITMC(n, ch, ..)` in a program (Programming Manual Job planning,
//! program coordination): wait at marker `n` until the channels named have reached it. NCTwin
//! has one channel per session, so the only channel a program may name is 1, which reaches
//! the marker by executing the statement: nothing waits. The channel's markers that
//! synchronized actions set and clear (`SETM`/`CLEARM`) are kept in `channel/program_sync.rs`.

use crate::alarm::Alarm;
use crate::interp::eval::eval_f64;
use crate::interp::eval::scope::Ctx;
use crate::lang::Expr;

/// Checks a WAITM/WAITMC statement: a marker 0..=127 and channel numbers, each of them 1.
pub(in crate::interp) fn statement(name: &str, args: &[Expr], ctx: &Ctx, line: u32) -> Result<(), Alarm> {
    let Some((marker, channels)) = args.split_first() else {
        return Err(Alarm::syntax(line, &format!("{name}(marker, channel, ...)")));
    };
    let n = eval_f64(marker, ctx, line)?;
    if !(0.0..=127.0).contains(&n) || n.fract() != 0.0 {
        return Err(Alarm::value_out_of_range(line, &format!("{name} marker {n}")));
    }
    for c in channels {
        let ch = eval_f64(c, ctx, line)?;
        if ch != 1.0 {
            // Only channel 1 exists.
            return Err(Alarm::value_out_of_range(line, &format!("{name}: channel {ch}")));
        }
    }
    Ok(())
}
