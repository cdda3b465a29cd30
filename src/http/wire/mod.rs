//! Request and response types of the API (what travels on the wire) and their conversions
//! from and to core types; handlers live in [`super::routes`].

pub mod closest;
pub mod constraints;
pub mod curves;
pub mod families;
pub mod files;
pub mod methods;
pub mod shape_answer;
pub mod shape_request;
pub mod solutions;
pub mod toolkit;
// The curve toolkit of the third release.
pub mod from_points;
pub mod length;
pub mod reshape;
pub mod toolkit_parse;
// Surfaces (fourth release).
pub mod surface_closest;
pub mod surface_edit;
pub mod surface_edit_parse;
pub mod surface_mesh;
pub mod surface_toolkit;
pub mod surfaces;
