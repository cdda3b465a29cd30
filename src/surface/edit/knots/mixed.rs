//! Mixed moves (docs/method.md §46): knots in both directions for 3D targets.
//!
//! One direction `A` gets two unknown knots, the other `B` one. In `A` the local problem is
//! the envelope's (`a_r := ã`, both sides; degree ≥ 3, `q = p − 1`) or the direct one on
//! degree 2 (`q = 2`); in `B` the envelope (`b_s := b̃`, both sides) or the direct problem
//! (any degree ≥ 2). For `q = 2`
//!
//! ```text
//! S(ã, b̃) = Σ_k N_k(ã; a, a') D_k(c),   D_k(c) = Σ_l h_kl M_l(b̃; c)   (homogeneous),
//! ```
//!
//! `N_k` the three quadratic basis values of `A`'s local knots with the pair `(a, a')`, `M_l`
//! those of `B`'s local knots with the unknown `c`. For a fixed `c` the pair reaches only the
//! plane of `D_0(c), D_1(c), D_2(c)` (the `q = 2` region lies in its triangle), so `c` must
//! solve the **plane condition**
//!
//! ```text
//! g(c) = det[ X_0(c) − p W_0(c);  X_1(c) − p W_1(c);  X_2(c) − p W_2(c) ] = 0,
//! ```
//!
//! rows the homogeneous points `(X_k, W_k) = D_B(c) · D_k(c)` times the common product
//! `D_B(c) > 0` of `B`'s ratio denominators (so `g` is a polynomial of degree `≤ 3 n_c`, `n_c`
//! the knot's degree in `B`'s de Boor triangle). Its roots in `c`'s admissible interval are
//! isolated by certified subdivision of its Bernstein form
//! ([`crate::shape::family::isolate`], Krawczyk), and for each the pair is the curve solver's
//! closed form on the triangle `D_k(c)` ([`crate::shape::family::roots::solve_unknowns`],
//! at most one solution per pair). Every admissible solution of a set is found, except where
//! the subdivision's box budget runs out or a root of `g` is not simple (then a candidate is
//! still tried, not certified). A pair direction of degree ≥ 4 (`q ≥ 3`: the pair reaches a
//! curved patch, no plane condition) solves its three unknowns together
//! ([`super::curved`]).

use super::curved::{PairBasis, curved_roots, pair_basis, single_rows};
use super::iso::{iso_curve_along, movable};
use super::plane::plane_roots;
use super::{
    SurfaceKnotFamily, SurfaceKnotOptions, SurfaceKnotSolution, accepted_residual, affected_range,
    along, with_both_knots,
};
use crate::shape::Side;
use crate::shape::family::local::LocalProblem;
use crate::shape::family::problems::{
    Family, FamilyProblem, direct_problem, envelope_problem, extent, plane_of, unknown_sets,
};
use crate::shape::family::roots::solve_unknowns;
use crate::shape::family::solve::{knots_admissible, smallest_singular_value};
use crate::spline::Curve;
use crate::spline::vector::{Point, distance};
use crate::surface::{Direction, Surface};

/// Subdivision boxes all mixed sets of one request may examine (the plane conditions'
/// isolation and nothing else: the pairs are closed forms).
pub const MIXED_BOXES: usize = 20_000;

/// One direction's local problem of a mixed move.
#[derive(Debug, Clone)]
pub(crate) struct Side1 {
    /// The family problem (envelope side or direct) on the iso-curve along the direction.
    pub problem: FamilyProblem,
    /// Its primitive (poles of the iso-curve, replaced per row by the mixed solver).
    pub local: LocalProblem,
    /// Index along the direction of the first local pole.
    pub pole_start: usize,
}

/// The local problems of `curve` at `t` usable in a mixed move: for the pair direction
/// (`pair = true`) the envelope on both sides (degree ≥ 3: `q = p − 1`, the plane condition
/// for a cubic, the curved system of [`super::curved`] above) or a quadratic's direct
/// problem (`q = 2`), for the single direction every envelope side and, when `direct`, the
/// direct problem. Problems that do not apply (domain end, empty span) are left out; collinear
/// iso-curve poles are not a reason here (the rows' poles are used instead).
pub(crate) fn direction_problems(
    curve: &Curve,
    t: f64,
    keep_domain: bool,
    pair: bool,
    direct: bool,
) -> Vec<Side1> {
    let p = curve.degree();
    let mut problems = Vec::new();
    let envelope = if pair { p >= 3 } else { p >= 2 };
    if envelope {
        for side in [Side::Right, Side::Left] {
            problems.push(envelope_problem(curve, t, side, keep_domain));
        }
    }
    if (!pair && direct) || (pair && p == 2) {
        problems.push(direct_problem(curve, t, Family::Direct));
    }
    problems
        .into_iter()
        .filter_map(|problem| {
            let usable = matches!(
                problem.not_applicable,
                None | Some(crate::shape::family::FamilyNotApplicable::Collinear)
            );
            let local = problem.problem.clone().filter(|_| usable)?;
            // A set whose first acting pole would lie before the net's first (an end span
            // with too few knots before it) has no mixed move.
            let pole_start = problem.moved_knot.unwrap_or(problem.span).checked_sub(p)?;
            Some(Side1 {
                problem,
                local,
                pole_start,
            })
        })
        .collect()
}

/// The net seen with the pair direction first: `pole(a, b)` is `h_ab` (homogeneous).
#[derive(Clone, Copy)]
pub(crate) struct Oriented<'a> {
    pub surface: &'a Surface,
    pub pair: Direction,
}

impl Oriented<'_> {
    /// The homogeneous control point at index `a` along the pair direction, `b` along the
    /// other.
    pub fn pole(&self, a: usize, b: usize) -> [f64; 4] {
        let count_v = self.surface.v().count();
        match self.pair {
            Direction::U => self.surface.homogeneous()[a * count_v + b],
            Direction::V => self.surface.homogeneous()[b * count_v + a],
        }
    }
}

/// The rows of `B`'s primitive for the three poles `k` of `A` (`D_k` as functions of `B`'s
/// knots), the homogeneous poles shifted by `-origin` (`(w (d − o), w)`).
pub(crate) fn rows_of(
    net: Oriented,
    a: &Side1,
    b: &Side1,
    tb: f64,
    origin: Point,
) -> Vec<LocalProblem> {
    (0..=a.local.degree)
        .map(|k| LocalProblem {
            degree: b.local.degree,
            knots: b.local.knots.clone(),
            full_index: b.local.full_index.clone(),
            poles: (0..=b.local.degree)
                .map(|l| {
                    let h = net.pole(a.pole_start + k, b.pole_start + l);
                    [
                        h[0] - origin[0] * h[3],
                        h[1] - origin[1] * h[3],
                        h[2] - origin[2] * h[3],
                        h[3],
                    ]
                })
                .collect(),
            parameter: tb,
        })
        .collect()
}

/// Every mixed solution with two unknown knots along `pair` (module docs).
pub(crate) fn solve_mixed(
    surface: &Surface,
    pair: Direction,
    u: f64,
    v: f64,
    target: Point,
    options: &SurfaceKnotOptions,
) -> Vec<SurfaceKnotSolution> {
    let single = pair.other();
    if !movable(surface, pair) || !movable(surface, single) {
        return Vec::new();
    }
    let keep = options.keep_domain;
    let (ta, tb) = (along(pair, u, v), along(single, u, v));
    let curve_a = iso_curve_along(surface, pair, u, v);
    let curve_b = iso_curve_along(surface, single, u, v);
    let net = Oriented { surface, pair };
    let accepted = accepted_residual(surface, u, v, target);
    let mut budget = MIXED_BOXES;
    let mut found: Vec<SurfaceKnotSolution> = Vec::new();
    // A solved move as a surface solution, when the rules keep it and it is new.
    let solution_of = |move_: &Move, found: &[SurfaceKnotSolution]| {
        move_.solution(
            net,
            &curve_a,
            &curve_b,
            (u, v),
            target,
            accepted,
            keep,
            found,
        )
    };
    let b_problems = direction_problems(&curve_b, tb, keep, false, options.mixed_direct);
    for a in direction_problems(&curve_a, ta, keep, true, false) {
        let pairs = unknown_sets(&a.local, 2, &curve_a, keep);
        // A curved pair's basis numerators, shared by every `B` side.
        let bases: Vec<(&Vec<usize>, Option<PairBasis>)> = if a.local.degree > 2 {
            pairs
                .iter()
                .map(|set| (set, pair_basis(&a.local, set)))
                .collect()
        } else {
            Vec::new()
        };
        for b in &b_problems {
            let shifted = rows_of(net, &a, b, tb, target);
            if a.local.degree > 2 {
                // A curved pair (degree ≥ 4): the three unknowns together.
                for m in singles(&b.local, &curve_b, keep) {
                    let Some(single) = single_rows(&shifted, m) else {
                        continue;
                    };
                    for (set, pair) in &bases {
                        let Some(pair) = pair else {
                            continue;
                        };
                        for root in curved_roots(&a.local, pair, &shifted, &single, &mut budget) {
                            let move_ = Move {
                                a: &a,
                                b,
                                set,
                                m,
                                a_local: root.a_local,
                                b_local: root.b_local,
                            };
                            if let Some(solution) = solution_of(&move_, &found) {
                                found.push(solution);
                            }
                        }
                    }
                }
                continue;
            }
            let rows = rows_of(net, &a, b, tb, [0.0; 3]);
            for m in singles(&b.local, &curve_b, keep) {
                for c in plane_roots(&shifted, m, &mut budget) {
                    let mut b_local = b.local.knots.clone();
                    b_local[m] = c;
                    let poles: Vec<[f64; 4]> =
                        rows.iter().map(|r| r.homogeneous_point(&b_local)).collect();
                    let points: Vec<Point> = poles.iter().map(|h| project(*h)).collect();
                    let Some([e1, e2, _]) = plane_of(&points) else {
                        continue;
                    };
                    if outside_triangle(&points, e1, e2, target) {
                        // Every q = 2 pair stays in the triangle's hull (monotone knots).
                        continue;
                    }
                    let weighted = poles.iter().any(|h| h[3] != poles[0][3]);
                    let a_c = LocalProblem {
                        poles,
                        ..a.local.clone()
                    };
                    for set in &pairs {
                        let roots =
                            solve_unknowns(&a_c, set, target, &[e1, e2], weighted, &mut budget);
                        for root in roots {
                            let move_ = Move {
                                a: &a,
                                b,
                                set,
                                m,
                                a_local: root.knots,
                                b_local: b_local.clone(),
                            };
                            if let Some(solution) = solution_of(&move_, &found) {
                                found.push(solution);
                            }
                        }
                    }
                }
            }
        }
    }
    found
}

/// Barycentric coordinates below this (in the plane of the triangle) are outside it.
const TRIANGLE_MARGIN: f64 = 1e-9;

/// Whether `target`, in the plane `(e1, e2)` of the triangle `points`, lies outside it by
/// more than [`TRIANGLE_MARGIN`] in a barycentric coordinate: no `q = 2` pair reaches it
/// (with monotone knots the point is a convex combination of the poles).
fn outside_triangle(points: &[Point], e1: Point, e2: Point, target: Point) -> bool {
    let plane = |p: Point| {
        let d = [
            p[0] - points[0][0],
            p[1] - points[0][1],
            p[2] - points[0][2],
        ];
        [
            d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2],
            d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2],
        ]
    };
    let (a, b, t) = (plane(points[1]), plane(points[2]), plane(target));
    let det = a[0] * b[1] - a[1] * b[0];
    if det == 0.0 || !det.is_finite() {
        return false;
    }
    let beta1 = (t[0] * b[1] - t[1] * b[0]) / det;
    let beta2 = (a[0] * t[1] - a[1] * t[0]) / det;
    let beta0 = 1.0 - beta1 - beta2;
    beta0.min(beta1).min(beta2) < -TRIANGLE_MARGIN
}

/// The local indices of `B`'s relevant knots that may move alone (not a domain end under
/// `keep_domain`).
pub(crate) fn singles(local: &LocalProblem, curve: &Curve, keep_domain: bool) -> Vec<usize> {
    let p = curve.degree();
    let n = curve.control_points().len() - 1;
    (1..=2 * local.degree)
        .filter(|&m| {
            let full = local.full_index[m];
            !(keep_domain && (full == p || full == n + 1))
        })
        .collect()
}

/// The projected point of a homogeneous one.
fn project(h: [f64; 4]) -> Point {
    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
}

/// One solved mixed move in local terms.
pub(crate) struct Move<'a> {
    pub a: &'a Side1,
    pub b: &'a Side1,
    /// `A`'s unknown pair (local indices).
    pub set: &'a [usize],
    /// `B`'s unknown (local index).
    pub m: usize,
    /// `A`'s local knots with the pair solved.
    pub a_local: Vec<f64>,
    /// `B`'s local knots with `c` solved.
    pub b_local: Vec<f64>,
}

impl Move<'_> {
    /// The full knot vector of one direction with a local solution written in.
    fn full(curve: &Curve, side: &Side1, t: f64, local: &[f64], moved: &[usize]) -> Vec<f64> {
        let mut knots = curve.knots().to_vec();
        if let Some(i) = side.problem.moved_knot {
            knots[i] = t;
        }
        for &m in moved {
            knots[side.local.full_index[m]] = local[m];
        }
        knots
    }

    /// The surface solution, `None` when a rule drops it (either direction's knots not
    /// admissible, or the new surface misses the target at `(u, v)` by more than `accepted`)
    /// or when `found` holds it already.
    #[allow(clippy::too_many_arguments)]
    pub fn solution(
        &self,
        net: Oriented,
        curve_a: &Curve,
        curve_b: &Curve,
        (u, v): (f64, f64),
        target: Point,
        accepted: f64,
        keep: bool,
        found: &[SurfaceKnotSolution],
    ) -> Option<SurfaceKnotSolution> {
        let surface = net.surface;
        let (pair, single) = (net.pair, net.pair.other());
        let (ta, tb) = (along(pair, u, v), along(single, u, v));
        let knots_a = Move::full(curve_a, self.a, ta, &self.a_local, self.set);
        let knots_b = Move::full(curve_b, self.b, tb, &self.b_local, &[self.m]);
        if !knots_admissible(curve_a, &knots_a, keep) || !knots_admissible(curve_b, &knots_b, keep)
        {
            return None;
        }
        let (knots_u, knots_v) = match pair {
            Direction::U => (&knots_a, &knots_b),
            Direction::V => (&knots_b, &knots_a),
        };
        let known = found
            .iter()
            .any(|s| s.knots_u.as_ref() == Some(knots_u) && s.knots_v.as_ref() == Some(knots_v));
        if known {
            return None;
        }
        let new = with_both_knots(surface, knots_u.clone(), knots_v.clone());
        let point = new.point(u, v);
        let residual = distance(point, target);
        if residual.is_nan() || residual > accepted {
            return None;
        }
        let changed = |old: &[f64], new: &[f64]| -> Vec<usize> {
            (0..old.len()).filter(|&i| old[i] != new[i]).collect()
        };
        let changed_a = changed(curve_a.knots(), &knots_a);
        let changed_b = changed(curve_b.knots(), &knots_b);
        let range_a = affected_range(surface.axis(pair), &knots_a, &changed_a)?;
        let range_b = affected_range(surface.axis(single), &knots_b, &changed_b)?;
        let conditioning = self.conditioning(net, tb);
        let region = self.name(pair);
        let (knots_u, knots_v, changed_u, changed_v, ranges) = match pair {
            Direction::U => (knots_a, knots_b, changed_a, changed_b, [range_a, range_b]),
            Direction::V => (knots_b, knots_a, changed_b, changed_a, [range_b, range_a]),
        };
        Some(SurfaceKnotSolution {
            surface: new,
            knots_u: Some(knots_u),
            knots_v: Some(knots_v),
            changed_knots_u: changed_u,
            changed_knots_v: changed_v,
            family: SurfaceKnotFamily::Mixed { pair },
            region,
            point,
            residual,
            affected_domain: surface.domain(),
            changed_ranges: ranges.map(Some),
            conditioning,
        })
    }

    /// `"u right, v left: u_7 := ũ, v_6 := ṽ; u_5, u_9; v_8"`.
    fn name(&self, pair: Direction) -> String {
        let describe = |d: Direction, side: &Side1| {
            let family = match side.problem.side {
                Some(s) => s.name().to_string(),
                None => "direct".to_string(),
            };
            let moved = side
                .problem
                .moved_knot
                .map(|i| format!("{0}_{i} := {0}\u{303}", d.name()));
            (format!("{} {family}", d.name()), moved)
        };
        let single = pair.other();
        let (fa, ma) = describe(pair, self.a);
        let (fb, mb) = describe(single, self.b);
        let moved: Vec<String> = [ma, mb].into_iter().flatten().collect();
        let a_knots: Vec<String> = self
            .set
            .iter()
            .map(|&m| format!("{}_{}", pair.name(), self.a.local.full_index[m]))
            .collect();
        let b_knot = format!("{}_{}", single.name(), self.b.local.full_index[self.m]);
        let mut name = format!("{fa}, {fb}:");
        if !moved.is_empty() {
            name.push_str(&format!(" {};", moved.join(", ")));
        }
        name.push_str(&format!(" {}; {b_knot}", a_knots.join(", ")));
        name
    }

    /// The smallest singular value of the point's Jacobian in the three unknowns, each
    /// scaled by its room (central differences on the local tensor evaluation), over the
    /// local poles' extent.
    fn conditioning(&self, net: Oriented, tb: f64) -> f64 {
        let rows = rows_of(net, self.a, self.b, tb, [0.0; 3]);
        let eval = |a_local: &[f64], b_local: &[f64]| -> Point {
            let poles: Vec<[f64; 4]> = rows.iter().map(|r| r.homogeneous_point(b_local)).collect();
            let local = LocalProblem {
                poles,
                ..self.a.local.clone()
            };
            local.point(a_local)
        };
        let room = |local: &LocalProblem, m: usize, moving: &[usize]| {
            let below = (0..m).rev().find(|i| !moving.contains(i)).unwrap_or(0);
            let above = (m + 1..=2 * local.degree + 1)
                .find(|i| !moving.contains(i))
                .unwrap_or(2 * local.degree + 1);
            local.knots[above] - local.knots[below]
        };
        let mut columns: Vec<Point> = Vec::with_capacity(3);
        for &m in self.set {
            let h = 1e-6 * room(&self.a.local, m, self.set);
            let (mut plus, mut minus) = (self.a_local.clone(), self.a_local.clone());
            plus[m] += h;
            minus[m] -= h;
            let (p, q) = (eval(&plus, &self.b_local), eval(&minus, &self.b_local));
            let r = room(&self.a.local, m, self.set);
            columns.push(std::array::from_fn(|c| (p[c] - q[c]) / (2.0 * h) * r));
        }
        let r = room(&self.b.local, self.m, &[self.m]);
        let h = 1e-6 * r;
        let (mut plus, mut minus) = (self.b_local.clone(), self.b_local.clone());
        plus[self.m] += h;
        minus[self.m] -= h;
        let (p, q) = (eval(&self.a_local, &plus), eval(&self.a_local, &minus));
        columns.push(std::array::from_fn(|c| (p[c] - q[c]) / (2.0 * h) * r));
        let points: Vec<Point> = rows
            .iter()
            .flat_map(|row| row.poles.iter().map(|h| project(*h)))
            .collect();
        let size = extent(&points);
        if size > 0.0 {
            smallest_singular_value(&columns) / size
        } else {
            0.0
        }
    }
}
