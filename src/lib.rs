//! knotshape: B-spline/NURBS evaluation and knot-pair shape modification, with an HTTP edge.
#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod config;
pub mod http;
pub mod interchange;
pub mod parallel;
pub mod shape;
pub mod spline;
pub mod surface;
pub mod telemetry;

pub use http::{app, app_with_readiness, openapi, openapi_json};
