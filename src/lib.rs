//! knotshape: B-spline/NURBS evaluation and knot-pair shape modification, with an HTTP edge.
#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod shape;
pub mod spline;
