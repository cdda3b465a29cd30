//! Evaluation of points and derivatives, one parameter at a time or in batches, as exact as
//! de Boor's algorithm (docs/method.md, "Evaluation and its accuracy").
//!
//! Every method here only forms convex combinations of the curve's (homogeneous) control
//! points and of differences of neighbouring ones, so rounding errors stay a few units in the
//! last place of the control points involved, at every parameter: span ends, spans far shorter
//! than the domain, any degree. (A power form — Taylor coefficients at a span's left knot —
//! is faster but not that accurate: its coefficients grow like `(p / width)^d`, and near the
//! far end of a short span their rounding errors cancel badly; that was the batch evaluator
//! until the third release.)
//!
//! * Single points: the basis functions of The NURBS Book's A2.2 (a triangle of products of
//!   non-negative factors), summed against the homogeneous control points.
//! * Derivatives: the active control points of the `k`-th derivative of the homogeneous curve
//!   (its hodographs, `Q^(k)_i = (p - k + 1) (Q^(k-1)_i - Q^(k-1)_{i-1}) / (u_{i+p-k+1} - u_i)`,
//!   differences of neighbouring points, The NURBS Book eq. 3.8 and A3.3) against the basis
//!   functions of degree `p - k` (A3.4), then the rational quotient rule (A4.2):
//!   `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
//! * Batches of points: every span once in Bézier form (its blossoms, as
//!   [`Curve::bezier_pieces`] computes them), then per point the Bernstein sum
//!   `Σ_i C(p, i) B_i s^i (1 - s)^(p-i)` accumulated as
//!   `a_0 = C(p, 0) B_0`, `a_i = a_{i-1} (1 - s) + s^i C(p, i) B_i` (every term non-negative
//!   weight times a control point, as in de Casteljau, but `O(p)` per point): no allocation
//!   and no span search per point beyond a check of the span used last.
//!
//! One file, not split: the single-parameter, derivative and batch paths share the span's
//! local net and the accuracy argument above, which should stay beside the code it covers
//! (about 710 lines); the rest is its unit tests.

use super::basis::{CAP, basis_functions_of_every_degree};
use super::bernstein::BINOMIAL;
use super::curve::{Curve, Dimension};
use super::vector::Point;

/// A parameter that cannot be evaluated.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum EvalError {
    /// The parameter at `index` (of the batch) is NaN or infinite.
    #[error("parameter {index} is not a finite number")]
    NonFiniteParameter { index: usize },
    /// The parameter at `index` lies outside the domain `[lo, hi]`.
    #[error("parameter {index} = {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    OutsideDomain {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
}

/// Checks that parameter `index` of a batch is finite and inside `curve`'s domain.
fn check_parameter(curve: &Curve, index: usize, t: f64) -> Result<(), EvalError> {
    if !t.is_finite() {
        return Err(EvalError::NonFiniteParameter { index });
    }
    if !curve.contains_parameter(t) {
        return Err(EvalError::OutsideDomain {
            index,
            value: t,
            domain: curve.domain(),
        });
    }
    Ok(())
}

/// The first hodograph point `factor · (w_l d_l - w_{l-1} d_{l-1})` of two neighbouring
/// control points `(d_l, w_l) = here`, `(d_{l-1}, w_{l-1}) = previous`, in homogeneous form
/// relative to `origin` (`factor = p / (u_{i+p} - u_i)`), computed from the data themselves:
/// `w_l d_l - w_{l-1} d_{l-1} = w_l (d_l - d_{l-1}) + (w_l - w_{l-1}) (d_{l-1} - O)`, so that
/// neighbouring control points close together (as beside a short span) keep every digit of
/// their difference, which the rounded products `w (d - O)` would not. Shared by the curves
/// and by each direction of a surface.
#[inline(always)]
pub(crate) fn first_hodograph_point(
    factor: f64,
    (here, w): (Point, f64),
    (previous, before): (Point, f64),
    origin: Point,
) -> [f64; 4] {
    let change = w - before;
    let mut out = [0.0; 4];
    for c in 0..3 {
        let relative = previous[c] - origin[c];
        out[c] = factor * multiply_add(w, here[c] - previous[c], change * relative);
    }
    out[3] = factor * change;
    out
}

/// A later hodograph point, `factor · (q - before)` of two neighbours of the level below
/// (`factor = (p - k + 1) / (u_{i+p-k+1} - u_i)`, The NURBS Book eq. 3.8).
#[inline(always)]
pub(crate) fn hodograph_difference(factor: f64, q: [f64; 4], before: [f64; 4]) -> [f64; 4] {
    std::array::from_fn(|c| factor * (q[c] - before[c]))
}

/// `binom(k, i)` as a float (exact for the small orders used here).
fn binomial(k: usize, i: usize) -> f64 {
    let i = i.min(k - i);
    (0..i).fold(1.0, |acc, r| acc * (k - r) as f64 / (r + 1) as f64)
}

impl Curve {
    /// The point `s(t)`. Precondition-checked: `t` must be finite and in the domain.
    pub fn point(&self, t: f64) -> Result<Point, EvalError> {
        check_parameter(self, 0, t)?;
        Ok(self.point_unchecked(t))
    }

    /// The point `s(t)` for a `t` the caller knows to be in the domain (outside it the end
    /// span's polynomial is extrapolated). No allocation.
    pub fn point_unchecked(&self, t: f64) -> Point {
        self.point_with_knots(self.knots(), t)
    }

    /// `out[k]` := the `k`-th derivative `s^(k)(t)` for `k = 0..out.len()` (`out[0]` is the
    /// point). Exact for rational curves (quotient rule, no finite differences); as accurate
    /// as de Boor's algorithm (module docs).
    pub fn derivatives(&self, t: f64, out: &mut [Point]) -> Result<(), EvalError> {
        check_parameter(self, 0, t)?;
        self.derivatives_in_span(self.span(t), t, out);
        Ok(())
    }

    /// The net of knot span `span` moved to a local origin `O` (the span's first control
    /// point, which is returned): `net[l] := (w (d - O), w)` of control point `span - p + l`,
    /// `l = 0..=p`. The curve near the span is `O + (Σ N w (d - O)) / (Σ N w)` (affine
    /// invariance), and the rounding errors of everything computed from the moved net scale
    /// with the span's extent instead of the coordinates' magnitude.
    pub(crate) fn local_net(&self, span: usize, net: &mut [[f64; 4]; CAP]) -> Point {
        let p = self.degree();
        let points = &self.control_points()[span - p..=span];
        let origin = points[0];
        for (l, (slot, point)) in net.iter_mut().zip(points).enumerate() {
            let w = self.weight(span - p + l);
            *slot = [
                w * (point[0] - origin[0]),
                w * (point[1] - origin[1]),
                w * (point[2] - origin[2]),
                w,
            ];
        }
        origin
    }

    /// [`Curve::derivatives`] by the polynomial of knot span `span` (which holds `t`, or ends
    /// at `t`: the limit from the left).
    pub(crate) fn derivatives_in_span(&self, span: usize, t: f64, out: &mut [Point]) {
        let p = self.degree();
        let knots = self.knots();
        let order = out.len().saturating_sub(1);
        let top = order.min(p);
        let mut basis = [[0.0; CAP]; CAP];
        basis_functions_of_every_degree(knots, p, span, t, &mut basis);
        // level[l]: the coefficient of N_{span-p+l, p-k} in A^(k), for l = k..=p, of the
        // curve moved to the local origin (see `local_net`).
        let mut level = [[0.0; 4]; CAP];
        let origin = self.local_net(span, &mut level);
        let mut homogeneous = [[0.0; 4]; CAP];
        let points = &self.control_points()[span - p..=span];
        for (k, value) in homogeneous.iter_mut().enumerate().take(top + 1) {
            if k == 1 {
                // The first level from the data themselves: `w_l d_l - w_{l-1} d_{l-1} =
                // w_l (d_l - d_{l-1}) + (w_l - w_{l-1}) (d_{l-1} - O)`, so that neighbouring
                // control points close together (as beside a short span) keep every digit of
                // their difference, which the rounded products `w (d - O)` would not.
                for l in (1..=p).rev() {
                    let i = span - p + l;
                    let factor = p as f64 / (knots[i + p] - knots[i]);
                    level[l] = first_hodograph_point(
                        factor,
                        (points[l], self.weight(i)),
                        (points[l - 1], self.weight(i - 1)),
                        origin,
                    );
                }
            } else if k > 1 {
                for l in (k..=p).rev() {
                    let i = span - p + l;
                    let factor = (p - k + 1) as f64 / (knots[i + p - k + 1] - knots[i]);
                    level[l] = hodograph_difference(factor, level[l], level[l - 1]);
                }
            }
            let mut sum = [0.0; 4];
            for (q, &n) in level[k..=p].iter().zip(&basis[p - k][..=p - k]) {
                for c in 0..4 {
                    sum[c] = multiply_add(n, q[c], sum[c]);
                }
            }
            *value = sum;
        }
        if self.is_rational() {
            derivative_quotients(&homogeneous[..=top], out);
        } else {
            for (k, o) in out.iter_mut().enumerate() {
                let h = if k <= top { homogeneous[k] } else { [0.0; 4] };
                *o = [h[0], h[1], h[2]];
            }
        }
        if let Some(point) = out.first_mut() {
            *point = std::array::from_fn(|c| origin[c] + point[c]);
        }
    }

    /// `count >= 2` parameters spread uniformly over the domain, both ends included exactly:
    /// `lo + i · (hi - lo) / (count - 1)`, rounded as `numpy.linspace` rounds them.
    pub fn uniform_parameters(&self, count: usize) -> impl ExactSizeIterator<Item = f64> + '_ {
        let spacing = UniformSpacing::new(self.domain(), count);
        (0..count).map(move |i| spacing.parameter(i))
    }
}

/// `count` parameters spread uniformly over `[lo, hi]`.
#[derive(Debug, Clone, Copy)]
struct UniformSpacing {
    lo: f64,
    hi: f64,
    step: f64,
    last: usize,
}

impl UniformSpacing {
    fn new((lo, hi): (f64, f64), count: usize) -> Self {
        let last = count.saturating_sub(1).max(1);
        UniformSpacing {
            lo,
            hi,
            step: (hi - lo) / last as f64,
            last,
        }
    }

    /// Parameter `i`: `i · step + lo`, and exactly `hi` for the last one (as `numpy.linspace`).
    #[inline]
    fn parameter(&self, i: usize) -> f64 {
        if i == self.last {
            self.hi
        } else {
            i as f64 * self.step + self.lo
        }
    }
}

/// `a · b + c`: one fused instruction where the target has FMA; otherwise a plain multiply and
/// add (`f64::mul_add` would call a slow software routine).
#[inline(always)]
pub(crate) fn multiply_add(a: f64, b: f64, c: f64) -> f64 {
    #[cfg(target_feature = "fma")]
    {
        a.mul_add(b, c)
    }
    #[cfg(not(target_feature = "fma"))]
    {
        a * b + c
    }
}

/// Highest degree evaluated in centred power form; above it, in Bernstein form (module docs).
pub const POWER_FORM_MAX_DEGREE: usize = 3;

/// A curve prepared for evaluating many parameters quickly and as exactly as de Boor's
/// algorithm (module docs).
///
/// For every non-empty span `[u_m, u_{m+1})` of the domain it holds a local origin `O` (the
/// span's first control point) and `p + 1` homogeneous coefficients of `A(t) = (w (C - O), w)`:
///
/// * degree `<= POWER_FORM_MAX_DEGREE`: centred power form, `A = Σ_d α_d x^d` with
///   `x = 2 (t - u_m) / (u_{m+1} - u_m) - 1 ∈ [-1, 1]` (centred on the span's middle, but
///   computed from the knot: `t - u_m` is exact, a rounded middle would be off by a unit in
///   the last place of `t`, much of a short span);
/// * above: scaled Bézier points, `A = Σ_i C(p, i) B_i s^i (1 - s)^(p-i)` with
///   `s = (t - u_m) / (u_{m+1} - u_m) ∈ [0, 1]`.
///
/// Both come from the span's Bézier points (blossoms of the net moved to `O`). Building costs
/// one blossoming per span; each point then costs a span check and `p` (power form) or `2p`
/// (Bernstein form) multiply-adds per coordinate (only the coordinates the curve has: `x, y`
/// for a planar non-rational curve).
#[derive(Debug, Clone)]
pub struct BatchEvaluator<'c> {
    curve: &'c Curve,
    /// Left knot of each non-empty span, ascending.
    starts: Vec<f64>,
    /// `ends[s] = starts[s + 1]`, and `+∞` for the last span (which also takes the domain's
    /// right end): span `s` holds `t` iff `starts[s] <= t < ends[s]`.
    ends: Vec<f64>,
    /// Per span: how its local variable is made from `t`, and its origin.
    locals: Vec<LocalFrame>,
    /// The knot index `m` of each span.
    knot_spans: Vec<usize>,
    /// `(p + 1)` coefficients per span (struct docs).
    coefficients: Vec<[f64; 4]>,
}

/// A span's local variable `(t - offset) · factor` (less 1 in the power form) and origin `O`.
#[derive(Debug, Clone, Copy)]
struct LocalFrame {
    offset: f64,
    factor: f64,
    origin: Point,
}

/// `CENTRED[p][d][j]`: the coefficient of `x^d` in the Bernstein polynomial
/// `C(p, j) s^j (1 - s)^(p-j)` with `s = (1 + x) / 2`, i.e. in
/// `C(p, j) (1 + x)^j (1 - x)^(p-j) / 2^p` (exact binary fractions), for `p <= 3`.
const CENTRED: [[[f64; 4]; 4]; POWER_FORM_MAX_DEGREE + 1] = [
    [[1.0, 0.0, 0.0, 0.0], [0.0; 4], [0.0; 4], [0.0; 4]],
    [
        [0.5, 0.5, 0.0, 0.0],
        [-0.5, 0.5, 0.0, 0.0],
        [0.0; 4],
        [0.0; 4],
    ],
    [
        [0.25, 0.5, 0.25, 0.0],
        [-0.5, 0.0, 0.5, 0.0],
        [0.25, -0.5, 0.25, 0.0],
        [0.0; 4],
    ],
    [
        [0.125, 0.375, 0.375, 0.125],
        [-0.375, -0.375, 0.375, 0.375],
        [0.375, -0.375, -0.375, 0.375],
        [-0.125, 0.375, -0.375, 0.125],
    ],
];

impl<'c> BatchEvaluator<'c> {
    /// Prepares `curve` (one entry per non-empty span in the domain).
    pub fn new(curve: &'c Curve) -> Self {
        let p = curve.degree();
        let knots = curve.knots();
        let n = curve.control_points().len() - 1;
        let mut starts = Vec::new();
        let mut locals = Vec::new();
        let mut knot_spans = Vec::new();
        let mut coefficients = Vec::new();
        let mut net = [[0.0; 4]; CAP];
        let mut bezier = [[0.0; 4]; CAP];
        for span in p..=n {
            let (left, right) = (knots[span], knots[span + 1]);
            if left >= right {
                continue;
            }
            let origin = curve.local_net(span, &mut net);
            curve.bezier_piece_of_net(knots, span, &net[..=p], left, right, &mut bezier);
            let width = right - left;
            if p <= POWER_FORM_MAX_DEGREE {
                let matrix = &CENTRED[p];
                coefficients.extend((0..=p).map(|d| {
                    let mut alpha = [0.0; 4];
                    for (point, &m) in bezier[..=p].iter().zip(&matrix[d]) {
                        for c in 0..4 {
                            alpha[c] = multiply_add(m, point[c], alpha[c]);
                        }
                    }
                    alpha
                }));
                locals.push(LocalFrame {
                    offset: left,
                    factor: 2.0 / width,
                    origin,
                });
            } else {
                coefficients.extend(
                    bezier[..=p]
                        .iter()
                        .zip(&BINOMIAL[p])
                        .map(|(point, &binomial)| point.map(|c| binomial * c)),
                );
                locals.push(LocalFrame {
                    offset: left,
                    factor: 1.0 / width,
                    origin,
                });
            }
            starts.push(left);
            knot_spans.push(span);
        }
        let mut ends: Vec<f64> = starts[1..].to_vec();
        ends.push(f64::INFINITY);
        BatchEvaluator {
            curve,
            starts,
            ends,
            locals,
            knot_spans,
            coefficients,
        }
    }

    /// The curve this evaluator was built from.
    pub fn curve(&self) -> &'c Curve {
        self.curve
    }

    /// Index (into `starts`) of the span holding `t`, trying `hint` (the last one used) first.
    #[inline]
    fn locate(&self, t: f64, hint: usize) -> usize {
        if self.starts[hint] <= t && t < self.ends[hint] {
            hint
        } else {
            self.starts.partition_point(|&s| s <= t).saturating_sub(1)
        }
    }

    /// `out[i] := s(parameters[i])`; parameters in any order (ascending runs are fastest).
    /// Fails on the first parameter that is not finite or not in the domain (then `out` is
    /// partly written).
    pub fn points_into(&self, parameters: &[f64], out: &mut [Point]) -> Result<(), EvalError> {
        assert_eq!(parameters.len(), out.len(), "one output slot per parameter");
        /// Parameters checked, then evaluated, per chunk (small enough to stay in L1).
        const CHUNK: usize = 2048;
        let (lo, hi) = self.curve.domain();
        for (chunk, (parameters, out)) in parameters
            .chunks(CHUNK)
            .zip(out.chunks_mut(CHUNK))
            .enumerate()
        {
            // NaN fails both comparisons.
            if let Some(i) = parameters.iter().position(|&t| !(lo <= t && t <= hi)) {
                check_parameter(self.curve, chunk * CHUNK + i, parameters[i])?;
            }
            // Runs of parameters in one span share its coefficients.
            let mut span = 0;
            let mut first = 0;
            while first < parameters.len() {
                span = self.locate(parameters[first], span);
                let (start, end) = (self.starts[span], self.ends[span]);
                let run = parameters[first + 1..]
                    .iter()
                    .position(|&t| !(start <= t && t < end))
                    .map_or(parameters.len(), |length| first + 1 + length);
                self.dispatch(
                    span,
                    parameters[first..run].iter().copied(),
                    &mut out[first..run],
                );
                first = run;
            }
        }
        Ok(())
    }

    /// `count` uniformly spaced points over the whole domain (both ends included) into `out`
    /// (`out.len() == count >= 2`); the parameters are [`Curve::uniform_parameters`].
    pub fn uniform_points_into(&self, out: &mut [Point]) {
        let count = out.len();
        let Some(last) = count.checked_sub(1) else {
            return;
        };
        let spacing = UniformSpacing::new(self.curve.domain(), count);
        // Every parameter but the last is `i · step + lo` (the last is `hi` itself).
        let (lo, step) = (spacing.lo, spacing.step);
        let mut first = 0;
        for span in 0..self.starts.len() {
            // This span's parameters run up to the first one that reaches the next span (the
            // last span takes the rest): guessed from the spacing, then checked.
            let run = match self.starts.get(span + 1) {
                None => last,
                Some(&next) => {
                    let guess = ((next - lo) / step).floor();
                    let mut index = if guess > 0.0 {
                        (guess as usize).clamp(first, last)
                    } else {
                        first
                    };
                    while index > first && spacing.parameter(index - 1) >= next {
                        index -= 1;
                    }
                    while index < last && spacing.parameter(index) < next {
                        index += 1;
                    }
                    index
                }
            };
            // `i64` converts to a float in one instruction, `usize` does not (the values are
            // the same: `i < 2^53`).
            self.dispatch(
                span,
                (first..run).map(|i| i as i64 as f64 * step + lo),
                &mut out[first..run],
            );
            first = run;
        }
        let end = spacing.parameter(last);
        let span = self.locate(end, self.starts.len() - 1);
        self.dispatch(span, std::iter::once(end), &mut out[last..]);
    }

    /// Runs the span's kernel ([`power_form_in_span`] or [`bernstein_form_in_span`])
    /// monomorphised for the curve's kind and degree (so that the loop over the coefficients
    /// is unrolled: at degree 9 that is 1.4 times as fast as a loop bound read at run time,
    /// measured). Every parameter must lie in the span (index into `starts`).
    #[inline]
    fn dispatch(&self, span: usize, parameters: impl Iterator<Item = f64>, out: &mut [Point]) {
        let p = self.curve.degree();
        let coefficients = &self.coefficients[span * (p + 1)..(span + 1) * (p + 1)];
        let frame = self.locals[span];
        /// The kernel for `(lanes, rational)` at each degree.
        macro_rules! by_degree {
            ($lanes:literal, $rational:literal) => {
                match p {
                    1 => power_form_in_span::<$lanes, $rational, 1>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    2 => power_form_in_span::<$lanes, $rational, 2>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    3 => power_form_in_span::<$lanes, $rational, 3>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    4 => bernstein_form_in_span::<$lanes, $rational, 4>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    5 => bernstein_form_in_span::<$lanes, $rational, 5>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    6 => bernstein_form_in_span::<$lanes, $rational, 6>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    7 => bernstein_form_in_span::<$lanes, $rational, 7>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    8 => bernstein_form_in_span::<$lanes, $rational, 8>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    9 => bernstein_form_in_span::<$lanes, $rational, 9>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    10 => bernstein_form_in_span::<$lanes, $rational, 10>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    11 => bernstein_form_in_span::<$lanes, $rational, 11>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    12 => bernstein_form_in_span::<$lanes, $rational, 12>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                    _ => bernstein_form_in_span::<$lanes, $rational, 0>(
                        coefficients,
                        frame,
                        parameters,
                        out,
                    ),
                }
            };
        }
        match (self.curve.is_rational(), self.curve.dimension()) {
            (false, Dimension::Two) => by_degree!(2, false),
            (false, Dimension::Three) => by_degree!(3, false),
            (true, _) => by_degree!(4, true),
        }
    }

    /// Points and derivatives: `out[k * parameters.len() + i] := s^(k)(parameters[i])` for
    /// `k = 0..=order`, as [`Curve::derivatives`] computes them (the span found from the last
    /// one used). `out.len()` must be `(order + 1) * parameters.len()`.
    pub fn derivatives_into(
        &self,
        parameters: &[f64],
        order: usize,
        out: &mut [Point],
    ) -> Result<(), EvalError> {
        let count = parameters.len();
        assert_eq!(
            out.len(),
            (order + 1) * count,
            "one output slot per parameter and order"
        );
        let mut derivatives = [[0.0; 3]; CAP + 1];
        let mut heap = Vec::new();
        let derivatives: &mut [Point] = if order < derivatives.len() {
            &mut derivatives[..=order]
        } else {
            heap.resize(order + 1, [0.0; 3]);
            &mut heap
        };
        let mut span = 0;
        for (index, &t) in parameters.iter().enumerate() {
            check_parameter(self.curve, index, t)?;
            span = self.locate(t, span);
            self.curve
                .derivatives_in_span(self.knot_spans[span], t, derivatives);
            for (k, d) in derivatives.iter().enumerate() {
                out[k * count + index] = *d;
            }
        }
        Ok(())
    }
}

/// `O + A / w` (rational) or `O + A` of the first `LANES` homogeneous coordinates.
#[inline(always)]
fn from_local<const LANES: usize, const RATIONAL: bool>(acc: [f64; 4], origin: Point) -> Point {
    if RATIONAL {
        let w = acc[3];
        [
            origin[0] + acc[0] / w,
            origin[1] + acc[1] / w,
            origin[2] + acc[2] / w,
        ]
    } else if LANES == 2 {
        [origin[0] + acc[0], origin[1] + acc[1], 0.0]
    } else {
        [origin[0] + acc[0], origin[1] + acc[1], origin[2] + acc[2]]
    }
}

/// Evaluates `out[i] := s(t_i)` on one span in centred power form ([`BatchEvaluator`]):
/// Horner's rule on `Σ_d α_d x^d`, `x = (t - offset) · factor - 1 ∈ [-1, 1]`, for the first `LANES`
/// homogeneous coordinates (`x, y` or `x, y, z` when non-rational; all four when rational,
/// then divided by `w`), then the origin added. `DEGREE` is the degree (at most
/// [`POWER_FORM_MAX_DEGREE`]).
///
/// Why it is as exact as de Boor's algorithm at these degrees: with the local origin the Bézier
/// points `B_j` are within the diameter `δ` of the span's control points, and `α = M B` with
/// `Σ_{d,j} |M_dj| <= 5` (cubic); blossoming leaves errors `<= 4 p u δ` in the `B_j`
/// (`u = 2^-53`), Horner's rule with `|x| <= 1` adds `<= 2 p u Σ_d |α_d| <= 2 p u 2^p δ`, and
/// adding the origin `u |s(t)|`: below `110 u δ + u |s(t)|` for a cubic. De Boor's own bound
/// is `4 p u` times the control points' magnitude, so the power form is as exact wherever that
/// magnitude is more than about 10 δ, and within 1e-12 of the curve's size everywhere. The
/// form is used because it is fast: on the benchmark cubic it evaluates 1.3 times as many
/// points per second as the Bernstein form (`benches/evaluate.rs`, measured).
///
/// A free function of slices, so that the compiler knows `out` does not alias the span's
/// coefficients and keeps them in registers over the run.
#[inline(always)]
fn power_form_in_span<const LANES: usize, const RATIONAL: bool, const DEGREE: usize>(
    coefficients: &[[f64; 4]],
    frame: LocalFrame,
    parameters: impl Iterator<Item = f64>,
    out: &mut [Point],
) {
    let c = &coefficients[..=DEGREE];
    for (t, o) in parameters.zip(out.iter_mut()) {
        let x = multiply_add(t - frame.offset, frame.factor, -1.0);
        let mut acc = [0.0; 4];
        acc[..LANES].copy_from_slice(&c[DEGREE][..LANES]);
        for coefficient in c[..DEGREE].iter().rev() {
            for lane in 0..LANES {
                acc[lane] = multiply_add(acc[lane], x, coefficient[lane]);
            }
        }
        *o = from_local::<LANES, RATIONAL>(acc, frame.origin);
    }
}

/// Evaluates `out[i] := s(t_i)` on one span in Bernstein form ([`BatchEvaluator`]):
/// `s = (t - offset) · factor ∈ [0, 1]`, `r = 1 - s`, `a_0 = C(p, 0) B_0` and
/// `a_i = a_{i-1} r + s^i C(p, i) B_i`; `a_p` is the sum. Every term of it is a Bernstein
/// weight (a product of non-negative factors) times a Bézier point, so its rounding error is
/// `O(p u)` times the largest `|B_i|` (as de Casteljau's, in `O(p)` instead of `O(p²)`).
/// Lanes and origin as in [`power_form_in_span`]; `DEGREE` is the degree, or 0 for "read it
/// from `coefficients`".
#[inline(always)]
fn bernstein_form_in_span<const LANES: usize, const RATIONAL: bool, const DEGREE: usize>(
    coefficients: &[[f64; 4]],
    frame: LocalFrame,
    parameters: impl Iterator<Item = f64>,
    out: &mut [Point],
) {
    let p = if DEGREE == 0 {
        coefficients.len() - 1
    } else {
        DEGREE
    };
    let c = &coefficients[..=p];
    for (t, o) in parameters.zip(out.iter_mut()) {
        let s = (t - frame.offset) * frame.factor;
        let r = 1.0 - s;
        let mut acc = [0.0; 4];
        acc[..LANES].copy_from_slice(&c[0][..LANES]);
        let mut power = 1.0;
        for coefficient in &c[1..=p] {
            power *= s;
            for lane in 0..LANES {
                acc[lane] = multiply_add(power, coefficient[lane], acc[lane] * r);
            }
        }
        *o = from_local::<LANES, RATIONAL>(acc, frame.origin);
    }
}

/// Derivatives of the rational curve from the homogeneous ones `A^(k) = (w x, w y, w z, w)^(k)`,
/// given for `k = 0..=q` and zero beyond, into `out[0..]` (quotient rule, A4.2):
/// `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
fn derivative_quotients(homogeneous_to_p: &[[f64; 4]], out: &mut [Point]) {
    let w0 = homogeneous_to_p[0][3];
    let p = homogeneous_to_p.len() - 1;
    for k in 0..out.len() {
        let a = if k <= p {
            homogeneous_to_p[k]
        } else {
            [0.0; 4]
        };
        let mut v = [a[0], a[1], a[2]];
        for i in 1..=k.min(p) {
            let factor = binomial(k, i) * homogeneous_to_p[i][3];
            for (c, value) in v.iter_mut().enumerate() {
                *value -= factor * out[k - i][c];
            }
        }
        out[k] = [v[0] / w0, v[1] / w0, v[2] / w0];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;
    use crate::spline::vector::{cross, norm};
    use approx::assert_relative_eq;

    /// Closed-form values below are exact up to rounding.
    const TOL: f64 = 1e-13;

    #[test]
    fn binomials() {
        let row: Vec<f64> = (0..=6).map(|i| binomial(6, i)).collect();
        assert_eq!(row, [1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0]);
        assert_eq!(binomial(15, 7), 6435.0);
    }

    /// The quarter of the unit circle as a rational quadratic: `d = (1,0), (1,1), (0,1)`,
    /// `w = 1, √2/2, 1`. Every point is at distance 1 from the origin, the curvature is 1, and
    /// `s'(0) = 2 w_1/w_0 (d_1 - d_0) = (0, √2)`.
    fn quarter_circle() -> Curve {
        let points = [vec![1.0, 0.0], vec![1.0, 1.0], vec![0.0, 1.0]];
        let weights = [1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0];
        let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        Curve::new(2, &points, &knots, Some(&weights), &CurveLimits::default()).unwrap()
    }

    #[test]
    fn quarter_circle_points_and_derivatives() {
        let curve = quarter_circle();
        let parameters: Vec<f64> = (0..=20).map(|i| f64::from(i) / 20.0).collect();
        let mut batch = vec![[0.0; 3]; 3 * parameters.len()];
        BatchEvaluator::new(&curve)
            .derivatives_into(&parameters, 2, &mut batch)
            .unwrap();
        for (i, &t) in parameters.iter().enumerate() {
            let mut single = [[0.0; 3]; 3];
            curve.derivatives(t, &mut single).unwrap();
            for d in [
                single,
                [
                    batch[i],
                    batch[parameters.len() + i],
                    batch[2 * parameters.len() + i],
                ],
            ] {
                assert_relative_eq!(norm(d[0]), 1.0, epsilon = TOL);
                let speed = norm(d[1]);
                assert_relative_eq!(norm(cross(d[1], d[2])) / speed.powi(3), 1.0, epsilon = TOL);
            }
        }
        let mut start = [[0.0; 3]; 2];
        curve.derivatives(0.0, &mut start).unwrap();
        assert_relative_eq!(
            start[1][..],
            [0.0, std::f64::consts::SQRT_2, 0.0][..],
            epsilon = TOL
        );
        let middle = curve.point(0.5).unwrap();
        let half = std::f64::consts::FRAC_1_SQRT_2;
        assert_relative_eq!(middle[..], [half, half, 0.0][..], epsilon = TOL);
    }

    #[test]
    fn uniform_parameters_hit_both_ends_exactly() {
        let points: Vec<Vec<f64>> = (0..4).map(|i| vec![f64::from(i), 0.0]).collect();
        let knots = [0.1, 0.2, 0.3, 0.7, 0.9, 1.3, 1.7];
        let curve = Curve::new(2, &points, &knots, None, &CurveLimits::default()).unwrap();
        let parameters: Vec<f64> = curve.uniform_parameters(7).collect();
        assert_eq!(parameters.len(), 7);
        assert_eq!(parameters[0], 0.3);
        assert_eq!(parameters[6], 0.9);
        assert!(parameters.windows(2).all(|w| w[0] < w[1]));
    }
}
