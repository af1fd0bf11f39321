//! The OpenAPI 3.1 document, generated from the handlers' `#[utoipa::path]` annotations.
//!
//! It is served at `GET /api/v1/openapi.json` (with Swagger UI at `/api/docs`) and committed as
//! `openapi/openapi.json`; a test fails when the two differ
//! (`NCTWIN_UPDATE_OPENAPI=1 cargo test -p nctwin-server openapi` rewrites the file).

use axum::http::Method;
use serde_json::{Value, json};
use utoipa::OpenApi;
use utoipa_axum::router::OpenApiRouter;

use crate::api;
use crate::auth::access::{self, Need};
use crate::limits::Limits;
use crate::state::AppState;

/// Where the document is served.
pub const DOCUMENT_PATH: &str = "/api/v1/openapi.json";
/// Where Swagger UI is served.
pub const SWAGGER_UI_PATH: &str = "/api/docs";
/// The committed copy of the document, relative to the workspace root.
pub const COMMITTED_PATH: &str = "openapi/openapi.json";

/// Title, description and tags; the paths and schemas come from [`api::router`].
#[derive(OpenApi)]
#[openapi(
    info(
        title = "NCTwin",
        description = "Simulated SINUMERIK 840D sl-style NC channels: sessions, part programs, JOG, MDA, machine data and live state streams.\n\nUnits: lengths mm, angles degrees, feed mm/min, time s.\n\nServer-side limits: a `pace: \"fast\"` command runs at most 3600 s of simulated time or 10 s of wall time (then NC stop); a `wait: true` request is answered after at most 600 s of wall time; request bodies are limited to 1 MiB, except program uploads (`PUT .../programs/{name}`: 16 MiB of program text, 64 MiB per session). A reply cut short by a limit carries the header `nctwin-limit`. Counts and rates (defaults, each a flag of `nctwin`): 1000 sessions, 100 per client address, 64 stream clients per session, 50 commands per second per session in bursts of 100 (NC stop, reset and JOG stop are never refused), 4 MiB of program text per second per session syntax-checked in bursts of 8 MiB; a refusal is `429` (with `Retry-After` for the rates). A fast run stopped by its simulated-time limit says `nctwin-limit: fast-sim-time`, by its wall-time limit `fast-wall-time`; a `wait: true` request ended by its wall time `wait-wall-time`. A request answered because the server is shutting down is `503` with `Retry-After`.\n\nCross-site requests: JSON bodies need `Content-Type: application/json` (else `415`). The server answers only requests for its own address, `localhost`, `127.0.0.1` and `[::1]` with its port, and the names given with `nctwin --allow-host`; a request from a web page (its `Origin`, WebSocket upgrades included) only from the server's own origin and those given with `nctwin --allow-origin`; others are `403`.\n\nAuthentication: creating a session returns an owner token and two tokens to share (operator, observer). By default (`nctwin --auth off`) no token is needed. With `nctwin --auth required` every request to a session needs `Authorization: Bearer <token>` (the WebSocket stream may pass `?token=`): `401` without a valid token; observers read but every command is `403`; commands need control (`POST .../control/take`; the owner holds it first and can always take it back), otherwise `409`.\n\nSeveral nodes (`nctwin --database postgres://... --node-id NAME`): each node serves the sessions it holds a lease on (renewed while it runs, given up at shutdown). A request for a session another node holds is `421 Misdirected Request` naming that node; a session whose node stopped renewing is taken over by the next node it is asked of. `GET /sessions` lists the sessions of the node asked.\n\nErrors are JSON `{\"error\": \"...\", \"line\": n}` (`line` only when the error belongs to one line).",
        license(name = "MIT"),
    ),
    // What a client may send on the stream (not a request body of any path).
    components(schemas(crate::dto::ClientMessage)),
    tags(
        (name = "health", description = "Liveness"),
        (name = "machines", description = "Built-in machine presets"),
        (name = "sessions", description = "Sessions: one simulated NC channel each"),
        (name = "program", description = "Program control: run, start, stop, reset, MDA, mode"),
        (name = "jog", description = "Moving axes by hand"),
        (name = "programs", description = "Stored programs (called by name as subprograms) and syntax checks"),
        (name = "stream", description = "Live state and events over WebSocket"),
        (name = "control", description = "Who holds control of a session (with `--auth required`)"),
    )
)]
struct ApiDoc;

/// The API routes with the OpenAPI document attached (before [`finish`]).
pub fn router(limits: &Limits) -> OpenApiRouter<AppState> {
    OpenApiRouter::with_openapi(ApiDoc::openapi()).merge(api::router(limits))
}

/// The OpenAPI document, as served.
pub fn document() -> utoipa::openapi::OpenApi {
    finish(router(&Limits::default()).into_openapi())
}

/// Adds what follows from the access policy ([`access::need`]) to every operation on a
/// session, so the document and the middleware cannot disagree: the optional bearer security
/// scheme, `401`, `403` where a role can be refused, `421` (another node holds the session),
/// `503` (the server is shutting down), for commands `409` (not holding control) and, unless
/// they stop motion ([`access::rate_limited`]), `429` (rate limit, with `Retry-After`). Every
/// operation with a JSON request body gets `415` (not sent as JSON).
pub fn finish(document: utoipa::openapi::OpenApi) -> utoipa::openapi::OpenApi {
    let mut doc = match serde_json::to_value(&document) {
        Ok(doc) => doc,
        Err(_) => return document,
    };
    let error = |description: &str| {
        json!({
            "description": description,
            "content": {"application/json": {"schema": {"$ref": "#/components/schemas/ErrorBody"}}}
        })
    };
    doc["components"]["securitySchemes"]["bearer"] = json!({
        "type": "http",
        "scheme": "bearer",
        "description": "A session token (`nct_` + 32 hex digits) from `POST /sessions`. Needed only when the server runs with `--auth required`."
    });
    if let Some(paths) = doc["paths"].as_object_mut() {
        for (path, item) in paths.iter_mut() {
            let Some(item) = item.as_object_mut() else { continue };
            for (method, operation) in item.iter_mut() {
                let Ok(method) = method.to_ascii_uppercase().parse::<Method>() else { continue };
                if operation["requestBody"]["content"].get("application/json").is_some()
                    && operation["responses"].get("415").is_none()
                {
                    operation["responses"]["415"] =
                        error("A body that is not sent as JSON (`Content-Type: application/json`)");
                }
                let Some(need) = access::need(&method, path) else { continue };
                operation["security"] = json!([{}, {"bearer": []}]);
                let responses = &mut operation["responses"];
                let mut add = |status: &str, response: Value| {
                    if responses.get(status).is_none() {
                        responses[status] = response;
                    }
                };
                add("401", error("No token, or a token not of this session (auth required only)"));
                // Every operation on a session passes `AppState::find_entry`, as the middleware does.
                add(
                    "421",
                    error(
                        "Several nodes on one database (`--database`): another node holds the session's lease; the message names it",
                    ),
                );
                if need != Need::Read {
                    add(
                        "403",
                        error(
                            "The token's role may not do this: observers change nothing; only the owner deletes (auth required only)",
                        ),
                    );
                }
                let mut shutting_down = error("The server is shutting down; retry once it is back");
                shutting_down["headers"] = json!({"retry-after": {
                    "description": "Seconds after which to retry",
                    "schema": {"type": "integer", "minimum": 1}
                }});
                add("503", shutting_down);
                if need == Need::Command {
                    add("409", error("The caller does not hold control (auth required only)"));
                }
                if access::rate_limited(&method, path) {
                    let mut too_many = error("More commands per second than the session allows");
                    too_many["headers"] = json!({"retry-after": {
                        "description": "Seconds until a command is accepted again",
                        "schema": {"type": "integer", "minimum": 1}
                    }});
                    add("429", too_many);
                }
            }
        }
    }
    serde_json::from_value(doc).unwrap_or(document)
}

/// The document as committed: pretty-printed JSON with a trailing newline.
pub fn document_text() -> String {
    let mut text = document().to_pretty_json().unwrap_or_default();
    text.push('\n');
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fails when the generated document differs from the committed `openapi/openapi.json`.
    /// `NCTWIN_UPDATE_OPENAPI=1 cargo test -p nctwin-server openapi` rewrites the file.
    #[test]
    fn openapi_document_matches_the_committed_file() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(COMMITTED_PATH);
        let generated = document_text();
        if std::env::var_os("NCTWIN_UPDATE_OPENAPI").is_some() {
            std::fs::write(&path, &generated).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
            return;
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == generated,
            "{} is out of date with the handlers; regenerate it with\n    NCTWIN_UPDATE_OPENAPI=1 cargo test -p nctwin-server openapi\nand commit the result",
            path.display()
        );
    }

    #[test]
    fn openapi_document_is_version_3_1_and_documents_every_route() {
        let doc = document();
        let json = serde_json::to_value(&doc).expect("serializable");
        assert!(json["openapi"].as_str().is_some_and(|v| v.starts_with("3.1")));
        for path in ["/api/v1/health", "/api/v1/sessions/{id}/run", "/api/v1/sessions/{id}/stream"] {
            assert!(json["paths"].get(path).is_some(), "{path} documented");
        }
    }

    #[test]
    fn session_operations_document_the_access_policy() {
        let json = serde_json::to_value(document()).expect("serializable");
        assert_eq!(json["components"]["securitySchemes"]["bearer"]["scheme"], "bearer");
        let run = &json["paths"]["/api/v1/sessions/{id}/run"]["post"];
        for status in ["401", "403", "409", "421", "429"] {
            assert!(run["responses"].get(status).is_some(), "run documents {status}");
        }
        assert!(run["responses"]["429"]["headers"].get("retry-after").is_some());
        assert!(run["responses"].get("415").is_some(), "a JSON body");
        let stop = &json["paths"]["/api/v1/sessions/{id}/stop"]["post"];
        assert!(stop["responses"].get("429").is_none(), "stops are never rate-limited");
        assert!(stop["responses"].get("415").is_none(), "no body");
        let state = &json["paths"]["/api/v1/sessions/{id}/state"]["get"];
        assert!(state["responses"].get("401").is_some() && state["responses"].get("403").is_none());
        assert_eq!(state["security"], serde_json::json!([{}, {"bearer": []}]));
        assert!(json["paths"]["/api/v1/health"]["get"].get("security").is_none(), "health needs no token");
    }
}
