//! One NC channel: modes, program control, JOG, MDA, alarms, and the snapshot of its state.
//!
//! Input: commands ([`Channel::run_program`], [`Channel::start`], [`Channel::jog`], ...) and
//! [`Channel::step`], one IPO cycle each. Output: [`Snapshot`]s and [`Event`]s. Block preparation
//! runs ahead of the main run by up to [`LOOKAHEAD`] items, as on the real control.
//!
//! Submodules: `main_run` (preparation, planner feeding, actions, stop/end/alarms), `jog`,
//! `repos` (JOG in an interrupted program and the return to it), `search` (block search with
//! calculation), `reference` (reference point state per axis), `programs` (stored programs),
//! `spindle`, `trafo` (the active transformation per IPO cycle), `snapshot`.

pub mod action_log;
mod active_program;
mod command_axes;
mod counters;
mod exact_stop;
mod io;
mod jog;
pub mod limit_watch;
mod main_run;
mod oscillation;
mod pending;
mod positioning_axes;
mod probe;
mod program_sync;
mod programs;
mod reference;
mod repos;
mod resume;
mod search;
pub mod servo;
mod set_wo;
mod smoothing;
mod snapshot;
mod snapshot_refresh;
mod spindle;
pub mod standstill;
mod stock;
pub mod sync;
mod tools;
mod trafo;
pub mod workpiece_tip;

use std::collections::VecDeque;
use std::sync::Arc;

pub use active_program::{ActiveProgram, CallLevel};
pub use counters::SavedCounters;
pub use jog::settings::OrientationJogKind;
pub use jog::{JOG_INCREMENTS, JogSystem};
pub use positioning_axes::{PositioningInfo, SavedPositioning};
pub use probe::{MAX_PROBE_TARGETS, ProbeTarget};
pub use reference::approach::ReferencePhase;
pub use repos::approach::ReposApproach;
pub use repos::modes::ReposMode;
pub use resume::{ResumeProgram, ResumeState, SavedInputs};
pub use search::{PathStep, SEARCH_ASK_EVERY, SEARCH_BLOCK_BUDGET};
pub use snapshot::{BlockRef, Snapshot, TransformationInfo};
use spindle::Spindle;
pub use spindle::{SpindleMode, SpindleState};
pub use stock::cut::{StockCheck, StockInfo, StockOptions, StockWarning};
pub use stock::saved::SavedStock;
pub use stock::tiles::{StockChanges, TILE as STOCK_TILE};

use crate::alarm::{Alarm, Clear};
use crate::interp::{Interpreter, Programs, SharedOffsets};
use crate::kinematics::ActiveTrafo;
use crate::lang::{self, ProgramText};
use crate::machine_data::registry::MAX_CHANNEL_AXES;
use crate::machine_data::{MachineConfig, MachineData, MdError};
use crate::motion::{AxisLimit, AxisVec, Planner};

/// How many prepared items (moves, dwells, stops) block preparation may run ahead.
pub const LOOKAHEAD: usize = 48;

/// How many blocks preparation may interpret in one IPO cycle. Bounds the work of a cycle, so
/// a loop without motion (`LOOP ... ENDLOOP`) keeps running like on the control instead of
/// hanging the caller.
pub const MAX_BLOCKS_PER_CYCLE: usize = 64;

/// Operating mode of the mode group.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Jog,
    Mda,
    Auto,
}

impl Mode {
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Jog => "JOG",
            Mode::Mda => "MDA",
            Mode::Auto => "AUTO",
        }
    }
}

/// What the channel is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Reset state: no program active, nothing moves.
    Idle,
    /// A program or a JOG motion is executing.
    Running,
    /// A program is interrupted (M0, M1, NC stop) and can be continued.
    Stopped,
    /// An alarm stopped the channel; a reset is needed.
    Alarm,
}

impl Status {
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Idle => "idle",
            Status::Running => "running",
            Status::Stopped => "stopped",
            Status::Alarm => "alarm",
        }
    }
}

/// Something that happened, for event streams.
#[derive(Debug, Clone, PartialEq)]
pub enum Event {
    AlarmRaised(Alarm),
    AlarmCleared {
        number: u32,
    },
    BlockChanged(BlockRef),
    /// The program ended (M2/M17/M30 or end of text).
    ProgramEnded,
    /// The program stopped at M0/M1.
    ProgramStopped {
        line: u32,
    },
    ModeChanged(Mode),
    /// An M or H function reached the main run (the simulated PLC's input).
    AuxFunction {
        function: crate::interp::auxiliary::AuxFunction,
        line: u32,
    },
    /// A program set (`on`) or cleared digital output `signal` (`$A_OUT`).
    DigitalOutput {
        signal: usize,
        on: bool,
        line: u32,
    },
    /// Inputs set from outside ([`Channel::set_signals`], [`Channel::set_analog_inputs`]),
    /// with the IPO cycle count they arrived at: they act from the next cycle on, so a run fed
    /// the same inputs at the same counts is identical (see [`Channel::input_log`]).
    InputsChanged(sync::InputRecord),
    /// A check of material removal found something (`stock/cut.rs`).
    Stock(StockWarning),
    /// An operator's command, for the action log ("who did what", see `action_log.rs`).
    OperatorAction(action_log::OperatorAction),
}

/// A command the channel refuses in its current state.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CommandError {
    /// The program cannot be prepared: every error found before it runs, first one in
    /// `line`/`message`.
    #[error("program has syntax errors: line {line}: {message}")]
    Syntax { line: u32, message: String, errors: Vec<lang::Diagnostic> },
    #[error("the channel is busy ({0}); stop or reset it first")]
    Busy(&'static str),
    #[error("an alarm is active; reset the channel first")]
    AlarmActive,
    #[error("not possible in mode {0}: {1}")]
    WrongMode(&'static str, &'static str),
    #[error("unknown axis {0}")]
    UnknownAxis(String),
    #[error("{0}")]
    Invalid(String),
    #[error("machine data: {0}")]
    MachineData(#[from] MdError),
}

impl CommandError {
    /// `Ok` if `text` has no error found before it runs ([`lang::check`]), else
    /// [`CommandError::Syntax`] with every error.
    pub fn check(text: &str) -> Result<(), CommandError> {
        let errors = lang::check(text);
        let Some(first) = errors.first() else { return Ok(()) };
        let more = match errors.len() {
            1 => String::new(),
            n => format!(" (and {} more)", n - 1),
        };
        let message = format!("alarm {} column {}: {}{more}", first.alarm, first.column, first.message);
        Err(CommandError::Syntax { line: first.line, message, errors })
    }
}

/// The operator's overrides in percent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overrides {
    /// Path feed, 0..=120.
    pub feed: f64,
    /// Rapid traverse, 0..=100 (the control's rapid override stops at 100 %).
    pub rapid: f64,
    /// Spindle speed, 50..=120.
    pub spindle: f64,
}

impl Default for Overrides {
    fn default() -> Self {
        Overrides { feed: 100.0, rapid: 100.0, spindle: 100.0 }
    }
}

/// A JOG request for one axis.
#[derive(Debug, Clone, PartialEq)]
pub struct JogRequest {
    /// Program name of the axis (geometry or channel axis name).
    pub axis: String,
    /// +1 or -1.
    pub direction: i8,
    /// `Some(mm or deg)`: incremental JOG; `None`: continuous until [`Channel::jog_stop`].
    pub increment: Option<f64>,
    /// Rapid traverse override (`$MA_JOG_VELO_RAPID` instead of `$MA_JOG_VELO`).
    pub rapid: bool,
}

/// Bookkeeping for a move in the main run: its block and the offsets active with it.
#[derive(Debug, Clone)]
struct MoveMeta {
    line: u32,
    /// The sequence number of the move's block (`pending::NO_SEQ` for JOG, REPOS, approach).
    seq: u32,
    offsets: SharedOffsets,
    /// The path is in machine axes although a transformation is active.
    machine_space: bool,
    /// The move's programmed feed (infinite for rapid traverse), for REPOS.
    feed: f64,
}

/// One simulated NC channel.
#[derive(Debug, Clone)]
pub struct Channel {
    data: MachineData,
    cfg: Arc<MachineConfig>,
    mode: Mode,
    status: Status,
    tick: u64,
    /// The active program's text; blocks are read from it one at a time.
    program: Option<ProgramText>,
    /// Counts the programs loaded (see `active_program.rs`): a display reloads the text when it changes.
    program_serial: u64,
    /// Stored programs (main programs and subprograms) by upper-case name.
    programs: Programs,
    /// Programs the file functions changed since the shell last took them (by name, once).
    changed_files: std::collections::BTreeSet<String>,
    /// The prepared blocks whose items are still queued, with where their text is (for display).
    queued_blocks: VecDeque<main_run::QueuedBlock>,
    /// Block preparation has reached the end of the program or stopped on an alarm.
    prep_done: bool,
    interp: Interpreter,
    /// Prepared items not yet handed to the planner.
    pending: pending::PendingItems,
    planner: Planner,
    /// Meta data of the moves in the planner, in queue order, with their tags.
    in_planner: VecDeque<(u32, MoveMeta)>,
    next_tag: u32,
    /// Offsets of the block in the main run (for BCS and WCS display).
    offsets: SharedOffsets,
    dwell_ticks: u64,
    current_line: Option<u32>,
    /// The sequence number of the block shown as current (with `current_line`: which block).
    current_seq: u32,
    /// The sequence number the next prepared block gets (never `pending::NO_SEQ`).
    next_block_seq: u32,
    /// The block shown as current: its program level and where its text is.
    current_block: Option<main_run::QueuedBlock>,
    /// The line and program level of the block prepared before the last one (a move it held
    /// back comes out with the next block's items).
    prev_read: main_run::ReadBlock,
    spindles: Vec<Spindle>,
    alarms: Vec<Alarm>,
    events: Vec<Event>,
    /// M1 stops only when optional stop is selected.
    pub optional_stop: bool,
    /// Single block (SBL1): the program stops after each block that moves.
    pub single_block: bool,
    /// DRY: path feeds of blocks prepared from now on are SD42100's dry-run feed.
    pub dry_run: bool,
    /// SKP: blocks marked with an active level are skipped when prepared.
    pub skip_levels: crate::interp::program_control::SkipLevels,
    overrides: Overrides,
    /// Single block: the step (`pending.rs`) whose moves have just finished.
    sbl_done: Option<u32>,
    /// Single block: the step whose moves are being fed (SBLOF joins blocks into one).
    sbl_step: Option<u32>,
    /// The JOG motion in progress.
    jog: Option<jog::ActiveJog>,
    /// Counts JOG motions started, so a client can stop only the motion it started.
    jog_serial: u64,
    /// A program interrupted for JOG: its main run, waiting for REPOS and NC start.
    interrupted: Option<Box<repos::Interrupted>>,
    /// The REPOS motion back to the interruption point is executing.
    repos_returning: bool,
    /// After a block search: the next program move is preceded by the approach to its start.
    search_approach: bool,
    /// The mode the active program was started in (AUTO or MDA).
    program_mode: Mode,
    /// Reference point state per channel axis (spindles count as referenced).
    referenced: Vec<bool>,
    /// The reference point approach in progress.
    referencing: Option<reference::approach::Referencing>,
    /// The last MSG text of the program.
    message: Option<String>,
    /// Machine position of every channel axis. Equals the planner's position without a
    /// transformation; with one, each IPO sample of the BCS is mapped to it.
    machine: AxisVec,
    /// The transformation active in the main run.
    trafo: Option<ActiveTrafo>,
    /// Preparation waits until a transformation change it prepared has been executed, then
    /// continues from the machine position the main run reached.
    prep_waits_for_trafo: bool,
    /// The offsets item of the block whose selection preparation waits for (a value of its own,
    /// told apart by identity): executing it ends the wait. `None` after a block search, whose
    /// wait ends at the next switch of the transformation.
    trafo_selection: Option<crate::interp::SharedOffsets>,
    /// Corner rounding of continuous-path mode between prepared moves (`smoothing/`).
    blending: smoothing::Blending,
    /// The move whose transformation the main run has taken over (checked once per move, not
    /// every cycle).
    trafo_tag: Option<u32>,
    /// The last IPO cycle's orientation solve, from which TRAORI steps the next one (cleared
    /// at every new move and at rest, so those positions are solved directly).
    ori_memo: crate::kinematics::AngleMemo,
    /// The online tool length offset reached by the main run (`$AA_TOFF`).
    toff: tools::toff::OnlineOffset,
    /// The digital inputs and outputs (`$A_IN`, `$A_OUT`; see `io.rs`).
    io: crate::interp::io::DigitalIo,
    /// Workpiece counters, program runtimes and the clock (`counters.rs`).
    counters: counters::Counters,
    /// The axes' position loops: actual values and following errors.
    servo: servo::Servo,
    /// The block change waiting for the G601/G602 exact-stop window (`exact_stop.rs`).
    exact_stop: exact_stop::ExactStop,
    /// Motion-synchronous actions and their data (`sync/`).
    sync: sync::SyncActions,
    /// Axes travelling outside the path: POS/POSA, command axes (`positioning_axes.rs`).
    positioning: positioning_axes::PositioningAxes,
    /// STOPREOF, RDISABLE, wait markers, technology cycles (`program_sync.rs`).
    psync: program_sync::ProgramSync,
    /// Tool life and count monitoring (`tools/monitor.rs`).
    tool_monitor: tools::monitor::ToolMonitor,
    /// The blank being cut, if one is defined (`stock/cut.rs`).
    stock: Option<Box<stock::cut::StockRun>>,
    stock_options: StockOptions,
    /// FPR: the axis a feed per revolution follows instead of the master spindle, with its
    /// position at the last cycle (`spindle.rs`).
    feed_reference: Option<(usize, f64)>,
    /// The master spindle in the main run: MD20090's, or SETMS's until reset or program end.
    master_spindle: Option<usize>,
    /// The touch-trigger probe of MEAS/MEAW (`probe.rs`).
    probe: probe::Probe,
}

impl Channel {
    /// A channel for the given machine data (applied on top of the defaults).
    pub fn new(data: MachineData) -> Result<Channel, MdError> {
        let cfg = data.activate().map_err(|e| MdError { line: None, message: e.message })?;
        Ok(Channel::with_config(data, cfg, Programs::new()))
    }

    /// A channel for a built-in preset plus extra NC data text.
    pub fn from_preset(preset_id: &str, extra: &str) -> Result<Channel, MdError> {
        let preset = crate::machine_data::presets::find(preset_id)
            .ok_or_else(|| MdError { line: None, message: format!("unknown machine preset `{preset_id}`") })?;
        let mut data = MachineData::default();
        data.apply_text(preset.text)?;
        let cfg = data.apply_text(extra)?;
        Ok(Channel::with_config(data, cfg, Programs::new()))
    }

    /// A channel at power on for `data`/`cfg` holding the stored programs `programs`. The
    /// program store is an argument, not a default: the session's programs are data of the
    /// session, not of the machine data, so whatever builds a channel anew (a change of machine
    /// data or chain data) has to say which programs it keeps.
    fn with_config(data: MachineData, cfg: MachineConfig, programs: Programs) -> Channel {
        let cfg = Arc::new(cfg);
        let master_spindle = cfg.master_spindle;
        let planner = Planner::new(cfg.ipo_cycle, AxisLimit::for_channel(&cfg), [0.0; MAX_CHANNEL_AXES]);
        let spindles = spindle::for_config(&cfg, &data);
        let servo = servo::Servo::new(&cfg, &[0.0; MAX_CHANNEL_AXES]);
        let referenced = reference::initial_state(&data, &cfg);
        let mut ch = Channel {
            interp: Interpreter::new(&cfg),
            offsets: SharedOffsets::default(),
            data,
            cfg,
            mode: Mode::Auto,
            status: Status::Idle,
            tick: 0,
            program: None,
            program_serial: 0,
            queued_blocks: VecDeque::new(),
            programs,
            changed_files: Default::default(),
            prep_done: true,
            pending: pending::PendingItems::default(),
            planner,
            in_planner: VecDeque::new(),
            next_tag: 0,
            dwell_ticks: 0,
            current_line: None,
            current_seq: pending::NO_SEQ,
            next_block_seq: 1,
            current_block: None,
            prev_read: main_run::ReadBlock::default(),
            spindles,
            alarms: Vec::new(),
            events: Vec::new(),
            optional_stop: false,
            single_block: false,
            dry_run: false,
            skip_levels: Default::default(),
            overrides: Overrides::default(),
            sbl_done: None,
            sbl_step: None,
            jog: None,
            jog_serial: 0,
            interrupted: None,
            repos_returning: false,
            search_approach: false,
            program_mode: Mode::Auto,
            message: None,
            machine: [0.0; MAX_CHANNEL_AXES],
            trafo: None,
            prep_waits_for_trafo: false,
            trafo_selection: None,
            blending: Default::default(),
            trafo_tag: None,
            ori_memo: Default::default(),
            toff: Default::default(),
            io: Default::default(),
            counters: Default::default(),
            servo,
            exact_stop: Default::default(),
            referenced,
            referencing: None,
            sync: Default::default(),
            positioning: Default::default(),
            psync: Default::default(),
            tool_monitor: Default::default(),
            stock: None,
            stock_options: Default::default(),
            feed_reference: None,
            master_spindle,
            probe: Default::default(),
        };
        ch.publish_stored_data();
        ch.size_signals();
        // Power on acts like a reset: the reset transformation (if configured) is active.
        ch.place_axes([0.0; MAX_CHANNEL_AXES]);
        ch
    }

    /// Puts the stationary axes at machine position `pos` and brings the interpreter, the
    /// displayed offsets and the transformation in line with it (power on, restore, new data).
    fn place_axes(&mut self, pos: AxisVec) {
        self.machine = pos;
        self.sync.wake_all();
        self.servo.place(&pos);
        self.interp.reset(&self.cfg, &pos);
        self.offsets = self.interp.offsets();
        self.adopt_transformation();
    }

    /// The activated configuration.
    pub fn config(&self) -> &MachineConfig {
        &self.cfg
    }

    /// The active frame chain link by link and its total (`interp/frames/overview.rs`).
    pub fn frame_chain(&self) -> Vec<crate::interp::FrameChainLink> {
        self.interp.frame_chain(&self.cfg)
    }

    /// The active swivel (toolholder data set, axis angles, plane, WCS directions) for a
    /// display beside T, F, S (`interp/tools/active_swivel.rs`).
    pub fn active_swivel(&self) -> crate::interp::ActiveSwivel {
        self.interp.active_swivel(&self.cfg)
    }

    /// The unit tool direction in the BCS while an orientation transformation is active (a
    /// 5-axis program check draws it along the path); `None` otherwise.
    pub fn tool_direction_bcs(&self) -> Option<[f64; 3]> {
        use crate::kinematics::Transformation;
        self.trafo.as_ref().and_then(|t| t.trafo.orientation(&self.machine))
    }

    /// The stored machine data.
    pub fn machine_data(&self) -> &MachineData {
        &self.data
    }

    /// Applies NC data text (all-or-nothing) and activates it as a reset would. Only in reset
    /// state; axis positions are kept where the axes still exist.
    pub fn apply_machine_data(&mut self, text: &str) -> Result<(), CommandError> {
        if self.is_active() || self.status == Status::Stopped {
            return Err(CommandError::Busy("machine data can only change in reset state"));
        }
        let mut data = self.data.clone();
        let cfg = data.apply_text(text)?;
        self.replace_data(data, cfg);
        Ok(())
    }

    /// The session's kinematic chain data ($NK_/$NT_) as a part program (DELOBJ preamble,
    /// assignments, NEWCONF) that [`Channel::import_kinematic_chains`] and a control accept.
    pub fn export_kinematic_chains(&self) -> String {
        crate::machine_data::chains::export_program(self.data.kin())
    }

    /// Runs such a program on the session's data, all-or-nothing, and activates the result as
    /// [`Channel::apply_machine_data`] does; only in reset state.
    pub fn import_kinematic_chains(&mut self, program: &str) -> Result<(), CommandError> {
        if self.is_active() || self.status == Status::Stopped {
            return Err(CommandError::Busy("kinematic chain data can only change in reset state"));
        }
        let mut data = self.data.clone();
        let cfg = data.import_chain_program(program)?;
        self.replace_data(data, cfg);
        Ok(())
    }

    /// Becomes a channel on `data`/`cfg`, keeping the stored programs and the axis positions
    /// where the axes still exist.
    fn replace_data(&mut self, data: MachineData, cfg: MachineConfig) {
        let old_pos = *self.planner.position();
        let old_names: Vec<String> = self.cfg.machine_axes.iter().map(|a| a.name.clone()).collect();
        // The files a program wrote go into the store first, and stay listed as changed.
        let changed = self.take_changed_file_names();
        let mut next = Channel::with_config(data, cfg, std::mem::take(&mut self.programs));
        next.changed_files = changed;
        next.set_program_budget(self.interp.files().budget());
        let mut pos = [0.0; MAX_CHANNEL_AXES];
        for (k, ch) in next.cfg.channel_axes.iter().enumerate() {
            let name = &next.cfg.machine_axes[ch.machine_axis].name;
            if let Some(old) = self.cfg.channel_axes.iter().position(|c| old_names[c.machine_axis] == *name) {
                pos[k] = old_pos[old];
            }
        }
        next.place_axes(pos);
        next.keep_reference_state(self);
        next.mode = self.mode;
        next.tick = self.tick;
        let z = next.cfg.sync_sizes;
        next.set_digital_io(self.io.sized(z.digital_in, z.digital_out));
        (next.stock, next.stock_options) = (self.stock.take(), self.stock_options);
        next.probe = std::mem::take(&mut self.probe);
        next.probe.disarm();
        *self = next;
    }

    pub fn mode(&self) -> Mode {
        self.mode
    }

    pub fn status(&self) -> Status {
        self.status
    }

    /// Simulated time since the channel was created, in seconds.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.cfg.ipo_cycle
    }

    /// Number of IPO cycles stepped so far.
    pub fn ticks(&self) -> u64 {
        self.tick
    }

    pub fn alarms(&self) -> &[Alarm] {
        &self.alarms
    }

    /// True while stepping changes anything: a program runs, axes move or a spindle turns.
    pub fn is_active(&self) -> bool {
        self.is_busy() || self.spindles.iter().any(|s| s.is_turning())
    }

    /// True while a program or JOG motion is executing or the axes are still braking.
    pub fn is_busy(&self) -> bool {
        self.status == Status::Running || self.planner.velocity() > 0.0
    }

    /// Events since the last call, oldest first.
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// Changes the mode: in reset state to any mode; with an interrupted program (stopped,
    /// nothing moving) between the program's mode and JOG (for JOG and REPOS).
    pub fn set_mode(&mut self, mode: Mode) -> Result<(), CommandError> {
        if mode == self.mode {
            return Ok(());
        }
        if self.is_busy() {
            return Err(CommandError::Busy("a program or motion is active"));
        }
        if self.status == Status::Stopped && mode != Mode::Jog && mode != self.program_mode {
            return Err(CommandError::Busy(
                "a program is interrupted: only JOG or its own mode; reset it to change to another mode",
            ));
        }
        self.mode = mode;
        self.events.push(Event::ModeChanged(mode));
        Ok(())
    }

    /// Loads `text` as the active program and starts it in AUTO mode.
    pub fn run_program(&mut self, text: &str) -> Result<(), CommandError> {
        self.load_and_start(ProgramText::from(text), Mode::Auto)
    }

    /// [`Channel::run_program`] for text the caller already holds shared: the channel keeps
    /// this one copy instead of its own (a long program is in memory once).
    pub fn run_program_shared(&mut self, text: impl Into<ProgramText>) -> Result<(), CommandError> {
        self.load_and_start(text.into(), Mode::Auto)
    }

    /// [`Channel::run_program_shared`] without the syntax check, for a caller that runs
    /// [`lang::check`] itself (on another thread, alongside the run): the caller guarantees the
    /// check passes or discards the run and everything it produced. Without the check an error
    /// surfaces only when preparation reaches its line, as an alarm.
    pub fn run_program_prechecked(&mut self, text: impl Into<ProgramText>) -> Result<(), CommandError> {
        self.start_loaded(text.into(), Mode::Auto)
    }

    /// Executes `text` (one or more blocks) in MDA mode.
    pub fn mda(&mut self, text: &str) -> Result<(), CommandError> {
        self.load_and_start(ProgramText::from(text), Mode::Mda)
    }

    fn load_and_start(&mut self, text: ProgramText, mode: Mode) -> Result<(), CommandError> {
        CommandError::check(&text)?;
        self.start_loaded(text, mode)
    }

    /// Loads `text`, which passed the syntax check, and starts it in `mode`.
    fn start_loaded(&mut self, text: ProgramText, mode: Mode) -> Result<(), CommandError> {
        if self.is_busy() || self.status == Status::Stopped {
            return Err(CommandError::Busy("a program is active"));
        }
        if self.status == Status::Alarm {
            return Err(CommandError::AlarmActive);
        }
        if crate::programs::archive::is_data_file(&text) {
            return self.run_data_file(&text);
        }
        self.check_start_lock()?;
        self.set_mode(mode)?;
        self.program_mode = mode;
        self.search_approach = false;
        self.set_active_program(text.clone());
        self.queued_blocks.clear();
        self.current_block = None;
        self.prep_done = false;
        // Modal synchronized actions of an earlier run (one ended by an alarm) end here.
        self.sync.end_program();
        self.interp.begin_program(text, &self.machine);
        self.start_runtimes();
        self.status = Status::Running;
        Ok(())
    }

    /// NC start: continues an interrupted program (M0, M1, NC stop); after JOG it first returns
    /// to the interruption point (REPOS, RMI).
    pub fn start(&mut self) -> Result<(), CommandError> {
        self.start_with_repos(ReposMode::Interruption)
    }

    /// NC start as [`Channel::start`]; when it repositions after JOG, `repos` picks the point of
    /// the interrupted block the program resumes at (RMI, RMB, RME, RMN).
    pub fn start_with_repos(&mut self, repos: ReposMode) -> Result<(), CommandError> {
        self.start_with_repos_approach(repos, ReposApproach::Line)
    }

    /// NC start as [`Channel::start_with_repos`], travelling back along `approach` (REPOSL,
    /// REPOSQ, REPOSH).
    pub fn start_with_repos_approach(&mut self, repos: ReposMode, approach: ReposApproach) -> Result<(), CommandError> {
        match approach {
            ReposApproach::QuarterCircle { radius: r } | ReposApproach::SemiCircle { diameter: r }
                if !(r.is_finite() && r > 0.0) =>
            {
                return Err(CommandError::Invalid(format!("DISR must be a positive distance, not {r}")));
            }
            _ => {}
        }
        match self.status {
            Status::Alarm => Err(CommandError::AlarmActive),
            Status::Running => Ok(()),
            Status::Stopped => {
                if self.mode == Mode::Jog {
                    return Err(CommandError::WrongMode("JOG", "the interrupted program continues in its own mode"));
                }
                self.check_start_lock()?;
                if self.interrupted.is_some() || self.repos_returning {
                    self.start_repos(repos, approach);
                } else {
                    self.planner.set_hold(false);
                    self.status = Status::Running;
                }
                Ok(())
            }
            Status::Idle => match (self.program.clone(), self.mode) {
                (Some(text), Mode::Auto) => self.run_program_shared(text),
                (_, Mode::Jog) => Err(CommandError::WrongMode("JOG", "NC start runs programs in AUTO or MDA")),
                _ => Err(CommandError::Invalid("no program loaded".into())),
            },
        }
    }

    /// NC stop: brakes on the path; the program can be continued with [`Channel::start`].
    pub fn stop(&mut self) {
        match self.status {
            Status::Running if self.jog.is_some() => self.jog_stop(),
            Status::Running if self.referencing.is_some() => self.abort_referencing(),
            Status::Running if self.repos_returning => {
                // The REPOS motion is dropped at standstill; NC start plans it anew.
                self.planner.stop_and_flush();
                self.repos_returning = false;
                self.status = Status::Stopped;
            }
            Status::Running => {
                self.planner.set_hold(true);
                self.status = Status::Stopped;
            }
            _ => {}
        }
    }

    /// Channel reset: ends the program, stops every axis and spindle at once, clears the alarms
    /// a reset clears and returns the modal state to its reset values.
    pub fn reset(&mut self) {
        self.end_runtimes();
        self.sbl_done = None;
        self.sbl_step = None;
        self.probe.disarm();
        self.planner.abort();
        self.pending.clear();
        self.end_orison_run();
        self.in_planner.clear();
        self.prep_done = true;
        self.prep_waits_for_trafo = false;
        self.dwell_ticks = 0;
        self.jog = None;
        self.referencing = None;
        self.drop_interruption();
        self.search_approach = false;
        self.current_line = None;
        self.current_block = None;
        self.message = None;
        self.sync.end_program();
        self.reset_positioning_axes();
        self.psync.reset();
        self.feed_reference = None;
        self.master_spindle = self.cfg.master_spindle;
        let pos = *self.planner.position();
        for s in &mut self.spindles {
            s.leave_axis_mode(pos[s.axis]);
            s.stop_now();
        }
        // Machine data written by programs becomes active with the reset (when it is valid and
        // keeps the axes; otherwise it waits for a PUT of machine data to report the problem).
        if let Ok(cfg) = self.data.activate()
            && cfg != *self.cfg
            && cfg.channel_axes == self.cfg.channel_axes
        {
            self.planner.set_limits(AxisLimit::for_channel(&cfg));
            self.cfg = Arc::new(cfg);
            self.size_signals();
        }
        let pos = self.machine;
        self.servo = servo::Servo::new(&self.cfg, &pos);
        self.interp.reset(&self.cfg, &pos);
        self.offsets = self.interp.offsets();
        self.adopt_transformation();
        for a in std::mem::take(&mut self.alarms) {
            self.events.push(Event::AlarmCleared { number: a.number });
        }
        self.status = Status::Idle;
    }

    /// Sets feed, rapid and spindle override; they act at once (the path speed changes within
    /// the axes' acceleration).
    pub fn set_overrides(&mut self, o: Overrides) -> Result<(), CommandError> {
        let check = |name: &str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(CommandError::Invalid(format!("{name} override {v} % outside {lo}..{hi} %")))
            }
        };
        check("feed", o.feed, 0.0, 120.0)?;
        check("rapid", o.rapid, 0.0, 100.0)?;
        check("spindle", o.spindle, 50.0, 120.0)?;
        // The runtimes stand at feed override 0: what ran before counts at the old one.
        self.settle_runtimes();
        self.overrides = o;
        self.planner.set_overrides(o.feed, o.rapid);
        for s in &mut self.spindles {
            s.set_override(o.spindle / 100.0);
        }
        Ok(())
    }

    /// The active overrides.
    pub fn overrides(&self) -> Overrides {
        self.overrides
    }

    /// A view of the state for the outside world.
    pub fn snapshot(&self) -> Snapshot {
        snapshot::build(self)
    }

    /// Advances exactly one IPO cycle.
    pub fn step(&mut self) {
        self.tick += 1;
        self.step_spindles();
        if self.status == Status::Running && self.jog.is_none() && !self.repos_returning && self.referencing.is_none() {
            // A program runs in this cycle: its runtimes are worked out from the count
            // (`counters.rs`).
            self.counters.run_cycles += 1;
            self.prepare();
            self.feed_planner();
        }
        self.step_sync_actions();
        if !self.exact_stop.holds(&self.servo, &self.cfg) {
            let watched = exact_stop::ExactStop::watch(&self.planner, &self.servo);
            self.planner.step();
            if let Some(tag) = watched {
                let window = self.offsets.gcodes.stop_window();
                self.exact_stop.after_step(tag, self.planner.has_finished(), window, &self.cfg);
            }
        } else {
            self.planner.stood();
        }
        self.monitor_tools();
        self.update_machine_position();
        self.step_positioning_axes();
        if self.probe.armed() {
            self.step_probe();
        }
        if self.stock.is_some() {
            self.cut_stock();
        }
        self.servo.step(&self.machine, self.offsets.gcodes.ffw_on());
        if let Some(lag) = self.servo.take_changed() {
            self.interp.observe_following_error(lag);
        }
        self.retire_finished_moves();
        if self.jog.is_some() {
            self.finish_jog_if_done();
            return;
        }
        if self.referencing.is_some() {
            self.step_referencing();
            return;
        }
        if self.repos_returning {
            self.finish_repos_if_done();
            return;
        }
        if self.status == Status::Running && self.planner.is_empty() && !self.exact_stop.is_waiting() {
            self.execute_actions();
        }
        self.sync_files();
    }

    /// Removes alarms that the cancel key clears.
    pub fn cancel_alarms(&mut self) {
        let (cancel, keep): (Vec<_>, Vec<_>) =
            std::mem::take(&mut self.alarms).into_iter().partition(|a| a.clear == Clear::Cancel);
        self.alarms = keep;
        for a in cancel {
            self.events.push(Event::AlarmCleared { number: a.number });
        }
    }

    /// Puts the axes at `positions` (channel axis order, machine coordinates), as after a
    /// restart that restores a saved session. Only in reset state with nothing moving.
    pub fn restore_positions(&mut self, positions: &[f64]) -> Result<(), CommandError> {
        if self.is_busy() || self.status == Status::Stopped {
            return Err(CommandError::Busy("positions can only be restored in reset state"));
        }
        // Without the trailing spindles without axis function (as `axis_positions` gives them)
        // those spindles start at 0°, as after power on.
        let lengths = [self.cfg.channel_axes.len(), self.cfg.axes_len()];
        if !lengths.contains(&positions.len()) || positions.iter().any(|p| !p.is_finite()) {
            return Err(CommandError::Invalid(format!("expected {} finite positions", self.cfg.channel_axes.len())));
        }
        let mut pos = [0.0; MAX_CHANNEL_AXES];
        pos[..positions.len()].copy_from_slice(positions);
        self.place_axes(pos);
        Ok(())
    }

    /// An R parameter's value (0 for numbers beyond the R parameter count).
    pub fn r_param(&self, n: usize) -> f64 {
        self.interp.variables().r.get(n).copied().unwrap_or(0.0)
    }

    /// A user variable's element (flat index for arrays), if it is declared in the program
    /// level being prepared or globally.
    pub fn variable(&self, name: &str, index: usize) -> Option<crate::interp::eval::value::Value> {
        self.interp.variables().get(&name.to_ascii_uppercase()).and_then(|v| v.data.get(index).cloned())
    }

    /// The position loops of the channel axes: following errors.
    pub fn servo(&self) -> &servo::Servo {
        &self.servo
    }

    /// Actual value of channel axis `k` (machine coordinates): the setpoint of
    /// [`Channel::axis_positions`] less the following error.
    pub fn actual_position(&self, k: usize) -> f64 {
        self.machine[k] - self.servo.following_error(k)
    }

    /// Interpolated positions of the channel axes (machine coordinates, channel order); cheap
    /// to call every cycle, for recording IPO samples. Trailing spindles without axis function
    /// (the mill's tool spindle) are left out: they are no axes of the program.
    pub fn axis_positions(&self) -> &[f64] {
        &self.machine[..self.cfg.axes_len()]
    }
}
