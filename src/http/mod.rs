//! The HTTP edge: routes, request/response types, errors as problem documents, middleware,
//! metrics, the OpenAPI document and the server with graceful shutdown.
//!
//! Request bodies are parsed into validated core types once, here; the geometry core never
//! sees wire types, and answers use the caller's knot convention.

pub mod curve;
pub mod error;
pub mod extract;
pub mod metrics;
pub mod middleware;
pub mod openapi_rules;
pub mod pointer;
pub mod regions_media;
pub mod regions_svg;
pub mod routes;
pub mod server;
pub mod state;
pub mod surface;
pub mod svg_path;
pub mod wire;

use std::sync::Arc;

use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::http::{HeaderValue, Method, StatusCode, header};
use tower::ServiceBuilder;
use tower_http::catch_panic::CatchPanicLayer;
use tower_http::compression::CompressionLayer;
use tower_http::cors::{AllowOrigin, CorsLayer};
use tower_http::timeout::TimeoutLayer;
use tower_http::trace::TraceLayer;
use utoipa::openapi::security::{HttpAuthScheme, HttpBuilder, SecurityScheme};
use utoipa::openapi::{ContentBuilder, OpenApi as OpenApiDocument, Ref, RefOr, ResponseBuilder};
use utoipa::{Modify, OpenApi};
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use crate::config::Config;
use error::{FieldError, PROBLEM_JSON, Problem};
use routes::{closest, curves, editor, files, ops, shape, toolkit};
use routes::{from_points, length, reshape};
use routes::{surface_closest, surface_edit, surface_mesh, surface_toolkit, surfaces};
pub use server::{Server, shutdown_signal};
pub use state::{AppState, Readiness};

/// The router serving every route, with fresh readiness (always ready).
pub fn app(config: &Config) -> Router {
    app_with_readiness(config, Readiness::new())
}

/// The router serving every route; `readiness` is shared with whoever drives shutdown
/// (`/readyz` and `/v1` answer 503 once it starts draining).
pub fn app_with_readiness(config: &Config, readiness: Readiness) -> Router {
    let openapi_json: Arc<str> = openapi_json().into();
    app_with_state(config, AppState::new(config, readiness, openapi_json))
}

/// The router serving every route with `state`, which its creator shares (the server reports
/// connection metrics through `state.metrics`).
pub fn app_with_state(config: &Config, state: AppState) -> Router {
    let v1 = v1_routes().route_layer(middleware::GuardV1Layer::new(state.clone()));
    let (router, _) = OpenApiRouter::with_openapi(ApiDoc::openapi())
        .merge(v1)
        .merge(ops_routes())
        .split_for_parts();

    let cors = cors_layer(&config.cors_allow_origins);
    router
        .merge(editor::router())
        .fallback(middleware::not_found)
        .method_not_allowed_fallback(middleware::method_not_allowed)
        .layer(
            ServiceBuilder::new()
                .layer(
                    TraceLayer::new_for_http()
                        .make_span_with(middleware::request_span)
                        .on_response(middleware::record_response)
                        .on_failure(()),
                )
                .layer(axum::middleware::from_fn_with_state(
                    state.metrics.clone(),
                    middleware::record_metrics,
                ))
                .layer(CatchPanicLayer::custom(middleware::PanicResponder))
                .layer(axum::middleware::map_response_with_state(
                    middleware::RetryAfter(config.retry_after_secs),
                    middleware::problem_for_bare_errors,
                ))
                .layer(TimeoutLayer::with_status_code(
                    StatusCode::SERVICE_UNAVAILABLE,
                    config.request_timeout(),
                ))
                .layer(DefaultBodyLimit::max(config.max_body_bytes))
                .layer(CompressionLayer::new())
                .option_layer(cors),
        )
        .with_state(state)
}

/// The `/v1` API routes (API key and admission layers are added by [`app_with_readiness`]).
fn v1_routes() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(curves::evaluate))
        .routes(routes!(curves::envelope))
        .routes(routes!(closest::closest_point))
        .routes(routes!(toolkit::insert_knots))
        .routes(routes!(toolkit::bezier))
        .routes(routes!(files::import))
        .routes(routes!(files::export))
        // The curve toolkit of the third release.
        .routes(routes!(from_points::interpolate))
        .routes(routes!(from_points::approximate))
        .routes(routes!(reshape::elevate_degree))
        .routes(routes!(reshape::remove_knots))
        .routes(routes!(reshape::split))
        .routes(routes!(length::length))
        .routes(routes!(shape::membership))
        .routes(routes!(shape::regions))
        .routes(routes!(shape::solve))
        // Surfaces (fourth release).
        .routes(routes!(surfaces::evaluate))
        .routes(routes!(surface_closest::closest_point))
        .routes(routes!(surface_toolkit::iso_curve))
        .routes(routes!(surface_toolkit::insert_knots))
        .routes(routes!(surface_toolkit::split))
        .routes(routes!(surface_mesh::tessellate))
        .routes(routes!(surface_edit::solve))
        .routes(routes!(surface_edit::regions))
}

/// Probe, metrics and document routes (always open).
fn ops_routes() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(ops::healthz))
        .routes(routes!(ops::readyz))
        .routes(routes!(ops::metrics))
        .routes(routes!(ops::openapi_json))
}

/// CORS for the configured origins; `None` (CORS off) when there are none.
fn cors_layer(origins: &[String]) -> Option<CorsLayer> {
    let origins: Vec<HeaderValue> = origins
        .iter()
        .map(|origin| origin.trim())
        .filter(|origin| !origin.is_empty())
        .filter_map(|origin| HeaderValue::from_str(origin).ok())
        .collect();
    (!origins.is_empty()).then(|| {
        CorsLayer::new()
            .allow_origin(AllowOrigin::list(origins))
            .allow_methods([Method::GET, Method::POST])
            .allow_headers([header::CONTENT_TYPE, header::AUTHORIZATION])
            .expose_headers([header::RETRY_AFTER])
    })
}

/// The OpenAPI document, generated from the routes and types.
pub fn openapi() -> OpenApiDocument {
    let mut document = OpenApiRouter::<AppState>::with_openapi(ApiDoc::openapi())
        .merge(v1_routes())
        .merge(ops_routes())
        .into_openapi();
    // After the merge, so that the paths exist.
    SecurityAndCommonErrors.modify(&mut document);
    document
}

/// The OpenAPI document as pretty JSON with a final newline (the form of
/// `openapi/openapi.json`).
///
/// The rules utoipa's derive cannot state (array lengths, exclusive minimums, answers without
/// `null`, ...) are written into it by [`openapi_rules::apply`].
pub fn openapi_json() -> String {
    let mut json = match serde_json::to_value(openapi()) {
        Ok(mut document) => {
            openapi_rules::apply(&mut document);
            serde_json::to_string_pretty(&document)
                .unwrap_or_else(|error| format!("{{\"error\": \"{error}\"}}"))
        }
        Err(error) => format!("{{\"error\": \"{error}\"}}"),
    };
    json.push('\n');
    json
}

#[derive(OpenApi)]
#[openapi(
    info(
        title = "knotshape",
        description = "Evaluates B-spline/NURBS curves and edits their shape by moving knots \
            (Juhász & Hoffmann; Tornai's knot pairs Ω1–Ω6). Every error is an RFC 9457 \
            `application/problem+json` document; validation errors list JSON pointers into \
            the request body. Knot vectors may be full or trimmed (openNURBS), detected by \
            length, or distinct values with multiplicities (STEP, Open CASCADE; also periodic); \
            answers use the caller's form."
    ),
    tags(
        (name = "curves", description = "Curve evaluation, polylines, knot insertion, Bézier pieces and the knot-moving envelope; curves through and near points, degree elevation, knot removal, splitting, arc length and curvature"),
        (name = "surfaces", description = "B-spline/NURBS surfaces: points, partials, normals and curvature, closest points, iso-curves, knot insertion, splitting and certified triangle meshes"),
        (name = "shape", description = "Shape modification by knot pairs Ω1–Ω6 (Tornai; Juhász & Hoffmann), control points and weights, under constraints"),
        (name = "operations", description = "Probes, metrics and this document; never need the API key"),
    ),
    components(schemas(Problem, FieldError)),
)]
struct ApiDoc;

/// Adds the bearer security scheme and the error responses every `/v1` operation can give.
struct SecurityAndCommonErrors;

impl Modify for SecurityAndCommonErrors {
    fn modify(&self, openapi: &mut OpenApiDocument) {
        let components = openapi.components.get_or_insert_with(Default::default);
        components.add_security_scheme(
            "api_key",
            SecurityScheme::Http(
                HttpBuilder::new()
                    .scheme(HttpAuthScheme::Bearer)
                    .description(Some(
                        "Needed on every /v1 route when the service is configured with an API key",
                    ))
                    .build(),
            ),
        );
        let common = [
            (
                "401",
                "An API key is configured and the request lacks it or has a wrong one",
            ),
            (
                "408",
                "The body arrived slower than the configured body timeout; the connection is closed",
            ),
            ("413", "The body exceeds the configured limit"),
            ("415", "The body is not sent as application/json"),
            (
                "503",
                "Overloaded, timed out or shutting down; see Retry-After",
            ),
        ];
        for (path, item) in openapi.paths.paths.iter_mut() {
            if !path.starts_with("/v1/") {
                continue;
            }
            for operation in [&mut item.post, &mut item.get].into_iter().flatten() {
                for (status, description) in common {
                    operation
                        .responses
                        .responses
                        .entry(status.to_owned())
                        .or_insert_with(|| RefOr::T(problem_response(description)));
                }
            }
        }
    }
}

/// A response description whose body is a [`Problem`].
fn problem_response(description: &str) -> utoipa::openapi::Response {
    ResponseBuilder::new()
        .description(description)
        .content(
            PROBLEM_JSON,
            ContentBuilder::new()
                .schema(Some(Ref::from_schema_name("Problem")))
                .build(),
        )
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::body::Body;
    use axum::http::Request;
    use tower::ServiceExt;

    #[tokio::test]
    async fn draining_turns_readiness_and_v1_into_503_but_not_liveness() {
        let readiness = Readiness::new();
        let router = app_with_readiness(&Config::default(), readiness.clone());
        let get = |path: &str| Request::get(path).body(Body::empty()).unwrap();
        let ready = router.clone().oneshot(get("/readyz")).await.unwrap();
        assert_eq!(ready.status(), StatusCode::OK);
        readiness.start_draining();
        let ready = router.clone().oneshot(get("/readyz")).await.unwrap();
        assert_eq!(ready.status(), StatusCode::SERVICE_UNAVAILABLE);
        assert!(ready.headers().contains_key(header::RETRY_AFTER));
        let health = router.clone().oneshot(get("/healthz")).await.unwrap();
        assert_eq!(health.status(), StatusCode::OK);
        let evaluate = Request::post("/v1/curves/evaluate")
            .header(header::CONTENT_TYPE, "application/json")
            .body(Body::from("{}"))
            .unwrap();
        let refused = router.oneshot(evaluate).await.unwrap();
        assert_eq!(refused.status(), StatusCode::SERVICE_UNAVAILABLE);
        assert_eq!(refused.headers()[header::CONTENT_TYPE], PROBLEM_JSON);
    }

    #[test]
    fn the_document_names_every_route() {
        let document = openapi();
        let paths: Vec<&String> = document.paths.paths.keys().collect();
        // Curves and service (14), the fourth release's curve additions (6), surfaces (6)
        // and the surface edit (2).
        assert_eq!(paths.len(), 14 + 6 + 6 + 2, "{paths:?}");
    }
}
