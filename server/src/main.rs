//! `nctwin`: serves the REST API, the WebSocket streams and the browser HMI.

use std::io::IsTerminal;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use nctwin_server::limits::LimitFlags;
use nctwin_server::{AppState, AuthMode, Config, Limits};
use tokio::net::TcpListener;
use tracing_subscriber::EnvFilter;

mod cli;

/// NCTwin: simulated SINUMERIK 840D sl-style NC channels over HTTP and WebSocket.
#[derive(Debug, Parser)]
#[command(name = "nctwin", version)]
struct Args {
    /// Without a subcommand, `nctwin` serves HTTP.
    #[command(subcommand)]
    command: Option<cli::Command>,
    /// Address to listen on, IP:PORT (port 0 picks a free port).
    #[arg(long, default_value = "127.0.0.1:8080")]
    bind: SocketAddr,
    /// Where data that must survive a restart is kept (created if missing).
    #[arg(long, default_value = "./nctwin-data")]
    data_dir: PathBuf,
    /// Keep sessions in this database instead of the SQLite file under `--data-dir`:
    /// `postgres://user@host:port/dbname` (PostgreSQL, for several server nodes; a password may
    /// come from the PGPASSWORD environment variable instead of the URL).
    #[arg(long, value_name = "URL")]
    database: Option<String>,
    /// With `--database`: this node's name, unique among the nodes sharing the database
    /// (default: `HOST:PORT`, the host name and the bound port). A node restarted under the
    /// same name takes its sessions back at once.
    #[arg(long, value_name = "NAME")]
    node_id: Option<String>,
    /// With `--database`: seconds a node's lease lasts without renewal (renewed three times per
    /// period, one database row per node). A node that died frees its sessions for other nodes
    /// after at most this long: the default 6 keeps a takeover behind a proxy within 10 s.
    /// Every node of a database should run the same value.
    #[arg(long, value_name = "SECONDS", default_value_t = 6, value_parser = clap::value_parser!(u64).range(1..=3600))]
    lease_seconds: u64,
    /// Folder of the browser HMI's static files.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../web/dist"))]
    web_dir: PathBuf,
    /// `off`: no tokens needed (a local server). `required`: every request to a session needs
    /// one of its tokens (owner, operator, observer), see README.
    #[arg(long, value_enum, default_value_t = AuthMode::Off)]
    auth: AuthMode,
    /// A web page origin (`http://HOST:PORT`) besides the server's own that may call the API
    /// and open streams from a browser (CORS). Repeatable. None by default: a page of another
    /// site is refused (`403`).
    #[arg(long = "allow-origin", value_name = "ORIGIN", value_parser = nctwin_server::site::parse_origin)]
    allow_origins: Vec<String>,
    /// A host name clients use for this server besides its address and localhost, `NAME` (any
    /// port) or `NAME:PORT`: e.g. the machine's LAN name when bound to 0.0.0.0. Repeatable.
    /// Requests for other names are refused (`403`, against DNS rebinding).
    #[arg(long = "allow-host", value_name = "NAME", value_parser = nctwin_server::site::parse_host)]
    allow_hosts: Vec<String>,
    #[command(flatten)]
    limits: LimitFlags,
}

/// Subcommands run on the calling thread; only the server starts the async runtime (a
/// `nctwin simulate` of a short program would otherwise spend a good part of its time
/// starting and stopping worker threads it never uses).
fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_env_filter(EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new("info")))
        .with_ansi(std::io::stdout().is_terminal())
        .init();
    let args = Args::try_parse().unwrap_or_else(cli::parse_error);
    if let Some(command) = &args.command {
        return cli::run(command);
    }
    let served = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| format!("cannot start the async runtime: {e}"))
        .and_then(|runtime| runtime.block_on(serve(args)));
    match served {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            tracing::error!("{message}");
            ExitCode::FAILURE
        }
    }
}

async fn serve(args: Args) -> Result<(), String> {
    std::fs::create_dir_all(&args.data_dir)
        .map_err(|e| format!("cannot create data directory {}: {e}", args.data_dir.display()))?;
    if !args.web_dir.join("index.html").is_file() {
        tracing::warn!("no index.html in {}: the HMI will not be served", args.web_dir.display());
    }
    let listener = TcpListener::bind(args.bind).await.map_err(|e| format!("cannot bind {}: {e}", args.bind))?;
    let addr = listener.local_addr().map_err(|e| format!("cannot read the bound address: {e}"))?;
    let config = Config {
        limits: args.limits.apply(Limits::default()),
        auth: args.auth,
        database: args.database,
        node_id: Some(
            args.node_id.unwrap_or_else(|| format!("{}:{}", nctwin_server::storage::host_name(), addr.port())),
        ),
        lease_period: std::time::Duration::from_secs(args.lease_seconds),
        allow_origins: args.allow_origins,
        allow_hosts: args.allow_hosts,
        ..Config::new(args.data_dir, args.web_dir)
    };
    let state = AppState::open(config).await.map_err(|e| format!("cannot open the storage: {e}"))?;
    let shutdown = shutdown_signal();
    tracing::info!("listening on http://{addr}");
    nctwin_server::run(listener, state, shutdown).await.map_err(|e| format!("server error: {e}"))?;
    tracing::info!("stopped");
    Ok(())
}

/// Completes on Ctrl-C (SIGINT) or, on Unix, SIGTERM. The handlers are installed when this is
/// called, not when the future is first polled: a signal that arrives while the server is
/// already listening but the accept loop has not yet polled its shutdown future must not
/// kill the process with the default action (the loop polls it only when no connection is
/// waiting).
#[cfg(unix)]
fn shutdown_signal() -> impl std::future::Future<Output = ()> {
    use tokio::signal::unix::{SignalKind, signal};
    let interrupt = signal(SignalKind::interrupt());
    let terminate = signal(SignalKind::terminate());
    async move {
        let (Ok(mut interrupt), Ok(mut terminate)) = (interrupt, terminate) else {
            return std::future::pending::<()>().await;
        };
        tokio::select! {
            _ = interrupt.recv() => {}
            _ = terminate.recv() => {}
        }
        tracing::info!("shutting down");
    }
}

/// Completes on Ctrl-C.
#[cfg(not(unix))]
fn shutdown_signal() -> impl std::future::Future<Output = ()> {
    async {
        if tokio::signal::ctrl_c().await.is_err() {
            std::future::pending::<()>().await;
        }
        tracing::info!("shutting down");
    }
}
