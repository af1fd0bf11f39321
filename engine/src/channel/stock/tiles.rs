//! The stock's changes for the HMI: the dexel grid in tiles of [`TILE`] × [`TILE`] cells, each
//! with the version of the last cut that touched it, so the 3D view fetches only the tiles
//! changed since the version it shows; and the pens, the session's small numbers for the tools
//! that cut (a face's colour).

use crate::channel::Channel;
use crate::stock::Stock;

/// Cells per tile edge: 64 × 64 cells are 16 mm square at the default 0.25 mm, a mesh of a
/// few hundred kB at worst.
pub const TILE: usize = 64;

/// Most distinct pens; later tools share the last.
const MAX_PENS: usize = 255;

/// Tile versions and pens of one stock.
#[derive(Debug, Clone)]
pub(in crate::channel) struct TileLog {
    version: u32,
    /// Tiles in X and Y; a turned stock has one.
    size: (usize, usize),
    changed: Vec<u32>,
    /// Tool and cutting edge of pen n at n − 1.
    pens: Vec<(u32, u32)>,
}

/// What changed since a version.
#[derive(Debug, Clone, PartialEq)]
pub struct StockChanges {
    /// The stock's version now.
    pub version: u32,
    /// Cells per tile edge ([`TILE`]); the tiles' cell ranges are `i·TILE .. (i+1)·TILE`.
    pub tile: usize,
    /// The tiles changed since, `[i, j]`, row by row; all of them for version 0.
    pub tiles: Vec<[u32; 2]>,
    /// Tool and cutting edge of each pen (pen n at n − 1): the colours' key.
    pub pens: Vec<(u32, u32)>,
}

impl TileLog {
    pub(in crate::channel) fn new(stock: &Stock) -> TileLog {
        let size = match stock {
            Stock::Milling(g) => {
                let (nx, ny) = g.size();
                (nx.div_ceil(TILE), ny.div_ceil(TILE))
            }
            Stock::Turning(_) => (1, 1),
        };
        TileLog { version: 1, size, changed: vec![1; size.0 * size.1], pens: Vec::new() }
    }

    /// The stock became another grid (`spindle.rs`): its tiles, all changed, under a
    /// new version (the versions go on, so the HMI fetches them all).
    pub(in crate::channel) fn restart(&mut self, stock: &Stock) {
        let fresh = TileLog::new(stock);
        self.version = self.version.wrapping_add(1).max(1);
        self.size = fresh.size;
        self.changed = vec![self.version; fresh.changed.len()];
    }

    pub(in crate::channel) fn version(&self) -> u32 {
        self.version
    }

    /// The pen of `tool`, given at its first cut.
    pub(in crate::channel) fn pen(&mut self, tool: (u32, u32)) -> u8 {
        if let Some(n) = self.pens.iter().position(|t| *t == tool) {
            return (n + 1) as u8;
        }
        if self.pens.len() < MAX_PENS {
            self.pens.push(tool);
        }
        self.pens.len() as u8
    }

    /// A cut that removed material from `a` to `b`, reaching `reach` mm sideways.
    pub(in crate::channel) fn touch(&mut self, stock: &Stock, a: [f64; 3], b: [f64; 3], reach: f64) {
        self.version = self.version.wrapping_add(1).max(1);
        let Stock::Milling(g) = stock else {
            self.changed[0] = self.version;
            return;
        };
        let (x0, y0) = g.origin();
        let span = g.resolution() * TILE as f64;
        let tile = |v: f64, o: f64, n: usize| (((v - o) / span).floor().max(0.0) as usize).min(n - 1);
        let (i0, i1) = (tile(a[0].min(b[0]) - reach, x0, self.size.0), tile(a[0].max(b[0]) + reach, x0, self.size.0));
        let (j0, j1) = (tile(a[1].min(b[1]) - reach, y0, self.size.1), tile(a[1].max(b[1]) + reach, y0, self.size.1));
        for j in j0..=j1 {
            for i in i0..=i1 {
                self.changed[j * self.size.0 + i] = self.version;
            }
        }
    }
}

impl Channel {
    /// The tiles changed after version `since` (0: all), the open segment cut first; `None`
    /// without a blank.
    pub fn stock_changes(&mut self, since: u32) -> Option<StockChanges> {
        self.flush_stock_now();
        self.stock_delta(since)
    }

    /// [`Channel::stock_changes`] as the last cut left them (the open segment not yet cut, so
    /// reading does not change where segments end): for the stream's pushes, taken between
    /// IPO cycles.
    pub fn stock_delta(&self, since: u32) -> Option<StockChanges> {
        let log = &self.stock.as_ref()?.tiles;
        let (nx, _) = log.size;
        let tiles = (0..log.changed.len())
            .filter(|&k| log.changed[k] > since)
            .map(|k| [(k % nx) as u32, (k / nx) as u32])
            .collect();
        Some(StockChanges { version: log.version, tile: TILE, tiles, pens: log.pens.clone() })
    }

    /// The stock's version as the last cut left it; `None` without a blank.
    pub fn stock_version(&self) -> Option<u32> {
        self.stock.as_ref().map(|r| r.tiles.version())
    }

    /// Tile (i, j) of a milled stock as a binary STL (faces' attribute: the pen); the whole
    /// stock for a turned one (tile 0, 0). `None` without a blank or outside the grid.
    pub fn stock_tile_stl(&mut self, i: usize, j: usize) -> Option<Vec<u8>> {
        self.flush_stock_now();
        self.stock_tile_mesh(i, j)
    }

    /// [`Channel::stock_tile_stl`] as the last cut left it (see [`Channel::stock_delta`]).
    pub fn stock_tile_mesh(&self, i: usize, j: usize) -> Option<Vec<u8>> {
        let run = self.stock.as_ref()?;
        let (tx, ty) = run.tiles.size;
        if i >= tx || j >= ty {
            return None;
        }
        Some(match &run.stock {
            Stock::Milling(g) => {
                crate::stock::mesh::dexel_stl_region(g, [i * TILE, (i + 1) * TILE], [j * TILE, (j + 1) * TILE])
            }
            Stock::Turning(_) => run.stock.stl(),
        })
    }
}
