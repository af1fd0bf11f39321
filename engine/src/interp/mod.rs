//! Block preparation ("preprocessing"): the modal state of the channel applied to each block.
//!
//! Input: parsed [`Block`]s and the [`MachineConfig`]. Output: [`Item`]s in main-run order:
//! moves in channel-axis space (tool tip + tool length + work offset), dwells, spindle commands,
//! programmed stops and alarms. The interpreter runs ahead of the main run and keeps its own
//! programmed position, as the control's preprocessing does.

pub mod auxiliary;
mod calls;
mod compensation;
mod contour;
pub mod dynamics;
pub mod eval;
mod everyday;
pub mod files;
mod flow;
mod frames;
pub mod gcodes;
pub mod io;
mod lane;
pub mod measuring;
mod modal;
/// The words block preparation knows, for the static name check (`crate::check`).
pub(crate) use modal::vocabulary;
mod orientation;
pub(crate) mod path_control;
pub mod program_control;
mod published;
pub mod retained;
pub mod spindles;
mod statements;
pub mod synchronized;
mod tools;
mod transform;
mod workpiece;

use crate::alarm::Alarm;
use crate::kinematics;
use crate::lang::{Block, CoordMode, ProgramText};
use crate::machine_data::MachineConfig;
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::motion::{Arc, AxisLimit, AxisVec, Feed, Move, OriPath, Path};
use calls::CallFrame;
pub use calls::{Level, Programs};
pub(crate) use compensation::cutting_edge::edge_direction;
pub use contour::corners::Corner;
use eval::scope::sys_view;
use eval::vars::Variables;
use flow::Flow;
use frames::cache::{FrameCache, Tracked};
pub use frames::frame::Frame;
use frames::frame::SystemFrames;
pub use frames::overview::ChainLink as FrameChainLink;
use modal::{CircleForm, FrameKind, FrameOp, PoleRef};
pub use modal::{Modal, MotionMode, Plane};
pub use tools::active_swivel::ActiveSwivel;

/// Offsets in effect for a block, per channel axis, and the tool that causes them.
///
/// `gcodes` comes first: it is the field that changes most often (G1 ↔ G3 in every pocket), and
/// the derived comparison stops at the first field that differs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Offsets {
    /// The block's active G functions, for the display.
    pub gcodes: gcodes::GCodes,
    /// Tool length vector (MCS = BCS + tool).
    pub tool: AxisVec,
    /// The active frame, WCS → BCS: settable frame (G54 ...) then programmable frame.
    pub frame: Frame,
    /// Active tool number (the tool in the spindle) and cutting edge.
    pub t: u32,
    pub d: u32,
    /// The programmed tool (`$P_TOOLP`): prepared for the next change under MD22550 = 1.
    pub prepared: u32,
    /// The active kinematic transformation with the tool length it includes.
    pub trafo: Option<crate::kinematics::ActiveTrafo>,
    /// Online tool length offset in the tool directions X, Y, Z (`$AA_TOFF`, see `toff.rs`).
    pub toff: [f64; 3],
    /// Channel axes besides the transverse axis shown as diameters in the WCS (DIAMONA[ax]..;
    /// bit k: channel axis k).
    pub diameter_axes: u32,
}

/// The offsets an item carries: shared, because consecutive blocks mostly have the same
/// offsets and items are moved several times on their way to the main run.
pub type SharedOffsets = std::sync::Arc<Offsets>;

/// Why the main run stops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopKind {
    /// M0: programmed stop.
    M0,
    /// M1: optional stop.
    M1,
    /// M2/M17/M30 or end of text.
    End,
}

/// One prepared item for the main run.
#[derive(Debug, Clone, PartialEq)]
#[allow(
    clippy::large_enum_variant,
    reason = "items live briefly in a bounded queue; boxing moves would cost an allocation per block"
)]
pub enum Item {
    Move {
        mv: Move,
        line: u32,
        offsets: SharedOffsets,
    },
    /// A block without motion that changes the offsets shown (T, D, G54, ...).
    Offsets {
        line: u32,
        offsets: SharedOffsets,
    },
    Dwell {
        seconds: f64,
        line: u32,
    },
    /// Target speed of the spindle on channel axis `axis` in rev/min (+ = M3).
    Spindle {
        axis: usize,
        rpm: f64,
        line: u32,
    },
    Stop {
        kind: StopKind,
        line: u32,
    },
    /// A spindle command beyond a speed: limits, constant cutting speed, thread start.
    SpindleControl {
        ctl: spindles::Control,
        line: u32,
    },
    /// SPOS: the spindle stops at `angle` and becomes a rotary axis in position control.
    SpindleToAxis {
        axis: usize,
        angle: f64,
        line: u32,
    },
    /// MSG: text shown to the operator from this block on (empty clears it).
    Message {
        text: String,
        line: u32,
    },
    Alarm(Alarm),
    /// An M or H function for the PLC (see `auxiliary.rs`).
    Aux {
        function: auxiliary::AuxFunction,
        line: u32,
    },
    /// `$A_OUT[signal]=..`: a digital output set or cleared in the main run.
    DigitalOutput {
        signal: usize,
        on: bool,
        line: u32,
    },
    /// `$AC_MARKER[n]=..`, a workpiece counter written, GOTOS: done in the main run
    /// ([`synchronized::MainRunWrite`]).
    MainRunWrite {
        write: synchronized::MainRunWrite,
        line: u32,
    },
    /// A synchronized action, active from when the main run reaches it (`synchronized.rs`).
    SyncAction {
        def: std::sync::Arc<synchronized::SyncDef>,
        line: u32,
    },
    /// SETPIECE: `pieces` workpieces done for the tools used in the spindle since the last one
    /// (`tools/setpiece.rs`, counted in `channel/tools/monitor.rs`).
    SetPiece {
        pieces: u32,
        line: u32,
    },
    /// CANCEL/LOCK/UNLOCK/RESET of synchronized actions by ID.
    SyncControl {
        op: synchronized::SyncControl,
        ids: Vec<u32>,
        line: u32,
    },
    /// MEAS/MEAW: the next move (of this line) measures with a probe (`measuring.rs`).
    Measure {
        request: measuring::Request,
        line: u32,
    },
    /// POS/POSA/POSP (or a command axis): channel axis `axis` travels on its own interpolator to
    /// the machine position `target` at `velocity` (mm/s, deg/s), from the main run's start of
    /// the block (`path_control/positioning.rs`, `channel/positioning_axes.rs`).
    Positioning {
        axis: usize,
        target: f64,
        velocity: f64,
        /// POS, POSA or POSP with its parts.
        motion: path_control::positioning::Motion,
        line: u32,
    },
    /// WAITP, or the end of a POS block: the items after it wait until the positioning axes of
    /// `axes` (bit k: channel axis k) have arrived; `strict`: a path block programs them, so an
    /// axis still travelling is alarm 14092 instead.
    WaitPositioning {
        axes: u32,
        strict: bool,
        line: u32,
    },
    /// `WORKPIECE(..)`: the blank, in the WCS of the block's frame (`workpiece.rs`).
    Workpiece {
        request: crate::stock::blank::Request,
        offsets: SharedOffsets,
        line: u32,
    },
}

/// Marker in [`Interpreter::take_data_writes`]: activate the machine data written so far.
pub const NEWCONF: &str = "NEWCONF";

pub use tools::create_delete::DELT;
/// Prefix of the data-write entry of `DELOBJ("type")`, followed by the object type.
pub const DELOBJ: &str = "DELOBJ:";

/// Prefix of the data-write entry that rebuilds the channel's data set of chain record n
/// (followed by n) after CORRTRAFO corrected its `$NK_OFF_DIR`.
pub const CORRTRAFO: &str = "CORRTRAFO:";

/// What one call of [`Interpreter::prepare_next`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prep {
    /// A block was prepared (it may have produced no items).
    Prepared,
    /// The next block reads main-run values: call again once the main run has caught up.
    WaitForMainRun,
    /// Nothing left to prepare (end of program, or an alarm).
    Done,
}

impl Item {
    /// The program line the item belongs to.
    pub fn line(&self) -> Option<u32> {
        match self {
            Item::Move { line, .. }
            | Item::Offsets { line, .. }
            | Item::Dwell { line, .. }
            | Item::Spindle { line, .. }
            | Item::SpindleControl { line, .. }
            | Item::Stop { line, .. }
            | Item::Message { line, .. }
            | Item::SpindleToAxis { line, .. }
            | Item::Aux { line, .. }
            | Item::DigitalOutput { line, .. }
            | Item::MainRunWrite { line, .. }
            | Item::SyncAction { line, .. }
            | Item::SyncControl { line, .. }
            | Item::Workpiece { line, .. }
            | Item::SetPiece { line, .. }
            | Item::Measure { line, .. }
            | Item::Positioning { line, .. }
            | Item::WaitPositioning { line, .. } => Some(*line),
            Item::Alarm(a) => a.line,
        }
    }
}

/// Preprocessing state of the channel.
#[derive(Debug, Clone)]
pub struct Interpreter {
    modal: Modal,
    /// Programmed end position of the last block in channel-axis (machine) coordinates.
    pos: AxisVec,
    /// The main run's following errors per channel axis (`$AA_IM` = setpoint − error).
    lag: AxisVec,
    /// Offsets in effect; tracked, so that items share them while no block changes them.
    offsets: Tracked<Offsets>,
    /// The offsets of the last motion block, noted at the first change after it (SD42440,
    /// SD42442: the next incremental move travels the change).
    before_change: Option<Box<frames::incremental::BeforeChange>>,
    /// `offsets` as last handed out with an item (see [`Interpreter::shared_offsets`]).
    published: published::Published,
    /// R parameters and user variables.
    vars: Variables,
    /// The programmable frame ($P_PFRAME: TRANS, ROT, SCALE, MIRROR ...).
    pframe: Tracked<Frame>,
    /// The system frames of the frame chain.
    system: Tracked<SystemFrames>,
    /// `$P_IFRAME` as a program wrote it; `None`: the selected settable frame `$P_UIFR[n]`.
    iframe: Tracked<Option<Frame>>,
    /// The active frame as last built from the links above and the machine data.
    frame_cache: FrameCache,
    /// Master spindle and each spindle's programmed speed and direction.
    spindles: spindles::Spindles,
    /// Read position in the active program level, if one runs.
    flow: Option<Flow>,
    /// Subprogram calls in progress, outermost first.
    calls: Vec<CallFrame>,
    /// The line of the block read last, in the program level it was read in, and the byte
    /// offset of its start there (the channel shows the block from it without counting lines).
    read_at: flow::Pos,
    /// The modal call (MCALL) and EXTERN declarations.
    call_state: calls::CallState,
    /// Data written by prepared blocks (line, NC data text or `NEWCONF`) that the channel has
    /// not applied yet.
    data_writes: Vec<(u32, String)>,
    /// Files written or deleted by the file functions (WRITE, DELETE) not yet in the store.
    files: files::Files,
    /// Alarms that only inform (10910): shown while the program goes on.
    warnings: Vec<Alarm>,
    /// A move held back until the next block decides its corner (RND, CHF, CHR).
    held: Option<contour::corners::Held>,
    /// The spline sequence being collected (`path_control/spline.rs`).
    splines: Option<Box<path_control::spline::SplineRun>>,
    /// The corner the block being prepared asks for.
    corner_request: Option<Corner>,
    /// FRC= of the block whose corner is requested (`contour/corner_feed.rs`).
    corner_frc: Option<f64>,
    /// CONTCAPON..CONTCAPOF: motions recorded, not run (`contour/capture.rs`).
    capture: Option<Box<contour::capture::Capture>>,
    /// Tool radius compensation: moves held until their successor decides their end.
    trc: compensation::trc::Compensator,
    /// Spindles in position control (after SPOS), by channel axis.
    positioned: [bool; MAX_CHANNEL_AXES],
    /// FA per axis and the POSA axes not yet waited for (`path_control/positioning.rs`).
    positioning_axes: path_control::positioning::Positioning,
    /// The spindles' angles in the main run, as last observed (for SPOS).
    spindle_angles: AxisVec,
    /// The active kinematic transformation, if any (see `trafo.rs`).
    trafo: transform::selection::TrafoState,
    /// The orientable toolholder and G groups 22, 42, 52, 53 (see `swivel.rs`).
    holder: tools::toolholder::Holder,
    /// The tool-change cycle (MD10715/10716) a block's M6 calls after it, instead of changing.
    tool_cycle: Option<String>,
    /// The words of the last block, kept for the next one's (no allocation per block).
    spare_words: modal::SpareWords,
    /// Plain motion lines take the fast lane (`lane.rs`).
    fast_lane: bool,
    /// SKP and DRY as the channel last handed them (`program_control.rs`).
    program_control: program_control::ProgramControl,
    /// What the lane keeps between its blocks (a cache, cleared by the general path).
    lane_memo: lane::LaneMemo,
    /// The last path block in the working plane, for CT (`contour/tangent_circle.rs`).
    last_move: contour::tangent_circle::LastMove,
    /// The first block of a two-block contour definition with ANG, waiting for the second
    /// (`contour/angle_corner.rs`), and the corner it runs to once known.
    pending_angle: Option<Box<contour::angle_corner::Pending>>,
    angle_corner_end: Option<(f64, f64)>,
    /// The session's machine and setting data as stored, for programs' `$MN_`... reads
    /// (the channel hands over each new state, [`Interpreter::set_stored_data`]).
    stored: std::sync::Arc<crate::machine_data::MachineData>,
    /// The digital inputs and outputs as the main run last reported them.
    io: io::DigitalIo,
    /// How the shell runs the channel's programs (`$P_SIM`, `eval/run_vars.rs`).
    env: eval::run_vars::RunEnv,
    /// The workpiece counters, runtimes and clock as the main run last handed them over
    /// (`eval/process_vars.rs`).
    process: eval::process_vars::ProcessData,
    /// The PLC data area `$A_DBB`.. (`io/plc_data.rs`).
    plc: io::plc_data::PlcData,
    /// The enabled working-area limits (`path_control/work_area.rs`): `None` until read from
    /// the stored data after a change, `Some(None)` when no limit is enabled.
    work_area: Option<Option<Box<path_control::work_area::WorkArea>>>,
    /// Preparation held back behind a block-modal DELDTG (`synchronized.rs`).
    sync_wait: synchronized::PrepWait,
    /// The main run's `$AC_MARKER`, `$AC_PARAM`, `$AC_DELT` ... as last handed over.
    sync_data: synchronized::MainRunData,
    /// The main run's probe results (`$AC_MEA`, `$AA_MM`, `$AA_MW`) as last handed over.
    measured: measuring::Results,
}

impl Interpreter {
    pub fn new(cfg: &MachineConfig) -> Interpreter {
        Interpreter {
            modal: Modal::reset(cfg),
            pos: [0.0; MAX_CHANNEL_AXES],
            lag: [0.0; MAX_CHANNEL_AXES],
            offsets: Tracked::new(Offsets::default()),
            before_change: None,
            published: published::Published::default(),
            vars: Variables::default(),
            pframe: Tracked::new(Frame::identity()),
            system: Tracked::new(SystemFrames::default()),
            iframe: Tracked::new(None),
            frame_cache: FrameCache::default(),
            spindles: spindles::Spindles::new(cfg),
            flow: None,
            calls: Vec::new(),
            read_at: flow::Pos { offset: 0, line: 0 },
            call_state: Default::default(),
            data_writes: Vec::new(),
            files: files::Files::default(),
            warnings: Vec::new(),
            held: None,
            capture: None,
            splines: None,
            corner_request: None,
            corner_frc: None,
            trc: compensation::trc::Compensator::default(),
            positioned: [false; MAX_CHANNEL_AXES],
            positioning_axes: Default::default(),
            spindle_angles: [0.0; MAX_CHANNEL_AXES],
            trafo: Default::default(),
            holder: tools::toolholder::Holder { g53: 1, ..Default::default() },
            tool_cycle: None,
            spare_words: modal::SpareWords::default(),
            fast_lane: true,
            program_control: Default::default(),
            lane_memo: Default::default(),
            last_move: Default::default(),
            pending_angle: None,
            angle_corner_end: None,
            stored: Default::default(),
            io: io::DigitalIo::default(),
            env: Default::default(),
            process: Default::default(),
            plc: Default::default(),
            work_area: None,
            sync_wait: synchronized::PrepWait::None,
            measured: Default::default(),
            sync_data: Default::default(),
        }
    }

    /// Channel reset with the machine standing at `machine`: modal state to reset values, the
    /// reset transformation (if any); the tool stays selected.
    pub fn reset(&mut self, cfg: &MachineConfig, machine: &AxisVec) {
        self.lane_memo.forget();
        self.modal = Modal::reset(cfg);
        self.flow = None;
        self.calls.clear();
        self.call_state = Default::default();
        self.held = None;
        self.capture = None;
        self.splines = None;
        self.pending_angle = None;
        self.sync_wait = synchronized::PrepWait::None;
        self.trc.clear();
        self.positioned = [false; MAX_CHANNEL_AXES];
        self.positioning_axes = Default::default();
        self.spindles.reset(cfg, true);
        *self.pframe = Frame::identity();
        *self.iframe = None;
        self.before_change = None;
        self.offsets.frame = self.active_frame(cfg);
        self.offsets.tool = self.holder_tool(cfg, tool_vector(cfg, &self.modal, self.offsets.t, self.offsets.d));
        self.offsets.gcodes = gcodes::GCodes::of(&self.modal);
        self.reset_transformation(cfg, machine);
    }

    /// Program end acts like a reset of the modal state (the spindle keeps turning until M5 or reset).
    pub fn end_program(&mut self, cfg: &MachineConfig) {
        let machine = self.transformation_machine_position();
        let spindles = self.spindles.clone();
        self.reset(cfg, &machine);
        self.spindles = spindles;
        self.spindles.reset(cfg, false);
    }

    /// Starts preparing `text` from the machine's current position. Local variables of an
    /// earlier program are dropped; R parameters and global user data stay.
    pub fn begin_program(&mut self, text: impl Into<ProgramText>, pos: &AxisVec) {
        self.lane_memo.forget();
        self.pos = *pos;
        self.before_change = None;
        self.positioning_axes.posa_open = 0;
        self.vars.reset_locals();
        self.calls.clear();
        self.call_state = Default::default();
        self.flow = Some(Flow::new(text.into()));
        self.env.last_search = 0;
    }

    /// The machine and setting data programs read from now on (after every change the
    /// channel made to its stored data).
    pub fn set_stored_data(&mut self, stored: std::sync::Arc<crate::machine_data::MachineData>) {
        self.stored = stored;
        self.work_area = None;
    }

    /// The PLC data area (`$A_DBB`..) as programs left it.
    pub fn plc_data(&self) -> &io::plc_data::PlcData {
        &self.plc
    }

    /// Writes `bytes` into the PLC data area at byte `at` (checked by the caller).
    pub fn write_plc_data(&mut self, at: usize, bytes: &[u8]) {
        self.plc.put(at, bytes);
    }

    /// The workpiece counters, runtimes and clock of the main run, for the blocks prepared
    /// from now on (a block reading a counter or runtime has waited for the main run).
    pub fn set_process_data(&mut self, data: eval::process_vars::ProcessData) {
        self.process = data;
    }

    /// Marks the channel's runs as a simulation (`$P_SIM` TRUE) or the machine's own.
    pub fn set_simulation(&mut self, simulation: bool) {
        self.env.simulation = simulation;
    }

    /// A block search starts (`$P_SEARCH` 1, `$P_SEARCHL` its type) or has found its target
    /// (`$P_SEARCH` 0 again).
    pub fn set_searching(&mut self, searching: bool) {
        self.env.searching = searching;
        if searching {
            self.env.last_search = eval::run_vars::SEARCH_TO_CONTOUR;
        }
    }

    /// The digital I/O image as the main run holds it (read by blocks that waited for it).
    pub fn set_io(&mut self, io: io::DigitalIo) {
        self.io = io;
    }

    /// Data written by the blocks prepared since the last call (line, NC data text, or
    /// [`NEWCONF`]): the channel applies them before the next block is prepared.
    pub fn take_data_writes(&mut self) -> Vec<(u32, String)> {
        std::mem::take(&mut self.data_writes)
    }

    /// The file functions' changes not yet in the program store, and their clock.
    pub fn files(&self) -> &files::Files {
        &self.files
    }

    /// See [`Interpreter::files`]: the channel takes the changes and sets the clock.
    pub fn files_mut(&mut self) -> &mut files::Files {
        &mut self.files
    }

    /// Alarms raised by the blocks prepared since the last call that do not stop the program
    /// (the control's "alarm display" reaction).
    pub fn take_warnings(&mut self) -> Vec<Alarm> {
        std::mem::take(&mut self.warnings)
    }

    /// Tells preparation where a spindle in speed mode stands in the main run (SPOS starts
    /// from there).
    pub fn observe_spindle(&mut self, axis: usize, angle: f64) {
        self.spindle_angles[axis] = angle;
    }

    /// The user variables and R parameters.
    pub fn variables(&self) -> &Variables {
        &self.vars
    }

    /// Sets the programmed position after motion outside programs (JOG).
    pub fn sync_position(&mut self, pos: &AxisVec) {
        self.pos = *pos;
        self.before_change = None;
    }

    /// The main run's following errors (setpoint − actual per channel axis), which `$AA_IM`
    /// subtracts from the setpoint.
    pub fn observe_following_error(&mut self, lag: &AxisVec) {
        self.lag = *lag;
    }

    /// Number of subprogram levels below the main program being prepared (0: the main program).
    pub fn call_depth(&self) -> usize {
        self.calls.len()
    }

    /// The line of the block the last [`Interpreter::prepare_next`] read, in the program level
    /// it was read in (that level is [`Interpreter::level`] before the call: a block that
    /// calls or returns changes the level only after it was read).
    pub fn read_line(&self) -> u32 {
        self.read_at.line
    }

    /// The byte offset where the line of [`Interpreter::read_line`] starts in its program's
    /// text.
    pub fn read_offset(&self) -> usize {
        self.read_at.offset
    }

    /// Offsets currently selected by preprocessing.
    pub fn offsets(&self) -> SharedOffsets {
        SharedOffsets::new((*self.offsets).clone())
    }

    /// The current offsets for an item: the ones handed out last while they are unchanged.
    fn shared_offsets(&mut self) -> SharedOffsets {
        self.offsets_mark();
        self.published.current().clone()
    }

    /// Publishes the offsets' changes so far and returns how often the published offsets have
    /// changed: equal marks before and after a block mean it leaves the offsets as they were.
    fn offsets_mark(&mut self) -> u64 {
        if self.offsets.take_changed() {
            self.published.publish(&self.offsets);
        }
        self.published.changes()
    }

    /// Sets the block's frame, tool vector and G functions, touching the offsets only where
    /// they change (most blocks change none of them).
    fn refresh_offsets(&mut self, cfg: &MachineConfig) {
        // As `active_frame`, but the cached frame is copied only when it differs.
        let changed = [self.pframe.take_changed(), self.system.take_changed(), self.iframe.take_changed()];
        let (work_offset, rotary_slot) = (self.modal.work_offset, self.trafo.rotary_slot());
        let frame = self
            .frame_cache
            .get(cfg, work_offset, rotary_slot, changed.contains(&true), || sys_view!(self, cfg).chain(None));
        if !self.offsets.frame.same_bits(frame) {
            let frame = frame.clone();
            self.note_offsets_before_change();
            self.offsets.frame = frame;
        }
        let tool = self.holder_tool(cfg, tool_vector(cfg, &self.modal, self.offsets.t, self.offsets.d));
        if self.offsets.tool != tool {
            self.note_offsets_before_change();
            self.offsets.tool = tool;
        }
        self.refresh_gcodes();
    }

    fn refresh_gcodes(&mut self) {
        let gcodes = gcodes::GCodes::of(&self.modal);
        if self.offsets.gcodes != gcodes {
            self.offsets.gcodes = gcodes;
        }
        if self.offsets.diameter_axes != self.modal.diameter_display_axes {
            self.offsets.diameter_axes = self.modal.diameter_display_axes;
        }
    }

    pub fn modal(&self) -> &Modal {
        &self.modal
    }

    /// The tool shown for the block in the main run.
    pub fn tool_in_main_run(&self, offsets: &Offsets) -> (u32, u32) {
        (offsets.t, offsets.d)
    }

    /// Prepares the next block of the active program into `out`. `main_run_idle` tells whether
    /// everything prepared so far has been executed (needed by blocks that read main-run
    /// values). On an error the last item is an [`Item::Alarm`] and preparation is done.
    pub fn prepare_next(
        &mut self,
        cfg: &MachineConfig,
        programs: &Programs,
        main_run_idle: bool,
        out: &mut Vec<Item>,
    ) -> Prep {
        let first = out.len();
        if self.work_area.is_none() {
            // Read once per change of the stored data: without enabled limits the lane stays open.
            self.work_area = Some(path_control::work_area::WorkArea::of(&self.stored, cfg));
        }
        let prep = self.prepare_next_block(cfg, programs, main_run_idle, out);
        if let Some(items) = out.get_mut(first..) {
            dynamics::apply(&self.modal.dynamics, cfg, items);
        }
        prep
    }

    /// [`Interpreter::prepare_next`] before the dynamics words shape the moves.
    fn prepare_next_block(
        &mut self,
        cfg: &MachineConfig,
        programs: &Programs,
        main_run_idle: bool,
        out: &mut Vec<Item>,
    ) -> Prep {
        if self.fast_lane && self.capture.is_none() {
            #[cfg(debug_assertions)]
            let (reference, mark) = (self.clone(), out.len());
            if let Some(prep) = self.prepare_plain(cfg, out) {
                #[cfg(debug_assertions)]
                lane::cross_check(reference, self, cfg, programs, main_run_idle, (prep, out, mark));
                return prep;
            }
        }
        // Any block may change the offsets the lane remembers (see `lane::LaneMemo`).
        self.lane_memo.stale_offsets();
        self.corner_request = None;
        // A held move is not in the main run yet: blocks that read main-run values wait for it.
        let idle = main_run_idle && !self.holds_move() && !self.trc.holds() && self.splines.is_none();
        self.trc.begin_block(out);
        let mark = out.len();
        let result = self.step_program(cfg, programs, idle, out).and_then(|prep| {
            if self.capture.is_some() {
                // A contour being captured: its motions were recorded, none runs.
                out.retain(|item| !matches!(item, Item::Move { .. }));
            }
            // What a block without motion in the compensation plane produced waits behind the
            // held compensated move (look-ahead across dummy blocks, MD20250); anything that
            // cannot wait (a preprocessing stop, the program end, moves past the compensator)
            // ends the held move first.
            let deferred = prep == Prep::Prepared && self.trc.end_block(out)?;
            if self.trc.holds() && !deferred {
                let mut flushed = Vec::new();
                self.trc.flush(&AxisLimit::for_channel(cfg), &mut flushed)?;
                let at = out.iter().rposition(|i| matches!(i, Item::Move { .. })).map_or(0, |i| i + 1);
                out.splice(at..at, flushed);
            }
            self.settle_spline(out, mark, prep, cfg);
            let request = self.corner_request.take();
            self.shape_corners(out, prep, request, cfg)?;
            self.transform_moves(out)?;
            Ok(prep)
        });
        // Blocks the radius compensation omitted (warning 10763).
        self.warnings.append(&mut self.trc.take_warnings());
        // Data written may change the configuration before the next block.
        if !self.data_writes.is_empty() {
            self.lane_memo.forget();
        }
        match result {
            Ok(prep) => prep,
            Err(alarm) => self.fail(alarm, out),
        }
    }

    /// Ends preparation with `alarm`: it replaces what the block produced.
    fn fail(&mut self, alarm: Alarm, out: &mut Vec<Item>) -> Prep {
        out.clear();
        out.push(Item::Alarm(self.alarm_as_displayed(alarm)));
        self.flow = None;
        self.calls.clear();
        self.held = None;
        self.splines = None;
        Prep::Done
    }

    /// Prepares one block: a statement (control flow, declaration) or NC words.
    fn prepare_block(
        &mut self,
        block: &Block,
        cfg: &MachineConfig,
        programs: &Programs,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        // One `Words` is reused block after block (see `Words::clear`).
        let mut words = self.spare_words.0.take().unwrap_or_default();
        let result = self.prepare_words(&mut words, block, cfg, programs, out);
        self.spare_words.0 = Some(words);
        result
    }

    /// [`Interpreter::prepare_block`] with the block's words collected into `words`.
    fn prepare_words(
        &mut self,
        words: &mut modal::Words,
        block: &Block,
        cfg: &MachineConfig,
        programs: &Programs,
        out: &mut Vec<Item>,
    ) -> Result<(), Alarm> {
        let line = block.line;
        let (base_cfg, derived) = (cfg, self.trafo.config());
        let cfg = derived.as_deref().unwrap_or(base_cfg);
        if self.synchronized_block(block, cfg, programs, out)? || self.defer_angle_block(block, cfg) {
            return Ok(());
        }
        {
            let sys = sys_view!(self, cfg);
            modal::collect(words, block, cfg, &mut self.vars, &sys, programs)?;
        }
        if let Some(first) = self.pending_angle.take() {
            self.close_angle_corner(*first, words, cfg, programs, line, out)?;
        }
        let words = &*words;
        self.data_writes.extend(words.data_writes.iter().map(|t| (line, t.clone())));
        for (at, bytes) in &words.plc_writes {
            self.plc.put(*at, bytes);
        }
        if let Some(r) = words.rndm {
            self.modal.rndm = (r > 0.0).then_some(r);
        }
        // RND/CHF/CHR in the block take the place of the modal rounding at its corner.
        self.corner_request = words.corner.or(self.modal.rndm.map(Corner::Round));
        self.corner_feed_words(words.frc, words.frcm, line)?;
        if let Some(path) = &words.callpath {
            self.call_state.callpath = calls::callpath(path);
        }
        if words.newconf {
            self.data_writes.push((line, NEWCONF.to_string()));
        }
        let offsets_before = self.offsets_mark();
        let selection = {
            let sys = sys_view!(self, cfg);
            transform::selection::selection(block, |e| {
                eval::eval_f64(e, &eval::scope::Ctx { vars: &self.vars, sys: &sys }, line)
            })?
        };
        self.apply_transformation(selection, block, base_cfg, line)?;
        let derived = self.trafo.config();
        let cfg = derived.as_deref().unwrap_or(base_cfg);
        // Smooth approach runs its fast infeed at the velocity before the block.
        let sar_before = words.sar.contour.and_then(|_| self.path_feed(line).ok());
        self.modal.apply(words, cfg, line)?;
        if let Some(op) = &words.capture {
            self.capture_op(op, line)?;
        }
        if words.work_offset.is_some() {
            // G500/G54...: the stored settable frame replaces one a program wrote to $P_IFRAME.
            *self.iframe = None;
        }
        self.refresh_gcodes();
        if let Some(f) = words.feed.filter(|_| !words.dwell) {
            self.modal.feed = Some(f);
        }
        if let Some(spindle) = words.set_master {
            self.spindles.set_master(spindle, cfg, line)?;
        }
        self.select_tool(words, cfg, programs, line, out)?;
        if let Some(op) = words.frame_op {
            self.frame_instruction(op, words, cfg, line)?;
        }
        for (which, f) in &words.frame_writes {
            self.write_chain_frame(*which, f.clone());
        }
        self.holder_block(words, cfg, line, out)?;
        self.refresh_offsets(cfg);
        self.absorb_tool_into_transformation();
        self.online_tool_offset(&words.toff, cfg);

        // Spindle before motion (feed type, speeds, directions, SPOS).
        let positioned = self.spindle_block(words, cfg, line, out)?;

        // M and H functions and digital outputs before the motion (see `auxiliary.rs`).
        for function in words.aux.iter().filter(|f| !f.is_program_control()) {
            self.trc.emit_or_defer(Item::Aux { function: *function, line }, out);
        }
        for &(signal, on) in &words.digital_outputs {
            self.trc.emit_or_defer(Item::DigitalOutput { signal, on, line }, out);
        }
        for &write in &words.main_run_writes {
            self.trc.emit_or_defer(Item::MainRunWrite { write, line }, out);
        }
        for &(axis, position) in &words.presets {
            // The blocks after it are prepared from the new machine position (`frames/preset.rs`).
            self.pos[axis] = position;
            self.lane_memo.forget();
            self.trc.emit_or_defer(
                Item::MainRunWrite { write: synchronized::MainRunWrite::Preset(axis, position), line },
                out,
            );
        }
        if let Some(sp) = words.set_piece {
            // The tools are in the master spindle's holder: another spindle used none.
            let axis = match sp.spindle {
                Some(n) => Some(spindles::axis_of(cfg, n, line, "SETPIECE")?),
                None => self.spindles.master(),
            };
            if axis.is_none() || axis == self.spindles.master() {
                self.trc.emit_or_defer(Item::SetPiece { pieces: sp.pieces, line }, out);
            }
        }
        // Positioning axes start at the block's start (POS, POSA); WAITP.
        let pos_axes = self.positioning_block(words, cfg, line, out)?;
        if !words.oscillation.is_empty() {
            self.oscillation_block(words, cfg, line, out)?;
        }
        // MEAS/MEAW: the request goes before the block's move (`measuring.rs`).
        self.measure_request(words.measure, line)?;
        let measure_mark = out.len();
        // The block moves on the path: a modal call (MCALL) follows it.
        let mut path_motion = false;
        if words.dwell {
            let seconds = match (words.feed, words.speed) {
                (Some(f), None) => f,
                (None, Some(revs)) if self.dwell_speed(cfg) > 0.0 => revs * 60.0 / self.dwell_speed(cfg),
                (None, Some(_)) => return Err(Alarm::value_out_of_range(line, "G4 S (spindle stands)")),
                _ => return Err(Alarm::syntax(line, "G4 needs F<seconds> or S<revolutions>")),
            };
            if !(0.0..=1e6).contains(&seconds) {
                return Err(Alarm::value_out_of_range(line, &format!("G4 {} s", Alarm::shown(seconds))));
            }
            out.push(Item::Dwell { seconds, line });
        } else if let Some(upper) = words.spindle.work_area_limit(words) {
            // G25/G26 with axes and no S: working-area limits into the setting data.
            let lines =
                path_control::work_area::limit_lines(&self.stored, cfg, upper, &words.axes, self.modal.length_factor());
            self.data_writes.extend(lines.into_iter().map(|t| (line, t)));
        } else if let Some(approach) = words.fixed_point {
            self.fixed_point_block(approach, words, cfg, line, out)?;
        } else if let Some(reference) = words.pole {
            self.define_pole(reference, words, cfg, line)?;
        } else if words.frame_op.is_none() && !words.axes.is_empty()
            || self.angle_corner_end.is_some()
            || words.ori.moves()
            || words.polar()
            || (words.arc_params_given() && matches!(self.modal.motion, MotionMode::Cw | MotionMode::Ccw))
        {
            path_motion = true;
            // One set of limits for the move and its compensation (same configuration).
            let limits = AxisLimit::for_channel(cfg);
            let (mut mv, feed) = self.motion(words, cfg, &limits, line)?;
            if self.modal.spline.kind == Some(path_control::spline::Kind::Poly) {
                self.poly_move(&mut mv, words, cfg, &limits);
                // The polynomial may leave the range its end points keep to (or overflow).
                check_software_limits(cfg, &mv.path, line)?;
            }
            self.spindle_motion(&mut mv, words, cfg, &limits, line, out)?;
            self.request_point_to_point(mv.tag, mv.is_rapid(), words.stat, words.tu)?;
            let offsets = self.shared_offsets();
            // A captured contour is recorded as programmed: no compensation selected or held.
            let comp = if self.capture.is_some() { None } else { self.compensation(cfg, words, line)? };
            let sar = self.sar_request(words, cfg, &mv, comp.as_ref(), sar_before, line)?;
            self.trc.arm(sar);
            // A smooth approach without TRC runs with a compensation of radius 0.
            let comp = comp.or_else(|| self.trc.sar_compensation());
            let approach = self.modal.approach;
            // With compensation active a corner (RND, CHF) is shaped on the programmed contour.
            let corner = if comp.is_some() { self.corner_request.take() } else { None };
            if self.modal.spline.kind.is_some_and(|k| k != path_control::spline::Kind::Poly) {
                if comp.is_some() || self.offsets.trafo.is_some() {
                    return Err(Alarm::unknown_name(line, "spline with TRC or a transformation"));
                }
                self.spline_point(mv, words, line, offsets, cfg, out);
            } else if comp.is_none() && self.trc.idle() {
                // Nothing to compensate and nothing held: the move goes straight out (a G34/G35
                // thread in segments of its changing lead).
                match self.spindles.variable_lead.take() {
                    Some(lead) => lead.push_segments(mv, line, offsets, &limits, out),
                    None if self.rapid_apart(&mv, &offsets, cfg, line, out) => {}
                    None => out.push(Item::Move { mv, line, offsets }),
                }
                self.trc.passed(out);
            } else {
                let prepared = compensation::trc::Prepared { mv, feed, line, offsets, approach, corner };
                self.trc.push(prepared, comp, &limits, out)?;
            }
        } else if !positioned && self.offsets_mark() != offsets_before {
            // A new shared value is made only when the offsets differ from the last one.
            out.push(Item::Offsets { line, offsets: self.shared_offsets() });
        }
        self.end_positioning_block(pos_axes, line, out);

        self.measure_block_end(words.measure, measure_mark, line, out)?;
        if let Some(text) = &words.message {
            out.push(Item::Message { text: text.clone(), line });
        }
        if let Some(request) = words.workpiece {
            out.push(Item::Workpiece { request, offsets: self.shared_offsets(), line });
        }
        if let Some(alarm) = &words.user_alarm {
            out.push(Item::Alarm(calls::cycle_alarm::at_call(alarm, &self.calls)));
        }
        if let Some(kind) = words.stop {
            // M0/M1/M2/M17/M30 reach the PLC with their stop, after the motion.
            for function in words.aux.iter().filter(|f| f.is_program_control()) {
                out.push(Item::Aux { function: *function, line });
            }
            out.push(Item::Stop { kind, line });
        }
        if let Some(goto) = &words.goto {
            self.jump(goto, cfg, line, out)?;
        }
        if !path_motion && words.sar.contour.is_some() {
            // A SAR approach block without motion: the next motion block ends at P4 (with TRC
            // selected, which keeps that block off the fast lane); anything else: 10744.
            if self.modal.trc.is_none() || words.sar.contour.is_some_and(|c| c.1) {
                return Err(Alarm::sar_direction(line));
            }
            self.trc.defer_sar(words.sar, sar_before);
        }
        self.block_calls(words, path_motion, programs, cfg, line)
    }

    /// Where the word `value` (with its `AC`/`IC`/`DC`/`ACP`/`ACN` mode, if any) sends channel
    /// axis `k` in the WCS: inch or metric, G90/G91, diameter programming, a modulo axis's
    /// way; an increment counts from `incremental_from`, a modulo target from `current`.
    #[inline]
    pub(crate) fn axis_word_target(
        &self,
        cfg: &MachineConfig,
        k: usize,
        (value, mode): (f64, Option<CoordMode>),
        current: f64,
        incremental_from: f64,
        line: u32,
    ) -> Result<f64, Alarm> {
        let ax = cfg.axis(k);
        let v = if ax.rotary { value } else { value * self.modal.length_factor() };
        let absolute = match mode {
            Some(CoordMode::Ac) => true,
            Some(CoordMode::Ic) => false,
            Some(CoordMode::Dc | CoordMode::Acp | CoordMode::Acn) if ax.modulo.is_none() => {
                return Err(Alarm::value_out_of_range(
                    line,
                    &format!("{}: DC/ACP/ACN need a modulo rotary axis", cfg.program_axis_name(k)),
                ));
            }
            Some(_) => true,
            None => self.modal.absolute,
        };
        let v = v * self.spindles.diameter.factor(cfg, k, absolute);
        Ok(match (ax.modulo, absolute) {
            (Some((mstart, range)), true) => {
                let wrapped = mstart + (v - mstart).rem_euclid(range);
                modulo_target(current, wrapped, range, mode)
            }
            (_, true) => v,
            (_, false) => incremental_from + v,
        })
    }

    /// TRANS/ROT/SCALE/MIRROR replace the programmable frame; ATRANS/AROT/ASCALE/AMIRROR add
    /// to it in the current (already transformed) system. The block's axis words are the
    /// instruction's values.
    fn frame_instruction(
        &mut self,
        op: FrameOp,
        words: &modal::Words,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let geo = &cfg.geo_axes;
        let geo_index = |k: usize| geo.iter().position(|g| *g == Some(k));
        let g = match op.kind {
            FrameKind::Trans => {
                let mut t = [0.0; MAX_CHANNEL_AXES];
                for &(k, v, _) in &words.axes {
                    t[k] = if cfg.axis(k).rotary { v } else { v * self.modal.length_factor() };
                }
                Frame::translation(t)
            }
            FrameKind::Rot => {
                if let Some(angle) = words.rpl {
                    let (_, _, applicate) = self.modal.plane.axes();
                    Frame::rotation(frames::frame::about_axis(applicate, angle))
                } else {
                    let mut angles = [0.0; 3];
                    for &(k, v, _) in &words.axes {
                        let g = geo_index(k).ok_or_else(|| {
                            Alarm::value_out_of_range(
                                line,
                                &format!("ROT about {}: only geometry axes rotate", cfg.program_axis_name(k)),
                            )
                        })?;
                        angles[g] = v;
                    }
                    Frame::rotation(frames::frame::rotation_of(cfg.frame_angles, angles))
                }
            }
            FrameKind::Rots => {
                let mut angles = Vec::new();
                for &(k, v, _) in &words.axes {
                    let g = geo_index(k).ok_or_else(|| {
                        Alarm::value_out_of_range(
                            line,
                            &format!("ROTS about {}: only geometry axes rotate", cfg.program_axis_name(k)),
                        )
                    })?;
                    angles.push((g, v));
                }
                if angles.is_empty() {
                    Frame::identity()
                } else {
                    let r = frames::solid_angles::rotation(&angles)
                        .map_err(|what| Alarm::value_out_of_range(line, &format!("ROTS: {what}")))?;
                    Frame::rotation(r)
                }
            }
            FrameKind::Scale => {
                let factors: Vec<(usize, f64)> = words.axes.iter().map(|&(k, v, _)| (k, v)).collect();
                if factors.iter().any(|&(_, f)| f == 0.0) {
                    return Err(Alarm::value_out_of_range(line, "SCALE factor 0"));
                }
                Frame::scaling(geo, &factors)
            }
            FrameKind::Mirror => {
                let factors: Vec<(usize, f64)> = words.axes.iter().map(|&(k, _, _)| (k, -1.0)).collect();
                Frame::scaling(geo, &factors)
            }
        };
        *self.pframe = if op.additive { self.pframe.then(&g, geo) } else { g };
        Ok(())
    }

    /// G110/G111/G112 with the working-plane coordinates of the pole.
    fn define_pole(
        &mut self,
        reference: PoleRef,
        words: &modal::Words,
        cfg: &MachineConfig,
        line: u32,
    ) -> Result<(), Alarm> {
        let geo = &cfg.geo_axes;
        let (pa, po, _) = self.modal.plane.axes();
        let (Some(ka), Some(ko)) = (geo[pa], geo[po]) else {
            return Err(Alarm::value_out_of_range(line, "pole in a plane without both geometry axes"));
        };
        let basic = self.basic_position();
        let current = self.offsets.frame.unapply(geo, &basic).unwrap_or(basic);
        let base = match reference {
            PoleRef::LastPosition => (current[ka], current[ko]),
            PoleRef::WorkpieceZero => (0.0, 0.0),
            PoleRef::LastPole => self.modal.pole,
        };
        let f = self.modal.length_factor();
        let value = |k: usize| words.axes.iter().find(|(a, _, _)| *a == k).map_or(0.0, |(_, v, _)| v * f);
        self.modal.pole = (base.0 + value(ka), base.1 + value(ko));
        Ok(())
    }

    /// The radius compensation for the block's move: side and corner mode from G41/G42 and
    /// G450/G451, radius from the active cutting edge (geometry + wear) plus OFFN, plane from
    /// the working plane through the active frame.
    ///
    /// With TRACYL's groove-wall offset the programmed path is the groove centre line and OFFN
    /// half the groove width: the tool runs at `|OFFN| − r` from it, on the G41/G42 side (the
    /// other side for a negative OFFN). A tool wider than the groove is refused.
    fn compensation(
        &self,
        cfg: &MachineConfig,
        words: &modal::Words,
        line: u32,
    ) -> Result<Option<compensation::trc::Compensation>, Alarm> {
        let Some(mut side) = self.modal.trc else { return Ok(None) };
        let edge = cfg.edge(self.offsets.t, self.offsets.d);
        let Some(edge) = edge else { return Err(Alarm::trc_without_tool(line)) };
        let tool_radius = edge[5] + edge[14] + self.modal.tool_offsets.radius;
        let tip = compensation::cutting_edge::tip_offset(edge[0], edge[1], tool_radius);
        let groove_wall = self.groove_wall_axes();
        let offn = self.modal.offn;
        let radius = match groove_wall {
            None => tool_radius + offn,
            Some(_) if offn.abs() < tool_radius => {
                return Err(Alarm::value_out_of_range(
                    line,
                    &format!("groove-wall offset: tool radius {tool_radius} is larger than OFFN={offn}"),
                ));
            }
            Some(_) => {
                if offn < 0.0 {
                    side = side.opposite();
                }
                offn.abs() - tool_radius
            }
        };
        let frame = self.block_frame(words, cfg);
        let (pa, po, _) = self.modal.plane.axes();
        let unit = |v: AxisVec| {
            let n = norm(&v);
            if n > 0.0 { v.map(|x| x / n) } else { v }
        };
        let (mut u, mut v) = (frame.geo_direction(&cfg.geo_axes, pa), frame.geo_direction(&cfg.geo_axes, po));
        // CUT2D/CUT3DFS: a holder that turns the tool turns the compensation plane with it
        // (seeds/004); CUT2DF/CUT3DFF keep the plane of the frame.
        if let Some(c) = self.carrier(cfg).filter(|_| self.holder.cut.follows_holder())
            && c.kind != crate::machine_data::CarrierKind::Part
        {
            let turned = |g: usize| {
                let e = kinematics::orient::vec3::unit(g);
                let d = tools::toolholder::machine_orientation(c, self.holder.angles, e);
                let mut out = [0.0; MAX_CHANNEL_AXES];
                for (i, k) in cfg.geo_axes.iter().enumerate() {
                    if let Some(k) = k {
                        out[*k] = d[i];
                    }
                }
                out
            };
            if (0..3).any(|g| {
                tools::toolholder::machine_orientation(c, self.holder.angles, kinematics::orient::vec3::unit(g))
                    != kinematics::orient::vec3::unit(g)
            }) {
                (u, v) = (turned(pa), turned(po));
            }
        }
        Ok(Some(compensation::trc::Compensation {
            side,
            radius,
            corners: self.modal.trc_corners,
            disc: self.modal.disc,
            arc_feed: self.modal.arc_feed,
            u: unit(u),
            v: unit(v),
            tip: if groove_wall.is_some() { (0.0, 0.0) } else { tip },
            max_dummy_blocks: cfg.cutcom_max_dummy_blocks,
            max_check_blocks: cfg.cutcom_max_check_blocks,
            corner_limit: cfg.cutcom_corner_limit,
            collision_detection: self.modal.collision_detection,
            groove_wall,
        }))
    }

    fn motion(
        &mut self,
        words: &modal::Words,
        cfg: &MachineConfig,
        limits: &[AxisLimit],
        line: u32,
    ) -> Result<(Move, Feed), Alarm> {
        let n = cfg.channel_axes.len();
        let geo = &cfg.geo_axes;
        let start = self.pos;
        let tool = self.offsets.tool;
        // G53/G153/SUPA: frames suppressed for this block (borrowed, not copied, without).
        let frame = match words.suppress {
            None => std::borrow::Cow::Borrowed(&self.offsets.frame),
            some => std::borrow::Cow::Owned(sys_view!(self, cfg).chain(some)),
        };
        let mut basic = start;
        for k in 0..n {
            basic[k] -= tool[k];
        }
        let current =
            frame.unapply(geo, &basic).ok_or_else(|| Alarm::value_out_of_range(line, "frame with scale 0"))?;
        // After a change of frame or tool offset, increments count from the position programmed
        // before it (SD42440/SD42442).
        let incremental_from =
            frames::incremental::incremental_start(self.before_change.take(), cfg, &frame, &tool, &start)
                .unwrap_or(current);
        let mut target = current;
        let mut programmed = [false; MAX_CHANNEL_AXES];
        for &(k, value, mode) in &words.axes {
            target[k] = self.axis_word_target(cfg, k, (value, mode), current[k], incremental_from[k], line)?;
            programmed[k] = true;
        }
        // Polar coordinates: the working-plane end point from the pole, angle AP and radius RP.
        let (pa, po, papp) = self.modal.plane.axes();
        let plane = (geo[pa], geo[po]);
        if words.polar() {
            let (Some(ka), Some(ko)) = plane else {
                return Err(Alarm::value_out_of_range(line, "polar coordinates in a plane without both geometry axes"));
            };
            let ap = words.ap.unwrap_or(self.modal.polar.0);
            let rp = words.rp.map(|r| r * self.modal.length_factor()).unwrap_or(self.modal.polar.1);
            if rp < 0.0 {
                return Err(Alarm::value_out_of_range(line, &format!("RP={rp}")));
            }
            self.modal.polar = (ap, rp);
            let pole = self.modal.pole;
            target[ka] = pole.0 + rp * ap.to_radians().cos();
            target[ko] = pole.1 + rp * ap.to_radians().sin();
            programmed[ka] = true;
            programmed[ko] = true;
        }

        if let (Some(end), (Some(ka), Some(ko))) = (self.angle_corner_end.take(), plane) {
            // The first block of a two-block contour definition runs to the corner.
            (target[ka], target[ko]) = end;
            (programmed[ka], programmed[ko]) = (true, true);
        } else if let Some(ang) = words.ang {
            let (Some(ka), Some(ko)) = plane else {
                return Err(Alarm::value_out_of_range(line, "ANG= in a plane without both geometry axes"));
            };
            let given = (programmed[ka].then_some(target[ka]), programmed[ko].then_some(target[ko]));
            (target[ka], target[ko]) = contour::angle_line::end_point((current[ka], current[ko]), given, ang, line)?;
            (programmed[ka], programmed[ko]) = (true, true);
        }
        // The circle in the WCS plane (it may decide the end point: centre plus AR=); a CIP
        // circle outside it lies in space.
        let mut space_circle = None;
        let circle = match self.modal.motion {
            MotionMode::Cw | MotionMode::Ccw if self.modal.circle_form == CircleForm::ThroughPoint => {
                let (Some(ka), Some(ko)) = plane else {
                    return Err(Alarm::value_out_of_range(line, "circle in a plane without both geometry axes"));
                };
                let axes = [Some(ka), Some(ko), geo[papp]];
                let at = |p: &AxisVec| axes.map(|k| k.map_or(0.0, |k| p[k]));
                let start = at(&current);
                let mid = contour::through_point::intermediate(
                    &words.ijk1,
                    (pa, po, papp),
                    start,
                    self.modal.absolute,
                    self.modal.length_factor(),
                );
                let through = contour::through_point::circle(start, mid, at(&target))
                    .map_err(|_| Alarm::circle_end_point(line))?;
                match through {
                    contour::through_point::ThroughPoint::InPlane(c, turn) => {
                        self.modal.motion =
                            if turn == contour::arc::Turn::Clockwise { MotionMode::Cw } else { MotionMode::Ccw };
                        Some(c)
                    }
                    contour::through_point::ThroughPoint::Oblique(c) => {
                        if self.modal.trc.is_some() || self.capture.is_some() {
                            let why = if self.capture.is_some() { "in a captured contour" } else { "with G41/G42" };
                            return Err(Alarm::value_out_of_range(
                                line,
                                &format!("CIP circle out of the working plane {why}"),
                            ));
                        }
                        space_circle = Some(c);
                        None
                    }
                }
            }
            MotionMode::Cw | MotionMode::Ccw if self.modal.circle_form == CircleForm::Tangent => {
                let (Some(ka), Some(ko)) = plane else {
                    return Err(Alarm::value_out_of_range(line, "circle in a plane without both geometry axes"));
                };
                let tangent = self.last_move.end_direction().ok_or_else(|| Alarm::circle_end_point(line))?;
                let (c, turn) =
                    contour::tangent_circle::circle((current[ka], current[ko]), (target[ka], target[ko]), tangent)
                        .map_err(|_| Alarm::circle_end_point(line))?;
                self.modal.motion =
                    if turn == contour::arc::Turn::Clockwise { MotionMode::Cw } else { MotionMode::Ccw };
                Some(contour::arc::with_turns(c, words.turn.unwrap_or(0)))
            }
            MotionMode::Cw | MotionMode::Ccw => {
                let (Some(ka), Some(ko)) = plane else {
                    return Err(Alarm::value_out_of_range(line, "circle in a plane without both geometry axes"));
                };
                let turn = arc_turn(self.modal.motion);
                let f = self.modal.length_factor();
                let s = (current[ka], current[ko]);
                let e = (target[ka], target[ko]);
                let center = words.center(pa, po).map(|(i, j)| arc_center(s, i, j, f));
                let end_given = programmed[ka] || programmed[ko];
                let c = match (words.cr, words.ar, center) {
                    _ if words.polar() => contour::arc::from_center(s, e, self.modal.pole, turn),
                    (Some(cr), _, _) => contour::arc::from_radius(s, e, cr * f, turn),
                    (None, Some(ar), Some(c)) if !end_given => {
                        contour::arc::from_center_and_angle(s, c, ar, turn).map(|(circle, end)| {
                            target[ka] = end.0;
                            target[ko] = end.1;
                            programmed[ka] = true;
                            programmed[ko] = true;
                            circle
                        })
                    }
                    (None, Some(ar), _) => contour::arc::from_end_and_angle(s, e, ar, turn),
                    (None, None, Some(c)) => contour::arc::from_center(s, e, c, turn),
                    (None, None, None) => return Err(Alarm::circle_end_point(line)),
                }
                .map_err(|_| Alarm::circle_end_point(line))?;
                Some(contour::arc::with_turns(c, words.turn.unwrap_or(0)))
            }
            _ => None,
        };

        if let (Some(ka), Some(ko)) = plane {
            self.last_move.record((current[ka], current[ko]), (target[ka], target[ko]), circle.as_ref());
        }
        if let (Some(capture), (Some(ka), Some(ko))) = (self.capture.as_mut(), plane) {
            let center = circle.as_ref().map(|c| c.center);
            capture.record(self.modal.motion, (current[ka], current[ko]), (target[ka], target[ko]), center);
        }
        let mut end = block_end(&frame, geo, n, &start, &tool, &target, &mut programmed);

        if let Some(kind) = words.oblique {
            self.oblique_plunge(kind, &start, &mut end, line)?;
        }
        let tangent = end_tangent(&current, &target, geo, (pa, po, papp), circle.as_ref());
        let ori = self.orientation_block(words, cfg, &frame, &start, &mut end, tangent, line)?;
        self.modal.ori.last_change = ori.as_ref().and_then(OriPath::end_direction);
        self.modal.ori.upper = ori.as_ref().and_then(|o| o.curve).map(|c| c.upper[1]);
        if let Some(theta) = self.tool_rotation(words, &frame, &start, &mut end, tangent, line)? {
            self.modal.ori.theta = theta;
        }

        let (mut path, mut length) =
            block_path(&frame, geo, (pa, po, papp), &start, &end, &current, &target, circle.as_ref());
        if let Some(c) = &space_circle {
            length = oblique_arc(&mut path, &frame, geo, (pa, po, papp), c);
        }
        path.ori = ori.map(Box::new);
        if let Some(o) = self.orientation_on_arc(words, cfg, &frame, &path) {
            self.modal.ori.last_change = o.end_direction();
            path.ori = Some(Box::new(o));
        }
        let length = feed_length(&path, length, n);
        let length = self.modal.feed_group.as_ref().map_or(length, |g| g.path_length(&path, length, cfg));

        check_software_limits(cfg, &path, line)?;
        if !self.modal.walimof {
            let area = self.work_area.get_or_insert_with(|| path_control::work_area::WorkArea::of(&self.stored, cfg));
            if let Some(area) = area {
                area.check(cfg, &path, &tool, line)?;
            }
        }

        // A captured contour's move does not run: it needs no feed.
        let feed = if self.capture.is_some() { Feed::Rapid } else { self.path_feed(line)? };
        let exact_stop = self.modal.exact_stop || words.g9;
        self.pos = end;
        let mut mv = Move::new(path, length, feed, limits, exact_stop, line);
        if !exact_stop {
            mv.blend = self.modal.path.blend(false, matches!(feed, Feed::Rapid), cfg);
            mv.compress = self.modal.path.compress(cfg);
            mv.orison = self.modal.path.orison(cfg).map(Box::new);
        }
        Ok((mv, feed))
    }
}

impl Interpreter {
    /// The feed of a block's move from the modal state: rapid traverse under G0, else F in
    /// mm/s (alarm 10860 without F, 14800 for a feed that is not positive).
    fn path_feed(&self, line: u32) -> Result<Feed, Alarm> {
        Ok(match self.modal.motion {
            MotionMode::Rapid => Feed::Rapid,
            // A thread's feed comes from its lead (`spindles/motion.rs`).
            _ if self.spindles.thread.is_some() => Feed::Path(1.0),
            _ => {
                let f = self.modal.feed.ok_or_else(|| Alarm::no_feed(line))?;
                let mut per_min = if self.modal.feed_per_rev { f * self.spindles.reference_speed() } else { f }
                    * self.modal.feed_factor();
                if let Some(dry) = &self.program_control.dry_run {
                    per_min = dry.path_feed(per_min);
                }
                if per_min <= 0.0 {
                    return Err(Alarm::feed_not_positive(line));
                }
                Feed::Path(per_min / 60.0)
            }
        })
    }
}

/// G2 turns clockwise, G3 counter-clockwise (seen from the applicate's positive side).
fn arc_turn(motion: MotionMode) -> contour::arc::Turn {
    if motion == MotionMode::Cw { contour::arc::Turn::Clockwise } else { contour::arc::Turn::CounterClockwise }
}

/// The circle centre from I/J/K (`(value, absolute)` per plane axis, in program units times
/// `f`): incremental from the start point `s`, or absolute with `=AC(..)`.
fn arc_center(s: (f64, f64), (ia, abs_a): (f64, bool), (io, abs_o): (f64, bool), f: f64) -> (f64, f64) {
    (if abs_a { ia * f } else { s.0 + ia * f }, if abs_o { io * f } else { s.1 + io * f })
}

/// The block's end point in channel axes: the WCS `target` through the frame plus the tool
/// length for the axes the block programs, `start` for the others. With a rotation in the
/// frame a programmed geometry axis moves the others too (`programmed` is widened to say so).
fn block_end(
    frame: &Frame,
    geo: &[Option<usize>; 3],
    n: usize,
    start: &AxisVec,
    tool: &AxisVec,
    target: &AxisVec,
    programmed: &mut [bool; MAX_CHANNEL_AXES],
) -> AxisVec {
    let any_geo = geo.iter().flatten().any(|&k| programmed[k]);
    if any_geo && frame.couples_axes() {
        for &k in geo.iter().flatten() {
            programmed[k] = true;
        }
    }
    let target_basic = frame.apply(geo, target);
    let mut end = *start;
    for k in 0..n {
        if programmed[k] {
            end[k] = target_basic[k] + tool[k];
        }
    }
    end
}

/// The block's path from `start` to `end` (a line, or the WCS `circle` mapped through the
/// frame) and the length of its geometry-axis part, which the feed refers to.
#[allow(clippy::too_many_arguments)]
fn block_path(
    frame: &Frame,
    geo: &[Option<usize>; 3],
    (pa, po, papp): (usize, usize, usize),
    start: &AxisVec,
    end: &AxisVec,
    current: &AxisVec,
    target: &AxisVec,
    circle: Option<&contour::arc::Circle>,
) -> (Path, f64) {
    let mut path = Path::line(*start, *end);
    let length = shape_path(&mut path, frame, geo, (pa, po, papp), current, target, circle);
    (path, length)
}

/// [`block_path`] on a line `path` already made from start to end (the fast lane builds it in
/// place): adds the circle and returns the length the feed refers to.
fn shape_path(
    path: &mut Path,
    frame: &Frame,
    geo: &[Option<usize>; 3],
    (pa, po, papp): (usize, usize, usize),
    current: &AxisVec,
    target: &AxisVec,
    circle: Option<&contour::arc::Circle>,
) -> f64 {
    let (start, end) = (&path.start, &path.end);
    let mut length = geo.iter().flatten().map(|&k| (end[k] - start[k]).powi(2)).sum::<f64>().sqrt();
    if let Some(circle) = circle {
        // The circle is defined in the WCS plane and mapped through the frame.
        let u = frame.geo_direction(geo, pa);
        let v = frame.geo_direction(geo, po);
        // Without rotation, scale or mirror the image of a configured geometry axis' unit
        // vector is that unit vector: its norm is 1 exactly, no square root needed.
        let unmoved = frame.linear_is_identity();
        let norm_of = |g: usize, image: &AxisVec| if unmoved && geo[g].is_some() { 1.0 } else { norm(image) };
        let scale = (norm_of(pa, &u) + norm_of(po, &v)) / 2.0;
        let helix = geo[papp].map_or(0.0, |k| {
            let lead = target[k] - current[k];
            if unmoved { lead } else { lead * norm(&frame.geo_direction(geo, papp)) }
        });
        path.arc =
            Some(Box::new(Arc { u, v, radius: circle.radius, start_angle: circle.start_angle, sweep: circle.sweep }));
        length = ((circle.radius * circle.sweep * scale).powi(2) + helix * helix).sqrt();
    }
    length
}

/// Puts the CIP circle `c` (lying obliquely in the WCS, coordinates of the plane's abscissa,
/// ordinate and applicate) on the line `path` from its start to its end, mapped through the
/// frame; returns its length.
fn oblique_arc(
    path: &mut Path,
    frame: &Frame,
    geo: &[Option<usize>; 3],
    (pa, po, papp): (usize, usize, usize),
    c: &contour::through_point::SpaceCircle,
) -> f64 {
    let dirs = [pa, po, papp].map(|g| frame.geo_direction(geo, g));
    let image = |w: [f64; 3]| -> AxisVec { std::array::from_fn(|k| (0..3).map(|i| w[i] * dirs[i][k]).sum()) };
    let (u, v) = (image(c.u), image(c.v));
    let scale = (norm(&u) + norm(&v)) / 2.0;
    path.arc = Some(Box::new(Arc { u, v, radius: c.radius, start_angle: 0.0, sweep: c.sweep }));
    c.radius * c.sweep * scale
}

/// The length the feed refers to: the geometry axes' `length`, or when no geometry axis
/// moves the other axes together, or the angle the orientation turns through (degrees) when
/// it is interpolated as a vector.
fn feed_length(path: &Path, length: f64, n: usize) -> f64 {
    if length < 1e-9 {
        match &path.ori {
            Some(o) if o.angle.abs() > 1e-12 => o.angle.abs().to_degrees(),
            // Also a constant orientation held on the workpiece the 7th axis turns.
            _ => (0..n).map(|k| (path.end[k] - path.start[k]).powi(2)).sum::<f64>().sqrt(),
        }
    } else {
        length
    }
}

/// The unit direction of travel at the end of a block in the WCS geometry axes (X, Y, Z): along
/// the line, or along the circle at its end angle with the helix lead. `None` without a move of
/// the geometry axes.
fn end_tangent(
    current: &AxisVec,
    target: &AxisVec,
    geo: &[Option<usize>; 3],
    (pa, po, papp): (usize, usize, usize),
    circle: Option<&contour::arc::Circle>,
) -> Option<[f64; 3]> {
    let delta = |g: usize| geo[g].map_or(0.0, |k| target[k] - current[k]);
    let mut t = [0.0; 3];
    match circle {
        Some(c) => {
            let (a1, turn) = (c.start_angle + c.sweep, c.sweep.signum());
            t[pa] = -a1.sin() * turn;
            t[po] = a1.cos() * turn;
            t[papp] = delta(papp) / (c.radius * c.sweep.abs()).max(1e-12);
        }
        None => t = [delta(0), delta(1), delta(2)],
    }
    let n = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
    (n > 1e-12).then(|| t.map(|x| x / n))
}

fn norm(v: &AxisVec) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Target of a modulo rotary axis: shortest way (G90, DC), or forced direction (ACP, ACN).
pub(crate) fn modulo_target(current: f64, target: f64, range: f64, mode: Option<CoordMode>) -> f64 {
    let delta = (target - current).rem_euclid(range);
    match mode {
        Some(CoordMode::Acp) => current + delta,
        Some(CoordMode::Acn) => current + delta - if delta > 0.0 { range } else { 0.0 },
        _ if delta > range / 2.0 => current + delta - range,
        _ => current + delta,
    }
}

/// Alarm 10720 when any point of the path lies beyond a software limit switch.
fn check_software_limits(cfg: &MachineConfig, path: &Path, line: u32) -> Result<(), Alarm> {
    // The exact extremes of an arc (trigonometry per axis) only for axes near a limit.
    let mut exact: Option<(AxisVec, AxisVec)> = None;
    for k in 0..cfg.channel_axes.len() {
        let ax = cfg.axis(k);
        if ax.modulo.is_some() || ax.spindle.is_some() {
            continue;
        }
        let (s, e) = (path.start[k], path.end[k]);
        let moves = (e - s).abs() > 1e-12 || path.arc.as_ref().is_some_and(|a| a.moves_axis(k)) || path.curve.is_some();
        if !moves {
            continue;
        }
        let (lo, hi) = match &path.arc {
            None if path.curve.is_none() => (s.min(e), s.max(e)),
            None => {
                // A curve (POLY) may run out between its end points: its sampled extent.
                let (lo, hi) = exact.get_or_insert_with(|| path.extent());
                (lo[k], hi[k])
            }
            Some(a) => {
                // Every point of the arc lies within |e − s| + 4·r·ρ of its start (ρ: the
                // circle's share in this axis): the linear part is at most |e − s| plus a
                // chord, and the circle adds at most a diameter.
                let rho = (a.u[k] * a.u[k] + a.v[k] * a.v[k]).sqrt();
                let reach = (e - s).abs() + 4.0 * a.radius.abs() * rho;
                if s + reach <= ax.limit_plus + 1e-9 && s - reach >= ax.limit_minus - 1e-9 {
                    continue;
                }
                let (lo, hi) = exact.get_or_insert_with(|| path.extent());
                (lo[k], hi[k])
            }
        };
        // Written to be true for a NaN extent too (a curve whose coefficients overflow).
        if hi.is_nan() || hi > ax.limit_plus + 1e-9 {
            return Err(Alarm::software_limit(line, &ax.name, true));
        }
        if lo.is_nan() || lo < ax.limit_minus - 1e-9 {
            return Err(Alarm::software_limit(line, &ax.name, false));
        }
    }
    Ok(())
}

impl Interpreter {
    /// `$P_ACTFRAME`: the whole frame chain (see `frame_vars.rs`), from the BCS towards the WCS;
    /// rebuilt only when an input changed (see `frame_cache.rs`).
    fn active_frame(&mut self, cfg: &MachineConfig) -> Frame {
        // Each mark is taken (not short-circuited) so that all three are cleared.
        let changed = [self.pframe.take_changed(), self.system.take_changed(), self.iframe.take_changed()];
        let (work_offset, rotary_slot) = (self.modal.work_offset, self.trafo.rotary_slot());
        self.frame_cache
            .get(cfg, work_offset, rotary_slot, changed.contains(&true), || sys_view!(self, cfg).chain(None))
            .clone()
    }

    /// Where block preparation stands less the active tool offset (the BCS point the frames
    /// map into the WCS).
    fn basic_position(&self) -> AxisVec {
        let mut basic = self.pos;
        for (b, t) in basic.iter_mut().zip(&self.offsets.tool) {
            *b -= t;
        }
        basic
    }

    /// The frame a block's positions go through: the active frame, or what G53 (settable,
    /// programmable and the system frames above the basic frame suppressed) or G153/SUPA (every
    /// frame suppressed) leave of it.
    fn block_frame(&self, words: &modal::Words, cfg: &MachineConfig) -> Frame {
        match words.suppress {
            None => self.offsets.frame.clone(),
            some => sys_view!(self, cfg).chain(some),
        }
    }
}

/// Settable frame `frame` (0 = G500).
pub(super) fn work_offset(cfg: &MachineConfig, frame: usize) -> Frame {
    cfg.work_offsets.get(frame).map_or_else(Frame::identity, |f| Frame::from_data(f, &cfg.geo_axes, cfg.frame_angles))
}

/// The total basic frame `$P_ACTBFRAME`: the NCU-global basic frames, then the channel basic
/// frames, each chained in order.
pub(super) fn basic_frame(cfg: &MachineConfig) -> Frame {
    // Neutral basic frames (the usual case) add nothing to the chain: skipped unbuilt.
    let frames: Vec<Frame> = cfg
        .ncu_base_frames
        .iter()
        .chain(&cfg.base_frames)
        .filter(|f| !f.is_neutral())
        .map(|f| Frame::from_data(f, &cfg.geo_axes, cfg.frame_angles))
        .collect();
    frames::frame::chain(&frames.iter().collect::<Vec<_>>(), &cfg.geo_axes)
}

/// Tool length vector per channel axis: lengths L1..L3 (geometry + wear + adapter) mapped to the
/// geometry axes by tool type and plane (SD42940 = 0).
fn tool_vector(cfg: &MachineConfig, modal: &Modal, t: u32, d: u32) -> AxisVec {
    let mut v = [0.0; MAX_CHANNEL_AXES];
    let Some(p) = cfg.edge(t, d) else { return v };
    let lengths = [p[2] + p[11] + p[20], p[3] + p[12] + p[21], p[4] + p[13] + p[22]];
    let turning = (400.0..600.0).contains(&p[0]);
    // Geometry axis (0 = 1st) that receives L1, L2, L3.
    let map: [usize; 3] = match (turning, modal.plane) {
        (false, Plane::G17) => [2, 1, 0],
        (false, Plane::G18) => [1, 0, 2],
        (false, Plane::G19) => [0, 2, 1],
        (true, Plane::G17) => [1, 0, 2],
        (true, Plane::G18) => [0, 2, 1],
        (true, Plane::G19) => [2, 1, 0],
    };
    let programmed = &modal.tool_offsets;
    for ((l, extra), g) in lengths.iter().zip(programmed.lengths).zip(map) {
        if let Some(k) = cfg.geo_axes[g] {
            v[k] += l + extra;
        }
    }
    for (g, extra) in programmed.axes.iter().enumerate() {
        if let Some(k) = cfg.geo_axes[g] {
            v[k] += extra;
        }
    }
    v
}
