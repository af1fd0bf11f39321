//! `nctwin-loadgen`: the load client of `scripts/load.sh`.
//!
//! Creates N sessions on a running NCTwin server, attaches one WebSocket viewer to each, starts
//! a long program in real-time pace on every one, and measures over a window:
//! - IPO lag as the client sees it: per session, how far simulated time fell behind wall time
//!   since the first frame of the window (`(t − t₀) − (time − time₀)` over the state frames).
//!   This includes how late each frame arrived (server scheduling, the socket, this client's
//!   own scheduling), so on a busy machine it mostly measures delivery jitter;
//! - drift: the same offset, but per second of the window only its smallest value (the frame
//!   that arrived most promptly), compared with the first second's. Delivery delays do not add
//!   to it; a session whose simulation really falls behind wall time shows a growing drift.
//!   A session counts as behind when its drift exceeds `--behind`;
//! - the server's own IPO lag (`--server-pid` not needed): how late the real-time wake-ups of
//!   all sessions came, from the `nctwin_ipo_wake_lateness_seconds` histogram of `/metrics`,
//!   and the cycles dropped by the catch-up cap;
//! - state frames received per session and second (20 Hz expected at the default period);
//! - command-to-frame latency: on `--probes` sessions, NC stop and NC start alternate; the time
//!   from sending the REST command to the first stream frame showing its status;
//! - CPU of the server process (`--server-pid`, from /proc; user and system, per session and
//!   second, and the time its threads waited for a CPU on the run queue) and of this client.
//!
//! Prints a readable summary and, with `--json`, one JSON line for scripts.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use clap::Parser;
use futures_util::{StreamExt, stream};
use serde::Deserialize;
use serde_json::json;
use tokio::sync::oneshot;

/// Load client for NCTwin: real-time sessions with a WebSocket viewer each.
#[derive(Debug, Parser)]
struct Args {
    /// Server base URL.
    #[arg(long, default_value = "http://127.0.0.1:8080")]
    url: String,
    /// Number of sessions (one viewer each).
    #[arg(long)]
    sessions: usize,
    /// Part program every session runs in real time (must outlast warm-up + window).
    #[arg(long)]
    program: PathBuf,
    #[arg(long, default_value = "mill-3axis")]
    machine: String,
    /// Seconds after the last program started before the window opens.
    #[arg(long, default_value_t = 3.0)]
    warmup: f64,
    /// Measurement window, seconds.
    #[arg(long, default_value_t = 30.0)]
    duration: f64,
    /// Stream period of the viewers in ms (50 = 20 Hz).
    #[arg(long, default_value_t = 50)]
    period_ms: u64,
    /// Sessions whose viewers measure command-to-frame latency with NC stop/start (they are
    /// left out of the lag figures). Default: min(sessions, 50).
    #[arg(long)]
    probes: Option<usize>,
    /// Pause between two probe commands of one session, ms.
    #[arg(long, default_value_t = 500)]
    probe_interval_ms: u64,
    /// PID of the server, for its CPU use and memory.
    #[arg(long)]
    server_pid: Option<u32>,
    /// Concurrent requests while setting up.
    #[arg(long, default_value_t = 32)]
    concurrency: usize,
    /// A session counts as behind when its drift exceeds this, seconds.
    #[arg(long, default_value_t = 0.25)]
    behind: f64,
    /// Print one JSON line with every figure at the end.
    #[arg(long)]
    json: bool,
}

/// The fields of a stream message this client reads.
#[derive(Debug, Deserialize)]
struct Frame {
    #[serde(rename = "type")]
    kind: String,
    status: Option<String>,
    time: Option<f64>,
}

/// What one viewer has seen.
#[derive(Debug, Default)]
struct View {
    /// (wall, simulated) at the first running state frame of the window.
    anchor: Option<(Instant, f64)>,
    frames_in_window: u64,
    max_lag: f64,
    last_lag: f64,
    /// Per whole second of the window: the smallest `(t − window start) − time` of its frames.
    min_offset: Vec<f64>,
    /// Status awaited by a probe: (status, when the command was sent, reply).
    pending: Option<(&'static str, Instant, oneshot::Sender<f64>)>,
}

struct Session {
    id: String,
    view: Mutex<View>,
}

struct Shared {
    window_open: AtomicBool,
    window_start: std::sync::OnceLock<Instant>,
    closed: AtomicBool,
    ws_errors: AtomicU64,
    frames_total: AtomicU64,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

/// CPU use of a process at one moment.
#[derive(Debug, Clone, Copy)]
struct Usage {
    /// utime + stime, seconds.
    cpu: f64,
    /// stime, seconds.
    sys: f64,
    rss_kib: u64,
    peak_rss_kib: u64,
    /// Time its threads waited on a run queue for a CPU, seconds (0 where schedstat is missing).
    wait: f64,
}

/// utime and stime of a process in seconds, its VmRSS / VmHWM in KiB and its threads' run
/// queue wait.
fn proc_usage(pid: &str) -> Option<Usage> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // After "pid (comm) ", field 3 (state) is index 0: utime is field 14, stime 15.
    let user: f64 = fields.get(11)?.parse::<f64>().ok()?;
    let sys: f64 = fields.get(12)?.parse::<f64>().ok()?;
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let kib = |key: &str| -> u64 {
        status
            .lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .unwrap_or(0)
    };
    // schedstat: time on a CPU, time waiting on a run queue (ns), timeslices; per thread.
    let mut wait_ns = 0u64;
    if let Ok(tasks) = std::fs::read_dir(format!("/proc/{pid}/task")) {
        for task in tasks.flatten() {
            if let Ok(text) = std::fs::read_to_string(task.path().join("schedstat")) {
                wait_ns += text.split_whitespace().nth(1).and_then(|v| v.parse::<u64>().ok()).unwrap_or(0);
            }
        }
    }
    // USER_HZ is 100 on Linux.
    Some(Usage {
        cpu: (user + sys) / 100.0,
        sys: sys / 100.0,
        rss_kib: kib("VmRSS:"),
        peak_rss_kib: kib("VmHWM:"),
        wait: wait_ns as f64 * 1e-9,
    })
}

/// The wake-up lateness histogram and dropped cycles of the server's `/metrics`: (upper bound
/// in seconds, cumulative count) per bucket, +Inf as infinity, and the dropped cycles.
async fn wake_metrics(client: &reqwest::Client, base: &str) -> Option<(Vec<(f64, u64)>, u64)> {
    let text = client.get(format!("{base}/metrics")).send().await.ok()?.text().await.ok()?;
    let mut buckets = Vec::new();
    let mut dropped = 0;
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("nctwin_ipo_wake_lateness_seconds_bucket{le=\"") {
            let (bound, count) = rest.split_once("\"} ")?;
            let bound = if bound == "+Inf" { f64::INFINITY } else { bound.parse().ok()? };
            buckets.push((bound, count.trim().parse().ok()?));
        } else if let Some(rest) = line.strip_prefix("nctwin_ipo_cycles_dropped_total ") {
            dropped = rest.trim().parse().ok()?;
        }
    }
    (!buckets.is_empty()).then_some((buckets, dropped))
}

/// Figures of the wake-ups between two scrapes: count, the bucket bound at p50 and p99, how
/// many came later than `behind` seconds (by bucket bounds), dropped cycles.
fn wake_window(before: &(Vec<(f64, u64)>, u64), after: &(Vec<(f64, u64)>, u64), behind: f64) -> serde_json::Value {
    let delta: Vec<(f64, u64)> =
        after.0.iter().zip(&before.0).map(|((bound, a), (_, b))| (*bound, a.saturating_sub(*b))).collect();
    let total = delta.last().map_or(0, |d| d.1);
    let at = |p: f64| -> Option<f64> {
        let want = (total as f64 * p).ceil() as u64;
        delta.iter().find(|d| d.1 >= want.max(1)).map(|d| d.0).filter(|b| b.is_finite())
    };
    let within = delta.iter().rev().find(|d| d.0 <= behind).map_or(0, |d| d.1);
    json!({
        "wakes": total,
        "p50_le_s": at(0.5),
        "p99_le_s": at(0.99),
        "later_than_behind": total - within,
        "dropped_cycles": after.1.saturating_sub(before.1),
    })
}

#[tokio::main]
async fn main() -> std::process::ExitCode {
    let args = Args::parse();
    match run(args).await {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("nctwin-loadgen: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

async fn run(args: Args) -> Result<(), String> {
    let program = std::fs::read_to_string(&args.program).map_err(|e| format!("{}: {e}", args.program.display()))?;
    let (api, ws_base) = nctwin_loadgen::endpoints(&args.url);
    let client = nctwin_loadgen::http_client(args.concurrency)?;
    let shared = Arc::new(Shared {
        window_open: AtomicBool::new(false),
        window_start: std::sync::OnceLock::new(),
        closed: AtomicBool::new(false),
        ws_errors: AtomicU64::new(0),
        frames_total: AtomicU64::new(0),
    });

    // 1. Sessions.
    let t = Instant::now();
    let created: Vec<Result<String, String>> = stream::iter(0..args.sessions)
        .map(|_| {
            let (client, api, machine) = (client.clone(), api.clone(), args.machine.clone());
            async move {
                let r = client
                    .post(format!("{api}/sessions"))
                    .json(&json!({ "machine": machine }))
                    .send()
                    .await
                    .map_err(|e| e.to_string())?;
                let status = r.status();
                let body: serde_json::Value = r.json().await.map_err(|e| e.to_string())?;
                match body["id"].as_str() {
                    Some(id) if status.is_success() => Ok(id.to_string()),
                    _ => Err(format!("{status}: {body}")),
                }
            }
        })
        .buffer_unordered(args.concurrency)
        .collect()
        .await;
    let create_s = t.elapsed().as_secs_f64();
    let mut sessions = Vec::new();
    for r in created {
        match r {
            Ok(id) => sessions.push(Arc::new(Session { id, view: Mutex::new(View::default()) })),
            Err(e) => return Err(format!("creating a session failed ({} created): {e}", sessions.len())),
        }
    }
    eprintln!("{} sessions created in {create_s:.1} s", sessions.len());

    // 2. Viewers.
    let t = Instant::now();
    let connected: Vec<Result<(), String>> = stream::iter(sessions.iter().cloned())
        .map(|s| {
            let url = format!("{ws_base}/sessions/{}/stream?period_ms={}", s.id, args.period_ms);
            let shared = shared.clone();
            async move {
                let (ws, _) = tokio_tungstenite::connect_async(&url).await.map_err(|e| format!("{url}: {e}"))?;
                tokio::spawn(view(ws, s, shared));
                Ok(())
            }
        })
        .buffer_unordered(args.concurrency)
        .collect()
        .await;
    if let Some(Err(e)) = connected.into_iter().find(Result::is_err) {
        return Err(format!("a viewer could not connect: {e}"));
    }
    let connect_s = t.elapsed().as_secs_f64();
    eprintln!("{} viewers connected in {connect_s:.1} s", sessions.len());

    // 3. Programs, real-time pace.
    let t = Instant::now();
    let body = Arc::new(json!({ "program": program, "pace": "realtime" }));
    let started: Vec<Result<(), String>> = stream::iter(sessions.iter().cloned())
        .map(|s| {
            let (client, api, body) = (client.clone(), api.clone(), body.clone());
            async move {
                let r = client
                    .post(format!("{api}/sessions/{}/run", s.id))
                    .json(&*body)
                    .send()
                    .await
                    .map_err(|e| e.to_string())?;
                if r.status().is_success() {
                    Ok(())
                } else {
                    let status = r.status();
                    Err(format!("run {}: {status} {}", s.id, r.text().await.unwrap_or_default()))
                }
            }
        })
        .buffer_unordered(args.concurrency)
        .collect()
        .await;
    if let Some(Err(e)) = started.into_iter().find(Result::is_err) {
        return Err(e);
    }
    let start_s = t.elapsed().as_secs_f64();
    eprintln!("programs started in {start_s:.1} s; warm-up {} s, window {} s", args.warmup, args.duration);
    tokio::time::sleep(Duration::from_secs_f64(args.warmup)).await;

    // 4. The window.
    let pid = args.server_pid.map(|p| p.to_string());
    let server_before = pid.as_deref().and_then(proc_usage);
    let client_before = proc_usage("self");
    let frames_before = shared.frames_total.load(Ordering::Relaxed);
    let base = args.url.trim_end_matches('/').to_string();
    let wakes_before = wake_metrics(&client, &base).await;
    let window_start = Instant::now();
    let _ = shared.window_start.set(window_start);
    shared.window_open.store(true, Ordering::Relaxed);
    let end = window_start + Duration::from_secs_f64(args.duration);
    let n_probes = args.probes.unwrap_or(50).min(sessions.len());
    let interval = Duration::from_millis(args.probe_interval_ms);
    let probes: Vec<_> = sessions[..n_probes]
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let (client, api, s) = (client.clone(), api.clone(), s.clone());
            // Staggered, so probe commands do not arrive in bursts.
            let offset = interval.mul_f64(k as f64 / n_probes.max(1) as f64);
            tokio::spawn(probe(client, api, s, end, interval, offset))
        })
        .collect();
    let mut latencies = Vec::new();
    let mut timeouts = 0u64;
    for p in probes {
        if let Ok((l, t)) = p.await {
            latencies.extend(l);
            timeouts += t;
        }
    }
    tokio::time::sleep_until(end.into()).await;
    let window_s = window_start.elapsed().as_secs_f64();
    shared.window_open.store(false, Ordering::Relaxed);
    let server_after = pid.as_deref().and_then(proc_usage);
    let client_after = proc_usage("self");
    let frames_window = shared.frames_total.load(Ordering::Relaxed) - frames_before;
    let wakes_after = wake_metrics(&client, &base).await;
    let server_wakes = match (&wakes_before, &wakes_after) {
        (Some(b), Some(a)) => wake_window(b, a, args.behind),
        _ => serde_json::Value::Null,
    };

    // 5. Figures.
    let mut lags = Vec::new();
    let mut last_lags = Vec::new();
    let mut frame_rates = Vec::new();
    let mut drifts = Vec::new();
    let mut final_drifts = Vec::new();
    let mut no_anchor = 0;
    for s in &sessions[n_probes..] {
        let v = s.view.lock().expect("view lock");
        if v.anchor.is_none() {
            no_anchor += 1;
        }
        lags.push(v.max_lag);
        last_lags.push(v.last_lag);
        // Only whole seconds with frames count; the first is the reference.
        let seconds: Vec<f64> = v.min_offset.iter().copied().filter(|m| m.is_finite()).collect();
        if let Some(first) = seconds.first() {
            drifts.push(seconds.iter().map(|m| m - first).fold(0.0, f64::max));
            final_drifts.push(seconds.last().map_or(0.0, |m| m - first));
        }
        frame_rates.push(v.frames_in_window as f64 / window_s);
    }
    for s in &sessions[..n_probes] {
        frame_rates.push(s.view.lock().expect("view lock").frames_in_window as f64 / window_s);
    }
    let sort = |v: &mut Vec<f64>| v.sort_by(f64::total_cmp);
    sort(&mut lags);
    sort(&mut last_lags);
    sort(&mut frame_rates);
    sort(&mut latencies);
    sort(&mut drifts);
    sort(&mut final_drifts);
    let behind = drifts.iter().filter(|&&d| d > args.behind).count();
    let lag_over = lags.iter().filter(|&&l| l > args.behind).count();
    // (CPU %, RSS KiB, peak RSS KiB, system CPU %, run queue wait %), all % of one core.
    let cpu = |before: Option<Usage>, after: Option<Usage>| match (before, after) {
        (Some(b), Some(a)) => Some((
            (a.cpu - b.cpu) / window_s * 100.0,
            a.rss_kib,
            a.peak_rss_kib,
            (a.sys - b.sys) / window_s * 100.0,
            (a.wait - b.wait) / window_s * 100.0,
        )),
        _ => None,
    };
    let server = cpu(server_before, server_after);
    let client_cpu = cpu(client_before, client_after);
    let ms = |v: f64| (v * 1e4).round() / 10.0;
    let summary = json!({
        "sessions": sessions.len(),
        "probes": n_probes,
        "period_ms": args.period_ms,
        "setup_s": { "create": create_s, "connect": connect_s, "start": start_s },
        "window_s": window_s,
        "server_cpu_percent": server.map(|s| s.0),
        "server_sys_cpu_percent": server.map(|s| s.3),
        "server_cpu_ms_per_session_s": server.map(|s| s.0 * 10.0 / sessions.len().max(1) as f64),
        "server_runqueue_wait_percent": server.map(|s| s.4),
        "load_avg_1m": std::fs::read_to_string("/proc/loadavg").ok().and_then(|l| l.split_whitespace().next().and_then(|v| v.parse::<f64>().ok())),
        "server_rss_mib": server.map(|s| s.1 as f64 / 1024.0),
        "server_peak_rss_mib": server.map(|s| s.2 as f64 / 1024.0),
        "client_cpu_percent": client_cpu.map(|s| s.0),
        "frames_per_s": frames_window as f64 / window_s,
        "frames_per_session_per_s": { "min": percentile(&frame_rates, 0.0), "p50": percentile(&frame_rates, 0.5) },
        "lag_ms": {
            "sessions": lags.len(),
            "max_p50": ms(percentile(&lags, 0.5)),
            "max_p99": ms(percentile(&lags, 0.99)),
            "max_max": ms(percentile(&lags, 1.0)),
            "final_p50": ms(percentile(&last_lags, 0.5)),
            "final_max": ms(percentile(&last_lags, 1.0)),
            "over_threshold": lag_over,
        },
        "drift_ms": {
            "max_p50": ms(percentile(&drifts, 0.5)),
            "max_p99": ms(percentile(&drifts, 0.99)),
            "max_max": ms(percentile(&drifts, 1.0)),
            "final_p50": ms(percentile(&final_drifts, 0.5)),
            "final_max": ms(percentile(&final_drifts, 1.0)),
        },
        "server_wakes": server_wakes,
        "behind": behind,
        "behind_threshold_ms": ms(args.behind),
        "no_running_frame": no_anchor,
        "latency_ms": {
            "samples": latencies.len(),
            "timeouts": timeouts,
            "p50": ms(percentile(&latencies, 0.5)),
            "p90": ms(percentile(&latencies, 0.9)),
            "p99": ms(percentile(&latencies, 0.99)),
            "max": ms(percentile(&latencies, 1.0)),
        },
        "ws_errors": shared.ws_errors.load(Ordering::Relaxed),
    });
    shared.closed.store(true, Ordering::Relaxed);
    eprintln!("{}", serde_json::to_string_pretty(&summary).unwrap_or_default());
    if args.json {
        println!("{summary}");
    }
    Ok(())
}

/// Reads one session's stream until it closes, updating its [`View`].
async fn view<S>(mut ws: S, session: Arc<Session>, shared: Arc<Shared>)
where
    S: futures_util::Stream<
            Item = Result<tokio_tungstenite::tungstenite::Message, tokio_tungstenite::tungstenite::Error>,
        > + Unpin,
{
    use tokio_tungstenite::tungstenite::Message;
    while let Some(message) = ws.next().await {
        let now = Instant::now();
        let text = match message {
            Ok(Message::Text(text)) => text,
            Ok(Message::Close(_)) => break,
            Ok(_) => continue,
            Err(_) => {
                if !shared.closed.load(Ordering::Relaxed) {
                    shared.ws_errors.fetch_add(1, Ordering::Relaxed);
                }
                break;
            }
        };
        let Ok(frame) = serde_json::from_str::<Frame>(&text) else { continue };
        if frame.kind != "state" {
            continue;
        }
        shared.frames_total.fetch_add(1, Ordering::Relaxed);
        let mut v = session.view.lock().expect("view lock");
        let status = frame.status.as_deref().unwrap_or("");
        if let Some((want, sent, _)) = &v.pending
            && *want == status
        {
            let latency = now.duration_since(*sent).as_secs_f64();
            if let Some((_, _, reply)) = v.pending.take() {
                let _ = reply.send(latency);
            }
        }
        if !shared.window_open.load(Ordering::Relaxed) {
            continue;
        }
        v.frames_in_window += 1;
        let Some(time) = frame.time else { continue };
        if status == "running"
            && let Some(&start) = shared.window_start.get()
        {
            let since = now.duration_since(start).as_secs_f64();
            let second = since as usize;
            if v.min_offset.len() <= second {
                v.min_offset.resize(second + 1, f64::INFINITY);
            }
            v.min_offset[second] = v.min_offset[second].min(since - time);
        }
        match v.anchor {
            None if status == "running" => v.anchor = Some((now, time)),
            None => {}
            Some((t0, time0)) => {
                let lag = now.duration_since(t0).as_secs_f64() - (time - time0);
                v.last_lag = lag;
                v.max_lag = v.max_lag.max(lag);
            }
        }
    }
}

/// Alternates NC stop and NC start on one session until `end`, measuring each command's
/// latency to the first frame that shows it. Returns (latencies, timeouts).
async fn probe(
    client: reqwest::Client,
    api: String,
    session: Arc<Session>,
    end: Instant,
    interval: Duration,
    offset: Duration,
) -> (Vec<f64>, u64) {
    let (mut latencies, mut timeouts) = (Vec::new(), 0);
    tokio::time::sleep(offset).await;
    let commands = [("stop", "stopped"), ("start", "running")];
    let mut k = 0;
    while Instant::now() + Duration::from_secs(2) < end {
        let (command, status) = commands[k % 2];
        k += 1;
        let (tx, rx) = oneshot::channel();
        let sent = Instant::now();
        session.view.lock().expect("view lock").pending = Some((status, sent, tx));
        let ok = client
            .post(format!("{api}/sessions/{}/{command}", session.id))
            .send()
            .await
            .is_ok_and(|r| r.status().is_success());
        if ok {
            match tokio::time::timeout(Duration::from_secs(5), rx).await {
                Ok(Ok(latency)) => latencies.push(latency),
                _ => timeouts += 1,
            }
        } else {
            timeouts += 1;
        }
        session.view.lock().expect("view lock").pending = None;
        tokio::time::sleep(interval).await;
    }
    (latencies, timeouts)
}
