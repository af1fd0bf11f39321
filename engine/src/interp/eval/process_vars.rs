//! Workpiece counters, program runtimes and the clock, as programs read them (Function Manual
//! K1 and Programming Manual Job Planning, "Program runtime / workpiece counter"):
//!
//! - `$AC_REQUIRED_PARTS`, `$AC_TOTAL_PARTS`, `$AC_ACTUAL_PARTS`, `$AC_SPECIAL_PARTS` (INT,
//!   0..999,999,999, read and write). The main run counts them (`channel/counters.rs`); a
//!   program's write reaches it in block order ([`crate::interp::Item::MainRunWrite`]).
//! - `$AC_OPERATING_TIME`, `$AC_CYCLE_TIME`, `$AC_CUTTING_TIME` (REAL seconds, read only).
//!
//!   Like every `$AC_` variable, a block reading these waits for the main run (the control's
//!   implicit preprocessing stop), so it reads what the main run has counted up to its block.
//! - `$AN_POWERON_TIME`, `$AN_SETUP_TIME` (REAL minutes): since the session's channel was
//!   created, NCTwin's power on (with default values: a new session starts from them).
//! - `$A_YEAR`, `$A_MONTH`, `$A_DAY`, `$A_HOUR`, `$A_MINUTE`, `$A_SECOND`, `$A_MSECOND` (INT):
//!   the channel's clock, in UTC, read after the main run (as the `$AC_` variables): the wall time the shell gave when the session started
//!   (`Channel::set_clock`) plus the simulated time since, so a replay reads the same date
//!   and a simulation faster than real time stamps its log with the time its machine would
//!   have. Without a clock set it starts at 1970-01-01 00:00.
//! - `$P_CHANNO` (INT): the channel's number, 1. `$P_NUM_SPINDLES` (INT): the channel's
//!   spindles. `$P_DRYRUN` (BOOL): the dry-run feed (DRY) acts on the blocks being prepared.

use crate::alarm::Alarm;
use crate::interp::eval::scope::SysView;
use crate::interp::eval::value::Value;

/// The largest count a workpiece counter holds.
pub const MAX_PARTS: i64 = 999_999_999;

/// The workpiece counters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PartCounts {
    /// `$AC_REQUIRED_PARTS`.
    pub required: u32,
    /// `$AC_TOTAL_PARTS`.
    pub total: u32,
    /// `$AC_ACTUAL_PARTS`.
    pub actual: u32,
    /// `$AC_SPECIAL_PARTS`.
    pub special: u32,
}

/// A workpiece counter as a program names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartCounter {
    Required,
    Total,
    Actual,
    Special,
}

impl PartCounter {
    /// The counter named `name` (`$AC_ACTUAL_PARTS`..), if it is one.
    pub fn named(name: &str) -> Option<PartCounter> {
        Some(match name {
            "$AC_REQUIRED_PARTS" => PartCounter::Required,
            "$AC_TOTAL_PARTS" => PartCounter::Total,
            "$AC_ACTUAL_PARTS" => PartCounter::Actual,
            "$AC_SPECIAL_PARTS" => PartCounter::Special,
            _ => return None,
        })
    }
}

impl PartCounts {
    pub fn get(&self, counter: PartCounter) -> u32 {
        match counter {
            PartCounter::Required => self.required,
            PartCounter::Total => self.total,
            PartCounter::Actual => self.actual,
            PartCounter::Special => self.special,
        }
    }

    pub fn get_mut(&mut self, counter: PartCounter) -> &mut u32 {
        match counter {
            PartCounter::Required => &mut self.required,
            PartCounter::Total => &mut self.total,
            PartCounter::Actual => &mut self.actual,
            PartCounter::Special => &mut self.special,
        }
    }
}

/// The program runtimes in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Runtimes {
    /// `$AC_OPERATING_TIME`: all programs in AUTO mode, start to end.
    pub operating: f64,
    /// `$AC_CYCLE_TIME`: the program started last, start to end.
    pub cycle: f64,
    /// `$AC_CUTTING_TIME`: path motion other than rapid traverse.
    pub cutting: f64,
}

/// What the main run counts and the clock, as the channel last handed them to preparation.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ProcessData {
    pub parts: PartCounts,
    pub times: Runtimes,
    /// The channel's clock in milliseconds since 1970-01-01 00:00 UTC.
    pub clock_ms: i64,
    /// Seconds since the channel was created.
    pub powered_on_s: f64,
}

/// The value of `name`, or `None` if it is not one of these variables.
pub(in crate::interp) fn read(sys: &SysView, name: &str, indices: &[Value], line: u32) -> Option<Result<Value, Alarm>> {
    let p = sys.process;
    let value = match name {
        "$AC_OPERATING_TIME" => Value::Real(p.times.operating),
        "$AC_CYCLE_TIME" => Value::Real(p.times.cycle),
        "$AC_CUTTING_TIME" => Value::Real(p.times.cutting),
        "$AN_POWERON_TIME" | "$AN_SETUP_TIME" => Value::Real(p.powered_on_s / 60.0),
        "$P_CHANNO" => Value::Int(1),
        "$P_NUM_SPINDLES" => {
            Value::Int((0..sys.cfg.channel_axes.len()).filter(|&k| sys.cfg.axis(k).spindle.is_some()).count() as i64)
        }
        "$P_DRYRUN" => Value::Bool(sys.env.dry_run),
        _ if is_clock_name(name) => Value::Int(clock_field(p.clock_ms, name)?),
        _ => Value::Int(p.parts.get(PartCounter::named(name)?).into()),
    };
    if !indices.is_empty() {
        return Some(Err(Alarm::index_error(line, name, "takes no index")));
    }
    Some(Ok(value))
}

/// Whether `name` is one of the clock's variables: like the other actual values of the main
/// run, a block reading one waits for the main run, so a log line after a dwell stamps the
/// time after it.
pub fn is_clock_name(name: &str) -> bool {
    matches!(name, "$A_YEAR" | "$A_MONTH" | "$A_DAY" | "$A_HOUR" | "$A_MINUTE" | "$A_SECOND" | "$A_MSECOND")
}

/// `$A_YEAR`.. of the clock at `ms`; `None` for another name.
fn clock_field(ms: i64, name: &str) -> Option<i64> {
    let field = |t: time::OffsetDateTime| -> Option<i64> {
        Some(match name {
            "$A_YEAR" => t.year().into(),
            "$A_MONTH" => u8::from(t.month()).into(),
            "$A_DAY" => t.day().into(),
            "$A_HOUR" => t.hour().into(),
            "$A_MINUTE" => t.minute().into(),
            "$A_SECOND" => t.second().into(),
            "$A_MSECOND" => t.millisecond().into(),
            _ => return None,
        })
    };
    // A clock outside the years the calendar covers reads as its epoch.
    let t = time::OffsetDateTime::from_unix_timestamp_nanos(i128::from(ms) * 1_000_000)
        .unwrap_or(time::OffsetDateTime::UNIX_EPOCH);
    field(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clock_reads_as_the_calendar_date_and_time_in_utc() {
        // 2026-11-27 10:21:05.250 UTC: 20,784 days after 1970-01-01 (56 years with 14 leap
        // days: 56 * 365 + 14 = 20,454 to 2026-01-01, then 330 days to Nov 27), then
        // 10 h 21 min 5.25 s.
        let ms = (20_784 * 86_400 + 10 * 3600 + 21 * 60 + 5) * 1000 + 250;
        let read = |name| clock_field(ms, name).unwrap();
        assert_eq!(
            [read("$A_YEAR"), read("$A_MONTH"), read("$A_DAY"), read("$A_HOUR"), read("$A_MINUTE")],
            [2026, 11, 27, 10, 21]
        );
        assert_eq!([read("$A_SECOND"), read("$A_MSECOND")], [5, 250]);
        assert_eq!(clock_field(0, "$A_YEAR"), Some(1970));
        assert_eq!(clock_field(0, "$A_WEEKDAY"), None);
    }
}
