//! Smooth approach and retract (SAR, Programming Manual Fundamentals "Approach and retraction
//! (G140 to G143, G147, G148, G247, G248, G347, G348, G340, G341, DISR, DISCL, FAD, PM, PR)",
//! Function Manual W1 "Smooth approach and retraction").
//!
//! The approach runs from the start point P0 over up to three intermediate points to the
//! contour's start P4 and joins the contour tangentially; the retract is the same backwards:
//! - the approach contour (non-modal, G group 2): `G147`/`G148` a straight line, `G247`/`G248`
//!   a quadrant, `G347`/`G348` a semicircle;
//! - the side (modal, G group 43): `G140` (reset value) from the side of the active TRC (G41
//!   left, G42 right; G143 without TRC), `G141` from the left, `G142` from the right, `G143`
//!   from the side where the start (retract: end) point lies relative to the contour's tangent;
//! - the infeed (modal, G group 44): `G340` (reset value) in space: a straight line parallel to
//!   the plane to P1 above P3, the infeed to the safety clearance `DISCL` at P3 and the approach
//!   contour from there to P4 (a helix when the heights differ); `G341` in the plane: P1, the
//!   infeed to `DISCL` (P2), the slow infeed to the contour's height (P3) and the approach
//!   contour in the plane;
//! - `DISRP`: the height of P1 above the machining plane (`DISRP=AC(..)`: absolute), so that
//!   P0–P1 is no longer parallel to the plane; it may not lie between DISCL and the contour
//!   (10748);
//! - `DISR`: the straight line's distance from the cutter edge to the contour (its length is
//!   DISR plus the tool radius), or the radius of the tool centre path of the circle;
//!   `DISCL`: the safety clearance above the machining plane through P4 (`DISCL=AC(..)`: the
//!   plane's absolute position in the WCS); `FAD`: the feed of the slow infeed (`FAD=PM(..)`
//!   per minute, `FAD=PR(..)` per revolution, else per the active G94/G95).
//!
//! Feeds as the manual lists them: P0 to P2 at the velocity before the SAR block (rapid after a
//! G0 block), the slow infeed (G341: P2–P3, G340: the approach contour) at FAD, the rest at F.
//! On retract the roles swap: the retract contour at the contour's feed, FAD for the slow
//! part, the SAR block's own feed (G0 or F) from P2 to P0.
//!
//! Chosen where the manuals are silent:
//! - the straight line's length adds the compensation radius (tool radius plus OFFN);
//! - `FAD=PR(..)` (and FAD under G95) is turned into a feed per minute with the spindle speed
//!   at block preparation; rapid and FAD legs do not follow the spindle under G95;
//! - `DISCL` without a value is 0 (P2 lies in the machining plane: the fast infeed goes down
//!   to the contour's height); a positive `DISCL` points along the plane normal's positive
//!   direction (+Z under G17); an infeed that would have to turn back (start point between the
//!   clearance plane and the contour) is alarm 10741;
//! - axes outside the working plane other than its normal (rotary axes) move in the first
//!   sub-move of an approach and in the last of a retract, as the manual places other actions;
//! - the approach is modelled with tool radius compensation selected in the SAR block or with
//!   none active (then the tool centre is the contour's point, G140 acts as G143); the retract
//!   with TRC deselected in the SAR block. A SAR approach block without an end point in the
//!   plane takes P4 from the next motion block (its height from the SAR block), and the
//!   sub-moves carry that block's number; one without any motion leaves its words to the next
//!   motion block (with TRC selected; without TRC, 10744). A retract without TRC is refused with alarm 10744
//!   (the contour's last element is not known without a held element).

use crate::alarm::Alarm;
use crate::interp::compensation::trc::{Elem, P2, left};
use crate::lang::ast::{CoordMode, Expr};
use crate::motion::{AxisVec, Feed};
use std::f64::consts::{FRAC_PI_2, PI};

/// The approach or retract contour (non-modal).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// G147 / G148.
    Line,
    /// G247 / G248.
    Quadrant,
    /// G347 / G348.
    Semicircle,
}

/// G group 43: from which side the contour is approached (to which side it is left).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SideRule {
    /// G140: the side of the active TRC.
    #[default]
    Compensation,
    /// G141.
    Left,
    /// G142.
    Right,
    /// G143: where the start (end) point lies relative to the tangent.
    Auto,
}

/// The modal SAR state (G groups 43 and 44).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SarModal {
    /// G341 (in the plane) rather than G340 (in space).
    pub in_plane: bool,
    pub side: SideRule,
}

/// DISCL's value: a clearance above P4's plane, or an absolute WCS position (`AC`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Clearance {
    Distance(f64),
    Absolute(f64),
}

/// The SAR words of one block.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SarWords {
    /// The contour and whether it is a retract.
    pub contour: Option<(Shape, bool)>,
    pub in_plane: Option<bool>,
    pub side: Option<SideRule>,
    pub disr: Option<f64>,
    pub discl: Option<Clearance>,
    /// DISRP: the retraction plane of P1 (default: the start point's height).
    pub disrp: Option<Clearance>,
    /// FAD's value and its feed type (None: the active G94/G95; Some(true): PR).
    pub fad: Option<(f64, Option<bool>)>,
}

impl SarWords {
    /// Takes a G function of SAR; false for any other.
    pub fn g_function(&mut self, code: u32, line: u32) -> Result<bool, Alarm> {
        let contour = match code {
            147 => (Shape::Line, false),
            148 => (Shape::Line, true),
            247 => (Shape::Quadrant, false),
            248 => (Shape::Quadrant, true),
            347 => (Shape::Semicircle, false),
            348 => (Shape::Semicircle, true),
            140..=143 => {
                self.side = Some(
                    [SideRule::Compensation, SideRule::Left, SideRule::Right, SideRule::Auto][code as usize - 140],
                );
                return Ok(true);
            }
            340 | 341 => {
                self.in_plane = Some(code == 341);
                return Ok(true);
            }
            _ => return Ok(false),
        };
        if self.contour.is_some() {
            return Err(Alarm::sar_repeated(line));
        }
        self.contour = Some(contour);
        Ok(true)
    }

    /// Takes DISR or DISCL (with its `AC`/`IC` form); false for any other address. `f` is
    /// millimetres per program length unit.
    pub fn address(&mut self, name: &str, v: f64, mode: Option<CoordMode>, f: f64, line: u32) -> Result<bool, Alarm> {
        match name {
            "DISR" => self.disr = Some(v * f),
            "DISCL" | "DISRP" => {
                let c = match mode {
                    Some(CoordMode::Ac) => Clearance::Absolute(v * f),
                    None | Some(CoordMode::Ic) => Clearance::Distance(v * f),
                    Some(_) => return Err(Alarm::value_out_of_range(line, &format!("{name}: only AC(..) or IC(..)"))),
                };
                if name == "DISCL" {
                    self.discl = Some(c);
                } else {
                    self.disrp = Some(c);
                }
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// FAD=value, FAD=PM(value) or FAD=PR(value): the expression to evaluate and the feed type.
    pub fn fad_form(expr: &Expr) -> (&Expr, Option<bool>) {
        match expr {
            Expr::Call(name, args) if args.len() == 1 && (name == "PM" || name == "PR") => {
                (&args[0], Some(name == "PR"))
            }
            e => (e, None),
        }
    }
}

/// True for the addresses of SAR.
pub fn is_address(name: &str) -> bool {
    matches!(name, "DISR" | "DISCL" | "DISRP" | "FAD")
}

impl SarModal {
    /// Applies a block's modal SAR words.
    pub fn apply(&mut self, w: &SarWords) {
        if let Some(p) = w.in_plane {
            self.in_plane = p;
        }
        if let Some(s) = w.side {
            self.side = s;
        }
    }
}

/// A SAR block as the compensation runs it: everything in the units of the prepared moves.
#[derive(Debug, Clone, PartialEq)]
pub struct Sar {
    pub shape: Shape,
    pub retract: bool,
    pub in_plane: bool,
    pub side: SideRule,
    /// DISR in mm.
    pub disr: f64,
    /// Height of the clearance plane (P2) above the machining plane through P4, along `normal`.
    pub clearance: f64,
    /// Height of the retraction plane (P1, DISRP) likewise; None: P1 at the start (end) height.
    pub retract_plane: Option<f64>,
    /// Unit plane normal in axis space (its positive direction as in the WCS).
    pub normal: AxisVec,
    /// FAD as a path feed.
    pub fad: Option<Feed>,
    /// The velocity before the SAR block (approach: P0 to P2; retract: the contour's).
    pub before: Feed,
    /// The block's F as a path feed even under G0 (the approach contour runs at F).
    pub feed: Option<Feed>,
    /// Whether the block's end point lies in the plane (retract with G143 needs it).
    pub end_in_plane: bool,
    /// Approach without TRC: the compensation of radius 0 its block and the next element run
    /// with (the contour's tangent decides the approach as with TRC).
    pub zero: Option<crate::interp::compensation::trc::Compensation>,
    pub line: u32,
}

/// The geometry of an approach in plane coordinates of the tool centre: P3 and the approach
/// contour from P3 to P4c (`p4c`, on the equidistant), which arrives with tangent `t`.
/// `s0` is where the start point lies (G143), `p4` the programmed contour point, `radius`
/// the compensation radius (tool radius plus OFFN, 0 without TRC), `side` +1 for approach
/// from the left, −1 from the right.
pub(in crate::interp) fn approach_contour(
    shape: Shape,
    disr: f64,
    radius: f64,
    p4c: P2,
    t: P2,
    side: f64,
) -> (P2, Elem) {
    let n = left(t);
    match shape {
        Shape::Line => {
            let l = disr + radius;
            let p3 = (p4c.0 - l * t.0, p4c.1 - l * t.1);
            (p3, Elem::Line { s: p3, e: p4c })
        }
        Shape::Quadrant | Shape::Semicircle => {
            let r = disr;
            let c = (p4c.0 + side * r * n.0, p4c.1 + side * r * n.1);
            let sweep = side * if shape == Shape::Quadrant { FRAC_PI_2 } else { PI };
            // The arc ends at P4c = c − side·r·n; it starts `sweep` before.
            let a4 = (p4c.1 - c.1).atan2(p4c.0 - c.0);
            let a0 = a4 - sweep;
            let p3 = (c.0 + r * a0.cos(), c.1 + r * a0.sin());
            (p3, Elem::Arc { c, r, a0, sweep })
        }
    }
}

/// The side (+1 left, −1 right) per G140..G143: `offset` is the signed TRC offset (positive
/// G41), `p` the start (approach) or end (retract) point, `p4` the contour point, `t` the
/// contour's tangent there. G143 with `p` on the tangent, or with no point (`p` None), is
/// alarm 10744 (10747 on retract).
pub(in crate::interp) fn side(
    rule: SideRule,
    offset: f64,
    p: Option<P2>,
    p4: P2,
    t: P2,
    retract: bool,
    line: u32,
) -> Result<f64, Alarm> {
    match rule {
        SideRule::Left => Ok(1.0),
        SideRule::Right => Ok(-1.0),
        SideRule::Compensation if offset > 0.0 => Ok(1.0),
        SideRule::Compensation if offset < 0.0 => Ok(-1.0),
        _ => {
            let no_side = || if retract { Alarm::sar_retract_direction(line) } else { Alarm::sar_direction(line) };
            let p = p.ok_or_else(no_side)?;
            let cross = t.0 * (p.1 - p4.1) - t.1 * (p.0 - p4.0);
            if cross.abs() < 1e-9 { Err(no_side()) } else { Ok(cross.signum()) }
        }
    }
}

/// The retract contour from P4c (on the equidistant, leaving with tangent `t`) to P3: the
/// approach contour of the reversed direction, reversed.
pub(in crate::interp) fn retract_contour(
    shape: Shape,
    disr: f64,
    radius: f64,
    p4c: P2,
    t: P2,
    side: f64,
) -> (P2, Elem) {
    // Backwards the contour arrives at P4c with −t, the side mirrored.
    let (p3, e) = approach_contour(shape, disr, radius, p4c, (-t.0, -t.1), -side);
    let back = match e {
        Elem::Line { s, e } => Elem::Line { s: e, e: s },
        Elem::Arc { c, r, a0, sweep } => Elem::Arc { c, r, a0: a0 + sweep, sweep: -sweep },
    };
    (p3, back)
}

/// Signed height of `p` above `base` along the plane normal.
pub(in crate::interp) fn height(p: &AxisVec, base: &AxisVec, normal: &AxisVec) -> f64 {
    (0..p.len()).map(|k| (p[k] - base[k]) * normal[k]).sum()
}

/// `base` raised by `h` along the normal.
pub(in crate::interp) fn raised(base: &AxisVec, normal: &AxisVec, h: f64) -> AxisVec {
    std::array::from_fn(|k| base[k] + h * normal[k])
}

/// Alarm 10748 when the retraction plane `h1` (DISRP) lies between the clearance plane `hd`
/// and the contour (or beyond the contour).
pub(in crate::interp) fn check_retraction_plane(h1: f64, hd: f64, line: u32) -> Result<(), Alarm> {
    if (h1 - hd) * hd < -1e-9 || (hd.abs() <= 1e-9 && h1 < -1e-9) {
        return Err(Alarm::sar_retraction_plane(line));
    }
    Ok(())
}

/// Alarm 10741 when the infeed from height `h0` over the clearance `hd` to the contour's
/// height 0 would turn back.
pub(in crate::interp) fn check_infeed(h0: f64, hd: f64, line: u32) -> Result<(), Alarm> {
    if (h0 - hd) * hd < -1e-9 || (hd.abs() > 1e-9 && h0.abs() < 1e-9) {
        return Err(Alarm::sar_direction_reversal(line));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: P2, b: P2) -> bool {
        (a.0 - b.0).hypot(a.1 - b.1) < 1e-12
    }

    /// The manual's example: tool radius 7, G41, contour from (40, −10) along +X, G247 DISR=13:
    /// P4c = (40, −3); the centre 13 to the left of it, (40, 10); P3 a quadrant back, (27, 10).
    #[test]
    fn the_quadrant_starts_a_quarter_turn_before_the_contour() {
        let (p3, e) = approach_contour(Shape::Quadrant, 13.0, 7.0, (40.0, -3.0), (1.0, 0.0), 1.0);
        assert!(close(p3, (27.0, 10.0)), "{p3:?}");
        let Elem::Arc { c, r, sweep, .. } = e else { panic!() };
        assert!(close(c, (40.0, 10.0)) && r == 13.0 && (sweep - FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn the_semicircle_starts_two_radii_to_the_side() {
        let (p3, e) = approach_contour(Shape::Semicircle, 10.0, 5.0, (0.0, 5.0), (1.0, 0.0), -1.0);
        assert!(close(p3, (0.0, -15.0)), "{p3:?}");
        let Elem::Arc { sweep, .. } = e else { panic!() };
        assert!((sweep + PI).abs() < 1e-15);
    }

    #[test]
    fn the_retract_quadrant_leaves_tangentially_to_its_side() {
        // Leaving (50, 5) heading +X to the left with radius 10: centre (50, 15), end (60, 15).
        let (p3, e) = retract_contour(Shape::Quadrant, 10.0, 5.0, (50.0, 5.0), (1.0, 0.0), 1.0);
        assert!(close(p3, (60.0, 15.0)), "{p3:?}");
        let Elem::Arc { c, a0, sweep, .. } = e else { panic!() };
        assert!(close(c, (50.0, 15.0)) && sweep > 0.0);
        assert!(close((c.0 + 10.0 * a0.cos(), c.1 + 10.0 * a0.sin()), (50.0, 5.0)));
    }
}
