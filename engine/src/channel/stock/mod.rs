//! The channel's side of material removal: the tool cutting the session's blank
//! (`crate::stock`) in every IPO cycle, where the tool stands relative to the blank on lathes,
//! rotary tables and transformed machines, and the stock as the HMI and checkpoints see it.

pub(super) mod cut;
pub(super) mod mesh;
pub(super) mod pose;
pub(super) mod saved;
pub(super) mod spindle;
pub(super) mod table;
pub(super) mod tiles;
