//! The knot method on every degree (docs/method.md §30–§34): the knot families (the
//! envelope pairs of any degree, the curve's own direct pairs, and triples for 3D targets),
//! one primitive they all solve ([`local`]), and a certified solver for its equations
//! ([`tensor`], [`isolate`]).

// Index loops over the small fixed-size vectors and matrices of the solver read as the
// formulas they implement.
#![allow(clippy::needless_range_loop)]

pub(crate) mod domain;
pub(crate) mod hull;
pub(crate) mod isolate;
pub(crate) mod local;
pub(crate) mod nearest;
pub(crate) mod outline;
pub(crate) mod problems;
pub(crate) mod regions;
pub(crate) mod roots;
pub(crate) mod solve;
pub(crate) mod tensor;

pub use nearest::{FamilyNearest, nearest_across_families, nearest_solution_across_families};
pub use outline::Outline;
pub use problems::{Family, FamilyChoice, FamilyNotApplicable, FamilyProblem};
pub use regions::{FamilyRegions, SetRegion, family_regions};
pub use solve::{FamilyGroup, FamilyOutcome, KnotSet, KnotSolution, SetMembership, solve_families};
