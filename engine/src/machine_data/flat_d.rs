//! The flat D-number structure (Function Manual W1 "Flat D number structure"; MD18102
//! `$MN_MM_TYPE_OF_CUTTING_EDGE` = 1): D numbers 1..32000 name offset data sets directly,
//! without reference to a tool. The data are `$TC_DPx[d]` (one index); T is still programmed,
//! shown and put out, but a tool change leaves the active D as it is, and `D<n>` selects data
//! set n whatever the tool (17180 when it is not defined). With MD18102 = 0 (the default) the
//! D numbers are relative to their tool: `$TC_DPx[t, d]`.
//!
//! NCTwin keeps the flat data sets under tool number 0 of the edge table; [`edge_key`] is the
//! one place that maps an active tool and D number to their data set.

use super::{EdgeParams, MachineConfig};

/// The highest flat D number.
pub const MAX_FLAT_D: i64 = 32_000;

/// The key of the offset data set of edge `d` of tool `t` in [`MachineConfig::tools`].
pub fn edge_key(cfg: &MachineConfig, t: u32, d: u32) -> (u32, u32) {
    if cfg.flat_d { (0, d) } else { (t, d) }
}

impl MachineConfig {
    /// The offset data of D number `d` with tool `t` active (`None` for D0 or no data).
    pub fn edge(&self, t: u32, d: u32) -> Option<&EdgeParams> {
        if d == 0 { None } else { self.tools.get(&edge_key(self, t, d)) }
    }
}
