//! JSON body extractors whose every rejection is an [`ApiError`]: malformed JSON, wrong types,
//! unknown or missing fields are `400` with a message naming the field (axum's own `Json` would
//! answer `422` in plain text), an oversized body is `413`.
//!
//! The content type is not enforced: any non-empty body is parsed as JSON, so `curl -d '{...}'`
//! (which sends `application/x-www-form-urlencoded`) works. A body that is not JSON is a `400`
//! that mentions a non-JSON content type when there was one.

use axum::body::Bytes;
use axum::extract::{FromRequest, Request, State};
use axum::http::StatusCode;
use axum::http::header::{CONTENT_LENGTH, CONTENT_TYPE};
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
        match read_body(req, state).await? {
            Some((bytes, hint)) => parse_with_hint(&bytes, hint).map(ApiJson),
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
        match read_body(req, state).await? {
            Some((bytes, hint)) => parse_with_hint(&bytes, hint).map(OptionalJson),
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
        let Some((bytes, _)) = read_body(req, state).await? else { return Ok(ApiText(String::new())) };
        String::from_utf8(bytes.to_vec())
            .map(ApiText)
            .map_err(|e| ApiError::bad_request(format!("the body is not UTF-8 text: {e}")))
    }
}

/// The body, or `None` when it is empty or only white space, with a hint for error messages
/// when the content type says it is not JSON.
async fn read_body<S: Send + Sync>(req: Request, state: &S) -> Result<Option<(Bytes, Option<String>)>, ApiError> {
    let content_type = req.headers().get(CONTENT_TYPE).map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned());
    let limit = req.extensions().get::<BodyLimit>().map_or(Limits::default().body_bytes, |l| l.0);
    let bytes = Bytes::from_request(req, state).await.map_err(|rejection| {
        if rejection.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::PayloadTooLarge(limit)
        } else {
            ApiError::bad_request(format!("could not read the request body: {}", rejection.body_text()))
        }
    })?;
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Ok(None);
    }
    let hint = content_type
        .filter(|ct| !is_json(ct))
        .map(|ct| format!(" (the body must be JSON; its content type was `{ct}`)"));
    Ok(Some((bytes, hint)))
}

/// `application/json` or `application/<something>+json`, any parameters.
fn is_json(content_type: &str) -> bool {
    let essence = content_type.split(';').next().unwrap_or("").trim().to_ascii_lowercase();
    essence == "application/json" || (essence.starts_with("application/") && essence.ends_with("+json"))
}

/// Deserializes a whole JSON document; errors name the path of the offending field.
pub fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    parse_with_hint(bytes, None)
}

/// As [`parse`]; `hint` is appended when the body is not JSON at all.
fn parse_with_hint<T: DeserializeOwned>(bytes: &[u8], hint: Option<String>) -> Result<T, ApiError> {
    let not_json = |e: &serde_json::Error| -> String {
        match (&hint, e.classify()) {
            (Some(hint), serde_json::error::Category::Syntax | serde_json::error::Category::Eof) => hint.clone(),
            _ => String::new(),
        }
    };
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let value = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let hint = not_json(e.inner());
        if path == "." {
            ApiError::bad_request(format!("invalid JSON body: {}{hint}", e.inner()))
        } else {
            ApiError::bad_request(format!("invalid JSON body at `{path}`: {}{hint}", e.inner()))
        }
    })?;
    de.end().map_err(|e| ApiError::bad_request(format!("invalid JSON body: {e}{}", not_json(&e))))?;
    Ok(value)
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
        assert!(message(r#"{"wait": true}"#).contains("missing field `program`"));
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
