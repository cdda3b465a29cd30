//! Integration tests: the real server on `127.0.0.1:0`, driven over HTTP. One test binary, so
//! it links once. Set `TEST_LOG=1` (or a filter such as `TEST_LOG=knotshape=debug`) for logs.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod answer_schemas;
mod auth;
mod binary;
mod closest;
mod connections;
mod constraints;
mod curve_tools;
mod curves;
mod edit;
mod errors;
mod examples;
mod from_points;
mod helpers;
mod insert_knots;
mod interop;
mod limits;
mod openapi_examples;
mod ops;
mod peer_cases;
mod periodic_edit;
mod pictures;
mod pieces;
mod real_curves;
mod reference;
mod regions_constraints;
mod shape;
mod shutdown;
mod surface_edit;
mod surface_errors;
mod surface_files;
mod surface_mesh;
mod surface_picking;
mod surface_toolkit;
mod surfaces;
