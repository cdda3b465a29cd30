//! Wire types of `POST /v1/curves/evaluate` and `POST /v1/curves/envelope`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{CurveBody, WirePoint};

/// Points (and derivatives) of a curve at given parameters or at uniform samples.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]},
    "parameters": [0, 0.25, 0.5, 1],
    "derivatives": 1
}))]
pub struct EvaluateRequest {
    /// The curve.
    pub curve: CurveBody,
    /// Parameters inside the domain, in any order. One outside it by at most `1e-12` of the
    /// domain's length (or 4 units of roundoff of the ends) is taken as the nearer end, and
    /// answered as that end. Exactly one of `parameters`, `samples` and `tolerance`.
    #[serde(default)]
    #[schema(example = json!([0, 0.25, 0.5, 1]))]
    pub parameters: Option<Vec<f64>>,
    /// Number of parameters (>= 2) spread uniformly over the whole domain, both ends included.
    /// Exactly one of `parameters`, `samples` and `tolerance`.
    #[serde(default)]
    #[schema(minimum = 2, example = 11)]
    pub samples: Option<usize>,
    /// A distance `τ > 0`: answer increasing parameters, both ends and every knot included,
    /// whose points make a polyline within `τ` of the curve everywhere (Hausdorff distance,
    /// in the curve's coordinates). Certified on the Bézier pieces: a piece is a convex
    /// combination of its control points `P_i` (projected, for rational curves: the weights
    /// are positive), so its distance to the chord `[P_0, P_p]` is at most
    /// `D · a h / (a h + c (1 - h))`, `h = 1 - 2^(1-p)`, `D` the largest distance of a control
    /// point to the chord, `a` the largest interior weight, `c` the smaller end weight (at
    /// most `D`, the convex-hull bound; `h D` without weights). A piece whose bound exceeds `τ`
    /// is split by de Casteljau into parts of equal parameter length, recursively;
    /// deterministic. Refused (422) when more than the configured
    /// `max_parameters` points would be needed, when `τ` is below `1e-9` times the largest
    /// control-point coordinate magnitude (double precision cannot certify it), or when the
    /// curve jumps at a knot of multiplicity `degree + 1`. Exactly one of `parameters`,
    /// `samples` and `tolerance`.
    #[serde(default)]
    #[schema(exclusive_minimum = 0, example = 0.01)]
    pub tolerance: Option<f64>,
    /// Highest derivative order to return (0: points only).
    #[serde(default)]
    #[schema(minimum = 0, example = 1)]
    pub derivatives: usize,
    /// Also answer `curvature` at each parameter (default `false`).
    #[serde(default)]
    #[schema(example = false)]
    pub curvature: bool,
}

/// The evaluated points.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "domain": [0, 1],
    "parameters": [0, 1],
    "points": [[0, 0], [5, 1]],
    "derivatives": [[[6, 12], [6, 6]]]
}))]
pub struct EvaluateResponse {
    /// The parameter domain `[lo, hi]`.
    pub domain: [f64; 2],
    /// The parameters evaluated: the given ones (those just outside the domain as its ends),
    /// the uniform samples, or the polyline's vertices (increasing).
    pub parameters: Vec<f64>,
    /// `points[i]` is the curve point at `parameters[i]`.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub points: Vec<WirePoint>,
    /// Present when `derivatives > 0`: `derivatives[d-1][i]` is the d-th derivative at
    /// `parameters[i]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<Vec<Vec<f64>>>>)]
    pub derivatives: Option<Vec<Vec<WirePoint>>>,
    /// Present when `curvature` was asked: `curvature[i]` at `parameters[i]`,
    /// `|s' × s''| / |s'|³`; for a planar curve signed, `(x' y'' − y' x'') / |s'|³`, positive
    /// where the curve turns left (counter-clockwise) of its direction of travel. Where the
    /// tangent vanishes (`|s'|` within `1e-12` of the derivative's scale on the span: a cusp,
    /// or an end whose first two control points coincide) the curvature is undefined: the
    /// entry is 0 and its index is in `curvature_undefined`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature: Option<Vec<f64>>,
    /// The indices into `parameters` where the curvature is undefined (present only when
    /// there are any).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_undefined: Option<Vec<usize>>,
}

/// The knot whose run of equal knots is moved.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]},
    "knot_index": 4
}))]
pub struct EnvelopeRequest {
    /// The curve.
    pub curve: CurveBody,
    /// Index (caller's convention) of an interior knot; its whole run of equal knots moves.
    #[schema(example = 4)]
    pub knot_index: usize,
}

/// The envelope of the family of curves made by moving the run.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "multiplicity": 1,
    "range": [0, 1],
    "moved_knots": [4],
    "envelope": {"degree": 2, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]}
}))]
pub struct EnvelopeResponse {
    /// Number `m` of equal knots moved together (`m <= degree - 1`).
    pub multiplicity: usize,
    /// `[lo, hi]`: the values the moved knots may take.
    pub range: [f64; 2],
    /// Indices (caller's convention) of the moved knots.
    pub moved_knots: Vec<usize>,
    /// The envelope: degree `degree - m`, same control points and weights, the knot vector
    /// without the moved run (caller's convention).
    pub envelope: CurveBody,
}
