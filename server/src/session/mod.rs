//! Sessions: one actor task per simulated channel, and the handle the rest of the server uses.
//!
//! The actor (module `actor`) is the only code that touches a session's `Channel`; everything else
//! talks to it through a [`SessionHandle`]:
//! - commands go on a bounded `mpsc` queue, each with a `oneshot` for its reply;
//! - the latest state is published on a `watch` channel: readers (REST `GET .../state`, every
//!   WebSocket viewer) just look at the newest snapshot, and a slow viewer skips intermediate
//!   states, so nobody can slow the machine down;
//! - events (alarms, block changes, program end, ...) go on a `broadcast` channel of
//!   [`EVENT_CAPACITY`] entries.
//!
//! This module knows nothing of HTTP or JSON: it speaks engine types.

pub mod active_program;
mod actor;
mod pacer;
pub mod path_history;
mod snapshot_pool;
pub mod stock_feed;
mod wake_stats;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Duration;

use nctwin_engine::channel::{JogSystem, OrientationJogKind, ReposApproach, ReposMode};
use nctwin_engine::interp::program_control::SkipLevels;
use nctwin_engine::{Channel, CommandError, Event, JogRequest, Mode, Snapshot};
use tokio::sync::{broadcast, mpsc, oneshot, watch};

/// Sets `channel`'s clock (`$A_YEAR`..) to the wall time now: a new or restored session, or a
/// run of `nctwin simulate`, stamps what its programs write with the day it runs on.
pub fn start_clock(channel: &mut Channel) {
    let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default();
    channel.set_clock(i64::try_from(now.as_millis()).unwrap_or(i64::MAX));
}

pub use pacer::Pacer;
pub use wake_stats::{LATENESS_BUCKETS, WakeCounts, wake_stats};

/// Capacity of a session's event channel. A subscriber that falls more than this many events
/// behind does not slow the session down: its next `recv` reports the lag and it continues with
/// the oldest event still held (the skipped events are lost for that subscriber only).
pub const EVENT_CAPACITY: usize = 256;

/// Capacity of a session's command queue. Senders wait when it is full, which is back-pressure
/// on clients that flood one session, not on the session.
const COMMAND_CAPACITY: usize = 64;

/// How a command that starts motion is stepped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pace {
    /// At wall-clock pace: the actor wakes once per stream period and runs the IPO cycles that
    /// wall time owes.
    #[default]
    Realtime,
    /// As fast as the machine can compute, on a blocking-capable worker, until the program or
    /// motion ends (or the simulated-time limit is hit).
    Fast,
}

/// Stepping options of a command that starts something (run, start, MDA, JOG).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Drive {
    pub pace: Pace,
    /// Reply only once the channel is no longer running and nothing moves (or a limit is hit).
    pub wait: bool,
}

/// Program control switches (Operate's "Program control"); `None` keeps a value.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ProgramOptions {
    /// SBL1: stop after each block that moves.
    pub single_block: Option<bool>,
    /// M01: M1 stops the program.
    pub optional_stop: Option<bool>,
    /// DRY: path feeds become SD42100's dry-run feed.
    pub dry_run: Option<bool>,
    /// SKP: the active skip levels.
    pub skip_levels: Option<SkipLevels>,
}

impl ProgramOptions {
    /// The channel's current switches, all given (to put them back).
    pub fn of(channel: &Channel) -> ProgramOptions {
        ProgramOptions {
            single_block: Some(channel.single_block),
            optional_stop: Some(channel.optional_stop),
            dry_run: Some(channel.dry_run),
            skip_levels: Some(channel.skip_levels),
        }
    }

    /// Sets the switches given on `channel`.
    pub fn apply(&self, channel: &mut Channel) {
        if let Some(on) = self.single_block {
            channel.single_block = on;
        }
        if let Some(on) = self.optional_stop {
            channel.optional_stop = on;
        }
        if let Some(on) = self.dry_run {
            channel.dry_run = on;
        }
        if let Some(levels) = self.skip_levels {
            channel.skip_levels = levels;
        }
    }
}

/// What a command asks the channel to do.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// Load a program and start it in AUTO mode; `options` set program control first (kept
    /// as they were if the start fails). `program: None`: the stored program `name`.
    Run {
        program: Option<String>,
        options: ProgramOptions,
        /// The name the program is shown under (a stored program's); `None`: the server looks
        /// for a stored program with the same text.
        name: Option<String>,
    },
    /// Execute blocks in MDA mode.
    Mda {
        program: String,
    },
    /// NC start: continue after M0/M1/NC stop.
    Start,
    /// NC start whose repositioning after JOG resumes at the given point (RMI/RMB/RME/RMN)
    /// along the given approach (REPOSL/REPOSQ/REPOSH).
    StartRepos(ReposMode, ReposApproach),
    /// NC stop.
    Stop,
    /// Channel reset.
    Reset,
    /// Clear cancel-type alarms.
    Cancel,
    SetMode(Mode),
    /// Override switches in percent; `None` keeps a value.
    SetOverrides {
        feed: Option<f64>,
        rapid: Option<f64>,
        spindle: Option<f64>,
    },
    /// Program control: single block, optional stop, dry run, skip levels.
    SetOptions(ProgramOptions),
    /// The workpiece counters (required, total, actual, special); `None` keeps a value.
    SetParts([Option<u32>; 4]),
    /// Start a JOG motion; `inc` (INC steps of MD31090) replaces `request.increment`.
    Jog {
        request: JogRequest,
        /// `None`: SD42650 decides.
        system: Option<JogSystem>,
        /// `None`: SD42660 decides.
        rotation: Option<OrientationJogKind>,
        inc: Option<u32>,
    },
    /// Handwheel pulses on one axis, `inc` steps per pulse.
    Handwheel {
        axis: String,
        pulses: i32,
        inc: u32,
        system: JogSystem,
    },
    JogStop,
    /// Release the JOG key only if motion number `serial` is still the latest one.
    JogStopIf(u64),
    /// Block search with calculation to `line` of `program` (or of the active program).
    Search {
        program: Option<String>,
        /// A stored program's name to search in.
        name: Option<String>,
        line: u32,
        /// Steps into subprograms from `line` (see `SearchRequest::path`).
        path: Vec<nctwin_engine::channel::PathStep>,
    },
    /// Reference one axis, or all.
    Reference(Option<String>),
    /// Apply NC data text in reset state.
    MachineData(String),
    /// Set WO: the active work offset so that `axis` reads `value` (reset state).
    SetWorkOffset {
        axis: String,
        value: f64,
    },
    /// Run a kinematic chain program ($NK_/$NT_ assignments) on the data in reset state.
    KinematicChains(String),
    /// Replace the tool data ($TC_DP/$TC_TP/$TC_MAP/$TC_MPP/$TC_MOP lines) in reset state.
    ToolData(String),
    /// Load the tool `name` (with its duplo number if several share the name) into a place.
    LoadTool {
        name: String,
        duplo: Option<i64>,
        magazine: u32,
        place: u32,
    },
    /// Unload the tool `name` to the loading magazine.
    UnloadTool {
        name: String,
        duplo: Option<i64>,
    },
}

/// A server-side limit that ended a command early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Limit {
    /// A fast run reached [`crate::Limits::fast_sim_time`] of simulated time and was stopped.
    FastSimTime,
    /// A fast run reached [`crate::Limits::fast_wall_time`] of wall time and was stopped.
    FastWallTime,
    /// A waiting request reached [`crate::Limits::wait_wall_time`] of wall time.
    WaitWallTime,
}

/// The reply to a successful command: the state at that moment.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub snapshot: Arc<Snapshot>,
    /// Set when a server-side limit ended the command (or its wait) early.
    pub limit: Option<Limit>,
}

/// Why a command got no reply from the channel.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SessionError {
    /// The channel refused the command.
    #[error(transparent)]
    Command(#[from] CommandError),
    /// The actor has ended (the session was deleted, or stopped serving here).
    #[error("the session has ended")]
    Ended,
    /// The actor was ended because the server is shutting down (see
    /// [`SessionHandle::shutdown_for_server_stop`]): the session is saved and comes back with
    /// the server.
    #[error("the server is shutting down")]
    ServerStopping,
}

/// Tunables of every session actor; see [`crate::Limits`] for the values and their meaning.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ActorConfig {
    /// Wake period of real-time pacing.
    pub period: Duration,
    /// Simulated seconds a fast-paced command may run before it is stopped.
    pub fast_sim_time: f64,
    /// Wall time after which a waiting request is answered anyway.
    pub wait_wall_time: Duration,
    /// IPO cycles per blocking chunk in fast pace.
    pub fast_chunk: u64,
    /// Wall time a fast-paced command may run before it is stopped.
    pub fast_wall_time: Duration,
}

/// A request to the actor with the channel for its reply.
#[derive(Debug)]
enum Request {
    Command {
        action: Action,
        drive: Option<Drive>,
        reply: oneshot::Sender<Result<Outcome, CommandError>>,
    },
    /// End the actor; the reply is sent as its last act.
    Shutdown {
        reply: oneshot::Sender<()>,
    },
    /// Read or change data of the channel that needs no stepping (stored programs, ...); the
    /// closure sends its own reply.
    Query(Query),
}

/// A job run on the channel inside the actor.
struct Query(Box<dyn FnOnce(&mut Channel) + Send>);

impl std::fmt::Debug for Query {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Query")
    }
}

/// A cheap-to-clone handle to one running session.
#[derive(Debug, Clone)]
pub struct SessionHandle {
    id: Arc<str>,
    machine: Arc<str>,
    requests: mpsc::Sender<Request>,
    state: watch::Receiver<Arc<Snapshot>>,
    events: broadcast::Sender<Event>,
    settled: watch::Receiver<u64>,
    lag_micros: Arc<AtomicU64>,
    /// Set before the actor is ended for a server shutdown, so requests that lose their reply
    /// are told [`SessionError::ServerStopping`] rather than [`SessionError::Ended`].
    server_stopping: Arc<AtomicBool>,
    /// The loaded program's name and line index (see `active_program`).
    active: Arc<active_program::ActiveCache>,
    /// The executed path so far (see `path_history`); the actor records, REST reads.
    history: Arc<std::sync::Mutex<path_history::PathHistory>>,
    /// The stock's changes for the streams (see `stock_feed`).
    stock_feed: Arc<stock_feed::StockFeed>,
}

impl SessionHandle {
    /// Starts the actor for `channel` on the current Tokio runtime.
    pub fn spawn(id: &str, machine: &str, channel: Channel, config: ActorConfig) -> SessionHandle {
        let (requests, rx) = mpsc::channel(COMMAND_CAPACITY);
        let (state_tx, state) = watch::channel(Arc::new(channel.snapshot()));
        let (events, _) = broadcast::channel(EVENT_CAPACITY);
        let (settled_tx, settled) = watch::channel(0);
        let lag_micros = Arc::new(AtomicU64::new(0));
        let active = Arc::new(active_program::ActiveCache::default());
        let history = Arc::default();
        let mut actor =
            actor::Actor::new(config, state_tx, events.clone(), settled_tx, lag_micros.clone(), active.clone());
        actor.history = Arc::clone(&history);
        let stock_feed = Arc::new(stock_feed::StockFeed::default());
        actor.stock_feed = stock_feed.clone();
        tokio::spawn(actor.run(Box::new(channel), rx));
        SessionHandle {
            id: id.into(),
            machine: machine.into(),
            requests,
            state,
            events,
            settled,
            lag_micros,
            server_stopping: Arc::default(),
            active,
            history,
            stock_feed,
        }
    }

    /// The id the registry knows the session by.
    pub fn id(&self) -> &str {
        &self.id
    }

    /// The preset the session was created from.
    pub fn machine(&self) -> &str {
        &self.machine
    }

    /// The executed path recorded so far (held only to copy it: the actor records into it).
    pub fn path_history(&self) -> &Arc<std::sync::Mutex<path_history::PathHistory>> {
        &self.history
    }

    /// The loaded program's name and line index cache.
    pub fn active_cache(&self) -> &Arc<active_program::ActiveCache> {
        &self.active
    }

    /// The stock's changes for the streams.
    pub fn stock_feed(&self) -> &Arc<stock_feed::StockFeed> {
        &self.stock_feed
    }

    /// Whether the actor has ended (deleted, or its engine failed): its last published state
    /// no longer changes.
    pub fn has_ended(&self) -> bool {
        self.state.has_changed().is_err()
    }

    /// The latest published state; never waits for the actor.
    pub fn snapshot(&self) -> Arc<Snapshot> {
        self.state.borrow().clone()
    }

    /// A receiver of the latest state; `changed()` fails once the session has ended.
    pub fn watch_state(&self) -> watch::Receiver<Arc<Snapshot>> {
        self.state.clone()
    }

    /// A receiver of the events from now on (see [`EVENT_CAPACITY`] for lag behaviour).
    pub fn subscribe_events(&self) -> broadcast::Receiver<Event> {
        self.events.subscribe()
    }

    /// A counter the actor increments each time the channel comes to rest (nothing moves, no
    /// program runs) after one or more commands: the moment to save positions and mode.
    /// `changed()` fails once the session has ended.
    pub fn watch_settled(&self) -> watch::Receiver<u64> {
        self.settled.clone()
    }

    /// How late the last real-time wake-up came against its schedule (zero while the channel
    /// is not stepped in real time): the IPO lag a viewer sees on top of the stream period.
    pub fn ipo_lag(&self) -> Duration {
        Duration::from_micros(self.lag_micros.load(Ordering::Relaxed))
    }

    /// Sends a command and waits for its reply (with `drive.wait`, until the motion is over).
    pub async fn command(&self, action: Action, drive: Option<Drive>) -> Result<Outcome, SessionError> {
        let (reply, rx) = oneshot::channel();
        self.requests.send(Request::Command { action, drive, reply }).await.map_err(|_| self.ended())?;
        Ok(rx.await.map_err(|_| self.ended())??)
    }

    /// Runs `query` on the channel inside the actor (between IPO cycles) and returns its result.
    pub async fn with_channel<R: Send + 'static>(
        &self,
        query: impl FnOnce(&mut Channel) -> R + Send + 'static,
    ) -> Result<R, SessionError> {
        let (reply, rx) = oneshot::channel();
        let job = Box::new(move |channel: &mut Channel| {
            let _ = reply.send(query(channel));
        });
        self.requests.send(Request::Query(Query(job))).await.map_err(|_| self.ended())?;
        rx.await.map_err(|_| self.ended())
    }

    /// Why a request got no reply from the ended actor.
    fn ended(&self) -> SessionError {
        if self.server_stopping.load(Ordering::Acquire) { SessionError::ServerStopping } else { SessionError::Ended }
    }

    /// Ends the actor and waits until it has stopped. Waiting requests get
    /// [`SessionError::Ended`]; streams see the state channel close.
    pub async fn shutdown(&self) {
        let (reply, rx) = oneshot::channel();
        if self.requests.send(Request::Shutdown { reply }).await.is_ok() {
            let _ = rx.await;
        }
    }

    /// As [`SessionHandle::shutdown`], for a server shutdown: waiting and later requests get
    /// [`SessionError::ServerStopping`] (the session is saved and comes back with the server).
    pub async fn shutdown_for_server_stop(&self) {
        self.server_stopping.store(true, Ordering::Release);
        self.shutdown().await;
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use nctwin_engine::Status;
    use tokio::time::Instant;

    use super::*;

    fn config() -> ActorConfig {
        ActorConfig {
            period: Duration::from_millis(50),
            fast_sim_time: 3600.0,
            wait_wall_time: Duration::from_secs(600),
            fast_chunk: 1000,
            fast_wall_time: Duration::from_secs(10),
        }
    }

    fn mill() -> SessionHandle {
        let channel = Channel::from_preset("mill-3axis", "").expect("preset");
        SessionHandle::spawn("t", "mill-3axis", channel, config())
    }

    fn run(program: &str) -> Action {
        Action::Run { program: Some(program.into()), options: ProgramOptions::default(), name: None }
    }

    fn x(snapshot: &Snapshot) -> f64 {
        snapshot.machine[0].1
    }

    #[tokio::test(start_paused = true)]
    async fn realtime_pace_keeps_simulated_time_with_the_clock() {
        let session = mill();
        let start = Instant::now();
        let drive = Drive { pace: Pace::Realtime, wait: true };
        let outcome = session.command(run("G1 X10 F600\nM30"), Some(drive)).await.expect("run");
        let wall = start.elapsed().as_secs_f64();
        let snapshot = &outcome.snapshot;
        assert_eq!((snapshot.status, x(snapshot)), (Status::Idle, 10.0));
        // The clock is paused and advanced by Tokio only when every task sleeps, so this is
        // exact arithmetic, not a measurement: the difference is below one wake period.
        assert!((snapshot.time - wall).abs() <= 0.05 + 0.004, "simulated {} s, wall {wall} s", snapshot.time);
    }

    #[tokio::test(start_paused = true)]
    async fn an_idle_session_is_not_stepped() {
        let session = mill();
        let drive = Drive { pace: Pace::Realtime, wait: true };
        let end = session.command(run("G1 X1 F600\nM30"), Some(drive)).await.expect("run").snapshot;
        tokio::time::sleep(Duration::from_secs(60)).await;
        assert_eq!(session.snapshot().tick, end.tick);
    }

    #[tokio::test(start_paused = true)]
    async fn fast_and_realtime_pace_end_in_the_same_state() {
        let program = "G1 X10 Y5 F900\nG0 Z20\nG1 X0 F3000\nM30";
        let fast = mill()
            .command(run(program), Some(Drive { pace: Pace::Fast, wait: true }))
            .await
            .expect("fast run")
            .snapshot;
        let realtime = mill()
            .command(run(program), Some(Drive { pace: Pace::Realtime, wait: true }))
            .await
            .expect("realtime run")
            .snapshot;
        assert_eq!(fast, realtime);
    }

    #[tokio::test(start_paused = true)]
    async fn a_stop_acts_between_fast_chunks() {
        let session = mill();
        // One hundred simulated seconds: many chunks of 1000 cycles.
        let moving = session.command(run("G1 X100 F60\nM30"), Some(Drive { pace: Pace::Fast, wait: false })).await;
        assert_eq!(moving.expect("run").snapshot.status, Status::Running);
        let stopped = session.command(Action::Stop, None).await.expect("stop").snapshot;
        assert_eq!(stopped.status, Status::Stopped);
        assert!(x(&stopped) < 100.0);
    }

    #[tokio::test(start_paused = true)]
    async fn the_settled_counter_moves_when_a_command_has_come_to_rest() {
        let session = mill();
        let mut settled = session.watch_settled();
        let drive = Drive { pace: Pace::Realtime, wait: false };
        session.command(run("G1 X1 F600\nM30"), Some(drive)).await.expect("run");
        assert!(!settled.has_changed().expect("open"), "not while the program runs");
        settled.changed().await.expect("settles at the program end");
        assert_eq!(session.snapshot().status, Status::Idle);
        session.command(Action::SetMode(Mode::Jog), None).await.expect("mode");
        settled.changed().await.expect("a command without motion settles at once");
        session.with_channel(|ch| ch.stored_programs()).await.expect("query");
        tokio::time::sleep(Duration::from_secs(1)).await;
        assert!(!settled.has_changed().expect("open"), "reads do not count");
    }

    #[tokio::test(start_paused = true)]
    async fn commands_after_shutdown_report_that_the_session_ended() {
        let session = mill();
        let mut states = session.watch_state();
        session.shutdown().await;
        assert_eq!(session.command(Action::Reset, None).await.unwrap_err(), SessionError::Ended);
        assert!(states.changed().await.is_err(), "the state channel is closed");
    }

    #[tokio::test(start_paused = true)]
    async fn a_session_whose_engine_failed_reports_that_it_has_ended() {
        // An engine panic ends the actor; its last published state no longer changes, and the
        // state endpoint answers 404 instead of that stale picture (found by the fuzzers).
        let session = mill();
        assert!(!session.has_ended());
        let failed = session.with_channel(|_| -> u32 { panic!("an engine defect") }).await;
        assert_eq!(failed.unwrap_err(), SessionError::Ended);
        assert!(session.has_ended());
        let session = mill();
        session.shutdown().await;
        assert!(session.has_ended(), "a deleted session too");
    }
}
