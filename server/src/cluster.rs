//! Several nodes behind one proxy (`deploy/haproxy.cfg`): the two headers through which a node
//! and the proxy tell each other who holds a session.
//!
//! - [`HOLDER_HEADER`] (`nctwin-holder`) on a response names the node holding the session the
//!   request was for: this node on a success (and on `201` of a session's creation, whose
//!   `Location` names the session), the holder on a `421`. The proxy remembers it per session id
//!   and sends the session's next requests to that node, so a client never sees the `421`
//!   itself except once per proxy restart (the proxy turns it into a `307` to the same URL).
//! - [`ROUTED_HEADER`] (`nctwin-routed-holder`) on a request, set by the proxy only, names the
//!   node the proxy believes holds the session and sent the request to. When the request
//!   arrives at another node, the proxy could not reach that one: it is marked down, or the
//!   connection failed and the proxy redispatched. A node asked for a session held by the node
//!   this header names then waits for the holder's lease to run out and takes the session over
//!   (see [`crate::state::AppState::find_entry`]) instead of answering `421` (which would send
//!   the client back to the dead node): the takeover after a node failure costs the client a
//!   pause, not an error. The header cannot steal a live session: the storage hands a session
//!   over only when its holder stopped renewing; after one wait the node answers `421`.
//!
//! The per-request values travel in a task-local ([`RequestRouting`]): [`layer`] sets it
//! around the handler, the lease code reads and fills it.

use std::sync::{Arc, Mutex};

use axum::extract::{Request, State};
use axum::http::{HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::Response;

use crate::state::AppState;

/// Response header: the node that holds the request's session.
pub const HOLDER_HEADER: &str = "nctwin-holder";
/// Request header (set by the proxy): the node the proxy sent the request to as the holder.
pub const ROUTED_HEADER: &str = "nctwin-routed-holder";

/// What the cluster headers of one request carry.
#[derive(Debug, Default)]
pub struct RequestRouting {
    /// The node the proxy meant the request for ([`ROUTED_HEADER`]).
    pub routed_to: Option<String>,
    /// The node found holding the session when this node could not serve it (`421`).
    pub holder: Option<String>,
}

tokio::task_local! {
    static ROUTING: Arc<Mutex<RequestRouting>>;
}

/// The node the proxy meant the current request for, if it said so.
pub fn routed_to() -> Option<String> {
    ROUTING.try_with(|r| r.lock().unwrap_or_else(|e| e.into_inner()).routed_to.clone()).ok().flatten()
}

/// Notes that `node` holds the current request's session (it is answered `421`).
pub fn note_holder(node: &str) {
    let _ = ROUTING.try_with(|r| r.lock().unwrap_or_else(|e| e.into_inner()).holder = Some(node.to_string()));
}

/// Middleware: runs the request with its [`RequestRouting`] and names the holder in the
/// response ([`HOLDER_HEADER`]). Only on a node of a shared database; a single node's answers
/// are unchanged.
pub async fn layer(State(state): State<AppState>, request: Request, next: Next) -> Response {
    let Some(node) = state.node_name() else { return next.run(request).await };
    let routed_to = request.headers().get(ROUTED_HEADER).and_then(|v| v.to_str().ok()).map(str::to_string);
    let routing = Arc::new(Mutex::new(RequestRouting { routed_to, holder: None }));
    let mut response = ROUTING.scope(routing.clone(), next.run(request)).await;
    let holder = if response.status() == StatusCode::MISDIRECTED_REQUEST {
        routing.lock().unwrap_or_else(|e| e.into_inner()).holder.take()
    } else if response.status().is_success() || response.status() == StatusCode::SWITCHING_PROTOCOLS {
        Some(node)
    } else {
        None
    };
    if let Some(value) = holder.and_then(|h| HeaderValue::from_str(&h).ok()) {
        response.headers_mut().insert(HOLDER_HEADER, value);
    }
    response
}
