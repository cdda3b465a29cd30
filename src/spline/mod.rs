//! The spline core: validated B-spline/NURBS curves, evaluation, the knot-moving envelope,
//! knot insertion, Bézier pieces and certified tessellation.
//!
//! Pure geometry: no HTTP, wire-format or logging types. Conventions follow docs/method.md §1:
//! degree `p`, order `k = p + 1`, control points `d_0 ..= d_n`, full knot vector
//! `u_0 ..= u_{n+p+1}`, domain `[u_p, u_{n+1}]`.

mod basis;
pub(crate) mod bernstein;
mod bezier;
mod closest;
mod curve;
mod envelope;
mod eval;
mod insert;
mod other_knots;
mod periodic;
mod rational_basis;
mod tessellate;
pub use other_knots::PowerPiece;
pub mod vector;

pub use basis::MAX_DEGREE;
pub use bezier::{BezierPiece, BezierPieces};
pub use closest::{CLOSEST_POINT_TOLERANCE, ClosestPoint, ClosestPointError, ClosestPointSearch};
pub use curve::{
    CallerKnots, Curve, CurveError, CurveField, CurveLimits, DOMAIN_END_SLACK, DOMAIN_END_ULPS,
    Dimension, KnotConvention, KnotForm, distinct_knots,
};
pub use envelope::{EnvelopeError, KnotRun};
pub use eval::{BatchEvaluator, EvalError};
pub use insert::{EDITING_KNOT_SPACING, EDITING_KNOTS_EACH_SIDE, InsertError};
pub use periodic::{PeriodicWindow, WrapError};
pub use rational_basis::{MAX_BASIS_ORDER, RationalBasis};
pub use tessellate::{ROUNDING_MARGIN, TOLERANCE_FLOOR, TessellationError, distance_to_segment};
pub use vector::Point;
