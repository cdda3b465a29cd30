//! Wire types of the shape answers (candidates, membership, solutions, nearest, polygons) and
//! their conversion from the core's outcomes, knot indices and vectors in the caller's
//! convention.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{WirePoint, point_to_wire};
use crate::http::error::ApiError;
use crate::http::pointer::JsonPointer;
use crate::http::wire::methods::{ControlPointMembershipBody, Method};
use crate::http::wire::shape_request::{CandidateSide, Region};
use crate::shape::{self, Candidate, CandidateRegions, ShapeError, ShapeField, SolveOutcome};
use crate::spline::Curve;

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
    /// The multiplicities of `knots`, when the curve was sent with multiplicities (knot
    /// solutions; knot indices then refer to the full vector).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities: Option<Vec<usize>>,
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
    /// With `svg_paths: true` in the request: the new curve as an SVG path `d` string (as
    /// `/v1/curves/bezier` writes it), for planar non-rational curves of degree <= 3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg_path: Option<String>,
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

/// The wire form of a knot solution.
pub fn knot_solution_body(curve: &Curve, solution: &shape::Solution) -> SolutionBody {
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
        multiplicities: crate::http::curve::knots_in_caller_form(curve, &solution.knots).1,
        control_points: None,
        changed_control_points: None,
        point: point_to_wire(solution.point, curve.dimension()),
        svg_path: None,
        residual: solution.residual,
        affected_domain: [solution.affected_domain.0, solution.affected_domain.1],
        max_deviation: solution.max_deviation.unwrap_or(0.0),
    }
}

/// The wire form of a control-point solution.
pub fn control_point_solution_body(
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
        multiplicities: None,
        control_points: Some(
            solution
                .control_points
                .iter()
                .map(|&p| point_to_wire(p, dimension))
                .collect(),
        ),
        changed_control_points: Some(solution.changed_control_points.clone()),
        point: point_to_wire(solution.point, dimension),
        svg_path: None,
        residual: solution.residual,
        affected_domain: [solution.affected_domain.0, solution.affected_domain.1],
        max_deviation: solution.max_deviation.unwrap_or(0.0),
    }
}

/// The 422 for a core shape error, pointing at the offending request field.
pub fn shape_error(error: &ShapeError) -> ApiError {
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
pub fn caller_knot_index(curve: &Curve, full_index: usize) -> usize {
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

/// A full knot vector in the caller's convention (trimmed: without the two end values;
/// multiplicities form: the distinct values, see `knots_in_caller_form`).
pub fn knots_in_caller_convention(curve: &Curve, full: &[f64]) -> Vec<f64> {
    crate::http::curve::knots_in_caller_form(curve, full).0
}

pub fn candidate_body(curve: &Curve, candidate: &Candidate) -> CandidateBody {
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

pub fn membership_candidates(curve: &Curve, outcome: &SolveOutcome) -> Vec<MembershipCandidate> {
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

/// The wire form of the regions' polygons of every requested side.
pub fn regions_response(curve: &Curve, candidates: Vec<CandidateRegions>) -> RegionsResponse {
    let dimension = curve.dimension();
    RegionsResponse {
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
    }
}

/// The SVG path of a knot solution's new curve (`None` where SVG cannot draw it exactly).
pub fn knot_solution_path(curve: &Curve, solution: &shape::Solution) -> Option<String> {
    let moved = curve.with_full_knots(solution.knots.clone())?;
    path_of(&moved)
}

/// The SVG path of a control-point solution's new curve.
pub fn control_point_solution_path(
    curve: &Curve,
    solution: &shape::ControlPointSolution,
) -> Option<String> {
    let moved = curve.with_control_points(solution.control_points.clone())?;
    path_of(&moved)
}

fn path_of(curve: &Curve) -> Option<String> {
    let pieces: Vec<_> = curve.bezier_pieces().collect();
    crate::http::svg_path::svg_path(curve, &pieces)
}
