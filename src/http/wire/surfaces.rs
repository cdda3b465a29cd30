//! Wire types of `POST /v1/surfaces/evaluate`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::surface::SurfaceBody;

/// Points, partial derivatives, normals and curvature of a surface at given parameter pairs
/// or on a uniform grid.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]},
    "parameters": [[0.5, 0.5], [0, 0.5]],
    "derivatives": 1,
    "normals": true
}))]
pub struct SurfaceEvaluateRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// Parameter pairs `[u, v]` inside the domain, in any order. A value outside its
    /// direction's domain by at most `1e-12` of the domain's length (or 4 units of roundoff
    /// of the ends) is taken as the nearer end; a periodic direction takes any finite value
    /// and reduces it into its period. Exactly one of `parameters` and `samples`; at most the
    /// configured `max_parameters`.
    #[serde(default)]
    #[schema(example = json!([[0.5, 0.5], [0, 0.5]]))]
    pub parameters: Option<Vec<[f64; 2]>>,
    /// `[n_u, n_v]` (each >= 2): the uniform grid over the whole domain, ends included,
    /// answered row by row (`u` outer): entry `i · n_v + j` is
    /// `(u_lo + i (u_hi − u_lo) / (n_u − 1), v_lo + j (v_hi − v_lo) / (n_v − 1))`. At most
    /// `max_parameters` points in all.
    #[serde(default)]
    #[schema(example = json!([3, 3]))]
    pub samples: Option<[usize; 2]>,
    /// Highest order of partial derivatives to return: 0 (points only), 1 (`du`, `dv`) or 2
    /// (also `duu`, `duv`, `dvv`).
    #[serde(default)]
    #[schema(minimum = 0, maximum = 2, example = 1)]
    pub derivatives: usize,
    /// Also answer `normals` (default `false`).
    #[serde(default)]
    pub normals: bool,
    /// Also answer `curvature` (default `false`).
    #[serde(default)]
    pub curvature: bool,
}

/// Curvature at one point (do Carmo §3.3), with respect to the unit normal `normals[i]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({"gaussian": -0.4444, "mean": -0.1361, "principal": [0.5443, -0.8165],
                          "directions": [[0.6, 0.8, 0], [-0.8, 0.6, 0]]}))]
pub struct CurvatureBody {
    /// Gaussian curvature `K = (LN − M²) / (EG − F²)` (E, F, G and L, M, N the first and
    /// second fundamental forms' coefficients, with the normal `du × dv / |du × dv|`).
    pub gaussian: f64,
    /// Mean curvature `H = (EN − 2FM + GL) / (2 (EG − F²))` (positive where the surface bends
    /// towards the normal).
    pub mean: f64,
    /// `[k1, k2] = H ± √(H² − K)`, `k1 >= k2`.
    pub principal: [f64; 2],
    /// The unit principal directions of `k1` and `k2` (3D tangent vectors, orthogonal,
    /// `d2 = n × d1`). At an umbilic (`k1 = k2` within `1e-12`) every tangent direction is
    /// principal: `d1` is `du` normalised.
    pub directions: [[f64; 3]; 2],
}

/// The evaluated points and what was asked with them.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "domain": [[0, 1], [0, 1]],
    "parameters": [[0.5, 0.5], [0, 0.5]],
    "points": [[0.5, 0.5, 0.25], [0, 0.5, 0]],
    "du": [[1, 0, 0.5], [1, 0, 0.5]],
    "dv": [[0, 1, 0.5], [0, 1, 0]],
    "normals": [[-0.4082, -0.4082, 0.8165], [-0.4472, 0, 0.8944]]
}))]
pub struct SurfaceEvaluateResponse {
    /// `[[u_lo, u_hi], [v_lo, v_hi]]` (one period in a periodic direction).
    pub domain: [[f64; 2]; 2],
    /// The parameter pairs evaluated: the given ones (just outside the domain: its end;
    /// periodic: reduced into the period) or the grid's, row by row.
    pub parameters: Vec<[f64; 2]>,
    /// `points[i] = S(parameters[i])`.
    pub points: Vec<[f64; 3]>,
    /// With `derivatives >= 1`: `∂S/∂u` at each parameter pair (at a knot, the patch on the
    /// right's; at the domain's end, the limit from the left).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub du: Option<Vec<[f64; 3]>>,
    /// With `derivatives >= 1`: `∂S/∂v`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dv: Option<Vec<[f64; 3]>>,
    /// With `derivatives = 2`: `∂²S/∂u²`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duu: Option<Vec<[f64; 3]>>,
    /// With `derivatives = 2`: `∂²S/∂u∂v`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duv: Option<Vec<[f64; 3]>>,
    /// With `derivatives = 2`: `∂²S/∂v²`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dvv: Option<Vec<[f64; 3]>>,
    /// With `normals`: the unit normal `du × dv / |du × dv|`. Where `|du × dv|` vanishes
    /// (below `1e-12` of the partials' scales: a row or column of control points collapsed
    /// into one point, as at a sphere's pole), the limit from inside the domain: for `du = 0`,
    /// `±duv × dv` (the sign of the step in `v` into the domain), for `dv = 0`, `±du × duv`;
    /// those indices are listed in `limit_normals`. `null` where that limit vanishes too (both
    /// partials zero, or parallel): the surface has no normal there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normals: Option<Vec<Option<[f64; 3]>>>,
    /// The indices into `parameters` whose normal is a limit at a degenerate point (present
    /// only when there are any).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limit_normals: Option<Vec<usize>>,
    /// With `curvature`: one entry per parameter pair, `null` where `EG − F² = |du × dv|²`
    /// vanishes (a degenerate point, even where a limit normal exists).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature: Option<Vec<Option<CurvatureBody>>>,
}
