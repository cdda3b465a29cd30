//! Wire types of `POST /v1/curves/closest-point`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{CurveBody, WirePoint, point_to_wire};
use crate::spline::{ClosestPoint, Dimension};

/// Query points whose closest curve points are wanted.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0], [5, 1]], "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1]},
    "points": [[2, 3], [6, 0]],
    "range": [0, 1]
}))]
pub struct ClosestPointRequest {
    /// The curve (any degree, rational or not, 2D or 3D).
    pub curve: CurveBody,
    /// 1 to `max_parameters` query points, each with the curve's number of coordinates.
    #[schema(example = json!([[2, 3], [6, 0]]))]
    pub points: Vec<Vec<f64>>,
    /// The part `[lo, hi]` of the domain to search (`lo <= hi`, both inside the domain; an
    /// end outside it by at most `1e-12` of its length, or 4 units of roundoff of the ends,
    /// is taken as the domain's end); default the whole domain.
    #[serde(default)]
    #[schema(example = json!([0, 1]))]
    pub range: Option<[f64; 2]>,
}

/// One query point's closest curve point.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({"parameter": 0.375, "point": [2.08, 1.83], "distance": 1.17}))]
pub struct ClosestPointResult {
    /// The parameter `u` of the closest point: the global minimum of `|s(u) - q|` over the
    /// range (its ends and corners included); among distances within a relative `1e-12` of
    /// the least, the smallest parameter.
    pub parameter: f64,
    /// The curve point `s(u)`.
    #[schema(value_type = Vec<f64>)]
    pub point: WirePoint,
    /// `|s(u) - q|`.
    pub distance: f64,
}

impl ClosestPointResult {
    /// The wire form of a core answer.
    pub fn from_core(found: &ClosestPoint, dimension: Dimension) -> Self {
        ClosestPointResult {
            parameter: found.parameter,
            point: point_to_wire(found.point, dimension),
            distance: found.distance,
        }
    }
}

/// The closest points, one per query point, in order.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({"results": [{"parameter": 0.375, "point": [2.08, 1.83], "distance": 1.17}]}))]
pub struct ClosestPointResponse {
    /// One entry per query point, in the order sent.
    pub results: Vec<ClosestPointResult>,
}
