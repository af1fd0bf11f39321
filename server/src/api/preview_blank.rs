//! The blank a previewed program defines with `WORKPIECE(...)`, as the box the HMI draws around
//! the programmed path before the program has run: taken from the preview copy's stock the
//! first time one exists (before much of it is cut), through the engine's public stock views.

use nctwin_engine::Channel;
use nctwin_engine::stock::Stock;
use serde::Serialize;
use utoipa::ToSchema;

/// The blank of a preview: its bounding box in the BCS.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct PreviewBlank {
    /// A turned blank (a cylinder or tube about Z through X0 Y0 of the BCS); else milled.
    pub turning: bool,
    /// The low corner (mm): for a turned blank `[-r, -r, z0]`.
    pub min: [f64; 3],
    /// The high corner (mm): for a turned blank `[r, r, z1]`.
    pub max: [f64; 3],
}

/// The bounds of the channel's stock, `None` without one (or with no material left).
pub fn blank_of(channel: &mut Channel) -> Option<PreviewBlank> {
    match channel.stock()? {
        Stock::Milling(g) => {
            let (nx, ny) = g.size();
            let (x0, y0) = g.origin();
            let res = g.resolution();
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            let mut spans = Vec::new();
            for j in 0..ny {
                for i in 0..nx {
                    g.intervals(i, j, &mut spans);
                    for s in &spans {
                        lo = lo.min(f64::from(s[0]));
                        hi = hi.max(f64::from(s[1]));
                    }
                }
            }
            (lo < hi).then_some(PreviewBlank {
                turning: false,
                min: [x0, y0, lo],
                max: [x0 + nx as f64 * res, y0 + ny as f64 * res, hi],
            })
        }
        Stock::Turning(p) => {
            let (z0, n) = p.extent();
            let r = (0..n).map(|k| p.radii(k).0).fold(0.0, f64::max);
            (n > 0 && r > 0.0).then_some(PreviewBlank {
                turning: true,
                min: [-r, -r, z0],
                max: [r, r, z0 + n as f64 * p.resolution()],
            })
        }
    }
}
