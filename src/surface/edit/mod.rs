//! Surface editing (docs/method.md §41–§48): move a surface point `S(u, v)` to a 3D target by
//! knots in `u`, `v` or both ([`knots`]), the least-norm move of the free control points or
//! by three weights, under constraints
//! (points and first partials at parameter pairs, fixed poles, kept boundary), each solution
//! measured by the certified largest distance between the old and the new surface and ranked
//! by it. Every method answers one small interface ([`SurfaceEditMethod`]); [`surface_edit`]
//! runs the requested ones. Pure geometry: no HTTP or wire types.

mod basis;
mod constraints;
mod control_points;
mod deviation;
mod knot_method;
pub mod knots;
mod method;
mod solve;
mod weights;

pub use basis::SurfaceBasis;
pub use constraints::{
    FixedNet, FixedNetError, SurfaceCondition, SurfaceConstraintError, SurfaceConstraintField,
    SurfaceConstraintIssue, SurfaceConstraintSpec, SurfaceConstraints, caller_index,
    surface_edit_size, surface_values,
};
pub use control_points::{
    ControlPointsMethod, SurfacePoleMove, affected_domain_of_poles, pole_variables,
    surface_control_point_move,
};
pub use deviation::{MAX_CELLS, SURFACE_DEVIATION_RELATIVE_TOLERANCE, surface_max_deviation};
pub use knot_method::KnotsMethod;
pub use method::{
    SURFACE_METHODS, SurfaceEditContext, SurfaceEditMethod, SurfaceExclusion,
    SurfaceExclusionReason, SurfaceMethodKind, SurfaceMethodSolutions, SurfaceNearest,
    SurfaceReachable, SurfaceSolution, SurfaceSolutionDetail, TetrahedronRegion,
};
pub use solve::{
    SurfaceEditOptions, SurfaceEditOutcome, SurfaceEditRequest, SurfaceNearestOutcome, ranked,
    surface_edit, surface_regions,
};
pub use weights::{
    FLAT_TETRAHEDRON, MAX_ACTIVE_POLES, MAX_WEIGHT_SOLUTIONS, SurfaceWeightMove, WeightOutcome,
    WeightRefusal, WeightTriple, WeightsMethod, barycentric, closest_in_tetrahedron,
    closest_on_triangle, triple_weights, weight_moves, weight_triples, with_triple_weights,
};
