//! Moving a curve point by changing two weights (after The NURBS Book §11.3; docs/method.md
//! §20).
//!
//! At `t` the poles `i` with `N_i(t) > 0` act. For two of them, `k < l`, split off the other
//! poles, `S₀ = Σ_{i≠k,l} w_i N_i d_i` and `W₀ = Σ_{i≠k,l} w_i N_i`, and let `a, b` be the new
//! weights of `d_k, d_l`:
//!
//! ```text
//! s(t) = (W₀ s₀ + a N_k d_k + b N_l d_l) / (W₀ + a N_k + b N_l),   s₀ = S₀ / W₀.
//! ```
//!
//! The three coefficients are positive, so `s(t)` is the point of barycentric coordinates
//! `(λ₀, λ_k, λ_l) ∝ (W₀, a N_k, b N_l)` in the triangle `(s₀, d_k, d_l)`: a target with
//! coordinates `λ` (all positive) is reached by `a = λ_k W₀ / (λ₀ N_k)`, `b = λ_l W₀ / (λ₀ N_l)`.
//! The map `(a, b) → s(t)` is projective, so the weights allowed by [`weight_bounds`] (a
//! rectangle) reach exactly a convex quadrilateral of that triangle, whose edges are straight:
//! one weight at a bound keeps `λ_k / λ₀` (or `λ_l / λ₀`) fixed, a line through `d_l` (or `d_k`).
//! When only `k` and `l` act (`W₀ = 0`: degree 1, or `t` on a knot of high multiplicity) the
//! pair moves `s(t)` along the segment `d_k d_l`, and only the ratio `a N_k : b N_l` matters;
//! the change then scales the two weights by reciprocal factors.

use super::candidate::{DEGENERACY_TOLERANCE, PLANE_TOLERANCE};
use super::constraints::{CONSTRAINT_TOLERANCE, edit_size};
use super::control_points::affected_domain_of_poles;
use super::method::{
    EditContext, EditMethod, EditSolution, MethodKind, MethodMembership, MethodNearest,
    MethodSolutions, Reachable, SolutionDetail, WeightRegion,
};
use super::regions::PolygonOptions;
use super::solve::ShapeError;
use crate::spline::vector::{Point, add, cross, distance, dot, norm, scale, sub};
use crate::spline::{Curve, MAX_DEGREE};

/// A new weight may be at most this factor above or below the old one `w`, and at least
/// every weight in [`WEIGHT_ABSOLUTE_RANGE`] is allowed: the bounds of a weight `w` are
/// `[min(0.01, w / 100), max(100, 100 w)]`.
pub const WEIGHT_RATIO_LIMIT: f64 = 100.0;

/// Weights always allowed, whatever the old weight.
pub const WEIGHT_ABSOLUTE_RANGE: (f64, f64) = (0.01, 100.0);

/// A solved weight beyond a bound by at most this fraction of the bound is set onto the bound
/// (rounding of targets on the region's edge); the new point is checked all the same.
const BOUND_SLACK: f64 = 1e-9;

/// The interval a weight `w` may move in: `[min(0.01, w / 100), max(100, 100 w)]`.
pub fn weight_bounds(w: f64) -> (f64, f64) {
    (
        WEIGHT_ABSOLUTE_RANGE.0.min(w / WEIGHT_RATIO_LIMIT),
        WEIGHT_ABSOLUTE_RANGE.1.max(w * WEIGHT_RATIO_LIMIT),
    )
}

/// One pair of poles active at `t`, with the rest of the curve point split off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightPair {
    /// `[k, l]`, `k < l`.
    pub poles: [usize; 2],
    /// `N_k(t), N_l(t)` (both positive).
    pub basis: [f64; 2],
    /// `W₀`, the weighted basis of the other poles (`0` when only `k, l` act).
    pub rest_weight: f64,
    /// `s₀ = S₀ / W₀` (meaningless when `W₀ = 0`).
    pub rest_point: Point,
    /// The triangle `(s₀, d_k, d_l)`.
    pub triangle: [Point; 3],
    /// The current weights `w_k, w_l`.
    pub old_weights: [f64; 2],
    /// The allowed interval of each of the two weights.
    pub bounds: [(f64, f64); 2],
}

/// A pair's new weights that put `s(t)` on a target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightMove {
    /// The new weights `[a, b]` of the pair's poles.
    pub weights: [f64; 2],
}

/// Every pair of the poles with `N_i(t) > 0`, in order `(k, l)` lexicographic. Precondition:
/// `t` in the domain.
pub fn weight_pairs(curve: &Curve, t: f64) -> Vec<WeightPair> {
    let p = curve.degree();
    let mut basis = [0.0; MAX_DEGREE + 1];
    let first = curve.basis_at(t, &mut basis);
    let active: Vec<usize> = (0..=p).filter(|&r| basis[r] > 0.0).collect();
    let d = curve.control_points();
    let mut pairs = Vec::with_capacity(active.len() * active.len().saturating_sub(1) / 2);
    for (position, &rk) in active.iter().enumerate() {
        for &rl in &active[position + 1..] {
            let (k, l) = (first + rk, first + rl);
            let mut rest_sum = [0.0; 3];
            let mut rest_weight = 0.0;
            for &r in &active {
                if r == rk || r == rl {
                    continue;
                }
                let w = curve.weight(first + r) * basis[r];
                rest_weight += w;
                rest_sum = add(rest_sum, scale(d[first + r], w));
            }
            let rest_point = if rest_weight > 0.0 {
                scale(rest_sum, 1.0 / rest_weight)
            } else {
                d[k]
            };
            pairs.push(WeightPair {
                poles: [k, l],
                basis: [basis[rk], basis[rl]],
                rest_weight,
                rest_point,
                triangle: [rest_point, d[k], d[l]],
                old_weights: [curve.weight(k), curve.weight(l)],
                bounds: [
                    weight_bounds(curve.weight(k)),
                    weight_bounds(curve.weight(l)),
                ],
            });
        }
    }
    pairs
}

impl WeightPair {
    /// Whether only the pair's two poles act at `t` (`W₀ = 0`): it moves `s(t)` on a segment.
    pub fn is_segment(&self) -> bool {
        self.rest_weight <= 0.0
    }

    /// The longest edge of the triangle: the size the tolerances are relative to.
    pub fn size(&self) -> f64 {
        let [a, b, c] = self.triangle;
        distance(a, b).max(distance(b, c)).max(distance(a, c))
    }

    /// Whether the pair can move the point at all: its triangle (or segment) is not degenerate.
    pub fn is_applicable(&self) -> bool {
        let [s0, dk, dl] = self.triangle;
        let size = self.size();
        if self.is_segment() {
            return distance(dk, dl) > 0.0;
        }
        let area2 = norm(cross(sub(dk, s0), sub(dl, s0)));
        area2 > DEGENERACY_TOLERANCE * size * size
    }

    /// The curve point at `t` for the pair's weights `[a, b]`.
    pub fn point(&self, [a, b]: [f64; 2]) -> Point {
        let (ak, bl) = (a * self.basis[0], b * self.basis[1]);
        let [s0, dk, dl] = self.triangle;
        let numerator = add(
            add(scale(s0, self.rest_weight), scale(dk, ak)),
            scale(dl, bl),
        );
        scale(numerator, 1.0 / (self.rest_weight + ak + bl))
    }

    /// The weights that put `s(t)` on `target`, when they exist within the bounds
    /// (module docs); `None` when the target is outside the reachable quadrilateral, off the
    /// triangle's plane, or the pair is degenerate.
    pub fn solve(&self, target: Point) -> Option<WeightMove> {
        if !self.is_applicable() {
            return None;
        }
        let [_, dk, dl] = self.triangle;
        let size = self.size();
        let weights = if self.is_segment() {
            // s(t) = (α d_k + β d_l) / (α + β) with α = a N_k, β = b N_l: the ratio only.
            let direction = sub(dl, dk);
            let length_sq = dot(direction, direction);
            let along = dot(sub(target, dk), direction) / length_sq;
            let foot = add(dk, scale(direction, along));
            if distance(foot, target) > PLANE_TOLERANCE * size || !(along > 0.0 && along < 1.0) {
                return None;
            }
            // β / α = along / (1 - along); scale both weights by reciprocal factors g, 1/g.
            let ratio = along / (1.0 - along) * self.basis[0] / self.basis[1];
            let [wk, wl] = self.old_weights;
            let g = (wl / (ratio * wk)).sqrt();
            [wk * g, wl / g]
        } else {
            let lambda = barycentric(&self.triangle, target, size)?;
            let [l0, lk, ll] = lambda;
            if l0.is_nan() || l0 <= 0.0 {
                return None;
            }
            [
                lk * self.rest_weight / (l0 * self.basis[0]),
                ll * self.rest_weight / (l0 * self.basis[1]),
            ]
        };
        let mut clamped = [0.0; 2];
        for (slot, (&w, &(lo, hi))) in weights.iter().zip(&self.bounds).enumerate() {
            clamped[slot] = if w >= lo && w <= hi {
                w
            } else if w < lo && w >= lo * (1.0 - BOUND_SLACK) {
                lo
            } else if w > hi && w <= hi * (1.0 + BOUND_SLACK) {
                hi
            } else {
                return None;
            };
        }
        Some(WeightMove { weights: clamped })
    }

    /// The reachable quadrilateral: the points of the four bound corners `(a, b)` in order
    /// (lo, lo), (hi, lo), (hi, hi), (lo, hi); its edges are straight (module docs). For a
    /// segment pair two of them coincide in pairs.
    pub fn corners(&self) -> [Point; 4] {
        let [(a_lo, a_hi), (b_lo, b_hi)] = self.bounds;
        [
            self.point([a_lo, b_lo]),
            self.point([a_hi, b_lo]),
            self.point([a_hi, b_hi]),
            self.point([a_lo, b_hi]),
        ]
    }

    /// The barycentric coordinates `(λ_k, λ_l)` of a point of the triangle's plane
    /// (`p = s₀ + λ_k (d_k - s₀) + λ_l (d_l - s₀)`), the frame of the pair's region drawing; for
    /// a segment pair `(1 - μ, μ)` with `μ` the position along `d_k d_l`.
    pub fn frame_of(&self, point: Point) -> [f64; 2] {
        let [s0, dk, dl] = self.triangle;
        if self.is_segment() {
            let direction = sub(dl, dk);
            let along = dot(sub(point, dk), direction) / dot(direction, direction);
            return [1.0 - along, along];
        }
        let e1 = sub(dk, s0);
        let e2 = sub(dl, s0);
        let normal = cross(e1, e2);
        let area_sq = dot(normal, normal);
        let r = sub(point, s0);
        [
            dot(cross(r, e2), normal) / area_sq,
            dot(cross(e1, r), normal) / area_sq,
        ]
    }

    /// The point of the reachable quadrilateral nearest to `target` (Euclidean; a 3D target
    /// off the plane is matched by its foot in the plane), or `None` for a degenerate pair.
    pub fn nearest(&self, target: Point) -> Option<Point> {
        if !self.is_applicable() {
            return None;
        }
        let corners = self.corners();
        if !self.is_segment() {
            let [s0, dk, dl] = self.triangle;
            let normal = cross(sub(dk, s0), sub(dl, s0));
            let offset = dot(sub(target, s0), normal) / dot(normal, normal);
            let foot = sub(target, scale(normal, offset));
            if inside_convex(&corners, normal, foot) {
                return Some(foot);
            }
        }
        (0..4)
            .map(|i| closest_on_segment(target, corners[i], corners[(i + 1) % 4]))
            .min_by(|p, q| distance(*p, target).total_cmp(&distance(*q, target)))
    }
}

/// Barycentric coordinates `(λ₀, λ_k, λ_l)` of `target` in a non-degenerate triangle, or
/// `None` when it lies farther than `PLANE_TOLERANCE · size` from the triangle's plane.
fn barycentric(triangle: &[Point; 3], target: Point, size: f64) -> Option<[f64; 3]> {
    let [s0, dk, dl] = *triangle;
    let e1 = sub(dk, s0);
    let e2 = sub(dl, s0);
    let normal = cross(e1, e2);
    let area = norm(normal);
    let r = sub(target, s0);
    if dot(r, normal).abs() / area > PLANE_TOLERANCE * size {
        return None;
    }
    let area_sq = area * area;
    let lk = dot(cross(r, e2), normal) / area_sq;
    let ll = dot(cross(e1, r), normal) / area_sq;
    Some([1.0 - lk - ll, lk, ll])
}

/// Whether `point` (in the plane with normal `normal`) lies inside the convex polygon
/// `corners` (in order, either orientation), boundary included.
fn inside_convex(corners: &[Point; 4], normal: Point, point: Point) -> bool {
    let mut sign = 0.0;
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        let side = dot(cross(sub(b, a), sub(point, a)), normal);
        if side == 0.0 {
            continue;
        }
        if sign == 0.0 {
            sign = side.signum();
        } else if side.signum() != sign {
            return false;
        }
    }
    true
}

/// The point of the segment `a b` nearest to `point`.
fn closest_on_segment(point: Point, a: Point, b: Point) -> Point {
    let direction = sub(b, a);
    let length_sq = dot(direction, direction);
    if length_sq == 0.0 {
        return a;
    }
    let along = (dot(sub(point, a), direction) / length_sq).clamp(0.0, 1.0);
    add(a, scale(direction, along))
}

/// The weight method behind the edit's interface ([`EditMethod`]): any degree; a curve without
/// weights comes back rational.
#[derive(Debug, Clone, Copy)]
pub struct Weights;

/// The solution of `pair` with new weights `change` for the curve point at `t`, evaluated by
/// the spline core; `None` when the new point misses `target` by more than
/// [`CONSTRAINT_TOLERANCE`] of the curve's size.
pub fn weight_solution(
    curve: &Curve,
    t: f64,
    pair: &WeightPair,
    change: WeightMove,
    target: Point,
) -> Option<EditSolution> {
    let mut weights = curve
        .weights()
        .map_or_else(|| vec![1.0; curve.control_points().len()], <[f64]>::to_vec);
    let mut changed_weights = Vec::with_capacity(2);
    for (&pole, &weight) in pair.poles.iter().zip(&change.weights) {
        if weights[pole] != weight {
            weights[pole] = weight;
            changed_weights.push(pole);
        }
    }
    let new_curve = curve.with_weights(weights)?;
    let point = new_curve.point_unchecked(t);
    let residual = distance(point, target);
    if residual.is_nan() || residual > CONSTRAINT_TOLERANCE * edit_size(curve).max(norm(target)) {
        return None;
    }
    Some(EditSolution {
        affected_domain: affected_domain_of_poles(curve, &changed_weights),
        detail: SolutionDetail::Weights {
            poles: pair.poles,
            changed_weights,
        },
        curve: new_curve,
        point,
        residual,
        max_deviation: None,
    })
}

/// The pairs a request may use: applicable, and neither pole fixed.
fn usable_pairs(edit: &EditContext) -> Vec<WeightPair> {
    weight_pairs(edit.query.curve, edit.query.parameter)
        .into_iter()
        .filter(|pair| pair.is_applicable() && !pair.poles.iter().any(|&i| edit.fixed.is_fixed(i)))
        .collect()
}

impl EditMethod for Weights {
    fn kind(&self) -> MethodKind {
        MethodKind::Weights
    }

    fn refuses(&self, _curve: &Curve) -> Option<ShapeError> {
        None
    }

    /// Every applicable pair that reaches the target; pairs with a fixed pole too (the edit
    /// excludes them and says why).
    fn solve(&self, edit: &EditContext, target: Point) -> MethodSolutions {
        let (curve, t) = (edit.query.curve, edit.query.parameter);
        let pairs: Vec<WeightPair> = weight_pairs(curve, t)
            .into_iter()
            .filter(WeightPair::is_applicable)
            .collect();
        let solutions = pairs
            .iter()
            .filter_map(|pair| weight_solution(curve, t, pair, pair.solve(target)?, target))
            .collect();
        MethodSolutions {
            solutions,
            failure: None,
            membership: MethodMembership::WeightPairs(pairs.iter().map(|p| p.poles).collect()),
        }
    }

    /// The quadrilaterals of the usable pairs whose edits surely keep the constraints (the
    /// weights of poles `k < l` change the curve only on `[u_k, u_{l+p+1}]`).
    fn reachable(&self, edit: &EditContext, _options: PolygonOptions) -> Reachable {
        let curve = edit.query.curve;
        Reachable::WeightRegions(
            usable_pairs(edit)
                .into_iter()
                .filter(|pair| {
                    let mut poles = pair.poles;
                    poles.sort_unstable();
                    let affected = affected_domain_of_poles(curve, &poles);
                    edit.constraints.surely_kept_outside(curve, affected)
                })
                .map(|pair| {
                    let corners = pair.corners();
                    let polygon: Vec<Point> = corners
                        .iter()
                        .chain(std::iter::once(&corners[0]))
                        .copied()
                        .collect();
                    let polygon_frame = polygon.iter().map(|&q| pair.frame_of(q)).collect();
                    WeightRegion {
                        pair,
                        polygon,
                        polygon_frame,
                    }
                })
                .collect(),
        )
    }

    /// The nearest point of the usable pairs' quadrilaterals whose solution meets the
    /// constraints, and every usable pair's solution there that does.
    fn nearest(&self, edit: &EditContext, target: Point) -> Option<MethodNearest> {
        let (curve, t) = (edit.query.curve, edit.query.parameter);
        let pairs = usable_pairs(edit);
        let mut places: Vec<(f64, usize, Point)> = pairs
            .iter()
            .enumerate()
            .filter_map(|(i, pair)| {
                let q = pair.nearest(target)?;
                Some((distance(q, target), i, q))
            })
            .collect();
        places.sort_by(|p, q| p.0.total_cmp(&q.0));
        let meets = |s: &EditSolution| edit.constraints.check(&s.curve).is_ok();
        for (_, i, q) in places {
            let pair = &pairs[i];
            let Some(first) = pair
                .solve(q)
                .and_then(|change| weight_solution(curve, t, pair, change, q))
                .filter(meets)
            else {
                continue;
            };
            let point = first.point;
            let mut solutions: Vec<EditSolution> = pairs
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .filter_map(|(_, other)| {
                    weight_solution(curve, t, other, other.solve(point)?, point)
                })
                .filter(meets)
                .collect();
            solutions.insert(
                0,
                EditSolution {
                    residual: 0.0,
                    ..first
                },
            );
            return Some(MethodNearest { point, solutions });
        }
        None
    }
}
