//! A triangle mesh certified to lie within a tolerance of the surface, both ways: cells of the
//! parameter domain (the knot-span patches, halved or cut while their bound exceeds the
//! tolerance, [`super::cells`]) triangulated without cracks.
//!
//! Refinement: a cell whose two-triangle bound exceeds the tolerance is cut into the fewest
//! equal parts `k <= 8` along `u` or `v` after which every part is within the tolerance
//! ([`fitting_cut`]), or, when there is none, along `u` or `v` (where its net bends more; by
//! the longer side when it is flat and only twisted) into `k = ⌈√(bound / τ)⌉` equal parts,
//! `2 <= k <= 8` (the bound shrinks about as the square of the size). The two-triangle bound is the cell's `ε₁ + |T| / 4` or, when that exceeds the
//! tolerance, the lesser of it and, over the two diagonals, the larger of the two triangles'
//! own bounds ([`super::cells::triangle`]). Triangulation: every leaf's boundary carries the
//! corners of its neighbours that lie on its edges (the vertices are shared by their exact
//! parameters, so neighbouring triangles share whole edges: no cracks, no T-junctions); a leaf
//! without such vertices is two triangles over the diagonal with the lesser bound (the shorter
//! in space on a tie); one with them is its boundary polygon triangulated without a new
//! vertex (`n − 2` triangles, the triangulation whose largest triangle bound is least, by
//! dynamic programming) or, when that exceeds the tolerance, a fan from its centre, bounded by
//! the lesser of `ε₁ + |T| / 16 + max |S − B|` at its centre and edge vertices and its
//! triangles' bounds; a leaf over the tolerance is then refined *strictly*, until its pieces
//! meet `2 ε₁ + |T| / 16` (the fan's bound whatever its neighbours, as `|S − B| <= ε₁` at
//! every vertex) as well, and the leaves are triangulated again. Triangles turn
//! counter-clockwise in `(u, v)`, so that seen from the side of the normal `S_u × S_v` they
//! are counter-clockwise too.

use std::collections::{BTreeMap, HashMap};

mod plan;

use plan::{Plan, quad_plan};

use super::cells::{Cell, CellBounds};
use super::differential::{Inward, unit_normal};
use super::surface::{Direction, Surface};
use crate::spline::vector::{add, cross, distance, norm, scale, sub};
use crate::spline::{Point, ROUNDING_MARGIN, TOLERANCE_FLOOR};

/// Most parts a cell is cut into at once.
const MAX_PARTS: usize = 8;

/// Rounds of re-triangulation after cutting fanned leaves, at most (each one bounds every
/// leaf still over the tolerance strictly, which a leaf needs once).
const MAX_ROUNDS: usize = 256;

/// A triangle mesh of a surface and the bound it meets.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// The vertices `S(u, v)`.
    pub vertices: Vec<Point>,
    /// `[u, v]` of each vertex.
    pub parameters: Vec<[f64; 2]>,
    /// The unit normal at each vertex (the surface's, or its limit at a degenerate point; where
    /// the surface has none, the normalised sum of its triangles' normals).
    pub normals: Vec<Point>,
    /// Vertex indices, counter-clockwise seen from the side of the normal.
    pub triangles: Vec<[u32; 3]>,
    /// The certified bound: every point of the surface lies within it of the mesh and every
    /// point of the mesh within it of the surface.
    pub max_error: f64,
}

/// Why no certified mesh is given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TessellationError {
    /// The tolerance is not a number `> 0`, or too small for double precision to certify.
    #[error(
        "tolerance {tolerance} is below the smallest this surface allows, {floor:e} ({TOLERANCE_FLOOR:e} times its largest coordinate magnitude): double precision cannot certify a finer mesh"
    )]
    BelowFloor { tolerance: f64, floor: f64 },
    /// More triangles than allowed would be needed.
    #[error(
        "tolerance {tolerance} needs more than {max} triangles on this surface; give a larger tolerance"
    )]
    TooManyTriangles { tolerance: f64, max: usize },
    /// The surface jumps across a knot of multiplicity `degree + 1`.
    #[error(
        "the surface jumps at {} = {value} (a knot of multiplicity degree + 1); a mesh cannot follow a jump",
        direction.name()
    )]
    Discontinuous { direction: Direction, value: f64 },
}

impl Surface {
    /// A mesh within `tolerance` of the surface both ways (module docs), with at most
    /// `max_triangles` triangles; deterministic.
    pub fn tessellate(
        &self,
        tolerance: f64,
        max_triangles: usize,
    ) -> Result<Mesh, TessellationError> {
        let magnitude = self.coordinate_magnitude();
        let floor = TOLERANCE_FLOOR * magnitude;
        if tolerance.is_nan() || tolerance <= 0.0 || tolerance < floor {
            return Err(TessellationError::BelowFloor { tolerance, floor });
        }
        for direction in [Direction::U, Direction::V] {
            if let Some(&value) = self.axis(direction).jump_knots().first() {
                return Err(TessellationError::Discontinuous { direction, value });
            }
        }
        let target = tolerance - ROUNDING_MARGIN * magnitude;
        let degrees = (self.u().degree(), self.v().degree());
        let rational = self.is_rational();
        let too_many = || TessellationError::TooManyTriangles {
            tolerance,
            max: max_triangles,
        };
        let below_floor = || TessellationError::BelowFloor { tolerance, floor };
        let mut leaves: Vec<(Cell, CellBounds)> = Vec::new();
        // Cells to bound, and whether each must meet the fan's bound whatever its neighbours
        // (`strict`, for cells cut again because a fan exceeded the tolerance).
        let mut pending: Vec<(Cell, bool)> = self
            .patch_rects(self.domain())
            .iter()
            .rev()
            .map(|rect| (self.cell(rect), false))
            .collect();
        let mut points: HashMap<(u64, u64), (Point, Point)> = HashMap::new();
        let mut plans: Vec<Plan> = Vec::new();
        for _ in 0..MAX_ROUNDS {
            while let Some((cell, strict)) = pending.pop() {
                let bounds = cell.bounds(degrees, rational);
                let bound = leaf_bound(&cell, &bounds, degrees, rational, target, strict);
                if bound <= target {
                    leaves.push((cell, bounds));
                    if 2 * leaves.len() > max_triangles {
                        return Err(too_many());
                    }
                    continue;
                }
                if bounds.rounding > 0.5 * target {
                    // Finer cells only round worse: the parameters cannot resolve the tolerance.
                    return Err(below_floor());
                }
                let in_u = cut_direction(&cell, &bounds, degrees);
                if let Some(parts) =
                    fitting_cut(&cell, degrees, rational, (bound, target), in_u, strict)
                {
                    leaves.extend(parts);
                    if 2 * leaves.len() > max_triangles {
                        return Err(too_many());
                    }
                    continue;
                }
                let parts = cut_parts(bound, target);
                let children = cell.split(degrees, in_u, parts);
                if !children.iter().all(|c| c.u.0 < c.u.1 && c.v.0 < c.v.1) {
                    return Err(below_floor());
                }
                pending.extend(children.into_iter().rev().map(|c| (c, strict)));
            }
            let layout = Layout::of(&leaves);
            let mut over = Vec::new();
            plans.clear();
            for (index, (cell, bounds)) in leaves.iter().enumerate() {
                let plan = self.plan(cell, bounds, &layout, &mut points, target);
                if plan.bound + bounds.rounding > target {
                    over.push(index);
                }
                plans.push(plan);
            }
            if over.is_empty() {
                return self.triangulate(
                    &leaves,
                    &plans,
                    &layout,
                    &mut points,
                    magnitude,
                    max_triangles,
                    tolerance,
                );
            }
            // Bound every fanned leaf over the tolerance again, strictly (its pieces then meet
            // the fan's bound whatever vertices their neighbours put on their edges: the
            // refinement stops spreading), and triangulate again.
            for &index in over.iter().rev() {
                let (cell, _) = leaves.swap_remove(index);
                pending.push((cell, true));
            }
        }
        Err(too_many())
    }

    /// The point and unit normal (if any) at `(u, v)`, evaluated once per vertex.
    fn vertex(
        &self,
        cache: &mut HashMap<(u64, u64), (Point, Point)>,
        u: f64,
        v: f64,
    ) -> (Point, Point) {
        *cache.entry((u.to_bits(), v.to_bits())).or_insert_with(|| {
            let partials = self.partials(u, v, 2);
            let inward = |t: f64, axis: &super::surface::Axis| {
                if axis.is_periodic() {
                    Inward::Up
                } else {
                    Inward::of(t, axis.domain().1)
                }
            };
            let normal = unit_normal(&partials, [inward(u, self.u()), inward(v, self.v())])
                .map_or([0.0; 3], |(n, _)| n);
            (partials.point(), normal)
        })
    }

    /// The mesh of the leaves (module docs), with the bound they meet.
    #[allow(clippy::too_many_arguments)]
    fn triangulate(
        &self,
        leaves: &[(Cell, CellBounds)],
        plans: &[Plan],
        layout: &Layout,
        cache: &mut HashMap<(u64, u64), (Point, Point)>,
        magnitude: f64,
        max_triangles: usize,
        tolerance: f64,
    ) -> Result<Mesh, TessellationError> {
        let mut mesh = Mesh {
            vertices: Vec::new(),
            parameters: Vec::new(),
            normals: Vec::new(),
            triangles: Vec::new(),
            max_error: 0.0,
        };
        let mut index_of: HashMap<(u64, u64), u32> = HashMap::new();
        let mut vertex = |mesh: &mut Mesh, u: f64, v: f64| -> u32 {
            *index_of
                .entry((u.to_bits(), v.to_bits()))
                .or_insert_with(|| {
                    let (point, normal) = self.vertex(cache, u, v);
                    mesh.vertices.push(point);
                    mesh.parameters.push([u, v]);
                    mesh.normals.push(normal);
                    (mesh.vertices.len() - 1) as u32
                })
        };
        let mut worst = 0.0f64;
        for ((cell, bounds), plan) in leaves.iter().zip(plans) {
            let boundary = layout.boundary(cell);
            let mut ring: Vec<u32> = boundary
                .iter()
                .map(|&(u, v)| vertex(&mut mesh, u, v))
                .collect();
            if plan.fan {
                let (cu, cv) = centre(cell);
                ring.push(vertex(&mut mesh, cu, cv));
            }
            mesh.triangles
                .extend(plan.triangles.iter().map(|t| t.map(|k| ring[k])));
            worst = worst.max(plan.bound + bounds.rounding);
            if mesh.triangles.len() > max_triangles {
                return Err(TessellationError::TooManyTriangles {
                    tolerance,
                    max: max_triangles,
                });
            }
        }
        fill_missing_normals(&mut mesh);
        mesh.max_error = worst + ROUNDING_MARGIN * magnitude;
        Ok(mesh)
    }
}

/// The bound a cell must meet to be a leaf (module docs), rounding included: its two-triangle
/// bound (the triangles' own bounds computed only when the cell's `ε₁ + |T| / 4` exceeds
/// `target`), and when `strict` the fan's bound whatever its neighbours as well.
fn leaf_bound(
    cell: &Cell,
    bounds: &CellBounds,
    degrees: (usize, usize),
    rational: bool,
    target: f64,
    strict: bool,
) -> f64 {
    let mut bound = bounds.bilinear + bounds.twist / 4.0;
    if bound + bounds.rounding > target {
        bound = bound.min(quad_plan(cell, bounds, degrees, rational).1);
    }
    if strict {
        bound = bound.max(2.0 * bounds.bilinear + bounds.twist / 16.0);
    }
    bound + bounds.rounding
}

/// The cut of a cell over the tolerance into the fewest equal parts, `k <= 8`, along `u` or
/// `v` (`in_u` first on a tie), after which every part is a leaf (`(bound, target)`: the
/// cell's bound and the tolerance; only `k >= √(bound / target)` are tried, as a cut into `k`
/// parts divides a bound by `k²` at most), with the parts' bounds; `None` when there is none.
fn fitting_cut(
    cell: &Cell,
    degrees: (usize, usize),
    rational: bool,
    (bound, target): (f64, f64),
    in_u: bool,
    strict: bool,
) -> Option<Vec<(Cell, CellBounds)>> {
    let least = (bound / target).sqrt().ceil();
    if !least.is_finite() || least > MAX_PARTS as f64 {
        return None;
    }
    for parts in (least as usize).max(2)..=MAX_PARTS {
        for direction in [in_u, !in_u] {
            let children = cell.split(degrees, direction, parts);
            let mut fitted = Vec::with_capacity(parts);
            for child in children {
                if !(child.u.0 < child.u.1 && child.v.0 < child.v.1) {
                    break;
                }
                let bounds = child.bounds(degrees, rational);
                if leaf_bound(&child, &bounds, degrees, rational, target, strict) > target {
                    break;
                }
                fitted.push((child, bounds));
            }
            if fitted.len() == parts {
                return Some(fitted);
            }
        }
    }
    None
}

/// Into how many parts a cell whose bound is `bound` is cut (module docs).
fn cut_parts(bound: f64, target: f64) -> usize {
    let wanted = (bound / target).sqrt().ceil();
    if wanted.is_finite() && wanted <= MAX_PARTS as f64 {
        (wanted as usize).max(2)
    } else {
        2
    }
}

/// Whether to cut a cell along `u` (module docs): where its net bends more, or, when it is
/// flat in both and only twisted, along its longer side.
fn cut_direction(cell: &Cell, bounds: &CellBounds, degrees: (usize, usize)) -> bool {
    let [bend_u, bend_v] = bounds.bends;
    if bend_u.max(bend_v) > bounds.twist {
        return bend_u >= bend_v;
    }
    let side_u = distance(cell.corner(0, 0, degrees), cell.corner(1, 0, degrees))
        + distance(cell.corner(0, 1, degrees), cell.corner(1, 1, degrees));
    let side_v = distance(cell.corner(0, 0, degrees), cell.corner(0, 1, degrees))
        + distance(cell.corner(1, 0, degrees), cell.corner(1, 1, degrees));
    side_u >= side_v
}

/// The centre of a cell in parameters.
fn centre(cell: &Cell) -> (f64, f64) {
    (0.5 * (cell.u.0 + cell.u.1), 0.5 * (cell.v.0 + cell.v.1))
}

/// Every leaf corner by the line it lies on: for each `u` value the `v`s of the corners on the
/// line `u = const` (sorted), and for each `v` the `u`s.
struct Layout {
    at_u: BTreeMap<u64, Vec<f64>>,
    at_v: BTreeMap<u64, Vec<f64>>,
}

impl Layout {
    fn of(leaves: &[(Cell, CellBounds)]) -> Layout {
        let mut at_u: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
        let mut at_v: BTreeMap<u64, Vec<f64>> = BTreeMap::new();
        for (cell, _) in leaves {
            for u in [cell.u.0, cell.u.1] {
                for v in [cell.v.0, cell.v.1] {
                    at_u.entry(u.to_bits()).or_default().push(v);
                    at_v.entry(v.to_bits()).or_default().push(u);
                }
            }
        }
        for list in at_u.values_mut().chain(at_v.values_mut()) {
            list.sort_by(f64::total_cmp);
            list.dedup();
        }
        Layout { at_u, at_v }
    }

    /// The cell's boundary vertices, counter-clockwise in `(u, v)` from `(u0, v0)`: its corners
    /// and the corners of other leaves on its edges.
    fn boundary(&self, cell: &Cell) -> Vec<(f64, f64)> {
        let ((u0, u1), (v0, v1)) = (cell.u, cell.v);
        let inside = |list: Option<&Vec<f64>>, lo: f64, hi: f64| -> Vec<f64> {
            list.map(|values| {
                values
                    .iter()
                    .copied()
                    .filter(|&x| lo < x && x < hi)
                    .collect()
            })
            .unwrap_or_default()
        };
        let mut out = vec![(u0, v0)];
        out.extend(
            inside(self.at_v.get(&v0.to_bits()), u0, u1)
                .into_iter()
                .map(|u| (u, v0)),
        );
        out.push((u1, v0));
        out.extend(
            inside(self.at_u.get(&u1.to_bits()), v0, v1)
                .into_iter()
                .map(|v| (u1, v)),
        );
        out.push((u1, v1));
        out.extend(
            inside(self.at_v.get(&v1.to_bits()), u0, u1)
                .into_iter()
                .rev()
                .map(|u| (u, v1)),
        );
        out.push((u0, v1));
        out.extend(
            inside(self.at_u.get(&u0.to_bits()), v0, v1)
                .into_iter()
                .rev()
                .map(|v| (u0, v)),
        );
        out
    }
}

/// Gives each vertex without a normal (where the surface has none) the normalised sum of its
/// triangles' area-weighted normals.
fn fill_missing_normals(mesh: &mut Mesh) {
    if mesh.normals.iter().all(|n| norm(*n) > 0.0) {
        return;
    }
    let mut sums = vec![[0.0; 3]; mesh.vertices.len()];
    for triangle in &mesh.triangles {
        let [a, b, c] = triangle.map(|k| mesh.vertices[k as usize]);
        let face = cross(sub(b, a), sub(c, a));
        for &k in triangle {
            sums[k as usize] = add(sums[k as usize], face);
        }
    }
    for (normal, sum) in mesh.normals.iter_mut().zip(sums) {
        if norm(*normal) == 0.0 {
            let length = norm(sum);
            *normal = if length > 0.0 {
                scale(sum, 1.0 / length)
            } else {
                [0.0, 0.0, 1.0]
            };
        }
    }
}
