//! The small interface every way of moving a curve point answers (docs/method.md §21): its
//! solutions for a target, what it can reach, the nearest point it reaches, and how far the
//! curve moves. The edit ([`super::edit`]) runs the requested methods through it, applies the
//! constraints, ranks and explains; a new method is one file with an [`EditMethod`] and one
//! line in [`METHODS`].

use super::candidate::Side;
use super::constraints::{ConstraintSet, FixedPoles};
use super::control_points::{ControlPointFailure, PoleVariables};
use super::deviation::max_deviation_of_moved_poles;
use super::family::{Family, FamilyGroup, FamilyRegions, KnotSet};
use super::pairs::KnotPair;
use super::regions::{CandidateRegions, PolygonOptions};
use super::solve::{CandidateOutcome, ShapeError, ShapeQuery};
use super::weights::WeightPair;
use crate::spline::Curve;
use crate::spline::vector::Point;

/// The ways to move a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MethodKind {
    /// Knots: the envelope pairs (Ω1–Ω6 on cubics), the direct pairs and triples, every
    /// degree ≥ 2.
    Knots,
    /// The least-norm move of the free control points.
    ControlPoints,
    /// Two weights of the poles active at `t`.
    Weights,
}

impl MethodKind {
    /// The wire name.
    pub fn name(self) -> &'static str {
        match self {
            MethodKind::Knots => "knots",
            MethodKind::ControlPoints => "control_points",
            MethodKind::Weights => "weights",
        }
    }

    /// Its implementation.
    pub fn method(self) -> &'static dyn EditMethod {
        match METHODS.iter().find(|m| m.kind() == self) {
            Some(method) => *method,
            None => unreachable!("every method kind is registered in METHODS"),
        }
    }
}

/// Every method, in the order their solutions are listed before ranking.
pub static METHODS: [&dyn EditMethod; 3] = [
    &super::knot_method::KnotPairs,
    &super::control_points::ControlPoints,
    &super::weights::Weights,
];

/// What one edit works with: the curve and picked parameter (with the knot pairs' side and
/// region choices), the validated constraints and the free pole variables.
#[derive(Debug, Clone, Copy)]
pub struct EditContext<'a> {
    /// Curve, parameter, sides, knot pairs, `keep_domain`.
    pub query: ShapeQuery<'a>,
    /// Checked constraints.
    pub constraints: &'a ConstraintSet,
    /// Control points no solution may move (nor change the weight of).
    pub fixed: &'a FixedPoles,
    /// The free poles as variables of the control-point system.
    pub variables: &'a PoleVariables,
}

/// How a solution changes the curve, per method.
#[derive(Debug, Clone, PartialEq)]
pub enum SolutionDetail {
    /// New knots.
    Knots {
        /// The family.
        family: Family,
        /// Ω1–Ω6 for a cubic's envelope pairs.
        pair: Option<KnotPair>,
        /// The envelope's side.
        side: Option<Side>,
        /// The span `j` of the family's problem.
        span: usize,
        /// The envelope's knot set to `t` (full index).
        moved_knot: Option<usize>,
        /// The pair's or triple's knots (full indices).
        knots_moved: KnotSet,
        /// Full-vector indices whose values changed, ascending.
        changed_knots: Vec<usize>,
        /// How well the solution is determined ([`super::family::KnotSolution::conditioning`]).
        conditioning: f64,
    },
    /// New control points.
    ControlPoints {
        /// Indices of the control points that moved, ascending.
        changed_control_points: Vec<usize>,
    },
    /// New weights of two poles.
    Weights {
        /// `[k, l]`.
        poles: [usize; 2],
        /// Indices whose weights changed, ascending.
        changed_weights: Vec<usize>,
    },
}

impl SolutionDetail {
    /// The method.
    pub fn method(&self) -> MethodKind {
        match self {
            SolutionDetail::Knots { .. } => MethodKind::Knots,
            SolutionDetail::ControlPoints { .. } => MethodKind::ControlPoints,
            SolutionDetail::Weights { .. } => MethodKind::Weights,
        }
    }
}

/// One way to move `s(t)` onto the target, of any method.
#[derive(Debug, Clone, PartialEq)]
pub struct EditSolution {
    /// What changed.
    pub detail: SolutionDetail,
    /// The new curve.
    pub curve: Curve,
    /// The new curve's point at `t`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[lo, hi]`: outside it the new curve equals the old one.
    pub affected_domain: (f64, f64),
    /// Largest `|s_old(u) - s_new(u)|` over the domain, when measured.
    pub max_deviation: Option<f64>,
}

/// Which part of a method's reachable set a solution belongs to, for membership answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RegionKey {
    /// A pair or triple of a knot family (and side, for the envelope).
    Knots {
        /// The family.
        family: Family,
        /// The envelope's side.
        side: Option<Side>,
        /// The knots it moves.
        knots: KnotSet,
    },
    /// A weight pair.
    Weights([usize; 2]),
    /// The control-point move (one answer).
    ControlPoints,
}

impl EditSolution {
    /// The region (pair) of its method that holds the target.
    pub fn region_key(&self) -> RegionKey {
        match self.detail {
            SolutionDetail::Knots {
                family,
                side,
                knots_moved,
                ..
            } => RegionKey::Knots {
                family,
                side,
                knots: knots_moved,
            },
            SolutionDetail::Weights { poles, .. } => RegionKey::Weights(poles),
            SolutionDetail::ControlPoints { .. } => RegionKey::ControlPoints,
        }
    }
}

/// Why a method gave no solution at all, before any constraint was checked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodFailure {
    /// The control-point system has no solution.
    ControlPoints(ControlPointFailure),
}

/// The solutions of one method, before the edit checks them against the constraints, with
/// what its membership answer lists.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodSolutions {
    /// Every solution (the deviation not yet measured).
    pub solutions: Vec<EditSolution>,
    /// Why there is none, when the method itself says so.
    pub failure: Option<MethodFailure>,
    /// The parts its membership answer lists.
    pub membership: MethodMembership,
}

/// The parts of a method's reachable set that a membership answer lists.
#[derive(Debug, Clone, PartialEq)]
pub enum MethodMembership {
    /// Knots: the cubic's envelope candidates of the requested sides (each with its
    /// requested pairs), and every requested family with its pairs or triples.
    Knots {
        /// The cubic's envelope candidates (empty on other degrees).
        candidates: Vec<CandidateOutcome>,
        /// The families.
        groups: Vec<FamilyGroup>,
    },
    /// Weights: every pair of poles active at `t`.
    WeightPairs(Vec<[usize; 2]>),
    /// The control-point move: one answer.
    Single,
}

/// A weight pair's reachable quadrilateral, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct WeightRegion {
    /// The pair, its triangle and bounds.
    pub pair: WeightPair,
    /// The closed boundary (first vertex repeated last) in the curve's coordinates.
    pub polygon: Vec<Point>,
    /// The same in the pair's frame `(λ_k, λ_l)` ([`WeightPair::frame_of`]).
    pub polygon_frame: Vec<[f64; 2]>,
}

/// What a method can reach, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub enum Reachable {
    /// Every target (the control-point move, when its system is solvable).
    Everywhere,
    /// The knot families' regions (with `keep_domain` applied): a cubic's envelope
    /// candidates in their original form, and every family's pairs.
    KnotRegions {
        /// The cubic's envelope candidates (empty on other degrees).
        candidates: Vec<CandidateRegions>,
        /// Every requested family.
        families: Vec<FamilyRegions>,
    },
    /// Each weight pair's quadrilateral.
    WeightRegions(Vec<WeightRegion>),
}

/// The nearest point a method reaches, and its solutions there.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodNearest {
    /// The reachable point nearest to the target.
    pub point: Point,
    /// Solutions that reach `point` (residuals measured from it), best first.
    pub solutions: Vec<EditSolution>,
}

/// One way of moving the picked point (module docs).
pub trait EditMethod: Sync {
    /// Which method this is.
    fn kind(&self) -> MethodKind;

    /// Why the method cannot edit `curve` at all (e.g. the knot pairs need a cubic).
    fn refuses(&self, curve: &Curve) -> Option<ShapeError>;

    /// Every way it moves `s(t)` onto `target`. The control-point move builds the constraints
    /// in; the others are checked by the edit.
    fn solve(&self, edit: &EditContext, target: Point) -> MethodSolutions;

    /// What it can reach, for drawing.
    fn reachable(&self, edit: &EditContext, options: PolygonOptions) -> Reachable;

    /// The reachable point nearest to `target`, when something is reachable and the method
    /// has a bounded reachable set (the control-point move reaches everything: `None`).
    fn nearest(&self, edit: &EditContext, target: Point) -> Option<MethodNearest>;

    /// How far the curve moves: the largest `|s_old(u) - s_new(u)|` on the affected domain,
    /// certified by Bernstein branch and bound ([`super::max_deviation`]).
    fn deviation(&self, old: &Curve, solution: &EditSolution) -> f64 {
        max_deviation_of_moved_poles(old, &solution.curve, solution.affected_domain)
    }
}
