//! Polynomials in Bernstein form on `[0, 1]`: binomials, products, halving and evaluation,
//! shared by the searches that bound a function on Bézier pieces (closest point, deviation).

use super::basis::MAX_DEGREE;

/// Largest degree of the Bernstein polynomials built from curve pieces: `4p` (products of two
/// degree-`2p` polynomials, for rational curves).
pub(crate) const MAX_RATIO_DEGREE: usize = 4 * MAX_DEGREE;

/// `BINOMIAL[n][k] = C(n, k)` for `n <= MAX_RATIO_DEGREE`, by Pascal's triangle.
pub(crate) static BINOMIAL: [[f64; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1] = pascal_triangle();

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

/// `out += sign · a * b` (convolution: `out_k += sign Σ_{i+j=k} a_i b_j`), the product of two
/// polynomials in the scaled Bernstein basis; `out` has `a.len() + b.len() - 1` entries.
#[inline(always)]
pub(crate) fn convolve(a: &[f64], b: &[f64], out: &mut [f64], sign: f64) {
    debug_assert_eq!(out.len(), a.len() + b.len() - 1);
    for (i, &a_i) in a.iter().enumerate() {
        let a_i = sign * a_i;
        for (product, &b_j) in out[i..].iter_mut().zip(b) {
            *product += a_i * b_j;
        }
    }
}

/// Scaled-basis coefficients (`C(d, k)` times the Bernstein ones) to Bernstein coefficients.
#[inline(always)]
pub(crate) fn unscale(coefficients: &mut [f64]) {
    let degree = coefficients.len() - 1;
    for (k, value) in coefficients.iter_mut().enumerate() {
        *value /= BINOMIAL[degree][k];
    }
}

/// Splits a Bernstein polynomial on `[0, 1]` at `1/2` (de Casteljau): `left` and `right` get
/// the coefficients of its halves, each again on `[0, 1]`.
#[inline(always)]
pub(crate) fn halve(coefficients: &[f64], left: &mut [f64], right: &mut [f64]) {
    let n = coefficients.len() - 1;
    right.copy_from_slice(coefficients);
    left[0] = coefficients[0];
    for (level, first) in left.iter_mut().enumerate().skip(1) {
        for i in 0..n - level + 1 {
            right[i] = 0.5 * (right[i] + right[i + 1]);
        }
        *first = right[0];
    }
}

/// The value at `s ∈ [0, 1]` of the Bernstein polynomial with `coefficients`, and its
/// derivative there, in `O(n)`: Horner's scheme in `r = s / (1 - s)` (for `s <= 1/2`, else in
/// `(1 - s) / s` over the reversed coefficients), `f = (1 - s)^n Σ C(n, k) b_k r^k`, and the
/// derivative `n Σ (b_{k+1} - b_k) B_k^{n-1}(s)` likewise. Both ratios stay `<= 1`, so the sums
/// are as well conditioned as de Casteljau's.
pub(crate) fn value_and_slope(coefficients: &[f64], s: f64) -> (f64, f64) {
    let n = coefficients.len() - 1;
    if n == 0 {
        return (coefficients[0], 0.0);
    }
    let mirrored = s > 0.5;
    let (ratio, base) = if mirrored {
        ((1.0 - s) / s, s)
    } else {
        (s / (1.0 - s), 1.0 - s)
    };
    let binomials = &BINOMIAL[n][..=n];
    let lower = &BINOMIAL[n - 1][..n];
    let at = |k: usize| {
        if mirrored {
            coefficients[n - k]
        } else {
            coefficients[k]
        }
    };
    // Σ_k C(n, k) b_k r^k and Σ_k C(n-1, k) (b_{k+1} - b_k) r^k, by Horner from the top.
    let mut value = at(n);
    let mut slope = at(n) - at(n - 1);
    for k in (0..n).rev() {
        value = value * ratio + binomials[k] * at(k);
    }
    for k in (0..n - 1).rev() {
        slope = slope * ratio + lower[k] * (at(k + 1) - at(k));
    }
    let mut power = 1.0;
    for _ in 1..n {
        power *= base;
    }
    let slope = n as f64 * slope * power;
    (value * power * base, if mirrored { -slope } else { slope })
}

/// `out += a * a` in the scaled Bernstein basis ([`convolve`] of `a` with itself), with each
/// product `a_i a_j` formed once: `out_k += Σ_{i+j=k} a_i a_j`.
#[inline(always)]
pub(crate) fn add_square(a: &[f64], out: &mut [f64]) {
    debug_assert_eq!(out.len(), 2 * a.len() - 1);
    for (i, &a_i) in a.iter().enumerate() {
        out[2 * i] += a_i * a_i;
        let twice = 2.0 * a_i;
        for (product, &a_j) in out[2 * i + 1..].iter_mut().zip(&a[i + 1..]) {
            *product += twice * a_j;
        }
    }
}

/// `1 / C(n, k)` for `n <= MAX_RATIO_DEGREE`: [`unscale`] by products instead of quotients.
pub(crate) static INVERSE_BINOMIAL: [[f64; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1] =
    inverse_pascal_triangle();

const fn inverse_pascal_triangle() -> [[f64; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1] {
    let mut table = [[0.0; MAX_RATIO_DEGREE + 1]; MAX_RATIO_DEGREE + 1];
    let mut n = 0;
    while n <= MAX_RATIO_DEGREE {
        let mut k = 0;
        while k <= n {
            table[n][k] = 1.0 / BINOMIAL[n][k];
            k += 1;
        }
        n += 1;
    }
    table
}

/// The value at `s ∈ [0, 1)` of Bernstein polynomials in `L` lanes (`coefficients[k]` holds
/// their `k`-th coefficients, the first `len`; degree `n = len - 1 >= 2`) and their first
/// and second derivatives there, in `O(n)`: with `r = s / (1 - s)`, by Horner's scheme,
/// `f = (1 - s)^n Σ C(n, k) b_k r^k`, `f' = n (1 - s)^(n-1) Σ C(n-1, k) Δb_k r^k` and
/// `f'' = n (n - 1) (1 - s)^(n-2) Σ C(n-2, k) Δ²b_k r^k`.
///
/// As well conditioned as de Casteljau's evaluation for `s <= 1/2` (`r <= 1`); beyond,
/// evaluate the mirrored polynomials (coefficients reversed) at `1 - s`, as
/// [`value_and_slope`] does.
#[inline(always)]
pub(crate) fn values_and_derivatives<const L: usize, const LEN: usize>(
    coefficients: &[[f64; L]; LEN],
    len: usize,
    s: f64,
) -> [[f64; L]; 3] {
    debug_assert!((3..=LEN).contains(&len));
    // With `len` known to be `LEN`, the loops have fixed trip counts and unroll.
    if len == LEN {
        horner_derivatives(coefficients, LEN - 1, s)
    } else {
        horner_derivatives(coefficients, len - 1, s)
    }
}

/// [`values_and_derivatives`] of degree `n`.
#[inline(always)]
fn horner_derivatives<const L: usize, const LEN: usize>(
    b: &[[f64; L]; LEN],
    n: usize,
    s: f64,
) -> [[f64; L]; 3] {
    let (ratio, base) = (s / (1.0 - s), 1.0 - s);
    let (mut value, mut slope, mut curvature) = (b[n], [0.0; L], [0.0; L]);
    for l in 0..L {
        slope[l] = b[n][l] - b[n - 1][l];
        curvature[l] = slope[l] - (b[n - 1][l] - b[n - 2][l]);
        value[l] = value[l] * ratio + BINOMIAL[n][n - 1] * b[n - 1][l];
    }
    for k in (0..n - 1).rev() {
        for l in 0..L {
            value[l] = value[l] * ratio + BINOMIAL[n][k] * b[k][l];
            slope[l] = slope[l] * ratio + BINOMIAL[n - 1][k] * (b[k + 1][l] - b[k][l]);
        }
    }
    for k in (0..n - 2).rev() {
        for l in 0..L {
            let second = b[k + 2][l] - 2.0 * b[k + 1][l] + b[k][l];
            curvature[l] = curvature[l] * ratio + BINOMIAL[n - 2][k] * second;
        }
    }
    let mut power = 1.0;
    for _ in 2..n {
        power *= base;
    }
    let n = n as f64;
    let (value_scale, slope_scale, curvature_scale) =
        (power * base * base, n * power * base, n * (n - 1.0) * power);
    [
        value.map(|v| v * value_scale),
        slope.map(|v| v * slope_scale),
        curvature.map(|v| v * curvature_scale),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// de Casteljau's evaluation, the reference for the Horner form.
    fn de_casteljau(coefficients: &[f64], s: f64) -> f64 {
        let mut work = coefficients.to_vec();
        for level in 1..work.len() {
            for i in 0..work.len() - level {
                work[i] += s * (work[i + 1] - work[i]);
            }
        }
        work[0]
    }

    #[test]
    fn horner_values_and_slopes_match_de_casteljau_and_differences() {
        let coefficients = [1.5, -2.0, 0.25, 3.0, -1.0, 0.5];
        for i in 0..=40 {
            let s = i as f64 / 40.0;
            let (value, slope) = value_and_slope(&coefficients, s);
            assert!(
                (value - de_casteljau(&coefficients, s)).abs() < 1e-13,
                "s = {s}"
            );
            // The derivative's own Bernstein coefficients n (b_{k+1} - b_k), by de Casteljau.
            let differences: Vec<f64> = coefficients
                .windows(2)
                .map(|w| 5.0 * (w[1] - w[0]))
                .collect();
            let expected = de_casteljau(&differences, s);
            assert!(
                (slope - expected).abs() < 1e-12,
                "s = {s}: {slope} vs {expected}"
            );
            // And a central difference inside the interval.
            if (0.01..=0.99).contains(&s) {
                let h = 1e-5;
                let difference = (de_casteljau(&coefficients, s + h)
                    - de_casteljau(&coefficients, s - h))
                    / (2.0 * h);
                assert!(
                    (slope - difference).abs() < 1e-6,
                    "s = {s}: {slope} vs {difference}"
                );
            }
        }
        assert_eq!(value_and_slope(&[2.0], 0.3), (2.0, 0.0));
        let (value, slope) = value_and_slope(&[1.0, 3.0], 0.25);
        assert!((value - 1.5).abs() < 1e-15 && (slope - 2.0).abs() < 1e-15);
    }

    #[test]
    fn values_and_second_derivatives_match_de_casteljau_of_the_differences() {
        // Two lanes of degree 6; the derivatives' own Bernstein coefficients are
        // n Δb_k and n (n - 1) Δ²b_k, evaluated by de Casteljau.
        let first = [1.5, -2.0, 0.25, 3.0, -1.0, 0.5, 2.0];
        let second = [0.3, 0.9, 1.7, 1.2, 0.8, 1.1, 0.6];
        let lanes: [[f64; 2]; 7] = std::array::from_fn(|k| [first[k], second[k]]);
        let n = 6.0;
        for (lane, coefficients) in [first, second].iter().enumerate() {
            let slopes: Vec<f64> = coefficients.windows(2).map(|w| n * (w[1] - w[0])).collect();
            let curvatures: Vec<f64> = slopes
                .windows(2)
                .map(|w| (n - 1.0) * (w[1] - w[0]))
                .collect();
            for i in 0..=40 {
                let s = i as f64 / 40.0 * 0.999;
                let [value, slope, curvature] = values_and_derivatives(&lanes, 7, s);
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
                assert!(
                    close(value[lane], de_casteljau(coefficients, s)),
                    "value, s = {s}"
                );
                assert!(
                    close(slope[lane], de_casteljau(&slopes, s)),
                    "slope, s = {s}"
                );
                assert!(
                    close(curvature[lane], de_casteljau(&curvatures, s)),
                    "curvature, s = {s}"
                );
            }
        }
        // Only the first `len` coefficients count.
        let padded: [[f64; 1]; 5] = [[1.0], [2.0], [4.0], [9.0], [9.0]];
        let [value, slope, curvature] = values_and_derivatives(&padded, 3, 0.5);
        assert_eq!((value[0], slope[0], curvature[0]), (2.25, 3.0, 2.0));
    }

    #[test]
    fn a_square_is_the_convolution_with_itself() {
        let a = [1.5, -2.0, 0.25, 3.0];
        let (mut square, mut product) = ([0.5; 7], [0.5; 7]);
        add_square(&a, &mut square);
        convolve(&a, &a, &mut product, 1.0);
        for (s, p) in square.iter().zip(&product) {
            assert!((s - p).abs() < 1e-14, "{square:?} vs {product:?}");
        }
        for (n, row) in INVERSE_BINOMIAL.iter().enumerate() {
            for k in 0..=n {
                assert!((row[k] * BINOMIAL[n][k] - 1.0).abs() < 1e-15);
            }
        }
    }
}
