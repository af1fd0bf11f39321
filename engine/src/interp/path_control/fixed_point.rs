//! `G74` (reference point approach from the program) and `G75 FP=n` (fixed point approach),
//! G group 2, non-modal: the axes named in the block travel as machine axes to a position the
//! machine data give, whatever frame, tool offset or G90/G91 is active. The values written
//! after the axis names (`G75 FP=1 Z1`, `G74 X0 Y0`) are not positions; they only name the
//! axes. Typical end of a program: `G75 FP=1 Z1` (the spindle up to the tool-change point),
//! then `G75 FP=1 X1 Y1`.
//!
//! - `G75 FP=n`: the target of each axis is MD30600 `$MA_FIX_POINT_POS[n-1, ax]`; n runs
//!   1..MD30610 `$MA_NUM_FIX_POINT_POS` of that axis (default 0: no fixed point, so `G75` is
//!   refused with 12560 until the data define one). `G75` without `FP` is `FP=1`.
//! - `G74`: the target is MD34100 `$MA_REFP_SET_POS[0]`, the reference point. The axes are
//!   referenced already (NCTwin's axes are, or the JOG reference point approach did it), so
//!   the travel to the reference point is a rapid move there; the cam and zero-mark search of
//!   `channel/reference/approach.rs` is not repeated.
//! - Both run at rapid traverse, interpolated linearly in machine space (the control moves
//!   each axis at its own rapid velocity; with one axis per block, as programs write them, the
//!   two are the same), with exact stop at the end. An axis under an active transformation:
//!   17620 (G75) / 17630 (G74), as on the control; with G41/G42 active: 12560 (decision: the
//!   control's radius compensation cannot follow a machine-axis move).

use crate::alarm::Alarm;
use crate::interp::modal::Words;
use crate::interp::{Interpreter, Item};
use crate::machine_data::MachineConfig;
use crate::motion::{AxisLimit, Feed, Move, Path};

/// Which of the two approaches a block asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Approach {
    /// G74: to the reference point (MD34100).
    Reference,
    /// G75: to a fixed point (MD30600, `FP=`).
    FixedPoint,
}

impl Approach {
    fn code(self) -> &'static str {
        match self {
            Approach::Reference => "G74",
            Approach::FixedPoint => "G75",
        }
    }
}

impl Interpreter {
    /// Prepares the block's G74/G75 move: each named axis to its machine-data position.
    pub(in crate::interp) fn fixed_point_block(
        &mut self,
        approach: Approach,
        words: &Words,
        cfg: &MachineConfig,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let code = approach.code();
        if words.axes.is_empty() {
            return Err(Alarm::syntax(line, &format!("{code} needs the axes that travel")));
        }
        if self.offsets.trafo.is_some() {
            let axis = cfg.program_axis_name(words.axes[0].0);
            return Err(Alarm::fixed_point_transformed(line, approach == Approach::Reference, axis));
        }
        if self.modal.trc.is_some() {
            return Err(Alarm::value_out_of_range(line, &format!("{code} with G41/G42 active")));
        }
        let fp = match (approach, words.fixed_point_number) {
            (Approach::Reference, Some(_)) => return Err(Alarm::syntax(line, "FP= belongs to G75")),
            (_, n) => n.unwrap_or(1),
        };
        let mut end = self.pos;
        for &(k, _, _) in &words.axes {
            let m = cfg.channel_axes[k].machine_axis;
            end[k] = match approach {
                Approach::Reference => self.stored.num("$MA_REFP_SET_POS", m, 0),
                Approach::FixedPoint => {
                    let count = self.stored.num("$MA_NUM_FIX_POINT_POS", m, 0);
                    if fp == 0 || f64::from(fp) > count {
                        return Err(Alarm::value_out_of_range(
                            line,
                            &format!(
                                "G75 FP={fp}: axis {} has {count} fixed points (MD30610)",
                                cfg.program_axis_name(k)
                            ),
                        ));
                    }
                    self.stored.num("$MA_FIX_POINT_POS", m, fp as usize - 1)
                }
            };
        }
        let start = self.pos;
        let length = start.iter().zip(&end).map(|(s, e)| (e - s).powi(2)).sum::<f64>().sqrt();
        let path = Path::line(start, end);
        super::super::check_software_limits(cfg, &path, line)?;
        let limits = AxisLimit::for_channel(cfg);
        self.pos = end;
        let mv = Move::new(path, length, Feed::Rapid, &limits, true, line);
        let offsets = self.shared_offsets();
        out.push(Item::Move { mv, line, offsets });
        Ok(())
    }
}
