//! Coordinate frames between workpiece and basic coordinate system: the frame type and chain,
//! the cached active frame, the frame system variables and rotations by solid angles.

pub(super) mod cache;
pub mod frame;
pub(super) mod incremental;
pub mod overview;
pub(super) mod preset;
pub(super) mod solid_angles;
pub(super) mod vars;
