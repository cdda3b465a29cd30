//! Helpers shared by the shape checks: a seeded PRNG, random cubic curves, an independent
//! de Boor evaluator, and a bounded numerical search of a knot pair's parameter domain that
//! uses only spline evaluation (never the shape core's closed forms).
#![allow(dead_code)]
#![allow(clippy::unwrap_used)]

pub mod compare;
pub mod nurbs;

use knotshape::shape::{KnotPair, Side};
use knotshape::spline::{Curve, CurveLimits, Point};

/// SplitMix64 (Steele, Lea & Flood 2014): tiny, seeded, reproducible.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `0 .. n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
}

/// `a - b`.
pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `|a|`.
pub fn norm(a: Point) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// `|a - b|`.
pub fn dist(a: Point, b: Point) -> f64 {
    norm(sub(a, b))
}

/// `d1 + x (d0 - d1) + y (d2 - d1)`: the geometric point of frame `(x, y)` of a triangle.
pub fn affine_point(triangle: &[Point; 3], x: f64, y: f64) -> Point {
    let [d0, d1, d2] = *triangle;
    std::array::from_fn(|i| d1[i] + x * (d0[i] - d1[i]) + y * (d2[i] - d1[i]))
}

/// The longest edge of a triangle (what the shape core's tolerances are relative to).
pub fn triangle_size(triangle: &[Point; 3]) -> f64 {
    let [d0, d1, d2] = *triangle;
    dist(d0, d1).max(dist(d1, d2)).max(dist(d0, d2))
}

/// The control triangle `d_{j-2}, d_{j-1}, d_j` of span `j`.
pub fn triangle_of(curve: &Curve, span: usize) -> [Point; 3] {
    let d = curve.control_points();
    [d[span - 2], d[span - 1], d[span]]
}

/// Options of [`random_curve`].
#[derive(Debug, Clone, Copy)]
pub struct CurveMix {
    /// Probability of a 3D curve.
    pub three_d: f64,
    /// Probability of weights.
    pub rational: f64,
    /// Probability of a clamped knot vector.
    pub clamped: f64,
    /// Probability that the knot vector has coincident interior knots.
    pub coincident: f64,
    /// Probability of log-uniform (skewed) knot spacing.
    pub skewed: f64,
}

impl Default for CurveMix {
    fn default() -> Self {
        CurveMix {
            three_d: 0.35,
            rational: 0.35,
            clamped: 0.5,
            coincident: 0.3,
            skewed: 0.3,
        }
    }
}

/// A random cubic curve: 5 to 10 control points in `[-5, 5]^dim`, weights in `[1/3, 3]`,
/// clamped or not, interior multiplicities up to 3, knots over a random interval.
pub fn random_curve(rng: &mut SplitMix64, mix: CurveMix) -> Curve {
    loop {
        let dim = if rng.chance(mix.three_d) { 3 } else { 2 };
        let count = 5 + rng.below(6);
        let points: Vec<Vec<f64>> = (0..count)
            .map(|_| (0..dim).map(|_| rng.range(-5.0, 5.0)).collect())
            .collect();
        let weights: Option<Vec<f64>> = rng.chance(mix.rational).then(|| {
            (0..count)
                .map(|_| (rng.range(-1.0, 1.0) * 3f64.ln()).exp())
                .collect()
        });
        let clamped = rng.chance(mix.clamped);
        let coincident = rng.chance(mix.coincident);
        let skewed = rng.chance(mix.skewed);
        let knots = random_knots(rng, count + 4, clamped, coincident, skewed);
        if let Ok(curve) = Curve::new(
            3,
            &points,
            &knots,
            weights.as_deref(),
            &CurveLimits::default(),
        ) {
            return curve;
        }
    }
}

/// A non-decreasing knot vector of `len` values.
fn random_knots(
    rng: &mut SplitMix64,
    len: usize,
    clamped: bool,
    coincident: bool,
    skewed: bool,
) -> Vec<f64> {
    let steps = len - 1;
    let mut increments = Vec::with_capacity(steps);
    let mut run = 1; // multiplicity of the current value
    for i in 0..steps {
        let end_run = clamped && (i < 3 || i >= steps - 3);
        let next_to_end = clamped && (i == 3 || i == steps - 4);
        let zero = end_run || (coincident && !next_to_end && run < 3 && rng.chance(0.3));
        let step = if zero {
            0.0
        } else if skewed {
            rng.range(-5.0, 2.0).exp()
        } else {
            rng.range(0.2, 1.0)
        };
        run = if zero { run + 1 } else { 1 };
        increments.push(step);
    }
    let total: f64 = increments.iter().sum();
    let origin = rng.range(-3.0, 3.0);
    let length = rng.range(0.5, 10.0);
    let mut knots = Vec::with_capacity(len);
    let mut acc = 0.0;
    knots.push(origin);
    for step in increments {
        acc += step;
        knots.push(origin + length * acc / total);
    }
    knots
}

/// Cox–de Boor evaluation of `curve`'s control net over the full knot vector `knots` at `t`
/// (right end as the limit from the left): written here so that solutions are checked by an
/// evaluator outside the crate, too. `None` when the domain is empty.
pub fn de_boor(curve: &Curve, knots: &[f64], t: f64) -> Option<Point> {
    let p = curve.degree();
    let n = curve.control_points().len() - 1;
    if knots[p] >= knots[n + 1] {
        return None;
    }
    // Span: largest m in p..=n with u_m <= t and u_m < u_{m+1}, for t inside the domain.
    let mut m = p;
    for i in p..=n {
        if knots[i] <= t && knots[i] < knots[i + 1] && (knots[i] < knots[n + 1]) {
            m = i;
        }
    }
    let mut d: Vec<[f64; 4]> = (0..=p)
        .map(|r| {
            let i = m - p + r;
            let w = curve.weight(i);
            let q = curve.control_points()[i];
            [w * q[0], w * q[1], w * q[2], w]
        })
        .collect();
    for level in 1..=p {
        for r in (level..=p).rev() {
            let i = m - p + r;
            let denominator = knots[i + p + 1 - level] - knots[i];
            let alpha = if denominator == 0.0 {
                0.0
            } else {
                (t - knots[i]) / denominator
            };
            let previous = d[r - 1];
            for (value, before) in d[r].iter_mut().zip(previous) {
                *value = (1.0 - alpha) * before + alpha * *value;
            }
        }
    }
    let h = d[p];
    Some([h[0] / h[3], h[1] / h[3], h[2] / h[3]])
}

/// The local knots of span `j`: `[L, a, b, c, e, R]` = `u_{j-2}, u_{j-1}, u_j, u_{j+2}, u_{j+3},
/// u_{j+4}` (read here directly, not through the shape core).
pub fn local_knots(knots: &[f64], span: usize) -> [f64; 6] {
    [
        knots[span - 2],
        knots[span - 1],
        knots[span],
        knots[span + 2],
        knots[span + 3],
        knots[span + 4],
    ]
}

/// Indices (0 = a, 1 = b, 2 = c, 3 = e) of the two knots a pair moves (MATH.md's table).
pub fn pair_unknowns(pair: KnotPair) -> [usize; 2] {
    match pair {
        KnotPair::Omega1 => [0, 1],
        KnotPair::Omega2 => [1, 2],
        KnotPair::Omega3 => [2, 3],
        KnotPair::Omega4 => [0, 2],
        KnotPair::Omega5 => [0, 3],
        KnotPair::Omega6 => [1, 3],
    }
}

/// Full-vector index of local knot `k` (0 = a, 1 = b, 2 = c, 3 = e) of span `j`.
pub fn full_index(span: usize, k: usize) -> usize {
    [span - 1, span, span + 2, span + 3][k]
}

/// Search settings.
#[derive(Debug, Clone, Copy)]
pub struct SearchOptions {
    /// Grid nodes per axis of the (unit-square parametrised) domain.
    pub grid: usize,
    /// Local refinements started from the best grid local minima.
    pub starts: usize,
    /// Levenberg–Marquardt iterations per start.
    pub iterations: usize,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            grid: 6,
            starts: 3,
            iterations: 40,
        }
    }
}

/// Relative size (of `R - L`) below which two found knot vectors are always the same solution
/// (the search's local refinement converges to ~1e-14 in residual; this leaves room for
/// moderate ill-conditioning).
pub const DISTINCT_KNOTS: f64 = 1e-6;

/// Refinement stops when the frame residual is below this (rounding level of the
/// evaluation, with a margin).
const STOP_RESIDUAL: f64 = 1e-14;

/// Finite-difference step of the Jacobian, in unit-square coordinates.
const FD_STEP: f64 = 1e-6;

/// Rows `g0, g2, n / size` such that `g0 · (p - d1) = λ0`, `g2 · (p - d1) = λ2` for `p` in
/// the plane of the triangle `d0, d1, d2` (the dual basis of `e1 = d0 - d1`, `e2 = d2 - d1`),
/// and `n` its unit normal (zero rows for a degenerate triangle's normal).
pub fn frame_rows(triangle: &[Point; 3]) -> [Point; 3] {
    let [d0, d1, d2] = *triangle;
    let e1 = sub(d0, d1);
    let e2 = sub(d2, d1);
    let dot = |p: Point, q: Point| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let (g11, g12, g22) = (dot(e1, e1), dot(e1, e2), dot(e2, e2));
    let det = g11 * g22 - g12 * g12;
    let combine =
        |p: f64, q: f64| -> Point { std::array::from_fn(|i| (p * e1[i] + q * e2[i]) / det) };
    let g0 = combine(g22, -g12);
    let g2 = combine(-g12, g11);
    let cross = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let length = norm(cross);
    let size = triangle_size(triangle);
    let normal = if length > 0.0 {
        cross.map(|v| v / (length * size))
    } else {
        [0.0; 3]
    };
    [g0, g2, normal]
}

/// Grid nodes on `[0, 1]`: `count` Chebyshev–Lobatto nodes plus `10^-2, 10^-3, 10^-4` from
/// each end, where the map crowds (solutions with nearly coincident knots).
pub fn grid_nodes(count: usize) -> Vec<f64> {
    let count = count.max(2);
    let mut nodes: Vec<f64> = (0..count)
        .map(|i| 0.5 - 0.5 * (std::f64::consts::PI * i as f64 / (count - 1) as f64).cos())
        .map(|v| v.clamp(0.0, 1.0))
        .collect();
    for k in 2..=4 {
        let v = 10f64.powi(-k);
        nodes.push(v);
        nodes.push(1.0 - v);
    }
    nodes.sort_by(f64::total_cmp);
    nodes.dedup();
    nodes
}

/// A solution the search found.
#[derive(Debug, Clone, Copy)]
pub struct FoundSolution {
    /// `[a, b, c, e]`.
    pub knots: [f64; 4],
    /// Its frame residual.
    pub residual: f64,
    /// Knot vectors within this max-norm distance are the same solution
    /// ([`Search::same_solution_radius`]).
    pub radius: f64,
}

/// Largest coordinate difference of two local knot vectors.
pub fn max_gap(p: &[f64; 4], q: &[f64; 4]) -> f64 {
    p.iter()
        .zip(q)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// A search solution and another knot vector are the same solution when their distance is
/// within this many times `residual / sensitivity` (first-order knot error of a residual).
pub const CONDITION_MARGIN: f64 = 10.0;

/// Rounding error of a target's frame coordinates (targets of size ~10 in triangles of size
/// ~1, computed in double precision), with a margin.
pub const FRAME_ROUNDING: f64 = 1e-14;

/// What the search found for one pair.
#[derive(Debug, Clone)]
pub struct PairSearch {
    /// Smallest residual found over the domain, in the triangle's frame: `|(Δλ0, Δλ2, off-plane
    /// distance / size)|` between `s_new(t)` and the target. Up to the search's accuracy, the
    /// target's distance to the region in frame units.
    pub best_residual: f64,
    /// `[a, b, c, e]` at the best point.
    pub best_knots: [f64; 4],
    /// Smallest slack of the domain's inequalities at the best point (knot units).
    pub best_edge_slack: f64,
    /// Distinct solutions: knot vectors `[a, b, c, e]` whose residual is at most `accept`.
    pub solutions: Vec<FoundSolution>,
    /// Whether the domain is empty (the keep-domain rule forbids every point).
    pub empty: bool,
    /// Curve evaluations used.
    pub evaluations: usize,
}

/// A bounded search over one pair's domain for `s_new(t) = target`.
///
/// The domain (MATH.md's table, with the two other knots fixed; under keep-domain a pair knot
/// at `u_3` or `u_{n+1}` is frozen and more than 4 knots at a domain end are forbidden) is
/// parametrised by the unit square `z ∈ [0, 1]^2` (triangles by a collapsed square). The
/// residual is `point_with_knots(new knots, t) - target`, evaluated by the spline core and
/// measured in the control triangle's barycentric frame. A grid (Chebyshev nodes plus nodes
/// crowding at the edges, where the map is steep) is followed by projected Levenberg–Marquardt
/// with a finite-difference Jacobian from the best grid local minima. Nothing here uses the
/// closed forms.
pub struct Search<'a> {
    curve: &'a Curve,
    span: usize,
    t: f64,
    pair: KnotPair,
    local: [f64; 6],
    fixed: [bool; 4],
    keep_domain: bool,
    empty: bool,
    buffer: Vec<f64>,
    evaluations: usize,
    /// Rows mapping a curve-space difference to (Δλ0, Δλ2, normal offset / size) of the
    /// control triangle: the residual is measured in the triangle's frame (dimensionless).
    to_frame: [Point; 3],
    /// `d_{j-1}`, the frame's origin.
    origin: Point,
    /// The target's barycentric coordinates and off-plane offset.
    goal: [f64; 4],
    /// Signed square roots of `goal[0..3]`.
    goal_roots: [f64; 3],
    /// Print each refinement step (debugging).
    pub trace: bool,
}

impl<'a> Search<'a> {
    /// The search for `pair` of span `span` (`u_{span+1} := t`).
    pub fn new(
        curve: &'a Curve,
        span: usize,
        t: f64,
        target: Point,
        pair: KnotPair,
        keep_domain: bool,
    ) -> Self {
        let knots = curve.knots();
        let n = curve.control_points().len() - 1;
        let domain_knot = |i: usize| keep_domain && (i == 3 || i == n + 1);
        // The moved knot itself may be a domain end: then nothing is allowed unless t equals it.
        let empty = domain_knot(span + 1) && knots[span + 1] != t;
        let unknowns = pair_unknowns(pair);
        let mut fixed = [true; 4];
        for k in unknowns {
            fixed[k] = domain_knot(full_index(span, k));
        }
        let mut search = Search {
            curve,
            span,
            t,
            pair,
            local: local_knots(knots, span),
            fixed,
            keep_domain,
            empty,
            buffer: knots.to_vec(),
            evaluations: 0,
            to_frame: frame_rows(&triangle_of(curve, span)),
            origin: curve.control_points()[span - 1],
            goal: [0.0; 4],
            goal_roots: [0.0; 3],
            trace: false,
        };
        search.goal = search.barycentric(target);
        let root = |v: f64| v.signum() * v.abs().sqrt();
        search.goal_roots = [
            root(search.goal[0]),
            root(search.goal[1]),
            root(search.goal[2]),
        ];
        search
    }

    /// `[a, b, c, e]` at unit-square point `z`.
    pub fn knots_at(&self, z: [f64; 2]) -> [f64; 4] {
        let [l, a0, b0, c0, e0, r] = self.local;
        let t = self.t;
        let lerp = |lo: f64, hi: f64, s: f64| if s >= 1.0 { hi } else { lo + s * (hi - lo) };
        let [fa, fb, fc, fe] = self.fixed;
        let pick = |fixed: bool, old: f64, lo: f64, hi: f64, s: f64| {
            if fixed { old } else { lerp(lo, hi, s) }
        };
        match self.pair {
            KnotPair::Omega1 => {
                let b = pick(fb, b0, if fa { a0 } else { l }, t, z[0]);
                let a = pick(fa, a0, l, b, z[1]);
                [a, b, c0, e0]
            }
            KnotPair::Omega2 => [a0, pick(fb, b0, a0, t, z[0]), pick(fc, c0, t, e0, z[1]), e0],
            KnotPair::Omega3 => {
                let c = pick(fc, c0, t, if fe { e0 } else { r }, z[0]);
                let e = pick(fe, e0, c, r, z[1]);
                [a0, b0, c, e]
            }
            KnotPair::Omega4 => [pick(fa, a0, l, b0, z[0]), b0, pick(fc, c0, t, e0, z[1]), e0],
            KnotPair::Omega5 => [pick(fa, a0, l, b0, z[0]), b0, c0, pick(fe, e0, c0, r, z[1])],
            KnotPair::Omega6 => [a0, pick(fb, b0, a0, t, z[0]), c0, pick(fe, e0, c0, r, z[1])],
        }
    }

    /// Smallest slack of the pair's domain inequalities at `[a, b, c, e]` (knot units).
    pub fn edge_slack(&self, v: [f64; 4]) -> f64 {
        let [l, _, _, _, _, r] = self.local;
        let t = self.t;
        let [a, b, c, e] = v;
        let slacks: &[f64] = match self.pair {
            KnotPair::Omega1 => &[a - l, b - a, t - b],
            KnotPair::Omega2 => &[b - a, t - b, c - t, e - c],
            KnotPair::Omega3 => &[c - t, e - c, r - e],
            KnotPair::Omega4 => &[a - l, b - a, c - t, e - c],
            KnotPair::Omega5 => &[a - l, b - a, e - c, r - e],
            KnotPair::Omega6 => &[b - a, t - b, e - c, r - e],
        };
        let frozen = pair_unknowns(self.pair).iter().any(|&k| self.fixed[k]);
        if frozen {
            // The keep-domain rule froze an unknown: the domain is a segment (or a point),
            // all boundary.
            return 0.0;
        }
        slacks.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Whether, under the keep-domain rule, the local knots `v` lie within `radius` of a
    /// forbidden configuration (more than 4 knots at a domain end): the search then finds
    /// points arbitrarily close to a target that no allowed knot vector reaches exactly.
    pub fn touches_forbidden_end(&self, v: [f64; 4], radius: f64) -> bool {
        if !self.keep_domain {
            return false;
        }
        let knots = self.full_knots(v);
        let n = self.curve.control_points().len() - 1;
        let near = |value: f64| {
            knots
                .iter()
                .filter(|&&u| (u - value).abs() <= radius)
                .count()
        };
        near(knots[3]) > 4 || near(knots[n + 1]) > 4
    }

    /// How far (knot units) the target pins the pair's knots near `v` given a frame residual
    /// `residual` plus the frame's own rounding (both unknowns, frozen or not: what the closed
    /// form has to go by): a solution this close to the domain's edge may lie on either side
    /// of it in exact arithmetic.
    pub fn edge_uncertainty(&mut self, v: [f64; 4], residual: f64) -> f64 {
        CONDITION_MARGIN * (residual + FRAME_ROUNDING) / self.sensitivity_of(v, true)
    }

    /// `R - L` of the span.
    pub fn scale(&self) -> f64 {
        self.local[5] - self.local[0]
    }

    /// The full knot vector with `u_{j+1} := t` and the local knots `v`.
    pub fn full_knots(&self, v: [f64; 4]) -> Vec<f64> {
        let mut knots = self.curve.knots().to_vec();
        let j = self.span;
        knots[j - 1] = v[0];
        knots[j] = v[1];
        knots[j + 1] = self.t;
        knots[j + 2] = v[2];
        knots[j + 3] = v[3];
        knots
    }

    /// The residual at `z`, by the spline core; `None` when the new knot vector has an empty
    /// domain or the value is not finite.
    ///
    /// [`Metric::Frame`]: `(Δλ0, 0, Δλ2, Δoff-plane)` between `s_new(t)` and the target, in the
    /// control triangle's barycentric frame. [`Metric::Root`]: the same with signed square
    /// roots of all three barycentric coordinates; the coordinates are (for a non-rational
    /// curve) the quadratic envelope's basis values, roughly squares of knot differences near
    /// the domain's edges, so their roots are far closer to linear there and Newton-type steps
    /// converge where they crawl in `Frame`. Both vanish exactly at the same points.
    fn residual(&mut self, z: [f64; 2], metric: Metric) -> Option<[f64; 4]> {
        let v = self.knots_at(z);
        self.residual_at(v, metric)
    }

    /// The residual of the local knots `v = [a, b, c, e]` (see [`Search::residual`]).
    fn residual_at(&mut self, v: [f64; 4], metric: Metric) -> Option<[f64; 4]> {
        self.evaluations += 1;
        let j = self.span;
        let n = self.curve.control_points().len() - 1;
        self.buffer[j - 1] = v[0];
        self.buffer[j] = v[1];
        self.buffer[j + 1] = self.t;
        self.buffer[j + 2] = v[2];
        self.buffer[j + 3] = v[3];
        if self.buffer[3] >= self.buffer[n + 1] {
            return None;
        }
        if self.keep_domain {
            // The keep-domain rule also forbids more than 4 knots at a domain end (a clamped
            // end's control point would drop out and the end point move).
            let count = |value: f64| self.buffer.iter().filter(|&&u| u == value).count();
            if count(self.buffer[3]) > 4 || count(self.buffer[n + 1]) > 4 {
                return None;
            }
        }
        let p = self.curve.point_with_knots(&self.buffer, self.t);
        let ours = self.barycentric(p);
        let goal = self.goal;
        let r = match metric {
            Metric::Frame => [ours[0] - goal[0], 0.0, ours[2] - goal[2], ours[3] - goal[3]],
            Metric::Root => {
                let root = |v: f64| v.signum() * v.abs().sqrt();
                [
                    root(ours[0]) - self.goal_roots[0],
                    root(ours[1]) - self.goal_roots[1],
                    root(ours[2]) - self.goal_roots[2],
                    ours[3] - goal[3],
                ]
            }
        };
        r.iter().all(|c| c.is_finite()).then_some(r)
    }

    /// The frame residual of the local knots `v` (infinite when they cannot be evaluated).
    pub fn frame_residual(&mut self, v: [f64; 4]) -> f64 {
        self.residual_at(v, Metric::Frame)
            .map_or(f64::INFINITY, norm4)
    }

    /// Smallest singular value of the frame residual's Jacobian with respect to the pair's
    /// free unknowns (knot units), by one-sided differences that keep the knots ordered: how
    /// well the target pins the knots down near `v`. Infinite when no unknown is free.
    pub fn sensitivity(&mut self, v: [f64; 4]) -> f64 {
        self.sensitivity_of(v, false)
    }

    /// [`Search::sensitivity`], optionally over the keep-domain-frozen unknowns too (how well
    /// the equations alone pin the pair's knots down).
    fn sensitivity_of(&mut self, v: [f64; 4], include_frozen: bool) -> f64 {
        let [l, .., r] = self.local;
        let step = 1e-7 * (r - l);
        let base = match self.residual_at(v, Metric::Frame) {
            Some(f) => f,
            None => return 0.0,
        };
        let mut columns: Vec<[f64; 4]> = Vec::new();
        for k in pair_unknowns(self.pair) {
            if self.fixed[k] && !include_frozen {
                continue;
            }
            let mut column = None;
            for h in [step, -step] {
                let mut w = v;
                w[k] += h;
                let [a, b, c, e] = w;
                let ordered = l <= a && a <= b && b <= self.t && self.t <= c && c <= e && e <= r;
                if !ordered {
                    continue;
                }
                if let Some(f) = self.residual_at(w, Metric::Frame) {
                    column = Some(std::array::from_fn(|i| (f[i] - base[i]) / h));
                    break;
                }
            }
            match column {
                Some(c) => columns.push(c),
                None => return 0.0,
            }
        }
        let dot4 = |p: &[f64; 4], q: &[f64; 4]| p.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
        match columns.as_slice() {
            [] => f64::INFINITY,
            [c] => dot4(c, c).sqrt(),
            [c, d] => {
                let (g11, g12, g22) = (dot4(c, c), dot4(c, d), dot4(d, d));
                let mean = 0.5 * (g11 + g22);
                let spread = (0.25 * (g11 - g22).powi(2) + g12 * g12).sqrt();
                (mean - spread).max(0.0).sqrt()
            }
            _ => unreachable!("a pair has two unknowns"),
        }
    }

    /// Radius (max-norm, knot units) within which knot vectors with frame residuals
    /// `residual` near `v` are the same solution: [`DISTINCT_KNOTS`] of `R - L`, widened where
    /// the target pins the knots down only loosely (`residual / sensitivity`).
    pub fn same_solution_radius(&mut self, v: [f64; 4], residual: f64) -> f64 {
        let [l, .., r] = self.local;
        let sensitivity = self.sensitivity(v);
        (DISTINCT_KNOTS * (r - l)).max(CONDITION_MARGIN * (residual + 1e-15) / sensitivity)
    }

    /// `(λ0, λ1, λ2, off-plane / size)` of `p` in the control triangle.
    fn barycentric(&self, p: Point) -> [f64; 4] {
        let d = sub(p, self.origin);
        let [l0, l2, off] = self
            .to_frame
            .map(|row| row[0] * d[0] + row[1] * d[1] + row[2] * d[2]);
        [l0, 1.0 - l0 - l2, l2, off]
    }

    fn cost(&mut self, z: [f64; 2]) -> f64 {
        self.residual(z, Metric::Frame).map_or(f64::INFINITY, norm4)
    }

    /// Runs the search; frame residuals up to `accept` count as solutions.
    pub fn run(&mut self, options: SearchOptions, accept: f64) -> PairSearch {
        if self.empty {
            return PairSearch {
                best_residual: f64::INFINITY,
                best_knots: [f64::NAN; 4],
                best_edge_slack: f64::NAN,
                solutions: Vec::new(),
                empty: true,
                evaluations: 0,
            };
        }
        let nodes = grid_nodes(options.grid);
        let g = nodes.len();
        let mut costs = vec![f64::INFINITY; g * g];
        for i in 0..g {
            for k in 0..g {
                costs[i * g + k] = self.cost([nodes[i], nodes[k]]);
            }
        }
        // Grid local minima (not larger than any of the 8 neighbours), best first.
        let mut minima: Vec<(f64, usize, usize)> = Vec::new();
        for i in 0..g {
            for k in 0..g {
                let value = costs[i * g + k];
                if !value.is_finite() {
                    continue;
                }
                let mut local_min = true;
                for di in -1i64..=1 {
                    for dk in -1i64..=1 {
                        let (ni, nk) = (i as i64 + di, k as i64 + dk);
                        if (di, dk) == (0, 0)
                            || ni < 0
                            || nk < 0
                            || ni >= g as i64
                            || nk >= g as i64
                        {
                            continue;
                        }
                        if costs[ni as usize * g + nk as usize] < value {
                            local_min = false;
                        }
                    }
                }
                if local_min {
                    minima.push((value, i, k));
                }
            }
        }
        minima.sort_by(|p, q| p.0.total_cmp(&q.0));
        let mut best = (f64::INFINITY, [0.5, 0.5]);
        let mut found: Vec<FoundSolution> = Vec::new();
        for &(_, i, k) in minima.iter().take(options.starts) {
            let (z, cost) = self.refine([nodes[i], nodes[k]], options.iterations);
            if cost < best.0 {
                best = (cost, z);
            }
            if cost <= accept {
                let knots = self.knots_at(z);
                let radius = self.same_solution_radius(knots, cost);
                let known = found
                    .iter_mut()
                    .find(|w| max_gap(&w.knots, &knots) <= w.radius.max(radius));
                match known {
                    Some(w) if cost < w.residual => {
                        *w = FoundSolution {
                            knots,
                            residual: cost,
                            radius,
                        }
                    }
                    Some(_) => {}
                    None => found.push(FoundSolution {
                        knots,
                        residual: cost,
                        radius,
                    }),
                }
            }
        }
        let best_knots = self.knots_at(best.1);
        PairSearch {
            best_residual: best.0,
            best_knots,
            best_edge_slack: self.edge_slack(best_knots),
            solutions: found,
            empty: false,
            evaluations: self.evaluations,
        }
    }

    /// Projected Levenberg–Marquardt from `z`, clamped to the unit square: first on the
    /// [`Metric::Root`] residual, then polished on [`Metric::Frame`]; returns the point and
    /// its frame residual.
    fn refine(&mut self, z: [f64; 2], iterations: usize) -> ([f64; 2], f64) {
        let (z, _) = self.levenberg_marquardt(z, iterations, Metric::Root);
        self.levenberg_marquardt(z, POLISH_ITERATIONS, Metric::Frame)
    }

    fn levenberg_marquardt(
        &mut self,
        mut z: [f64; 2],
        iterations: usize,
        metric: Metric,
    ) -> ([f64; 2], f64) {
        let Some(mut f) = self.residual(z, metric) else {
            return (z, f64::INFINITY);
        };
        let mut cost = norm4(f);
        let mut mu = 1e-3;
        let mut stalls = 0;
        for _ in 0..iterations {
            if cost <= STOP_RESIDUAL {
                break;
            }
            let mut jac = [[0.0; 4]; 2];
            for (axis, column) in jac.iter_mut().enumerate() {
                // Central differences, shifted inwards at the square's edges.
                let centre = z[axis].clamp(FD_STEP, 1.0 - FD_STEP);
                let (mut lo, mut hi) = (z, z);
                lo[axis] = centre - FD_STEP;
                hi[axis] = centre + FD_STEP;
                // One-sided at an edge the keep-domain rule forbids (the point itself is valid).
                let (f_lo, h_lo) = match self.residual(lo, metric) {
                    Some(v) => (v, lo[axis]),
                    None => (f, z[axis]),
                };
                let (f_hi, h_hi) = match self.residual(hi, metric) {
                    Some(v) => (v, hi[axis]),
                    None => (f, z[axis]),
                };
                if h_hi <= h_lo {
                    return (z, self.cost(z));
                }
                for c in 0..4 {
                    column[c] = (f_hi[c] - f_lo[c]) / (h_hi - h_lo);
                }
            }
            let dot4 =
                |p: &[f64; 4], q: &[f64; 4]| p.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
            let a11 = dot4(&jac[0], &jac[0]);
            let a22 = dot4(&jac[1], &jac[1]);
            let a12 = dot4(&jac[0], &jac[1]);
            let g1 = dot4(&jac[0], &f);
            let g2 = dot4(&jac[1], &f);
            let floor = 1e-14 * (a11 + a22) + f64::MIN_POSITIVE;
            let mut accepted = false;
            for _ in 0..12 {
                let m11 = a11 + mu * a11 + floor;
                let m22 = a22 + mu * a22 + floor;
                let det = m11 * m22 - a12 * a12;
                if !(det.is_finite() && det > 0.0) {
                    mu *= 4.0;
                    continue;
                }
                let d1 = -(m22 * g1 - a12 * g2) / det;
                let d2 = -(m11 * g2 - a12 * g1) / det;
                let zn = [(z[0] + d1).clamp(0.0, 1.0), (z[1] + d2).clamp(0.0, 1.0)];
                if let Some(fnew) = self.residual(zn, metric) {
                    let cost_new = norm4(fnew);
                    if cost_new < cost {
                        // Progress below 1e-6 of the cost, three times running: stalled on a
                        // positive minimum (a target outside the region).
                        stalls = if cost - cost_new < 1e-6 * cost {
                            stalls + 1
                        } else {
                            0
                        };
                        z = zn;
                        f = fnew;
                        cost = cost_new;
                        mu = (mu / 3.0).max(1e-12);
                        accepted = true;
                        break;
                    }
                }
                mu *= 4.0;
            }
            if self.trace {
                println!(
                    "  {metric:?} z = {z:?} cost = {cost:e} mu = {mu:e} accepted = {accepted}"
                );
            }
            if !accepted || stalls >= 3 {
                break;
            }
        }
        (z, self.cost(z))
    }
}

/// Which residual a refinement minimises (see [`Search::residual`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Metric {
    Frame,
    Root,
}

/// Euclidean norm of a 4-vector.
fn norm4(v: [f64; 4]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

/// Levenberg–Marquardt iterations of the final polish on the frame residual.
const POLISH_ITERATIONS: usize = 20;

/// `j` per side, computed here from the knots: `u_m <= t < u_{m+1}` (last non-empty span at
/// the right end); right: `j = m`, left: `j = m - 1`.
pub fn span_of(curve: &Curve, t: f64, side: Side) -> usize {
    let u = curve.knots();
    let n = curve.control_points().len() - 1;
    let mut m = 3;
    for i in 3..=n {
        if u[i] <= t && u[i] < u[i + 1] && u[i] < u[n + 1] {
            m = i;
        }
    }
    match side {
        Side::Right => m,
        Side::Left => m - 1,
    }
}

/// A random knot configuration of `pair` (edges a = L, a = b, c = e, e = R hit on purpose;
/// b = t and c = t avoided: those are the x = 0 / y = 0 edge cases, tested separately).
pub fn reachable_target(
    rng: &mut SplitMix64,
    curve: &Curve,
    span: usize,
    t: f64,
    pair: KnotPair,
) -> Option<Point> {
    let search = Search::new(curve, span, t, [0.0; 3], pair, false);
    for _ in 0..20 {
        let mut z = [rng.unit(), rng.unit()];
        for v in &mut z {
            if rng.chance(0.12) {
                *v = if rng.chance(0.5) { 0.0 } else { 1.0 };
            }
        }
        let v = search.knots_at(z);
        if v[1] == t || v[2] == t {
            continue;
        }
        let knots = search.full_knots(v);
        let moved = curve.with_full_knots(knots)?;
        let p = moved.point(t).ok()?;
        if p.iter().all(|c| c.is_finite()) {
            return Some(p);
        }
    }
    None
}

/// One random completeness case.
#[derive(Debug, Clone)]
pub struct RandomCase {
    /// The curve.
    pub curve: Curve,
    /// The picked parameter.
    pub t: f64,
    /// Whether the query keeps the domain.
    pub keep_domain: bool,
    /// The span the target was made for.
    pub span: usize,
    /// The target.
    pub target: Point,
    /// Made by moving a pair's knots (else random in/near the triangle).
    pub reachable: bool,
}

/// The case of `seed`: a random curve and `t`; half the targets made reachable by moving a
/// random pair's knots (evaluated by the spline core), half random in/near the triangle
/// (frame coordinates in `[-0.1, 1.1]`, `x + y <= 1.1`). `None` when no side applies.
pub fn random_case(seed: u64) -> Option<RandomCase> {
    let mut rng = SplitMix64::new(seed);
    let curve = random_curve(&mut rng, CurveMix::default());
    let (lo, hi) = curve.domain();
    let t = rng.range(lo, hi);
    let n = curve.control_points().len() - 1;
    let keep_domain = rng.chance(0.25);
    let usable: Vec<usize> = [Side::Right, Side::Left]
        .iter()
        .map(|&s| span_of(&curve, t, s))
        .filter(|&j| (2..=n).contains(&j))
        .collect();
    if usable.is_empty() {
        return None;
    }
    let span = usable[rng.below(usable.len())];
    let reachable = rng.chance(0.5);
    let target = if reachable {
        let pair = KnotPair::ALL[rng.below(6)];
        reachable_target(&mut rng, &curve, span, t, pair)?
    } else {
        let triangle = triangle_of(&curve, span);
        let (x, y) = loop {
            let (x, y) = (rng.range(-0.1, 1.1), rng.range(-0.1, 1.1));
            if x + y <= 1.1 {
                break (x, y);
            }
        };
        affine_point(&triangle, x, y)
    };
    Some(RandomCase {
        curve,
        t,
        keep_domain,
        span,
        target,
        reachable,
    })
}
