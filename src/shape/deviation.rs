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
//! When both curves have the same knots (weight and control-point edits), the pieces are the
//! knot spans, and for polynomial curves the gap's Bézier points are those of the difference
//! of the two nets (blossoming is linear); spans where the nets agree are skipped.
//!
//! A Bernstein polynomial lies within the range of its coefficients, and its end coefficients
//! are its end values. So when every coefficient of `N - M D` is `<= 0`, the squared gap is
//! at most `M` on the whole interval. Starting from the pieces' end and midpoint values, every
//! interval that may still hold more than `M = best (1 + DEVIATION_RELATIVE_TOLERANCE)` is
//! split (de Casteljau), the split point's value raising `best`, until none may.
//!
//! Near an interior maximum a halved interval's bound tightens only with the square of its
//! width (15–17 halvings per maximum for `1e-10`). So an interval whose control polygon of
//! `N - M D` rises and then falls is split at a Newton estimate of the maximum instead
//! ([`estimate_maximum`]): both parts then hold the maximum at an end where the slope
//! vanishes, and pass the test after few more splits (one to four per solution for the
//! worked example). Where an interval is split never changes what the test certifies.
//!
//! One algorithm in one file (about 640 lines, then its unit tests), over 600 on purpose: the
//! search, its split rule and the piece extraction it inlines into fixed-size loops for
//! cubics; split apart, the pieces would only be read together.

use crate::spline::bernstein::{
    BINOMIAL, INVERSE_BINOMIAL, MAX_RATIO_DEGREE, add_square, convolve, values_and_derivatives,
};
use crate::spline::{Curve, MAX_DEGREE};

/// Relative precision of the squared deviation: the answer `d` is a distance the curves
/// really have somewhere, and no place has a squared distance above
/// `d² (1 + DEVIATION_RELATIVE_TOLERANCE)` (up to rounding, within `1e-13` of the curve's
/// size).
pub const DEVIATION_RELATIVE_TOLERANCE: f64 = 1e-10;

/// Splits of one piece at most (halved parts are then `2^-48` of it).
const MAX_DEPTH: u32 = 48;

/// Splits per call at most, which bounds the time whatever the input.
const MAX_SPLITS: usize = 4096;

/// Gaps below this fraction of the size of the control points acting on the compared
/// interval (their largest coordinate) count as zero (rounding noise).
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
    let gap = Gap {
        curve,
        moved,
        new_knots,
        p,
        // Coordinates beyond a planar curve's two are zero in both.
        coordinates: curve.dimension().count().max(moved.dimension().count()),
        lo,
        hi,
    };
    // Cubics (every shape request) get copies compiled for their exact sizes: degree 3, 4 Bézier
    // points, 7 coefficients (13 when rational, in two lanes: N and D).
    let squared = match (p, curve.is_rational() || moved.is_rational()) {
        (3, false) => maximum_squared_gap::<3, 4, 1, 7>(gap),
        (3, true) => maximum_squared_gap::<3, 4, 2, 13>(gap),
        // Degrees 4 and 5 with arrays sized for quintics: the pieces are copied on every
        // split, and with the widest size a quintic's deviation took 15% more instructions.
        (4..=5, false) => maximum_squared_gap::<0, 6, 1, 11>(gap),
        (4..=5, true) => maximum_squared_gap::<0, 6, 2, 21>(gap),
        (_, false) => maximum_squared_gap::<0, { MAX_DEGREE + 1 }, 1, { 2 * MAX_DEGREE + 1 }>(gap),
        (_, true) => maximum_squared_gap::<0, { MAX_DEGREE + 1 }, 2, { MAX_RATIO_DEGREE + 1 }>(gap),
    };
    squared.sqrt()
}

/// The curves' degree: `P`, a literal for cubics (so that the loops over the coefficients get
/// fixed trip counts), or `gap.p` when `P = 0`.
#[inline(always)]
fn degree<const P: usize>(gap: &Gap) -> usize {
    if P > 0 { P } else { gap.p }
}

/// What the search compares: `curve` with the control net of `moved` over `new_knots`, on
/// `[lo, hi]`, both of degree `p`, in `coordinates` coordinates.
#[derive(Clone, Copy)]
struct Gap<'a> {
    curve: &'a Curve,
    moved: &'a Curve,
    new_knots: &'a [f64],
    p: usize,
    coordinates: usize,
    lo: f64,
    hi: f64,
}

/// A part `[s0, s1]` of a piece in the search: the Bernstein coefficients of the squared
/// gap's `N` and, for rational curves (`L = 2`), `D` there, lanes of the first
/// `len` of `LEN` slots.
#[derive(Clone, Copy)]
struct Interval<const L: usize, const LEN: usize> {
    coefficients: [[f64; L]; LEN],
    /// Splits from the whole piece.
    depth: u32,
    /// Whether the part ends at a point where the search found a local maximum (a split at
    /// a Newton estimate), where another estimate would only find that end again.
    ends_at_estimate: bool,
}

/// `N / D` of one coefficient's lanes (`D = 1` for one lane).
#[inline(always)]
fn ratio<const L: usize>(lanes: [f64; L]) -> f64 {
    if L == 2 {
        lanes[0] / lanes[L - 1]
    } else {
        lanes[0]
    }
}

/// `N - bound D` of one coefficient's lanes.
#[inline(always)]
fn excess<const L: usize>(lanes: [f64; L], bound: f64) -> f64 {
    if L == 2 {
        lanes[0] - bound * lanes[L - 1]
    } else {
        lanes[0] - bound
    }
}

/// The squared gaps of the pieces of `[lo, hi]` as intervals of the search: one piece per
/// knot span of the common vector when both curves have the same knots (the knot vector of
/// a weight or control-point edit; pieces where both nets agree, without gap, are left out),
/// else one between consecutive values of either vector.
#[inline(always)]
fn pieces<const P: usize, const POINTS: usize, const L: usize, const LEN: usize>(
    gap: &Gap,
    stack: &mut Vec<Interval<L, LEN>>,
) {
    let Gap {
        curve,
        moved,
        new_knots,
        lo,
        hi,
        ..
    } = *gap;
    let p = degree::<P>(gap);
    let old_knots = curve.knots();
    if old_knots == new_knots {
        // The span holding `start`: the last knot `<= start` (knots are sorted, `start` lies
        // below the domain's end).
        let mut span = old_knots.partition_point(|&u| u <= lo) - 1;
        let mut start = lo;
        let (old_net, new_net) = (curve.homogeneous(), moved.homogeneous());
        loop {
            let end = old_knots[span + 1].min(hi);
            let (old, new) = (&old_net[span - p..=span], &new_net[span - p..=span]);
            if old != new {
                let piece = |net: &[[f64; 4]]| {
                    let mut points = [[0.0; 4]; POINTS];
                    curve.bezier_piece_of_net(old_knots, span, net, start, end, &mut points);
                    points
                };
                stack.push(if L == 2 {
                    rational_gap_on_piece::<P, POINTS, L, LEN>(gap, piece(old), piece(new))
                } else {
                    // Blossoming is linear in the net: the gap's points are those of the
                    // difference of the nets.
                    let mut difference = [[0.0; 4]; POINTS];
                    for (d, (o, n)) in difference.iter_mut().zip(old.iter().zip(new)) {
                        *d = std::array::from_fn(|c| o[c] - n[c]);
                    }
                    polynomial_gap_on_piece::<P, POINTS, L, LEN>(gap, piece(&difference[..=p]))
                });
            }
            if end >= hi {
                break;
            }
            start = end;
            while old_knots[span + 1] <= start {
                span += 1;
            }
        }
        return;
    }
    // Both knot vectors are sorted: merge their values inside (lo, hi), without repeats;
    // each piece between consecutive values becomes one interval of the search.
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
        stack.push(if L == 2 {
            rational_gap_on_piece::<P, POINTS, L, LEN>(gap, old, new)
        } else {
            let difference: [[f64; 4]; POINTS] =
                std::array::from_fn(|i| std::array::from_fn(|c| old[i][c] - new[i][c]));
            polynomial_gap_on_piece::<P, POINTS, L, LEN>(gap, difference)
        });
        if end >= hi {
            break;
        }
        start = end;
    }
}

/// The largest squared gap on `[lo, hi]` (module docs). `POINTS > p`; `L` lanes, 1 for
/// polynomial curves (`N`), 2 for rational ones (`N` and `D`); `LEN >=` the number of
/// coefficients (`2p + 1`, or `4p + 1` when rational).
#[inline(always)]
fn maximum_squared_gap<const P: usize, const POINTS: usize, const L: usize, const LEN: usize>(
    gap: Gap,
) -> f64 {
    let p = degree::<P>(&gap);
    debug_assert_eq!(p, gap.curve.degree());
    let len = if L == 2 { 4 * p + 1 } else { 2 * p + 1 };
    debug_assert!(p < POINTS && len <= LEN);
    let mut stack: Vec<Interval<L, LEN>> =
        Vec::with_capacity(2 * (gap.curve.knots().len() + p) + MAX_DEPTH as usize);
    pieces::<P, POINTS, L, LEN>(&gap, &mut stack);

    // Squared gaps at most this count as zero (rounding noise): relative to the largest
    // coordinate of the control points acting on [lo, hi] (the spans of lo and of hi's left
    // limit, and all between).
    let knots = gap.curve.knots();
    let first = knots.partition_point(|&u| u <= gap.lo) - 1 - p;
    let last = knots.partition_point(|&u| u < gap.hi) - 1;
    let size = gap.curve.control_points()[first..=last]
        .iter()
        .flat_map(|point| &point[..gap.coordinates])
        .fold(0.0, |size: f64, coordinate| size.max(coordinate.abs()));
    let zero = (ZERO_GAP * size) * (ZERO_GAP * size);
    // The pieces' end values and midpoint values start the search: a start near the largest
    // gap lets the pieces far below it go without a single split.
    let degree = len - 1;
    let midpoint_value = |interval: &Interval<L, LEN>| {
        // A Bernstein polynomial at s = 1/2 is Σ b_k C(d, k) / 2^d; the 2^d cancels in a ratio.
        let mut sum = [0.0; L];
        for (lanes, &binomial) in interval.coefficients[..len].iter().zip(&BINOMIAL[degree]) {
            for l in 0..L {
                sum[l] += binomial * lanes[l];
            }
        }
        ratio(sum)
            * if L == 2 {
                1.0
            } else {
                0.5f64.powi(degree as i32)
            }
    };
    let (mut best, mut best_piece) = (0.0, 0);
    for (index, interval) in stack.iter().enumerate() {
        let ends = ratio(interval.coefficients[0]).max(ratio(interval.coefficients[len - 1]));
        let value = ends.max(midpoint_value(interval));
        if value > best {
            (best, best_piece) = (value, index);
        }
    }
    // The piece with the largest start value is searched first: it most likely holds the
    // maximum, and with `best` there the others mostly pass the test without a split.
    if let Some(last) = stack.len().checked_sub(1) {
        stack.swap(best_piece, last);
    }
    let mut splits = 0;
    // Depth-first, so the stack stays short: the left part of a split is searched next.
    let Some(mut interval) = stack.pop() else {
        return best;
    };
    loop {
        let bound = best * (1.0 + DEVIATION_RELATIVE_TOLERANCE) + zero;
        // Whether the squared gap may exceed `bound`: some coefficient of N - bound D is
        // positive (NaN never is).
        let may_exceed = interval.coefficients[..len]
            .iter()
            .any(|&lanes| excess(lanes, bound) > 0.0);
        if !may_exceed || interval.depth >= MAX_DEPTH || splits >= MAX_SPLITS {
            match stack.pop() {
                Some(next) => interval = next,
                None => return best,
            }
            continue;
        }
        splits += 1;
        // Split at the local maximum when Newton finds one inside, else halve.
        let estimate = if interval.ends_at_estimate {
            None
        } else {
            estimate_maximum(&interval.coefficients, len, bound)
        };
        interval.depth += 1;
        interval.ends_at_estimate |= estimate.is_some();
        stack.push(interval);
        let right = stack.last_mut().expect("just pushed");
        split(
            &mut interval.coefficients,
            &mut right.coefficients,
            len,
            estimate.unwrap_or(0.5),
        );
        best = best.max(ratio(right.coefficients[0]));
    }
}

/// Newton steps at most for a local maximum.
const NEWTON_STEPS: usize = 6;

/// A Newton step this small (in the part's parameter) ends the iteration: the next would be
/// about its square.
const NEWTON_CONVERGED: f64 = 1e-5;

/// Estimates too close to an end of the part are left to halving.
const ESTIMATE_MARGIN: f64 = 1e-6;

/// Where in `(0, 1)` the squared gap `f = N / D` with the Bernstein coefficients
/// `coefficients` (lanes as in [`Interval`]) has a local maximum, by Newton's method on
/// `(log f)' = N'/N - D'/D` (its zeros are the critical points; at a maximum its derivative
/// is negative) from where the control polygon of the derivative of `N - bound D` crosses
/// zero; `None` when the iteration leaves the part, meets no maximum or does not settle, or
/// the largest coefficient of `N - bound D` is an end one.
///
/// A split there makes the search's bound tight to second order: each part then holds the
/// maximum at its end, where the slope vanishes, so that the Bernstein coefficients of
/// `N - M D` next to that end are `N - M D` itself, `<= 0` once `best` has the value there,
/// and the next ones fall with the square of the distance; halving alone would have to
/// narrow the part until its width squared were below the tolerance.
#[inline(always)]
fn estimate_maximum<const L: usize, const LEN: usize>(
    coefficients: &[[f64; L]; LEN],
    len: usize,
    bound: f64,
) -> Option<f64> {
    let degree = len - 1;
    // Only a control polygon of N - bound D that rises to its largest coefficient and then
    // falls (one sign change of its derivative's, hence one critical point of N - bound D)
    // gets an estimate: elsewhere halving separates the maxima first.
    let mut excesses = [0.0; LEN];
    for (value, &lanes) in excesses.iter_mut().zip(&coefficients[..len]) {
        *value = excess(lanes, bound);
    }
    let excesses = &excesses[..len];
    let largest = excesses.windows(2).take_while(|w| w[1] > w[0]).count();
    if largest == 0 || largest == degree || excesses[largest..].windows(2).any(|w| w[1] > w[0]) {
        return None;
    }
    // Start where the control polygon of the derivative crosses zero.
    let (rise, fall) = (
        excesses[largest] - excesses[largest - 1],
        excesses[largest + 1] - excesses[largest],
    );
    let mut s = (largest as f64 - 1.0 + rise / (rise - fall)) / (degree - 1) as f64;
    // Newton on the mirrored polynomials (coefficients reversed) from a start past the
    // middle, where the Horner form of the evaluation is best conditioned.
    let mirrored = s > 0.5;
    let mut oriented = *coefficients;
    if mirrored {
        oriented[..len].reverse();
        s = 1.0 - s;
    }
    for _ in 0..NEWTON_STEPS {
        let [value, slope, curvature] = values_and_derivatives(&oriented, len, s);
        // The derivative of log N - log D and its own derivative.
        let (mut q, mut q1) = (0.0, 0.0);
        for l in 0..L {
            let relative = slope[l] / value[l];
            let sign = if l == 0 { 1.0 } else { -1.0 };
            q += sign * relative;
            q1 += sign * (curvature[l] / value[l] - relative * relative);
        }
        // Not near a maximum (or NaN).
        if q1.is_nan() || q1 >= 0.0 {
            return None;
        }
        let step = q / q1;
        s -= step;
        if !(ESTIMATE_MARGIN..=1.0 - ESTIMATE_MARGIN).contains(&s) {
            return None;
        }
        if step.abs() <= NEWTON_CONVERGED {
            return Some(if mirrored { 1.0 - s } else { s });
        }
    }
    None
}

/// Splits Bernstein polynomials on `[0, 1]` (lanes as in [`Interval`], the first `len`
/// coefficients) at `s` (de Casteljau): `left` and `right` both hold the coefficients of the
/// whole; `left` gets those of `[0, s]`, `right` those of `[s, 1]`, each again on `[0, 1]`.
#[inline(always)]
fn split<const L: usize, const LEN: usize>(
    left: &mut [[f64; L]; LEN],
    right: &mut [[f64; L]; LEN],
    len: usize,
    s: f64,
) {
    // With `len` known to be `LEN` (cubics), the loops have fixed trip counts and unroll.
    if len == LEN {
        split_first(left, right, LEN, s);
    } else {
        split_first(left, right, len, s);
    }
}

/// [`split`] of the first `len` coefficients.
#[inline(always)]
fn split_first<const L: usize, const LEN: usize>(
    left: &mut [[f64; L]; LEN],
    right: &mut [[f64; L]; LEN],
    len: usize,
    s: f64,
) {
    // Indices, not iterators: the triangle of de Casteljau reads plainly and unrolls.
    #[allow(clippy::needless_range_loop)]
    for level in 1..len {
        for i in 0..len - level {
            let (a, b) = (right[i], right[i + 1]);
            right[i] = std::array::from_fn(|l| a[l] + s * (b[l] - a[l]));
        }
        left[level] = right[0];
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

/// The squared gap `N = |G|²` on a piece where the old curve minus the new one has the
/// Bézier points `gap` (polynomial curves, `D = 1`), as a search interval.
///
/// Products are formed in the scaled basis `s^k (1 - s)^(d-k)`, whose coefficients are
/// `C(d, k)` times the Bernstein ones: there a product is a plain convolution.
#[inline(always)]
fn polynomial_gap_on_piece<
    const P: usize,
    const POINTS: usize,
    const L: usize,
    const LEN: usize,
>(
    gap: &Gap,
    mut points: [[f64; 4]; POINTS],
) -> Interval<L, LEN> {
    let p = degree::<P>(gap);
    scale_points(&mut points, p);
    let mut numerator = [0.0; LEN];
    let column = |c: usize| -> [f64; POINTS] { std::array::from_fn(|i| points[i][c]) };
    for c in 0..gap.coordinates {
        add_square(&column(c)[..p + 1], &mut numerator[..2 * p + 1]);
    }
    interval(&numerator, &numerator, 2 * p + 1)
}

/// The squared gap on a piece where the old curve has the homogeneous Bézier points `old`
/// and the new one `new` (rational curves): `N = |X_old W_new - X_new W_old|²` and
/// `D = (W_old W_new)²`, products in the scaled basis as in [`polynomial_gap_on_piece`].
#[inline(always)]
fn rational_gap_on_piece<const P: usize, const POINTS: usize, const L: usize, const LEN: usize>(
    gap: &Gap,
    mut old: [[f64; 4]; POINTS],
    mut new: [[f64; 4]; POINTS],
) -> Interval<L, LEN> {
    let p = degree::<P>(gap);
    scale_points(&mut old, p);
    scale_points(&mut new, p);
    let column = |points: &[[f64; 4]; POINTS], c: usize| -> [f64; POINTS] {
        std::array::from_fn(|i| points[i][c])
    };
    let len = 4 * p + 1;
    let (mut numerator, mut denominator) = ([0.0; LEN], [0.0; LEN]);
    let (old_w, new_w) = (column(&old, 3), column(&new, 3));
    let mut cross = [0.0; LEN];
    let cross = &mut cross[..2 * p + 1];
    for c in 0..gap.coordinates {
        // X_old W_new - X_new W_old, then its square into N.
        cross.fill(0.0);
        convolve(&column(&old, c)[..p + 1], &new_w[..p + 1], cross, 1.0);
        convolve(&column(&new, c)[..p + 1], &old_w[..p + 1], cross, -1.0);
        add_square(cross, &mut numerator[..len]);
    }
    cross.fill(0.0);
    convolve(&old_w[..p + 1], &new_w[..p + 1], cross, 1.0);
    add_square(cross, &mut denominator[..len]);
    interval(&numerator, &denominator, len)
}

/// Bézier points (the first `p + 1`) to the scaled basis: `C(p, i)` times the `i`-th.
#[inline(always)]
fn scale_points<const POINTS: usize>(points: &mut [[f64; 4]; POINTS], p: usize) {
    for (point, &scale) in points.iter_mut().zip(&BINOMIAL[p][..p + 1]) {
        for value in point.iter_mut() {
            *value *= scale;
        }
    }
}

/// The search interval of a whole piece from the first `len` scaled-basis coefficients of
/// `N` and `D` (the latter unused in one lane): Bernstein coefficients, products with
/// `1 / C(d, k)`.
#[inline(always)]
fn interval<const L: usize, const LEN: usize>(
    numerator: &[f64; LEN],
    denominator: &[f64; LEN],
    len: usize,
) -> Interval<L, LEN> {
    let inverse = &INVERSE_BINOMIAL[len - 1];
    Interval {
        coefficients: std::array::from_fn(|k| {
            if k < len {
                std::array::from_fn(|l| [numerator, denominator][l][k] * inverse[k])
            } else {
                [0.0; L]
            }
        }),
        depth: 0,
        ends_at_estimate: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;
    use crate::spline::bernstein::halve;
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
