//! Incremental moves after a change of offsets (SD42440 `$SC_FRAME_OFFSET_INCR_PROG`, SD42442
//! `$SC_TOOL_OFFSET_INCR_PROG`): with the control's defaults, `TRANS X100` then `X=IC(1)` after
//! a move to X1 ends at WCS X2 (machine X102): the increment counts from the position
//! programmed before the change, so the change itself is travelled too. With a setting datum
//! at 0 the increment counts from where the machine stands, seen through the new offsets.
//!
//! The offsets of the last motion block are noted at the first change after it; the next
//! motion block takes the note. A note is only used while the programmed position is the one
//! it was taken at (a transformation or a swivel that moved the axes in between drops it).

use crate::interp::Interpreter;
use crate::interp::frames::frame::Frame;
use crate::machine_data::MachineConfig;
use crate::motion::AxisVec;

/// The offsets before the first change since the last motion block.
#[derive(Debug, Clone)]
pub(in crate::interp) struct BeforeChange {
    frame: Frame,
    tool: AxisVec,
    pos: AxisVec,
}

impl Interpreter {
    /// Notes the offsets in effect, unless a change since the last motion block was noted
    /// already. Called just before the frame or the tool offset changes.
    pub(in crate::interp) fn note_offsets_before_change(&mut self) {
        if self.before_change.is_none() {
            let (frame, tool, pos) = (self.offsets.frame.clone(), self.offsets.tool, self.pos);
            self.before_change = Some(Box::new(BeforeChange { frame, tool, pos }));
        }
    }
}

/// The WCS position a motion block's incremental axes count from when the offsets changed
/// since the last motion block (`before`, taken from the interpreter by the motion block), or
/// `None` when they count from the machine's position seen through the new offsets (`frame`,
/// `tool`) as usual.
pub(in crate::interp) fn incremental_start(
    before: Option<Box<BeforeChange>>,
    cfg: &MachineConfig,
    frame: &Frame,
    tool: &AxisVec,
    pos: &AxisVec,
) -> Option<AxisVec> {
    let before = before.filter(|b| b.pos == *pos)?;
    let travels = cfg.incremental_travels;
    if !travels.frame && !travels.tool {
        return None;
    }
    let frame = if travels.frame { &before.frame } else { frame };
    let tool = if travels.tool { &before.tool } else { tool };
    let mut basic = *pos;
    for (b, t) in basic.iter_mut().zip(tool).take(cfg.channel_axes.len()) {
        *b -= t;
    }
    frame.unapply(&cfg.geo_axes, &basic)
}
