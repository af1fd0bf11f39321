//! Who may call what: the one table of the access policy and the middleware that applies it
//! (with the command rate limit) to every request to a session.
//!
//! | request                                          | needs                                    |
//! |--------------------------------------------------|------------------------------------------|
//! | any `GET` (state, programs, stream, control)     | any role ([`Need::Read`])                |
//! | `POST .../check`, `.../preview` (change nothing) | any role                                 |
//! | `POST .../control/take`, `.../control/release`   | operator or owner ([`Need::Join`])       |
//! | `DELETE /sessions/{id}`, `PATCH /sessions/{id}`   | owner ([`Need::Owner`])                  |
//! | every other request to a session               | operator or owner holding control ([`Need::Command`]) |
//!
//! Observers get `403` for everything beyond reading; an operator without control gets `409`.
//! With `--auth off` nothing is checked but the command rate limit, which never refuses the
//! commands that stop motion ([`rate_limited`]).

use std::collections::HashMap;

use axum::extract::{FromRequestParts, MatchedPath, Path, Query, Request, State};
use axum::http::Method;
use axum::http::header::AUTHORIZATION;
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::{AuthMode, Role, role_of};
use crate::error::ApiError;
use crate::state::AppState;

/// Route template prefix of every request to one session.
const SESSION_ROUTE: &str = "/api/v1/sessions/{id}";

/// What a request to a session needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Need {
    Read,
    Join,
    Command,
    Owner,
}

/// The access policy: what `method` on the route template `route` needs (`None`: not a
/// request to one session).
pub fn need(method: &Method, route: &str) -> Option<Need> {
    let rest = route.strip_prefix(SESSION_ROUTE)?;
    if !(rest.is_empty() || rest.starts_with('/')) {
        return None;
    }
    Some(match (method, rest) {
        (&Method::GET | &Method::HEAD, _) => Need::Read,
        (&Method::POST, "/check" | "/preview") => Need::Read,
        (&Method::POST, "/control/take" | "/control/release") => Need::Join,
        (&Method::DELETE | &Method::PATCH, "") => Need::Owner,
        _ => Need::Command,
    })
}

/// Whether a command is counted against the session's command rate limit. Commands that stop
/// motion (NC stop, reset, JOG stop) are not: a client flooding the session with commands must
/// never keep another client from stopping the machine. They cost the server about what a read
/// does.
pub fn rate_limited(method: &Method, route: &str) -> bool {
    let stops = method == Method::POST
        && route.strip_prefix(SESSION_ROUTE).is_some_and(|rest| matches!(rest, "/stop" | "/reset" | "/jog/stop"));
    need(method, route) == Some(Need::Command) && !stops
}

/// The caller's role in the session a request addresses, for handlers that need it (the
/// control endpoints). With `--auth off` every caller is the owner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Caller(pub Role);

/// Decides whether `role` may do what `need` requires, given who holds control.
pub fn check(need: Need, role: Role, holder: Option<Role>) -> Result<(), ApiError> {
    match (need, role) {
        (Need::Read, _) => Ok(()),
        (_, Role::Observer) => Err(ApiError::Forbidden("observers may read but not change a session".into())),
        (Need::Owner, r) if r != Role::Owner => Err(ApiError::Forbidden("only the owner may do this".into())),
        (Need::Command, r) if holder != Some(r) => Err(ApiError::Conflict(match holder {
            Some(h) => format!("the {h} holds control; POST .../control/take once it is released"),
            None => "nobody holds control; POST .../control/take first".into(),
        })),
        _ => Ok(()),
    }
}

/// The bearer token of a request: the `Authorization: Bearer` header, or for the WebSocket
/// stream (browsers cannot set headers there) the `token` query parameter.
fn presented_token(request: &Request, route: &str) -> Option<String> {
    bearer(request.headers()).or_else(|| {
        if !route.ends_with("/stream") {
            return None;
        }
        let Query(mut query) = Query::<HashMap<String, String>>::try_from_uri(request.uri()).ok()?;
        query.remove("token")
    })
}

/// Middleware (route layer): finds the session, checks the token and role, counts commands
/// against the rate limit, and hands the [`Caller`] to the handler.
pub async fn layer(State(state): State<AppState>, request: Request, next: Next) -> Response {
    match authorize(&state, request).await {
        Ok(request) => next.run(request).await,
        Err(e) => e.into_response(),
    }
}

async fn authorize(state: &AppState, request: Request) -> Result<Request, ApiError> {
    let route = request.extensions().get::<MatchedPath>().map(|p| p.as_str().to_string()).unwrap_or_default();
    if route == "/api/v1/sessions" && state.auth() == AuthMode::Required && request.method() == Method::GET {
        // The listing filters by token itself; it still needs one.
        if presented_token(&request, &route).is_none() {
            return Err(ApiError::Unauthorized("a bearer token is required to list sessions".into()));
        }
    }
    let Some(need) = need(request.method(), &route) else { return Ok(request) };
    let (mut parts, body) = request.into_parts();
    // The same decoding as the handlers' `Path` extractor, so both see the same id.
    let Path(params) = Path::<HashMap<String, String>>::from_request_parts(&mut parts, state)
        .await
        .map_err(|e| ApiError::bad_request(e.body_text()))?;
    let mut request = Request::from_parts(parts, body);
    let id = params.get("id").cloned().unwrap_or_default();
    let entry = state.find_entry(&id).await?;

    let role = match state.auth() {
        // A watch link asks for view-only access: an observer, refused as one.
        AuthMode::Off if super::who::view_only(&request) => {
            check(need, Role::Observer, None)?;
            Role::Observer
        }
        AuthMode::Off => Role::Owner,
        AuthMode::Required => {
            let token = presented_token(&request, &route).ok_or_else(|| {
                ApiError::Unauthorized("this server requires a token: `Authorization: Bearer <token>`".into())
            })?;
            let role = role_of(&entry.tokens, &token)
                .ok_or_else(|| ApiError::Unauthorized(format!("the token is not valid for session `{id}`")))?;
            check(need, role, entry.control_holder())?;
            role
        }
    };
    if rate_limited(request.method(), &route) {
        entry.take_command(state.limits())?;
    }
    // Any request that passed the checks is use of the session (idle expiry).
    entry.touch();
    if need == Need::Command {
        let rest = route.strip_prefix(SESSION_ROUTE).unwrap_or_default();
        super::who::log_command(&entry, request.method().as_str(), rest, role, super::who::display_name(&request))
            .await;
    }
    request.extensions_mut().insert(Caller(role));
    Ok(request)
}

/// Sessions a token gives access to (for the listing with `--auth required`).
pub fn visible_to(state: &AppState, token: Option<&str>) -> Vec<std::sync::Arc<crate::state::SessionEntry>> {
    let all = state.list_entries();
    match (state.auth(), token) {
        (AuthMode::Off, _) => all,
        (AuthMode::Required, Some(token)) => all.into_iter().filter(|e| role_of(&e.tokens, token).is_some()).collect(),
        (AuthMode::Required, None) => Vec::new(),
    }
}

/// The bearer token of a request's headers, if any (for handlers).
pub fn bearer(headers: &axum::http::HeaderMap) -> Option<String> {
    let v = headers.get(AUTHORIZATION)?.to_str().ok()?;
    let (scheme, token) = v.trim().split_once(' ')?;
    scheme.eq_ignore_ascii_case("bearer").then(|| token.trim().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_policy_table() {
        let s = |rest: &str| format!("{SESSION_ROUTE}{rest}");
        assert_eq!(need(&Method::GET, &s("/state")), Some(Need::Read));
        assert_eq!(need(&Method::GET, &s("/stream")), Some(Need::Read));
        assert_eq!(need(&Method::GET, &s("/programs/{name}")), Some(Need::Read));
        assert_eq!(need(&Method::GET, &s("/kinematic-chains")), Some(Need::Read));
        assert_eq!(need(&Method::POST, &s("/check")), Some(Need::Read));
        assert_eq!(need(&Method::POST, &s("/preview")), Some(Need::Read));
        assert_eq!(need(&Method::POST, &s("/control/take")), Some(Need::Join));
        assert_eq!(need(&Method::DELETE, &s("")), Some(Need::Owner));
        assert_eq!(need(&Method::PATCH, &s("")), Some(Need::Owner));
        for (method, rest) in [
            (Method::POST, "/run"),
            (Method::POST, "/stop"),
            (Method::POST, "/jog/stop"),
            (Method::PUT, "/mode"),
            (Method::PUT, "/machine-data"),
            (Method::PUT, "/kinematic-chains"),
            (Method::PUT, "/programs/{name}"),
            (Method::DELETE, "/programs/{name}"),
        ] {
            assert_eq!(need(&method, &s(rest)), Some(Need::Command), "{method} {rest}");
        }
        assert_eq!(need(&Method::POST, "/api/v1/sessions"), None);
        assert_eq!(need(&Method::GET, "/api/v1/health"), None);
    }

    #[test]
    fn commands_that_stop_motion_are_not_rate_limited() {
        let s = |rest: &str| format!("{SESSION_ROUTE}{rest}");
        for rest in ["/stop", "/reset", "/jog/stop"] {
            assert_eq!(need(&Method::POST, &s(rest)), Some(Need::Command), "{rest} still needs control");
            assert!(!rate_limited(&Method::POST, &s(rest)), "{rest}");
        }
        for rest in ["/run", "/start", "/jog", "/cancel", "/mda"] {
            assert!(rate_limited(&Method::POST, &s(rest)), "{rest}");
        }
        assert!(rate_limited(&Method::PUT, &s("/overrides")));
        assert!(!rate_limited(&Method::GET, &s("/state")));
        assert!(!rate_limited(&Method::POST, &s("/check")), "reads have their own limits");
    }

    #[test]
    fn observers_only_read_and_commands_need_control() {
        assert!(check(Need::Read, Role::Observer, Some(Role::Owner)).is_ok());
        for need in [Need::Join, Need::Command, Need::Owner] {
            assert_eq!(check(need, Role::Observer, None).unwrap_err().status(), 403);
        }
        assert_eq!(check(Need::Owner, Role::Operator, Some(Role::Operator)).unwrap_err().status(), 403);
        assert_eq!(check(Need::Command, Role::Operator, Some(Role::Owner)).unwrap_err().status(), 409);
        assert!(check(Need::Command, Role::Operator, Some(Role::Operator)).is_ok());
        assert_eq!(check(Need::Command, Role::Owner, None).unwrap_err().status(), 409);
        assert!(check(Need::Join, Role::Operator, Some(Role::Owner)).is_ok(), "asking is allowed; take decides");
    }

    #[test]
    fn the_stream_token_may_come_in_the_query() {
        let request = Request::builder().uri("/x/stream?period_ms=50&token=nct_a%2Bb").body(axum::body::Body::empty());
        let request = request.expect("request");
        assert_eq!(presented_token(&request, "/api/v1/sessions/{id}/stream").as_deref(), Some("nct_a+b"));
        assert_eq!(presented_token(&request, "/api/v1/sessions/{id}/state"), None, "only for the stream");
    }
}
