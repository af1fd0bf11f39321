//! The frame variables of the active frame chain (REFERENCE.md section 1):
//!
//! `$P_ACTFRAME = $P_PARTFRAME : $P_SETFRAME : $P_EXTFRAME : $P_ACTBFRAME : $P_IFRAME :
//! $P_TOOLFRAME : $P_WPFRAME : $P_TRAFRAME : $P_PFRAME : $P_CYCFRAME`
//!
//! which of them a program reads and writes, and what G53, G153 and SUPA leave of the chain.

use std::borrow::Cow;

use crate::interp::Interpreter;
use crate::interp::eval::scope::SysView;
use crate::interp::frames::frame::Frame;
use crate::machine_data::MachineConfig;

/// One link of the active frame chain, by its system variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChainFrame {
    /// `$P_PARTFRAME` (TCARR, PAROT).
    Part,
    /// `$P_SETFRAME` (actual value setting, PRESETON).
    Set,
    /// `$P_EXTFRAME` (external work offset).
    Ext,
    /// `$P_ACTBFRAME`: the total basic frame (NCU-global, then channel basic frames).
    ActB,
    /// `$P_IFRAME`: the active settable frame.
    I,
    /// `$P_TOOLFRAME` (TOROT, TOFRAME).
    Tool,
    /// `$P_WPFRAME` (workpiece reference points).
    Wp,
    /// `$P_TRAFRAME` (frames of transformations).
    Tra,
    /// `$P_PFRAME`: the programmable frame.
    P,
    /// `$P_CYCFRAME` (cycles, CYCLE800).
    Cyc,
}

impl ChainFrame {
    /// The chain from the BCS towards the WCS.
    pub const ORDER: [ChainFrame; 10] = [
        ChainFrame::Part,
        ChainFrame::Set,
        ChainFrame::Ext,
        ChainFrame::ActB,
        ChainFrame::I,
        ChainFrame::Tool,
        ChainFrame::Wp,
        ChainFrame::Tra,
        ChainFrame::P,
        ChainFrame::Cyc,
    ];

    /// The link a system variable names.
    pub fn of(name: &str) -> Option<ChainFrame> {
        Some(match name {
            "$P_PARTFRAME" => ChainFrame::Part,
            "$P_SETFRAME" => ChainFrame::Set,
            "$P_EXTFRAME" => ChainFrame::Ext,
            "$P_ACTBFRAME" => ChainFrame::ActB,
            "$P_IFRAME" => ChainFrame::I,
            "$P_TOOLFRAME" => ChainFrame::Tool,
            "$P_WPFRAME" => ChainFrame::Wp,
            "$P_TRAFRAME" => ChainFrame::Tra,
            "$P_PFRAME" => ChainFrame::P,
            "$P_CYCFRAME" => ChainFrame::Cyc,
            _ => return None,
        })
    }

    /// A program may assign the link: the programmable and settable frame and the system
    /// frames no function of this product writes. `$P_PARTFRAME`, `$P_TOOLFRAME` and
    /// `$P_CYCFRAME` belong to TCARR/PAROT, TOROT/TOFRAME and CYCLE800; `$P_ACTBFRAME` is the
    /// chain of the stored basic frames (written through `$P_CHBFR`/`$P_NCBFR`).
    pub fn writable(self) -> bool {
        matches!(
            self,
            ChainFrame::Set | ChainFrame::Ext | ChainFrame::I | ChainFrame::Wp | ChainFrame::Tra | ChainFrame::P
        )
    }

    /// G53 keeps the links below the settable frame (BCS to BZS); G153 and SUPA keep none.
    fn kept_by_g53(self) -> bool {
        matches!(self, ChainFrame::Part | ChainFrame::Set | ChainFrame::Ext | ChainFrame::ActB)
    }
}

/// Frame suppression of one block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Suppress {
    /// G53: settable, programmable and the system frames above the basic frame.
    G53,
    /// G153 and SUPA: the whole chain, the basic frames included.
    All,
}

impl SysView<'_> {
    /// The current value of one link.
    pub fn chain_frame(&self, which: ChainFrame) -> Frame {
        self.chain_link(which).into_owned()
    }

    /// [`SysView::chain_frame`] borrowed where the link is stored as a frame (no copy).
    fn chain_link(&self, which: ChainFrame) -> Cow<'_, Frame> {
        let cfg = self.cfg;
        let s = self.system;
        match which {
            ChainFrame::Part => Cow::Borrowed(&s.part),
            ChainFrame::Set => Cow::Borrowed(&s.set),
            ChainFrame::Ext => Cow::Borrowed(&s.ext),
            ChainFrame::ActB => Cow::Owned(crate::interp::basic_frame(cfg)),
            ChainFrame::I => match self.iframe {
                Some(f) => Cow::Borrowed(f),
                None => Cow::Owned(crate::interp::work_offset(cfg, self.modal.work_offset)),
            },
            ChainFrame::Tool => Cow::Borrowed(&s.tool),
            ChainFrame::Wp => Cow::Borrowed(&s.wp),
            ChainFrame::Tra => Cow::Borrowed(&s.tra),
            ChainFrame::P => Cow::Borrowed(self.pframe),
            ChainFrame::Cyc => Cow::Borrowed(&s.cycle),
        }
    }

    /// `$P_ACTFRAME`, or what a block's frame suppression leaves of it.
    pub fn chain(&self, suppress: Option<Suppress>) -> Frame {
        // `frame::chain` over the links, folded as they come: no list of copied links.
        let mut out: Option<Frame> = None;
        let kept = ChainFrame::ORDER.iter().filter(|l| match suppress {
            None => true,
            Some(Suppress::G53) => l.kept_by_g53(),
            Some(Suppress::All) => false,
        });
        for &l in kept {
            let mut f = self.chain_link(l);
            if let Some(rot) = self.trafo.rotary_slot().filter(|_| self.stored(l)) {
                // TRANSMIT/TRACYL put a Cartesian axis into the rotary axis' slot: the
                // offsets the stored frames hold for the rotary axis stay out of it (frames
                // programmed while the transformation is active address the Cartesian axis).
                f.to_mut().trans[rot] = 0.0;
            }
            if f.is_identity() {
                continue;
            }
            out = Some(match out {
                None => f.into_owned(),
                Some(parent) => parent.then(&f, &self.cfg.geo_axes),
            });
        }
        out.unwrap_or_default()
    }
}

impl SysView<'_> {
    /// The link comes from stored data (toolholder, basic frames, `$P_UIFR`), not from a
    /// program's assignment.
    fn stored(&self, link: ChainFrame) -> bool {
        match link {
            ChainFrame::Part | ChainFrame::ActB => true,
            ChainFrame::I => self.iframe.is_none(),
            _ => false,
        }
    }
}

impl Interpreter {
    /// Assigns a writable link (`$P_PFRAME = ...`, `$P_SETFRAME = ...`); it acts at once.
    pub(in crate::interp) fn write_chain_frame(&mut self, which: ChainFrame, f: Frame) {
        let s = &mut self.system;
        match which {
            ChainFrame::P => *self.pframe = f,
            ChainFrame::I => *self.iframe = Some(f),
            ChainFrame::Set => s.set = f,
            ChainFrame::Ext => s.ext = f,
            ChainFrame::Wp => s.wp = f,
            ChainFrame::Tra => s.tra = f,
            ChainFrame::Part | ChainFrame::ActB | ChainFrame::Tool | ChainFrame::Cyc => {}
        }
    }

    /// The active settable frame `$P_IFRAME`.
    pub(in crate::interp) fn iframe(&self, cfg: &MachineConfig) -> Frame {
        (*self.iframe).clone().unwrap_or_else(|| crate::interp::work_offset(cfg, self.modal.work_offset))
    }
}
