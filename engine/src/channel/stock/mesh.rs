//! Meshes from outside for the session's stock: a blank from an STL, and the comparison of the
//! cut stock with a target STL (both in the WCS of the active frame, like a `PUT` blank).

use crate::channel::{Channel, CommandError};
use crate::stock::dexel::DexelGrid;
use crate::stock::target::{Comparison, Mesh};
use crate::stock::{MAX_CELLS, Stock};

impl Channel {
    /// Defines the blank as the closed `mesh` (WCS of the active frame, mm), cut from now on.
    /// Mills only (a lathe's stock is a turned profile); only while nothing moves.
    pub fn define_stock_mesh(&mut self, mesh: &Mesh) -> Result<(), CommandError> {
        if self.is_busy() {
            return Err(CommandError::Busy("the blank can only change while nothing moves"));
        }
        if self.stock_turns() {
            return Err(CommandError::Invalid("an STL blank needs a mill: a lathe's stock is a turned profile".into()));
        }
        let placement = self.stock_placement(&self.offsets.frame);
        placement.check_upright().map_err(CommandError::Invalid)?;
        let bcs = mesh.map(|p| placement.apply(p));
        let grid =
            DexelGrid::from_mesh(&bcs, self.stock_options.resolution, MAX_CELLS).map_err(CommandError::Invalid)?;
        self.install_stock(Stock::Milling(grid));
        Ok(())
    }

    /// The stock as it is now against the `target` part (WCS of the active frame, mm): the
    /// largest over- and undercut. `Err` without a blank or for a turned stock.
    pub fn compare_stock(&mut self, target: &Mesh) -> Result<Comparison, CommandError> {
        let placement = self.stock_placement(&self.offsets.frame);
        placement.check_upright().map_err(CommandError::Invalid)?;
        let bcs = target.map(|p| placement.apply(p));
        match self.stock() {
            Some(Stock::Milling(g)) => Ok(g.compare(&bcs)),
            Some(Stock::Turning(_)) => {
                Err(CommandError::Invalid("comparing with a target STL needs a milled stock, not a turned one".into()))
            }
            None => {
                Err(CommandError::Invalid("no blank to compare: define one first (WORKPIECE or PUT .../stock)".into()))
            }
        }
    }
}
