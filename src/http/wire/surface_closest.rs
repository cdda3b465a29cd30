//! Wire types of `POST /v1/surfaces/closest-point`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::surface::SurfaceBody;
use crate::surface::SurfaceClosestPoint;

/// Query points whose closest surface points are wanted.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]},
    "points": [[0.5, 0.5, 1], [2, 2, 0]],
    "range": [[0, 1], [0, 1]]
}))]
pub struct SurfaceClosestPointRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// 1 to `max_parameters` query points `[x, y, z]`.
    #[schema(example = json!([[0.5, 0.5, 1], [2, 2, 0]]))]
    pub points: Vec<Vec<f64>>,
    /// The part `[[u0, u1], [v0, v1]]` of the domain to search (`u0 <= u1`, `v0 <= v1`,
    /// inside the domain; an end outside it by at most `1e-12` of its length, or 4 units of
    /// roundoff, is taken as the domain's end; a periodic direction's ends are reduced into
    /// its period); default the whole domain. A zero-width range searches one iso-curve.
    #[serde(default)]
    #[schema(example = json!([[0, 1], [0, 1]]))]
    pub range: Option<[[f64; 2]; 2]>,
}

/// One query point's closest surface point.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({"u": 0.75, "v": 0.75, "point": [0.75, 0.75, 0.5625], "distance": 0.5}))]
pub struct SurfaceClosestPointResult {
    /// The parameters `(u, v)` of the closest point: the global minimum of `|S(u, v) − q|`
    /// over the range, its edges and corners included. Among distances within
    /// `1e-12 · (size + d) + 8 ε · magnitude` of the least `d` (`size` the diagonal of the
    /// control points' bounding box, `magnitude` their largest coordinate), the smallest `u`,
    /// then `v`.
    pub u: f64,
    /// See `u`.
    pub v: f64,
    /// `S(u, v)`.
    pub point: [f64; 3],
    /// `|S(u, v) − q|`.
    pub distance: f64,
}

impl SurfaceClosestPointResult {
    /// The wire form of a core answer.
    pub fn from_core(found: &SurfaceClosestPoint) -> Self {
        SurfaceClosestPointResult {
            u: found.u,
            v: found.v,
            point: found.point,
            distance: found.distance,
        }
    }
}

/// The closest points, one per query point, in order.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({"results": [{"u": 0.75, "v": 0.75, "point": [0.75, 0.75, 0.5625], "distance": 0.5}]}))]
pub struct SurfaceClosestPointResponse {
    /// One entry per query point, in the order sent.
    pub results: Vec<SurfaceClosestPointResult>,
}
