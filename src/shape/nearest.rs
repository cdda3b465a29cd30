//! The nearest reachable target: when no knot pair reaches a target, the reachable point
//! closest to it, so that a drag can follow the cursor outside the regions.
//!
//! The reachable set of a candidate is the union of its regions `Ω_r` (the requested pairs,
//! after the keep-domain rule). Each region is closed, so for a target outside it the nearest
//! point lies on the region's boundary: the image of the perimeter of the pair's parameter
//! domain. The domain is parametrised by the unit square (the same shear as the region table:
//! `L <= a <= b <= t` is `b = L + z0 (t - L)`, `a = L + z1 (b - L)`), so the perimeter is the
//! square's four edges, each a one-parameter curve of knots; an unknown that the keep-domain
//! rule freezes keeps its value, and the region shrinks to a segment or a point.
//!
//! Per edge the distance to the target is sampled adaptively (bisection while the image's
//! midpoint is farther than [`NEAREST_SAMPLING_TOLERANCE`] from its chord) and refined by
//! golden-section search inside the bracket of every sampled local minimum that may beat the
//! best one. Distances are Euclidean in the curve's coordinates (the frame map is projective
//! for rational curves, so the distance is taken after mapping back); a 3D target off the
//! triangle's plane is thereby matched in the plane. The point finally claimed is the new
//! curve's point at `t`, evaluated by the spline core from the new knots.

use super::candidate::{Side, SideChoice, candidate, frame_to_point, triangle_size};
use super::pairs::{KnotPair, LocalKnot, LocalKnots};
use super::regions::frame_of;
use super::solve::{
    KnotEdit, ShapeError, ShapeQuery, Solution, SolveOptions, knot_solution, solve,
    sort_by_deviation,
};
use crate::spline::vector::{Point, cross, distance, dot, sub};
use crate::spline::{Dimension, distance_to_segment};

/// Sampling tolerance of the boundaries, relative to the control triangle's longest edge.
pub const NEAREST_SAMPLING_TOLERANCE: f64 = 1e-3;

/// Uniform pieces per edge before adaptive bisection.
const INITIAL_PIECES: usize = 8;

/// Bisections per edge at most.
const MAX_SPLITS_PER_EDGE: usize = 64;

/// Golden-section steps at most per refined segment (the bracket shrinks to `0.618^60`).
const GOLDEN_STEPS: usize = 60;

/// Golden-section search stops at a bracket this wide (in edge parameter, `[0, 1]`): every
/// place of an edge is a boundary point, and at a minimum the distance changes only with the
/// square of the step.
const GOLDEN_WIDTH: f64 = 1e-9;

/// A point of an open boundary (a knot moved onto a clamped end, which the keep-domain rule
/// forbids) is pulled into the domain, by the first of these fractions of the unit square
/// that makes it reachable.
const OPEN_BOUNDARY_PULLS: [f64; 4] = [1e-9, 1e-7, 1e-5, 1e-3];

/// The reachable point nearest to an unreachable target.
#[derive(Debug, Clone, PartialEq)]
pub struct NearestOutcome {
    /// The nearest reachable point: the new curve's point at `t` for the first solution.
    pub point: Point,
    /// `|point - target|`.
    pub distance: f64,
    /// Every solution that reaches `point`, sorted by `max_deviation` (their `residual` is
    /// measured from `point`).
    pub solutions: Vec<Solution>,
}

/// A piece of an edge between two samples, with a lower bound of the distance on it.
#[derive(Debug, Clone, Copy)]
struct Segment {
    edge: usize,
    from: f64,
    to: f64,
    bound: f64,
}

/// One side and pair's search domain: the local knots and which unknowns are frozen.
struct EdgeSearch<'a> {
    query: &'a ShapeQuery<'a>,
    side: Side,
    span: usize,
    pair: KnotPair,
    local: LocalKnots,
    frozen: [bool; 2],
    target: Point,
}

/// The best place found on the boundaries so far.
#[derive(Debug, Clone, Copy)]
struct Found {
    distance: f64,
    side: Side,
    span: usize,
    pair: KnotPair,
    local_knots: [f64; 4],
    /// The unit-square point, to pull it inward when its boundary is open.
    z: [f64; 2],
    /// Which unknowns the keep-domain rule froze.
    frozen: [bool; 2],
}

impl EdgeSearch<'_> {
    /// The pair's two unknowns at unit-square point `z` (frozen ones keep their value).
    fn unknowns_at(&self, z: [f64; 2]) -> [f64; 2] {
        let k = &self.local;
        let (l, t, r) = (k.l, k.t, k.r);
        let [first, second] = self.pair.unknowns();
        let old = [k.get(first), k.get(second)];
        let lerp = |lo: f64, hi: f64, s: f64| if s >= 1.0 { hi } else { lo + s * (hi - lo) };
        let pick = |index: usize, lo: f64, hi: f64, s: f64| {
            if self.frozen[index] {
                old[index]
            } else {
                lerp(lo, hi, s)
            }
        };
        match self.pair {
            // L <= a <= b <= t: b first, then a below it.
            KnotPair::Omega1 => {
                let low = if self.frozen[0] { old[0] } else { l };
                let b = pick(1, low, t, z[0]);
                [pick(0, l, b, z[1]), b]
            }
            // a <= b <= t, t <= c <= e.
            KnotPair::Omega2 => [pick(0, k.a, t, z[0]), pick(1, t, k.e, z[1])],
            // t <= c <= e <= R: c first, then e above it.
            KnotPair::Omega3 => {
                let high = if self.frozen[1] { old[1] } else { r };
                let c = pick(0, t, high, z[0]);
                [c, pick(1, c, r, z[1])]
            }
            // L <= a <= b, t <= c <= e.
            KnotPair::Omega4 => [pick(0, l, k.b, z[0]), pick(1, t, k.e, z[1])],
            // L <= a <= b, c <= e <= R.
            KnotPair::Omega5 => [pick(0, l, k.b, z[0]), pick(1, k.c, r, z[1])],
            // a <= b <= t, c <= e <= R.
            KnotPair::Omega6 => [pick(0, k.a, t, z[0]), pick(1, k.c, r, z[1])],
        }
    }

    /// `[a, b, c, e]` at unit-square point `z`.
    fn local_knots_at(&self, z: [f64; 2]) -> [f64; 4] {
        let k = &self.local;
        let mut knots = [k.a, k.b, k.c, k.e];
        let values = self.unknowns_at(z);
        for (unknown, value) in self.pair.unknowns().into_iter().zip(values) {
            let slot = match unknown {
                LocalKnot::A => 0,
                LocalKnot::B => 1,
                LocalKnot::C => 2,
                LocalKnot::E => 3,
            };
            knots[slot] = value;
        }
        knots
    }

    /// The region's point at unit-square point `z`, by equations (2) and the frame.
    fn point_at(&self, z: [f64; 2]) -> Point {
        let [x, y] = frame_of(self.pair, &self.local, self.unknowns_at(z));
        frame_to_point(self.query.curve, self.span, x, y)
    }

    /// The unit-square point of edge `edge` (0: z1 = 0, 1: z0 = 1, 2: z1 = 1, 3: z0 = 0) at `s`.
    fn edge_point(edge: usize, s: f64) -> [f64; 2] {
        match edge {
            0 => [s, 0.0],
            1 => [1.0, s],
            2 => [1.0 - s, 1.0],
            _ => [0.0, 1.0 - s],
        }
    }

    /// Samples the four edges (adaptively, to `tolerance`): the best sampled place, and the
    /// segments between consecutive samples with a lower bound of the distance on each (the
    /// distance to the chord less `tolerance`, the image's allowed gap from its chord).
    fn sample(&self, tolerance: f64) -> (Option<Found>, Vec<Segment>) {
        let mut best = None;
        let mut segments = Vec::new();
        let mut samples: Vec<(f64, Point)> = Vec::with_capacity(INITIAL_PIECES + 1);
        for edge in 0..4 {
            let at = |s: f64| self.point_at(Self::edge_point(edge, s));
            samples.clear();
            samples.push((0.0, at(0.0)));
            let mut splits = MAX_SPLITS_PER_EDGE;
            for piece in 1..=INITIAL_PIECES {
                let s1 = piece as f64 / INITIAL_PIECES as f64;
                let end = (s1, at(s1));
                let Some(&start) = samples.last() else { break };
                self.refine(&at, start, end, tolerance, &mut splits, &mut samples, 0);
            }
            for &(s, point) in &samples {
                self.offer(
                    Self::edge_point(edge, s),
                    distance(point, self.target),
                    &mut best,
                );
            }
            for pair in samples.windows(2) {
                let chord = distance_to_segment(self.target, pair[0].1, pair[1].1);
                segments.push(Segment {
                    edge,
                    from: pair[0].0,
                    to: pair[1].0,
                    bound: chord - tolerance,
                });
            }
        }
        (best, segments)
    }

    /// The least distance on `segment` (golden-section search), offered to `best`.
    fn refine_segment(&self, segment: &Segment, best: &mut Option<Found>) {
        let at = |s: f64| self.point_at(Self::edge_point(segment.edge, s));
        let s = golden_minimum(|s| distance(at(s), self.target), segment.from, segment.to);
        self.offer(
            Self::edge_point(segment.edge, s),
            distance(at(s), self.target),
            best,
        );
    }

    fn offer(&self, z: [f64; 2], distance: f64, best: &mut Option<Found>) {
        if best.is_none_or(|found| distance < found.distance) {
            *best = Some(Found {
                distance,
                side: self.side,
                span: self.span,
                pair: self.pair,
                local_knots: self.local_knots_at(z),
                z,
                frozen: self.frozen,
            });
        }
    }

    /// Appends the samples of `(start, end]`, bisecting while the image's midpoint lies
    /// farther than `tolerance` from the chord.
    #[allow(clippy::too_many_arguments)]
    fn refine(
        &self,
        at: &dyn Fn(f64) -> Point,
        start: (f64, Point),
        end: (f64, Point),
        tolerance: f64,
        splits: &mut usize,
        samples: &mut Vec<(f64, Point)>,
        depth: u32,
    ) {
        let middle_s = 0.5 * (start.0 + end.0);
        let middle = (middle_s, at(middle_s));
        let chord_middle: Point = std::array::from_fn(|c| 0.5 * (start.1[c] + end.1[c]));
        if *splits > 0 && depth < 30 && distance(middle.1, chord_middle) > tolerance {
            *splits -= 1;
            self.refine(at, start, middle, tolerance, splits, samples, depth + 1);
            self.refine(at, middle, end, tolerance, splits, samples, depth + 1);
        } else {
            samples.push(end);
        }
    }
}

/// The `s` in `[lo, hi]` where `f` is least, by golden-section search (for a unimodal `f`).
fn golden_minimum(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    const RATIO: f64 = 0.618_033_988_749_894_8;
    let (mut a, mut b) = (lo, hi);
    let mut x = b - RATIO * (b - a);
    let mut y = a + RATIO * (b - a);
    let (mut fx, mut fy) = (f(x), f(y));
    for _ in 0..GOLDEN_STEPS {
        if b - a <= GOLDEN_WIDTH {
            break;
        }
        if fx < fy {
            b = y;
            y = x;
            fy = fx;
            x = b - RATIO * (b - a);
            fx = f(x);
        } else {
            a = x;
            x = y;
            fx = fy;
            y = a + RATIO * (b - a);
            fy = f(y);
        }
    }
    let candidates = [(lo, f(lo)), (hi, f(hi)), (x, fx), (y, fy)];
    candidates
        .into_iter()
        .min_by(|p, q| p.1.total_cmp(&q.1))
        .map_or(lo, |(s, _)| s)
}

/// The reachable point nearest to `target` over the requested sides and pairs (module docs),
/// with every solution that reaches it; `None` when nothing at all is reachable. Meant for a
/// target that [`solve`] cannot reach (for a reachable one the answer is the target itself,
/// up to rounding).
pub fn nearest_reachable(
    query: &ShapeQuery,
    target: Point,
    measure_deviation: bool,
) -> Result<Option<NearestOutcome>, ShapeError> {
    query.validate()?;
    let curve = query.curve;
    let knots = curve.knots();
    let n = curve.control_points().len() - 1;
    let t = query.parameter;
    let frozen_index = |i: usize| query.keep_domain && (i == 3 || i == n + 1);
    let mut found: Vec<Found> = Vec::new();
    let mut searches: Vec<(EdgeSearch, Option<Found>, Vec<Segment>)> = Vec::new();
    let mut projections: Vec<(f64, Solution)> = Vec::new();
    let mut buffer = knots.to_vec();
    for &side in query.side.sides() {
        let candidate = candidate(curve, t, side, None);
        let (true, Some(triangle)) = (candidate.is_applicable(), candidate.triangle) else {
            continue;
        };
        let span = candidate.span;
        if frozen_index(span + 1) && knots[span + 1] != t {
            // The moved knot is an end of the domain: no edit of this side is kept.
            continue;
        }
        if curve.dimension() == Dimension::Three {
            // Off the triangle's plane, the nearest point is nearest to the target's foot in
            // the plane; when a region holds the foot, that is the answer of this side.
            let foot = foot_in_plane(&triangle, target);
            let one_side = ShapeQuery {
                side: match side {
                    Side::Right => SideChoice::Right,
                    Side::Left => SideChoice::Left,
                },
                ..*query
            };
            let options = SolveOptions { measure_deviation };
            if let Some(solution) = solve(&one_side, &foot, options)?
                .solutions
                .into_iter()
                .next()
            {
                projections.push((distance(solution.point, target), solution));
                continue;
            }
        }
        let tolerance = NEAREST_SAMPLING_TOLERANCE * triangle_size(&triangle);
        let local = LocalKnots::from_full(knots, span, t);
        for &pair in query.pairs {
            let [first, second] = pair.unknowns();
            let search = EdgeSearch {
                query,
                side,
                span,
                pair,
                local,
                frozen: [
                    frozen_index(first.full_index(span)),
                    frozen_index(second.full_index(span)),
                ],
                target,
            };
            let (best, segments) = search.sample(tolerance);
            searches.push((search, best, segments));
        }
    }
    // Refine, most promising segment first, only where the bound may beat the best so far
    // (per pair, and over all pairs).
    let mut overall = searches
        .iter()
        .filter_map(|(_, best, _)| best.map(|found| found.distance))
        .fold(f64::INFINITY, f64::min);
    for (search, best, segments) in &mut searches {
        segments.sort_by(|p, q| p.bound.total_cmp(&q.bound));
        for segment in segments.iter() {
            let pair_best = best.map_or(f64::INFINITY, |found| found.distance);
            if segment.bound >= pair_best.min(overall) {
                break;
            }
            search.refine_segment(segment, best);
            overall = overall.min(best.map_or(f64::INFINITY, |found| found.distance));
        }
        found.extend(*best);
    }
    found.sort_by(|p, q| p.distance.total_cmp(&q.distance));
    let best_projection = projections.into_iter().min_by(|p, q| p.0.total_cmp(&q.0));
    let boundary = found
        .iter()
        .find_map(|place| reach(query, place, &mut buffer, measure_deviation));
    let solution = match (best_projection, boundary) {
        (Some((d, projected)), Some(on_boundary)) => {
            if d <= distance(on_boundary.point, target) {
                projected
            } else {
                on_boundary
            }
        }
        (Some((_, projected)), None) => projected,
        (None, Some(on_boundary)) => on_boundary,
        (None, None) => return Ok(None),
    };
    let point = solution.point;
    // Every solution that reaches the point: the closed forms, plus this one.
    let mut solutions = solve(
        query,
        &point[..curve.dimension().count()],
        SolveOptions { measure_deviation },
    )?
    .solutions;
    if !solutions
        .iter()
        .any(|s| s.side == solution.side && s.pair == solution.pair)
    {
        solutions.push(Solution {
            residual: 0.0,
            ..solution
        });
    }
    if measure_deviation {
        sort_by_deviation(&mut solutions);
    }
    Ok(Some(NearestOutcome {
        point,
        distance: distance(point, target),
        solutions,
    }))
}

/// The foot of `target` in the plane of `triangle` (non-degenerate).
fn foot_in_plane(triangle: &[Point; 3], target: Point) -> [f64; 3] {
    let normal = cross(sub(triangle[0], triangle[1]), sub(triangle[2], triangle[1]));
    let offset = dot(sub(target, triangle[1]), normal) / dot(normal, normal);
    std::array::from_fn(|c| target[c] - offset * normal[c])
}

/// The solution of a boundary place: its knots as they are, or pulled into the domain when
/// the keep-domain rule forbids the boundary itself.
fn reach(
    query: &ShapeQuery,
    place: &Found,
    buffer: &mut [f64],
    measure_deviation: bool,
) -> Option<Solution> {
    let edit = KnotEdit {
        pair: place.pair,
        side: place.side,
        span: place.span,
        local_knots: place.local_knots,
    };
    // The claimed point is what the new knots give, so it is its own target.
    let attempt = |edit: &KnotEdit, buffer: &mut [f64]| {
        let mut solution = knot_solution(
            query,
            edit,
            [0.0; 3],
            f64::INFINITY,
            buffer,
            measure_deviation,
        )?;
        solution.residual = 0.0;
        Some(solution)
    };
    if let Some(solution) = attempt(&edit, buffer) {
        return Some(solution);
    }
    let knots = query.curve.knots();
    let search = EdgeSearch {
        query,
        side: place.side,
        span: place.span,
        pair: place.pair,
        local: LocalKnots::from_full(knots, place.span, query.parameter),
        frozen: place.frozen,
        target: [0.0; 3],
    };
    // Pulled ever further until the edit is allowed: the shear of the unit square can make
    // a small pull vanish in one knot.
    OPEN_BOUNDARY_PULLS.iter().find_map(|&pull| {
        let pulled = place.z.map(|v| v + pull * (0.5 - v).signum());
        let edit = KnotEdit {
            local_knots: search.local_knots_at(pulled),
            ..edit
        };
        attempt(&edit, buffer)
    })
}
