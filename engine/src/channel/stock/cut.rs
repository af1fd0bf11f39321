//! The main run's side of material removal: the tool tip of every IPO cycle gathered into
//! straight segments, each cut from the session's stock (`crate::stock`), and the checks on
//! what a segment removed.
//!
//! Segments: consecutive IPO samples stay in one segment while they lie within a tenth of the
//! resolution of its line (an arc becomes chords of that sagitta), for at most
//! [`MAX_SEGMENT`] mm, and while the block, rapid or feed, the spindle state and the tool stay
//! the same. A segment is cut when it ends, so nothing between IPO samples is missed and the
//! cost is per segment, not per cycle; at rest the open segment is cut at once.
//!
//! Checks (each raised once per block and kind, as [`Event::Stock`] and in the state):
//! - rapid traverse (G0) that removes material;
//! - material removed while no spindle of the channel turns (a mill's tool spindle, a lathe's
//!   work spindle);
//! - a depth of cut beyond the limit the user set: the thickest material one dexel (one slab)
//!   lost in one segment: the axial depth of a side cut, the radial depth on a lathe;
//! - the tool's shank, the holder ([`StockOptions::holder`]) or the spindle housing touching
//!   the stock (`crate::stock::body`).
//!
//! Tip and tool axis come from `pose.rs` (5-axis machines through the TRAORI chain),
//! `table.rs` (a rotary table without TRAORI data: TRACYL on a trunnion table) and
//! `spindle.rs` (TRANSMIT, TRACYL, TRAANG and their TRACON chain; a blank turning with
//! the spindle). Skipped
//! (counted in `skipped`): what `spindle.rs` names.

use crate::channel::{Channel, CommandError, Event};
use crate::stock::blank::{Blank, Placement};
use crate::stock::cutter::Cutter;
use crate::stock::{DEFAULT_RESOLUTION, Stock};

/// Longest segment cut at once, mm: bounds the cells a segment's box holds beyond its path.
const MAX_SEGMENT: f64 = 8.0;

/// Material thinner than this (mm) removed by a segment does not raise a check.
const CHECK_DEPTH: f64 = 1e-3;

/// Warnings kept for `GET .../stock` (the latest; the count goes on).
const KEEP_WARNINGS: usize = 64;

/// What a check found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StockCheck {
    /// G0 removed material.
    RapidIntoStock,
    /// Material removed with no spindle turning.
    NoSpindle,
    /// The depth of cut exceeded the user's limit.
    DepthOfCut,
    /// The holder (or spindle) touched the stock.
    HolderCollision,
}

impl StockCheck {
    pub fn as_str(self) -> &'static str {
        match self {
            StockCheck::RapidIntoStock => "rapid_into_stock",
            StockCheck::NoSpindle => "no_spindle",
            StockCheck::DepthOfCut => "depth_of_cut",
            StockCheck::HolderCollision => "holder_collision",
        }
    }
}

/// One finding, with the program line of the block that made it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockWarning {
    pub check: StockCheck,
    pub line: u32,
    /// Volume the segment removed, mm³ (a holder collision: the material inside the holder
    /// at the worst point).
    pub volume: f64,
    /// Its depth of cut, mm (a holder collision: the thickest material inside the holder
    /// on one dexel line).
    pub depth: f64,
    /// Where the segment began that cut (tool tip, BCS, mm): the place to mark (a holder
    /// collision: the tip where the holder went deepest).
    pub position: [f64; 3],
}

/// The settings of material removal a session chooses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockOptions {
    /// Cell size (milling) or slab length (turning), mm; applies to the next blank.
    pub resolution: f64,
    /// Depth of cut beyond which [`StockCheck::DepthOfCut`] is raised; `None`: no limit.
    pub depth_limit: Option<f64>,
    /// The holder whose touching the stock raises [`StockCheck::HolderCollision`]; `None`:
    /// no holder check (and no cost).
    pub holder: Option<crate::stock::holder::Holder>,
}

impl Default for StockOptions {
    fn default() -> Self {
        StockOptions { resolution: DEFAULT_RESOLUTION, depth_limit: None, holder: None }
    }
}

/// The state's summary of the stock (no allocation: refreshed every snapshot).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockInfo {
    /// Turned profile (lathe) rather than dexels (mill).
    pub turning: bool,
    pub resolution: f64,
    /// Blank volume at the resolution, mm³.
    pub initial_volume: f64,
    /// Material left, mm³.
    pub volume: f64,
    /// Material removed, mm³.
    pub removed: f64,
    /// Checks raised since the blank was defined.
    pub warnings: u64,
    /// The latest of them.
    pub last_warning: Option<StockWarning>,
    /// IPO cycles not cut because a transformation was active.
    pub skipped: u64,
    /// Grows with every cut that removed material: the HMI fetches the changed tiles when it
    /// differs from the one it shows (`Channel::stock_changes`).
    pub version: u32,
    /// Where the stock's frame lies in the machine's Cartesian frame now, rows of `[R | t]`
    /// (`machine = R·p + t`): the pose of the table carrying the blank, so the HMI draws the
    /// mesh turned with C and tilted with A/B; `None` where the blank does not move.
    pub frame: Option<[[f64; 4]; 3]>,
}

/// What decides where one segment ends besides its geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Key {
    line: u32,
    rapid: bool,
    spindle: bool,
    tool: (u32, u32),
    /// A turning cut of a part that turns with the spindle (`spindle.rs`).
    ring: bool,
}

#[derive(Debug, Clone)]
struct Segment {
    start: [f64; 3],
    end: [f64; 3],
    /// Unit direction from `start`, zero until the first step.
    dir: [f64; 3],
    key: Key,
    /// The tool's axis (unit, tip → holder) and length in the blank's frame.
    axis: [f64; 3],
    length: f64,
}

/// Largest change of the tool's axis (unit vector difference) within one segment: 0.1 mrad,
/// 0.01 mm at a 100 mm tool.
const AXIS_TOLERANCE: f64 = 1e-4;

/// The cutting edge last used: tool and edge, its cutter and its shank (radius, height).
type EdgeCache = ((u32, u32), Option<Cutter>, Option<(f64, f64)>);

/// The stock of a session with its segment in progress and its findings.
#[derive(Debug, Clone)]
pub(in crate::channel) struct StockRun {
    pub(in crate::channel) stock: Stock,
    initial_volume: f64,
    options: StockOptions,
    /// The active edge's cutter and shank (`crate::stock::body`).
    cutter: Option<EdgeCache>,
    /// `$MC_SPINDLE_HOUSING`: diameter and length of the spindle round its nose.
    housing: Option<[f64; 2]>,
    segment: Option<Segment>,
    warnings: std::collections::VecDeque<StockWarning>,
    warnings_total: u64,
    /// The line each check was last raised for (once per block and kind; JOG is line 0).
    reported: [u32; 4],
    skipped: u64,
    /// The last segment cut removed material at feed with a spindle turning (the T/F/S
    /// display's spindle load symbol, `snapshot_refresh.rs`).
    removing: bool,
    /// The orientation kinematics the blank is mounted on (`pose.rs`).
    pub(in crate::channel) kin: Option<Box<crate::kinematics::Traori>>,
    /// Changes for the HMI's incremental mesh (`tiles.rs`).
    pub(in crate::channel) tiles: super::tiles::TileLog,
    /// The work spindle the blank turns with (a lathe with driven tools, `spindle.rs`).
    pub(in crate::channel) mount: Option<super::spindle::SpindleMount>,
    /// The rotary table the blank turns and tilts with (`table.rs`).
    pub(in crate::channel) table: Option<super::table::TableMount>,
}

impl StockRun {
    /// The stock as cut so far (the probe of MEAS reads it, `probe.rs`).
    pub(in crate::channel) fn stock(&self) -> &Stock {
        &self.stock
    }

    fn new(stock: Stock, options: StockOptions, kin: Option<Box<crate::kinematics::Traori>>) -> StockRun {
        StockRun {
            mount: None,
            table: None,
            housing: None,
            tiles: super::tiles::TileLog::new(&stock),
            kin,
            initial_volume: stock.volume(),
            stock,
            options,
            cutter: None,
            segment: None,
            warnings: Default::default(),
            warnings_total: 0,
            reported: [u32::MAX; 4],
            skipped: 0,
            removing: false,
        }
    }
}

impl StockRun {
    /// The stock changed representation (`spindle.rs`): the blank's volume moves by the
    /// difference, so the removed volume goes on.
    pub(in crate::channel) fn shift_initial_volume(&mut self, dv: f64) {
        self.initial_volume += dv;
        self.segment = None;
    }

    /// Every tile changed (a new grid).
    pub(in crate::channel) fn restart_tiles(&mut self) {
        self.tiles.restart(&self.stock);
    }

    /// Keeps `w` among the latest warnings and counts it.
    fn push_warning(&mut self, w: StockWarning) {
        if self.warnings.len() == KEEP_WARNINGS {
            self.warnings.pop_front();
        }
        self.warnings.push_back(w);
        self.warnings_total += 1;
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Channel {
    /// Defines the blank: `blank` in the WCS of the active frame (the main run's), cut from now
    /// on. Only while nothing moves.
    pub fn define_stock(&mut self, blank: Blank) -> Result<(), CommandError> {
        if self.is_busy() {
            return Err(CommandError::Busy("the blank can only change while nothing moves"));
        }
        let offsets = self.offsets.clone();
        self.place_stock(&blank, &offsets.frame).map_err(CommandError::Invalid)
    }

    /// Removes the blank: no material removal from now on.
    pub fn clear_stock(&mut self) {
        self.stock = None;
    }

    /// Sets resolution and depth limit; the resolution acts on the next blank.
    pub fn set_stock_options(&mut self, options: StockOptions) -> Result<(), CommandError> {
        if !(options.resolution.is_finite() && options.resolution >= crate::stock::MIN_RESOLUTION) {
            return Err(CommandError::Invalid(format!(
                "stock resolution {} mm: at least {} mm",
                options.resolution,
                crate::stock::MIN_RESOLUTION
            )));
        }
        if options.depth_limit.is_some_and(|d| !(d.is_finite() && d > 0.0)) {
            return Err(CommandError::Invalid("the depth-of-cut limit must be a positive length".into()));
        }
        self.stock_options = options;
        if let Some(run) = self.stock.as_mut() {
            run.options.depth_limit = options.depth_limit;
            run.options.holder = options.holder;
        }
        Ok(())
    }

    /// The settings of material removal.
    pub fn stock_options(&self) -> StockOptions {
        self.stock_options
    }

    /// The stock's summary (`None` without a blank), the open segment cut first.
    pub fn stock_info(&mut self) -> Option<StockInfo> {
        self.flush_stock();
        self.stock_summary()
    }

    /// The summary as the snapshot shows it (the open segment not yet cut).
    pub(in crate::channel) fn stock_summary(&self) -> Option<StockInfo> {
        let run = self.stock.as_ref()?;
        let volume = run.stock.volume();
        Some(StockInfo {
            turning: matches!(run.stock, Stock::Turning(_)),
            resolution: run.stock.resolution(),
            initial_volume: run.initial_volume,
            volume,
            removed: run.initial_volume - volume,
            warnings: run.warnings_total,
            last_warning: run.warnings.back().copied(),
            skipped: run.skipped,
            version: run.tiles.version(),
            frame: self.stock_frame(),
        })
    }

    /// Whether the last segment cut removed material at feed with a spindle turning.
    pub(in crate::channel) fn stock_removing(&self) -> bool {
        self.stock.as_ref().is_some_and(|r| r.removing)
    }

    /// The latest warnings, oldest first (at most 64).
    pub fn stock_warnings(&self) -> Vec<StockWarning> {
        self.stock.as_ref().map(|r| r.warnings.iter().copied().collect()).unwrap_or_default()
    }

    /// The current stock (its intervals, volumes, mesh), the open segment cut first: for
    /// tests and for probing (where a measuring probe touches the blank).
    pub fn stock(&mut self) -> Option<&Stock> {
        self.flush_stock();
        self.stock.as_ref().map(|r| &r.stock)
    }

    /// The current stock as a binary STL (BCS, mm), the open segment cut first.
    pub fn stock_stl(&mut self) -> Option<Vec<u8>> {
        self.flush_stock();
        self.stock.as_ref().map(|r| r.stock.stl())
    }

    /// A `WORKPIECE(..)` reached the main run with the offsets of its block.
    pub(in crate::channel) fn execute_workpiece(
        &mut self,
        request: crate::stock::blank::Request,
        frame: &crate::interp::Frame,
        line: u32,
    ) {
        match request {
            crate::stock::blank::Request::Delete => self.stock = None,
            crate::stock::blank::Request::Define(blank) => {
                if let Err(message) = self.place_stock(&blank, frame) {
                    self.raise(crate::alarm::Alarm::value_out_of_range(line, &format!("WORKPIECE: {message}")));
                }
            }
        }
    }

    /// Builds the stock of `blank` in the WCS of `frame`.
    fn place_stock(&mut self, blank: &Blank, frame: &crate::interp::Frame) -> Result<(), String> {
        let turning = self.stock_turns();
        let placement = self.stock_placement(frame);
        // Dexels on a work spindle (a lathe with a Y axis) turn with it.
        let placement = if turning { placement } else { self.mount_placement(placement) };
        let stock = Stock::new(blank, &placement, turning, self.stock_options.resolution)?;
        self.install_stock(stock);
        Ok(())
    }

    /// Where the WCS of `frame` lies in the BCS.
    pub(in crate::channel) fn stock_placement(&self, frame: &crate::interp::Frame) -> Placement {
        let geo = self.cfg.geo_axes;
        Placement { lin: frame.lin, trans: std::array::from_fn(|g| geo[g].map_or(0.0, |k| frame.trans[k])) }
    }

    /// A machine without a second geometry axis is a lathe: the workpiece turns on the spindle.
    pub(in crate::channel) fn stock_turns(&self) -> bool {
        self.cfg.geo_axes[1].is_none()
    }

    /// The stock and its blank's volume, for a checkpoint.
    pub(in crate::channel) fn stock_parts(&self) -> Option<(&Stock, f64)> {
        self.stock.as_ref().map(|r| (&r.stock, r.initial_volume))
    }

    /// The blank's volume a restored stock was cut from.
    pub(in crate::channel) fn set_initial_stock_volume(&mut self, volume: f64) {
        if let Some(run) = self.stock.as_mut() {
            run.initial_volume = volume;
        }
    }

    /// Makes `stock` the session's, cut from now on.
    pub(in crate::channel) fn install_stock(&mut self, stock: Stock) {
        let kin = if matches!(stock, Stock::Turning(_)) { None } else { self.stock_kinematics() };
        let mount = self.stock_spindle_mount();
        let mut run = StockRun::new(stock, self.stock_options, kin);
        run.mount = mount;
        run.table = if matches!(run.stock, Stock::Milling(_)) { self.stock_table_mount() } else { None };
        let housing = [0, 1].map(|i| self.data.num("$MC_SPINDLE_HOUSING", 0, i));
        run.housing = (housing[0] > 0.0 && housing[1] > 0.0).then_some(housing);
        self.stock = Some(Box::new(run));
    }

    /// One IPO cycle of material removal (called only while a blank is defined).
    #[inline(never)]
    pub(in crate::channel) fn cut_stock(&mut self) {
        let (line, rapid, offsets) = self.stock_meta();
        let tool = (offsets.t, offsets.d);
        let table = self.stock.as_ref().and_then(|r| r.table);
        let mounted = if let Some(m) = table {
            let length = self.machine_tool_vector(offsets);
            super::spindle::Mounted::At(self.table_tool_pose(&m, &self.machine, length), false)
        } else if self.trafo.is_some() || self.stock.as_ref().is_some_and(|r| r.mount.is_some()) {
            let geo = self.cfg.geo_axes;
            let toff = self.toff.current;
            let plain = std::array::from_fn(|g| geo[g].map_or(0.0, |k| offsets.tool[k]) + toff[g]);
            self.stock_mounted_pose(plain)
        } else {
            super::spindle::Mounted::Plain
        };
        let (pose, ring) = match mounted {
            super::spindle::Mounted::At(pose, ring) => (pose, ring),
            super::spindle::Mounted::Plain => {
                let offsets = self.stock_meta().2;
                (
                    self.stock_tool_pose(&self.machine, offsets, self.stock.as_ref().and_then(|r| r.kin.as_deref())),
                    false,
                )
            }
            super::spindle::Mounted::Skip => {
                if let Some(run) = self.stock.as_mut() {
                    run.skipped += 1;
                    run.segment = None;
                }
                return;
            }
        };
        let tip = pose.tip;
        let key = Key { line, rapid, spindle: self.spindles.iter().any(|s| s.is_turning()), tool, ring };
        let Some(run) = self.stock.as_mut() else { return };
        let tol = run.stock.resolution() / 10.0;
        let Some(seg) = run.segment.as_mut() else {
            run.segment =
                Some(Segment { start: tip, end: tip, dir: [0.0; 3], key, axis: pose.axis, length: pose.length });
            return;
        };
        let turned = {
            let d = sub(pose.axis, seg.axis);
            dot(d, d) > AXIS_TOLERANCE * AXIS_TOLERANCE
        };
        if seg.key.tool != key.tool {
            // A new tool or cutting edge moves the tip without motion: the jump cuts nothing.
            self.flush_stock();
            if let Some(run) = self.stock.as_mut() {
                run.segment =
                    Some(Segment { start: tip, end: tip, dir: [0.0; 3], key, axis: pose.axis, length: pose.length });
            }
            return;
        }
        if tip == seg.end && !turned {
            // At rest: the open segment is cut now.
            if seg.start != seg.end || seg.key != key {
                self.flush_stock();
                if let Some(seg) = self.stock.as_mut().and_then(|r| r.segment.as_mut()) {
                    seg.key = key;
                }
            }
            return;
        }
        let v = sub(tip, seg.start);
        let along = dot(v, seg.dir);
        let off = dot(v, v) - along * along;
        let straight = seg.dir != [0.0; 3] && along >= dot(sub(seg.end, seg.start), seg.dir) && off <= tol * tol;
        if seg.key == key && !turned && tip != seg.end && (seg.dir == [0.0; 3] || (straight && along <= MAX_SEGMENT)) {
            if seg.dir == [0.0; 3] {
                let n = dot(v, v).sqrt();
                seg.dir = v.map(|c| c / n);
            }
            seg.end = tip;
            return;
        }
        // The segment ends at the last sample; the new one starts there.
        let (from, from_axis) = (seg.end, seg.axis);
        self.flush_stock();
        if turned {
            // The axis turned: from the last sample to this one the tool is swept with its
            // axis turning (a tool turning about a standing tip sweeps its shank), and the next
            // segment starts here.
            self.cut_piece(from, tip, [from_axis, pose.axis], key, pose.length);
            if let Some(run) = self.stock.as_mut() {
                run.segment =
                    Some(Segment { start: tip, end: tip, dir: [0.0; 3], key, axis: pose.axis, length: pose.length });
            }
            return;
        }
        let Some(run) = self.stock.as_mut() else { return };
        let v = sub(tip, from);
        let n = dot(v, v).sqrt();
        let dir = if n > 0.0 { v.map(|c| c / n) } else { [0.0; 3] };
        run.segment = Some(Segment { start: from, end: tip, dir, key, axis: pose.axis, length: pose.length });
    }

    /// Line, rapid traverse and offsets of the block the planner's position lies on (line 0
    /// and the channel's offsets outside a move).
    #[inline]
    fn stock_meta(&self) -> (u32, bool, &crate::interp::Offsets) {
        let tag = self.planner.position_tag();
        let meta = match self.in_planner.front() {
            Some((t, m)) if Some(*t) == tag => Some(m),
            _ => tag.and_then(|t| self.in_planner.iter().find(|(x, _)| *x == t)).map(|(_, m)| m),
        };
        match meta {
            Some(m) => (m.line, !m.feed.is_finite(), &m.offsets),
            None => (0, false, &self.offsets),
        }
    }

    /// [`Channel::flush_stock`] for the sibling modules.
    pub(in crate::channel) fn flush_stock_now(&mut self) {
        self.flush_stock();
    }

    /// Cuts the open segment (if it has length) and starts the next one at its end.
    fn flush_stock(&mut self) {
        let Some(run) = self.stock.as_mut() else { return };
        let Some(seg) = run.segment.as_mut() else { return };
        // A tilted tool turning about its tip (a segment without length but with a new axis)
        // still cuts where it stands.
        if seg.start == seg.end && seg.axis[2] >= 1.0 - 1e-12 {
            return;
        }
        let (a, b, key, axis, length) = (seg.start, seg.end, seg.key, seg.axis, seg.length);
        seg.start = seg.end;
        seg.dir = [0.0; 3];
        self.cut_piece(a, b, [axis, axis], key, length);
    }

    /// Cuts the tip's way from `a` to `b` with the tool's axis turning from `axes[0]` to
    /// `axes[1]`, and raises the checks.
    fn cut_piece(&mut self, a: [f64; 3], b: [f64; 3], axes: [[f64; 3]; 2], key: Key, length: f64) {
        let Some(run) = self.stock.as_mut() else { return };
        let axis = axes[0];
        if run.cutter.as_ref().is_none_or(|(k, _, _)| *k != key.tool) {
            let edge = (key.tool.0 != 0 && key.tool.1 != 0).then(|| self.cfg.tools.get(&key.tool)).flatten();
            run.cutter = Some((key.tool, edge.map(Cutter::from_edge), edge.and_then(crate::stock::body::shank)));
        }
        let Some((_, Some(cutter), shank)) = run.cutter else { return };
        let pen = run.tiles.pen(key.tool);
        if let Stock::Milling(g) = &mut run.stock {
            g.set_pen(pen);
        }
        let removal = match &mut run.stock {
            Stock::Milling(g) if key.ring => match g.cut_ring(&cutter, a, b) {
                Some(removal) => removal,
                // A tool on the axis of the turning part (a drill) cuts as it stands.
                None if a[0].hypot(a[1]).max(b[0].hypot(b[1])) <= g.resolution() / 2.0 => g.cut(&cutter, a, b),
                None => {
                    run.skipped += 1;
                    crate::stock::Removal::default()
                }
            },
            stock => stock.cut_swept(&cutter, a, b, axis, axes[1], length.max(4.0 * cutter.radius)),
        };
        run.removing = removal.volume > 0.0 && !key.rapid && key.spindle;
        if removal.volume > 0.0 {
            let side = |o: [f64; 3]| (1.0 - o[2] * o[2]).max(0.0).sqrt();
            let reach = cutter.radius + length * side(axes[0]).max(side(axes[1]));
            run.tiles.touch(&run.stock, a, b, reach);
        }
        let bodies = crate::stock::body::Bodies::new(shank, run.options.holder.as_ref(), run.housing, length);
        if !bodies.cylinders().is_empty() {
            let touch = run.stock.overlap(bodies.cylinders(), a, b, axis);
            if touch.depth >= CHECK_DEPTH && run.reported[3] != key.line {
                run.reported[3] = key.line;
                let w = StockWarning {
                    check: StockCheck::HolderCollision,
                    line: key.line,
                    volume: touch.volume,
                    depth: touch.depth,
                    position: touch.at,
                };
                run.push_warning(w);
                self.events.push(Event::Stock(w));
            }
        }
        let Some(run) = self.stock.as_mut() else { return };
        if removal.depth < CHECK_DEPTH {
            return;
        }
        let mut found = [None; 3];
        if key.rapid {
            found[0] = Some(StockCheck::RapidIntoStock);
        }
        if !key.spindle {
            found[1] = Some(StockCheck::NoSpindle);
        }
        if run.options.depth_limit.is_some_and(|l| removal.depth > l) {
            found[2] = Some(StockCheck::DepthOfCut);
        }
        for (i, check) in found.into_iter().enumerate() {
            let Some(check) = check else { continue };
            if run.reported[i] == key.line {
                continue;
            }
            run.reported[i] = key.line;
            let w = StockWarning { check, line: key.line, volume: removal.volume, depth: removal.depth, position: a };
            run.push_warning(w);
            self.events.push(Event::Stock(w));
        }
    }
}
