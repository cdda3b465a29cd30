//! Moving a surface point by changing three weights (docs/method.md §42), the surface form of
//! the curves' two-weight move ([`crate::shape::weights`]).
//!
//! At `(u, v)` the poles with `n_k = N_i(u) M_j(v) > 0` act. For three of them, `T = {a, b, c}`,
//! split off the others, `W₀ = Σ_{k∉T} w_k n_k` and `s₀ = Σ_{k∉T} w_k n_k d_k / W₀`, and let
//! `x_t` be the new weights of the three:
//!
//! ```text
//! S(u, v) = (W₀ s₀ + Σ_{t∈T} x_t n_t d_t) / (W₀ + Σ_{t∈T} x_t n_t).
//! ```
//!
//! The four coefficients are positive, so `S(u, v)` is the point of barycentric coordinates
//! `(λ₀, λ_a, λ_b, λ_c) ∝ (W₀, x_a n_a, x_b n_b, x_c n_c)` in the tetrahedron
//! `(s₀, d_a, d_b, d_c)`. A target `p` with coordinates `λ` (the 3×3 system
//! `p - s₀ = Σ_t λ_t (d_t - s₀)`, `λ₀ = 1 - Σ_t λ_t`), all positive, is reached by
//!
//! ```text
//! x_t = λ_t W₀ / (λ₀ n_t),
//! ```
//!
//! and by no other weights of these three (the map is projective and one to one onto the
//! tetrahedron's interior). The weights must also stay within the curves' bounds
//! ([`weight_bounds`]), which cut the reachable set to part of the tetrahedron. Where at most
//! three poles act (`W₀ = 0`) the three weights only move the point in their triangle, and
//! the triple is left out.

use super::constraints::{FixedNet, SurfaceConstraints, caller_index, surface_edit_size};
use super::control_points::affected_domain_of_poles;
use super::method::{
    SurfaceEditContext, SurfaceEditMethod, SurfaceExclusion, SurfaceExclusionReason,
    SurfaceMethodKind, SurfaceMethodSolutions, SurfaceNearest, SurfaceReachable, SurfaceSolution,
    SurfaceSolutionDetail, TetrahedronRegion,
};
use crate::shape::{CONSTRAINT_TOLERANCE, weight_bounds};
use crate::spline::vector::{Point, add, cross, distance, dot, norm, scale, sub};
use crate::spline::{CAP, basis_functions};
use crate::surface::Surface;

/// The most poles acting at one parameter pair for which the method looks at every triple
/// (degree 5 in both directions: 36 poles, 7 140 triples); beyond it the method is refused.
pub const MAX_ACTIVE_POLES: usize = 36;

/// At most this many solutions are returned (those that change the weights least, by
/// `max_t |ln(x_t / w_t)|`), each measured and ranked by the edit.
pub const MAX_WEIGHT_SOLUTIONS: usize = 4;

/// A tetrahedron whose volume is below this fraction of the cube of its longest edge is flat:
/// its three weights move the point in (nearly) a plane only, and the triple is left out.
pub const FLAT_TETRAHEDRON: f64 = 1e-12;

/// A solved weight beyond a bound by at most this fraction of the bound is set onto it.
const BOUND_SLACK: f64 = 1e-9;

/// One triple of the poles acting at `(u, v)`, with the rest of the point split off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightTriple {
    /// Stored flat indices `i · count_v + j`, ascending.
    pub poles: [usize; 3],
    /// `n_t = N_i(u) M_j(v)` of each (positive).
    pub basis: [f64; 3],
    /// `W₀` (positive).
    pub rest_weight: f64,
    /// The tetrahedron `(s₀, d_a, d_b, d_c)`.
    pub tetrahedron: [Point; 4],
    /// The current weights.
    pub old_weights: [f64; 3],
    /// `6 |volume| / (e₁ e₂ e₃)` of the edges from `s₀`, in `(0, 1]`: how well the three
    /// weights determine a point (1 for orthogonal edges).
    pub conditioning: f64,
}

/// New weights of a triple that put `S(u, v)` on a target.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceWeightMove {
    /// The triple.
    pub triple: WeightTriple,
    /// `x_a, x_b, x_c`.
    pub weights: [f64; 3],
    /// The new surface (its stored weights; a periodic pole's copies all changed).
    pub surface: Surface,
    /// The new `S(u, v)`.
    pub point: Point,
    /// `|point - target|`.
    pub residual: f64,
    /// Outside it the surface is unchanged.
    pub affected_domain: [(f64, f64); 2],
}

/// Why the weight method has nothing to offer at `(u, v)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WeightRefusal {
    /// More than [`MAX_ACTIVE_POLES`] poles act.
    TooManyActivePoles(usize),
}

/// Every triple of the poles acting at `(u, v)` (in the domain) whose tetrahedron is not
/// flat and which leaves other poles acting (`W₀ > 0`), lexicographic; poles that a periodic
/// direction holds twice among the active ones are left out (their copies would have to
/// change together).
// The loops fill the tensor product's active list by both indices at once.
#[allow(clippy::needless_range_loop)]
pub fn weight_triples(
    surface: &Surface,
    u: f64,
    v: f64,
) -> Result<Vec<WeightTriple>, WeightRefusal> {
    let (p, q) = (surface.u().degree(), surface.v().degree());
    let (a, b) = (surface.u().span(u), surface.v().span(v));
    let mut nu = [0.0; CAP];
    let mut nv = [0.0; CAP];
    basis_functions(surface.u().knots(), p, a, u, &mut nu);
    basis_functions(surface.v().knots(), q, b, v, &mut nv);
    let n_v = surface.v().count();
    let mut active: Vec<(usize, f64)> = Vec::new();
    for r in 0..=p {
        for s in 0..=q {
            let n = nu[r] * nv[s];
            if n > 0.0 {
                active.push(((a - p + r) * n_v + b - q + s, n));
            }
        }
    }
    if active.len() > MAX_ACTIVE_POLES {
        return Err(WeightRefusal::TooManyActivePoles(active.len()));
    }
    // Whether each active pole's caller index is held by another active pole too.
    let callers: Vec<[usize; 2]> = active
        .iter()
        .map(|&(flat, _)| caller_index(surface, flat))
        .collect();
    let repeated: Vec<bool> = callers
        .iter()
        .map(|caller| callers.iter().filter(|other| *other == caller).count() > 1)
        .collect();
    let weight = |flat: usize| surface.weights().map_or(1.0, |w| w[flat]);
    let points = surface.control_points();
    let mut total_weight = 0.0;
    let mut total = [0.0; 3];
    for &(flat, n) in &active {
        total_weight += weight(flat) * n;
        total = add(total, scale(points[flat], weight(flat) * n));
    }
    let mut triples = Vec::new();
    let m = active.len();
    for x in 0..m {
        for y in x + 1..m {
            for z in y + 1..m {
                if repeated[x] || repeated[y] || repeated[z] {
                    continue;
                }
                let chosen = [active[x], active[y], active[z]];
                let mut rest_weight = total_weight;
                let mut rest = total;
                for &(flat, n) in &chosen {
                    rest_weight -= weight(flat) * n;
                    rest = sub(rest, scale(points[flat], weight(flat) * n));
                }
                // Below rounding of the total: only the three act.
                if rest_weight <= 1e-12 * total_weight {
                    continue;
                }
                let s0 = scale(rest, 1.0 / rest_weight);
                let tetrahedron = [
                    s0,
                    points[chosen[0].0],
                    points[chosen[1].0],
                    points[chosen[2].0],
                ];
                let Some(conditioning) = shape_quality(&tetrahedron) else {
                    continue;
                };
                triples.push(WeightTriple {
                    poles: [chosen[0].0, chosen[1].0, chosen[2].0],
                    basis: [chosen[0].1, chosen[1].1, chosen[2].1],
                    rest_weight,
                    tetrahedron,
                    old_weights: [
                        weight(chosen[0].0),
                        weight(chosen[1].0),
                        weight(chosen[2].0),
                    ],
                    conditioning,
                });
            }
        }
    }
    Ok(triples)
}

/// `6 |V| / (e₁ e₂ e₃)` for the edges `e_t = d_t - s₀`, or `None` when the tetrahedron is
/// flat ([`FLAT_TETRAHEDRON`]).
fn shape_quality(t: &[Point; 4]) -> Option<f64> {
    let e = [sub(t[1], t[0]), sub(t[2], t[0]), sub(t[3], t[0])];
    let det = dot(e[0], cross(e[1], e[2]));
    let lengths = [norm(e[0]), norm(e[1]), norm(e[2])];
    let longest = lengths.iter().fold(0.0f64, |m, &l| m.max(l));
    if det.abs().partial_cmp(&(FLAT_TETRAHEDRON * longest.powi(3)))
        != Some(std::cmp::Ordering::Greater)
    {
        return None;
    }
    Some(det.abs() / (lengths[0] * lengths[1] * lengths[2]))
}

/// Barycentric coordinates `(λ₀, λ_a, λ_b, λ_c)` of `target` in the tetrahedron, by Cramer's
/// rule on `target - s₀ = Σ λ_t (d_t - s₀)`.
pub fn barycentric(t: &[Point; 4], target: Point) -> [f64; 4] {
    let e = [sub(t[1], t[0]), sub(t[2], t[0]), sub(t[3], t[0])];
    let r = sub(target, t[0]);
    let det = dot(e[0], cross(e[1], e[2]));
    let la = dot(r, cross(e[1], e[2])) / det;
    let lb = dot(e[0], cross(r, e[2])) / det;
    let lc = dot(e[0], cross(e[1], r)) / det;
    [1.0 - la - lb - lc, la, lb, lc]
}

/// The weights of `triple` that put the point on `target` (module docs), when the target is
/// inside the tetrahedron and the weights within their bounds; `None` otherwise.
pub fn triple_weights(triple: &WeightTriple, target: Point) -> Option<[f64; 3]> {
    let lambda = barycentric(&triple.tetrahedron, target);
    if !lambda.iter().all(|&l| l > 0.0 && l.is_finite()) {
        return None;
    }
    let mut weights = [0.0; 3];
    for t in 0..3 {
        let x = lambda[t + 1] * triple.rest_weight / (lambda[0] * triple.basis[t]);
        let (lo, hi) = weight_bounds(triple.old_weights[t]);
        weights[t] = if x < lo && x >= lo * (1.0 - BOUND_SLACK) {
            lo
        } else if x > hi && x <= hi * (1.0 + BOUND_SLACK) {
            hi
        } else {
            x
        };
        if !(weights[t] >= lo && weights[t] <= hi) {
            return None;
        }
    }
    Some(weights)
}

/// The stored flat indices of `pole` and of its periodic copies (a periodic direction stores
/// its first poles again at its end; caller index `i` is stored at `i`, `i + caller_count`, …).
fn stored_copies(surface: &Surface, pole: usize) -> impl Iterator<Item = usize> {
    let [i, j] = caller_index(surface, pole);
    let (u, v) = (surface.u(), surface.v());
    let (count_v, step_u, step_v) = (v.count(), u.caller_count(), v.caller_count());
    (i..u.count()).step_by(step_u).flat_map(move |row| {
        (j..count_v)
            .step_by(step_v)
            .map(move |column| row * count_v + column)
    })
}

/// The surface with the weights of the triple's poles (and of their periodic copies) set.
pub fn with_triple_weights(surface: &Surface, poles: [usize; 3], weights: [f64; 3]) -> Surface {
    let count = surface.control_points().len();
    let mut new_weights = surface
        .weights()
        .map_or_else(|| vec![1.0; count], <[f64]>::to_vec);
    for (pole, weight) in poles.into_iter().zip(weights) {
        for flat in stored_copies(surface, pole) {
            new_weights[flat] = weight;
        }
    }
    Surface::from_valid_parts(
        surface.u().clone(),
        surface.v().clone(),
        surface.control_points().to_vec(),
        Some(new_weights),
    )
}

/// What the weight method found for one target: the moves, and how many were dropped for
/// each reason.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WeightOutcome {
    /// Verified moves that change the weights least, at most [`MAX_WEIGHT_SOLUTIONS`].
    pub moves: Vec<SurfaceWeightMove>,
    /// Triples that reach the target but change a fixed pole: `(count, first such pole)`.
    pub fixed: Option<(usize, usize)>,
    /// Triples that reach the target but break a constraint: `(count, first constraint)`.
    pub broken: Option<(usize, usize)>,
}

/// Every triple that reaches `target`, verified on the new surface (its point within
/// `CONSTRAINT_TOLERANCE · size`, every constraint kept, no fixed pole changed).
pub fn weight_moves(
    surface: &Surface,
    (u, v): (f64, f64),
    target: Point,
    triples: &[WeightTriple],
    constraints: &SurfaceConstraints,
    fixed: &FixedNet,
) -> WeightOutcome {
    let size = surface_edit_size(surface).max(norm(target));
    let mut reaching: Vec<(f64, &WeightTriple, [f64; 3])> = triples
        .iter()
        .filter_map(|triple| {
            let weights = triple_weights(triple, target)?;
            let change = (0..3)
                .map(|t| (weights[t] / triple.old_weights[t]).ln().abs())
                .fold(0.0f64, f64::max);
            Some((change, triple, weights))
        })
        .collect();
    reaching.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut outcome = WeightOutcome::default();
    for (_, triple, weights) in reaching {
        if let Some(&pole) = triple.poles.iter().find(|&&pole| fixed.is_fixed(pole)) {
            let entry = outcome.fixed.get_or_insert((0, pole));
            entry.0 += 1;
            continue;
        }
        if outcome.moves.len() == MAX_WEIGHT_SOLUTIONS {
            continue;
        }
        let new_surface = with_triple_weights(surface, triple.poles, weights);
        let point = new_surface.point(u, v);
        let residual = distance(point, target);
        if residual.is_nan() || residual > CONSTRAINT_TOLERANCE * size {
            continue;
        }
        if let Err(index) = constraints.check(&new_surface) {
            let entry = outcome.broken.get_or_insert((0, index));
            entry.0 += 1;
            continue;
        }
        let mut changed: Vec<usize> = triple
            .poles
            .iter()
            .flat_map(|&pole| stored_copies(surface, pole))
            .collect();
        changed.sort_unstable();
        changed.dedup();
        outcome.moves.push(SurfaceWeightMove {
            triple: *triple,
            weights,
            affected_domain: affected_domain_of_poles(surface, &changed),
            surface: new_surface,
            point,
            residual,
        });
    }
    outcome
}

/// The point of the tetrahedron nearest to `target`: itself when inside, else the nearest of
/// the four faces' nearest points ([`closest_on_triangle`]).
pub fn closest_in_tetrahedron(t: &[Point; 4], target: Point) -> Point {
    if barycentric(t, target).iter().all(|&l| l >= 0.0) {
        return target;
    }
    let faces = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
    faces
        .iter()
        .map(|f| closest_on_triangle(target, t[f[0]], t[f[1]], t[f[2]]))
        .min_by(|a, b| distance(*a, target).total_cmp(&distance(*b, target)))
        .unwrap_or(target)
}

/// The point of triangle `abc` nearest to `p` (Ericson, Real-Time Collision Detection §5.1.5:
/// the Voronoi regions of the vertices, edges and face).
pub fn closest_on_triangle(p: Point, a: Point, b: Point, c: Point) -> Point {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return add(a, scale(ab, d1 / (d1 - d3)));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return add(a, scale(ac, d2 / (d2 - d6)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return add(b, scale(sub(c, b), w));
    }
    let denominator = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denominator, vc * denominator);
    add(a, add(scale(ab, v), scale(ac, w)))
}

/// Barycentric coordinates of a nearest point are at least this (the open tetrahedron).
const NEAREST_PULL: f64 = 1e-9;

/// The nearest points of at most this many tetrahedra are tried (nearest first), which bounds
/// the work of a nearest search.
const NEAREST_TRIES: usize = 16;

/// The weight triples behind the surface edit's interface ([`SurfaceEditMethod`]).
#[derive(Debug, Clone, Copy)]
pub struct WeightsMethod;

impl WeightsMethod {
    /// The moves that reach `target`, as solutions, with the method's own exclusions.
    fn solutions(
        edit: &SurfaceEditContext,
        triples: &[WeightTriple],
        target: Point,
    ) -> SurfaceMethodSolutions {
        let surface = edit.surface;
        let outcome = weight_moves(
            surface,
            edit.parameter,
            target,
            triples,
            edit.constraints,
            edit.fixed,
        );
        let mut excluded = Vec::new();
        if let Some((count, pole)) = outcome.fixed {
            excluded.push(SurfaceExclusion {
                method: SurfaceMethodKind::Weights,
                count,
                reason: SurfaceExclusionReason::MovesFixedPole {
                    pole: caller_index(surface, pole),
                },
            });
        }
        if let Some((count, constraint)) = outcome.broken {
            excluded.push(SurfaceExclusion {
                method: SurfaceMethodKind::Weights,
                count,
                reason: SurfaceExclusionReason::Breaks { constraint },
            });
        }
        let solutions = outcome
            .moves
            .into_iter()
            .map(|m| SurfaceSolution {
                detail: SurfaceSolutionDetail::Weights {
                    poles: m.triple.poles.map(|pole| caller_index(surface, pole)),
                    weights: m.weights,
                    tetrahedron: m.triple.tetrahedron,
                },
                conditioning: m.triple.conditioning,
                surface: m.surface,
                point: m.point,
                residual: m.residual,
                affected_domain: m.affected_domain,
                max_deviation: None,
            })
            .collect();
        SurfaceMethodSolutions {
            solutions,
            excluded,
        }
    }

    fn refusal(count: usize) -> SurfaceExclusionReason {
        SurfaceExclusionReason::TooManyActivePoles { count }
    }
}

impl SurfaceEditMethod for WeightsMethod {
    fn kind(&self) -> SurfaceMethodKind {
        SurfaceMethodKind::Weights
    }

    fn solve(&self, edit: &SurfaceEditContext, target: Point) -> SurfaceMethodSolutions {
        let (u, v) = edit.parameter;
        match weight_triples(edit.surface, u, v) {
            Ok(triples) => WeightsMethod::solutions(edit, &triples, target),
            Err(WeightRefusal::TooManyActivePoles(count)) => SurfaceMethodSolutions {
                solutions: Vec::new(),
                excluded: vec![SurfaceExclusion {
                    method: SurfaceMethodKind::Weights,
                    count: 1,
                    reason: WeightsMethod::refusal(count),
                }],
            },
        }
    }

    fn reachable(&self, edit: &SurfaceEditContext) -> SurfaceReachable {
        let (u, v) = edit.parameter;
        match weight_triples(edit.surface, u, v) {
            Ok(triples) => SurfaceReachable::Tetrahedra(
                triples
                    .iter()
                    .filter(|t| !t.poles.iter().any(|&pole| edit.fixed.is_fixed(pole)))
                    .map(|t| TetrahedronRegion {
                        poles: t.poles.map(|pole| caller_index(edit.surface, pole)),
                        tetrahedron: t.tetrahedron,
                    })
                    .collect(),
            ),
            Err(WeightRefusal::TooManyActivePoles(count)) => {
                SurfaceReachable::Nothing(WeightsMethod::refusal(count))
            }
        }
    }

    /// Per free triple, the point its weights reach nearest to the target's nearest point of
    /// the tetrahedron ([`closest_in_tetrahedron`]): that point's weights (from its
    /// barycentric coordinates) clamped into their bounds and mapped back. The nearest of
    /// those that some triple reaches within its bounds and the constraints, solved there.
    fn nearest(&self, edit: &SurfaceEditContext, target: Point) -> Option<SurfaceNearest> {
        let (u, v) = edit.parameter;
        let triples = weight_triples(edit.surface, u, v).ok()?;
        let points = edit.surface.control_points();
        let mut candidates: Vec<(f64, Point)> = triples
            .iter()
            .filter(|t| !t.poles.iter().any(|&pole| edit.fixed.is_fixed(pole)))
            .map(|t| {
                let closest = closest_in_tetrahedron(&t.tetrahedron, target);
                let lambda = barycentric(&t.tetrahedron, closest).map(|l| l.max(NEAREST_PULL));
                let mut numerator = scale(t.tetrahedron[0], t.rest_weight);
                let mut denominator = t.rest_weight;
                for k in 0..3 {
                    let (lo, hi) = weight_bounds(t.old_weights[k]);
                    let x =
                        (lambda[k + 1] * t.rest_weight / (lambda[0] * t.basis[k])).clamp(lo, hi);
                    numerator = add(numerator, scale(points[t.poles[k]], x * t.basis[k]));
                    denominator += x * t.basis[k];
                }
                let reached = scale(numerator, 1.0 / denominator);
                (distance(reached, target), reached)
            })
            .collect();
        candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
        candidates
            .into_iter()
            .take(NEAREST_TRIES)
            .find_map(|(_, point)| {
                let found = WeightsMethod::solutions(edit, &triples, point).solutions;
                (!found.is_empty()).then_some(SurfaceNearest {
                    point,
                    solutions: found,
                })
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::SurfaceLimits;

    /// A bicubic periodic in `u` (5 caller rows, stored with their first three again) and
    /// clamped in `v` (4 columns).
    fn periodic_in_u() -> Surface {
        let poles: Vec<Vec<[f64; 3]>> = (0..5)
            .map(|i| {
                let angle = i as f64 * std::f64::consts::TAU / 5.0;
                (0..4)
                    .map(|j| [angle.cos(), angle.sin(), j as f64])
                    .collect()
            })
            .collect();
        let u_knots = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let u_multiplicities = [1; 6];
        let v_knots = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        Surface::from_knot_forms(
            (3, 3),
            &poles,
            (
                KnotForm::Periodic {
                    knots: &u_knots,
                    multiplicities: &u_multiplicities,
                },
                KnotForm::Flat(&v_knots),
            ),
            None::<&[Vec<f64>]>,
            &SurfaceLimits::default(),
        )
        .unwrap()
    }

    #[test]
    fn stored_copies_are_every_stored_pole_of_the_same_caller_pole() {
        let surface = periodic_in_u();
        assert!(surface.u().count() > surface.u().caller_count());
        let stored = surface.control_points().len();
        for pole in 0..stored {
            // By the definition: every stored pole whose caller index is the same.
            let expected: Vec<usize> = (0..stored)
                .filter(|&flat| caller_index(&surface, flat) == caller_index(&surface, pole))
                .collect();
            let found: Vec<usize> = stored_copies(&surface, pole).collect();
            assert_eq!(found, expected, "pole {pole}");
        }
    }

    #[test]
    fn new_weights_reach_every_copy_and_nothing_else() {
        let surface = periodic_in_u();
        let poles = [1, 5, 6];
        let moved = with_triple_weights(&surface, poles, [2.0, 3.0, 0.5]);
        let weights = moved.weights().unwrap();
        for (flat, &weight) in weights.iter().enumerate() {
            let caller = caller_index(&surface, flat);
            let expected = poles
                .iter()
                .zip([2.0, 3.0, 0.5])
                .find(|(pole, _)| caller_index(&surface, **pole) == caller)
                .map_or(1.0, |(_, w)| w);
            assert_eq!(weight, expected, "stored pole {flat}");
        }
    }
}
