//! `POST /v1/curves/closest-point`: picking, a query point to the parameter of its closest
//! curve point ([`crate::spline::ClosestPointSearch`]).

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::curve::point_from_wire;
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::wire::closest::{ClosestPointRequest, ClosestPointResponse, ClosestPointResult};
use crate::spline::{ClosestPointError, ClosestPointSearch, CurveLimits, Point};

/// Estimated work of one query, in point evaluations, per Bézier piece of the curve (the
/// bounding-box pass visits every piece).
const WORK_PER_QUERY_AND_PIECE: usize = 1;

/// Closest points of a curve.
///
/// For each query point, the curve point nearest to it: the global minimum of the distance
/// over the curve or over `range`, the range's ends and the curve's corners included.
#[utoipa::path(
    post,
    path = "/v1/curves/closest-point",
    tag = "curves",
    request_body = ClosestPointRequest,
    responses(
        (status = 200, description = "The closest curve point of each query point", body = ClosestPointResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn closest_point(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ClosestPointRequest>,
) -> Result<ApiJson<ClosestPointResponse>, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    let pieces = request.curve.control_points.len();
    let work = pieces
        + request
            .points
            .len()
            .saturating_mul(pieces.saturating_mul(WORK_PER_QUERY_AND_PIECE) + 64);
    compute(admission, work, move || {
        closest_point_request(&request, &limits, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn closest_point_request(
    request: &ClosestPointRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<ClosestPointResponse, ApiError> {
    let mut errors = Vec::new();
    let curve =
        request
            .curve
            .parse_collecting_allowing_periodic(curve_limits, "/curve", &mut errors);
    let count = request.points.len();
    if count == 0 {
        errors.push(FieldError::new("/points", "give at least one query point"));
    } else if count > limits.max_parameters {
        errors.push(FieldError::new(
            "/points",
            format!(
                "{count} query points exceed the limit of {}",
                limits.max_parameters
            ),
        ));
    }
    let (Some(curve), true) = (curve, errors.is_empty()) else {
        return Err(ApiError::Invalid(errors));
    };
    let mut queries: Vec<Point> = Vec::with_capacity(count);
    for (index, point) in request.points.iter().enumerate() {
        let at = JsonPointer::from("/points").push(index);
        match point_from_wire(point, curve.dimension(), &at) {
            Ok(point) => queries.push(point),
            Err(ApiError::Invalid(point_errors)) => errors.extend(point_errors),
            Err(other) => return Err(other),
        }
        if errors.len() >= MAX_LISTED_ERRORS {
            break;
        }
    }
    let range = request.range.map(|[lo, hi]| (lo, hi));
    let search = match ClosestPointSearch::new(&curve, range) {
        Ok(search) => Some(search),
        Err(error) => {
            errors.push(range_error(&error));
            None
        }
    };
    let (Some(search), true) = (search, errors.is_empty()) else {
        return Err(ApiError::Invalid(errors));
    };
    let dimension = curve.dimension();
    let results = queries
        .iter()
        .map(|&q| ClosestPointResult::from_core(&search.closest(q), dimension))
        .collect();
    Ok(ClosestPointResponse { results })
}

/// Largest number of query-point errors listed in one 422.
const MAX_LISTED_ERRORS: usize = 20;

fn range_error(error: &ClosestPointError) -> FieldError {
    FieldError::new(
        JsonPointer::from("/range").push(error.range_index()),
        error.to_string(),
    )
}
