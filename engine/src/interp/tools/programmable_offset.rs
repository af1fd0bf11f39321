//! Programmable tool offsets `TOFFL`, `TOFFL[1..3]`, `TOFF[axis]` and `TOFFR` (Programming
//! Manual Fundamentals, "Programmable tool offset"): lengths and a radius added to the active
//! cutting edge's data without changing the tool data, e.g. an allowance for a finishing pass.
//!
//! - `TOFFL=v` (as `TOFFL[1]=v`): added to length L1, `TOFFL[2]`, `TOFFL[3]` to L2 and L3;
//!   they act on the geometry axes L1..L3 act on in the working plane (G17: L1 on Z, L2 on Y,
//!   L3 on X), so they follow a plane change as the lengths do.
//! - `TOFF[X]=v`: an offset parallel to geometry axis X, whatever the plane.
//! - `TOFFR=v`: added to the edge's radius (`$TC_DP6` + `$TC_DP15`) where the tool radius
//!   compensation G41/G42 uses it; like a radius wear, it takes effect with the next block the
//!   compensation prepares.
//! - The values are modal: they stay until overwritten (`=0` ends one) and until the program
//!   starts anew or the channel is reset; a tool change keeps them (NCTwin's decision, the
//!   manual leaves the default to machine data). Like the lengths, they act only while a
//!   cutting edge is active (D0: no tool offset) and become effective with the block's
//!   motion, as a D change does.
//! - `TOFF` with a name that is no geometry axis, an index outside 1..3: 12550 and 17020.
//!
//! `TOFFON`/`TOFFOF` (the online offset `$AA_TOFF`) are another function: `compensation/toff.rs`.

use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::Ctx;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;

/// Which offset a word writes: length component 1..3 (index 0..2) or geometry axis 0..2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    Length(usize),
    Axis(usize),
    Radius,
}

/// The programmed offsets (mm).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ProgrammedOffsets {
    /// TOFFL[1..3]: added to L1, L2, L3.
    pub lengths: [f64; 3],
    /// TOFF[axis] per geometry axis (0 = the first).
    pub axes: [f64; 3],
    /// TOFFR: added to the radius of tool radius compensation.
    pub radius: f64,
}

impl ProgrammedOffsets {
    /// Takes the block's words in their order.
    pub fn apply(&mut self, words: &[(Slot, f64)]) {
        for &(slot, v) in words {
            match slot {
                Slot::Length(i) => self.lengths[i] = v,
                Slot::Axis(g) => self.axes[g] = v,
                Slot::Radius => self.radius = v,
            }
        }
    }
}

/// Whether `name` is one of the words of this module.
pub(in crate::interp) fn is_word(name: &str) -> bool {
    matches!(name, "TOFFL" | "TOFF" | "TOFFR")
}

/// The slot of `TOFFL`, `TOFFL[i]` or `TOFF[axis]`.
pub(in crate::interp) fn slot(
    name: &str,
    indices: &[Expr],
    cfg: &MachineConfig,
    ctx: &Ctx,
    line: u32,
) -> Result<Slot, Alarm> {
    match (name, indices) {
        ("TOFFL", []) => Ok(Slot::Length(0)),
        ("TOFFR", []) => Ok(Slot::Radius),
        ("TOFFL", [i]) => {
            let n = eval(i, ctx, line)?.as_f64().map_err(|e| Alarm::type_error(line, &e.0))?;
            if ![1.0, 2.0, 3.0].contains(&n) {
                return Err(Alarm::index_error(line, "TOFFL", &format!("{} (1..3)", Alarm::shown(n))));
            }
            Ok(Slot::Length(n as usize - 1))
        }
        ("TOFF", [Expr::Var { name: axis, indices: none }]) if none.is_empty() => {
            let k = cfg.program_axis(axis);
            let g = cfg.geo_axes.iter().position(|a| k.is_some() && *a == k);
            g.map(Slot::Axis).ok_or_else(|| Alarm::unknown_name(line, &format!("TOFF[{axis}] (no geometry axis)")))
        }
        _ => Err(Alarm::index_error(line, name, "TOFFL[1..3], TOFF[geometry axis] or TOFFR")),
    }
}
