//! Region boundaries for drawing: each region `Ω_r` as the image of its parameter domain's
//! perimeter under `(unknowns) → (x, y)` (docs/method.md §5).
//!
//! Polygons are for drawing only; membership is decided exactly by solving
//! ([`super::membership`]).

use super::candidate::{Candidate, frame_to_point, triangle_size};
use super::pairs::{KnotPair, LocalKnot, LocalKnots};
use super::solve::{ShapeError, ShapeQuery};
use crate::spline::Curve;
use crate::spline::vector::{Point, cross, dot, norm, sub};

/// Default boundary tolerance, relative to the control triangle's longest edge.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-3;

/// Uniform pieces each domain edge is cut into before adaptive refinement.
const INITIAL_PIECES_PER_EDGE: usize = 8;

/// Bisection depth limit of the adaptive refinement (a piece shrinks to `2^-30` of its edge).
const MAX_REFINEMENT_DEPTH: u32 = 30;

/// How finely to sample the boundaries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolygonOptions {
    /// Largest distance, in curve coordinates, between the true boundary and the polygon;
    /// `None`: [`DEFAULT_RELATIVE_TOLERANCE`] times the triangle's longest edge.
    pub tolerance: Option<f64>,
    /// Most vertices per polygon, the closing repeat included (at least 5 are always allowed:
    /// a rectangle's corners); refinement stops there (then `tolerance_met` is false).
    pub max_vertices: usize,
}

/// One region's boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionPolygon {
    /// The knot pair.
    pub pair: KnotPair,
    /// Full-vector indices of the pair's two knots.
    pub knots: [usize; 2],
    /// Closed boundary (first vertex repeated last) in frame coordinates `[x, y]`.
    pub polygon_frame: Vec<[f64; 2]>,
    /// The same boundary in the curve's coordinates.
    pub polygon: Vec<Point>,
    /// Whether every edge met the tolerance within the vertex budget.
    pub tolerance_met: bool,
}

/// A candidate with its regions' boundaries (empty when the side does not apply).
#[derive(Debug, Clone, PartialEq)]
pub struct CandidateRegions {
    /// The side's candidate (no target, so no frame).
    pub candidate: Candidate,
    /// One entry per requested pair.
    pub regions: Vec<RegionPolygon>,
}

/// The boundary polygons of every requested region of every requested side.
///
/// With `keep_domain`, only what solving with the same query can reach is drawn: no region of
/// a side whose moved knot is an end of the domain (`u_p` or `u_{n+1}`, unless it already
/// equals `t`), and no pair one of whose knots is such an end (the rule freezes that knot, so
/// the region shrinks to a curve, of no area). The region's edge where a knot would reach a
/// clamped end is open; the polygon draws it.
pub fn region_polygons(
    query: &ShapeQuery,
    options: PolygonOptions,
) -> Result<Vec<CandidateRegions>, ShapeError> {
    let candidates = query.candidates(None)?;
    let knots = query.curve.knots();
    let n = query.curve.control_points().len() - 1;
    let is_end = |index: usize| query.keep_domain && (index == 3 || index == n + 1);
    Ok(candidates
        .into_iter()
        .map(|candidate| {
            let span = candidate.span;
            let side_kept =
                !(is_end(candidate.moved_knot) && knots[candidate.moved_knot] != query.parameter);
            let regions = match (candidate.is_applicable() && side_kept, candidate.triangle) {
                (true, Some(triangle)) => {
                    let tolerance = options
                        .tolerance
                        .unwrap_or(DEFAULT_RELATIVE_TOLERANCE * triangle_size(&triangle));
                    let local =
                        LocalKnots::from_full(query.curve.knots(), candidate.span, query.parameter);
                    query
                        .pairs
                        .iter()
                        .filter(|pair| {
                            pair.unknowns()
                                .iter()
                                .all(|knot| !is_end(knot.full_index(span)))
                        })
                        .map(|&pair| {
                            region_polygon(
                                query.curve,
                                candidate.span,
                                &local,
                                pair,
                                tolerance,
                                options.max_vertices,
                            )
                        })
                        .collect()
                }
                _ => Vec::new(),
            };
            CandidateRegions { candidate, regions }
        })
        .collect())
}

/// The corners of `pair`'s parameter domain, in order around it, as values of its two
/// unknowns (docs/method.md §5.1).
pub fn domain_corners(pair: KnotPair, k: &LocalKnots) -> Vec<[f64; 2]> {
    let (l, a, b, t, c, e, r) = (k.l, k.a, k.b, k.t, k.c, k.e, k.r);
    match pair {
        // L <= a <= b <= t (triangle in (a, b)).
        KnotPair::Omega1 => vec![[l, l], [l, t], [t, t]],
        // a <= b <= t, t <= c <= e (rectangle in (b, c)).
        KnotPair::Omega2 => vec![[a, t], [a, e], [t, e], [t, t]],
        // t <= c <= e <= R (triangle in (c, e)).
        KnotPair::Omega3 => vec![[t, t], [t, r], [r, r]],
        // L <= a <= b, t <= c <= e (rectangle in (a, c)).
        KnotPair::Omega4 => vec![[l, t], [l, e], [b, e], [b, t]],
        // L <= a <= b, c <= e <= R (rectangle in (a, e)).
        KnotPair::Omega5 => vec![[l, c], [l, r], [b, r], [b, c]],
        // a <= b <= t, c <= e <= R (rectangle in (b, e)).
        KnotPair::Omega6 => vec![[a, c], [a, r], [t, r], [t, c]],
    }
}

/// The frame point `(x, y)` of `pair`'s unknowns set to `values` (equations (2)); at the
/// corner `b = c = t` (a triple knot) the limit `(0, 0)`, the point `d_{j-1}`.
pub fn frame_of(pair: KnotPair, k: &LocalKnots, values: [f64; 2]) -> [f64; 2] {
    let mut knots = *k;
    for (unknown, value) in pair.unknowns().into_iter().zip(values) {
        match unknown {
            LocalKnot::A => knots.a = value,
            LocalKnot::B => knots.b = value,
            LocalKnot::C => knots.c = value,
            LocalKnot::E => knots.e = value,
        }
    }
    // Interpolated edge points can overshoot a bound by a rounding error (`r + (c - r)` need
    // not be `c`): keep the order `a <= b <= t <= c <= e` that equations (2) assume.
    knots.b = knots.b.min(knots.t);
    knots.a = knots.a.min(knots.b);
    knots.c = knots.c.max(knots.t);
    knots.e = knots.e.max(knots.c);
    if knots.c <= knots.b {
        return [0.0, 0.0];
    }
    let (x, y) = knots.frame();
    // `c = t` forces `x = 0`, `b = t` forces `y = 0`, whatever the other factors (no 0/0).
    let x = if knots.c == knots.t { 0.0 } else { x };
    let y = if knots.b == knots.t { 0.0 } else { y };
    [x, y]
}

/// Distance from `point` to the segment `from`–`to`.
fn distance_to_segment(point: Point, from: Point, to: Point) -> f64 {
    let direction = sub(to, from);
    let length_sq = dot(direction, direction);
    let offset = sub(point, from);
    if length_sq == 0.0 {
        return norm(offset);
    }
    // Not `clamp`: it panics on a NaN bound, and a degenerate edge may give one.
    let along = dot(offset, direction).max(0.0).min(length_sq);
    if along == 0.0 || along == length_sq {
        return norm(sub(point, if along == 0.0 { from } else { to }));
    }
    norm(cross(offset, direction)) / length_sq.sqrt()
}

/// Adaptive sampler of one region's boundary.
struct BoundarySampler<'a> {
    curve: &'a Curve,
    span: usize,
    local: &'a LocalKnots,
    pair: KnotPair,
    tolerance: f64,
    /// Bisections still allowed: each adds one vertex.
    splits_left: usize,
    frame: Vec<[f64; 2]>,
    points: Vec<Point>,
    tolerance_met: bool,
}

impl BoundarySampler<'_> {
    /// Frame and curve point of the parameter-space point `values`.
    fn image(&self, values: [f64; 2]) -> ([f64; 2], Point) {
        let f = frame_of(self.pair, self.local, values);
        (f, frame_to_point(self.curve, self.span, f[0], f[1]))
    }

    /// Appends a vertex unless it repeats the previous one (collapsed edges vanish).
    fn push(&mut self, vertex: ([f64; 2], Point)) {
        if self.frame.last() != Some(&vertex.0) {
            self.frame.push(vertex.0);
            self.points.push(vertex.1);
        }
    }

    /// Appends the image of the parameter segment `from`–`to` (without its start), bisecting
    /// while the image's midpoint is farther than the tolerance from the chord.
    fn refine(
        &mut self,
        from: [f64; 2],
        to: [f64; 2],
        start: Point,
        end: ([f64; 2], Point),
        depth: u32,
    ) {
        let middle = [0.5 * (from[0] + to[0]), 0.5 * (from[1] + to[1])];
        let image = self.image(middle);
        let too_far = distance_to_segment(image.1, start, end.1) > self.tolerance;
        if too_far && depth < MAX_REFINEMENT_DEPTH && self.splits_left > 0 {
            self.splits_left -= 1;
            self.refine(from, middle, start, image, depth + 1);
            self.refine(middle, to, image.1, end, depth + 1);
        } else {
            if too_far {
                self.tolerance_met = false;
            }
            self.push(end);
        }
    }
}

/// One region's closed boundary polygon.
fn region_polygon(
    curve: &Curve,
    span: usize,
    local: &LocalKnots,
    pair: KnotPair,
    tolerance: f64,
    max_vertices: usize,
) -> RegionPolygon {
    let corners = domain_corners(pair, local);
    // The polygon has 1 + (number of pieces) vertices: the first corner, then one per piece
    // (the last piece ends on the first corner again). Bisecting a piece adds one.
    let max_vertices = max_vertices.max(corners.len() + 1);
    let pieces_per_edge = INITIAL_PIECES_PER_EDGE.min((max_vertices - 1) / corners.len());
    let mut sampler = BoundarySampler {
        curve,
        span,
        local,
        pair,
        tolerance,
        splits_left: max_vertices - 1 - corners.len() * pieces_per_edge,
        frame: Vec::new(),
        points: Vec::new(),
        tolerance_met: true,
    };
    let first = sampler.image(corners[0]);
    sampler.push(first);
    for (i, &from) in corners.iter().enumerate() {
        let to = corners[(i + 1) % corners.len()];
        for piece in 0..pieces_per_edge {
            let at = |s: f64| {
                [
                    from[0] + s * (to[0] - from[0]),
                    from[1] + s * (to[1] - from[1]),
                ]
            };
            let s0 = piece as f64 / pieces_per_edge as f64;
            let s1 = (piece + 1) as f64 / pieces_per_edge as f64;
            let start = *sampler.points.last().unwrap_or(&first.1);
            let end = sampler.image(at(s1));
            sampler.refine(at(s0), at(s1), start, end, 0);
        }
    }
    // Close explicitly: the loop ends on the first corner's image; make it bit-identical.
    if sampler.frame.len() > 1 {
        sampler.frame.pop();
        sampler.points.pop();
    }
    sampler.frame.push(first.0);
    sampler.points.push(first.1);
    let [first_knot, second_knot] = pair.unknowns();
    RegionPolygon {
        pair,
        knots: [first_knot.full_index(span), second_knot.full_index(span)],
        polygon_frame: sampler.frame,
        polygon: sampler.points,
        tolerance_met: sampler.tolerance_met,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by the structured fuzzer: an edge point interpolated to `e` one rounding error
    /// below `c`, with `b = t`, made `y = 0/0` and a NaN vertex, which panicked the polygon's
    /// `clamp` (a 500 from `/v1/shape/regions`). The order is restored, `y` is 0.
    #[test]
    fn an_edge_point_overshooting_its_bound_by_rounding_has_a_finite_frame() {
        let k = LocalKnots {
            l: -7.1875,
            a: -4.974375,
            b: -2.7612500000000004,
            t: -0.28812500000000085,
            c: -0.28812500000000063,
            e: -0.28812500000000063,
            r: 3.565624999999999,
        };
        let frame = frame_of(KnotPair::Omega6, &k, [k.t, k.t]);
        assert!(frame.iter().all(|v| v.is_finite()), "{frame:?}");
        assert_eq!(frame[1], 0.0);
        assert!(distance_to_segment([0.0; 3], [f64::NAN; 3], [1.0, 0.0, 0.0]).is_nan());
    }
}
