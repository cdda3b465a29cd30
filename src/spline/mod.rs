//! The spline core: validated B-spline/NURBS curves, evaluation, the knot-moving envelope,
//! knot insertion, Bézier pieces and certified tessellation; curves through and near points,
//! degree elevation, knot removal, splitting, arc length and curvature.
//!
//! Pure geometry: no HTTP, wire-format or logging types. Conventions follow docs/method.md §1:
//! degree `p`, order `k = p + 1`, control points `d_0 ..= d_n`, full knot vector
//! `u_0 ..= u_{n+p+1}`, domain `[u_p, u_{n+1}]`.

mod basis;
pub(crate) mod bernstein;
mod bezier;
pub(crate) mod box_tree;
mod closest;
mod curve;
mod envelope;
mod eval;
mod insert;
mod other_knots;
mod periodic;
mod rational_basis;
mod tessellate;
// Curves from points and the rest of the toolkit (third release).
mod approximate;
pub mod banded;
mod curvature;
mod elevate;
mod fit_points;
mod interpolate;
mod length;
mod remove;
mod split;
pub use other_knots::PowerPiece;
pub mod vector;

pub use basis::MAX_DEGREE;
pub use bezier::{BezierPiece, BezierPieces};
pub use closest::{CLOSEST_POINT_TOLERANCE, ClosestPoint, ClosestPointError, ClosestPointSearch};
pub use curve::{
    CallerKnots, Curve, CurveError, CurveField, CurveLimits, DOMAIN_END_SLACK, DOMAIN_END_ULPS,
    Dimension, KnotConvention, KnotForm, distinct_knots, snap_parameter,
};
// The pieces the surfaces (crate::surface) build on, one direction at a time.
pub(crate) use basis::{CAP, basis_functions, basis_functions_of_every_degree, find_span};
pub(crate) use curve::validate_knots;
pub use envelope::{EnvelopeError, KnotRun};
pub use eval::{BatchEvaluator, EvalError};
pub(crate) use eval::{first_hodograph_point, hodograph_difference, multiply_add};
pub use insert::{EDITING_KNOT_SPACING, EDITING_KNOTS_EACH_SIDE, InsertError};
pub(crate) use other_knots::bezier_of_net;
pub(crate) use periodic::Periodicity;
pub use periodic::{PeriodicWindow, WrapError};
pub use rational_basis::{MAX_BASIS_ORDER, RationalBasis};
pub use tessellate::{ROUNDING_MARGIN, TOLERANCE_FLOOR, TessellationError, distance_to_segment};
pub use vector::Point;

pub use approximate::{
    APPROXIMATION_TOLERANCE_FLOOR, Approximation, ApproximationError, ApproximationSpec,
    approximate,
};
pub use curvature::CURVATURE_TANGENT_FLOOR;
pub use elevate::ElevateError;
pub use fit_points::{
    COINCIDENT_POINT_TOLERANCE, Parametrization, PointSet, PointsError, PointsField,
};
pub use interpolate::{
    Interpolation, InterpolationError, InterpolationField, InterpolationSpec, ParameterChoice,
    averaged_knots, interpolate, periodic_knots,
};
pub use length::{
    ArcLength, LENGTH_ESTIMATE_TARGET, LENGTH_RELATIVE_ERROR, LengthError, gauss_legendre_rule,
};
pub use remove::{EXACT_REMOVAL_ALLOWANCE, KnotRemoval, MAX_REMOVAL_ROUNDS, RemoveError};
pub use split::SplitError;
