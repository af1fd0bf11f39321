//! Orientable toolholders (TCARR, TOFRAME, TOROT) and the swivel cycle CYCLE800 that drives
//! them.

pub(super) mod swivel;
pub mod toolholder;
