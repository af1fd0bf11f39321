//! JSON body extractors whose every rejection is an [`ApiError`]: malformed JSON, wrong types,
//! unknown or missing fields are `400` with a message naming the field (axum's own `Json` would
//! answer `422` in plain text), an oversized body is `413`.
//!
//! A non-empty JSON body needs a JSON content type (`application/json`, or
//! `application/<...>+json`), else `415` naming it: a web page of another site can send
//! `text/plain`, form or untyped bodies anywhere without the browser asking the server first
//! (a CORS "simple" request), but not JSON (see [`crate::site`]). An empty body (or only white
//! space) is no body, whatever its content type, so body-less POSTs keep working.
//!
//! [`close_unread`] makes every reply sent before the request body was read say
//! `Connection: close`.

use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::task::{Context, Poll};

use axum::body::{Bytes, HttpBody};
use axum::extract::{FromRequest, Request, State};
use axum::http::header::{CONNECTION, CONTENT_LENGTH, CONTENT_TYPE};
use axum::http::{HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use serde::de::DeserializeOwned;

use crate::error::ApiError;
use crate::limits::Limits;

/// The request body limit of a group of routes (see [`limit_body`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BodyLimit(pub usize);

/// Middleware that refuses a body whose `Content-Length` exceeds the group's limit with `413`
/// before reading it, and tells the extractors the limit (axum's `DefaultBodyLimit`, set with
/// the same value, cuts off bodies without a length).
pub async fn limit_body(State(limit): State<BodyLimit>, mut request: Request, next: Next) -> Response {
    let length =
        request.headers().get(CONTENT_LENGTH).and_then(|v| v.to_str().ok()).and_then(|v| v.parse::<u64>().ok());
    if length.is_some_and(|n| n > limit.0 as u64) {
        return ApiError::PayloadTooLarge(limit.0).into_response();
    }
    request.extensions_mut().insert(limit);
    next.run(request).await
}

/// A required JSON body.
#[derive(Debug, Clone)]
pub struct ApiJson<T>(pub T);

/// An optional JSON body: an empty body (with or without a content type) gives `T::default()`.
#[derive(Debug, Clone)]
pub struct OptionalJson<T>(pub T);

impl<S, T> FromRequest<S> for ApiJson<T>
where
    S: Send + Sync,
    T: DeserializeOwned,
{
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        match read_json(req, state).await? {
            Some(bytes) => parse(&bytes).map(ApiJson),
            None => Err(ApiError::bad_request("request body is empty: expected a JSON object")),
        }
    }
}

impl<S, T> FromRequest<S> for OptionalJson<T>
where
    S: Send + Sync,
    T: DeserializeOwned + Default,
{
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        match read_json(req, state).await? {
            Some(bytes) => parse(&bytes).map(OptionalJson),
            None => Ok(OptionalJson(T::default())),
        }
    }
}

/// A plain-text body (any content type), UTF-8; empty is the empty string.
#[derive(Debug, Clone)]
pub struct ApiText(pub String);

impl<S: Send + Sync> FromRequest<S> for ApiText {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, ApiError> {
        let Some(bytes) = read_body(req, state).await? else { return Ok(ApiText(String::new())) };
        String::from_utf8(bytes.to_vec())
            .map(ApiText)
            .map_err(|e| ApiError::bad_request(format!("the body is not UTF-8 text: {e}")))
    }
}

/// A JSON body: as [`read_body`], `415` when a non-empty body has no JSON content type.
async fn read_json<S: Send + Sync>(req: Request, state: &S) -> Result<Option<Bytes>, ApiError> {
    let content_type = req.headers().get(CONTENT_TYPE).map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned());
    let Some(bytes) = read_body(req, state).await? else { return Ok(None) };
    match content_type {
        Some(ct) if is_json(&ct) => Ok(Some(bytes)),
        Some(ct) => Err(ApiError::UnsupportedMediaType(format!(
            "the body must be JSON sent with `Content-Type: application/json`; its content type was `{ct}`"
        ))),
        None => Err(ApiError::UnsupportedMediaType(
            "the body must be JSON sent with `Content-Type: application/json`; it had no content type".into(),
        )),
    }
}

/// The body, or `None` when it is empty or only white space.
async fn read_body<S: Send + Sync>(req: Request, state: &S) -> Result<Option<Bytes>, ApiError> {
    let limit = req.extensions().get::<BodyLimit>().map_or(Limits::default().body_bytes, |l| l.0);
    let bytes = Bytes::from_request(req, state).await.map_err(|rejection| {
        if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::PayloadTooLarge(limit)
        } else {
            ApiError::bad_request(format!("could not read the request body: {}", rejection.body_text()))
        }
    })?;
    Ok(if bytes.iter().all(u8::is_ascii_whitespace) { None } else { Some(bytes) })
}

/// `application/json` or `application/<something>+json`, any parameters.
fn is_json(content_type: &str) -> bool {
    let essence = content_type.split(';').next().unwrap_or("").trim().to_ascii_lowercase();
    essence == "application/json" || (essence.starts_with("application/") && essence.ends_with("+json"))
}

/// Deserializes a whole JSON document; errors name the path of the offending field.
pub fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let value = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        if path == "." {
            ApiError::bad_request(format!("invalid JSON body: {}", e.inner()))
        } else {
            ApiError::bad_request(format!("invalid JSON body at `{path}`: {}", e.inner()))
        }
    })?;
    de.end().map_err(|e| ApiError::bad_request(format!("invalid JSON body: {e}")))?;
    Ok(value)
}

/// Middleware: a reply sent before the request body was read to its end says
/// `Connection: close`. The server closes such a connection after the reply (the unread rest
/// of the body would be taken for the next request); without the header a keep-alive client
/// sends its next request into the closing connection and sees it fail. Refusals before the
/// body is read are the access check (`401`/`403`/`409`/`429`), a `Content-Length` over the
/// limit (`413`), a refused host or origin (`403`, [`crate::site`]) and routing (`404`/`405`).
pub async fn close_unread(request: Request, next: Next) -> Response {
    if request.version() > axum::http::Version::HTTP_11 || request.body().is_end_stream() {
        return next.run(request).await;
    }
    let read = Arc::new(AtomicBool::new(false));
    let flag = read.clone();
    let request = request.map(|body| axum::body::Body::new(ReadToEnd { inner: body, read: flag }));
    let mut response = next.run(request).await;
    if !read.load(Ordering::Acquire) {
        response.headers_mut().insert(CONNECTION, HeaderValue::from_static("close"));
    }
    response
}

/// A request body that notes when it has been read to its end.
struct ReadToEnd {
    inner: axum::body::Body,
    read: Arc<AtomicBool>,
}

impl http_body::Body for ReadToEnd {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<http_body::Frame<Bytes>, axum::Error>>> {
        let polled = Pin::new(&mut self.inner).poll_frame(cx);
        if matches!(polled, Poll::Ready(None)) || self.inner.is_end_stream() {
            self.read.store(true, Ordering::Release);
        }
        polled
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> http_body::SizeHint {
        self.inner.size_hint()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dto::RunRequest;

    fn message(json: &str) -> String {
        parse::<RunRequest>(json.as_bytes()).unwrap_err().body().error
    }

    #[test]
    fn errors_name_the_problem() {
        assert!(message(r#"{"program": 5}"#).contains("`program`"), "{}", message(r#"{"program": 5}"#));
        // `run` may name a stored program instead of its text; MDA always needs its blocks.
        let missing = parse::<crate::dto::MdaRequest>(br#"{"wait": true}"#).unwrap_err().body().error;
        assert!(missing.contains("missing field `program`"), "{missing}");
        assert!(message(r#"{"program": "M30", "speed": 2}"#).contains("unknown field `speed`"));
        assert!(message(r#"{"program": "M30", "pace": "slow"}"#).contains("unknown variant `slow`"));
        assert!(message(r#"{"program": "#).contains("EOF"));
        assert!(message(r#"{"program": "M30"} x"#).contains("trailing"));
    }

    #[test]
    fn json_content_types_are_recognised() {
        assert!(is_json("application/json"));
        assert!(is_json("Application/JSON; charset=utf-8"));
        assert!(is_json("application/merge-patch+json"));
        assert!(!is_json("text/plain"));
    }
}
