//! How far a knot change moves the curve: the largest distance between a curve and the same
//! control net over new knots, certified by Bernstein branch and bound.
//!
//! Between consecutive knots of the old and the new vector both curves are single polynomial
//! (or rational) pieces. On such a piece `[a, b]`, with `s = (u - a) / (b - a)`, the squared
//! gap `|s_old(u) - s_new(u)|²` is a ratio `N(s) / D(s)` of polynomials, both held in Bernstein
//! form on `[0, 1]`:
//!
//! * polynomial curves: `N = |B_old - B_new|²` (degree `2p`) and `D = 1`;
//! * rational curves, homogeneous `A = (w x, w y, w z, w)` = `(X, W)`:
//!   `N = |X_old W_new - X_new W_old|²` and `D = (W_old W_new)²` (degree `4p`, `D > 0`).
//!
//! A Bernstein polynomial lies within the range of its coefficients, and its end coefficients
//! are its end values. So when every coefficient of `N - M D` is `<= 0`, the squared gap is
//! at most `M` on the whole interval. Starting from the pieces' end values, every interval
//! that may still hold more than `M = best (1 + DEVIATION_RELATIVE_TOLERANCE)` is halved (de
//! Casteljau), its midpoint value raising `best`, until none may. Near a maximum the bound
//! tightens with the square of the interval's width, so a maximum takes some 20 halvings.

use crate::spline::{Curve, MAX_DEGREE};

/// Relative precision of the squared deviation: the answer `d` is a distance the curves
/// really have somewhere, and no place has a squared distance above
/// `d² (1 + DEVIATION_RELATIVE_TOLERANCE)` (up to rounding, within `1e-13` of the curve's
/// size).
pub const DEVIATION_RELATIVE_TOLERANCE: f64 = 1e-10;

/// Halvings of one piece at most: its parts are then `2^-48` of it.
const MAX_DEPTH: u32 = 48;

/// Halvings per call at most, which bounds the time whatever the input; a maximum typically
/// takes 20 to 40 of them.
const MAX_HALVINGS: usize = 4096;

/// Gaps below this fraction of the control net's size count as zero (rounding noise).
const ZERO_GAP: f64 = 1e-13;

/// Largest degree of the polynomials `N` and `D`: `4p` for rational curves.
const MAX_RATIO_DEGREE: usize = 4 * MAX_DEGREE;

/// `BINOMIAL[n][k] = C(n, k)` for `n <= MAX_RATIO_DEGREE`, by Pascal's triangle.
static BINOMIAL: [[f64; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1] = pascal_triangle();

const fn pascal_triangle() -> [[f64; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1] {
    let mut table = [[0.0; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1];
    let mut n = 0;
    while n <= MAX_RATIO_DEGREE {
        table[n][0] = 1.0;
        let mut k = 1;
        while k <= n {
            table[n][k] = table[n - 1][k - 1] + table[n - 1][k];
            k += 1;
        }
        n += 1;
    }
    table
}

/// Largest distance `|s_old(u) - s_new(u)|` for `u` in `interval` (outside it the two curves
/// agree) and in both curves' domains, where `s_old` is `curve` and `s_new` has the same
/// control net (and weights) over the full knot vector `new_knots`.
///
/// Certified (module docs): the result is attained, and it is the maximum to within a
/// relative [`DEVIATION_RELATIVE_TOLERANCE`]`/2`, unless the search's bounded budget runs out
/// first (then it is still an attained distance, a bound from below).
///
/// Preconditions: `new_knots` is a full, non-decreasing knot vector of `curve`'s length with
/// a non-empty domain.
pub fn max_deviation(curve: &Curve, new_knots: &[f64], interval: (f64, f64)) -> f64 {
    let old_knots = curve.knots();
    let (p, end) = (curve.degree(), curve.control_points().len());
    // Both curves are defined on the intersection of their domains.
    let lo = interval.0.max(old_knots[p]).max(new_knots[p]);
    let hi = interval.1.min(old_knots[end]).min(new_knots[end]);
    if hi <= lo {
        return 0.0;
    }
    let mut gaps = SquaredGaps::new(curve);
    // Both knot vectors are sorted: merge their values inside (lo, hi), without repeats.
    let (mut i, mut k) = (0, 0);
    let mut start = lo;
    while i < old_knots.len() || k < new_knots.len() {
        let next = if k >= new_knots.len() || (i < old_knots.len() && old_knots[i] <= new_knots[k])
        {
            i += 1;
            old_knots[i - 1]
        } else {
            k += 1;
            new_knots[k - 1]
        };
        if next > start && next < hi {
            gaps.push_piece(curve, new_knots, start, next);
            start = next;
        }
    }
    gaps.push_piece(curve, new_knots, start, hi);
    gaps.maximum().sqrt()
}

/// The squared gap on every piece, as Bernstein coefficients of `N` (then of `D`, for
/// rational curves), and the branch-and-bound search for its maximum.
struct SquaredGaps {
    /// Degree of the curves.
    degree: usize,
    /// Whether the curves are rational (then `D` is stored after `N`).
    rational: bool,
    /// Number of coefficients of `N` (and of `D`): `2p + 1`, or `4p + 1` when rational.
    len: usize,
    /// Per piece: `N`'s coefficients, then `D`'s when rational.
    pieces: Vec<f64>,
    /// Squared gaps at most this count as zero: `(ZERO_GAP · net size)²`.
    zero: f64,
}

impl SquaredGaps {
    fn new(curve: &Curve) -> Self {
        let degree = curve.degree();
        let rational = curve.is_rational();
        let len = if rational {
            4 * degree + 1
        } else {
            2 * degree + 1
        };
        let size = curve
            .control_points()
            .iter()
            .flatten()
            .fold(0.0, |size: f64, coordinate| size.max(coordinate.abs()));
        SquaredGaps {
            degree,
            rational,
            len,
            pieces: Vec::with_capacity(len * (if rational { 2 } else { 1 }) * (2 * degree + 4)),
            zero: (ZERO_GAP * size) * (ZERO_GAP * size),
        }
    }

    /// Entries per piece (and per search interval): `N`, then `D` when rational.
    fn stride(&self) -> usize {
        if self.rational {
            2 * self.len
        } else {
            self.len
        }
    }

    /// Adds the piece `[a, b]` (inside one span of both knot vectors).
    ///
    /// Products are formed in the scaled basis `s^k (1 - s)^(d-k)`, whose coefficients are
    /// `C(d, k)` times the Bernstein ones: there a product is a plain convolution.
    fn push_piece(&mut self, curve: &Curve, new_knots: &[f64], a: f64, b: f64) {
        let p = self.degree;
        let mut old = [[0.0; 4]; MAX_DEGREE + 1];
        let mut new = [[0.0; 4]; MAX_DEGREE + 1];
        curve.bezier_piece_with_knots(curve.knots(), a, b, &mut old);
        curve.bezier_piece_with_knots(new_knots, a, b, &mut new);
        for i in 0..=p {
            let scale = BINOMIAL[p][i];
            for c in 0..4 {
                old[i][c] *= scale;
                new[i][c] *= scale;
            }
        }
        let start = self.pieces.len();
        self.pieces.resize(start + self.stride(), 0.0);
        let (numerator, denominator) = self.pieces[start..].split_at_mut(self.len);
        if self.rational {
            let column = |points: &[[f64; 4]], c: usize| -> [f64; MAX_DEGREE + 1] {
                std::array::from_fn(|i| points[i][c])
            };
            let (old_w, new_w) = (column(&old, 3), column(&new, 3));
            let mut cross = [0.0; 2 * MAX_DEGREE + 1];
            let cross = &mut cross[..=2 * p];
            for c in 0..3 {
                // X_old W_new - X_new W_old, then its square into N.
                cross.fill(0.0);
                convolve(&column(&old, c)[..=p], &new_w[..=p], cross, 1.0);
                convolve(&column(&new, c)[..=p], &old_w[..=p], cross, -1.0);
                convolve(cross, cross, numerator, 1.0);
            }
            cross.fill(0.0);
            convolve(&old_w[..=p], &new_w[..=p], cross, 1.0);
            convolve(cross, cross, denominator, 1.0);
            unscale(denominator);
        } else {
            for c in 0..3 {
                let gap: [f64; MAX_DEGREE + 1] = std::array::from_fn(|i| old[i][c] - new[i][c]);
                convolve(&gap[..=p], &gap[..=p], numerator, 1.0);
            }
        }
        unscale(numerator);
    }

    /// The squared gap's value at the end `s = 0` (`first`) or `s = 1` of an interval.
    fn end_value(&self, interval: &[f64], first: bool) -> f64 {
        let index = if first { 0 } else { self.len - 1 };
        let numerator = interval[index];
        if self.rational {
            numerator / interval[self.len + index]
        } else {
            numerator
        }
    }

    /// Whether the squared gap may exceed `bound` somewhere on the interval: some coefficient
    /// of `N - bound · D` is positive. (NaN coefficients never count.)
    fn may_exceed(&self, interval: &[f64], bound: f64) -> bool {
        let (numerator, denominator) = interval.split_at(self.len);
        if self.rational {
            numerator
                .iter()
                .zip(denominator)
                .any(|(&n, &d)| n - bound * d > 0.0)
        } else {
            numerator.iter().any(|&n| n > bound)
        }
    }

    /// The largest squared gap over all pieces (module docs).
    fn maximum(mut self) -> f64 {
        let stride = self.stride();
        let mut best = self
            .pieces
            .chunks_exact(stride)
            .flat_map(|piece| [self.end_value(piece, true), self.end_value(piece, false)])
            .fold(0.0, f64::max);
        // Depth-first: a stack of intervals (their coefficients) and their depths.
        let mut stack = std::mem::take(&mut self.pieces);
        let mut depths = vec![0u32; stack.len() / stride];
        const MAX_STRIDE: usize = 2 * (MAX_RATIO_DEGREE + 1);
        let mut interval = [0.0; MAX_STRIDE];
        let (mut left, mut right) = ([0.0; MAX_STRIDE], [0.0; MAX_STRIDE]);
        let (interval, left, right) = (
            &mut interval[..stride],
            &mut left[..stride],
            &mut right[..stride],
        );
        let mut halvings = 0;
        while let Some(depth) = depths.pop() {
            let top = stack.len() - stride;
            interval.copy_from_slice(&stack[top..]);
            stack.truncate(top);
            let bound = best * (1.0 + DEVIATION_RELATIVE_TOLERANCE) + self.zero;
            if !self.may_exceed(interval, bound) || depth >= MAX_DEPTH || halvings >= MAX_HALVINGS {
                continue;
            }
            halvings += 1;
            for part in 0..stride / self.len {
                let range = part * self.len..(part + 1) * self.len;
                halve(
                    &interval[range.clone()],
                    &mut left[range.clone()],
                    &mut right[range],
                );
            }
            best = best.max(self.end_value(left, false));
            stack.extend_from_slice(right);
            stack.extend_from_slice(left);
            depths.extend([depth + 1, depth + 1]);
        }
        best
    }
}

/// `out += sign · a * b` (convolution: `out_k += sign Σ_{i+j=k} a_i b_j`), the product of two
/// polynomials in the scaled Bernstein basis; `out` has `a.len() + b.len() - 1` entries.
fn convolve(a: &[f64], b: &[f64], out: &mut [f64], sign: f64) {
    debug_assert_eq!(out.len(), a.len() + b.len() - 1);
    for (i, &a_i) in a.iter().enumerate() {
        let a_i = sign * a_i;
        for (product, &b_j) in out[i..].iter_mut().zip(b) {
            *product += a_i * b_j;
        }
    }
}

/// Scaled-basis coefficients (`C(d, k)` times the Bernstein ones) to Bernstein coefficients.
fn unscale(coefficients: &mut [f64]) {
    let degree = coefficients.len() - 1;
    for (k, value) in coefficients.iter_mut().enumerate() {
        *value /= BINOMIAL[degree][k];
    }
}

/// Splits a Bernstein polynomial on `[0, 1]` at `1/2` (de Casteljau): `left` and `right` get
/// the coefficients of its halves, each again on `[0, 1]`.
fn halve(coefficients: &[f64], left: &mut [f64], right: &mut [f64]) {
    let n = coefficients.len() - 1;
    right.copy_from_slice(coefficients);
    left[0] = coefficients[0];
    for (level, first) in left.iter_mut().enumerate().skip(1) {
        for i in 0..=n - level {
            right[i] = 0.5 * (right[i] + right[i + 1]);
        }
        *first = right[0];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;
    use crate::spline::vector::distance;

    fn curve(degree: usize, points: &[&[f64]], knots: &[f64], weights: Option<&[f64]>) -> Curve {
        let points: Vec<Vec<f64>> = points.iter().map(|p| p.to_vec()).collect();
        Curve::new(degree, &points, knots, weights, &CurveLimits::default()).unwrap()
    }

    /// The largest gap by brute force with the spline evaluator: 20 000 uniform samples, then
    /// golden-section search around the best one (independent of the Bernstein bounds).
    fn brute_force(old: &Curve, new: &Curve) -> f64 {
        let (lo, hi) = old.domain();
        let gap = |u: f64| distance(old.point(u).unwrap(), new.point(u).unwrap());
        let count = 20_000;
        let step = (hi - lo) / count as f64;
        let best = (0..=count)
            .map(|i| lo + step * i as f64)
            .max_by(|&a, &b| gap(a).total_cmp(&gap(b)))
            .unwrap();
        let (mut left, mut right) = ((best - step).max(lo), (best + step).min(hi));
        for _ in 0..80 {
            let (a, b) = (left + (right - left) / 3.0, right - (right - left) / 3.0);
            if gap(a) < gap(b) { left = a } else { right = b }
        }
        gap(0.5 * (left + right)).max(gap(best))
    }

    fn check(old: &Curve, new_knots: &[f64]) {
        let dimension = old.dimension().count();
        let points: Vec<Vec<f64>> = old
            .control_points()
            .iter()
            .map(|p| p[..dimension].to_vec())
            .collect();
        let new = Curve::new(
            old.degree(),
            &points,
            new_knots,
            old.weights(),
            &CurveLimits::default(),
        )
        .unwrap();
        let expected = brute_force(old, &new);
        let found = max_deviation(old, new_knots, old.domain());
        assert!(
            (found - expected).abs() <= 1e-9 * expected.max(1.0),
            "certified {found} vs brute force {expected}"
        );
    }

    #[test]
    fn unchanged_knots_deviate_nowhere() {
        let c = curve(
            3,
            &[
                &[0.0, 0.0],
                &[1.0, 3.0],
                &[3.0, 4.0],
                &[5.0, 3.5],
                &[6.0, 1.0],
            ],
            &[0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            None,
        );
        assert_eq!(max_deviation(&c, c.knots(), c.domain()), 0.0);
    }

    #[test]
    fn planar_cubic_matches_brute_force() {
        let c = curve(
            3,
            &[
                &[0.0, 0.0],
                &[1.0, 3.0],
                &[3.0, 4.0],
                &[5.0, 3.5],
                &[6.0, 1.0],
                &[8.0, 0.0],
                &[9.0, 2.0],
                &[10.0, 4.0],
            ],
            &[0.0, 0.0, 0.0, 0.0, 0.2, 0.35, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0],
            None,
        );
        check(
            &c,
            &[0.0, 0.0, 0.0, 0.0, 0.3, 0.42, 0.6, 0.75, 1.0, 1.0, 1.0, 1.0],
        );
        check(
            &c,
            &[0.0, 0.0, 0.0, 0.0, 0.2, 0.21, 0.5, 0.9, 1.0, 1.0, 1.0, 1.0],
        );
    }

    #[test]
    fn rational_space_curve_matches_brute_force() {
        let c = curve(
            3,
            &[
                &[0.0, 0.0, 1.0],
                &[1.0, 3.0, -1.0],
                &[3.0, 4.0, 2.0],
                &[5.0, 3.5, 0.0],
                &[6.0, 1.0, 1.5],
                &[8.0, 0.0, -2.0],
            ],
            &[0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0],
            Some(&[1.0, 0.5, 2.5, 1.0, 0.7, 1.2]),
        );
        check(&c, &[0.0, 0.0, 0.0, 0.0, 0.45, 0.5, 1.0, 1.0, 1.0, 1.0]);
    }

    #[test]
    fn quintic_with_unclamped_knots_matches_brute_force() {
        let c = curve(
            5,
            &[
                &[0.0, 0.0],
                &[1.0, 2.0],
                &[2.0, -1.0],
                &[3.0, 3.0],
                &[4.0, 0.0],
                &[5.0, 2.0],
                &[6.0, -2.0],
                &[7.0, 1.0],
            ],
            &[
                0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3,
            ],
            None,
        );
        let mut knots = c.knots().to_vec();
        knots[6] = 0.52;
        knots[7] = 0.78;
        check(&c, &knots);
    }

    #[test]
    fn bernstein_halves_agree_with_the_whole() {
        // p(s) = 1 - 3s + 2s³ in Bernstein form on [0, 1], checked by evaluating both halves.
        let power = [1.0, -3.0, 0.0, 2.0];
        let value = |s: f64| power.iter().rev().fold(0.0, |acc, &c| acc * s + c);
        let bernstein: Vec<f64> = (0..4)
            .map(|k| {
                (0..=k)
                    .map(|m| BINOMIAL[k][m] / BINOMIAL[3][m] * power[m])
                    .sum()
            })
            .collect();
        let (mut left, mut right) = ([0.0; 4], [0.0; 4]);
        halve(&bernstein, &mut left, &mut right);
        let evaluate = |c: &[f64], s: f64| -> f64 {
            (0..4)
                .map(|k| c[k] * BINOMIAL[3][k] * s.powi(k as i32) * (1.0 - s).powi(3 - k as i32))
                .sum()
        };
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            assert!((evaluate(&left, s) - value(0.5 * s)).abs() < 1e-14);
            assert!((evaluate(&right, s) - value(0.5 + 0.5 * s)).abs() < 1e-14);
        }
    }
}
