//! Cross-site protection: which `Host` the server answers to, and which web pages (`Origin`)
//! may call it from a browser.
//!
//! A server without tokens (`--auth off`, the default) on `localhost` must not be driven by a
//! web page of another site that its user happens to visit:
//! - DNS rebinding: the page's own name is made to resolve to 127.0.0.1, so its requests reach
//!   this server with that name in `Host`. Only the bound address and the loopback names
//!   (`localhost`, `127.0.0.1`, `[::1]`), each with the bound port, and the names the operator
//!   lists (`--allow-host`) are answered. A server bound to every interface (`0.0.0.0`, `::`)
//!   answers any address literal with its port, as no page can rebind an address.
//! - Cross-site requests: a page may send "simple" requests (a form POST, a body-less POST, a
//!   `text/plain` body) anywhere without the browser asking the server first, and it may open
//!   WebSockets anywhere. Browsers name the page in `Origin`; a request whose `Origin` is
//!   neither the server's own (the scheme and the `Host` it was sent to) nor one the operator
//!   lists (`--allow-origin`) is refused, WebSocket upgrades and CORS preflights included. JSON
//!   bodies need a JSON content type ([`crate::extract`]), so a page of another site can never
//!   send the API's requests as simple requests either.
//!
//! Clients that are not browsers (curl, scripts, the test harnesses) send no `Origin` and name
//! the address they connect to in `Host`, so they are not affected.
//!
//! Both refusals are `403` with a message naming the flag that would allow the request. (`421`
//! would fit a wrong `Host` too, but this API already answers `421` for "another node holds the
//! session", which a client acts on by going to that node.)

use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;

use axum::extract::{Request, State};
use axum::http::header::{HOST, ORIGIN};
use axum::http::request::Parts;
use axum::http::{HeaderValue, Method};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use tower_http::cors::{AllowHeaders, AllowMethods, AllowOrigin, CorsLayer, ExposeHeaders};

use crate::error::ApiError;

/// Names every server answers to on its bound port.
const LOOPBACK_NAMES: [&str; 3] = ["localhost", "127.0.0.1", "[::1]"];

/// Who may call the server: the bound address and the operator's lists.
#[derive(Debug, Clone)]
pub struct SitePolicy {
    /// The listener's address; `None` when the app is driven without a socket (any port).
    bound: Option<SocketAddr>,
    hosts: Vec<AllowedHost>,
    /// Normalised origins (see [`normalize_origin`]).
    origins: Vec<String>,
}

/// One `--allow-host` entry: a name (lower case; an IPv6 address in brackets) and, if given,
/// the one port it is allowed with.
#[derive(Debug, Clone, PartialEq, Eq)]
struct AllowedHost {
    name: String,
    port: Option<u16>,
}

impl SitePolicy {
    /// The policy of a server bound to `bound` with the operator's `--allow-host` and
    /// `--allow-origin` entries; entries that do not parse are left out with a warning
    /// (`nctwin` checks its flags with [`parse_host`] and [`parse_origin`] first).
    pub fn new(bound: Option<SocketAddr>, allow_hosts: &[String], allow_origins: &[String]) -> SitePolicy {
        let hosts = allow_hosts
            .iter()
            .filter_map(|h| match split_authority(h) {
                Some((name, port)) => Some(AllowedHost { name, port }),
                None => {
                    tracing::warn!(host = %h, "not a host name (NAME or NAME:PORT): left out of the allowed hosts");
                    None
                }
            })
            .collect();
        let origins = allow_origins
            .iter()
            .filter_map(|o| {
                let normal = normalize_origin(o);
                if normal.is_none() {
                    tracing::warn!(origin = %o, "not an origin (http[s]://HOST[:PORT]): left out of the allowed origins");
                }
                normal
            })
            .collect();
        SitePolicy { bound, hosts, origins }
    }

    /// Whether a request naming `authority` (its `Host`) is for this server.
    pub fn host_allowed(&self, authority: &str) -> bool {
        let Some((name, port)) = split_authority(authority) else { return false };
        if self.hosts.iter().any(|h| h.name == name && h.port.is_none_or(|p| p == port.unwrap_or(80))) {
            return true;
        }
        let Some(bound) = self.bound else {
            return LOOPBACK_NAMES.contains(&name.as_str()) || parse_ip(&name).is_some();
        };
        if port.unwrap_or(80) != bound.port() {
            return false;
        }
        if LOOPBACK_NAMES.contains(&name.as_str()) {
            return true;
        }
        parse_ip(&name).is_some_and(|ip| ip == bound.ip() || bound.ip().is_unspecified())
    }

    /// Whether a browser page of `origin` may call the server, for a request sent to
    /// `authority` (its `Host`, when known): the server's own origin, or a listed one.
    pub fn origin_allowed(&self, origin: &str, authority: Option<&str>) -> bool {
        let Some(origin) = normalize_origin(origin) else { return false };
        if self.origins.contains(&origin) {
            return true;
        }
        let Some(authority) = authority else { return false };
        let Some((scheme, rest)) = origin.split_once("://") else { return false };
        let default_port = if scheme == "https" { 443 } else { 80 };
        let (Some((origin_name, origin_port)), Some((name, port))) =
            (split_authority(rest), split_authority(authority))
        else {
            return false;
        };
        // A `Host` without a port (behind a proxy, say) matches the origin's port.
        let origin_port = origin_port.unwrap_or(default_port);
        origin_name == name && port.is_none_or(|p| p == origin_port)
    }

    /// The refusal of a request, if it is refused.
    fn check(&self, method: &Method, authority: Option<&str>, origin: Option<&HeaderValue>) -> Result<(), ApiError> {
        if let Some(authority) = authority
            && !self.host_allowed(authority)
        {
            let port = self.bound.map_or_else(|| "its port".to_string(), |b| format!("port {}", b.port()));
            return Err(ApiError::Forbidden(format!(
                "this server does not answer to the host `{authority}`: only to its address, localhost, 127.0.0.1 and \
                 [::1] on {port}, and to the names given with --allow-host (a web page of another site may have \
                 pointed its own name here: DNS rebinding)"
            )));
        }
        if let Some(origin) = origin {
            let text = String::from_utf8_lossy(origin.as_bytes());
            if !self.origin_allowed(&text, authority) {
                let what = if method == Method::OPTIONS { "a cross-site preflight" } else { "a request" };
                return Err(ApiError::Forbidden(format!(
                    "{what} from a web page of the origin `{text}` is refused: only the server's own pages and the \
                     origins given with --allow-origin may call it from a browser"
                )));
            }
        }
        Ok(())
    }

    /// The CORS layer: preflights and `Access-Control-Allow-*` headers for the allowed
    /// origins (any method, the request headers asked for, every response header exposed).
    pub fn cors(self: &Arc<Self>) -> CorsLayer {
        let policy = self.clone();
        let allow = AllowOrigin::predicate(move |origin: &HeaderValue, parts: &Parts| {
            let authority = authority_of(&parts.uri, &parts.headers);
            policy.origin_allowed(&String::from_utf8_lossy(origin.as_bytes()), authority)
        });
        CorsLayer::new()
            .allow_origin(allow)
            .allow_methods(AllowMethods::mirror_request())
            .allow_headers(AllowHeaders::mirror_request())
            .expose_headers(ExposeHeaders::any())
    }
}

/// Middleware (outside CORS, so refused preflights get no permission): refuses a request for
/// a host that is not this server's, or from a web page of an origin that may not call it.
pub async fn guard(State(policy): State<Arc<SitePolicy>>, request: Request, next: Next) -> Response {
    let authority = authority_of(request.uri(), request.headers());
    match policy.check(request.method(), authority, request.headers().get(ORIGIN)) {
        Ok(()) => next.run(request).await,
        Err(e) => e.into_response(),
    }
}

/// The authority a request was sent to: the URI's (absolute form, HTTP/2) or the `Host`
/// header (`""` for one that is not text, which no host check passes). `None` without either
/// (an HTTP/1.0 client, a request built in a test).
fn authority_of<'a>(uri: &'a axum::http::Uri, headers: &'a axum::http::HeaderMap) -> Option<&'a str> {
    if let Some(authority) = uri.authority() {
        return Some(authority.as_str());
    }
    headers.get(HOST).map(|h| h.to_str().unwrap_or(""))
}

/// `NAME`, `NAME:PORT`, `[IPv6]` or `[IPv6]:PORT` → (lower-case name, port). `None` for
/// anything else (user info, a path, an empty name, a bad port).
fn split_authority(text: &str) -> Option<(String, Option<u16>)> {
    let port_of = |digits: &str| -> Option<u16> {
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        digits.parse().ok()
    };
    let text = text.trim();
    let (name, port) = if let Some(rest) = text.strip_prefix('[') {
        let (inside, after) = rest.split_once(']')?;
        inside.parse::<std::net::Ipv6Addr>().ok()?;
        let port = if after.is_empty() { None } else { Some(port_of(after.strip_prefix(':')?)?) };
        (format!("[{inside}]"), port)
    } else {
        let (name, port) = match text.rsplit_once(':') {
            Some((name, digits)) => (name, Some(port_of(digits)?)),
            None => (text, None),
        };
        let name_char = |b: u8| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_');
        if name.is_empty() || !name.bytes().all(name_char) {
            return None;
        }
        (name.to_string(), port)
    };
    Some((name.to_ascii_lowercase(), port))
}

/// An address literal (`192.168.1.5`, `[fd00::5]`).
fn parse_ip(name: &str) -> Option<IpAddr> {
    let bare = name.strip_prefix('[').and_then(|n| n.strip_suffix(']')).unwrap_or(name);
    bare.parse().ok()
}

/// `http://HOST[:PORT]` or `https://...` in lower case, without a default port or a trailing
/// slash; `None` for anything else (`null`, a path, another scheme).
fn normalize_origin(origin: &str) -> Option<String> {
    let origin = origin.trim().trim_end_matches('/').to_ascii_lowercase();
    let (scheme, rest) = origin.split_once("://")?;
    let default_port = match scheme {
        "http" => 80,
        "https" => 443,
        _ => return None,
    };
    let (name, port) = split_authority(rest)?;
    Some(match port {
        Some(port) if port != default_port => format!("{scheme}://{name}:{port}"),
        _ => format!("{scheme}://{name}"),
    })
}

/// Checks an `--allow-host` value (for clap): `NAME` or `NAME:PORT`.
pub fn parse_host(text: &str) -> Result<String, String> {
    match split_authority(text) {
        Some((name, Some(port))) => Ok(format!("{name}:{port}")),
        Some((name, None)) => Ok(name),
        None => Err(format!("`{text}` is not a host name: NAME or NAME:PORT (an IPv6 address in brackets)")),
    }
}

/// Checks an `--allow-origin` value (for clap): `http[s]://HOST[:PORT]`, as browsers send it.
pub fn parse_origin(text: &str) -> Result<String, String> {
    normalize_origin(text)
        .ok_or_else(|| format!("`{text}` is not a web origin: http://HOST[:PORT] or https://HOST[:PORT], no path"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn policy(bound: &str, hosts: &[&str], origins: &[&str]) -> SitePolicy {
        let strings = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        SitePolicy::new(Some(bound.parse().expect("address")), &strings(hosts), &strings(origins))
    }

    #[test]
    fn the_bound_address_and_loopback_names_with_the_bound_port_are_this_server() {
        let p = policy("127.0.0.1:8080", &[], &[]);
        for host in ["127.0.0.1:8080", "localhost:8080", "LOCALHOST:8080", "[::1]:8080"] {
            assert!(p.host_allowed(host), "{host}");
        }
        for host in ["evil.example:8080", "localhost:8081", "localhost", "127.0.0.2:8080", "", "u@localhost:8080"] {
            assert!(!p.host_allowed(host), "{host}");
        }
        let p = policy("127.0.0.1:80", &[], &[]);
        assert!(p.host_allowed("localhost"), "port 80 is the default");
    }

    #[test]
    fn every_interface_answers_address_literals_and_listed_names() {
        let p = policy("0.0.0.0:8080", &["nctwin.lan", "cell:9000"], &[]);
        for host in ["192.168.1.5:8080", "[fd00::1]:8080", "localhost:8080", "NCTWIN.LAN", "nctwin.lan:1", "cell:9000"]
        {
            assert!(p.host_allowed(host), "{host}");
        }
        for host in ["192.168.1.5:8081", "pc.lan:8080", "cell:8080", "cell"] {
            assert!(!p.host_allowed(host), "{host}");
        }
    }

    #[test]
    fn the_servers_own_origin_and_listed_origins_may_call_it() {
        let p = policy("127.0.0.1:8080", &[], &["HTTPS://hmi.example/", "http://dev:5173"]);
        assert!(p.origin_allowed("http://127.0.0.1:8080", Some("127.0.0.1:8080")));
        assert!(p.origin_allowed("http://localhost:8080", Some("localhost:8080")));
        assert!(p.origin_allowed("https://nctwin.example", Some("nctwin.example")), "behind a TLS proxy");
        assert!(p.origin_allowed("https://hmi.example:443", Some("127.0.0.1:8080")));
        assert!(p.origin_allowed("http://dev:5173", None));
        for origin in ["http://evil.example", "null", "http://localhost:8081", "file://", "http://dev:5174"] {
            assert!(!p.origin_allowed(origin, Some("localhost:8080")), "{origin}");
        }
        assert!(!p.origin_allowed("http://localhost:8080", None), "no host: not the same origin");
    }

    #[test]
    fn flags_are_checked_and_normalised() {
        assert_eq!(parse_origin("HTTP://Example.com:80/").as_deref(), Ok("http://example.com"));
        assert_eq!(parse_origin("https://a.b:8443").as_deref(), Ok("https://a.b:8443"));
        assert!(parse_origin("http://a.b/path").is_err() && parse_origin("ftp://a.b").is_err());
        assert!(parse_origin("*").is_err() && parse_origin("null").is_err());
        assert_eq!(parse_host("NCTwin.lan").as_deref(), Ok("nctwin.lan"));
        assert_eq!(parse_host("[fd00::1]:80").as_deref(), Ok("[fd00::1]:80"));
        assert!(parse_host("a/b").is_err() && parse_host("").is_err() && parse_host("a:b").is_err());
    }
}
