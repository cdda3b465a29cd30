//! `POST /v1/surfaces/closest-point`: picking on a surface, query points to the parameters of
//! their closest surface points ([`crate::surface::SurfaceClosestSearch`]).

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::config::Limits;
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::wire::surface_closest::{
    SurfaceClosestPointRequest, SurfaceClosestPointResponse, SurfaceClosestPointResult,
};
use crate::spline::Point;
use crate::surface::{SurfaceClosestSearch, SurfaceLimits, SurfaceRangeError};

/// Estimated work of one query, in point evaluations, per patch of the surface (the boxes'
/// pass may visit many), and per query on top.
const WORK_PER_QUERY_AND_PATCH: usize = 1;
const WORK_PER_QUERY: usize = 400;

/// Largest number of query-point errors listed in one 422.
const MAX_LISTED_ERRORS: usize = 20;

/// Closest points of a surface.
///
/// For each query point, the surface point nearest to it: the global minimum of the distance
/// over the parameter rectangle (or `range`), edges and corners included.
#[utoipa::path(
    post,
    path = "/v1/surfaces/closest-point",
    operation_id = "surface_closest_point",
    tag = "surfaces",
    request_body = SurfaceClosestPointRequest,
    responses(
        (status = 200, description = "The closest surface point of each query point", body = SurfaceClosestPointResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn closest_point(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<SurfaceClosestPointRequest>,
) -> Result<ApiJson<SurfaceClosestPointResponse>, ApiError> {
    let (limits, surface_limits) = (state.limits, state.surface_limits);
    let patches: usize = request.surface.control_points.iter().map(Vec::len).sum();
    let per_query = patches
        .saturating_mul(WORK_PER_QUERY_AND_PATCH)
        .saturating_add(WORK_PER_QUERY);
    let work = patches.saturating_add(request.points.len().saturating_mul(per_query));
    compute(admission, work, move || {
        closest_point_request(&request, &limits, &surface_limits)
    })
    .await
    .map(ApiJson)
}

fn closest_point_request(
    request: &SurfaceClosestPointRequest,
    limits: &Limits,
    surface_limits: &SurfaceLimits,
) -> Result<SurfaceClosestPointResponse, ApiError> {
    let mut errors = Vec::new();
    let surface = request
        .surface
        .parse_collecting(surface_limits, "/surface", &mut errors);
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
    let mut queries: Vec<Point> = Vec::with_capacity(count.min(limits.max_parameters));
    for (index, point) in request.points.iter().enumerate() {
        if errors.len() >= MAX_LISTED_ERRORS || index >= limits.max_parameters {
            break;
        }
        let at = JsonPointer::from("/points").push(index);
        if point.len() != 3 {
            errors.push(FieldError::new(
                at,
                format!(
                    "the point has {} coordinates; a surface's query points are 3D",
                    point.len()
                ),
            ));
            continue;
        }
        match point.iter().position(|x| !x.is_finite()) {
            Some(coordinate) => errors.push(FieldError::new(
                at.push(coordinate),
                "coordinates must be finite numbers",
            )),
            None => queries.push([point[0], point[1], point[2]]),
        }
    }
    let (Some(surface), true) = (surface, errors.is_empty()) else {
        return Err(ApiError::Invalid(errors));
    };
    let range = request.range.map(|[u, v]| [(u[0], u[1]), (v[0], v[1])]);
    let search = SurfaceClosestSearch::new(&surface, range).map_err(|error| range_error(&error))?;
    let results = queries
        .iter()
        .map(|&q| SurfaceClosestPointResult::from_core(&search.closest(q)))
        .collect();
    Ok(SurfaceClosestPointResponse { results })
}

fn range_error(error: &SurfaceRangeError) -> ApiError {
    let (direction, index) = error.position();
    ApiError::invalid(
        JsonPointer::from("/range").push(direction).push(index),
        error.to_string(),
    )
}
