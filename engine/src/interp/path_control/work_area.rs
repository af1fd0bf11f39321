//! Working-area limitation in the basic coordinate system (Function Manual A3): per axis a lower
//! limit SD43430 `$SA_WORKAREA_LIMIT_MINUS` and an upper one SD43420 `$SA_WORKAREA_LIMIT_PLUS`,
//! each checked while SD43410 `$SA_WORKAREA_MINUS_ENABLE` / SD43400 `$SA_WORKAREA_PLUS_ENABLE`
//! is TRUE and G group 28 is `WALIMON` (the reset value); `WALIMOF` switches the check off.
//!
//! - `G25 X.. Y..` / `G26 X.. Y..` (without S: with S they are the spindle speed limits) write
//!   the lower / upper limits of the named axes into the setting data, as the control does;
//!   the values are BCS positions (no frame applies), the axes do not move.
//! - A move whose tool tip (the BCS: machine position less the tool offset) would end outside
//!   the area (an arc: leave it anywhere) is refused at block preparation with 10730 naming the
//!   axis and the side, as the control refuses a programmed end point behind the limitation.
//!
//! Cost: the limits are read once per change of the stored data ([`WorkArea::of`]); without
//! an enabled limit the check is one `Option` test, and the fast lane stays open.

use crate::alarm::Alarm;
use crate::machine_data::{MachineConfig, MachineData};
use crate::motion::{AxisVec, Path};

/// The enabled limits per channel axis (`None`: that side is not checked).
#[derive(Debug, Clone, PartialEq)]
pub struct WorkArea {
    limits: Vec<(Option<f64>, Option<f64>)>,
}

impl WorkArea {
    /// The limits the stored setting data enable; `None` when no axis has one.
    pub fn of(stored: &MachineData, cfg: &MachineConfig) -> Option<Box<WorkArea>> {
        let mut any = false;
        let limits = cfg
            .channel_axes
            .iter()
            .map(|a| {
                let m = a.machine_axis;
                let on = |name: &str| stored.num(name, m, 0) != 0.0;
                let minus = on("$SA_WORKAREA_MINUS_ENABLE").then(|| stored.num("$SA_WORKAREA_LIMIT_MINUS", m, 0));
                let plus = on("$SA_WORKAREA_PLUS_ENABLE").then(|| stored.num("$SA_WORKAREA_LIMIT_PLUS", m, 0));
                any |= minus.is_some() || plus.is_some();
                (minus, plus)
            })
            .collect();
        any.then(|| Box::new(WorkArea { limits }))
    }

    /// 10730 when the end of `path` (machine coordinates of the channel axes; an arc: any of
    /// its points) less `tool` lies outside an enabled limit.
    pub fn check(&self, cfg: &MachineConfig, path: &Path, tool: &AxisVec, line: u32) -> Result<(), Alarm> {
        // A line is checked at its end point (a move from outside back into the area passes,
        // as on the control), an arc over its whole extent.
        let (lo, hi) = match path.arc {
            None => (path.end, path.end),
            Some(_) => path.extent(),
        };
        for (k, (minus, plus)) in self.limits.iter().enumerate() {
            let name = || cfg.program_axis_name(k);
            if plus.is_some_and(|p| hi[k] - tool[k] > p + 1e-9) {
                return Err(Alarm::work_area_limit(line, name(), true));
            }
            if minus.is_some_and(|m| lo[k] - tool[k] < m - 1e-9) {
                return Err(Alarm::work_area_limit(line, name(), false));
            }
        }
        Ok(())
    }
}

/// The NC data lines `G25 X..` (`upper` false) or `G26 X..` write: one per axis word.
pub(in crate::interp) fn limit_lines(
    stored: &MachineData,
    cfg: &MachineConfig,
    upper: bool,
    axes: &[(usize, f64, Option<crate::lang::CoordMode>)],
    length_factor: f64,
) -> Vec<String> {
    let name = if upper { "$SA_WORKAREA_LIMIT_PLUS" } else { "$SA_WORKAREA_LIMIT_MINUS" };
    axes.iter()
        .map(|&(k, v, _)| {
            let axis = crate::interp::eval::machine_data::axis_index_for_text(
                stored,
                cfg,
                name,
                cfg.program_axis_name(k).to_string(),
            );
            let v = if cfg.axis(k).rotary { v } else { v * length_factor };
            format!("{name}[{axis}]={v:?}")
        })
        .collect()
}
