//! Wire types: what the REST API and the WebSocket stream send and accept, with their OpenAPI
//! schemas, and the conversions from engine types (the engine has no serde).
//!
//! Request bodies reject unknown fields, so a typo (`"wiat": true`) is a `400`, not a silently
//! ignored option.

use nctwin_engine::channel::{BlockRef, TransformationInfo};
use nctwin_engine::{Alarm, Event, Mode, Snapshot, Status};
use serde::ser::SerializeMap;
use serde::{Deserialize, Serialize, Serializer};
use utoipa::ToSchema;

use nctwin_engine::channel::{JOG_INCREMENTS, JogSystem, OrientationJogKind, ReposApproach, ReposMode};

use crate::session::{Drive, Pace};

/// An error: what is wrong and, when the error belongs to one line of a program or of machine
/// data text, that line (1-based).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ErrorBody {
    pub error: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<u32>,
    /// A program that cannot be prepared: every error found before it ran, as the NC alarms
    /// the control shows (absent for other errors).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<DiagnosticInfo>,
    /// Errors found beyond the first [`MAX_DIAGNOSTICS`] (1000), not listed in `errors`
    /// (absent when none were left out).
    #[serde(skip_serializing_if = "is_zero")]
    pub errors_omitted: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Most syntax errors a reply lists (`POST .../check`, a program refused with `400`); the
/// count of the others is given instead. A program of errors answered a list 20 times its size.
pub const MAX_DIAGNOSTICS: usize = 1000;

/// The first [`MAX_DIAGNOSTICS`] of `all`, and how many were left out.
pub fn first_diagnostics(all: &[nctwin_engine::lang::Diagnostic]) -> (Vec<DiagnosticInfo>, usize) {
    let listed = all.iter().take(MAX_DIAGNOSTICS).map(DiagnosticInfo::from).collect();
    (listed, all.len().saturating_sub(MAX_DIAGNOSTICS))
}

/// Liveness and size of the server.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Health {
    /// `"ok"` when the server answers and its storage works, `"degraded"` when the storage
    /// fails (changes cannot be saved).
    pub status: String,
    pub version: String,
    /// Number of live sessions.
    pub sessions: usize,
    pub storage: StorageStatus,
    /// `"off"` (no tokens needed) or `"required"`.
    pub auth: String,
}

/// Whether the storage works.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct StorageStatus {
    /// `sqlite` (the embedded default under `--data-dir`), `postgres` (`--database`) or `memory`.
    pub backend: String,
    /// `"ok"` or `"error"`.
    pub status: String,
    /// What failed, when it failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The tokens of a new session, shown only in the reply that creates it (the server keeps
/// only their hashes). Each is `nct_` + 32 hex digits (128 random bits).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Tokens {
    /// Full control, can always take control back, may delete the session. Keep it.
    pub owner: String,
    /// To share: may take control when it is free and then drive the session.
    pub operator: String,
    /// To share: may read everything (state, stream, programs) and change nothing.
    pub observer: String,
}

/// Control of a session.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ControlState {
    /// Whether the server requires tokens (`--auth required`).
    pub auth: bool,
    /// The caller's role (always `owner` when auth is off).
    pub role: crate::auth::Role,
    /// The role holding control, if any (auth required only).
    pub holder: Option<crate::auth::Role>,
    /// Whether the caller may send commands now.
    pub you_hold_control: bool,
}

/// The reply to `POST /sessions`: the session and its tokens.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CreatedSession {
    pub id: String,
    /// The preset the session was created from.
    pub machine: String,
    pub state: State,
    pub tokens: Tokens,
    /// Whether the session is persistent: it never expires when idle.
    pub persistent: bool,
}

/// A built-in machine preset.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct MachineSummary {
    pub id: String,
    pub name: String,
    pub description: String,
}

/// A built-in machine preset with its NC data text.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct MachineDetail {
    pub id: String,
    pub name: String,
    pub description: String,
    /// The preset as NC data text (`$MN_...`, `$MC_...`, `$MA_...`, `$TC_DP...` assignments).
    pub machine_data: String,
}

impl From<&nctwin_engine::machine_data::presets::Preset> for MachineSummary {
    fn from(p: &nctwin_engine::machine_data::presets::Preset) -> MachineSummary {
        MachineSummary { id: p.id.into(), name: p.name.into(), description: p.description.into() }
    }
}

impl From<&nctwin_engine::machine_data::presets::Preset> for MachineDetail {
    fn from(p: &nctwin_engine::machine_data::presets::Preset) -> MachineDetail {
        MachineDetail {
            id: p.id.into(),
            name: p.name.into(),
            description: p.description.into(),
            machine_data: p.text.into(),
        }
    }
}

/// Body of `POST /sessions`; an empty body means all defaults.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CreateSession {
    /// Preset id from `GET /machines`; default `mill-3axis`.
    #[schema(example = "mill-3axis")]
    pub machine: Option<String>,
    /// NC data text applied on top of the preset, as if written and activated by a reset.
    #[schema(example = "$MA_POS_LIMIT_PLUS[X]=400.")]
    pub machine_data: Option<String>,
    /// `true`: the session never expires when idle (see `--session-idle-timeout`); default
    /// `false`. `PATCH /sessions/{id}` changes it later.
    pub persistent: Option<bool>,
}

/// Body of `PATCH /sessions/{id}`: the fields to change.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SessionPatch {
    /// `true`: the session never expires when idle; `false`: it expires after the server's
    /// idle timeout without use.
    pub persistent: Option<bool>,
}

/// A session with its full state.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Session {
    pub id: String,
    /// The preset the session was created from.
    pub machine: String,
    pub state: State,
    /// Whether the session is persistent: it never expires when idle.
    pub persistent: bool,
}

/// A session in the list.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct SessionSummary {
    pub id: String,
    pub machine: String,
    pub status: ChannelStatus,
    pub mode: OpMode,
}

/// What the channel is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum ChannelStatus {
    /// Reset state: no program active, nothing moves.
    Idle,
    /// A program, MDA blocks or a JOG motion execute.
    Running,
    /// A program is interrupted (M0, M1, NC stop) and can be continued with `start`.
    Stopped,
    /// An alarm stopped the channel; a reset is needed.
    Alarm,
}

impl From<Status> for ChannelStatus {
    fn from(s: Status) -> ChannelStatus {
        match s {
            Status::Idle => ChannelStatus::Idle,
            Status::Running => ChannelStatus::Running,
            Status::Stopped => ChannelStatus::Stopped,
            Status::Alarm => ChannelStatus::Alarm,
        }
    }
}

/// Operating mode of the channel's mode group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "UPPERCASE")]
pub enum OpMode {
    Jog,
    Mda,
    Auto,
}

impl From<Mode> for OpMode {
    fn from(m: Mode) -> OpMode {
        match m {
            Mode::Jog => OpMode::Jog,
            Mode::Mda => OpMode::Mda,
            Mode::Auto => OpMode::Auto,
        }
    }
}

impl From<OpMode> for Mode {
    fn from(m: OpMode) -> Mode {
        match m {
            OpMode::Jog => Mode::Jog,
            OpMode::Mda => Mode::Mda,
            OpMode::Auto => Mode::Auto,
        }
    }
}

/// The state of a session's channel at one IPO cycle.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct State {
    pub status: ChannelStatus,
    pub mode: OpMode,
    /// Simulated seconds since the session started.
    pub time: f64,
    /// IPO cycles since the session started.
    pub tick: u64,
    pub positions: Positions,
    /// The position loop of every machine axis (the servo model).
    pub servo: ServoInfo,
    /// Unit tool direction in the WCS, when known.
    pub orientation: Option<[f64; 3]>,
    /// The active kinematic transformation, if any.
    pub transformation: Option<Transformation>,
    /// The block shown as current.
    pub block: Option<Block>,
    /// Active alarms, oldest first.
    pub alarms: Vec<AlarmInfo>,
    /// Active tool and cutting edge.
    pub tool: Tool,
    /// Path velocity in mm/min.
    pub path_velocity: f64,
    /// Counts the programs the channel loaded (a run, MDA, a block search, a restart that
    /// resumed one): when it changes, `GET .../active-program` has another text.
    pub program_serial: u64,
    /// Path length still to go of the block in execution (mm; 0 when nothing moves).
    pub distance_to_go: f64,
    /// Programmed path feed of the block in execution (mm/min); null for rapid traverse or
    /// when no block moves.
    pub programmed_feed: Option<f64>,
    /// The program stands at a preprocessing stop (STOPRE, a read of main-run values): block
    /// preparation waits while the path has nothing left and another part of the main run
    /// (a POSA axis, an online tool offset) still has to finish (absent when not).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub preprocessing_stop_wait: bool,
    /// The workpiece counters (`$AC_..._PARTS`; `PUT .../counters` sets them).
    pub parts: Parts,
    /// The program runtimes (`$AC_OPERATING_TIME`, `$AC_CYCLE_TIME`, `$AC_CUTTING_TIME`).
    pub runtimes: Runtimes,
    /// Spindle speeds in rev/min by channel axis name (signed: + is M3).
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub spindles: AxisValues,
    /// Each spindle's speed, mode (M3/M4/M5/SPOS), angle and master flag, by the names of
    /// `spindles`.
    #[schema(value_type = std::collections::HashMap<String, crate::api::spindle_dto::SpindleInfo>)]
    pub spindle_info: crate::api::spindle_dto::SpindleInfos,
    /// The axes travelling on their own interpolators (POS/POSA/POSP, command axes of
    /// synchronized actions), in channel axis order; absent when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub positioning: Vec<crate::api::positioning_dto::PositioningState>,
    /// The program's last MSG text, if any.
    pub message: Option<String>,
    /// Feed, rapid and spindle override in percent.
    pub overrides: OverridesInfo,
    /// Single block (SBL1) selected.
    pub single_block: bool,
    /// Optional stop (M1) selected.
    pub optional_stop: bool,
    /// Dry-run feed (DRY) selected: path feeds are SD42100 `$SC_DRY_RUN_FEED` as SD42101 says.
    pub dry_run: bool,
    /// Skip levels (SKP) selected, ascending: blocks marked `/n` with one of them are skipped
    /// (`/` is level 0).
    pub skip_levels: Vec<u8>,
    /// Active G functions of the block in execution, one per displayed G group (motion, plane,
    /// radius compensation, settable frame, exact stop, units, dimensions, feed type, arc feed,
    /// corner type, orientation reference, PTP, angle definition, orientation interpolation).
    pub gcodes: Vec<String>,
    /// Reference point state of every machine axis by machine axis name (`true` = referenced).
    /// Unreferenced axes refuse NC start in AUTO and MDA (alarm 16905) while MD20700
    /// REFP_NC_START_LOCK is set; presets start referenced (MD34210 ENC_REFP_STATE = 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<std::collections::HashMap<String, bool>>)]
    pub referenced: Option<AxisFlags>,
    /// The program is interrupted and axes were moved by JOG: NC start first returns to the
    /// interruption point (REPOS).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repos_pending: Option<bool>,
    /// The reference point approach in progress (absent when none runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub referencing: Option<ReferencingInfo>,
    /// The active synchronized actions in the order the main run checks them: by ID, then the
    /// block-modal ones (absent when none is active).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub synchronized_actions: Vec<SyncActionState>,
    /// Material removal: volumes and the checks raised (absent without a blank; details in
    /// `GET .../stock`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stock: Option<crate::api::stock::StockSummary>,
}

/// A reference point approach in progress (JOG REF, axes with an incremental encoder).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ReferencingInfo {
    /// Machine axis name.
    #[schema(example = "X")]
    pub axis: String,
    /// `cam` (travelling to the reference cam at MD34020 and braking on it), `marker`
    /// (to the zero mark at MD34040) or `position` (to the reference point at MD34070).
    #[schema(example = "cam")]
    pub phase: String,
}

/// Axis positions in the three coordinate systems (mm or degrees), as objects name -> value in
/// the machine's axis order.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Positions {
    /// MCS: every machine axis by its machine axis name.
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub machine: AxisValues,
    /// BCS: geometry axes, then the other channel axes, by program name.
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub basic: AxisValues,
    /// WCS: as `basic`, after work offsets.
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub workpiece: AxisValues,
}

/// Setpoint, actual value and following error of every machine axis by machine axis name. The
/// actual value follows the setpoint through a first-order position loop (Kv, MD32200): with
/// FFWON (the presets' reset value) it equals the setpoint; with FFWOF it lags by the
/// velocity over Kv. `positions.machine` keeps showing the setpoint.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ServoInfo {
    /// The interpolator's setpoint (`$AA_IPO`), the same values as `positions.machine`.
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub setpoint: AxisValues,
    /// The actual value (`$AA_IM`).
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub actual: AxisValues,
    /// Setpoint minus actual value.
    #[schema(value_type = std::collections::HashMap<String, f64>)]
    pub following_error: AxisValues,
}

/// Named values that serialize as a JSON object in their given order (the engine's axis order),
/// independent of any map's iteration order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AxisValues(pub Vec<(String, f64)>);

impl Serialize for AxisValues {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// Named flags that serialize as a JSON object in the engine's axis order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AxisFlags(pub Vec<(String, bool)>);

impl Serialize for AxisFlags {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// A kinematic transformation.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Transformation {
    /// E.g. `TRANSMIT`.
    pub name: String,
    /// `$MC_TRAFO_TYPE_n`, e.g. 256.
    #[serde(rename = "type")]
    pub trafo_type: u32,
    /// The data set n (1-based).
    pub index: u32,
}

/// A program block.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Block {
    /// 1-based line in the text of the program the block is in.
    pub line: u32,
    pub text: String,
    /// The subprogram the block is in (its stored name); `null`: the main program.
    pub program: Option<String>,
}

/// An active NC alarm.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct AlarmInfo {
    pub number: u32,
    pub message: String,
    /// 1-based program line, when the alarm belongs to a block.
    pub line: Option<u32>,
}

/// Active tool number T and cutting edge D (D0 = no offset).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct Tool {
    pub t: u32,
    pub d: u32,
    /// The name of the tool in the spindle (`$TC_TP2`; empty for a tool known by number only).
    pub name: String,
    /// The programmed tool `$P_TOOLP`: under MD22550 = 1 the one the next M6 changes to.
    pub prepared: u32,
}

/// The workpiece counters of the channel (Function Manual K1, "workpiece counter"): what
/// MD27880/MD27882 switch on counts in the main run, and programs read and write all four.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Parts {
    /// `$AC_REQUIRED_PARTS`: the setpoint; at 0 nothing is watched.
    #[schema(maximum = 999_999_999)]
    pub required: u32,
    /// `$AC_TOTAL_PARTS`.
    #[schema(maximum = 999_999_999)]
    pub total: u32,
    /// `$AC_ACTUAL_PARTS`: starts again from 0 when it reaches a watched setpoint.
    #[schema(maximum = 999_999_999)]
    pub actual: u32,
    /// `$AC_SPECIAL_PARTS`.
    #[schema(maximum = 999_999_999)]
    pub special: u32,
}

impl From<nctwin_engine::interp::eval::process_vars::PartCounts> for Parts {
    fn from(p: nctwin_engine::interp::eval::process_vars::PartCounts) -> Parts {
        Parts { required: p.required, total: p.total, actual: p.actual, special: p.special }
    }
}

impl From<Parts> for nctwin_engine::interp::eval::process_vars::PartCounts {
    fn from(p: Parts) -> Self {
        Self { required: p.required, total: p.total, actual: p.actual, special: p.special }
    }
}

impl From<nctwin_engine::interp::eval::process_vars::Runtimes> for Runtimes {
    fn from(t: nctwin_engine::interp::eval::process_vars::Runtimes) -> Runtimes {
        Runtimes { operating: t.operating, cycle: t.cycle, cutting: t.cutting }
    }
}

/// The program runtimes in seconds, as MD27860 switches them on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Runtimes {
    /// `$AC_OPERATING_TIME`: all AUTO programs, start to end.
    pub operating: f64,
    /// `$AC_CYCLE_TIME`: the AUTO program started last.
    pub cycle: f64,
    /// `$AC_CUTTING_TIME`: path motion at feed with a tool.
    pub cutting: f64,
}

impl From<&Snapshot> for State {
    fn from(s: &Snapshot) -> State {
        State {
            status: s.status.into(),
            mode: s.mode.into(),
            time: s.time,
            tick: s.tick,
            positions: Positions {
                machine: AxisValues(s.machine.clone()),
                basic: AxisValues(s.basic.clone()),
                workpiece: AxisValues(s.workpiece.clone()),
            },
            servo: ServoInfo {
                setpoint: AxisValues(s.machine.clone()),
                actual: AxisValues(s.actual.clone()),
                following_error: AxisValues(s.following_error.clone()),
            },
            orientation: s.orientation,
            transformation: s.transformation.as_ref().map(Transformation::from),
            block: s.block.as_ref().map(Block::from),
            alarms: s.alarms.iter().map(AlarmInfo::from).collect(),
            tool: Tool { t: s.tool.0, d: s.tool.1, name: s.tool_name.clone(), prepared: s.prepared_tool },
            path_velocity: s.path_velocity,
            program_serial: s.program_serial,
            distance_to_go: s.distance_to_go,
            programmed_feed: s.programmed_feed,
            preprocessing_stop_wait: s.preprocessing_stop_wait,
            parts: s.parts.into(),
            runtimes: s.runtimes.into(),
            spindles: AxisValues(s.spindles.clone()),
            spindle_info: crate::api::spindle_dto::SpindleInfos::of(&s.spindle_states),
            positioning: s.positioning.iter().map(Into::into).collect(),
            message: s.message.clone(),
            overrides: OverridesInfo { feed: s.overrides.feed, rapid: s.overrides.rapid, spindle: s.overrides.spindle },
            single_block: s.single_block,
            optional_stop: s.optional_stop,
            dry_run: s.dry_run,
            skip_levels: s.skip_levels.levels(),
            gcodes: s.gcodes.clone(),
            referenced: Some(AxisFlags(s.referenced.clone())),
            repos_pending: Some(s.repos_pending),
            referencing: s
                .referencing
                .as_ref()
                .map(|(axis, phase)| ReferencingInfo { axis: axis.clone(), phase: phase.as_str().into() }),
            synchronized_actions: s.sync_actions.iter().map(SyncActionState::from).collect(),
            stock: s.stock.as_ref().map(crate::api::stock::StockSummary::from),
        }
    }
}

impl From<&TransformationInfo> for Transformation {
    fn from(t: &TransformationInfo) -> Transformation {
        Transformation { name: t.name.clone(), trafo_type: t.trafo_type, index: t.index }
    }
}

impl From<&BlockRef> for Block {
    fn from(b: &BlockRef) -> Block {
        Block { line: b.line, text: b.text.clone(), program: b.program.clone() }
    }
}

impl From<&Alarm> for AlarmInfo {
    fn from(a: &Alarm) -> AlarmInfo {
        AlarmInfo { number: a.number, message: a.message.clone(), line: a.line }
    }
}

/// How a command's motion is stepped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum PaceOption {
    /// At wall-clock pace (what an operator watches).
    #[default]
    Realtime,
    /// As fast as the server can compute; simulated time is unaffected. Limited to 3600 s of
    /// simulated time per command, after which the channel is stopped (NC stop).
    Fast,
}

impl From<PaceOption> for Pace {
    fn from(p: PaceOption) -> Pace {
        match p {
            PaceOption::Realtime => Pace::Realtime,
            PaceOption::Fast => Pace::Fast,
        }
    }
}

/// Body of `POST /sessions/{id}/run`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RunRequest {
    /// Part program text, one block per line. Absent: the stored program `name` runs (its text
    /// shared, not copied: a CAM program of any stored size).
    #[schema(example = "G0 X10 Y20 Z30\nM30")]
    pub program: Option<String>,
    #[serde(default)]
    pub pace: PaceOption,
    /// Answer when the program has ended, stopped (M0/M1, alarm) or a server-side limit was hit
    /// (fast: 3600 s simulated; any pace: 600 s wall time), with the state at that moment.
    #[serde(default)]
    pub wait: bool,
    /// Sets optional stop (M1 stops) before the start; absent keeps the current setting.
    pub optional_stop: Option<bool>,
    /// Sets dry-run feed (DRY) before the start; absent keeps the current setting.
    pub dry_run: Option<bool>,
    /// Sets the skip levels (SKP, 0..=9) before the start; absent keeps the current setting.
    #[schema(example = json!([0]))]
    pub skip_levels: Option<Vec<i64>>,
    /// The name the program is shown under (`GET .../active-program`), e.g. the stored program
    /// it was read from. Absent: the name of a stored program with the same text, if any.
    /// Without `program`: the stored program to run.
    pub name: Option<String>,
}

/// Body of `POST /sessions/{id}/start`; may be empty.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StartRequest {
    /// When NC start repositions after JOG in the interrupted program (REPOS): where on the
    /// interrupted block it resumes. `RMI` (default) the interruption point, `RMB` the block
    /// start (the block runs again), `RME` the block end (the next block follows), `RMN` the
    /// block's point nearest to the axes. The return is a straight line (REPOSL).
    pub repos: Option<ReposTarget>,
    /// How that repositioning travels back: `REPOSL` (default) or `REPOSA` a straight line,
    /// `REPOSQ` a quarter circle of radius `disr`, `REPOSH` a semicircle of diameter `disr`,
    /// each ending tangentially in the path (in the plane of the path tangent and the side the
    /// tool stands on).
    pub approach: Option<ReposShape>,
    /// DISR in mm for `REPOSQ`/`REPOSH` (required there, positive).
    pub disr: Option<f64>,
    #[serde(default)]
    pub pace: PaceOption,
    /// As for `run`.
    #[serde(default)]
    pub wait: bool,
}

/// The REPOS target mode (G group 26).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, ToSchema)]
pub enum ReposTarget {
    /// The interruption point.
    #[serde(rename = "RMI")]
    Rmi,
    /// The start of the interrupted block.
    #[serde(rename = "RMB")]
    Rmb,
    /// The end of the interrupted block.
    #[serde(rename = "RME")]
    Rme,
    /// The point of the interrupted block nearest to where the axes stand.
    #[serde(rename = "RMN")]
    Rmn,
}

/// The approach shape of REPOS.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, ToSchema)]
pub enum ReposShape {
    #[serde(rename = "REPOSL")]
    Line,
    #[serde(rename = "REPOSA")]
    AllAxes,
    #[serde(rename = "REPOSQ")]
    QuarterCircle,
    #[serde(rename = "REPOSH")]
    SemiCircle,
}

impl StartRequest {
    /// The approach the body asks for; `Err` names what is missing.
    pub fn approach(&self) -> Result<ReposApproach, String> {
        let disr = || match self.disr {
            Some(d) if d.is_finite() && d > 0.0 => Ok(d),
            Some(d) => Err(format!("disr must be a positive distance, not {d}")),
            None => Err("REPOSQ and REPOSH need `disr` (mm)".to_string()),
        };
        Ok(match self.approach {
            None | Some(ReposShape::Line) | Some(ReposShape::AllAxes) => ReposApproach::Line,
            Some(ReposShape::QuarterCircle) => ReposApproach::QuarterCircle { radius: disr()? },
            Some(ReposShape::SemiCircle) => ReposApproach::SemiCircle { diameter: disr()? },
        })
    }
}

impl From<ReposTarget> for ReposMode {
    fn from(t: ReposTarget) -> ReposMode {
        match t {
            ReposTarget::Rmi => ReposMode::Interruption,
            ReposTarget::Rmb => ReposMode::BlockStart,
            ReposTarget::Rme => ReposMode::BlockEnd,
            ReposTarget::Rmn => ReposMode::Nearest,
        }
    }
}

/// Body of `POST /sessions/{id}/mda`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MdaRequest {
    /// Blocks to execute in MDA mode.
    #[schema(example = "G91 G1 X5 F500")]
    pub program: String,
    #[serde(default)]
    pub pace: PaceOption,
    /// As for `run`.
    #[serde(default)]
    pub wait: bool,
}

/// The swivel mode of `POST /sessions/{id}/swivel` (CYCLE800 `_MODE` bits 7–6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SwivelMode {
    /// Rotations `a`, `b`, `c` about the axes of `sequence` in turn, each about the rotated axes.
    AxisByAxis,
    /// `a` about Z, then `b` about the new Y (`c` then turns about the new Z).
    SolidAngle,
    /// Projection angles `a`, `b` about the first two axes of `sequence`, `c` in the plane
    /// about its third axis (e.g. `XYZ`: Xα, Yα, Zβ).
    ProjectionAngle,
    /// `a`, `b` are the positions of rotary axes 1 and 2; the frame follows the kinematics.
    Direct,
}

/// Body of `POST /sessions/{id}/swivel`: the parameters of CYCLE800 by name. The swivel runs
/// as one MDA block `CYCLE800(...)` (from JOG the channel returns to JOG when `wait` is set
/// and the swivel ended without an alarm).
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SwivelRequest {
    /// `_TC`: swivel data set name (`$TC_CARR34`) or number; absent: the active one; `"0"`
    /// deselects (TCARR=0, PAROTOF, TOROTOF; nothing moves). Letters, digits and `_` only.
    #[schema(example = "HEAD_CA")]
    pub data_set: Option<String>,
    /// `_FR` retraction before swivelling: 0 none, 1 machine Z to `$TC_CARR40`, 2 machine Z
    /// then X/Y (`$TC_CARR38/39`), 4 maximum along the tool, 5 `retract_distance` along the tool.
    #[serde(default)]
    pub retract: u8,
    /// `_FR_I`: incremental retraction path for `retract: 5` (mm, ≥ 0).
    #[serde(default)]
    pub retract_distance: f64,
    /// `_ST` units digit: add to the active swivel instead of replacing it.
    #[serde(default)]
    pub additive: bool,
    /// `_ST` tens digit: tool tip tracking (effective with an active TRAORI).
    #[serde(default)]
    pub tracking: bool,
    pub mode: SwivelMode,
    /// Axis sequence for axis-by-axis and projection angle: a permutation of `XYZ`.
    #[serde(default = "default_sequence")]
    #[schema(example = "XYZ")]
    pub sequence: String,
    /// `_X0`, `_Y0`, `_Z0`: reference point of the rotation.
    #[serde(default)]
    pub x0: f64,
    #[serde(default)]
    pub y0: f64,
    #[serde(default)]
    pub z0: f64,
    /// `_A`, `_B`, `_C`: angles in degrees (meaning by `mode`).
    #[serde(default)]
    pub a: f64,
    #[serde(default)]
    pub b: f64,
    #[serde(default)]
    pub c: f64,
    /// `_X1`, `_Y1`, `_Z1`: zero point of the swivelled plane.
    #[serde(default)]
    pub x1: f64,
    #[serde(default)]
    pub y1: f64,
    #[serde(default)]
    pub z1: f64,
    /// `_DIR`: −1 minus (lower value of the direction-reference rotary axis), +1 plus (higher),
    /// 0 compute the plane without moving the rotary axes.
    #[serde(default = "default_direction")]
    pub direction: i8,
    #[serde(default)]
    pub pace: PaceOption,
    /// As for `run`.
    #[serde(default)]
    pub wait: bool,
}

fn default_sequence() -> String {
    "XYZ".into()
}

fn default_direction() -> i8 {
    1
}

/// Body of `PUT /sessions/{id}/mode`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ModeRequest {
    pub mode: OpMode,
}

/// Body of `PUT /sessions/{id}/overrides`: the operator's override switches in percent; absent
/// fields keep their value.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OverridesRequest {
    /// Path feed override, 0..=120 %.
    pub feed: Option<f64>,
    /// Rapid traverse override, 0..=100 %.
    pub rapid: Option<f64>,
    /// Spindle speed override, 50..=120 %.
    pub spindle: Option<f64>,
}

/// Body of `PUT /sessions/{id}/parts`: the workpiece counters to set, each 0..=999,999,999, as
/// the operator sets them on the control's times/counters page; absent fields keep their value.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PartsRequest {
    /// `$AC_REQUIRED_PARTS` (0: not watched).
    #[schema(maximum = 999_999_999)]
    pub required: Option<u32>,
    /// `$AC_TOTAL_PARTS`.
    #[schema(maximum = 999_999_999)]
    pub total: Option<u32>,
    /// `$AC_ACTUAL_PARTS`.
    #[schema(maximum = 999_999_999)]
    pub actual: Option<u32>,
    /// `$AC_SPECIAL_PARTS`.
    #[schema(maximum = 999_999_999)]
    pub special: Option<u32>,
}

/// Body of `PUT /sessions/{id}/options`: program control switches; absent fields keep their value.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OptionsRequest {
    /// Single block (SBL1): the program stops after each block that moves.
    pub single_block: Option<bool>,
    /// Optional stop: M1 stops the program.
    pub optional_stop: Option<bool>,
    /// Dry-run feed (DRY): the path feed of G1/G2/G3.. blocks prepared from now on is SD42100
    /// `$SC_DRY_RUN_FEED`, combined with the programmed feed as SD42101 says (0 max, 1 min,
    /// 2 dry-run feed; 10..12 the same, threads as programmed); G0 stays rapid, the feed
    /// override still acts.
    pub dry_run: Option<bool>,
    /// Skip levels (SKP): the active levels 0..=9 (`[]` none); blocks marked `/n` (`/` = `/0`)
    /// with an active level are skipped when they are prepared, statements included. Blocks
    /// prepared already keep running (a STOPRE before them makes a change certain).
    #[schema(example = json!([0, 2]))]
    pub skip_levels: Option<Vec<i64>>,
}

/// Override switches in percent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct OverridesInfo {
    pub feed: f64,
    pub rapid: f64,
    pub spindle: f64,
}

/// The coordinate system of a JOG motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, ToSchema)]
pub enum JogCoordinates {
    /// Machine coordinates: the machine axis behind the named axis moves alone (with a
    /// transformation active, the machine axis itself).
    #[default]
    #[serde(rename = "MCS")]
    Mcs,
    /// Basic coordinates: a geometry axis moves along the BCS axis (frames do not act); with a
    /// transformation active the tool tip moves Cartesian. Other axes move as in the MCS.
    #[serde(rename = "BCS")]
    Bcs,
    /// Workpiece coordinates: a geometry axis moves along that axis of the active frame (all
    /// geometry axes move when the frame is rotated); with a transformation active the tool tip
    /// moves Cartesian and the machine axes follow. Other axes move as in the MCS.
    #[serde(rename = "WCS")]
    Wcs,
    /// Tool coordinates: a geometry axis moves along that axis of the tool (Z along the tool,
    /// X in the old X-Z plane) with the orientation held. With an orientation transformation the
    /// axes A2, B2, C2 turn the tool about X, Y, Z of the chosen system (BCS, WCS or TCS) while
    /// the tool tip stands still (orientation JOG; increments in degrees).
    #[serde(rename = "TCS")]
    Tcs,
}

/// How orientation JOG changes the tool orientation (SD42660 `$SC_ORI_JOG_MODE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, ToSchema)]
pub enum OrientationRotation {
    /// A2, B2, C2 turn about X, Y, Z of the reference system (SD42660 = 0).
    #[serde(rename = "AXES")]
    Axes,
    /// A2, B2, C2 change the Euler angles ZX'Z'' (1).
    #[serde(rename = "ORIEULER")]
    Euler,
    /// A2, B2, C2 change the RPY angles XY'Z'' (2).
    #[serde(rename = "ORIRPY")]
    Rpy,
    /// A2, B2, C2 change the RPY angles ZY'X'' (3).
    #[serde(rename = "ORIRPY2")]
    Rpy2,
    /// A2, B2, C2 change the angles of MD21120 ORIAX_TURN_TAB_1 (4).
    #[serde(rename = "ORIVIRT1")]
    Virtual1,
    /// A2, B2, C2 change the angles of MD21130 ORIAX_TURN_TAB_2 (5).
    #[serde(rename = "ORIVIRT2")]
    Virtual2,
}

impl From<OrientationRotation> for OrientationJogKind {
    fn from(r: OrientationRotation) -> OrientationJogKind {
        match r {
            OrientationRotation::Axes => OrientationJogKind::Axes,
            OrientationRotation::Euler => OrientationJogKind::Euler,
            OrientationRotation::Rpy => OrientationJogKind::Rpy,
            OrientationRotation::Rpy2 => OrientationJogKind::Rpy2,
            OrientationRotation::Virtual1 => OrientationJogKind::Virtual1,
            OrientationRotation::Virtual2 => OrientationJogKind::Virtual2,
        }
    }
}

impl From<JogCoordinates> for JogSystem {
    fn from(c: JogCoordinates) -> JogSystem {
        match c {
            JogCoordinates::Mcs => JogSystem::Machine,
            JogCoordinates::Bcs => JogSystem::Basic,
            JogCoordinates::Wcs => JogSystem::Workpiece,
            JogCoordinates::Tcs => JogSystem::Tool,
        }
    }
}

/// Body of `POST /sessions/{id}/jog`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct JogBody {
    /// The axis: a machine axis name, a geometry axis name or a channel axis name.
    #[schema(example = "X")]
    pub axis: String,
    /// `1` (plus) or `-1` (minus).
    #[schema(minimum = -1, maximum = 1, example = 1)]
    pub direction: i8,
    /// Variable increment (INCvar): JOG by this distance (mm or degrees, positive). Absent with
    /// `inc` absent: continuous JOG until `jog/stop` or the software limit.
    pub increment: Option<f64>,
    /// Fixed increment INC1, INC10, INC100 or INC1000: that many steps of MD31090
    /// JOG_INCR_WEIGHT (0.001 mm or 0.001° by default). Not together with `increment`.
    #[schema(example = 100)]
    pub inc: Option<u32>,
    /// `MCS`, `BCS`, `WCS` or `TCS`. Absent: as SD42650 `$SC_CART_JOG_MODE` selects (bits
    /// 0/1/2 BCS/WCS/TCS for translation while a transformation is active, else MCS; bits
    /// 8/9/10 for orientation JOG A2/B2/C2, else BCS).
    pub coordinates: Option<JogCoordinates>,
    /// How orientation JOG (A2, B2, C2) turns the tool. Absent: as SD42660 `$SC_ORI_JOG_MODE`
    /// selects (0 = `AXES`).
    pub rotation: Option<OrientationRotation>,
    /// Rapid traverse overlay: MD32010 JOG_VELO_RAPID under the rapid override (else MD32020
    /// JOG_VELO under the feed override).
    #[serde(default)]
    pub rapid: bool,
    #[serde(default)]
    pub pace: PaceOption,
    /// As for `run`: answer when the axis stands.
    #[serde(default)]
    pub wait: bool,
}

impl JogBody {
    /// The JOG distance: `increment`, or `inc` steps (resolved by the channel); `Err` names
    /// what is wrong.
    pub fn validate(&self) -> Result<(), String> {
        if self.increment.is_some() && self.inc.is_some() {
            return Err("give either `increment` (mm) or `inc` (INC steps), not both".into());
        }
        match self.inc {
            Some(n) if !JOG_INCREMENTS.contains(&n) => Err(format!(
                "inc must be 1, 10, 100 or 1000 (INC1 … INC1000), not {n}; use `increment` for a variable distance"
            )),
            _ => Ok(()),
        }
    }
}

/// Body of `POST /sessions/{id}/jog/handwheel`: pulses of a handwheel assigned to one axis.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct HandwheelBody {
    /// The axis: a machine axis name, a geometry axis name or a channel axis name.
    #[schema(example = "X")]
    pub axis: String,
    /// Detents turned, signed by the direction (non-zero, at most 10000 either way).
    #[schema(example = 5)]
    pub pulses: i32,
    /// Increment per detent: 1, 10, 100 or 1000 steps of MD31090 JOG_INCR_WEIGHT (default 1).
    pub inc: Option<u32>,
    /// `MCS` (default), `BCS` or `WCS`.
    #[serde(default)]
    pub coordinates: JogCoordinates,
}

impl HandwheelBody {
    pub fn validate(&self) -> Result<u32, String> {
        if self.pulses == 0 || self.pulses.unsigned_abs() > 10_000 {
            return Err(format!("pulses must be between -10000 and 10000 and not 0, not {}", self.pulses));
        }
        let inc = self.inc.unwrap_or(1);
        if !JOG_INCREMENTS.contains(&inc) {
            return Err(format!("inc must be 1, 10, 100 or 1000 (INC1 … INC1000), not {inc}"));
        }
        Ok(inc)
    }
}

/// Body of `POST /sessions/{id}/search`: block search with calculation.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SearchRequest {
    /// The target line (1-based) of the program.
    #[schema(example = 5)]
    pub line: u32,
    /// The program text to search in (it becomes the active program); absent: the active
    /// program (the one last run or searched).
    pub program: Option<String>,
    /// A stored program (`PUT .../programs/{name}`) to search in, instead of `program`.
    pub name: Option<String>,
    /// A target inside subprograms: `line` of the main program calls `path[0].program`, whose
    /// line `path[0].line` is the target or calls `path[1].program`, and so on; the last step's
    /// line is the target. The search stops the first time preparation reaches that block
    /// through these calls (the subprograms' blocks before it are computed like the main
    /// program's). Absent or empty: `line` of the main program. Each program must be stored
    /// and hold a block at its line (else `400`).
    #[serde(default)]
    #[schema(example = json!([{"program": "HOLE", "line": 2}]))]
    pub path: Vec<SearchStep>,
}

/// One level of a block search target inside subprograms (see [`SearchRequest::path`]); also
/// a level of the current block's place in the state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SearchStep {
    /// The stored program the line of the level above calls (`HOLE`, `hole.spf`).
    #[schema(example = "HOLE")]
    pub program: String,
    /// The 1-based line in it.
    #[schema(example = 2)]
    pub line: u32,
}

/// Body of `POST /sessions/{id}/reference`; may be empty.
#[derive(Debug, Clone, Default, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ReferenceRequest {
    /// The axis to reference (machine, geometry or channel axis name); absent: every
    /// unreferenced axis.
    #[schema(example = "X")]
    pub axis: Option<String>,
    #[serde(default)]
    pub pace: PaceOption,
    /// As for `run`: answer when the reference point approach has ended.
    #[serde(default)]
    pub wait: bool,
}

/// Body of `PUT /sessions/{id}/machine-data`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MachineDataRequest {
    /// NC data text, applied all-or-nothing and activated as by a reset.
    #[schema(example = "$MA_POS_LIMIT_PLUS[X]=400.")]
    pub text: String,
}

/// The stepping options shared by run, start, MDA and JOG.
pub fn drive(pace: PaceOption, wait: bool) -> Drive {
    Drive { pace: pace.into(), wait }
}

/// A message on `GET /sessions/{id}/stream`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum StreamMessage {
    /// The state (at most one per stream period, only when it changed; the first at once).
    State(Box<State>),
    /// Something happened.
    Event(EventMessage),
    /// The stock's tiles a cut changed, pushed after the state showing the new version.
    Stock(crate::api::stock_tiles::StockTilesMessage),
    /// A client message (`jog`, `jog_stop`, `handwheel`) was carried out.
    Ack {
        /// The `type` of the client message.
        request: String,
    },
    /// A client message was refused, or the server stopped a JOG of this client (dead man).
    Error {
        /// The `type` of the client message, when the error answers one.
        request: Option<String>,
        /// What is wrong.
        error: String,
        /// HTTP status the same request would have got over REST (400, 403, 409, 429 ...).
        status: u16,
    },
}

/// A message a client sends on `GET /sessions/{id}/stream` (JSON text): the HMI's JOG keys
/// and handwheel over the low-latency path. Needs control of the session like the REST
/// commands (observers get an `error` with status 403).
#[derive(Debug, Clone, PartialEq, Deserialize, ToSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ClientMessage {
    /// Press a JOG key. Continuous (no `inc`/`increment`): a dead-man motion that runs while
    /// the client keeps sending `jog_keepalive` (or repeats `jog`) at least every 400 ms
    /// (`JOG_DEADMAN`), and stops on `jog_stop`, a missed keep-alive, or disconnect.
    /// Incremental: runs to its distance; stops early on `jog_stop` or disconnect.
    Jog {
        axis: String,
        #[schema(minimum = -1, maximum = 1)]
        direction: i8,
        increment: Option<f64>,
        inc: Option<u32>,
        /// As for `POST .../jog`: absent = SD42650.
        coordinates: Option<JogCoordinates>,
        /// As for `POST .../jog`: absent = SD42660.
        rotation: Option<OrientationRotation>,
        #[serde(default)]
        rapid: bool,
    },
    /// The JOG key is still held.
    JogKeepalive,
    /// Release the JOG key: the motion this client started brakes to standstill.
    JogStop,
    /// Handwheel pulses (as `POST .../jog/handwheel`); stops on disconnect.
    Handwheel {
        axis: String,
        pulses: i32,
        inc: Option<u32>,
        #[serde(default)]
        coordinates: JogCoordinates,
    },
}

/// An event of a session.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum EventMessage {
    AlarmRaised {
        alarm: AlarmInfo,
    },
    AlarmCleared {
        number: u32,
    },
    BlockChanged {
        line: u32,
        text: String,
    },
    /// The program ended (M2/M17/M30 or end of text).
    ProgramEnded,
    /// The program stopped at M0/M1.
    ProgramStopped {
        line: u32,
    },
    ModeChanged {
        mode: OpMode,
    },
    /// An M or H function reached the main run: what the PLC receives. M functions are output
    /// before the block's motion, M0/M1/M2/M17/M30 with their stop after it.
    AuxFunction {
        /// `M` or `H`.
        #[schema(example = "M")]
        letter: String,
        /// The address extension (`M2=5`: 2; plain `M8`: 0).
        extension: u32,
        /// The function's value (`M8`: 8; `H2=1.5`: 1.5).
        value: f64,
        /// As written: `M8`, `M2=5`, `H2=1.5`.
        #[schema(example = "M8")]
        text: String,
        line: u32,
    },
    /// A program set or cleared digital output `signal` (`$A_OUT[signal]`).
    DigitalOutput {
        signal: usize,
        value: bool,
        line: u32,
    },
    /// Signals set from outside (`PUT .../io`) and the IPO cycle count they arrived at: they
    /// act from the next cycle on, so the same inputs at the same counts replay a run exactly.
    InputsChanged {
        tick: u64,
        inputs: Vec<SignalLevel>,
        outputs: Vec<SignalLevel>,
        analog_inputs: Vec<AnalogLevel>,
    },
    /// A check of material removal found something: `rapid_into_stock`, `no_spindle`, `holder_collision` or
    /// `depth_of_cut`, at the program line of the block that cut (`GET .../stock`).
    Stock {
        warning: crate::api::stock::StockWarningInfo,
    },
    /// The action log: an operator's command (`POST start`, `PUT mode`, ...), the role it was
    /// done in and the display name sent with it (header `nctwin-user`; empty when none).
    OperatorAction {
        action: String,
        role: String,
        name: String,
    },
}

/// A digital signal's number and level.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct SignalLevel {
    pub signal: usize,
    pub value: bool,
}

/// An analog signal's number and value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct AnalogLevel {
    pub signal: usize,
    pub value: f64,
}

/// A synchronized action as the state lists it.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct SyncActionState {
    /// `ID=n`/`IDS=n`; `null` for a block-modal action.
    pub id: Option<u32>,
    /// `block` (no ID: while its motion block runs), `modal` (`ID`: until program end or
    /// CANCEL) or `static` (`IDS`: until CANCEL, beyond program end and reset).
    #[schema(example = "modal")]
    pub kind: String,
    /// `WHEN`, `WHENEVER`, `FROM`, `EVERY` or `DO` (no condition).
    #[schema(example = "WHENEVER")]
    pub trigger: String,
    /// The condition as written (upper case); empty for `DO` alone.
    #[schema(example = "$AA_IM[X]>20")]
    pub condition: String,
    /// The actions ran (WHEN/FROM/EVERY: since activation; WHENEVER/DO: in the last cycle).
    pub fired: bool,
    /// Suspended by LOCK.
    pub locked: bool,
    /// The line that defined it.
    pub line: u32,
}

impl From<&nctwin_engine::channel::sync::SyncActionInfo> for SyncActionState {
    fn from(a: &nctwin_engine::channel::sync::SyncActionInfo) -> SyncActionState {
        SyncActionState {
            id: a.id,
            kind: a.kind.into(),
            trigger: a.trigger.into(),
            condition: a.condition.clone(),
            fired: a.fired,
            locked: a.locked,
            line: a.line,
        }
    }
}

impl From<&Event> for EventMessage {
    fn from(e: &Event) -> EventMessage {
        match e {
            Event::AlarmRaised(a) => EventMessage::AlarmRaised { alarm: a.into() },
            Event::AlarmCleared { number } => EventMessage::AlarmCleared { number: *number },
            Event::BlockChanged(b) => EventMessage::BlockChanged { line: b.line, text: b.text.clone() },
            Event::ProgramEnded => EventMessage::ProgramEnded,
            Event::ProgramStopped { line } => EventMessage::ProgramStopped { line: *line },
            Event::ModeChanged(m) => EventMessage::ModeChanged { mode: (*m).into() },
            Event::AuxFunction { function, line } => EventMessage::AuxFunction {
                letter: function.letter.to_string(),
                extension: function.extension,
                value: function.value,
                text: function.text(),
                line: *line,
            },
            Event::DigitalOutput { signal, on, line } => {
                EventMessage::DigitalOutput { signal: *signal, value: *on, line: *line }
            }
            Event::InputsChanged(r) => {
                let levels =
                    |l: &[(usize, bool)]| l.iter().map(|&(signal, value)| SignalLevel { signal, value }).collect();
                EventMessage::InputsChanged {
                    tick: r.tick,
                    inputs: levels(&r.inputs),
                    outputs: levels(&r.outputs),
                    analog_inputs: r.analog.iter().map(|&(signal, value)| AnalogLevel { signal, value }).collect(),
                }
            }
            Event::Stock(w) => EventMessage::Stock { warning: w.into() },
            Event::OperatorAction(a) => {
                EventMessage::OperatorAction { action: a.action.clone(), role: a.role.clone(), name: a.name.clone() }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn state() -> State {
        State {
            status: ChannelStatus::Idle,
            mode: OpMode::Auto,
            time: 0.5,
            tick: 125,
            positions: Positions {
                machine: AxisValues(vec![("Z".into(), 3.0), ("A".into(), 1.0)]),
                basic: AxisValues::default(),
                workpiece: AxisValues::default(),
            },
            servo: ServoInfo {
                setpoint: AxisValues(vec![("Z".into(), 3.0), ("A".into(), 1.0)]),
                actual: AxisValues(vec![("Z".into(), 2.5), ("A".into(), 1.0)]),
                following_error: AxisValues(vec![("Z".into(), 0.5), ("A".into(), 0.0)]),
            },
            orientation: None,
            transformation: None,
            block: None,
            alarms: vec![],
            tool: Tool { t: 0, d: 0, name: String::new(), prepared: 0 },
            path_velocity: 0.0,
            program_serial: 0,
            distance_to_go: 0.0,
            programmed_feed: None,
            preprocessing_stop_wait: false,
            parts: Parts { required: 0, total: 0, actual: 0, special: 0 },
            runtimes: Runtimes { operating: 0.0, cycle: 0.0, cutting: 0.0 },
            spindles: AxisValues::default(),
            spindle_info: Default::default(),
            positioning: vec![],
            message: None,
            overrides: OverridesInfo { feed: 100.0, rapid: 100.0, spindle: 100.0 },
            single_block: false,
            optional_stop: false,
            dry_run: false,
            skip_levels: vec![],
            gcodes: vec!["G1".into(), "G17".into()],
            referenced: None,
            repos_pending: None,
            referencing: None,
            synchronized_actions: vec![],
            stock: None,
        }
    }

    #[test]
    fn axis_values_keep_the_engine_order() {
        let text = serde_json::to_string(&state().positions.machine).unwrap();
        assert_eq!(text, r#"{"Z":3.0,"A":1.0}"#);
    }

    #[test]
    fn a_state_message_is_the_state_with_a_type_field() {
        let v = serde_json::to_value(StreamMessage::State(Box::new(state()))).unwrap();
        assert_eq!(v["type"], "state");
        assert_eq!(v["status"], "idle");
        assert_eq!(v["mode"], "AUTO");
        assert_eq!(v["positions"]["machine"]["Z"], 3.0);
        assert_eq!(v["servo"]["following_error"]["Z"], 0.5);
    }

    #[test]
    fn event_messages_name_the_event() {
        let ended = serde_json::to_value(StreamMessage::Event(EventMessage::ProgramEnded)).unwrap();
        assert_eq!(ended, json!({"type": "event", "event": "program_ended"}));
        let mode = serde_json::to_value(StreamMessage::Event(EventMessage::ModeChanged { mode: OpMode::Jog })).unwrap();
        assert_eq!(mode, json!({"type": "event", "event": "mode_changed", "mode": "JOG"}));
        let alarm = EventMessage::AlarmRaised { alarm: AlarmInfo { number: 10720, message: "m".into(), line: None } };
        let v = serde_json::to_value(StreamMessage::Event(alarm)).unwrap();
        assert_eq!(
            v,
            json!({"type": "event", "event": "alarm_raised", "alarm": {"number": 10720, "message": "m", "line": null}})
        );
    }

    #[test]
    fn request_bodies_reject_unknown_fields() {
        let e = serde_json::from_str::<RunRequest>(r#"{"program": "M30", "wiat": true}"#).unwrap_err();
        assert!(e.to_string().contains("unknown field `wiat`"), "{e}");
    }
}

/// A stored program in a listing.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ProgramInfo {
    /// Upper-case name (a `.MPF`/`.SPF` ending given on upload is dropped).
    pub name: String,
    /// Size of the text in bytes.
    pub size: usize,
}

/// A stored program with its text.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ProgramText {
    pub name: String,
    pub text: String,
}

/// Body of `PUT /sessions/{id}/programs/{name}`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ProgramBody {
    /// Program text; refused with 400 and the line when it has syntax errors.
    #[schema(example = "PROC HOLE(REAL DEPTH)\nG1 Z=-DEPTH F200\nG0 Z5\nRET")]
    pub text: String,
}

/// Body of `POST /sessions/{id}/check`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CheckRequest {
    pub program: String,
}

/// One error found by `check`.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct DiagnosticInfo {
    /// The NC alarm number: 12080 syntax error, 12640 invalid nesting of control structures,
    /// 12641 nesting too deep; for names: 12470 unknown G function, 12550 name not defined,
    /// 14011 called program not available, 14080 jump destination not found.
    pub alarm: u32,
    /// 1-based line.
    pub line: u32,
    /// 1-based column within the line.
    pub column: usize,
    pub message: String,
}

impl From<&nctwin_engine::lang::Diagnostic> for DiagnosticInfo {
    fn from(d: &nctwin_engine::lang::Diagnostic) -> Self {
        DiagnosticInfo { alarm: d.alarm, line: d.line, column: d.column as usize, message: d.message.clone() }
    }
}

/// The errors of a program found without running it (syntax, and names a run would refuse):
/// the first 1000 in program order, and the count of the others.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CheckResponse {
    pub diagnostics: Vec<DiagnosticInfo>,
    /// Errors found beyond the first 1000 ([`MAX_DIAGNOSTICS`]), not listed (absent when
    /// every error is listed).
    #[serde(skip_serializing_if = "is_zero")]
    pub omitted: usize,
}

/// `POST /sessions/{id}/program-archive`: what an archive held and what was stored.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ArchiveImport {
    /// The programs stored, in archive order.
    pub programs: Vec<ArchiveProgram>,
    /// The NC data sections (`_INI`: tool offsets, frames, setting data) loaded and activated,
    /// in archive order, as the control loads an INI file it reads in.
    pub nc_data: Vec<ArchiveNcData>,
    /// Sections of the archive that are neither programs nor NC data, not stored.
    pub skipped: Vec<ArchiveSkipped>,
}

/// An NC data section (`%_N_TOA_INI` ...) of an archive, loaded.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ArchiveNcData {
    /// Name and type as the header writes them, e.g. `TOA_INI`.
    pub name: String,
    /// Line of its header in the archive.
    pub line: u32,
}

/// A program of an archive, stored under `name`.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ArchiveProgram {
    /// The stored name: with its directory when the archive's `;$PATH=` names one
    /// (`/_N_WKS_DIR/_N_FLANGE_WPD/FLANGE`), else the name alone (the session's flat store).
    pub name: String,
    /// `MPF` (main program) or `SPF` (subprogram), from its header.
    #[serde(rename = "type")]
    pub kind: String,
    /// The directory of its `;$PATH=` line (else `_N_MPF_DIR`/`_N_SPF_DIR` by type, the
    /// directory the export files it in).
    pub directory: String,
    /// Size of the program text (without its header lines) in bytes.
    pub size: usize,
}

/// A section of an archive that was not stored.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ArchiveSkipped {
    /// Name and type as the header writes them, e.g. `TOA_INI`.
    pub name: String,
    /// Line of its header in the archive.
    pub line: u32,
    pub reason: String,
}
