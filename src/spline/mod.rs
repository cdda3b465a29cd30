//! The spline core: validated B-spline/NURBS curves, evaluation and the knot-moving envelope.
//!
//! Pure geometry: no HTTP, wire-format or logging types. Conventions follow docs/method.md §1:
//! degree `p`, order `k = p + 1`, control points `d_0 ..= d_n`, full knot vector
//! `u_0 ..= u_{n+p+1}`, domain `[u_p, u_{n+1}]`.

mod basis;
pub(crate) mod bernstein;
mod closest;
mod curve;
mod envelope;
mod eval;
mod other_knots;
pub use other_knots::PowerPiece;
pub mod vector;

pub use basis::MAX_DEGREE;
pub use closest::{CLOSEST_POINT_TOLERANCE, ClosestPoint, ClosestPointError, ClosestPointSearch};
pub use curve::{Curve, CurveError, CurveField, CurveLimits, Dimension, KnotConvention};
pub use envelope::{EnvelopeError, KnotRun};
pub use eval::{BatchEvaluator, EvalError};
pub use vector::Point;
