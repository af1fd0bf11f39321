//! The stock in a checkpoint (the channel state's `stock`, absent in checkpoints written
//! before): a restarted session keeps the cut part, its volumes and its settings. The checks'
//! findings are not kept (a restart starts their list afresh).

use super::cut::StockOptions;
use crate::channel::Channel;
use crate::stock::holder::Holder;
use crate::stock::saved;

/// The saved stock.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SavedStock {
    /// Format of `data` ([`saved::FORMAT`]).
    pub format: u32,
    /// The stock, base64 of the run-length coded binary (`saved.rs`).
    pub data: String,
    /// The blank's volume when it was defined, mm³.
    pub initial_volume: f64,
    /// The settings: resolution of the next blank, depth limit, holder sections.
    pub resolution: f64,
    pub depth_limit: Option<f64>,
    #[cfg_attr(feature = "serde", serde(default))]
    pub holder: Vec<[f64; 2]>,
}

impl Channel {
    /// The stock for a checkpoint; `None` without a blank.
    pub(in crate::channel) fn saved_stock(&self) -> Option<SavedStock> {
        let (stock, initial_volume) = self.stock_parts()?;
        let o = self.stock_options;
        Some(SavedStock {
            format: saved::FORMAT,
            data: saved::encode(stock),
            initial_volume,
            resolution: o.resolution,
            depth_limit: o.depth_limit,
            holder: o.holder.map(|h| h.sections().to_vec()).unwrap_or_default(),
        })
    }

    /// Takes back the stock of a checkpoint after the rest of it. A stock that does not decode
    /// is dropped (the session comes back without a blank rather than not at all). The saved
    /// stock is the program's blank already cut: a blank a block search collected on the way
    /// would replace it uncut, so that one goes.
    pub(in crate::channel) fn restore_saved_stock(&mut self, state: &crate::channel::ResumeState) {
        let Some(s) = &state.stock else { return };
        if self.restore_stock(s).is_ok() {
            self.pending.retain(|item| !matches!(item, crate::interp::Item::Workpiece { .. }));
        }
    }

    /// Takes back a saved stock; `Err` (nothing changed) if it does not decode.
    pub(in crate::channel) fn restore_stock(&mut self, s: &SavedStock) -> Result<(), String> {
        let stock = saved::decode(s.format, &s.data)?;
        let holder = if s.holder.is_empty() { None } else { Some(Holder::new(&s.holder)?) };
        self.stock_options = StockOptions { resolution: s.resolution, depth_limit: s.depth_limit, holder };
        self.install_stock(stock);
        self.set_initial_stock_volume(s.initial_volume);
        Ok(())
    }
}
