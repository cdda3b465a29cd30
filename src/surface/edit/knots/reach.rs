//! What the surface knot families reach (docs/method.md §47): membership per family and set,
//! the regions of the planar (one-direction pair) families as 3D polygons in the plane of
//! the iso-curve's control points acting, and the nearest reachable point.
//!
//! The one-direction families' regions and nearest points are the curve families' own on the
//! iso-curve ([`crate::shape::family::family_regions`],
//! [`crate::shape::family::nearest_solution_across_families`], and for a cubic's envelope pairs
//! [`crate::shape::nearest_reachable`]): their points are the surface's at `(ũ, ṽ)` with the
//! same knots. The mixed moves reach a solid (three knots, 3D): they are not drawn; their
//! nearest point is searched ([`super::nearest`], verified by the mixed solver).

use super::iso::{iso_curve_along, iso_query, movable};
use super::{
    SurfaceKnotFamily, SurfaceKnotOptions, SurfaceKnotSolution, snap, solve_surface_knots_with,
};
use crate::shape::family::{
    FamilyChoice, KnotSet, family_regions, nearest_solution_across_families,
};
use crate::shape::{PolygonOptions, Side, nearest_reachable};
use crate::spline::vector::{Point, distance};
use crate::surface::{Direction, Surface};

/// Boundary vertices per region at most when none are given.
pub const DEFAULT_REGION_VERTICES: usize = 512;

/// One pair's reachable region: a plane polygon in 3D.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceKnotRegion {
    /// The family (a one-direction family).
    pub family: SurfaceKnotFamily,
    /// The knot set, as [`SurfaceKnotSolution::region`] names it.
    pub region: String,
    /// Full-vector indices (in the family's direction) of the pair's knots.
    pub knots: Vec<usize>,
    /// Closed rings (first vertex repeated last) in the surface's coordinates, in the plane
    /// of the control points acting: each outer ring counter-clockwise, then its holes.
    pub rings: Vec<Vec<Point>>,
    /// Whether the pair's map folds (the outline then follows fold curves too).
    pub folded: bool,
    /// Whether the vertex budget allowed the tolerance everywhere.
    pub tolerance_met: bool,
}

/// Whether one family's set reaches the target.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceKnotMembership {
    /// The family.
    pub family: SurfaceKnotFamily,
    /// The set (for a mixed family whose sets all miss: `"mixed, pair u: no set"`).
    pub region: String,
    /// A kept solution exists.
    pub contains: bool,
}

/// `"u envelope right: u_7 := ũ; u_5, u_9"` from its parts.
pub(crate) fn iso_set_name(
    direction: Direction,
    family: crate::shape::family::Family,
    side: Option<Side>,
    moved: Option<usize>,
    knots: &KnotSet,
) -> String {
    let d = direction.name();
    let mut name = format!("{d} {}", family.name());
    if let Some(side) = side {
        name.push(' ');
        name.push_str(side.name());
    }
    name.push(':');
    if let Some(i) = moved {
        name.push_str(&format!(" {d}_{i} := {d}\u{303};"));
    }
    let list: Vec<String> = knots.indices().iter().map(|i| format!("{d}_{i}")).collect();
    name.push(' ');
    name.push_str(&list.join(", "));
    name
}

/// The regions of the one-direction pairs at `(u, v)` (module docs), both directions, with
/// [`DEFAULT_REGION_VERTICES`] and the default tolerance.
pub fn surface_knot_regions(
    surface: &Surface,
    u: f64,
    v: f64,
    keep_domain: bool,
) -> Vec<SurfaceKnotRegion> {
    surface_knot_regions_with(
        surface,
        u,
        v,
        keep_domain,
        PolygonOptions {
            tolerance: None,
            max_vertices: DEFAULT_REGION_VERTICES,
        },
    )
}

/// [`surface_knot_regions`] with the polygons' tolerance and vertex limit.
pub fn surface_knot_regions_with(
    surface: &Surface,
    u: f64,
    v: f64,
    keep_domain: bool,
    polygons: PolygonOptions,
) -> Vec<SurfaceKnotRegion> {
    let Some((u, v)) = snap(surface, u, v) else {
        return Vec::new();
    };
    let options = SurfaceKnotOptions::all(keep_domain);
    let mut regions = Vec::new();
    for direction in [Direction::U, Direction::V] {
        if !movable(surface, direction) {
            continue;
        }
        let curve = iso_curve_along(surface, direction, u, v);
        let query = iso_query(&curve, direction, u, v, &options);
        let (_, families) = family_regions(&query, FamilyChoice::Default, polygons);
        for family in families {
            for region in family.regions {
                if region.outline.rings.is_empty() {
                    continue;
                }
                regions.push(SurfaceKnotRegion {
                    family: SurfaceKnotFamily::Iso {
                        direction,
                        family: family.problem.family,
                    },
                    region: iso_set_name(
                        direction,
                        family.problem.family,
                        family.problem.side,
                        family.problem.moved_knot,
                        &region.knots,
                    ),
                    knots: region.knots.indices().to_vec(),
                    rings: region.outline.rings,
                    folded: region.outline.folded,
                    tolerance_met: region.outline.tolerance_met,
                });
            }
        }
    }
    regions
}

/// Whether each family's sets reach `target` from `(u, v)`: every one-direction set (as the
/// curve solver tried it), every mixed set with a solution, and one entry per mixed family
/// (`contains` false, region `"mixed, pair u: no set"`) when none of its sets reaches.
pub fn surface_knot_membership(
    surface: &Surface,
    u: f64,
    v: f64,
    target: Point,
    keep_domain: bool,
) -> Vec<SurfaceKnotMembership> {
    let Some((u, v)) = snap(surface, u, v) else {
        return Vec::new();
    };
    let options = SurfaceKnotOptions::all(keep_domain);
    let solutions = solve_surface_knots_with(surface, u, v, target, &options);
    let mut members = Vec::new();
    for direction in [Direction::U, Direction::V] {
        if !movable(surface, direction) {
            continue;
        }
        let curve = iso_curve_along(surface, direction, u, v);
        let query = iso_query(&curve, direction, u, v, &options);
        let outcome = crate::shape::family::solve_families(&query, options.iso_families, target);
        for group in &outcome.groups {
            for member in &group.members {
                let region = iso_set_name(
                    direction,
                    group.problem.family,
                    group.problem.side,
                    group.problem.moved_knot,
                    &member.knots,
                );
                // The surface's own check may drop a curve solution (rounding): follow it.
                let family = SurfaceKnotFamily::Iso {
                    direction,
                    family: group.problem.family,
                };
                let contains = member.contains
                    && solutions
                        .iter()
                        .any(|s| s.family == family && s.region.starts_with(&region));
                members.push(SurfaceKnotMembership {
                    family,
                    region,
                    contains,
                });
            }
        }
    }
    for pair in [Direction::U, Direction::V] {
        let family = SurfaceKnotFamily::Mixed { pair };
        let mut any = false;
        for solution in solutions.iter().filter(|s| s.family == family) {
            if !members
                .iter()
                .any(|m: &SurfaceKnotMembership| m.region == solution.region)
            {
                members.push(SurfaceKnotMembership {
                    family,
                    region: solution.region.clone(),
                    contains: true,
                });
            }
            any = true;
        }
        if !any {
            members.push(SurfaceKnotMembership {
                family,
                region: format!("mixed, pair {}: no set", pair.name()),
                contains: false,
            });
        }
    }
    members
}

/// The point nearest `target` that a knot family reaches from `(u, v)`: `target` itself when
/// a solution reaches it, else the nearest point over the one-direction families of both
/// directions and the mixed moves ([`super::nearest`]; module docs); `None` when nothing is
/// reachable.
pub fn nearest_surface_knot_target(
    surface: &Surface,
    u: f64,
    v: f64,
    target: Point,
    keep_domain: bool,
) -> Option<Point> {
    let (u, v) = snap(surface, u, v)?;
    let options = SurfaceKnotOptions::all(keep_domain);
    let solutions: Vec<SurfaceKnotSolution> =
        solve_surface_knots_with(surface, u, v, target, &options);
    if let Some(best) = solutions
        .iter()
        .min_by(|a, b| a.residual.total_cmp(&b.residual))
    {
        return Some(best.point);
    }
    let mut best: Option<(f64, Point)> = None;
    let mut offer = |point: Point| {
        let d = distance(point, target);
        if d.is_finite() && best.is_none_or(|(b, _)| d < b) {
            best = Some((d, point));
        }
    };
    for direction in [Direction::U, Direction::V] {
        if !movable(surface, direction) {
            continue;
        }
        let curve = iso_curve_along(surface, direction, u, v);
        let query = iso_query(&curve, direction, u, v, &options);
        if let Some(found) = nearest_solution_across_families(&query, options.iso_families, target)
        {
            offer(found.point);
        }
        if curve.degree() == 3 {
            if let Ok(Some(found)) = nearest_reachable(&query, target, false) {
                offer(found.point);
            }
        }
    }
    if let Some((_, point)) = super::nearest::nearest_mixed(surface, u, v, target, &options) {
        offer(point);
    }
    best.map(|(_, point)| point)
}
