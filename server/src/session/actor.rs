//! The session actor: the one task that owns a `Channel`, applies commands to it and steps it.
//!
//! When is the channel stepped?
//! - Idle (`Channel::is_active()` is false): never; the task sleeps until a request arrives.
//! - Real-time pace: the task wakes once per period and runs the IPO cycles wall time owes
//!   ([`Pacer`]), so thousands of sessions fit on two cores.
//! - Fast pace: chunks of [`ActorConfig::fast_chunk`] cycles run back to back on a blocking
//!   worker (`spawn_blocking`), the channel moved there and back, so the async runtime is never
//!   starved. Between chunks the state is published and queued requests are handled, so an NC
//!   stop or reset acts at once. Fast pace ends with the motion (`is_busy()` false); whatever
//!   still turns (a spindle) then goes on in real time.
//!
//! A block search may prepare millions of blocks: it, too, runs on a blocking worker, bounded
//! by `SEARCH_WALL_LIMIT` (alarm 15370 when it is spent); requests wait for it.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use nctwin_engine::{Channel, CommandError, Event, Overrides, Snapshot, Status};
use tokio::sync::{broadcast, mpsc, oneshot, watch};
use tokio::time::{Instant, sleep_until};

use super::active_program::ActiveCache;
use super::snapshot_pool::SnapshotPool;
use super::wake_stats::wake_stats;
use super::{Action, ActorConfig, Limit, Outcome, Pace, Pacer, ProgramOptions, Request};

/// Wall time a block search may compute before it gives up with alarm 15370 (a program that
/// never reaches its target, a LOOP without end); the engine's own limit is
/// `SEARCH_BLOCK_BUDGET` blocks.
const SEARCH_WALL_LIMIT: std::time::Duration = std::time::Duration::from_secs(10);

/// Extra simulated seconds a fast run stopped by its limit may take to brake before the actor
/// resets the channel.
const BRAKE_GRACE: f64 = 60.0;

/// A request that asked to be answered once the motion is over.
#[derive(Debug)]
struct Waiter {
    reply: oneshot::Sender<Result<Outcome, CommandError>>,
    /// Wall time at which it is answered anyway.
    deadline: Instant,
}

/// What the loop does after a request.
enum Flow {
    Continue,
    Stop(oneshot::Sender<()>),
}

/// Everything the actor keeps besides the channel itself (which is moved to blocking workers
/// in fast pace and therefore lives in a local variable of [`Actor::run`]).
pub(super) struct Actor {
    config: ActorConfig,
    state: watch::Sender<Arc<Snapshot>>,
    /// Retired snapshots, refreshed in place as the next state.
    snapshots: SnapshotPool,
    events: broadcast::Sender<Event>,
    pace: Pace,
    /// Tick at which the current fast-paced command is stopped.
    fast_limit_tick: u64,
    /// Wall time at which the current fast-paced command is stopped (a program that computes
    /// without end, e.g. a LOOP without motion, must not hold a worker for long).
    fast_deadline: Instant,
    /// The fast limit (simulated or wall time) that stopped the channel; replies report it
    /// until the next driving command.
    limit_hit: Option<Limit>,
    /// Present while the channel is stepped in real time.
    pacer: Option<Pacer>,
    next_wake: Instant,
    waiters: Vec<Waiter>,
    /// Incremented when the channel comes to rest after commands (see
    /// `SessionHandle::watch_settled`).
    settled: watch::Sender<u64>,
    /// A command was applied since the channel last came to rest.
    dirty: bool,
    /// Lateness of the last real-time wake-up in microseconds (see `SessionHandle::ipo_lag`).
    lag_micros: Arc<AtomicU64>,
    /// Where the name a program was started under is recorded.
    active: Arc<super::active_program::ActiveCache>,
    /// The executed path, recorded from every published state (a std mutex: held for one
    /// push, never across an await).
    pub(super) history: Arc<std::sync::Mutex<super::path_history::PathHistory>>,
    /// The stock's changes for the streams (set by `SessionHandle::spawn`).
    pub(super) stock_feed: Arc<super::stock_feed::StockFeed>,
}

impl Actor {
    pub(super) fn new(
        config: ActorConfig,
        state: watch::Sender<Arc<Snapshot>>,
        events: broadcast::Sender<Event>,
        settled: watch::Sender<u64>,
        lag_micros: Arc<AtomicU64>,
        active: Arc<super::active_program::ActiveCache>,
    ) -> Actor {
        Actor {
            config,
            state,
            snapshots: SnapshotPool::default(),
            events,
            pace: Pace::Realtime,
            fast_limit_tick: 0,
            fast_deadline: Instant::now(),
            limit_hit: None,
            pacer: None,
            next_wake: Instant::now(),
            waiters: Vec::new(),
            settled,
            dirty: false,
            lag_micros,
            active,
            history: Arc::default(),
            stock_feed: Arc::default(),
        }
    }

    /// The actor loop; ends on a shutdown request, when every handle is gone, or when the
    /// engine panics on a blocking worker (the session then reports that it has ended).
    pub(super) async fn run(mut self, mut channel: Box<Channel>, mut requests: mpsc::Receiver<Request>) {
        loop {
            if self.pace == Pace::Fast && !channel.is_busy() {
                // The fast motion is over (or never started); what still turns goes on in real time.
                self.pace = Pace::Realtime;
            }
            if self.pace == Pace::Fast {
                self.pacer = None;
                // Requests that queued up during the last chunk act before the next one.
                loop {
                    match requests.try_recv() {
                        Ok(request) => match self.dispatch(channel, request).await {
                            Some((c, Flow::Continue)) => channel = c,
                            Some((_, Flow::Stop(reply))) => return self.finish(reply),
                            None => return,
                        },
                        Err(mpsc::error::TryRecvError::Empty) => break,
                        Err(mpsc::error::TryRecvError::Disconnected) => return,
                    }
                }
                if self.pace == Pace::Fast && channel.is_busy() {
                    match self.fast_chunk(channel).await {
                        Some(c) => channel = c,
                        None => return,
                    }
                }
                continue;
            }

            let stepping = channel.is_active();
            if !stepping {
                self.pacer = None;
                self.lag_micros.store(0, Ordering::Relaxed);
            } else if self.pacer.is_none() {
                let now = Instant::now();
                self.pacer = Some(Pacer::new(channel.config().ipo_cycle, now));
                self.next_wake = now + self.config.period;
            }
            tokio::select! {
                request = requests.recv() => match request {
                    None => return,
                    Some(request) => match self.dispatch(channel, request).await {
                        Some((c, Flow::Continue)) => channel = c,
                        Some((_, Flow::Stop(reply))) => return self.finish(reply),
                        None => return,
                    },
                },
                () = sleep_until(self.next_wake), if stepping => self.realtime_wake(&mut channel),
            }
        }
    }

    /// Drops the state and event senders (closing every stream) and then confirms shutdown.
    fn finish(self, reply: oneshot::Sender<()>) {
        drop(self);
        let _ = reply.send(());
    }

    /// Handles one request. A block search computes on a blocking worker (it may prepare
    /// millions of blocks: the async runtime must not wait for it), the channel moved there and
    /// back as in fast pace. `None` if the engine panicked there (the session has ended).
    async fn dispatch(&mut self, mut channel: Box<Channel>, request: Request) -> Option<(Box<Channel>, Flow)> {
        let Request::Command { action: action @ Action::Search { .. }, drive, reply } = request else {
            let flow = self.handle(&mut channel, request);
            return Some((channel, flow));
        };
        let active = self.active.clone();
        let joined = tokio::task::spawn_blocking(move || {
            let result = apply(&mut channel, action, &active);
            (channel, result)
        })
        .await;
        match joined {
            Ok((mut channel, result)) => {
                let flow = self.command_applied(&mut channel, result, drive, reply);
                Some((channel, flow))
            }
            Err(e) => {
                tracing::error!(error = %e, "session engine failed during a block search; the session has ended");
                None
            }
        }
    }

    fn handle(&mut self, channel: &mut Channel, request: Request) -> Flow {
        let (action, drive, reply) = match request {
            Request::Shutdown { reply } => return Flow::Stop(reply),
            Request::Query(job) => {
                (job.0)(channel);
                self.publish(channel);
                return Flow::Continue;
            }
            Request::Command { action, drive, reply } => (action, drive, reply),
        };
        let result = apply(channel, action, &self.active);
        self.command_applied(channel, result, drive, reply)
    }

    /// Publishes what a command did and answers it (now, or once its motion is over).
    fn command_applied(
        &mut self,
        channel: &mut Channel,
        result: Result<(), CommandError>,
        drive: Option<super::Drive>,
        reply: oneshot::Sender<Result<Outcome, CommandError>>,
    ) -> Flow {
        self.dirty |= result.is_ok();
        self.publish(channel);
        if let Err(e) = result {
            let _ = reply.send(Err(e));
            return Flow::Continue;
        }
        let now = Instant::now();
        match drive {
            Some(drive) => {
                self.pace = drive.pace;
                self.limit_hit = None;
                if drive.pace == Pace::Fast {
                    let cycles = (self.config.fast_sim_time / channel.config().ipo_cycle).ceil() as u64;
                    self.fast_limit_tick = channel.ticks().saturating_add(cycles);
                    self.fast_deadline = now + self.config.fast_wall_time;
                }
                if drive.wait {
                    self.waiters.push(Waiter { reply, deadline: now + self.config.wait_wall_time });
                    self.settle_waiters(channel, now);
                } else {
                    let _ = reply.send(Ok(self.outcome(None)));
                }
            }
            None => {
                let _ = reply.send(Ok(self.outcome(None)));
            }
        }
        Flow::Continue
    }

    /// Runs the IPO cycles wall time owes, stopping early once nothing is left to move.
    fn realtime_wake(&mut self, channel: &mut Channel) {
        let now = Instant::now();
        let late = now.saturating_duration_since(self.next_wake);
        self.lag_micros.store(u64::try_from(late.as_micros()).unwrap_or(u64::MAX), Ordering::Relaxed);
        let (owed, dropped) = self.pacer.as_mut().map_or((0, 0), |p| (p.owed(now), p.take_dropped()));
        wake_stats().record(late, dropped);
        // The executed path sees every cycle (held for this wake-up only; REST reads wait).
        let mut history = self.history.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        for _ in 0..owed {
            if !channel.is_active() {
                break;
            }
            channel.step();
            history.observe(channel);
        }
        drop(history);
        self.next_wake += self.config.period;
        if self.next_wake <= now {
            self.next_wake = now + self.config.period;
        }
        self.publish(channel);
        self.settle_waiters(channel, now);
    }

    /// Runs one chunk of fast-paced cycles on a blocking worker. `None` if the engine panicked.
    async fn fast_chunk(&mut self, mut channel: Box<Channel>) -> Option<Box<Channel>> {
        let (steps, limit) = (self.config.fast_chunk, self.fast_limit_tick);
        let deadline = self.fast_deadline.into_std();
        let history = self.history.clone();
        let joined = tokio::task::spawn_blocking(move || {
            step_fast(&mut channel, steps, limit, deadline, &history);
            channel
        })
        .await;
        let mut channel = match joined {
            Ok(channel) => channel,
            Err(e) => {
                tracing::error!(error = %e, "session engine failed during a fast run; the session has ended");
                return None;
            }
        };
        let out_of_time = Instant::now() >= self.fast_deadline;
        if channel.is_busy() && (channel.ticks() >= self.fast_limit_tick || out_of_time) {
            if self.limit_hit.is_some() {
                // Still moving after the grace period: a reset stops everything at once.
                channel.reset();
            } else {
                channel.stop();
                // Which limit came first: the simulated time reached, or the wall time.
                let sim_time_reached = channel.ticks() >= self.fast_limit_tick;
                self.limit_hit = Some(if sim_time_reached { Limit::FastSimTime } else { Limit::FastWallTime });
                let grace = (BRAKE_GRACE / channel.config().ipo_cycle).ceil() as u64;
                self.fast_limit_tick = channel.ticks().max(self.fast_limit_tick).saturating_add(grace);
                self.fast_deadline = Instant::now() + self.config.fast_wall_time;
            }
        }
        if !channel.is_busy() {
            self.pace = Pace::Realtime;
        }
        self.publish(&mut channel);
        self.settle_waiters(&channel, Instant::now());
        Some(channel)
    }

    /// Broadcasts new events, publishes the state if it changed, and reports when the channel
    /// has come to rest after commands.
    fn publish(&mut self, channel: &mut Channel) {
        if self.dirty && !channel.is_busy() {
            self.dirty = false;
            self.settled.send_modify(|n| *n = n.wrapping_add(1));
        }
        for event in channel.take_events() {
            // No subscribers is not an error: events are for whoever listens right now.
            let _ = self.events.send(event);
        }
        // Before the state, so a stream never sees a stock version the feed does not know.
        self.stock_feed.update(channel, self.events.receiver_count() > 0);
        self.snapshots.publish(channel, &self.state);
    }

    /// Answers waiting requests whose motion is over or whose wall-time limit has come.
    fn settle_waiters(&mut self, channel: &Channel, now: Instant) {
        if self.waiters.is_empty() {
            return;
        }
        let done = channel.status() != Status::Running && !channel.is_busy();
        let limit = self.limit_hit;
        let mut keep = Vec::new();
        for waiter in std::mem::take(&mut self.waiters) {
            if done {
                let _ = waiter.reply.send(Ok(self.outcome(limit)));
            } else if now >= waiter.deadline {
                let _ = waiter.reply.send(Ok(self.outcome(Some(Limit::WaitWallTime))));
            } else {
                keep.push(waiter);
            }
        }
        self.waiters = keep;
    }

    fn outcome(&self, limit: Option<Limit>) -> Outcome {
        Outcome { snapshot: self.state.borrow().clone(), limit }
    }
}

/// Applies one action; a refused action changes nothing. A program loaded by it is recorded in
/// `active` with the name it was started under.
fn apply(channel: &mut Channel, action: Action, active: &ActiveCache) -> Result<(), CommandError> {
    let serial = channel.program_serial();
    let label = match &action {
        Action::Run { name, .. } => name.clone(),
        Action::Search { name, .. } => name.clone(),
        _ => None,
    };
    let result = apply_action(channel, action);
    // Only a name given with the command is recorded; otherwise the reader looks for a stored
    // program with the same text (see `api::active_program`).
    if channel.program_serial() != serial && label.is_some() {
        active.set_label(channel.program_serial(), label);
    }
    result
}

fn apply_action(channel: &mut Channel, action: Action) -> Result<(), CommandError> {
    match action {
        Action::Run { program, options, name } => {
            let before = ProgramOptions::of(channel);
            options.apply(channel);
            let result = match (program, name) {
                (Some(program), _) => channel.run_program(&program),
                (None, Some(name)) => match channel.program_text(&name) {
                    Some(text) => channel.run_program_shared(text),
                    None => Err(CommandError::Invalid(format!("no stored program `{name}` to run"))),
                },
                (None, None) => Err(CommandError::Invalid("no program to run".into())),
            };
            if result.is_err() {
                before.apply(channel);
            }
            result
        }
        Action::Mda { program } => channel.mda(&program),
        Action::Start => channel.start(),
        Action::StartRepos(mode, approach) => channel.start_with_repos_approach(mode, approach),
        Action::Stop => {
            channel.stop();
            Ok(())
        }
        Action::Reset => {
            channel.reset();
            Ok(())
        }
        Action::Cancel => {
            channel.cancel_alarms();
            Ok(())
        }
        Action::SetMode(mode) => channel.set_mode(mode),
        Action::SetOverrides { feed, rapid, spindle } => {
            let now = channel.overrides();
            channel.set_overrides(Overrides {
                feed: feed.unwrap_or(now.feed),
                rapid: rapid.unwrap_or(now.rapid),
                spindle: spindle.unwrap_or(now.spindle),
            })
        }
        Action::SetOptions(options) => {
            options.apply(channel);
            Ok(())
        }
        Action::SetParts([required, total, actual, special]) => {
            let now = channel.part_counts();
            channel.set_part_counts(nctwin_engine::interp::eval::process_vars::PartCounts {
                required: required.unwrap_or(now.required),
                total: total.unwrap_or(now.total),
                actual: actual.unwrap_or(now.actual),
                special: special.unwrap_or(now.special),
            })
        }
        Action::Jog { mut request, system, rotation, inc } => {
            if let Some(steps) = inc {
                request.increment = Some(channel.increment_distance(&request.axis, steps)?);
            }
            channel.jog_with(&request, system, rotation)
        }
        Action::Handwheel { axis, pulses, inc, system } => channel.handwheel(&axis, pulses, inc, system),
        Action::JogStop => {
            channel.jog_stop();
            Ok(())
        }
        Action::JogStopIf(serial) => {
            channel.jog_stop_if(serial);
            Ok(())
        }
        // A stored program is searched in place: the channel shares its text, no copy. The
        // search gives up with alarm 15370 after SEARCH_WALL_LIMIT of wall time.
        Action::Search { program, name, line, path } => {
            let deadline = std::time::Instant::now() + SEARCH_WALL_LIMIT;
            let mut go_on = |_| std::time::Instant::now() < deadline;
            channel.block_search_with(program.as_deref(), name.as_deref(), line, &path, &mut go_on)
        }
        Action::Reference(axis) => channel.reference_axes(axis.as_deref()),
        Action::MachineData(text) => channel.apply_machine_data(&text),
        Action::SetWorkOffset { axis, value } => channel.set_work_offset(&axis, value),
        Action::KinematicChains(text) => channel.import_kinematic_chains(&text),
        Action::ToolData(text) => channel.replace_tool_data(&text),
        Action::LoadTool { name, duplo, magazine, place } => {
            channel.find_tool(&name, duplo).and_then(|t| channel.load_tool(t, magazine, place))
        }
        Action::UnloadTool { name, duplo } => channel.find_tool(&name, duplo).and_then(|t| channel.unload_tool(t)),
    }
}

/// Cycles the fast pace steps between two locks of the executed path: a REST reader waits
/// at most these (some µs), and the lock's cost is shared by all of them.
const HISTORY_BATCH: u64 = 64;

/// Steps up to `max_steps` cycles while something moves and the limit tick is not reached;
/// the executed path looks at every one.
fn step_fast(
    channel: &mut Channel,
    max_steps: u64,
    limit_tick: u64,
    deadline: std::time::Instant,
    history: &std::sync::Mutex<super::path_history::PathHistory>,
) {
    let mut i = 0;
    while i < max_steps {
        let mut history = history.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        for _ in 0..HISTORY_BATCH.min(max_steps - i) {
            if !channel.is_busy() || channel.ticks() >= limit_tick {
                return;
            }
            // Cycles that prepare many blocks are slow: look at the clock now and then.
            if i % 1024 == 1023 && std::time::Instant::now() >= deadline {
                return;
            }
            channel.step();
            history.observe(channel);
            i += 1;
        }
    }
}
