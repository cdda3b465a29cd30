//! Wire types of `POST /v1/curves/insert-knots` and `POST /v1/curves/bezier`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{CurveBody, WirePoint};

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
