//! The knot families checked from outside (docs: MATH.md §8): random curves of any degree,
//! each family's problem read off the knot vector here (relevant knots, unknown sets, their
//! admissible boxes), the admissibility rules of §8.2, a check of one returned solution, and
//! a brute-force search for every solution of one unknown set (a graded grid over its box,
//! then Levenberg–Marquardt from every cell whose image may hold the target). Nothing here
//! calls the solver or the spline core's evaluation: points come from this module's own
//! de Boor on the curve's control net (read through the curve's accessors).
#![allow(dead_code)]
// The checks compare with `!(a <= b)` on purpose (a NaN fails them), and the small dense linear
// algebra of the brute force reads best with index loops.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::needless_range_loop)]

use std::fmt::Write as _;

use knotshape::shape::family::{Family, FamilyChoice, KnotSolution};
use knotshape::shape::{ShapeQuery, Side, SideChoice};
use knotshape::spline::{Curve, CurveLimits, Point};

use super::SplitMix64;

/// Residual a returned solution may have, relative to the extent of the control points
/// acting at `t` (the bound).
pub const RESIDUAL_TOLERANCE: f64 = 1e-9;

/// A solution lying at least this fraction of its box's width inside the box must be found
/// (MATH.md §8.2).
pub const INSIDE: f64 = 1e-7;

/// Roots whose conditioning (the smallest singular value of `∂P/∂x · diag(width)` over the
/// acting poles' extent) is below this are not required: moving their knots by a tenth of
/// their room moves the point by less than the solver's acceptance (`1e-9` of the size), so
/// they are not determined by the target (a knot far from `t` has leverage `∝ distance^q`,
/// MATH.md §8.3). A knot without any leverage (conditioning 0: `t` on a knot, whose far
/// neighbour then does not act) makes a set whose solutions are not isolated.
pub const DETERMINED: f64 = 1e-6;

/// Triples keep the span at least this fraction of its room from collapsing (the solver's
/// documented limit, `TRIPLE_COLLAPSE`); the tests require triples only above twice it.
pub const TRIPLE_COLLAPSE: f64 = 1e-4;

/// Relevant knots nearest `t` that triples are drawn from (the documented `TRIPLE_WINDOW`).
pub const TRIPLE_WINDOW: usize = 6;

// ------------------------------------------------------------------------------------------
// Random curves

/// What [`random_curve`] makes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveKind {
    pub degree: usize,
    pub dimension: usize,
    pub rational: bool,
    pub clamped: bool,
    /// Interior knots repeated (multiplicity up to `p − 1`).
    pub coincident: bool,
    /// Log-uniform knot gaps (some tiny) instead of even ones.
    pub skewed: bool,
}

impl CurveKind {
    /// A random kind of degree in `degrees`.
    pub fn random(rng: &mut SplitMix64, degrees: std::ops::RangeInclusive<usize>) -> CurveKind {
        let (lo, hi) = (*degrees.start(), *degrees.end());
        CurveKind {
            degree: lo + rng.below(hi - lo + 1),
            dimension: if rng.chance(0.4) { 3 } else { 2 },
            rational: rng.chance(0.4),
            clamped: rng.chance(0.6),
            coincident: rng.chance(0.35),
            skewed: rng.chance(0.25),
        }
    }
}

/// A random curve of `kind`: `p + 2` to `2p + 6` control points (a wavy polygon or uniform
/// random points in `[-5, 5]^dim`), weights uniform in `[0.3, 3]`, interior knots repeated
/// up to `p − 1` times, knots over a random interval.
pub fn random_curve(rng: &mut SplitMix64, kind: &CurveKind) -> Curve {
    let p = kind.degree;
    loop {
        let count = p + 2 + rng.below(p + 5);
        let wavy = rng.chance(0.5);
        let mut walk = [0.0f64; 3];
        let points: Vec<Vec<f64>> = (0..count)
            .map(|i| {
                (0..kind.dimension)
                    .map(|c| {
                        if wavy {
                            walk[c] += rng.range(-1.6, 1.6);
                            if c == 0 {
                                i as f64 + rng.range(-0.3, 0.3)
                            } else {
                                walk[c]
                            }
                        } else {
                            rng.range(-5.0, 5.0)
                        }
                    })
                    .collect()
            })
            .collect();
        let weights: Option<Vec<f64>> = kind
            .rational
            .then(|| (0..count).map(|_| rng.range(0.3, 3.0)).collect());
        let knots = random_knots(rng, p, count, kind);
        if let Ok(curve) = Curve::new(
            p,
            &points,
            &knots,
            weights.as_deref(),
            &CurveLimits::default(),
        ) {
            return curve;
        }
    }
}

/// A full knot vector (`count + p + 1` values).
fn random_knots(rng: &mut SplitMix64, p: usize, count: usize, kind: &CurveKind) -> Vec<f64> {
    let len = count + p + 1;
    let mut steps = Vec::with_capacity(len - 1);
    let mut run = 1;
    for i in 0..len - 1 {
        let end_run = kind.clamped && (i < p || i >= len - 1 - p);
        // Interior steps (the domain's inside, and the unclamped ends' outside) may be zero
        // while the run stays below p.
        let inside = i >= p && i < len - 1 - p;
        let zero = end_run
            || (kind.coincident
                && inside
                && i > p
                && i + 1 < len - 1 - p
                && run < p - 1
                && rng.chance(0.35));
        let step = if zero {
            0.0
        } else if kind.skewed {
            rng.range(-6.0, 1.0).exp()
        } else {
            rng.range(0.3, 1.0)
        };
        run = if zero && !end_run { run + 1 } else { 1 };
        steps.push(step);
    }
    let total: f64 = steps.iter().sum();
    let origin = rng.range(-3.0, 3.0);
    let length = rng.range(0.5, 10.0);
    let mut knots = vec![origin];
    let mut acc = 0.0;
    for step in steps {
        acc += step;
        knots.push(origin + length * acc / total);
    }
    knots
}

/// A parameter in the domain: uniform, exactly at an interior knot, a little off one (1e-9,
/// 1e-6 or 1e-3 of the span), at a domain end or 1e-7 of the domain inside it.
pub fn random_parameter(rng: &mut SplitMix64, curve: &Curve) -> f64 {
    let (lo, hi) = curve.domain();
    let interior: Vec<f64> = curve
        .knots()
        .iter()
        .copied()
        .filter(|&u| u > lo && u < hi)
        .collect();
    let roll = rng.below(20);
    let t = match roll {
        0 => lo,
        1 => hi,
        2 => lo + 1e-7 * (hi - lo),
        3 => hi - 1e-7 * (hi - lo),
        4..=6 if !interior.is_empty() => interior[rng.below(interior.len())],
        7..=9 if !interior.is_empty() => {
            let k = interior[rng.below(interior.len())];
            let offset = [1e-9, 1e-6, 1e-3][rng.below(3)] * (hi - lo);
            if rng.chance(0.5) {
                k + offset
            } else {
                k - offset
            }
        }
        _ => rng.range(lo, hi),
    };
    t.clamp(lo, hi)
}

// ------------------------------------------------------------------------------------------
// Evaluation (this module's own de Boor)

/// The control net of a curve as homogeneous points, with its degree.
#[derive(Debug, Clone)]
pub struct Net {
    pub degree: usize,
    pub poles: Vec<[f64; 4]>,
}

impl Net {
    /// The net of `curve` (through its accessors).
    pub fn of(curve: &Curve) -> Net {
        Net {
            degree: curve.degree(),
            poles: curve
                .control_points()
                .iter()
                .enumerate()
                .map(|(i, d)| {
                    let w = curve.weight(i);
                    [w * d[0], w * d[1], w * d[2], w]
                })
                .collect(),
        }
    }

    /// `n` (the last pole's index).
    pub fn n(&self) -> usize {
        self.poles.len() - 1
    }

    /// De Boor on span `m` (`u_m ≤ t ≤ u_{m+1}` expected; the formula is used as is).
    pub fn point_in_span(&self, knots: &[f64], m: usize, t: f64) -> Point {
        let p = self.degree;
        let mut d = [[0.0f64; 4]; 16];
        d[..=p].copy_from_slice(&self.poles[m - p..=m]);
        for level in 1..=p {
            for r in (level..=p).rev() {
                let i = m - p + r;
                let den = knots[i + p + 1 - level] - knots[i];
                let alpha = if den == 0.0 {
                    0.0
                } else {
                    (t - knots[i]) / den
                };
                let previous = d[r - 1];
                for c in 0..4 {
                    d[r][c] = previous[c] + alpha * (d[r][c] - previous[c]);
                }
            }
        }
        let h = d[p];
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    /// The curve over `knots` at `t` (the span right of `t`, the last non-empty one at the
    /// domain's right end).
    pub fn point(&self, knots: &[f64], t: f64) -> Point {
        self.point_in_span(knots, span_of(knots, self.degree, self.n(), t), t)
    }
}

/// The span `m` (`p ≤ m ≤ n`) with `u_m ≤ t < u_{m+1}`, or the last non-empty one when `t`
/// is at or past the domain's right end.
pub fn span_of(knots: &[f64], p: usize, n: usize, t: f64) -> usize {
    if t >= knots[n + 1] {
        return (p..=n)
            .rev()
            .find(|&m| knots[m] < knots[m + 1])
            .unwrap_or(n);
    }
    (p..=n)
        .rev()
        .find(|&m| knots[m] <= t && t < knots[m + 1])
        .unwrap_or(p)
}

/// `|a − b|`.
pub fn distance(a: Point, b: Point) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The largest distance between two of `points`.
pub fn extent(points: &[Point]) -> f64 {
    let mut largest = 0.0f64;
    for (k, a) in points.iter().enumerate() {
        for b in &points[k + 1..] {
            largest = largest.max(distance(*a, *b));
        }
    }
    largest
}

/// The largest absolute coordinate.
pub fn magnitude(p: Point) -> f64 {
    p.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

// ------------------------------------------------------------------------------------------
// Families as this module reads them

/// One family's problem at `t`, read off the knot vector.
#[derive(Debug, Clone)]
pub struct Setup {
    pub family: Family,
    pub side: Option<Side>,
    /// `j`: the direct family's span of `t`; the envelope's `i − 1`.
    pub span: usize,
    /// The envelope's knot `i` set to `t`.
    pub moved_knot: Option<usize>,
    /// The curve's knots, with `u_i := t` for the envelope.
    pub base: Vec<f64>,
    /// The `2q` relevant knots (full indices, ascending).
    pub relevant: Vec<usize>,
    /// The control points acting (full indices).
    pub poles: Vec<usize>,
    pub t: f64,
    pub degree: usize,
    pub n: usize,
    pub keep_domain: bool,
    /// The acting control points' extent (what residuals are relative to).
    pub size: f64,
}

/// Why a family does not apply (as this module sees it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NotApplicable {
    Degree,
    OutOfRange,
    MovesDomainEnd,
    EmptySpan,
    Collinear,
}

/// The family problem of `family` (and `side` for the envelope) at `t`.
pub fn setup(
    curve: &Curve,
    t: f64,
    family: Family,
    side: Option<Side>,
    keep_domain: bool,
) -> Result<Setup, NotApplicable> {
    let p = curve.degree();
    let n = curve.control_points().len() - 1;
    let knots = curve.knots();
    let m = span_of(knots, p, n, t);
    let mut base = knots.to_vec();
    let (span, moved_knot, relevant, poles) = match family {
        Family::Envelope => {
            if p < 3 {
                return Err(NotApplicable::Degree);
            }
            let i = match side {
                Some(Side::Left) => m,
                _ => m + 1,
            };
            if i < p || i > n + 1 {
                return Err(NotApplicable::OutOfRange);
            }
            if keep_domain && (i == p || i == n + 1) && knots[i] != t {
                return Err(NotApplicable::MovesDomainEnd);
            }
            if knots[i - 1] >= knots[i + 1] {
                return Err(NotApplicable::EmptySpan);
            }
            base[i] = t;
            let relevant: Vec<usize> = (i - p + 1..i).chain(i + 1..i + p).collect();
            (i - 1, Some(i), relevant, (i - p..i).collect::<Vec<_>>())
        }
        Family::Direct | Family::Triples => {
            if p < 2 {
                return Err(NotApplicable::Degree);
            }
            (
                m,
                None,
                (m - p + 1..=m + p).collect(),
                (m - p..=m).collect(),
            )
        }
    };
    let points: Vec<Point> = poles.iter().map(|&k| curve.control_points()[k]).collect();
    let size = extent(&points);
    if largest_triangle(&points) <= 1e-9 * size * size {
        return Err(NotApplicable::Collinear);
    }
    Ok(Setup {
        family,
        side: if family == Family::Envelope {
            side.or(Some(Side::Right))
        } else {
            None
        },
        span,
        moved_knot,
        base,
        relevant,
        poles,
        t,
        degree: p,
        n,
        keep_domain,
        size,
    })
}

/// Twice the largest triangle area of three of `points`.
fn largest_triangle(points: &[Point]) -> f64 {
    let mut best = 0.0f64;
    for a in 0..points.len() {
        for b in a + 1..points.len() {
            for c in b + 1..points.len() {
                let (e, f) = (sub(points[b], points[a]), sub(points[c], points[a]));
                let x = [
                    e[1] * f[2] - e[2] * f[1],
                    e[2] * f[0] - e[0] * f[2],
                    e[0] * f[1] - e[1] * f[0],
                ];
                best = best.max((x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt());
            }
        }
    }
    best
}

fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

impl Setup {
    /// The relevant knots that may move (the domain's ends stay under `keep_domain`).
    pub fn movable(&self) -> Vec<usize> {
        self.relevant
            .iter()
            .copied()
            .filter(|&g| !(self.keep_domain && (g == self.degree || g == self.n + 1)))
            .collect()
    }

    /// The window of triples: local indices `q − 2 ..= q + 3` of the relevant knots.
    pub fn triple_window(&self) -> Vec<usize> {
        let q = self.relevant.len() / 2;
        let half = TRIPLE_WINDOW / 2;
        let first = (q + 1).saturating_sub(half).max(1);
        let last = (q + half).min(2 * q);
        (first..=last)
            .map(|m| self.relevant[m - 1])
            .filter(|&g| !(self.keep_domain && (g == self.degree || g == self.n + 1)))
            .collect()
    }

    /// Every unknown set of this family (pairs; triples for `Family::Triples`).
    pub fn unknown_sets(&self) -> Vec<Vec<usize>> {
        let mut sets = Vec::new();
        if self.family == Family::Triples {
            let w = self.triple_window();
            for a in 0..w.len() {
                for b in a + 1..w.len() {
                    for c in b + 1..w.len() {
                        sets.push(vec![w[a], w[b], w[c]]);
                    }
                }
            }
        } else {
            let m = self.movable();
            for a in 0..m.len() {
                for b in a + 1..m.len() {
                    sets.push(vec![m[a], m[b]]);
                }
            }
        }
        sets
    }

    /// The knots with `unknowns` set to `x`.
    pub fn knots_with(&self, unknowns: &[usize], x: &[f64]) -> Vec<f64> {
        let mut knots = self.base.clone();
        for (&g, &v) in unknowns.iter().zip(x) {
            knots[g] = v;
        }
        knots
    }

    /// The span the point is evaluated on while the unknowns move: the direct family's `j`;
    /// for the envelope the curve's span right of `t = u_i` while it is not empty, else
    /// the one left of it.
    pub fn evaluation_span(&self, knots: &[f64]) -> usize {
        match self.moved_knot {
            Some(i) if i - 1 < self.degree || (i <= self.n && knots[i + 1] > self.t) => i,
            Some(i) => i - 1,
            None => self.span,
        }
    }
}

/// The admissible box of one unknown set: per unknown (ascending full indices) its interval
/// with the other unknowns free, and whether it is bound below by the previous unknown
/// (neighbours in the knot vector).
#[derive(Debug, Clone)]
pub struct SetBox {
    pub unknowns: Vec<usize>,
    pub lo: Vec<f64>,
    pub hi: Vec<f64>,
    pub chained: Vec<bool>,
    /// Both ends of `t`'s span (the direct family's `j`, `j + 1`), as positions in `unknowns`.
    pub span_ends: Option<(usize, usize)>,
}

impl SetBox {
    /// The box of `unknowns` (ascending) in `setup`; `None` when one has no room.
    pub fn new(setup: &Setup, unknowns: &[usize]) -> Option<SetBox> {
        let mut lo = Vec::new();
        let mut hi = Vec::new();
        for &g in unknowns {
            let below = (0..g).rev().find(|&k| !unknowns.contains(&k))?;
            let above = (g + 1..setup.base.len()).find(|&k| !unknowns.contains(&k))?;
            let (mut l, mut h) = (setup.base[below], setup.base[above]);
            if setup.moved_knot.is_none() {
                if g <= setup.span {
                    h = h.min(setup.t);
                } else {
                    l = l.max(setup.t);
                }
            }
            if !(h > l) {
                return None;
            }
            lo.push(l);
            hi.push(h);
        }
        let chained = (0..unknowns.len())
            .map(|k| k > 0 && unknowns[k] == unknowns[k - 1] + 1)
            .collect();
        let span_ends = if setup.moved_knot.is_none() {
            let a = unknowns.iter().position(|&g| g == setup.span);
            let b = unknowns.iter().position(|&g| g == setup.span + 1);
            a.zip(b)
        } else {
            None
        };
        Some(SetBox {
            unknowns: unknowns.to_vec(),
            lo,
            hi,
            chained,
            span_ends,
        })
    }

    pub fn width(&self, k: usize) -> f64 {
        self.hi[k] - self.lo[k]
    }

    /// The knots at unit-box point `s` (each unknown from its lower bound — the previous
    /// unknown when chained — to its upper bound).
    pub fn at(&self, s: &[f64]) -> Vec<f64> {
        let mut x = Vec::with_capacity(s.len());
        for k in 0..s.len() {
            let lo = if self.chained[k] {
                self.lo[k].max(x[k - 1])
            } else {
                self.lo[k]
            };
            let hi = self.hi[k];
            x.push(if s[k] >= 1.0 {
                hi
            } else {
                lo + s[k] * (hi - lo)
            });
        }
        x
    }

    /// `x` moved into the box.
    pub fn clamp(&self, x: &mut [f64]) {
        for k in 0..x.len() {
            let lo = if self.chained[k] {
                self.lo[k].max(x[k - 1])
            } else {
                self.lo[k]
            };
            x[k] = x[k].max(lo).min(self.hi[k]);
        }
    }

    /// How far inside the box `x` lies: the smallest distance to a bound (the previous
    /// unknown when chained) relative to the unknown's width (negative outside).
    pub fn inside(&self, x: &[f64]) -> f64 {
        let mut least = f64::INFINITY;
        for k in 0..x.len() {
            let w = self.width(k);
            least = least
                .min((x[k] - self.lo[k]) / w)
                .min((self.hi[k] - x[k]) / w);
            if self.chained[k] {
                least = least.min((x[k] - x[k - 1]) / w);
            }
        }
        least
    }

    /// The span's length relative to its room when both its ends are unknown.
    pub fn span_fraction(&self, x: &[f64]) -> Option<f64> {
        self.span_ends
            .map(|(a, b)| (x[b] - x[a]) / (self.hi[b] - self.lo[a]))
    }
}

// ------------------------------------------------------------------------------------------
// Admissibility and the check of one solution

/// Whether `knots` keeps MATH.md §8.2's rules for `setup` (with `changed` the indices that
/// differ from the curve's): `Err` says which rule fails.
pub fn admissible(curve: &Curve, setup: &Setup, knots: &[f64]) -> Result<(), String> {
    let old = curve.knots();
    let p = setup.degree;
    let n = setup.n;
    if knots.len() != old.len() {
        return Err("wrong length".into());
    }
    if knots.iter().any(|u| !u.is_finite()) {
        return Err("a knot is not finite".into());
    }
    if let Some(k) = (1..knots.len()).find(|&k| knots[k] < knots[k - 1]) {
        return Err(format!(
            "knots decrease at {k}: {} < {}",
            knots[k],
            knots[k - 1]
        ));
    }
    let t = setup.t;
    match setup.moved_knot {
        Some(i) => {
            if knots[i] != t {
                return Err(format!(
                    "the envelope's knot {i} is {} not t = {t}",
                    knots[i]
                ));
            }
            if !(knots[i - 1] < knots[i + 1]) {
                return Err("the envelope's span is empty".into());
            }
        }
        None => {
            let j = setup.span;
            if !(knots[j] <= t && t <= knots[j + 1] && knots[j] < knots[j + 1]) {
                return Err(format!(
                    "t = {t} left its span [{}, {}]",
                    knots[j],
                    knots[j + 1]
                ));
            }
        }
    }
    let count = |v: &[f64], x: f64| v.iter().filter(|&&u| u == x).count();
    let (lo, hi) = (knots[p], knots[n + 1]);
    for &x in knots {
        if x > lo && x < hi && count(knots, x) > p.max(count(old, x)) {
            return Err(format!(
                "knot value {x} has multiplicity {} > {p}",
                count(knots, x)
            ));
        }
    }
    if setup.keep_domain {
        for e in [p, n + 1] {
            if knots[e] != old[e] {
                return Err(format!("domain end {e} moved: {} -> {}", old[e], knots[e]));
            }
            if count(knots, knots[e]) > count(old, old[e]).max(p + 1) {
                return Err(format!("a knot moved onto the domain end {e}"));
            }
        }
    }
    if !(knots[p] < knots[n + 1]) {
        return Err("empty domain".into());
    }
    Ok(())
}

/// Checks one returned solution against `setup` (its family's problem), with the test's
/// own evaluators: family, side, span and moved knot as the problem says; the moved set one
/// the family draws; the admissibility rules; `changed_knots` exactly the knots that differ;
/// the new curve (common::de_boor) through the target within [`RESIDUAL_TOLERANCE`] of the
/// acting control points' extent, and the reported point and residual the same; and the
/// curve unchanged (sampled) outside `affected_domain`.
pub fn check_solution(
    curve: &Curve,
    setup: &Setup,
    target: Point,
    solution: &KnotSolution,
) -> Result<(), String> {
    let t = setup.t;
    if solution.family != setup.family
        || solution.side != setup.side
        || solution.moved_knot != setup.moved_knot
        || solution.span != setup.span
    {
        return Err(format!(
            "labels {:?} {:?} span {} moved {:?}; expected {:?} {:?} span {} moved {:?}",
            solution.family,
            solution.side,
            solution.span,
            solution.moved_knot,
            setup.family,
            setup.side,
            setup.span,
            setup.moved_knot
        ));
    }
    let set = solution.knots_moved.indices().to_vec();
    // A cubic's envelope pairs are the third release's Ω1–Ω6, answered as before: they are
    // tried with a domain end too (a solution then keeps it in place, checked below).
    let omega = setup.family == Family::Envelope && setup.degree == 3;
    let drawn = if omega {
        set.len() == 2 && set.iter().all(|g| setup.relevant.contains(g))
    } else {
        setup.unknown_sets().contains(&set)
    };
    if !drawn {
        return Err(format!("moved set {set:?} is not one the family draws"));
    }
    admissible(curve, setup, &solution.knots)?;
    let old = curve.knots();
    let changed: Vec<usize> = (0..old.len())
        .filter(|&i| solution.knots[i] != old[i])
        .collect();
    if changed != solution.changed_knots {
        return Err(format!(
            "changed {changed:?}, reported {:?}",
            solution.changed_knots
        ));
    }
    if let Some(&stray) = changed
        .iter()
        .find(|&&i| !set.contains(&i) && setup.moved_knot != Some(i))
    {
        return Err(format!(
            "knot {stray} changed outside the moved set {set:?}"
        ));
    }
    let point =
        super::de_boor(curve, &solution.knots, t).ok_or("the new knots have an empty domain")?;
    let miss = distance(point, target);
    let allowed = RESIDUAL_TOLERANCE * setup.size + 64.0 * f64::EPSILON * magnitude(target);
    if !(miss <= allowed) {
        return Err(format!(
            "misses the target by {miss:e} (allowed {allowed:e})"
        ));
    }
    if !(distance(point, solution.point) <= allowed) {
        return Err(format!(
            "reported point {:?} differs from the evaluated {point:?}",
            solution.point
        ));
    }
    if !((solution.residual - miss).abs() <= allowed) {
        return Err(format!(
            "reported residual {:e}, evaluated {miss:e}",
            solution.residual
        ));
    }
    // Outside the affected interval the curve is unchanged.
    let (lo, hi) = curve.domain();
    let (new_lo, new_hi) = (solution.knots[setup.degree], solution.knots[setup.n + 1]);
    let (a_lo, a_hi) = solution.affected_domain;
    if !(changed.is_empty() || a_lo <= t && t <= a_hi) {
        return Err(format!(
            "t = {t} outside the affected domain {:?}",
            (a_lo, a_hi)
        ));
    }
    let scale = curve
        .control_points()
        .iter()
        .map(|&p| magnitude(p))
        .fold(1.0, f64::max);
    let width = hi - lo;
    let samples = (0..=160).map(|k| lo + width * k as f64 / 160.0).chain([
        a_lo - 1e-9 * width,
        a_hi + 1e-9 * width,
        a_lo,
        a_hi,
    ]);
    for u in samples {
        if u < a_lo || u > a_hi {
            if u < lo.max(new_lo) || u > hi.min(new_hi) {
                continue;
            }
            let before = super::de_boor(curve, old, u).ok_or("old curve")?;
            let after = super::de_boor(curve, &solution.knots, u).ok_or("new curve")?;
            if distance(before, after) > 1e-12 * scale {
                return Err(format!(
                    "the curve changed by {:e} at u = {u}, outside the affected domain {:?}",
                    distance(before, after),
                    (a_lo, a_hi)
                ));
            }
        }
    }
    Ok(())
}

// ------------------------------------------------------------------------------------------
// Brute force

/// A root of one unknown set found by the brute-force search.
#[derive(Debug, Clone)]
pub struct BruteRoot {
    /// The unknowns' values.
    pub x: Vec<f64>,
    /// `|P(x) − target|`.
    pub residual: f64,
    /// [`SetBox::inside`].
    pub inside: f64,
    /// The smallest singular value of `∂P/∂x · diag(width)` over the acting poles' extent.
    pub conditioning: f64,
}

/// What the brute force found for one set.
#[derive(Debug, Clone, Default)]
pub struct BruteSet {
    /// Roots within the acceptance (rounding level).
    pub roots: Vec<BruteRoot>,
    /// Points where the residual is small but above the acceptance (near a fold's tangency,
    /// or a target just off a pair's surface in 3D): neither required nor excluded.
    pub near: Vec<BruteRoot>,
    /// Point evaluations made.
    pub evaluations: usize,
}

/// Brute-force settings.
#[derive(Debug, Clone, Copy)]
pub struct BruteOptions {
    /// Chebyshev–Lobatto nodes per axis (plus nodes crowding at both ends).
    pub grid: usize,
    /// Levenberg–Marquardt iterations per seed.
    pub iterations: usize,
}

impl BruteOptions {
    pub fn pairs() -> BruteOptions {
        BruteOptions {
            grid: 24,
            iterations: 60,
        }
    }
    pub fn triples() -> BruteOptions {
        BruteOptions {
            grid: 9,
            iterations: 60,
        }
    }
}

/// Graded nodes on `[0, 1]`: `count + 1` Chebyshev–Lobatto nodes and `10^-k`, `1 − 10^-k` for
/// `k = 2 ..= deepest`.
fn nodes(count: usize, deepest: i32) -> Vec<f64> {
    let mut v: Vec<f64> = (0..=count)
        .map(|i| 0.5 - 0.5 * (std::f64::consts::PI * i as f64 / count as f64).cos())
        .collect();
    for k in 2..=deepest {
        let e = 10f64.powi(-k);
        v.push(e);
        v.push(1.0 - e);
    }
    v.iter_mut().for_each(|x| *x = x.clamp(0.0, 1.0));
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The acceptance of a brute-force root: rounding of the evaluation.
pub fn root_acceptance(setup: &Setup, target: Point) -> f64 {
    1e-12 * setup.size + 256.0 * f64::EPSILON * magnitude(target)
}

/// Every solution of `unknowns` in `setup` for `target`: the graded grid, seeds from every
/// cell whose image (its corners' bounding box, enlarged by half) holds the target and from
/// the grid's local minima, Levenberg–Marquardt on this module's de Boor from each, and the
/// distinct results.
pub fn brute_force(
    net: &Net,
    setup: &Setup,
    sbox: &SetBox,
    target: Point,
    options: BruteOptions,
) -> BruteSet {
    let k = sbox.unknowns.len();
    let deepest = if k == 2 { 7 } else { 4 };
    let axis = nodes(options.grid, deepest);
    let count = axis.len();
    let cells_per_axis = count - 1;
    let total: usize = count.pow(k as u32);
    let mut evaluations = 0;
    let mut values: Vec<Point> = Vec::with_capacity(total);
    let mut knots = setup.base.clone();
    let eval = |x: &[f64], knots: &mut Vec<f64>, evaluations: &mut usize| -> Point {
        for (&g, &v) in sbox.unknowns.iter().zip(x) {
            knots[g] = v;
        }
        *evaluations += 1;
        let m = setup.evaluation_span(knots);
        net.point_in_span(knots, m, setup.t)
    };
    let index_of = |flat: usize| -> [usize; 3] {
        let mut i = [0; 3];
        let mut rest = flat;
        for slot in i.iter_mut().take(k) {
            *slot = rest % count;
            rest /= count;
        }
        i
    };
    for flat in 0..total {
        let i = index_of(flat);
        let s: Vec<f64> = (0..k).map(|c| axis[i[c]]).collect();
        let x = sbox.at(&s);
        values.push(eval(&x, &mut knots, &mut evaluations));
    }
    let flat_of = |i: [usize; 3]| -> usize {
        let mut f = 0;
        for c in (0..k).rev() {
            f = f * count + i[c];
        }
        f
    };
    // Seeds: cells whose image may hold the target.
    let mut seeds: Vec<(f64, Vec<f64>)> = Vec::new();
    let cells: usize = cells_per_axis.pow(k as u32);
    for cell in 0..cells {
        let mut c = [0; 3];
        let mut rest = cell;
        for slot in c.iter_mut().take(k) {
            *slot = rest % cells_per_axis;
            rest /= cells_per_axis;
        }
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut mean = [0.0; 3];
        for corner in 0..(1usize << k) {
            let mut i = c;
            for d in 0..k {
                i[d] += (corner >> d) & 1;
            }
            let v = values[flat_of(i)];
            for d in 0..3 {
                lo[d] = lo[d].min(v[d]);
                hi[d] = hi[d].max(v[d]);
                mean[d] += v[d] / (1usize << k) as f64;
            }
        }
        let spread = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let pad = 0.5 * spread + 1e-9 * setup.size;
        if (0..3).all(|d| target[d] >= lo[d] - pad && target[d] <= hi[d] + pad) {
            let s: Vec<f64> = (0..k)
                .map(|d| 0.5 * (axis[c[d]] + axis[c[d] + 1]))
                .collect();
            seeds.push((distance(mean, target), s));
        }
    }
    // Local minima of the residual over the grid's vertices.
    let mut minima: Vec<(f64, Vec<f64>)> = Vec::new();
    for flat in 0..total {
        let i = index_of(flat);
        let r = distance(values[flat], target);
        if r > 0.2 * setup.size {
            continue;
        }
        let mut lowest = true;
        for d in 0..k {
            for step in [-1i64, 1] {
                let v = i[d] as i64 + step;
                if v < 0 || v >= count as i64 {
                    continue;
                }
                let mut j = i;
                j[d] = v as usize;
                if distance(values[flat_of(j)], target) < r {
                    lowest = false;
                }
            }
        }
        if lowest {
            minima.push((r, (0..k).map(|d| axis[i[d]]).collect()));
        }
    }
    minima.sort_by(|a, b| a.0.total_cmp(&b.0));
    minima.truncate(12);
    seeds.sort_by(|a, b| a.0.total_cmp(&b.0));
    if seeds.len() > 160 {
        // Keep the best few of each connected group of cells (in seed order) — near a fold
        // many neighbouring cells qualify; far apart groups hold different roots.
        seeds = thin(seeds, &axis, 6);
    }
    seeds.extend(minima);
    let accept = root_acceptance(setup, target);
    let mut set = BruteSet::default();
    for (_, s) in seeds {
        let x0 = sbox.at(&s);
        let (x, residual) = levenberg_marquardt(
            &|x: &[f64], knots: &mut Vec<f64>, e: &mut usize| eval(x, knots, e),
            sbox,
            target,
            x0,
            options.iterations,
            accept,
            &mut knots,
            &mut evaluations,
        );
        if residual > 1e-8 * setup.size {
            continue;
        }
        let conditioning = conditioning_at(
            &|x: &[f64], knots: &mut Vec<f64>, e: &mut usize| eval(x, knots, e),
            sbox,
            &x,
            setup.size,
            &mut knots,
            &mut evaluations,
        );
        let root = BruteRoot {
            inside: sbox.inside(&x),
            x,
            residual,
            conditioning,
        };
        let list = if residual <= accept {
            &mut set.roots
        } else {
            &mut set.near
        };
        let same = list
            .iter_mut()
            .find(|r| same_point(sbox, &r.x, &root.x, 1e-7));
        match same {
            Some(r) if r.residual > root.residual => *r = root,
            Some(_) => {}
            None => list.push(root),
        }
    }
    // A near point that converged onto a root is the root.
    let roots = set.roots.clone();
    set.near
        .retain(|n| !roots.iter().any(|r| same_point(sbox, &r.x, &n.x, 1e-6)));
    set.evaluations = evaluations;
    set
}

/// The seeds kept from a large list: walking it best first, a seed is kept while fewer than
/// `per_group` kept seeds lie within two cells' width (in the unit box) of it.
fn thin(seeds: Vec<(f64, Vec<f64>)>, axis: &[f64], per_group: usize) -> Vec<(f64, Vec<f64>)> {
    let widest = axis.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    let mut kept: Vec<(f64, Vec<f64>)> = Vec::new();
    for seed in seeds {
        let close = kept
            .iter()
            .filter(|k| {
                k.1.iter()
                    .zip(&seed.1)
                    .all(|(a, b)| (a - b).abs() <= 2.0 * widest)
            })
            .count();
        if close < per_group {
            kept.push(seed);
        }
    }
    kept
}

/// Whether two points of a set's box are the same within `relative` of each unknown's width.
pub fn same_point(sbox: &SetBox, a: &[f64], b: &[f64], relative: f64) -> bool {
    (0..a.len()).all(|k| (a[k] - b[k]).abs() <= relative * sbox.width(k))
}

type Eval<'a> = dyn Fn(&[f64], &mut Vec<f64>, &mut usize) -> Point + 'a;

/// The Jacobian `∂P/∂x` (3 × k) by central differences (one-sided at the box's bounds).
fn jacobian(
    eval: &Eval,
    sbox: &SetBox,
    x: &[f64],
    knots: &mut Vec<f64>,
    evaluations: &mut usize,
) -> Vec<Point> {
    let k = x.len();
    let mut columns = Vec::with_capacity(k);
    for d in 0..k {
        let h = (1e-7 * sbox.width(d)).max(1e3 * f64::EPSILON * x[d].abs());
        let up = (x[d] + h).min(sbox.hi[d]);
        let down = (x[d] - h).max(sbox.lo[d]);
        let (mut a, mut b) = (x.to_vec(), x.to_vec());
        a[d] = up;
        b[d] = down;
        let (pa, pb) = (eval(&a, knots, evaluations), eval(&b, knots, evaluations));
        let span = up - down;
        columns.push(if span > 0.0 {
            [0, 1, 2].map(|c| (pa[c] - pb[c]) / span)
        } else {
            [0.0; 3]
        });
    }
    columns
}

/// Levenberg–Marquardt on `|P(x) − target|²` in the box (projected), from `x`.
#[allow(clippy::too_many_arguments)]
fn levenberg_marquardt(
    eval: &Eval,
    sbox: &SetBox,
    target: Point,
    mut x: Vec<f64>,
    iterations: usize,
    accept: f64,
    knots: &mut Vec<f64>,
    evaluations: &mut usize,
) -> (Vec<f64>, f64) {
    let k = x.len();
    sbox.clamp(&mut x);
    let residual = |p: Point| sub(p, target);
    let mut r = residual(eval(&x, knots, evaluations));
    let mut f = r.iter().map(|v| v * v).sum::<f64>();
    let mut mu = 1e-4;
    let mut quiet = 0;
    for _ in 0..iterations {
        if f.sqrt() <= 0.01 * accept {
            break;
        }
        let j = jacobian(eval, sbox, &x, knots, evaluations);
        let mut a = [[0.0f64; 3]; 3];
        let mut g = [0.0f64; 3];
        for p in 0..k {
            for q in 0..k {
                a[p][q] = (0..3).map(|c| j[p][c] * j[q][c]).sum();
            }
            g[p] = (0..3).map(|c| j[p][c] * r[c]).sum();
        }
        let mut improved = false;
        for _ in 0..12 {
            let mut m = a;
            for p in 0..k {
                m[p][p] += mu * a[p][p].max(1e-300);
            }
            let Some(step) = solve_small(&m, &g, k) else {
                mu *= 10.0;
                continue;
            };
            let mut trial: Vec<f64> = (0..k).map(|p| x[p] - step[p]).collect();
            sbox.clamp(&mut trial);
            let rt = residual(eval(&trial, knots, evaluations));
            let ft = rt.iter().map(|v| v * v).sum::<f64>();
            if ft < f {
                let moved = (0..k)
                    .map(|p| (trial[p] - x[p]).abs() / sbox.width(p))
                    .fold(0.0, f64::max);
                x = trial;
                r = rt;
                f = ft;
                mu = (mu * 0.2).max(1e-12);
                improved = true;
                quiet = if moved < 1e-15 { quiet + 1 } else { 0 };
                break;
            }
            mu *= 10.0;
        }
        if !improved || quiet >= 2 {
            break;
        }
    }
    (x, f.sqrt())
}

/// `σ_min(J · diag(width)) / size` at `x`.
fn conditioning_at(
    eval: &Eval,
    sbox: &SetBox,
    x: &[f64],
    size: f64,
    knots: &mut Vec<f64>,
    evaluations: &mut usize,
) -> f64 {
    let j = jacobian(eval, sbox, x, knots, evaluations);
    let k = x.len();
    let columns: Vec<Point> = (0..k)
        .map(|d| j[d].map(|v| v * sbox.width(d) / size))
        .collect();
    smallest_singular_value(&columns)
}

/// The smallest singular value of the 3 × k matrix of `columns` (k = 2 or 3), by Jacobi
/// rotations of its Gram matrix.
pub fn smallest_singular_value(columns: &[Point]) -> f64 {
    let k = columns.len();
    let mut a = [[0.0f64; 3]; 3];
    for p in 0..k {
        for q in 0..k {
            a[p][q] = (0..3).map(|c| columns[p][c] * columns[q][c]).sum();
        }
    }
    for _ in 0..50 {
        let mut off = 0.0;
        for p in 0..k {
            for q in p + 1..k {
                off += a[p][q] * a[p][q];
            }
        }
        if off < 1e-300 {
            break;
        }
        for p in 0..k {
            for q in p + 1..k {
                if a[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for r in 0..k {
                    let (arp, arq) = (a[r][p], a[r][q]);
                    a[r][p] = c * arp - s * arq;
                    a[r][q] = s * arp + c * arq;
                }
                for r in 0..k {
                    let (apr, aqr) = (a[p][r], a[q][r]);
                    a[p][r] = c * apr - s * aqr;
                    a[q][r] = s * apr + c * aqr;
                }
            }
        }
    }
    (0..k)
        .map(|p| a[p][p])
        .fold(f64::INFINITY, f64::min)
        .max(0.0)
        .sqrt()
}

/// Solves the k × k system `m y = g` (Gaussian elimination with pivoting).
fn solve_small(m: &[[f64; 3]; 3], g: &[f64; 3], k: usize) -> Option<[f64; 3]> {
    let mut a = *m;
    let mut b = *g;
    for c in 0..k {
        let pivot = (c..k).max_by(|&r, &s| a[r][c].abs().total_cmp(&a[s][c].abs()))?;
        if !(a[pivot][c].abs() > 0.0) {
            return None;
        }
        a.swap(c, pivot);
        b.swap(c, pivot);
        for r in c + 1..k {
            let f = a[r][c] / a[c][c];
            for q in c..k {
                a[r][q] -= f * a[c][q];
            }
            b[r] -= f * b[c];
        }
    }
    let mut y = [0.0; 3];
    for c in (0..k).rev() {
        let s: f64 = (c + 1..k).map(|q| a[c][q] * y[q]).sum();
        y[c] = (b[c] - s) / a[c][c];
    }
    y.iter().all(|v| v.is_finite()).then_some(y)
}

/// How far (relative to each unknown's width) a returned solution may lie from a root and
/// still be that root: `INSIDE`, widened for ill-conditioned roots by the rounding of the
/// point over `σ_min` and by ten times the returned solution's own residual over `σ_min`
/// (its first-order distance from the root it approximates: a closed form near a region's
/// edge may return a point within the solver's acceptance that is farther from the root
/// than rounding); `residual` and `rounding` ([`rounding`]) are relative to the acting
/// poles' extent. At most 1e-2.
pub fn match_tolerance(conditioning: f64, residual: f64, rounding: f64) -> f64 {
    let c = conditioning.max(1e-300);
    (rounding / c).max(10.0 * residual / c).clamp(INSIDE, 1e-2)
}

/// The rounding of a point of `setup`'s problem relative to its acting poles' extent:
/// `10⁻¹²`, times the ratio of the poles' largest coordinate to their extent when that is
/// above one (a small fillet far from the origin, as in real CAD models, evaluates with the
/// rounding of its large coordinates).
pub fn rounding(curve: &Curve, setup: &Setup) -> f64 {
    let magnitude = setup
        .poles
        .iter()
        .flat_map(|&i| curve.control_points()[i].iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    1e-12 * (magnitude / setup.size).max(1.0)
}

/// The residual of a returned solution (the tests' own de Boor), relative to the acting
/// poles' extent.
pub fn relative_residual(
    curve: &Curve,
    setup: &Setup,
    solution: &KnotSolution,
    target: Point,
) -> f64 {
    super::de_boor(curve, &solution.knots, setup.t)
        .map_or(f64::INFINITY, |p| distance(p, target) / setup.size)
}

/// The conditioning of `x` for `unknowns` (for solutions found elsewhere).
pub fn conditioning(net: &Net, setup: &Setup, sbox: &SetBox, x: &[f64]) -> f64 {
    let mut knots = setup.base.clone();
    let mut evaluations = 0;
    let eval = |x: &[f64], knots: &mut Vec<f64>, _: &mut usize| -> Point {
        for (&g, &v) in sbox.unknowns.iter().zip(x) {
            knots[g] = v;
        }
        let m = setup.evaluation_span(knots);
        net.point_in_span(knots, m, setup.t)
    };
    conditioning_at(&eval, sbox, x, setup.size, &mut knots, &mut evaluations)
}

// ------------------------------------------------------------------------------------------
// Comparison of an answer with the brute force

/// The solutions of one family problem (family and side) moving exactly `unknowns`.
pub fn answers_of<'a>(
    solutions: &'a [KnotSolution],
    setup: &Setup,
    unknowns: &[usize],
) -> Vec<&'a KnotSolution> {
    solutions
        .iter()
        .filter(|s| {
            s.family == setup.family && s.side == setup.side && s.knots_moved.indices() == unknowns
        })
        .collect()
}

/// Counts of one completeness comparison.
#[derive(Debug, Clone, Copy, Default)]
pub struct Completeness {
    pub sets: usize,
    /// Brute-force roots that had to be found (inside by [`INSIDE`], triples off the collapse).
    pub required: usize,
    pub found: usize,
    /// Brute-force roots on or within `INSIDE` of the box's edge (not required).
    pub edge: usize,
    /// Answer solutions.
    pub answered: usize,
    /// Answer solutions inside by `INSIDE` that the brute force also found.
    pub confirmed: usize,
    /// Sets with two or more required roots.
    pub multiple: usize,
    /// Brute-force roots inside the box but not determined ([`DETERMINED`]), and how many of
    /// them the answer has.
    pub undetermined: usize,
    pub undetermined_found: usize,
    pub evaluations: usize,
}

impl std::ops::AddAssign for Completeness {
    fn add_assign(&mut self, o: Completeness) {
        self.sets += o.sets;
        self.required += o.required;
        self.found += o.found;
        self.edge += o.edge;
        self.answered += o.answered;
        self.confirmed += o.confirmed;
        self.multiple += o.multiple;
        self.undetermined += o.undetermined;
        self.undetermined_found += o.undetermined_found;
        self.evaluations += o.evaluations;
    }
}

/// Whether a brute-force root lies in the part of the box where solutions must be found:
/// inside by [`INSIDE`], and for triples the span at least twice [`TRIPLE_COLLAPSE`] of its
/// room.
pub fn required(sbox: &SetBox, root: &BruteRoot) -> bool {
    let collapse_ok = sbox.unknowns.len() < 3
        || sbox
            .span_fraction(&root.x)
            .is_none_or(|f| f >= 2.0 * TRIPLE_COLLAPSE);
    root.inside >= INSIDE && collapse_ok
}

/// Compares the answer's solutions of every set in `sets` with the brute force: every
/// required brute-force root must be among the answer's solutions of its set (within
/// [`match_tolerance`] of each unknown's width), and every answer solution inside by
/// [`INSIDE`] among the brute force's roots or near points. `Err` describes each miss.
pub fn compare_with_brute_force(
    curve: &Curve,
    setup: &Setup,
    target: Point,
    solutions: &[KnotSolution],
    sets: &[Vec<usize>],
    options: BruteOptions,
) -> Result<Completeness, String> {
    let net = Net::of(curve);
    let mut counts = Completeness::default();
    let mut report = String::new();
    for unknowns in sets {
        let Some(sbox) = SetBox::new(setup, unknowns) else {
            continue;
        };
        counts.sets += 1;
        let brute = brute_force(&net, setup, &sbox, target, options);
        counts.evaluations += brute.evaluations;
        let answers = answers_of(solutions, setup, unknowns);
        let answer_x: Vec<Vec<f64>> = answers
            .iter()
            .map(|s| unknowns.iter().map(|&g| s.knots[g]).collect())
            .collect();
        let answer_r: Vec<f64> = answers
            .iter()
            .map(|s| relative_residual(curve, setup, s, target))
            .collect();
        counts.answered += answers.len();
        let mut required_here = 0;
        for root in &brute.roots {
            if !required(&sbox, root) {
                counts.edge += 1;
                continue;
            }
            let found = answer_x.iter().zip(&answer_r).any(|(a, &r)| {
                same_point(
                    &sbox,
                    a,
                    &root.x,
                    match_tolerance(root.conditioning, r, rounding(curve, setup)),
                )
            });
            if root.conditioning < DETERMINED {
                counts.undetermined += 1;
                counts.undetermined_found += usize::from(found);
                continue;
            }
            required_here += 1;
            counts.required += 1;
            if found {
                counts.found += 1;
            } else {
                let _ = writeln!(
                    report,
                    "MISSED {:?} side {:?} set {unknowns:?}: brute-force root {:?} (residual {:.1e}, inside {:.1e}, conditioning {:.1e}); answer has {:?}; box lo {:?} hi {:?}",
                    setup.family,
                    setup.side,
                    root.x,
                    root.residual,
                    root.inside,
                    root.conditioning,
                    answer_x,
                    sbox.lo,
                    sbox.hi
                );
            }
        }
        if required_here >= 2 {
            counts.multiple += 1;
        }
        for (a, &r) in answer_x.iter().zip(&answer_r) {
            if sbox.inside(a) < INSIDE {
                continue;
            }
            let c = conditioning(&net, setup, &sbox, a);
            if c < DETERMINED {
                continue;
            }
            let tolerance = match_tolerance(c, r, rounding(curve, setup));
            if brute
                .roots
                .iter()
                .chain(&brute.near)
                .any(|r| same_point(&sbox, a, &r.x, tolerance))
            {
                counts.confirmed += 1;
            } else {
                let _ = writeln!(
                    report,
                    "UNCONFIRMED {:?} side {:?} set {unknowns:?}: answer {a:?} (conditioning {c:.1e}) not found by the brute force {:?}",
                    setup.family,
                    setup.side,
                    brute.roots.iter().map(|r| &r.x).collect::<Vec<_>>()
                );
            }
        }
    }
    if report.is_empty() {
        Ok(counts)
    } else {
        Err(report)
    }
}

// ------------------------------------------------------------------------------------------
// Queries

/// Only `family` (and only `side` for the envelope).
pub fn only(family: Family) -> FamilyChoice {
    FamilyChoice::Only {
        envelope: family == Family::Envelope,
        direct: family == Family::Direct,
        triples: family == Family::Triples,
    }
}

/// The query at `t` on one side (or both), domain kept or not.
pub fn query(curve: &Curve, t: f64, side: Option<Side>, keep_domain: bool) -> ShapeQuery<'_> {
    ShapeQuery {
        side: match side {
            Some(Side::Left) => SideChoice::Left,
            Some(Side::Right) => SideChoice::Right,
            None => SideChoice::Both,
        },
        keep_domain,
        ..ShapeQuery::new(curve, t)
    }
}

/// A random target: most of the time in a disc of radius `0.15·size` around `s(t)` (where
/// the families reach most), otherwise a random convex combination of the acting control
/// points moved out by up to a fifth of the size (in and around what knots can reach).
pub fn random_target_near(rng: &mut SplitMix64, curve: &Curve, setup: &Setup) -> Point {
    let dims = if curve.dimension().count() == 3 { 3 } else { 2 };
    let offset = |rng: &mut SplitMix64, radius: f64| -> Point {
        let mut v = [0.0; 3];
        for c in v.iter_mut().take(dims) {
            *c = radius * rng.range(-1.0, 1.0);
        }
        v
    };
    let base = if rng.chance(0.6) {
        super::de_boor(curve, curve.knots(), setup.t).unwrap_or([0.0; 3])
    } else {
        let d = curve.control_points();
        let mut w: Vec<f64> = setup.poles.iter().map(|_| rng.unit().powi(2)).collect();
        let total: f64 = w.iter().sum::<f64>().max(1e-12);
        w.iter_mut().for_each(|v| *v /= total);
        let mut p = [0.0; 3];
        for (&i, &wi) in setup.poles.iter().zip(&w) {
            for c in 0..3 {
                p[c] += wi * d[i][c];
            }
        }
        p
    };
    let radius = if rng.chance(0.5) { 0.05 } else { 0.2 } * setup.size * rng.unit();
    let v = offset(rng, radius);
    [base[0] + v[0], base[1] + v[1], base[2] + v[2]]
}

// ------------------------------------------------------------------------------------------
// Planted targets

/// A planted solution of one set: the knots' values and the target the new curve reaches.
#[derive(Debug, Clone)]
pub struct Planted {
    pub unknowns: Vec<usize>,
    pub x: Vec<f64>,
    pub target: Point,
    /// [`SetBox::inside`] of `x`.
    pub inside: f64,
    /// Its conditioning (see [`DETERMINED`]).
    pub conditioning: f64,
}

impl Planted {
    /// Whether the answer must hold it: inside by [`INSIDE`] and determined.
    pub fn required(&self) -> bool {
        self.inside >= INSIDE && self.conditioning >= DETERMINED
    }
}

/// Where a planted knot lies in its interval (unit coordinate): mostly well inside, sometimes
/// `1e-6` from an end (inside by more than [`INSIDE`]: must be found) or exactly on one (a
/// target on the region's edge: need not be found).
pub fn planted_coordinate(rng: &mut SplitMix64, edges: bool) -> f64 {
    match rng.below(if edges { 12 } else { 10 }) {
        0 => 1e-6,
        1 => 1.0 - 1e-6,
        10 => 0.0,
        11 => 1.0,
        _ => rng.range(0.02, 0.98),
    }
}

/// Plants a solution of `unknowns`: values drawn in the box (see [`planted_coordinate`]),
/// the target the new curve reaches at `t` by `common::de_boor`. `None` when the set has no
/// room, or for triples whose span would come within 1e-3 of its room of collapsing.
pub fn plant(
    rng: &mut SplitMix64,
    curve: &Curve,
    setup: &Setup,
    unknowns: &[usize],
    edges: bool,
) -> Option<Planted> {
    let sbox = SetBox::new(setup, unknowns)?;
    let s: Vec<f64> = unknowns
        .iter()
        .map(|_| planted_coordinate(rng, edges))
        .collect();
    let x = sbox.at(&s);
    if unknowns.len() == 3 && sbox.span_fraction(&x).is_some_and(|f| f < 1e-3) {
        return None;
    }
    let knots = setup.knots_with(unknowns, &x);
    admissible(curve, setup, &knots).ok()?;
    let target = super::de_boor(curve, &knots, setup.t)?;
    Some(Planted {
        unknowns: unknowns.to_vec(),
        inside: sbox.inside(&x),
        conditioning: conditioning(&Net::of(curve), setup, &sbox, &x),
        x,
        target,
    })
}

/// Whether the answer holds the planted solution (same family, side and set; each knot
/// within [`match_tolerance`] of its width).
pub fn planted_found(
    curve: &Curve,
    setup: &Setup,
    planted: &Planted,
    solutions: &[KnotSolution],
) -> bool {
    let Some(sbox) = SetBox::new(setup, &planted.unknowns) else {
        return false;
    };
    answers_of(solutions, setup, &planted.unknowns)
        .iter()
        .any(|s| {
            let a: Vec<f64> = planted.unknowns.iter().map(|&g| s.knots[g]).collect();
            let r = relative_residual(curve, setup, s, planted.target);
            same_point(
                &sbox,
                &a,
                &planted.x,
                match_tolerance(planted.conditioning, r, rounding(curve, setup)),
            )
        })
}
