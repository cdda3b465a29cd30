//! Wire types of `POST /v1/curves/length`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::CurveBody;

/// A curve to measure.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 2, "control_points": [[1, 0], [1, 1], [0, 1]], "knots": [0, 0, 0, 1, 1, 1], "weights": [1, std::f64::consts::FRAC_1_SQRT_2, 1]},
    "at_lengths": [std::f64::consts::FRAC_PI_4]
}))]
pub struct LengthRequest {
    /// The curve (rational or not, 2D or 3D, either knot convention).
    pub curve: CurveBody,
    /// `[lo, hi]`: the part of the domain to measure (default the whole domain); an end
    /// outside the domain by at most `1e-12` of its length is taken as the domain's end.
    #[serde(default)]
    pub range: Option<[f64; 2]>,
    /// Arc lengths from the range's start, each in `[0, length]` (one above `length` by at
    /// most `1e-12 · length` is taken as `length`), at most the configured
    /// `max_parameters`; the answer gives the parameter at each.
    #[serde(default)]
    pub at_lengths: Option<Vec<f64>>,
}

/// The arc length.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "length": std::f64::consts::FRAC_PI_2,
    "error_estimate": 2.220446049250313e-16,
    "parameters": [0.5]
}))]
pub struct LengthResponse {
    /// `∫ |s'(u)| du` over the range, with relative error at most `1e-10` (adaptive
    /// Gauss–Legendre on each knot span, docs/method.md); a jump at a knot of multiplicity
    /// `degree + 1` adds nothing.
    pub length: f64,
    /// The quadrature's own estimate of its absolute error (at most `1e-12 · length` unless
    /// the curve has many cusps).
    pub error_estimate: f64,
    /// When `at_lengths` was given: the parameter `u` with `L(range start → u) = ℓ` for each
    /// length `ℓ`, in order (where the curve stands still, the smallest such `u` of the
    /// quadrature segment is approached).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parameters: Option<Vec<f64>>,
}
