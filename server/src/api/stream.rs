//! `GET /sessions/{id}/stream`: a WebSocket that pushes a session's state and events, and takes
//! the HMI's JOG keys and handwheel (the dead-man JOG).
//!
//! The socket logic ([`pump`]) is generic over a `Sink` of text messages and a future that
//! completes when the client goes away, so it is tested without a socket.
//!
//! Dead-man JOG: a continuous JOG started by a client message moves only while that client
//! keeps saying so: it is stopped when the client sends `jog_stop`, when no `jog_keepalive` (or
//! repeated `jog`) came for [`JOG_DEADMAN`], and when the socket closes or breaks. Only the
//! motion this socket started is stopped (a later motion started by someone else goes on).

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::rejection::QueryRejection;
use axum::extract::ws::rejection::WebSocketUpgradeRejection;
use axum::extract::ws::{CloseFrame, Message, Utf8Bytes, WebSocket, WebSocketUpgrade, close_code};
use axum::extract::{Extension, Path, Query, State};
use axum::response::Response;
use futures_util::{Sink, SinkExt, Stream, StreamExt};
use nctwin_engine::{Event, JogRequest, Snapshot};
use serde::Deserialize;
use tokio::sync::broadcast::error::RecvError;
use tokio::sync::{broadcast, mpsc, watch};
use tokio::time::{Instant, sleep_until};
use utoipa::IntoParams;

use super::find_entry;
use super::stream_frame::{FrameCache, encode};
use super::stream_gate::FrameGate;
use crate::auth::access::{Caller, Need, check};
use crate::auth::{AuthMode, Role};
use crate::dto::{self, ClientMessage, ErrorBody, EventMessage, StreamMessage};
use crate::error::ApiError;
use crate::session::{Action, Drive, Pace, SessionHandle};
use crate::state::{AppState, SessionEntry};

/// A continuous JOG started over the stream stops when its client has sent no keep-alive
/// (`jog_keepalive`, or the same `jog` again) for this long: a client should send one about every
/// 100 ms while the key is held.
pub const JOG_DEADMAN: Duration = Duration::from_millis(400);

/// Largest client message accepted (the JOG messages are a few dozen bytes).
const MAX_CLIENT_MESSAGE_BYTES: usize = 16 * 1024;

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
/// "block_changed" | "program_ended" | "program_stopped" | "mode_changed", ...}`). A client that
/// falls more than 256 events behind skips the oldest. The server closes the socket when the
/// session is deleted or the server shuts down (close code 1001). At most 64 clients per
/// session (`429`).
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
    let upgrade = upgrade
        .map_err(|e| ApiError::bad_request(format!("not a WebSocket request: {}", e.body_text())))?
        .read_buffer_size(READ_BUFFER_BYTES)
        .max_message_size(MAX_CLIENT_MESSAGE_BYTES);
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

/// Runs [`pump`] on an axum WebSocket and closes it when the session has ended.
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
    let (tx, rx) = socket.split();
    let mut sink = tx.with(|text: Utf8Bytes| std::future::ready(Ok::<_, axum::Error>(Message::Text(text))));
    let (replies_tx, replies) = mpsc::channel(16);
    let reader = tokio::spawn(client_loop(rx, commander, replies_tx));
    // Dropping the reader (it owns the socket's JOG) stops a JOG this client started.
    let stop_reader = reader.abort_handle();
    let client_gone = async move {
        let _ = reader.await;
    };
    let end = pump(&mut sink, client_gone, states, events, replies, period, &entry.frames).await;
    stop_reader.abort();
    if end == StreamEnd::SessionEnded {
        let frame = CloseFrame { code: close_code::AWAY, reason: "session ended".into() };
        let _ = sink.into_inner().send(Message::Close(Some(frame))).await;
    }
}

/// Why [`pump`] returned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamEnd {
    /// The client closed the connection.
    ClientGone,
    /// The session was deleted (its state channel closed).
    SessionEnded,
    /// Sending failed (the connection broke).
    SendFailed,
}

/// Sends the current state, then state changes (one per `period` on a fixed grid, newest only,
/// see [`FrameGate`]) and events, until the client goes, the session ends or a send fails.
///
/// Whatever is ready at one wake-up (replies, events, the state) goes out in one write. State
/// messages come from `frames`, encoded once per snapshot for every client of the session.
pub async fn pump<S>(
    mut sink: S,
    client_gone: impl Future<Output = ()>,
    mut states: watch::Receiver<Arc<Snapshot>>,
    mut events: broadcast::Receiver<Event>,
    mut replies: mpsc::Receiver<StreamMessage>,
    period: Duration,
    frames: &FrameCache,
) -> StreamEnd
where
    S: Sink<Utf8Bytes> + Unpin,
{
    tokio::pin!(client_gone);
    let first = states.borrow_and_update().clone();
    if sink.send(frames.state(&first)).await.is_err() {
        return StreamEnd::SendFailed;
    }
    let mut gate = FrameGate::new(Instant::now(), period);
    let mut pending = false;
    let mut replies_open = true;
    let mut batch: Vec<Utf8Bytes> = Vec::new();
    loop {
        let mut ended = false;
        tokio::select! {
            () = &mut client_gone => return StreamEnd::ClientGone,
            reply = replies.recv(), if replies_open => match reply {
                Some(message) => batch.push(encode(&message)),
                None => replies_open = false,
            },
            changed = states.changed(), if !pending => {
                if changed.is_err() {
                    return StreamEnd::SessionEnded;
                }
                pending = true;
            }
            () = sleep_until(gate.opens_at()), if pending => {}
            event = events.recv() => match event {
                Ok(event) => batch.push(encode(&StreamMessage::Event(EventMessage::from(&event)))),
                // Lagged: the skipped events are lost for this client only; go on with the rest.
                Err(RecvError::Lagged(_)) => {}
                Err(RecvError::Closed) => ended = true,
            },
        }
        // Take along whatever else is ready now.
        while replies_open && let Ok(message) = replies.try_recv() {
            batch.push(encode(&message));
        }
        loop {
            match events.try_recv() {
                Ok(event) => batch.push(encode(&StreamMessage::Event(EventMessage::from(&event)))),
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
            batch.push(frames.state(&latest));
        }
        if !batch.is_empty() && send_all(&mut sink, &mut batch).await.is_err() {
            return StreamEnd::SendFailed;
        }
        if ended {
            return StreamEnd::SessionEnded;
        }
    }
}

/// Writes every message of `batch` and then flushes once (one system call for all of them).
async fn send_all<S: Sink<Utf8Bytes> + Unpin>(sink: &mut S, batch: &mut Vec<Utf8Bytes>) -> Result<(), S::Error> {
    for text in batch.drain(..) {
        sink.feed(text).await?;
    }
    sink.flush().await
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
        if self.state.auth() == AuthMode::Required {
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

/// Reads the client's messages until it goes: carries out its JOG commands and watches the
/// dead man. Reading also answers pings; the client is gone on a close frame, an error or the
/// end of the stream.
async fn client_loop<R>(mut rx: R, commander: Commander, replies: mpsc::Sender<StreamMessage>)
where
    R: Stream<Item = Result<Message, axum::Error>> + Unpin,
{
    let mut own = OwnJog { session: commander.session().clone(), serial: None, deadline: None, key: None };
    loop {
        let deadline = own.deadline;
        tokio::select! {
            message = rx.next() => match message {
                Some(Ok(Message::Text(text))) => {
                    let reply = handle_client_message(text.as_str(), &commander, &mut own).await;
                    if let Some(reply) = reply && replies.send(reply).await.is_err() {
                        break;
                    }
                }
                Some(Ok(Message::Close(_))) | Some(Err(_)) | None => break,
                Some(Ok(_)) => {}
            },
            () = sleep_until(deadline.unwrap_or_else(Instant::now)), if deadline.is_some() => {
                own.stop().await;
                let error = format!("no keep-alive within {} ms: the JOG was stopped (dead man)", JOG_DEADMAN.as_millis());
                let _ = replies.send(StreamMessage::Error { request: Some("jog".into()), error, status: 408 }).await;
            }
        }
    }
    // `own` drops here and stops a motion that may still run.
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
        let sink = Box::pin(sink::unfold(out_tx, |tx, text: Utf8Bytes| async move {
            tx.send(text.to_string()).map_err(|_| ())?;
            Ok::<_, ()>(tx)
        }));
        let (gone_tx, gone_rx) = oneshot::channel::<()>();
        let gone = async move {
            let _ = gone_rx.await;
        };
        let (_replies_tx, replies) = mpsc::channel(1);
        let task = tokio::spawn(async move {
            let frames = FrameCache::default();
            pump(sink, gone, state_rx, event_rx, replies, period, &frames).await
        });
        Harness { states, events, out, client_gone: Some(gone_tx), task, channel }
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

    impl Sink<Utf8Bytes> for Recorder {
        type Error = ();
        fn poll_ready(
            self: std::pin::Pin<&mut Self>,
            _: &mut std::task::Context<'_>,
        ) -> std::task::Poll<Result<(), ()>> {
            std::task::Poll::Ready(Ok(()))
        }
        fn start_send(self: std::pin::Pin<&mut Self>, item: Utf8Bytes) -> Result<(), ()> {
            self.get_mut().buffer.push(item.to_string());
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
            pump(sink, std::future::pending(), state_rx, event_rx, replies, Duration::from_millis(50), &frames).await
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

    #[tokio::test(start_paused = true)]
    async fn the_pump_ends_when_the_session_ends() {
        let mut h = start(Duration::from_millis(50));
        next(&mut h).await;
        drop(h.states);
        assert_eq!(h.task.await.expect("pump"), StreamEnd::SessionEnded);
    }
}
