//! Tool radius compensation (G40/G41/G42, G450/G451, DISC, OFFN): the tool centre runs on
//! the equidistant of the programmed contour in the working plane.
//!
//! Works on prepared moves: each move's working-plane part is read in plane coordinates (the
//! frame's images of the plane axes, so mirroring and rotation need no special cases), offset
//! to the left (G41) or right (G42) by the radius, and joined to its neighbour at the corner:
//! G450 inserts a transition arc about the contour corner (DISC pulls it towards the
//! intersection), G451 extends both equidistants to their intersection (the transition circle
//! from MD20210's change of direction); inner corners are cut at the intersection, and
//! equidistants of arcs that cross before a corner are cut at the first crossing. A move is
//! held back until its successor decides its end point, and joined elements wait in a chain
//! of at most MD20240 until the corners after them are resolved (`Next`): an element its
//! corners would reverse is omitted, and no motion of a corner is released before that; blocks
//! without motion in the plane wait behind it (at most MD20250 of them, else alarm 10762) and
//! run at the corner point. Elements too short for the tool are bridged (`trc_bottleneck`),
//! approach and retract follow G group 17 (`trc_approach`, KONTC in `trc_kontc`), RND/CHF are shaped on the
//! programmed contour first, and a turning tool's reference is its theoretical tip
//! (`trc_edge`).

use crate::alarm::Alarm;
use crate::interp::compensation::approach::{self, ApproachMode};
use crate::interp::contour::corners;
use crate::interp::{
    Item, SharedOffsets, compensation::bottleneck, compensation::disc, compensation::distant, compensation::rounding,
};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{Arc, AxisLimit, AxisVec, Feed, Move, Path};

// Smooth approach and retract's moves: a child module, so it reaches the compensator's state.
#[path = "sar_run.rs"]
mod sar_run;

/// Compensation side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// G41: tool left of the contour in the direction of travel.
    Left,
    /// G42: tool right of the contour.
    Right,
}

impl Side {
    pub fn opposite(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

/// Behaviour at outer corners (G group 18).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CornerMode {
    /// G450: transition circle about the corner.
    Circle,
    /// G451: intersection of the equidistants.
    Intersection,
}

/// Where the programmed feed applies on compensated arcs (G group 16).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcFeed {
    /// CFC: at the contour, on outer and inner arcs.
    Contour,
    /// CFTCP: at the tool centre path (no correction).
    CentrePath,
    /// CFIN: at the contour on inner arcs only (reduced), centre path on outer arcs.
    InnerOnly,
}

/// The compensation a move is prepared with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compensation {
    pub side: Side,
    /// Tool radius plus OFFN.
    pub radius: f64,
    pub corners: CornerMode,
    /// DISC (0..100): G450's transition circle pulled towards the intersection.
    pub disc: f64,
    pub arc_feed: ArcFeed,
    /// The working plane's abscissa and ordinate in axis space (unit vectors).
    pub u: AxisVec,
    pub v: AxisVec,
    /// Turning tools: the theoretical tip P relative to the cutting-edge centre S in plane
    /// coordinates (cutting edge position, `trc_edge`); the centre runs on the equidistant
    /// and the reference point follows P. Zero for milling tools and position 9.
    pub tip: P2,
    /// MD20250 CUTCOM_MAXNUM_DUMMY_BLOCKS.
    pub max_dummy_blocks: usize,
    /// MD20240 CUTCOM_MAXNUM_CHECK_BLOCKS: blocks examined for a bottleneck.
    pub max_check_blocks: usize,
    /// MD20210 CUTCOM_CORNER_LIMIT (radians): from this change of direction at an outer
    /// corner G451 takes the transition circle, not the far intersection.
    pub corner_limit: f64,
    /// CDON (G group 23): a bottleneck is bridged over up to MD20240 blocks (warning 10763);
    /// CDOF stops with alarm 10751 before entering it.
    pub collision_detection: bool,
    /// TRACYL groove-wall offset (513, 514 with k = 1): the channel slots of the unrolled
    /// peripheral coordinate and of the real Y axis. The part of the offset along the periphery
    /// is then travelled by the real Y axis, so the groove walls stay parallel.
    pub groove_wall: Option<(usize, usize)>,
}

impl Compensation {
    /// Signed offset: positive to the left of the direction of travel.
    pub(in crate::interp) fn offset(&self) -> f64 {
        match self.side {
            Side::Left => self.radius,
            Side::Right => -self.radius,
        }
    }
}

/// A prepared move with what the compensation needs besides it.
#[derive(Debug, Clone)]
pub struct Prepared {
    pub mv: Move,
    pub feed: Feed,
    pub line: u32,
    /// The offsets the move's item carries.
    pub offsets: SharedOffsets,
    /// G group 17 active in the block (approach with G41/G42, retract with G40).
    pub approach: ApproachMode,
    /// RND/CHF/CHR at its end: shaped into the programmed contour before the offset.
    pub corner: Option<corners::Corner>,
}

/// The contour element of a move in plane coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::interp) enum Elem {
    Line { s: P2, e: P2 },
    Arc { c: P2, r: f64, a0: f64, sweep: f64 },
}

pub(in crate::interp) type P2 = (f64, f64);

/// A compensated move waiting for its successor.
#[derive(Debug, Clone)]
struct Held {
    /// Elements after it whose equidistants the tool cannot reach (bottleneck look-ahead,
    /// MD20240): they are bridged when a later element meets this one.
    skipped: Vec<(Prepared, Elem)>,
    /// The elements after it, each joined to its predecessor but not released (at most
    /// MD20240 of them): see [`Next`]. `skipped` follows the last of them.
    chain: Vec<Next>,
    p: Prepared,
    /// The programmed contour element.
    contour: Elem,
    /// Where its equidistant starts (decided by the previous corner).
    start: P2,
    comp: Compensation,
}

/// An element after the held one, joined to its predecessor but not yet released. The join
/// (the predecessor's end, the transition, this element's start) is final only once the
/// corners after it are known not to reverse it: an element shorter than what the tool needs
/// is omitted and its predecessor joined to a later element instead, going back as far as the
/// look-ahead (MD20240) reaches. No motion of a corner leaves the compensator before the
/// corner is resolved.
#[derive(Debug, Clone)]
struct Next {
    /// Elements omitted between the predecessor and this one (only their motion outside the
    /// plane runs, at the join).
    omitted: Vec<(Prepared, Elem)>,
    p: Prepared,
    contour: Elem,
    comp: Compensation,
    meet: Meet,
    /// How many of the pending items wait before it (they run at the held element's end).
    mark: usize,
}

/// What waits behind the held move: blocks without motion in the compensation plane. They
/// run where the held move's equidistant ends, before the next corner's transition.
#[derive(Debug, Clone)]
enum Pending {
    /// A move outside the plane (infeed), kept at the tool's plane position.
    Move(Box<(Prepared, Compensation)>),
    /// Anything else the block produced (M functions, dwell, messages, stops).
    Item(Box<Item>),
}

/// State of the compensation between moves.
#[derive(Debug, Clone, Default)]
pub struct Compensator {
    held: Option<Held>,
    /// The selection move (G41/G42 switched on), waiting for the first compensated element.
    approach: Option<(Prepared, Compensation)>,
    /// Where the tool centre stands in plane coordinates after the last emitted move, while
    /// compensation is active.
    tool_at: Option<P2>,
    /// Axis-space end of the last move handed out (the tool's position in the prepared stream).
    last_end: Option<AxisVec>,
    pending: Vec<Pending>,
    /// Blocks without plane motion in a row behind the held move (MD20250).
    dummy_blocks: usize,
    /// Whether the current block reached the compensator with motion in the plane, with motion
    /// outside it only, and how long `out` was after the compensator last wrote to it.
    block_plane_move: bool,
    block_dummy_move: bool,
    mark: usize,
    /// Smooth approach (from the selection block until the first element) or retract.
    sar: Option<Box<super::sar::Sar>>,
    /// The held element runs with the radius-0 compensation of a smooth approach without TRC:
    /// the next uncompensated move just follows it.
    sar_virtual: bool,
    /// A SAR approach block without an end point in the plane: P4 comes from the next block.
    sar_head: Option<Box<Prepared>>,
    /// The SAR words of an approach block without any motion and the feed before it: the next
    /// motion block runs them.
    sar_deferred: Option<(super::sar::SarWords, Option<Feed>)>,
    /// The selection block's moves (and what waited with them), held back until the first
    /// element's end corner is resolved: an alarm then stops the program before the tool
    /// has moved onto a contour it cannot follow.
    lead_in: Vec<Item>,
    /// Warnings (10763: a block omitted) for the interpreter's alarm display.
    warnings: Vec<Alarm>,
    /// The first element of the compensated contour (where the approach put the tool): a
    /// closed contour's last element is its neighbour for the bottleneck check.
    first_contour: Option<Elem>,
}

impl Compensator {
    /// The warnings raised since the last call (they do not stop the program).
    pub fn take_warnings(&mut self) -> Vec<Alarm> {
        std::mem::take(&mut self.warnings)
    }

    /// True while a move is held back.
    pub fn holds(&self) -> bool {
        self.held.is_some() || self.approach.is_some() || !self.pending.is_empty() || self.sar_head.is_some()
    }

    /// True when nothing is held and the tool has no compensated position of its own: a move
    /// without compensation passes through unchanged (block preparation's fast lane needs this).
    pub fn idle(&self) -> bool {
        !self.holds() && self.tool_at.is_none()
    }

    /// Takes note of a move without compensation that the caller has just pushed onto `out`
    /// while the compensator is [`idle`](Self::idle): what [`push`](Self::push) does for it
    /// then, without the way through `deselect` and without moving the item again (block
    /// preparation's fast lane and general path).
    pub fn passed(&mut self, out: &[Item]) {
        debug_assert!(self.idle(), "only an idle compensator lets a move pass");
        self.dummy_blocks = 0;
        if let Some(Item::Move { mv, .. }) = out.last() {
            // Into the value already there: one copy, no `Option` built on the way.
            match &mut self.last_end {
                Some(end) => *end = mv.path.end,
                none => *none = Some(mv.path.end),
            }
        }
        self.mark = out.len();
    }

    /// Takes the SAR request of the block about to be pushed (kept until it is run).
    pub fn arm(&mut self, sar: Option<Box<super::sar::Sar>>) {
        if sar.is_some() {
            self.sar = sar;
        }
    }

    /// Keeps the SAR words of an approach block without motion for the next motion block.
    pub fn defer_sar(&mut self, words: super::sar::SarWords, before: Option<Feed>) {
        self.sar_deferred = Some((words, before));
    }

    /// The SAR words a block without motion left for this one.
    pub fn take_deferred_sar(&mut self) -> Option<(super::sar::SarWords, Option<Feed>)> {
        self.sar_deferred.take()
    }

    /// The compensation of radius 0 that a smooth approach without TRC runs its block and the
    /// contour's first element with; None otherwise.
    pub fn sar_compensation(&self) -> Option<Compensation> {
        self.sar.as_ref().and_then(|s| s.zero)
    }

    /// Starts a block: `out` is where its items go.
    pub fn begin_block(&mut self, out: &[Item]) {
        self.block_plane_move = false;
        self.block_dummy_move = false;
        self.mark = out.len();
    }

    /// Ends a block: the items it added to `out` after the compensator's last output wait
    /// behind the held move (they belong to the block, which has not run yet). A block without
    /// motion in the plane counts towards MD20250; one too many is alarm 10762. Returns false
    /// (and defers nothing) when the block produced moves past the compensator, which then
    /// has to be flushed.
    pub fn end_block(&mut self, out: &mut Vec<Item>) -> Result<bool, Alarm> {
        if !self.holds() {
            return Ok(true);
        }
        let mark = self.mark.min(out.len());
        if out[mark..].iter().any(|i| matches!(i, Item::Move { .. })) {
            return Ok(false);
        }
        let items: Vec<Item> = if mark < out.len() { out.drain(mark..).collect() } else { Vec::new() };
        if !self.block_plane_move && (self.block_dummy_move || !items.is_empty()) {
            self.dummy_blocks += 1;
            let max = self.max_dummy_blocks();
            let line = items.iter().rev().find_map(Item::line).or_else(|| {
                self.pending.iter().rev().find_map(|p| match p {
                    Pending::Move(m) => Some(m.0.line),
                    Pending::Item(i) => i.line(),
                })
            });
            if self.dummy_blocks > max {
                let line = line.unwrap_or(0);
                return Err(Alarm::trc_dummy_blocks(line, max));
            }
        }
        self.pending.extend(items.into_iter().map(|i| Pending::Item(Box::new(i))));
        Ok(true)
    }

    fn max_dummy_blocks(&self) -> usize {
        self.held
            .as_ref()
            .map(|h| h.comp.max_dummy_blocks)
            .or(self.approach.as_ref().map(|a| a.1.max_dummy_blocks))
            .unwrap_or(usize::MAX)
    }

    /// Hands an item to the main run, or keeps it behind the held move.
    pub fn emit_or_defer(&mut self, item: Item, out: &mut Vec<Item>) {
        if self.holds() {
            self.block_dummy_move = true;
            self.pending.push(Pending::Item(Box::new(item)));
        } else {
            self.emit(item, out);
        }
    }

    fn emit(&mut self, item: Item, out: &mut Vec<Item>) {
        if let Item::Move { mv, .. } = &item {
            self.last_end = Some(mv.path.end);
        }
        out.push(item);
        self.mark = out.len();
    }

    /// Where a move outside the plane starts: its own start with the plane part (and TRACYL's
    /// groove-wall share) where the last move handed out ended. Spindle axes in position
    /// control start where the block found them, not at a stale value of an earlier move.
    fn start_at_tool(&self, own: AxisVec, comp: &Compensation) -> AxisVec {
        let Some(last) = self.last_end else { return own };
        let mut s = with_plane(&own, to_plane(&last, comp), comp);
        if let Some((_, extra)) = comp.groove_wall {
            s[extra] = last[extra];
        }
        s
    }

    /// Where the next move starts: the end of the last move handed out, else `fallback`.
    fn from(&self, fallback: AxisVec) -> AxisVec {
        self.last_end.unwrap_or(fallback)
    }

    /// Feeds one move. `comp` is the compensation active for it (None: G40). Appends the moves
    /// that are ready for the main run to `out`.
    pub fn push(
        &mut self,
        p: Prepared,
        comp: Option<Compensation>,
        limits: &[AxisLimit],
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let Some(comp) = comp else {
            return self.deselect(p, limits, out);
        };
        let line = p.line;
        if let Some(arc) = &p.mv.path.arc
            && (arc_in_plane(arc, &comp).2.abs() - 1.0).abs() > 1e-6
        {
            return Err(Alarm::trc_helix_axis(line));
        }
        let Some(contour) = element(&p.mv, &comp) else {
            if self.sar.as_ref().is_some_and(|s| !s.retract)
                && self.held.is_none()
                && self.approach.is_none()
                && self.sar_head.is_none()
            {
                // The SAR block's end point in the plane is the next block's.
                self.sar_head = Some(Box::new(p));
                return Ok(());
            }
            // No motion in the working plane: wait behind the held move (look-ahead across
            // dummy blocks), or run at the tool's plane position.
            self.block_dummy_move = true;
            if self.held.is_some() || self.approach.is_some() {
                self.pending.push(Pending::Move(Box::new((p, comp))));
                return Ok(());
            }
            self.flush(limits, out)?;
            let mut p = p;
            if let Some(at) = self.tool_at {
                let from = self.start_at_tool(p.mv.path.start, &comp);
                let end = hold_groove_wall(place(&p.mv.path.end, at, &comp), &from, &comp);
                p.mv = rebuild(&p, Path::line(from, end), limits);
            }
            self.emit(p.into_item(), out);
            return Ok(());
        };
        self.block_plane_move = true;
        self.dummy_blocks = 0;
        let waiting = self.pending.len();
        if let Some(h) = self.held.as_mut()
            && h.skipped.is_empty()
        {
            // The last element received: the tentative one after the held element, if any.
            let (last, last_contour, last_comp, quiet) = match h.chain.last_mut() {
                Some(n) => (&mut n.p, &mut n.contour, n.comp, waiting == n.mark),
                None => (&mut h.p, &mut h.contour, h.comp, waiting == 0),
            };
            if quiet && let Some(corner) = last.corner.take() {
                // The rounding or chamfer is part of the contour: insert it, then offset.
                let mut next = p.clone();
                if let Some((first, between)) = corners::split(&last.mv, corner, last.line, &mut next.mv, limits)?
                    && let (Some(shortened), Some(_)) = (element(&first, &last_comp), element(&next.mv, &comp))
                {
                    last.mv = first;
                    *last_contour = shortened;
                    let inserted = Prepared { mv: between, corner: None, ..last.clone() };
                    self.push(inserted, Some(last_comp), limits, out)?;
                    return self.push(next, Some(comp), limits, out);
                }
                // A rounding where an arc meets the corner, shaped in the plane.
                if let corners::Corner::Round(rho) = corner
                    && let Some((e1, round, e2)) = rounding::round(last_contour, &contour, rho, last.line)?
                {
                    let (s1, e1_3) = (last.mv.path.start, last.mv.path.end);
                    last.mv = contour_move(last, e1, s1, e1_3, &last_comp, limits);
                    *last_contour = e1;
                    let between = contour_move(last, round, e1_3, e1_3, &last_comp, limits);
                    let inserted = Prepared { mv: between, corner: None, ..last.clone() };
                    let (s2, e2_3) = (next.mv.path.start, next.mv.path.end);
                    next.mv = contour_move(&next, e2, s2, e2_3, &comp, limits);
                    self.push(inserted, Some(last_comp), limits, out)?;
                    return self.push(next, Some(comp), limits, out);
                }
            }
        }
        let d = comp.offset();
        if let Some((approach, _)) = self.approach.take() {
            if let Some(sar) = self.sar.take() {
                return self.sar_approach(approach, *sar, p, contour, comp, limits, out);
            }
            // The selection block ends on the first element's equidistant (NORM) or goes round
            // its start point (KONT) or joins it tangentially (KONTT) or with continuous
            // curvature (KONTC).
            let s0 = minus(to_plane(&approach.mv.path.start, &comp), comp.tip);
            let (a3, b3) = (approach.mv.path.start, approach.mv.path.end);
            let lift = outside_plane(&a3, &b3, &comp);
            let (segments, start) = approach::approach(approach.approach, s0, &contour, d, lift, &comp, line)?;
            // The approach's items go to the lead-in buffer, released with the first corner.
            let mut buf = Vec::new();
            let out_mark = self.mark;
            let out = &mut buf;
            if segments.is_empty() {
                // Already on the equidistant: only the axes outside the plane move.
                let end = place(&b3, start, &comp);
                let mv = rebuild(&approach, Path::line(a3, end), limits);
                self.emit(approach.item_with(mv), out);
            }
            let n = segments.len();
            let mut from3 = a3;
            for (i, (seg, share)) in segments.into_iter().enumerate() {
                let mut mv = plain(&approach, seg, from3, mix(&a3, &b3, share), &comp, limits);
                if i == 0 {
                    // The first piece starts where the tool stands (uncompensated).
                    let mut path = mv.path.clone();
                    path.start = a3;
                    mv = rebuild(&approach, path, limits);
                }
                // KONTC's chords are one polynomial block: no exact stop (G60) between them.
                mv.exact_stop &= i + 1 == n || approach.approach != ApproachMode::Curvature;
                from3 = mv.path.end;
                self.emit(approach.item_with(mv), out);
            }
            self.tool_at = Some(start);
            self.release_pending(limits, out);
            self.lead_in = std::mem::take(out);
            self.mark = out_mark;
            self.first_contour = Some(contour);
            self.held = Some(Held { skipped: Vec::new(), chain: Vec::new(), p, contour, start, comp });
            return Ok(());
        }
        match self.held.take() {
            None if self.tool_at.is_none() => {
                // The selection block itself: a straight move, held until the next element.
                if matches!(contour, Elem::Arc { .. }) {
                    return Err(Alarm::trc_selection(line));
                }
                self.approach = Some((p, comp));
            }
            None => {
                // After moves outside the plane: link from where the tool stands.
                let start = offset_start(&contour, d);
                if let Some(at) = self.tool_at
                    && dist(at, start) > 1e-9
                {
                    let from = self.from(p.mv.path.start);
                    let to = place(&from, start, &comp);
                    self.emit(p.item_with(rebuild(&p, Path::line(from, to), limits)), out);
                }
                self.tool_at = Some(start);
                self.first_contour = Some(contour);
                self.held = Some(Held { skipped: Vec::new(), chain: Vec::new(), p, contour, start, comp });
            }
            Some(prev)
                if prev.skipped.is_empty() && {
                    let last = prev.chain.last().map_or(&prev.comp, |n| &n.comp);
                    last.side != comp.side || last.radius != comp.radius
                } =>
            {
                // G41 ⇄ G42 (or another radius) without G40: the old side ends perpendicular at
                // its end point, a straight line leads to the perpendicular start of the new.
                self.held = Some(prev);
                self.flush(limits, out)?;
                let start = offset_start(&contour, d);
                let from = self.from(p.mv.path.start);
                if self.tool_at.is_some_and(|at| dist(at, start) > 1e-9) {
                    let to = place(&from, start, &comp);
                    self.emit(p.item_with(rebuild(&p, Path::line(from, to), limits)), out);
                }
                self.tool_at = Some(start);
                self.first_contour = Some(contour);
                self.held = Some(Held { skipped: Vec::new(), chain: Vec::new(), p, contour, start, comp });
            }
            Some(mut prev) => {
                let max_check = comp.max_check_blocks.max(1);
                let waiting = self.pending.len();
                if prev.skipped.is_empty() {
                    let (last, start) = match prev.chain.last() {
                        Some(n) => (&n.contour, n.meet.2),
                        None => (&prev.contour, prev.start),
                    };
                    let line_last = prev.chain.last().map_or(prev.p.line, |n| n.p.line);
                    match corner(last, &contour, d, &comp, line_last)? {
                        Some(meet) if forward(last, start, meet.0) => {
                            prev.chain.push(Next { omitted: Vec::new(), p, contour, comp, meet, mark: waiting });
                        }
                        // p is too short for the tool: a later element may join (MD20240).
                        None => prev.skipped.push((p, contour)),
                        // The last element is shorter than its corners need: omit it.
                        Some(_) => self.backtrack(&mut prev, p, contour, comp, waiting)?,
                    }
                } else {
                    let (last, start, comp_last) = match prev.chain.last() {
                        Some(n) => (&n.contour, n.meet.2, n.comp),
                        None => (&prev.contour, prev.start, prev.comp),
                    };
                    let eq = offset_elem(last, comp_last.offset(), Some(start), None, prev.p.line)?;
                    let skipped_last = &prev.skipped.last().expect("skipped").1;
                    match bottleneck::bridge(
                        &eq,
                        skipped_last,
                        &contour,
                        d,
                        comp.collision_detection || prev.skipped.len() == 1,
                    ) {
                        Some(meet) if forward(last, start, meet.0) => {
                            let omitted = std::mem::take(&mut prev.skipped);
                            prev.chain.push(Next { omitted, p, contour, comp, meet, mark: waiting });
                        }
                        _ => self.backtrack(&mut prev, p, contour, comp, waiting)?,
                    }
                }
                if prev.skipped.len() >= max_check {
                    return Err(bottleneck(line));
                }
                self.held = Some(prev);
                // Release what lies beyond the look-ahead window.
                while self.held.as_ref().is_some_and(|h| h.chain.len() > max_check) {
                    self.commit(limits, out, false)?;
                }
            }
        }
        Ok(())
    }

    /// The element `p` cannot follow the last element joined (that one would run backwards, or
    /// the bottleneck is not passed yet): omit joined elements from the end, joining each
    /// predecessor to `p` through its transition circle or across the omitted elements, back
    /// to the held element. Where no join is found `p` waits among the skipped elements.
    fn backtrack(
        &mut self,
        prev: &mut Held,
        p: Prepared,
        contour: Elem,
        comp: Compensation,
        waiting: usize,
    ) -> Result<(), Alarm> {
        let d = comp.offset();
        while let Some(n) = prev.chain.pop() {
            let Next { omitted, p: np, contour: nc, meet: nmeet, .. } = n;
            let mut skipped = omitted;
            skipped.push((np, nc));
            skipped.append(&mut prev.skipped);
            prev.skipped = skipped;
            let (last, start, comp_last) = match prev.chain.last() {
                Some(n) => (&n.contour, n.meet.2, n.comp),
                None => (&prev.contour, prev.start, prev.comp),
            };
            let joined = match nmeet.1.and_then(|arc| cut_transition(&arc, &contour, d)) {
                Some((arc, x)) => Some((nmeet.0, arc, x)),
                None => {
                    let eq = offset_elem(last, comp_last.offset(), Some(start), None, prev.p.line)?;
                    let skipped_last = &prev.skipped.last().expect("skipped").1;
                    bottleneck::bridge(
                        &eq,
                        skipped_last,
                        &contour,
                        d,
                        comp.collision_detection || prev.skipped.len() == 1,
                    )
                    .filter(|m| forward(last, start, m.0))
                }
            };
            if let Some(meet) = joined {
                let omitted = std::mem::take(&mut prev.skipped);
                prev.chain.push(Next { omitted, p, contour, comp, meet, mark: waiting });
                return Ok(());
            }
        }
        prev.skipped.push((p, contour));
        Ok(())
    }

    /// Hands out the selection block's held-back moves.
    fn release_lead_in(&mut self, out: &mut Vec<Item>) {
        if !self.lead_in.is_empty() {
            out.append(&mut self.lead_in);
            self.mark = out.len();
        }
    }

    /// Releases the held element up to its corner with the first joined element (and what was
    /// omitted and what waited between them), which becomes the held element. Before that the
    /// held element is checked against the later elements in the look-ahead (`distant`);
    /// `last`: no more elements follow (the last joined one ends perpendicular to its end).
    fn commit(&mut self, limits: &[AxisLimit], out: &mut Vec<Item>, last: bool) -> Result<(), Alarm> {
        self.check_distant(last)?;
        self.release_lead_in(out);
        let Some(mut prev) = self.held.take() else { return Ok(()) };
        if prev.chain.is_empty() {
            self.held = Some(prev);
            return Ok(());
        }
        let Next { omitted, p, contour, comp, meet: (prev_end, transition, next_start), mark } = prev.chain.remove(0);
        let eq = offset_elem(&prev.contour, prev.comp.offset(), Some(prev.start), Some(prev_end), prev.p.line)?;
        let mv = finish(&prev.p, eq, &prev.comp, limits, true);
        self.emit(prev.p.item_with(mv), out);
        self.tool_at = Some(prev_end);
        for (skipped, _) in omitted {
            self.warnings.push(Alarm::trc_block_omitted(skipped.line));
            // An omitted element leaves only its axes outside the plane to travel.
            let from = self.from(skipped.mv.path.start);
            let end = place(&skipped.mv.path.end, prev_end, &comp);
            self.emit(skipped.item_with(rebuild(&skipped, Path::line(from, end), limits)), out);
        }
        let mark = mark.min(self.pending.len());
        let after = self.pending.split_off(mark);
        self.release_pending(limits, out);
        self.pending = after;
        for n in &mut prev.chain {
            n.mark = n.mark.saturating_sub(mark);
        }
        if let Some(arc) = transition {
            // The transition belongs to the next block (its line and feed) and runs at the
            // tool's height after the dummy blocks.
            let from = self.from(prev.p.mv.path.end);
            let mv = finish_transition(&p, arc, from, &comp, limits);
            self.emit(p.item_with(mv), out);
        }
        self.tool_at = Some(next_start);
        let chain = std::mem::take(&mut prev.chain);
        self.held = Some(Held { skipped: prev.skipped, chain, p, contour, start: next_start, comp });
        Ok(())
    }

    /// Bottleneck detection between the held element and the later elements in the look-ahead
    /// that are not its neighbour (`distant`): with CDON the elements between are skipped and
    /// the held element joined to the later one where their tool paths cross; with CDOF alarm
    /// 10751 before the held element moves. The last joined element's equidistant is left out
    /// until no more elements follow (where it ends is not known before). A closed contour's
    /// last and first elements are neighbours: they are not checked against each other (the
    /// approach and the deselection end on each other's extension, as programmed).
    fn check_distant(&mut self, last: bool) -> Result<(), Alarm> {
        let first = self.first_contour;
        let Some(prev) = self.held.as_mut() else { return Ok(()) };
        let Some(t) = prev.chain.first() else { return Ok(()) };
        let d = prev.comp.offset();
        let head = offset_elem(&prev.contour, d, Some(prev.start), Some(t.meet.0), prev.p.line)?;
        if !t.omitted.is_empty() {
            // A join across omitted elements (the look-ahead's, or a cut below): the joined
            // paths may come nearer than the radius to the skipped contour, or to each other's
            // element before they meet: alarm 10751.
            let t_end = prev.chain.get(1).map(|m| m.meet.0);
            let mut t_pieces: Vec<Elem> = t.meet.1.into_iter().collect();
            if t_end.is_some() || last {
                t_pieces.push(offset_elem(&t.contour, t.comp.offset(), Some(t.meet.2), t_end, t.p.line)?);
            }
            let skipped = || t.omitted.iter().map(|(_, c)| *c);
            let r = d.abs();
            if distant::near_any(&[head], skipped().chain(std::iter::once(t.contour)), r)
                || distant::near_any(&t_pieces, skipped().chain(std::iter::once(prev.contour)), r)
            {
                return Err(bottleneck(t.p.line));
            }
        }
        if prev.chain.len() < 2 {
            return Ok(());
        }
        let mut later = Vec::new();
        for (k, n) in prev.chain.iter().enumerate().skip(1) {
            if let Some(t) = n.meet.1 {
                later.push((k, true, t));
            }
            let end = prev.chain.get(k + 1).map(|m| m.meet.0);
            if (end.is_none() && !last) || end.is_some_and(|e| dist(e, n.meet.2) < 1e-9) {
                continue;
            }
            later.push((k, false, offset_elem(&n.contour, n.comp.offset(), Some(n.meet.2), end, n.p.line)?));
        }
        let n = prev.chain.len() - 1;
        let closed =
            first == Some(prev.contour) && dist(elem_end(&prev.chain[n].contour), elem_start(&prev.contour)) < 1e-6;
        if closed {
            later.retain(|&(k, ..)| k != n);
        }
        let Some((k, on_transition, x)) = distant::first_crossing(&head, &later) else {
            let upto = if last && !closed { n + 1 } else { n };
            let contours: Vec<_> = prev.chain[..upto].iter().enumerate().skip(1).map(|(k, n)| (k, n.contour)).collect();
            let pieces: Vec<Elem> = std::iter::once(head).chain(prev.chain[0].meet.1).collect();
            return match distant::too_near(&pieces, &prev.contour, &later, &contours, prev.comp.offset().abs()) {
                Some(k) => Err(bottleneck(prev.chain[k].p.line)),
                None => Ok(()),
            };
        };
        if !prev.comp.collision_detection {
            return Err(bottleneck(prev.chain[k].p.line));
        }
        let mut omitted = Vec::new();
        for n in prev.chain.drain(..k) {
            omitted.extend(n.omitted);
            omitted.push((n.p, n.contour));
        }
        let target = &mut prev.chain[0];
        omitted.append(&mut target.omitted);
        target.omitted = omitted;
        target.meet = match (on_transition, target.meet.1) {
            (true, Some(arc)) => (x, distant::arc_from(&arc, x), target.meet.2),
            _ => (x, None, x),
        };
        // What remains is checked again (another loop, or a band reached without a crossing).
        self.check_distant(last)
    }

    /// Releases every joined element up to the last one, which stays held.
    fn commit_all(&mut self, limits: &[AxisLimit], out: &mut Vec<Item>) -> Result<(), Alarm> {
        self.release_lead_in(out);
        while self.held.as_ref().is_some_and(|h| !h.chain.is_empty()) {
            self.commit(limits, out, true)?;
        }
        Ok(())
    }

    /// G40 (or a move without compensation): the held move ends perpendicular to its contour
    /// (NORM) or goes round its end point (KONT, KONTT, KONTC), then this move travels uncompensated
    /// to its programmed end.
    fn deselect(&mut self, p: Prepared, limits: &[AxisLimit], out: &mut Vec<Item>) -> Result<(), Alarm> {
        self.commit_all(limits, out)?;
        if let Some(sar) = self.sar.take() {
            return self.sar_retract(p, *sar, limits, out);
        }
        if std::mem::take(&mut self.sar_virtual) {
            self.flush(limits, out)?;
            self.tool_at = None;
            self.emit(p.into_item(), out);
            return Ok(());
        }
        let was_active = self.tool_at.is_some() || self.holds();
        if was_active && p.mv.path.arc.is_some() {
            return Err(Alarm::trc_deselection(p.line));
        }
        let retract = match &self.held {
            Some(h) if p.approach != ApproachMode::Norm && self.pending.is_empty() && h.skipped.is_empty() => {
                let to = minus(to_plane(&p.mv.path.end, &h.comp), h.comp.tip);
                let from = to_plane(&p.mv.path.start, &h.comp);
                (dist(from, to) > 1e-9).then_some((h.clone(), to))
            }
            _ => None,
        };
        if let Some((h, to)) = retract {
            self.held = None;
            let d = h.comp.offset();
            let b3 = p.mv.path.end;
            let lift = outside_plane(&p.mv.path.start, &b3, &h.comp);
            let (end, segments) = approach::retract(p.approach, &h.contour, d, to, lift, &h.comp, p.line)?;
            let eq = offset_elem(&h.contour, d, Some(h.start), Some(end), h.p.line)?;
            let mv = finish(&h.p, eq, &h.comp, limits, true);
            self.emit(h.p.item_with(mv), out);
            let a3 = self.from(p.mv.path.start);
            let n = segments.len();
            for (i, (seg, share)) in segments.into_iter().enumerate() {
                let from = self.from(p.mv.path.start);
                let mut mv = plain(&p, seg, from, mix(&a3, &b3, share), &h.comp, limits);
                if i + 1 == n {
                    // The last piece ends at the programmed end point (the uncompensated tip).
                    let mut path = mv.path.clone();
                    path.end = b3;
                    mv = rebuild(&p, path, limits);
                }
                mv.exact_stop &= i + 1 == n || p.approach != ApproachMode::Curvature;
                self.emit(p.item_with(mv), out);
            }
            self.tool_at = None;
            return Ok(());
        }
        self.flush(limits, out)?;
        self.tool_at = None;
        let mut p = p;
        if was_active {
            let from = self.from(p.mv.path.start);
            p.mv = rebuild(&p, Path::line(from, p.mv.path.end), limits);
        }
        self.emit(p.into_item(), out);
        Ok(())
    }

    /// Hands out what waited behind the held move, at the tool's current plane position.
    fn release_pending(&mut self, limits: &[AxisLimit], out: &mut Vec<Item>) {
        self.dummy_blocks = 0;
        for pending in std::mem::take(&mut self.pending) {
            match pending {
                Pending::Item(item) => self.emit(*item, out),
                Pending::Move(m) => {
                    let (mut p, comp) = *m;
                    let from = self.start_at_tool(p.mv.path.start, &comp);
                    let end = match self.tool_at {
                        Some(at) => hold_groove_wall(place(&p.mv.path.end, at, &comp), &from, &comp),
                        None => p.mv.path.end,
                    };
                    p.mv = rebuild(&p, Path::line(from, end), limits);
                    self.emit(p.into_item(), out);
                }
            }
        }
    }

    /// Ends the held move perpendicular to its contour end (before anything that is not a
    /// compensated move, and at the end of the program).
    pub fn flush(&mut self, limits: &[AxisLimit], out: &mut Vec<Item>) -> Result<(), Alarm> {
        self.release_lead_in(out);
        self.sar_virtual = false;
        if let Some(head) = self.sar_head.take() {
            self.sar = None;
            self.emit(head.into_item(), out);
        }
        if let Some((approach, _)) = self.approach.take() {
            // A selection block without a following element stays uncompensated.
            self.sar = None;
            self.emit(approach.item_with(approach.mv.clone()), out);
            self.tool_at = None;
        }
        self.commit_all(limits, out)?;
        if let Some(h) = self.held.take() {
            if let Some((skipped, _)) = h.skipped.last() {
                // The contour ends inside the bottleneck.
                return Err(bottleneck(skipped.line));
            }
            if !forward(&h.contour, h.start, offset_end(&h.contour, h.comp.offset())) {
                // The last element is shorter than its start corner needs.
                return Err(bottleneck(h.p.line));
            }
            let eq = offset_elem(&h.contour, h.comp.offset(), Some(h.start), None, h.p.line)?;
            self.tool_at = Some(elem_end(&eq));
            let mv = finish(&h.p, eq, &h.comp, limits, true);
            self.emit(h.p.item_with(mv), out);
        }
        self.release_pending(limits, out);
        Ok(())
    }

    /// Drops everything (reset).
    pub fn clear(&mut self) {
        *self = Compensator::default();
    }
}

impl Prepared {
    /// The item with the prepared move moved into it (no copy of the move or the offsets).
    fn into_item(self) -> Item {
        Item::Move { mv: self.mv, line: self.line, offsets: self.offsets }
    }

    fn item_with(&self, mut mv: Move) -> Item {
        // A feed per spindle revolution stays one on the offset path.
        mv.per_rev = self.mv.per_rev;
        Item::Move { mv, line: self.line, offsets: self.offsets.clone() }
    }
}

/// A move of the tool centre along `elem` at the programmed feed (approach and retract
/// pieces). The axes outside the plane move from `from3` to `to3` on it.
fn plain(p: &Prepared, elem: Elem, from3: AxisVec, to3: AxisVec, comp: &Compensation, limits: &[AxisLimit]) -> Move {
    let start3 = place(&from3, elem_start(&elem), comp);
    let end3 = place(&to3, elem_end(&elem), comp);
    rebuild(p, elem_path(elem, start3, end3, comp), limits)
}

/// The path of `elem` from `start3` to `end3` (a line, or the arc in the plane).
fn elem_path(elem: Elem, start3: AxisVec, end3: AxisVec, comp: &Compensation) -> Path {
    match elem {
        Elem::Line { .. } => Path::line(start3, end3),
        Elem::Arc { r, a0, sweep, .. } => Path {
            start: start3,
            end: end3,
            arc: Some(Box::new(Arc { u: comp.u, v: comp.v, radius: r, start_angle: a0, sweep })),
            ori: None,
            curve: None,
        },
    }
}

/// A programmed contour element as a move (the contour itself, not the tool centre): RND
/// shaped in the plane. The axes outside the plane move from `from3` to `to3`.
fn contour_move(
    p: &Prepared,
    elem: Elem,
    from3: AxisVec,
    to3: AxisVec,
    comp: &Compensation,
    limits: &[AxisLimit],
) -> Move {
    let start3 = with_plane(&from3, elem_start(&elem), comp);
    let end3 = with_plane(&to3, elem_end(&elem), comp);
    rebuild(p, elem_path(elem, start3, end3, comp), limits)
}

/// `a` moved the share `s` of the way to `b` (exactly `a` or `b` at the ends).
fn mix(a: &AxisVec, b: &AxisVec, s: f64) -> AxisVec {
    if s <= 0.0 {
        *a
    } else if s >= 1.0 {
        *b
    } else {
        std::array::from_fn(|k| a[k] + s * (b[k] - a[k]))
    }
}

/// Length of the travel from `a` to `b` outside the working plane.
fn outside_plane(a: &AxisVec, b: &AxisVec, comp: &Compensation) -> f64 {
    let d: AxisVec = std::array::from_fn(|k| b[k] - a[k]);
    let (du, dv) = (dot(&d, &comp.u), dot(&d, &comp.v));
    (dot(&d, &d) - du * du - dv * dv).max(0.0).sqrt()
}

/// The move rebuilt on a new path with the same feed and limits.
fn rebuild(p: &Prepared, path: Path, limits: &[AxisLimit]) -> Move {
    let length = path_length(&path);
    continuous_path(p, Move::new(path, length, p.feed, limits, p.mv.exact_stop, p.mv.tag))
}

/// The programmed block's corner rounding, compressor and ORISON limits on a move made from it.
fn continuous_path(p: &Prepared, mut mv: Move) -> Move {
    (mv.blend, mv.compress, mv.orison) = (p.mv.blend, p.mv.compress, p.mv.orison.clone());
    mv
}

/// The move of an equidistant element (or, with `contour_feed` false, a transition arc at
/// the programmed feed). Its axis-space start is the original start with the plane part
/// replaced, its end likewise; axes outside the plane move as programmed.
fn finish(p: &Prepared, elem: Elem, comp: &Compensation, limits: &[AxisLimit], contour_feed: bool) -> Move {
    finish_between(p, elem, p.mv.path.start, p.mv.path.end, comp, limits, contour_feed)
}

/// A transition arc after `p`, starting at `from` (its axes outside the plane stay there).
fn finish_transition(p: &Prepared, elem: Elem, from: AxisVec, comp: &Compensation, limits: &[AxisLimit]) -> Move {
    finish_between(p, elem, from, from, comp, limits, false)
}

fn finish_between(
    p: &Prepared,
    elem: Elem,
    from: AxisVec,
    to: AxisVec,
    comp: &Compensation,
    limits: &[AxisLimit],
    contour_feed: bool,
) -> Move {
    let (s, e) = (elem_start(&elem), elem_end(&elem));
    let start3 = place(&from, s, comp);
    let end3 = place(&to, e, comp);
    let (mut start3, mut end3) = (start3, end3);
    let (path, feed) = match elem {
        Elem::Line { s: ls, e: le } => {
            if let Some((rot, extra)) = comp.groove_wall {
                // The offset of a line is the same along it: the left normal times the offset.
                let len = dist(ls, le);
                let n = (-(le.1 - ls.1) / len, (le.0 - ls.0) / len);
                let along = comp.offset() * (n.0 * comp.u[rot] + n.1 * comp.v[rot]);
                start3[extra] += along;
                end3[extra] += along;
            }
            (Path::line(start3, end3), p.feed)
        }
        Elem::Arc { r, a0, sweep, .. } => {
            // CFC: the programmed feed acts on the contour; the centre path runs faster on
            // outer and slower on inner arcs, by the ratio of the radii.
            let feed = match (p.feed, contour_feed, element(&p.mv, comp)) {
                (Feed::Path(f), true, Some(Elem::Arc { r: r0, .. })) if r0 > 1e-9 => {
                    let ratio = r / r0;
                    match comp.arc_feed {
                        ArcFeed::Contour => Feed::Path(f * ratio),
                        ArcFeed::InnerOnly if ratio < 1.0 => Feed::Path(f * ratio),
                        _ => Feed::Path(f),
                    }
                }
                (f, _, _) => f,
            };
            let mut arc = Arc { u: comp.u, v: comp.v, radius: r, start_angle: a0, sweep };
            if let Some((rot, extra)) = comp.groove_wall {
                // The offset runs along the radius: a share k of the radial vector, where k is
                // the offset over the equidistant's radius (1 for a transition circle about a
                // contour corner).
                let r0 = match element(&p.mv, comp) {
                    Some(Elem::Arc { r: r0, .. }) if contour_feed => r0,
                    _ => 0.0,
                };
                let k = if r > 1e-12 { (r - r0) / r } else { 0.0 };
                let radial = |a: f64| r * (a.cos() * comp.u[rot] + a.sin() * comp.v[rot]);
                start3[extra] += k * radial(a0);
                end3[extra] += k * radial(a0 + sweep);
                arc.u[extra] += k * comp.u[rot];
                arc.v[extra] += k * comp.v[rot];
            }
            (Path { start: start3, end: end3, arc: Some(Box::new(arc)), ori: None, curve: None }, feed)
        }
    };
    let length = path_length(&path);
    continuous_path(p, Move::new(path, length, feed, limits, p.mv.exact_stop, p.mv.tag))
}

fn path_length(path: &Path) -> f64 {
    let chord: f64 = path.start.iter().zip(&path.end).map(|(a, b)| (b - a).powi(2)).sum::<f64>().sqrt();
    match &path.arc {
        None => chord,
        Some(arc) => {
            // Arc length in the plane plus the linear remainder (helix).
            let mut linear = 0.0;
            for k in 0..MAX_CHANNEL_AXES {
                if !arc.moves_axis(k) {
                    linear += (path.end[k] - path.start[k]).powi(2);
                }
            }
            ((arc.radius * arc.sweep).powi(2) + linear).sqrt()
        }
    }
}

/// The move's contour in plane coordinates; `None` without motion in the plane.
fn element(mv: &Move, comp: &Compensation) -> Option<Elem> {
    let s = to_plane(&mv.path.start, comp);
    let e = to_plane(&mv.path.end, comp);
    match &mv.path.arc {
        Some(arc) => {
            // The arc's own axes (a rounding arc has its own) read in the plane.
            let (ru, rv, orient) = arc_in_plane(arc, comp);
            let (cs, sn) = (arc.start_angle.cos(), arc.start_angle.sin());
            let a0 = (cs * ru.1 + sn * rv.1).atan2(cs * ru.0 + sn * rv.0);
            let c = (s.0 - arc.radius * a0.cos(), s.1 - arc.radius * a0.sin());
            Some(Elem::Arc { c, r: arc.radius, a0, sweep: arc.sweep * orient.signum() })
        }
        None if dist(s, e) > 1e-9 => Some(Elem::Line { s, e }),
        None => None,
    }
}

/// An arc's axes in plane coordinates and the sense of its plane against the working plane
/// (±1 when the arc lies in it).
fn arc_in_plane(arc: &Arc, comp: &Compensation) -> (P2, P2, f64) {
    let ru = (dot(&arc.u, &comp.u), dot(&arc.u, &comp.v));
    let rv = (dot(&arc.v, &comp.u), dot(&arc.v, &comp.v));
    (ru, rv, ru.0 * rv.1 - ru.1 * rv.0)
}

fn to_plane(p: &AxisVec, comp: &Compensation) -> P2 {
    (dot(p, &comp.u), dot(p, &comp.v))
}

/// `p` with its working-plane part replaced by the tool-centre point `q` moved to the
/// reference point (the theoretical tip of a turning tool).
pub(in crate::interp) fn place(p: &AxisVec, q: P2, comp: &Compensation) -> AxisVec {
    with_plane(p, (q.0 + comp.tip.0, q.1 + comp.tip.1), comp)
}

pub(in crate::interp) fn minus(a: P2, b: P2) -> P2 {
    (a.0 - b.0, a.1 - b.1)
}

/// A move at the tool's plane position keeps TRACYL's groove-wall share on the real Y axis
/// where the tool stands.
fn hold_groove_wall(mut end: AxisVec, from: &AxisVec, comp: &Compensation) -> AxisVec {
    if let Some((_, extra)) = comp.groove_wall {
        end[extra] = from[extra];
    }
    end
}

/// `p` with its working-plane part replaced by `q`.
fn with_plane(p: &AxisVec, q: P2, comp: &Compensation) -> AxisVec {
    let (x, y) = to_plane(p, comp);
    std::array::from_fn(|k| p[k] + (q.0 - x) * comp.u[k] + (q.1 - y) * comp.v[k])
}

fn dot(a: &AxisVec, b: &AxisVec) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub(in crate::interp) fn dist(a: P2, b: P2) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

pub(in crate::interp) fn elem_start(e: &Elem) -> P2 {
    match *e {
        Elem::Line { s, .. } => s,
        Elem::Arc { c, r, a0, .. } => (c.0 + r * a0.cos(), c.1 + r * a0.sin()),
    }
}

pub(in crate::interp) fn elem_end(e: &Elem) -> P2 {
    match *e {
        Elem::Line { e, .. } => e,
        Elem::Arc { c, r, a0, sweep } => (c.0 + r * (a0 + sweep).cos(), c.1 + r * (a0 + sweep).sin()),
    }
}

/// Unit tangent at the start (`at_end` false) or end of an element.
pub(in crate::interp) fn tangent(e: &Elem, at_end: bool) -> P2 {
    match *e {
        Elem::Line { s, e } => {
            let l = dist(s, e);
            ((e.0 - s.0) / l, (e.1 - s.1) / l)
        }
        Elem::Arc { a0, sweep, .. } => {
            let a = if at_end { a0 + sweep } else { a0 };
            let sgn = sweep.signum();
            (-sgn * a.sin(), sgn * a.cos())
        }
    }
}

/// Left normal of a tangent.
pub(in crate::interp) fn left(t: P2) -> P2 {
    (-t.1, t.0)
}

/// Start point of the equidistant at offset `d` (perpendicular at the contour start).
pub(in crate::interp) fn offset_start(e: &Elem, d: f64) -> P2 {
    let p = elem_start(e);
    let n = left(tangent(e, false));
    (p.0 + d * n.0, p.1 + d * n.1)
}

/// End point of the equidistant at offset `d` (perpendicular at the contour end).
fn offset_end(e: &Elem, d: f64) -> P2 {
    let p = elem_end(e);
    let n = left(tangent(e, true));
    (p.0 + d * n.0, p.1 + d * n.1)
}

/// Whether the piece of an element's equidistant from `start` to `end` (both on it) runs in
/// the element's direction: false when the corners at its ends have eaten it up and more (the
/// element is shorter than the tool needs there).
pub(in crate::interp) fn forward(e: &Elem, start: P2, end: P2) -> bool {
    match *e {
        Elem::Line { s, e } => (end.0 - start.0) * (e.0 - s.0) + (end.1 - start.1) * (e.1 - s.1) >= -1e-9,
        Elem::Arc { c, a0, sweep, .. } => {
            // The shifts of the start and the end against the contour's, in the sense of travel.
            let sg = sweep.signum();
            let angle = |p: P2| (p.1 - c.1).atan2(p.0 - c.0);
            let wrap = |x: f64| {
                let y = x.rem_euclid(std::f64::consts::TAU);
                if y > std::f64::consts::PI { y - std::f64::consts::TAU } else { y }
            };
            let ds = wrap((angle(start) - a0) * sg);
            let de = wrap((angle(end) - (a0 + sweep)) * sg);
            sweep.abs() - ds + de >= -1e-9
        }
    }
}

/// The transition circle `arc` cut by the equidistant of `next` at offset `d`: the arc up to
/// the first crossing (None where it has shrunk to nothing) and the crossing point. Used when
/// the element after an outer corner is too short: the tool leaves the circle where it meets
/// the equidistant of the element after.
fn cut_transition(arc: &Elem, next: &Elem, d: f64) -> Option<(Option<Elem>, P2)> {
    let Elem::Arc { c, r, a0, sweep } = *arc else { return None };
    let eq = offset_elem(next, d, None, None, 0).ok()?;
    let hits = match eq {
        Elem::Line { s, e } => line_circle(s, e, c, r),
        Elem::Arc { c: c2, r: r2, .. } => circle_circle(c, r, c2, r2),
    };
    let sg = sweep.signum();
    let (w, x) = hits
        .into_iter()
        .map(|x| (((x.1 - c.1).atan2(x.0 - c.0) - a0) * sg, x))
        .map(|(w, x)| (w.rem_euclid(std::f64::consts::TAU), x))
        .filter(|(w, x)| {
            // On the arc, and not beyond the end of the next equidistant.
            *w <= sweep.abs() + 1e-9
                && match eq {
                    Elem::Line { s, e } => (x.0 - e.0) * (s.0 - e.0) + (x.1 - e.1) * (s.1 - e.1) >= -1e-9,
                    Elem::Arc { .. } => true,
                }
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    Some(((w > 1e-12).then_some(Elem::Arc { c, r, a0, sweep: sg * w }), x))
}

/// The element offset by `d`, with its start and end optionally moved to given points on the
/// equidistant (corners decide them).
pub(in crate::interp) fn offset_elem(
    e: &Elem,
    d: f64,
    start: Option<P2>,
    end: Option<P2>,
    line: u32,
) -> Result<Elem, Alarm> {
    Ok(match *e {
        Elem::Line { s, e } => {
            let n = left(tangent(&Elem::Line { s, e }, false));
            let shift = |p: P2| (p.0 + d * n.0, p.1 + d * n.1);
            Elem::Line { s: start.unwrap_or(shift(s)), e: end.unwrap_or(shift(e)) }
        }
        Elem::Arc { c, r, a0, sweep } => {
            let r2 = r - d * sweep.signum();
            if r2 <= 1e-9 {
                return Err(Alarm::collision(line, "the tool radius is larger than the radius of an inner arc"));
            }
            let a_start = start.map_or(a0, |p| (p.1 - c.1).atan2(p.0 - c.0));
            let a_end = end.map_or(a0 + sweep, |p| (p.1 - c.1).atan2(p.0 - c.0));
            let sw = if start.is_none() && end.is_none() {
                sweep
            } else {
                // The trimmed sweep: same direction, the number of turns nearest the original.
                let base = a_end - a_start;
                (-3..=3)
                    .map(|k| base + f64::from(k) * std::f64::consts::TAU)
                    .filter(|w| w * sweep >= 0.0)
                    .min_by(|x, y| (x - sweep).abs().total_cmp(&(y - sweep).abs()))
                    .unwrap_or(base)
            };
            Elem::Arc { c, r: r2, a0: a_start, sweep: sw }
        }
    })
}

/// The corner between two elements (already in contour coordinates) at offset `d`: the end of
/// the first equidistant, a transition arc if one is needed, and the start of the second.
/// `Ok(None)`: an inner corner whose intersection lies beyond the end of the second
/// equidistant; the second element is too short for the tool and may be bridged by the
/// bottleneck look-ahead.
fn corner(a: &Elem, b: &Elem, d: f64, comp: &Compensation, line: u32) -> Result<Option<Meet>, Alarm> {
    let mode = comp.corners;
    let p = elem_end(a);
    let (ta, tb) = (tangent(a, true), tangent(b, false));
    let (na, nb) = (left(ta), left(tb));
    let q1 = (p.0 + d * na.0, p.1 + d * na.1);
    let q2 = (p.0 + d * nb.0, p.1 + d * nb.1);
    if dist(q1, q2) < 1e-9 {
        return Ok(Some((q1, None, q1)));
    }
    let cross = ta.0 * tb.1 - ta.1 * tb.0;
    let outer = cross * d < 0.0;
    let oa = offset_elem(a, d, None, None, line)?;
    let ob = offset_elem(b, d, None, None, line)?;
    if outer && let Some(x) = crossing(&oa, &ob, b) {
        // An outer corner whose equidistants cross before it (an arc curving back towards
        // the other element): going round the corner would cut into the other element, so
        // the tool stops at the crossing as at an inner corner.
        clear_at(a, b, d, x, line)?;
        return Ok(Some((x, None, x)));
    }
    if outer {
        // G451: the intersection of the equidistants nearest the corner (lines and arcs), as
        // long as the change of direction stays below MD20210 and the equidistants meet ahead
        // of the first one's end and behind the second one's start.
        let turn = cross.abs().atan2(ta.0 * tb.0 + ta.1 * tb.1);
        if mode == CornerMode::Intersection
            && turn < comp.corner_limit
            && let Some(x) = intersection(&oa, &ob, p)
            && (x.0 - q1.0) * ta.0 + (x.1 - q1.1) * ta.1 >= -1e-9
            && (x.0 - q2.0) * tb.0 + (x.1 - q2.1) * tb.1 <= 1e-9
        {
            return Ok(Some((x, None, x)));
        }
        if let (Elem::Line { s: s1, e: e1 }, Elem::Line { s: s2, e: e2 }) = (oa, ob)
            && comp.disc > 0.0
            && let Some(x) = line_line(s1, e1, s2, e2)
        {
            return Ok(Some(disc::disc_corner(q1, q2, x, p, comp.disc)));
        }
        // Transition circle about the contour corner, turning like the corner.
        let a0 = (q1.1 - p.1).atan2(q1.0 - p.0);
        let a1 = (q2.1 - p.1).atan2(q2.0 - p.0);
        let mut sweep = a1 - a0;
        let tau = std::f64::consts::TAU;
        if cross > 0.0 {
            while sweep <= 0.0 {
                sweep += tau;
            }
        } else {
            while sweep >= 0.0 {
                sweep -= tau;
            }
        }
        return Ok(Some((q1, Some(Elem::Arc { c: p, r: d.abs(), a0, sweep }), q2)));
    }
    // Inner corner: cut both equidistants where they first cross along the first one (with
    // arcs they may cross twice: beyond the first crossing the tool would be nearer to the
    // second element than the radius), else at their intersection nearest the corner.
    let x = crossing(&oa, &ob, b)
        .or_else(|| intersection(&oa, &ob, p))
        .ok_or_else(|| Alarm::collision(line, "the equidistants of an inner corner do not meet"))?;
    // The cut must not lie beyond the second equidistant's end (whether the first one is long
    // enough is the caller's question: its start may have moved).
    let beyond_b = match ob {
        Elem::Line { s, e } => ((x.0 - e.0) * (s.0 - e.0) + (x.1 - e.1) * (s.1 - e.1)) < -1e-9,
        Elem::Arc { .. } => false,
    };
    if beyond_b {
        return Ok(None);
    }
    clear_at(a, b, d, x, line)?;
    Ok(Some((x, None, x)))
}

/// Alarm 10751 where a corner cut at `x` would still bring the tool nearer than the radius
/// to one of the two elements: the first equidistant up to `x` to the second contour element,
/// or the second equidistant from `x` to the first (equidistants of arcs that cross twice
/// with the tool too large for the pocket between them).
fn clear_at(a: &Elem, b: &Elem, d: f64, x: P2, line: u32) -> Result<(), Alarm> {
    let r = d.abs() - 1e-7;
    let clear = |piece: Result<Elem, Alarm>, other: &Elem| {
        piece.is_ok_and(|e| (0..=16).all(|k| contour_distance(point_at(&e, f64::from(k) / 16.0), other) >= r))
    };
    let before = offset_elem(a, d, None, Some(x), line);
    let after = offset_elem(b, d, Some(x), None, line);
    let reversed =
        |piece: &Result<Elem, Alarm>, e: &Elem| piece.as_ref().is_ok_and(|p| !forward(e, elem_start(p), elem_end(p)));
    if reversed(&before, a) || reversed(&after, b) || (clear(before, b) && clear(after, a)) {
        // A reversed piece is the look-ahead's business (the element is omitted).
        return Ok(());
    }
    Err(bottleneck(line))
}

/// The point the share `t` (0..1) along an element.
fn point_at(e: &Elem, t: f64) -> P2 {
    match *e {
        Elem::Line { s, e } => (s.0 + t * (e.0 - s.0), s.1 + t * (e.1 - s.1)),
        Elem::Arc { c, r, a0, sweep } => (c.0 + r * (a0 + t * sweep).cos(), c.1 + r * (a0 + t * sweep).sin()),
    }
}

/// Distance of `x` from a contour element (segment or arc with its end points).
fn contour_distance(x: P2, e: &Elem) -> f64 {
    let ends = dist(x, elem_start(e)).min(dist(x, elem_end(e)));
    match *e {
        Elem::Line { s, e } => {
            let t = share(&Elem::Line { s, e }, x);
            if (0.0..=1.0).contains(&t) { dist(x, point_at(&Elem::Line { s, e }, t)) } else { ends }
        }
        Elem::Arc { c, r, .. } => {
            let t = share(e, x);
            if (0.0..=1.0).contains(&t) { (dist(x, c) - r).abs().min(ends) } else { ends }
        }
    }
}

/// Where the equidistants `a` and `b` cross before the end of `a` and after the start of `b`
/// (the first along `a`); None when they meet only on their extensions.
fn crossing(a: &Elem, b: &Elem, b_contour: &Elem) -> Option<P2> {
    let points: Vec<P2> = match (*a, *b) {
        (Elem::Line { .. }, Elem::Line { .. }) => return None,
        (Elem::Line { s, e }, Elem::Arc { c, r, .. }) | (Elem::Arc { c, r, .. }, Elem::Line { s, e }) => {
            line_circle(s, e, c, r)
        }
        (Elem::Arc { c: c1, r: r1, .. }, Elem::Arc { c: c2, r: r2, .. }) => circle_circle(c1, r1, c2, r2),
    };
    points
        .into_iter()
        .filter(|x| {
            let (ta, tb) = (share(a, *x), share(b, *x));
            ta < 1.0 - 1e-6 && tb > 1e-6 && tb <= 1.0 + 1e-9 && enters(a, b, b_contour, *x)
        })
        // The first crossing along `a`: beyond it the tool would be nearer to `b` than the
        // radius. One behind the tool's start on `a` makes `a` too short (the caller's check).
        .min_by(|x, y| share(a, *x).total_cmp(&share(a, *y)))
}

/// Whether `a` (an equidistant) passes `x` into the band between `b`'s equidistant and its
/// contour `b_contour`, where the tool would be nearer to that contour than the radius.
fn enters(a: &Elem, b: &Elem, b_contour: &Elem, x: P2) -> bool {
    let dir = match *a {
        Elem::Line { s, e } => (e.0 - s.0, e.1 - s.1),
        Elem::Arc { c, sweep, .. } => {
            let sg = sweep.signum();
            (-sg * (x.1 - c.1), sg * (x.0 - c.0))
        }
    };
    let band = match (*b, *b_contour) {
        (Elem::Line { s, .. }, Elem::Line { s: cs, .. }) => (cs.0 - s.0, cs.1 - s.1),
        (Elem::Arc { c, r, .. }, Elem::Arc { r: r0, .. }) => {
            let out = (x.0 - c.0, x.1 - c.1);
            if r > r0 { (-out.0, -out.1) } else { out }
        }
        _ => return false,
    };
    dir.0 * band.0 + dir.1 * band.1 > 1e-12
}

/// How far along an element (0 at its start, 1 at its end) the point `x` on it lies.
fn share(e: &Elem, x: P2) -> f64 {
    match *e {
        Elem::Line { s, e } => {
            let d = (e.0 - s.0, e.1 - s.1);
            ((x.0 - s.0) * d.0 + (x.1 - s.1) * d.1) / (d.0 * d.0 + d.1 * d.1)
        }
        Elem::Arc { c, a0, sweep, .. } => {
            let tau = std::f64::consts::TAU;
            let w = (((x.1 - c.1).atan2(x.0 - c.0) - a0) * sweep.signum()).rem_euclid(tau);
            // Angles in the gap after the end, past its middle, lie behind the start.
            let w = if w > sweep.abs() + (tau - sweep.abs()) / 2.0 { w - tau } else { w };
            w / sweep.abs().max(1e-12)
        }
    }
}

/// The end of the first equidistant, the transition (if any) and the start of the next.
pub(in crate::interp) type Meet = (P2, Option<Elem>, P2);

pub(in crate::interp) fn bottleneck(line: u32) -> Alarm {
    Alarm::collision(line, "the tool does not fit between the contour elements (bottleneck)")
}

/// Intersection of two infinite lines through (s1, e1) and (s2, e2).
pub(in crate::interp) fn line_line(s1: P2, e1: P2, s2: P2, e2: P2) -> Option<P2> {
    let (d1, d2) = ((e1.0 - s1.0, e1.1 - s1.1), (e2.0 - s2.0, e2.1 - s2.1));
    let den = d1.0 * d2.1 - d1.1 * d2.0;
    if den.abs() < 1e-12 {
        return None;
    }
    let t = ((s2.0 - s1.0) * d2.1 - (s2.1 - s1.1) * d2.0) / den;
    Some((s1.0 + t * d1.0, s1.1 + t * d1.1))
}

/// Intersection of two offset elements nearest `near`.
pub(in crate::interp) fn intersection(a: &Elem, b: &Elem, near: P2) -> Option<P2> {
    let points: Vec<P2> = match (*a, *b) {
        (Elem::Line { s: s1, e: e1 }, Elem::Line { s: s2, e: e2 }) => line_line(s1, e1, s2, e2).into_iter().collect(),
        (Elem::Line { s, e }, Elem::Arc { c, r, .. }) | (Elem::Arc { c, r, .. }, Elem::Line { s, e }) => {
            line_circle(s, e, c, r)
        }
        (Elem::Arc { c: c1, r: r1, .. }, Elem::Arc { c: c2, r: r2, .. }) => circle_circle(c1, r1, c2, r2),
    };
    points.into_iter().min_by(|p, q| dist(*p, near).total_cmp(&dist(*q, near)))
}

pub(in crate::interp) fn line_circle(s: P2, e: P2, c: P2, r: f64) -> Vec<P2> {
    let d = (e.0 - s.0, e.1 - s.1);
    let f = (s.0 - c.0, s.1 - c.1);
    let (a, b, cc) = (d.0 * d.0 + d.1 * d.1, 2.0 * (f.0 * d.0 + f.1 * d.1), f.0 * f.0 + f.1 * f.1 - r * r);
    let mut disc = b * b - 4.0 * a * cc;
    if disc < 0.0 && disc > -1e-12 * (b * b).max(a) {
        // A tangent line touches the circle (rounding must not lose the point).
        disc = 0.0;
    }
    if disc < 0.0 || a < 1e-18 {
        return Vec::new();
    }
    let sq = disc.sqrt();
    [(-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a)].iter().map(|t| (s.0 + t * d.0, s.1 + t * d.1)).collect()
}

pub(in crate::interp) fn circle_circle(c1: P2, r1: f64, c2: P2, r2: f64) -> Vec<P2> {
    let d = dist(c1, c2);
    if d < 1e-12 || d > r1 + r2 || d < (r1 - r2).abs() {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let m = (c1.0 + a * (c2.0 - c1.0) / d, c1.1 + a * (c2.1 - c1.1) / d);
    let o = (-(c2.1 - c1.1) / d * h, (c2.0 - c1.0) / d * h);
    vec![(m.0 + o.0, m.1 + o.1), (m.0 - o.0, m.1 - o.1)]
}
