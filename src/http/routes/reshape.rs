//! `POST /v1/curves/elevate-degree`, `/v1/curves/remove-knots` and `/v1/curves/split`: the
//! same curve written otherwise (higher degree, fewer knots, pieces).

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::curve::CurveBody;
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::state::AppState;
use crate::http::wire::reshape::{
    ElevateDegreeRequest, ElevateDegreeResponse, RemoveKnotsRequest, RemoveKnotsResponse,
    SplitRequest, SplitResponse,
};
use crate::http::wire::toolkit_parse::{elevate_error, remove_error, split_error};
use crate::spline::CurveLimits;

/// Elevate the degree.
///
/// The same curve with a higher degree (The NURBS Book A5.9: Bézier pieces raised, then the
/// knots removed again that the continuity allows), rational and 3D curves included.
#[utoipa::path(
    post,
    path = "/v1/curves/elevate-degree",
    tag = "curves",
    request_body = ElevateDegreeRequest,
    responses(
        (status = 200, description = "The elevated curve", body = ElevateDegreeResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn elevate_degree(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ElevateDegreeRequest>,
) -> Result<ApiJson<ElevateDegreeResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    let degree = request.degree.saturating_add(1);
    let work = request
        .curve
        .control_points
        .len()
        .saturating_mul(degree.saturating_mul(degree));
    compute(admission, work, move || {
        let curve = request.curve.parse(&curve_limits, "/curve")?;
        let elevated = curve
            .elevate_degree(
                request.degree,
                curve_limits.max_degree,
                curve_limits.max_control_points,
            )
            .map_err(|error| elevate_error(&error))?;
        Ok(ElevateDegreeResponse {
            curve: CurveBody::from_curve(&elevated),
        })
    })
    .await
    .map(ApiJson)
}

/// Remove knots within a tolerance.
///
/// Removes as many interior knots as it can (The NURBS Book A5.8) while the curve moves at
/// most `tolerance`, certified by a bound from the control points; tolerance 0 removes only
/// the exactly removable knots.
#[utoipa::path(
    post,
    path = "/v1/curves/remove-knots",
    tag = "curves",
    request_body = RemoveKnotsRequest,
    responses(
        (status = 200, description = "The curve with fewer knots", body = RemoveKnotsResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn remove_knots(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<RemoveKnotsRequest>,
) -> Result<ApiJson<RemoveKnotsResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    let degree = request.curve.degree.saturating_add(1);
    // Each round tries every knot (degree² per try) and may shift the control points.
    let count = request.curve.control_points.len();
    let work = count
        .saturating_mul(degree.saturating_mul(degree).saturating_add(count / 64))
        .saturating_mul(4);
    compute(admission, work, move || {
        let curve = request.curve.parse(&curve_limits, "/curve")?;
        let removal = curve
            .remove_knots(request.tolerance, request.knots.as_deref())
            .map_err(|error| remove_error(&error))?;
        Ok(RemoveKnotsResponse {
            curve: CurveBody::from_curve(&removal.curve),
            removed: removal.removed,
            max_deviation: removal.max_deviation,
        })
    })
    .await
    .map(ApiJson)
}

/// Split a curve.
///
/// The curve cut at the given parameters into clamped pieces that together are the curve
/// (each cut inserted to multiplicity `degree`).
#[utoipa::path(
    post,
    path = "/v1/curves/split",
    tag = "curves",
    request_body = SplitRequest,
    responses(
        (status = 200, description = "The pieces", body = SplitResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn split(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SplitRequest>,
) -> Result<ApiJson<SplitResponse>, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    let degree = request.curve.degree.saturating_add(1);
    let work = (request.curve.control_points.len() + request.parameters.len())
        .saturating_mul(degree.saturating_mul(degree));
    compute(admission, work, move || {
        split_request(&request, &limits, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn split_request(
    request: &SplitRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<SplitResponse, ApiError> {
    let curve = request.curve.parse(curve_limits, "/curve")?;
    let pieces = curve
        .split_at(&request.parameters, limits.max_parameters)
        .map_err(|error| split_error(&error))?;
    Ok(SplitResponse {
        curves: pieces.iter().map(CurveBody::from_curve).collect(),
    })
}
