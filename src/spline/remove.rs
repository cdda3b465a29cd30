//! Knot removal within a tolerance (The NURBS Book §5.4, A5.8), with a certified bound on how
//! far the curve moves.
//!
//! Removing one occurrence of `ū` (last index `r` in the full vector `U`, multiplicity `s`)
//! from a curve with homogeneous points `P` gives the knot vector `V = U \ {u_r}` and points
//! `Q` that inserting `ū` again would turn back into `P` (Boehm, eq. 5.15):
//!
//! `P_i = α_i Q_i + (1 − α_i) Q_{i−1}`, `α_i = (ū − v_i) / (v_{i+p} − v_i)`, `i = r−p … r−s`,
//!
//! with `Q_i = P_i` for `i <= r−p−1` and `Q_i = P_{i+1}` for `i >= r−s`: `p − s + 1`
//! equations for the `p − s` points in between. They are solved from both ends towards the
//! middle (dividing by `α_i` from the left, by `1 − α_i` from the right; the meeting point
//! moves off the middle where one of them would be below 1/4), and the two values met are
//! averaged. The knot is exactly removable when they
//! agree; otherwise the curve moves, and by how much is bounded by inserting `ū` again:
//! the new curve is then written on `U` with points `P'`, and the difference of the two
//! curves is the spline with points `P − P'` (non-zero only for `i = r−p−1 … r−s+1`), so
//!
//! * non-rational: `|C(u) − C'(u)| <= max_i |P_i − P'_i|` (the basis functions are a
//!   partition of unity);
//! * rational, with `A, W` the homogeneous numerator and weight, any centre `c`:
//!   `C − C' = [(A − cW) − (A' − cW') − (C' − c)(W − W')] / W`, so
//!   `|C − C'| <= (max_i |ΔA_i − c Δw_i| + R max_i |Δw_i|) / w_min`, `R` the largest
//!   distance from `c` of the new curve's control points that reach the changed part, `w_min`
//!   the smallest weight there.
//!
//! The bound of one removal orders the candidates (cheapest first), except that those within
//! the rounding allowance (removable at tolerance 0) come before the rest with the longest
//! run of equal knots first: a knot inserted `m` times next to a knot of the curve can make
//! that knot removable within rounding too (its removal then changes the curve only on tiny
//! spans), and taking it first would leave copies of the inserted one that no longer come
//! out. Whether a removal is made is decided against the original curve, so that the bounds of successive removals do
//! not add up: on each original knot span that the removal changes, the Bézier pieces of the
//! original and of the new curve are compared, the same bounds applied to their Bernstein
//! coefficients (the Bernstein polynomials are a partition of unity too), the pair halved by
//! de Casteljau while the bound exceeds the tolerance. A removal is made when every span it
//! reaches stays within the tolerance (plus the rounding allowance of
//! [`Curve::removal_allowance`], which is what tolerance 0 allows); each span keeps its bound,
//! and `max_deviation` is the largest.

use smallvec::SmallVec;

use super::basis::CAP;
use super::bezier::BezierPiece;
use super::curve::{Curve, Dimension, KnotConvention};
use super::vector::Point;

/// Rounding allowance of removal, relative to the curve's rounding scale
/// ([`Curve::removal_allowance`]): a knot whose certified bound is within the tolerance plus
/// this counts as removable, so that tolerance 0 removes the exactly removable knots (a knot
/// inserted `m` times comes out `m` times). Their bound is rounding, not 0: measured on 20,000
/// random insert-then-remove cases of degrees 1–7 (docs/method.md §26) it stayed below
/// `1e-13` of the scale, so the allowance leaves a factor of 10, and it is far below any
/// change of shape a caller could mean by "0".
pub const EXACT_REMOVAL_ALLOWANCE: f64 = 1e-12;

/// Rounds of trying every candidate at most (a round that removes nothing ends the search).
pub const MAX_REMOVAL_ROUNDS: usize = 32;

/// One removal computed on a window of the control points, not yet applied.
#[derive(Debug, Clone)]
pub(crate) struct LocalRemoval {
    /// The full-vector index of the removed knot occurrence (last of its run).
    pub knot_index: usize,
    /// `Q_first …`: the new points replacing `P_first ..= P_{first + len}`.
    pub first: usize,
    pub points: SmallVec<[[f64; 4]; CAP + 1]>,
    /// Certified bound on `|C(u) − C'(u)|` (module docs).
    pub bound: f64,
    /// `[u_{r−p−1}, u_{r−s+p+2}]` (in `U`): outside it the curve does not change.
    pub changed: (f64, f64),
}

/// The last index of the run of `value` in `knots` and its multiplicity (0 when absent).
pub(crate) fn knot_run(knots: &[f64], value: f64) -> (usize, usize) {
    let end = knots.partition_point(|&u| u <= value);
    let start = knots.partition_point(|&u| u < value);
    (end.saturating_sub(1), end - start)
}

/// Computes the removal of one occurrence of the knot `knots[r]` (the last of its run, of
/// multiplicity `s`, strictly inside the domain) from the degree-`p` curve with homogeneous
/// points `points`. `None` when a new weight is not positive or a value is not finite.
pub(crate) fn local_removal(
    p: usize,
    knots: &[f64],
    points: &[[f64; 4]],
    r: usize,
    s: usize,
    rational: bool,
) -> Option<LocalRemoval> {
    let value = knots[r];
    let first = r - p - 1;
    let last = r - s;
    // α_i on V = U \ {u_r}: v_j = u_j for j < r, u_{j+1} otherwise.
    let v = |j: usize| if j < r { knots[j] } else { knots[j + 1] };
    let alpha = |i: usize| (value - v(i)) / (v(i + p) - v(i));
    let len = last - first + 1;
    // The sweeps meet in the middle of the chain (the change spreads over the interior, and
    // the ends of a clamped curve stay), but α_i falls from near 1 to near 0 along it: the
    // left sweep (dividing by α_i) may only cross equations with α_i >= 1/4, the right one
    // (dividing by 1 − α_i) those with α_i <= 3/4, so that a step at most triples the
    // rounding it inherits, even next to a multiple knot.
    let stable_left = (first + 1..=last).take_while(|&i| alpha(i) >= 0.25).count();
    let needs_left = (first + 1..=last).take_while(|&i| alpha(i) > 0.75).count();
    let middle = first + ((len - 1) / 2).clamp(needs_left, stable_left);
    let mut q: SmallVec<[[f64; 4]; CAP + 1]> = SmallVec::from_elem([0.0; 4], len);
    q[0] = points[first];
    for i in first + 1..=middle {
        let a = alpha(i);
        let previous = q[i - 1 - first];
        q[i - first] = std::array::from_fn(|c| (points[i][c] - (1.0 - a) * previous[c]) / a);
    }
    let from_left = q[middle - first];
    q[len - 1] = points[last + 1];
    let mut from_right = q[len - 1];
    for i in (middle + 1..=last).rev() {
        let a = alpha(i);
        let next = q[i - first];
        let value: [f64; 4] = std::array::from_fn(|c| (points[i][c] - a * next[c]) / (1.0 - a));
        if i - 1 == middle {
            from_right = value;
        } else {
            q[i - 1 - first] = value;
        }
    }
    // Where the sweeps meet inside the chain, the two estimates of that point are averaged.
    // When one sweep took every equation (the middle at an end of the chain), its estimate
    // of the end is the other's fixed neighbour P_first or P_{last+1}: the end stays, and the
    // mismatch is in the bound below (the curve must not change beyond its own span there).
    if first < middle && middle < last {
        q[middle - first] = std::array::from_fn(|c| 0.5 * (from_left[c] + from_right[c]));
    }
    if q.iter()
        .any(|h| h.iter().any(|x| !x.is_finite()) || h[3] <= 0.0)
    {
        return None;
    }
    // Insert ū again: P'_i for i = first ..= last + 1, compared with P_i.
    let reinserted = |i: usize| -> [f64; 4] {
        if i == first {
            q[0]
        } else if i == last + 1 {
            q[len - 1]
        } else {
            let a = alpha(i);
            std::array::from_fn(|c| a * q[i - first][c] + (1.0 - a) * q[i - 1 - first][c])
        }
    };
    let differences: SmallVec<[[f64; 4]; CAP + 2]> = (first..=last + 1)
        .map(|i| {
            let again = reinserted(i);
            std::array::from_fn(|c| points[i][c] - again[c])
        })
        .collect();
    let bound = if rational {
        rational_bound(p, points, first, last, &differences)
    } else {
        differences
            .iter()
            .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
            .fold(0.0, f64::max)
    };
    if !bound.is_finite() {
        return None;
    }
    let changed_end = (last + p + 2).min(knots.len() - 1);
    Some(LocalRemoval {
        knot_index: r,
        first,
        points: q,
        bound,
        changed: (knots[first], knots[changed_end]),
    })
}

/// The rational bound of the module docs for the differences `ΔP_i`, `i = first ..= last+1`.
fn rational_bound(
    p: usize,
    points: &[[f64; 4]],
    first: usize,
    last: usize,
    differences: &[[f64; 4]],
) -> f64 {
    let window = first.saturating_sub(p)..=(last + 1 + p).min(points.len() - 1);
    // The new curve's control points on U: P'_i = P_i outside first ..= last + 1.
    let projected = |i: usize| -> Point {
        let h = if i < first || i > last + 1 {
            points[i]
        } else {
            let d = differences[i - first];
            std::array::from_fn(|c| points[i][c] - d[c])
        };
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    };
    let mut low = [f64::INFINITY; 3];
    let mut high = [f64::NEG_INFINITY; 3];
    let mut min_weight = f64::INFINITY;
    for i in window.clone() {
        let point = projected(i);
        for c in 0..3 {
            low[c] = low[c].min(point[c]);
            high[c] = high[c].max(point[c]);
        }
        min_weight = min_weight.min(points[i][3]);
    }
    let centre: Point = std::array::from_fn(|c| 0.5 * (low[c] + high[c]));
    let radius = window
        .map(|i| {
            let point = projected(i);
            (0..3)
                .map(|c| (point[c] - centre[c]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    let mut numerator = 0.0f64;
    let mut weight = 0.0f64;
    for d in differences {
        let shifted: f64 = (0..3)
            .map(|c| (d[c] - centre[c] * d[3]).powi(2))
            .sum::<f64>()
            .sqrt();
        numerator = numerator.max(shifted);
        weight = weight.max(d[3].abs());
    }
    (numerator + radius * weight) / min_weight
}

/// Applies a computed removal to the full knot vector and the homogeneous points.
pub(crate) fn apply_removal(
    knots: &mut Vec<f64>,
    points: &mut Vec<[f64; 4]>,
    removal: &LocalRemoval,
) {
    let end = removal.first + removal.points.len();
    points.splice(removal.first..=end, removal.points.iter().copied());
    knots.remove(removal.knot_index);
}

/// The curve with full knots `knots` and homogeneous points `homogeneous` (projected; weights
/// kept when `rational`), which the caller guarantees valid.
pub(crate) fn from_homogeneous(
    degree: usize,
    dimension: Dimension,
    rational: bool,
    knots: Vec<f64>,
    homogeneous: &[[f64; 4]],
    convention: KnotConvention,
) -> Curve {
    let (points, weights) = if rational {
        (
            homogeneous
                .iter()
                .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3]])
                .collect(),
            Some(homogeneous.iter().map(|h| h[3]).collect()),
        )
    } else {
        (
            homogeneous.iter().map(|h| [h[0], h[1], h[2]]).collect(),
            None,
        )
    };
    Curve::from_valid_parts(degree, dimension, points, weights, knots, convention)
}

/// Why knots cannot be removed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RemoveError {
    #[error("the tolerance must be a finite number at least 0")]
    InvalidTolerance,
    #[error("knot value {index} is not a finite number")]
    NonFinite { index: usize },
    #[error(
        "{value} is not an interior knot of the curve (a knot value strictly inside the domain [{}, {}])",
        domain.0, domain.1
    )]
    NotAnInteriorKnot {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
}

impl RemoveError {
    /// The position in the caller's list of the value at fault, when one value is.
    pub fn index(&self) -> Option<usize> {
        match *self {
            RemoveError::InvalidTolerance => None,
            RemoveError::NonFinite { index } | RemoveError::NotAnInteriorKnot { index, .. } => {
                Some(index)
            }
        }
    }
}

/// The curve with knots removed and how far it moved.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotRemoval {
    /// The new curve, same degree, domain and knot convention.
    pub curve: Curve,
    /// The removed values, ascending, a value once per removed occurrence.
    pub removed: Vec<f64>,
    /// A certified bound on `max_u |C(u) − C'(u)|` (module docs); 0 when nothing was removed.
    pub max_deviation: f64,
}

impl Curve {
    /// Removes as many interior knots as it can while the curve moves at most `tolerance`
    /// plus [`Curve::removal_allowance`] (certified; module docs). `candidates`: the values to
    /// try, each as often as its multiplicity (a value listed twice is tried the same way);
    /// `None`: every interior knot, each as often as its multiplicity. Candidates are tried
    /// cheapest first (smallest bound), in rounds until one removes nothing
    /// ([`MAX_REMOVAL_ROUNDS`] at most).
    pub fn remove_knots(
        &self,
        tolerance: f64,
        candidates: Option<&[f64]>,
    ) -> Result<KnotRemoval, RemoveError> {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(RemoveError::InvalidTolerance);
        }
        let p = self.degree();
        let (_, hi) = self.domain();
        let original = self.knots();
        let budgets = self.removal_budgets(candidates)?;
        let allowance = self.removal_allowance();
        let limit = tolerance + allowance;
        // Each original span's certified bound of the current curve against the original,
        // from their Bézier pieces there.
        let original_pieces: Vec<BezierPiece> = self.bezier_pieces().collect();
        let breaks: Vec<f64> = original_pieces
            .iter()
            .map(|piece| piece.domain.0)
            .chain(std::iter::once(hi))
            .collect();
        let mut span_bounds = vec![0.0f64; original_pieces.len()];
        let mut knots = original.to_vec();
        let mut points = self.homogeneous().to_vec();
        let mut budgets = budgets;
        let mut removed = Vec::new();
        let rational = self.is_rational();
        let mut trial_bounds: Vec<f64> = Vec::new();
        for _round in 0..MAX_REMOVAL_ROUNDS {
            let mut order: Vec<(f64, usize, usize)> = budgets
                .iter()
                .enumerate()
                .filter(|(_, (_, left))| *left > 0)
                .filter_map(|(index, &(value, _))| {
                    let (r, s) = knot_run(&knots, value);
                    (s > 0)
                        .then(|| local_removal(p, &knots, &points, r, s, rational))
                        .flatten()
                        .map(|t| (t.bound, s, index))
                })
                .collect();
            // Within the allowance (rounding) the longest run first, then the smallest bound
            // (module docs).
            order.sort_by(|a, b| {
                let (a_exact, b_exact) = (a.0 <= allowance, b.0 <= allowance);
                b_exact
                    .cmp(&a_exact)
                    .then(if a_exact && b_exact {
                        b.1.cmp(&a.1)
                    } else {
                        std::cmp::Ordering::Equal
                    })
                    .then(a.0.total_cmp(&b.0))
            });
            let mut removed_this_round = false;
            for (_, _, index) in order {
                let value = budgets[index].0;
                while budgets[index].1 > 0 {
                    let (r, s) = knot_run(&knots, value);
                    if s == 0 {
                        break;
                    }
                    let Some(trial) = local_removal(p, &knots, &points, r, s, rational) else {
                        break;
                    };
                    let first = breaks
                        .partition_point(|&b| b <= trial.changed.0)
                        .saturating_sub(1);
                    let last = breaks
                        .partition_point(|&b| b < trial.changed.1)
                        .min(span_bounds.len());
                    let window = self.trial_window(&knots, &points, &trial);
                    trial_bounds.clear();
                    let mut within = true;
                    for piece in &original_pieces[first..last] {
                        let bound = window.deviation_from(piece, limit);
                        within &= bound <= limit;
                        if !within {
                            break;
                        }
                        trial_bounds.push(bound);
                    }
                    if !within {
                        break;
                    }
                    span_bounds[first..last].copy_from_slice(&trial_bounds);
                    apply_removal(&mut knots, &mut points, &trial);
                    budgets[index].1 -= 1;
                    removed.push(value);
                    removed_this_round = true;
                }
            }
            if !removed_this_round {
                break;
            }
        }
        removed.sort_by(f64::total_cmp);
        let max_deviation = span_bounds.iter().copied().fold(0.0, f64::max);
        let curve = self.with_homogeneous(knots, &points);
        Ok(KnotRemoval {
            curve,
            removed,
            max_deviation,
        })
    }

    /// The part of the curve after `trial` (applied to `knots`, `points`) that the removal
    /// changes: its control points from `p` before the first changed one to `p` after the
    /// last (clipped), with their knots, as a curve whose domain holds the changed part.
    fn trial_window(&self, knots: &[f64], points: &[[f64; 4]], trial: &LocalRemoval) -> Curve {
        let p = self.degree();
        let changed = trial.points.len();
        let count = points.len() - 1;
        let point = |i: usize| -> [f64; 4] {
            if i < trial.first {
                points[i]
            } else if i < trial.first + changed {
                trial.points[i - trial.first]
            } else {
                points[i + 1]
            }
        };
        let knot = |j: usize| {
            if j < trial.knot_index {
                knots[j]
            } else {
                knots[j + 1]
            }
        };
        let low = trial.first.saturating_sub(p);
        let high = (trial.first + changed - 1 + p).min(count - 1);
        let window_points: Vec<[f64; 4]> = (low..=high).map(point).collect();
        let window_knots: Vec<f64> = (low..=high + p + 1).map(knot).collect();
        from_homogeneous(
            p,
            self.dimension(),
            self.is_rational(),
            window_knots,
            &window_points,
            self.convention(),
        )
    }

    /// A certified bound of `|C(u) − C_o(u)|` on the domain of `original` (one Bézier piece of
    /// the original curve, inside this curve's domain): the two pieces' Bézier points compared
    /// (module docs' bounds, on Bernstein coefficients), both halved by de Casteljau up to
    /// [`PIECE_HALVINGS`] times while the bound exceeds `limit`.
    fn deviation_from(&self, original: &BezierPiece, limit: f64) -> f64 {
        let (a, b) = original.domain;
        let span = super::basis::find_span(self.knots(), self.degree(), 0.5 * (a + b));
        let mut out = [[0.0; 4]; CAP];
        self.bezier_piece_in_span(self.knots(), span, a, b, &mut out);
        let ours = BezierPiece::new((a, b), self.degree(), self.is_rational(), out);
        piece_bound(original, &ours, limit, PIECE_HALVINGS)
    }

    /// `(value, removals allowed)` for each distinct candidate, checked against the knots: its
    /// multiplicity (a value listed more than once counts once).
    fn removal_budgets(
        &self,
        candidates: Option<&[f64]>,
    ) -> Result<Vec<(f64, usize)>, RemoveError> {
        let (lo, hi) = self.domain();
        let knots = self.knots();
        let interior = |u: f64| lo < u && u < hi;
        let Some(values) = candidates else {
            let mut budgets: Vec<(f64, usize)> = Vec::new();
            for run in knots.chunk_by(|a, b| a == b) {
                if interior(run[0]) {
                    budgets.push((run[0], run.len()));
                }
            }
            return Ok(budgets);
        };
        let mut budgets: Vec<(f64, usize)> = Vec::new();
        for (index, &value) in values.iter().enumerate() {
            if !value.is_finite() {
                return Err(RemoveError::NonFinite { index });
            }
            let (_, multiplicity) = knot_run(knots, value);
            if !interior(value) || multiplicity == 0 {
                return Err(RemoveError::NotAnInteriorKnot {
                    index,
                    value,
                    domain: (lo, hi),
                });
            }
            if !budgets.iter().any(|(v, _)| *v == value) {
                budgets.push((value, multiplicity));
            }
        }
        Ok(budgets)
    }

    /// What tolerance 0 allows ([`EXACT_REMOVAL_ALLOWANCE`] times the rounding scale): the
    /// rounding scale is the largest control-point coordinate magnitude `M`, times
    /// `w_max / w_min` for a rational curve. The removal's arithmetic runs on the
    /// homogeneous points `(w P, w)`, whose rounding is relative to `M w_max`, and the
    /// rational bound divides by a weight (`>= w_min`); the rounding of a polynomial curve is
    /// relative to `M`. In units of the curve's size `D` (its control points' bounding-box
    /// diagonal): `M >= D / (2√3)`, so the allowance is at least `2.9e-13 D`, and for a
    /// polynomial curve around the origin (`M <= D`) at most `1e-12 D`.
    pub fn removal_allowance(&self) -> f64 {
        let magnitude = self
            .control_points()
            .iter()
            .flatten()
            .fold(0.0, |m: f64, v| m.max(v.abs()));
        let weight_ratio = self.weights().map_or(1.0, |weights| {
            let (low, high) = weights
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, h), &w| (l.min(w), h.max(w)));
            high / low
        });
        EXACT_REMOVAL_ALLOWANCE * magnitude * weight_ratio
    }

    /// A curve of the same degree, dimension and convention with other full knots and
    /// homogeneous points (valid by construction: knots taken from a valid curve).
    pub(crate) fn with_homogeneous(&self, knots: Vec<f64>, homogeneous: &[[f64; 4]]) -> Curve {
        from_homogeneous(
            self.degree(),
            self.dimension(),
            self.is_rational(),
            knots,
            homogeneous,
            self.convention(),
        )
    }
}

/// Halvings of a pair of Bézier pieces at most when their bound exceeds the limit.
pub const PIECE_HALVINGS: u32 = 3;

/// The bound of `|C_new − C_old|` on one pair of Bézier pieces over the same interval (the
/// module docs' bounds with Bernstein coefficients in place of control points), halved while
/// above `limit`.
fn piece_bound(old: &BezierPiece, new: &BezierPiece, limit: f64, halvings: u32) -> f64 {
    let (a, b) = (old.homogeneous(), new.homogeneous());
    let differences: SmallVec<[[f64; 4]; CAP]> = a
        .iter()
        .zip(b)
        .map(|(x, y)| std::array::from_fn(|c| x[c] - y[c]))
        .collect();
    let bound = if old.is_rational() {
        // C_new on the old piece's coefficients: P'_i = P_i − ΔP_i (homogeneous).
        rational_bound(0, a, 0, a.len() - 2, &differences)
    } else {
        differences
            .iter()
            .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
            .fold(0.0, f64::max)
    };
    if bound <= limit || halvings == 0 || !bound.is_finite() {
        return bound;
    }
    let middle = 0.5 * (old.domain.0 + old.domain.1);
    let (old_left, old_right) = old.split(0.5, middle);
    let (new_left, new_right) = new.split(0.5, middle);
    piece_bound(&old_left, &new_left, limit, halvings - 1).max(piece_bound(
        &old_right,
        &new_right,
        limit,
        halvings - 1,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    /// A removal whose sweeps meet at an end of the chain keeps that end's pole (the curve
    /// changes only inside the removed knot's span), and its bound is the largest pole
    /// change of the net with the knot inserted again, computed here by hand.
    #[test]
    fn a_removal_keeps_the_poles_at_the_ends_of_its_chain() {
        // Degree 1, knots 0, 0, 0.1, 1, 1: α_1 = 0.1 (below 1/4), so the right sweep takes
        // the one equation; the chain's ends P_0 and P_2 stay.
        let knots = [0.0, 0.0, 0.1, 1.0, 1.0];
        let points = [
            [0.0, 0.0, 0.0, 1.0],
            [0.1, 0.05, 0.0, 1.0],
            [1.0, 0.0, 0.0, 1.0],
        ];
        let removal = local_removal(1, &knots, &points, 2, 1, false).unwrap();
        assert_eq!(removal.first, 0);
        assert_eq!(removal.points.as_slice(), [points[0], points[2]]);
        // With 0.1 inserted again, P'_1 = 0.9 P_0 + 0.1 P_2 = (0.1, 0): P_1 moves by 0.05.
        assert!((removal.bound - 0.05).abs() < 1e-15, "{}", removal.bound);
    }

    fn cubic() -> Curve {
        let points = [
            [0.0, 0.0],
            [1.0, 2.0],
            [3.0, 3.0],
            [5.0, 1.0],
            [6.0, -1.0],
            [8.0, 0.0],
        ];
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
        Curve::new(3, &points, &knots, None, &CurveLimits::default()).unwrap()
    }

    #[test]
    fn an_inserted_knot_comes_out_exactly() {
        let curve = cubic();
        let refined = curve.insert_knots(&[0.45, 0.45], 100).unwrap();
        let removal = refined.remove_knots(0.0, Some(&[0.45, 0.45])).unwrap();
        assert_eq!(removal.removed, vec![0.45, 0.45]);
        assert!(removal.max_deviation < 1e-13, "{}", removal.max_deviation);
        for (a, b) in removal
            .curve
            .control_points()
            .iter()
            .zip(curve.control_points())
        {
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 1e-12);
            }
        }
        // The curve's own knots are not removable with tolerance 0.
        let none = curve.remove_knots(0.0, None).unwrap();
        assert!(none.removed.is_empty());
        assert_eq!(none.max_deviation, 0.0);
    }

    /// A value inserted `m` times and listed once comes out `m` times at tolerance 0; listing
    /// it again changes nothing.
    #[test]
    fn a_listed_value_is_tried_as_often_as_its_multiplicity() {
        let curve = cubic();
        let refined = curve.insert_knots(&[0.45, 0.45, 0.45, 0.8], 100).unwrap();
        for listed in [
            &[0.45, 0.8][..],
            &[0.8, 0.45, 0.45],
            &[0.45, 0.45, 0.45, 0.45, 0.8],
        ] {
            let removal = refined.remove_knots(0.0, Some(listed)).unwrap();
            assert_eq!(removal.removed, vec![0.45, 0.45, 0.45, 0.8], "{listed:?}");
            assert_eq!(removal.curve.knots(), curve.knots(), "{listed:?}");
        }
        // Only the listed values are tried.
        let removal = refined.remove_knots(0.0, Some(&[0.8])).unwrap();
        assert_eq!(removal.removed, vec![0.8]);
    }

    /// The allowance of tolerance 0, by hand: `1e-12` times the largest coordinate magnitude,
    /// times `w_max / w_min` for a rational curve.
    #[test]
    fn the_allowance_is_relative_to_the_rounding_scale() {
        let curve = cubic();
        assert_eq!(curve.removal_allowance(), EXACT_REMOVAL_ALLOWANCE * 8.0);
        let points = [[0.0, 0.0], [1.0, -3.0], [2.0, 0.5], [2.5, 1.0]];
        let knots = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
        let weights = [1.0, 0.25, 2.0, 1.0];
        let rational =
            Curve::new(2, &points, &knots, Some(&weights), &CurveLimits::default()).unwrap();
        assert_eq!(
            rational.removal_allowance(),
            EXACT_REMOVAL_ALLOWANCE * 3.0 * 8.0
        );
    }

    #[test]
    fn candidates_must_be_interior_knots() {
        let curve = cubic();
        assert!(matches!(
            curve.remove_knots(0.1, Some(&[0.5])),
            Err(RemoveError::NotAnInteriorKnot { index: 0, .. })
        ));
        assert!(matches!(
            curve.remove_knots(0.1, Some(&[0.3, 0.6, 0.7])),
            Err(RemoveError::NotAnInteriorKnot { index: 2, .. })
        ));
        assert!(matches!(
            curve.remove_knots(0.1, Some(&[0.0])),
            Err(RemoveError::NotAnInteriorKnot { .. })
        ));
        assert_eq!(
            curve.remove_knots(0.1, Some(&[0.3, f64::NAN])),
            Err(RemoveError::NonFinite { index: 1 })
        );
        assert_eq!(
            curve.remove_knots(-1.0, None),
            Err(RemoveError::InvalidTolerance)
        );
    }
}
