//! [`Limits`]: every server-side limit in one place, with its default and why, and the
//! per-session command [`RateLimiter`].
//!
//! Each refusal is a 4xx with a message naming the limit: `413` for sizes, `429` (with
//! `Retry-After` where waiting helps) for counts and rates.

use std::time::Duration;

use tokio::time::Instant;

use crate::session::ActorConfig;

/// Server-side limits and pacing; [`Limits::default`] holds the documented values, `nctwin`
/// flags override some, tests shrink them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Wake period of real-time pacing (the default stream period): 50 ms, 20 Hz.
    pub period: Duration,
    /// Simulated time one fast-paced command may run before the channel is stopped: 3600 s.
    pub fast_sim_time: f64,
    /// Wall time after which a `wait: true` request is answered with the current state: 600 s.
    pub wait_wall_time: Duration,
    /// IPO cycles per blocking chunk in fast pace: 20,000.
    pub fast_chunk: u64,
    /// Largest request body of every endpoint except program uploads: 1 MiB (`413`).
    pub body_bytes: usize,
    /// Largest stored program (`PUT .../programs/{name}`): 16 MiB of text (`413`). Its request
    /// body may be [`Limits::program_body_bytes`] for the JSON around it. Programs larger than
    /// [`Limits::body_bytes`] are stored first and then called by name from a short `run`.
    pub program_bytes: usize,
    /// Total text of one session's stored programs: 64 MiB (`413`).
    pub session_program_bytes: usize,
    /// Live sessions on the server: 1000 (`429`). An idle session costs a sleeping task and
    /// some kilobytes, so this guards memory, not CPU.
    pub sessions: usize,
    /// Live sessions created from one client IP address: 100 (`429`), enough for a class behind
    /// one NAT address with a few sessions each.
    pub sessions_per_ip: usize,
    /// WebSocket stream clients of one session: 64 (`429`): a class watching one machine.
    pub stream_clients: usize,
    /// Sustained commands per second per session: 50 (`429` with `Retry-After`). Commands are
    /// every request that changes a session (run, start, stop, reset, MDA, JOG, mode, machine
    /// data, program uploads and deletions); reads are not counted.
    pub commands_per_second: f64,
    /// Commands a session may take in a burst above the sustained rate: 100.
    pub command_burst: f64,
    /// Longest a graceful shutdown waits for open connections after every session is saved
    /// and closed: 5 s. The process then exits anyway.
    pub shutdown_grace: Duration,
    /// A session no client has used for this long is deleted, from storage too: 24 h. Zero:
    /// sessions never expire. Use is any request to the session that passes the access check
    /// (reads too), an open stream or a running program; a session the owner marked
    /// persistent never expires. The idle time counts across restarts (the last activity is
    /// saved, see `state::expiry`).
    pub session_idle: Duration,
    /// Bytes of stored programs on the whole server, all sessions together: 2 GiB (`413`
    /// naming the budget). With [`Limits::session_program_bytes`] per session and
    /// [`Limits::sessions`] this caps the memory programs hold.
    pub program_budget_bytes: usize,
    /// Open TCP connections from one client IP address: 256. A WebSocket stream is a connection
    /// of its own (HTTP/1.1 upgrade) and counts until it closes. The connection over the cap is
    /// answered `429` and closed. Enough for a class behind one NAT address (a browser holds
    /// about six connections and one stream per open session).
    pub connections_per_ip: usize,
    /// Time a connection has to deliver a complete request head: 15 s, counted from its opening
    /// and, on a kept-alive connection, from the end of the previous response (hyper's HTTP/1
    /// header timer), so it is also the keep-alive idle time. The connection is closed.
    pub header_read_timeout: Duration,
    /// Period of the server's pings on a WebSocket stream: 15 s.
    pub stream_ping_interval: Duration,
    /// Pings a stream client may leave unanswered before the server closes the stream (1008):
    /// 2, so a silent client is closed 30 to 45 s after its last pong. A write to the client
    /// that cannot complete for `stream_ping_interval × stream_missed_pongs` closes it as well.
    pub stream_missed_pongs: u32,
    /// Largest WebSocket frame and message a stream client may send: 4 KiB (its messages are
    /// JSON of a few hundred bytes). A larger frame is refused when its header arrives (1009).
    pub stream_message_bytes: usize,
    /// Most bytes queued for one stream client (replies, states, events, pongs) that the socket
    /// does not take: 1 MiB. A client that fills it is disconnected.
    pub stream_write_buffer_bytes: usize,
    /// Wall time one fast-paced command may run before the channel is stopped: 10 s (the
    /// reply says `nctwin-limit: fast-wall-time`). Keeps a program that the engine computes
    /// slowly from holding a worker thread for its whole simulated hour.
    pub fast_wall_time: Duration,
    /// Program text per second a session may have syntax-checked (`POST .../check`): 4 MiB/s
    /// (`429` with `Retry-After`). A check's cost grows with its text, so the budget is in
    /// bytes: an HMI checking as the operator types stays far below it.
    pub check_bytes_per_second: usize,
    /// Program text a session may have checked in a burst above the sustained rate: 8 MiB.
    pub check_burst_bytes: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            period: Duration::from_millis(50),
            fast_sim_time: 3600.0,
            wait_wall_time: Duration::from_secs(600),
            fast_chunk: 20_000,
            body_bytes: 1 << 20,
            program_bytes: 16 << 20,
            session_program_bytes: 64 << 20,
            sessions: 1000,
            sessions_per_ip: 100,
            stream_clients: 64,
            commands_per_second: 50.0,
            command_burst: 100.0,
            shutdown_grace: Duration::from_secs(5),
            session_idle: Duration::from_secs(24 * 3600),
            program_budget_bytes: 2 << 30,
            connections_per_ip: 256,
            header_read_timeout: Duration::from_secs(15),
            stream_ping_interval: Duration::from_secs(15),
            stream_missed_pongs: 2,
            stream_message_bytes: 4 << 10,
            stream_write_buffer_bytes: 1 << 20,
            fast_wall_time: Duration::from_secs(10),
            check_bytes_per_second: 4 << 20,
            check_burst_bytes: 8 << 20,
        }
    }
}

impl Limits {
    pub(crate) fn actor_config(&self) -> ActorConfig {
        ActorConfig {
            period: self.period,
            fast_sim_time: self.fast_sim_time,
            wait_wall_time: self.wait_wall_time,
            fast_chunk: self.fast_chunk,
            fast_wall_time: self.fast_wall_time,
        }
    }

    /// Largest request body of a program upload: the program limit plus a quarter for JSON
    /// escapes (`\n` is two bytes) plus 64 KiB.
    pub fn program_body_bytes(&self) -> usize {
        self.program_bytes.saturating_add(self.program_bytes / 4).saturating_add(64 << 10)
    }
}

/// The limits `nctwin` takes as flags (the others keep their defaults).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct LimitFlags {
    /// Live sessions on the server [default: 1000].
    #[arg(long, value_name = "N")]
    pub max_sessions: Option<usize>,
    /// Live sessions created from one client IP address [default: 100].
    #[arg(long, value_name = "N")]
    pub max_sessions_per_ip: Option<usize>,
    /// WebSocket stream clients per session [default: 64].
    #[arg(long, value_name = "N")]
    pub max_stream_clients: Option<usize>,
    /// Sustained commands per second per session [default: 50].
    #[arg(long, value_name = "RATE")]
    pub commands_per_second: Option<f64>,
    /// Commands per session in a burst above the sustained rate [default: 100].
    #[arg(long, value_name = "N")]
    pub command_burst: Option<f64>,
    /// Largest stored program in bytes [default: 16777216 = 16 MiB].
    #[arg(long, value_name = "BYTES")]
    pub max_program_bytes: Option<usize>,
    /// Seconds a session may stay unused before it is deleted (also from storage); 0: never.
    /// Sessions marked persistent never expire [default: 86400 = 24 h].
    #[arg(long, value_name = "SECONDS")]
    pub session_idle_timeout: Option<u64>,
    /// Bytes of stored programs on the whole server, all sessions together
    /// [default: 2147483648 = 2 GiB].
    #[arg(long, value_name = "BYTES")]
    pub program_budget_bytes: Option<usize>,
    /// Open connections (WebSocket streams included) from one client IP address [default: 256].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_connections_per_ip: Option<u64>,
    /// Seconds a connection has to send a complete request head, after opening or after its
    /// previous response (the keep-alive idle time) [default: 15].
    #[arg(long, value_name = "SECONDS", value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub header_read_timeout: Option<u64>,
    /// Seconds between two server pings on a WebSocket stream; a stream that leaves two pings
    /// unanswered is closed [default: 15].
    #[arg(long, value_name = "SECONDS", value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub stream_ping_interval: Option<u64>,
    /// Program text per second a session may have syntax-checked [default: 4194304 = 4 MiB].
    #[arg(long, value_name = "BYTES")]
    pub check_bytes_per_second: Option<usize>,
    /// Program text a session may have checked in a burst [default: 8388608 = 8 MiB].
    #[arg(long, value_name = "BYTES")]
    pub check_burst_bytes: Option<usize>,
}

impl LimitFlags {
    /// `limits` with the given flags applied.
    pub fn apply(&self, limits: Limits) -> Limits {
        Limits {
            sessions: self.max_sessions.unwrap_or(limits.sessions),
            sessions_per_ip: self.max_sessions_per_ip.unwrap_or(limits.sessions_per_ip),
            stream_clients: self.max_stream_clients.unwrap_or(limits.stream_clients),
            commands_per_second: self.commands_per_second.unwrap_or(limits.commands_per_second),
            command_burst: self.command_burst.unwrap_or(limits.command_burst),
            program_bytes: self.max_program_bytes.unwrap_or(limits.program_bytes),
            session_idle: self.session_idle_timeout.map_or(limits.session_idle, Duration::from_secs),
            program_budget_bytes: self.program_budget_bytes.unwrap_or(limits.program_budget_bytes),
            connections_per_ip: self
                .max_connections_per_ip
                .map_or(limits.connections_per_ip, |n| usize::try_from(n).unwrap_or(usize::MAX)),
            header_read_timeout: self.header_read_timeout.map_or(limits.header_read_timeout, Duration::from_secs),
            stream_ping_interval: self.stream_ping_interval.map_or(limits.stream_ping_interval, Duration::from_secs),
            check_bytes_per_second: self.check_bytes_per_second.unwrap_or(limits.check_bytes_per_second),
            check_burst_bytes: self.check_burst_bytes.unwrap_or(limits.check_burst_bytes),
            ..limits
        }
    }
}

/// A token bucket: `rate` tokens per second up to `burst`; each command takes one.
///
/// Pure arithmetic on instants handed in by the caller, so it is tested without a clock.
#[derive(Debug, Clone)]
pub struct RateLimiter {
    rate: f64,
    burst: f64,
    tokens: f64,
    last: Instant,
}

impl RateLimiter {
    /// A full bucket at `now`.
    pub fn new(rate: f64, burst: f64, now: Instant) -> RateLimiter {
        let burst = burst.max(1.0);
        RateLimiter { rate: rate.max(f64::MIN_POSITIVE), burst, tokens: burst, last: now }
    }

    /// Takes one token; `Err(wait)` when none is left, with the time until one is.
    pub fn take(&mut self, now: Instant) -> Result<(), Duration> {
        self.take_n(1.0, now)
    }

    /// Takes `cost` tokens (at most the burst, so any single request can pass when the bucket
    /// is full); `Err(wait)` when fewer are left, with the time until there are. A refusal
    /// takes nothing.
    pub fn take_n(&mut self, cost: f64, now: Instant) -> Result<(), Duration> {
        let cost = cost.clamp(0.0, self.burst);
        let elapsed = now.saturating_duration_since(self.last).as_secs_f64();
        self.last = now;
        self.tokens = (self.tokens + elapsed * self.rate).min(self.burst);
        if self.tokens >= cost {
            self.tokens -= cost;
            Ok(())
        } else {
            Err(Duration::from_secs_f64(((cost - self.tokens) / self.rate).min(3600.0)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_burst_is_allowed_then_the_rate_holds() {
        let t0 = Instant::now();
        let mut bucket = RateLimiter::new(10.0, 3.0, t0);
        assert!((0..3).all(|_| bucket.take(t0).is_ok()));
        let wait = bucket.take(t0).expect_err("the burst is spent");
        assert!((wait.as_secs_f64() - 0.1).abs() < 1e-9, "{wait:?}");
        assert!(bucket.take(t0 + Duration::from_millis(100)).is_ok(), "one token after 1/rate");
        assert!(bucket.take(t0 + Duration::from_millis(100)).is_err());
    }

    #[test]
    fn an_idle_bucket_refills_only_up_to_the_burst() {
        let t0 = Instant::now();
        let mut bucket = RateLimiter::new(10.0, 2.0, t0);
        let later = t0 + Duration::from_secs(60);
        assert!(bucket.take(later).is_ok() && bucket.take(later).is_ok());
        assert!(bucket.take(later).is_err());
    }

    #[test]
    fn a_costly_request_takes_its_cost_and_waits_for_it() {
        let t0 = Instant::now();
        let mut bucket = RateLimiter::new(100.0, 300.0, t0);
        assert!(bucket.take_n(250.0, t0).is_ok());
        let wait = bucket.take_n(100.0, t0).expect_err("50 left");
        assert!((wait.as_secs_f64() - 0.5).abs() < 1e-9, "{wait:?}");
        assert!(bucket.take_n(50.0, t0).is_ok(), "the refusal took nothing");
        assert!(bucket.take_n(1e9, t0 + Duration::from_secs(3)).is_ok(), "capped at the burst");
    }

    #[test]
    fn program_uploads_may_be_larger_than_other_bodies() {
        let limits = Limits::default();
        assert!(limits.program_body_bytes() > limits.program_bytes);
        assert!(limits.program_bytes > limits.body_bytes);
    }
}
