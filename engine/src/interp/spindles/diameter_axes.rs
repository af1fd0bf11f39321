//! The words of axis-specific diameter programming (Programming Manual "Fundamentals",
//! "Axis-specific diameter programming"): `DIAMONA[ax]` (diameters for absolute and
//! incremental values), `DIAM90A[ax]` (diameters for absolute values), `DIAMOFA[ax]`
//! (radius), `DIACYCOFA[ax]` (radius in the cycles, the display as before), `DIAMCHANA[ax]`
//! (the axis takes over the channel's G group 29) and `DIAMCHAN` (every axis released by
//! MD30460 `$MA_BASE_FUNCTION_MASK` bit 2 takes it over). The axis must be released by
//! MD30460 bit 2: else alarm 16510, as for an axis that cannot be a transverse axis.
//!
//! The effect is modal per axis until reset or program end (then the transverse axis of MD20100
//! follows the channel again and every other axis is radius-programmed); `diameter.rs` keeps
//! the state. The WCS display shows the diameter for the transverse axis of MD20100 (whether
//! by the channel's mode or its own) and for every other axis whose values are diameters
//! (`Diameter::display_mask`, carried to the main run in `Offsets::diameter_axes`).

use super::diameter::DiamMode;
use super::words::SpindleWords;
use crate::alarm::Alarm;
use crate::interp::eval::eval;
use crate::interp::eval::scope::Ctx;
use crate::lang::Expr;
use crate::machine_data::MachineConfig;

/// One axis-specific instruction: the axis (`None`: DIAMCHAN, all released axes) and its own
/// mode (`None`: linked to the channel).
pub type AxisDiamOp = (Option<usize>, Option<DiamMode>);

/// Whether `name` is one of this module's words.
pub(in crate::interp) fn is_keyword(name: &str) -> bool {
    matches!(name, "DIAMONA" | "DIAM90A" | "DIAMOFA" | "DIACYCOFA" | "DIAMCHANA" | "DIAMCHAN")
}

/// Reads `name[axis]` (or `DIAMCHAN`) into the block's spindle words.
pub(in crate::interp) fn word(
    w: &mut SpindleWords,
    name: &str,
    args: &[Expr],
    ctx: &Ctx,
    cfg: &MachineConfig,
    line: u32,
) -> Result<(), Alarm> {
    let mode = match name {
        "DIAMONA" => Some(DiamMode::On),
        "DIAM90A" => Some(DiamMode::D90),
        "DIAMOFA" => Some(DiamMode::Of),
        "DIACYCOFA" => Some(DiamMode::CycOf),
        _ => None,
    };
    let axis = match (name, args) {
        ("DIAMCHAN", []) => None,
        ("DIAMCHAN", _) => return Err(Alarm::syntax(line, "DIAMCHAN takes no axis")),
        (_, [e]) => {
            let axis_name = eval(e, ctx, line)?.as_text().to_ascii_uppercase();
            let k = cfg
                .program_axis(&axis_name)
                .ok_or_else(|| Alarm::unknown_name(line, &format!("{name}[{axis_name}]")))?;
            Some(k)
        }
        _ => return Err(Alarm::syntax(line, &format!("{name}[axis] needs one axis"))),
    };
    if w.axis_diameter.iter().any(|(a, _)| *a == axis) {
        return Err(Alarm::conflicting_functions(line, "axis-specific diameter programming twice for one axis"));
    }
    w.axis_diameter.push((axis, mode));
    Ok(())
}
