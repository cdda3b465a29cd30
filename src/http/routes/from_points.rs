//! `POST /v1/curves/interpolate` (a curve through points) and `POST /v1/curves/approximate`
//! (a curve within a tolerance of points).

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::curve::CurveBody;
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::state::AppState;
use crate::http::wire::from_points::{
    ApproximateRequest, ApproximateResponse, InterpolateRequest, InterpolateResponse,
};
use crate::http::wire::toolkit_parse::{
    approximation_error, interpolation_error, parse_end_tangents, parse_points,
};
use crate::spline::{
    ApproximationSpec, CurveLimits, InterpolationSpec, ParameterChoice, Parametrization,
    approximate as approximate_points, interpolate as interpolate_points,
};

/// The degree when a request gives none.
const DEFAULT_DEGREE: usize = 3;

/// Interpolate points.
///
/// The curve of the given degree through every point (The NURBS Book §9.2): parameters by
/// chord length, centripetal, uniform or given; knots by averaging or given; optional end
/// tangents; open, or closed with `C^{degree−1}` continuity across the seam. A banded
/// solve, `O(points · degree²)`.
#[utoipa::path(
    post,
    path = "/v1/curves/interpolate",
    tag = "curves",
    request_body = InterpolateRequest,
    responses(
        (status = 200, description = "The interpolating curve", body = InterpolateResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn interpolate(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<InterpolateRequest>,
) -> Result<ApiJson<InterpolateResponse>, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    let degree = request.degree.unwrap_or(DEFAULT_DEGREE).saturating_add(1);
    let work = request
        .points
        .len()
        .saturating_mul(degree.saturating_mul(degree));
    compute(admission, work, move || {
        interpolate_request(&request, &limits, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn interpolate_request(
    request: &InterpolateRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<InterpolateResponse, ApiError> {
    let points = parse_points(&request.points, limits.max_fit_points)?;
    let end_tangents = parse_end_tangents(request.end_tangents.as_deref(), points.dimension())?;
    let parameters = match (&request.parameters, request.parametrization) {
        (Some(_), Some(_)) => {
            return Err(ApiError::invalid(
                "/parameters",
                "give either `parameters` or `parametrization`, not both",
            ));
        }
        (Some(given), None) => ParameterChoice::Given(given),
        (None, kind) => ParameterChoice::By(kind.map_or(Parametrization::ChordLength, Into::into)),
    };
    let spec = InterpolationSpec {
        degree: request.degree.unwrap_or(DEFAULT_DEGREE),
        parameters,
        knots: request.knots.as_deref(),
        end_tangents,
        closed: request.closed.unwrap_or(false),
    };
    let interpolation = interpolate_points(&points, &spec, curve_limits)
        .map_err(|error| interpolation_error(&error, request.parameters.is_some()))?;
    Ok(InterpolateResponse {
        curve: CurveBody::from_curve(&interpolation.curve),
        parameters: interpolation.parameters,
    })
}

/// Approximate points.
///
/// A curve with as few control points as the method manages such that every point lies
/// within `tolerance` of it (least squares with Gauss–Newton parameter correction, knots
/// added where the error is large and removed where the budget allows), the distances
/// certified by the closest-point search; `max_error` is the largest.
#[utoipa::path(
    post,
    path = "/v1/curves/approximate",
    tag = "curves",
    request_body = ApproximateRequest,
    responses(
        (status = 200, description = "The approximating curve", body = ApproximateResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn approximate(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ApproximateRequest>,
) -> Result<ApiJson<ApproximateResponse>, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    let degree = request.degree.unwrap_or(DEFAULT_DEGREE).saturating_add(1);
    // Dozens of fits, each a few passes over the points.
    let work = request
        .points
        .len()
        .saturating_mul(degree.saturating_mul(degree))
        .saturating_mul(100);
    compute(admission, work, move || {
        approximate_request(&request, &limits, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn approximate_request(
    request: &ApproximateRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<ApproximateResponse, ApiError> {
    let points = parse_points(&request.points, limits.max_fit_points)?;
    let spec = ApproximationSpec {
        degree: request.degree.unwrap_or(DEFAULT_DEGREE),
        tolerance: request.tolerance,
        parametrization: request
            .parametrization
            .map_or(Parametrization::ChordLength, Into::into),
        end_points_exact: request.end_points_exact.unwrap_or(true),
    };
    let approximation = approximate_points(&points, &spec, curve_limits)
        .map_err(|error| approximation_error(&error))?;
    Ok(ApproximateResponse {
        curve: CurveBody::from_curve(&approximation.curve),
        max_error: approximation.max_error,
        parameters: approximation.parameters,
    })
}
