//! The knot method on every degree (docs/method.md §30–§34): the knot families (the
//! envelope pairs of any degree, the curve's own direct pairs, and triples for 3D targets),
//! one primitive they all solve ([`local`]), and a certified solver for its equations
//! ([`tensor`], [`isolate`]).

pub(crate) mod isolate;
pub(crate) mod local;
pub(crate) mod tensor;
pub(crate) mod problems;
pub(crate) mod roots;
pub(crate) mod solve;

pub use problems::{Family, FamilyChoice, FamilyNotApplicable, FamilyProblem};
pub use solve::{FamilyGroup, FamilyOutcome, KnotSet, KnotSolution, SetMembership, solve_families};
