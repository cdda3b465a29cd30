//! The iso-curve families (docs/method.md §45): the curve knot families of every degree run
//! on the iso-curve through `S(ũ, ṽ)`, each solution's knots given to the surface.
//!
//! Along `u` the iso-curve `c(u) = S(u, ṽ)` has the `u` knots and the control points
//! `D_i(ṽ) = Σ_l w_il d_il M_l(ṽ) / W_i` with weights `W_i = Σ_l w_il M_l(ṽ)`; `u` knots change
//! neither, so `S(ũ, ṽ)` with new `u` knots is the iso-curve's point with the same knots, and
//! a curve solution is a surface solution. Each is rebuilt as a surface (the old net, the new
//! `knots_u`), checked again by the surface core's evaluation at `(ũ, ṽ)`, and the strip it
//! changes is its `u` range over the whole `v` domain. Periodic directions are left alone (a
//! knot move would break the period).

use super::reach::iso_set_name;
use super::{
    SurfaceKnotFamily, SurfaceKnotOptions, SurfaceKnotSolution, accepted_residual, along,
    with_knots,
};
use crate::shape::ShapeQuery;
use crate::shape::family::{KnotSolution, solve_families};
use crate::spline::Curve;
use crate::spline::vector::{Point, distance};
use crate::surface::{Direction, Surface};

/// The iso-curve along `direction` through `(u, v)`: `u ↦ S(u, v)` for `U`.
pub(crate) fn iso_curve_along(surface: &Surface, direction: Direction, u: f64, v: f64) -> Curve {
    let fixed = direction.other();
    surface.iso_curve(fixed, along(fixed, u, v))
}

/// Whether knots of `direction` may move at all: degree ≥ 2 and not periodic.
pub(crate) fn movable(surface: &Surface, direction: Direction) -> bool {
    let axis = surface.axis(direction);
    axis.degree() >= 2 && !axis.is_periodic()
}

/// The query of the curve solver on the iso-curve along `direction`.
pub(crate) fn iso_query<'a>(
    curve: &'a Curve,
    direction: Direction,
    u: f64,
    v: f64,
    options: &SurfaceKnotOptions,
) -> ShapeQuery<'a> {
    let mut query = ShapeQuery::new(curve, along(direction, u, v));
    query.keep_domain = options.keep_domain;
    query.families = options.iso_families;
    query
}

/// Every solution of the iso families along `direction` (module docs).
pub(crate) fn solve_iso(
    surface: &Surface,
    direction: Direction,
    u: f64,
    v: f64,
    target: Point,
    options: &SurfaceKnotOptions,
) -> Vec<SurfaceKnotSolution> {
    if !movable(surface, direction) {
        return Vec::new();
    }
    let curve = iso_curve_along(surface, direction, u, v);
    let query = iso_query(&curve, direction, u, v, options);
    let outcome = solve_families(&query, options.iso_families, target);
    let accepted = accepted_residual(surface, u, v, target);
    outcome
        .solutions
        .iter()
        .filter_map(|solution| {
            surface_solution(surface, direction, u, v, target, solution, accepted)
        })
        .collect()
}

/// A curve solution on the iso-curve as a surface solution, `None` when the surface's own
/// evaluation at `(u, v)` misses the target by more than `accepted`.
pub(crate) fn surface_solution(
    surface: &Surface,
    direction: Direction,
    u: f64,
    v: f64,
    target: Point,
    solution: &KnotSolution,
    accepted: f64,
) -> Option<SurfaceKnotSolution> {
    let new = with_knots(surface, direction, solution.knots.clone());
    let point = new.point(u, v);
    let residual = distance(point, target);
    if residual.is_nan() || residual > accepted {
        return None;
    }
    let other = surface.axis(direction.other()).domain();
    let (affected_domain, knots_u, knots_v, changed_u, changed_v) = match direction {
        Direction::U => (
            [solution.affected_domain, other],
            Some(solution.knots.clone()),
            None,
            solution.changed_knots.clone(),
            Vec::new(),
        ),
        Direction::V => (
            [other, solution.affected_domain],
            None,
            Some(solution.knots.clone()),
            Vec::new(),
            solution.changed_knots.clone(),
        ),
    };
    Some(SurfaceKnotSolution {
        surface: new,
        knots_u,
        knots_v,
        changed_knots_u: changed_u,
        changed_knots_v: changed_v,
        family: SurfaceKnotFamily::Iso {
            direction,
            family: solution.family,
        },
        region: set_name(direction, solution),
        point,
        residual,
        affected_domain,
        changed_ranges: match direction {
            Direction::U => [Some(solution.affected_domain), None],
            Direction::V => [None, Some(solution.affected_domain)],
        },
        conditioning: solution.conditioning,
    })
}

/// `"u envelope right: u_7 := ũ; u_5, u_9"` (with `(Omega5)` for a cubic's envelope pairs).
pub(crate) fn set_name(direction: Direction, solution: &KnotSolution) -> String {
    let mut name = iso_set_name(
        direction,
        solution.family,
        solution.side,
        solution.moved_knot,
        &solution.knots_moved,
    );
    if let Some(omega) = solution.omega {
        name.push_str(&format!(" ({omega:?})"));
    }
    name
}
