//! Polynomials in tensor-product Bernstein form on `[0, 1]²`:
//! `f(s, t) = Σ_i Σ_j b_ij B_i^m(s) B_j^n(t)`, coefficients row by row (`b_ij` at
//! `i (n + 1) + j`). Products, halving in either variable (de Casteljau on each column or
//! row: the curves' [`crate::spline::bernstein::halve`]), the bounds that the convex hull
//! property gives (of the values and of the second derivatives), and evaluation with the
//! gradient and Hessian; what the surfaces' closest-point search needs to bound and minimise
//! the squared distance on a patch.

use crate::spline::bernstein::{BINOMIAL, halve};

/// A tensor-product Bernstein polynomial's degrees `(m, n)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Degrees {
    pub(crate) m: usize,
    pub(crate) n: usize,
}

impl Degrees {
    /// The number of coefficients, `(m + 1)(n + 1)`.
    #[inline]
    pub(crate) fn len(self) -> usize {
        (self.m + 1) * (self.n + 1)
    }
}

/// `out = Σ_c (a_c)²` in the scaled bases and back: the Bernstein coefficients (degrees
/// `(2m, 2n)`) of the sum of squares of the polynomials `factors[c]` (degrees `(m, n)`,
/// Bernstein coefficients). Products are convolutions of the scaled coefficients
/// `C(m, i) C(n, j) b_ij` (module docs of [`crate::spline::bernstein`]).
pub(crate) fn sum_of_squares(factors: &[&[f64]], degrees: Degrees, out: &mut [f64]) {
    let Degrees { m, n } = degrees;
    let (wide, len) = (2 * n + 1, (2 * m + 1) * (2 * n + 1));
    out[..len].iter_mut().for_each(|x| *x = 0.0);
    // (p + 1)(q + 1) <= 16² coefficients: the degrees are at most MAX_DEGREE.
    let mut scaled = [0.0; (crate::spline::MAX_DEGREE + 1) * (crate::spline::MAX_DEGREE + 1)];
    for factor in factors {
        for i in 0..=m {
            for j in 0..=n {
                scaled[i * (n + 1) + j] = BINOMIAL[m][i] * BINOMIAL[n][j] * factor[i * (n + 1) + j];
            }
        }
        for i in 0..=m {
            for j in 0..=n {
                let a = scaled[i * (n + 1) + j];
                if a == 0.0 {
                    continue;
                }
                for k in 0..=m {
                    let row = &scaled[k * (n + 1)..(k + 1) * (n + 1)];
                    let target = &mut out[(i + k) * wide + j..(i + k) * wide + j + n + 1];
                    for (o, &b) in target.iter_mut().zip(row) {
                        *o += a * b;
                    }
                }
            }
        }
    }
    for k in 0..=2 * m {
        for l in 0..=2 * n {
            out[k * wide + l] /= BINOMIAL[2 * m][k] * BINOMIAL[2 * n][l];
        }
    }
}

/// The halves of `f` at `s = 1/2` (`in_s`) or `t = 1/2`, each again on `[0, 1]²`.
pub(crate) fn halve_2d(
    coefficients: &[f64],
    degrees: Degrees,
    in_s: bool,
    left: &mut [f64],
    right: &mut [f64],
) {
    let Degrees { m, n } = degrees;
    if in_s {
        let mut column = [0.0; 32];
        let mut low = [0.0; 32];
        let mut high = [0.0; 32];
        for j in 0..=n {
            for i in 0..=m {
                column[i] = coefficients[i * (n + 1) + j];
            }
            halve(&column[..=m], &mut low[..=m], &mut high[..=m]);
            for i in 0..=m {
                left[i * (n + 1) + j] = low[i];
                right[i * (n + 1) + j] = high[i];
            }
        }
    } else {
        for i in 0..=m {
            let row = i * (n + 1)..(i + 1) * (n + 1);
            halve(
                &coefficients[row.clone()],
                &mut left[row.clone()],
                &mut right[row],
            );
        }
    }
}

/// The lower bounds of `f_ss`, `f_tt` and the bound of `|f_st|` on `[0, 1]²` from the
/// Bernstein coefficients of the second derivatives: `m (m − 1) Δ²_i b`, `n (n − 1) Δ²_j b`
/// and `m n Δ_i Δ_j b` (each a convex combination's coefficients, so their extremes bound the
/// derivative everywhere).
pub(crate) fn second_derivative_bounds(coefficients: &[f64], degrees: Degrees) -> [f64; 3] {
    let Degrees { m, n } = degrees;
    let at = |i: usize, j: usize| coefficients[i * (n + 1) + j];
    let (mut ss, mut tt, mut st) = (f64::INFINITY, f64::INFINITY, 0.0f64);
    for i in 0..=m {
        for j in 0..=n {
            if i + 2 <= m {
                let d = at(i + 2, j) - 2.0 * at(i + 1, j) + at(i, j);
                ss = ss.min((m * (m - 1)) as f64 * d);
            }
            if j + 2 <= n {
                let d = at(i, j + 2) - 2.0 * at(i, j + 1) + at(i, j);
                tt = tt.min((n * (n - 1)) as f64 * d);
            }
            if i < m && j < n {
                let d = at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j);
                st = st.max(((m * n) as f64 * d).abs());
            }
        }
    }
    [ss, tt, st]
}

/// The largest `|f_ss|` and `|f_tt|` bounds on `[0, 1]²`: `m (m − 1) max |Δ²_i b|` and
/// `n (n − 1) max |Δ²_j b|` (how far the Bernstein coefficients can be from the values in
/// each variable).
pub(crate) fn second_derivative_sizes(coefficients: &[f64], degrees: Degrees) -> [f64; 2] {
    let Degrees { m, n } = degrees;
    let at = |i: usize, j: usize| coefficients[i * (n + 1) + j];
    let (mut ss, mut tt) = (0.0f64, 0.0f64);
    for i in 0..=m {
        for j in 0..=n {
            if i + 2 <= m {
                ss = ss.max((at(i + 2, j) - 2.0 * at(i + 1, j) + at(i, j)).abs());
            }
            if j + 2 <= n {
                tt = tt.max((at(i, j + 2) - 2.0 * at(i, j + 1) + at(i, j)).abs());
            }
        }
    }
    [
        ss * (m * m.saturating_sub(1)) as f64,
        tt * (n * n.saturating_sub(1)) as f64,
    ]
}

/// The value, gradient and Hessian of `f` at `(s, t)`: `(f, [f_s, f_t], [f_ss, f_st, f_tt])`.
/// Each row's polynomial in `t` and its two derivatives by de Casteljau (the last levels of
/// the triangle), then the columns of those in `s` likewise: every step a convex combination.
pub(crate) fn evaluate_2d(
    coefficients: &[f64],
    degrees: Degrees,
    s: f64,
    t: f64,
) -> (f64, [f64; 2], [f64; 3]) {
    let Degrees { m, n } = degrees;
    // Per row: the value and the t-derivatives.
    let mut rows = [[0.0; 3]; 32];
    for (i, row) in rows.iter_mut().enumerate().take(m + 1) {
        *row = with_derivatives(&coefficients[i * (n + 1)..(i + 1) * (n + 1)], t);
    }
    let mut column = [0.0; 32];
    let mut column_of = |k: usize| {
        for (i, row) in rows.iter().enumerate().take(m + 1) {
            column[i] = row[k];
        }
        with_derivatives(&column[..=m], s)
    };
    let [f, f_s, f_ss] = column_of(0);
    let [f_t, f_st, _] = column_of(1);
    let [f_tt, _, _] = column_of(2);
    (f, [f_s, f_t], [f_ss, f_st, f_tt])
}

/// The value and first two derivatives at `x ∈ [0, 1]` of the Bernstein polynomial with
/// `coefficients` (degree `d = len − 1 <= 31`), in `O(d)`: Horner's scheme in `r = x / (1 − x)`
/// for `x <= 1/2` (else in `(1 − x) / x` over the reversed coefficients), as the curves'
/// [`crate::spline::bernstein`] evaluates: `f = (1 − x)^d Σ C(d, k) b_k r^k`,
/// `f' = d (1 − x)^(d−1) Σ C(d−1, k) Δb_k r^k`, `f'' = d (d − 1) (1 − x)^(d−2) Σ C(d−2, k)
/// Δ²b_k r^k`. Both ratios stay `<= 1`, so the sums are as well conditioned as de Casteljau's.
pub(crate) fn with_derivatives(coefficients: &[f64], x: f64) -> [f64; 3] {
    let d = coefficients.len() - 1;
    if d == 0 {
        return [coefficients[0], 0.0, 0.0];
    }
    let mirrored = x > 0.5;
    let (ratio, base) = if mirrored {
        ((1.0 - x) / x, x)
    } else {
        (x / (1.0 - x), 1.0 - x)
    };
    let at = |k: usize| {
        if mirrored {
            coefficients[d - k]
        } else {
            coefficients[k]
        }
    };
    let mut value = at(d);
    for k in (0..d).rev() {
        value = value * ratio + BINOMIAL[d][k] * at(k);
    }
    let mut slope = at(d) - at(d - 1);
    for k in (0..d - 1).rev() {
        slope = slope * ratio + BINOMIAL[d - 1][k] * (at(k + 1) - at(k));
    }
    let mut curvature = 0.0;
    if d >= 2 {
        curvature = at(d) - 2.0 * at(d - 1) + at(d - 2);
        for k in (0..d - 2).rev() {
            curvature =
                curvature * ratio + BINOMIAL[d - 2][k] * (at(k + 2) - 2.0 * at(k + 1) + at(k));
        }
    }
    // base^(d-2), base^(d-1), base^d.
    let mut power = 1.0;
    for _ in 2..d {
        power *= base;
    }
    let (to_d_minus_1, to_d) = if d >= 2 {
        (power * base, power * base * base)
    } else {
        (1.0, base)
    };
    let d_f = d as f64;
    let slope = d_f * to_d_minus_1 * slope;
    let curvature = d_f * (d_f - 1.0) * power * curvature;
    [
        value * to_d,
        if mirrored { -slope } else { slope },
        curvature,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f(s, t) = (s − 0.3)² + 2 (t − 0.6)² + (s − 0.3)(t − 0.6)` in Bernstein form of degrees
    /// (2, 2): the blossom of a quadratic in each variable.
    fn quadratic() -> Vec<f64> {
        let f =
            |s: f64, t: f64| (s - 0.3).powi(2) + 2.0 * (t - 0.6).powi(2) + (s - 0.3) * (t - 0.6);
        // Bernstein coefficients of degree 2 from values at 0, 1/2, 1 (interpolation):
        // b_0 = f(0), b_2 = f(1), b_1 = 2 f(1/2) - (f(0) + f(1)) / 2, per direction.
        let grid = |i: usize, j: usize| f(i as f64 / 2.0, j as f64 / 2.0);
        let values: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| grid(i, j)));
        let to_bernstein = |v: [f64; 3]| [v[0], 2.0 * v[1] - 0.5 * (v[0] + v[2]), v[2]];
        let rows: Vec<[f64; 3]> = values.iter().map(|r| to_bernstein(*r)).collect();
        let mut out = vec![0.0; 9];
        for j in 0..3 {
            let column = to_bernstein([rows[0][j], rows[1][j], rows[2][j]]);
            for i in 0..3 {
                out[i * 3 + j] = column[i];
            }
        }
        out
    }

    #[test]
    fn evaluation_gives_values_gradients_and_hessians() {
        let b = quadratic();
        let degrees = Degrees { m: 2, n: 2 };
        for (s, t) in [(0.0, 0.0), (0.3, 0.6), (0.9, 0.1), (1.0, 1.0)] {
            let (f, gradient, hessian) = evaluate_2d(&b, degrees, s, t);
            let (x, y) = (s - 0.3, t - 0.6);
            assert!((f - (x * x + 2.0 * y * y + x * y)).abs() < 1e-15);
            assert!((gradient[0] - (2.0 * x + y)).abs() < 1e-14);
            assert!((gradient[1] - (4.0 * y + x)).abs() < 1e-14);
            assert!((hessian[0] - 2.0).abs() < 1e-13);
            assert!((hessian[1] - 1.0).abs() < 1e-13);
            assert!((hessian[2] - 4.0).abs() < 1e-13);
        }
        let [ss, tt, st] = second_derivative_bounds(&b, degrees);
        assert!((ss - 2.0).abs() < 1e-13 && (tt - 4.0).abs() < 1e-13 && (st - 1.0).abs() < 1e-13);
    }

    #[test]
    fn the_horner_form_matches_de_casteljau_and_its_differences() {
        let coefficients = [1.5, -2.0, 0.25, 3.0, -1.0, 0.5, 2.0];
        let casteljau = |b: &[f64], x: f64| {
            let mut work = b.to_vec();
            for level in 1..work.len() {
                for i in 0..work.len() - level {
                    work[i] += x * (work[i + 1] - work[i]);
                }
            }
            work[0]
        };
        let d = 6.0;
        let slopes: Vec<f64> = coefficients.windows(2).map(|w| d * (w[1] - w[0])).collect();
        let curvatures: Vec<f64> = slopes
            .windows(2)
            .map(|w| (d - 1.0) * (w[1] - w[0]))
            .collect();
        for i in 0..=40 {
            let x = f64::from(i) / 40.0;
            let [f, f1, f2] = with_derivatives(&coefficients, x);
            assert!((f - casteljau(&coefficients, x)).abs() < 1e-13, "{x}");
            assert!((f1 - casteljau(&slopes, x)).abs() < 1e-12, "{x}");
            assert!((f2 - casteljau(&curvatures, x)).abs() < 1e-11, "{x}");
        }
        assert_eq!(with_derivatives(&[2.0, 4.0], 0.25), [2.5, 2.0, 0.0]);
        assert_eq!(with_derivatives(&[3.0], 0.7), [3.0, 0.0, 0.0]);
    }

    #[test]
    fn halves_are_the_polynomial_on_each_half() {
        let b = quadratic();
        let degrees = Degrees { m: 2, n: 2 };
        for in_s in [true, false] {
            let (mut left, mut right) = (vec![0.0; 9], vec![0.0; 9]);
            halve_2d(&b, degrees, in_s, &mut left, &mut right);
            for (s, t) in [(0.2, 0.7), (0.9, 0.4)] {
                let (a, _, _) = evaluate_2d(&left, degrees, s, t);
                let (c, _, _) = evaluate_2d(&right, degrees, s, t);
                let (ls, lt, rs, rt) = if in_s {
                    (s / 2.0, t, 0.5 + s / 2.0, t)
                } else {
                    (s, t / 2.0, s, 0.5 + t / 2.0)
                };
                assert!((a - evaluate_2d(&b, degrees, ls, lt).0).abs() < 1e-15);
                assert!((c - evaluate_2d(&b, degrees, rs, rt).0).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn a_sum_of_squares_is_the_product_of_the_factors() {
        // Degrees (1, 1): a(s, t) = 1 + s + 2t + st, b(s, t) = s - t.
        let a = [1.0, 3.0, 2.0, 5.0];
        let b = [0.0, -1.0, 1.0, 0.0];
        let degrees = Degrees { m: 1, n: 1 };
        let mut out = vec![0.0; 9];
        sum_of_squares(&[&a, &b], degrees, &mut out);
        for (s, t) in [(0.0f64, 0.0f64), (0.25, 0.5), (1.0, 0.3)] {
            let expected = (1.0 + s + 2.0 * t + s * t).powi(2) + (s - t).powi(2);
            let (found, _, _) = evaluate_2d(&out, Degrees { m: 2, n: 2 }, s, t);
            assert!((found - expected).abs() < 1e-14, "{found} vs {expected}");
        }
    }
}
