//! Online tool length offset (Transformations Function Manual F2 §3.12): `$AA_TOFF[X|Y|Z]`,
//! `TOFFON(dir[, value])`, `TOFFOF([dir])`. The offset lengthens (positive) or shifts the tool
//! in the tool coordinate system (Z = along the tool in the zero position, X and Y across it)
//! and acts through the active transformation, so the machine axes compensate while the tool
//! tip stays on the programmed path; without a transformation it adds to the geometry axes.
//!
//! Conventions of this product where the manual is silent or the real control differs:
//! * The real control writes `$AA_TOFF` in synchronized actions. Here a program assignment
//!   `$AA_TOFF[Z]=v` is accepted and acts from its block on in the main run (like a tool
//!   change travelling with its block); MD21190 `TOFF_MODE` = 1 adds `v` to the offset in force.
//! * The main run traverses every change with MD21194 `TOFF_VELO` and MD21196 `TOFF_ACCEL`.
//! * `TOFFON(dir, v)` sets the offset of one direction to `v` (without `v` it keeps the value);
//!   `TOFFOF(dir)` / `TOFFOF()` takes it (them) back to 0 with the same traversing motion (the
//!   real control keeps the deselected share in the position display instead).
//! * The offset survives reset and program end (no axis moves in reset state); reading
//!   `$AA_TOFF[dir]` waits for the main run (preprocessing stop) and returns the offset the
//!   main run has reached.

use crate::alarm::Alarm;
use crate::interp::Interpreter;
use crate::interp::frames::frame::GeoAxes;
use crate::kinematics::ActiveTrafo;
use crate::machine_data::MachineConfig;
use crate::motion::AxisVec;

/// The machine position the main run reaches for the prepared position with the online offset
/// `toff` in force (what `$AA_IM` reads): with a transformation the BCS point of `machine`
/// (prepared without the offset) mapped back with the lengthened tool; without one the
/// programmed position `pos` plus the offset on the geometry axes.
pub(in crate::interp) fn machine_in_force(
    trafo: Option<&ActiveTrafo>,
    machine: Option<&AxisVec>,
    pos: &AxisVec,
    toff: &[f64; 3],
    geo: &GeoAxes,
) -> AxisVec {
    match (trafo, machine) {
        (Some(t), Some(m)) if *toff != [0.0; 3] => t.lengthened(toff).inverse(&t.forward(m), m).unwrap_or(*m),
        (_, Some(m)) => *m,
        (_, None) => {
            let mut out = *pos;
            for (g, k) in geo.iter().enumerate() {
                if let Some(k) = k {
                    out[*k] += toff[g];
                }
            }
            out
        }
    }
}

/// One online-offset instruction of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ToffOp {
    /// `$AA_TOFF[dir] = value`.
    Write { dir: usize, value: f64 },
    /// `TOFFON(dir[, value])`.
    On { dir: usize, value: Option<f64> },
    /// `TOFFOF(dir)`, or every direction without one.
    Off { dir: Option<usize> },
}

/// The tool direction (0 = X, 1 = Y, 2 = Z) a geometry axis name stands for.
pub(in crate::interp) fn direction(cfg: &MachineConfig, name: &str, line: u32) -> Result<usize, Alarm> {
    cfg.program_axis(name)
        .and_then(|k| cfg.geo_axes.iter().position(|g| *g == Some(k)))
        .ok_or_else(|| Alarm::value_out_of_range(line, &format!("tool direction {name} (a geometry axis X, Y or Z)")))
}

impl Interpreter {
    /// Applies a block's online-offset instructions to the offsets that travel with it.
    pub(in crate::interp) fn online_tool_offset(&mut self, ops: &[ToffOp], cfg: &MachineConfig) {
        for op in ops {
            let toff = &mut self.offsets.toff;
            match *op {
                ToffOp::Write { dir, value } if cfg.ori.toff_integrating => toff[dir] += value,
                ToffOp::Write { dir, value } => toff[dir] = value,
                ToffOp::On { dir, value } => toff[dir] = value.unwrap_or(toff[dir]),
                ToffOp::Off { dir: Some(d) } => toff[d] = 0.0,
                ToffOp::Off { dir: None } => *toff = [0.0; 3],
            }
        }
    }
}
