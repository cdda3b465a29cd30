//! The surface knot method ([`super::knots`]: the iso-curve families in `u` and `v` and the
//! mixed moves) as one [`SurfaceEditMethod`]: its solutions become [`SurfaceSolution`]s
//! (knot changes move no control point, so fixed poles never exclude them), its reach is the
//! one-direction families' planar regions, and its nearest point is the knot families'.

use super::knots::{
    SurfaceKnotSolution, nearest_surface_knot_target, solve_surface_knots, surface_knot_regions,
};
use super::method::{
    SurfaceEditContext, SurfaceEditMethod, SurfaceMethodKind, SurfaceMethodSolutions,
    SurfaceNearest, SurfaceReachable, SurfaceSolution, SurfaceSolutionDetail,
};
use crate::spline::vector::Point;

/// Moving knots in `u`, `v` or both.
pub struct KnotsMethod;

impl KnotsMethod {
    /// Every knot solution for `target`, as edit solutions.
    fn solutions(edit: &SurfaceEditContext, target: Point) -> Vec<SurfaceSolution> {
        let (u, v) = edit.parameter;
        solve_surface_knots(edit.surface, u, v, target, edit.keep_domain)
            .into_iter()
            .map(solution_of)
            .collect()
    }
}

/// One knot solution as an edit solution.
fn solution_of(found: SurfaceKnotSolution) -> SurfaceSolution {
    SurfaceSolution {
        detail: SurfaceSolutionDetail::Knots {
            family: found.family.name(),
            region: found.region,
            changed_knots_u: found.changed_knots_u,
            changed_knots_v: found.changed_knots_v,
            changed_ranges: found.changed_ranges,
        },
        surface: found.surface,
        point: found.point,
        residual: found.residual,
        affected_domain: found.affected_domain,
        conditioning: found.conditioning,
        max_deviation: None,
    }
}

impl SurfaceEditMethod for KnotsMethod {
    fn kind(&self) -> SurfaceMethodKind {
        SurfaceMethodKind::Knots
    }

    fn solve(&self, edit: &SurfaceEditContext, target: Point) -> SurfaceMethodSolutions {
        SurfaceMethodSolutions {
            solutions: KnotsMethod::solutions(edit, target),
            excluded: Vec::new(),
        }
    }

    fn reachable(&self, edit: &SurfaceEditContext) -> SurfaceReachable {
        let (u, v) = edit.parameter;
        SurfaceReachable::KnotRegions(surface_knot_regions(edit.surface, u, v, edit.keep_domain))
    }

    fn nearest(&self, edit: &SurfaceEditContext, target: Point) -> Option<SurfaceNearest> {
        let (u, v) = edit.parameter;
        let point = nearest_surface_knot_target(edit.surface, u, v, target, edit.keep_domain)?;
        let solutions = KnotsMethod::solutions(edit, point);
        (!solutions.is_empty()).then_some(SurfaceNearest { point, solutions })
    }
}
