//! The shape core: move a curve point `s(t)` to a target by moving knots (Juhász & Hoffmann;
//! Tornai's knot pairs Ω1–Ω6), control points or two weights, under constraints, per
//! docs/method.md §3–§21.
//!
//! For a cubic curve and a picked parameter `t`, one knot next to `t` moves to `t` (the
//! [`Side`]); two more knots around it (a [`KnotPair`]) are solved in closed form so that
//! the envelope point, and hence the new curve at `t`, lands on the target. The control-point
//! move ([`control_points`]) and the weight pairs ([`weights`]) work on any degree. Each
//! method answers the same small interface ([`EditMethod`]); one [`edit`] runs the requested
//! ones, applies the [`ConstraintSet`] and ranks. Pure geometry: no HTTP, wire-format or
//! logging types.

mod candidate;
mod constraints;
pub mod control_points;
mod deviation;
mod edit;
pub mod family;
mod fixed_poles;
mod knot_method;
mod least_norm;
mod method;
mod nearest;
mod pairs;
mod periodic_edit;
mod regions;
mod solve;
pub mod weights;

pub use candidate::{
    Candidate, DEGENERACY_TOLERANCE, Frame, NotApplicable, PLANE_TOLERANCE, Side, SideChoice,
    candidate, frame_to_point,
};
pub use constraints::{
    Breach, CONSTRAINT_TOLERANCE, Condition, ConstraintError, ConstraintField, ConstraintIssue,
    ConstraintSet, ConstraintSpec, FixedPoleError, FixedPoles, MAX_CONSTRAINTS, Requirement,
    edit_size,
};
pub use control_points::{
    CONTROL_POINT_RESIDUAL, ControlPointFailure, ControlPointSolution, PoleVariables,
    constrained_control_point_move, control_point_move,
};
pub use deviation::{DEVIATION_RELATIVE_TOLERANCE, max_deviation, max_deviation_of_moved_poles};
pub use edit::{
    EditOptions, EditOutcome, Exclusion, ExclusionReason, ReachableRegions, WeightPairMembership,
    admissibility, edit, reachable_regions,
};
pub use least_norm::{DenseSystem, LeastNormSolution, RANK_TOLERANCE};
pub use method::{
    EditContext, EditMethod, EditSolution, METHODS, MethodFailure, MethodKind, MethodMembership,
    MethodNearest, MethodSolutions, Reachable, RegionKey, SolutionDetail, WeightRegion,
};
pub use nearest::{NEAREST_SAMPLING_TOLERANCE, NearestOutcome, nearest_reachable};
pub use pairs::{
    CLAMP_TOLERANCE, FRAME_ZERO_TOLERANCE, KNOT_TOLERANCE, KnotPair, LocalKnot, LocalKnots,
    solve_pair,
};
pub use regions::{
    CandidateRegions, DEFAULT_RELATIVE_TOLERANCE, PolygonOptions, RegionPolygon, domain_corners,
    frame_of, region_polygons,
};
pub use solve::{
    CandidateOutcome, RESIDUAL_TOLERANCE, RegionMembership, ShapeError, ShapeField, ShapeQuery,
    Solution, SolveOptions, SolveOutcome, affected_domain, membership, solve, target_point,
};
pub use weights::{
    WEIGHT_ABSOLUTE_RANGE, WEIGHT_RATIO_LIMIT, WeightMove, WeightPair, weight_bounds, weight_pairs,
};
