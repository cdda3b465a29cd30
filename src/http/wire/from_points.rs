//! Wire types of `POST /v1/curves/interpolate` and `POST /v1/curves/approximate`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{CurveBody, WireCoordinates};
use crate::spline::Parametrization;

/// How the points' parameters are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("chord_length"))]
pub enum ParametrizationBody {
    /// Spacing proportional to the distance between consecutive points (The NURBS Book
    /// eq. 9.5).
    ChordLength,
    /// Spacing proportional to the square root of that distance (eq. 9.6): follows sharp
    /// turns more tightly.
    Centripetal,
    /// Equal spacing (eq. 9.4).
    Uniform,
}

impl From<ParametrizationBody> for Parametrization {
    fn from(body: ParametrizationBody) -> Self {
        match body {
            ParametrizationBody::ChordLength => Parametrization::ChordLength,
            ParametrizationBody::Centripetal => Parametrization::Centripetal,
            ParametrizationBody::Uniform => Parametrization::Uniform,
        }
    }
}

/// Points to interpolate.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "points": [[0, 0], [3, 4], [-1, 4], [-4, 0], [-4, -3]],
    "degree": 3
}))]
pub struct InterpolateRequest {
    /// The points `Q_0 … Q_{m−1}`, all 2D or all 3D, at least 2 and at most the configured
    /// `max_fit_points` (10,000 by default); consecutive points must differ (by more than
    /// `1e-12` of the points' size). For `closed`, give each point once: do not repeat the
    /// first at the end.
    #[schema(value_type = Vec<Vec<f64>>, example = json!([[0, 0], [3, 4], [-1, 4], [-4, 0], [-4, -3]]))]
    pub points: Vec<WireCoordinates>,
    /// Degree `p >= 1` (default 3), at most `points − 1` plus the number of end tangents
    /// given; at least 2 when an end tangent is given (`end_tangents`).
    #[serde(default)]
    #[schema(minimum = 1, example = 3)]
    pub degree: Option<usize>,
    /// How the parameters are chosen (default `chord_length`); exclusive with `parameters`.
    #[serde(default)]
    pub parametrization: Option<ParametrizationBody>,
    /// The parameters themselves, strictly increasing: one per point; for `closed` one
    /// more, where the curve returns to the first point (the end of its domain). Without
    /// `knots` the curve's domain is `[parameters[0], parameters[last]]`; with `knots` they
    /// must lie in the knots' domain. Exclusive with `parametrization`.
    #[serde(default)]
    pub parameters: Option<Vec<f64>>,
    /// `[start, end]`: the first derivative at the start and at the end (`null` for none),
    /// with respect to the curve's own parameter; each adds a control point. Only for open
    /// curves of `degree` ≥ 2: a tangent given (not `null`) with `degree: 1` or with
    /// `closed: true` is a 422 at `/end_tangents` (a degree-1 curve has no room for them).
    #[serde(default)]
    #[schema(value_type = Option<Vec<Option<Vec<f64>>>>, example = json!([[1, 1], null]))]
    pub end_tangents: Option<Vec<Option<WireCoordinates>>>,
    /// A closed curve (default `false`): `C^{degree−1}` across the seam at `points[0]`, which
    /// is at the start of the domain and again at its end. The answer is a plain curve with
    /// an unclamped knot vector and its first `degree` control points repeated at the end.
    #[serde(default)]
    #[schema(example = false)]
    pub closed: Option<bool>,
    /// The knot vector to use instead of averaging (The NURBS Book eq. 9.8), in either
    /// convention: `points + tangents + degree + 1` values (full) or two fewer (without the
    /// end values). A computed parametrization is mapped onto its domain. Every basis
    /// function must be non-zero at the parameter of its row (Schoenberg–Whitney:
    /// `u_k < ū_k < u_(k+p+1)`), else a 422. Open curves only; the answer uses the same
    /// convention.
    #[serde(default)]
    pub knots: Option<Vec<f64>>,
}

/// The interpolating curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "curve": {
        "degree": 3,
        "control_points": [[0, 0], [7.3169635171119936, 3.6867775257587376], [-2.9581305658514245, 6.678276528176592], [-4.494953466891108, -0.6736915062424752], [-4, -3]],
        "knots": [0, 0, 0, 0, 0.5490196078431372, 1, 1, 1, 1]
    },
    "parameters": [0, 0.29411764705882354, 0.5294117647058824, 0.8235294117647058, 1]
}))]
pub struct InterpolateResponse {
    /// The curve through every point: `s(parameters[k]) = points[k]`; clamped with knots by
    /// averaging (full convention), or with the given knots in their convention, or closed
    /// and unclamped.
    pub curve: CurveBody,
    /// The parameter of each point on the curve.
    pub parameters: Vec<f64>,
}

/// Points to approximate within a tolerance.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "points": [[0, 0], [1, 0.8], [2, 0.9], [3, 0.1], [4, -0.8], [5, -1], [6, -0.3]],
    "tolerance": 0.05
}))]
pub struct ApproximateRequest {
    /// The points, all 2D or all 3D, at least `degree + 1` and at most the configured
    /// `max_fit_points` (10,000 by default); repeated points are allowed.
    #[schema(value_type = Vec<Vec<f64>>, example = json!([[0, 0], [1, 0.8], [2, 0.9], [3, 0.1], [4, -0.8], [5, -1], [6, -0.3]]))]
    pub points: Vec<WireCoordinates>,
    /// `τ > 0`: every point within `τ` of the curve (Euclidean distance to the nearest curve
    /// point); at least `1e-9` times the points' largest coordinate magnitude.
    #[schema(exclusive_minimum = 0, example = 0.05)]
    pub tolerance: f64,
    /// Degree `p >= 1` (default 3).
    #[serde(default)]
    #[schema(minimum = 1, example = 3)]
    pub degree: Option<usize>,
    /// How the points' initial parameters are chosen (default `chord_length`).
    #[serde(default)]
    pub parametrization: Option<ParametrizationBody>,
    /// The curve starts exactly at the first point and ends at the last (default `true`).
    #[serde(default)]
    #[schema(example = true)]
    pub end_points_exact: Option<bool>,
}

/// The approximating curve and its certified error.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [2.9932705702000284, 3.242623872080212], [3.290293767869331, -3.089350749906089], [6, -0.3]], "knots": [0, 0, 0, 0, 1, 1, 1, 1]},
    "max_error": 0.021611297973411412,
    "parameters": [0, 0.12411465998160857, 0.2802350736255141, 0.48082120566597925, 0.6848401654250432, 0.8609164176334769, 1]
}))]
pub struct ApproximateResponse {
    /// The curve: clamped, domain `[0, 1]`, full knot convention, as few control points as
    /// the method manages (docs/method.md).
    pub curve: CurveBody,
    /// The largest distance from a point to the curve, measured by the closest-point search
    /// (the global minimum over the curve, as `/v1/curves/closest-point` answers it); at
    /// most `tolerance`.
    pub max_error: f64,
    /// The parameter of each point's closest curve point.
    pub parameters: Vec<f64>,
}
