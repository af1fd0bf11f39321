//! NCTwin server: the async shell around the deterministic [`nctwin_engine`].
//!
//! The engine is stepped one IPO cycle at a time and knows nothing of clocks, threads or the
//! network; this crate turns wall time, HTTP and WebSockets into calls on it.
//!
//! Layout, one job per module:
//! - [`session`]: one actor task per session owns its `Channel`, paces it (real time or fast)
//!   and publishes its state (`watch`) and events (`broadcast`). Knows nothing of HTTP or JSON.
//! - [`state`]: [`AppState`], the cheap-to-clone handle shared by every request: the session
//!   registry, the configured directories and the server-side limits.
//! - [`api`]: one file per REST resource plus the WebSocket stream; handlers are thin: parse,
//!   send a command, map the reply.
//! - [`dto`]: the wire types (serde + OpenAPI schemas) and their conversion from engine types.
//!   Only `dto` and `api` know JSON.
//! - [`extract`]: the JSON body extractors that turn every malformed request into a `400`.
//! - [`error`]: [`ApiError`], the one error type, mapped to an HTTP status and `{"error", "line"}`.
//! - [`openapi`]: the OpenAPI 3.1 document generated from the handlers, and Swagger UI.
//! - [`http`]: the tower-http layers (tracing, CORS, compression, body limit, timeouts), the
//!   static HMI files and the JSON shape of errors produced outside the handlers.

pub mod api;
pub mod dto;
pub mod error;
pub mod extract;
pub mod http;
pub mod openapi;
pub mod session;
pub mod state;

use std::future::Future;

use axum::Router;
use tokio::net::TcpListener;

pub use error::ApiError;
pub use state::{AppState, Limits};

/// Version reported by `GET /api/v1/health` and in the OpenAPI document.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The complete application: REST API, WebSocket streams, OpenAPI document, Swagger UI and the
/// static HMI. Tests can drive it without a socket, or serve it with [`run`].
pub fn app(state: AppState) -> Router {
    http::app(state)
}

/// Serves [`app`] on `listener` until `shutdown` completes, then stops every session and lets
/// open requests finish.
///
/// Tests bind `127.0.0.1:0`, spawn this and read the address from the listener.
pub async fn run(
    listener: TcpListener,
    state: AppState,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    let router = app(state.clone());
    let shutdown_state = state.clone();
    axum::serve(listener, router)
        .with_graceful_shutdown(async move {
            shutdown.await;
            // Ending the actors closes every WebSocket stream and answers every waiting
            // request, so graceful shutdown does not wait for up to ten minutes.
            shutdown_state.close_all_sessions().await;
        })
        .await
}
