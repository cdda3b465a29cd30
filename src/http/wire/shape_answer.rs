//! Wire types of the shape answers (candidates, membership, solutions, nearest, polygons) and
//! their conversion from the core's outcomes, knot indices and vectors in the caller's
//! convention.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{WirePoint, point_to_wire};
use crate::http::error::ApiError;
use crate::http::pointer::JsonPointer;
use crate::http::wire::families::{FamilyMembershipBody, FamilyRegionsBody, family_regions_bodies};
use crate::http::wire::methods::{ControlPointMembershipBody, ExclusionBody, WeightMembershipBody};
use crate::http::wire::shape_request::{CandidateSide, Region};
use crate::http::wire::solutions::SolutionBody;
use crate::shape::{
    Candidate, CandidateOutcome, CandidateRegions, ReachableRegions, ShapeError, ShapeField,
    WeightRegion,
};
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
    /// The control points `d_{j-2}, d_{j-1}, d_j` (every side has them, also one that does
    /// not apply; the OpenAPI document requires them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Vec<Vec<f64>>>)]
    pub triangle: Option<[WirePoint; 3]>,
    /// The target's frame coordinates: in membership and solve answers on every applicable
    /// side (required there), never in regions answers (which have no target).
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
#[schema(example = json!({"reachable": true, "excluded": [], "families": [{"family": "envelope", "side": "left", "applicable": true, "span": 4, "moved_knot": 5, "control_points": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "pairs": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}], "candidates": [{"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "frame": {"x": 0.18, "y": 0.106667}, "regions": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}]}))]
pub struct MembershipResponse {
    /// Whether any requested method reaches the target: a region of a candidate holds it, a
    /// weight pair does, or the control-point move meets it (and every constraint).
    pub reachable: bool,
    /// A cubic's envelope candidates, one per requested side, when `methods` holds `knots`
    /// (else empty).
    pub candidates: Vec<MembershipCandidate>,
    /// Every requested knot family (and envelope side) with the membership of its pairs or
    /// triples, when `methods` holds `knots` (else empty); a cubic's envelope is here too.
    pub families: Vec<FamilyMembershipBody>,
    /// The control-point move, when `methods` holds `control_points`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control_points: Option<ControlPointMembershipBody>,
    /// The weight pairs, when `methods` holds `weights`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<WeightMembershipBody>,
    /// Per method and reason, what the constraints and fixed control points ruled out (as in
    /// the solve answer).
    pub excluded: Vec<ExclusionBody>,
}

/// The reachable point nearest to an unreachable target, and the solutions that reach it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"point": [5.2, 3.9], "distance": 0.41, "solutions": [{"method": "knots", "family": "envelope", "region": "omega3", "side": "right", "span": 5, "moved_knot": 6, "solved_knots": [7, 8], "changed_knots": [6, 7, 8], "conditioning": 0.12,
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

/// Every way the requested methods move `s(t)` to the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"reachable": true, "families": [{"family": "envelope", "side": "left", "applicable": true, "span": 4, "moved_knot": 5, "control_points": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "pairs": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}], "candidates": [{"side": "left", "applicable": true, "span": 4, "moved_knot": 5,
              "triangle": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "frame": {"x": 0.18, "y": 0.106667}, "regions": [{"region": "omega2", "knots": [4, 6], "contains": true}, {"region": "omega4", "knots": [3, 6], "contains": false}]}], "excluded": [], "solutions": [{"method": "knots", "family": "envelope", "region": "omega2", "side": "left", "span": 4, "moved_knot": 5, "solved_knots": [4, 6], "changed_knots": [4, 5, 6], "conditioning": 0.21,
     "knots": [0, 0, 0, 0, 0.3, 0.42, 0.6, 0.75, 1, 1, 1, 1], "point": [4.746667, 3.323333],
     "residual": 3.2e-15, "affected_domain": [0, 1], "max_deviation": 1.030559}]}))]
pub struct SolveResponse {
    /// Whether any solution exists (`false` is a normal answer, not an error).
    pub reachable: bool,
    /// A cubic's envelope candidates, one per requested side, with region membership, when
    /// `methods` holds `knots` (else empty).
    pub candidates: Vec<MembershipCandidate>,
    /// Every requested knot family (and envelope side) with the membership of its pairs or
    /// triples, when `methods` holds `knots` (else empty); a cubic's envelope is here too.
    pub families: Vec<FamilyMembershipBody>,
    /// Every solution of every requested method, sorted by `max_deviation`, smallest first.
    pub solutions: Vec<SolutionBody>,
    /// With `nearest: true`, when no solution reaches the target: the nearest reachable
    /// point. Absent when the target is reachable or nothing at all is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nearest: Option<NearestBody>,
    /// Per method and reason, the solutions that the constraints or fixed control points
    /// ruled out, and methods that could not meet them at all (empty without constraints).
    pub excluded: Vec<ExclusionBody>,
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
     "tolerance_met": true}]}],
     "families": [{"family": "envelope", "side": "left", "applicable": true, "span": 4, "moved_knot": 5,
       "control_points": [[3.0, 4.0], [5.0, 3.5], [6.0, 1.0]], "regions": [{"region": "omega2", "knots": [4, 6],
       "polygon": [[5.56, 2.1], [4.9264, 2.8128], [4.12, 3.72], [5.0, 3.5], [5.56, 2.1]],
       "polygons": [[[5.56, 2.1], [4.9264, 2.8128], [4.12, 3.72], [5.0, 3.5], [5.56, 2.1]]],
       "folded": false, "tolerance_met": true,
       "polygon_frame": [[0.0, 0.56], [0.1936, 0.3136], [0.44, 0.0], [0.0, 0.0], [0.0, 0.56]]}]}],
     "weight_regions": []}))]
pub struct RegionsResponse {
    /// A cubic's envelope candidates, one per requested side, when `methods` holds `knots`
    /// (else empty).
    pub candidates: Vec<RegionsCandidate>,
    /// Every requested knot family (and envelope side) with its pairs' regions, when
    /// `methods` holds `knots` (else empty); a cubic's envelope is here too.
    pub families: Vec<FamilyRegionsBody>,
    /// Each weight pair's reachable quadrilateral, when `methods` holds `weights` (pairs with
    /// a fixed pole left out).
    pub weight_regions: Vec<WeightRegionBody>,
}

/// `"weights"`: the kind of a weight pair's region.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("weights"))]
pub enum WeightsRegion {
    /// A weight pair's reachable set.
    Weights,
}

/// The targets one pair of poles reaches by its weights within the weight bounds: a convex
/// quadrilateral inside the triangle `(s₀, d_k, d_l)`, exact (its edges are straight).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"region": "weights", "poles": [3, 5],
     "triangle": [[4.6, 2.9], [5.0, 3.5], [8.0, 0.0]],
     "polygon": [[4.61, 2.91], [4.99, 3.48], [5.04, 3.44], [7.9, 0.07], [4.61, 2.91]],
     "polygon_frame": [[0.002, 0.003], [0.98, 0.004], [0.97, 0.02], [0.01, 0.97], [0.002, 0.003]],
     "tolerance_met": true}))]
pub struct WeightRegionBody {
    /// `"weights"`.
    pub region: WeightsRegion,
    /// The pair of poles `[k, l]`.
    pub poles: [usize; 2],
    /// `s₀` (the curve point at `parameter` of the other poles alone), `d_k`, `d_l`.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub triangle: [WirePoint; 3],
    /// Closed boundary polygon (first vertex repeated last) in the curve's coordinates: the
    /// images of the weight bounds' four corners.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub polygon: Vec<WirePoint>,
    /// The same in the triangle's barycentric coordinates `[λ_k, λ_l]`
    /// (`p = s₀ + λ_k (d_k - s₀) + λ_l (d_l - s₀)`).
    pub polygon_frame: Vec<[f64; 2]>,
    /// Always true: the polygon is the exact boundary.
    pub tolerance_met: bool,
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

pub fn membership_candidates(
    curve: &Curve,
    candidates: &[CandidateOutcome],
) -> Vec<MembershipCandidate> {
    candidates
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

/// The wire form of a weight pair's region.
fn weight_region_body(curve: &Curve, region: &WeightRegion) -> WeightRegionBody {
    let dimension = curve.dimension();
    WeightRegionBody {
        region: WeightsRegion::Weights,
        poles: region.pair.poles,
        triangle: region.pair.triangle.map(|p| point_to_wire(p, dimension)),
        polygon: region
            .polygon
            .iter()
            .map(|&p| point_to_wire(p, dimension))
            .collect(),
        polygon_frame: region.polygon_frame.clone(),
        tolerance_met: true,
    }
}

/// The wire form of the reachable regions of every requested method.
pub fn regions_response(curve: &Curve, reachable: ReachableRegions) -> RegionsResponse {
    let dimension = curve.dimension();
    let candidates: Vec<CandidateRegions> = reachable.candidates;
    RegionsResponse {
        families: family_regions_bodies(curve, &reachable.families),
        weight_regions: reachable
            .weight_regions
            .iter()
            .map(|region| weight_region_body(curve, region))
            .collect(),
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
