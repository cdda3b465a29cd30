//! Wire types of the solutions of every method — a union discriminated by `method` — and their
//! conversion from the core's [`EditSolution`], knot indices and vectors in the caller's
//! convention.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{WirePoint, point_to_wire};
use crate::http::wire::families::{KnotFamily, region_label};
use crate::http::wire::shape_answer::caller_knot_index;
use crate::http::wire::shape_request::CandidateSide;
use crate::shape::{EditSolution, SolutionDetail};
use crate::spline::Curve;

/// `"knots"`: the tag of a knot-pair solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("knots"))]
pub enum KnotsMethod {
    /// The knot-pair method.
    Knots,
}

/// `"control_points"`: the tag of a control-point solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("control_points"))]
pub enum ControlPointsMethod {
    /// The control-point move.
    ControlPoints,
}

/// `"weights"`: the tag of a weight solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
#[schema(example = json!("weights"))]
pub enum WeightsMethod {
    /// The weight pairs.
    Weights,
}

/// New knots that move `s(t)` onto the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "knots", "family": "envelope", "region": "omega2", "side": "left", "span": 4, "moved_knot": 5,
     "solved_knots": [4, 6], "changed_knots": [4, 5, 6],
     "knots": [0, 0, 0, 0, 0.3, 0.42, 0.6, 0.75, 1, 1, 1, 1], "point": [4.746667, 3.323333],
     "residual": 3.2e-15, "affected_domain": [0, 1], "max_deviation": 1.030559, "conditioning": 0.21}))]
pub struct KnotSolutionBody {
    /// `"knots"`.
    pub method: KnotsMethod,
    /// The knot family.
    pub family: KnotFamily,
    /// The pair or triple that reaches the target: `"omega1"` … `"omega6"` for a cubic's
    /// envelope pairs, otherwise `"<family>:<a>,<b>"` (or `"triples:<a>,<b>,<c>"`) with the
    /// knots' indices in the caller's convention.
    #[schema(example = "omega2")]
    pub region: String,
    /// The envelope's side: which knot moved to `t`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<CandidateSide>,
    /// The span `j` (full-vector numbering, as in the candidates and families).
    pub span: usize,
    /// The envelope's knot set to `t` (caller's convention).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moved_knot: Option<usize>,
    /// Indices (caller's convention) of the pair's or triple's knots.
    pub solved_knots: Vec<usize>,
    /// How well the solution is determined: the smallest singular value of the point's
    /// derivative with respect to the solved knots (each scaled by its room), over the size
    /// of the control points acting. Near 0 close to a fold of the map or for knots far
    /// from `t`: such a solution moves a lot for a small change of the target. Among
    /// solutions of (nearly) equal `max_deviation` the better determined comes first.
    pub conditioning: f64,
    /// Indices (caller's convention) of the knots whose values changed, ascending.
    pub changed_knots: Vec<usize>,
    /// The whole new knot vector, in the caller's convention.
    pub knots: Vec<f64>,
    /// The multiplicities of `knots`, when the curve was sent with multiplicities (knot
    /// indices then refer to the full vector).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities: Option<Vec<usize>>,
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

/// New control points that move `s(t)` onto the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "control_points", "control_points": [[0, 0], [1, 3], [3.05, 4.1], [4.9, 3.3], [6.1, 1.2], [8, 0], [9, 2], [10, 4]],
     "changed_control_points": [2, 3, 4], "point": [4.746667, 3.323333],
     "residual": 1.1e-15, "affected_domain": [0.2, 0.75], "max_deviation": 0.21}))]
pub struct ControlPointSolutionBody {
    /// `"control_points"`.
    pub method: ControlPointsMethod,
    /// The whole new list of control points, in the caller's order.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub control_points: Vec<WirePoint>,
    /// Indices of the control points that moved, ascending.
    pub changed_control_points: Vec<usize>,
    /// The new curve's point at `parameter`.
    #[schema(value_type = Vec<f64>)]
    pub point: WirePoint,
    /// With `svg_paths: true`: the new curve's SVG path (planar non-rational curves of degree
    /// <= 3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub svg_path: Option<String>,
    /// `|point - target|` (for `nearest` solutions: `|point - nearest.point|`).
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: [f64; 2],
    /// Largest distance between the old and the new curve (certified).
    pub max_deviation: f64,
}

/// New weights of two poles that move `s(t)` onto the target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[schema(example = json!({"method": "weights", "poles": [3, 5], "weights": [1, 1, 1, 1.8, 1, 0.62, 1, 1],
     "changed_weights": [3, 5], "point": [4.9, 3.2],
     "residual": 4.4e-16, "affected_domain": [0.2, 1], "max_deviation": 0.19}))]
pub struct WeightSolutionBody {
    /// `"weights"`.
    pub method: WeightsMethod,
    /// The pair of poles `[k, l]` whose weights change.
    pub poles: [usize; 2],
    /// The whole new list of weights (a curve without weights gets them: all 1 but the
    /// changed ones).
    pub weights: Vec<f64>,
    /// Indices of the weights that changed, ascending.
    pub changed_weights: Vec<usize>,
    /// The new curve's point at `parameter`.
    #[schema(value_type = Vec<f64>)]
    pub point: WirePoint,
    /// `|point - target|` (for `nearest` solutions: `|point - nearest.point|`). (No
    /// `svg_path`: the new curve is rational, which an SVG path cannot draw exactly.)
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: [f64; 2],
    /// Largest distance between the old and the new curve (certified).
    pub max_deviation: f64,
}

/// One way to move `s(t)` onto the target, by its `method`: new knots, new control points or
/// new weights.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
#[schema(example = json!({"method": "knots", "family": "envelope", "region": "omega2", "side": "left", "span": 4, "moved_knot": 5,
     "solved_knots": [4, 6], "changed_knots": [4, 5, 6],
     "knots": [0, 0, 0, 0, 0.3, 0.42, 0.6, 0.75, 1, 1, 1, 1], "point": [4.746667, 3.323333],
     "residual": 3.2e-15, "affected_domain": [0, 1], "max_deviation": 1.030559, "conditioning": 0.21}))]
#[schema(discriminator(property_name = "method", mapping(
    ("knots" = "#/components/schemas/KnotSolutionBody"),
    ("control_points" = "#/components/schemas/ControlPointSolutionBody"),
    ("weights" = "#/components/schemas/WeightSolutionBody"),
)))]
pub enum SolutionBody {
    /// New knots.
    Knots(KnotSolutionBody),
    /// New control points.
    ControlPoints(ControlPointSolutionBody),
    /// New weights.
    Weights(WeightSolutionBody),
}

impl SolutionBody {
    /// `max_deviation`, whatever the method.
    pub fn max_deviation(&self) -> f64 {
        match self {
            SolutionBody::Knots(s) => s.max_deviation,
            SolutionBody::ControlPoints(s) => s.max_deviation,
            SolutionBody::Weights(s) => s.max_deviation,
        }
    }
}

/// The wire form of a solution of `curve`'s edit; with `svg_path`, the new curve's SVG path
/// where SVG draws it exactly.
pub fn solution_body(curve: &Curve, solution: &EditSolution, svg_path: bool) -> SolutionBody {
    let dimension = curve.dimension();
    let point = point_to_wire(solution.point, dimension);
    let affected_domain = [solution.affected_domain.0, solution.affected_domain.1];
    let max_deviation = solution.max_deviation.unwrap_or(0.0);
    let residual = solution.residual;
    let svg_path = svg_path.then(|| path_of(&solution.curve)).flatten();
    // A periodic solution's curve is already in the periodic form (of one period); any other
    // is written in the caller's form of the request's curve.
    let new_knots = if solution.curve.is_periodic() {
        solution.curve.caller_knots()
    } else {
        curve.full_knots_in_caller_form(solution.curve.knots())
    };
    match &solution.detail {
        SolutionDetail::Knots {
            family,
            pair,
            side,
            span,
            moved_knot,
            knots_moved,
            changed_knots,
            conditioning,
        } => SolutionBody::Knots(KnotSolutionBody {
            method: KnotsMethod::Knots,
            family: (*family).into(),
            region: region_label(curve, *family, *pair, knots_moved),
            side: side.map(Into::into),
            span: *span,
            moved_knot: moved_knot.map(|i| caller_knot_index(curve, i)),
            solved_knots: knots_moved
                .indices()
                .iter()
                .map(|&i| caller_knot_index(curve, i))
                .collect(),
            conditioning: *conditioning,
            changed_knots: changed_knots
                .iter()
                .map(|&full| caller_knot_index(curve, full))
                .collect(),
            knots: new_knots.knots,
            multiplicities: new_knots.multiplicities,
            point,
            svg_path,
            residual,
            affected_domain,
            max_deviation,
        }),
        SolutionDetail::ControlPoints {
            changed_control_points,
        } => SolutionBody::ControlPoints(ControlPointSolutionBody {
            method: ControlPointsMethod::ControlPoints,
            control_points: solution
                .curve
                .caller_control_points()
                .iter()
                .map(|&p| point_to_wire(p, dimension))
                .collect(),
            changed_control_points: changed_control_points.clone(),
            point,
            svg_path,
            residual,
            affected_domain,
            max_deviation,
        }),
        SolutionDetail::Weights {
            poles,
            changed_weights,
        } => SolutionBody::Weights(WeightSolutionBody {
            method: WeightsMethod::Weights,
            poles: *poles,
            weights: solution
                .curve
                .caller_weights()
                .map(<[f64]>::to_vec)
                .unwrap_or_default(),
            changed_weights: changed_weights.clone(),
            point,
            residual,
            affected_domain,
            max_deviation,
        }),
    }
}

/// The SVG path of a new curve (`None` where SVG cannot draw it exactly).
fn path_of(curve: &Curve) -> Option<String> {
    let pieces: Vec<_> = curve.bezier_pieces().collect();
    crate::http::svg_path::svg_path(curve, &pieces)
}
