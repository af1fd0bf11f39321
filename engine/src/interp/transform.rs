//! The interpreter's side of the kinematic transformations: selecting and deselecting them
//! (TRANSMIT, TRACYL, TRAANG, TRAORI, TRACON, TRAFOOF) and correcting kinematic chains with
//! CORRTRAFO.

pub(super) mod corrtrafo;
pub(super) mod ptp_stat;
pub(super) mod selection;
