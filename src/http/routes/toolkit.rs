//! `POST /v1/curves/insert-knots` (knot insertion, and the knots that make a curve editable
//! around a parameter) and `POST /v1/curves/bezier` (Bézier pieces and an SVG path).

use axum::Extension;
use axum::extract::State;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::compute;
use crate::http::curve::{CurveBody, WirePoint, point_to_wire};
use crate::http::error::{ApiError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::state::AppState;
use crate::http::svg_path::svg_path;
use crate::spline::{BezierPiece, CurveLimits, InsertError};

/// Knots to insert into a curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]},
    "knots": [0.25]
}))]
pub struct InsertKnotsRequest {
    /// The curve.
    pub curve: CurveBody,
    /// Values to insert, in any order, inside the domain; a value may repeat to raise its
    /// multiplicity. After insertion a value may have multiplicity at most `degree` (an
    /// interior knot of multiplicity `degree` is a corner; a clamped end already has
    /// `degree + 1`). One outside the domain by at most `1e-12` of its length (or 4 units of
    /// roundoff of the ends) is taken as the nearer end. Default: none.
    #[serde(default)]
    #[schema(example = json!([0.25]))]
    pub knots: Vec<f64>,
    /// Also insert what the cubic knot-pair method (`/v1/shape/*`) needs to move the point at
    /// `parameter` with the domain kept: after `knots` are inserted, three knots strictly
    /// inside the domain on each side of `t` (in `(lo, t]` and `(t, hi)`, counting those the
    /// curve has). A single Bézier piece gets six.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub editable_at: Option<EditableAt>,
}

/// Where a curve is to be made editable by the knot-pair method.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"parameter": 0.5, "spacing": 0.1}))]
pub struct EditableAt {
    /// The picked parameter `t`, inside the domain but not at its ends (the curve's end point
    /// cannot move without moving the domain). One outside it by at most `1e-12` of its
    /// length is taken as the nearer end (and refused as an end).
    #[schema(example = 0.5)]
    pub parameter: f64,
    /// Distance in parameter between the inserted knots (`> 0`), `t ± k · spacing`,
    /// `k = 1, 2, 3`, shortened near an end of the domain so that they stay inside it.
    /// Wider spacing gives larger regions Ω1–Ω6 and a larger changed part of the curve.
    /// Default: `0.125 · (hi - lo)`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(exclusive_minimum = 0, example = 0.1)]
    pub spacing: Option<f64>,
}

/// The refined curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [0.25, 0.5], [1.5, 2], [3.25, 1.5], [4, 0]], "knots": [0, 0, 0, 0, 0.25, 1, 1, 1, 1]},
    "inserted": [0.25]
}))]
pub struct InsertKnotsResponse {
    /// The same curve with the knots inserted (same shape, more control points), knots in the
    /// caller's convention.
    pub curve: CurveBody,
    /// Every value inserted (those of `knots`, snapped, and those for `editable_at`),
    /// ascending.
    pub inserted: Vec<f64>,
}

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
    let curve = request.curve.parse(limits, "/curve")?;
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

/// A curve to split into Bézier pieces.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]}
}))]
pub struct BezierRequest {
    /// The curve.
    pub curve: CurveBody,
}

/// One Bézier piece.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({"domain": [0, 0.5], "control_points": [[0, 0], [1, 2], [2, 2], [2.75, 1.5]]}))]
pub struct BezierSegment {
    /// `[lo, hi]`: the knot span it covers; the piece is
    /// `Σ_i B_i C(p, i) s^i (1 - s)^(p - i)`, `s = (u - lo) / (hi - lo)` (rational: the
    /// same with `w_i B_i`, divided by `Σ_i w_i C(p, i) s^i (1 - s)^(p - i)`).
    pub domain: [f64; 2],
    /// The `degree + 1` control points `B_i`, in the curve's dimension.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub control_points: Vec<WirePoint>,
    /// The `degree + 1` weights `w_i`; rational curves only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
}

/// The curve as Bézier pieces.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "segments": [
        {"domain": [0, 0.5], "control_points": [[0, 0], [1, 2], [2, 2], [2.75, 1.5]]},
        {"domain": [0.5, 1], "control_points": [[2.75, 1.5], [3.5, 1], [4, 0], [5, 1]]}
    ],
    "svg_path": "M 0 0 C 1 2 2 2 2.75 1.5 C 3.5 1 4 0 5 1"
}))]
pub struct BezierResponse {
    /// One piece per non-empty knot span of the domain, in order.
    pub segments: Vec<BezierSegment>,
    /// For a planar, non-rational curve of degree 1, 2 or 3: an SVG path `d` string, `M` to
    /// the first point, then one `L`, `Q` or `C` command per piece with its control points
    /// after the first (a new `M` where the curve jumps, at a knot of multiplicity
    /// `degree + 1`). Numbers are the shortest text that reads back as the same double
    /// (whole numbers without a decimal point, exponents where shorter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg_path: Option<String>,
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
    let curve = request.curve.parse(limits, "/curve")?;
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
