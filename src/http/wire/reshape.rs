//! Wire types of `POST /v1/curves/elevate-degree`, `/v1/curves/remove-knots` and
//! `/v1/curves/split`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::CurveBody;

/// A curve and the degree to raise it to.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 2, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0]], "knots": [0, 0, 0, 0.5, 1, 1, 1]},
    "degree": 3
}))]
pub struct ElevateDegreeRequest {
    /// The curve (rational or not, 2D or 3D, either knot convention).
    pub curve: CurveBody,
    /// The new degree: greater than the curve's, at most 15.
    #[schema(minimum = 2, example = 3)]
    pub degree: usize,
}

/// The same curve with the higher degree.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [0.6666666666666667, 1.3333333333333335], [1.3333333333333335, 2], [2.6666666666666665, 2], [3.3333333333333335, 1.3333333333333333], [4, 0]], "knots": [0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1]}
}))]
pub struct ElevateDegreeResponse {
    /// The same shape (The NURBS Book A5.9): each interior knot's multiplicity grows by the
    /// degree difference (continuity kept); clamped over the input's domain (`degree + 1`
    /// equal knots at each end, even when the input was not clamped); the caller's knot
    /// convention and weights.
    pub curve: CurveBody,
}

/// A curve whose knots are to be removed within a tolerance.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [0.5, 1], [2, 2.03], [3.5, 1], [4, 0]], "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]},
    "tolerance": 0.05
}))]
pub struct RemoveKnotsRequest {
    /// The curve (rational or not, 2D or 3D, either knot convention).
    pub curve: CurveBody,
    /// How far the curve may move (`>= 0`): `max_u |C(u) − C'(u)|`, certified. A removal is
    /// made when its certified bound is within the tolerance plus a rounding allowance of
    /// `1e-12 · M · w_max / w_min` (`M` the largest control-point coordinate magnitude, the
    /// weight ratio 1 for a polynomial curve): so 0 removes exactly the exactly removable
    /// knots, such as every knot `insert-knots` added, as often as it was added.
    #[schema(minimum = 0, example = 0.05)]
    pub tolerance: f64,
    /// The knot values to try: interior knots of the curve (strictly inside the domain), each
    /// removed as often as the tolerance allows, up to its multiplicity (listing a value
    /// again changes nothing). Default: every interior knot.
    #[serde(default)]
    pub knots: Option<Vec<f64>>,
}

/// The curve with fewer knots.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2.03], [3, 2], [4, 0]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]},
    "removed": [0.5],
    "max_deviation": 0.015000000000000124
}))]
pub struct RemoveKnotsResponse {
    /// The new curve: same degree, domain, weights' presence and knot convention.
    pub curve: CurveBody,
    /// The removed values, ascending, a value once per removed occurrence.
    pub removed: Vec<f64>,
    /// A certified bound on how far the curve moved, `max_u |C(u) − C'(u)|` at equal
    /// parameters (a bound from the control points, not samples): at most `tolerance` plus
    /// the rounding allowance; 0 when nothing was removed.
    pub max_deviation: f64,
}

/// A curve and where to split it.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]},
    "parameters": [0.25, 0.5]
}))]
pub struct SplitRequest {
    /// The curve (rational or not, 2D or 3D, either knot convention).
    pub curve: CurveBody,
    /// Where to split: strictly inside the domain, any order (a repeated value counts once),
    /// at most the configured `max_parameters`.
    pub parameters: Vec<f64>,
}

/// The pieces.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "curves": [
        {"degree": 3, "control_points": [[0, 0], [0.5, 1], [1, 1.5], [1.46875, 1.6875]], "knots": [0, 0, 0, 0, 0.25, 0.25, 0.25, 0.25]},
        {"degree": 3, "control_points": [[1.46875, 1.6875], [1.9375, 1.875], [2.375, 1.75], [2.75, 1.5]], "knots": [0.25, 0.25, 0.25, 0.25, 0.5, 0.5, 0.5, 0.5]},
        {"degree": 3, "control_points": [[2.75, 1.5], [3.5, 1], [4, 0], [5, 1]], "knots": [0.5, 0.5, 0.5, 0.5, 1, 1, 1, 1]}
    ]
}))]
pub struct SplitResponse {
    /// One curve per piece, in order of parameter: piece `i` is the input on
    /// `[c_i, c_(i+1)]` (`c` the domain's start, the sorted split values, the domain's
    /// end), clamped (`degree + 1` equal knots at each end), with the input's degree,
    /// weights' presence and knot convention. Together they are the input curve.
    pub curves: Vec<CurveBody>,
}
