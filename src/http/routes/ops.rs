//! Operational routes, open to probes even when an API key is set: liveness, readiness,
//! Prometheus metrics and the OpenAPI document.

use axum::extract::State;
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::metrics::METRICS_CONTENT_TYPE;
use crate::http::state::AppState;

/// The state reported by a probe.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"status": "ok"}))]
pub struct ProbeStatus {
    /// `ok` (liveness) or `ready` (readiness).
    pub status: String,
}

/// Liveness: the process serves requests.
#[utoipa::path(
    get,
    path = "/healthz",
    tag = "operations",
    responses((status = 200, description = "The process is alive", body = ProbeStatus)),
)]
pub async fn healthz() -> ApiJson<ProbeStatus> {
    ApiJson(ProbeStatus {
        status: "ok".to_owned(),
    })
}

/// Readiness: 503 once shutdown has begun (in-flight requests still finish).
#[utoipa::path(
    get,
    path = "/readyz",
    tag = "operations",
    responses(
        (status = 200, description = "Ready for traffic", body = ProbeStatus),
        (status = 503, description = "Draining before shutdown", body = Problem, content_type = "application/problem+json"),
    ),
)]
pub async fn readyz(State(state): State<AppState>) -> Result<ApiJson<ProbeStatus>, ApiError> {
    if state.readiness.is_ready() {
        Ok(ApiJson(ProbeStatus {
            status: "ready".to_owned(),
        }))
    } else {
        Err(ApiError::ShuttingDown {
            retry_after_secs: state.retry_after_secs,
        })
    }
}

/// Prometheus metrics (OpenMetrics text): requests by method, matched route and status,
/// latency histograms, requests in flight.
#[utoipa::path(
    get,
    path = "/metrics",
    tag = "operations",
    responses((status = 200, description = "Metrics in OpenMetrics text format", body = String, content_type = "application/openmetrics-text")),
)]
pub async fn metrics(State(state): State<AppState>) -> Response {
    let mut response = state.metrics.encode().into_response();
    response.headers_mut().insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static(METRICS_CONTENT_TYPE),
    );
    response
}

/// This service's OpenAPI document (the same as `openapi/openapi.json`).
#[utoipa::path(
    get,
    path = "/openapi.json",
    tag = "operations",
    responses((status = 200, description = "The OpenAPI 3.1 document", body = serde_json::Value)),
)]
pub async fn openapi_json(State(state): State<AppState>) -> Response {
    let mut response = state.openapi_json.to_string().into_response();
    response.headers_mut().insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("application/json"),
    );
    response
}
