//! The nearest reachable point across the knot families (docs/method.md §33): when no pair
//! or triple reaches a target, the point of their reachable sets closest to it, so that a
//! drag can follow the cursor outside the regions (and a 3D target off every pair's surface
//! lands on the nearest point a family reaches).
//!
//! Each pair (or triple) is searched over its admissible knots: a coarse lattice of its
//! domain ([`PairDomain`] for pairs, the solver's box for triples) picks the best starting
//! points, and projected Gauss–Newton on `|P - target|²` (finite-difference Jacobian, steps
//! kept in the domain) refines them. The span's collapse (`r = 0` of the span pair) is kept
//! [`COLLAPSE_MARGIN`] away, where the span is still not empty. The point claimed is the new
//! curve's, evaluated by the spline core, and every family's solutions there are returned.
//! This is a search for drawing, not a certificate: it samples, so a region thinner than the
//! lattice's cells can be missed.

use super::domain::{PairDomain, point_at};
use super::local::LocalProblem;
use super::problems::{Family, FamilyChoice, unknown_sets};
use super::roots::LocalRoot;
use super::solve::{FamilyOutcome, KnotSolution, family_problems, full_solution, solve_families};
use super::tensor::MAX_VARIABLES;
use crate::shape::solve::ShapeQuery;
use crate::spline::vector::{Point, distance, dot, sub};

/// Lattice points per side of a pair's domain.
const PAIR_LATTICE: usize = 9;

/// Lattice points per side of a triple's box.
const TRIPLE_LATTICE: usize = 5;

/// Gauss–Newton steps per start.
const STEPS: usize = 25;

/// Starts refined per pair or triple.
const STARTS: usize = 2;

/// The span's collapse is kept this far away (in the domain's unit coordinates).
pub const COLLAPSE_MARGIN: f64 = 1e-6;

/// The nearest reachable point and the solutions that reach it.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyNearest {
    /// The point (the first solution's new curve at `t`).
    pub point: Point,
    /// Every family's solutions at `point` (residuals from it).
    pub solutions: Vec<KnotSolution>,
}

/// A candidate: distance, group index, unknowns, local knots.
struct Candidate {
    distance: f64,
    group: usize,
    unknowns: Vec<usize>,
    knots: Vec<f64>,
}

/// The nearest point the requested families reach (module docs), `None` when none reaches
/// anything. The cubic's envelope pairs are searched by [`crate::shape::nearest_reachable`]
/// instead (the caller compares).
pub fn nearest_across_families(
    query: &ShapeQuery,
    choice: FamilyChoice,
    target: Point,
) -> Option<FamilyNearest> {
    let mut solution = nearest_solution_across_families(query, choice, target)?;
    let reached = solution.point;
    solution.residual = 0.0;
    // Every family's solutions at the point reached (on the edge of the reach, usually: the
    // most expensive place for the solver, near a fold).
    let FamilyOutcome { solutions, .. } = solve_families(query, choice, reached);
    let mut all = vec![solution];
    for other in solutions {
        if !all.iter().any(|s| s.knots == other.knots) {
            all.push(other);
        }
    }
    for s in &mut all {
        s.residual = distance(s.point, reached);
    }
    Some(FamilyNearest {
        point: reached,
        solutions: all,
    })
}

/// The nearest point the requested families reach and the one solution found reaching it
/// (its `point`), without the other families' solutions there that
/// [`nearest_across_families`] adds: for a caller that wants the point only (the surfaces'
/// nearest point over both iso-curves).
pub fn nearest_solution_across_families(
    query: &ShapeQuery,
    choice: FamilyChoice,
    target: Point,
) -> Option<KnotSolution> {
    let curve = query.curve;
    let problems = family_problems(query, choice);
    let mut candidates: Vec<Candidate> = Vec::new();
    for (group, problem) in problems.iter().enumerate() {
        if problem.not_applicable.is_some()
            || (problem.family == Family::Envelope && curve.degree() == 3)
        {
            continue;
        }
        let Some(local) = &problem.problem else {
            continue;
        };
        let size = if problem.family == Family::Triples {
            3
        } else {
            2
        };
        if size == 3 && curve.dimension().count() != 3 {
            continue;
        }
        for unknowns in unknown_sets(local, size, curve, query.keep_domain) {
            let found = if size == 2 {
                nearest_on_pair(local, &unknowns, target)
            } else {
                nearest_on_triple(local, &unknowns, target)
            };
            for (distance, knots) in found {
                candidates.push(Candidate {
                    distance,
                    group,
                    unknowns: unknowns.clone(),
                    knots,
                });
            }
        }
    }
    candidates.sort_by(|a, b| a.distance.total_cmp(&b.distance));
    for candidate in candidates {
        let problem = &problems[candidate.group];
        let Some(local) = &problem.problem else {
            continue;
        };
        let point = local.point(&candidate.knots);
        let root = LocalRoot {
            knots: candidate.knots,
            certified: false,
        };
        let accepted = 1e-9 * super::problems::extent(&problem.control_points()) + 1e-12;
        if let Some(solution) = full_solution(
            query,
            problem,
            local,
            &candidate.unknowns,
            &root,
            point,
            accepted,
        ) {
            return Some(solution);
        }
    }
    None
}

/// Projected Gauss–Newton on `|P(x) - target|²` over the unit box in `n` variables, from
/// `start`; `map` gives the point of unit-box coordinates (`None` outside the admissible set).
fn descend(
    n: usize,
    start: [f64; MAX_VARIABLES],
    lower: [f64; MAX_VARIABLES],
    map: &impl Fn([f64; MAX_VARIABLES]) -> Option<Point>,
    target: Point,
) -> Option<(f64, [f64; MAX_VARIABLES])> {
    let mut x = start;
    let mut value = map(x)?;
    let mut best = distance(value, target);
    for _ in 0..STEPS {
        // Finite-difference Jacobian (3 × n), one-sided inward at the box's faces.
        let mut columns = [[0.0; 3]; MAX_VARIABLES];
        for k in 0..n {
            let h = 1e-6;
            let mut y = x;
            let forward = x[k] + h <= 1.0;
            y[k] = if forward { x[k] + h } else { x[k] - h };
            let p = map(y)?;
            let sign = if forward { 1.0 } else { -1.0 };
            columns[k] = [0, 1, 2].map(|c| sign * (p[c] - value[c]) / h);
        }
        // Normal equations (JᵀJ) δ = Jᵀ r, with a small damping.
        let r = sub(target, value);
        let mut a = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
        let mut b = [0.0; MAX_VARIABLES];
        for i in 0..n {
            for k in 0..n {
                a[i][k] = dot(columns[i], columns[k]);
            }
            a[i][i] *= 1.0 + 1e-9;
            a[i][i] += 1e-300;
            b[i] = dot(columns[i], r);
        }
        let Some(inverse) = super::isolate::invert(&a, n) else {
            break;
        };
        let mut step = [0.0; MAX_VARIABLES];
        for i in 0..n {
            step[i] = (0..n).map(|k| inverse[i][k] * b[k]).sum();
        }
        // Halve the step until it improves (and stays admissible).
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..12 {
            let mut y = x;
            for k in 0..n {
                y[k] = (x[k] + scale * step[k]).clamp(lower[k], 1.0);
            }
            if let Some(p) = map(y) {
                let d = distance(p, target);
                if d < best {
                    x = y;
                    value = p;
                    best = d;
                    improved = true;
                    break;
                }
            }
            scale *= 0.5;
        }
        if !improved {
            break;
        }
    }
    Some((best, x))
}

/// The best points of pair `unknowns`: `(distance, local knots)` for up to [`STARTS`] starts.
fn nearest_on_pair(
    local: &LocalProblem,
    unknowns: &[usize],
    target: Point,
) -> Vec<(f64, Vec<f64>)> {
    let pair = [unknowns[0], unknowns[1]];
    let Some(domain) = PairDomain::new(local, pair) else {
        return Vec::new();
    };
    let span = matches!(domain, PairDomain::Span { .. });
    let lower = [if span { COLLAPSE_MARGIN } else { 0.0 }, 0.0, 0.0];
    let map = |x: [f64; MAX_VARIABLES]| Some(point_at(local, pair, &domain, (x[0], x[1])));
    let mut starts: Vec<(f64, [f64; MAX_VARIABLES])> = Vec::new();
    for i in 0..PAIR_LATTICE {
        for j in 0..PAIR_LATTICE {
            let x = [
                (i as f64 / (PAIR_LATTICE - 1) as f64).max(lower[0]),
                j as f64 / (PAIR_LATTICE - 1) as f64,
                0.0,
            ];
            if let Some(p) = map(x) {
                starts.push((distance(p, target), x));
            }
        }
    }
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    starts
        .into_iter()
        .take(STARTS)
        .filter_map(|(_, x)| descend(2, x, lower, &map, target))
        .map(|(d, x)| {
            let (values, _) = domain.knots_at(local.parameter, (x[0], x[1]));
            let mut knots = local.knots.clone();
            knots[pair[0]] = values[0];
            knots[pair[1]] = values[1];
            (d, knots)
        })
        .collect()
}

/// The best points of triple `unknowns` (its solver box, unordered knots skipped).
fn nearest_on_triple(
    local: &LocalProblem,
    unknowns: &[usize],
    target: Point,
) -> Vec<(f64, Vec<f64>)> {
    let Some(search) = local.search_box(unknowns, 0.0, COLLAPSE_MARGIN) else {
        return Vec::new();
    };
    let ordered = |knots: &[f64]| knots.windows(2).all(|w| w[0] <= w[1]);
    let map = |x: [f64; MAX_VARIABLES]| {
        let knots = local.knots_at(&search, x);
        ordered(&knots).then(|| local.point(&knots))
    };
    let mut starts: Vec<(f64, [f64; MAX_VARIABLES])> = Vec::new();
    let node = |i: usize| i as f64 / (TRIPLE_LATTICE - 1) as f64;
    for i in 0..TRIPLE_LATTICE {
        for j in 0..TRIPLE_LATTICE {
            for k in 0..TRIPLE_LATTICE {
                let x = [node(i), node(j), node(k)];
                if let Some(p) = map(x) {
                    starts.push((distance(p, target), x));
                }
            }
        }
    }
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    starts
        .into_iter()
        .take(STARTS)
        .filter_map(|(_, x)| descend(3, x, [0.0; MAX_VARIABLES], &map, target))
        .map(|(d, x)| (d, local.knots_at(&search, x)))
        .collect()
}
