//! The everyday words of shop and CAM programs that change nothing NCTwin models, or change it
//! in a simple way, sorted out of a block's words before the general keyword handling:
//!
//! - `FNORM`, `FLIN`, `FCUB` (G group 37, feed profile): FNORM, the reset value, is the constant
//!   programmed feed NCTwin runs; FLIN and FCUB (feed ramped linearly or as a spline over the
//!   block) are accepted and run as FNORM's constant feed for now.
//! - `DRFOF`: clears the handwheel (DRF) offsets; NCTwin applies none, so there is nothing to clear.
//!   `CORROF()`, `CORROF(X,"DRF")`, `CORROF(X,"AA_OFF")` (deselect DRF and `$AA_OFF` offsets,
//!   all or per axis, as tool-change and measuring cycles do) likewise.
//! - `WAITS`, `WAITS(n, ..)`: wait for the spindles a SPOSA positions. NCTwin runs SPOSA like
//!   SPOS, its block ending when the spindle stands at its angle, so there is nothing left to
//!   wait for.
//! - `SBLOF`/`SBLON` (single-block suppression) and `DISPLOF`/`DISPLON` (block display of a
//!   cycle) in a block: no word of the block's own; they act on the blocks after them
//!   (`calls/suppression.rs`).
//! - `GROUP_BEGIN(..)`/`GROUP_END(..)`: the program editor's structure markers; no effect.
//! - `ACTBLOCNO` in a block (on the PROC line it keeps a DISPLOF subprogram's alarms at its own
//!   block: `calls.rs`, `alarm_as_displayed`).
//! - `FIFOCTRL`, `STOPFIFO`, `STARTFIFO` (how full the preprocessing buffer is kept before the
//!   main run starts): NCTwin prepares a bounded number of items ahead (`channel::LOOKAHEAD`)
//!   and its preparation takes no simulated time, so the buffer is never what the main run
//!   waits for; the path and its timing come out the same. Accepted.
//! - `IPTRLOCK`/`IPTRUNLOCK` (freeze the block search's interruption pointer at the block of a
//!   section, e.g. a probing cycle, so a search after an interruption starts before it): NCTwin
//!   keeps no interruption pointer for the operator's search; accepted.
//! - `LFON`/`LFOF`, `LFTXT`/`LFWP`/`LFPOS`, `ALF=`, `DILF=` (fast retraction from a thread after
//!   NC stop or an alarm): the retraction is not modelled, an NC stop in G33 brakes on the path as
//!   in any block. Accepted; `ALF=` (0..8) and `DILF=` (≥ 0) are checked (12560).
//! - `H5`, `H=5`, `H2=5`: auxiliary functions for the PLC (with address extension); `M2=3`-style
//!   M functions with an address extension. They go to the main run as `Item::Aux` and are
//!   published there (`auxiliary.rs`); `M<n>=3/4/5` also act on spindle n, which must be the
//!   master spindle (the only spindle the interpreter commands).

use crate::alarm::Alarm;

/// True for a keyword without arguments that needs no action (see the module doc).
pub(super) fn is_inert_keyword(name: &str, has_args: bool) -> bool {
    match name {
        "FNORM" | "FLIN" | "FCUB" | "DRFOF" | "SBLOF" | "SBLON" | "DISPLOF" | "DISPLON" | "ACTBLOCNO" => !has_args,
        "FIFOCTRL" | "STOPFIFO" | "STARTFIFO" | "IPTRLOCK" | "IPTRUNLOCK" | "LFON" | "LFOF" | "LFTXT" | "LFWP"
        | "LFPOS" => !has_args,
        "GROUP_BEGIN" | "GROUP_END" | "CORROF" | "WAITS" => true,
        _ => false,
    }
}

/// `ALF=` (retraction direction code 0..8) and `DILF=` (retraction length, mm): checked and
/// accepted (see the module doc); `false` for any other address.
pub(super) fn retraction_address(name: &str, value: f64, line: u32) -> Result<bool, Alarm> {
    let ok = match name {
        "ALF" => (0.0..=8.0).contains(&value) && value.fract() == 0.0,
        "DILF" => value >= 0.0 && value.is_finite(),
        _ => return Ok(false),
    };
    if !ok {
        return Err(Alarm::value_out_of_range(line, &format!("{name}={}", Alarm::shown(value))));
    }
    Ok(true)
}

/// An address with an extension, `H2`, `M1`, `S2`: the letter and the extension number.
pub(super) fn extended_address(name: &str) -> Option<(u8, u32)> {
    let (letter, digits) = name.split_at_checked(1)?;
    let letter = letter.as_bytes()[0];
    if !matches!(letter, b'H' | b'M' | b'S') || digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some((letter, digits.parse().ok()?))
}

/// The value of an M function with address extension `M<ext>=<value>`: the spindle direction
/// it sets (M3, M4, M5 of spindle `ext`), if any.
pub(super) fn extended_m(ext: u32, value: f64, line: u32) -> Result<Option<i8>, Alarm> {
    if value < 0.0 || value.fract() != 0.0 || value > 99_999.0 {
        return Err(Alarm::value_out_of_range(line, &format!("M{ext}={value}")));
    }
    Ok(match value as u32 {
        3 => Some(1),
        4 => Some(-1),
        5 => Some(0),
        0 | 1 | 2 | 17 | 30 => {
            return Err(Alarm::unknown_name(
                line,
                &format!("M{ext}={value} (program control has no address extension)"),
            ));
        }
        _ => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extended_addresses_are_h_or_m_with_digits() {
        assert_eq!(extended_address("H2"), Some((b'H', 2)));
        assert_eq!(extended_address("M12"), Some((b'M', 12)));
        assert_eq!(extended_address("H"), None);
        assert_eq!(extended_address("MA"), None);
        assert_eq!(extended_address("X1"), None);
    }
}
