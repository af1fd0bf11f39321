//! The tool holder (and spindle nose) as a stack of cylinders on the tool's axis, for the
//! collision check: unlike the cutting part it removes nothing; material inside it is a crash.
//!
//! The stack begins at the tool's reference point, the gauge line the tool length is measured
//! to (`$TC_DP3` above the tip), and goes up the axis: each section a diameter and a length.
//! The tool data of the control have no holder geometry (Operate keeps it in its simulation
//! settings), so the user sets it for the session (`PUT .../stock` `holder`, or
//! [`crate::channel::StockOptions::holder`]); the shank below the gauge line and the spindle
//! housing come from the tool and machine data (`body.rs`).

/// Most sections of one holder (nose, taper, collar, spindle).
pub const MAX_SECTIONS: usize = 4;

/// A cylinder stack above the gauge line. `Copy`: it travels with the stock options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Holder {
    /// `[diameter, length]` from the gauge line up, mm.
    sections: [[f64; 2]; MAX_SECTIONS],
    count: usize,
}

impl Holder {
    /// The holder of `sections` (`[diameter, length]` from the gauge line up); `Err` names a
    /// section without size or too many of them.
    pub fn new(sections: &[[f64; 2]]) -> Result<Holder, String> {
        if sections.is_empty() || sections.len() > MAX_SECTIONS {
            return Err(format!("a holder has 1 to {MAX_SECTIONS} sections, not {}", sections.len()));
        }
        if let Some((n, s)) = sections
            .iter()
            .enumerate()
            .find(|(_, s)| !(s[0].is_finite() && s[0] > 0.0 && s[1].is_finite() && s[1] > 0.0))
        {
            return Err(format!("holder section {}: diameter {} and length {} must be positive", n + 1, s[0], s[1]));
        }
        let mut h = Holder { sections: [[0.0; 2]; MAX_SECTIONS], count: sections.len() };
        h.sections[..sections.len()].copy_from_slice(sections);
        Ok(h)
    }

    /// `[diameter, length]` from the gauge line up.
    pub fn sections(&self) -> &[[f64; 2]] {
        &self.sections[..self.count]
    }

    /// The cylinders `(radius, from, to)` in heights above the tool tip for a tool
    /// `tool_length` long.
    pub fn cylinders(&self, tool_length: f64) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.sections().iter().scan(tool_length, |h, s| {
            let from = *h;
            *h += s[1];
            Some((s[0] / 2.0, from, *h))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_stack_from_the_gauge_line() {
        let h = Holder::new(&[[40.0, 50.0], [63.0, 20.0]]).unwrap();
        let c: Vec<_> = h.cylinders(30.0).collect();
        assert_eq!(c, vec![(20.0, 30.0, 80.0), (31.5, 80.0, 100.0)]);
        assert!(Holder::new(&[]).is_err());
        assert!(Holder::new(&[[40.0, 0.0]]).unwrap_err().contains("section 1"));
    }
}
