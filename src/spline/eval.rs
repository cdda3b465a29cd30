//! Evaluation of points and derivatives, one parameter at a time or in batches.
//!
//! Single points use the basis-function derivatives of The NURBS Book (A2.3) on the
//! homogeneous control points, then the rational quotient rule (A4.2):
//! `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
//! Batches convert every span once to power form (Taylor coefficients at the span's left knot)
//! and evaluate with Horner's rule: no allocation and no span search per point beyond a check
//! of the span used last.

use super::basis::{CAP, basis_derivatives};
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
    /// point). Exact for rational curves (quotient rule, no finite differences).
    pub fn derivatives(&self, t: f64, out: &mut [Point]) -> Result<(), EvalError> {
        check_parameter(self, 0, t)?;
        let p = self.degree();
        let span = self.span(t);
        let mut ders = [[0.0; CAP]; CAP];
        let order = out.len().saturating_sub(1);
        basis_derivatives(self.knots(), p, span, t, order, &mut ders);
        let top = order.min(p);
        let mut homogeneous = [[0.0; 4]; CAP];
        for (k, h) in homogeneous.iter_mut().enumerate().take(top + 1) {
            for (r, &n) in ders[k].iter().enumerate().take(p + 1) {
                let pw = self.homogeneous()[span - p + r];
                for c in 0..4 {
                    h[c] += n * pw[c];
                }
            }
        }
        if self.is_rational() {
            derivative_quotients(&homogeneous[..=top], out);
        } else {
            for (k, o) in out.iter_mut().enumerate() {
                let h = if k <= top { homogeneous[k] } else { [0.0; 4] };
                *o = [h[0], h[1], h[2]];
            }
        }
        Ok(())
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

/// A curve in piecewise power form, for evaluating many parameters quickly.
///
/// For every non-empty span `[u_m, u_{m+1})` of the domain it holds the homogeneous Taylor
/// coefficients `c_d = A^(d)(u_m) / d!`, so that `A(t) = Σ_d c_d (t - u_m)^d` on that span.
/// Building costs one A2.3 evaluation per span; each point then costs a span check and
/// `p` multiply-adds per coordinate (only the coordinates the curve has: `x, y` for a planar
/// non-rational curve).
#[derive(Debug, Clone)]
pub struct BatchEvaluator<'c> {
    curve: &'c Curve,
    /// Left knot of each non-empty span, ascending.
    starts: Vec<f64>,
    /// `ends[s] = starts[s + 1]`, and `+∞` for the last span (which also takes the domain's
    /// right end): span `s` holds `t` iff `starts[s] <= t < ends[s]`.
    ends: Vec<f64>,
    /// `(p + 1)` coefficients per span.
    coefficients: Vec<[f64; 4]>,
}

impl<'c> BatchEvaluator<'c> {
    /// Converts `curve` to power form (one entry per non-empty span in the domain).
    pub fn new(curve: &'c Curve) -> Self {
        let p = curve.degree();
        let knots = curve.knots();
        let n = curve.control_points().len() - 1;
        let mut starts = Vec::new();
        let mut coefficients = Vec::new();
        for span in p..=n {
            let left = knots[span];
            if left >= knots[span + 1] {
                continue;
            }
            let piece = curve.power_piece_with_knots(knots, left);
            coefficients.extend_from_slice(piece.coefficients());
            starts.push(left);
        }
        let mut ends: Vec<f64> = starts[1..].to_vec();
        ends.push(f64::INFINITY);
        BatchEvaluator {
            curve,
            starts,
            ends,
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

    /// `out[i] := s(parameters[i])`; parameters in any order. Fails on the first parameter
    /// that is not finite or not in the domain (then `out` is partly written).
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
            self.dispatch(parameters.iter().copied(), out);
        }
        Ok(())
    }

    /// `count` uniformly spaced points over the whole domain (both ends included) into `out`
    /// (`out.len() == count >= 2`); the parameters are [`Curve::uniform_parameters`].
    pub fn uniform_points_into(&self, out: &mut [Point]) {
        let spacing = UniformSpacing::new(self.curve.domain(), out.len());
        self.dispatch((0..out.len()).map(|i| spacing.parameter(i)), out);
    }

    /// Runs [`Self::points_kernel`] monomorphised for the curve's kind and, up to degree 5, its
    /// degree (so that Horner's loop is unrolled). Every parameter must lie in the domain.
    #[inline]
    fn dispatch(&self, parameters: impl Iterator<Item = f64>, out: &mut [Point]) {
        /// Picks the kernel for `(lanes, rational)`, with the degree a compile-time constant
        /// up to 5 (`0`: read at run time).
        macro_rules! by_degree {
            ($lanes:literal, $rational:literal) => {
                match self.curve.degree() {
                    1 => self.points_kernel::<$lanes, $rational, 1>(parameters, out),
                    2 => self.points_kernel::<$lanes, $rational, 2>(parameters, out),
                    3 => self.points_kernel::<$lanes, $rational, 3>(parameters, out),
                    4 => self.points_kernel::<$lanes, $rational, 4>(parameters, out),
                    5 => self.points_kernel::<$lanes, $rational, 5>(parameters, out),
                    _ => self.points_kernel::<$lanes, $rational, 0>(parameters, out),
                }
            };
        }
        match (self.curve.is_rational(), self.curve.dimension()) {
            (false, Dimension::Two) => by_degree!(2, false),
            (false, Dimension::Three) => by_degree!(3, false),
            (true, _) => by_degree!(4, true),
        }
    }

    /// Evaluates `out[i] := s(t_i)` by Horner's rule on the span's power form, computing only
    /// the first `LANES` homogeneous coordinates (`x, y` or `x, y, z` when non-rational; all
    /// four when rational, then divided by `w`). `DEGREE` is the degree, or 0 for "read it at
    /// run time". Parameters must lie in the domain.
    #[inline(always)]
    fn points_kernel<const LANES: usize, const RATIONAL: bool, const DEGREE: usize>(
        &self,
        parameters: impl Iterator<Item = f64>,
        out: &mut [Point],
    ) {
        let p = if DEGREE == 0 {
            self.curve.degree()
        } else {
            DEGREE
        };
        let mut span = 0;
        for (t, o) in parameters.zip(out.iter_mut()) {
            span = self.locate(t, span);
            let h = t - self.starts[span];
            let c = &self.coefficients[span * (p + 1)..(span + 1) * (p + 1)];
            let mut acc = [0.0; 4];
            acc[..LANES].copy_from_slice(&c[p][..LANES]);
            for coefficient in c[..p].iter().rev() {
                for lane in 0..LANES {
                    acc[lane] = multiply_add(acc[lane], h, coefficient[lane]);
                }
            }
            *o = if RATIONAL {
                let w = acc[3];
                [acc[0] / w, acc[1] / w, acc[2] / w]
            } else {
                [acc[0], acc[1], acc[2]]
            };
        }
    }

    /// Points and derivatives: `out[k * parameters.len() + i] := s^(k)(parameters[i])` for
    /// `k = 0..=order`. `out.len()` must be `(order + 1) * parameters.len()`.
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
        let p = self.curve.degree();
        let rational = self.curve.is_rational();
        let mut homogeneous = [[0.0; 4]; CAP];
        let mut derivatives = vec![[0.0; 3]; order + 1];
        let mut span = 0;
        for (index, &t) in parameters.iter().enumerate() {
            check_parameter(self.curve, index, t)?;
            span = self.locate(t, span);
            let h = t - self.starts[span];
            let c = &self.coefficients[span * (p + 1)..(span + 1) * (p + 1)];
            // A^(k)(t) = Σ_{e>=k} c_e e!/(e-k)! h^(e-k), zero for k > p.
            for (k, value) in homogeneous.iter_mut().enumerate().take(p + 1) {
                let mut acc = [0.0f64; 4];
                for e in (k..=p).rev() {
                    let falling: f64 = ((e - k + 1)..=e).map(|f| f as f64).product();
                    for i in 0..4 {
                        acc[i] = multiply_add(acc[i], h, c[e][i] * falling);
                    }
                }
                *value = acc;
            }
            if rational {
                derivative_quotients(&homogeneous[..=p], &mut derivatives);
            } else {
                for (k, d) in derivatives.iter_mut().enumerate() {
                    let a = if k <= p { homogeneous[k] } else { [0.0; 4] };
                    *d = [a[0], a[1], a[2]];
                }
            }
            for (k, d) in derivatives.iter().enumerate() {
                out[k * count + index] = *d;
            }
        }
        Ok(())
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
