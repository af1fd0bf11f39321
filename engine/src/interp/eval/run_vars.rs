//! System variables that describe how the program runs rather than what the machine does:
//!
//! - `$P_SIM` (BOOL): TRUE while the program runs in a simulation. Operate sets it in its
//!   simulation (and the machine's program test), so programs skip what only the real machine
//!   can do: `IF $P_SIM GOTOF SKIP_PROBE`. NCTwin's channel is the machine: a program run over
//!   REST or by `nctwin simulate` reads FALSE, so probing and PLC handshakes run as written; the
//!   HMI's preview (`POST .../preview`, a throwaway copy that draws the path) is Operate's
//!   simulation and reads TRUE ([`RunEnv::simulation`], set by `Channel::set_simulation`).
//! - `$P_ISTEST` (BOOL): program test (PRT, axes held while the program runs). NCTwin has no
//!   program test mode, so FALSE.
//! - `$P_PROG_EVENT` (INT): the event that started an event-driven program (PROG_EVENT, 1 start,
//!   2 end, 3 reset, 4 power up, 5 after block search). NCTwin starts none: 0, as in a part
//!   program the operator started.
//! - `$AC_PROG` (INT): the program status, 0 not started, 1 running, 2 stopped, 3 waiting,
//!   4 aborted. A program reading it runs: 1.
//! - `$P_SUBPAR[n]` (BOOL): whether the call of the running subprogram gave its n-th parameter
//!   (`NAME(1,,3)`: 1 and 3 TRUE, 2 FALSE); FALSE in the main program and beyond the arguments
//!   written; n < 1: 17020.
//! - `$P_SEARCH` (INT): 1 while a block search (with calculation, `channel/search.rs`)
//!   prepares the blocks up to its target, else 0 (K1: "`$P_SEARCH == 1` ; block search
//!   active"); tool-change programs skip what the search must not do: `IF $P_SEARCH GOTOF ..`.
//!   The blocks from the target on, prepared after the search, read 0.
//! - `$P_SEARCHL` (INT): the type of the last block search, set when it starts and kept until
//!   the next program start (the control resets it with RESET): 0 none, 2 with calculation
//!   to the contour (K1's numbering: 1 without calculation, 2 to the contour, 4 to the block
//!   end point, 5 SERUPRO). NCTwin's search is type 2.
//! - `$P_MSNUM` / `$AC_MSNUM` (INT): the number of the master spindle (SETMS or MD20090), 0
//!   without one. Preparation and main run agree because SETMS reaches the main run in order.

use crate::alarm::Alarm;
use crate::interp::eval::scope::SysView;
use crate::interp::eval::value::Value;

/// How the channel runs its programs, as the shell set it up.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RunEnv {
    /// The run is a simulation (the HMI's preview): `$P_SIM` reads TRUE.
    pub simulation: bool,
    /// A block search prepares blocks up to its target: `$P_SEARCH` reads 1.
    pub searching: bool,
    /// The type of the last block search since the program started (`$P_SEARCHL`), 0 none.
    pub last_search: u8,
    /// The dry-run feed (DRY) acts on the blocks prepared now (`$P_DRYRUN`).
    pub dry_run: bool,
}

/// `$P_SEARCHL` of NCTwin's block search: with calculation to the contour.
pub const SEARCH_TO_CONTOUR: u8 = 2;

/// The value of `name`, or `None` if it is not one of these variables.
pub(in crate::interp) fn read(sys: &SysView, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
    if name == "$P_SUBPAR" {
        return Some(subpar(sys, indices, line));
    }
    let value = match name {
        "$P_SIM" => Value::Bool(sys.env.simulation),
        "$P_ISTEST" => Value::Bool(false),
        "$P_SEARCH" => Value::Int(sys.env.searching.into()),
        "$P_SEARCHL" => Value::Int(sys.env.last_search.into()),
        "$P_PROG_EVENT" => Value::Int(0),
        "$AC_PROG" => Value::Int(1),
        "$P_MSNUM" | "$AC_MSNUM" => {
            let master = sys.spindles.master().and_then(|k| sys.cfg.axis(k).spindle);
            Value::Int(master.unwrap_or(0).into())
        }
        _ => return None,
    };
    if !indices.is_empty() {
        return Some(Err(Alarm::index_error(line, name, "takes no index")));
    }
    Some(Ok(value))
}

fn subpar(sys: &SysView, indices: &[Value], line: u32) -> Result<Value, Alarm> {
    let [n] = indices else { return Err(Alarm::index_error(line, "$P_SUBPAR", "needs one parameter number")) };
    let n = n.as_i64().map_err(|e| Alarm::type_error(line, &e.0))?;
    let k = usize::try_from(n - 1).map_err(|_| Alarm::index_error(line, "$P_SUBPAR", &format!("parameter {n}")))?;
    Ok(Value::Bool(sys.call_args.get(k).is_some_and(Option::is_some)))
}
