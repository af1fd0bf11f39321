//! NCTwin server: the async shell around the deterministic [`nctwin_engine`].
//!
//! The engine is stepped one IPO cycle at a time and knows nothing of clocks, threads or the
//! network; this crate turns wall time, HTTP and WebSockets into calls on it.
//!
//! Layout, one job per module:
//! - [`session`]: one actor task per session owns its `Channel`, paces it (real time or fast)
//!   and publishes its state (`watch`) and events (`broadcast`). Knows nothing of HTTP or JSON.
//! - [`state`]: [`AppState`], the cheap-to-clone handle shared by every request: the session
//!   registry with each session's tokens, control holder and rate limiter, the storage, the
//!   configured directories and limits. Every save goes through it.
//! - [`storage`]: the one module that touches files: the [`storage::Storage`] trait with the
//!   embedded SQLite default (and an in-memory one for tests).
//! - [`auth`]: roles, tokens and the access policy with its middleware.
//! - [`limits`]: every server-side limit with its default, and the command rate limiter.
//! - [`metrics`]: counters and the Prometheus text of `GET /metrics`.
//! - [`api`]: one file per REST resource plus the WebSocket stream; handlers are thin: parse,
//!   send a command, map the reply.
//! - [`dto`]: the wire types (serde + OpenAPI schemas) and their conversion from engine types.
//!   Only `dto` and `api` know JSON.
//! - [`extract`]: the JSON body extractors that turn every malformed request into a `400`.
//! - [`error`]: [`ApiError`], the one error type, mapped to an HTTP status and `{"error", "line"}`.
//! - [`openapi`]: the OpenAPI 3.1 document generated from the handlers, and Swagger UI.
//! - [`conn`]: the accept loop: one hyper HTTP/1.1 task per connection, the per-IP connection
//!   cap and the header-read timeout.
//! - [`text_decode`]: file bytes → text (UTF-8, UTF-16 with BOM, legacy code pages guessed).
//! - [`http`]: the tower-http layers (tracing, CORS, compression, body limit, timeouts), the
//!   static HMI files and the JSON shape of errors produced outside the handlers.
//! - [`site`]: which `Host` the server answers to and which web page origins may call it
//!   (DNS rebinding, cross-site requests).

pub mod api;
pub mod auth;
pub mod cluster;
mod conn;
pub mod dto;
pub mod error;
pub mod extract;
pub mod http;
pub mod limits;
pub mod metrics;
pub mod openapi;
pub mod session;
pub mod site;
pub mod state;
pub mod storage;
pub mod text_decode;

use std::future::Future;
use std::time::Duration;

use axum::Router;
use tokio::net::TcpListener;
use tokio::sync::watch;

pub use auth::AuthMode;
pub use error::ApiError;
pub use limits::Limits;
pub use state::{AppState, Config};

/// Version reported by `GET /api/v1/health` and in the OpenAPI document.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The complete application: REST API, WebSocket streams, OpenAPI document, Swagger UI and the
/// static HMI. Tests can drive it without a socket (the `Host` check then knows no port: see
/// [`site`]), or serve it with [`run`].
pub fn app(state: AppState) -> Router {
    http::app(state, None)
}

/// Serves [`app`] on `listener` until `shutdown` completes, then shuts down gracefully:
///
/// Each connection is served by hyper's HTTP/1.1 with upgrades, with the header-read timeout and
/// the per-IP connection cap of [`Limits`]; handlers can extract `ConnectInfo<SocketAddr>`.
///
/// 1. stop accepting connections (the listener is closed at once);
/// 2. save every session's checkpoint, then stop every session, which answers waiting requests
///    and closes every WebSocket stream with a close frame (1001, "session ended");
/// 3. wait for open connections and streams to finish, at most [`Limits::shutdown_grace`];
///    then return anyway.
///
/// Every session is saved before this returns, however the server stopped. Tests bind
/// `127.0.0.1:0`, spawn this and read the address from the listener.
pub async fn run(
    listener: TcpListener,
    state: AppState,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    // The `Host` check needs the port actually bound (tests bind port 0).
    let router = http::app(state.clone(), listener.local_addr().ok());
    let grace = state.limits().shutdown_grace;
    let (stop_tx, mut stop_rx) = watch::channel(false);
    let stop_tx = std::sync::Arc::new(stop_tx);
    let (saved_tx, mut saved_rx) = watch::channel(false);
    let signal = stop_tx.clone();
    let serve = conn::serve(listener, router, state.clone(), async move {
        shutdown.await;
        tracing::info!("shutting down: no new connections; saving and closing every session");
        let _ = signal.send(true);
    });
    let closer_state = state.clone();
    tokio::spawn(async move {
        if stop_rx.wait_for(|stop| *stop).await.is_ok() {
            closer_state.shutdown_sessions().await;
            tracing::info!("every session closed");
        }
        let _ = saved_tx.send(true);
    });
    let deadline = {
        let mut saved_rx = saved_rx.clone();
        async move {
            if saved_rx.wait_for(|saved| *saved).await.is_ok() {
                tokio::time::sleep(grace).await;
            } else {
                std::future::pending::<()>().await;
            }
        }
    };
    let result = tokio::select! {
        result = serve => result,
        () = deadline => {
            tracing::warn!("connections still open {grace:?} after every session was closed; stopping anyway");
            Ok(())
        }
    };
    // However serving ended (also on an I/O error), every session is saved before returning.
    let _ = stop_tx.send(true);
    let _ = saved_rx.wait_for(|saved| *saved).await;
    // Let the streams send their close frames (bounded by the grace time).
    let streams_deadline = tokio::time::Instant::now() + grace;
    while state.open_streams() > 0 && tokio::time::Instant::now() < streams_deadline {
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    result
}
