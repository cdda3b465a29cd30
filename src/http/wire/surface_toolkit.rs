//! Wire types of `POST /v1/surfaces/iso-curve`, `/v1/surfaces/insert-knots` and
//! `/v1/surfaces/split`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::CurveBody;
use crate::http::surface::SurfaceBody;
use crate::surface::Direction;

/// Which parameter is held (iso-curve) or cut (split).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("v"))]
pub enum FixedParameter {
    /// `u`.
    U,
    /// `v`.
    V,
}

impl FixedParameter {
    /// The core direction.
    pub fn direction(self) -> Direction {
        match self {
            FixedParameter::U => Direction::U,
            FixedParameter::V => Direction::V,
        }
    }
}

/// The iso-curve with one parameter held.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]},
    "fixed": "v",
    "parameter": 0.3
}))]
pub struct IsoCurveRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// The parameter held: `"v"` gives the curve `u ↦ S(u, parameter)`, `"u"` the curve
    /// `v ↦ S(parameter, v)`.
    pub fixed: FixedParameter,
    /// Its value, inside that direction's domain (just outside: the end; periodic: reduced
    /// into the period).
    #[schema(example = 0.3)]
    pub parameter: f64,
}

/// The iso-curve.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "parameter": 0.3,
    "curve": {"degree": 1, "control_points": [[0, 0.3, 0], [1, 0.3, 0.3]], "knots": [0, 0, 1, 1]}
}))]
pub struct IsoCurveResponse {
    /// The value held (snapped into the domain).
    pub parameter: f64,
    /// The curve along the other direction, equal to the surface on that line: 3D, of that
    /// direction's degree, with its knots in the caller's convention, rational exactly when
    /// the surface is (control points the rows or columns evaluated at `parameter`, weights
    /// their weights' sums). A periodic direction gives its curve cut open over one period,
    /// in the multiplicities form, so that every curve endpoint takes it.
    pub curve: CurveBody,
}

/// Knots to insert into a surface.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]},
    "knots_u": [0.5],
    "knots_v": [0.25, 0.75]
}))]
pub struct SurfaceInsertKnotsRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// Values to insert in `u`, in any order, inside the domain; a value may repeat to raise
    /// its multiplicity, up to `degree_u` (the rules of `/v1/curves/insert-knots` for the
    /// curves along `u`). Default: none.
    #[serde(default)]
    #[schema(example = json!([0.5]))]
    pub knots_u: Vec<f64>,
    /// Values to insert in `v` (as `knots_u`). Default: none.
    #[serde(default)]
    #[schema(example = json!([0.25, 0.75]))]
    pub knots_v: Vec<f64>,
}

/// The refined surface.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[0.5, 0, 0], [0.5, 1, 0.5]],
                                   [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 0.5, 1, 1], "knots_v": [0, 0, 1, 1]}
}))]
pub struct SurfaceInsertKnotsResponse {
    /// The same surface over the finer knot vectors (same shape, more control points), in the
    /// caller's knot conventions (periodic directions stay periodic).
    pub surface: SurfaceBody,
}

/// Parameters to split a surface at.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]},
    "fixed": "u",
    "parameters": [0.5]
}))]
pub struct SurfaceSplitRequest {
    /// The surface.
    pub surface: SurfaceBody,
    /// `"u"` cuts at `u` values (the pieces lie side by side in `u`), `"v"` at `v` values.
    pub fixed: FixedParameter,
    /// Values strictly inside that direction's domain, in any order (repeats count once), at
    /// most `max_parameters`.
    #[schema(example = json!([0.5]))]
    pub parameters: Vec<f64>,
}

/// The pieces.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "surfaces": [
        {"degree_u": 1, "degree_v": 1,
         "control_points": [[[0, 0, 0], [0, 1, 0]], [[0.5, 0, 0], [0.5, 1, 0.5]]],
         "knots_u": [0, 0, 0.5, 0.5], "knots_v": [0, 0, 1, 1]},
        {"degree_u": 1, "degree_v": 1,
         "control_points": [[[0.5, 0, 0], [0.5, 1, 0.5]], [[1, 0, 0], [1, 1, 1]]],
         "knots_u": [0.5, 0.5, 1, 1], "knots_v": [0, 0, 1, 1]}
    ]
}))]
pub struct SurfaceSplitResponse {
    /// One surface per piece, in order of the cut parameter: each clamped in the cut
    /// direction (`degree + 1` equal end knots; a periodic direction is cut open), the other
    /// direction as given; together equal to the input.
    pub surfaces: Vec<SurfaceBody>,
}
