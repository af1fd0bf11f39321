//! Tool orientation under an orientation transformation (TRAORI): the orientation words of a
//! block, rotation about the tool axis, orientation polynomials and curves, directly programmed
//! rotary axes, and the orientation system variables.

pub(super) mod curve;
pub(super) mod direct;
pub(super) mod path_frame;
pub(super) mod poly;
pub(super) mod rotation;
pub(super) mod vars;
pub(super) mod words;
