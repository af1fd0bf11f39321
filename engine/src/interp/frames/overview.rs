//! The active frame chain link by link, for the work-offset screen's overview (Operate's
//! "Work offset > Overview": basic frames, settable frame, programmable frame, total).
//!
//! Input: the interpreter's frame state. Output: each link of `$P_ACTFRAME` (REFERENCE.md
//! section 1) as stored frame data (translation, rotation angles per MD10600, scale, mirror),
//! and the total. The links are preparation's: in a running program they may already hold
//! a block the main run has not reached; at rest (and after a preprocessing stop) they are
//! the main run's.

use super::vars::ChainFrame;
use crate::interp::Interpreter;
use crate::interp::eval::scope::sys_view;
use crate::machine_data::{FrameData, MachineConfig};

/// One link of the active frame chain.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainLink {
    /// Its system variable (`$P_ACTBFRAME`, `$P_IFRAME`, ...; `$P_ACTFRAME` for the total).
    pub name: &'static str,
    /// The frame as stored frame data for the channel axes (`None`: a linear part that is no
    /// rotation with scale and mirror, which frame data cannot hold).
    pub data: Option<FrameData>,
}

fn var_name(link: ChainFrame) -> &'static str {
    match link {
        ChainFrame::Part => "$P_PARTFRAME",
        ChainFrame::Set => "$P_SETFRAME",
        ChainFrame::Ext => "$P_EXTFRAME",
        ChainFrame::ActB => "$P_ACTBFRAME",
        ChainFrame::I => "$P_IFRAME",
        ChainFrame::Tool => "$P_TOOLFRAME",
        ChainFrame::Wp => "$P_WPFRAME",
        ChainFrame::Tra => "$P_TRAFRAME",
        ChainFrame::P => "$P_PFRAME",
        ChainFrame::Cyc => "$P_CYCFRAME",
    }
}

impl Interpreter {
    /// Every link of the active frame chain from the BCS towards the WCS, then the total
    /// (`$P_ACTFRAME`).
    pub fn frame_chain(&self, cfg: &MachineConfig) -> Vec<ChainLink> {
        let sys = sys_view!(self, cfg);
        let n = cfg.channel_axes.len();
        let data = |f: &super::frame::Frame| f.to_data(&cfg.geo_axes, n, cfg.frame_angles);
        let mut links: Vec<ChainLink> = ChainFrame::ORDER
            .iter()
            .map(|&l| ChainLink { name: var_name(l), data: data(&sys.chain_frame(l)) })
            .collect();
        links.push(ChainLink { name: "$P_ACTFRAME", data: data(&sys.chain(None)) });
        links
    }
}
