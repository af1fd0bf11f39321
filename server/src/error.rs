//! [`ApiError`]: every way a request can fail, each with its HTTP status, as one JSON shape
//! `{"error": "<message>", "line": <1-based line, only when the error belongs to one>}`.

use std::time::Duration;

use axum::Json;
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use nctwin_engine::{CommandError, MdError};

use crate::dto::ErrorBody;
use crate::session::SessionError;

/// `Retry-After` of a request answered at shutdown: a supervisor (systemd, a container
/// runtime) typically has the server back within seconds.
pub const SHUTDOWN_RETRY_AFTER_S: u64 = 5;

/// A failed request. Client mistakes are 4xx with a message that names the problem; nothing
/// a client sends produces a 5xx.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ApiError {
    /// Malformed or invalid input: bad JSON, unknown fields, a program with syntax errors, bad
    /// machine data, an unknown preset or axis, ...
    #[error("{message}")]
    BadRequest { message: String, line: Option<u32> },
    /// A program that cannot be prepared (400): every error found before it ran.
    #[error("{message}")]
    /// At most [`crate::dto::MAX_DIAGNOSTICS`] are listed; `omitted` counts the others.
    Program { message: String, line: u32, errors: Vec<crate::dto::DiagnosticInfo>, omitted: usize },
    /// The channel refuses the command in its current state (busy, alarm, wrong mode).
    #[error("{0}")]
    Conflict(String),
    #[error("session `{0}` does not exist")]
    SessionNotFound(String),
    /// Several nodes on one database: another node holds the session's lease (421).
    #[error(
        "session `{session}` is served by node `{node}` (its lease runs for another {seconds_left:.0} s unless renewed); send the request to that node"
    )]
    WrongNode { session: String, node: String, seconds_left: f64 },
    /// The session was deleted (or the server shut down) while the request waited for it.
    #[error("session `{0}` has ended")]
    SessionEnded(String),
    #[error("machine preset `{0}` does not exist")]
    MachineNotFound(String),
    #[error("no such resource: {0}")]
    NotFound(String),
    #[error("request body is larger than the limit of {0} bytes")]
    PayloadTooLarge(usize),
    /// A program or the programs of a session exceed a size limit.
    #[error("{0}")]
    TooLarge(String),
    /// No token, or a token that belongs to no role of this session (`--auth required`).
    #[error("{0}")]
    Unauthorized(String),
    /// The token's role may not do this (an observer sending a command, ...).
    #[error("{0}")]
    Forbidden(String),
    /// A count or rate limit; `retry_after` when waiting that long helps.
    #[error("{message}")]
    TooManyRequests { message: String, retry_after: Option<Duration> },
    /// The storage failed: the change was not saved (and not acknowledged).
    #[error("{0}")]
    StorageUnavailable(String),
    /// The server is shutting down: the request's session was saved and closed before it
    /// was answered (503 with `Retry-After`: a restarted server has the session back).
    #[error("the server is shutting down; session `{0}` was saved: retry once it is back")]
    ShuttingDown(String),
    /// A request body that is not of the content type the endpoint takes (415).
    #[error("{0}")]
    UnsupportedMediaType(String),
}

impl ApiError {
    /// A 400 without a line.
    pub fn bad_request(message: impl Into<String>) -> ApiError {
        ApiError::BadRequest { message: message.into(), line: None }
    }

    /// The HTTP status this error is sent with.
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::BadRequest { .. } | ApiError::Program { .. } => StatusCode::BAD_REQUEST,
            ApiError::Conflict(_) => StatusCode::CONFLICT,
            ApiError::SessionNotFound(_)
            | ApiError::SessionEnded(_)
            | ApiError::MachineNotFound(_)
            | ApiError::NotFound(_) => StatusCode::NOT_FOUND,
            ApiError::PayloadTooLarge(_) | ApiError::TooLarge(_) => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::Unauthorized(_) => StatusCode::UNAUTHORIZED,
            ApiError::Forbidden(_) => StatusCode::FORBIDDEN,
            ApiError::TooManyRequests { .. } => StatusCode::TOO_MANY_REQUESTS,
            ApiError::WrongNode { .. } => StatusCode::MISDIRECTED_REQUEST,
            ApiError::StorageUnavailable(_) | ApiError::ShuttingDown(_) => StatusCode::SERVICE_UNAVAILABLE,
            ApiError::UnsupportedMediaType(_) => StatusCode::UNSUPPORTED_MEDIA_TYPE,
        }
    }

    /// The JSON body sent to the client.
    pub fn body(&self) -> ErrorBody {
        let (line, errors, errors_omitted) = match self {
            ApiError::BadRequest { line, .. } => (*line, Vec::new(), 0),
            ApiError::Program { line, errors, omitted, .. } => (Some(*line), errors.clone(), *omitted),
            _ => (None, Vec::new(), 0),
        };
        ErrorBody { error: self.to_string(), line, errors, errors_omitted }
    }

    /// Maps a session's reply error; `id` names the session in the message.
    pub fn from_session(id: &str, e: SessionError) -> ApiError {
        match e {
            SessionError::Command(e) => e.into(),
            SessionError::Ended => ApiError::SessionEnded(id.to_string()),
            SessionError::ServerStopping => ApiError::ShuttingDown(id.to_string()),
        }
    }
}

impl From<CommandError> for ApiError {
    fn from(e: CommandError) -> ApiError {
        match &e {
            CommandError::Syntax { line, errors, .. } => {
                let (errors, omitted) = crate::dto::first_diagnostics(errors);
                ApiError::Program { message: e.to_string(), line: *line, errors, omitted }
            }
            CommandError::MachineData(md) => md.clone().into(),
            CommandError::UnknownAxis(_) | CommandError::Invalid(_) => ApiError::bad_request(e.to_string()),
            CommandError::Busy(_) | CommandError::AlarmActive | CommandError::WrongMode(..) => {
                ApiError::Conflict(e.to_string())
            }
        }
    }
}

impl From<MdError> for ApiError {
    fn from(e: MdError) -> ApiError {
        ApiError::BadRequest { message: format!("machine data: {e}"), line: e.line }
    }
}

impl From<crate::storage::StorageError> for ApiError {
    fn from(e: crate::storage::StorageError) -> ApiError {
        if let Some(held) = e.held_by {
            // Not a storage failure: another node took the session between this node's routing
            // check and the write (the write was refused, nothing changed).
            return ApiError::WrongNode { session: held.session, node: held.node, seconds_left: held.seconds_left };
        }
        tracing::error!(error = %e, "storage failed; the change was not saved");
        ApiError::StorageUnavailable(format!("not saved: {e}"))
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut response = (self.status(), Json(self.body())).into_response();
        match &self {
            ApiError::TooManyRequests { retry_after: Some(wait), .. } => {
                // Whole seconds, rounded up, at least 1: what `Retry-After` can say.
                let seconds = wait.as_secs() + u64::from(wait.subsec_nanos() > 0);
                response.headers_mut().insert(header::RETRY_AFTER, HeaderValue::from(seconds.max(1)));
            }
            ApiError::Unauthorized(_) => {
                response.headers_mut().insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
            }
            ApiError::ShuttingDown(_) => {
                response.headers_mut().insert(header::RETRY_AFTER, HeaderValue::from(SHUTDOWN_RETRY_AFTER_S));
            }
            _ => {}
        }
        response
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn syntax_errors_are_400_with_their_line() {
        let e: ApiError = CommandError::check("G1 X1\nX=(\nWHILE 1\nENDIF\nENDWHILE").unwrap_err().into();
        assert_eq!(e.status(), StatusCode::BAD_REQUEST);
        let body = e.body();
        assert_eq!(body.line, Some(2));
        // Both errors, with their alarms: the unclosed parenthesis, then an ENDIF inside a WHILE
        // without an IF (line 4).
        let found: Vec<(u32, u32)> = body.errors.iter().map(|e| (e.alarm, e.line)).collect();
        assert_eq!(found, [(12080, 2), (12640, 4)]);
    }

    #[test]
    fn refusals_in_the_current_state_are_409() {
        for e in [CommandError::Busy("x"), CommandError::AlarmActive, CommandError::WrongMode("AUTO", "y")] {
            assert_eq!(ApiError::from(e).status(), StatusCode::CONFLICT);
        }
    }

    #[test]
    fn rate_limits_say_when_to_retry_in_whole_seconds() {
        let e = ApiError::TooManyRequests { message: "slow down".into(), retry_after: Some(Duration::from_millis(20)) };
        let response = e.into_response();
        assert_eq!(response.status(), StatusCode::TOO_MANY_REQUESTS);
        assert_eq!(response.headers()[header::RETRY_AFTER], "1");
    }

    #[test]
    fn machine_data_errors_keep_their_line() {
        let e: ApiError = CommandError::MachineData(MdError { line: Some(2), message: "unknown name".into() }).into();
        assert_eq!((e.status(), e.body().line), (StatusCode::BAD_REQUEST, Some(2)));
        assert!(e.body().error.contains("line 2"), "{}", e.body().error);
    }
}
