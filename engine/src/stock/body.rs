//! What of the tool and the spindle must not touch the stock: cylinders on the tool's axis,
//! in heights above the tip, for the collision check of `channel/stock/cut.rs`.
//!
//! - The shank: the 840D's tool data have no flute length and no holder geometry (`$TC_DP`
//!   holds lengths, radius, corner radius and angles; `$TC_DP21..23` are adapter lengths, not
//!   shapes), so it is a default per tool type, decided here: a milling tool (1xx) cuts over
//!   3·D from its tip (the cutting length of a regular end mill), a drill (2xx) over 5·D (a
//!   "5×D" drill); from there to the gauge line (`$TC_DP3` above the tip) the shank and the
//!   chuck's nose are one body of diameter 2·D (a collet nut or a shrink chuck's nose is about
//!   twice the shank). None where the cutting length reaches the gauge line, none for turning,
//!   grinding and special tools.
//! - The holder the session sets (`holder.rs`): sections from the gauge line up.
//! - The spindle housing: `$MC_SPINDLE_HOUSING[0]` diameter, `[1]` length (this product's
//!   datum, no number: the cylinder round the spindle whose face is the spindle nose, the
//!   gauge line); 0: none.

use super::holder::{Holder, MAX_SECTIONS};
use crate::machine_data::EdgeParams;

/// Most cylinders of one check: shank, holder sections, housing.
pub const MAX_BODIES: usize = MAX_SECTIONS + 2;

/// The non-cutting bodies of the active tool: `(radius, from, to)` above the tip.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Bodies {
    list: [(f64, f64, f64); MAX_BODIES],
    count: usize,
}

impl Bodies {
    /// The bodies of a tool `length` long (tip to gauge line) with the `shank` of its edge
    /// data (radius, height where it begins), the session's `holder` above the gauge line and
    /// the spindle `housing` (`[diameter, length]`) from the gauge line up.
    pub fn new(shank: Option<(f64, f64)>, holder: Option<&Holder>, housing: Option<[f64; 2]>, length: f64) -> Bodies {
        let mut b = Bodies::default();
        let mut push = |c: (f64, f64, f64)| {
            if c.0 > 0.0 && c.2 > c.1 && b.count < MAX_BODIES {
                b.list[b.count] = c;
                b.count += 1;
            }
        };
        if let Some((r, from)) = shank {
            push((r, from, length));
        }
        for c in holder.into_iter().flat_map(|h| h.cylinders(length)) {
            push(c);
        }
        if let Some([d, l]) = housing {
            push((d / 2.0, length, length + l));
        }
        b
    }

    /// `(radius, from, to)` above the tip.
    pub fn cylinders(&self) -> &[(f64, f64, f64)] {
        &self.list[..self.count]
    }
}

/// The shank of the tool with edge data `p` (see the module doc): radius and the height above
/// the tip where it begins (up to the gauge line; none if that lies lower), `None` for a tool
/// type without one.
pub fn shank(p: &EdgeParams) -> Option<(f64, f64)> {
    let dp = |n: usize| p[n - 1];
    let d = 2.0 * (dp(6) + dp(15)).max(0.0);
    let cutting = match dp(1).round() as i64 {
        100..=199 => 3.0 * d,
        200..=299 => 5.0 * d,
        _ => return None,
    };
    (d > 0.0).then_some((d, cutting))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::cutter::edge;

    #[test]
    fn an_end_mill_has_its_shank_above_three_diameters_and_a_drill_above_five() {
        // End mill R3 (D6): cuts to 18, then Ø12 (radius 6).
        assert_eq!(shank(&edge(&[(1, 120.0), (6, 3.0)])), Some((6.0, 18.0)));
        // Drill R4 (D8): cuts to 40; a tool 40 long has no shank below its gauge line.
        let drill = shank(&edge(&[(1, 200.0), (6, 4.0)]));
        assert_eq!(drill, Some((8.0, 40.0)));
        assert!(Bodies::new(drill, None, None, 40.0).cylinders().is_empty());
        // Turning tools: none.
        assert_eq!(shank(&edge(&[(1, 500.0), (6, 0.8)])), None);
    }

    #[test]
    fn the_bodies_stack_shank_holder_and_housing() {
        let holder = Holder::new(&[[40.0, 50.0]]).unwrap();
        let b = Bodies::new(Some((6.0, 18.0)), Some(&holder), Some([120.0, 200.0]), 40.0);
        assert_eq!(b.cylinders(), &[(6.0, 18.0, 40.0), (20.0, 40.0, 90.0), (60.0, 40.0, 240.0)]);
        assert!(Bodies::new(None, None, None, 40.0).cylinders().is_empty());
    }
}
