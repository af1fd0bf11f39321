//! Who a request comes from, beyond its token: the display name a user typed when joining
//! (header `nctwin-user`), and the view-only request of a watch link (header
//! `nctwin-view-only: 1`, or `view_only=1` on the stream's address). With `--auth off` a
//! view-only client is an observer: the server refuses its commands as it refuses an
//! observer token's, so a watch link cannot drive even without tokens.

use std::collections::HashMap;

use axum::extract::{Query, Request};
use nctwin_engine::channel::action_log::OperatorAction;

use super::Role;
use crate::state::SessionEntry;

/// Header with the user's display name.
pub const USER_HEADER: &str = "nctwin-user";
/// Header that asks for view-only access.
pub const VIEW_ONLY_HEADER: &str = "nctwin-view-only";
/// Longest display name kept (characters).
const MAX_NAME: usize = 40;

/// Whether the request asks for view-only access.
pub fn view_only(request: &Request) -> bool {
    if request.headers().get(VIEW_ONLY_HEADER).is_some_and(|v| v.as_bytes() == b"1") {
        return true;
    }
    Query::<HashMap<String, String>>::try_from_uri(request.uri())
        .is_ok_and(|Query(q)| q.get("view_only").is_some_and(|v| v == "1"))
}

/// The display name sent with the request: printable characters only, at most 40.
pub fn display_name(request: &Request) -> String {
    let Some(raw) = request.headers().get(USER_HEADER).and_then(|v| v.to_str().ok()) else { return String::new() };
    // Browsers send header values as Latin-1; names arrive percent-encoded (encodeURIComponent).
    let decoded = percent_decode(raw.trim());
    decoded.chars().filter(|c| !c.is_control()).take(MAX_NAME).collect::<String>().trim().to_string()
}

/// Writes a command to the session's action log (an `operator_action` event on its stream):
/// `POST start`, `PUT mode` ... with the role and display name.
pub async fn log_command(entry: &SessionEntry, method: &str, rest: &str, role: Role, name: String) {
    let action = OperatorAction {
        action: format!("{method} {}", rest.trim_start_matches('/')).trim().to_string(),
        role: role.to_string(),
        name,
    };
    // A session that just ended logs nothing; the command itself reports that.
    let _ = entry.handle.with_channel(move |ch| ch.log_operator_action(action)).await;
}

/// `%XX` sequences to bytes, read as UTF-8 (invalid sequences stay as they are).
fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let (Some(h), Some(l)) = (hex(bytes[i + 1]), hex(bytes[i + 2]))
        {
            out.push((h * 16 + l) as u8);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_decoded_and_cut() {
        assert_eq!(percent_decode("J%C3%BCrgen%20M."), "Jürgen M.");
        assert_eq!(percent_decode("100%"), "100%");
        let req = Request::builder().header(USER_HEADER, "A%0Ab").body(axum::body::Body::empty()).unwrap();
        assert_eq!(display_name(&req), "Ab");
        let long = "x".repeat(100);
        let req = Request::builder().header(USER_HEADER, long).body(axum::body::Body::empty()).unwrap();
        assert_eq!(display_name(&req).len(), MAX_NAME);
    }

    #[test]
    fn view_only_by_header_or_query() {
        let req = Request::builder().header(VIEW_ONLY_HEADER, "1").body(axum::body::Body::empty()).unwrap();
        assert!(view_only(&req));
        let req = Request::builder().uri("/x/stream?period_ms=50&view_only=1").body(axum::body::Body::empty()).unwrap();
        assert!(view_only(&req));
        let req = Request::builder().uri("/x/stream?view_only=0").body(axum::body::Body::empty()).unwrap();
        assert!(!view_only(&req));
    }
}
