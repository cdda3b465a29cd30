//! The small interface every way of moving a surface point answers (docs/method.md §44), the
//! surface form of the curves' [`crate::shape::EditMethod`]: its solutions for a target
//! (checked against the fixed poles it would change), what it can reach for drawing, the
//! nearest point it reaches, and how far the surface moves. The edit ([`super::solve`]) runs
//! the requested methods through it, checks the constraints, ranks by the certified deviation
//! and explains what it dropped; a new method is one implementation and one line in
//! [`SURFACE_METHODS`].

use std::fmt;

use super::constraints::{FixedNet, SurfaceConstraints};
use super::deviation::surface_max_deviation;
use super::knots::SurfaceKnotRegion;
use crate::spline::vector::Point;
use crate::surface::Surface;

/// The ways to move a surface point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SurfaceMethodKind {
    /// Knots in `u`, `v` or both ([`super::knots`]).
    Knots,
    /// The least-norm move of the free control points.
    ControlPoints,
    /// Three weights of the poles active at `(u, v)`.
    Weights,
}

impl SurfaceMethodKind {
    /// Every kind, in wire order.
    pub const ALL: [SurfaceMethodKind; 3] = [
        SurfaceMethodKind::Knots,
        SurfaceMethodKind::ControlPoints,
        SurfaceMethodKind::Weights,
    ];

    /// The wire name.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceMethodKind::Knots => "knots",
            SurfaceMethodKind::ControlPoints => "control_points",
            SurfaceMethodKind::Weights => "weights",
        }
    }

    /// Its implementation, when registered.
    pub fn method(self) -> Option<&'static dyn SurfaceEditMethod> {
        SURFACE_METHODS.iter().find(|m| m.kind() == self).copied()
    }
}

/// Every registered method, in the order their solutions are listed before ranking (a kind
/// without an implementation would be answered with an exclusion,
/// [`SurfaceExclusionReason::NotAvailable`]).
pub static SURFACE_METHODS: [&dyn SurfaceEditMethod; 3] = [
    &super::knot_method::KnotsMethod,
    &super::control_points::ControlPointsMethod,
    &super::weights::WeightsMethod,
];

/// What one surface edit works with.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceEditContext<'a> {
    /// The surface.
    pub surface: &'a Surface,
    /// The picked `(u, v)`, in the domain.
    pub parameter: (f64, f64),
    /// Checked constraints (without a clash).
    pub constraints: &'a SurfaceConstraints,
    /// Poles no solution may change.
    pub fixed: &'a FixedNet,
    /// Knot edits keep the domain (for the knot method).
    pub keep_domain: bool,
}

/// How a solution changes the surface, per method.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceSolutionDetail {
    /// New knots in `u`, `v` or both.
    Knots {
        /// The family's wire name (`iso_u_envelope` … `mixed`).
        family: &'static str,
        /// The knot set, named for people.
        region: String,
        /// Full-vector indices of the changed `u`-knots, ascending.
        changed_knots_u: Vec<usize>,
        /// Full-vector indices of the changed `v`-knots, ascending.
        changed_knots_v: Vec<usize>,
        /// The `u`- and `v`-ranges whose strips change (a mixed move changes a cross of two
        /// strips; `affected_domain` is their bounding rectangle).
        changed_ranges: [Option<(f64, f64)>; 2],
    },
    /// New control points.
    ControlPoints {
        /// The caller's `[i, j]` of the poles that moved, ascending.
        changed_control_points: Vec<[usize; 2]>,
        /// `sqrt(Σ |Δd_ij|²)` over the caller's poles.
        displacement_norm: f64,
    },
    /// New weights of three poles.
    Weights {
        /// The caller's `[i, j]` of the three poles.
        poles: [[usize; 2]; 3],
        /// Their new weights.
        weights: [f64; 3],
        /// The tetrahedron `(s₀, d_a, d_b, d_c)` that holds the target.
        tetrahedron: [Point; 4],
    },
}

impl SurfaceSolutionDetail {
    /// The method.
    pub fn method(&self) -> SurfaceMethodKind {
        match self {
            SurfaceSolutionDetail::Knots { .. } => SurfaceMethodKind::Knots,
            SurfaceSolutionDetail::ControlPoints { .. } => SurfaceMethodKind::ControlPoints,
            SurfaceSolutionDetail::Weights { .. } => SurfaceMethodKind::Weights,
        }
    }
}

/// One way to move `S(u, v)` onto the target, of any method.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceSolution {
    /// What changed.
    pub detail: SurfaceSolutionDetail,
    /// The new surface.
    pub surface: Surface,
    /// The new surface's point at `(u, v)`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// `[[u0, u1], [v0, v1]]`: outside it the new surface equals the old one.
    pub affected_domain: [(f64, f64); 2],
    /// How well the solution is determined, in `(0, 1]` (1: the linear control-point move;
    /// for weights, the tetrahedron's shape, [`super::weights::WeightTriple::conditioning`]).
    pub conditioning: f64,
    /// The certified largest `|S_old - S_new|`, once measured.
    pub max_deviation: Option<f64>,
}

/// Why solutions of a method were dropped, or why it has none.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceExclusionReason {
    /// The method is not offered by this build.
    NotAvailable,
    /// Two constraints at one place ask different values.
    Contradiction {
        /// Positions in the request.
        first: usize,
        /// Positions in the request.
        second: usize,
    },
    /// A constraint does not hold on the new surface.
    Breaks {
        /// Position in the request.
        constraint: usize,
    },
    /// The solution changes a fixed control point (its weight).
    MovesFixedPole {
        /// The caller's `[i, j]`.
        pole: [usize; 2],
    },
    /// Every control point is fixed.
    NoFreeControlPoint,
    /// Every control point acting at `(u, v)` is fixed.
    NoFreeControlPointAtTarget,
    /// The free control points cannot meet the target and the constraints together.
    Unmet,
    /// Too many poles act at `(u, v)` for the weight triples.
    TooManyActivePoles {
        /// How many act.
        count: usize,
    },
}

impl SurfaceExclusionReason {
    /// The constraint it is about, if one.
    pub fn constraint(&self) -> Option<usize> {
        match *self {
            SurfaceExclusionReason::Breaks { constraint } => Some(constraint),
            SurfaceExclusionReason::Contradiction { first, .. } => Some(first),
            _ => None,
        }
    }
}

impl fmt::Display for SurfaceExclusionReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SurfaceExclusionReason::NotAvailable => write!(
                f,
                "this method is not available for surfaces in this version of the service"
            ),
            SurfaceExclusionReason::Contradiction { first, second } => write!(
                f,
                "the constraints contradict each other: constraints[{first}] and constraints[{second}] ask different values of the same quantity"
            ),
            SurfaceExclusionReason::Breaks { constraint } => write!(
                f,
                "constraints[{constraint}] does not hold on the new surface"
            ),
            SurfaceExclusionReason::MovesFixedPole { pole } => write!(
                f,
                "it changes control point [{}, {}], which is fixed",
                pole[0], pole[1]
            ),
            SurfaceExclusionReason::NoFreeControlPoint => {
                write!(f, "the constraints leave no free control point")
            }
            SurfaceExclusionReason::NoFreeControlPointAtTarget => write!(
                f,
                "every control point acting at the picked parameter is fixed"
            ),
            SurfaceExclusionReason::Unmet => write!(
                f,
                "the free control points cannot meet the target and the constraints together"
            ),
            SurfaceExclusionReason::TooManyActivePoles { count } => write!(
                f,
                "{count} control points act at the picked parameter; the weight method looks at triples of at most {}",
                super::weights::MAX_ACTIVE_POLES
            ),
        }
    }
}

/// Dropped solutions (or a method's failure), counted per method and reason.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceExclusion {
    /// The method.
    pub method: SurfaceMethodKind,
    /// How many solutions were dropped (1 for a method that has none at all).
    pub count: usize,
    /// Why.
    pub reason: SurfaceExclusionReason,
}

/// One method's answer for a target, before the edit checks the constraints.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfaceMethodSolutions {
    /// Verified solutions (deviation not yet measured).
    pub solutions: Vec<SurfaceSolution>,
    /// What the method itself dropped, and why.
    pub excluded: Vec<SurfaceExclusion>,
}

/// A weight triple's reachable set, for drawing: the tetrahedron (the weight bounds cut it
/// further near its faces).
#[derive(Debug, Clone, PartialEq)]
pub struct TetrahedronRegion {
    /// The caller's `[i, j]` of the three poles.
    pub poles: [[usize; 2]; 3],
    /// `(s₀, d_a, d_b, d_c)`.
    pub tetrahedron: [Point; 4],
}

/// What a method can reach, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceReachable {
    /// Every target (the control-point move, when its system is solvable).
    Everywhere,
    /// The weight triples' tetrahedra.
    Tetrahedra(Vec<TetrahedronRegion>),
    /// The one-direction knot families' planar regions (the mixed moves reach solids, not
    /// drawn).
    KnotRegions(Vec<SurfaceKnotRegion>),
    /// Nothing (every pole fixed, or the method refused), with the reason.
    Nothing(SurfaceExclusionReason),
}

/// The nearest point a method reaches, and its solutions there.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceNearest {
    /// The reachable point nearest to the target.
    pub point: Point,
    /// Solutions reaching `point` (residuals measured from it).
    pub solutions: Vec<SurfaceSolution>,
}

/// One way of moving the picked surface point (module docs).
pub trait SurfaceEditMethod: Sync {
    /// Which method this is.
    fn kind(&self) -> SurfaceMethodKind;

    /// Every way it moves `S(u, v)` onto `target` without changing a fixed pole (the edit
    /// checks the constraints on every solution again).
    fn solve(&self, edit: &SurfaceEditContext, target: Point) -> SurfaceMethodSolutions;

    /// What it can reach, for drawing.
    fn reachable(&self, edit: &SurfaceEditContext) -> SurfaceReachable;

    /// The reachable point nearest to `target` with its solutions, for a method whose
    /// reachable set is bounded (the control-point move reaches everything: `None`).
    fn nearest(&self, edit: &SurfaceEditContext, target: Point) -> Option<SurfaceNearest>;

    /// How far the surface moves: the certified largest `|S_old - S_new|` on the affected
    /// rectangle ([`surface_max_deviation`]).
    fn deviation(&self, old: &Surface, solution: &SurfaceSolution) -> f64 {
        surface_max_deviation(old, &solution.surface, solution.affected_domain)
    }
}
