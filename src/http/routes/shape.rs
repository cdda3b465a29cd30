//! `POST /v1/shape/membership`, `/v1/shape/regions` and `/v1/shape/solve`: the knot-pair
//! method (docs/method.md §3–§8) over the wire. Knot indices and vectors are converted from the
//! core's full convention to the caller's.

use axum::Extension;
use axum::extract::State;
use axum::http::HeaderMap;
use axum::response::Response;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::compute;
use crate::config::Limits;
use crate::http::curve::{CurveBody, WirePoint, point_to_wire};
use crate::http::error::{ApiError, FieldError, Problem};
use crate::http::extract::ApiJson;
use crate::http::middleware::AdmissionPermit;
use crate::http::pointer::JsonPointer;
use crate::http::regions_media;
use crate::http::state::AppState;
use crate::http::wire::methods::{ControlPointMembershipBody, Method, Methods};
use crate::shape::{
    self, Candidate, KnotPair, PolygonOptions, ShapeError, ShapeField, ShapeQuery, Side,
    SideChoice, SolveOptions, SolveOutcome,
};
use crate::spline::{Curve, CurveLimits};

/// The degree the knot-pair method works on.
const CUBIC: usize = 3;

/// The smallest effective polygon vertex limit (smaller configured values act as this).
pub const MIN_POLYGON_VERTEX_LIMIT: usize = 128;

/// Which knot next to `t` may move to `t`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("both"))]
pub enum SideRequest {
    /// The knot right of `t`, `u_{m+1}`.
    Right,
    /// The knot left of (or at) `t`, `u_m`.
    Left,
    /// Both, each as its own candidate (right first).
    #[default]
    Both,
}

impl From<SideRequest> for SideChoice {
    fn from(side: SideRequest) -> Self {
        match side {
            SideRequest::Right => SideChoice::Right,
            SideRequest::Left => SideChoice::Left,
            SideRequest::Both => SideChoice::Both,
        }
    }
}

/// The side of a candidate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("left"))]
pub enum CandidateSide {
    /// The knot right of `t` moved to `t`.
    Right,
    /// The knot left of (or at) `t` moved to `t`.
    Left,
}

impl CandidateSide {
    /// The name on the wire (as serde writes it).
    pub fn wire_name(self) -> &'static str {
        match self {
            CandidateSide::Right => "right",
            CandidateSide::Left => "left",
        }
    }
}

impl From<Side> for CandidateSide {
    fn from(side: Side) -> Self {
        match side {
            Side::Right => CandidateSide::Right,
            Side::Left => CandidateSide::Left,
        }
    }
}

/// A region `Ω_r`: the targets one knot pair reaches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("omega2"))]
pub enum Region {
    /// `(a, b) = (v_{j-1}, v_j)` move (paper §3.1).
    Omega1,
    /// `(b, c) = (v_j, v_{j+1})` move (paper §3.1).
    Omega2,
    /// `(c, e) = (v_{j+1}, v_{j+2})` move (paper §3.1).
    Omega3,
    /// `(a, c) = (v_{j-1}, v_{j+1})` move (paper §3.2.1).
    Omega4,
    /// `(a, e) = (v_{j-1}, v_{j+2})` move (paper §3.2.2).
    Omega5,
    /// `(b, e) = (v_j, v_{j+2})` move (paper §3.2.3).
    Omega6,
}

impl Region {
    /// The name on the wire (as serde writes it).
    pub fn wire_name(self) -> &'static str {
        match self {
            Region::Omega1 => "omega1",
            Region::Omega2 => "omega2",
            Region::Omega3 => "omega3",
            Region::Omega4 => "omega4",
            Region::Omega5 => "omega5",
            Region::Omega6 => "omega6",
        }
    }
}

impl From<Region> for KnotPair {
    fn from(region: Region) -> Self {
        match region {
            Region::Omega1 => KnotPair::Omega1,
            Region::Omega2 => KnotPair::Omega2,
            Region::Omega3 => KnotPair::Omega3,
            Region::Omega4 => KnotPair::Omega4,
            Region::Omega5 => KnotPair::Omega5,
            Region::Omega6 => KnotPair::Omega6,
        }
    }
}

impl From<KnotPair> for Region {
    fn from(pair: KnotPair) -> Self {
        match pair {
            KnotPair::Omega1 => Region::Omega1,
            KnotPair::Omega2 => Region::Omega2,
            KnotPair::Omega3 => Region::Omega3,
            KnotPair::Omega4 => Region::Omega4,
            KnotPair::Omega5 => Region::Omega5,
            KnotPair::Omega6 => Region::Omega6,
        }
    }
}

fn keep_domain_default() -> bool {
    true
}

/// A picked curve point `s(parameter)` and the target it should move to.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
              "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]},
    "parameter": 0.42,
    "target": [4.746666666666666, 3.3233333333333333],
    "side": "both",
    "regions": ["omega1", "omega2", "omega3", "omega4", "omega5", "omega6"],
    "keep_domain": true
}))]
pub struct ShapeRequest {
    /// A cubic curve (degree 3).
    pub curve: CurveBody,
    /// The picked parameter `t`, inside the domain; one outside it by at most `1e-12` of the
    /// domain's length (or 4 units of roundoff of the ends) is taken as the nearer end.
    #[schema(example = 0.42)]
    pub parameter: f64,
    /// The target point `p` (same dimension as the control points).
    #[schema(example = json!([4.746666666666666, 3.3233333333333333]))]
    pub target: Vec<f64>,
    /// Which knot next to `t` moves to `t` (default `both`).
    #[serde(default)]
    pub side: SideRequest,
    /// The regions to try (default all six); no repeats.
    #[serde(default)]
    pub regions: Option<Vec<Region>>,
    /// Drop solutions that move the ends of the curve's domain (default `true`).
    #[serde(default = "keep_domain_default")]
    #[schema(default = true, example = true)]
    pub keep_domain: bool,
    /// Solve only: when no solution reaches the target, answer `nearest`, the reachable point
    /// closest to it (default `false`). Membership ignores it.
    #[serde(default)]
    #[schema(example = false)]
    pub nearest: bool,
    /// The ways to move the point (default `["knots"]`): `knots` (the knot pairs) and/or
    /// `control_points` (the least-squares move of the poles whose basis is non-zero at `t`).
    #[serde(default)]
    #[schema(value_type = Option<Vec<Method>>, example = json!(["knots", "control_points"]))]
    pub methods: Option<Vec<String>>,
}

/// A picked parameter whose regions' boundaries are wanted.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "curve": {"degree": 3, "control_points": [[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
              "knots": [0, 0, 0, 0, 0.2, 0.35, 0.5, 0.75, 1, 1, 1, 1]},
    "parameter": 0.42,
    "side": "left",
    "regions": ["omega2", "omega4"],
    "tolerance": 0.01
}))]
pub struct RegionsRequest {
    /// A cubic curve (degree 3).
    pub curve: CurveBody,
    /// The picked parameter `t`, inside the domain; one outside it by at most `1e-12` of the
    /// domain's length (or 4 units of roundoff of the ends) is taken as the nearer end.
    #[schema(example = 0.42)]
    pub parameter: f64,
    /// Which knot next to `t` moves to `t` (default `both`).
    #[serde(default)]
    pub side: SideRequest,
    /// The regions to draw (default all six); no repeats.
    #[serde(default)]
    pub regions: Option<Vec<Region>>,
    /// Accepted for symmetry with the other shape endpoints; the polygons are the whole
    /// regions (membership and solve apply the rule).
    #[serde(default = "keep_domain_default")]
    #[schema(default = true)]
    pub keep_domain: bool,
    /// Largest distance, in curve coordinates, between the true boundary and the polygon
    /// (> 0; default 1/1000 of the control triangle's longest edge). Refinement also stops at
    /// the configured vertex limit (then `tolerance_met` is false).
    #[serde(default)]
    #[schema(example = 0.01)]
    pub tolerance: Option<f64>,
    /// A target point (same dimension as the control points), drawn in the SVG picture
    /// (`Accept: image/svg+xml`); checked but otherwise unused by the JSON answer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = json!([4.746666666666666, 3.3233333333333333]))]
    pub target: Option<Vec<f64>>,
}

/// The target in the control triangle's frame:
/// `p = d_{j-1} + x (d_{j-2} - d_{j-1}) + y (d_j - d_{j-1})` (rational: docs/method.md §7).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"x": 0.18, "y": 0.1067}))]
pub struct FrameBody {
    /// The basis value `N_{j-2}^3(t)` the target needs.
    pub x: f64,
    /// The basis value `N_j^3(t)` the target needs.
    pub y: f64,
}

/// One side's candidate: the knot that moves to `t`, its span and control triangle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "frame": {"x": 0.18, "y": 0.106667}}))]
pub struct CandidateBody {
    /// Which knot moves to `t`.
    pub side: CandidateSide,
    /// Whether this side can move the point; when not, `reason` says why and no region
    /// holds the target.
    pub applicable: bool,
    /// Why the side does not apply (index out of range, degenerate triangle, target off the
    /// triangle's plane).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
    /// The span `j` of docs/method.md §3.1 (full-vector numbering: the moved knot is `u_{j+1}`, the
    /// triangle is `d_{j-2}, d_{j-1}, d_j`).
    #[schema(example = 4)]
    pub span: usize,
    /// Index of the knot set to `t`, in the caller's knot convention.
    #[schema(example = 5)]
    pub moved_knot: usize,
    /// The control points `d_{j-2}, d_{j-1}, d_j`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<Vec<f64>>>)]
    pub triangle: Option<[WirePoint; 3]>,
    /// The target's frame coordinates (membership and solve, applicable sides).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<FrameBody>,
}

/// Whether one region of a candidate holds the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"region": "omega2", "knots": [4, 6], "contains": true}))]
pub struct RegionMembershipBody {
    /// The region.
    pub region: Region,
    /// Indices (caller's convention) of the pair of knots this region moves.
    pub knots: [usize; 2],
    /// True exactly when `/v1/shape/solve` gives a solution for this region and candidate.
    pub contains: bool,
}

/// A candidate with the membership of each requested region.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "frame": {"x": 0.18, "y": 0.106667}, "regions": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}))]
pub struct MembershipCandidate {
    /// The candidate.
    #[serde(flatten)]
    pub candidate: CandidateBody,
    /// One entry per requested region (empty when the side does not apply).
    pub regions: Vec<RegionMembershipBody>,
}

/// Which regions hold the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"reachable": true, "candidates": [{"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "frame": {"x": 0.18, "y": 0.106667}, "regions": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}]}))]
pub struct MembershipResponse {
    /// Whether any requested method reaches the target: a region of a candidate holds it, or
    /// the control-point move was asked for.
    pub reachable: bool,
    /// One entry per requested side.
    pub candidates: Vec<MembershipCandidate>,
    /// The control-point move, when `methods` holds `control_points`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control_points: Option<ControlPointMembershipBody>,
}

/// One way to move `s(t)` onto the target: new knots (`method: "knots"`, with `region`,
/// `side`, `span`, `moved_knot`, `changed_knots`, `knots`) or new control points
/// (`method: "control_points"`, with `control_points`, `changed_control_points`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "knots", "region": "omega2", "side": "left", "span": 4, "moved_knot": 5, "changed_knots": [4, 5, 6],
     "knots": [0, 0, 0, 0, 0.3, 0.42, 0.6, 0.75, 1, 1, 1, 1], "point": [4.746667, 3.323333],
     "residual": 3.2e-15, "affected_domain": [0, 1], "max_deviation": 1.030559}))]
pub struct SolutionBody {
    /// How the point is moved.
    pub method: Method,
    /// The region (knot pair) that reaches the target (knot solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<Region>,
    /// Which knot moved to `t` (knot solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<CandidateSide>,
    /// The span `j` (full-vector numbering, as in the candidates; knot solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub span: Option<usize>,
    /// Index (caller's convention) of the knot set to `t` (knot solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moved_knot: Option<usize>,
    /// Indices (caller's convention) of the knots whose values changed, ascending (knot
    /// solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub changed_knots: Option<Vec<usize>>,
    /// The whole new knot vector, in the caller's convention (knot solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub knots: Option<Vec<f64>>,
    /// The whole new list of control points, in the caller's order (control-point solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<Vec<f64>>>)]
    pub control_points: Option<Vec<WirePoint>>,
    /// Indices of the control points that moved, ascending (control-point solutions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub changed_control_points: Option<Vec<usize>>,
    /// The new curve's point at `parameter`.
    #[schema(value_type = Vec<f64>)]
    pub point: WirePoint,
    /// `|point - target|` (for `nearest` solutions: `|point - nearest.point|`).
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: [f64; 2],
    /// Largest distance between the old and the new curve (certified to a relative 5e-11 by
    /// Bernstein branch and bound).
    pub max_deviation: f64,
}

/// The reachable point nearest to an unreachable target, and the solutions that reach it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"point": [5.2, 3.9], "distance": 0.41, "solutions": [{"method": "knots", "region": "omega3", "side": "right", "span": 5, "moved_knot": 6, "changed_knots": [6, 7, 8],
     "knots": [0, 0, 0, 0, 0.2, 0.35, 0.42, 0.61, 0.97, 1, 1, 1], "point": [5.2, 3.9],
     "residual": 0.0, "affected_domain": [0.2, 1], "max_deviation": 0.83}]}))]
pub struct NearestBody {
    /// The nearest reachable point (Euclidean, in the curve's coordinates), as the first
    /// solution's new curve gives it at `parameter`.
    #[schema(value_type = Vec<f64>)]
    pub point: WirePoint,
    /// `|point - target|`.
    pub distance: f64,
    /// Every solution that reaches `point`, sorted by `max_deviation`.
    pub solutions: Vec<SolutionBody>,
}

/// New knot vectors that move `s(t)` to the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"reachable": true, "candidates": [{"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "frame": {"x": 0.18, "y": 0.106667}, "regions": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}], "solutions": [{"region": "omega2", "side": "left", "span": 4, "moved_knot": 5, "changed_knots": [4, 5, 6],
     "knots": [0, 0, 0, 0, 0.3, 0.42, 0.6, 0.75, 1, 1, 1, 1], "point": [4.746667, 3.323333],
     "residual": 3.2e-15, "affected_domain": [0, 1], "max_deviation": 1.030559}]}))]
pub struct SolveResponse {
    /// Whether any solution exists (`false` is a normal answer, not an error).
    pub reachable: bool,
    /// One entry per requested side, with region membership.
    pub candidates: Vec<MembershipCandidate>,
    /// Every solution of every requested method, sorted by `max_deviation`, smallest first.
    pub solutions: Vec<SolutionBody>,
    /// With `nearest: true`, when no solution reaches the target: the nearest reachable
    /// point. Absent when the target is reachable or nothing at all is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nearest: Option<NearestBody>,
}

/// One region's boundary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"region": "omega2", "knots": [4, 6],
     "polygon": [[5.56, 2.1], [4.9264, 2.8128], [4.12, 3.72], [5.0, 3.5], [5.56, 2.1]],
     "polygon_frame": [[0.0, 0.56], [0.1936, 0.3136], [0.44, 0.0], [0.0, 0.0], [0.0, 0.56]],
     "tolerance_met": true}))]
pub struct RegionPolygonBody {
    /// The region.
    pub region: Region,
    /// Indices (caller's convention) of the pair of knots this region moves.
    pub knots: [usize; 2],
    /// Closed boundary polygon (first vertex repeated last) in the curve's coordinates.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub polygon: Vec<WirePoint>,
    /// The same polygon in frame coordinates `[x, y]`.
    pub polygon_frame: Vec<[f64; 2]>,
    /// Whether the polygon is within `tolerance` of the true boundary everywhere (false when
    /// the vertex limit stopped the refinement).
    pub tolerance_met: bool,
}

/// A candidate with its regions' boundaries.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "regions": [{"region": "omega2", "knots": [4, 6],
     "polygon": [[5.56, 2.1], [4.9264, 2.8128], [4.12, 3.72], [5.0, 3.5], [5.56, 2.1]],
     "polygon_frame": [[0.0, 0.56], [0.1936, 0.3136], [0.44, 0.0], [0.0, 0.0], [0.0, 0.56]],
     "tolerance_met": true}]}))]
pub struct RegionsCandidate {
    /// The candidate (no target, so no frame).
    #[serde(flatten)]
    pub candidate: CandidateBody,
    /// One entry per requested region (empty when the side does not apply).
    pub regions: Vec<RegionPolygonBody>,
}

/// The regions' boundary polygons, for drawing (membership is decided by solving).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"candidates": [{"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "regions": [{"region": "omega2", "knots": [4, 6],
     "polygon": [[5.56, 2.1], [4.9264, 2.8128], [4.12, 3.72], [5.0, 3.5], [5.56, 2.1]],
     "polygon_frame": [[0.0, 0.56], [0.1936, 0.3136], [0.44, 0.0], [0.0, 0.0], [0.0, 0.56]],
     "tolerance_met": true}]}]}))]
pub struct RegionsResponse {
    /// One entry per requested side.
    pub candidates: Vec<RegionsCandidate>,
}

/// Which regions Ω1–Ω6 contain the target.
///
/// For each side's candidate, whether each requested region holds the target; exact (decided
/// by solving), and consistent with `/v1/shape/solve`.
#[utoipa::path(
    post,
    path = "/v1/shape/membership",
    tag = "shape",
    request_body = ShapeRequest,
    responses(
        (status = 200, description = "Membership per candidate and region", body = MembershipResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn membership(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ShapeRequest>,
) -> Result<ApiJson<MembershipResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    // Validation is linear in the control points; the method itself is local and bounded.
    let work = request.curve.control_points.len();
    compute(admission, work, move || {
        let methods = Methods::parse(request.methods.as_deref())?;
        let parsed = ParsedShape::parse(&request.curve, &request.regions, &curve_limits)?;
        let query = parsed.query(request.parameter, request.side, request.keep_domain);
        let outcome =
            shape::membership(&query, &request.target).map_err(|error| shape_error(&error))?;
        let control_points = methods.control_points.then(|| {
            let target = shape::target_point(&parsed.curve, &request.target).ok();
            let moved = target.and_then(|target| {
                shape::control_point_move(&parsed.curve, query.parameter, target, false)
            });
            ControlPointMembershipBody {
                contains: moved.is_some(),
                changed_control_points: moved.map_or_else(Vec::new, |m| m.changed_control_points),
            }
        });
        let knots_reach = methods.knots && outcome.reachable();
        let poles_reach = control_points.as_ref().is_some_and(|c| c.contains);
        Ok(MembershipResponse {
            reachable: knots_reach || poles_reach,
            candidates: membership_candidates(&parsed.curve, &outcome),
            control_points,
        })
    })
    .await
    .map(ApiJson)
}

/// The knot-pair solver.
///
/// New knot vectors that move the curve point `s(parameter)` to `target`, one per region and
/// candidate that reaches it, sorted by how little the curve changes. An unreachable target
/// is a normal answer (`reachable: false`).
#[utoipa::path(
    post,
    path = "/v1/shape/solve",
    tag = "shape",
    request_body = ShapeRequest,
    responses(
        (status = 200, description = "Solutions (possibly none)", body = SolveResponse),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn solve(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    ApiJson(request): ApiJson<ShapeRequest>,
) -> Result<ApiJson<SolveResponse>, ApiError> {
    let curve_limits = state.curve_limits;
    // Validation is linear in the control points; the method itself is local and bounded.
    let work = request.curve.control_points.len();
    compute(admission, work, move || {
        let methods = Methods::parse(request.methods.as_deref())?;
        let parsed = ParsedShape::parse(&request.curve, &request.regions, &curve_limits)?;
        let query = parsed.query(request.parameter, request.side, request.keep_domain);
        let options = SolveOptions {
            measure_deviation: true,
        };
        let outcome =
            shape::solve(&query, &request.target, options).map_err(|error| shape_error(&error))?;
        let curve = &parsed.curve;
        let target =
            shape::target_point(curve, &request.target).map_err(|error| shape_error(&error))?;
        let mut solutions: Vec<SolutionBody> = Vec::new();
        if methods.knots {
            solutions.extend(
                outcome
                    .solutions
                    .iter()
                    .map(|s| knot_solution_body(curve, s)),
            );
        }
        if methods.control_points {
            let moved = shape::control_point_move(curve, query.parameter, target, true);
            solutions.extend(moved.map(|m| control_point_solution_body(curve, &m)));
        }
        solutions.sort_by(|p, q| p.max_deviation.total_cmp(&q.max_deviation));
        let nearest = if request.nearest && methods.knots && solutions.is_empty() {
            shape::nearest_reachable(&query, target, true)
                .map_err(|error| shape_error(&error))?
                .map(|nearest| NearestBody {
                    point: point_to_wire(nearest.point, curve.dimension()),
                    distance: nearest.distance,
                    solutions: nearest
                        .solutions
                        .iter()
                        .map(|s| knot_solution_body(curve, s))
                        .collect(),
                })
        } else {
            None
        };
        let response = SolveResponse {
            reachable: !solutions.is_empty(),
            candidates: membership_candidates(curve, &outcome),
            solutions,
            nearest,
        };
        Ok(response)
    })
    .await
    .map(ApiJson)
}

/// The regions' boundary polygons.
///
/// Each requested region of each side's candidate as a closed polygon, in the curve's
/// coordinates and in frame coordinates, sampled adaptively to `tolerance`. For drawing only.
#[utoipa::path(
    post,
    path = "/v1/shape/regions",
    tag = "shape",
    request_body = RegionsRequest,
    responses(
        (status = 200, description = "Boundary polygons per candidate and region (JSON, the default), or, with `Accept: image/svg+xml`, an SVG picture of them: one panel per candidate with its control triangle, the regions in their colours (polygon `points` are the JSON answer's x and y), the picked point, the target when the request has one, and a legend", content(
            (RegionsResponse = "application/json"),
            (String = "image/svg+xml"),
        )),
        (status = 400, description = "Malformed JSON, wrong types, unknown fields", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A rule is broken (see `errors`)", body = Problem, content_type = "application/problem+json"),
    ),
    security((), ("api_key" = [])),
)]
pub async fn regions(
    State(state): State<AppState>,
    admission: Option<Extension<AdmissionPermit>>,
    headers: HeaderMap,
    ApiJson(request): ApiJson<RegionsRequest>,
) -> Result<Response, ApiError> {
    let (limits, curve_limits) = (state.limits, state.curve_limits);
    // Up to two sides of six polygons, each up to the vertex limit.
    let work = 12 * limits.max_polygon_vertices.max(MIN_POLYGON_VERTEX_LIMIT);
    let svg = regions_media::prefers_svg(&headers);
    compute(admission, work, move || {
        let answer = regions_request(&request, &limits, &curve_limits)?;
        regions_media::respond(&request, answer, &curve_limits, svg)
    })
    .await
}

fn regions_request(
    request: &RegionsRequest,
    limits: &Limits,
    curve_limits: &CurveLimits,
) -> Result<RegionsResponse, ApiError> {
    let parsed = ParsedShape::parse(&request.curve, &request.regions, curve_limits);
    let tolerance_error = match request.tolerance {
        Some(tolerance) if !(tolerance.is_finite() && tolerance > 0.0) => Some(FieldError::new(
            "/tolerance",
            "`tolerance` must be a positive number",
        )),
        _ => None,
    };
    let parsed = match (parsed, tolerance_error) {
        (Ok(parsed), None) => parsed,
        (Ok(_), Some(error)) => return Err(ApiError::Invalid(vec![error])),
        (Err(ApiError::Invalid(mut errors)), Some(error)) => {
            errors.push(error);
            return Err(ApiError::Invalid(errors));
        }
        (Err(other), _) => return Err(other),
    };
    let query = parsed.query(request.parameter, request.side, request.keep_domain);
    let candidates = shape::region_polygons(
        &query,
        PolygonOptions {
            tolerance: request.tolerance,
            max_vertices: limits.max_polygon_vertices.max(MIN_POLYGON_VERTEX_LIMIT),
        },
    )
    .map_err(|error| shape_error(&error))?;
    let curve = &parsed.curve;
    let dimension = curve.dimension();
    Ok(RegionsResponse {
        candidates: candidates
            .into_iter()
            .map(|outcome| RegionsCandidate {
                candidate: candidate_body(curve, &outcome.candidate),
                regions: outcome
                    .regions
                    .into_iter()
                    .map(|region| RegionPolygonBody {
                        region: region.pair.into(),
                        knots: region.knots.map(|full| caller_knot_index(curve, full)),
                        polygon: region
                            .polygon
                            .iter()
                            .map(|&point| point_to_wire(point, dimension))
                            .collect(),
                        polygon_frame: region.polygon_frame,
                        tolerance_met: region.tolerance_met,
                    })
                    .collect(),
            })
            .collect(),
    })
}

/// The validated parts shared by the shape endpoints.
struct ParsedShape {
    curve: Curve,
    pairs: Vec<KnotPair>,
}

impl ParsedShape {
    /// Checks the degree first (the method is for cubics), then the curve and the regions.
    fn parse(
        curve: &CurveBody,
        regions: &Option<Vec<Region>>,
        curve_limits: &CurveLimits,
    ) -> Result<ParsedShape, ApiError> {
        if curve.degree != CUBIC {
            return Err(ApiError::invalid(
                "/curve/degree",
                ShapeError::NotCubic {
                    degree: curve.degree,
                }
                .to_string(),
            ));
        }
        let mut errors = Vec::new();
        let parsed_curve = match curve.parse(curve_limits, "/curve") {
            Ok(parsed) => Some(parsed),
            Err(ApiError::Invalid(curve_errors)) => {
                errors.extend(curve_errors);
                None
            }
            Err(other) => return Err(other),
        };
        let pairs = match regions {
            None => KnotPair::ALL.to_vec(),
            Some(regions) => {
                if regions.is_empty() {
                    errors.push(FieldError::new(
                        "/regions",
                        "`regions` must name at least one region (omit it for all six)",
                    ));
                }
                let mut pairs: Vec<KnotPair> = Vec::with_capacity(regions.len().min(6));
                for (index, &region) in regions.iter().enumerate() {
                    let pair = KnotPair::from(region);
                    if pairs.contains(&pair) {
                        errors.push(FieldError::new(
                            JsonPointer::from("/regions").push(index),
                            format!("region {} is listed twice", pair.name()),
                        ));
                        break;
                    }
                    pairs.push(pair);
                }
                pairs
            }
        };
        match parsed_curve {
            Some(curve) if errors.is_empty() => Ok(ParsedShape { curve, pairs }),
            _ => Err(ApiError::Invalid(errors)),
        }
    }

    fn query(&self, parameter: f64, side: SideRequest, keep_domain: bool) -> ShapeQuery<'_> {
        ShapeQuery {
            curve: &self.curve,
            // Just outside the domain: onto its end; farther out the query's check refuses it.
            parameter: self.curve.snap_to_domain(parameter).unwrap_or(parameter),
            side: side.into(),
            pairs: &self.pairs,
            keep_domain,
        }
    }
}

/// The wire form of a knot solution.
fn knot_solution_body(curve: &Curve, solution: &shape::Solution) -> SolutionBody {
    SolutionBody {
        method: Method::Knots,
        region: Some(solution.pair.into()),
        side: Some(solution.side.into()),
        span: Some(solution.span),
        moved_knot: Some(caller_knot_index(curve, solution.moved_knot)),
        changed_knots: Some(
            solution
                .changed_knots
                .iter()
                .map(|&full| caller_knot_index(curve, full))
                .collect(),
        ),
        knots: Some(knots_in_caller_convention(curve, &solution.knots)),
        control_points: None,
        changed_control_points: None,
        point: point_to_wire(solution.point, curve.dimension()),
        residual: solution.residual,
        affected_domain: [solution.affected_domain.0, solution.affected_domain.1],
        max_deviation: solution.max_deviation.unwrap_or(0.0),
    }
}

/// The wire form of a control-point solution.
fn control_point_solution_body(
    curve: &Curve,
    solution: &shape::ControlPointSolution,
) -> SolutionBody {
    let dimension = curve.dimension();
    SolutionBody {
        method: Method::ControlPoints,
        region: None,
        side: None,
        span: None,
        moved_knot: None,
        changed_knots: None,
        knots: None,
        control_points: Some(
            solution
                .control_points
                .iter()
                .map(|&p| point_to_wire(p, dimension))
                .collect(),
        ),
        changed_control_points: Some(solution.changed_control_points.clone()),
        point: point_to_wire(solution.point, dimension),
        residual: solution.residual,
        affected_domain: [solution.affected_domain.0, solution.affected_domain.1],
        max_deviation: solution.max_deviation.unwrap_or(0.0),
    }
}

/// The 422 for a core shape error, pointing at the offending request field.
fn shape_error(error: &ShapeError) -> ApiError {
    let pointer = match error.field() {
        ShapeField::Degree => JsonPointer::from("/curve/degree"),
        ShapeField::Parameter => JsonPointer::from("/parameter"),
        ShapeField::Target => JsonPointer::from("/target"),
        ShapeField::TargetCoordinate(index) => JsonPointer::from("/target").push(index),
    };
    let detail = error.to_string();
    ApiError::invalid(pointer, detail)
}

/// A full-vector knot index in the caller's convention. The shape method only names interior
/// knots, which both conventions hold; the clamp is a guard, never expected to act.
fn caller_knot_index(curve: &Curve, full_index: usize) -> usize {
    let full_len = curve.knots().len();
    curve
        .convention()
        .caller_index(full_index, full_len)
        .unwrap_or_else(|| {
            let caller_len = curve.knots_in_convention().len();
            full_index
                .saturating_sub(1)
                .min(caller_len.saturating_sub(1))
        })
}

/// A full knot vector in the caller's convention (trimmed: without the two end values).
fn knots_in_caller_convention(curve: &Curve, full: &[f64]) -> Vec<f64> {
    match curve.convention() {
        crate::spline::KnotConvention::Full => full.to_vec(),
        crate::spline::KnotConvention::Trimmed => full[1..full.len() - 1].to_vec(),
    }
}

fn candidate_body(curve: &Curve, candidate: &Candidate) -> CandidateBody {
    let dimension = curve.dimension();
    CandidateBody {
        side: candidate.side.into(),
        applicable: candidate.is_applicable(),
        reason: candidate.not_applicable.map(|reason| reason.to_string()),
        span: candidate.span,
        moved_knot: caller_knot_index(curve, candidate.moved_knot),
        triangle: candidate
            .triangle
            .map(|triangle| triangle.map(|p| point_to_wire(p, dimension))),
        frame: candidate.frame.map(|frame| FrameBody {
            x: frame.x,
            y: frame.y,
        }),
    }
}

fn membership_candidates(curve: &Curve, outcome: &SolveOutcome) -> Vec<MembershipCandidate> {
    outcome
        .candidates
        .iter()
        .map(|entry| MembershipCandidate {
            candidate: candidate_body(curve, &entry.candidate),
            regions: entry
                .regions
                .iter()
                .map(|membership| RegionMembershipBody {
                    region: membership.pair.into(),
                    knots: membership.knots.map(|full| caller_knot_index(curve, full)),
                    contains: membership.contains,
                })
                .collect(),
        })
        .collect()
}
