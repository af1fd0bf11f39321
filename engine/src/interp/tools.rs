//! Orientable toolholders (TCARR, TOFRAME, TOROT) and the swivel cycle CYCLE800 that drives
//! them; tool selection and change by number or name (`management.rs`); NEWT/DELT
//! (`create_delete.rs`).

pub mod active_swivel;
pub(super) mod create_delete;
pub(super) mod dnumbers;
pub(super) mod management;
pub(super) mod programmable_offset;
pub mod setpiece;
pub(super) mod swivel;
pub mod toolholder;
