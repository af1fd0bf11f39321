//! The accept loop: one task per connection serving HTTP/1.1 with upgrades (hyper), the
//! per-IP cap on open connections and the header-read timeout.
//!
//! Why not `axum::serve`: it has no timer, so a connection that never finishes its request head
//! stays open for ever, and no hook to count or refuse connections by address.
//!
//! A connection's place in its address' count is held by its socket ([`Counted`]), so a
//! connection upgraded to a WebSocket stream keeps counting until the stream is dropped.
//! HTTP/2 is not served (as before): every stream is a TCP connection of its own.

use std::collections::HashMap;
use std::future::Future;
use std::io;
use std::net::IpAddr;
use std::pin::{Pin, pin};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::Duration;

use axum::Router;
use axum::extract::ConnectInfo;
use hyper::body::Incoming;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, ReadBuf};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::watch;
use tower_service::Service;

use crate::state::AppState;

/// Longest a refused connection is kept for its `429` to be sent and read.
const REFUSE_WAIT: Duration = Duration::from_secs(1);

/// Serves `router` on `listener` until `shutdown` completes; then drops the listener (no new
/// connections), asks every open connection to finish gracefully (an idle one closes at once,
/// one in a request after its response) and waits until all have ended.
///
/// Every request carries the peer's `ConnectInfo<SocketAddr>` as an extension.
pub(crate) async fn serve(
    listener: TcpListener,
    router: Router,
    state: AppState,
    shutdown: impl Future<Output = ()>,
) -> io::Result<()> {
    let limits = *state.limits();
    let peers = Peers::new(state, limits.connections_per_ip);
    let (stop_tx, stop_rx) = watch::channel(false);
    // Every connection task holds a receiver; `closed()` completes when the last one is gone.
    let (done_tx, done_rx) = watch::channel(());
    let mut shutdown = pin!(shutdown);
    loop {
        let (tcp, remote) = tokio::select! {
            accepted = listener.accept() => match accepted {
                Ok(accepted) => accepted,
                Err(e) if is_connection_error(&e) => continue,
                Err(e) => {
                    // Out of file descriptors, say: wait for some to be freed.
                    tracing::error!("accepting a connection failed: {e}");
                    tokio::select! {
                        () = tokio::time::sleep(Duration::from_secs(1)) => continue,
                        () = &mut shutdown => break,
                    }
                }
            },
            () = &mut shutdown => break,
        };
        let Some(guard) = peers.admit(remote.ip()) else {
            tracing::debug!("refused a connection from {remote}: {} are open", limits.connections_per_ip);
            tokio::spawn(refuse(tcp, limits.connections_per_ip));
            continue;
        };
        let io = TokioIo::new(Counted { io: tcp, _guard: guard });
        let router = router.clone();
        let service = hyper::service::service_fn(move |mut request: hyper::Request<Incoming>| {
            request.extensions_mut().insert(ConnectInfo(remote));
            let mut router = router.clone();
            async move { router.call(request).await }
        });
        let mut stop = stop_rx.clone();
        let done = done_rx.clone();
        tokio::spawn(async move {
            let mut builder = http1::Builder::new();
            builder.timer(TokioTimer::new()).header_read_timeout(limits.header_read_timeout);
            let mut conn = pin!(builder.serve_connection(io, service).with_upgrades());
            let mut stopping = false;
            loop {
                tokio::select! {
                    result = conn.as_mut() => {
                        if let Err(e) = result {
                            tracing::debug!("connection from {remote}: {e}");
                        }
                        break;
                    }
                    _ = stop.changed(), if !stopping => {
                        stopping = true;
                        conn.as_mut().graceful_shutdown();
                    }
                }
            }
            drop(done);
        });
    }
    drop(listener);
    let _ = stop_tx.send(true);
    drop(done_rx);
    done_tx.closed().await;
    Ok(())
}

/// Errors of one connection that `accept` reports; the listener is fine.
fn is_connection_error(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::ConnectionRefused | io::ErrorKind::ConnectionAborted | io::ErrorKind::ConnectionReset
    )
}

/// Answers a connection over the per-IP cap with `429` and closes it. What the client sent is
/// read (and dropped) until it closes, briefly, so that the close does not reset the connection
/// before the client has read the answer.
async fn refuse(mut tcp: TcpStream, cap: usize) {
    let body = format!("{{\"error\":\"too many connections from this address: the limit is {cap}\"}}");
    let response = format!(
        "HTTP/1.1 429 Too Many Requests\r\ncontent-type: application/json\r\ncontent-length: {}\r\nconnection: close\r\n\r\n{body}",
        body.len()
    );
    let _ = tokio::time::timeout(REFUSE_WAIT, async {
        tcp.write_all(response.as_bytes()).await?;
        tcp.shutdown().await?;
        let mut buf = [0u8; 1024];
        let mut left = 64usize << 10;
        while left > 0 {
            let n = tcp.read(&mut buf).await?;
            if n == 0 {
                break;
            }
            left = left.saturating_sub(n);
        }
        Ok::<_, io::Error>(())
    })
    .await;
}

/// Open connections by client address.
#[derive(Clone)]
struct Peers(Arc<PeersInner>);

struct PeersInner {
    /// Held for one update, never across an await.
    open: Mutex<HashMap<IpAddr, usize>>,
    cap: usize,
    state: AppState,
}

impl Peers {
    fn new(state: AppState, cap: usize) -> Peers {
        Peers(Arc::new(PeersInner { open: Mutex::new(HashMap::new()), cap, state }))
    }

    /// A place for a connection from `ip`, or `None` when it holds as many as allowed.
    fn admit(&self, ip: IpAddr) -> Option<PeerGuard> {
        let mut open = self.0.open.lock().unwrap_or_else(|e| e.into_inner());
        let count = open.entry(ip).or_default();
        if *count >= self.0.cap {
            if *count == 0 {
                open.remove(&ip);
            }
            drop(open);
            self.0.state.metrics().connection_refused();
            return None;
        }
        *count += 1;
        drop(open);
        self.0.state.metrics().connection(true);
        Some(PeerGuard { peers: self.clone(), ip })
    }
}

/// One connection's place in its address' count, given back on drop.
struct PeerGuard {
    peers: Peers,
    ip: IpAddr,
}

impl Drop for PeerGuard {
    fn drop(&mut self) {
        let inner = &self.peers.0;
        let mut open = inner.open.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(count) = open.get_mut(&self.ip) {
            *count -= 1;
            if *count == 0 {
                open.remove(&self.ip);
            }
        }
        drop(open);
        inner.state.metrics().connection(false);
    }
}

/// A connection's socket with its place in the per-IP count: it goes where the socket goes,
/// into a WebSocket stream after an upgrade.
struct Counted {
    io: TcpStream,
    _guard: PeerGuard,
}

impl AsyncRead for Counted {
    fn poll_read(self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_read(cx, buf)
    }
}

impl AsyncWrite for Counted {
    fn poll_write(self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &[u8]) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.get_mut().io).poll_write(cx, buf)
    }

    fn poll_write_vectored(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        Pin::new(&mut self.get_mut().io).poll_write_vectored(cx, bufs)
    }

    fn is_write_vectored(&self) -> bool {
        self.io.is_write_vectored()
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_flush(cx)
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_shutdown(cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_address_gets_its_places_back_when_connections_close() {
        let peers = Peers::new(AppState::new("unused", "unused"), 2);
        let a: IpAddr = [10, 0, 0, 1].into();
        let b: IpAddr = [10, 0, 0, 2].into();
        let first = peers.admit(a).expect("first");
        let second = peers.admit(a).expect("second");
        assert!(peers.admit(a).is_none(), "the cap holds");
        let other = peers.admit(b).expect("another address has its own count");
        drop(first);
        let third = peers.admit(a).expect("a place came free");
        drop((second, third, other));
        assert!(peers.0.open.lock().expect("lock").is_empty(), "no entry is left behind");
    }
}
