//! Metrics in the Prometheus text format (`GET /metrics`): sessions, stream clients, IPO lag,
//! request counts and latencies per route, storage calls, bytes of stored programs (per
//! session: a label per live session, bounded by the session limit), open and refused
//! connections, streams the server closed on a misbehaving client.
//!
//! Counters are plain atomics and one small map per route template (not per URL: the label
//! set stays bounded however many sessions exist); gauges are read from the registry when
//! scraped. No metrics crate: the format is a few lines of text.

use std::collections::BTreeMap;
use std::fmt::Write;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use axum::extract::{MatchedPath, Request, State};
use axum::http::header::CONTENT_TYPE;
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use nctwin_engine::Status;

use crate::session::{LATENESS_BUCKETS, WakeCounts, wake_stats};
use crate::state::AppState;

/// Upper bounds (seconds) of the request latency histogram: quick answers up to the longest
/// `wait: true` request.
const LATENCY_BUCKETS: [f64; 12] = [0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 1.0, 5.0, 30.0, 600.0];

/// Content type of the Prometheus text exposition format.
pub const CONTENT_TYPE_TEXT: &str = "text/plain; version=0.0.4; charset=utf-8";

/// The server's counters.
#[derive(Debug, Default)]
pub struct Metrics {
    /// By (method, route template). Held for one update or one scrape, never across an await.
    routes: Mutex<BTreeMap<(String, String), RouteStats>>,
    storage_ok: AtomicU64,
    storage_failed: AtomicU64,
    /// Open TCP connections (WebSocket streams included).
    connections: AtomicU64,
    /// Connections refused by the per-IP cap.
    connections_refused: AtomicU64,
    /// Streams the server closed, by [`StreamClose`].
    stream_closes: [AtomicU64; StreamClose::ALL.len()],
    /// Several nodes on one database: lease renewals and takeovers.
    leases: Mutex<LeaseStats>,
}

/// Upper bounds (seconds) of the lease renewal latency histogram: one small transaction, up
/// to the lease period a renewal must beat.
const RENEWAL_BUCKETS: [f64; 10] = [0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.5, 1.0, 5.0];

/// Lease renewals of this node (one per tick of its heartbeat) and sessions it took over.
#[derive(Debug, Default, Clone)]
struct LeaseStats {
    renewals_ok: u64,
    renewals_failed: u64,
    /// Per bucket of [`RENEWAL_BUCKETS`] (not cumulative), plus one for +Inf.
    renewal_buckets: [u64; RENEWAL_BUCKETS.len() + 1],
    renewal_sum: f64,
    /// Sessions the last successful renewal found leased to this node.
    held_at_renewal: u64,
    takeovers: u64,
    /// Seconds spent claiming and loading the sessions taken over.
    takeover_sum: f64,
}

/// Why the server closed a WebSocket stream on its client.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamClose {
    /// Pings went unanswered (1008).
    PongsMissed,
    /// A write did not complete in time: the client does not read.
    Stalled,
    /// A write failed: the connection broke or the write buffer is full.
    SendFailed,
    /// The client sent a frame or message over the size limit (1009).
    TooBig,
}

impl StreamClose {
    const ALL: [StreamClose; 4] =
        [StreamClose::PongsMissed, StreamClose::Stalled, StreamClose::SendFailed, StreamClose::TooBig];

    fn label(self) -> &'static str {
        match self {
            StreamClose::PongsMissed => "pongs_missed",
            StreamClose::Stalled => "write_stalled",
            StreamClose::SendFailed => "write_failed",
            StreamClose::TooBig => "message_too_big",
        }
    }
}

#[derive(Debug, Default, Clone)]
struct RouteStats {
    by_status: BTreeMap<u16, u64>,
    /// Counts per bucket of [`LATENCY_BUCKETS`] (not cumulative), plus one for +Inf.
    buckets: [u64; LATENCY_BUCKETS.len() + 1],
    sum: f64,
    count: u64,
}

impl Metrics {
    /// Counts one answered request.
    pub fn record_request(&self, method: &str, route: &str, status: u16, elapsed: Duration) {
        let seconds = elapsed.as_secs_f64();
        let bucket = LATENCY_BUCKETS.iter().position(|b| seconds <= *b).unwrap_or(LATENCY_BUCKETS.len());
        let mut routes = self.routes.lock().unwrap_or_else(|e| e.into_inner());
        let stats = routes.entry((method.to_string(), route.to_string())).or_default();
        *stats.by_status.entry(status).or_default() += 1;
        stats.buckets[bucket] += 1;
        stats.sum += seconds;
        stats.count += 1;
    }

    /// Counts one storage call.
    pub fn storage_call(&self, ok: bool) {
        let counter = if ok { &self.storage_ok } else { &self.storage_failed };
        counter.fetch_add(1, Ordering::Relaxed);
    }

    /// Counts a connection opened (`true`) or closed.
    pub fn connection(&self, opened: bool) {
        if opened {
            self.connections.fetch_add(1, Ordering::Relaxed);
        } else {
            self.connections.fetch_sub(1, Ordering::Relaxed);
        }
    }

    /// Counts a connection refused by the per-IP cap.
    pub fn connection_refused(&self) {
        self.connections_refused.fetch_add(1, Ordering::Relaxed);
    }

    /// Counts a stream the server closed on its client.
    pub fn stream_closed(&self, why: StreamClose) {
        let i = StreamClose::ALL.iter().position(|w| *w == why).unwrap_or_default();
        self.stream_closes[i].fetch_add(1, Ordering::Relaxed);
    }

    /// Counts one lease renewal: `held` sessions still leased to this node (`None`: it failed),
    /// taking `elapsed`.
    pub fn lease_renewal(&self, held: Option<usize>, elapsed: Duration) {
        let seconds = elapsed.as_secs_f64();
        let bucket = RENEWAL_BUCKETS.iter().position(|b| seconds <= *b).unwrap_or(RENEWAL_BUCKETS.len());
        let mut leases = self.leases.lock().unwrap_or_else(|e| e.into_inner());
        match held {
            Some(n) => {
                leases.renewals_ok += 1;
                leases.held_at_renewal = n as u64;
            }
            None => leases.renewals_failed += 1,
        }
        leases.renewal_buckets[bucket] += 1;
        leases.renewal_sum += seconds;
    }

    /// Counts a session taken over from the shared database (its claim took `elapsed`).
    pub fn lease_takeover(&self, elapsed: Duration) {
        let mut leases = self.leases.lock().unwrap_or_else(|e| e.into_inner());
        leases.takeovers += 1;
        leases.takeover_sum += elapsed.as_secs_f64();
    }

    /// The text exposition of every metric, with the registry's gauges read now.
    pub fn render(&self, state: &AppState) -> String {
        let entries = state.list_entries();
        let streams: usize = entries.iter().map(|e| e.stream_clients()).sum();
        let running = entries.iter().filter(|e| e.handle.snapshot().status == Status::Running).count();
        let lag = entries.iter().map(|e| e.handle.ipo_lag()).max().unwrap_or_default();

        let mut out = String::new();
        gauge(&mut out, "nctwin_sessions", "Live sessions.", entries.len() as f64);
        gauge(&mut out, "nctwin_running_sessions", "Sessions whose channel is running.", running as f64);
        gauge(&mut out, "nctwin_stream_clients", "Open WebSocket stream clients.", streams as f64);
        gauge(
            &mut out,
            "nctwin_ipo_lag_seconds_max",
            "Largest lateness of the last real-time wake-up over all sessions (0 when none is stepped in real time).",
            lag.as_secs_f64(),
        );
        program_bytes(&mut out, &entries, state.limits().program_budget_bytes);
        gauge(
            &mut out,
            "nctwin_connections",
            "Open TCP connections, WebSocket streams included.",
            self.connections.load(Ordering::Relaxed) as f64,
        );
        let refused = "nctwin_connections_refused_total";
        let _ =
            writeln!(out, "# HELP {refused} Connections refused (429) because their address held as many as allowed.");
        let _ = writeln!(out, "# TYPE {refused} counter");
        let _ = writeln!(out, "{refused} {}", self.connections_refused.load(Ordering::Relaxed));
        let closes = "nctwin_stream_closes_total";
        let _ = writeln!(
            out,
            "# HELP {closes} WebSocket streams the server closed on a client that misbehaved, by reason."
        );
        let _ = writeln!(out, "# TYPE {closes} counter");
        for (why, n) in StreamClose::ALL.iter().zip(&self.stream_closes) {
            let _ = writeln!(out, "{closes}{{reason=\"{}\"}} {}", why.label(), n.load(Ordering::Relaxed));
        }
        wake_histogram(&mut out, &wake_stats().counts());
        if let Some(node) = state.node_name() {
            let leases = self.leases.lock().unwrap_or_else(|e| e.into_inner()).clone();
            lease_metrics(&mut out, &node, entries.len(), &leases);
        }
        let _ = writeln!(out, "# HELP nctwin_storage_operations_total Storage calls by result.");
        let _ = writeln!(out, "# TYPE nctwin_storage_operations_total counter");
        let _ = writeln!(
            out,
            "nctwin_storage_operations_total{{result=\"ok\"}} {}",
            self.storage_ok.load(Ordering::Relaxed)
        );
        let _ = writeln!(
            out,
            "nctwin_storage_operations_total{{result=\"error\"}} {}",
            self.storage_failed.load(Ordering::Relaxed)
        );

        let routes = self.routes.lock().unwrap_or_else(|e| e.into_inner()).clone();
        let _ = writeln!(out, "# HELP nctwin_http_requests_total Answered HTTP requests by method, route and status.");
        let _ = writeln!(out, "# TYPE nctwin_http_requests_total counter");
        for ((method, route), stats) in &routes {
            for (status, n) in &stats.by_status {
                let _ = writeln!(
                    out,
                    "nctwin_http_requests_total{{method=\"{}\",route=\"{}\",status=\"{status}\"}} {n}",
                    escape(method),
                    escape(route)
                );
            }
        }
        let _ = writeln!(out, "# HELP nctwin_http_request_duration_seconds Time to answer HTTP requests.");
        let _ = writeln!(out, "# TYPE nctwin_http_request_duration_seconds histogram");
        for ((method, route), stats) in &routes {
            let labels = format!("method=\"{}\",route=\"{}\"", escape(method), escape(route));
            let mut cumulative = 0;
            for (i, bound) in LATENCY_BUCKETS.iter().enumerate() {
                cumulative += stats.buckets[i];
                let _ = writeln!(
                    out,
                    "nctwin_http_request_duration_seconds_bucket{{{labels},le=\"{bound}\"}} {cumulative}"
                );
            }
            let _ =
                writeln!(out, "nctwin_http_request_duration_seconds_bucket{{{labels},le=\"+Inf\"}} {}", stats.count);
            let _ = writeln!(out, "nctwin_http_request_duration_seconds_sum{{{labels}}} {}", stats.sum);
            let _ = writeln!(out, "nctwin_http_request_duration_seconds_count{{{labels}}} {}", stats.count);
        }
        out
    }
}

fn gauge(out: &mut String, name: &str, help: &str, value: f64) {
    let _ = writeln!(out, "# HELP {name} {help}");
    let _ = writeln!(out, "# TYPE {name} gauge");
    let _ = writeln!(out, "{name} {value}");
}

/// Bytes of stored programs: per session, on the whole server, and the server's budget.
fn program_bytes(out: &mut String, entries: &[std::sync::Arc<crate::state::SessionEntry>], budget: usize) {
    let name = "nctwin_session_program_bytes";
    let _ = writeln!(out, "# HELP {name} Bytes of stored programs held by each live session.");
    let _ = writeln!(out, "# TYPE {name} gauge");
    for entry in entries {
        let _ = writeln!(out, "{name}{{session=\"{}\"}} {}", escape(entry.id()), entry.program_bytes());
    }
    let total: usize = entries.iter().map(|e| e.program_bytes()).sum();
    gauge(out, "nctwin_program_bytes", "Bytes of stored programs held by all live sessions.", total as f64);
    gauge(
        out,
        "nctwin_program_budget_bytes",
        "The server's budget of stored program bytes, all sessions together (--program-budget-bytes).",
        budget as f64,
    );
}

/// The lateness of real-time wake-ups (the server-side IPO lag) and the cycles dropped by the
/// catch-up cap.
fn wake_histogram(out: &mut String, counts: &WakeCounts) {
    let name = "nctwin_ipo_wake_lateness_seconds";
    let _ = writeln!(out, "# HELP {name} How late real-time wake-ups of sessions came against their schedule.");
    let _ = writeln!(out, "# TYPE {name} histogram");
    let mut cumulative = 0;
    for (bound, n) in LATENESS_BUCKETS.iter().zip(&counts.buckets) {
        cumulative += n;
        let _ = writeln!(out, "{name}_bucket{{le=\"{bound}\"}} {cumulative}");
    }
    let _ = writeln!(out, "{name}_bucket{{le=\"+Inf\"}} {}", counts.count());
    let _ = writeln!(out, "{name}_sum {}", counts.sum.as_secs_f64());
    let _ = writeln!(out, "{name}_count {}", counts.count());
    let dropped = "nctwin_ipo_cycles_dropped_total";
    let _ = writeln!(
        out,
        "# HELP {dropped} IPO cycles not stepped because a wake-up came later than the catch-up cap (1 s): simulated time lost against wall time."
    );
    let _ = writeln!(out, "# TYPE {dropped} counter");
    let _ = writeln!(out, "{dropped} {}", counts.dropped_cycles);
}

/// This node's leases: sessions held, renewals (count, failures, latency histogram) and
/// takeovers, each labelled with the node's name.
fn lease_metrics(out: &mut String, node: &str, held: usize, leases: &LeaseStats) {
    let label = format!("node=\"{}\"", escape(node));
    let mut counter = |name: &str, help: &str, kind: &str, value: String| {
        let _ = writeln!(out, "# HELP {name} {help}");
        let _ = writeln!(out, "# TYPE {name} {kind}");
        let _ = writeln!(out, "{name}{{{label}}} {value}");
    };
    counter(
        "nctwin_node_sessions_held",
        "Sessions this node holds the lease of and serves.",
        "gauge",
        held.to_string(),
    );
    counter(
        "nctwin_node_sessions_leased",
        "Sessions leased to this node at its last lease renewal (the database's count).",
        "gauge",
        leases.held_at_renewal.to_string(),
    );
    counter(
        "nctwin_node_takeovers_total",
        "Sessions this node took over from the shared database (free, or their holder's lease expired).",
        "counter",
        leases.takeovers.to_string(),
    );
    counter(
        "nctwin_node_takeover_seconds_total",
        "Time spent claiming and restoring the sessions taken over.",
        "counter",
        leases.takeover_sum.to_string(),
    );
    counter(
        "nctwin_node_lease_renewal_failures_total",
        "Lease renewals that failed (the database did not answer).",
        "counter",
        leases.renewals_failed.to_string(),
    );
    let name = "nctwin_node_lease_renewal_seconds";
    let _ = writeln!(out, "# HELP {name} Time of this node's lease renewals (one row per node, whatever it holds).");
    let _ = writeln!(out, "# TYPE {name} histogram");
    let mut cumulative = 0;
    for (bound, n) in RENEWAL_BUCKETS.iter().zip(&leases.renewal_buckets) {
        cumulative += n;
        let _ = writeln!(out, "{name}_bucket{{{label},le=\"{bound}\"}} {cumulative}");
    }
    let count = leases.renewals_ok + leases.renewals_failed;
    let _ = writeln!(out, "{name}_bucket{{{label},le=\"+Inf\"}} {count}");
    let _ = writeln!(out, "{name}_sum{{{label}}} {}", leases.renewal_sum);
    let _ = writeln!(out, "{name}_count{{{label}}} {count}");
}

/// Escapes a label value (backslash, double quote, newline).
fn escape(value: &str) -> String {
    value.replace('\\', "\\\\").replace('"', "\\\"").replace('\n', "\\n")
}

/// Middleware (route layer) that counts every routed request by its route template.
pub async fn track(State(state): State<AppState>, request: Request, next: Next) -> Response {
    let start = Instant::now();
    let method = request.method().to_string();
    let route =
        request.extensions().get::<MatchedPath>().map_or_else(|| "unmatched".to_string(), |p| p.as_str().to_string());
    let response = next.run(request).await;
    state.metrics().record_request(&method, &route, response.status().as_u16(), start.elapsed());
    response
}

/// `GET /metrics`.
pub async fn metrics(State(state): State<AppState>) -> Response {
    ([(CONTENT_TYPE, CONTENT_TYPE_TEXT)], state.metrics().render(&state)).into_response()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_counted_with_a_cumulative_latency_histogram() {
        let metrics = Metrics::default();
        let state = AppState::new("unused", "unused");
        metrics.record_request("GET", "/api/v1/health", 200, Duration::from_micros(500));
        metrics.record_request("GET", "/api/v1/health", 200, Duration::from_millis(20));
        metrics.record_request("POST", "/api/v1/sessions/{id}/run", 404, Duration::from_secs(1000));
        let text = metrics.render(&state);
        assert!(
            text.contains("nctwin_http_requests_total{method=\"GET\",route=\"/api/v1/health\",status=\"200\"} 2"),
            "{text}"
        );
        assert!(text.contains("route=\"/api/v1/health\",le=\"0.001\"} 1\n"), "{text}");
        assert!(text.contains("route=\"/api/v1/health\",le=\"0.025\"} 2\n"), "{text}");
        assert!(text.contains("route=\"/api/v1/sessions/{id}/run\",le=\"600\"} 0\n"), "{text}");
        assert!(text.contains("route=\"/api/v1/sessions/{id}/run\",le=\"+Inf\"} 1\n"), "{text}");
        assert!(text.contains("nctwin_sessions 0\n"), "{text}");
        assert!(text.contains("# TYPE nctwin_ipo_wake_lateness_seconds histogram\n"), "{text}");
        assert!(text.contains("nctwin_ipo_cycles_dropped_total "), "{text}");
        assert!(text.contains("nctwin_connections 0\n"), "{text}");
        assert!(text.contains("nctwin_stream_closes_total{reason=\"pongs_missed\"} 0\n"), "{text}");
    }

    #[test]
    fn connections_and_stream_closes_are_counted() {
        let metrics = Metrics::default();
        let state = AppState::new("unused", "unused");
        metrics.connection(true);
        metrics.connection(true);
        metrics.connection(false);
        metrics.connection_refused();
        metrics.stream_closed(StreamClose::TooBig);
        let text = metrics.render(&state);
        assert!(text.contains("nctwin_connections 1\n"), "{text}");
        assert!(text.contains("nctwin_connections_refused_total 1\n"), "{text}");
        assert!(text.contains("nctwin_stream_closes_total{reason=\"message_too_big\"} 1\n"), "{text}");
        assert!(text.contains("nctwin_stream_closes_total{reason=\"write_stalled\"} 0\n"), "{text}");
    }

    #[test]
    fn the_wake_histogram_is_cumulative() {
        let mut counts = WakeCounts { buckets: vec![0; LATENESS_BUCKETS.len() + 1], ..WakeCounts::default() };
        counts.buckets[0] = 3; // ≤ 1 ms
        counts.buckets[7] = 1; // ≤ 250 ms
        counts.buckets[10] = 2; // +Inf
        counts.sum = Duration::from_millis(2_500);
        counts.dropped_cycles = 40;
        let mut out = String::new();
        wake_histogram(&mut out, &counts);
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_bucket{le=\"0.001\"} 3\n"), "{out}");
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_bucket{le=\"0.1\"} 3\n"), "{out}");
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_bucket{le=\"0.25\"} 4\n"), "{out}");
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_bucket{le=\"1\"} 4\n"), "{out}");
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_bucket{le=\"+Inf\"} 6\n"), "{out}");
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_count 6\n"), "{out}");
        assert!(out.contains("nctwin_ipo_wake_lateness_seconds_sum 2.5\n"), "{out}");
        assert!(out.contains("nctwin_ipo_cycles_dropped_total 40\n"), "{out}");
    }

    #[test]
    fn lease_metrics_name_the_node_and_count_renewals_and_takeovers() {
        let metrics = Metrics::default();
        metrics.lease_renewal(Some(1500), Duration::from_micros(800));
        metrics.lease_renewal(Some(1499), Duration::from_millis(30));
        metrics.lease_renewal(None, Duration::from_secs(10));
        metrics.lease_takeover(Duration::from_millis(250));
        let leases = metrics.leases.lock().expect("lock").clone();
        let mut out = String::new();
        lease_metrics(&mut out, "n1", 1499, &leases);
        assert!(out.contains("nctwin_node_sessions_held{node=\"n1\"} 1499\n"), "{out}");
        assert!(out.contains("nctwin_node_sessions_leased{node=\"n1\"} 1499\n"), "{out}");
        assert!(out.contains("nctwin_node_takeovers_total{node=\"n1\"} 1\n"), "{out}");
        assert!(out.contains("nctwin_node_lease_renewal_failures_total{node=\"n1\"} 1\n"), "{out}");
        // 0.8 ms in the first bucket, 30 ms in the 50 ms one, 10 s only in +Inf.
        assert!(out.contains("nctwin_node_lease_renewal_seconds_bucket{node=\"n1\",le=\"0.001\"} 1\n"), "{out}");
        assert!(out.contains("nctwin_node_lease_renewal_seconds_bucket{node=\"n1\",le=\"0.05\"} 2\n"), "{out}");
        assert!(out.contains("nctwin_node_lease_renewal_seconds_bucket{node=\"n1\",le=\"5\"} 2\n"), "{out}");
        assert!(out.contains("nctwin_node_lease_renewal_seconds_bucket{node=\"n1\",le=\"+Inf\"} 3\n"), "{out}");
        assert!(out.contains("nctwin_node_lease_renewal_seconds_count{node=\"n1\"} 3\n"), "{out}");
    }

    #[test]
    fn label_values_are_escaped() {
        assert_eq!(escape("a\"b\\c\nd"), "a\\\"b\\\\c\\nd");
    }
}
