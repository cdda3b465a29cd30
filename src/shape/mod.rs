//! The shape core: move a curve point `s(t)` to a target by moving knots (Juhász & Hoffmann;
//! Tornai's knot pairs Ω1–Ω6), per docs/method.md §3–§8.
//!
//! For a cubic curve and a picked parameter `t`, one knot next to `t` moves to `t` (the
//! [`Side`]); two more knots around it (a [`KnotPair`]) are solved in closed form so that
//! the envelope point, and hence the new curve at `t`, lands on the target. Pure geometry:
//! no HTTP, wire-format or logging types.

mod candidate;
mod control_points;
mod deviation;
mod nearest;
mod pairs;
mod regions;
mod solve;

pub use candidate::{
    Candidate, DEGENERACY_TOLERANCE, Frame, NotApplicable, PLANE_TOLERANCE, Side, SideChoice,
    candidate, frame_to_point,
};
pub use control_points::{CONTROL_POINT_RESIDUAL, ControlPointSolution, control_point_move};
pub use deviation::{DEVIATION_RELATIVE_TOLERANCE, max_deviation, max_deviation_of_moved_poles};
pub use nearest::{NEAREST_SAMPLING_TOLERANCE, NearestOutcome, nearest_reachable};
pub use pairs::{
    CLAMP_TOLERANCE, FRAME_ZERO_TOLERANCE, KNOT_TOLERANCE, KnotPair, LocalKnot, LocalKnots,
    solve_pair,
};
pub use regions::{
    CandidateRegions, DEFAULT_RELATIVE_TOLERANCE, PolygonOptions, RegionPolygon, domain_corners,
    frame_of, region_polygons,
};
pub use solve::{
    CandidateOutcome, RESIDUAL_TOLERANCE, RegionMembership, ShapeError, ShapeField, ShapeQuery,
    Solution, SolveOptions, SolveOutcome, affected_domain, membership, solve, target_point,
};
