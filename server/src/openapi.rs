//! The OpenAPI 3.1 document, generated from the handlers' `#[utoipa::path]` annotations.
//!
//! It is served at `GET /api/v1/openapi.json` (with Swagger UI at `/api/docs`) and committed as
//! `openapi/openapi.json`; a test fails when the two differ
//! (`NCTWIN_UPDATE_OPENAPI=1 cargo test -p nctwin-server openapi` rewrites the file).

use utoipa::OpenApi;
use utoipa_axum::router::OpenApiRouter;

use crate::api;
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
        description = "Simulated SINUMERIK 840D sl-style NC channels: sessions, part programs, JOG, MDA, machine data and live state streams.\n\nUnits: lengths mm, angles degrees, feed mm/min, time s.\n\nServer-side limits: a `pace: \"fast\"` command runs at most 3600 s of simulated time (then NC stop); a `wait: true` request is answered after at most 600 s of wall time; request bodies are limited to 1 MiB. A reply cut short by a limit carries the header `nctwin-limit`.\n\nErrors are JSON `{\"error\": \"...\", \"line\": n}` (`line` only when the error belongs to one line).",
        license(name = "MIT"),
    ),
    tags(
        (name = "health", description = "Liveness"),
        (name = "machines", description = "Built-in machine presets"),
        (name = "sessions", description = "Sessions: one simulated NC channel each"),
        (name = "program", description = "Program control: run, start, stop, reset, MDA, mode"),
        (name = "jog", description = "Moving axes by hand"),
        (name = "programs", description = "Stored programs (called by name as subprograms) and syntax checks"),
        (name = "stream", description = "Live state and events over WebSocket"),
    )
)]
struct ApiDoc;

/// The API routes with the complete OpenAPI document attached.
pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::with_openapi(ApiDoc::openapi()).merge(api::router())
}

/// The OpenAPI document.
pub fn document() -> utoipa::openapi::OpenApi {
    router().into_openapi()
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
}
