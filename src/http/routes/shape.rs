//! `POST /v1/shape/membership`, `/v1/shape/regions` and `/v1/shape/solve`: the knot-pair
//! method (docs/method.md §3–§8) and the control-point move over the wire. Each handler
//! parses its request ([`ParsedShape`]), calls the core ([`crate::shape`]) and converts the
//! outcome ([`crate::http::wire::shape_answer`]).

use axum::Extension;
use axum::extract::State;
use axum::http::HeaderMap;
use axum::response::Response;

use super::compute;
use crate::config::Limits;
use crate::http::curve::point_to_wire;
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::regions_media;
use crate::http::state::AppState;
use crate::http::wire::methods::{ControlPointMembershipBody, Methods};
use crate::http::wire::shape_answer::{
    MembershipResponse, NearestBody, RegionsResponse, SolutionBody, SolveResponse,
    control_point_solution_body, control_point_solution_path, knot_solution_body,
    knot_solution_path, membership_candidates, regions_response, shape_error,
};
use crate::http::wire::shape_request::{ParsedShape, RegionsRequest, ShapeRequest};
use crate::shape::{self, PolygonOptions, SolveOptions};
use crate::spline::CurveLimits;

/// The smallest effective polygon vertex limit (smaller configured values act as this).
pub const MIN_POLYGON_VERTEX_LIMIT: usize = 128;

/// Which regions Ω1–Ω6 contain the target.
///
/// For each side's candidate, whether each requested region holds the target; exact (decided
/// by solving), and consistent with `/v1/shape/solve`.
#[utoipa::path(
    post,
    path = "/v1/shape/membership",
    tag = "shape",
    request_body = ShapeRequest,
    responses(
        (status = 200, description = "Membership per candidate and region", body = MembershipResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn membership(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ShapeRequest>,
) -> Result<ApiJson<MembershipResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    // Validation is linear in the control points; the method itself is local and bounded.
    let work = request.curve.control_points.len();
    compute(admission, work, move || {
        let methods = Methods::parse(request.methods.as_deref())?;
        let parsed = ParsedShape::parse(&request.curve, &request.regions, &curve_limits)?;
        let query = parsed.query(request.parameter, request.side, request.keep_domain);
        let outcome =
            shape::membership(&query, &request.target).map_err(|error| shape_error(&error))?;
        let control_points = methods.control_points.then(|| {
            let target = shape::target_point(&parsed.curve, &request.target).ok();
            let moved = target.and_then(|target| {
                shape::control_point_move(&parsed.curve, query.parameter, target, false)
            });
            ControlPointMembershipBody {
                contains: moved.is_some(),
                changed_control_points: moved.map_or_else(Vec::new, |m| m.changed_control_points),
            }
        });
        let knots_reach = methods.knots && outcome.reachable();
        let poles_reach = control_points.as_ref().is_some_and(|c| c.contains);
        Ok(MembershipResponse {
            reachable: knots_reach || poles_reach,
            candidates: membership_candidates(&parsed.curve, &outcome),
            control_points,
        })
    })
    .await
    .map(ApiJson)
}

/// The knot-pair solver.
///
/// New knot vectors that move the curve point `s(parameter)` to `target`, one per region and
/// candidate that reaches it, sorted by how little the curve changes. An unreachable target
/// is a normal answer (`reachable: false`).
#[utoipa::path(
    post,
    path = "/v1/shape/solve",
    tag = "shape",
    request_body = ShapeRequest,
    responses(
        (status = 200, description = "Solutions (possibly none)", body = SolveResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn solve(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ShapeRequest>,
) -> Result<ApiJson<SolveResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    // Validation is linear in the control points; the method itself is local and bounded.
    let work = request.curve.control_points.len();
    compute(admission, work, move || {
        let methods = Methods::parse(request.methods.as_deref())?;
        let parsed = ParsedShape::parse(&request.curve, &request.regions, &curve_limits)?;
        let query = parsed.query(request.parameter, request.side, request.keep_domain);
        let options = SolveOptions {
            measure_deviation: true,
        };
        let outcome =
            shape::solve(&query, &request.target, options).map_err(|error| shape_error(&error))?;
        let curve = &parsed.curve;
        let target =
            shape::target_point(curve, &request.target).map_err(|error| shape_error(&error))?;
        let mut solutions: Vec<SolutionBody> = Vec::new();
        let paths = request.svg_paths;
        if methods.knots {
            solutions.extend(outcome.solutions.iter().map(|s| SolutionBody {
                svg_path: paths.then(|| knot_solution_path(curve, s)).flatten(),
                ..knot_solution_body(curve, s)
            }));
        }
        if methods.control_points {
            let moved = shape::control_point_move(curve, query.parameter, target, true);
            solutions.extend(moved.map(|m| {
                SolutionBody {
                    svg_path: paths
                        .then(|| control_point_solution_path(curve, &m))
                        .flatten(),
                    ..control_point_solution_body(curve, &m)
                }
            }));
        }
        solutions.sort_by(|p, q| p.max_deviation.total_cmp(&q.max_deviation));
        let nearest = if request.nearest && methods.knots && solutions.is_empty() {
            shape::nearest_reachable(&query, target, true)
                .map_err(|error| shape_error(&error))?
                .map(|nearest| NearestBody {
                    point: point_to_wire(nearest.point, curve.dimension()),
                    distance: nearest.distance,
                    solutions: nearest
                        .solutions
                        .iter()
                        .map(|s| SolutionBody {
                            svg_path: paths.then(|| knot_solution_path(curve, s)).flatten(),
                            ..knot_solution_body(curve, s)
                        })
                        .collect(),
                })
        } else {
            None
        };
        let response = SolveResponse {
            reachable: !solutions.is_empty(),
            candidates: membership_candidates(curve, &outcome),
            solutions,
            nearest,
        };
        Ok(response)
    })
    .await
    .map(ApiJson)
}

/// The regions' boundary polygons.
///
/// Each requested region of each side's candidate as a closed polygon, in the curve's
/// coordinates and in frame coordinates, sampled adaptively to `tolerance`. For drawing only.
#[utoipa::path(
    post,
    path = "/v1/shape/regions",
    tag = "shape",
    request_body = RegionsRequest,
    responses(
        (status = 200, description = "Boundary polygons per candidate and region (JSON, the default), or, with `Accept: image/svg+xml`, an SVG picture of them: one panel per candidate with its control triangle, the regions in their colours (polygon `points` are the JSON answer's x and y), the picked point, the target when the request has one, and a legend", content(
            (RegionsResponse = "application/json"),
            (String = "image/svg+xml"),
        )),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn regions(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    headers: HeaderMap,
    ApiJson(request): ApiJson<RegionsRequest>,
) -> Result<Response, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    // Up to two sides of six polygons, each up to the vertex limit.
    let work = 12 * limits.max_polygon_vertices.max(MIN_POLYGON_VERTEX_LIMIT);
    let svg = regions_media::prefers_svg(&headers);
    compute(admission, work, move || {
        let answer = regions_request(&request, &limits, &curve_limits)?;
        regions_media::respond(&request, answer, &curve_limits, svg)
    })
    .await
}

fn regions_request(
    request: &RegionsRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<RegionsResponse, ApiError> {
    let parsed = ParsedShape::parse(&request.curve, &request.regions, curve_limits);
    let tolerance_error = match request.tolerance {
        Some(tolerance) if !(tolerance.is_finite() && tolerance > 0.0) => Some(FieldError::new(
            "/tolerance",
            "`tolerance` must be a positive number",
        )),
        _ => None,
    };
    let parsed = match (parsed, tolerance_error) {
        (Ok(parsed), None) => parsed,
        (Ok(_), Some(error)) => return Err(ApiError::Invalid(vec![error])),
        (Err(ApiError::Invalid(mut errors)), Some(error)) => {
            errors.push(error);
            return Err(ApiError::Invalid(errors));
        }
        (Err(other), _) => return Err(other),
    };
    let query = parsed.query(request.parameter, request.side, request.keep_domain);
    let candidates = shape::region_polygons(
        &query,
        PolygonOptions {
            tolerance: request.tolerance,
            max_vertices: limits.max_polygon_vertices.max(MIN_POLYGON_VERTEX_LIMIT),
        },
    )
    .map_err(|error| shape_error(&error))?;
    Ok(regions_response(&parsed.curve, candidates))
}
