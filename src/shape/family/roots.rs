//! Every admissible solution of one set of unknown knots (docs/method.md §31.4): closed forms
//! where they exist (`q = 2`: the paper's six; the outermost pair of any degree: a 2 × 2
//! linear system), certified subdivision ([`super::isolate`]) for the rest, each root then
//! polished by Newton's method on de Boor itself and checked against the admissible box.
//!
//! One file (about 680 lines) over 600 on purpose: the solvers of one unknown set are chosen
//! by [`solver_for`] and share the search box, the polish and the admissibility check; split
//! by solver, each part would only call back into the others.

use super::isolate::{IsolationOptions, ZERO_MARGIN, invert, isolate};
use super::local::{LocalProblem, SearchBox};
use super::tensor::{MAX_VARIABLES, Tensor};
use crate::shape::candidate::{Frame, triangle_frame};
use crate::shape::pairs::{CLAMP_TOLERANCE, KNOT_TOLERANCE, KnotPair, LocalKnots, solve_pair};
use crate::spline::vector::{Point, dot, sub};

/// The search box is widened by this fraction of each unknown's interval, so that roots on
/// a bound (a knot moved onto its neighbour) lie inside it.
pub const SEARCH_MARGIN: f64 = 1e-9;

/// Triples keep the span at least this fraction of its room away from collapsing onto `t`
/// (where three unknowns meeting at `t` would make the system vanish on a line).
pub const TRIPLE_COLLAPSE: f64 = 1e-4;

/// Boxes the subdivision of one pair may examine at most.
pub const PAIR_BOXES: usize = 4096;

/// Boxes the subdivision of one triple may examine at most.
pub const TRIPLE_BOXES: usize = 8192;

/// Newton steps at most when polishing a root on de Boor.
const POLISH_STEPS: usize = 8;

/// Newton steps at most when refining a root of a pair's univariate equation.
const UNIVARIATE_STEPS: usize = 40;

/// A solution of one unknown set: the whole local knot vector.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalRoot {
    /// `t_0 ..= t_{2q+1}` with the unknowns solved.
    pub knots: Vec<f64>,
    /// Found by a closed form or certified by Krawczyk's test.
    pub certified: bool,
}

/// How one unknown set was solved (for tests and benchmarks).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solver {
    /// The paper's closed forms (`q = 2`).
    Quadratic,
    /// The outermost pair's linear system.
    Outermost,
    /// A pair with one outermost knot: one polynomial equation in the other knot.
    OneOutermost,
    /// Certified subdivision.
    Subdivision,
}

/// The solver that `unknowns` of `problem` get.
pub fn solver_for(problem: &LocalProblem, unknowns: &[usize]) -> Solver {
    let q = problem.degree;
    if unknowns.len() == 2 && q == 2 {
        Solver::Quadratic
    } else if unknowns.len() == 2 && unknowns == [1, 2 * q] {
        Solver::Outermost
    } else if unknowns.len() == 2 && (unknowns[0] == 1 || unknowns[1] == 2 * q) {
        Solver::OneOutermost
    } else {
        Solver::Subdivision
    }
}

/// Every admissible local knot vector with `rows · (P - target) = 0`, `rows` one direction
/// per unknown (the plane's axes for pairs, the three axes for triples). `weighted` tells
/// whether the poles' weights differ (the `q = 2` frame then weighs the barycentric
/// coordinates).
///
/// `budget` is the number of subdivision boxes the whole request may still examine; this
/// set takes what it uses from it.
pub fn solve_unknowns(
    problem: &LocalProblem,
    unknowns: &[usize],
    target: Point,
    rows: &[Point],
    weighted: bool,
    budget: &mut usize,
) -> Vec<LocalRoot> {
    let collapse = if unknowns.len() == 3 {
        TRIPLE_COLLAPSE
    } else {
        0.0
    };
    let Some(search) = problem.search_box(unknowns, SEARCH_MARGIN, collapse) else {
        return Vec::new();
    };
    if search.admissible.iter().any(|(lo, hi)| hi <= lo) {
        // A knot without room: the set is really a smaller one.
        return Vec::new();
    }
    let raw: Vec<(Vec<f64>, bool)> = match solver_for(problem, unknowns) {
        Solver::Quadratic => quadratic(problem, unknowns, target, weighted)
            .into_iter()
            .map(|k| (k, true))
            .collect(),
        Solver::Outermost => outermost(problem, target, rows)
            .into_iter()
            .map(|k| (k, true))
            .collect(),
        Solver::OneOutermost => match one_outermost(problem, unknowns, target, rows, budget) {
            Some(found) => found
                .into_iter()
                .map(|(mut knots, certified)| {
                    polish(problem, &search, &mut knots, target, rows);
                    (knots, certified)
                })
                .collect(),
            None => subdivision(problem, &search, target, rows, budget),
        },
        Solver::Subdivision if unknowns.len() == 3 && rows.len() == 2 => {
            stationary_triples(problem, &search, target, rows, budget)
        }
        Solver::Subdivision => subdivision(problem, &search, target, rows, budget),
    };
    let mut roots: Vec<LocalRoot> = Vec::new();
    for (knots, certified) in raw {
        let Some(knots) = admissible(problem, &search, knots) else {
            continue;
        };
        let scale = problem.knots[2 * problem.degree + 1] - problem.knots[0];
        let duplicate = roots.iter().any(|r| {
            r.knots
                .iter()
                .zip(&knots)
                .all(|(a, b)| (a - b).abs() <= CLAMP_TOLERANCE * scale)
        });
        if !duplicate {
            roots.push(LocalRoot { knots, certified });
        }
    }
    roots
}

/// Every root of the unknowns of `search` by certified subdivision ([`isolate`]), polished
/// on de Boor.
fn subdivision(
    problem: &LocalProblem,
    search: &SearchBox,
    target: Point,
    rows: &[Point],
    budget: &mut usize,
) -> Vec<(Vec<f64>, bool)> {
    let count = search.unknowns.len();
    let system = problem.system(search, target, rows);
    let cap = if count == 3 { TRIPLE_BOXES } else { PAIR_BOXES };
    let options = IsolationOptions {
        max_boxes: cap.min(*budget),
        ..IsolationOptions::default()
    };
    let outside = |lo: [f64; MAX_VARIABLES], width: [f64; MAX_VARIABLES]| {
        disordered(problem, search, lo, width)
    };
    let isolation = isolate(&system, count, options, &outside);
    *budget = budget.saturating_sub(isolation.boxes);
    isolation
        .roots
        .into_iter()
        .map(|root| {
            let mut knots = problem.knots_at(search, root.point);
            polish(problem, search, &mut knots, target, rows);
            (knots, root.certified)
        })
        .collect()
}

/// Three knots for a 2D target (docs/method.md §31.4): two equations leave a curve of
/// solutions; returned are its points where the change of the knots is stationary,
/// measured in the solver's unit box (`|s - s⁰|²`, `s⁰` the current knots): `F = 0` and
/// `det(s - s⁰, ∇F₁, ∇F₂) = 0` (the change is normal to the curve of solutions), a square
/// polynomial system solved by the same certified subdivision.
fn stationary_triples(
    problem: &LocalProblem,
    search: &SearchBox,
    target: Point,
    rows: &[Point],
    budget: &mut usize,
) -> Vec<(Vec<f64>, bool)> {
    let system = problem.system(search, target, rows);
    let current = unit_coordinates(problem, search);
    let scalar = |t: &Tensor, i: usize| {
        t.combine(&[
            if i == 0 { 1.0 } else { 0.0 },
            if i == 1 { 1.0 } else { 0.0 },
        ])
    };
    let gradients: Vec<[Tensor; 2]> = (0..3)
        .map(|k| {
            let d = system.derivative(k);
            [scalar(&d, 0).scaled(), scalar(&d, 1).scaled()]
        })
        .collect();
    let minus = Tensor::constant(&[-1.0]);
    let cofactor = |i: usize, j: usize| {
        gradients[i][0]
            .times(&gradients[j][1])
            .plus(&gradients[j][0].times(&gradients[i][1]).times(&minus))
    };
    let displacement = |k: usize| {
        let mut mask = [false; MAX_VARIABLES];
        mask[k] = true;
        let start = current[k];
        Tensor::multi_affine(mask, move |s| s[k] - start)
    };
    let stationary = displacement(0)
        .times(&cofactor(1, 2))
        .plus(&displacement(1).times(&cofactor(2, 0)))
        .plus(&displacement(2).times(&cofactor(0, 1)));
    let degrees = [0, 1, 2].map(|k| stationary.degrees[k].max(system.degrees[k]));
    let parts = [
        scalar(&system, 0).scaled().raised_to(degrees).unscaled(),
        scalar(&system, 1).scaled().raised_to(degrees).unscaled(),
        stationary.raised_to(degrees).unscaled(),
    ];
    let combined = Tensor::stack(&parts);
    let options = IsolationOptions {
        max_boxes: TRIPLE_BOXES.min(*budget),
        ..IsolationOptions::default()
    };
    let outside = |lo: [f64; MAX_VARIABLES], width: [f64; MAX_VARIABLES]| {
        disordered(problem, search, lo, width)
    };
    let isolation = isolate(&combined, 3, options, &outside);
    *budget = budget.saturating_sub(isolation.boxes);
    isolation
        .roots
        .into_iter()
        .map(|root| {
            let mut knots = problem.knots_at(search, root.point);
            polish_underdetermined(problem, search, &mut knots, target, rows);
            (knots, root.certified)
        })
        .collect()
}

/// The current knots of `search`'s unknowns in its unit box.
fn unit_coordinates(problem: &LocalProblem, search: &SearchBox) -> [f64; MAX_VARIABLES] {
    let mut s = [0.0; MAX_VARIABLES];
    let unit = |k: usize, value: f64| {
        let (lo, hi) = search.bounds[k];
        if hi > lo {
            (value - lo) / (hi - lo)
        } else {
            0.0
        }
    };
    for (k, &m) in search.unknowns.iter().enumerate() {
        s[k] = unit(k, problem.knots[m]);
    }
    if let Some((a, b)) = search.blow_up {
        let (ta, tb) = (
            problem.knots[search.unknowns[a]],
            problem.knots[search.unknowns[b]],
        );
        let sigma = tb - ta;
        s[a] = unit(a, sigma);
        s[b] = unit(
            b,
            if sigma > 0.0 {
                (problem.parameter - ta) / sigma
            } else {
                0.5
            },
        );
    }
    s
}

/// Newton's method with the least-norm step (`Δ = -Jᵀ (J Jᵀ)⁻¹ r`) for two equations in three
/// knots: it lands on the curve of solutions next to the start.
fn polish_underdetermined(
    problem: &LocalProblem,
    search: &SearchBox,
    knots: &mut [f64],
    target: Point,
    rows: &[Point],
) {
    let unknowns = &search.unknowns;
    for _ in 0..POLISH_STEPS {
        let (point, partials) = problem.point_and_partials(knots, unknowns);
        let d = sub(point, target);
        let r = [dot(rows[0], d), dot(rows[1], d)];
        if r[0] == 0.0 && r[1] == 0.0 {
            break;
        }
        let j: Vec<[f64; 3]> = (0..2)
            .map(|i| [0, 1, 2].map(|k| dot(rows[i], partials[k])))
            .collect();
        let mut gram = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
        for i in 0..2 {
            for l in 0..2 {
                gram[i][l] = (0..3).map(|k| j[i][k] * j[l][k]).sum();
            }
        }
        let Some(inverse) = invert(&gram, 2) else {
            break;
        };
        let y = [0, 1].map(|i| inverse[i][0] * r[0] + inverse[i][1] * r[1]);
        let mut trial = knots.to_vec();
        for (k, &m) in unknowns.iter().enumerate() {
            let (lo, hi) = search.admissible[k];
            let widen = SEARCH_MARGIN * (hi - lo);
            trial[m] = (knots[m] - (j[0][k] * y[0] + j[1][k] * y[1]))
                .max(lo - widen)
                .min(hi + widen);
        }
        let next = sub(problem.point(&trial), target);
        let next_r = [dot(rows[0], next), dot(rows[1], next)];
        let (after, before) = (next_r[0].hypot(next_r[1]), r[0].hypot(r[1]));
        if after.is_nan() || after >= before {
            break;
        }
        knots.copy_from_slice(&trial);
    }
}

/// A pair with one outermost knot (docs/method.md §31.4): that knot enters one ratio only,
/// `α_A = α_{1,1}` for `t_1` (`α_{q,1}` for `t_{2q}`), and the homogeneous point is affine in
/// it, `H = H_0(b) + α_A (H_1(b) - H_0(b))` with `b` the other knot. The equations
/// `F_0(b) + α_A G(b) = 0` (`G = F_1 - F_0`, both projected) hold exactly when
/// `g(b) = F_0 × G = 0` (a univariate polynomial, isolated with certification) and
/// `α_A = -F_0 · G / |G|²`; then `t_1 = (ũ - α_A t_{q+1}) / (1 - α_A)` (or
/// `t_{2q} = t_q + (ũ - t_q) / α_B`). `None` when the other knot's degree is too high for
/// this construction (the caller subdivides in two variables).
fn one_outermost(
    problem: &LocalProblem,
    unknowns: &[usize],
    target: Point,
    rows: &[Point],
    budget: &mut usize,
) -> Option<Vec<(Vec<f64>, bool)>> {
    let q = problem.degree;
    let u = problem.parameter;
    let (outer, other, ratio) = if unknowns[0] == 1 {
        (1, unknowns[1], (1, 1))
    } else {
        (2 * q, unknowns[0], (q, 1))
    };
    // The other knot ranges over its interval in the pair's box: the outer knot moves too,
    // so a neighbour of it is bounded by the next fixed knot, not by the outer knot's old
    // value (which `search_box(&[other], ..)` would hold fixed). Without a margin, so that the
    // span's collapse (below) sits exactly at an end.
    let pair = problem.search_box(unknowns, 0.0, 0.0)?;
    let position = unknowns.iter().position(|&m| m == other)?;
    let mut search = problem.search_box(&[other], 0.0, 0.0)?;
    search.admissible = vec![pair.admissible[position]];
    search.bounds = vec![pair.admissible[position]];
    let project = |numerator: &Tensor| -> [Tensor; 2] {
        [0, 1].map(|i| {
            let e = rows[i];
            numerator.combine(&[
                e[0],
                e[1],
                e[2],
                -(e[0] * target[0] + e[1] * target[1] + e[2] * target[2]),
            ])
        })
    };
    let f0 = project(&problem.numerator_with_ratios(&search, &[(ratio, 0.0)])?);
    let f1 = project(&problem.numerator_with_ratios(&search, &[(ratio, 1.0)])?);
    let minus = Tensor::constant(&[-1.0]);
    let g: [Tensor; 2] = [0, 1].map(|i| {
        f1[i]
            .clone()
            .scaled()
            .plus(&f0[i].clone().scaled().times(&minus))
    });
    let f0s = [f0[0].clone().scaled(), f0[1].clone().scaled()];
    // The outer knot's leverage is a product of `q - 1` ratios that all vanish when the other
    // knot closes `t`'s span onto `ũ` (the pairs (t_1, t_{q+1}) and (t_q, t_{2q})): `G` has
    // the factor `(b - ũ)^k` there, a root of `g` on the box's edge that is no solution. It
    // is divided out. `k = q - 1` unless fixed knots at `ũ` force some of those ratios (`t`
    // on a knot): the order is read off the coefficients, the leading ones at that end that
    // vanish (up to rounding) in both components.
    let collapse = match (outer == 1, other) {
        (true, m) if m == q + 1 => Some(true),
        (false, m) if m == q => Some(false),
        _ => None,
    };
    let g_reduced: [Tensor; 2] = match collapse {
        Some(at_start) => {
            let order = |t: &Tensor| {
                let c = &t.coefficients;
                let big = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let n = c.len();
                (0..n)
                    .take_while(|&k| {
                        let i = if at_start { k } else { n - 1 - k };
                        c[i].abs() <= ZERO_MARGIN * big
                    })
                    .count()
            };
            let u0 = g[0].clone().unscaled();
            let u1 = g[1].clone().unscaled();
            let k = order(&u0).min(order(&u1)).min(q - 1);
            [u0, u1].map(|u| u.divided_at_end(k, at_start).scaled())
        }
        None => g.clone(),
    };
    let cross = f0s[0]
        .times(&g_reduced[1])
        .plus(&f0s[1].times(&g_reduced[0]).times(&minus))
        .unscaled();
    let options = IsolationOptions {
        max_boxes: PAIR_BOXES.min(*budget),
        ..IsolationOptions::default()
    };
    let isolation = isolate(&cross, 1, options, &|_, _| false);
    *budget = budget.saturating_sub(isolation.boxes);
    let (g0, g1) = (g[0].clone().unscaled(), g[1].clone().unscaled());
    let mut found = Vec::new();
    let slope = cross.derivative(0);
    for root in isolation.roots {
        // The isolating box's centre is refined on `g` first: the outer knot extrapolated
        // from `α_A` at a point off the root can be far from the solution, beyond the reach of
        // the polish on de Boor.
        let s = refine_univariate(&cross, &slope, root.point);
        let (mut v0, mut v1, mut w0, mut w1) = ([0.0], [0.0], [0.0], [0.0]);
        f0[0].evaluate(s, &mut v0);
        f0[1].evaluate(s, &mut v1);
        g0.evaluate(s, &mut w0);
        g1.evaluate(s, &mut w1);
        let norm = w0[0] * w0[0] + w1[0] * w1[0];
        if norm.is_nan() || norm <= 0.0 {
            continue;
        }
        let alpha = -(v0[0] * w0[0] + v1[0] * w1[0]) / norm;
        let mut knots = problem.knots_at(&search, s);
        knots[outer] = if outer == 1 {
            (u - alpha * knots[q + 1]) / (1.0 - alpha)
        } else {
            knots[q] + (u - knots[q]) / alpha
        };
        if knots[outer].is_finite() {
            found.push((knots, root.certified));
        }
    }
    Some(found)
}

/// Newton's method on the univariate polynomial `f` (derivative `slope`) from `start`, kept
/// in the unit interval; a step that fails to lower `|f|` ends it.
fn refine_univariate(
    f: &Tensor,
    slope: &Tensor,
    start: [f64; MAX_VARIABLES],
) -> [f64; MAX_VARIABLES] {
    let (mut s, mut value, mut derivative) = (start, [0.0], [0.0]);
    f.evaluate(s, &mut value);
    for _ in 0..UNIVARIATE_STEPS {
        if value[0] == 0.0 {
            break;
        }
        slope.evaluate(s, &mut derivative);
        let mut next = s;
        next[0] = (s[0] - value[0] / derivative[0]).clamp(0.0, 1.0);
        let mut next_value = [0.0];
        f.evaluate(next, &mut next_value);
        // A NaN step ends it too.
        if next_value[0].abs().is_nan() || next_value[0].abs() >= value[0].abs() {
            break;
        }
        s = next;
        value = next_value;
    }
    s
}

/// Whether two neighbouring unknowns (local indices `m`, `m + 1`) are out of order on the
/// whole box (lower corner `lo`, widths `width` in the unit box): each knot is affine in
/// each variable, so its extremes over the box lie at the box's corners.
pub(crate) fn disordered(
    problem: &LocalProblem,
    search: &SearchBox,
    lo: [f64; MAX_VARIABLES],
    width: [f64; MAX_VARIABLES],
) -> bool {
    let unknowns = &search.unknowns;
    let n = unknowns.len();
    let pairs: Vec<(usize, usize)> = (1..n)
        .filter(|&k| unknowns[k] == unknowns[k - 1] + 1 && search.blow_up != Some((k - 1, k)))
        .map(|k| (unknowns[k - 1], unknowns[k]))
        .collect();
    if pairs.is_empty() {
        return false;
    }
    let scale = problem.knots[2 * problem.degree + 1] - problem.knots[0];
    // Out of order everywhere when even the best corner has the lower knot above the upper.
    let mut largest_gap = vec![f64::NEG_INFINITY; pairs.len()];
    for corner in 0..(1usize << n) {
        let mut s = [0.0; MAX_VARIABLES];
        for k in 0..n {
            s[k] = lo[k] + if corner >> k & 1 == 1 { width[k] } else { 0.0 };
        }
        let knots = problem.knots_at(search, s);
        for (gap, &(m, next)) in largest_gap.iter_mut().zip(&pairs) {
            *gap = gap.max(knots[next] - knots[m]);
        }
    }
    largest_gap
        .iter()
        .any(|&gap| gap < -CLAMP_TOLERANCE * scale)
}

/// The `q = 2` closed forms (the paper's six pairs, docs/method.md §4) on the triangle of
/// the local poles: the target's frame, then [`solve_pair`].
fn quadratic(
    problem: &LocalProblem,
    unknowns: &[usize],
    target: Point,
    weighted: bool,
) -> Vec<Vec<f64>> {
    let pair = match unknowns {
        [1, 2] => KnotPair::Omega1,
        [2, 3] => KnotPair::Omega2,
        [3, 4] => KnotPair::Omega3,
        [1, 3] => KnotPair::Omega4,
        [1, 4] => KnotPair::Omega5,
        [2, 4] => KnotPair::Omega6,
        _ => return Vec::new(),
    };
    let poles = &problem.poles;
    let triangle = [0, 1, 2].map(|i| {
        let h = poles[i];
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    });
    let weights = weighted.then(|| [0, 1, 2].map(|i| poles[i][3]));
    let Ok(Some(Frame { x, y })) = triangle_frame(&triangle, weights, Some(target)) else {
        return Vec::new();
    };
    let t = &problem.knots;
    let local = LocalKnots {
        l: t[0],
        a: t[1],
        b: t[2],
        t: problem.parameter,
        c: t[3],
        e: t[4],
        r: t[5],
    };
    let (solutions, count) = solve_pair(pair, &local, x, y);
    solutions[..count]
        .iter()
        .map(|&[a, b, c, e]| vec![t[0], a, b, c, e, t[5]])
        .collect()
}

/// The outermost pair `(t_1, t_{2q})` (docs/method.md §31.4): each enters one ratio only,
/// `α_A = α_{1,1}` and `α_B = α_{q,1}`, and the homogeneous point is affine in the two
/// together, `H = H_00 + α_A (H_10 - H_00) + α_B (H_01 - H_00)`, so `rows · (X - p W) = 0` is a
/// 2 × 2 linear system; then `t_1 = (ũ - α_A t_{q+1}) / (1 - α_A)` and
/// `t_{2q} = t_q + (ũ - t_q) / α_B`.
fn outermost(problem: &LocalProblem, target: Point, rows: &[Point]) -> Vec<Vec<f64>> {
    let q = problem.degree;
    let u = problem.parameter;
    let value = |alpha_a: f64, alpha_b: f64| {
        let h =
            problem.homogeneous_point_with(&problem.knots, &[((1, 1), alpha_a), ((q, 1), alpha_b)]);
        [0, 1].map(|i| {
            let e = rows[i];
            e[0] * (h[0] - target[0] * h[3])
                + e[1] * (h[1] - target[1] * h[3])
                + e[2] * (h[2] - target[2] * h[3])
        })
    };
    let f00 = value(0.0, 0.0);
    let fa = value(1.0, 0.0);
    let fb = value(0.0, 1.0);
    let mut m = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
    for i in 0..2 {
        m[i][0] = fa[i] - f00[i];
        m[i][1] = fb[i] - f00[i];
    }
    let Some(inverse) = invert(&m, 2) else {
        return Vec::new();
    };
    let alpha_a = -(inverse[0][0] * f00[0] + inverse[0][1] * f00[1]);
    let alpha_b = -(inverse[1][0] * f00[0] + inverse[1][1] * f00[1]);
    let t = &problem.knots;
    let first = (u - alpha_a * t[q + 1]) / (1.0 - alpha_a);
    let last = t[q] + (u - t[q]) / alpha_b;
    if !(first.is_finite() && last.is_finite()) {
        return Vec::new();
    }
    let mut knots = t.clone();
    knots[1] = first;
    knots[2 * q] = last;
    vec![knots]
}

/// Newton's method on `rows · (P(knots) - target) = 0` in the unknown knots, from a root of
/// the polynomial system (a few steps refine it to the accuracy of de Boor itself); a step is
/// kept only while it lowers the residual, and stays in the widened box.
fn polish(
    problem: &LocalProblem,
    search: &SearchBox,
    knots: &mut [f64],
    target: Point,
    rows: &[Point],
) {
    let n = search.unknowns.len();
    let residual = |point: Point| -> [f64; MAX_VARIABLES] {
        let d = sub(point, target);
        let mut r = [0.0; MAX_VARIABLES];
        for (i, row) in rows.iter().enumerate().take(n) {
            r[i] = dot(*row, d);
        }
        r
    };
    let size = |r: &[f64; MAX_VARIABLES]| r.iter().map(|v| v * v).sum::<f64>();
    let (point, mut partials) = problem.point_and_partials(knots, &search.unknowns);
    let mut current = residual(point);
    for _ in 0..POLISH_STEPS {
        if size(&current) == 0.0 {
            break;
        }
        let mut jacobian = [[0.0; MAX_VARIABLES]; MAX_VARIABLES];
        for i in 0..n {
            for k in 0..n {
                jacobian[i][k] = dot(rows[i], partials[k]);
            }
        }
        let Some(inverse) = invert(&jacobian, n) else {
            break;
        };
        let mut trial = knots.to_vec();
        for (k, &m) in search.unknowns.iter().enumerate() {
            let step: f64 = (0..n).map(|i| inverse[k][i] * current[i]).sum();
            let (lo, hi) = search.admissible[k];
            let widen = SEARCH_MARGIN * (hi - lo);
            trial[m] = (knots[m] - step).max(lo - widen).min(hi + widen);
        }
        let (point, trial_partials) = problem.point_and_partials(&trial, &search.unknowns);
        let next = residual(point);
        let (after, before) = (size(&next), size(&current));
        if after.is_nan() || after >= before {
            break;
        }
        knots.copy_from_slice(&trial);
        current = next;
        partials = trial_partials;
    }
}

/// The root clamped into the admissible box (a bound missed by at most
/// [`CLAMP_TOLERANCE`] of the unknown's room is taken as met), unknowns within
/// [`KNOT_TOLERANCE`] of their old value snapped back to it; `None` when it lies outside, the
/// knots are not monotone, or `ũ` leaves its (non-empty) span.
pub(crate) fn admissible(
    problem: &LocalProblem,
    search: &SearchBox,
    mut knots: Vec<f64>,
) -> Option<Vec<f64>> {
    let q = problem.degree;
    let scale = problem.knots[2 * q + 1] - problem.knots[0];
    for (k, &m) in search.unknowns.iter().enumerate() {
        let (lo, hi) = search.admissible[k];
        let slack = CLAMP_TOLERANCE * scale;
        let value = knots[m];
        if !value.is_finite() || value < lo - slack || value > hi + slack {
            return None;
        }
        let mut value = value.max(lo).min(hi);
        if (value - problem.knots[m]).abs() <= KNOT_TOLERANCE * scale {
            value = problem.knots[m];
        }
        knots[m] = value;
    }
    // Unknowns next to each other may cross by rounding: within the slack they meet.
    for w in 1..knots.len() {
        if knots[w] < knots[w - 1] {
            if knots[w - 1] - knots[w] <= CLAMP_TOLERANCE * scale && search.unknowns.contains(&w) {
                knots[w] = knots[w - 1];
            } else {
                return None;
            }
        }
    }
    let u = problem.parameter;
    (knots[q] <= u && u <= knots[q + 1] && knots[q] < knots[q + 1]).then_some(knots)
}
