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

/// The value at `s` of the Bernstein polynomial with `coefficients` (de Casteljau), and its
/// derivative there. `scratch` holds at least `coefficients.len()` values.
pub(crate) fn value_and_slope(coefficients: &[f64], s: f64, scratch: &mut [f64]) -> (f64, f64) {
    let n = coefficients.len() - 1;
    let work = &mut scratch[..=n];
    work.copy_from_slice(coefficients);
    if n == 0 {
        return (work[0], 0.0);
    }
    for level in 1..n {
        for i in 0..=n - level {
            work[i] += s * (work[i + 1] - work[i]);
        }
    }
    let slope = n as f64 * (work[1] - work[0]);
    (work[0] + s * (work[1] - work[0]), slope)
}
