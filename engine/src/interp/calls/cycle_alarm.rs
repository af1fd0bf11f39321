//! Cycle alarms (SETAL) raised inside the cycle directories (CST, CMA, CUS) belong to the block
//! that called the cycle: the cycles run with DISPLOF, so the operator sees the call, and the
//! control reports the alarm there. The standard cycles' alarm numbers carry the control's texts.

use super::CallFrame;
use crate::alarm::Alarm;
use crate::programs::Dir;

/// The texts of the standard cycles' alarms (Cycles Programming Manual, "Alarm, error and
/// system messages"; 61000..62999 are the cycle package's numbers).
const TEXTS: &[(u32, &str)] = &[
    (61000, "no tool offset active"),
    (61001, "thread pitch incorrect"),
    (61002, "machining type defined incorrectly"),
    (61003, "no feed programmed in cycle"),
    (61009, "active tool number = 0"),
    (61010, "finishing allowance too large"),
    (61011, "scaling not permissible"),
    (61101, "reference plane defined incorrectly"),
    (61102, "no spindle direction programmed"),
    (61103, "number of holes is zero"),
    (61104, "contour violation of slots/elongated holes"),
    (61105, "cutter radius too large"),
    (61106, "number or position of elements incorrect"),
    (61107, "first drilling depth defined incorrectly"),
    (61108, "no permissible values for parameters _RAD1 and _DP1"),
    (61109, "parameter _CDIR defined incorrectly"),
    (61110, "finishing allowance at bottom > infeed depth"),
    (61111, "infeed width > tool diameter"),
    (61112, "tool radius negative"),
    (61113, "parameter _CRAD for corner radius too large"),
    (61114, "machining direction G41/G42 defined incorrectly"),
    (61115, "approach or retraction mode defined incorrectly"),
    (61116, "approach or retraction path = 0"),
    (61117, "active tool radius <= 0"),
    (61118, "length or width = 0"),
    (61601, "finished part diameter too small"),
    (61602, "tool width defined incorrectly"),
    (61603, "groove form defined incorrectly"),
    (61605, "contour defined incorrectly"),
    (61607, "starting point defined incorrectly"),
    (61608, "wrong cutting edge position programmed"),
    (61609, "form defined incorrectly"),
];

/// `alarm` as the control reports it: a cycle alarm set in a cycle directory's program moves to
/// the line of the block that called the outermost such program, and a standard number without
/// a text of its own gets the manual's text.
pub(in crate::interp) fn at_call(alarm: &Alarm, calls: &[CallFrame]) -> Alarm {
    let mut out = alarm.clone();
    let cycle = calls.iter().find(|f| matches!(f.dir, Some(Dir::Cst | Dir::Cma | Dir::Cus)));
    if let Some(line) = cycle.and_then(|f| f.level.calls.last()).map(|(line, _)| *line) {
        out.line = Some(line);
    }
    let generic = out.message.ends_with(" cycle alarm");
    if let (true, Some((_, text))) = (generic, TEXTS.iter().find(|(n, _)| *n == alarm.number)) {
        out = Alarm::user(
            out.line.unwrap_or(0),
            alarm.number,
            &format!("Channel 1 block {} {text}", out.line.unwrap_or(0)),
        );
    } else if generic {
        out = Alarm::user(out.line.unwrap_or(0), alarm.number, "");
    }
    out
}
