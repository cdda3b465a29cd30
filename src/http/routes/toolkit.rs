//! `POST /v1/curves/insert-knots` (knot insertion, and the knots that make a curve editable
//! around a parameter) and `POST /v1/curves/bezier` (Bézier pieces and an SVG path).

use axum::Extension;
use axum::extract::State;

use super::compute;
use crate::http::curve::{CurveBody, point_to_wire};
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::svg_path::svg_path;
use crate::http::wire::toolkit::{
    BezierRequest, BezierResponse, BezierSegment, InsertKnotsRequest, InsertKnotsResponse,
};
use crate::spline::{BezierPiece, CurveLimits, InsertError};

/// Insert knots.
///
/// The same curve over a finer knot vector (Boehm's algorithm; The NURBS Book A5.4), rational
/// curves through their homogeneous points, optionally with the knots that make it editable
/// by the knot-pair method around a parameter.
#[utoipa::path(
    post,
    path = "/v1/curves/insert-knots",
    tag = "curves",
    request_body = InsertKnotsRequest,
    responses(
        (status = 200, description = "The refined curve", body = InsertKnotsResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn insert_knots(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<InsertKnotsRequest>,
) -> Result<ApiJson<InsertKnotsResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    let work = (request.curve.control_points.len() + request.knots.len() + 6)
        .saturating_mul(request.curve.degree.saturating_add(1));
    compute(admission, work, move || {
        insert_knots_request(&request, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn insert_knots_request(
    request: &InsertKnotsRequest,
    limits: &CurveLimits,
) -> Result<InsertKnotsResponse, ApiError> {
    let curve = request.curve.parse_allowing_periodic(limits, "/curve")?;
    if curve.is_periodic() && request.editable_at.is_some() {
        return Err(ApiError::invalid(
            "/editable_at",
            "`editable_at` prepares a curve for the editing methods, which do not take periodic curves yet",
        ));
    }
    let knots = JsonPointer::from("/knots");
    let mut inserted = curve
        .checked_insertions(&request.knots)
        .map_err(|error| insertion_error(&error, &knots))?;
    let refined = curve
        .insert_knots(&inserted, limits.max_control_points)
        .map_err(|error| insertion_error(&error, &knots))?;
    let refined = match &request.editable_at {
        None => refined,
        Some(editable) => {
            let at = JsonPointer::from("/editable_at");
            let parameter = at.clone().push("parameter");
            let Some(t) = refined.snap_to_domain(editable.parameter) else {
                let (lo, hi) = refined.domain();
                return Err(ApiError::invalid(
                    parameter,
                    format!(
                        "parameter {} lies outside the domain [{lo}, {hi}]",
                        editable.parameter
                    ),
                ));
            };
            let values =
                refined
                    .knots_for_editing(t, editable.spacing)
                    .map_err(|error| match error {
                        InsertError::InvalidSpacing => {
                            ApiError::invalid(at.clone().push("spacing"), error.to_string())
                        }
                        _ => ApiError::invalid(parameter.clone(), error.to_string()),
                    })?;
            let editable = refined
                .insert_knots(&values, limits.max_control_points)
                .map_err(|error| match error {
                    InsertError::TooManyControlPoints { .. } => {
                        ApiError::invalid(at.clone(), error.to_string())
                    }
                    _ => ApiError::invalid(parameter.clone(), error.to_string()),
                })?;
            inserted.extend_from_slice(&values);
            inserted.sort_by(f64::total_cmp);
            editable
        }
    };
    Ok(InsertKnotsResponse {
        curve: CurveBody::from_curve(&refined),
        inserted,
    })
}

/// The 422 of an insertion error: at `list/index` for one value, at `list` otherwise.
fn insertion_error(error: &InsertError, list: &JsonPointer) -> ApiError {
    let pointer = match error.index() {
        Some(index) => list.clone().push(index),
        None => list.clone(),
    };
    ApiError::invalid(pointer, error.to_string())
}

/// Bézier pieces.
///
/// The curve as one Bézier piece per non-empty knot span (every knot inserted up to
/// multiplicity `degree`; The NURBS Book A5.6), and an SVG path when SVG can draw it exactly.
#[utoipa::path(
    post,
    path = "/v1/curves/bezier",
    tag = "curves",
    request_body = BezierRequest,
    responses(
        (status = 200, description = "The Bézier pieces", body = BezierResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn bezier(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<BezierRequest>,
) -> Result<ApiJson<BezierResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    let degree = request.curve.degree.saturating_add(1);
    let work = request
        .curve
        .control_points
        .len()
        .saturating_mul(degree.saturating_mul(degree));
    compute(admission, work, move || {
        bezier_request(&request, &curve_limits)
    })
    .await
    .map(ApiJson)
}

fn bezier_request(
    request: &BezierRequest,
    limits: &CurveLimits,
) -> Result<BezierResponse, ApiError> {
    let curve = request.curve.parse_allowing_periodic(limits, "/curve")?;
    let pieces: Vec<BezierPiece> = curve.bezier_pieces().collect();
    let finite = pieces
        .iter()
        .all(|piece| piece.homogeneous().iter().flatten().all(|v| v.is_finite()))
        && pieces
            .iter()
            .all(|piece| piece.control_points().flatten().all(f64::is_finite));
    if !finite {
        return Err(ApiError::non_finite_result());
    }
    let dimension = curve.dimension();
    let segments = pieces
        .iter()
        .map(|piece| BezierSegment {
            domain: [piece.domain.0, piece.domain.1],
            control_points: piece
                .control_points()
                .map(|point| point_to_wire(point, dimension))
                .collect(),
            weights: curve.is_rational().then(|| piece.weights().collect()),
        })
        .collect();
    Ok(BezierResponse {
        segments,
        svg_path: svg_path(&curve, &pieces),
    })
}
