//! The HTTP application: API routes, OpenAPI/Swagger UI, the static HMI and the tower-http
//! layers that do the cross-cutting work.

use std::net::SocketAddr;
use std::sync::Arc;

use axum::Json;
use axum::Router;
use axum::extract::Request;
use axum::handler::HandlerWithoutStateExt;
use axum::http::header::{CONTENT_LENGTH, CONTENT_TYPE};
use axum::http::{StatusCode, Uri, Version};
use axum::middleware;
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use tower_http::compression::CompressionLayer;
use tower_http::compression::predicate::{DefaultPredicate, Predicate};
use tower_http::services::ServeDir;
use tower_http::trace::TraceLayer;
use utoipa_swagger_ui::SwaggerUi;

use crate::auth::access;
use crate::dto::ErrorBody;
use crate::error::ApiError;
use crate::extract;
use crate::metrics;
use crate::openapi;
use crate::site::{self, SitePolicy};
use crate::state::AppState;

/// Where the Prometheus metrics are served (outside `/api/v1`, where scrapers look).
pub const METRICS_PATH: &str = "/metrics";

/// See [`crate::app`]. Body limits are per route group (see [`crate::api::router`]).
/// `bound` is the listener's address (the `Host` check needs its port; without it any port
/// of the loopback names and address literals passes, see [`site`]).
pub fn app(state: AppState, bound: Option<SocketAddr>) -> Router {
    let site = Arc::new(SitePolicy::new(bound, &state.config().allow_hosts, &state.config().allow_origins));
    let (api, document) = openapi::router(state.limits()).split_for_parts();
    let document = openapi::finish(document);
    // Route layers run after routing, so they see the route template (`MatchedPath`): the
    // access check applies the policy by template, the metrics count by it. Metrics is outer,
    // so refusals are counted too.
    let api = api
        .route_layer(middleware::from_fn_with_state(state.clone(), access::layer))
        .route_layer(middleware::from_fn_with_state(state.clone(), metrics::track));
    let hmi = ServeDir::new(state.web_dir())
        .call_fallback_on_method_not_allowed(true)
        .not_found_service(not_found.into_service());
    // A WebSocket upgrade has no body to compress.
    let compress = DefaultPredicate::new().and(
        |status: StatusCode, _: Version, _: &axum::http::HeaderMap, _: &axum::http::Extensions| {
            status != StatusCode::SWITCHING_PROTOCOLS
        },
    );
    let metrics = Router::new().route(METRICS_PATH, get(metrics::metrics)).with_state(state.clone());
    let state_for_cluster = state.clone();
    // The span names the path without the query: a stream's `?token=` stays out of the logs.
    let trace = TraceLayer::new_for_http().make_span_with(
        |request: &Request| tracing::info_span!("request", method = %request.method(), path = %request.uri().path()),
    );
    Router::new()
        .merge(api.with_state(state))
        .merge(metrics)
        .merge(SwaggerUi::new(openapi::SWAGGER_UI_PATH).url(openapi::DOCUMENT_PATH, document))
        .fallback_service(hmi)
        .layer(middleware::map_response(json_errors))
        .layer(middleware::from_fn_with_state(state_for_cluster, crate::cluster::layer))
        .layer(CompressionLayer::new().compress_when(compress))
        .layer(site.cors())
        .layer(middleware::from_fn_with_state(site, site::guard))
        .layer(middleware::from_fn(extract::close_unread))
        .layer(trace)
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
        ErrorBody {
            error: "request body is larger than the limit".into(),
            line: None,
            errors: Vec::new(),
            errors_omitted: 0,
        }
    } else {
        let reason = status.canonical_reason().unwrap_or("error").to_lowercase();
        ErrorBody { error: reason, line: None, errors: Vec::new(), errors_omitted: 0 }
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
