//! How one leaf of a mesh is triangulated ([`super`], docs/method.md §38): two triangles
//! over the diagonal with the lesser bound, the least-bound triangulation of its boundary
//! polygon when neighbours put vertices on its edges, or the fan from its centre.

use std::collections::HashMap;

use super::super::cells::triangle::TriangleBounds;
use super::super::cells::{Cell, CellBounds, vertex_gap};
use super::super::surface::Surface;
use super::{Layout, centre};
use crate::spline::Point;
use crate::spline::vector::distance;

/// How a leaf is triangulated: triangles as indices into its boundary (module docs;
/// `boundary.len()` is the centre of a fan) and the bound they meet, rounding aside.
pub(super) struct Plan {
    pub(super) triangles: Vec<[usize; 3]>,
    pub(super) fan: bool,
    pub(super) bound: f64,
}

impl Surface {
    /// The plan of a leaf (module docs): two triangles over the diagonal with the lesser bound
    /// when no neighbour's corner lies on its edges; otherwise the triangulation of its
    /// boundary polygon with the least largest triangle bound, or, when that exceeds the
    /// tolerance, the fan from its centre.
    pub(super) fn plan(
        &self,
        cell: &Cell,
        bounds: &CellBounds,
        layout: &Layout,
        cache: &mut HashMap<(u64, u64), (Point, Point)>,
        target: f64,
    ) -> Plan {
        let degrees = (self.u().degree(), self.v().degree());
        let rational = self.is_rational();
        let boundary = layout.boundary(cell);
        if boundary.len() == 4 {
            let (across, bound) = quad_plan(cell, bounds, degrees, rational);
            let triangles = if across {
                vec![[0, 1, 2], [0, 2, 3]]
            } else {
                vec![[0, 1, 3], [1, 2, 3]]
            };
            return Plan {
                triangles,
                fan: false,
                bound,
            };
        }
        let local = |(u, v): (f64, f64)| {
            [
                (u - cell.u.0) / (cell.u.1 - cell.u.0),
                (v - cell.v.0) / (cell.v.1 - cell.v.0),
            ]
        };
        let corner_point = |(u, v): (f64, f64)| -> Option<Point> {
            let i = [cell.u.0, cell.u.1].iter().position(|&x| x == u)?;
            let j = [cell.v.0, cell.v.1].iter().position(|&x| x == v)?;
            Some(cell.corner(i, j, degrees))
        };
        let x: Vec<[f64; 2]> = boundary.iter().map(|&b| local(b)).collect();
        let points: Vec<Point> = boundary
            .iter()
            .map(|&(u, v)| corner_point((u, v)).unwrap_or_else(|| self.vertex(cache, u, v).0))
            .collect();
        let triangle_bounds = TriangleBounds::new(cell, degrees, rational);
        let polygon = polygon_plan(&boundary, &x, &points, &triangle_bounds);
        if let Some((triangles, bound)) = &polygon
            && bound + bounds.rounding <= target
        {
            return Plan {
                triangles: triangles.clone(),
                fan: false,
                bound: *bound,
            };
        }
        // The fan from the centre: the least of its cell bound and its triangles' bounds.
        let (cu, cv) = centre(cell);
        let middle = self.vertex(cache, cu, cv).0;
        let mut gap = vertex_gap(cell, degrees, (cu, cv), middle);
        for (&(u, v), &point) in boundary.iter().zip(&points) {
            gap = gap.max(vertex_gap(cell, degrees, (u, v), point));
        }
        let n = boundary.len();
        let triangles: Vec<[usize; 3]> = (0..n).map(|k| [n, k, (k + 1) % n]).collect();
        let mut each = 0.0f64;
        for t in &triangles {
            let xs = t.map(|k| if k == n { [0.5, 0.5] } else { x[k] });
            let ps = t.map(|k| if k == n { middle } else { points[k] });
            each = each.max(triangle_bounds.bound(xs, ps));
        }
        let fan = Plan {
            triangles,
            fan: true,
            bound: (bounds.bilinear + bounds.twist / 16.0 + gap).min(each),
        };
        match polygon {
            Some((triangles, bound)) if bound <= fan.bound => Plan {
                triangles,
                fan: false,
                bound,
            },
            _ => fan,
        }
    }
}

/// The two triangles of a leaf without other vertices on its edges: whether over the diagonal
/// from `(u0, v0)` (else from `(u1, v0)`), and their bound, the lesser over the two diagonals
/// of the cell's `ε₁ + |T| / 4` and the larger of the two triangle bounds (ties: the shorter
/// diagonal in space).
pub(super) fn quad_plan(
    cell: &Cell,
    bounds: &CellBounds,
    degrees: (usize, usize),
    rational: bool,
) -> (bool, f64) {
    let cell_bound = bounds.bilinear + bounds.twist / 4.0;
    let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let points = [
        cell.corner(0, 0, degrees),
        cell.corner(1, 0, degrees),
        cell.corner(1, 1, degrees),
        cell.corner(0, 1, degrees),
    ];
    let triangle_bounds = TriangleBounds::new(cell, degrees, rational);
    let pair = |a: [usize; 3], b: [usize; 3]| {
        let one = |t: [usize; 3]| triangle_bounds.bound(t.map(|k| x[k]), t.map(|k| points[k]));
        cell_bound.min(one(a).max(one(b)))
    };
    let across = pair([0, 1, 2], [0, 2, 3]);
    let other = pair([0, 1, 3], [1, 2, 3]);
    if across != other {
        return if across < other {
            (true, across)
        } else {
            (false, other)
        };
    }
    let shorter = distance(points[0], points[2]) <= distance(points[1], points[3]);
    (shorter, across)
}

/// Most boundary vertices of a leaf triangulated without its centre (the search costs the
/// cube of their number).
const MAX_POLYGON: usize = 24;

/// The triangulation of a leaf's boundary polygon (`boundary` in parameters, `x` local,
/// surface `points`), `n − 2` triangles, whose largest bound is least, with that bound: by
/// dynamic programming over the convex polygon (a triangle of three vertices on one side of
/// the cell is flat and excluded). `None` when the polygon has too many vertices.
fn polygon_plan(
    boundary: &[(f64, f64)],
    x: &[[f64; 2]],
    points: &[Point],
    triangle_bounds: &TriangleBounds,
) -> Option<(Vec<[usize; 3]>, f64)> {
    let n = boundary.len();
    if n > MAX_POLYGON {
        return None;
    }
    let flat = |i: usize, k: usize, j: usize| {
        let same = |f: fn(&(f64, f64)) -> f64| {
            let a = f(&boundary[i]);
            a == f(&boundary[k]) && a == f(&boundary[j])
        };
        same(|b| b.0) || same(|b| b.1)
    };
    let mut cost = vec![f64::INFINITY; n * n];
    let mut choice = vec![0usize; n * n];
    for i in 0..n - 1 {
        cost[i * n + i + 1] = 0.0;
    }
    for length in 2..n {
        for i in 0..n - length {
            let j = i + length;
            for k in i + 1..j {
                let sides = cost[i * n + k].max(cost[k * n + j]);
                if sides >= cost[i * n + j] || flat(i, k, j) {
                    continue;
                }
                let t = [i, k, j];
                let here = triangle_bounds
                    .bound(t.map(|m| x[m]), t.map(|m| points[m]))
                    .max(sides);
                if here < cost[i * n + j] {
                    cost[i * n + j] = here;
                    choice[i * n + j] = k;
                }
            }
        }
    }
    let bound = cost[n - 1];
    if !bound.is_finite() {
        return None;
    }
    let mut triangles = Vec::with_capacity(n - 2);
    let mut stack = vec![(0, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j - i < 2 {
            continue;
        }
        let k = choice[i * n + j];
        triangles.push([i, k, j]);
        stack.push((i, k));
        stack.push((k, j));
    }
    Some((triangles, bound))
}
