//! The channel's side of the tools: the tool list the operator edits, tool life and count
//! monitoring while a tool cuts, and the online tool length offset (`$AA_TOFF`).

pub(super) mod list;
pub(super) mod monitor;
pub(super) mod toff;
