//! Region boundary polygons (`region_polygons`) against membership and an independent search:
//! closed, within tolerance, vertices reachable, and random points clearly inside (outside) a
//! polygon are (are not) members of its region.
//!
//! Random curves as in the completeness test, both sides, all six regions, the default and an
//! explicit tolerance. Points are classified by the even–odd rule in the plane of the control
//! triangle (curve units), and only when farther than `MARGIN_FACTOR` tolerances from the
//! polygon. Polygons draw the regions without the keep-domain rule, so membership is asked
//! with `keep_domain: false`.
#![allow(clippy::unwrap_used)]

mod common;

use common::{
    CurveMix, Search, SearchOptions, SplitMix64, dist, random_curve, span_of, triangle_of,
    triangle_size,
};
use knotshape::shape::{
    KnotPair, PolygonOptions, RegionPolygon, ShapeQuery, Side, SideChoice, membership,
    region_polygons,
};
use knotshape::spline::{Curve, Point};

/// Curves tried (each with both sides and all six regions).
const CURVES: usize = 100;

/// Random frame points classified per region.
const POINTS_PER_REGION: usize = 80;

/// Polygon tolerance, relative to the triangle's longest edge, when given explicitly.
const RELATIVE_TOLERANCE: f64 = 2e-4;

/// A point is classified only when it is farther than this many tolerances from the polygon:
/// the sampler bounds the chord error at each piece's midpoint only, so leave ample room.
const MARGIN_FACTOR: f64 = 20.0;

/// Vertex budget: generous, so that every polygon meets its tolerance.
const MAX_VERTICES: usize = 20_000;

/// A polygon vertex is a boundary point of its region, so the independent search reaches it
/// (frame residual; the search converges to ~1e-14 where a point is reachable). Vertices at
/// the triangle's corners are not searched: they need a triple knot at `t` (`a = b = t`,
/// `b = c = t`, `c = e = t`), which on a short curve empties the domain, so they can be limits
/// that no valid knot vector reaches.
const VERTEX_REACHED: f64 = 1e-9;

/// `polygon[i]` and the curve point of `polygon_frame[i]` (computed here) agree to this,
/// relative to the triangle's size (double rounding of a rational combination).
const FRAME_TO_POINT: f64 = 1e-12;

const SEED: u64 = 0x9017_6017;

/// The (rational) combination of the triangle with basis values `(x, 1 - x - y, y)`, written
/// here independently of `frame_to_point`; `None` when the weight sum is not positive.
fn point_of_frame(curve: &Curve, span: usize, x: f64, y: f64) -> Option<Point> {
    let d = triangle_of(curve, span);
    let basis = [x, 1.0 - x - y, y];
    let mut numerator = [0.0; 3];
    let mut denominator = 0.0;
    for r in 0..3 {
        let w = curve.weight(span - 2 + r) * basis[r];
        for c in 0..3 {
            numerator[c] += w * d[r][c];
        }
        denominator += w;
    }
    (denominator > 0.0).then(|| numerator.map(|v| v / denominator))
}

/// Orthonormal 2D coordinates in the plane of the triangle (origin `d_{j-1}`).
struct Plane {
    origin: Point,
    u: Point,
    v: Point,
}

impl Plane {
    fn of(triangle: &[Point; 3]) -> Plane {
        let [d0, d1, d2] = *triangle;
        let e1: Point = std::array::from_fn(|i| d0[i] - d1[i]);
        let e2: Point = std::array::from_fn(|i| d2[i] - d1[i]);
        let dot = |p: Point, q: Point| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        let n1 = dot(e1, e1).sqrt();
        let u = e1.map(|c| c / n1);
        let w: Point = std::array::from_fn(|i| e2[i] - dot(e2, u) * u[i]);
        let nw = dot(w, w).sqrt();
        Plane {
            origin: d1,
            u,
            v: w.map(|c| c / nw),
        }
    }

    fn coordinates(&self, p: Point) -> [f64; 2] {
        let r: Point = std::array::from_fn(|i| p[i] - self.origin[i]);
        let dot = |p: Point, q: Point| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        [dot(r, self.u), dot(r, self.v)]
    }
}

/// Even–odd rule: whether `p` is inside the closed polygon `ring` (first == last).
fn inside(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut odd = false;
    for edge in ring.windows(2) {
        let ([x0, y0], [x1, y1]) = (edge[0], edge[1]);
        if (y0 > p[1]) != (y1 > p[1]) {
            let x = x0 + (p[1] - y0) * (x1 - x0) / (y1 - y0);
            if p[0] < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// Distance from `p` to the polygon's boundary.
fn distance_to_ring(ring: &[[f64; 2]], p: [f64; 2]) -> f64 {
    ring.windows(2)
        .map(|edge| {
            let ([x0, y0], [x1, y1]) = (edge[0], edge[1]);
            let (dx, dy) = (x1 - x0, y1 - y0);
            let length_sq = dx * dx + dy * dy;
            let s = if length_sq > 0.0 {
                (((p[0] - x0) * dx + (p[1] - y0) * dy) / length_sq).clamp(0.0, 1.0)
            } else {
                0.0
            };
            ((p[0] - x0 - s * dx).powi(2) + (p[1] - y0 - s * dy).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

#[derive(Debug, Default)]
struct Tally {
    polygons: usize,
    vertices: usize,
    vertices_searched: usize,
    inside_checked: usize,
    outside_checked: usize,
    skipped_near_boundary: usize,
    max_vertex_residual: f64,
    failures: Vec<String>,
}

/// One candidate's regions under test.
struct Setting<'a> {
    curve: &'a Curve,
    t: f64,
    side: Side,
    span: usize,
    /// The polygons' tolerance (curve units).
    tolerance: f64,
    /// Prefix of every message.
    context: &'a str,
}

fn check_region(
    setting: &Setting,
    region: &RegionPolygon,
    rng: &mut SplitMix64,
    tally: &mut Tally,
) {
    let Setting {
        curve,
        t,
        side,
        span,
        tolerance,
        context,
    } = *setting;
    let pair = region.pair;
    let label = format!("{context}: {side:?} j = {span} {pair:?}");
    let triangle = triangle_of(curve, span);
    let size = triangle_size(&triangle);
    tally.polygons += 1;
    tally.vertices += region.polygon.len();
    let (frame, points) = (&region.polygon_frame, &region.polygon);
    // A region may collapse to a point (e.g. Ω5 when L = a = b and c = e = R): 2 vertices.
    if frame.len() < 2 || frame.len() != points.len() {
        tally
            .failures
            .push(format!("{label}: {} vertices", frame.len()));
        return;
    }
    if frame.first() != frame.last() || points.first() != points.last() {
        tally.failures.push(format!("{label}: polygon not closed"));
    }
    if !region.tolerance_met {
        tally.failures.push(format!("{label}: tolerance not met"));
    }
    for (f, p) in frame.iter().zip(points) {
        let finite = f.iter().chain(p.iter()).all(|v| v.is_finite());
        let ours = point_of_frame(curve, span, f[0], f[1]);
        let agrees = ours.is_some_and(|q| dist(q, *p) <= FRAME_TO_POINT * size);
        if !(finite && agrees) {
            tally.failures.push(format!(
                "{label}: vertex {f:?} -> {p:?} is not the curve point of its frame ({ours:?})"
            ));
            return;
        }
    }
    // Vertices are boundary points: the independent search must reach them.
    let corner = |f: &[f64; 2]| {
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
            .iter()
            .any(|c| (f[0] - c[0]).abs() + (f[1] - c[1]).abs() <= 1e-12)
    };
    let mut picks: Vec<usize> = (0..frame.len()).filter(|&i| !corner(&frame[i])).collect();
    if picks.len() > 3 {
        picks = vec![picks[0], picks[picks.len() / 3], picks[2 * picks.len() / 3]];
    }
    for index in picks {
        let mut search = Search::new(curve, span, t, points[index], pair, false);
        let result = search.run(SearchOptions::default(), VERTEX_REACHED);
        tally.vertices_searched += 1;
        tally.max_vertex_residual = tally.max_vertex_residual.max(result.best_residual);
        if result.best_residual > VERTEX_REACHED {
            tally.failures.push(format!(
                "{label}: vertex {index} {:?} not reached by the search ({result:?})",
                frame[index]
            ));
        }
    }
    // Random points, classified by the polygon (in the plane of the triangle, curve units).
    let plane = Plane::of(&triangle);
    let ring: Vec<[f64; 2]> = points.iter().map(|&p| plane.coordinates(p)).collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for f in frame {
        for c in 0..2 {
            lo[c] = lo[c].min(f[c]);
            hi[c] = hi[c].max(f[c]);
        }
    }
    let margin = MARGIN_FACTOR * tolerance;
    let pairs = [pair];
    let query = ShapeQuery {
        curve,
        parameter: t,
        side: match side {
            Side::Right => SideChoice::Right,
            Side::Left => SideChoice::Left,
        },
        pairs: &pairs,
        families: Default::default(),
        keep_domain: false,
    };
    for k in 0..POINTS_PER_REGION {
        // Three in four near the region (its frame box, widened), the rest over the whole
        // triangle.
        let (x, y) = if k % 4 != 3 {
            let grow = |c: usize, s: f64| {
                let w = hi[c] - lo[c];
                lo[c] - 0.2 * w + s * 1.4 * w
            };
            (grow(0, rng.unit()), grow(1, rng.unit()))
        } else {
            (rng.range(-0.05, 1.05), rng.range(-0.05, 1.05))
        };
        if !(x >= -0.05 && y >= -0.05 && x + y <= 1.05) {
            continue;
        }
        let Some(p) = point_of_frame(curve, span, x, y) else {
            continue;
        };
        let q = plane.coordinates(p);
        if distance_to_ring(&ring, q) <= margin {
            tally.skipped_near_boundary += 1;
            continue;
        }
        let expected = inside(&ring, q);
        let outcome = membership(&query, &p[..curve.dimension().count()]).unwrap();
        let contains = outcome.candidates[0]
            .regions
            .first()
            .is_some_and(|r| r.contains);
        if expected {
            tally.inside_checked += 1;
        } else {
            tally.outside_checked += 1;
        }
        if contains != expected {
            tally.failures.push(format!(
                "{label}: frame point ({x:?}, {y:?}) is {} the polygon (by {:e}) but membership says {contains}",
                if expected { "inside" } else { "outside" },
                distance_to_ring(&ring, q)
            ));
        }
    }
}

#[test]
fn polygons_are_closed_accurate_and_agree_with_membership() {
    let started = std::time::Instant::now();
    let mut tally = Tally::default();
    for case in 0..CURVES {
        let seed = SEED + case as u64;
        let mut rng = SplitMix64::new(seed);
        let curve = random_curve(&mut rng, CurveMix::default());
        let (lo, hi) = curve.domain();
        let t = rng.range(lo, hi);
        let n = curve.control_points().len() - 1;
        let explicit = case % 2 == 0;
        let sizes: Vec<f64> = [Side::Right, Side::Left]
            .iter()
            .map(|&s| span_of(&curve, t, s))
            .filter(|j| (2..=n).contains(j))
            .map(|j| triangle_size(&triangle_of(&curve, j)))
            .collect();
        let Some(smallest) = sizes.iter().copied().reduce(f64::min) else {
            continue;
        };
        let options = PolygonOptions {
            tolerance: explicit.then_some(RELATIVE_TOLERANCE * smallest),
            max_vertices: MAX_VERTICES,
        };
        let query = ShapeQuery {
            curve: &curve,
            parameter: t,
            side: SideChoice::Both,
            pairs: &KnotPair::ALL,
            families: Default::default(),
            keep_domain: false,
        };
        let context = format!("case {case} (seed {seed:#x}) t = {t:?} curve = {curve:?}");
        for candidate in region_polygons(&query, options).unwrap() {
            let side = candidate.candidate.side;
            let span = span_of(&curve, t, side);
            if candidate.candidate.span != span {
                tally.failures.push(format!("{context}: {side:?} span"));
                continue;
            }
            if !candidate.candidate.is_applicable() {
                if !candidate.regions.is_empty() {
                    tally.failures.push(format!(
                        "{context}: {side:?} not applicable but has regions"
                    ));
                }
                continue;
            }
            if candidate.regions.len() != KnotPair::ALL.len() {
                tally.failures.push(format!("{context}: {side:?} regions"));
                continue;
            }
            let size = triangle_size(&triangle_of(&curve, span));
            let tolerance = options
                .tolerance
                .unwrap_or(knotshape::shape::DEFAULT_RELATIVE_TOLERANCE * size);
            let setting = Setting {
                curve: &curve,
                t,
                side,
                span,
                tolerance,
                context: &context,
            };
            for region in &candidate.regions {
                check_region(&setting, region, &mut rng, &mut tally);
            }
        }
    }
    let failures = std::mem::take(&mut tally.failures);
    println!("{tally:#?}\nelapsed {:?}", started.elapsed());
    for failure in failures.iter().take(8) {
        println!("FAIL {failure}\n");
    }
    assert!(failures.is_empty(), "{} failures", failures.len());
    assert!(tally.polygons >= CURVES * 6, "too few polygons");
    assert!(tally.inside_checked >= tally.polygons && tally.outside_checked >= tally.polygons);
}
