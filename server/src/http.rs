//! The HTTP application: API routes, OpenAPI/Swagger UI, the static HMI and the tower-http
//! layers that do the cross-cutting work.

use axum::Json;
use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::handler::HandlerWithoutStateExt;
use axum::http::header::{CONTENT_LENGTH, CONTENT_TYPE};
use axum::http::{StatusCode, Uri, Version};
use axum::middleware;
use axum::response::{IntoResponse, Response};
use tower_http::compression::CompressionLayer;
use tower_http::compression::predicate::{DefaultPredicate, Predicate};
use tower_http::cors::CorsLayer;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::services::ServeDir;
use tower_http::trace::TraceLayer;
use utoipa_swagger_ui::SwaggerUi;

use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::openapi;
use crate::state::AppState;

/// Largest request body accepted: 1 MiB (larger is `413`).
pub const BODY_LIMIT: usize = 1 << 20;

/// See [`crate::app`].
pub fn app(state: AppState) -> Router {
    let (api, document) = openapi::router().split_for_parts();
    let hmi = ServeDir::new(state.web_dir())
        .call_fallback_on_method_not_allowed(true)
        .not_found_service(not_found.into_service());
    // A WebSocket upgrade has no body to compress.
    let compress = DefaultPredicate::new().and(
        |status: StatusCode, _: Version, _: &axum::http::HeaderMap, _: &axum::http::Extensions| {
            status != StatusCode::SWITCHING_PROTOCOLS
        },
    );
    Router::new()
        .merge(api.with_state(state))
        .merge(SwaggerUi::new(openapi::SWAGGER_UI_PATH).url(openapi::DOCUMENT_PATH, document))
        .fallback_service(hmi)
        .layer(DefaultBodyLimit::max(BODY_LIMIT))
        .layer(RequestBodyLimitLayer::new(BODY_LIMIT))
        .layer(middleware::map_response(json_errors))
        .layer(CompressionLayer::new().compress_when(compress))
        .layer(CorsLayer::permissive())
        .layer(TraceLayer::new_for_http())
}

/// Unknown routes and missing files.
async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(uri.path().to_string())
}

/// Gives errors produced outside the handlers (405 from the router, 413 from the body limit,
/// 503 from a timeout, 400 from axum's extractors, ...) the same JSON shape as [`ApiError`].
async fn json_errors(response: Response) -> Response {
    let status = response.status();
    if !(status.is_client_error() || status.is_server_error()) {
        return response;
    }
    let is_json = response
        .headers()
        .get(CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.starts_with("application/json"));
    if is_json {
        return response;
    }
    let body = if status == StatusCode::PAYLOAD_TOO_LARGE {
        ApiError::PayloadTooLarge(BODY_LIMIT).body()
    } else {
        let reason = status.canonical_reason().unwrap_or("error").to_lowercase();
        ErrorBody { error: reason, line: None }
    };
    let (mut parts, _) = response.into_parts();
    parts.headers.remove(CONTENT_TYPE);
    parts.headers.remove(CONTENT_LENGTH);
    let mut json = Json(body).into_response();
    for (name, value) in parts.headers.iter() {
        json.headers_mut().insert(name.clone(), value.clone());
    }
    *json.status_mut() = status;
    json
}
