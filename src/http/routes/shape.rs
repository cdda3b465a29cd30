//! `POST /v1/shape/membership`, `/v1/shape/regions` and `/v1/shape/solve`: the shape edit
//! (knot pairs, control points, weights, under constraints; docs/method.md §3–§21) over the
//! wire. Each handler parses its request ([`ParsedShape`]), calls the core's edit
//! ([`shape::edit`], [`shape::reachable_regions`]) and converts the outcome
//! ([`crate::http::wire`]).

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
use crate::http::wire::families::family_memberships;
use crate::http::wire::methods::{ControlPointMembershipBody, ExclusionBody, WeightMembershipBody};
use crate::http::wire::shape_answer::{
    MembershipResponse, NearestBody, RegionsResponse, SolveResponse, membership_candidates,
    regions_response, shape_error,
};
use crate::http::wire::shape_request::{ParsedShape, RegionsRequest, ShapeRequest};
use crate::http::wire::solutions::{SolutionBody, solution_body};
use crate::shape::{self, EditOptions, EditOutcome, PolygonOptions};
use crate::spline::CurveLimits;

/// The smallest effective polygon vertex limit (smaller configured values act as this).
pub const MIN_POLYGON_VERTEX_LIMIT: usize = 128;

/// Which methods reach the target.
///
/// For each side's candidate, whether each requested region Ω1–Ω6 holds the target; whether
/// the control-point move and each weight pair reach it; exact (decided by solving, under the
/// same constraints), and consistent with `/v1/shape/solve`.
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
    let work = edit_work(&request);
    compute(admission, work, move || {
        let options = EditOptions {
            measure_deviation: false,
            nearest: false,
        };
        let (parsed, outcome) = run_edit(&request, &curve_limits, options)?;
        let curve = &parsed.curve;
        Ok(MembershipResponse {
            reachable: outcome.reachable(),
            candidates: membership_candidates(curve, &outcome.candidates),
            families: family_memberships(curve, &outcome.families),
            control_points: outcome.control_points.clone().map(|changed| {
                ControlPointMembershipBody {
                    contains: changed.is_some(),
                    changed_control_points: changed.unwrap_or_default(),
                }
            }),
            weights: outcome
                .weight_pairs
                .as_deref()
                .map(WeightMembershipBody::from_pairs),
            excluded: outcome.excluded.iter().map(ExclusionBody::from).collect(),
        })
    })
    .await
    .map(ApiJson)
}

/// The work of an edit request in point evaluations (for [`compute`]): validation is linear
/// in the control points; the control-point system grows with the cube of its rows (a few
/// per constraint) times the poles under each row.
fn edit_work(request: &ShapeRequest) -> usize {
    let rows = 1 + request.constraints.as_ref().map_or(0, Vec::len);
    let poles_per_row = request.curve.degree.saturating_add(1).min(64);
    request
        .curve
        .control_points
        .len()
        .saturating_add(rows.pow(3).saturating_mul(poles_per_row))
        .saturating_add(knot_family_work(&request.curve, KNOT_SET_WORK))
}

/// Point evaluations (roughly) one pair costs the knot families' solver per `(2p)²` of its
/// polynomial's size; a triple ten times as much.
const KNOT_SET_WORK: usize = 20;

/// Point evaluations (roughly) one pair's region costs (its outline or its lattice of
/// 33 × 33 points where the map folds).
const KNOT_REGION_WORK: usize = 1_100;

/// The knot families' work on `curve` (every family, both sides: the most a request asks),
/// at `per_set` point evaluations per pair and unit of size: a cubic's solve stays inline, a
/// quintic's (about a millisecond) goes to the blocking pool.
fn knot_family_work(curve: &crate::http::curve::CurveBody, per_set: usize) -> usize {
    let p = curve.degree.min(64);
    if p < 2 {
        return 0;
    }
    let pairs = (2 * p) * (2 * p - 1) / 2 + if p >= 3 { (2 * p - 2) * (2 * p - 3) } else { 0 };
    let three_d = curve
        .control_points
        .first()
        .is_some_and(|point| point.len() == 3);
    let triples = if three_d { 20 } else { 0 };
    (pairs + 10 * triples)
        .saturating_mul((2 * p) * (2 * p))
        .saturating_mul(per_set)
}

/// Parses a solve or membership request and runs the core's edit.
fn run_edit(
    request: &ShapeRequest,
    curve_limits: &CurveLimits,
    options: EditOptions,
) -> Result<(ParsedShape, EditOutcome), ApiError> {
    let parsed = ParsedShape::parse(
        &request.curve,
        &request.regions,
        request.knot_families.as_deref(),
        request.methods.as_deref(),
        curve_limits,
    )?;
    let conditions = parsed.conditions(
        request.parameter,
        request.constraints.as_deref(),
        request.fixed_control_points.as_deref(),
    )?;
    let query = parsed.query(request.parameter, request.side, request.keep_domain);
    let outcome = shape::edit(
        &conditions.context(query),
        &parsed.methods.kinds,
        &request.target,
        options,
    )
    .map_err(|error| shape_error(&error))?;
    Ok((parsed, outcome))
}

/// Move a curve point onto a target.
///
/// Every way the requested `methods` move the curve point `s(parameter)` onto `target`: new
/// knot vectors (one per knot pair and candidate that reaches it), the least-norm move of the
/// control points, new weights of two poles; each meets every constraint, and all are sorted
/// by how little the curve changes. An unreachable target is a normal answer
/// (`reachable: false`, with `nearest` when asked).
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
    let work = edit_work(&request);
    compute(admission, work, move || {
        let options = EditOptions {
            measure_deviation: true,
            nearest: request.nearest,
        };
        let (parsed, outcome) = run_edit(&request, &curve_limits, options)?;
        let curve = &parsed.curve;
        let paths = request.svg_paths;
        let solutions: Vec<SolutionBody> = outcome
            .solutions
            .iter()
            .map(|s| solution_body(curve, s, paths))
            .collect();
        let nearest = outcome.nearest.as_ref().map(|nearest| NearestBody {
            point: point_to_wire(nearest.point, curve.dimension()),
            distance: crate::spline::vector::distance(
                nearest.point,
                shape::target_point(curve, &request.target).unwrap_or(nearest.point),
            ),
            solutions: nearest
                .solutions
                .iter()
                .map(|s| solution_body(curve, s, paths))
                .collect(),
        });
        Ok(SolveResponse {
            reachable: !solutions.is_empty(),
            candidates: membership_candidates(curve, &outcome.candidates),
            families: family_memberships(curve, &outcome.families),
            solutions,
            nearest,
            excluded: outcome.excluded.iter().map(ExclusionBody::from).collect(),
        })
    })
    .await
    .map(ApiJson)
}

/// The regions' boundary polygons.
///
/// Each requested region of each side's candidate as a closed polygon, in the curve's
/// coordinates and in frame coordinates, sampled adaptively to `tolerance`, cut to what solve
/// reaches with the same `keep_domain`; with `weights` among the `methods`, each weight
/// pair's reachable region too. For drawing only.
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
    // Up to two sides of six polygons, each up to the vertex limit, and every family's pairs.
    let work = (12 * limits.max_polygon_vertices.max(MIN_POLYGON_VERTEX_LIMIT))
        .saturating_add(knot_family_work(&request.curve, KNOT_REGION_WORK / 16));
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
    let parsed = ParsedShape::parse(
        &request.curve,
        &request.regions,
        request.knot_families.as_deref(),
        request.methods.as_deref(),
        curve_limits,
    );
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
    let conditions = parsed.conditions(
        request.parameter,
        request.constraints.as_deref(),
        request.fixed_control_points.as_deref(),
    )?;
    let query = parsed.query(request.parameter, request.side, request.keep_domain);
    let reachable = shape::reachable_regions(
        &conditions.context(query),
        &parsed.methods.kinds,
        PolygonOptions {
            tolerance: request.tolerance,
            max_vertices: limits.max_polygon_vertices.max(MIN_POLYGON_VERTEX_LIMIT),
        },
    )
    .map_err(|error| shape_error(&error))?;
    Ok(regions_response(&parsed.curve, reachable))
}
