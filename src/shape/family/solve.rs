//! Solving every requested family at a picked parameter (docs/method.md §31): the cubic's
//! envelope pairs Ω1–Ω6 by the closed forms of §4 (unchanged), every other family's pairs and
//! triples by [`super::roots`], and each solution rebuilt as a whole knot vector, checked
//! against the admissibility rules and verified by evaluating the new curve with the spline
//! core.

use super::hull::Triangle;
use super::local::LocalProblem;
use super::problems::{
    Family, FamilyChoice, FamilyProblem, direct_problem, envelope_problem, extent, plane_of,
    unknown_sets,
};
use super::roots::{LocalRoot, Solver, solve_unknowns, solver_for};
use super::tensor::MAX_VARIABLES;
use crate::shape::candidate::Side;
use crate::shape::pairs::KnotPair;
use crate::shape::solve::{
    CandidateOutcome, RESIDUAL_TOLERANCE, ShapeQuery, SolveOptions, affected_domain, solve,
};
use crate::spline::Curve;
use crate::spline::vector::{Point, distance, dot};

/// The knots a pair or triple moves: full-vector indices, ascending.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct KnotSet {
    indices: [usize; MAX_VARIABLES],
    len: usize,
}

impl KnotSet {
    /// The set of `indices` (2 or 3, ascending).
    pub fn new(indices: &[usize]) -> KnotSet {
        let mut set = KnotSet {
            indices: [0; MAX_VARIABLES],
            len: indices.len().min(MAX_VARIABLES),
        };
        set.indices[..set.len].copy_from_slice(&indices[..set.len]);
        set
    }

    /// The indices.
    pub fn indices(&self) -> &[usize] {
        &self.indices[..self.len]
    }
}

/// One way a knot family moves `s(t)` onto the target.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotSolution {
    /// The family.
    pub family: Family,
    /// The envelope's side.
    pub side: Option<Side>,
    /// The span `j` of the family's problem.
    pub span: usize,
    /// The envelope's knot set to `t` (full index).
    pub moved_knot: Option<usize>,
    /// Ω1–Ω6 for a cubic's envelope pairs.
    pub omega: Option<KnotPair>,
    /// The solved knots.
    pub knots_moved: KnotSet,
    /// The new full knot vector.
    pub knots: Vec<f64>,
    /// Full-vector indices whose values changed, ascending.
    pub changed_knots: Vec<usize>,
    /// The new curve's point at `t`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// Outside it the new curve equals the old one.
    pub affected_domain: (f64, f64),
    /// The smallest singular value of `∂P/∂(knots)` with each knot scaled by its room,
    /// relative to the local control points' extent: how well the solution is determined
    /// (small near a fold, or for a knot far from `t`).
    pub conditioning: f64,
}

/// Whether one pair or triple reaches the target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SetMembership {
    /// The knots it moves.
    pub knots: KnotSet,
    /// Ω1–Ω6 for a cubic's envelope pairs.
    pub omega: Option<KnotPair>,
    /// A kept solution exists.
    pub contains: bool,
}

/// One family (one side of the envelope) at the picked parameter, with its pairs or triples.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyGroup {
    /// The family and its local problem.
    pub problem: FamilyProblem,
    /// Why it does not apply, if so (as a sentence).
    pub reason: Option<String>,
    /// One entry per pair or triple tried.
    pub members: Vec<SetMembership>,
}

/// Every family's answer.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FamilyOutcome {
    /// The cubic's envelope candidates in their original form (empty on other degrees).
    pub candidates: Vec<CandidateOutcome>,
    /// One entry per family (and envelope side).
    pub groups: Vec<FamilyGroup>,
    /// Every kept solution.
    pub solutions: Vec<KnotSolution>,
}

/// Subdivision boxes one request may examine over all its pairs and triples (a time bound:
/// a few tens of milliseconds at most).
pub const REQUEST_BOXES: usize = 60_000;

/// The local problems of the requested families at `query.parameter`, in answer order:
/// envelope right, envelope left, direct, triples.
pub fn family_problems(query: &ShapeQuery, choice: FamilyChoice) -> Vec<FamilyProblem> {
    let curve = query.curve;
    let t = query.parameter;
    let mut problems = Vec::new();
    if choice.includes(Family::Envelope, curve) {
        for &side in query.side.sides() {
            problems.push(envelope_problem(curve, t, side, query.keep_domain));
        }
    }
    for family in [Family::Direct, Family::Triples] {
        if choice.includes(family, curve) {
            problems.push(direct_problem(curve, t, family));
        }
    }
    problems
}

/// The directions the equations of a set of `size` unknowns are taken along: the plane's
/// axes for pairs on 3D curves (the target must lie on the pair's surface of reach), the
/// coordinate axes otherwise (on a 2D curve triples meet two equations: their solutions
/// where the knots' change is stationary are taken, docs/method.md §31.4).
fn rows_for(curve: &Curve, problem: &FamilyProblem, size: usize) -> Option<Vec<Point>> {
    let axes = vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    match (curve.dimension().count(), size) {
        (2, _) => Some(axes[..2].to_vec()),
        (3, 3) => Some(axes),
        (3, 2) => plane_of(&problem.control_points()).map(|[e1, e2, _]| vec![e1, e2]),
        _ => None,
    }
}

/// Solves `s(t) → target` with every requested family (module docs).
///
/// The pairs and triples are independent problems: they are collected first, solved (on
/// several threads when there are enough of them, [`solve_sets`]) and put back in answer
/// order, so the answer does not depend on how they were scheduled.
pub fn solve_families(query: &ShapeQuery, choice: FamilyChoice, target: Point) -> FamilyOutcome {
    solve_families_within(query, choice, target, REQUEST_BOXES)
}

/// [`solve_families`] with `boxes` subdivision boxes for the whole request.
fn solve_families_within(
    query: &ShapeQuery,
    choice: FamilyChoice,
    target: Point,
    boxes: usize,
) -> FamilyOutcome {
    let curve = query.curve;
    let mut outcome = FamilyOutcome::default();
    let mut pending: Vec<PendingGroup> = Vec::new();
    let mut jobs: Vec<SetJob> = Vec::new();
    for problem in family_problems(query, choice) {
        if problem.family == Family::Envelope && curve.degree() == 3 {
            cubic_envelope(query, target, problem, &mut outcome);
            continue;
        }
        let mut group = FamilyGroup {
            reason: problem.not_applicable.map(|r| r.to_string()),
            members: Vec::new(),
            problem,
        };
        let Some(local) = group.problem.problem.clone() else {
            outcome.groups.push(group);
            continue;
        };
        if group.reason.is_some() {
            outcome.groups.push(group);
            continue;
        }
        let size = if group.problem.family == Family::Triples {
            3
        } else {
            2
        };
        let Some(rows) = rows_for(curve, &group.problem, size) else {
            group.reason = Some("the control points acting are collinear".to_string());
            outcome.groups.push(group);
            continue;
        };
        let accepted = accepted_residual(&group.problem.control_points(), target);
        let weighted = local.poles.iter().any(|h| h[3] != local.poles[0][3]);
        let triangle = Triangle::of(&local);
        // Beyond the accepted residual (and rounding) from a set's hull, nothing is accepted.
        let margin = accepted * (1.0 + 1e-6) + 1e-12 * extent(&group.problem.control_points());
        let mut sets = Vec::new();
        for unknowns in unknown_sets(&local, size, curve, query.keep_domain) {
            let full: Vec<usize> = unknowns.iter().map(|&m| local.full_index[m]).collect();
            let set = KnotSet::new(&full);
            if triangle.excludes(&unknowns, target, &rows, margin) {
                sets.push((set, None));
                continue;
            }
            sets.push((set, Some(jobs.len())));
            jobs.push(SetJob {
                group: pending.len(),
                unknowns,
                rows: rows.clone(),
                weighted,
                accepted,
            });
        }
        pending.push((group, sets));
    }
    let problems: Vec<&FamilyProblem> = pending.iter().map(|(g, _)| &g.problem).collect();
    let mut found = solve_sets(query, &problems, &jobs, target, boxes);
    for (mut group, sets) in pending {
        for (set, job) in sets {
            let solutions = job
                .map(|j| std::mem::take(&mut found[j]))
                .unwrap_or_default();
            group.members.push(SetMembership {
                knots: set,
                omega: None,
                contains: !solutions.is_empty(),
            });
            outcome.solutions.extend(solutions);
        }
        outcome.groups.push(group);
    }
    outcome
}

/// A group in answer order and its sets, each with the index of the job solving it (none
/// when the set's hull excludes the target).
type PendingGroup = (FamilyGroup, Vec<(KnotSet, Option<usize>)>);

/// One pair or triple to solve: its group's index (whose local problem it is), the unknowns, the
/// directions of its equations and the residual a solution may have.
struct SetJob {
    group: usize,
    unknowns: Vec<usize>,
    rows: Vec<Point>,
    weighted: bool,
    accepted: f64,
}

/// Sets that call for a subdivision at least this many before [`solve_sets`] uses more than
/// one thread: below it waking the pool costs more than it saves (a cubic's direct pairs).
const PARALLEL_SUBDIVISIONS: usize = 12;

/// Every job's kept solutions, in job order.
///
/// The request's box budget (`boxes`, [`REQUEST_BOXES`] in a request) is shared without
/// depending on the order
/// the jobs run in: each first gets an equal share (at most its own cap); a job that used its
/// whole share (it may have needed more) is solved again afterwards, one after the other in
/// job order, with what is left of the budget. When no job needs more than its share, which
/// is the rule, every job gets the boxes it would get alone.
///
/// Jobs run on the rayon pool when at least [`PARALLEL_SUBDIVISIONS`] of them subdivide (and
/// [`crate::parallel::allowed`]);
/// the answer is the same either way.
fn solve_sets(
    query: &ShapeQuery,
    problems: &[&FamilyProblem],
    jobs: &[SetJob],
    target: Point,
    boxes: usize,
) -> Vec<Vec<KnotSolution>> {
    use rayon::prelude::*;
    let share = boxes / jobs.len().max(1);
    // Jobs are made only for groups with a local problem.
    let local = |job: &SetJob| problems[job.group].problem.as_ref();
    let run = |job: &SetJob, budget: &mut usize| -> Vec<KnotSolution> {
        let Some(local) = local(job) else {
            return Vec::new();
        };
        solve_unknowns(
            local,
            &job.unknowns,
            target,
            &job.rows,
            job.weighted,
            budget,
        )
        .iter()
        .filter_map(|root| {
            full_solution(
                query,
                problems[job.group],
                local,
                &job.unknowns,
                root,
                target,
                job.accepted,
            )
        })
        .collect()
    };
    let first = |job: &SetJob| {
        let mut budget = share;
        let solutions = run(job, &mut budget);
        (solutions, share - budget, budget == 0)
    };
    let subdivisions = jobs
        .iter()
        .filter(|job| {
            local(job).is_some_and(|l| solver_for(l, &job.unknowns) == Solver::Subdivision)
        })
        .count();
    let results: Vec<(Vec<KnotSolution>, usize, bool)> =
        if subdivisions >= PARALLEL_SUBDIVISIONS && crate::parallel::allowed() {
            jobs.par_iter().map(first).collect()
        } else {
            jobs.iter().map(first).collect()
        };
    // The boxes of the jobs solved again are not counted twice.
    let kept: usize = results.iter().filter(|r| !r.2).map(|r| r.1).sum();
    let mut left = boxes.saturating_sub(kept);
    results
        .into_iter()
        .zip(jobs)
        .map(|((solutions, _, spent), job)| {
            if spent && left > 0 {
                run(job, &mut left)
            } else {
                solutions
            }
        })
        .collect()
}

/// The cubic's envelope side by the closed forms of §4 (the third release's solver, whose
/// answers stay as they were), converted to the families' form.
fn cubic_envelope(
    query: &ShapeQuery,
    target: Point,
    problem: FamilyProblem,
    outcome: &mut FamilyOutcome,
) {
    let Some(side) = problem.side else { return };
    let side_query = ShapeQuery {
        side: match side {
            Side::Right => crate::shape::SideChoice::Right,
            Side::Left => crate::shape::SideChoice::Left,
        },
        ..*query
    };
    let dimension = query.curve.dimension().count();
    let options = SolveOptions {
        measure_deviation: false,
    };
    let Ok(found) = solve(&side_query, &target[..dimension], options) else {
        return;
    };
    let mut group = FamilyGroup {
        reason: None,
        members: Vec::new(),
        problem,
    };
    for candidate in found.candidates {
        group.reason = candidate
            .candidate
            .not_applicable
            .map(|reason| reason.to_string());
        group.members = candidate
            .regions
            .iter()
            .map(|region| SetMembership {
                knots: KnotSet::new(&region.knots),
                omega: Some(region.pair),
                contains: region.contains,
            })
            .collect();
        outcome.candidates.push(candidate);
    }
    for solution in found.solutions {
        let [first, second] = solution.pair.unknowns();
        let indices = [
            first.full_index(solution.span),
            second.full_index(solution.span),
        ];
        let conditioning = group.problem.problem.as_ref().map_or(0.0, |local| {
            let local_knots: Vec<f64> = local
                .full_index
                .iter()
                .map(|&i| solution.knots[i])
                .collect();
            let unknowns: Vec<usize> = indices
                .iter()
                .filter_map(|&i| local.full_index.iter().position(|&f| f == i))
                .collect();
            conditioning(local, &local_knots, &unknowns)
        });
        outcome.solutions.push(KnotSolution {
            family: Family::Envelope,
            side: Some(solution.side),
            span: solution.span,
            moved_knot: Some(solution.moved_knot),
            omega: Some(solution.pair),
            knots_moved: KnotSet::new(&indices),
            knots: solution.knots,
            changed_knots: solution.changed_knots,
            point: solution.point,
            residual: solution.residual,
            affected_domain: solution.affected_domain,
            conditioning,
        });
    }
    outcome.groups.push(group);
}

/// The residual a solution may have: [`RESIDUAL_TOLERANCE`] times the local control points'
/// extent, plus the rounding floor `64 ε |target|`.
fn accepted_residual(control_points: &[Point], target: Point) -> f64 {
    let magnitude = target.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    RESIDUAL_TOLERANCE * extent(control_points) + 64.0 * f64::EPSILON * magnitude
}

/// The whole solution of a local root, or `None` when a rule drops it (docs/method.md §31.2):
/// the new knot vector is not monotone or not finite, its domain is empty or (under
/// `keep_domain`) moved, a knot value's multiplicity grows past `p`, or the new curve,
/// evaluated by the spline core at `t`, misses the target by more than `accepted`.
pub(crate) fn full_solution(
    query: &ShapeQuery,
    problem: &FamilyProblem,
    local: &LocalProblem,
    unknowns: &[usize],
    root: &LocalRoot,
    target: Point,
    accepted: f64,
) -> Option<KnotSolution> {
    let curve = query.curve;
    let t = query.parameter;
    let old = curve.knots();
    let mut knots = old.to_vec();
    if let Some(i) = problem.moved_knot {
        knots[i] = t;
    }
    for &m in unknowns {
        knots[local.full_index[m]] = root.knots[m];
    }
    if !knots_admissible(curve, &knots, query.keep_domain) {
        return None;
    }
    let point = curve.point_with_knots(&knots, t);
    let residual = distance(point, target);
    if residual.is_nan() || residual > accepted {
        return None;
    }
    let changed_knots: Vec<usize> = (0..old.len()).filter(|&i| knots[i] != old[i]).collect();
    let affected = affected_domain(curve, &knots, &changed_knots);
    let full: Vec<usize> = unknowns.iter().map(|&m| local.full_index[m]).collect();
    Some(KnotSolution {
        family: problem.family,
        side: problem.side,
        span: problem.span,
        moved_knot: problem.moved_knot,
        omega: None,
        knots_moved: KnotSet::new(&full),
        conditioning: conditioning(local, &root.knots, unknowns),
        knots,
        changed_knots,
        point,
        residual,
        affected_domain: affected,
    })
}

/// Whether a new full knot vector keeps the rules of docs/method.md §31.2: finite and
/// non-decreasing, a non-empty domain, no knot value repeated more than `p` times inside the
/// domain (more than it already was), and, under `keep_domain`, the domain's ends in place
/// without a knot moved onto them.
pub fn knots_admissible(curve: &Curve, knots: &[f64], keep_domain: bool) -> bool {
    let old = curve.knots();
    let p = curve.degree();
    let n = curve.control_points().len() - 1;
    if knots.iter().any(|u| !u.is_finite()) || knots.windows(2).any(|w| w[0] > w[1]) {
        return false;
    }
    if knots[p] >= knots[n + 1] {
        return false;
    }
    let count = |vector: &[f64], value: f64| vector.iter().filter(|&&u| u == value).count();
    if keep_domain
        && [p, n + 1]
            .into_iter()
            .any(|i| knots[i] != old[i] || count(knots, knots[i]) > count(old, old[i]).max(p + 1))
    {
        return false;
    }
    let (lo, hi) = (knots[p], knots[n + 1]);
    let mut start = 0;
    while start < knots.len() {
        let value = knots[start];
        let mut end = start;
        while end < knots.len() && knots[end] == value {
            end += 1;
        }
        if value > lo && value < hi && end - start > p.max(count(old, value)) {
            return false;
        }
        start = end;
    }
    true
}

/// [`KnotSolution::conditioning`] of the local knots `knots` with `unknowns` solved: the
/// smallest singular value of `J · diag(room)`, over the extent of the local poles (the plane
/// part of `J` for pairs on a 3D curve).
fn conditioning(local: &LocalProblem, knots: &[f64], unknowns: &[usize]) -> f64 {
    if unknowns.is_empty() {
        return 0.0;
    }
    let (_, partials) = local.point_and_partials(knots, unknowns);
    let q = local.degree;
    let room = |m: usize| {
        let below = (0..m).rev().find(|i| !unknowns.contains(i)).unwrap_or(0);
        let above = (m + 1..=2 * q + 1)
            .find(|i| !unknowns.contains(i))
            .unwrap_or(2 * q + 1);
        local.knots[above] - local.knots[below]
    };
    let columns: Vec<Point> = unknowns
        .iter()
        .enumerate()
        .map(|(k, &m)| partials[k].map(|v| v * room(m)))
        .collect();
    let poles: Vec<Point> = local
        .poles
        .iter()
        .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
        .collect();
    let size = extent(&poles);
    smallest_singular_value(&columns) / size
}

/// The smallest singular value of the 3 × k matrix with columns `columns` (k = 2 or 3): the
/// square root of the Gram matrix's smallest eigenvalue.
pub(crate) fn smallest_singular_value(columns: &[Point]) -> f64 {
    let k = columns.len();
    let gram = |a: usize, b: usize| dot(columns[a], columns[b]);
    let eigenvalue = if k == 2 {
        let (a, b, c) = (gram(0, 0), gram(0, 1), gram(1, 1));
        let mean = 0.5 * (a + c);
        let radius = (0.25 * (a - c) * (a - c) + b * b).sqrt();
        // The smaller root, computed as det / larger to keep its accuracy.
        let larger = mean + radius;
        if larger > 0.0 {
            (a * c - b * b) / larger
        } else {
            0.0
        }
    } else {
        // Symmetric 3 × 3: the trigonometric formula for the smallest eigenvalue.
        let m = [
            [gram(0, 0), gram(0, 1), gram(0, 2)],
            [gram(1, 0), gram(1, 1), gram(1, 2)],
            [gram(2, 0), gram(2, 1), gram(2, 2)],
        ];
        let trace = m[0][0] + m[1][1] + m[2][2];
        let mean = trace / 3.0;
        let off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        let spread = ((m[0][0] - mean).powi(2)
            + (m[1][1] - mean).powi(2)
            + (m[2][2] - mean).powi(2)
            + 2.0 * off)
            / 6.0;
        let s = spread.sqrt();
        if s == 0.0 {
            mean
        } else {
            let b = |i: usize, j: usize| (m[i][j] - if i == j { mean } else { 0.0 }) / s;
            let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1))
                - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
                + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
            let phi = (0.5 * det).clamp(-1.0, 1.0).acos() / 3.0;
            mean + 2.0 * s * (phi + 2.0 * std::f64::consts::PI / 3.0).cos()
        }
    };
    eigenvalue.max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    /// The worked quintic of the fourth release's study (tests/knot_families.rs).
    fn quintic() -> Curve {
        let points: Vec<[f64; 2]> = [
            [0.0, 0.0],
            [1.0, 1.5],
            [2.0, 2.5],
            [3.2, 3.0],
            [4.5, 2.8],
            [5.5, 1.8],
            [6.3, 0.6],
            [7.5, 0.2],
            [8.8, 0.9],
            [9.8, 2.2],
            [11.0, 3.0],
            [12.2, 2.6],
            [13.0, 1.2],
            [14.0, 0.0],
            [15.0, 0.5],
            [16.0, 2.0],
        ]
        .to_vec();
        let mut knots = vec![0.0; 6];
        knots.extend((0..10).map(|i| ((0.08 + 0.84 * i as f64 / 9.0) * 1e4).round() / 1e4));
        knots.extend([1.0; 6]);
        Curve::new(5, &points, &knots, None, &CurveLimits::default()).unwrap()
    }

    /// Budgets too small for the sets' shares make sets solve again with what is left, in
    /// order: the answer is still the same on one thread and on two, and every solution it
    /// keeps is one the full budget finds.
    #[test]
    fn a_short_budget_gives_the_same_answer_on_any_threads() {
        let curve = quintic();
        let query = ShapeQuery::new(&curve, 0.5);
        let p = curve.point(0.5).unwrap();
        let target = [p[0] + 0.1, p[1] + 0.05, 0.0];
        let on = |threads: usize, boxes: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| solve_families_within(&query, FamilyChoice::Default, target, boxes))
        };
        let full = on(2, REQUEST_BOXES);
        assert!(full.solutions.len() >= 20, "{}", full.solutions.len());
        let mut fewer_somewhere = false;
        for boxes in [0, 40, 400, 1000] {
            let (one, two) = (on(1, boxes), on(2, boxes));
            assert_eq!(one, two, "{boxes} boxes");
            fewer_somewhere |= one.solutions.len() < full.solutions.len();
            for solution in &one.solutions {
                let matched = full.solutions.iter().any(|s| {
                    s.knots_moved == solution.knots_moved
                        && s.knots
                            .iter()
                            .zip(&solution.knots)
                            .all(|(a, b)| (a - b).abs() <= 1e-9)
                });
                assert!(
                    matched,
                    "{boxes} boxes: {solution:?} not in the full answer"
                );
            }
        }
        assert!(fewer_somewhere, "a short budget loses some solution");
    }
}
