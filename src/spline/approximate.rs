//! Approximation to a tolerance (The NURBS Book §9.4): a curve of degree `p`, with as few
//! control points as this method manages, such that every point lies within `τ` of it.
//!
//! 1. Least squares for a knot vector (§9.4.1): with the end points interpolated
//!    (`P_0 = Q_0`, `P_n = Q_{m−1}`) the interior poles solve the banded, positive definite
//!    normal equations `(Nᵀ N) P = Nᵀ R`, `R_k = Q_k − N_0(ū_k) Q_0 − N_n(ū_k) Q_{m−1}`
//!    (Cholesky, `O(m p²)`); without exact ends all poles are unknowns.
//! 2. Parameter correction (Hoschek 1988): each `ū_k` moves by Newton's method on
//!    `(s(u) − Q_k) · s'(u) = 0` towards the foot of `Q_k` on the curve, a step kept only if
//!    it brings the curve point closer; then the fit is repeated.
//! 3. Refinement: starting from a single Bézier piece, every knot span holding a point
//!    farther than the target gets a knot between its points' middle parameters, and steps
//!    1–2 run again, until every point is within the target.
//! 4. Reduction: interior knots are removed, the cheapest first (the removal's certified
//!    bound, [`super::remove`]), as long as the points the removal changes the curve near
//!    stay within the target (their distance to the new curve at their parameter is
//!    measured); then the fit and the correction run again on the fewer knots, and the
//!    reduction repeats while it removes knots and the refit stays within the target.
//! 5. Certification: each point's distance to the final curve is measured by the
//!    closest-point search ([`super::ClosestPointSearch`], the global minimum over the
//!    curve); `max_error` is the largest. Every step above only accepts curves whose
//!    distances at the points' parameters (upper bounds of the true distances) are within
//!    the target, so the certified error is too.
//!
//! If refinement cannot reach the target (spans too small to split, as many poles as
//! points, or a fit so nearly singular that its poles swing far from the points), the
//! reduction starts instead from the curve interpolating every point (distance 0 at the
//! points), which is within any tolerance.
//!
//! One file for one algorithm: the fit, its certification, the refinement and the reduction
//! work on the same knot vector and fit state and are read together (about 850 lines); the
//! rest is its unit tests.

use super::banded::SymmetricBandedMatrix;
use super::basis::{CAP, MAX_DEGREE, basis_functions, find_span};
use super::closest::ClosestPointSearch;
use super::curve::{Curve, CurveLimits, Dimension, KnotConvention};
use super::fit_points::{COINCIDENT_POINT_TOLERANCE, Parametrization, PointSet, PointsError};
use super::interpolate::{InterpolationSpec, ParameterChoice, interpolate};
use super::remove::{apply_removal, knot_run, local_removal};
use super::vector::{Point, distance};

/// Smallest tolerance accepted, relative to the points' largest coordinate magnitude: below
/// it rounding in the curve's evaluation is no longer negligible and the distances cannot be
/// certified.
pub const APPROXIMATION_TOLERANCE_FLOOR: f64 = 1e-9;

/// The target the steps aim at is `τ` less this fraction of the largest coordinate
/// magnitude, which covers the rounding of the distances measured.
const ROUNDING_MARGIN: f64 = 1e-12;

/// Refinement rounds at most (each at least doubles the knots where the error is large).
const MAX_REFINEMENT_ROUNDS: usize = 64;

/// Gauss–Newton passes per fit at most.
const MAX_CORRECTION_PASSES: usize = 24;

/// Newton steps per point and correction pass.
const NEWTON_STEPS: usize = 4;

/// The first `μ` of a fit: the weight of the tangential part of a point's error (step 1 of
/// the module docs; 1 is plain least squares at the parameters).
const INITIAL_TANGENTIAL_WEIGHT: f64 = 0.01;

/// The factor by which `μ` falls after a good pass and rises after a bad one.
const WEIGHT_STEP: f64 = 3.0;

/// The smallest `μ` (which keeps the normal equations positive definite).
const MIN_TANGENTIAL_WEIGHT: f64 = 1e-6;

/// The passes of a fit stop when the sum of squared distances falls by less than this
/// fraction.
const STALL_FRACTION: f64 = 1e-4;

/// A fit whose poles stray farther than this many times the points' size from their centre
/// is refused as wild (a nearly singular least-squares system: the curve may meet the points
/// yet swing far out between them), as if singular.
const WILD_REACH: f64 = 10.0;

/// Gauss–Newton passes of a local refit after a removal at most.
const LOCAL_REFIT_PASSES: usize = 3;

/// Reduction rounds (removal, then refit) at most.
const MAX_REDUCTION_ROUNDS: usize = 16;

/// What to approximate with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApproximationSpec {
    /// Degree `p >= 1`.
    pub degree: usize,
    /// `τ > 0`: every point within `τ` of the curve.
    pub tolerance: f64,
    /// How the initial parameters are chosen.
    pub parametrization: Parametrization,
    /// The curve starts at the first point and ends at the last.
    pub end_points_exact: bool,
}

/// The approximating curve, its certified error and each point's closest parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Approximation {
    /// The curve: clamped, domain `[0, 1]`, full knot convention.
    pub curve: Curve,
    /// The largest distance from a point to the curve (closest-point search), `<= τ`.
    pub max_error: f64,
    /// The parameter of each point's closest curve point.
    pub parameters: Vec<f64>,
}

/// Why no curve is given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ApproximationError {
    #[error(transparent)]
    Points(#[from] PointsError),
    #[error("degree must be at least 1")]
    DegreeTooLow,
    #[error("degree {degree} exceeds the limit {max}")]
    DegreeTooHigh { degree: usize, max: usize },
    #[error("the tolerance must be a finite number greater than 0")]
    InvalidTolerance,
    #[error(
        "tolerance {tolerance} is below the smallest these points allow, {floor:e} ({APPROXIMATION_TOLERANCE_FLOOR:e} times their largest coordinate magnitude): double precision cannot certify it"
    )]
    ToleranceBelowFloor { tolerance: f64, floor: f64 },
    #[error(
        "the tolerance needs more than {max} control points for these points; give a larger tolerance"
    )]
    TooManyControlPoints { max: usize },
    #[error("the result is not finite: the points are too extreme for double precision")]
    NonFiniteResult,
}

/// The data every fit of one request shares.
struct Fitter<'a> {
    points: &'a [Point],
    p: usize,
    ends_exact: bool,
    dimension: Dimension,
    target: f64,
    /// The centre of the points' bounding box and the radius ([`WILD_REACH`] times its
    /// diagonal) beyond which a fitted pole counts as wild.
    centre: Point,
    reach: f64,
}

/// A fitted curve with each point's parameter and distance at that parameter.
#[derive(Debug, Clone)]
struct Fit {
    knots: Vec<f64>,
    poles: Vec<Point>,
    parameters: Vec<f64>,
    errors: Vec<f64>,
    /// Unit tangents of the curve at the parameters (for the next fit's weights).
    tangents: Vec<Point>,
}

impl Fit {
    fn max_error(&self) -> f64 {
        self.errors.iter().copied().fold(0.0, f64::max)
    }

    fn squared_sum(&self) -> f64 {
        self.errors.iter().map(|e| e * e).sum()
    }
}

impl Fitter<'_> {
    fn curve(&self, knots: Vec<f64>, poles: Vec<Point>) -> Curve {
        Curve::from_valid_parts(
            self.p,
            self.dimension,
            poles,
            None,
            knots,
            KnotConvention::Full,
        )
    }

    /// Step 1: the least-squares poles for `knots` at `parameters` (the ends fixed at the end
    /// points when they are exact); `None` when the normal equations are singular (a pole no
    /// point constrains). See [`Fitter::solve_free_poles`] for `tangents` and the weight.
    fn least_squares(
        &self,
        knots: &[f64],
        parameters: &[f64],
        tangents: Option<&[Point]>,
        tangential_weight: f64,
    ) -> Option<Vec<Point>> {
        let p = self.p;
        let m = self.points.len();
        let count = knots.len() - p - 1;
        let mut poles = vec![[0.0; 3]; count];
        let (free, rows) = if self.ends_exact {
            poles[0] = self.points[0];
            poles[count - 1] = self.points[m - 1];
            (1..count - 1, 1..m - 1)
        } else {
            (0..count, 0..m)
        };
        let indices: Vec<usize> = rows.clone().collect();
        self.solve_free_poles(
            knots,
            &mut poles,
            free,
            &indices,
            &parameters[rows.clone()],
            tangents.map(|all| &all[rows]),
            tangential_weight,
        )
        .then_some(poles)
    }

    /// Least squares for the poles `free` of the curve with `knots` and `poles` (the others
    /// fixed, their part subtracted from the points), over the points `rows` (indices) at
    /// `parameters` (one per row, in the same order; `tangents` likewise); writes them into
    /// `poles` and returns whether the normal equations were regular and the result finite.
    ///
    /// With `tangents` (unit tangents of the previous curve at the points), the squared
    /// distance of point `k` is weighted as `|e|² − (1 − μ) (e · T_k)²` (the distance to the
    /// tangent line plus `μ` times the tangential part): a Gauss–Newton step of the
    /// point-to-curve distance (Wang, Pottmann & Liu 2006, "tangent distance minimization",
    /// regularised), which lets the curve slide along itself instead of dragging every point
    /// to its old parameter. The coordinates then couple: the unknowns are interleaved, `d`
    /// per pole, in a band of width `d (p + 1)`.
    #[allow(clippy::too_many_arguments)]
    fn solve_free_poles(
        &self,
        knots: &[f64],
        poles: &mut [Point],
        free: std::ops::Range<usize>,
        rows: &[usize],
        parameters: &[f64],
        tangents: Option<&[Point]>,
        tangential_weight: f64,
    ) -> bool {
        let p = self.p;
        let d = self.dimension.count();
        let unknowns = free.len();
        if unknowns == 0 {
            return true;
        }
        let mut normal = SymmetricBandedMatrix::zeros(unknowns * d, (p + 1) * d - 1);
        let mut rhs = vec![0.0; unknowns * d];
        let mut basis = [0.0; CAP];
        for (row_index, &k) in rows.iter().enumerate() {
            let t = parameters[row_index];
            let span = find_span(knots, p, t);
            basis_functions(knots, p, span, t, &mut basis);
            let mut residual = self.points[k];
            for (i, &value) in basis.iter().enumerate().take(p + 1) {
                let column = span - p + i;
                if !free.contains(&column) {
                    for c in 0..3 {
                        residual[c] -= value * poles[column][c];
                    }
                }
            }
            // The weight matrix M = I − (1 − μ) T Tᵀ.
            let tangent = tangents.map_or([0.0; 3], |all| all[row_index]);
            let weight: [[f64; 3]; 3] = std::array::from_fn(|r| {
                std::array::from_fn(|c| {
                    let identity = if r == c { 1.0 } else { 0.0 };
                    identity - (1.0 - tangential_weight) * tangent[r] * tangent[c]
                })
            });
            let weighted: [f64; 3] =
                std::array::from_fn(|r| (0..3).map(|c| weight[r][c] * residual[c]).sum());
            for (i, &a) in basis.iter().enumerate().take(p + 1) {
                let column = span - p + i;
                if !free.contains(&column) || a == 0.0 {
                    continue;
                }
                let row = column - free.start;
                for c in 0..d {
                    rhs[row * d + c] += a * weighted[c];
                }
                for (j, &b) in basis.iter().enumerate().take(i + 1) {
                    let other = span - p + j;
                    if !free.contains(&other) || b == 0.0 {
                        continue;
                    }
                    let other = other - free.start;
                    for (r, weights) in weight.iter().enumerate().take(d) {
                        let columns = if other == row { r + 1 } else { d };
                        for (c, &w) in weights.iter().enumerate().take(columns) {
                            normal.add_lower(row * d + r, other * d + c, a * b * w);
                        }
                    }
                }
            }
        }
        if normal.factor_cholesky().is_err() {
            return false;
        }
        normal.solve(&mut rhs, 1);
        if rhs.iter().any(|v| !v.is_finite()) {
            return false;
        }
        for (index, chunk) in rhs.chunks_exact(d).enumerate() {
            let pole = &mut poles[free.start + index];
            pole[..d].copy_from_slice(chunk);
            if distance(*pole, self.centre) > self.reach {
                return false;
            }
        }
        true
    }

    /// Step 2 on one point: Newton's method from `t` towards the foot of `q`, each step kept
    /// only if it brings the curve point closer. Returns the parameter, its distance and the
    /// unit tangent there (0 where the tangent vanishes).
    fn correct(&self, curve: &Curve, q: Point, t: f64) -> (f64, f64, Point) {
        let (lo, hi) = curve.domain();
        let mut derivatives = [[0.0; 3]; 3];
        let mut best = (t, f64::INFINITY);
        let mut u = t;
        let mut tangent = [0.0; 3];
        for step in 0..=NEWTON_STEPS {
            if curve.derivatives(u, &mut derivatives).is_err() {
                break;
            }
            let [c, d1, d2] = derivatives;
            let offset = [c[0] - q[0], c[1] - q[1], c[2] - q[2]];
            let found =
                (offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2]).sqrt();
            if found.is_nan() || found >= best.1 {
                break;
            }
            best = (u, found);
            let speed = (d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]).sqrt();
            tangent = if speed > 0.0 {
                [d1[0] / speed, d1[1] / speed, d1[2] / speed]
            } else {
                [0.0; 3]
            };
            if step == NEWTON_STEPS {
                break;
            }
            let f = offset[0] * d1[0] + offset[1] * d1[1] + offset[2] * d1[2];
            let slope = speed * speed + offset[0] * d2[0] + offset[1] * d2[1] + offset[2] * d2[2];
            if slope.is_nan() || slope <= 0.0 {
                break;
            }
            let next = (u - f / slope).clamp(lo, hi);
            if next == u {
                break;
            }
            u = next;
        }
        (best.0, best.1, tangent)
    }

    /// Step 2 for every point on the curve with `poles`: the corrected parameters, errors
    /// and tangents (the end points keep their parameters when they are fixed).
    fn corrected(&self, knots: &[f64], poles: Vec<Point>, parameters: &[f64]) -> Fit {
        let curve = self.curve(knots.to_vec(), poles);
        let m = self.points.len();
        let mut fit = Fit {
            knots: knots.to_vec(),
            poles: Vec::new(),
            parameters: parameters.to_vec(),
            errors: vec![0.0; m],
            tangents: vec![[0.0; 3]; m],
        };
        for (k, (&q, &start)) in self.points.iter().zip(parameters).enumerate() {
            let (t, e, tangent) = self.correct(&curve, q, start);
            if self.ends_exact && (k == 0 || k == m - 1) {
                fit.errors[k] = distance(curve.point_unchecked(start), q);
            } else {
                (fit.parameters[k], fit.errors[k]) = (t, e);
            }
            fit.tangents[k] = tangent;
        }
        fit.poles = curve.control_points().to_vec();
        fit
    }

    /// Steps 1–2: a fit, then Gauss–Newton passes (tangent-weighted fits at the corrected
    /// parameters, [`Fitter::least_squares`]) with Levenberg–Marquardt control of `μ`: a
    /// pass that lowers the sum of squared distances is kept and `μ` shrinks threefold, one
    /// that does not is dropped and `μ` grows threefold; the passes stop at
    /// [`MAX_CORRECTION_PASSES`], when the sum improves by less than [`STALL_FRACTION`],
    /// when `μ` would exceed 1, or (with `stop_at_target`) once every point is within the
    /// target. Returns the pass with the smallest largest error; `None` when the first fit is
    /// singular.
    fn fit(
        &self,
        knots: Vec<f64>,
        parameters: &[f64],
        tangents: Option<&[Point]>,
        stop_at_target: bool,
    ) -> Option<Fit> {
        let poles = self.least_squares(&knots, parameters, tangents, INITIAL_TANGENTIAL_WEIGHT)?;
        let mut current = self.corrected(&knots, poles, parameters);
        let mut best = current.clone();
        let mut weight = INITIAL_TANGENTIAL_WEIGHT;
        for _pass in 0..MAX_CORRECTION_PASSES {
            if stop_at_target && best.max_error() <= self.target {
                break;
            }
            let trial = self
                .least_squares(&knots, &current.parameters, Some(&current.tangents), weight)
                .map(|poles| self.corrected(&knots, poles, &current.parameters));
            let (before, after) = (
                current.squared_sum(),
                trial.as_ref().map_or(f64::INFINITY, Fit::squared_sum),
            );
            match trial {
                Some(trial) if after < before => {
                    if trial.max_error() < best.max_error() {
                        best = trial.clone();
                    }
                    current = trial;
                    weight = (weight / WEIGHT_STEP).max(MIN_TANGENTIAL_WEIGHT);
                    if after > (1.0 - STALL_FRACTION) * before {
                        break;
                    }
                }
                _ => {
                    weight *= WEIGHT_STEP;
                    if weight > 1.0 {
                        break;
                    }
                }
            }
        }
        Some(best)
    }

    /// Step 3: a knot between the middle parameters of each span holding a point farther
    /// than the target (the span's midpoint when they coincide); empty when no span can be
    /// split.
    fn refinements(&self, fit: &Fit, parameters: &[f64]) -> Vec<f64> {
        let knots = &fit.knots;
        let p = self.p;
        let mut breaks: Vec<f64> = knots[p..knots.len() - p].to_vec();
        breaks.dedup();
        let mut by_parameter: Vec<usize> = (0..parameters.len()).collect();
        by_parameter.sort_by(|&a, &b| parameters[a].total_cmp(&parameters[b]));
        let mut inserted = Vec::new();
        let mut start = 0;
        for (span, window) in breaks.windows(2).enumerate() {
            let (a, b) = (window[0], window[1]);
            let last_span = span + 2 == breaks.len();
            let end = start
                + by_parameter[start..].partition_point(|&k| {
                    let t = parameters[k];
                    t < b || (last_span && t <= b)
                });
            let members = &by_parameter[start..end];
            start = end;
            if !members.iter().any(|&k| fit.errors[k] > self.target) {
                continue;
            }
            let inside: Vec<f64> = members
                .iter()
                .map(|&k| parameters[k])
                .filter(|&t| a < t && t < b)
                .collect();
            let half = inside.len() / 2;
            let mut knot = if inside.len() >= 2 {
                0.5 * (inside[half - 1] + inside[half])
            } else {
                0.5 * (a + b)
            };
            let room = 1e-9 * (b - a);
            if !(a + room < knot && knot < b - room) {
                knot = 0.5 * (a + b);
            }
            if a < knot && knot < b {
                inserted.push(knot);
            }
        }
        inserted
    }

    /// Step 4's removal round: tries every interior knot, the cheapest first, on the current
    /// curve. A removal is kept when each point where the curve changed stays within the
    /// target, first as the removal leaves the curve, else after a local refit: the poles
    /// the removal changed and one more on each side move by [`LOCAL_REFIT_PASSES`]
    /// Gauss–Newton passes over those points (the other poles fixed, so the curve elsewhere
    /// stays as it is). Returns whether any knot went.
    fn removal_round(&self, fit: &mut Fit) -> bool {
        let p = self.p;
        let mut homogeneous: Vec<[f64; 4]> = fit
            .poles
            .iter()
            .map(|pole| [pole[0], pole[1], pole[2], 1.0])
            .collect();
        let mut knots = fit.knots.clone();
        let (lo, hi) = (knots[p], knots[knots.len() - p - 1]);
        let mut candidates: Vec<(f64, f64)> = knots
            .chunk_by(|a, b| a == b)
            .filter(|run| lo < run[0] && run[0] < hi)
            .filter_map(|run| {
                let (r, s) = knot_run(&knots, run[0]);
                local_removal(p, &knots, &homogeneous, r, s, false).map(|t| (t.bound, run[0]))
            })
            .collect();
        candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut by_parameter: Vec<usize> = (0..fit.parameters.len()).collect();
        by_parameter.sort_by(|&a, &b| fit.parameters[a].total_cmp(&fit.parameters[b]));
        let mut removed_any = false;
        for (_, value) in candidates {
            let (r, s) = knot_run(&knots, value);
            if s == 0 {
                continue;
            }
            let Some(removal) = local_removal(p, &knots, &homogeneous, r, s, false) else {
                continue;
            };
            // The curve after the removal, read through the removal (no copy of the whole).
            let changed = removal.points.len();
            let trial_point = |i: usize| -> [f64; 4] {
                if i < removal.first {
                    homogeneous[i]
                } else if i < removal.first + changed {
                    removal.points[i - removal.first]
                } else {
                    homogeneous[i + 1]
                }
            };
            let trial_knot = |j: usize| {
                if j < removal.knot_index {
                    knots[j]
                } else {
                    knots[j + 1]
                }
            };
            let count = homogeneous.len() - 1;
            // Free poles: the changed ones and one more on each side (never a fixed end).
            let lowest_free = usize::from(self.ends_exact);
            let highest_free = count - 1 - usize::from(self.ends_exact);
            let free_start = removal.first.saturating_sub(1).max(lowest_free);
            let free_end = (removal.first + changed).min(highest_free);
            if free_start > free_end {
                continue;
            }
            let window_start = free_start.saturating_sub(p);
            let window_end = (free_end + p).min(count - 1);
            let window_knots: Vec<f64> = (window_start..=window_end + p + 1)
                .map(trial_knot)
                .collect();
            let (from, to) = (window_knots[p], window_knots[window_knots.len() - p - 1]);
            let first = by_parameter.partition_point(|&k| fit.parameters[k] < from);
            let last = by_parameter.partition_point(|&k| fit.parameters[k] <= to);
            let rows: Vec<usize> = by_parameter[first..last].to_vec();
            let mut window_poles: Vec<Point> = (window_start..=window_end)
                .map(|i| {
                    let h = trial_point(i);
                    [h[0], h[1], h[2]]
                })
                .collect();
            let free = free_start - window_start..free_end - window_start + 1;
            let Some(local) = self.local_refit(&window_knots, &mut window_poles, free, &rows, fit)
            else {
                continue;
            };
            // Accepted: the removal, the window's poles into the curve, the rows' parameters
            // and errors.
            apply_removal(&mut knots, &mut homogeneous, &removal);
            for (offset, pole) in window_poles.iter().enumerate() {
                homogeneous[window_start + offset] = [pole[0], pole[1], pole[2], 1.0];
            }
            for (&k, (t, e, tangent)) in rows.iter().zip(local) {
                fit.parameters[k] = t;
                fit.errors[k] = e;
                fit.tangents[k] = tangent;
            }
            by_parameter[first..last]
                .sort_by(|&a, &b| fit.parameters[a].total_cmp(&fit.parameters[b]));
            removed_any = true;
        }
        if removed_any {
            fit.knots = knots;
            fit.poles = homogeneous.iter().map(|h| [h[0], h[1], h[2]]).collect();
        }
        removed_any
    }

    /// The check of a removal on the window curve (`knots`, `poles`): first as it is, then
    /// after up to [`LOCAL_REFIT_PASSES`] refits of the `free` poles. `Some` (each row's
    /// corrected parameter, distance and tangent) when every row is within the target.
    fn local_refit(
        &self,
        knots: &[f64],
        poles: &mut [Point],
        free: std::ops::Range<usize>,
        rows: &[usize],
        fit: &Fit,
    ) -> Option<Vec<(f64, f64, Point)>> {
        let mut parameters: Vec<f64> = rows.iter().map(|&k| fit.parameters[k]).collect();
        let mut tangents: Vec<Point> = rows.iter().map(|&k| fit.tangents[k]).collect();
        let mut weight = INITIAL_TANGENTIAL_WEIGHT;
        for pass in 0..=LOCAL_REFIT_PASSES {
            if pass > 0 {
                let mut trial = poles.to_vec();
                if !self.solve_free_poles(
                    knots,
                    &mut trial,
                    free.clone(),
                    rows,
                    &parameters,
                    Some(&tangents),
                    weight,
                ) {
                    return None;
                }
                poles.copy_from_slice(&trial);
                weight = (weight * 0.1).max(MIN_TANGENTIAL_WEIGHT);
            }
            let curve = Curve::from_valid_parts(
                self.p,
                Dimension::Three,
                poles.to_vec(),
                None,
                knots.to_vec(),
                KnotConvention::Full,
            );
            let m = self.points.len();
            let mut within = true;
            let mut results = Vec::with_capacity(rows.len());
            for (row, &k) in rows.iter().enumerate() {
                let fixed = self.ends_exact && (k == 0 || k == m - 1);
                let start = parameters[row].clamp(curve.domain().0, curve.domain().1);
                let (t, e, tangent) = if fixed {
                    let e = distance(curve.point_unchecked(start), self.points[k]);
                    (start, e, tangents[row])
                } else {
                    self.correct(&curve, self.points[k], start)
                };
                within &= e <= self.target;
                parameters[row] = t;
                tangents[row] = tangent;
                results.push((t, e, tangent));
            }
            if within {
                return Some(results);
            }
        }
        None
    }
}

/// The curve of degree `spec.degree` within `spec.tolerance` of every point, with as few
/// control points as the method manages (module docs).
///
/// Rules: `1 <= p <=` the limit; at least `p + 1` points; not all coincident; `τ` finite and
/// at least [`APPROXIMATION_TOLERANCE_FLOOR`] times the largest coordinate magnitude; at most
/// `limits.max_control_points` control points.
pub fn approximate(
    points: &PointSet,
    spec: &ApproximationSpec,
    limits: &CurveLimits,
) -> Result<Approximation, ApproximationError> {
    let p = spec.degree;
    if p < 1 {
        return Err(ApproximationError::DegreeTooLow);
    }
    let max_degree = limits.max_degree.min(MAX_DEGREE);
    if p > max_degree {
        return Err(ApproximationError::DegreeTooHigh {
            degree: p,
            max: max_degree,
        });
    }
    let tolerance = spec.tolerance;
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(ApproximationError::InvalidTolerance);
    }
    let magnitude = points.magnitude();
    let floor = APPROXIMATION_TOLERANCE_FLOOR * magnitude;
    if tolerance < floor {
        return Err(ApproximationError::ToleranceBelowFloor { tolerance, floor });
    }
    let m = points.len();
    if m < p + 1 {
        return Err(PointsError::TooFewPoints {
            count: m,
            needed: p + 1,
            reason: format!(" for degree {p} (degree + 1)"),
        }
        .into());
    }
    if p + 1 > limits.max_control_points {
        return Err(ApproximationError::TooManyControlPoints {
            max: limits.max_control_points,
        });
    }
    let parameters = points.parameters(spec.parametrization, false)?;
    let fitter = Fitter {
        points: points.points(),
        p,
        ends_exact: spec.end_points_exact,
        dimension: points.dimension(),
        target: tolerance - ROUNDING_MARGIN * magnitude,
        centre: points.centre(),
        reach: WILD_REACH * points.size(),
    };
    let start = match refine(&fitter, &parameters, limits.max_control_points) {
        Some(fit) => fit,
        None => interpolant_fit(&fitter, points, spec, limits)?,
    };
    let fit = reduce(&fitter, start);
    let curve = fitter.curve(fit.knots.clone(), fit.poles.clone());
    let (max_error, closest) = certify(&curve, points.points(), &fit);
    if max_error <= tolerance {
        return Ok(Approximation {
            curve,
            max_error,
            parameters: closest,
        });
    }
    // Not reached: every accepted curve is within the target at the points' parameters.
    let fit = interpolant_fit(&fitter, points, spec, limits)?;
    let curve = fitter.curve(fit.knots.clone(), fit.poles.clone());
    let (max_error, closest) = certify(&curve, points.points(), &fit);
    Ok(Approximation {
        curve,
        max_error,
        parameters: closest,
    })
}

/// Steps 1–3 from a single Bézier piece; `None` when the target cannot be reached with fewer
/// poles than points (or within the limit).
fn refine(fitter: &Fitter<'_>, parameters: &[f64], max_poles: usize) -> Option<Fit> {
    let p = fitter.p;
    let m = fitter.points.len();
    let mut knots = vec![0.0; p + 1];
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    for _round in 0..MAX_REFINEMENT_ROUNDS {
        // Each round starts from the points' own parameters: the feet on a poor curve are a
        // poor parametrization, and the knots go between the points' own parameters.
        let fit = fitter.fit(knots.clone(), parameters, None, true)?;
        if fit.max_error() <= fitter.target {
            return Some(fit);
        }
        let inserted = fitter.refinements(&fit, parameters);
        let poles = knots.len() - p - 1 + inserted.len();
        if inserted.is_empty() || poles >= m || poles > max_poles {
            return None;
        }
        knots.extend_from_slice(&inserted);
        knots.sort_by(f64::total_cmp);
    }
    None
}

/// Step 4: removal rounds, each followed by a refit kept when within the target.
fn reduce(fitter: &Fitter<'_>, mut fit: Fit) -> Fit {
    for _round in 0..MAX_REDUCTION_ROUNDS {
        if !fitter.removal_round(&mut fit) {
            break;
        }
        let refit = fitter.fit(
            fit.knots.clone(),
            &fit.parameters,
            Some(&fit.tangents),
            false,
        );
        if let Some(refit) = refit.filter(|refit| refit.max_error() <= fitter.target) {
            fit = refit;
        }
    }
    fit
}

/// The curve through every point as a fit (distance 0 at its parameters), the start of the
/// reduction when refinement cannot reach the target (module docs): distinct consecutive
/// points interpolated (a lower degree elevated back when fewer than `p + 1` remain), each
/// repeated point at the parameter of the one it repeats.
fn interpolant_fit(
    fitter: &Fitter<'_>,
    points: &PointSet,
    spec: &ApproximationSpec,
    limits: &CurveLimits,
) -> Result<Fit, ApproximationError> {
    let threshold = COINCIDENT_POINT_TOLERANCE * points.size();
    let mut distinct: Vec<Point> = Vec::with_capacity(points.len());
    let mut owner = Vec::with_capacity(points.len());
    for &point in points.points() {
        if distinct
            .last()
            .is_none_or(|&last| distance(last, point) > threshold)
        {
            distinct.push(point);
        }
        owner.push(distinct.len() - 1);
    }
    let dimension = points.dimension().count();
    let raw: Vec<&[f64]> = distinct.iter().map(|point| &point[..dimension]).collect();
    let set = PointSet::new(&raw, usize::MAX)?;
    let degree = spec.degree.min(set.len() - 1);
    let interpolation = interpolate(
        &set,
        &InterpolationSpec {
            degree,
            parameters: ParameterChoice::By(spec.parametrization),
            knots: None,
            end_tangents: [None, None],
            closed: false,
        },
        limits,
    )
    .map_err(|error| match error {
        super::interpolate::InterpolationError::TooManyControlPoints { max, .. } => {
            ApproximationError::TooManyControlPoints { max }
        }
        _ => ApproximationError::NonFiniteResult,
    })?;
    let mut curve = interpolation.curve;
    if degree < spec.degree {
        curve = curve
            .elevate_degree(spec.degree, limits.max_degree, limits.max_control_points)
            .map_err(|_| ApproximationError::TooManyControlPoints {
                max: limits.max_control_points,
            })?;
    }
    let parameters: Vec<f64> = owner.iter().map(|&i| interpolation.parameters[i]).collect();
    let fit = fitter.corrected(curve.knots(), curve.control_points().to_vec(), &parameters);
    Ok(fit)
}

/// Step 5: each point's distance to the curve by the closest-point search (the global
/// minimum), and the parameter there; where the search's bounded work ends above the
/// distance at the fit's own parameter (possible on wild curves), the fit's. The largest
/// distance.
fn certify(curve: &Curve, points: &[Point], fit: &Fit) -> (f64, Vec<f64>) {
    let Ok(search) = ClosestPointSearch::new(curve, None) else {
        return (fit.max_error(), fit.parameters.clone());
    };
    let mut max_error = 0.0f64;
    let parameters = points
        .iter()
        .enumerate()
        .map(|(k, &q)| {
            let closest = search.closest(q);
            let (parameter, found) = if closest.distance <= fit.errors[k] {
                (closest.parameter, closest.distance)
            } else {
                (fit.parameters[k], fit.errors[k])
            };
            max_error = max_error.max(found);
            parameter
        })
        .collect();
    (max_error, parameters)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_on_a_cubic_need_one_bezier_piece() {
        let points: Vec<[f64; 2]> = (0..=40)
            .map(|i| {
                let x = i as f64 / 40.0;
                [x, x * x * x - x]
            })
            .collect();
        let set = PointSet::new(&points, 1000).unwrap();
        let result = approximate(
            &set,
            &ApproximationSpec {
                degree: 3,
                tolerance: 1e-6,
                parametrization: Parametrization::ChordLength,
                end_points_exact: true,
            },
            &CurveLimits::default(),
        )
        .unwrap();
        assert_eq!(result.curve.control_points().len(), 4);
        assert!(result.max_error <= 1e-6);
    }
}
