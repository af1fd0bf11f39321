//! `GET /sessions/{id}/stream`: a WebSocket that pushes a session's state and events.
//!
//! The socket logic ([`pump`]) is generic over a `Sink` of text messages and a future that
//! completes when the client goes away, so it is tested without a socket.

use std::future::Future;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::rejection::QueryRejection;
use axum::extract::ws::rejection::WebSocketUpgradeRejection;
use axum::extract::ws::{CloseFrame, Message, WebSocket, WebSocketUpgrade, close_code};
use axum::extract::{Path, Query, State};
use axum::response::Response;
use futures_util::{Sink, SinkExt, StreamExt};
use nctwin_engine::{Event, Snapshot};
use serde::Deserialize;
use tokio::sync::broadcast::error::RecvError;
use tokio::sync::{broadcast, watch};
use tokio::time::{Instant, sleep_until};
use utoipa::IntoParams;

use super::find_entry;
use crate::dto::{self, ErrorBody, EventMessage, StreamMessage};
use crate::error::ApiError;
use crate::state::AppState;

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
/// The current state is sent at once as `{"type": "state", ...}`; then at most one state
/// message per period while the state changes (intermediate states are skipped), and every
/// event as it happens (`{"type": "event", "event": "alarm_raised" | "alarm_cleared" |
/// "block_changed" | "program_ended" | "program_stopped" | "mode_changed", ...}`). A client that
/// falls more than 256 events behind skips the oldest. The server closes the socket when the
/// session is deleted or the server shuts down (close code 1001). Messages from the client are
/// ignored. At most 64 clients per session (`429`).
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
    query: Result<Query<StreamParams>, QueryRejection>,
    upgrade: Result<WebSocketUpgrade, WebSocketUpgradeRejection>,
) -> Result<Response, ApiError> {
    let entry = find_entry(&state, &id)?;
    let session = &entry.handle;
    let Query(params) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    let period = params.period()?;
    let upgrade = upgrade
        .map_err(|e| ApiError::bad_request(format!("not a WebSocket request: {}", e.body_text())))?
        .read_buffer_size(READ_BUFFER_BYTES);
    // Counted from before the upgrade until the socket is done (a failed upgrade drops the
    // closure and with it the guard).
    let client = state.add_stream_client(&entry)?;
    // Subscribe before the first state is read, so no event after it is missed.
    let events = session.subscribe_events();
    let states = session.watch_state();
    Ok(upgrade.on_upgrade(move |socket| async move {
        serve_socket(socket, states, events, period).await;
        drop(client);
    }))
}

/// Runs [`pump`] on an axum WebSocket and closes it when the session has ended.
async fn serve_socket(
    socket: WebSocket,
    states: watch::Receiver<Arc<Snapshot>>,
    events: broadcast::Receiver<Event>,
    period: Duration,
) {
    let (tx, mut rx) = socket.split();
    let mut sink = tx.with(|text: String| std::future::ready(Ok::<_, axum::Error>(Message::Text(text.into()))));
    // Reading also answers pings; the client is gone on a close frame, an error or the end.
    let client_gone = async move {
        while let Some(Ok(message)) = rx.next().await {
            if matches!(message, Message::Close(_)) {
                break;
            }
        }
    };
    let end = pump(&mut sink, client_gone, states, events, period).await;
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

/// Sends the current state, then state changes (at most one per `period`, newest only) and
/// events, until the client goes, the session ends or a send fails.
pub async fn pump<S>(
    mut sink: S,
    client_gone: impl Future<Output = ()>,
    mut states: watch::Receiver<Arc<Snapshot>>,
    mut events: broadcast::Receiver<Event>,
    period: Duration,
) -> StreamEnd
where
    S: Sink<String> + Unpin,
{
    tokio::pin!(client_gone);
    let first = states.borrow_and_update().clone();
    if send(&mut sink, StreamMessage::State(Box::new(dto::State::from(first.as_ref())))).await.is_err() {
        return StreamEnd::SendFailed;
    }
    let mut next_state_at = Instant::now() + period;
    let mut pending = false;
    loop {
        tokio::select! {
            () = &mut client_gone => return StreamEnd::ClientGone,
            changed = states.changed(), if !pending => {
                if changed.is_err() {
                    return StreamEnd::SessionEnded;
                }
                pending = true;
            }
            () = sleep_until(next_state_at), if pending => {
                pending = false;
                let latest = states.borrow_and_update().clone();
                if send(&mut sink, StreamMessage::State(Box::new(dto::State::from(latest.as_ref())))).await.is_err() {
                    return StreamEnd::SendFailed;
                }
                next_state_at = Instant::now() + period;
            }
            event = events.recv() => match event {
                Ok(event) => {
                    if send(&mut sink, StreamMessage::Event(EventMessage::from(&event))).await.is_err() {
                        return StreamEnd::SendFailed;
                    }
                }
                // Lagged: the skipped events are lost for this client only; go on with the rest.
                Err(RecvError::Lagged(_)) => {}
                Err(RecvError::Closed) => return StreamEnd::SessionEnded,
            },
        }
    }
}

async fn send<S: Sink<String> + Unpin>(sink: &mut S, message: StreamMessage) -> Result<(), S::Error> {
    // Serializing plain data with string keys cannot fail; an empty object would be harmless.
    let text = serde_json::to_string(&message).unwrap_or_else(|_| "{}".into());
    sink.send(text).await
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
        let sink = Box::pin(sink::unfold(out_tx, |tx, text: String| async move {
            tx.send(text).map_err(|_| ())?;
            Ok::<_, ()>(tx)
        }));
        let (gone_tx, gone_rx) = oneshot::channel::<()>();
        let gone = async move {
            let _ = gone_rx.await;
        };
        let task = tokio::spawn(pump(sink, gone, state_rx, event_rx, period));
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

    #[tokio::test(start_paused = true)]
    async fn the_pump_ends_when_the_session_ends() {
        let mut h = start(Duration::from_millis(50));
        next(&mut h).await;
        drop(h.states);
        assert_eq!(h.task.await.expect("pump"), StreamEnd::SessionEnded);
    }
}
