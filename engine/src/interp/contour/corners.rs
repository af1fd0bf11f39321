//! Contour corners: RND= (rounding), CHF= (chamfer by its length) and CHR= (chamfer by the leg
//! length along the contour) between two straight blocks.
//!
//! A block with a corner request is held back until the next block is prepared; then both are
//! shortened and the rounding arc or chamfer is inserted between them. A rounding next to a
//! circle is shaped by `arc_rounding`; a chamfer next to a circle is left sharp (a limit).

use crate::alarm::Alarm;
use crate::interp::{Interpreter, Item, Prep};
use crate::machine_data::MachineConfig;
use crate::motion::{Arc, AxisLimit, AxisVec, Feed, Move, Path};

/// A corner requested at the end of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Corner {
    /// RND=: rounding radius.
    Round(f64),
    /// CHF=: length of the chamfer itself.
    Chamfer(f64),
    /// CHR=: length cut off each of the two blocks.
    ChamferLeg(f64),
}

/// A move held back for its corner.
#[derive(Debug, Clone)]
pub(in crate::interp) struct Held {
    item: Item,
    corner: Corner,
    line: u32,
    /// FRC/FRCM of the block (`corner_feed.rs`); `None`: the block's own feed.
    feed: Option<super::corner_feed::CornerFeed>,
}

impl Interpreter {
    /// Applies held corners to the items one preparation step produced.
    pub(in crate::interp) fn shape_corners(
        &mut self,
        out: &mut Vec<Item>,
        prep: Prep,
        request: Option<Corner>,
        cfg: &MachineConfig,
    ) -> Result<(), Alarm> {
        if let Some(held) = self.held.take() {
            match out.first_mut() {
                Some(Item::Move { mv, .. }) if prep != Prep::WaitForMainRun => {
                    let (first, insert) = corner_between(&held, mv, &AxisLimit::for_channel(cfg))?;
                    out.splice(0..0, std::iter::once(first).chain(insert));
                }
                // A statement between the two blocks (IF, ELSE, ENDIF, an assignment) makes
                // nothing: the corner waits for the next motion, as the control's does across
                // blocks without motion (MD20200 $MC_CHFRND_MAXNUM_DUMMY_BLOCKS).
                None if prep == Prep::Prepared => {
                    self.held = Some(held);
                    return Ok(());
                }
                _ => out.insert(0, held.item),
            }
        }
        // Hold this block's move when it asks for a corner and nothing follows it in the block.
        if let (Some(corner), Some(Item::Move { line, .. })) = (request, out.last()) {
            let line = *line;
            if prep == Prep::Prepared {
                let item = out.pop().expect("checked above");
                let rapid = matches!(&item, Item::Move { mv, .. } if mv.is_rapid());
                let feed = if rapid { None } else { self.corner_feed() };
                self.held = Some(Held { item, corner, line, feed });
            }
        }
        Ok(())
    }

    /// True while a move waits for the next block.
    pub(in crate::interp) fn holds_move(&self) -> bool {
        self.held.is_some()
    }
}

/// The corner between two programmed moves for the radius compensation, which shapes the
/// contour before offsetting it: `first` shortened and the corner element, `next` shortened
/// in place; None where the corner stays sharp (tangent blocks) or an arc meets it (TRC
/// shapes those in its plane with `compensation::rounding`).
pub(in crate::interp) fn split(
    first: &Move,
    corner: Corner,
    line: u32,
    next: &mut Move,
    limits: &[AxisLimit],
) -> Result<Option<(Move, Move)>, Alarm> {
    if first.path.arc.is_some() || next.path.arc.is_some() {
        return Ok(None);
    }
    let held =
        Held { item: Item::Move { mv: first.clone(), line, offsets: Default::default() }, corner, line, feed: None };
    Ok(match corner_between(&held, next, limits)? {
        (Item::Move { mv: a, .. }, Some(Item::Move { mv: b, .. })) => Some((a, b)),
        _ => None,
    })
}

/// The held move shortened to the corner, and the corner element, with `next` shortened too.
fn corner_between(held: &Held, next: &mut Move, limits: &[AxisLimit]) -> Result<(Item, Option<Item>), Alarm> {
    let Item::Move { mv: first, line, offsets } = &held.item else { unreachable!("only moves are held") };
    let sharp = || Ok((held.item.clone(), None));
    let item = |mv: Move| Item::Move { mv, line: *line, offsets: offsets.clone() };
    if first.path.arc.is_some() || next.path.arc.is_some() {
        return match held.corner {
            Corner::Round(r) => match super::arc_rounding::round_at_arc(first, next, r, held.line, limits)? {
                Some((shortened, mut corner)) => {
                    super::corner_feed::apply(&mut corner, held.feed, limits);
                    Ok((item(shortened), Some(item(corner))))
                }
                None => sharp(),
            },
            _ => sharp(),
        };
    }
    let p = first.path.end;
    let d1 = unit(&diff(&first.path.end, &first.path.start));
    let d2 = unit(&diff(&next.path.end, &next.path.start));
    let (Some(d1), Some(d2)) = (d1, d2) else { return sharp() };
    let cos_phi = dot(&d1, &d2).clamp(-1.0, 1.0);
    let phi = cos_phi.acos();
    if !(1e-9..=std::f64::consts::PI - 1e-9).contains(&phi) {
        // Tangent or reversing blocks have no corner to round.
        return sharp();
    }
    let leg = match held.corner {
        Corner::Round(r) => r / ((std::f64::consts::PI - phi) / 2.0).tan(),
        Corner::Chamfer(c) => c / (2.0 * (phi / 2.0).cos()),
        Corner::ChamferLeg(t) => t,
    };
    let len1 = norm(&diff(&first.path.end, &first.path.start));
    let len2 = norm(&diff(&next.path.end, &next.path.start));
    let fits = leg > 0.0 && leg <= len1 + 1e-9 && leg <= len2 + 1e-9;
    if !fits {
        return Err(Alarm::value_out_of_range(
            held.line,
            &format!(
                "corner {:?} needs {leg:.3} mm of the adjacent blocks ({len1:.3} and {len2:.3} available)",
                held.corner
            ),
        ));
    }
    let a = add(&p, &scale(&d1, -leg));
    let b = add(&p, &scale(&d2, leg));
    let scale_len =
        |mv: &Move, new_len: f64| -> f64 { mv.length * new_len / norm(&diff(&mv.path.end, &mv.path.start)) };

    let mut shortened = first.clone();
    shortened.path.end = a;
    shortened.length = scale_len(first, len1 - leg);
    shortened.exact_stop = false;
    let corner_path = match held.corner {
        Corner::Round(r) => {
            // Centre on the inner side: perpendicular to d1 in the plane of the corner.
            let inward = unit(&add(&d2, &scale(&d1, -cos_phi))).expect("the blocks are not parallel");
            let u = scale(&inward, -1.0);
            Path {
                start: a,
                end: b,
                arc: Some(Box::new(Arc { u, v: d1, radius: r, start_angle: 0.0, sweep: phi })),
                ori: None,
                curve: None,
            }
        }
        _ => Path::line(a, b),
    };
    let corner_len = match held.corner {
        Corner::Round(r) => r * phi,
        _ => norm(&diff(&b, &a)),
    };
    // The corner runs at the held block's feed (or its FRC/FRCM), within the axes' limits on
    // its arc.
    let mut corner = Move::new(corner_path, corner_len, Feed::Path(first.v_max), limits, first.exact_stop, first.tag);
    super::corner_feed::apply(&mut corner, held.feed, limits);
    let next_len = scale_len(next, len2 - leg);
    next.path.start = b;
    next.length = next_len;
    Ok((item(shortened), Some(item(corner))))
}

fn diff(a: &AxisVec, b: &AxisVec) -> AxisVec {
    std::array::from_fn(|k| a[k] - b[k])
}

fn add(a: &AxisVec, b: &AxisVec) -> AxisVec {
    std::array::from_fn(|k| a[k] + b[k])
}

fn scale(a: &AxisVec, s: f64) -> AxisVec {
    std::array::from_fn(|k| a[k] * s)
}

fn dot(a: &AxisVec, b: &AxisVec) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &AxisVec) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: &AxisVec) -> Option<AxisVec> {
    let n = norm(a);
    (n > 1e-12).then(|| scale(a, 1.0 / n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine_data::registry::MAX_CHANNEL_AXES;

    #[test]
    fn a_right_angle_rounding_leaves_each_line_by_the_radius() {
        let line = |from: [f64; 2], to: [f64; 2]| {
            let mut s = [0.0; MAX_CHANNEL_AXES];
            let mut e = [0.0; MAX_CHANNEL_AXES];
            s[..2].copy_from_slice(&from);
            e[..2].copy_from_slice(&to);
            let len = ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2)).sqrt();
            Move {
                length: len,
                v_max: 10.0,
                v_axes: 10.0,
                feed: 10.0,
                a_max: 100.0,
                ..Move::unlimited(Path::line(s, e), false, 0)
            }
        };
        let held = Held {
            item: Item::Move { mv: line([0.0, 0.0], [10.0, 0.0]), line: 1, offsets: Default::default() },
            corner: Corner::Round(2.0),
            line: 1,
            feed: None,
        };
        let mut next = line([10.0, 0.0], [10.0, 10.0]);
        let limits = vec![AxisLimit { max_velocity: 100.0, max_accel: 1000.0, accel_overload: 1.2 }; 3];
        let (first, corner) = corner_between(&held, &mut next, &limits).unwrap();
        let Item::Move { mv: first, .. } = first else { panic!() };
        let Some(Item::Move { mv: corner, .. }) = corner else { panic!() };
        assert!((first.path.end[0] - 8.0).abs() < 1e-12);
        assert!((next.path.start[1] - 2.0).abs() < 1e-12);
        // The arc's midpoint lies on the circle about (8, 2) at 45°.
        let mut mid = [0.0; MAX_CHANNEL_AXES];
        corner.path.at(0.5, &mut mid);
        let c = (8.0, 2.0);
        assert!(((mid[0] - c.0).hypot(mid[1] - c.1) - 2.0).abs() < 1e-12);
        assert!(mid[0] > 9.0 && mid[1] < 1.0, "{mid:?}");
    }
}
