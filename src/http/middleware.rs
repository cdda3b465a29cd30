//! Middleware of the HTTP edge: API key check, admission (load shedding and draining), metrics,
//! trace spans, problem documents for bare error responses, the panic responder and the
//! 404/405 fallbacks.

use std::any::Any;
use std::convert::Infallible;
use std::future::{Ready, ready};
use std::sync::Arc;
use std::task::{Context, Poll};
use std::time::{Duration, Instant};

use axum::body::Body;
use axum::extract::{MatchedPath, Request, State};
use axum::http::{HeaderValue, Method, StatusCode, Uri, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use futures_util::future::Either;
use subtle::ConstantTimeEq;
use tokio::sync::OwnedSemaphorePermit;
use tower::{Layer, Service};
use tower_http::catch_panic::ResponseForPanic;
use tracing::Span;

use super::error::{ApiError, PROBLEM_JSON, Problem};
use super::metrics::{Metrics, UNMATCHED_ROUTE};
use super::state::AppState;

/// The gate of every `/v1` request, one layer: first the API key ([`check_api_key`], 401),
/// then admission ([`admit`], 503). The admission permit rides along in the request's
/// extensions as an [`AdmissionPermit`].
///
/// A plain [`Layer`] rather than `axum::middleware::from_fn`: the check is synchronous, so
/// the route is called directly, without the per-request clone of the boxed route and the
/// boxed future that `from_fn` costs.
#[derive(Debug, Clone)]
pub struct GuardV1Layer {
    state: AppState,
}

impl GuardV1Layer {
    /// The gate for routes served with `state`.
    pub fn new(state: AppState) -> Self {
        GuardV1Layer { state }
    }
}

impl<S> Layer<S> for GuardV1Layer {
    type Service = GuardV1<S>;

    fn layer(&self, inner: S) -> GuardV1<S> {
        GuardV1 {
            inner,
            state: self.state.clone(),
        }
    }
}

/// The service of [`GuardV1Layer`] around one route.
#[derive(Debug, Clone)]
pub struct GuardV1<S> {
    inner: S,
    state: AppState,
}

impl<S> Service<Request> for GuardV1<S>
where
    S: Service<Request, Response = Response, Error = Infallible>,
{
    type Response = Response;
    type Error = Infallible;
    type Future = Either<Ready<Result<Response, Infallible>>, S::Future>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), Infallible>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, mut request: Request) -> Self::Future {
        match check_api_key(&self.state, &request).and_then(|()| admit(&self.state)) {
            Ok(permit) => {
                request.extensions_mut().insert(permit);
                Either::Right(self.inner.call(request))
            }
            Err(refusal) => Either::Left(ready(Ok(refusal.into_response()))),
        }
    }
}

/// Refuses a request without the configured API key (401); passes all when none is set.
/// The key is compared in constant time.
fn check_api_key(state: &AppState, request: &Request) -> Result<(), ApiError> {
    if let Some(expected) = &state.api_key {
        let presented = request
            .headers()
            .get(header::AUTHORIZATION)
            .and_then(|value| value.to_str().ok())
            .and_then(bearer_token);
        let authorized =
            presented.is_some_and(|token| bool::from(token.as_bytes().ct_eq(expected.as_bytes())));
        if !authorized {
            return Err(ApiError::Unauthorized);
        }
    }
    Ok(())
}

/// The token of an `Authorization: Bearer <token>` header value (scheme case-insensitive).
fn bearer_token(value: &str) -> Option<&str> {
    let (scheme, token) = value.trim().split_once(' ')?;
    scheme
        .eq_ignore_ascii_case("bearer")
        .then(|| token.trim())
        .filter(|token| !token.is_empty())
}

/// One `/v1` request's share of the concurrency limit; released when the last clone drops
/// (the request's and, for computing handlers, the blocking work's).
#[derive(Debug, Clone)]
pub struct AdmissionPermit {
    _permit: Arc<OwnedSemaphorePermit>,
}

/// Admits a request only while the service is ready and below its concurrency limit;
/// otherwise answers 503 with `Retry-After` at once instead of queueing.
fn admit(state: &AppState) -> Result<AdmissionPermit, ApiError> {
    let retry_after_secs = state.retry_after_secs;
    if !state.readiness.is_ready() {
        return Err(ApiError::ShuttingDown { retry_after_secs });
    }
    let Ok(permit) = state.admission.clone().try_acquire_owned() else {
        return Err(ApiError::Overloaded { retry_after_secs });
    };
    Ok(AdmissionPermit {
        _permit: Arc::new(permit),
    })
}

/// Counts the request by method, matched route and status, and observes its latency.
pub async fn record_metrics(
    State(metrics): State<Metrics>,
    request: Request,
    next: Next,
) -> Response {
    let route = matched_route(&request).to_owned();
    let method = request.method().clone();
    let _in_flight = metrics.start_request();
    let started = Instant::now();
    let response = next.run(request).await;
    metrics.record(
        &method,
        &route,
        response.status().as_u16(),
        started.elapsed(),
    );
    response
}

/// The matched route template of a request, or `unmatched`.
fn matched_route<B>(request: &axum::http::Request<B>) -> &str {
    request
        .extensions()
        .get::<MatchedPath>()
        .map_or(UNMATCHED_ROUTE, MatchedPath::as_str)
}

/// The tracing span of one request: method and matched route now, status and latency when
/// the response is ready.
pub fn request_span(request: &axum::http::Request<Body>) -> Span {
    tracing::info_span!(
        "http_request",
        method = %request.method(),
        route = matched_route(request),
        status = tracing::field::Empty,
        latency_ms = tracing::field::Empty,
    )
}

/// Records status and latency in the request's span and logs the finished request.
pub fn record_response(response: &Response, latency: Duration, span: &Span) {
    let status = response.status().as_u16();
    let latency_ms = latency.as_secs_f64() * 1e3;
    span.record("status", status);
    span.record("latency_ms", latency_ms);
    if response.status().is_server_error() {
        tracing::warn!(status, latency_ms, "request failed");
    } else {
        tracing::info!(status, latency_ms, "request finished");
    }
}

/// Seconds sent with `Retry-After` on a 503.
#[derive(Debug, Clone, Copy)]
pub struct RetryAfter(pub u64);

/// Turns an error response that is not yet a problem document (the timeout's empty 503, or
/// any other bare error from a layer) into one, keeping its status and headers.
pub async fn problem_for_bare_errors<B>(
    State(RetryAfter(retry_after_secs)): State<RetryAfter>,
    response: Response<B>,
) -> Response
where
    B: axum::body::HttpBody<Data = axum::body::Bytes> + Send + 'static,
    B::Error: Into<axum::BoxError>,
{
    let status = response.status();
    if !(status.is_client_error() || status.is_server_error()) {
        return response.into_response();
    }
    let is_problem = response
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|value| value.as_bytes().starts_with(PROBLEM_JSON.as_bytes()));
    if is_problem {
        return response.into_response();
    }
    let detail = match status {
        StatusCode::SERVICE_UNAVAILABLE => {
            "the request did not complete within the configured time limit"
        }
        StatusCode::PAYLOAD_TOO_LARGE => "the request body exceeds the configured limit",
        _ => "the request could not be served",
    };
    let (mut parts, _) = response.into_parts();
    let mut problem = Problem::for_status(status, detail).into_response();
    parts.headers.remove(header::CONTENT_LENGTH);
    parts.headers.remove(header::CONTENT_ENCODING);
    parts
        .headers
        .insert(header::CONTENT_TYPE, HeaderValue::from_static(PROBLEM_JSON));
    if status == StatusCode::SERVICE_UNAVAILABLE && !parts.headers.contains_key(header::RETRY_AFTER)
    {
        parts
            .headers
            .insert(header::RETRY_AFTER, HeaderValue::from(retry_after_secs));
    }
    *problem.headers_mut() = parts.headers;
    problem
}

/// Answers a panic in a handler with a 500 problem document and logs it.
#[derive(Debug, Clone, Copy, Default)]
pub struct PanicResponder;

impl ResponseForPanic for PanicResponder {
    type ResponseBody = Body;

    fn response_for_panic(&mut self, payload: Box<dyn Any + Send + 'static>) -> Response<Body> {
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("(no message)");
        tracing::error!(panic = message, "request handler panicked");
        ApiError::Internal(message.to_owned()).into_response()
    }
}

/// The fallback for paths no route matches: 404.
pub async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound {
        path: uri.path().to_owned(),
    }
}

/// The fallback for a known path with a method it does not serve: 405 (axum adds `Allow`).
pub async fn method_not_allowed(method: Method) -> ApiError {
    ApiError::MethodNotAllowed {
        method: method.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::Router;
    use axum::routing::get;
    use tower::ServiceExt;

    async fn body_json(response: Response) -> serde_json::Value {
        let bytes = axum::body::to_bytes(response.into_body(), 1 << 20)
            .await
            .unwrap();
        serde_json::from_slice(&bytes).unwrap()
    }

    #[tokio::test]
    async fn a_panicking_handler_is_answered_with_a_500_problem() {
        async fn explode() -> &'static str {
            panic!("boom")
        }
        let router = Router::new().route("/explode", get(explode)).layer(
            tower_http::catch_panic::CatchPanicLayer::custom(PanicResponder),
        );
        let request = axum::http::Request::get("/explode")
            .body(Body::empty())
            .unwrap();
        let response = router.oneshot(request).await.unwrap();
        assert_eq!(response.status(), StatusCode::INTERNAL_SERVER_ERROR);
        assert_eq!(response.headers()[header::CONTENT_TYPE], PROBLEM_JSON);
        let body = body_json(response.into_response()).await;
        assert_eq!(body["status"], 500);
        assert!(
            !body["detail"].as_str().unwrap().contains("boom"),
            "no internals leak"
        );
    }

    #[tokio::test]
    async fn bare_error_responses_become_problem_documents() {
        let bare = (StatusCode::SERVICE_UNAVAILABLE, "").into_response();
        let response = problem_for_bare_errors(State(RetryAfter(3)), bare).await;
        assert_eq!(response.status(), StatusCode::SERVICE_UNAVAILABLE);
        assert_eq!(response.headers()[header::CONTENT_TYPE], PROBLEM_JSON);
        assert_eq!(response.headers()[header::RETRY_AFTER], "3");
        assert_eq!(body_json(response).await["status"], 503);
        let fine = (StatusCode::OK, "fine").into_response();
        let response = problem_for_bare_errors(State(RetryAfter(3)), fine).await;
        assert_eq!(response.status(), StatusCode::OK);
    }

    #[test]
    fn bearer_tokens_are_parsed() {
        assert_eq!(bearer_token("Bearer abc"), Some("abc"));
        assert_eq!(bearer_token("bearer   abc "), Some("abc"));
        assert_eq!(bearer_token("Basic abc"), None);
        assert_eq!(bearer_token("Bearer "), None);
        assert_eq!(bearer_token("abc"), None);
    }
}
