//! `GET /sessions/{id}/stream`: a WebSocket that pushes a session's state and events, and takes
//! the HMI's JOG keys and handwheel (the dead-man JOG).
//!
//! The socket logic ([`pump`]) is generic over a `Sink` of text messages and a future that
//! completes when the client goes away, so it is tested without a socket.
//!
//! Dead-man JOG: a continuous JOG started by a client message moves only while that client
//! keeps saying so: it is stopped when the client sends `jog_stop`, when no `jog_keepalive` (or
//! repeated `jog`) came for [`JOG_DEADMAN`], and when the socket closes or breaks. Only the
//! motion this socket started is stopped (a later motion started by someone else goes on). The
//! deadline never waits on the socket: a reply that cannot be sent holds up reading the client's
//! next message, never the stop.
//!
//! A client that does not keep up is let go, not buffered for: its replies wait in a queue of
//! 16, the socket's write buffer holds at most [`Limits::stream_write_buffer_bytes`] (pongs
//! included), the server pings every [`Limits::stream_ping_interval`] and closes the stream
//! (1008) when [`Limits::stream_missed_pongs`] pings in a row went unanswered, and a write that
//! cannot complete for as long is given up. Frames and messages larger than
//! [`Limits::stream_message_bytes`] are refused as soon as their header arrives (1009).

use std::collections::VecDeque;
use std::future::Future;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::rejection::QueryRejection;
use axum::extract::ws::rejection::WebSocketUpgradeRejection;
use axum::extract::ws::{CloseFrame, Message, WebSocket, WebSocketUpgrade, close_code};
use axum::extract::{Extension, Path, Query, State};
use axum::response::Response;
use futures_util::{Sink, SinkExt, Stream, StreamExt};
use nctwin_engine::{Event, JogRequest, Snapshot};
use serde::Deserialize;
use tokio::sync::broadcast::error::RecvError;
use tokio::sync::{broadcast, mpsc, oneshot, watch};
use tokio::time::{Instant, sleep_until, timeout};
use utoipa::IntoParams;

use super::find_entry;
use super::stream_frame::{FrameCache, encode};
use super::stream_gate::FrameGate;
use crate::auth::access::{Caller, Need, check};
use crate::auth::{AuthMode, Role};
use crate::dto::{self, ClientMessage, ErrorBody, EventMessage, StreamMessage};
use crate::error::ApiError;
use crate::limits::Limits;
use crate::metrics::StreamClose;
use crate::session::{Action, Drive, Pace, SessionHandle};
use crate::state::{AppState, SessionEntry};

/// A continuous JOG started over the stream stops when its client has sent no keep-alive
/// (`jog_keepalive`, or the same `jog` again) for this long: a client should send one about every
/// 100 ms while the key is held.
pub const JOG_DEADMAN: Duration = Duration::from_millis(400);

/// Default stream period: 50 ms (20 Hz).
pub const DEFAULT_PERIOD_MS: u64 = 50;
/// Shortest stream period accepted.
pub const MIN_PERIOD_MS: u64 = 10;
/// Longest stream period accepted.
pub const MAX_PERIOD_MS: u64 = 5000;

/// Read buffer of a stream socket. Clients only send close and pong frames; tungstenite zeroes
/// the whole read buffer (default 128 KiB) on every read attempt, and the pump polls the read
/// half at every wake-up: with 1000 viewers that memset was a fifth of the server's CPU.
const READ_BUFFER_BYTES: usize = 4096;

/// The write buffer size at which tungstenite starts writing to the socket (its default); the
/// pump flushes after every batch anyway.
const WRITE_BUFFER_BYTES: usize = 128 * 1024;

/// Longest the server waits to send a close frame to a client that may not be reading.
const CLOSE_WAIT: Duration = Duration::from_secs(1);

/// Replies to client messages waiting for the pump.
const REPLY_QUEUE: usize = 16;

/// Query parameters of the stream.
#[derive(Debug, Clone, Default, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct StreamParams {
    /// Least time between two state messages in ms (10..=5000, default 50).
    pub period_ms: Option<u64>,
    /// The session token when the server requires one (`--auth required`); browsers cannot set
    /// an `Authorization` header on a WebSocket. Any role may watch.
    pub token: Option<String>,
    /// `1`: watch only (a watch link): this client's commands are refused as an observer's,
    /// also with `--auth off`.
    pub view_only: Option<u8>,
}

impl StreamParams {
    fn period(&self) -> Result<Duration, ApiError> {
        let ms = self.period_ms.unwrap_or(DEFAULT_PERIOD_MS);
        if !(MIN_PERIOD_MS..=MAX_PERIOD_MS).contains(&ms) {
            return Err(ApiError::bad_request(format!(
                "period_ms must be between {MIN_PERIOD_MS} and {MAX_PERIOD_MS}, not {ms}"
            )));
        }
        Ok(Duration::from_millis(ms))
    }
}

/// WebSocket stream of a session (JSON text messages, see `StreamMessage`).
///
/// The current state is sent at once as `{"type": "state", ...}`; then one state message per
/// period while the state changes (on a fixed grid of the period, at most one per grid slot, up
/// to a quarter period early; intermediate states are skipped), and every
/// event as it happens (`{"type": "event", "event": "alarm_raised" | "alarm_cleared" |
/// "block_changed" | "program_ended" | "program_stopped" | "mode_changed", ...}`), and after a
/// state whose stock version changed `{"type": "stock", ...}` with the tiles cut since (see
/// `StockTilesMessage`; at most 4 meshes inline, `reload` when the client must fetch over
/// REST). A client that
/// falls more than 256 events behind skips the oldest. The server closes the socket when the
/// session is deleted or the server shuts down (close code 1001). At most 64 clients per
/// session (`429`).
///
/// The server pings every 15 s and closes the stream (1008) when two pings in a row went
/// unanswered (browsers and WebSocket libraries answer by themselves while they read). A
/// client message larger than 4 KiB is refused with close code 1009.
///
/// Client messages (JSON text, see `ClientMessage`) drive JOG with the control's dead-man
/// safety; they need control of the session like REST commands (observers: `error` 403):
/// - `{"type": "jog", "axis": "X", "direction": 1}` (optional `inc`, `increment`,
///   `coordinates` `MCS`/`BCS`/`WCS`/`TCS` (absent: SD42650), `rotation` `AXES`/`ORIEULER`/
///   `ORIRPY`/`ORIRPY2`/`ORIVIRT1`/`ORIVIRT2` (absent: SD42660), `rapid`, as for `POST .../jog`): continuous without `inc` and
///   `increment`. A continuous JOG runs while the client sends `{"type": "jog_keepalive"}` (or
///   the same `jog`) at least every 400 ms (`JOG_DEADMAN`); it stops on `{"type": "jog_stop"}`,
///   on a missed keep-alive and when the socket closes. An incremental JOG runs to its
///   distance and stops early on `jog_stop` or disconnect.
/// - `{"type": "handwheel", "axis": "X", "pulses": -3, "inc": 10}`: as `POST .../jog/handwheel`;
///   stops on disconnect.
///
/// Each `jog`, `jog_stop` and `handwheel` is answered with `{"type": "ack", "request": ...}` or
/// `{"type": "error", "request": ..., "error": "...", "status": <HTTP status of the same REST
/// request>}`; a dead-man stop is reported as an `error` for `jog` with status 408.
#[utoipa::path(
    get,
    path = "/sessions/{id}/stream",
    tag = "stream",
    params(("id" = String, Path, description = "Session id"), StreamParams),
    responses(
        (status = 101, description = "WebSocket; every text message is a StreamMessage", body = StreamMessage),
        (status = 400, description = "Not a WebSocket request, or a bad period", body = ErrorBody),
        (status = 404, description = "No such session", body = ErrorBody),
        (status = 429, description = "The session has as many stream clients as allowed", body = ErrorBody),
    )
)]
pub async fn stream(
    State(state): State<AppState>,
    Path(id): Path<String>,
    caller: Option<Extension<Caller>>,
    query: Result<Query<StreamParams>, QueryRejection>,
    upgrade: Result<WebSocketUpgrade, WebSocketUpgradeRejection>,
) -> Result<Response, ApiError> {
    let entry = find_entry(&state, &id)?;
    let session = &entry.handle;
    let Query(params) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    let period = params.period()?;
    let limits = *state.limits();
    // tungstenite requires the most it buffers to exceed the size at which it starts writing.
    let max_write_buffer = limits.stream_write_buffer_bytes.max(2);
    let upgrade = upgrade
        .map_err(|e| ApiError::bad_request(format!("not a WebSocket request: {}", e.body_text())))?
        .read_buffer_size(READ_BUFFER_BYTES)
        .write_buffer_size(WRITE_BUFFER_BYTES.min(max_write_buffer / 2))
        .max_write_buffer_size(max_write_buffer)
        .max_frame_size(limits.stream_message_bytes)
        .max_message_size(limits.stream_message_bytes);
    // Counted from before the upgrade until the socket is done (a failed upgrade drops the
    // closure and with it the guard).
    let client = state.add_stream_client(&entry)?;
    // Subscribe before the first state is read, so no event after it is missed.
    let events = session.subscribe_events();
    let states = session.watch_state();
    // With `--auth off` every caller is the owner (the access layer always names the caller).
    let role = caller.map_or(Role::Owner, |Extension(Caller(role))| role);
    let commander = Commander { state, entry: entry.clone(), role };
    Ok(upgrade.on_upgrade(move |socket| async move {
        serve_socket(socket, states, events, period, commander).await;
        drop(client);
    }))
}

/// Runs [`pump`] on an axum WebSocket and closes it with a close frame saying why, when there
/// is a reason to give (the session ended, pongs missed, a message too big).
///
/// The client's messages are read by a task of its own ([`client_loop`]), so the socket's read
/// half is polled only when the client sent something: polled from the pump, it was tried (and
/// its read buffer cleared) at every state message.
async fn serve_socket(
    socket: WebSocket,
    states: watch::Receiver<Arc<Snapshot>>,
    events: broadcast::Receiver<Event>,
    period: Duration,
    commander: Commander,
) {
    let entry = commander.entry.clone();
    let state = commander.state.clone();
    let liveness = Liveness::new(state.limits());
    let (mut sink, rx) = socket.split();
    let (replies_tx, replies) = mpsc::channel(REPLY_QUEUE);
    let reader = tokio::spawn(client_loop(rx, commander, replies_tx, liveness.pongs.clone()));
    // Dropping the reader (it owns the socket's JOG) stops a JOG this client started.
    let stop_reader = reader.abort_handle();
    let (close_tx, mut close_rx) = oneshot::channel();
    let client_gone = async move {
        let close = reader.await.ok().flatten();
        let _ = close_tx.send(close);
    };
    let feeds = Feeds { frames: &entry.frames, stock: entry.handle.stock_feed() };
    let end = pump(&mut sink, client_gone, states, events, replies, period, feeds, liveness).await;
    stop_reader.abort();
    let close = match end {
        StreamEnd::SessionEnded => Some(CloseFrame { code: close_code::AWAY, reason: "session ended".into() }),
        StreamEnd::PongsMissed => {
            state.metrics().stream_closed(StreamClose::PongsMissed);
            Some(CloseFrame { code: close_code::POLICY, reason: "pings not answered".into() })
        }
        StreamEnd::ClientGone => close_rx.try_recv().ok().flatten().inspect(|frame| {
            if frame.code == close_code::SIZE {
                state.metrics().stream_closed(StreamClose::TooBig);
            }
        }),
        StreamEnd::SendFailed => {
            state.metrics().stream_closed(StreamClose::SendFailed);
            None
        }
        StreamEnd::Stalled => {
            state.metrics().stream_closed(StreamClose::Stalled);
            None
        }
    };
    if let Some(frame) = close {
        let _ = timeout(CLOSE_WAIT, sink.send(Message::Close(Some(frame)))).await;
    }
}

/// The server's pings on a stream and the pongs that answer them.
#[derive(Debug, Clone)]
pub struct Liveness {
    /// Time between two pings.
    pub interval: Duration,
    /// Pings in a row that may go unanswered; at this many the stream is closed. Also, a write
    /// that cannot complete within `interval × missed` is given up.
    pub missed: u32,
    /// The highest ping number a pong answered (pings carry their number, 8 bytes big-endian);
    /// written by the reader of the socket.
    pub pongs: Arc<AtomicU64>,
}

impl Liveness {
    /// The stream limits of `limits`, no pong seen yet.
    pub fn new(limits: &Limits) -> Liveness {
        Liveness {
            interval: limits.stream_ping_interval,
            missed: limits.stream_missed_pongs.max(1),
            pongs: Arc::new(AtomicU64::new(0)),
        }
    }

    /// The longest a write to the client may take.
    fn stall(&self) -> Duration {
        self.interval.saturating_mul(self.missed)
    }

    /// Notes a pong from the client.
    fn pong(pongs: &AtomicU64, payload: &[u8]) {
        if let Ok(number) = <[u8; 8]>::try_from(payload) {
            pongs.fetch_max(u64::from_be_bytes(number), Ordering::Relaxed);
        }
    }
}

/// Why [`pump`] returned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamEnd {
    /// The client closed the connection.
    ClientGone,
    /// The session was deleted (its state channel closed).
    SessionEnded,
    /// Sending failed (the connection broke, or the write buffer is full).
    SendFailed,
    /// A write did not complete within the time a client may stay silent: it does not read.
    Stalled,
    /// The client left as many pings in a row unanswered as allowed.
    PongsMissed,
}

/// The messages a session's streams share: its encoded state and its stock's changes.
#[derive(Clone, Copy)]
pub struct Feeds<'a> {
    pub frames: &'a FrameCache,
    pub stock: &'a crate::session::stock_feed::StockFeed,
}

/// Sends the current state, then state changes (one per `period` on a fixed grid, newest only,
/// see [`FrameGate`]) and events, and pings (see [`Liveness`]), until the client goes, the
/// session ends, a send fails or stalls, or pongs stop.
///
/// Whatever is ready at one wake-up (replies, events, the state) goes out in one write. State
/// messages come from `feeds.frames`, encoded once per snapshot for every client of the
/// session; after a state whose stock version differs from the one this client shows come the
/// stock's changes (`feeds.stock`).
#[allow(clippy::too_many_arguments)]
pub async fn pump<S>(
    mut sink: S,
    client_gone: impl Future<Output = ()>,
    mut states: watch::Receiver<Arc<Snapshot>>,
    mut events: broadcast::Receiver<Event>,
    mut replies: mpsc::Receiver<StreamMessage>,
    period: Duration,
    feeds: Feeds<'_>,
    liveness: Liveness,
) -> StreamEnd
where
    S: Sink<Message> + Unpin,
{
    tokio::pin!(client_gone);
    let stall = liveness.stall();
    let first = states.borrow_and_update().clone();
    let mut batch: Vec<Message> = vec![Message::Text(feeds.frames.state(&first))];
    // The stock version this client shows: the first state's (it fetches that over REST).
    let mut stock_shown = first.stock.as_ref().map(|s| s.version);
    if let Err(end) = send_all(&mut sink, &mut batch, stall).await {
        return end;
    }
    let mut gate = FrameGate::new(Instant::now(), period);
    let mut pending = false;
    let mut replies_open = true;
    let mut next_ping = Instant::now() + liveness.interval;
    let mut pings: u64 = 0;
    let mut unanswered: u32 = 0;
    loop {
        let mut ended = false;
        tokio::select! {
            () = &mut client_gone => return StreamEnd::ClientGone,
            reply = replies.recv(), if replies_open => match reply {
                Some(message) => batch.push(text(&message)),
                None => replies_open = false,
            },
            () = sleep_until(next_ping) => {
                if liveness.pongs.load(Ordering::Relaxed) < pings {
                    unanswered += 1;
                    if unanswered >= liveness.missed {
                        return StreamEnd::PongsMissed;
                    }
                } else {
                    unanswered = 0;
                }
                pings += 1;
                batch.push(Message::Ping(Bytes::copy_from_slice(&pings.to_be_bytes())));
                next_ping = Instant::now() + liveness.interval;
            }
            changed = states.changed(), if !pending => {
                if changed.is_err() {
                    return StreamEnd::SessionEnded;
                }
                pending = true;
            }
            () = sleep_until(gate.opens_at()), if pending => {}
            event = events.recv() => match event {
                Ok(event) => batch.push(text(&StreamMessage::Event(EventMessage::from(&event)))),
                // Lagged: the skipped events are lost for this client only; go on with the rest.
                Err(RecvError::Lagged(_)) => {}
                Err(RecvError::Closed) => ended = true,
            },
        }
        // Take along whatever else is ready now.
        while replies_open && let Ok(message) = replies.try_recv() {
            batch.push(text(&message));
        }
        loop {
            match events.try_recv() {
                Ok(event) => batch.push(text(&StreamMessage::Event(EventMessage::from(&event)))),
                Err(broadcast::error::TryRecvError::Lagged(_)) => {}
                Err(broadcast::error::TryRecvError::Empty) => break,
                Err(broadcast::error::TryRecvError::Closed) => {
                    ended = true;
                    break;
                }
            }
        }
        if !pending && states.has_changed().unwrap_or(false) {
            pending = true;
        }
        let now = Instant::now();
        if pending && gate.is_open(now) {
            pending = false;
            gate.sent(now);
            let latest = states.borrow_and_update().clone();
            batch.push(Message::Text(feeds.frames.state(&latest)));
            let now = latest.stock.as_ref().map(|s| s.version);
            if now != stock_shown {
                stock_shown = feeds.stock.catch_up(stock_shown, now, &mut batch);
            }
        }
        if !batch.is_empty()
            && let Err(end) = send_all(&mut sink, &mut batch, stall).await
        {
            return end;
        }
        if ended {
            return StreamEnd::SessionEnded;
        }
    }
}

/// A stream message as a WebSocket text message.
fn text(message: &StreamMessage) -> Message {
    Message::Text(encode(message))
}

/// Writes every message of `batch` and then flushes once (one system call for all of them);
/// gives up when that takes longer than `stall`.
async fn send_all<S: Sink<Message> + Unpin>(
    sink: &mut S,
    batch: &mut Vec<Message>,
    stall: Duration,
) -> Result<(), StreamEnd> {
    let write = async {
        for message in batch.drain(..) {
            sink.feed(message).await?;
        }
        sink.flush().await
    };
    match timeout(stall, write).await {
        Ok(Ok(())) => Ok(()),
        Ok(Err(_)) => Err(StreamEnd::SendFailed),
        Err(_) => Err(StreamEnd::Stalled),
    }
}

/// The client of one socket as a commander of its session.
struct Commander {
    state: AppState,
    entry: Arc<SessionEntry>,
    role: Role,
}

impl Commander {
    /// The access policy of a REST command, applied to a client message; `count` also takes it
    /// from the session's command rate limit.
    fn authorize(&self, count: bool) -> Result<(), ApiError> {
        // A view-only client (`view_only=1` with auth off) is an observer too.
        if self.state.auth() == AuthMode::Required || self.role == Role::Observer {
            check(Need::Command, self.role, self.entry.control_holder())?;
        }
        if count {
            self.entry.take_command(self.state.limits())?;
        }
        Ok(())
    }

    fn session(&self) -> &SessionHandle {
        &self.entry.handle
    }
}

/// The JOG motion a socket started. Dropping it (the socket closed or broke, the session or
/// the server ended) stops that motion.
struct OwnJog {
    session: SessionHandle,
    /// Number of the motion (`Snapshot::jog_serial`) while it may still run.
    serial: Option<u64>,
    /// For a continuous JOG: when it is stopped unless a keep-alive comes first.
    deadline: Option<Instant>,
    /// For a continuous JOG: the key held (axis, direction).
    key: Option<(String, i8)>,
}

impl OwnJog {
    async fn stop(&mut self) {
        self.deadline = None;
        self.key = None;
        if let Some(serial) = self.serial.take() {
            let _ = self.session.command(Action::JogStopIf(serial), None).await;
        }
    }
}

impl Drop for OwnJog {
    fn drop(&mut self) {
        if let Some(serial) = self.serial.take()
            && let Ok(runtime) = tokio::runtime::Handle::try_current()
        {
            let session = self.session.clone();
            runtime.spawn(async move {
                let _ = session.command(Action::JogStopIf(serial), None).await;
            });
        }
    }
}

/// Reads the client's messages until it goes: carries out its JOG commands, watches the dead
/// man and notes pongs in `pongs`. Reading also answers the client's pings; the client is gone
/// on a close frame, an error or the end of the stream. Returns the close frame to send, if
/// the client broke the protocol or its limits.
///
/// A reply waits until the reply queue has room, and the client's next message is not read
/// meanwhile (the socket holds it), so at most a reply and a dead-man notice wait. The dead man
/// is watched all the while: a client whose replies pile up cannot hold a JOG.
async fn client_loop<R>(
    mut rx: R,
    commander: Commander,
    replies: mpsc::Sender<StreamMessage>,
    pongs: Arc<AtomicU64>,
) -> Option<CloseFrame>
where
    R: Stream<Item = Result<Message, axum::Error>> + Unpin,
{
    let mut own = OwnJog { session: commander.session().clone(), serial: None, deadline: None, key: None };
    let mut waiting: VecDeque<StreamMessage> = VecDeque::new();
    // `own` drops when this returns and stops a motion that may still run.
    loop {
        let deadline = own.deadline;
        tokio::select! {
            permit = replies.reserve(), if !waiting.is_empty() => match (permit, waiting.pop_front()) {
                (Ok(permit), Some(reply)) => permit.send(reply),
                _ => return None,
            },
            message = rx.next(), if waiting.is_empty() => match message {
                Some(Ok(Message::Text(text))) => {
                    waiting.extend(handle_client_message(text.as_str(), &commander, &mut own).await);
                }
                Some(Ok(Message::Pong(payload))) => Liveness::pong(&pongs, &payload),
                Some(Ok(Message::Close(_))) | None => return None,
                Some(Err(e)) => return close_for(e),
                Some(Ok(_)) => {}
            },
            () = sleep_until(deadline.unwrap_or_else(Instant::now)), if deadline.is_some() => {
                own.stop().await;
                let error = format!("no keep-alive within {} ms: the JOG was stopped (dead man)", JOG_DEADMAN.as_millis());
                waiting.push_back(StreamMessage::Error { request: Some("jog".into()), error, status: 408 });
            }
        }
    }
}

/// The close frame for a read error: 1009 for a frame or message over the size limit, 1002
/// for a protocol error; none when the connection broke.
fn close_for(error: axum::Error) -> Option<CloseFrame> {
    let error = error.into_inner();
    match error.downcast_ref::<tungstenite::Error>()? {
        tungstenite::Error::Capacity(_) => {
            Some(CloseFrame { code: close_code::SIZE, reason: "message too big".into() })
        }
        tungstenite::Error::Protocol(_) => {
            Some(CloseFrame { code: close_code::PROTOCOL, reason: "protocol error".into() })
        }
        _ => None,
    }
}

/// Carries out one client message; the reply to send, if any.
async fn handle_client_message(text: &str, commander: &Commander, own: &mut OwnJog) -> Option<StreamMessage> {
    let message: ClientMessage = match serde_json::from_str(text) {
        Ok(m) => m,
        Err(e) => {
            let error = format!("bad client message: {e}");
            return Some(StreamMessage::Error { request: None, error, status: 400 });
        }
    };
    let (request, result) = match message {
        ClientMessage::JogKeepalive => {
            if own.deadline.is_some() && commander.authorize(false).is_ok() {
                own.deadline = Some(Instant::now() + JOG_DEADMAN);
            }
            return None;
        }
        ClientMessage::JogStop => {
            // Stopping is always allowed: it only ends this client's own motion.
            own.stop().await;
            ("jog_stop", Ok(()))
        }
        ClientMessage::Jog { axis, direction, increment, inc, coordinates, rotation, rapid } => {
            let continuous = increment.is_none() && inc.is_none();
            if own.deadline.is_some() {
                if continuous && own.key.as_ref().is_some_and(|(a, d)| a.eq_ignore_ascii_case(&axis) && *d == direction)
                {
                    // The key is still held: a repeated `jog` is a keep-alive.
                    own.deadline = Some(Instant::now() + JOG_DEADMAN);
                    return None;
                }
                let error = "another JOG key is held: send jog_stop first".to_string();
                return Some(StreamMessage::Error { request: Some("jog".into()), error, status: 409 });
            }
            let key = (axis.clone(), direction);
            let body = dto::JogBody {
                axis,
                direction,
                increment,
                inc,
                coordinates,
                rotation,
                rapid,
                pace: dto::PaceOption::Realtime,
                wait: false,
            };
            let result = async {
                commander.authorize(true)?;
                body.validate().map_err(ApiError::bad_request)?;
                let request = JogRequest { axis: body.axis, direction, increment, rapid };
                let action = Action::Jog {
                    request,
                    system: coordinates.map(Into::into),
                    rotation: rotation.map(Into::into),
                    inc,
                };
                start_own(commander, own, action, continuous).await
            }
            .await;
            if result.is_ok() && continuous {
                own.key = Some(key);
            }
            ("jog", result)
        }
        ClientMessage::Handwheel { axis, pulses, inc, coordinates } => {
            let body = dto::HandwheelBody { axis, pulses, inc, coordinates };
            let result = async {
                commander.authorize(true)?;
                let inc = body.validate().map_err(ApiError::bad_request)?;
                let action = Action::Handwheel { axis: body.axis, pulses, inc, system: coordinates.into() };
                start_own(commander, own, action, false).await
            }
            .await;
            ("handwheel", result)
        }
    };
    Some(match result {
        Ok(()) => StreamMessage::Ack { request: request.into() },
        Err(e) => {
            StreamMessage::Error { request: Some(request.into()), error: e.body().error, status: e.status().as_u16() }
        }
    })
}

/// Sends a JOG action and takes over the motion it started.
async fn start_own(commander: &Commander, own: &mut OwnJog, action: Action, continuous: bool) -> Result<(), ApiError> {
    let drive = Drive { pace: Pace::Realtime, wait: false };
    let id = commander.entry.id().to_string();
    let outcome = commander.session().command(action, Some(drive)).await.map_err(|e| ApiError::from_session(&id, e))?;
    own.serial = Some(outcome.snapshot.jog_serial);
    own.deadline = continuous.then(|| Instant::now() + JOG_DEADMAN);
    Ok(())
}

#[cfg(test)]
mod tests {
    use axum::extract::ws::Utf8Bytes;
    use futures_util::sink;
    use nctwin_engine::Channel;
    use serde_json::Value;
    use tokio::sync::{mpsc, oneshot};

    use super::*;

    struct Harness {
        states: watch::Sender<Arc<Snapshot>>,
        events: broadcast::Sender<Event>,
        out: mpsc::UnboundedReceiver<String>,
        client_gone: Option<oneshot::Sender<()>>,
        task: tokio::task::JoinHandle<StreamEnd>,
        channel: Channel,
    }

    fn start(period: Duration) -> Harness {
        let channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let (states, state_rx) = watch::channel(Arc::new(channel.snapshot()));
        let (events, event_rx) = broadcast::channel(16);
        let (out_tx, out) = mpsc::unbounded_channel::<String>();
        let sink = Box::pin(sink::unfold(out_tx, |tx, message: Message| async move {
            let text = match message {
                Message::Text(text) => text.to_string(),
                Message::Ping(payload) => format!("ping {payload:?}"),
                other => format!("{other:?}"),
            };
            tx.send(text).map_err(|_| ())?;
            Ok::<_, ()>(tx)
        }));
        let (gone_tx, gone_rx) = oneshot::channel::<()>();
        let gone = async move {
            let _ = gone_rx.await;
        };
        let (_replies_tx, replies) = mpsc::channel(1);
        let task = tokio::spawn(async move {
            let frames = FrameCache::default();
            let stock = crate::session::stock_feed::StockFeed::default();
            pump(sink, gone, state_rx, event_rx, replies, period, Feeds { frames: &frames, stock: &stock }, quiet())
                .await
        });
        Harness { states, events, out, client_gone: Some(gone_tx), task, channel }
    }

    /// Pings so rare that no test sees one.
    fn quiet() -> Liveness {
        let limits = Limits { stream_ping_interval: Duration::from_secs(86_400), ..Limits::default() };
        Liveness::new(&limits)
    }

    async fn next(h: &mut Harness) -> Value {
        serde_json::from_str(&h.out.recv().await.expect("a message")).expect("JSON")
    }

    #[tokio::test(start_paused = true)]
    async fn states_are_throttled_to_the_newest_per_period_and_events_pass_at_once() {
        let mut h = start(Duration::from_millis(50));
        let first = next(&mut h).await;
        assert_eq!((first["type"].as_str(), first["tick"].as_u64()), (Some("state"), Some(0)));

        h.channel.run_program("G1 X10 F600\nM30").expect("program");
        for _ in 0..3 {
            h.channel.step();
            h.states.send_replace(Arc::new(h.channel.snapshot()));
        }
        h.events.send(Event::ProgramEnded).expect("a subscriber");

        let event = next(&mut h).await;
        assert_eq!((event["type"].as_str(), event["event"].as_str()), (Some("event"), Some("program_ended")));
        let state = next(&mut h).await;
        assert_eq!((state["type"].as_str(), state["tick"].as_u64()), (Some("state"), Some(3)), "only the newest state");

        tokio::time::sleep(Duration::from_secs(1)).await;
        assert!(h.out.try_recv().is_err(), "nothing is sent while nothing changes");

        h.client_gone.take().map(|tx| tx.send(()));
        assert_eq!(h.task.await.expect("pump"), StreamEnd::ClientGone);
    }

    /// A sink that records what each flush wrote.
    struct Recorder {
        writes: Arc<std::sync::Mutex<Vec<Vec<String>>>>,
        buffer: Vec<String>,
    }

    impl Sink<Message> for Recorder {
        type Error = ();
        fn poll_ready(
            self: std::pin::Pin<&mut Self>,
            _: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            std::task::Poll::Ready(Ok(()))
        }
        fn start_send(self: std::pin::Pin<&mut Self>, item: Message) -> Result<(), ()> {
            let item = item.into_text().map_or_else(|_| String::new(), |text: Utf8Bytes| text.to_string());
            self.get_mut().buffer.push(item);
            Ok(())
        }
        fn poll_flush(
            self: std::pin::Pin<&mut Self>,
            _: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            let this = self.get_mut();
            if !this.buffer.is_empty() {
                this.writes.lock().expect("writes").push(std::mem::take(&mut this.buffer));
            }
            std::task::Poll::Ready(Ok(()))
        }
        fn poll_close(
            self: std::pin::Pin<&mut Self>,
            cx: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            self.poll_flush(cx)
        }
    }

    #[tokio::test(start_paused = true)]
    async fn an_event_and_a_due_state_go_out_in_one_write() {
        let mut channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let (states, state_rx) = watch::channel(Arc::new(channel.snapshot()));
        let (events, event_rx) = broadcast::channel(16);
        let writes = Arc::new(std::sync::Mutex::new(Vec::new()));
        let sink = Recorder { writes: writes.clone(), buffer: Vec::new() };
        let (_replies_tx, replies) = mpsc::channel(1);
        let task = tokio::spawn(async move {
            let frames = FrameCache::default();
            let stock = crate::session::stock_feed::StockFeed::default();
            let period = Duration::from_millis(50);
            pump(
                sink,
                std::future::pending(),
                state_rx,
                event_rx,
                replies,
                period,
                Feeds { frames: &frames, stock: &stock },
                quiet(),
            )
            .await
        });
        // The first state goes out at once; the next slot (50 ms) opens at 37.5 ms.
        tokio::time::sleep(Duration::from_millis(45)).await;
        assert_eq!(writes.lock().expect("writes").len(), 1);

        channel.run_program("G1 X10 F600\nM30").expect("program");
        channel.step();
        events.send(Event::ProgramEnded).expect("a subscriber");
        states.send_replace(Arc::new(channel.snapshot()));
        tokio::time::sleep(Duration::from_millis(1)).await;
        let writes = writes.lock().expect("writes").clone();
        assert_eq!(writes.len(), 2, "{writes:?}");
        assert_eq!(writes[1].len(), 2, "the event and the state in one write: {writes:?}");
        assert!(writes[1][0].starts_with("{\"type\":\"event\""), "{writes:?}");
        assert!(writes[1][1].starts_with("{\"type\":\"state\""), "{writes:?}");
        task.abort();
    }

    fn liveness(interval_ms: u64, missed: u32) -> Liveness {
        let limits = Limits {
            stream_ping_interval: Duration::from_millis(interval_ms),
            stream_missed_pongs: missed,
            ..Limits::default()
        };
        Liveness::new(&limits)
    }

    /// Runs the pump on an idle session with `liveness`, recording what it writes.
    fn idle_pump(
        liveness: Liveness,
    ) -> (mpsc::UnboundedReceiver<Message>, tokio::task::JoinHandle<StreamEnd>, watch::Sender<Arc<Snapshot>>) {
        let channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let (states, state_rx) = watch::channel(Arc::new(channel.snapshot()));
        let (out_tx, out) = mpsc::unbounded_channel::<Message>();
        let sink = Box::pin(sink::unfold(out_tx, |tx, message: Message| async move {
            tx.send(message).map_err(|_| ())?;
            Ok::<_, ()>(tx)
        }));
        let task = tokio::spawn(async move {
            let (_events_tx, events) = broadcast::channel(1);
            let (_replies_tx, replies) = mpsc::channel(1);
            let frames = FrameCache::default();
            let stock = crate::session::stock_feed::StockFeed::default();
            let period = Duration::from_millis(50);
            pump(
                sink,
                std::future::pending(),
                state_rx,
                events,
                replies,
                period,
                Feeds { frames: &frames, stock: &stock },
                liveness,
            )
            .await
        });
        (out, task, states)
    }

    #[tokio::test(start_paused = true)]
    async fn an_idle_stream_is_pinged_and_closed_after_the_missed_pongs() {
        let (mut out, task, _states) = idle_pump(liveness(100, 2));
        let started = Instant::now();
        assert!(matches!(out.recv().await, Some(Message::Text(_))), "the first state");
        let mut pings = Vec::new();
        while let Some(message) = out.recv().await {
            match message {
                Message::Ping(payload) => pings.push(payload),
                other => panic!("{other:?}"),
            }
        }
        assert_eq!(task.await.expect("pump"), StreamEnd::PongsMissed);
        assert_eq!(pings, [Bytes::copy_from_slice(&1u64.to_be_bytes()), Bytes::copy_from_slice(&2u64.to_be_bytes())]);
        assert_eq!(started.elapsed(), Duration::from_millis(300), "closed at the third ping's time");
    }

    #[tokio::test(start_paused = true)]
    async fn answered_pings_keep_a_stream_open() {
        let liveness = liveness(100, 2);
        let pongs = liveness.pongs.clone();
        let (mut out, task, _states) = idle_pump(liveness);
        let mut pings = 0;
        while pings < 20 {
            if let Some(Message::Ping(payload)) = out.recv().await {
                Liveness::pong(&pongs, &payload);
                pings += 1;
            }
        }
        // A pong of another shape counts for nothing.
        Liveness::pong(&pongs, b"pong");
        assert!(!task.is_finished());
        task.abort();
    }

    /// A sink whose socket never takes anything.
    struct Stuck;

    impl Sink<Message> for Stuck {
        type Error = ();
        fn poll_ready(
            self: std::pin::Pin<&mut Self>,
            _: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            std::task::Poll::Pending
        }
        fn start_send(self: std::pin::Pin<&mut Self>, _: Message) -> Result<(), ()> {
            Ok(())
        }
        fn poll_flush(
            self: std::pin::Pin<&mut Self>,
            _: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            std::task::Poll::Pending
        }
        fn poll_close(
            self: std::pin::Pin<&mut Self>,
            _: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            std::task::Poll::Pending
        }
    }

    #[tokio::test(start_paused = true)]
    async fn a_write_the_client_never_takes_is_given_up() {
        let channel = Channel::from_preset("mill-3axis", "").expect("preset");
        let (_states, state_rx) = watch::channel(Arc::new(channel.snapshot()));
        let (_events_tx, events) = broadcast::channel(1);
        let (_replies_tx, replies) = mpsc::channel(1);
        let frames = FrameCache::default();
        let stock = crate::session::stock_feed::StockFeed::default();
        let started = Instant::now();
        let end = pump(
            Stuck,
            std::future::pending(),
            state_rx,
            events,
            replies,
            Duration::from_millis(50),
            Feeds { frames: &frames, stock: &stock },
            liveness(100, 3),
        )
        .await;
        assert_eq!(end, StreamEnd::Stalled);
        assert_eq!(started.elapsed(), Duration::from_millis(300), "interval × missed pongs");
    }

    #[tokio::test(start_paused = true)]
    async fn the_pump_ends_when_the_session_ends() {
        let mut h = start(Duration::from_millis(50));
        next(&mut h).await;
        drop(h.states);
        assert_eq!(h.task.await.expect("pump"), StreamEnd::SessionEnded);
    }
}
