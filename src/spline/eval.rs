//! Evaluation of points and derivatives, one parameter at a time or in batches.
//!
//! Single points use the basis-function derivatives of The NURBS Book (A2.3) on the
//! homogeneous control points, then the rational quotient rule (A4.2):
//! `C^(k) = (A^(k) - Σ_{i=1..k} binom(k, i) w^(i) C^(k-i)) / w`.
//! Batches convert every span once to power form (Taylor coefficients at the span's left knot)
//! and evaluate with Horner's rule: no allocation and no span search per point beyond a check
//! of the span used last.

use super::basis::{CAP, basis_derivatives};
use super::curve::Curve;
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

    /// `count >= 2` parameters spread uniformly over the domain, both ends included exactly.
    pub fn uniform_parameters(&self, count: usize) -> impl ExactSizeIterator<Item = f64> + '_ {
        let (lo, hi) = self.domain();
        let last = count.saturating_sub(1).max(1);
        (0..count).map(move |i| {
            if i == last {
                hi
            } else {
                lo + (hi - lo) * (i as f64 / last as f64)
            }
        })
    }
}

/// A curve in piecewise power form, for evaluating many parameters quickly.
///
/// For every non-empty span `[u_m, u_{m+1})` of the domain it holds the homogeneous Taylor
/// coefficients `c_d = A^(d)(u_m) / d!`, so that `A(t) = Σ_d c_d (t - u_m)^d` on that span.
/// Building costs one A2.3 evaluation per span; each point then costs a span check and
/// `p` fused multiply-adds per coordinate.
#[derive(Debug, Clone)]
pub struct BatchEvaluator<'c> {
    curve: &'c Curve,
    /// Left knot of each non-empty span, ascending.
    starts: Vec<f64>,
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
        let mut ders = [[0.0; CAP]; CAP];
        for span in p..=n {
            let left = knots[span];
            if left >= knots[span + 1] {
                continue;
            }
            basis_derivatives(knots, p, span, left, p, &mut ders);
            let mut factorial = 1.0;
            for (d, row) in ders.iter().enumerate().take(p + 1) {
                if d > 0 {
                    factorial *= d as f64;
                }
                let mut c = [0.0; 4];
                for (r, &value) in row.iter().enumerate().take(p + 1) {
                    let pw = curve.homogeneous()[span - p + r];
                    for (ci, cv) in c.iter_mut().enumerate() {
                        *cv += value * pw[ci];
                    }
                }
                coefficients.push(c.map(|v| v / factorial));
            }
            starts.push(left);
        }
        BatchEvaluator {
            curve,
            starts,
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
        let last = self.starts.len() - 1;
        let in_hint = self.starts[hint] <= t && (hint == last || t < self.starts[hint + 1]);
        if in_hint {
            hint
        } else {
            self.starts
                .partition_point(|&s| s <= t)
                .saturating_sub(1)
                .min(last)
        }
    }

    /// Homogeneous point on span `s` at local offset `h = t - starts[s]` (Horner's rule).
    #[inline]
    fn homogeneous_at(&self, s: usize, h: f64) -> [f64; 4] {
        let p = self.curve.degree();
        let c = &self.coefficients[s * (p + 1)..(s + 1) * (p + 1)];
        let mut acc = c[p];
        for coefficient in c[..p].iter().rev() {
            for i in 0..4 {
                acc[i] = acc[i].mul_add(h, coefficient[i]);
            }
        }
        acc
    }

    /// `out[i] := s(parameters[i])`; parameters in any order. Fails on the first parameter
    /// that is not finite or not in the domain (then `out` is partly written).
    pub fn points_into(&self, parameters: &[f64], out: &mut [Point]) -> Result<(), EvalError> {
        assert_eq!(parameters.len(), out.len(), "one output slot per parameter");
        let rational = self.curve.is_rational();
        let mut span = 0;
        for (index, (&t, o)) in parameters.iter().zip(out.iter_mut()).enumerate() {
            check_parameter(self.curve, index, t)?;
            span = self.locate(t, span);
            let a = self.homogeneous_at(span, t - self.starts[span]);
            *o = if rational {
                [a[0] / a[3], a[1] / a[3], a[2] / a[3]]
            } else {
                [a[0], a[1], a[2]]
            };
        }
        Ok(())
    }

    /// `count` uniformly spaced points over the whole domain (both ends included) into `out`
    /// (`out.len() == count >= 2`); the parameters are [`Curve::uniform_parameters`].
    pub fn uniform_points_into(&self, out: &mut [Point]) {
        let rational = self.curve.is_rational();
        let mut span = 0;
        for (t, o) in self.curve.uniform_parameters(out.len()).zip(out.iter_mut()) {
            span = self.locate(t, span);
            let a = self.homogeneous_at(span, t - self.starts[span]);
            *o = if rational {
                [a[0] / a[3], a[1] / a[3], a[2] / a[3]]
            } else {
                [a[0], a[1], a[2]]
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
                        acc[i] = acc[i].mul_add(h, c[e][i] * falling);
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
