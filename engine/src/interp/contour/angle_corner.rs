//! The two-block contour definition with `ANG=` (Programming Manual Fundamentals, "Contour
//! definitions: two straight lines"): a drawing gives the start point, the angle of the first
//! line, and the end point and angle of the second, but not the corner between them.
//!
//! ```text
//! N10 G1 ANG=α1          ; the first line leaves the start at α1 (no end coordinate)
//! N20 X.. Y.. ANG=α2     ; the second line ends at X/Y and runs at α2
//! ```
//!
//! The corner is where the line from the start at α1 meets the line into the end point at α2.
//! The first block waits (unread: nothing of it runs) until the second arrives; then the first
//! runs to the corner with its own words (feed, RND/CHF/CHR for the corner), and the second from
//! the corner to its end. Angles count counter-clockwise from the abscissa of the working plane
//! (degrees), as the single-block form's (`angle_line.rs`).
//!
//! Refused with 12560 at the second block (NCTwin's choice of number; the manual names none):
//! a second block without ANG and both end coordinates (the three-block forms are not
//! modelled), incremental end coordinates (the end would count from the unknown corner),
//! parallel lines, and lines that meet behind the start or beyond the end. Side effects of the
//! second block's words (assignments) happen before the first block is prepared.

use super::super::eval::eval_f64;
use super::super::eval::scope::{Ctx, sys_view};
use super::super::{Interpreter, Item, Prep, Programs, modal};
use crate::alarm::Alarm;
use crate::lang::{Block, CoordMode, Word};
use crate::machine_data::MachineConfig;

/// The first block, waiting for the second.
#[derive(Debug, Clone)]
pub struct Pending {
    block: Block,
}

/// Whether `block` opens a two-block definition: `ANG=` and no coordinate of the working plane
/// `plane` (the names of its abscissa and ordinate) nor polar words (read from the words as
/// written: nothing of the block is evaluated before the second block arrives).
fn opens(block: &Block, plane: (&str, &str)) -> bool {
    let mut ang = false;
    for w in &block.words {
        if let Word::Address { name, indices, .. } = w
            && indices.is_empty()
        {
            match &**name {
                "ANG" => ang = true,
                "AP" | "RP" => return false,
                n if n.eq_ignore_ascii_case(plane.0) || n.eq_ignore_ascii_case(plane.1) => return false,
                _ => {}
            }
        }
    }
    ang && block.stmt.is_none()
}

/// The corner of the line from `start` at `a1` degrees and the line into `end` at `a2` degrees.
pub fn corner(start: (f64, f64), a1: f64, end: (f64, f64), a2: f64) -> Result<(f64, f64), &'static str> {
    let (s1, c1) = a1.to_radians().sin_cos();
    let (s2, c2) = a2.to_radians().sin_cos();
    // start + s·d1 = end − t·d2: s·d1 + t·d2 = end − start.
    let det = c1 * s2 - s1 * c2;
    if det.abs() < 1e-12 {
        return Err("the two lines are parallel");
    }
    let (dx, dy) = (end.0 - start.0, end.1 - start.1);
    let s = (dx * s2 - dy * c2) / det;
    let t = (c1 * dy - s1 * dx) / det;
    if s < -1e-9 || t < -1e-9 {
        return Err("the lines meet behind the start or beyond the end");
    }
    Ok((start.0 + s * c1, start.1 + s * s1))
}

impl Interpreter {
    /// Holds `block` if it is the first block of a two-block definition (true), before any of
    /// its words is evaluated.
    pub(in crate::interp) fn defer_angle_block(&mut self, block: &Block, cfg: &MachineConfig) -> bool {
        let (pa, po, _) = self.modal.plane.axes();
        let (Some(ka), Some(ko)) = (cfg.geo_axes[pa], cfg.geo_axes[po]) else { return false };
        // (The first block prepared to its corner is not held again.)
        if self.pending_angle.is_some()
            || self.angle_corner_end.is_some()
            || !opens(block, (cfg.program_axis_name(ka), cfg.program_axis_name(ko)))
        {
            return false;
        }
        self.pending_angle = Some(Box::new(Pending { block: block.clone() }));
        true
    }

    /// The second block's words are collected in `words`: prepares the waiting first block to
    /// the corner, then leaves `words` as a plain line to the end point (its ANG used up).
    pub(in crate::interp) fn close_angle_corner(
        &mut self,
        pending: Pending,
        words: &mut modal::Words,
        cfg: &MachineConfig,
        programs: &Programs,
        line: u32,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let refuse = |why: &str| Alarm::value_out_of_range(line, &format!("contour definition with ANG: {why}"));
        let geo = cfg.geo_axes;
        let (pa, po, _) = self.modal.plane.axes();
        let (Some(ka), Some(ko)) = (geo[pa], geo[po]) else {
            return Err(refuse("the working plane lacks a geometry axis"));
        };
        let given = |k: usize| words.axes.iter().find(|a| a.0 == k).map(|a| (a.1, a.2));
        let (Some(a2), Some(wa), Some(wo)) = (words.ang, given(ka), given(ko)) else {
            return Err(refuse("the block after ANG= alone needs both end coordinates and ANG="));
        };
        let incremental = |mode: Option<CoordMode>| match mode {
            Some(CoordMode::Ac) => false,
            Some(CoordMode::Ic) => true,
            _ => !words.absolute.unwrap_or(self.modal.absolute),
        };
        if incremental(wa.1) || incremental(wo.1) {
            return Err(refuse("incremental end coordinates count from the unknown corner"));
        }
        // The start in the WCS: nothing moved since the first block.
        let frame = self.block_frame(words, cfg);
        let current = frame.unapply(&geo, &self.basic_position()).ok_or_else(|| refuse("frame with scale 0"))?;
        let end = (
            self.axis_word_target(cfg, ka, wa, current[ka], current[ka], line)?,
            self.axis_word_target(cfg, ko, wo, current[ko], current[ko], line)?,
        );
        // The first block's angle, read now (its words are collected when it is prepared).
        let first = {
            let Some(expr) = pending.block.words.iter().find_map(|w| match w {
                Word::Address { name, value, .. } if &**name == "ANG" => Some(&value.expr),
                _ => None,
            }) else {
                return Err(refuse("no ANG= in the first block"));
            };
            let sys = sys_view!(self, cfg);
            eval_f64(expr, &Ctx { vars: &self.vars, sys: &sys }, pending.block.line)?
        };
        let p2 = corner((current[ka], current[ko]), first, end, a2).map_err(refuse)?;
        self.angle_corner_end = Some(p2);
        let mut first = Vec::new();
        self.prepare_block(&pending.block, cfg, programs, &mut first)?;
        self.angle_corner_end = None;
        // The first block's RND/CHF/CHR: its move waits for the second's, as after any block.
        let request = self.corner_request.take();
        self.shape_corners(&mut first, Prep::Prepared, request, cfg)?;
        out.append(&mut first);
        words.ang = None;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_at_45_degrees_meets_a_horizontal_line_into_the_end() {
        // From (10,0) at 45° and into (40,10) along 0°: the corner lies on Y = 10, at X = 20.
        let (x, y) = corner((10.0, 0.0), 45.0, (40.0, 10.0), 0.0).unwrap();
        assert!((x - 20.0).abs() < 1e-12 && (y - 10.0).abs() < 1e-12, "({x}, {y})");
    }

    #[test]
    fn parallel_lines_and_corners_behind_are_refused() {
        assert!(corner((0.0, 0.0), 30.0, (40.0, 10.0), 30.0).is_err());
        // From (0,0) at 0° (along Y = 0) into (10,10): at 180° the second line is parallel; at
        // 90° (upwards into (10,10)) the corner (10,0) lies before the end; at −90° (downwards
        // into (10,10)) the lines meet at (10,0) beyond the end.
        assert!(corner((0.0, 0.0), 0.0, (10.0, 10.0), 180.0).is_err());
        assert!(corner((0.0, 0.0), 0.0, (10.0, 10.0), 90.0).is_ok());
        assert!(corner((0.0, 0.0), 0.0, (10.0, 10.0), -90.0).is_err());
    }
}
