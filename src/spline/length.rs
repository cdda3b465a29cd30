//! Arc length `L = ∫ |s'(u)| du` over a parameter range, and the parameter at a given length.
//!
//! The speed `|s'|` is smooth inside a knot span (a square root of a polynomial, or of a
//! rational function for NURBS) but only continuous across knots, so each Bézier piece is
//! integrated on its own with 16-point Gauss–Legendre (exact for polynomials of degree 31).
//! Adaptive: each segment's error is estimated as `|G(seg) − G(left) − G(right)|` and the
//! segment with the largest estimate is halved until the estimates sum to at most
//! [`LENGTH_ESTIMATE_TARGET`] of the length. The speed has a kink where `s'` vanishes (a
//! cusp), where Gauss–Legendre converges only like `h²`; halving concentrates there. The
//! answer is guaranteed to [`LENGTH_RELATIVE_ERROR`]: the estimate of the halves' sum is
//! pessimistic (it measures the coarser rule), and the target leaves a factor of 100.
//!
//! The parameter at length `ℓ` solves `L(u) = ℓ` by Newton's method with `L'(u) = |s'(u)|`,
//! bracketed inside the accepted segment that holds `ℓ` (bisection when a step leaves the
//! bracket), where the 16-point rule on a part of the segment is at least as accurate as on
//! the segment.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::LazyLock;

use super::basis::CAP;
use super::bezier::BezierPiece;
use super::closest::ClosestPointError;
use super::curve::Curve;

/// The relative error of [`ArcLength::length`] that the service states: at most `1e-10`.
pub const LENGTH_RELATIVE_ERROR: f64 = 1e-10;

/// Refinement stops when the estimated errors sum to at most this fraction of the length.
pub const LENGTH_ESTIMATE_TARGET: f64 = 1e-12;

/// Gauss–Legendre points per segment.
const GAUSS_POINTS: usize = 16;

/// Segment halvings at most: this many per Bézier piece, plus [`EXTRA_HALVINGS`].
pub const HALVINGS_PER_PIECE: usize = 32;

/// Segment halvings allowed beyond [`HALVINGS_PER_PIECE`] per piece.
pub const EXTRA_HALVINGS: usize = 4096;

/// The range's faults are the closest-point search's (the same check, [`Curve::checked_range`]).
impl From<ClosestPointError> for LengthError {
    fn from(error: ClosestPointError) -> Self {
        match error {
            ClosestPointError::NonFiniteRange { index } => LengthError::NonFiniteRange { index },
            ClosestPointError::RangeOutsideDomain {
                index,
                value,
                domain,
            } => LengthError::RangeOutsideDomain {
                index,
                value,
                domain,
            },
            ClosestPointError::ReversedRange { lo, hi } => LengthError::ReversedRange { lo, hi },
        }
    }
}

/// Newton/bisection steps at most when solving `L(u) = ℓ`.
const MAX_INVERSE_STEPS: usize = 100;

/// Why no length is given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LengthError {
    #[error("range end {index} is not a finite number")]
    NonFiniteRange { index: usize },
    #[error("range end {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    RangeOutsideDomain {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
    #[error("the range [{lo}, {hi}] is reversed: its first value must not exceed its second")]
    ReversedRange { lo: f64, hi: f64 },
    #[error(
        "the length did not reach relative accuracy {LENGTH_RELATIVE_ERROR:e} within the work limit (estimated {estimate:e}): the curve's speed has too many kinks (cusps)"
    )]
    NotConverged { estimate: f64 },
    #[error("the curve's coordinates are too large to measure its length in double precision")]
    NonFinite,
}

/// The nodes and weights of Gauss–Legendre quadrature on `[0, 1]`, computed once by Newton's
/// method on the Legendre polynomial `P_16` (Golub–Welsch would give the same values).
static GAUSS_LEGENDRE: LazyLock<[(f64, f64); GAUSS_POINTS]> = LazyLock::new(|| {
    let n = GAUSS_POINTS;
    let mut rule = [(0.0, 0.0); GAUSS_POINTS];
    for (i, slot) in rule.iter_mut().enumerate() {
        // Tricomi's initial guess, then Newton on P_n(x) = 0 (converges in a few steps).
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 0.0;
        for _ in 0..100 {
            let (value, slope) = legendre(n, x);
            derivative = slope;
            let step = value / slope;
            x -= step;
            if step.abs() <= 1e-17 {
                break;
            }
        }
        let (_, slope) = legendre(n, x);
        if slope.is_finite() {
            derivative = slope;
        }
        let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
        // Map [-1, 1] to [0, 1].
        *slot = (0.5 * (1.0 - x), 0.5 * weight);
    }
    rule
});

/// `P_n(x)` and `P_n'(x)` by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (1.0, x);
    for k in 2..=n {
        let next = ((2 * k - 1) as f64 * x * current - (k - 1) as f64 * previous) / k as f64;
        previous = current;
        current = next;
    }
    let slope = n as f64 * (x * current - previous) / (x * x - 1.0);
    (current, slope)
}

/// The 16-point Gauss–Legendre nodes and weights on `[0, 1]` (ascending nodes' order not
/// guaranteed), for tests and callers who integrate the same way.
pub fn gauss_legendre_rule() -> &'static [(f64, f64); 16] {
    &GAUSS_LEGENDRE
}

/// The speed `|dC/ds|` of a Bézier piece at local parameter `s` (`|s'(u)| · (b − a)`), by
/// de Casteljau down to two points `X, Y`: `A = (1−s) X + s Y`, `A' = p (Y − X)`, and for a
/// rational piece `C' = (A'_xyz − C A'_w) / A_w`.
fn piece_speed(piece: &BezierPiece, s: f64) -> f64 {
    let points = piece.homogeneous();
    let p = points.len() - 1;
    let mut row = [[0.0; 4]; CAP];
    row[..=p].copy_from_slice(points);
    for level in 1..p {
        for i in 0..=p - level {
            let (a, b) = (row[i], row[i + 1]);
            row[i] = std::array::from_fn(|c| (1.0 - s) * a[c] + s * b[c]);
        }
    }
    let (x, y) = (row[0], row[1]);
    let derivative: [f64; 4] = std::array::from_fn(|c| p as f64 * (y[c] - x[c]));
    if piece.is_rational() {
        let a: [f64; 4] = std::array::from_fn(|c| (1.0 - s) * x[c] + s * y[c]);
        let w = a[3];
        let v: [f64; 3] = std::array::from_fn(|c| (derivative[c] - a[c] / w * derivative[3]) / w);
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    } else {
        let v = derivative;
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    }
}

/// `∫_{s0}^{s1} |dC/ds| ds` by the 16-point rule.
fn gauss(piece: &BezierPiece, s0: f64, s1: f64) -> f64 {
    let width = s1 - s0;
    GAUSS_LEGENDRE
        .iter()
        .map(|&(x, w)| w * piece_speed(piece, s0 + x * width))
        .sum::<f64>()
        * width
}

/// A part `[s0, s1]` of piece `piece` with its length (the sum of its halves' rule values)
/// and the estimated error of that length.
#[derive(Debug, Clone, Copy)]
struct Segment {
    piece: usize,
    s0: f64,
    s1: f64,
    /// Rule values of the two halves.
    halves: [f64; 2],
    estimate: f64,
}

impl Segment {
    fn new(piece_index: usize, piece: &BezierPiece, s0: f64, s1: f64, whole: f64) -> Segment {
        let middle = 0.5 * (s0 + s1);
        let halves = [gauss(piece, s0, middle), gauss(piece, middle, s1)];
        Segment {
            piece: piece_index,
            s0,
            s1,
            halves,
            estimate: (whole - halves[0] - halves[1]).abs(),
        }
    }

    fn length(&self) -> f64 {
        self.halves[0] + self.halves[1]
    }
}

/// Heap order: the largest estimate first.
struct ByEstimate(Segment);

impl PartialEq for ByEstimate {
    fn eq(&self, other: &Self) -> bool {
        self.0.estimate.total_cmp(&other.0.estimate) == Ordering::Equal
    }
}
impl Eq for ByEstimate {}
impl PartialOrd for ByEstimate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for ByEstimate {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.estimate.total_cmp(&other.0.estimate)
    }
}

/// The arc length of a range of a curve, with what is needed to find parameters at lengths.
#[derive(Debug, Clone)]
pub struct ArcLength {
    pieces: Vec<BezierPiece>,
    /// Accepted segments in order of parameter, with the length before each.
    segments: Vec<(Segment, f64)>,
    length: f64,
    estimate: f64,
    range: (f64, f64),
}

impl Curve {
    /// The arc length of `range` (default: the domain; ends just outside it are its ends),
    /// to relative accuracy [`LENGTH_RELATIVE_ERROR`] (module docs). A jump at a knot of
    /// multiplicity `p + 1` adds nothing (each piece is measured on its own).
    pub fn arc_length(&self, range: Option<(f64, f64)>) -> Result<ArcLength, LengthError> {
        let (lo, hi) = self.checked_range(range).map_err(LengthError::from)?;
        let pieces: Vec<BezierPiece> = self
            .bezier_pieces()
            .filter(|piece| piece.domain.1 > lo && piece.domain.0 < hi)
            .collect();
        let mut heap = BinaryHeap::with_capacity(pieces.len());
        for (index, piece) in pieces.iter().enumerate() {
            let (a, b) = piece.domain;
            let s0 = ((lo.max(a) - a) / (b - a)).clamp(0.0, 1.0);
            let s1 = ((hi.min(b) - a) / (b - a)).clamp(0.0, 1.0);
            if s1 > s0 {
                let whole = gauss(piece, s0, s1);
                heap.push(ByEstimate(Segment::new(index, piece, s0, s1, whole)));
            }
        }
        let budget = pieces
            .len()
            .saturating_mul(HALVINGS_PER_PIECE)
            .saturating_add(EXTRA_HALVINGS);
        let total = |heap: &BinaryHeap<ByEstimate>| -> (f64, f64) {
            let mut length = Neumaier::default();
            let mut estimate = 0.0;
            for segment in heap.iter() {
                length.add(segment.0.length());
                estimate += segment.0.estimate;
            }
            (length.sum(), estimate)
        };
        let (mut length, mut estimate) = total(&heap);
        let mut halvings = 0;
        // Halve the worst segments; re-sum now and then (the running sums drift by rounding).
        while estimate > LENGTH_ESTIMATE_TARGET * length && halvings < budget {
            let Some(ByEstimate(worst)) = heap.pop() else {
                break;
            };
            let piece = &pieces[worst.piece];
            let middle = 0.5 * (worst.s0 + worst.s1);
            if !(worst.s0 < middle && middle < worst.s1) {
                // No room to halve: keep it as it is.
                heap.push(ByEstimate(Segment {
                    estimate: 0.0,
                    ..worst
                }));
                estimate -= worst.estimate;
                continue;
            }
            let left = Segment::new(worst.piece, piece, worst.s0, middle, worst.halves[0]);
            let right = Segment::new(worst.piece, piece, middle, worst.s1, worst.halves[1]);
            length += left.length() + right.length() - worst.length();
            estimate += left.estimate + right.estimate - worst.estimate;
            heap.push(ByEstimate(left));
            heap.push(ByEstimate(right));
            halvings += 1;
            if halvings % 1024 == 0 {
                (length, estimate) = total(&heap);
            }
        }
        (length, estimate) = total(&heap);
        if !(length.is_finite() && estimate.is_finite()) {
            return Err(LengthError::NonFinite);
        }
        if estimate > LENGTH_RELATIVE_ERROR * length {
            return Err(LengthError::NotConverged {
                estimate: estimate / length,
            });
        }
        let mut ordered: Vec<Segment> = heap.into_iter().map(|s| s.0).collect();
        ordered.sort_by(|a, b| a.piece.cmp(&b.piece).then(a.s0.total_cmp(&b.s0)));
        let mut before = Neumaier::default();
        let segments = ordered
            .into_iter()
            .map(|segment| {
                let start = before.sum();
                before.add(segment.length());
                (segment, start)
            })
            .collect();
        Ok(ArcLength {
            pieces,
            segments,
            length,
            estimate,
            range: (lo, hi),
        })
    }
}

impl ArcLength {
    /// The length.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The estimated absolute error of the length (module docs).
    pub fn error_estimate(&self) -> f64 {
        self.estimate
    }

    /// The range measured.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }

    /// The parameter `u` in the range with `L(range.0 → u) = ℓ`, for `0 <= ℓ <= length`
    /// (clamped to it). Where the curve stands still (zero speed over an interval) the
    /// smallest such `u` of the segment is approached.
    pub fn parameter_at(&self, target: f64) -> f64 {
        let target = target.clamp(0.0, self.length);
        if self.segments.is_empty() {
            return self.range.0;
        }
        let index = self
            .segments
            .partition_point(|(segment, start)| start + segment.length() < target)
            .min(self.segments.len() - 1);
        let (segment, start) = self.segments[index];
        let piece = &self.pieces[segment.piece];
        let (a, b) = piece.domain;
        let to_parameter = |s: f64| (a + s * (b - a)).clamp(self.range.0, self.range.1);
        let remaining = target - start;
        if remaining <= 0.0 {
            return to_parameter(segment.s0);
        }
        if remaining >= segment.length() {
            return to_parameter(segment.s1);
        }
        // F(s) = ∫_{s0}^{s} speed − remaining, increasing; bracket [low, high].
        let (mut low, mut high) = (segment.s0, segment.s1);
        let mut s = low + (high - low) * remaining / segment.length();
        let tolerance = LENGTH_ESTIMATE_TARGET * self.length.max(f64::MIN_POSITIVE);
        for _ in 0..MAX_INVERSE_STEPS {
            let value = gauss(piece, segment.s0, s) - remaining;
            if value.abs() <= tolerance {
                break;
            }
            if value > 0.0 {
                high = s;
            } else {
                low = s;
            }
            let speed = piece_speed(piece, s);
            let newton = s - value / speed;
            s = if speed > 0.0 && low < newton && newton < high {
                newton
            } else {
                0.5 * (low + high)
            };
            if high - low <= 4.0 * f64::EPSILON * high.abs().max(1.0) {
                break;
            }
        }
        to_parameter(s)
    }
}

/// Neumaier's compensated sum (the length of many segments keeps full precision).
#[derive(Debug, Default, Clone, Copy)]
struct Neumaier {
    sum: f64,
    compensation: f64,
}

impl Neumaier {
    fn add(&mut self, value: f64) {
        let t = self.sum + value;
        if self.sum.abs() >= value.abs() {
            self.compensation += (self.sum - t) + value;
        } else {
            self.compensation += (value - t) + self.sum;
        }
        self.sum = t;
    }

    fn sum(&self) -> f64 {
        self.sum + self.compensation
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    #[test]
    fn the_rule_integrates_polynomials_of_degree_31_exactly() {
        let rule = gauss_legendre_rule();
        for degree in 0..=31 {
            let integral: f64 = rule.iter().map(|&(x, w)| w * x.powi(degree)).sum();
            let exact = 1.0 / (degree as f64 + 1.0);
            assert!((integral - exact).abs() < 1e-14, "degree {degree}");
        }
        // Abramowitz & Stegun, Table 25.4, n = 16: the largest node on [-1, 1] and its weight.
        let (node, weight) = rule
            .iter()
            .copied()
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .unwrap();
        assert!(((2.0 * node - 1.0) - 0.989_400_934_991_649_9).abs() < 1e-15);
        assert!((2.0 * weight - 0.027_152_459_411_754_1).abs() < 1e-15);
    }

    #[test]
    fn a_quarter_circle_has_length_pi_over_two() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let arc = Curve::new(
            2,
            &[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Some(&[1.0, w, 1.0]),
            &CurveLimits::default(),
        )
        .unwrap();
        let length = arc.arc_length(None).unwrap();
        let exact = std::f64::consts::FRAC_PI_2;
        assert!((length.length() - exact).abs() < 1e-14 * exact);
        // Half the length: the point at 45°.
        let t = length.parameter_at(exact / 2.0);
        let point = arc.point(t).unwrap();
        assert!((point[0] - w).abs() < 1e-12 && (point[1] - w).abs() < 1e-12);
    }
}
