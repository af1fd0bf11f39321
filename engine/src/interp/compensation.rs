//! Tool compensations applied to the programmed path: the tool radius compensation (G41/G42,
//! its approach and retract, DISC, KONTC, bottleneck look-ahead, turning tools' cutting edge
//! positions) and the online tool length offset TOFF.

pub mod approach;
pub(super) mod bottleneck;
pub(super) mod cutting_edge;
pub(super) mod disc;
pub(super) mod distant;
pub(super) mod kontc;
pub(super) mod rounding;
pub mod sar;
mod sar_block;
pub(super) mod toff;
pub mod trc;
