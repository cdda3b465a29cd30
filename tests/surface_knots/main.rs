//! The knot method for surfaces (`knotshape::surface::edit::knots`): the worked example of
//! the study, properties over random surfaces checked by an independent evaluator, and the
//! real surfaces of the corpus.
#![allow(clippy::unwrap_used)]

mod completeness;
mod mixed;
mod properties;
mod random;
mod real;
#[path = "../common/real_surfaces.rs"]
mod real_surfaces;
mod reference;
mod worked_example;
