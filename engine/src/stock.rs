//! Material removal: the session's workpiece, cut by the simulated motion.
//!
//! Input: a [`blank::Blank`] (from `WORKPIECE(..)` or an API call) placed in the BCS, a
//! [`cutter::Cutter`] from the cutting edge's tool data and straight tool-tip segments in the
//! BCS. Output: the remaining and removed volume, what each segment removed (for the checks
//! of `channel/stock/cut.rs`) and a binary STL of the current stock ([`mesh`]).
//!
//! Two representations, chosen by the machine (see ARCHITECTURE.md, "Material removal"):
//! - milling ([`dexel::DexelGrid`]): Z-dexels, per grid cell of the XY plane a sorted list of
//!   material intervals along Z. A tool along Z removes everything above its lower surface, so
//!   a cut is a clip of the cell's intervals; memory is one interval per cell plus the rare
//!   extra ones, bounded by the blank's footprint over the resolution squared.
//! - turning ([`profile::Profile`]): the part turns, so the stock is axisymmetric about the
//!   spindle axis Z: per slab of the Z axis an outer and an inner radius. A turning insert's
//!   nose circle swept over a segment removes a ring.
//!
//! Pure and deterministic: no I/O, no clock; every loop runs in index order.

pub mod blank;
pub mod body;
pub mod cutter;
pub mod dexel;
pub mod holder;
pub mod mesh;
pub mod profile;
pub mod saved;
pub mod target;

use blank::{Blank, Placement};
use cutter::Cutter;

/// The resolution a session uses unless it sets another one, in mm: the dexel grid's cell
/// size for milling, the slab length for turning. At 0.25 mm a 200 x 100 mm blank has 320,000
/// cells (2.6 MB) and a pocket's volume is right to well under 1 % (see ARCHITECTURE.md).
pub const DEFAULT_RESOLUTION: f64 = 0.25;

/// Finest resolution accepted, in mm.
pub const MIN_RESOLUTION: f64 = 0.01;

/// Most cells (milling) or slabs (turning) one stock may have: bounds the memory (8 bytes a
/// cell: about 128 MB) whatever the program; a finer resolution on a large blank is refused.
pub const MAX_CELLS: usize = 16_000_000;

/// The stock of one session.
#[derive(Debug, Clone, PartialEq)]
pub enum Stock {
    /// Milling: Z-dexels.
    Milling(dexel::DexelGrid),
    /// Turning: the radius profile along the spindle axis.
    Turning(profile::Profile),
}

/// What one swept segment removed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Removal {
    /// Volume removed, mm³.
    pub volume: f64,
    /// The largest thickness of material removed in one dexel (milling: along the tool axis)
    /// or one slab (turning: radially), mm: the depth of cut of this segment.
    pub depth: f64,
}

impl Stock {
    /// The stock of `blank` placed by `placement` (WCS → BCS) at `resolution` mm; `turning`
    /// for a machine whose workpiece turns on the spindle. `Err` names what is wrong.
    pub fn new(blank: &Blank, placement: &Placement, turning: bool, resolution: f64) -> Result<Stock, String> {
        if !(resolution.is_finite() && resolution >= MIN_RESOLUTION) {
            return Err(format!("stock resolution {resolution} mm: at least {MIN_RESOLUTION} mm"));
        }
        if turning {
            profile::Profile::new(blank, placement, resolution).map(Stock::Turning)
        } else {
            dexel::DexelGrid::new(blank, placement, resolution).map(Stock::Milling)
        }
    }

    /// Removes what `cutter` sweeps with its tip (milling: the lowest point on the tool axis;
    /// turning: the theoretical tip P) going straight from `a` to `b` (BCS, mm).
    pub fn cut(&mut self, cutter: &Cutter, a: [f64; 3], b: [f64; 3]) -> Removal {
        match self {
            Stock::Milling(g) => g.cut(cutter, a, b),
            Stock::Turning(p) => p.cut(cutter, a, b),
        }
    }

    /// [`Stock::cut`] with the tool's axis along the unit vector `axis` (tip → holder, in the
    /// blank's frame) and its cutting part `length` long: 5-axis orientations and tilted
    /// tables. A milling tool along +Z takes the exact path of [`Stock::cut`]; a turned stock
    /// ignores the axis (a lathe's tools lie in the turning plane).
    pub fn cut_oriented(&mut self, cutter: &Cutter, a: [f64; 3], b: [f64; 3], axis: [f64; 3], length: f64) -> Removal {
        match self {
            Stock::Milling(g) if axis[0].abs() > 1e-9 || axis[1].abs() > 1e-9 || axis[2] < 0.0 => {
                g.cut_tilted(cutter, a, b, axis, length)
            }
            _ => self.cut(cutter, a, b),
        }
    }

    /// [`Stock::cut_oriented`] with the axis turning from `axis_a` to `axis_b` on the way (on
    /// their great circle): 5-axis simultaneous motion, a tool turning about its standing tip.
    pub fn cut_swept(
        &mut self,
        cutter: &Cutter,
        a: [f64; 3],
        b: [f64; 3],
        axis_a: [f64; 3],
        axis_b: [f64; 3],
        length: f64,
    ) -> Removal {
        match self {
            Stock::Milling(g) if axis_a != axis_b => g.cut_swept(cutter, a, b, axis_a, axis_b, length),
            _ => self.cut_oriented(cutter, a, b, axis_a, length),
        }
    }

    /// The material inside the `cylinders` (`(radius, from, to)` above the tip along the unit
    /// `axis`: shank, holder, spindle, [`body::Bodies`]) while the tip goes from `a` to `b`: a
    /// collision where it is not zero. A turned stock has no holder model (the default:
    /// nothing found).
    pub fn overlap(&self, cylinders: &[(f64, f64, f64)], a: [f64; 3], b: [f64; 3], axis: [f64; 3]) -> dexel::Overlap {
        match self {
            Stock::Milling(g) if !cylinders.is_empty() => g.overlap(cylinders, a, b, axis),
            _ => dexel::Overlap::default(),
        }
    }

    /// The material left, mm³.
    pub fn volume(&self) -> f64 {
        match self {
            Stock::Milling(g) => g.volume(),
            Stock::Turning(p) => p.volume(),
        }
    }

    /// The resolution, mm.
    pub fn resolution(&self) -> f64 {
        match self {
            Stock::Milling(g) => g.resolution(),
            Stock::Turning(p) => p.resolution(),
        }
    }

    /// The current stock as a binary STL (BCS, mm).
    pub fn stl(&self) -> Vec<u8> {
        match self {
            Stock::Milling(g) => mesh::dexel_stl(g),
            Stock::Turning(p) => mesh::profile_stl(p, mesh::TURNING_SEGMENTS),
        }
    }
}
