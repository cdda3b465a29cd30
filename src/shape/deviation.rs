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
//! tightens with the square of the interval's width: the first worked example takes 15 halvings.

use crate::spline::bernstein::{BINOMIAL, MAX_RATIO_DEGREE, convolve, halve, unscale};
use crate::spline::{Curve, MAX_DEGREE};

/// Relative precision of the squared deviation: the answer `d` is a distance the curves
/// really have somewhere, and no place has a squared distance above
/// `d² (1 + DEVIATION_RELATIVE_TOLERANCE)` (up to rounding, within `1e-13` of the curve's
/// size).
pub const DEVIATION_RELATIVE_TOLERANCE: f64 = 1e-10;

/// Halvings of one piece at most: its parts are then `2^-48` of it.
const MAX_DEPTH: u32 = 48;

/// Halvings per call at most, which bounds the time whatever the input (the first worked
/// example takes 15).
const MAX_HALVINGS: usize = 4096;

/// Gaps below this fraction of the control net's size count as zero (rounding noise).
const ZERO_GAP: f64 = 1e-13;

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
    max_deviation_between(curve, curve, new_knots, interval)
}

/// Largest distance `|s_old(u) - s_new(u)|` for `u` in `interval` between `curve` and
/// `moved`, a curve of the same degree and control point count (an edit of its knots, poles
/// or weights; either may be rational), certified as [`max_deviation`] is.
pub fn max_deviation_of_moved_poles(curve: &Curve, moved: &Curve, interval: (f64, f64)) -> f64 {
    debug_assert_eq!(curve.degree(), moved.degree());
    debug_assert_eq!(curve.control_points().len(), moved.control_points().len());
    max_deviation_between(curve, moved, moved.knots(), interval)
}

/// The deviation between `curve` and the control net of `moved` over `new_knots`.
fn max_deviation_between(
    curve: &Curve,
    moved: &Curve,
    new_knots: &[f64],
    interval: (f64, f64),
) -> f64 {
    let old_knots = curve.knots();
    let (p, end) = (curve.degree(), curve.control_points().len());
    // Both curves are defined on the intersection of their domains.
    let lo = interval.0.max(old_knots[p]).max(new_knots[p]);
    let hi = interval.1.min(old_knots[end]).min(new_knots[end]);
    if hi <= lo {
        return 0.0;
    }
    // Cubics (every shape request) get copies compiled for their exact sizes: 4 Bézier points,
    // 7 coefficients (13 when rational).
    let squared = match (p, curve.is_rational() || moved.is_rational()) {
        (3, false) => maximum_squared_gap::<4, 7>(curve, moved, 3, new_knots, lo, hi, false),
        (3, true) => maximum_squared_gap::<4, 13>(curve, moved, 3, new_knots, lo, hi, true),
        (p, rational) => maximum_squared_gap::<{ MAX_DEGREE + 1 }, { MAX_RATIO_DEGREE + 1 }>(
            curve, moved, p, new_knots, lo, hi, rational,
        ),
    };
    squared.sqrt()
}

/// A part `[s0, s1]` of a piece in the search: the Bernstein coefficients of `N` and `D`
/// there, the first `len` of `LEN` slots (`D` unused for polynomial curves).
#[derive(Clone, Copy)]
struct Interval<const LEN: usize> {
    numerator: [f64; LEN],
    denominator: [f64; LEN],
    /// Halvings from the whole piece.
    depth: u32,
}

/// The largest squared gap on `[lo, hi]` (module docs). `p` is the curve's degree (a literal
/// for cubics, so that the loops over the coefficients get fixed trip counts), `POINTS > p`
/// and `LEN >=` the number of coefficients (`2p + 1`, or `4p + 1` when `rational`).
#[inline(always)]
fn maximum_squared_gap<const POINTS: usize, const LEN: usize>(
    curve: &Curve,
    moved: &Curve,
    p: usize,
    new_knots: &[f64],
    lo: f64,
    hi: f64,
    rational: bool,
) -> f64 {
    debug_assert_eq!(p, curve.degree());
    let len = if rational { 4 * p + 1 } else { 2 * p + 1 };
    debug_assert!(p < POINTS && len <= LEN);
    let old_knots = curve.knots();
    // Both knot vectors are sorted: merge their values inside (lo, hi), without repeats;
    // each piece between consecutive values becomes one interval of the search.
    let mut stack: Vec<Interval<LEN>> = Vec::with_capacity(2 * (p + 2) + MAX_DEPTH as usize);
    let mut old_pieces = PieceCursor::<POINTS>::new(curve, old_knots);
    let mut new_pieces = PieceCursor::<POINTS>::new(moved, new_knots);
    let (mut i, mut k) = (0, 0);
    let mut start = lo;
    loop {
        // The piece ends at the first value of either vector above its start, or at `hi`.
        while i < old_knots.len() && old_knots[i] <= start {
            i += 1;
        }
        while k < new_knots.len() && new_knots[k] <= start {
            k += 1;
        }
        let mut end = hi;
        if let Some(&knot) = old_knots.get(i) {
            end = end.min(knot);
        }
        if let Some(&knot) = new_knots.get(k) {
            end = end.min(knot);
        }
        let old = old_pieces.next(start, end, p);
        let new = new_pieces.next(start, end, p);
        stack.push(squared_gap_on_piece::<POINTS, LEN>(
            p, old, new, len, rational,
        ));
        if end >= hi {
            break;
        }
        start = end;
    }

    let value_at = |interval: &Interval<LEN>, index: usize| {
        let numerator = interval.numerator[index];
        if rational {
            numerator / interval.denominator[index]
        } else {
            numerator
        }
    };
    // Squared gaps at most this count as zero (rounding noise).
    let size = curve
        .control_points()
        .iter()
        .flatten()
        .fold(0.0, |size: f64, coordinate| size.max(coordinate.abs()));
    let zero = (ZERO_GAP * size) * (ZERO_GAP * size);
    // The pieces' end values and midpoint values start the search: a start near the largest
    // gap lets the pieces far below it go without a single halving (a quarter fewer
    // instructions for a weight solution's deviation; samples at 1/4 and 3/4 too gained 1%).
    let degree = len - 1;
    let midpoint_value = |interval: &Interval<LEN>| {
        // A Bernstein polynomial at s = 1/2 is Σ b_k C(d, k) / 2^d; the 2^d cancels in a ratio.
        let at_half = |coefficients: &[f64; LEN]| {
            coefficients[..len]
                .iter()
                .zip(&BINOMIAL[degree][..len])
                .map(|(b, c)| b * c)
                .sum::<f64>()
        };
        let numerator = at_half(&interval.numerator);
        if rational {
            numerator / at_half(&interval.denominator)
        } else {
            numerator * 0.5f64.powi(degree as i32)
        }
    };
    let mut best = stack
        .iter()
        .map(|interval| {
            value_at(interval, 0)
                .max(value_at(interval, len - 1))
                .max(midpoint_value(interval))
        })
        .fold(0.0, f64::max);
    let mut halvings = 0;
    // Depth-first, so the stack stays short.
    while let Some(interval) = stack.pop() {
        let bound = best * (1.0 + DEVIATION_RELATIVE_TOLERANCE) + zero;
        // Whether the squared gap may exceed `bound`: some coefficient of N - bound D is
        // positive (NaN never is).
        let numerator = &interval.numerator[..len];
        let may_exceed = if rational {
            numerator
                .iter()
                .zip(&interval.denominator[..len])
                .any(|(&n, &d)| n - bound * d > 0.0)
        } else {
            numerator.iter().any(|&n| n > bound)
        };
        if !may_exceed || interval.depth >= MAX_DEPTH || halvings >= MAX_HALVINGS {
            continue;
        }
        halvings += 1;
        let (mut left, mut right) = (interval, interval);
        left.depth += 1;
        right.depth += 1;
        if rational {
            halve_pair(&interval, &mut left, &mut right, len);
        } else {
            halve(
                &interval.numerator[..len],
                &mut left.numerator[..len],
                &mut right.numerator[..len],
            );
        }
        best = best.max(value_at(&left, len - 1));
        stack.push(right);
        stack.push(left);
    }
    best
}

/// [`halve`] of the numerator and the denominator together (de Casteljau at `s = 1/2`): one
/// loop over both, which the compiler runs two lanes wide.
#[inline(always)]
fn halve_pair<const LEN: usize>(
    interval: &Interval<LEN>,
    left: &mut Interval<LEN>,
    right: &mut Interval<LEN>,
    len: usize,
) {
    let mut work: [[f64; 2]; LEN] =
        std::array::from_fn(|i| [interval.numerator[i], interval.denominator[i]]);
    left.numerator[0] = work[0][0];
    left.denominator[0] = work[0][1];
    for level in 1..len {
        for i in 0..len - level {
            let (a, b) = (work[i], work[i + 1]);
            work[i] = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        }
        left.numerator[level] = work[0][0];
        left.denominator[level] = work[0][1];
    }
    for (i, [numerator, denominator]) in work.iter().take(len).enumerate() {
        right.numerator[i] = *numerator;
        right.denominator[i] = *denominator;
    }
}

/// The Bézier pieces of one curve (a control net over one knot vector) on consecutive
/// intervals, left to right. Each knot span is extracted once, from the first interval's
/// start to the span's end (blossoming, [`Curve::bezier_span_rest_with_knots`]), and cut at
/// the ends of the intervals inside it (de Casteljau, a fraction of an extraction's cost): a
/// span of the old vector holds several pieces where the new vector has knots inside it.
struct PieceCursor<'a, const POINTS: usize> {
    curve: &'a Curve,
    knots: &'a [f64],
    /// The Bézier points of the span's rest `[start, end]`, not yet handed out.
    rest: [[f64; 4]; POINTS],
    start: f64,
    end: f64,
}

impl<'a, const POINTS: usize> PieceCursor<'a, POINTS> {
    fn new(curve: &'a Curve, knots: &'a [f64]) -> Self {
        PieceCursor {
            curve,
            knots,
            rest: [[0.0; 4]; POINTS],
            start: f64::NEG_INFINITY,
            end: f64::NEG_INFINITY,
        }
    }

    /// The Bézier points (homogeneous) of the piece `[a, b]`; `p` is the curve's degree.
    ///
    /// Preconditions: `a < b` inside one span of `knots` and inside the domain; `a` is the
    /// previous call's `b` (or the first call's start).
    #[inline(always)]
    fn next(&mut self, a: f64, b: f64, p: usize) -> [[f64; 4]; POINTS] {
        if a >= self.end {
            self.end = self
                .curve
                .bezier_span_rest_with_knots(self.knots, a, &mut self.rest);
            self.start = a;
        }
        debug_assert!(a == self.start && b <= self.end);
        if b >= self.end {
            self.start = self.end;
            return self.rest;
        }
        let mut piece = [[0.0; 4]; POINTS];
        split_bezier(
            &mut self.rest[..=p],
            (b - a) / (self.end - a),
            &mut piece[..=p],
        );
        self.start = b;
        piece
    }
}

/// Splits the Bézier curve with control points `points` at parameter `s` in `(0, 1)` (de
/// Casteljau): `left` gets the points of `[0, s]`, `points` become those of `[s, 1]`.
#[inline(always)]
fn split_bezier(points: &mut [[f64; 4]], s: f64, left: &mut [[f64; 4]]) {
    let n = points.len() - 1;
    left[0] = points[0];
    for (level, first) in left.iter_mut().enumerate().take(n + 1).skip(1) {
        for i in 0..=n - level {
            let (current, next) = (points[i], points[i + 1]);
            for c in 0..4 {
                points[i][c] = current[c] + s * (next[c] - current[c]);
            }
        }
        *first = points[0];
    }
}

/// The squared gap on a piece where the old curve has the Bézier points `old` and the new
/// one `new` (degree `p`), as a search interval: `len` Bernstein coefficients of `N` and,
/// when `rational`, of `D`.
///
/// Products are formed in the scaled basis `s^k (1 - s)^(d-k)`, whose coefficients are
/// `C(d, k)` times the Bernstein ones: there a product is a plain convolution.
#[inline(always)]
fn squared_gap_on_piece<const POINTS: usize, const LEN: usize>(
    p: usize,
    mut old: [[f64; 4]; POINTS],
    mut new: [[f64; 4]; POINTS],
    len: usize,
    rational: bool,
) -> Interval<LEN> {
    for i in 0..p + 1 {
        let scale = BINOMIAL[p][i];
        for c in 0..4 {
            old[i][c] *= scale;
            new[i][c] *= scale;
        }
    }
    let mut interval = Interval {
        numerator: [0.0; LEN],
        denominator: [0.0; LEN],
        depth: 0,
    };
    let numerator = &mut interval.numerator[..len];
    if rational {
        let column = |points: &[[f64; 4]; POINTS], c: usize| -> [f64; POINTS] {
            std::array::from_fn(|i| points[i][c])
        };
        let (old_w, new_w) = (column(&old, 3), column(&new, 3));
        let mut cross = [0.0; LEN];
        let cross = &mut cross[..2 * p + 1];
        for c in 0..3 {
            // X_old W_new - X_new W_old, then its square into N.
            cross.fill(0.0);
            convolve(&column(&old, c)[..p + 1], &new_w[..p + 1], cross, 1.0);
            convolve(&column(&new, c)[..p + 1], &old_w[..p + 1], cross, -1.0);
            convolve(cross, cross, numerator, 1.0);
        }
        cross.fill(0.0);
        convolve(&old_w[..p + 1], &new_w[..p + 1], cross, 1.0);
        let denominator = &mut interval.denominator[..len];
        convolve(cross, cross, denominator, 1.0);
        unscale(denominator);
    } else {
        for c in 0..3 {
            let gap: [f64; POINTS] = std::array::from_fn(|i| old[i][c] - new[i][c]);
            convolve(&gap[..p + 1], &gap[..p + 1], numerator, 1.0);
        }
    }
    unscale(&mut interval.numerator[..len]);
    interval
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

    /// The control net of the first worked example (`tests/data/examples.json`, docs/method.md §10).
    const PLANAR_NET: [&[f64]; 8] = [
        &[0.0, 0.0],
        &[1.0, 3.0],
        &[3.0, 4.0],
        &[5.0, 3.5],
        &[6.0, 1.0],
        &[8.0, 0.0],
        &[9.0, 2.0],
        &[10.0, 4.0],
    ];

    #[test]
    fn unchanged_knots_deviate_nowhere() {
        let c = curve(
            3,
            &PLANAR_NET[..5],
            &[0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            None,
        );
        assert_eq!(max_deviation(&c, c.knots(), c.domain()), 0.0);
    }

    #[test]
    fn planar_cubic_matches_brute_force() {
        let c = curve(
            3,
            &PLANAR_NET,
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
    fn a_split_bezier_curve_keeps_its_points() {
        // A cubic in four coordinates, split at 0.3: the parts, evaluated in Bernstein form,
        // must trace the whole on [0, 0.3] and [0.3, 1].
        let whole = [
            [0.0, 1.0, -2.0, 1.0],
            [3.0, 4.0, 0.5, 2.0],
            [-1.0, 2.5, 7.0, 0.5],
            [5.0, -3.0, 1.0, 1.5],
        ];
        let evaluate = |points: &[[f64; 4]; 4], s: f64| -> [f64; 4] {
            std::array::from_fn(|c| {
                (0..4)
                    .map(|k| {
                        points[k][c]
                            * BINOMIAL[3][k]
                            * s.powi(k as i32)
                            * (1.0 - s).powi(3 - k as i32)
                    })
                    .sum()
            })
        };
        let split = 0.3;
        let (mut right, mut left) = (whole, [[0.0; 4]; 4]);
        split_bezier(&mut right, split, &mut left);
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            let (on_left, on_right) = (evaluate(&left, s), evaluate(&right, s));
            let (expected_left, expected_right) = (
                evaluate(&whole, split * s),
                evaluate(&whole, split + (1.0 - split) * s),
            );
            for c in 0..4 {
                assert!(
                    (on_left[c] - expected_left[c]).abs() < 1e-13,
                    "left, s = {s}"
                );
                assert!(
                    (on_right[c] - expected_right[c]).abs() < 1e-13,
                    "right, s = {s}"
                );
            }
        }
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
