//! The fast lane of block preparation: plain motion lines (`X.. Y.. Z..`, `G1 X.. F..`,
//! `G3 X.. Y.. I.. J..`), 95 % of generated toolpaths, prepared straight from the line's bytes
//! without the syntax tree, `modal::collect` and the twenty stages a general block passes.
//!
//! The lane gives exactly the items and the interpreter state the general path gives: it
//! computes the move with the same building blocks (`Frame::unapply/apply`, [`block_end`],
//! [`shape_path`], `arc::from_center`, `check_software_limits`, `path_feed`, `Move::new`,
//! `trc::Compensator::passed`, the idle case of `push`) and falls back to the general path,
//! which is always right, for anything it does not take, including every error (the general
//! path then raises the alarm).
//! For a frame that only translates (G54 and TRANS, the usual case) the lane maps start and
//! end on the channel's axes itself ([`translated_current`], [`translated_end`]: the same
//! values bit for bit, zero coordinates whose sign the frame's sums could flip go to
//! `unapply`/`block_end`), and it builds the move in its place in the output.
//! In debug builds every block the lane prepares is prepared once more by the general path on
//! a copy of the interpreter, and items and state must be equal ([`cross_check`]).
//!
//! A line is plain when [`crate::lang::plain_words`] (the scan the syntax check uses) accepts it
//! and it holds only: a leading `N` block number, G0..G3 and G90/G91 (one per group), the
//! geometry axes by their single-letter names (linear axes), I/J/K (incremental centre) and F;
//! each address once (no user variable can shadow one: a name begins with two letters).
//!
//! The stages of the general path and why the lane may skip them, in the order they run:
//! - `prepare_next`: `corner_request` cleared (the lane clears it); held-move check for the
//!   main-run wait (plain lines never wait); `trc.begin_block` (called).
//! - `step_program`: `refresh_derived_chain_data` (only with a transformation: refused);
//!   `flow.read` (the lane reads the same line and sets `next`/`current` as it does; empty
//!   lines, which it skips, fall back; a comment-only line is a block without words); syntax errors (a plain line has none); `reads_main_run`
//!   and effect calls (no variables, no functions); `check_unbound` (refused while a call's
//!   arguments are unbound); alarm/end items afterwards (the lane makes none).
//! - `prepare_block`: `modal::collect` (replaced by the scan; data writes, NEWCONF, corners,
//!   messages, stops, jumps, calls need words the lane refuses); `transform::selection::selection` and
//!   `apply_transformation` (no keyword; no active transformation, refused); `modal.apply`
//!   (only motion and G90/G91 change, the lane sets them); work offset, S, SETMS, T/D, frame
//!   instructions and frame writes, `holder_block` (no such words); `refresh_offsets` (called,
//!   so tool, frame and G codes are exactly as the general path leaves them);
//!   `absorb_tool_into_transformation` (no transformation and no transformation offsets:
//!   refused otherwise); `online_tool_offset` (no TOFF words); spindle items, SPOS, G4, poles
//!   (no such words); the `Offsets` item of a block without motion (the same test).
//! - `motion`: frame suppression (no G53/G153/SUPA); axis targets (linear axes, G90/G91 only,
//!   no AC/IC/DC/ACP/ACN); polar coordinates (no AP/RP); circles only from I/J/K without
//!   CR/AR/TURN; `oblique_plunge` (no G05/G07); `orientation_block` and `tool_rotation` (no
//!   orientation words and no orientation transformation, and ORIROTC refused: both give no
//!   orientation path and no THETA, so `last_change`/`upper` become `None` as they do there);
//!   G9 (not taken).
//! - after `motion`: `request_point_to_point` (no transformation); `compensation` (G40 only:
//!   refused with G41/G42 selected); `trc.push` without compensation (the lane requires the
//!   compensator idle, where `push` only hands the move on: `Compensator::passed` notes the move the lane pushed); `trc.end_block`, `flush` (nothing
//!   held); `shape_corners` (nothing held, no RND/CHF/CHR); `transform_moves` (none active).

use super::flow::Pos;
use super::frames::frame::{Frame, GeoAxes};
use super::modal::MotionMode;
use super::orientation::words::RotReference;
use super::{
    AxisLimit, Interpreter, Item, Move, Prep, arc_center, arc_turn, block_end, check_software_limits, contour::arc,
    feed_length, shape_path,
};
use crate::lang::plain_words;
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{AxisLimits, AxisVec, Path};

/// The words of a plain motion line, by meaning.
#[derive(Debug, Default)]
struct PlainBlock {
    motion: Option<MotionMode>,
    absolute: Option<bool>,
    /// Value of each geometry axis word (program units), by geometry axis (0 = 1st).
    axes: [Option<f64>; 3],
    /// I, J, K (program units), by geometry axis.
    ijk: [Option<f64>; 3],
    feed: Option<f64>,
    /// Any word at all.
    words: bool,
}

/// What the lane keeps between its blocks for one machine configuration, so that a plain
/// block reads nothing twice from it. What it knows of the offsets goes stale whenever the
/// general path prepares a block: every input of the block's offsets (frames, work offset,
/// tool, plane, toolholder) changes only through general blocks. The whole memo is forgotten
/// when the interpreter is reset, begun, restored or synchronised, and after a general block
/// that wrote data: the configuration changes only through such data writes (the channel
/// applies them before the next block) and at a reset. So a statement-heavy program, where
/// general and lane blocks alternate, does not rebuild the limits and the letter table per block.
#[derive(Clone, Default)]
pub(super) struct LaneMemo(Option<Box<Memo>>);

#[derive(Clone)]
struct Memo {
    /// The configuration the memo belongs to (its address; 0: none, the memo is cleared).
    cfg: usize,
    /// `AxisLimit::for_channel(cfg)`.
    limits: AxisLimits,
    /// The geometry axis (0 = 1st) each letter A..Z addresses, see [`geometry_axis`].
    letters: [Option<usize>; 26],
    /// `refresh_offsets` ran for this configuration and nothing but lane blocks ran since:
    /// the tool, the frame and the G codes of the offsets are what it would make them.
    offsets_fresh: bool,
    /// The offsets' frame only translates (set with `offsets_fresh`), see [`translated_end`].
    translation_only: bool,
}

/// The memo is a cache: it is no state of block preparation (the debug cross-check compares
/// the lane's state with the general path's, which keeps no memo).
impl std::fmt::Debug for LaneMemo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("LaneMemo")
    }
}

impl LaneMemo {
    /// The memo `for_config` made for the block being prepared.
    fn for_config_ref(&self) -> &Memo {
        self.0.as_ref().expect("made at the start of the block")
    }

    /// Forgets everything (see the type's doc for when); the allocation stays for the next.
    pub(super) fn forget(&mut self) {
        if let Some(m) = self.0.as_mut() {
            m.cfg = 0;
        }
    }

    /// Forgets what the memo knows of the offsets (a general block may have changed them).
    pub(super) fn stale_offsets(&mut self) {
        if let Some(m) = self.0.as_mut() {
            m.offsets_fresh = false;
        }
    }

    /// The memo for `cfg`, made afresh if it belonged to another configuration or none.
    fn for_config(&mut self, cfg: &MachineConfig) -> &mut Memo {
        let id = std::ptr::from_ref(cfg) as usize;
        if self.0.as_ref().is_none_or(|m| m.cfg != id) {
            let memo = Memo {
                cfg: id,
                limits: AxisLimit::for_channel(cfg),
                letters: std::array::from_fn(|i| geometry_axis(cfg, b'A' + i as u8)),
                offsets_fresh: false,
                translation_only: false,
            };
            match self.0.as_mut() {
                Some(m) => **m = memo,
                None => self.0 = Some(Box::new(memo)),
            }
        }
        self.0.as_mut().expect("made above")
    }
}

/// Reads `text` (one line without its line end) as a plain motion line; `None` for anything
/// else. `letters`: the geometry axis each letter addresses.
fn scan(text: &str, letters: &[Option<usize>; 26]) -> Option<PlainBlock> {
    let mut block = PlainBlock::default();
    let mut seen = 0u32;
    let plain = plain_words(text, |letter, end, value| {
        let first = !block.words;
        block.words = true;
        if letter == b'N' {
            // A block number only at the start and standing alone (`N10X5` is the address N).
            return first && matches!(text.as_bytes().get(end), None | Some(b' ' | b'\t' | b';'));
        }
        if letter == b'G' {
            // Whole numbers only (the scan's digits), one function per group.
            return match value as u32 {
                0..=3 if block.motion.is_none() => {
                    block.motion =
                        Some([MotionMode::Rapid, MotionMode::Linear, MotionMode::Cw, MotionMode::Ccw][value as usize]);
                    true
                }
                90 | 91 if block.absolute.is_none() => {
                    block.absolute = Some(value == 90.0);
                    true
                }
                _ => false,
            };
        }
        let bit = 1u32 << (letter - b'A');
        if seen & bit != 0 {
            return false;
        }
        seen |= bit;
        match letter {
            b'F' => block.feed = Some(value),
            b'I' | b'J' | b'K' => block.ijk[usize::from(letter - b'I')] = Some(value),
            _ => {
                let Some(g) = letters[usize::from(letter - b'A')] else { return false };
                block.axes[g] = Some(value);
            }
        }
        true
    });
    // A line of blanks is no block (`read_block` skips it); one with a comment is a block
    // without words, which the lane prepares like a plain line without motion.
    (plain && (block.words || text.contains(';'))).then_some(block)
}

/// The geometry axis (0 = 1st) a single-letter name addresses, if it is a linear axis the
/// lane can move (geometry names come first, as in `MachineConfig::program_axis`).
fn geometry_axis(cfg: &MachineConfig, letter: u8) -> Option<usize> {
    let g = cfg.geo_names.iter().position(|n| n.len() == 1 && n.as_bytes()[0].eq_ignore_ascii_case(&letter))?;
    let k = cfg.geo_axes[g]?;
    let ax = cfg.axis(k);
    (!ax.rotary && ax.modulo.is_none() && ax.spindle.is_none()).then_some(g)
}

impl Interpreter {
    /// Turns the fast lane for plain motion lines on or off (on by default). Off, every block
    /// takes the general path: for comparisons and measurements.
    pub fn set_fast_lane(&mut self, on: bool) {
        self.fast_lane = on;
    }

    /// True when the state leaves nothing for the stages the lane skips (see the module doc).
    fn lane_open(&self) -> bool {
        self.flow.as_ref().is_some_and(|f| f.sections.is_empty())
            && self.call_state.mcall.is_none()
            && self.held.is_none()
            && self.pending_angle.is_none()
            && self.modal.rndm.is_none()
            && self.modal.circle_form == super::modal::CircleForm::Standard
            && self.modal.feed_group.is_none()
            && !self.modal.rtliof
            && matches!(self.work_area, Some(None))
            && self.modal.spline.kind.is_none()
            && self.modal.trc.is_none()
            && self.trc.idle()
            && self.active_data_set().is_none()
            && self.offsets.trafo.is_none()
            && self.before_change.is_none()
            && self.modal.ori.rotation != RotReference::PathTangent
            && !self.modal.dynamics.shapes_moves()
            && !self.call_unbound()
            && self.spindles_plain()
            && !self.sync_wait_pending()
            && self.positioning_axes.posa_open == 0
    }

    /// Prepares the next block if it is a plain motion line and the state is simple; `None`
    /// (and nothing changed that the general path would not change the same way) otherwise.
    pub(super) fn prepare_plain(&mut self, cfg: &MachineConfig, out: &mut Vec<Item>) -> Option<Prep> {
        if self.work_area.is_none() {
            // Read once per change of the stored data, as `prepare_next` does.
            self.work_area = Some(super::path_control::work_area::WorkArea::of(&self.stored, cfg));
        }
        if !self.lane_open() {
            return None;
        }
        let flow = self.flow.as_ref()?;
        let at = flow.next;
        let rest = flow.text.get(at.offset..).filter(|r| !r.is_empty())?;
        // A byte loop: lines are short, where `find` pays for a vectorised search's set-up.
        let end = rest.bytes().position(|b| b == b'\n').unwrap_or(rest.len());
        let raw = &rest[..end];
        let memo = self.lane_memo.for_config(cfg);
        let offsets_fresh = memo.offsets_fresh;
        let block = scan(raw.strip_suffix('\r').unwrap_or(raw), &memo.letters)?;
        let next = Pos { offset: at.offset + raw.len() + 1, line: at.line + 1 };
        let line = at.line;

        // From here on every step is one the general path takes the same way, and repeats
        // harmlessly if the lane falls back (only on an error, which the general path raises).
        self.corner_request = None;
        let offsets_before = self.offsets_mark();
        let g_codes = (self.modal.motion, self.modal.absolute);
        if let Some(m) = block.motion {
            self.modal.motion = m;
        }
        if let Some(a) = block.absolute {
            self.modal.absolute = a;
        }
        if let Some(f) = block.feed {
            self.modal.feed = Some(f);
        }
        if !offsets_fresh {
            self.refresh_offsets(cfg);
            let translation_only = only_translates(&self.offsets.frame);
            let memo = self.lane_memo.for_config(cfg);
            memo.offsets_fresh = true;
            memo.translation_only = translation_only;
        } else if g_codes != (self.modal.motion, self.modal.absolute) {
            // Tool and frame are as the last refresh left them; only the G codes changed.
            self.refresh_gcodes();
        }
        let circle_mode = matches!(self.modal.motion, MotionMode::Cw | MotionMode::Ccw);
        let moves = block.axes.iter().any(Option::is_some) || (circle_mode && block.ijk.iter().any(Option::is_some));
        if moves && self.before_change.is_some() {
            // The first move after a change of offsets (SD42440/SD42442): the general path.
            return None;
        }
        if !moves {
            self.commit_position(at, next, out);
            if self.offsets_mark() != offsets_before {
                out.push(Item::Offsets { line, offsets: self.shared_offsets() });
            }
            return Some(Prep::Prepared);
        }
        self.plain_move(&block, cfg, (at, next), out)?;
        Some(Prep::Prepared)
    }

    /// The read position after the line `at` (ending before `next`), and the compensator's
    /// start of the block, as `step_program` and `prepare_next` set them.
    fn commit_position(&mut self, at: Pos, next: Pos, out: &[Item]) {
        self.read_at = at;
        if let Some(flow) = self.flow.as_mut() {
            flow.current = at;
            flow.next = next;
        }
        self.trc.begin_block(out);
    }

    /// Prepares the move of a plain block (as `motion` computes it for such a block) straight
    /// into `out`, with the bookkeeping of `step_program` and `trc.push` for the line from
    /// `at` to `next`; `None` (and nothing changed but the published offsets, which the general
    /// path publishes the same) where `motion` would raise an alarm.
    fn plain_move(
        &mut self,
        block: &PlainBlock,
        cfg: &MachineConfig,
        (at, next): (Pos, Pos),
        out: &mut Vec<Item>,
    ) -> Option<()> {
        let n = cfg.channel_axes.len();
        let geo = &cfg.geo_axes;
        let line = at.line;
        let offsets = self.shared_offsets();
        let memo = self.lane_memo.for_config_ref();
        let (start, tool, frame) = (&self.pos, &self.offsets.tool, &self.offsets.frame);
        let mut current = [0.0; MAX_CHANNEL_AXES];
        let translated = memo.translation_only && translated_current(frame, geo, n, start, tool, &mut current);
        if !translated {
            let mut basic = *start;
            for k in 0..n {
                basic[k] -= tool[k];
            }
            current = frame.unapply(geo, &basic)?;
        }
        let mut target = current;
        let mut programmed = [false; MAX_CHANNEL_AXES];
        let f = self.modal.length_factor();
        for (value, k) in block.axes.iter().zip(geo) {
            if let (Some(v), Some(k)) = (value, *k) {
                let v = v * f;
                target[k] = if self.modal.absolute { v } else { current[k] + v };
                programmed[k] = true;
            }
        }
        let planes = self.modal.plane.axes();
        let (pa, po, _) = planes;
        let circle = match self.modal.motion {
            MotionMode::Cw | MotionMode::Ccw => {
                let (Some(ka), Some(ko)) = (geo[pa], geo[po]) else { return None };
                if block.ijk[pa].is_none() && block.ijk[po].is_none() {
                    return None;
                }
                let s = (current[ka], current[ko]);
                let e = (target[ka], target[ko]);
                let incremental = |g: usize| (block.ijk[g].unwrap_or(0.0), false);
                let center = arc_center(s, incremental(pa), incremental(po), f);
                let c = arc::from_center(s, e, center, arc_turn(self.modal.motion)).ok()?;
                Some(arc::with_turns(c, 0))
            }
            _ => None,
        };
        if let (Some(ka), Some(ko)) = (geo[pa], geo[po]) {
            self.last_move.record((current[ka], current[ko]), (target[ka], target[ko]), circle.as_ref());
        }
        let feed = self.path_feed(line).ok()?;
        // The move is made in its place in `out` (see `Move::unlimited`) and leaves again if
        // the software limits refuse it.
        let mark = out.len();
        let rest = Path::line(*start, *start);
        out.push(Item::Move { mv: Move::unlimited(rest, self.modal.exact_stop, line), line, offsets });
        let Some(Item::Move { mv, .. }) = out.last_mut() else { unreachable!("pushed just above") };
        let path = &mut mv.path;
        if !(translated && translated_end(frame, geo, n, tool, &target, &programmed, &mut path.end)) {
            path.end = block_end(frame, geo, n, start, tool, &target, &mut programmed);
        }
        let length = shape_path(path, frame, geo, planes, &current, &target, circle.as_ref());
        let length = feed_length(path, length, n);
        if check_software_limits(cfg, path, line).is_err() {
            out.pop();
            return None;
        }
        mv.set_limits(length, feed, &self.lane_memo.for_config_ref().limits);
        if !mv.exact_stop {
            mv.blend = self.modal.path.blend(false, matches!(feed, crate::motion::Feed::Rapid), cfg);
            mv.compress = self.modal.path.compress(cfg);
        }
        // The axes past the channel's keep their start (block_end leaves them).
        self.pos[..n].copy_from_slice(&mv.path.end[..n]);

        self.commit_position(at, next, &out[..mark]);
        self.modal.ori.last_change = None;
        self.modal.ori.upper = None;
        self.trc.passed(out);
        Some(())
    }
}

/// True when `frame` only translates: no rotation, scale or mirror on any axis. Its
/// `unapply`/`apply` then subtract/add the translation, which [`translated_current`] and
/// [`translated_end`] do for the configured axes only.
fn only_translates(frame: &Frame) -> bool {
    frame.linear_is_identity() && frame.factor.iter().all(|&f| f == 1.0)
}

/// `frame.unapply(start − tool)` on the first `n` axes for a frame that [`only_translates`]
/// (the others are not read for a plain block), into `current`. Bit for bit: `unapply`
/// divides by the factor 1 and sums the identity row times the point, where adding the zero
/// terms leaves a non-zero coordinate exact; a zero geometry coordinate (whose sign the sum
/// may flip) gives false, and the caller takes `unapply` itself.
fn translated_current(
    frame: &Frame,
    geo: &GeoAxes,
    n: usize,
    start: &AxisVec,
    tool: &AxisVec,
    current: &mut AxisVec,
) -> bool {
    for k in 0..n {
        current[k] = (start[k] - tool[k]) - frame.trans[k];
    }
    geo.iter().flatten().all(|&k| current[k] != 0.0)
}

/// [`block_end`] for a frame that [`only_translates`]: `frame.apply(target) + tool` on the
/// programmed axes (the frame couples none) into `end`, which holds the start; exact by the
/// argument of [`translated_current`]. A zero geometry coordinate comes out of `apply`'s sum
/// as a zero of either sign, which adding a translation other than zero makes exact again; on
/// a zero translation false (and `end` untouched), and the caller takes `block_end`.
fn translated_end(
    frame: &Frame,
    geo: &GeoAxes,
    n: usize,
    tool: &AxisVec,
    target: &AxisVec,
    programmed: &[bool; MAX_CHANNEL_AXES],
    end: &mut AxisVec,
) -> bool {
    if geo.iter().flatten().any(|&k| programmed[k] && target[k] == 0.0 && frame.trans[k] == 0.0) {
        return false;
    }
    for k in 0..n {
        if programmed[k] {
            end[k] = (target[k] + frame.trans[k]) + tool[k];
        }
    }
    true
}

/// Debug builds: prepares the block the lane just prepared once more on `reference` (the
/// interpreter before the lane ran) by the general path, and panics with both versions unless
/// the items (values and the sharing of the offsets) and the whole state are equal.
#[cfg(debug_assertions)]
pub(super) fn cross_check(
    mut reference: Interpreter,
    lane: &Interpreter,
    cfg: &MachineConfig,
    programs: &super::Programs,
    main_run_idle: bool,
    (lane_prep, lane_out, mark): (Prep, &[Item], usize),
) {
    let published_before = reference.published.current().clone();
    reference.fast_lane = false;
    // The same output before the block as the lane had: the compensator's mark counts it.
    let mut items = lane_out[..mark].to_vec();
    let prep = reference.prepare_next(cfg, programs, main_run_idle, &mut items);
    reference.fast_lane = lane.fast_lane;
    let (items, lane_items) = (&items[mark..], &lane_out[mark..]);
    let sharing = |it: &Interpreter, items: &[Item]| -> Vec<(bool, bool)> {
        let offsets = items.iter().filter_map(|i| match i {
            Item::Move { offsets, .. } | Item::Offsets { offsets, .. } => Some(offsets),
            _ => None,
        });
        offsets
            .map(|o| {
                let shared = |with: &super::SharedOffsets| super::SharedOffsets::ptr_eq(o, with);
                (shared(it.published.current()), shared(&published_before))
            })
            .collect()
    };
    assert!(
        prep == lane_prep && items == lane_items && sharing(&reference, items) == sharing(lane, lane_items),
        "fast lane: items differ from the general path\nlane {lane_prep:?} {lane_items:#?}\ngeneral {prep:?} {items:#?}"
    );
    let (general_state, lane_state) = (format!("{reference:#?}"), format!("{lane:#?}"));
    if general_state != lane_state {
        let diff: Vec<String> = general_state
            .lines()
            .zip(lane_state.lines())
            .enumerate()
            .filter(|(_, (g, l))| g != l)
            .take(20)
            .map(|(i, (g, l))| format!("line {i}: general {g} | lane {l}"))
            .collect();
        panic!("fast lane: state differs from the general path:\n{}", diff.join("\n"));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Channel;

    fn mill() -> MachineConfig {
        Channel::from_preset("mill-3axis", "").unwrap().config().clone()
    }

    /// Whether the lane takes the first line of `program` (after `setup`, prepared the general way).
    fn takes(setup: &str, line: &str) -> bool {
        let cfg = mill();
        let mut interp = Interpreter::new(&cfg);
        let lines = setup.lines().filter(|l| !l.is_empty()).count();
        interp.begin_program(format!("{setup}{line}\nM30\n"), &[0.0; MAX_CHANNEL_AXES]);
        interp.set_fast_lane(false);
        let mut out = Vec::new();
        for _ in 0..lines {
            assert_eq!(interp.prepare_next(&cfg, &super::super::Programs::new(), true, &mut out), Prep::Prepared);
        }
        assert!(!out.iter().any(|i| matches!(i, Item::Alarm(_))), "{out:?}");
        out.clear();
        let taken = interp.prepare_plain(&cfg, &mut out);
        assert!(taken.is_none_or(|p| p == Prep::Prepared) && out.iter().all(|i| !matches!(i, Item::Alarm(_))));
        taken.is_some()
    }

    #[test]
    fn plain_motion_lines_take_the_lane() {
        for line in [
            "G0 X10 Y5 Z2",
            "G1 X20 F100",
            "N30 G3 X0 Y0 I-5 J0 F100",
            "  g91 g0 x1 y-.5 ; comment",
            "G90 G2 I5 J5 F1",
            "N40",
            "F200",
            "G1",
            "; only a comment",
            "N50 ; numbered comment",
        ] {
            assert!(takes("", line), "{line}");
        }
        // States the lane takes: a frame, a tool, inch units, G64, once a move followed them.
        assert!(takes("TRANS X5\nT1 D1\nG70 G64 F10\nG0 X1\n", "G2 J1"));
        // The first move after a change of offsets travels it (SD42440/SD42442): not the lane's.
        assert!(!takes("TRANS X5\n", "G91 X1"));
        assert!(!takes("T1 D1\n", "G0 X1"));
    }

    #[test]
    fn anything_else_takes_the_general_path() {
        for line in [
            "",
            "  \t",
            "X=10",
            "X1 X2",
            "G1 G2 X1",
            "G17 X1",
            "N10X5",
            "X1 N10",
            "T1",
            "G4 F1",
            "G9 X1",
            "X1 RND=2",
            "G2 X1 Y1 CR=5",
            "X1 M3",
            "/X1",
            "A10",
            "X1EX2",
        ] {
            assert!(!takes("", line), "{line:?}");
        }
        // States the lane refuses: compensation, a corner held. (A user variable cannot be
        // named like an address: the naming rule refuses single letters.)
        assert!(!takes("T1 D1\nG41 G1 X10 Y0 F100\n", "X20"));
        assert!(!takes("G1 X10 Y0 F100 RND=2\n", "X20 Y10"));
        assert!(!takes("T1 D1\nG41 G1 X10 Y0 F100\nG40\n", "X20"));
    }

    /// The items of `program` from a start at the machine zero, lane on or off.
    fn items(program: &str, lane: bool) -> Vec<Item> {
        let cfg = mill();
        let mut interp = Interpreter::new(&cfg);
        interp.set_fast_lane(lane);
        interp.begin_program(program.to_string(), &[0.0; MAX_CHANNEL_AXES]);
        let mut out = Vec::new();
        while interp.prepare_next(&cfg, &super::super::Programs::new(), true, &mut out) != Prep::Done {}
        out
    }

    #[test]
    fn translations_map_zero_and_signed_zero_coordinates_exactly() {
        // Machine end = WCS value + translation, worked out by hand per block:
        // X0 Y0 → (10, −5); X−0 Y5 Z0 → (10, 0, 0); G91 X−10 Y−0 from WCS (0, 5) → WCS
        // (−10, 5) → (0, 0); G3 back to WCS X0 Y5 around I5 (centre WCS (−5, 5)) → (10, 0).
        let program = "TRANS X10 Y-5\nG1 X0 Y0 F100\nX-0 Y5 Z0\nG91 X-10 Y-0\nG90 G3 X0 Y5 I5 J0\nM30\n";
        let lane = items(program, true);
        let ends: Vec<[f64; 3]> = lane
            .iter()
            .filter_map(|i| match i {
                Item::Move { mv, .. } => Some([mv.path.end[0], mv.path.end[1], mv.path.end[2]]),
                _ => None,
            })
            .collect();
        assert_eq!(ends, [[10.0, -5.0, 0.0], [10.0, 0.0, 0.0], [0.0, 0.0, 0.0], [10.0, 0.0, 0.0]]);
        // `Debug` tells −0.0 from 0.0, which `PartialEq` does not.
        assert_eq!(format!("{lane:?}"), format!("{:?}", items(program, false)));
    }
}
