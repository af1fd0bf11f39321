//! The channel's state as the outside world sees it (the contract's state object, in engine
//! types; the server turns it into JSON).

use super::{Channel, Mode, Overrides, Status};
use crate::alarm::Alarm;
use crate::interp::gcodes::GCodes;

/// The block shown as current.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockRef {
    /// 1-based line in the text of the program the block is in.
    pub line: u32,
    pub text: String,
    /// The subprogram the block is in (its stored name); `None`: the main program.
    pub program: Option<String>,
}

/// The active kinematic transformation.
#[derive(Debug, Clone, PartialEq)]
pub struct TransformationInfo {
    pub name: String,
    pub trafo_type: u32,
    pub index: u32,
    /// TRACYL: the working diameter of the selection (programmed Y is the arc length on it), so
    /// a view can wrap the unrolled path onto the cylinder.
    pub diameter: Option<f64>,
}

/// A consistent view of one channel at one IPO cycle.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    pub status: Status,
    pub mode: Mode,
    /// Simulated seconds since the channel was created.
    pub time: f64,
    pub tick: u64,
    /// MCS: every machine axis of the channel, by machine axis name: the interpolator's
    /// setpoint (`$AA_IPO`).
    pub machine: Vec<(String, f64)>,
    /// MCS actual values of the servo model (`$AA_IM`), as `machine`.
    pub actual: Vec<(String, f64)>,
    /// Following errors (setpoint − actual), as `machine`.
    pub following_error: Vec<(String, f64)>,
    /// BCS: channel axes by program name (geometry axes first by their geometry names).
    pub basic: Vec<(String, f64)>,
    /// WCS: as `basic`, after work offsets.
    pub workpiece: Vec<(String, f64)>,
    /// Unit tool direction in the WCS, when known.
    pub orientation: Option<[f64; 3]>,
    pub transformation: Option<TransformationInfo>,
    pub block: Option<BlockRef>,
    pub alarms: Vec<Alarm>,
    /// Active tool and cutting edge (T, D); D0 = no offset.
    pub tool: (u32, u32),
    /// The tool in the spindle by name (`$TC_TP2`; empty for a tool without one).
    pub tool_name: String,
    /// The programmed tool (`$P_TOOLP`): under MD22550 = 1 the one the next M6 changes to.
    pub prepared_tool: u32,
    /// Path velocity in mm/min.
    pub path_velocity: f64,
    /// Spindles: (channel axis name, speed in rev/min, signed: + = M3).
    pub spindles: Vec<(String, f64)>,
    /// Spindles with mode and angle, by the same names and in the same order as `spindles`.
    pub spindle_states: Vec<(String, super::spindle::SpindleState)>,
    /// The program's last MSG text.
    pub message: Option<String>,
    /// Feed, rapid and spindle override.
    pub overrides: Overrides,
    /// Single block (SBL1) and optional stop (M1) selected.
    pub single_block: bool,
    pub optional_stop: bool,
    /// DRY (dry-run feed) and SKP (the active skip levels) selected.
    pub dry_run: bool,
    pub skip_levels: crate::interp::program_control::SkipLevels,
    /// The active G functions of the block in execution, one per displayed G group.
    pub gcodes: Vec<String>,
    /// What `gcodes` was written from (see `Channel::refresh_snapshot`).
    pub(super) gcodes_seen: GCodesSeen,
    /// Reference point state by machine axis name, in machine axis order.
    pub referenced: Vec<(String, bool)>,
    /// The axis whose reference point approach is in progress, and its phase.
    pub referencing: Option<(String, super::ReferencePhase)>,
    /// Number of the last JOG motion started (see `Channel::jog_stop_if`).
    pub jog_serial: u64,
    /// The program was interrupted and axes moved by JOG: NC start repositions first (REPOS).
    pub repos_pending: bool,
    /// The active synchronized actions (ID order, then block-modal ones).
    pub sync_actions: Vec<super::sync::SyncActionInfo>,
    /// The axes travelling on their own interpolators (POS/POSA/POSP, command axes), in
    /// channel axis order; empty when none.
    pub positioning: Vec<super::PositioningInfo>,
    /// Material removal: volumes and checks (`None` without a blank).
    pub stock: Option<super::StockInfo>,
    /// Counts the programs loaded (see `Channel::active_program`): a display reloads the
    /// program text when it changes.
    pub program_serial: u64,
    /// Path length still to go of the block in execution (mm; 0 when nothing moves).
    pub distance_to_go: f64,
    /// Programmed path feed of the block in execution in mm/min; `None` for rapid traverse or
    /// when no block moves.
    pub programmed_feed: Option<f64>,
    /// The program stands at a preprocessing stop, waiting for the main run
    /// (`Channel::stands_at_preprocessing_stop`).
    pub preprocessing_stop_wait: bool,
    /// The workpiece counters (`$AC_REQUIRED_PARTS`..).
    pub parts: crate::interp::eval::process_vars::PartCounts,
    /// The program runtimes (`$AC_OPERATING_TIME`..).
    pub runtimes: crate::interp::eval::process_vars::Runtimes,
}

/// The G functions a snapshot's `gcodes` names were written from, so that a refresh rewrites
/// the names only when they change. Not part of the state: it compares equal always.
#[derive(Debug, Clone, Copy, Default)]
pub struct GCodesSeen(pub(super) Option<GCodes>);

impl PartialEq for GCodesSeen {
    fn eq(&self, _: &GCodesSeen) -> bool {
        true
    }
}

/// A new snapshot of the channel: a refresh of an empty one.
pub(super) fn build(ch: &Channel) -> Snapshot {
    let mut s = Snapshot {
        status: Status::Idle,
        mode: Mode::Jog,
        time: 0.0,
        tick: 0,
        machine: Vec::new(),
        actual: Vec::new(),
        following_error: Vec::new(),
        basic: Vec::new(),
        workpiece: Vec::new(),
        orientation: None,
        transformation: None,
        block: None,
        alarms: Vec::new(),
        tool: (0, 0),
        tool_name: String::new(),
        prepared_tool: 0,
        path_velocity: 0.0,
        spindles: Vec::new(),
        spindle_states: Vec::new(),
        message: None,
        overrides: Overrides::default(),
        single_block: false,
        optional_stop: false,
        dry_run: false,
        skip_levels: Default::default(),
        gcodes: Vec::new(),
        gcodes_seen: GCodesSeen(None),
        referenced: Vec::new(),
        referencing: None,
        jog_serial: 0,
        repos_pending: false,
        sync_actions: Vec::new(),
        positioning: Vec::new(),
        stock: None,
        program_serial: 0,
        distance_to_go: 0.0,
        programmed_feed: None,
        preprocessing_stop_wait: false,
        parts: Default::default(),
        runtimes: Default::default(),
    };
    super::snapshot_refresh::refresh(ch, &mut s);
    s
}
