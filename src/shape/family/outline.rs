//! Region outlines of the pairs of every family (docs/method.md §32): the set of targets a
//! pair reaches is the image of its admissible knots ([`PairDomain`]) under `P`. Where the
//! map does not fold, the outline is the image of the domain's boundary; where it folds, the
//! image's outline also runs along fold curves, and the region is built as the union of the
//! images of a refined mesh of the domain.
//!
//! Whether the map folds is decided by the sign of its Jacobian determinant, certified on
//! the Bernstein form of `det(H, ∂H/∂s₀, ∂H/∂s₁)` (`H` the homogeneous point's numerator in
//! the plane): all coefficients of one sign prove that it does not fold.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::float::simplify::SimplifyShape;

use super::domain::{PairDomain, point_at};
use super::local::LocalProblem;
use super::tensor::Tensor;
use crate::spline::vector::{Point, dot, sub};

/// Where the region lives: an origin and two orthonormal axes (the curve's plane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneFrame {
    /// A point of the plane.
    pub origin: Point,
    /// First axis.
    pub e1: Point,
    /// Second axis.
    pub e2: Point,
}

impl PlaneFrame {
    /// Plane coordinates of a point.
    pub fn coordinates(&self, p: Point) -> [f64; 2] {
        let d = sub(p, self.origin);
        [dot(d, self.e1), dot(d, self.e2)]
    }

    /// The point of plane coordinates `c`.
    pub fn point(&self, c: [f64; 2]) -> Point {
        [0, 1, 2].map(|k| self.origin[k] + c[0] * self.e1[k] + c[1] * self.e2[k])
    }
}

/// One region's outline.
#[derive(Debug, Clone, PartialEq)]
pub struct Outline {
    /// Closed rings (first vertex repeated last) in the curve's coordinates: each outer ring
    /// counter-clockwise in the plane, followed by its holes (clockwise).
    pub rings: Vec<Vec<Point>>,
    /// Whether the map folds (the outline then follows fold curves too).
    pub folded: bool,
    /// Whether the vertex budget allowed the tolerance everywhere.
    pub tolerance_met: bool,
}

/// Initial pieces per edge of the unit square (boundary path).
const EDGE_PIECES: usize = 8;

/// Bisection depth limit.
const MAX_DEPTH: u32 = 24;

/// Cells per side of the mesh of a folding map.
const MESH_CELLS: usize = 8;

/// Lattice squares per cell side (where the Jacobian is sampled; a fold cell is drawn as
/// these squares).
const LATTICE: usize = 4;

/// The outline of pair `unknowns` (local indices) of `problem` in `plane`, within
/// `tolerance` (curve units), with at most `max_vertices` boundary vertices on the
/// unfolded path.
pub fn pair_outline(
    problem: &LocalProblem,
    unknowns: [usize; 2],
    plane: &PlaneFrame,
    tolerance: f64,
    max_vertices: usize,
) -> Option<Outline> {
    let domain = PairDomain::new(problem, unknowns)?;
    let map = |uv: (f64, f64)| plane.coordinates(point_at(problem, unknowns, &domain, uv));
    let folded = !fold_free(problem, unknowns, plane);
    let (contours, tolerance_met) = if folded {
        mesh_polygons(&map, tolerance, max_vertices)
    } else {
        boundary(&map, tolerance, max_vertices)
    };
    let shapes = contours.simplify_shape(FillRule::NonZero);
    // Holes thinner than the tolerance are the mesh's seams, not holes of the region.
    let rings: Vec<Vec<Point>> = shapes
        .into_iter()
        .flat_map(|shape| {
            shape.into_iter().enumerate().filter_map(|(index, ring)| {
                let keep = index == 0 || area(&ring).abs() > tolerance * perimeter(&ring);
                keep.then(|| {
                    let mut closed: Vec<Point> = ring.iter().map(|&c| plane.point(c)).collect();
                    if let Some(&first) = closed.first() {
                        closed.push(first);
                    }
                    closed
                })
            })
        })
        .collect();
    Some(Outline {
        rings,
        folded,
        tolerance_met,
    })
}

/// Signed area of a ring (counter-clockwise positive).
fn area(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    0.5 * (0..n)
        .map(|i| {
            let (p, q) = (ring[i], ring[(i + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum::<f64>()
}

/// Length of a closed ring.
fn perimeter(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| {
            let (p, q) = (ring[i], ring[(i + 1) % n]);
            (q[0] - p[0]).hypot(q[1] - p[1])
        })
        .sum()
}

/// Distance from `p` to the segment `a`–`b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length = dx * dx + dy * dy;
    let s = if length > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - s * dx).hypot(p[1] - a[1] - s * dy)
}

/// The image of the unit square's boundary, sampled adaptively: one contour.
fn boundary(
    map: &impl Fn((f64, f64)) -> [f64; 2],
    tolerance: f64,
    max_vertices: usize,
) -> (Vec<Vec<[f64; 2]>>, bool) {
    let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let mut ring = Vec::new();
    let mut budget = max_vertices.saturating_sub(4 * EDGE_PIECES + 1);
    let mut met = true;
    for (k, &from) in corners.iter().enumerate() {
        let to = corners[(k + 1) % 4];
        let at = |s: f64| (from.0 + s * (to.0 - from.0), from.1 + s * (to.1 - from.1));
        for piece in 0..EDGE_PIECES {
            let s0 = piece as f64 / EDGE_PIECES as f64;
            let s1 = (piece + 1) as f64 / EDGE_PIECES as f64;
            let start = map(at(s0));
            ring.push(start);
            refine(
                map,
                &at,
                (s0, start),
                (s1, map(at(s1))),
                tolerance,
                0,
                &mut budget,
                &mut met,
                &mut ring,
            );
        }
    }
    (vec![ring], met)
}

/// Appends the interior samples of the edge piece `from`–`to` (its end excluded).
#[allow(clippy::too_many_arguments)]
fn refine(
    map: &impl Fn((f64, f64)) -> [f64; 2],
    at: &impl Fn(f64) -> (f64, f64),
    from: (f64, [f64; 2]),
    to: (f64, [f64; 2]),
    tolerance: f64,
    depth: u32,
    budget: &mut usize,
    met: &mut bool,
    ring: &mut Vec<[f64; 2]>,
) {
    let s = 0.5 * (from.0 + to.0);
    let middle = map(at(s));
    if to_segment(middle, from.1, to.1) <= tolerance {
        return;
    }
    if depth >= MAX_DEPTH || *budget == 0 {
        *met = false;
        return;
    }
    *budget -= 1;
    refine(
        map,
        at,
        from,
        (s, middle),
        tolerance,
        depth + 1,
        budget,
        met,
        ring,
    );
    ring.push(middle);
    refine(
        map,
        at,
        (s, middle),
        to,
        tolerance,
        depth + 1,
        budget,
        met,
        ring,
    );
}

/// The region of a folding map as polygons whose union it is: the unit square is cut into
/// [`MESH_CELLS`]² cells and the map's Jacobian determinant sampled on a lattice
/// ([`LATTICE`] points per cell side, central differences). A cell where it keeps one strict
/// sign maps one-to-one: its image is bounded by the image of its boundary, sampled to the
/// tolerance (each edge the same way from both of its cells, so that neighbours meet). A cell
/// where it changes sign holds a fold: its lattice squares are taken as straight
/// quadrilaterals. Every polygon is oriented counter-clockwise for the union.
fn mesh_polygons(
    map: &impl Fn((f64, f64)) -> [f64; 2],
    tolerance: f64,
    max_vertices: usize,
) -> (Vec<Vec<[f64; 2]>>, bool) {
    let points = MESH_CELLS * LATTICE + 1;
    let step = 1.0 / (points - 1) as f64;
    let lattice: Vec<[f64; 2]> = (0..points * points)
        .map(|k| map(((k % points) as f64 * step, (k / points) as f64 * step)))
        .collect();
    let at = |i: usize, j: usize| lattice[j * points + i];
    // det J at each lattice point by central (one-sided at the border) differences.
    let determinant = |i: usize, j: usize| {
        let (i0, i1) = (i.saturating_sub(1), (i + 1).min(points - 1));
        let (j0, j1) = (j.saturating_sub(1), (j + 1).min(points - 1));
        let du = [at(i1, j)[0] - at(i0, j)[0], at(i1, j)[1] - at(i0, j)[1]];
        let dv = [at(i, j1)[0] - at(i, j0)[0], at(i, j1)[1] - at(i, j0)[1]];
        (du[0] * dv[1] - du[1] * dv[0]) / ((i1 - i0) * (j1 - j0)) as f64
    };
    let mut polygons = Vec::new();
    let mut met = true;
    let mut budget = max_vertices.saturating_mul(4);
    for cj in 0..MESH_CELLS {
        for ci in 0..MESH_CELLS {
            let (i0, j0) = (ci * LATTICE, cj * LATTICE);
            let signs: Vec<f64> = (0..=LATTICE)
                .flat_map(|dj| (0..=LATTICE).map(move |di| (i0 + di, j0 + dj)))
                .map(|(i, j)| determinant(i, j))
                .collect();
            let positive = signs.iter().all(|&d| d > 0.0);
            let negative = signs.iter().all(|&d| d < 0.0);
            if positive || negative {
                let mut ring = Vec::new();
                let corners = [
                    (i0, j0),
                    (i0 + LATTICE, j0),
                    (i0 + LATTICE, j0 + LATTICE),
                    (i0, j0 + LATTICE),
                ];
                for k in 0..4 {
                    let (a, b) = (corners[k], corners[(k + 1) % 4]);
                    for piece in 0..LATTICE {
                        let point = |t: usize| {
                            (
                                (a.0 * (LATTICE - t) + b.0 * t) as f64 / LATTICE as f64 * step,
                                (a.1 * (LATTICE - t) + b.1 * t) as f64 / LATTICE as f64 * step,
                            )
                        };
                        let (s0, s1) = (point(piece), point(piece + 1));
                        let along = |s: f64| (s0.0 + s * (s1.0 - s0.0), s0.1 + s * (s1.1 - s0.1));
                        let start = map(s0);
                        ring.push(start);
                        refine(
                            map,
                            &along,
                            (0.0, start),
                            (1.0, map(s1)),
                            tolerance,
                            0,
                            &mut budget,
                            &mut met,
                            &mut ring,
                        );
                    }
                }
                if area(&ring) < 0.0 {
                    ring.reverse();
                }
                polygons.push(ring);
            } else {
                for dj in 0..LATTICE {
                    for di in 0..LATTICE {
                        let (i, j) = (i0 + di, j0 + dj);
                        let mut quad = vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                        let middle = map(((i as f64 + 0.5) * step, (j as f64 + 0.5) * step));
                        let bilinear =
                            [0, 1].map(|c| 0.25 * quad.iter().map(|p| p[c]).sum::<f64>());
                        if (middle[0] - bilinear[0]).hypot(middle[1] - bilinear[1]) > tolerance {
                            met = false;
                        }
                        if area(&quad) < 0.0 {
                            quad.reverse();
                        }
                        polygons.push(quad);
                    }
                }
            }
        }
    }
    (polygons, met)
}

/// Whether the map of pair `unknowns` provably does not fold on its search box: the
/// Bernstein coefficients of its Jacobian determinant (of the homogeneous numerator's plane
/// coordinates) all have one sign.
fn fold_free(problem: &LocalProblem, unknowns: [usize; 2], plane: &PlaneFrame) -> bool {
    let Some(search) = problem.search_box(&unknowns, 0.0, 0.0) else {
        return true;
    };
    let numerator = problem.numerator(&search);
    let o = plane.origin;
    let coordinate = |e: Point| {
        numerator.combine(&[e[0], e[1], e[2], -(e[0] * o[0] + e[1] * o[1] + e[2] * o[2])])
    };
    let x = coordinate(plane.e1);
    let y = coordinate(plane.e2);
    let w = numerator.combine(&[0.0, 0.0, 0.0, 1.0]);
    let parts = [x, y, w];
    let d0: Vec<Tensor> = parts.iter().map(|t| t.derivative(0).scaled()).collect();
    let d1: Vec<Tensor> = parts.iter().map(|t| t.derivative(1).scaled()).collect();
    let values: Vec<Tensor> = parts.into_iter().map(Tensor::scaled).collect();
    let minus = Tensor::constant(&[-1.0]);
    let cofactor =
        |i: usize, j: usize| d0[i].times(&d1[j]).plus(&d0[j].times(&d1[i]).times(&minus));
    let determinant = values[0]
        .times(&cofactor(1, 2))
        .plus(&values[1].times(&cofactor(2, 0)))
        .plus(&values[2].times(&cofactor(0, 1)))
        .unscaled();
    let (lo, hi) = determinant.range(0);
    let margin = 1e-10 * lo.abs().max(hi.abs());
    lo > margin || hi < -margin
}
